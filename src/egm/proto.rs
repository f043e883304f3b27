//! Generated prost types for `proto/egm.proto` (package `abb.egm`) plus readable accessors.
//!
//! prost derives Rust names from ABB's field names, which gives a few odd identifiers
//! (`feed_back`, `rapi_dfrom_robot`, `rapi_dto_robot`, `EgmRapiDdata`). The hand-written
//! accessors and the alias below give them readable names; the generated fields stay public.

#[allow(missing_docs, clippy::all, clippy::pedantic)]
mod generated {
    include!(concat!(env!("OUT_DIR"), "/abb.egm.rs"));
}

pub use generated::*;

/// ABB's `EgmRAPIDdata` (RobotWare 7.7): one digital value and up to 40 `dnum` values.
pub type EgmRapidData = EgmRapiDdata;

impl EgmRobot {
    /// `feedBack` (field 2): measured position and its time.
    pub fn feedback(&self) -> Option<&EgmFeedBack> {
        self.feed_back.as_ref()
    }

    /// Mutable `feedBack`, created empty when absent.
    pub fn feedback_mut(&mut self) -> &mut EgmFeedBack {
        self.feed_back.get_or_insert_with(EgmFeedBack::default)
    }

    /// `RAPIDfromRobot` (field 13, RobotWare 7.7): data the RAPID program sends to the sensor.
    pub fn rapid_from_robot(&self) -> Option<&EgmRapidData> {
        self.rapi_dfrom_robot.as_ref()
    }

    /// Sets or clears `RAPIDfromRobot`.
    pub fn set_rapid_from_robot(&mut self, data: Option<EgmRapidData>) {
        self.rapi_dfrom_robot = data;
    }
}

impl EgmSensor {
    /// `RAPIDtoRobot` (field 4, RobotWare 7.7): data the sensor sends to the RAPID program.
    pub fn rapid_to_robot(&self) -> Option<&EgmRapidData> {
        self.rapi_dto_robot.as_ref()
    }

    /// Sets or clears `RAPIDtoRobot`.
    pub fn set_rapid_to_robot(&mut self, data: Option<EgmRapidData>) {
        self.rapi_dto_robot = data;
    }
}
