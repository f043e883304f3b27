//! A controller that stays up (`rapidvc serve`): the operator panel's limits applied to every
//! move, and stopping and continuing a program's motion.
//!
//! * **Speed ratio** (1–100 %, `rw/panel/speedratio`): scales the robot's speed at once, as
//!   the FlexPendant's override does: the executor plays the planned path at the ratio
//!   (`motion::PathOp::Ratio`; moves already planned slow down or speed up within the axis
//!   accelerations) and an EGM run scales its EGM speed by it
//!   ([`crate::controller::egm_controller::EgmController::set_speed_ratio`]).
//! * **Manual reduced speed** (MANR): the TCP speed of moves planned in MANR is capped at
//!   250 mm/s.
//! * **Stop and continue**: [`ControllerHost::hold_motion`] decelerates the robot on its
//!   path (the bounded ramp of `StopMove`: the TCP does not leave the planned path, fly-by
//!   corners included) and holds it there with the moves kept planned;
//!   [`ControllerHost::resume_motion`] lets the same path go on, so an interrupted move
//!   continues to its target when the program is started again (its position events,
//!   `TriggL` and the like, fire once). If manual reduced speed was switched on while
//!   stopped, the kept moves are planned again from where the robot stands, under its cap.
//!   An EGM run going on pauses instead (its EGM speed ramps to zero, the sensor session
//!   goes on) and continues at the start.

use std::collections::VecDeque;
use std::sync::Arc;
use std::sync::atomic::{AtomicBool, AtomicU8, Ordering};

use super::ControllerHost;
use crate::controller::ControllerHandle;
use crate::interp::HostError;
use crate::robot::command::MotionCommand;

/// TCP speed cap in manual reduced speed mode (mm/s).
pub const MANUAL_REDUCED_TCP_SPEED: f64 = 250.0;

/// The panel's settings as the program side reads them (shared with the services' side).
#[derive(Debug)]
pub struct PanelLimits {
    /// Speed ratio in percent (1–100).
    pub speed_ratio: AtomicU8,
    /// Manual reduced speed mode.
    pub manual_reduced: AtomicBool,
}

impl Default for PanelLimits {
    fn default() -> Self {
        PanelLimits {
            speed_ratio: AtomicU8::new(100),
            manual_reduced: AtomicBool::new(false),
        }
    }
}

/// What the host keeps for a controller that stays up.
#[derive(Debug)]
pub(super) struct PanelMoves {
    pub(super) limits: Arc<PanelLimits>,
    /// Moves accepted and not yet known to have ended, oldest first, with their ids.
    pub(super) unfinished: VecDeque<(u64, MotionCommand)>,
    /// The robot is held on its path by [`ControllerHost::hold_motion`].
    held: bool,
    /// Manual reduced speed was on when the robot was held.
    manual_at_hold: bool,
}

/// Run `submit` with the panel's MANR cap (when `limits` are given and the mode is MANR)
/// applied to the modal settings for this one move. (The speed ratio is not planned in: the
/// executor plays every move at it, [`ControllerHost::set_speed_ratio`].)
pub(super) fn with_limits<T>(
    ctl: &mut ControllerHandle,
    limits: Option<&PanelLimits>,
    submit: impl FnOnce(&mut ControllerHandle) -> T,
) -> T {
    let Some(limits) = limits else {
        return submit(ctl);
    };
    if !limits.manual_reduced.load(Ordering::Relaxed) {
        return submit(ctl);
    }
    let saved = ctl.settings();
    let mut s = saved;
    s.velset.max_tcp = s.velset.max_tcp.min(MANUAL_REDUCED_TCP_SPEED);
    ctl.set_settings(s);
    let result = submit(ctl);
    ctl.set_settings(saved);
    result
}

impl ControllerHost {
    /// Apply the panel's `limits` to every move from now on and keep moves so a stopped
    /// program's motion can continue ([`Self::hold_motion`], [`Self::resume_motion`]).
    pub fn with_panel(mut self, limits: Arc<PanelLimits>) -> Self {
        self.panel = Some(PanelMoves {
            limits,
            unfinished: VecDeque::new(),
            held: false,
            manual_at_hold: false,
        });
        self
    }

    /// Forget the moves that have ended.
    fn prune_unfinished(&mut self) {
        let Some(st) = self.ctl.as_mut().map(ControllerHandle::state) else {
            return;
        };
        let void = self.void_up_to;
        if let Some(p) = self.panel.as_mut() {
            p.unfinished.retain(|(id, _)| *id > void && !st.done(*id));
        }
    }

