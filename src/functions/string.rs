//! RAPID string functions: StrLen, StrPart, StrFind, StrMatch, StrMemb, StrMap, StrOrder, StrToByte/ByteToStr, the character-set constants and the 80-character limit.
//!
//! Strings are Rust `String`s; one RAPID character is one `char` (RAPID strings are
//! ISO-8859-1, so a controller never sees a character above U+00FF; a UTF-8 source file may
//! still hold one, and it counts as one character). Positions are 1-based.
//!
//! # Decisions (pinned by the tests below)
//!
//! * **Length limit**: a string value holds at most [`MAX_STRING_LEN`] = 80 characters; a
//!   longer result (concatenation, StrMap, NumToStr) is `ERR_STRTOOLNG`.
//! * **Positions**: `StrPart(s, pos, len)` needs `pos ≥ 1`, `len ≥ 0` and
//!   `pos + len − 1 ≤ StrLen(s)`; StrFind/StrMatch need `1 ≤ pos ≤ StrLen(s) + 1` (the
//!   position just after the end is allowed and finds nothing); StrMemb needs
//!   `1 ≤ pos ≤ StrLen(s)`. Anything else is `ERR_OUTOFBND`.
//! * **Not found**: StrFind and StrMatch return `StrLen(s) + 1`. An empty StrMatch pattern
//!   matches at `pos`.
//! * **StrMap**: a character found in `FromMap` (first occurrence) is replaced by the
//!   character at the same position of `ToMap`; when `ToMap` is shorter than that position
//!   the character is kept.
//! * **StrOrder**: TRUE when `Str1` comes before `Str2` or equals it, comparing character
//!   by character by their position in `Order` (its first occurrence); characters that
//!   `Order` does not hold come after all that it holds, among themselves by character
//!   code; a string that is the beginning of the other comes first.
//! * **Character sets**: [`STR_DIGIT`], [`STR_UPPER`], [`STR_LOWER`] follow the RAPID
//!   manual's ISO-8859-1 letter lists (upper case includes À–Þ except ×, lower case
//!   à–þ except ÷, plus ß and ÿ), so `StrMap(s, STR_LOWER, STR_UPPER)` upper-cases
//!   Latin-1 text (ß and ÿ have no upper-case partner and stay). [`STR_WHITE`] is the
//!   blank character plus the ASCII layout characters (tab, line feed, vertical tab, form
//!   feed, carriage return) — the manual's exact set is not verified.
//! * **StrToByte / ByteToStr**: formats decimal (default, `0`–`255`, no padding), `\Hex`
//!   (two upper-case digits, `0A`; input any case), `\Okt` (three digits, `012`), `\Bin`
//!   (eight digits, `00001010`) and `\Char` (one character, code 0–255). Text that is not a
//!   valid byte in the chosen format is `ERR_ARGVALERR`.

use super::{RtError, RtResult};

/// Maximum number of characters in a RAPID string.
pub const MAX_STRING_LEN: usize = 80;

/// `STR_DIGIT`: the decimal digits.
pub const STR_DIGIT: &str = "0123456789";

/// `STR_UPPER`: upper-case letters of ISO-8859-1.
pub const STR_UPPER: &str = "ABCDEFGHIJKLMNOPQRSTUVWXYZÀÁÂÃÄÅÆÇÈÉÊËÌÍÎÏÐÑÒÓÔÕÖØÙÚÛÜÝÞ";

/// `STR_LOWER`: lower-case letters of ISO-8859-1, position by position matching
/// [`STR_UPPER`], then `ß` and `ÿ`.
pub const STR_LOWER: &str = "abcdefghijklmnopqrstuvwxyzàáâãäåæçèéêëìíîïðñòóôõöøùúûüýþßÿ";

/// `STR_WHITE`: blank characters (space, tab, LF, VT, FF, CR).
pub const STR_WHITE: &str = " \t\n\u{0B}\u{0C}\r";

/// `StrLen(Str)`: the number of characters.
pub fn str_len(s: &str) -> usize {
    // ASCII text (checked a word at a time) has as many characters as bytes.
    if s.is_ascii() {
        s.len()
    } else {
        s.chars().count()
    }
}

