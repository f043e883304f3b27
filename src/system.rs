//! The controller's operating-system side that RAPID reaches through the
//! [`Host`](crate::interp::Host): the calendar clock (`CDate`, `CTime`, `GetTime`), what the
//! system says about itself (`GetSysInfo`, `OpMode`, `GetTaskName`, the mechanical units, the
//! active tool, work object and payload), the configuration database (`ReadCfgData`,
//! `WriteCfgData`, `SaveCfgData`) and the installed text tables (`TextGet`).
//!
//! It holds plain state and pure rules, no threads and no clock of its own: times come in as
//! the host's seconds since the program started. Both hosts own one [`Services`]
//! (`interp::VirtualHost`, and `controller::ControllerHost` through it) and hand it to the
//! natives through `Host::system`.

pub mod backup_defaults;
pub mod calendar;
pub mod cfg_data;
pub mod info;
pub mod sockets;
pub mod text_tables;

/// The controller's system side of one program run.
#[derive(Debug, Default)]
pub struct Services {
    /// The calendar: controller date and time from robot time.
    pub calendar: calendar::Calendar,
    /// Identity, operating mode, task, mechanical units and active system data.
    pub info: info::SystemInfo,
    /// The configuration database (the loaded CFG files).
    pub cfg: cfg_data::CfgData,
    /// The installed text tables.
    pub texts: text_tables::TextTables,
    /// The task's sockets (`SocketCreate` … `SocketClose`).
    pub sockets: sockets::Sockets,
}

/// A copy of the system side for another run (`rapidvc test` runs each test on one): the
/// same calendar, identity, configuration and texts, and no open sockets.
impl Clone for Services {
    fn clone(&self) -> Self {
        Services {
            calendar: self.calendar,
            info: self.info.clone(),
            cfg: self.cfg.clone(),
            texts: self.texts.clone(),
            sockets: sockets::Sockets::default(),
        }
    }
}
