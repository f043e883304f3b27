//! The EGM options of `rapidvc run` (`--device`, `--egm-log`, `--lockstep`) and the EGM side of the controller they set up: device table, clock decision, [`EgmController`] and its cycle hook.

use std::path::PathBuf;
use std::sync::Arc;
use std::time::Duration;

use crate::config::Config;
use crate::config::devices::DeviceOverride;
use crate::controller::egm_controller::registry_config;
use crate::controller::egm_controller::{EgmController, EgmHook, EgmSetup};
use crate::egm::DriverOptions;
use crate::egm::driver::DEFAULT_REPLY_TIMEOUT;
use crate::output::Feed;
use crate::robot::Robot;
use crate::signals::SignalTable;

/// EGM options of `rapidvc run`.
#[derive(Debug, Clone, Default, clap::Args)]
pub struct EgmArgs {
    /// Point an EGM device at an external sensor (`NAME=HOST:PORT`) or at the built-in
    /// sensor (`NAME=builtin[:PATTERN]`); repeatable. Without SIO.cfg and without this,
    /// every device is the built-in sensor.
    #[arg(long = "device", value_name = "NAME=TARGET")]
    pub devices: Vec<DeviceOverride>,
    /// Write one CSV row per EGM message (send and receive time, seqno, reference,
    /// feedback, state, utilization).
    #[arg(long, value_name = "FILE.csv")]
    pub egm_log: Option<PathBuf>,
    /// Keep virtual time with an external sensor: each EGM message waits for the sensor's
    /// reply (or --lockstep-timeout) before time advances. Deterministic and faster than
    /// real time with sensors that answer every message.
    #[arg(long)]
    pub lockstep: bool,
    /// Lockstep: the longest wait for one reply, milliseconds of real time (1 to 600000).
    #[arg(long, value_name = "MS", default_value_t = DEFAULT_REPLY_TIMEOUT.as_millis() as u64,
          value_parser = clap::value_parser!(u64).range(crate::cli::num::LOCKSTEP_TIMEOUT_MS))]
    pub lockstep_timeout: u64,
}

/// The EGM side of a controller, ready to start.
pub struct EgmPrepared {
    /// The program side.
    pub controller: EgmController,
    /// The cycle hook for `ControllerHandle::start_with_hook`.
    pub hook: EgmHook,
    /// External devices exist and no lockstep was asked for: the clock must run in real
    /// time.
    pub needs_realtime: bool,
    /// The external devices the program may use (for the notice).
    pub external: Vec<String>,
    /// `--egm-log` is written (the program uses EGM).
    pub log_written: bool,
}

impl EgmArgs {
    /// Builds the EGM side for `robot` with motion period `period` from the configuration
    /// directory's `cfg` and these options; `feed` reaches the trace and plot. `used` are
    /// the devices the program sets up (`None`: the program uses no EGM, and `--egm-log`
    /// writes nothing).
    pub fn prepare(
        &self,
        cfg: &Config,
        robot: &Robot,
        signals: Arc<SignalTable>,
        period: Duration,
        feed: Option<Feed>,
        used: Option<&DeviceUse>,
    ) -> Result<EgmPrepared, String> {
        let devices = cfg.device_table(&self.devices).map_err(|e| e.to_string())?;
        let external: Vec<String> = devices
            .external_devices()
            .into_iter()
            .filter(|d| used.is_some_and(|u| u.computed || u.uses(d)))
            .collect();
        let log: Option<Box<dyn std::io::Write + Send>> =
            match self.egm_log.as_ref().filter(|_| used.is_some()) {
                Some(path) => {
                    let f = std::fs::File::create(path)
                        .map_err(|e| format!("cannot create {}: {e}", path.display()))?;
                    Some(Box::new(std::io::BufWriter::new(f)))
                }
                None => None,
            };
        let log_written = log.is_some();
        let driver = DriverOptions {
            tick: period,
            reply_timeout: Duration::from_millis(self.lockstep_timeout),
            ..DriverOptions::default()
        };
        let setup = EgmSetup {
            registry: registry_config(&cfg.moc, &devices),
            driver,
            lockstep: self.lockstep.then_some(driver.reply_timeout),
            feed,
            log,
        };
        let (controller, hook) = EgmController::new(setup, robot.clone(), signals)?;
        Ok(EgmPrepared {
            controller,
            hook,
            needs_realtime: !self.lockstep && !external.is_empty(),
            external,
            log_written,
        })
    }
}

/// Whether the program uses EGM (one of its own modules declares an `egmident`): then the
/// trace gets the `egm_state` columns and the plot its EGM section, and an external device
/// sets the clock.
pub fn uses_egm(prog: &crate::ir::Program, sources: &crate::source::SourceMap) -> bool {
    prog.modules.iter().filter(|m| !m.stdlib).any(|m| {
        sources
            .get(m.source)
            .text
            .to_ascii_lowercase()
            .contains("egmident")
    })
}

/// After the controller finished: wait for the EGM log writer; report the datagrams the
/// sessions dropped (by cause), the lockstep counts and the log (when `log_written`).
pub fn finish(controller: EgmController, args: &EgmArgs, log_written: bool) -> Result<(), String> {
    let summary = controller.finish()?;
    if summary.datagrams.dropped() > 0 {
        eprintln!("EGM: {}", summary.datagrams);
    }
    if args.lockstep && summary.lockstep_waits > 0 {
        eprintln!(
            "lockstep: {} replies awaited, {} timed out (--lockstep-timeout {} ms)",
            summary.lockstep_waits, summary.lockstep_timeouts, args.lockstep_timeout
        );
    }
    if let Some(path) = args.egm_log.as_ref().filter(|_| log_written) {
        eprintln!(
            "EGM log: {} rows written to {}{}",
            summary.rows_written,
            path.display(),
            if summary.rows_dropped > 0 {
                format!(
                    " ({} rows lost: the writer fell behind)",
                    summary.rows_dropped
                )
            } else {
                String::new()
            }
        );
    }
    Ok(())
}