/// Check the 80-character limit (`ERR_STRTOOLNG`).
pub fn check_len(s: &str) -> RtResult<()> {
    let len = str_len(s);
    if len > MAX_STRING_LEN {
        Err(RtError::StrTooLong { len })
    } else {
        Ok(())
    }
}

/// `a + b` for strings, within the 80-character limit.
pub fn concat(a: &str, b: &str) -> RtResult<String> {
    let len = str_len(a) + str_len(b);
    if len > MAX_STRING_LEN {
        return Err(RtError::StrTooLong { len });
    }
    let mut s = String::with_capacity(a.len() + b.len());
    s.push_str(a);
    s.push_str(b);
    Ok(s)
}

fn out_of_bounds(func: &'static str, reason: String) -> RtError {
    RtError::OutOfBounds { func, reason }
}

/// Check a search start position: `1 ≤ pos ≤ len + 1`; returns the 0-based index.
fn start_index(func: &'static str, pos: i64, len: usize) -> RtResult<usize> {
    if pos < 1 || pos > len as i64 + 1 {
        return Err(out_of_bounds(
            func,
            format!(
                "start position {pos} is outside 1..{} (string length {len})",
                len + 1
            ),
        ));
    }
    Ok((pos - 1) as usize)
}

/// `StrPart(Str, ChPos, Len)`: `len` characters from 1-based position `pos`.
pub fn str_part(s: &str, pos: i64, len: i64) -> RtResult<String> {
    let n = str_len(s);
    if pos < 1 {
        return Err(out_of_bounds(
            "StrPart",
            format!("start position {pos} is below 1"),
        ));
    }
    if len < 0 {
        return Err(out_of_bounds(
            "StrPart",
            format!("length {len} is negative"),
        ));
    }
    // pos ≥ 1 and len ≥ 0 here; saturating, as huge arguments (`1E30`) arrive as i64::MAX.
    let last = pos.saturating_add(len - 1);
    if last > n as i64 {
        return Err(out_of_bounds(
            "StrPart",
            format!("characters {pos}..{last} are past the end of the string (length {n})"),
        ));
    }
    Ok(s.chars()
        .skip((pos - 1) as usize)
        .take(len as usize)
        .collect())
}

/// `StrPart(text, p, l)` of ASCII text within its bounds: a slice (anything else goes to the
/// walk over characters of [`str_part`], and its errors).
///
/// Only the bytes up to the end of the part need to be ASCII: then they are as many
/// characters, and the part's character positions are its byte positions.
#[inline(always)]
pub fn ascii_part(text: &str, p: i64, l: i64) -> Option<&str> {
    if p < 1 || l < 0 {
        return None;
    }
    let end = usize::try_from(p.checked_add(l - 1)?).ok()?;
    let head = text.as_bytes().get(..end)?;
    if !head.is_ascii() {
        return None;
    }
    text.get((p - 1) as usize..end)
}

/// `StrFind(Str, ChPos, Set [\NotInSet])`: the position of the first character at or after
/// `pos` that is in `set` (or, with `not_in_set`, not in it); `StrLen + 1` when none.
pub fn str_find(s: &str, pos: i64, set: &str, not_in_set: bool) -> RtResult<usize> {
    let n = str_len(s);
    let start = start_index("StrFind", pos, n)?;
    let found = s
        .chars()
        .enumerate()
        .skip(start)
        .find(|&(_, c)| set.contains(c) != not_in_set)
        .map(|(i, _)| i + 1);
    Ok(found.unwrap_or(n + 1))
}

/// `StrMatch(Str, ChPos, Pattern)`: the position where `pattern` first occurs at or after
/// `pos`; `StrLen + 1` when it does not.
pub fn str_match(s: &str, pos: i64, pattern: &str) -> RtResult<usize> {
    let n = str_len(s);
    let start = start_index("StrMatch", pos, n)?;
    // The text from character `start` on; a match of the pattern's bytes starts at a
    // character boundary (the pattern is whole characters), so counting the characters
    // before it gives its position.
    let from = s.char_indices().nth(start).map_or(s.len(), |(b, _)| b);
    let tail = s.get(from..).unwrap_or("");
    let found = tail
        .find(pattern)
        .map(|b| start + tail.get(..b).map_or(0, str_len) + 1);
    Ok(found.unwrap_or(n + 1))
}

