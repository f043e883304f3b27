//! EGM messages a test sensor sends, encoded with rapidvc's own protobuf types.

use prost::Message;
use rapidvc::egm::proto;

/// An `EgmSensor` correction with joint reference `joints` (degrees) and sequence number
/// `seq` (`tm` = 4 ms per message).
pub fn joint_reply(seq: u32, joints: [f64; 6]) -> Vec<u8> {
    proto::EgmSensor {
        header: Some(correction_header(seq)),
        planned: Some(proto::EgmPlanned {
            joints: Some(proto::EgmJoints {
                joints: joints.to_vec(),
            }),
            ..Default::default()
        }),
        ..Default::default()
    }
    .encode_to_vec()
}

/// An `EgmSensor` correction with pose reference `pos` (mm) and `orient` (quaternion
/// `[w, x, y, z]`) in the correction frame, sequence number `seq` (`tm` = 4 ms per message).
pub fn pose_reply(seq: u32, pos: [f64; 3], orient: [f64; 4]) -> Vec<u8> {
    let [x, y, z] = pos;
    let [u0, u1, u2, u3] = orient;
    proto::EgmSensor {
        header: Some(correction_header(seq)),
        planned: Some(proto::EgmPlanned {
            cartesian: Some(proto::EgmPose {
                pos: Some(proto::EgmCartesian { x, y, z }),
                orient: Some(proto::EgmQuaternion { u0, u1, u2, u3 }),
                euler: None,
            }),
            ..Default::default()
        }),
        ..Default::default()
    }
    .encode_to_vec()
}

/// The header of a correction message with sequence number `seq` (`tm` = 4 ms per message).
fn correction_header(seq: u32) -> proto::EgmHeader {
    proto::EgmHeader {
        seqno: Some(seq),
        tm: Some(seq.wrapping_mul(4)),
        mtype: Some(proto::egm_header::MessageType::MsgtypeCorrection as i32),
    }
}
