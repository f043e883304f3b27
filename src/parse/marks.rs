//! The lexical pre-pass: a copy of the text for pest in which the two most frequent kinds of
//! tokens are marked, so the grammar matches them without its most expensive tests
//! (`grammar/marks_fast.pest`):
//!
//! * a name that is not a reserved word gets [`NAME`] instead of its first letter: pest then
//!   needs no reserved-word check for it;
//! * a literal aggregate gets [`OPEN`] and [`CLOSE`] instead of its outer brackets: pest then
//!   skips it with one search instead of parsing every number in it again (the builder reads
//!   it from the text as written).
//!
//! The copy has the same length and every replaced byte is ASCII, so positions and spans are
//! those of the text. The marks never change what the fast parser accepts or the extent of a
//! token, in any context:
//!
//! * A literal aggregate is marked only where [`literal_aggregate`] — this module's
//!   transcription of `plain_literal_aggregate` — matches, with the same extent. Pest reaches
//!   its first bracket either as a primary, where `literal_aggregate` is tried before any other
//!   rule that could start with `[`, or inside a skipped region, where `[` and the mark are both
//!   "any character".
//! * A name is marked only when the byte before it cannot end a token that looks at the name's
//!   first letter: not a letter, digit or `_` (the name would continue a longer word or a
//!   number such as `1e5`), not `<` (`<ID>` is a placeholder), not `.` after a digit (`1.e5`),
//!   and not any other character this module does not know to be a separator. Reserved words
//!   are never marked, and every rule that could match a name's first letter besides `ident`
//!   (keywords, operators, `TRUE`, exponents, `word` in skipped regions) fails on a name that is
//!   not reserved as it fails on the mark, or accepts the mark (`word`).
//! * Strings and comments are not marked. Where this scan and pest disagree about a string or
//!   comment (only in broken code), a mark inside pest's string or comment is just another
//!   character there.
//! * The mark characters themselves, wherever they occur in the text, are replaced by the
//!   neutral [`NEUTRAL`], which no rule treats differently from them.
//!
//! A differential test (every construct, mutated programs, edge cases) compares the trees
//! and diagnostics with and without the pre-pass.

use super::jobs;
use super::recover::RESERVED;

/// Replaces the first letter of a name that is not a reserved word.
pub(crate) const NAME: u8 = 0x03;
/// Replaces the `[` of a literal aggregate.
pub(crate) const OPEN: u8 = 0x01;
/// Replaces the `]` that closes a marked literal aggregate.
pub(crate) const CLOSE: u8 = 0x02;
/// Replaces the mark characters where the text itself holds them.
const NEUTRAL: u8 = 0x04;

/// Deepest literal aggregate the pre-pass reads (deeper ones are left to pest, which never
/// sees them: the nesting limit is checked first).
const MAX_DEPTH: usize = 64;

/// The marked copy of `text` (see the module documentation).
#[cfg(test)]
pub(crate) fn mark(text: &str) -> String {
    mark_alongside(text, 1, || ()).1
}

/// The marked copy of `text`, made on up to `threads` threads, and the result of `first`, run
/// on the calling thread meanwhile. The text is cut at line starts into runs marked each on
/// its own: nothing but a literal aggregate spans lines, and one that spans a cut is left
/// unmarked (an unmarked token is read by the plain rules, which is always correct).
pub(crate) fn mark_alongside<R>(
    text: &str,
    threads: usize,
    first: impl FnOnce() -> R,
) -> (R, String) {
    let b = text.as_bytes();
    let mut out = neutralised(b);
    let mut cuts = vec![0];
    for k in 1..threads.max(1) {
        let at = line_end(b, b.len() / threads * k) + 1;
        if at > cuts[cuts.len() - 1] && at < b.len() {
            cuts.push(at);
        }
    }
    cuts.push(b.len());
    let mut runs = Vec::with_capacity(cuts.len());
    let mut rest: &mut [u8] = &mut out;
    for w in cuts.windows(2) {
        let (run, tail) = std::mem::take(&mut rest).split_at_mut(w[1] - w[0]);
        rest = tail;
        runs.push((w[0], run));
    }
    // (A run left unmarked is read by the plain rules: slower, not different.)
    let (r, _) = jobs::run(threads, runs, |(from, run)| mark_run(b, run, from), first);
    // Only ASCII bytes were replaced by ASCII bytes: still UTF-8.
    let marked = String::from_utf8(out).unwrap_or_else(|_| text.to_string());
    (r, marked)
}

