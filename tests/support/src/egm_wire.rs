//! EGM messages a test sensor sends, encoded with rapidvc's own protobuf types.

use prost::Message;
use rapidvc::egm::proto;

/// An `EgmSensor` correction with joint reference `joints` (degrees) and sequence number
/// `seq` (`tm` = 4 ms per message).
pub fn joint_reply(seq: u32, joints: [f64; 6]) -> Vec<u8> {
    proto::EgmSensor {
        header: Some(proto::EgmHeader {
            seqno: Some(seq),
            tm: Some(seq.wrapping_mul(4)),
            mtype: Some(proto::egm_header::MessageType::MsgtypeCorrection as i32),
        }),
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
