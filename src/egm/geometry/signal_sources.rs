//! Signal sources of `EGMSetupAI` / `EGMSetupAO` / `EGMSetupGI`: I/O signals mapped to joints or to x, y, z, rx, ry, rz, read lock-free every EGM cycle.
//!
//! The logical signal value is used directly as degrees (joint mode) or as mm and degrees
//! (pose mode), as in the manual's example (`SetAO ao_MoveX, 150` for 150 mm). Group inputs
//! can only carry non-negative integers (the signal table refuses anything else), so a GI
//! source can only order non-negative values.
//!
//! Pose mode: the six values are the sensor pose `S` in the sensor frame: x, y, z in mm and
//! rx, ry, rz in degrees as **ZYX Euler angles**, `R = Rz(rz)·Ry(ry)·Rx(rx)` (the wire's
//! convention; docs/egm.md, "Signal sources"). A component without a signal keeps its start
//! value in the sensor frame ([`super::PoseGuidance::start_sensor_pose`], decomposed the
//! same way). Joint mode: an axis without a signal keeps its start value.

use nalgebra::Translation3;

use super::{DIRECTIONS, GuidanceError};
use crate::robot::units::{quat_from_euler_zyx_deg, quat_to_euler_zyx_deg};
use crate::robot::{JointsDeg, Pose};
use crate::signals::{IoError, SignalId, SignalKind, SignalTable};

/// Number of additional-axis signals (`\<p>E1` … `\<p>E6`).
pub const EXTERNAL_SIGNALS: usize = 6;

/// The signals of one `EGMSetupAI/AO/GI`: `mapping` = `R1x, R2y, R3z, R4rx, R5ry, R6rz`,
/// `ext` = `E1` … `E6`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct SignalSource {
    /// Robot values: joint 1…6 in joint mode, x, y, z, rx, ry, rz in pose mode.
    pub mapping: [Option<SignalId>; DIRECTIONS],
    /// Additional axes 1…6.
    pub ext: [Option<SignalId>; EXTERNAL_SIGNALS],
}

impl SignalSource {
    /// A source of `kind` (`Ai` for EGMSetupAI, `Ao` for EGMSetupAO, `Gi` for EGMSetupGI),
    /// checked against `table`: every id must exist and be of that kind, and at least one
    /// signal must be given.
    pub fn new(
        table: &SignalTable,
        kind: SignalKind,
        mapping: [Option<SignalId>; DIRECTIONS],
        ext: [Option<SignalId>; EXTERNAL_SIGNALS],
    ) -> Result<SignalSource, GuidanceError> {
        let instruction = instruction_of(kind)?;
        let mut any = false;
        for id in mapping.iter().chain(&ext).flatten() {
            any = true;
            let def = table.def(*id).ok_or_else(|| IoError::UnknownSignal {
                name: format!("#{}", id.index()),
            })?;
            if def.kind != kind {
                return Err(GuidanceError::WrongSignalKind {
                    name: def.name.clone(),
                    instruction,
                    expected: kind,
                    found: def.kind,
                });
            }
        }
        if !any {
            return Err(GuidanceError::NoSignals { instruction });
        }
        Ok(SignalSource { mapping, ext })
    }

    /// Like [`SignalSource::new`], with signal names (case-insensitive) instead of ids.
    pub fn from_names(
        table: &SignalTable,
        kind: SignalKind,
        mapping: [Option<&str>; DIRECTIONS],
        ext: [Option<&str>; EXTERNAL_SIGNALS],
    ) -> Result<SignalSource, GuidanceError> {
        let look = |n: Option<&str>| n.map(|n| table.lookup_or_err(n)).transpose();
        let [a, b, c, d, e, f] = mapping;
        let m = [look(a)?, look(b)?, look(c)?, look(d)?, look(e)?, look(f)?];
        let [a, b, c, d, e, f] = ext;
        let x = [look(a)?, look(b)?, look(c)?, look(d)?, look(e)?, look(f)?];
        SignalSource::new(table, kind, m, x)
    }

