//! EGM event-log entries: an [`EventKind`] of the one event table ([`crate::events`]: ABB's
//! number where public, rapidvc's own 901xx otherwise) with a detail line.

use std::fmt;

pub use crate::events::EventKind;

/// One event-log entry: number, fixed title and a free-form detail line.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct EgmEvent {
    /// Event number (ABB's where known, else 901xx).
    pub number: u32,
    /// Fixed title of the event number.
    pub title: &'static str,
    /// What exactly happened.
    pub detail: String,
}

impl EgmEvent {
    /// An event of `kind` with a detail line.
    pub fn new(kind: EventKind, detail: impl Into<String>) -> Self {
        EgmEvent {
            number: kind.number(),
            title: kind.title(),
            detail: detail.into(),
        }
    }
}

impl fmt::Display for EgmEvent {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "{} {}: {}",
            self.number,
            self.title,
            shorten_numbers(&self.detail)
        )
    }
}

/// Longest run of digits a detail line keeps as written.
const MAX_DIGITS: usize = 15;

/// `text` with every decimal number longer than [`MAX_DIGITS`] digits (a sensor's 1e308 is
/// 309 of them in Rust's fixed form) written in exponent notation, as
/// [`crate::robot::error::msg_num`] writes it. Digits that are part of a name are kept.
fn shorten_numbers(text: &str) -> std::borrow::Cow<'_, str> {
    let b = text.as_bytes();
    let is_digit = |i: usize| b.get(i).is_some_and(u8::is_ascii_digit);
    let mut out = String::new();
    let mut copied = 0;
    let mut i = 0;
    while i < b.len() {
        let part_of_name = i > 0
            && b.get(i - 1)
                .is_some_and(|c| c.is_ascii_alphanumeric() || matches!(c, b'_' | b'.'));
        if !is_digit(i) || part_of_name {
            i += 1;
            continue;
        }
        let start = if i > 0 && b.get(i - 1) == Some(&b'-') {
            i - 1
        } else {
            i
        };
        let mut end = i;
        while is_digit(end) {
            end += 1;
        }
        if b.get(end) == Some(&b'.') && is_digit(end + 1) {
            end += 1;
            while is_digit(end) {
                end += 1;
            }
        }
        let digits = b
            .get(i..end)
            .map_or(0, |run| run.iter().filter(|c| c.is_ascii_digit()).count());
        if digits > MAX_DIGITS
            && let Some(x) = text.get(start..end).and_then(|t| t.parse::<f64>().ok())
        {
            out.push_str(text.get(copied..start).unwrap_or(""));
            out.push_str(&crate::robot::error::msg_num(x, None));
            copied = end;
        }
        i = end;
    }
    if copied == 0 {
        return std::borrow::Cow::Borrowed(text);
    }
    out.push_str(text.get(copied..).unwrap_or(""));
    std::borrow::Cow::Owned(out)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn long_numbers_in_details_are_written_with_an_exponent() {
        let huge = format!("{}", 1e308_f64);
        assert_eq!(huge.len(), 309);
        let e = EgmEvent::new(
            EventKind::OutOfBounds,
            format!("`planned.joints[0]` = {huge} is outside [-180, 180]"),
        );
        assert_eq!(
            e.to_string(),
            "90105 External Motion Interface input out of bounds: `planned.joints[0]` = 1e308 is outside [-180, 180]"
        );
        let tiny = format!("{}", -1e-300_f64);
        let e = EgmEvent::new(
            EventKind::InvalidReference,
            format!("x = {tiny}; seq 12345"),
        );
        assert_eq!(
            e.to_string(),
            "90104 Invalid EGM reference: x = -1e-300; seq 12345"
        );
        // Short numbers and digits in names stay as written.
        let text = "device sig_12345678901234567890 at 127.0.0.1:6510, 0.004 s, -2000.5";
        let e = EgmEvent::new(EventKind::Malformed, text);
        assert_eq!(
            e.to_string(),
            format!("90102 Malformed EGM datagram: {text}")
        );
    }
}