/// Mark `b[from..from + out.len()]` into `out` (which starts as its neutralised copy).
fn mark_run(b: &[u8], out: &mut [u8], from: usize) {
    let to = from + out.len();
    let mut i = from;
    while i < to {
        let c = b[i];
        match c {
            b'!' => i = line_end(b, i),
            b'"' => i = string(b, i).unwrap_or_else(|| line_end(b, i)),
            b'[' => match literal_aggregate(b, i, 0) {
                Some(end) if end <= to => {
                    out[i - from] = OPEN;
                    out[end - 1 - from] = CLOSE;
                    i = end;
                }
                _ => i += 1,
            },
            b'a'..=b'z' | b'A'..=b'Z' => {
                let end = word_end(b, i);
                if separated(b, i) && !is_reserved(&b[i..end]) {
                    out[i - from] = NAME;
                }
                i = end;
            }
            // A number, with any letters, digits, `_` and `.` stuck to it (`1e5`, `0x1F`,
            // `1.e3`, `1abc`): nothing in it is marked.
            b'0'..=b'9' => {
                i += b[i..]
                    .iter()
                    .position(|&c| !(IDENT_CHAR[usize::from(c)] || c == b'.'))
                    .unwrap_or(b.len() - i);
            }
            _ => i += 1,
        }
    }
}
/// The marked copy of `text[from..to]` alone (`from` and `to` at line starts or the text's
/// ends), made on this thread: what pest reads for one piece of a large file, so the file is
/// never copied whole. Offsets in it are shifted by `from`.
pub(crate) fn mark_range(text: &str, from: usize, to: usize) -> String {
    let Some(part) = text.get(from..to) else {
        return String::new();
    };
    let mut out = neutralised(part.as_bytes());
    mark_run(text.as_bytes(), &mut out, from);
    // Only ASCII bytes were replaced by ASCII bytes: still UTF-8.
    String::from_utf8(out).unwrap_or_else(|_| part.to_string())
}

/// The copy of `text` pest reads without the pre-pass: only the mark characters the text
/// itself holds are made neutral, so that pest sees the same characters as with the marks
/// wherever there are none (the text itself, not a copy, when it holds none, as nearly every
/// file). Tests compare the two parses: see `ParseOptions::lexical_marks`.
pub(crate) fn unmarked(text: &str) -> std::borrow::Cow<'_, str> {
    if !text.bytes().any(|c| c.wrapping_sub(OPEN) < 3) {
        return std::borrow::Cow::Borrowed(text);
    }
    std::borrow::Cow::Owned(
        String::from_utf8(neutralised(text.as_bytes())).unwrap_or_else(|_| text.to_string()),
    )
}

/// `b` with the mark characters it holds replaced by [`NEUTRAL`] (rare: only in binary junk).
fn neutralised(b: &[u8]) -> Vec<u8> {
    let mut out = b.to_vec();
    // (Branch-free, so the compiler vectorises it: OPEN, CLOSE and NAME are 1, 2 and 3.)
    for o in &mut out {
        *o = if o.wrapping_sub(OPEN) < 3 {
            NEUTRAL
        } else {
            *o
        };
    }
    out
}

/// Letters, digits and `_`.
static IDENT_CHAR: [bool; 256] = {
    let mut t = [false; 256];
    let mut c = 0;
    while c < 256 {
        t[c] = (c as u8).is_ascii_alphanumeric() || c as u8 == b'_';
        c += 1;
    }
    t
};

