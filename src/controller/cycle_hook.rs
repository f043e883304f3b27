//! Work the shell does around every motion cycle — e.g. exchanging datagrams with an EGM
//! session and feeding the running guidance — in both clock modes: on the motion thread in real
//! time, on the caller's thread in virtual time.

use crate::motion::{Executor, Setpoint};
use crate::time::RobotTime;

/// Called around every motion cycle. Runs on the real-time path: keep it short, never block
/// for long, never panic.
pub trait CycleHook: Send {
    /// Before the cycle at `now` (e.g. hand the datagrams that arrived to the running
    /// guidance, through the hook's own typed handle on it).
    fn before_tick(&mut self, now: RobotTime, exec: &mut Executor) {
        let _ = (now, exec);
    }

    /// After the cycle produced `sp` (e.g. send feedback to the sensor).
    fn after_tick(&mut self, sp: &Setpoint, exec: &mut Executor) {
        let _ = (sp, exec);
    }
}