    /// The joint reference (degrees): each mapped joint the signal's value, the others
    /// `start`.
    pub fn joint_reference(
        &self,
        table: &SignalTable,
        start: &JointsDeg,
    ) -> Result<JointsDeg, GuidanceError> {
        let mut out = *start;
        self.read_into(table, &mut out)?;
        if out.iter().all(|v| v.is_finite()) {
            Ok(out)
        } else {
            Err(GuidanceError::NotFinite {
                what: "joint reference",
            })
        }
    }

    /// The sensor pose: mapped components from the signals (x, y, z mm; rx, ry, rz degrees,
    /// ZYX Euler), the others from `start_sensor_pose` (the TCP in the sensor frame at the
    /// start).
    pub fn sensor_pose(
        &self,
        table: &SignalTable,
        start_sensor_pose: &Pose,
    ) -> Result<Pose, GuidanceError> {
        let t = start_sensor_pose.translation.vector;
        let [ex, ey, ez] = quat_to_euler_zyx_deg(&start_sensor_pose.rotation);
        let mut v = [t.x, t.y, t.z, ex, ey, ez];
        self.read_into(table, &mut v)?;
        if !v.iter().all(|c| c.is_finite()) {
            return Err(GuidanceError::NotFinite {
                what: "sensor pose",
            });
        }
        let [x, y, z, rx, ry, rz] = v;
        Ok(Pose::from_parts(
            Translation3::new(x, y, z),
            quat_from_euler_zyx_deg(rx, ry, rz),
        ))
    }

    /// The additional-axis values (`None` where no signal is mapped).
    pub fn external(
        &self,
        table: &SignalTable,
    ) -> Result<[Option<f64>; EXTERNAL_SIGNALS], GuidanceError> {
        let mut out = [None; EXTERNAL_SIGNALS];
        for (o, id) in out.iter_mut().zip(&self.ext) {
            if let Some(id) = id {
                *o = Some(read(table, *id)?);
            }
        }
        Ok(out)
    }

    /// Overwrite `out[i]` with the value of every mapped signal `i` (one atomic load each).
    fn read_into(
        &self,
        table: &SignalTable,
        out: &mut [f64; DIRECTIONS],
    ) -> Result<(), GuidanceError> {
        for (o, id) in out.iter_mut().zip(&self.mapping) {
            if let Some(id) = id {
                *o = read(table, *id)?;
            }
        }
        Ok(())
    }
}

fn read(table: &SignalTable, id: SignalId) -> Result<f64, GuidanceError> {
    let v = table.value(id).ok_or(GuidanceError::NotFinite {
        what: "signal value (unknown signal id)",
    })?;
    if v.is_finite() {
        Ok(v)
    } else {
        Err(GuidanceError::NotFinite {
            what: "signal value",
        })
    }
}

fn instruction_of(kind: SignalKind) -> Result<&'static str, GuidanceError> {
    match kind {
        SignalKind::Ai => Ok("EGMSetupAI"),
        SignalKind::Ao => Ok("EGMSetupAO"),
        SignalKind::Gi => Ok("EGMSetupGI"),
        _ => Err(GuidanceError::Unsupported(
            "an EGM signal source other than AI, AO or GI signals",
        )),
    }
}

#[cfg(test)]
mod tests {
    #![allow(clippy::unwrap_used, clippy::indexing_slicing, clippy::panic)]

    use super::*;
    use crate::robot::units::pose_from_pos_quat;
    use crate::signals::SignalDef;

    fn table() -> SignalTable {
        let mut defs = crate::signals::builtin_signals();
        defs.push(SignalDef::analog("ai_X", SignalKind::Ai, -1000.0, 1000.0));
        defs.push(SignalDef::group("gi_J1", SignalKind::Gi, 16));
        defs.push(SignalDef::analog("ao_E1", SignalKind::Ao, -1000.0, 1000.0));
        SignalTable::new(defs).unwrap()
    }

    const NONE6: [Option<&str>; 6] = [None; 6];