/// Whether the byte before the name at `i` lets a mark there change nothing (see the module
/// documentation).
fn separated(b: &[u8], i: usize) -> bool {
    let Some(&prev) = i.checked_sub(1).and_then(|p| b.get(p)) else {
        return true;
    };
    match prev {
        b' ' | b'\t' | b'\n' | b'\r' | 0x0B | 0x0C => true,
        b',' | b';' | b'(' | b')' | b'[' | b']' | b'{' | b'}' | b':' | b'=' | b'\\' | b'+'
        | b'-' | b'*' | b'/' | b'%' | b'?' | b'|' | b'>' => true,
        // A component (`p.x`, `f(a).x`, `a{1}.x`), not the end of a number (`1.e5`).
        b'.' => i
            .checked_sub(2)
            .and_then(|p| b.get(p))
            .is_some_and(|&c| c.is_ascii_alphabetic() || matches!(c, b'_' | b')' | b'}')),
        _ => false,
    }
}

/// The end of the letters, digits and `_` from `i`.
fn word_end(b: &[u8], i: usize) -> usize {
    b[i..]
        .iter()
        .position(|&c| !IDENT_CHAR[usize::from(c)])
        .map_or(b.len(), |n| i + n)
}

/// The position of the LF or CR that ends the line holding `i` (or the end of the text).
fn line_end(b: &[u8], i: usize) -> usize {
    b[i..]
        .iter()
        .position(|&c| c == b'\n' || c == b'\r')
        .map_or(b.len(), |n| i + n)
}

/// The reserved words as numbers (upper-case ASCII, little-endian), sorted for a binary search
/// without string comparisons.
static RESERVED_KEYS: [u128; RESERVED.len()] = {
    let mut keys = [0u128; RESERVED.len()];
    let mut k = 0;
    while k < RESERVED.len() {
        keys[k] = key(RESERVED[k].as_bytes());
        k += 1;
    }
    // (Insertion sort: the list is short and this runs at compile time.)
    let mut i = 1;
    while i < keys.len() {
        let mut j = i;
        while j > 0 && keys[j - 1] > keys[j] {
            let t = keys[j];
            keys[j] = keys[j - 1];
            keys[j - 1] = t;
            j -= 1;
        }
        i += 1;
    }
    keys
};

/// A word of up to 16 ASCII letters as a number, upper-cased.
const fn key(word: &[u8]) -> u128 {
    let mut k = 0u128;
    let mut i = 0;
    while i < word.len() {
        k |= (word[i].to_ascii_uppercase() as u128) << (8 * i);
        i += 1;
    }
    k
}

/// A reserved word (letters only, any case)?
fn is_reserved(word: &[u8]) -> bool {
    (2..=9).contains(&word.len())
        && word.iter().all(u8::is_ascii_alphabetic)
        && RESERVED_KEYS.binary_search(&key(word)).is_ok()
}

// ---- `plain_literal_aggregate` (grammar/expr.pest), transcribed ----
//
// Each function returns the end of what the rule matches at `i`, or `None` where it fails:
// the same extents, including PEG's greedy, non-backtracking repetitions and options.

/// `plain_literal_aggregate` at `i` (which holds `[`).
pub(crate) fn literal_aggregate(b: &[u8], i: usize, depth: usize) -> Option<usize> {
    if depth >= MAX_DEPTH {
        return None;
    }
    // '[' ~ (lit_item | lit_ws ~ lit_item)
    let mut i = item(b, ws(b, i + 1), depth)?;
    // ((',' | lit_ws ~ ',') ~ (lit_item | lit_ws ~ lit_item))*
    loop {
        let j = ws(b, i);
        if b.get(j) != Some(&b',') {
            break;
        }
        match item(b, ws(b, j + 1), depth) {
            Some(k) => i = k,
            None => break,
        }
    }
    // (']' | lit_ws ~ ']')
    let j = ws(b, i);
    (b.get(j) == Some(&b']')).then_some(j + 1)
}

