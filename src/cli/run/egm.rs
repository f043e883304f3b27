//! The EGM options of `rapidvc run` (`--device`, `--egm-log`, `--lockstep`) and the EGM side of the controller they set up: device table, clock decision, [`EgmController`] and its cycle hook.

use std::path::PathBuf;
use std::sync::Arc;
use std::time::Duration;

use crate::config::Config;
use crate::config::devices::DeviceOverride;
use crate::controller::egm::{EgmController, EgmHook, EgmSetup};
use crate::egm::DriverOptions;
use crate::egm::driver::DEFAULT_REPLY_TIMEOUT;
use crate::egm::registry::RegistryConfig;
use crate::io::SignalTable;
use crate::report::Feed;
use crate::robot::Robot;

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
    /// Lockstep: the longest wait for one reply, milliseconds of real time.
    #[arg(long, value_name = "MS", default_value_t = DEFAULT_REPLY_TIMEOUT.as_millis() as u64)]
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
    /// The external devices (for the notice).
    pub external: Vec<String>,
}

impl EgmArgs {
    /// Builds the EGM side for `robot` with motion period `period` from the configuration
    /// directory's `cfg` and these options; `feed` reaches the trace and plot.
    pub fn prepare(
        &self,
        cfg: &Config,
        robot: &Robot,
        signals: Arc<SignalTable>,
        period: Duration,
        feed: Option<Feed>,
    ) -> Result<EgmPrepared, String> {
        let devices = cfg.device_table(&self.devices).map_err(|e| e.to_string())?;
        let external = devices.external_devices();
        let log: Option<Box<dyn std::io::Write + Send>> = match &self.egm_log {
            Some(path) => {
                let f = std::fs::File::create(path)
                    .map_err(|e| format!("cannot create {}: {e}", path.display()))?;
                Some(Box::new(std::io::BufWriter::new(f)))
            }
            None => None,
        };
        let driver = DriverOptions {
            tick: period,
            reply_timeout: Duration::from_millis(self.lockstep_timeout.max(1)),
            ..DriverOptions::default()
        };
        let setup = EgmSetup {
            registry: RegistryConfig::new(cfg.moc.clone(), devices),
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
/// sessions dropped (by cause) and the lockstep counts.
pub fn finish(controller: EgmController, args: &EgmArgs) -> Result<(), String> {
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
    if let Some(path) = &args.egm_log {
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
