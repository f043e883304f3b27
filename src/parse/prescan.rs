//! A linear scan before pest runs: bounds the nesting of brackets and blocks, so neither the
//! recursive-descent parser nor the builders nor later phases can exhaust the stack.

/// Byte classes of the scan.
const OTHER: u8 = 0;
const LETTER: u8 = 1;
/// A digit or `_`: inside a word, part of it; alone, nothing.
const DIGIT: u8 = 2;
const OPEN: u8 = 3;
const CLOSE: u8 = 4;
const BANG: u8 = 5;
const QUOTE: u8 = 6;

static CLASS: [u8; 256] = {
    let mut t = [OTHER; 256];
    let mut c = 0;
    while c < 256 {
        let b = c as u8;
        t[c] = match b {
            b'a'..=b'z' | b'A'..=b'Z' => LETTER,
            b'0'..=b'9' | b'_' => DIGIT,
            b'(' | b'[' | b'{' => OPEN,
            b')' | b']' | b'}' => CLOSE,
            b'!' => BANG,
            b'"' => QUOTE,
            _ => OTHER,
        };
        c += 1;
    }
    t
};

/// The first place where nesting exceeds `limit`: the byte range of the opening token.
pub(crate) fn too_deep(text: &str, limit: usize) -> Option<(usize, usize)> {
    let b = text.as_bytes();
    let class = |i: usize| b.get(i).map_or(OTHER, |&c| CLASS[usize::from(c)]);
    let mut depth: usize = 0;
    let mut i = 0;
    // Whether the last IF-like keyword was ELSEIF (its THEN opens no new block).
    let mut after_elseif = false;
    while i < b.len() {
        match class(i) {
            BANG => {
                // (A comment ends at LF or CR, as in the grammar.)
                i += b[i..]
                    .iter()
                    .position(|&c| c == b'\n' || c == b'\r')
                    .unwrap_or(b.len() - i);
            }
            QUOTE => {
                i += 1;
                i += b[i..]
                    .iter()
                    .position(|&c| c == b'"' || c == b'\n' || c == b'\r')
                    .unwrap_or(b.len() - i);
                i += 1;
            }
            OPEN => {
                depth += 1;
                if depth > limit {
                    return Some((i, i + 1));
                }
                i += 1;
            }
            CLOSE => {
                depth = depth.saturating_sub(1);
                i += 1;
            }
            LETTER => {
                let start = i;
                i += 1;
                while matches!(class(i), LETTER | DIGIT) {
                    i += 1;
                }
                let w = &b[start..i];
                // (Only words of up to 8 letters starting with W, F, T, I or E can open or
                // close a block.)
                if w.len() <= 8 && matches!(b[start] | 0x20, b'w' | b'f' | b't' | b'i' | b'e') {
                    let mut up = [0u8; 8];
                    for (d, s) in up.iter_mut().zip(w) {
                        *d = s.to_ascii_uppercase();
                    }
                    match &up[..w.len()] {
                        b"WHILE" | b"FOR" | b"TEST" => depth += 1,
                        b"IF" => after_elseif = false,
                        b"ELSEIF" => after_elseif = true,
                        b"THEN" if !after_elseif => depth += 1,
                        b"ENDIF" | b"ENDWHILE" | b"ENDFOR" | b"ENDTEST" => {
                            depth = depth.saturating_sub(1)
                        }
                        _ => {}
                    }
                    if depth > limit {
                        return Some((start, i));
                    }
                }
            }
            _ => i += 1,
        }
    }
    None
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn counts_brackets_and_blocks() {
        assert_eq!(too_deep("((( )))", 3), None);
        assert_eq!(too_deep("(((( ))))", 3), Some((3, 4)));
        assert_eq!(too_deep("\"((((\" ! ((((\n", 1), None);
        let ifs = "IF a THEN IF b THEN x; ELSEIF c THEN y; ENDIF ENDIF";
        assert_eq!(too_deep(ifs, 2), None);
        assert!(too_deep(ifs, 1).is_some());
        assert_eq!(
            too_deep("WHILE a DO [ ] ENDWHILE WHILE b DO ENDWHILE", 2),
            None
        );
        assert_eq!(too_deep("IFx THENy", 0), None);
    }
}
