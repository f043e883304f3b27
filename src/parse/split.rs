//! Where a large module body may be cut so its pieces parse on several threads.
//!
//! A line whose first word is `PROC`, `FUNC` or `TRAP` (possibly after `LOCAL`) starts a
//! routine in every program that parses cleanly: those words are reserved, a RAPID string
//! cannot span lines and a comment ends at its line's end, so such a line is never inside a
//! string, a comment, an expression or another routine's body (a routine without its end
//! keyword is a syntax error). The driver in `build.rs` parses the pieces between such lines
//! separately and, when any piece reports a problem, throws the pieces away and parses the
//! module from the start in one go, so the cuts can never change what is accepted nor which
//! diagnostics a broken file gets.

/// Byte offsets (into `text`) of the lines of the module body starting at `from` that begin a
/// routine, in order, up to the first line that begins with `ENDMODULE` (the end of that
/// module); at most one per `min_gap` bytes.
pub(crate) fn routine_starts(text: &str, from: usize, min_gap: usize) -> Vec<usize> {
    let mut out = Vec::new();
    let b = text.as_bytes();
    let mut line = from;
    // (The body starts after the module head, not necessarily at a line start: the head's own
    // line is never a routine start.)
    if from > 0 && b.get(from - 1) != Some(&b'\n') {
        line = next_line(b, from);
    }
    while line < b.len() {
        let (word, after) = word_at(b, skip_blanks(b, line));
        if eq(word, b"ENDMODULE") {
            break;
        }
        let starts = if eq(word, b"LOCAL") {
            let (next, _) = word_at(b, skip_blanks(b, after));
            is_routine_keyword(next)
        } else {
            is_routine_keyword(word)
        };
        if starts && out.last().is_none_or(|&prev| line - prev >= min_gap) {
            out.push(line);
        }
        line = next_line(b, line);
    }
    out
}

fn is_routine_keyword(word: &[u8]) -> bool {
    eq(word, b"PROC") || eq(word, b"FUNC") || eq(word, b"TRAP")
}

/// Whether `word` is `keyword` (upper case) in any case.
fn eq(word: &[u8], keyword: &[u8]) -> bool {
    word.eq_ignore_ascii_case(keyword)
}

/// The offset of the line after the one holding `i` (the text's length at the end).
fn next_line(b: &[u8], i: usize) -> usize {
    b[i..]
        .iter()
        .position(|&c| c == b'\n')
        .map_or(b.len(), |n| i + n + 1)
}

/// The first offset from `i` that is not a space or a tab.
fn skip_blanks(b: &[u8], mut i: usize) -> usize {
    while matches!(b.get(i), Some(b' ' | b'\t')) {
        i += 1;
    }
    i
}

/// The word (letters, digits, `_`) at `i`, and the offset after it. A word must end at a
/// character that cannot continue a name.
fn word_at(b: &[u8], i: usize) -> (&[u8], usize) {
    let mut j = i;
    while b
        .get(j)
        .is_some_and(|c| c.is_ascii_alphanumeric() || *c == b'_')
    {
        j += 1;
    }
    (&b[i..j], j)
}

#[cfg(test)]
mod tests {
    use super::routine_starts;

    #[test]
    fn finds_routine_lines_up_to_the_module_end() {
        let text = "MODULE m\n  VAR num x;\n  PROC a()\n    x := 1;\n  ENDPROC\n\
                    local func num f()\n  RETURN 1;\nENDFUNC\n\tTRAP t\n  ENDTRAP\n\
                    ENDMODULE\nMODULE n\nPROC b()\nENDPROC\nENDMODULE\n";
        let starts = routine_starts(text, 8, 0);
        let lines: Vec<&str> = starts
            .iter()
            .map(|&s| text[s..].lines().next().unwrap_or(""))
            .collect();
        assert_eq!(lines, ["  PROC a()", "local func num f()", "\tTRAP t"]);
    }

    #[test]
    fn words_that_only_begin_with_a_keyword_are_not_routine_starts() {
        let text = "MODULE m\nPROCEDURE;\nLOCAL VAR num PROC;\nFUNCx\n  ! PROC in a comment\n\
                    PROC_a;\nPROC p()\nENDPROC\nENDMODULE\n";
        let starts = routine_starts(text, 8, 0);
        assert_eq!(starts.len(), 1);
        assert!(text[starts[0]..].starts_with("PROC p()"));
    }

    #[test]
    fn keeps_the_gap_and_never_cuts_the_module_head_line() {
        let text = "MODULE m PROC a()\nENDPROC\nPROC b()\nENDPROC\nPROC c()\nENDPROC\nENDMODULE";
        let all = routine_starts(text, 8, 0);
        assert_eq!(all.len(), 2);
        let sparse = routine_starts(text, 8, 18);
        assert_eq!(sparse.len(), 1);
    }
}