/// `lit_item`.
fn item(b: &[u8], i: usize, depth: usize) -> Option<usize> {
    match *b.get(i)? {
        b'0'..=b'9' | b'.' => number(b, i),
        b'[' => literal_aggregate(b, i, depth + 1),
        b'-' | b'+' => number(b, ws(b, i + 1)),
        b'"' => string(b, i),
        b'T' | b't' => b
            .get(i..i + 4)
            .filter(|w| w.eq_ignore_ascii_case(b"TRUE"))
            .map(|_| i + 4),
        b'F' | b'f' => b
            .get(i..i + 5)
            .filter(|w| w.eq_ignore_ascii_case(b"FALSE"))
            .map(|_| i + 5),
        _ => None,
    }
}

/// `lit_number`: `(digits ('.' digits?)? | '.' digits) (('e'|'E') ('+'|'-')? digits)?`.
fn number(b: &[u8], i: usize) -> Option<usize> {
    let digits = |mut i: usize| {
        while b.get(i).is_some_and(u8::is_ascii_digit) {
            i += 1;
        }
        i
    };
    let mut end = match b.get(i)? {
        c if c.is_ascii_digit() => {
            let j = digits(i);
            if b.get(j) == Some(&b'.') {
                digits(j + 1)
            } else {
                j
            }
        }
        b'.' => {
            let j = digits(i + 1);
            if j == i + 1 {
                return None;
            }
            j
        }
        _ => return None,
    };
    if let Some(b'e' | b'E') = b.get(end) {
        let mut k = end + 1;
        if let Some(b'+' | b'-') = b.get(k) {
            k += 1;
        }
        let j = digits(k);
        if j > k {
            end = j;
        }
    }
    Some(end)
}

/// `string`: `"` then anything but `"`, CR and LF, or `""`, then `"`.
fn string(b: &[u8], i: usize) -> Option<usize> {
    let mut j = i + 1;
    loop {
        match *b.get(j)? {
            b'"' if b.get(j + 1) == Some(&b'"') => j += 2,
            b'"' => return Some(j + 1),
            b'\n' | b'\r' => return None,
            _ => j += 1,
        }
    }
}

/// `lit_ws`: white space (Unicode `White_Space`) and comments.
#[inline]
fn ws(b: &[u8], mut i: usize) -> usize {
    while let Some(&c) = b.get(i) {
        match c {
            b' ' | b'\t'..=b'\r' => i += 1,
            b'!' => i = line_end(b, i),
            c if c >= 0x80 => {
                let ch = std::str::from_utf8(&b[i..b.len().min(i + 4)])
                    .or_else(|e| std::str::from_utf8(&b[i..i + e.valid_up_to()]))
                    .ok()
                    .and_then(|s| s.chars().next());
                match ch {
                    Some(ch) if ch.is_whitespace() => i += ch.len_utf8(),
                    _ => return i,
                }
            }
            _ => return i,
        }
    }
    i
}

#[cfg(test)]
mod tests {
    use pest::Parser;

    use super::*;
    use crate::parse::grammar::diag::{DiagParser, Rule};

    /// Pest's `plain_literal_aggregate` at the start of `text`: its extent, if it matches.
    fn pest_literal(text: &str) -> Option<usize> {
        DiagParser::parse(Rule::plain_literal_aggregate, text)
            .ok()
            .and_then(|mut p| p.next())
            .map(|p| p.as_span().end())
    }