/// `StrMemb(Str, ChPos, Set)`: whether the character at `pos` is in `set`.
pub fn str_memb(s: &str, pos: i64, set: &str) -> RtResult<bool> {
    let n = str_len(s);
    if pos < 1 || pos > n as i64 {
        return Err(out_of_bounds(
            "StrMemb",
            format!("position {pos} is outside 1..{n} (string length {n})"),
        ));
    }
    Ok(s.chars()
        .nth((pos - 1) as usize)
        .is_some_and(|c| set.contains(c)))
}

/// `StrMap(Str, FromMap, ToMap)`: each character found in `from` is replaced by the
/// character at the same position in `to`.
pub fn str_map(s: &str, from: &str, to: &str) -> String {
    let to: Vec<char> = to.chars().collect();
    s.chars()
        .map(|c| {
            from.chars()
                .position(|f| f == c)
                .and_then(|i| to.get(i).copied())
                .unwrap_or(c)
        })
        .collect()
}

/// `StrOrder(Str1, Str2, Order)`: whether `a` comes before `b`, or equals it, in the
/// character order `order`.
pub fn str_order(a: &str, b: &str, order: &str) -> bool {
    let n = order.chars().count() as u64;
    let rank = |c: char| {
        order
            .chars()
            .position(|o| o == c)
            .map_or(n + u64::from(c), |i| i as u64)
    };
    for (x, y) in a.chars().zip(b.chars()) {
        if x != y {
            return rank(x) < rank(y);
        }
    }
    a.chars().count() <= b.chars().count()
}

/// The text format of StrToByte and ByteToStr.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum ByteFormat {
    /// Decimal, `0`–`255` (the default).
    #[default]
    Dec,
    /// `\Hex`: two hexadecimal digits.
    Hex,
    /// `\Okt`: three octal digits.
    Okt,
    /// `\Bin`: eight binary digits.
    Bin,
    /// `\Char`: the character with that code.
    Char,
}

/// `ByteToStr(BitVal [\Hex | \Okt | \Bin | \Char])`.
pub fn byte_to_str(b: u8, format: ByteFormat) -> String {
    match format {
        ByteFormat::Dec => b.to_string(),
        ByteFormat::Hex => format!("{b:02X}"),
        ByteFormat::Okt => format!("{b:03o}"),
        ByteFormat::Bin => format!("{b:08b}"),
        ByteFormat::Char => char::from(b).to_string(),
    }
}

