//! Ctrl-C during `rapidvc run`: the first SIGINT sets a flag that the interpreter and the
//! controller watch, so the program stops as a controller stops it (the robot is halted, an
//! EGM run ramps out, every output is finished, the summary printed) and the run exits with
//! 130. A second SIGINT ends the process at once with 130.

use std::sync::Arc;
use std::sync::atomic::AtomicBool;

use signal_hook::consts::SIGINT;

/// Exit code of a run ended by SIGINT (128 + 2, as shells report it).
pub const EXIT_INTERRUPTED: u8 = 130;

/// Install the SIGINT handlers; the flag turns true on the first SIGINT.
pub fn install() -> std::io::Result<Arc<AtomicBool>> {
    let flag = Arc::new(AtomicBool::new(false));
    // Registered first, so it sees the flag as the previous SIGINT left it: the second one
    // exits.
    signal_hook::flag::register_conditional_shutdown(
        SIGINT,
        i32::from(EXIT_INTERRUPTED),
        Arc::clone(&flag),
    )?;
    signal_hook::flag::register(SIGINT, Arc::clone(&flag))?;
    Ok(flag)
}