    /// The controller's speed ratio changed (1–100 %): every move, planned or not, and EGM
    /// go at it from now on (module docs).
    pub fn set_speed_ratio(&mut self, percent: u8) {
        let percent = percent.clamp(1, 100);
        if let Some(ctl) = self.ctl.as_mut() {
            // Refused only when the motion thread is gone (the controller shuts down).
            let _ = ctl.path_op(crate::motion::PathOp::Ratio(f64::from(percent) / 100.0));
        }
        if let Some(egm) = self.egm.as_mut() {
            egm.set_speed_ratio(percent);
        }
    }

    /// The program's state and the motors' (polled by the program side): what EGM reports
    /// to its sensors ([`crate::controller::egm_controller::EgmController::set_controller_state`]).
    pub fn set_controller_state(&mut self, program_running: bool, motors_on: bool) {
        if let Some(egm) = self.egm.as_mut() {
            egm.set_controller_state(program_running, motors_on);
        }
    }

    /// The program stops: the robot decelerates on its path and holds there, the moves kept
    /// planned (an EGM run pauses instead). Returns how many moves had not ended.
    pub fn hold_motion(&mut self) -> usize {
        if let Some(egm) = self.egm.as_mut() {
            egm.pause_run();
        }
        self.prune_unfinished();
        let Some(ctl) = self.ctl.as_mut() else {
            return 0;
        };
        if self.panel.is_none() {
            // No panel to start it again: brake, as the end of a run does.
            let st = ctl.state();
            if st.moving || st.pending > 0 {
                ctl.stop_motion();
            }
            self.pump_events();
            return 0;
        }
        // Refused only under external guidance (the EGM run paused above holds the robot)
        // or when the motion thread is gone (nothing moves then).
        let paused = ctl.pause_motion().is_ok();
        self.pump_events();
        match self.panel.as_mut() {
            Some(p) => {
                p.held = paused;
                p.manual_at_hold = p.limits.manual_reduced.load(Ordering::Relaxed);
                p.unfinished.len()
            }
            None => 0,
        }
    }

    /// The program starts again: the held path goes on where the robot stands on it. When
    /// manual reduced speed was switched on while stopped, the moves planned before are
    /// planned again from here under its 250 mm/s cap instead.
    pub fn resume_motion(&mut self) -> Result<(), HostError> {
        if let Some(egm) = self.egm.as_mut() {
            egm.resume_run();
        }
        let Some(p) = self.panel.as_mut() else {
            return Ok(());
        };
        if !p.held {
            return Ok(());
        }
        p.held = false;
        let replan = !p.manual_at_hold && p.limits.manual_reduced.load(Ordering::Relaxed);
        if !replan {
            let ctl = self.ctl()?;
            ctl.continue_motion()
                .map_err(|e| HostError::fatal(format!("the stopped moves cannot continue: {e}")))?;
            self.pump_events();
            return Ok(());
        }
        self.prune_unfinished();
        let moves: Vec<(u64, MotionCommand)> = match self.panel.as_mut() {
            Some(p) => p.unfinished.drain(..).collect(),
            None => Vec::new(),
        };
        let limits = self.panel.as_ref().map(|p| p.limits.clone());
        let ctl = self.ctl()?;
        // The robot stands on the held path: drop it, then plan the moves again.
        ctl.stop_motion();
        ctl.continue_motion()
            .map_err(|e| HostError::fatal(format!("the stopped moves cannot continue: {e}")))?;
        for (id, cmd) in moves {
            let ctl = self.ctl()?;
            match with_limits(ctl, limits.as_deref(), |c| c.submit(cmd.clone())) {
                Ok(()) => {
                    if let Some(p) = self.panel.as_mut() {
                        p.unfinished.push_back((id, cmd));
                    }
                }
                Err(e) => {
                    // The move cannot continue from here: the program's wait for it is over
                    // and the event says why.
                    self.void_up_to = self.void_up_to.max(id);
                    self.pump_events();
                    return Err(HostError::fatal(format!(
                        "the stopped move cannot continue: {e}"
                    )));
                }
            }
        }
        self.pump_events();
        Ok(())
    }

    /// After a program-pointer reset: the kept moves are dropped (the robot stays where it
    /// stopped) and the program's waits for them are over.
    pub fn forget_motion(&mut self) {
        let held = match self.panel.as_mut() {
            Some(p) => {
                p.unfinished.clear();
                std::mem::take(&mut p.held)
            }
            None => false,
        };
        if held && let Some(ctl) = self.ctl.as_mut() {
            // The held path is dropped; the robot stands where it stopped.
            ctl.stop_motion();
            let _ = ctl.continue_motion();
        }
        self.void_up_to = self.last_id;
    }
}