/// `StrToByte(ConStr [\Hex | \Okt | \Bin | \Char])`.
pub fn str_to_byte(s: &str, format: ByteFormat) -> RtResult<u8> {
    let (radix, max_len) = match format {
        ByteFormat::Dec => (10, 3),
        ByteFormat::Hex => (16, 2),
        ByteFormat::Okt => (8, 3),
        ByteFormat::Bin => (2, 8),
        ByteFormat::Char => {
            let mut it = s.chars();
            return match (it.next(), it.next()) {
                (Some(c), None) if (c as u32) <= 0xFF => Ok(c as u32 as u8),
                _ => Err(RtError::arg(
                    "StrToByte",
                    format!("\"{s}\" is not a single character with a code 0-255"),
                )),
            };
        }
    };
    let ok_digits =
        !s.is_empty() && s.chars().count() <= max_len && s.chars().all(|c| c.is_digit(radix));
    let value = if ok_digits {
        u32::from_str_radix(s, radix).ok()
    } else {
        None
    };
    match value.and_then(|v| u8::try_from(v).ok()) {
        Some(b) => Ok(b),
        None => Err(RtError::arg(
            "StrToByte",
            format!("\"{s}\" is not a byte value in the {format:?} format"),
        )),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn str_order() {
        // ABB's StrOrder examples: "FIRST" before "SECOND", a string before its extension.
        assert!(super::str_order("FIRST", "SECOND", STR_UPPER));
        assert!(super::str_order("FIRST", "FIRSTB", STR_UPPER));
        assert!(!super::str_order("FIRSTB", "FIRST", STR_UPPER));
        assert!(super::str_order("SAME", "SAME", STR_UPPER));
        // The order given decides, not the character codes.
        assert!(super::str_order("B", "A", "BA"));
        assert!(!super::str_order("A", "B", "BA"));
        // Characters outside the order come after those in it, by code among themselves.
        assert!(super::str_order("A", "a", STR_UPPER));
        assert!(!super::str_order("a", "Z", STR_UPPER));
        assert!(super::str_order("a", "b", STR_UPPER));
        assert!(super::str_order("", "", ""));
    }

    #[test]
    fn len_and_limit() {
        assert_eq!(str_len(""), 0);
        assert_eq!(str_len("Robotics"), 8);
        assert_eq!(str_len("Åkerö"), 5);
        let s80 = "x".repeat(80);
        assert!(check_len(&s80).is_ok());
        assert_eq!(
            check_len(&"x".repeat(81)).unwrap_err(),
            RtError::StrTooLong { len: 81 }
        );
        assert_eq!(concat("ab", "cd").unwrap(), "abcd");
        assert_eq!(concat(&s80, "").unwrap(), s80);
        assert_eq!(concat(&s80, "y").unwrap_err().err_name(), "ERR_STRTOOLNG");
        // Characters, not bytes: 80 two-byte characters fit.
        assert!(concat(&"é".repeat(40), &"é".repeat(40)).is_ok());
    }

    #[test]
    fn str_part_bounds() {
        assert_eq!(str_part("Robotics", 1, 5).unwrap(), "Robot");
        assert_eq!(str_part("Robotics", 6, 3).unwrap(), "ics");
        assert_eq!(str_part("Robotics", 9, 0).unwrap(), "");
        assert_eq!(str_part("Robotics", 1, 0).unwrap(), "");
        assert_eq!(str_part("Åkerö", 2, 4).unwrap(), "kerö");
        assert_eq!(
            str_part("Robotics", 0, 1).unwrap_err().err_name(),
            "ERR_OUTOFBND"
        );
        assert_eq!(
            str_part("Robotics", 6, 4).unwrap_err().err_name(),
            "ERR_OUTOFBND"
        );
        // Huge arguments (a num of 1E30 arrives as i64::MAX) fail, they do not overflow.
        assert_eq!(
            str_part("Robotics", i64::MAX, i64::MAX)
                .unwrap_err()
                .err_name(),
            "ERR_OUTOFBND"
        );
        assert_eq!(
            str_part("Robotics", 10, 0).unwrap_err().err_name(),
            "ERR_OUTOFBND"
        );
        assert_eq!(
            str_part("Robotics", 1, -1).unwrap_err().err_name(),
            "ERR_OUTOFBND"
        );
        assert_eq!(
            str_part("abc", 2, 3).unwrap_err().to_string(),
            "StrPart: characters 2..4 are past the end of the string (length 3)"
        );
    }

    #[test]
    fn find_match_memb() {
        assert_eq!(str_find("Robotics", 1, STR_DIGIT, false).unwrap(), 9);
        assert_eq!(str_find("Robotics", 1, "stu", false).unwrap(), 5);
        assert_eq!(str_find("IRB 6400", 1, STR_DIGIT, false).unwrap(), 5);
        assert_eq!(str_find("IRB 6400", 1, STR_WHITE, false).unwrap(), 4);
        assert_eq!(str_find("IRB 6400", 1, STR_UPPER, true).unwrap(), 4);
        assert_eq!(str_find("abc", 4, "a", false).unwrap(), 4);
        assert_eq!(str_find("abcabc", 2, "a", false).unwrap(), 4);
        assert_eq!(
            str_find("abc", 5, "a", false).unwrap_err().err_name(),
            "ERR_OUTOFBND"
        );
        assert_eq!(
            str_find("abc", 0, "a", false).unwrap_err().err_name(),
            "ERR_OUTOFBND"
        );
        assert_eq!(str_match("Robotics", 1, "bo").unwrap(), 3);
        assert_eq!(str_match("Robotics", 4, "bo").unwrap(), 9);
        assert_eq!(str_match("abab", 2, "ab").unwrap(), 3);
        assert_eq!(str_match("abc", 2, "").unwrap(), 2);
        assert_eq!(str_match("abc", 1, "abcd").unwrap(), 4);
        assert_eq!(str_match("", 1, "a").unwrap(), 1);
        assert_eq!(
            str_match("äbäb", 2, "äb").unwrap(),
            3,
            "positions count characters"
        );
        assert_eq!(str_match("ääx", 3, "x").unwrap(), 3);
        assert_eq!(str_match("ää", 3, "").unwrap(), 3);
        assert_eq!(
            str_match("abc", 9, "a").unwrap_err().err_name(),
            "ERR_OUTOFBND"
        );
        assert!(str_memb("Robotics", 2, "aeiou").unwrap());
        assert!(!str_memb("Robotics", 3, "aeiou").unwrap());
        assert!(str_memb("S-2", 3, STR_DIGIT).unwrap());
        assert_eq!(
            str_memb("abc", 4, "a").unwrap_err().err_name(),
            "ERR_OUTOFBND"
        );
        assert_eq!(str_memb("", 1, "a").unwrap_err().err_name(), "ERR_OUTOFBND");
    }

    #[test]
    fn map_and_sets() {
        assert_eq!(str_map("Robotics", "aeiou", "AEIOU"), "RObOtIcs");
        assert_eq!(str_map("Robotics", STR_LOWER, STR_UPPER), "ROBOTICS");
        assert_eq!(
            str_map("ÅkerÖ straße", STR_UPPER, STR_LOWER),
            "åkerö straße"
        );
        assert_eq!(str_map("straße", STR_LOWER, STR_UPPER), "STRAßE");
        assert_eq!(str_map("abc", "abc", "x"), "xbc");
        assert_eq!(str_map("aaa", "aa", "xy"), "xxx");
        assert_eq!(str_len(STR_DIGIT), 10);
        assert_eq!(str_len(STR_UPPER), 56);
        assert_eq!(str_len(STR_LOWER), 58);
        assert!(!STR_UPPER.contains('×') && !STR_LOWER.contains('÷'));
        assert!(STR_WHITE.starts_with(' '));
    }

    #[test]
    fn bytes() {
        assert_eq!(byte_to_str(10, ByteFormat::Dec), "10");
        assert_eq!(byte_to_str(10, ByteFormat::Hex), "0A");
        assert_eq!(byte_to_str(10, ByteFormat::Okt), "012");
        assert_eq!(byte_to_str(10, ByteFormat::Bin), "00001010");
        assert_eq!(byte_to_str(65, ByteFormat::Char), "A");
        assert_eq!(byte_to_str(233, ByteFormat::Char), "é");
        assert_eq!(str_to_byte("10", ByteFormat::Dec).unwrap(), 10);
        assert_eq!(str_to_byte("0a", ByteFormat::Hex).unwrap(), 10);
        assert_eq!(str_to_byte("FF", ByteFormat::Hex).unwrap(), 255);
        assert_eq!(str_to_byte("012", ByteFormat::Okt).unwrap(), 10);
        assert_eq!(str_to_byte("377", ByteFormat::Okt).unwrap(), 255);
        assert_eq!(str_to_byte("00001010", ByteFormat::Bin).unwrap(), 10);
        assert_eq!(str_to_byte("A", ByteFormat::Char).unwrap(), 65);
        for (s, f) in [
            ("256", ByteFormat::Dec),
            ("", ByteFormat::Dec),
            ("-1", ByteFormat::Dec),
            ("1000", ByteFormat::Dec),
            ("G", ByteFormat::Hex),
            ("100", ByteFormat::Hex),
            ("400", ByteFormat::Okt),
            ("8", ByteFormat::Okt),
            ("2", ByteFormat::Bin),
            ("111111111", ByteFormat::Bin),
            ("AB", ByteFormat::Char),
            ("", ByteFormat::Char),
            ("€", ByteFormat::Char),
        ] {
            assert_eq!(
                str_to_byte(s, f).unwrap_err().err_name(),
                "ERR_ARGVALERR",
                "{s:?} {f:?}"
            );
        }
        for b in 0..=255u8 {
            for f in [
                ByteFormat::Dec,
                ByteFormat::Hex,
                ByteFormat::Okt,
                ByteFormat::Bin,
                ByteFormat::Char,
            ] {
                assert_eq!(str_to_byte(&byte_to_str(b, f), f).unwrap(), b);
            }
        }
    }
}
