//! Wire-level presence check for proto2 `required` leaves, which prost does not enforce.
//!
//! prost decodes a missing `required double` as 0.0, so an `EgmQuaternion` without `u0` would
//! silently become a different rotation. Google's C++ parser (used by ABB and libegm) rejects
//! such a message. This walker re-reads the raw bytes of an already successfully decoded
//! message and reports which field numbers are present at a nested path, so the converter can
//! reject incomplete leaves the way a real controller is assumed to.

/// Wire types of the protobuf encoding.
const VARINT: u64 = 0;
const FIXED64: u64 = 1;
const LEN: u64 = 2;
const FIXED32: u64 = 5;

/// Bit mask of the field numbers 1..=31 present in the (sub)message at `path`, taking the
/// union over every occurrence (protobuf merges repeated occurrences of a sub-message).
/// `None` when the sub-message never occurs or the bytes cannot be walked.
pub(crate) fn fields_at(bytes: &[u8], path: &[u32]) -> Option<u32> {
    let mut reader = Reader { bytes, pos: 0 };
    let mut found: Option<u32> = None;
    while !reader.at_end() {
        let key = reader.varint()?;
        let field = key >> 3;
        let wire = key & 7;
        let payload = match wire {
            VARINT => {
                reader.varint()?;
                None
            }
            FIXED64 => {
                reader.skip(8)?;
                None
            }
            FIXED32 => {
                reader.skip(4)?;
                None
            }
            LEN => {
                let len = usize::try_from(reader.varint()?).ok()?;
                Some(reader.take(len)?)
            }
            // Groups (3, 4) are not used by EGM; stop walking.
            _ => return None,
        };
        match path.split_first() {
            None => {
                if (1..32).contains(&field) {
                    found = Some(found.unwrap_or(0) | (1u32 << field));
                } else {
                    found = Some(found.unwrap_or(0));
                }
            }
            Some((&head, rest)) => {
                if u64::from(head) == field
                    && let Some(sub) = payload
                    && let Some(mask) = fields_at(sub, rest)
                {
                    found = Some(found.unwrap_or(0) | mask);
                }
            }
        }
    }
    if path.is_empty() && found.is_none() {
        // The message itself exists (it was reached) even when it has no fields.
        return Some(0);
    }
    found
}

/// True when every field number in `required` has its bit set in `mask`.
pub(crate) fn has_all(mask: u32, required: &[u32]) -> bool {
    required.iter().all(|&f| f < 32 && mask & (1u32 << f) != 0)
}

struct Reader<'a> {
    bytes: &'a [u8],
    pos: usize,
}

impl<'a> Reader<'a> {
    fn at_end(&self) -> bool {
        self.pos >= self.bytes.len()
    }

    fn varint(&mut self) -> Option<u64> {
        let mut value: u64 = 0;
        for shift in (0..70).step_by(7) {
            let byte = *self.bytes.get(self.pos)?;
            self.pos += 1;
            if shift < 64 {
                value |= u64::from(byte & 0x7f) << shift;
            }
            if byte & 0x80 == 0 {
                return Some(value);
            }
        }
        None
    }

    fn skip(&mut self, n: usize) -> Option<()> {
        self.take(n).map(|_| ())
    }

    fn take(&mut self, n: usize) -> Option<&'a [u8]> {
        let end = self.pos.checked_add(n)?;
        let slice = self.bytes.get(self.pos..end)?;
        self.pos = end;
        Some(slice)
    }
}

#[cfg(test)]
#[allow(clippy::unwrap_used, clippy::indexing_slicing, clippy::panic)]
mod tests {
    use super::*;
    use crate::egm::proto::{EgmCartesian, EgmPlanned, EgmPose, EgmQuaternion, EgmSensor};
    use prost::Message;

    fn pose_msg() -> Vec<u8> {
        EgmSensor {
            planned: Some(EgmPlanned {
                cartesian: Some(EgmPose {
                    pos: Some(EgmCartesian {
                        x: 1.0,
                        y: 2.0,
                        z: 3.0,
                    }),
                    orient: Some(EgmQuaternion {
                        u0: 1.0,
                        u1: 0.0,
                        u2: 0.0,
                        u3: 0.0,
                    }),
                    euler: None,
                }),
                ..EgmPlanned::default()
            }),
            ..EgmSensor::default()
        }
        .encode_to_vec()
    }

    #[test]
    fn finds_required_leaves() {
        let bytes = pose_msg();
        assert_eq!(fields_at(&bytes, &[2, 2, 1]), Some(0b1110));
        assert_eq!(fields_at(&bytes, &[2, 2, 2]), Some(0b11110));
        assert_eq!(fields_at(&bytes, &[2, 2, 3]), None);
        assert_eq!(fields_at(&bytes, &[2, 2]), Some(0b110));
        assert!(has_all(0b1110, &[1, 2, 3]));
        assert!(!has_all(0b0110, &[1, 2, 3]));
    }

    #[test]
    fn detects_a_missing_leaf() {
        // planned { cartesian { pos { x: 1.0, y: 2.0 } } } written by hand without z.
        let mut pos = vec![0x09];
        pos.extend_from_slice(&1.0f64.to_le_bytes());
        pos.push(0x11);
        pos.extend_from_slice(&2.0f64.to_le_bytes());
        let mut cart = vec![0x0a, u8::try_from(pos.len()).unwrap_or(0)];
        cart.extend_from_slice(&pos);
        let mut planned = vec![0x12, u8::try_from(cart.len()).unwrap_or(0)];
        planned.extend_from_slice(&cart);
        let mut msg = vec![0x12, u8::try_from(planned.len()).unwrap_or(0)];
        msg.extend_from_slice(&planned);
        assert!(
            EgmSensor::decode(msg.as_slice()).is_ok(),
            "prost accepts it"
        );
        assert_eq!(fields_at(&msg, &[2, 2, 1]), Some(0b110));
    }

    #[test]
    fn merges_repeated_occurrences() {
        // Two `planned` sub-messages, the first with joints, the second with cartesian.
        let mut bytes = vec![0x12, 0x00];
        bytes.extend_from_slice(&pose_msg());
        assert_eq!(fields_at(&bytes, &[2]), Some(0b100));
        assert_eq!(fields_at(&[], &[]), Some(0));
        assert_eq!(fields_at(&[0xff], &[]), None);
    }
}