/// The EGM device names a program sets up (`EGMSetupUC` and `EGMSetupLTAPP`), found without
/// running it.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct DeviceUse {
    /// Device names written as string literals (or `CONST string` data).
    pub names: Vec<String>,
    /// Some setup computes its device name (a variable, a late-bound call): names outside
    /// [`DeviceUse::names`] may be used too.
    pub computed: bool,
}

impl DeviceUse {
    /// Whether the device `name` is set up (case-insensitive, one trailing `:` ignored, as
    /// devices are looked up).
    pub fn uses(&self, name: &str) -> bool {
        let key = name.trim_end_matches(':');
        self.names
            .iter()
            .any(|n| n.trim_end_matches(':').eq_ignore_ascii_case(key))
    }
}

/// The setup instructions whose fourth argument names a device.
const DEVICE_SETUPS: [&str; 2] = ["EGMSetupUC", "EGMSetupLTAPP"];
/// Index of the device argument of [`DEVICE_SETUPS`].
const DEVICE_ARG: usize = 3;

/// The devices the program's own modules set up.
pub fn device_use(prog: &crate::ir::Program) -> DeviceUse {
    let mut out = DeviceUse::default();
    for r in prog.routines.iter().filter(|r| {
        prog.modules
            .get(r.module.0 as usize)
            .is_some_and(|m| !m.stdlib)
    }) {
        walk_block(prog, &r.body, &mut out);
        if let Some(h) = &r.error {
            walk_block(prog, &h.body, &mut out);
        }
        if let Some(u) = &r.undo {
            walk_block(prog, u, &mut out);
        }
    }
    out
}

fn walk_block(prog: &crate::ir::Program, block: &crate::ir::Block, out: &mut DeviceUse) {
    use crate::ir::{ExprKind, StmtKind};
    for stmt in &block.stmts {
        match &stmt.kind {
            StmtKind::Native { native, args } => {
                let is_setup = prog.natives.get(native.0 as usize).is_some_and(|n| {
                    DEVICE_SETUPS
                        .iter()
                        .any(|s| s.eq_ignore_ascii_case(&n.name))
                });
                if is_setup {
                    match args.get(DEVICE_ARG).and_then(|a| constant_string(prog, a)) {
                        Some(name) => {
                            if !out.uses(&name) {
                                out.names.push(name);
                            }
                        }
                        None => out.computed = true,
                    }
                }
            }
            StmtKind::LateCall { name, .. } => {
                let other = matches!(&name.kind, ExprKind::Str(s)
                    if !DEVICE_SETUPS.iter().any(|d| d.eq_ignore_ascii_case(s)));
                if !other {
                    out.computed = true;
                }
            }
            StmtKind::If {
                branches,
                else_body,
            } => {
                for (_, b) in branches {
                    walk_block(prog, b, out);
                }
                if let Some(b) = else_body {
                    walk_block(prog, b, out);
                }
            }
            StmtKind::While { body, .. } | StmtKind::For { body, .. } => {
                walk_block(prog, body, out);
            }
            StmtKind::Test { cases, default, .. } => {
                for (_, b) in cases {
                    walk_block(prog, b, out);
                }
                if let Some(b) = default {
                    walk_block(prog, b, out);
                }
            }
            _ => {}
        }
    }
}

/// The text of a string argument known before the run: a literal, or `CONST string` data
/// initialised with one.
fn constant_string(prog: &crate::ir::Program, arg: &crate::ir::Arg) -> Option<String> {
    use crate::ir::{Arg, ExprKind};
    let Arg::Value(e) = arg else { return None };
    match &e.kind {
        ExprKind::Str(s) => Some(s.to_string()),
        ExprKind::Global(g) => {
            let g = prog.globals.get(*g as usize)?;
            if g.storage != crate::ast::Storage::Const {
                return None;
            }
            match &g.init.as_ref()?.kind {
                ExprKind::Str(s) => Some(s.to_string()),
                _ => None,
            }
        }
        _ => None,
    }
}

/// Check the `--device` names against the program's setups: a name no setup uses is an
/// error (a misspelling would otherwise be ignored silently), or a warning when some setup
/// computes its device name. Returns the warnings.
pub fn check_devices(args: &EgmArgs, used: &DeviceUse) -> Result<Vec<String>, String> {
    let mut warnings = Vec::new();
    for d in &args.devices {
        if used.uses(&d.name) {
            continue;
        }
        let known = if used.names.is_empty() {
            "it sets up no EGM device by name".to_string()
        } else {
            let names: Vec<String> = used.names.iter().map(|n| format!("`{n}`")).collect();
            format!("it sets up {}", names.join(", "))
        };
        if used.computed {
            warnings.push(format!(
                "--device {}: no EGMSetupUC/EGMSetupLTAPP of the program names this device ({known}; some device names are computed at run time)",
                d.name
            ));
        } else {
            return Err(format!(
                "--device {}: no EGMSetupUC/EGMSetupLTAPP of the program uses this device ({known})",
                d.name
            ));
        }
    }
    Ok(warnings)
}