    #[test]
    fn the_literal_aggregate_transcription_agrees_with_the_grammar() {
        let cases = [
            "[1,2]",
            "[1, 2]",
            "[ 1 , 2 ]",
            "[1 ! c\n,2]",
            "[TRUE,false]",
            "[TRUEx]",
            "[1e]",
            "[1e5]",
            "[1E+5,2e-3]",
            "[.5,1.]",
            "[1.2.3]",
            "[--1]",
            "[- 1]",
            "[+ 1.5]",
            "[\"a\"\"b\",\"c\"]",
            "[[1],[2,[3]]]",
            "[]",
            "[1 2]",
            "[a,1]",
            "[1,a]",
            "[1-2]",
            "[1,-2e]",
            "[0x1F]",
            "[1,\"x]",
            "[\u{3000} 1]",
            "[1 \u{a0},2]",
            "[1,\u{2}]",
            "[9E+09,9E+09]",
            "[1,TRUE1]",
            "[1_]",
            "[1.e3]",
            "[.e3]",
            "[1,\n2]",
            "[1,!x\n2]",
            "[1]!c",
            "[1]x",
            "[[1,2],[3,4]].x",
            "[1",
            "[",
            "[1,",
            "[\"a\nb\"]",
            "[1,\r\n2]",
            "[-.5]",
            "[+.]",
            "[1.5e+]",
            "[ [ 1 ] ]",
            "[1,[2]",
            "[\"]\"]",
            "[1 !]\n]",
        ];
        for c in cases {
            assert_eq!(
                literal_aggregate(c.as_bytes(), 0, 0),
                pest_literal(c),
                "{c:?}"
            );
        }
        // Generated ones: every character the rule cares about, in every order.
        let alphabet = [
            "[", "]", ",", " ", "1", "2", ".", "e", "E", "+", "-", "\"", "!", "\n", "T", "RUE",
            "x", "\u{3000}",
        ];
        let mut x: u64 = 0x9e37_79b9_7f4a_7c15;
        for _ in 0..20_000 {
            let mut t = String::from("[");
            for _ in 0..(x % 12) {
                x ^= x << 13;
                x ^= x >> 7;
                x ^= x << 17;
                t.push_str(alphabet[(x % alphabet.len() as u64) as usize]);
            }
            x = x.wrapping_mul(6364136223846793005).wrapping_add(1);
            assert_eq!(
                literal_aggregate(t.as_bytes(), 0, 0),
                pest_literal(&t),
                "{t:?}"
            );
        }
    }

    #[test]
    fn rust_white_space_is_pest_white_space() {
        for c in (0..=0x10FFFFu32).filter_map(char::from_u32) {
            assert_eq!(c.is_whitespace(), pest::unicode::WHITE_SPACE(c), "{c:?}");
        }
    }

    #[test]
    fn reserved_words_are_sorted_and_recognised() {
        assert!(RESERVED.iter().all(|w| w.len() <= 16));
        for w in RESERVED {
            assert!(is_reserved(w.as_bytes()));
            assert!(is_reserved(w.to_ascii_lowercase().as_bytes()));
        }
        for w in ["ENDIFX", "IFF", "X", "tBench", "MoveL", "ELS", "p10"] {
            assert!(!is_reserved(w.as_bytes()), "{w}");
        }
    }

    #[test]
    fn marks() {
        let m = mark("MoveL p1, v500\\WObj:=w; x := [1,-2,[3]]; IF a.b THEN");
        assert_eq!(
            m,
            "\u{3}oveL \u{3}1, \u{3}500\\\u{3}Obj:=\u{3}; \u{3} := \u{1}1,-2,[3]\u{2}; IF \u{3}.\u{3} THEN"
        );
        // Not after a digit, `<` or a number's `.`; not in strings or comments.
        assert_eq!(
            mark("1abc <ID> 1.e5 \"a b\" ! c d"),
            "1abc <ID> 1.e5 \"a b\" ! c d"
        );
        // Mark characters in the text become neutral.
        assert_eq!(mark("a\u{1}\u{2}\u{3}"), "\u{3}\u{4}\u{4}\u{4}");
        // Same length, always.
        let text = "x\u{3000}y é [1,\"é\"] z";
        assert_eq!(mark(text).len(), text.len());
    }
}
