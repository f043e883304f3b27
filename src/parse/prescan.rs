//! A linear scan before pest runs: bounds the nesting of brackets and blocks, so neither the
//! recursive-descent parser nor the builders nor later phases can exhaust the stack.

/// The first place where nesting exceeds `limit`: the byte range of the opening token.
pub(crate) fn too_deep(text: &str, limit: usize) -> Option<(usize, usize)> {
    let b = text.as_bytes();
    let mut depth: usize = 0;
    let mut i = 0;
    // Whether the last IF-like keyword was ELSEIF (its THEN opens no new block).
    let mut after_elseif = false;
    while i < b.len() {
        let c = b[i];
        match c {
            b'!' => {
                while i < b.len() && b[i] != b'\n' {
                    i += 1;
                }
                continue;
            }
            b'"' => {
                i += 1;
                while i < b.len() && b[i] != b'"' && b[i] != b'\n' {
                    i += 1;
                }
                i += 1;
                continue;
            }
            b'(' | b'[' | b'{' => {
                depth += 1;
                if depth > limit {
                    return Some((i, i + 1));
                }
            }
            b')' | b']' | b'}' => depth = depth.saturating_sub(1),
            c if c.is_ascii_alphabetic() => {
                let start = i;
                while i < b.len() && (b[i].is_ascii_alphanumeric() || b[i] == b'_') {
                    i += 1;
                }
                let w = &b[start..i];
                if w.len() <= 8 {
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
                continue;
            }
            _ => {}
        }
        i += 1;
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
