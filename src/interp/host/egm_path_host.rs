//! The path-correction capability of a host ([`EgmPathHost`]): what EGMMoveL and EGMMoveC ask of the controller. A host without it returns `None` from [`super::Host::egm_path`] and the instructions stop the program with "… is not supported by this controller".

use crate::robot::command::MotionCommand;

use super::HostError;

/// A controller that corrects paths (EGM path correction). `ident` is the identity's name,
/// as for [`super::EgmHost`]. Errors with [`HostError::errno`] set are catchable RAPID
/// errors (`ERR_UDPUC_COMM`); the others stop the program.
pub trait EgmPathHost {
    /// `EGMMoveL` / `EGMMoveC`: queue `cmd` (a `MoveL` / `MoveC` built from the
    /// instruction's arguments and the active program displacement; its id is replaced) as a
    /// path-corrected move of `ident`'s sequence, starting the sequence when none runs.
    /// Returns the move's id; at a fine point the native waits for
    /// [`super::MotionWait::Done`] and then calls [`EgmPathHost::egm_move_end`].
    fn egm_move(
        &mut self,
        ident: &str,
        cmd: MotionCommand,
        no_corr: bool,
    ) -> Result<u64, HostError>;

    /// The fine point that ends `ident`'s corrected sequence was reached (`ok`), or waiting
    /// for it failed (the sequence is abandoned): the identity is CONNECTED again.
    fn egm_move_end(&mut self, ident: &str, ok: bool) -> Result<(), HostError>;
}