    #[test]
    fn joint_mode_keeps_unmapped_axes() {
        let t = table();
        let src = SignalSource::from_names(
            &t,
            SignalKind::Ao,
            [
                None,
                Some("ao_MoveY"),
                Some("AO_MOVEZ"),
                None,
                None,
                Some("ao_RotZ"),
            ],
            [Some("ao_E1"), None, None, None, None, None],
        )
        .unwrap();
        t.set(t.lookup("ao_MoveY").unwrap(), -5.0).unwrap();
        t.set(t.lookup("ao_MoveZ").unwrap(), 12.5).unwrap();
        t.set(t.lookup("ao_E1").unwrap(), 300.0).unwrap();
        let start = [70.0, 1.0, 2.0, 3.0, 4.0, 5.0];
        let j = src.joint_reference(&t, &start).unwrap();
        assert_eq!(j, [70.0, -5.0, 12.5, 3.0, 4.0, 0.0]);
        let ext = src.external(&t).unwrap();
        assert_eq!(ext, [Some(300.0), None, None, None, None, None]);
        assert!(src.joint_reference(&t, &[f64::NAN; 6]).is_err());
    }

    #[test]
    fn pose_mode_euler_zyx_and_start_values() {
        let t = table();
        let src = SignalSource::from_names(
            &t,
            SignalKind::Ao,
            [
                Some("ao_MoveX"),
                None,
                Some("ao_MoveZ"),
                None,
                None,
                Some("ao_RotZ"),
            ],
            NONE6,
        )
        .unwrap();
        t.set(t.lookup("ao_MoveX").unwrap(), 150.0).unwrap();
        t.set(t.lookup("ao_MoveZ").unwrap(), 900.0).unwrap();
        t.set(t.lookup("ao_RotZ").unwrap(), 30.0).unwrap();
        let q0 = quat_from_euler_zyx_deg(10.0, -20.0, 5.0);
        let start = pose_from_pos_quat([1.0, 2.0, 3.0], [q0.w, q0.i, q0.j, q0.k]);
        let s = src.sensor_pose(&t, &start).unwrap();
        let p = s.translation.vector;
        assert_eq!([p.x, p.y, p.z], [150.0, 2.0, 900.0]);
        let e = quat_to_euler_zyx_deg(&s.rotation);
        assert!((e[0] - 10.0).abs() < 1e-9 && (e[1] + 20.0).abs() < 1e-9);
        assert!((e[2] - 30.0).abs() < 1e-9);
    }

    #[test]
    fn setup_checks() {
        let t = table();
        assert_eq!(
            SignalSource::from_names(&t, SignalKind::Ao, NONE6, NONE6),
            Err(GuidanceError::NoSignals {
                instruction: "EGMSetupAO"
            })
        );
        let e = SignalSource::from_names(
            &t,
            SignalKind::Ao,
            [Some("ai_X"), None, None, None, None, None],
            NONE6,
        )
        .unwrap_err();
        assert_eq!(
            e.to_string(),
            "signal `ai_X` is a AI signal, but EGMSetupAO takes AO signals"
        );
        let e = SignalSource::from_names(
            &t,
            SignalKind::Ai,
            [Some("nope"), None, None, None, None, None],
            NONE6,
        )
        .unwrap_err();
        assert!(matches!(
            e,
            GuidanceError::Signal(IoError::UnknownSignal { .. })
        ));
        assert!(matches!(
            SignalSource::from_names(
                &t,
                SignalKind::Do,
                [Some("ao_MoveX"), None, None, None, None, None],
                NONE6
            ),
            Err(GuidanceError::Unsupported(_))
        ));
        // An id from a bigger table is unknown here.
        let other = SignalTable::new(
            (0..40)
                .map(|i| SignalDef::analog(format!("s{i}"), SignalKind::Ao, 0.0, 1.0))
                .collect(),
        )
        .unwrap();
        let far = other.lookup("s39").unwrap();
        let mut m = [None; 6];
        m[0] = Some(far);
        assert!(SignalSource::new(&t, SignalKind::Ao, m, [None; 6]).is_err());
        let forged = SignalSource {
            mapping: m,
            ext: [None; 6],
        };
        assert!(forged.joint_reference(&t, &[0.0; 6]).is_err());
    }

    #[test]
    fn group_inputs_are_non_negative() {
        let t = table();
        let src = SignalSource::from_names(
            &t,
            SignalKind::Gi,
            [Some("gi_J1"), None, None, None, None, None],
            NONE6,
        )
        .unwrap();
        let id = t.lookup("gi_J1").unwrap();
        assert!(t.set(id, -10.0).is_err());
        t.set(id, 45.0).unwrap();
        assert_eq!(src.joint_reference(&t, &[0.0; 6]).unwrap()[0], 45.0);
    }
}
