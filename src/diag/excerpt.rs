//! The part of a source file a diagnostic shows, prepared for miette's graphical renderer.
//!
//! miette renders whatever text it is given, and it cannot render every text: a label past
//! column 65535 panics inside its formatter, escape sequences in the source reach the
//! terminal, and it does not see a lone CR as a line end while its line numbers do. So the
//! renderer never sees the file itself but an [`Excerpt`]: the lines around the labels, each
//! line end written as LF, control characters replaced by visible ones, and a long line
//! clipped to windows around the labels (`…` where text is left out). The labels are moved to
//! the excerpt's offsets; the header keeps the file's own line and column.

use std::borrow::Cow;

use miette::{LabeledSpan, MietteError, MietteSpanContents, SourceCode, SourceSpan, SpanContents};

use crate::source::SourceFile;

/// Lines shown around a label (miette asks for one; a little more keeps its reads inside the
/// excerpt whatever it asks).
const CONTEXT_LINES: usize = 2;
/// A line longer than this (in characters) is clipped.
const LONG_LINE: usize = 240;
/// Characters kept before and after each label end on a clipped line.
const WINDOW_BEFORE: usize = 48;
const WINDOW_AFTER: usize = 48;
/// Characters kept of a clipped line no label points into.
const WINDOW_PLAIN: usize = 96;
/// At most this many windows on one line (a label end beyond them points at an ellipsis).
const MAX_WINDOWS: usize = 8;
/// Windows closer than this are joined.
const JOIN_GAP: usize = 8;

/// What is shown for text left out of a clipped line.
const ELLIPSIS: &str = "…";

/// The visible form of a character that must not reach a terminal as it is: C0 controls and
/// DEL as their Unicode control pictures (`␛`, one column like the character's place), C1
/// controls and the bidirectional overrides as `\u{…}`. Tabs stay (the renderer expands
/// them); line ends never occur inside a line.
fn visible(c: char) -> Option<Cow<'static, str>> {
    match c {
        '\t' | '\n' => None,
        '\u{0}'..='\u{1f}' => char::from_u32(0x2400 + c as u32).map(|p| Cow::Owned(p.into())),
        '\u{7f}' => Some(Cow::Borrowed("\u{2421}")),
        c if is_terminal_control(c) => Some(Cow::Owned(format!("\\u{{{:x}}}", c as u32))),
        _ => None,
    }
}

/// A character a terminal acts on rather than shows: C0 and C1 controls, DEL, and the
/// bidirectional formatting characters (which reorder what follows them).
pub(crate) fn is_terminal_control(c: char) -> bool {
    matches!(c,
        '\u{0}'..='\u{1f}' | '\u{7f}'..='\u{9f}' | '\u{200e}' | '\u{200f}'
        | '\u{202a}'..='\u{202e}' | '\u{2066}'..='\u{2069}')
}

/// `s` with every character [`visible`] replaces replaced (messages, labels and help quote
/// source text).
pub(crate) fn escape_controls(s: &str) -> Cow<'_, str> {
    if !s.chars().any(|c| visible(c).is_some()) {
        return Cow::Borrowed(s);
    }
    let mut out = String::with_capacity(s.len() + 8);
    for c in s.chars() {
        match visible(c) {
            Some(v) => out.push_str(&v),
            None => out.push(c),
        }
    }
    Cow::Owned(out)
}

/// One line of an excerpt.
struct Line {
    /// 0-based line number in the file.
    number: usize,
    /// Index of the run of consecutive lines it belongs to.
    group: usize,
    /// Where the line starts in the file.
    file_start: usize,
    /// Where it starts in the excerpt, and its length there without the LF.
    start: usize,
    len: usize,
    /// (file offset, excerpt offset) at every character boundary kept, both ascending.
    map: Vec<(usize, usize)>,
}

/// The lines of one file around the labels of one diagnostic (see the module docs).
pub(crate) struct Excerpt {
    name: String,
    file_text: crate::source::SourceText,
    text: String,
    lines: Vec<Line>,
}

impl Excerpt {
    /// The excerpt of `file` for `labels`, and the labels moved onto it.
    pub(crate) fn new(file: &SourceFile, labels: &[LabeledSpan]) -> (Excerpt, Vec<LabeledSpan>) {
        let text_len = file.text.len();
        let bounds = |l: &LabeledSpan| {
            let start = l.offset().min(text_len);
            let end = (l.offset().saturating_add(l.len())).clamp(start, text_len);
            (start, end)
        };
        // The empty "line" after a final line end is shown only when a label is on it.
        let mut last_line = file.line_count().saturating_sub(1);
        if last_line > 0 && file.line_bounds(last_line).0 == text_len {
            last_line -= 1;
        }
        // Runs of lines to show, in order, joined when they touch.
        let mut runs: Vec<(usize, usize)> = labels
            .iter()
            .map(|l| {
                let (s, e) = bounds(l);
                let first = file.line_index(s);
                let last = file.line_index(if e > s { e - 1 } else { s });
                (
                    first.saturating_sub(CONTEXT_LINES),
                    (last + CONTEXT_LINES).min(last_line).max(last),
                )
            })
            .collect();
        runs.sort_unstable();
        let mut joined: Vec<(usize, usize)> = Vec::with_capacity(runs.len());
        for (a, b) in runs {
            match joined.last_mut() {
                Some(last) if a <= last.1 + 1 => last.1 = last.1.max(b),
                _ => joined.push((a, b)),
            }
        }
        let mut ex = Excerpt {
            name: escape_controls(&file.name).into_owned(),
            file_text: file.text.clone(),
            text: String::new(),
            lines: Vec::new(),
        };
        let points: Vec<usize> = labels
            .iter()
            .flat_map(|l| {
                let (s, e) = bounds(l);
                [s, e]
            })
            .collect();
        for (group, &(a, b)) in joined.iter().enumerate() {
            for number in a..=b {
                ex.push_line(file, number, group, &points);
            }
        }
        let moved = labels
            .iter()
            .map(|l| {
                let (s, e) = bounds(l);
                let xs = ex.map_offset(file, s, false);
                let xe = if e > s {
                    ex.map_offset(file, e, true)
                } else {
                    xs
                };
                let label = l.label().map(|t| escape_controls(t).into_owned());
                let span = SourceSpan::new(xs.into(), xe.saturating_sub(xs));
                if l.primary() {
                    LabeledSpan::new_primary_with_span(label, span)
                } else {
                    LabeledSpan::new_with_span(label, span)
                }
            })
            .collect();
        (ex, moved)
    }

    /// Add 0-based line `number` of `file`, clipped around those of `points` (file offsets)
    /// that fall on it when it is long.
    fn push_line(&mut self, file: &SourceFile, number: usize, group: usize, points: &[usize]) {
        let (cs, ce) = file.line_bounds(number);
        let content = file.text.get(cs..ce).unwrap_or("");
        let chars: Vec<(usize, char)> = content.char_indices().collect();
        let n = chars.len();
        // Windows of kept characters, as char index ranges.
        let windows: Vec<(usize, usize)> = if n <= LONG_LINE {
            vec![(0, n)]
        } else {
            let mut at: Vec<usize> = points
                .iter()
                .filter(|&&p| (cs..=ce).contains(&p))
                .map(|&p| chars.partition_point(|&(i, _)| cs + i < p))
                .collect();
            at.sort_unstable();
            let mut w: Vec<(usize, usize)> = Vec::new();
            for c in at {
                let (a, b) = (c.saturating_sub(WINDOW_BEFORE), (c + WINDOW_AFTER).min(n));
                match w.last_mut() {
                    Some(last) if a <= last.1 + JOIN_GAP => last.1 = last.1.max(b),
                    _ => w.push((a, b)),
                }
            }
            w.truncate(MAX_WINDOWS);
            if w.is_empty() {
                w.push((0, WINDOW_PLAIN.min(n)));
            }
            w
        };
        let start = self.text.len();
        let mut map = Vec::new();
        let mut shown_to = 0;
        for &(a, b) in &windows {
            if a > shown_to {
                self.text.push_str(ELLIPSIS);
            }
            for &(i, c) in &chars[a..b] {
                map.push((cs + i, self.text.len()));
                match visible(c) {
                    Some(v) => self.text.push_str(&v),
                    None => self.text.push(c),
                }
            }
            let end = chars.get(b).map_or(ce, |&(i, _)| cs + i);
            map.push((end, self.text.len()));
            shown_to = b;
        }
        if shown_to < n {
            self.text.push_str(ELLIPSIS);
        }
        let len = self.text.len() - start;
        self.text.push('\n');
        self.lines.push(Line {
            number,
            group,
            file_start: cs,
            start,
            len,
            map,
        });
    }

    /// The excerpt offset of file offset `offset` (which lies on a line of the excerpt). An
    /// offset in left-out text goes to the end of the text kept before it; one inside a line
    /// end goes to the line's end, or just past it when `end` (the end of a label that covers
    /// the line end).
    fn map_offset(&self, file: &SourceFile, offset: usize, end: bool) -> usize {
        let number = file.line_index(if end {
            offset.saturating_sub(1)
        } else {
            offset
        });
        let Some(line) = self.lines.iter().find(|l| l.number == number) else {
            return self.text.len();
        };
        let (_, ce) = file.line_bounds(number);
        if offset > ce {
            return line.start + line.len + usize::from(end);
        }
        let i = line.map.partition_point(|&(f, _)| f <= offset);
        match i.checked_sub(1).and_then(|i| line.map.get(i)) {
            Some(&(_, x)) => x,
            None => line.start,
        }
    }

    /// The line of the excerpt holding excerpt offset `x`.
    fn line_at(&self, x: usize) -> usize {
        self.lines
            .partition_point(|l| l.start <= x)
            .saturating_sub(1)
    }

    /// The file's 0-based column (in characters) of excerpt offset `x`.
    fn file_column(&self, x: usize) -> usize {
        let Some(line) = self.lines.get(self.line_at(x)) else {
            return 0;
        };
        let i = line.map.partition_point(|&(_, e)| e <= x);
        let file_offset = i
            .checked_sub(1)
            .and_then(|i| line.map.get(i))
            .map_or(line.file_start, |&(f, _)| f);
        self.file_text
            .get(line.file_start..file_offset)
            .map_or(0, |s| s.chars().count())
    }
}

impl SourceCode for Excerpt {
    fn read_span<'a>(
        &'a self,
        span: &SourceSpan,
        context_lines_before: usize,
        context_lines_after: usize,
    ) -> Result<Box<dyn SpanContents<'a> + 'a>, MietteError> {
        let (s, len) = (span.offset(), span.len());
        if self.lines.is_empty() || s + len > self.text.len() {
            return Err(MietteError::OutOfBounds);
        }
        let first = self.line_at(s);
        let last = self.line_at(if len > 0 { s + len - 1 } else { s });
        let group = self.lines[first].group;
        // A span across left-out lines cannot be shown (miette then shows its labels apart).
        if self.lines[last].group != group {
            return Err(MietteError::OutOfBounds);
        }
        let group_first = self.lines[..first]
            .iter()
            .rposition(|l| l.group != group)
            .map_or(0, |i| i + 1);
        let group_last = self.lines[last..]
            .iter()
            .position(|l| l.group != group)
            .map_or(self.lines.len() - 1, |i| last + i - 1);
        let top = first.saturating_sub(context_lines_before).max(group_first);
        let bottom = (last + context_lines_after).min(group_last);
        // miette reads the primary label without context for the header's line and column:
        // those are the file's, not the excerpt's.
        let (from, column) = if context_lines_before == 0 {
            (s, self.file_column(s))
        } else {
            (self.lines[top].start, 0)
        };
        let line = if context_lines_before == 0 {
            self.lines[first].number
        } else {
            self.lines[top].number
        };
        let to = self.lines[bottom].start + self.lines[bottom].len + 1;
        let data = self
            .text
            .as_bytes()
            .get(from..to)
            .ok_or(MietteError::OutOfBounds)?;
        Ok(Box::new(MietteSpanContents::new_named(
            self.name.clone(),
            data,
            SourceSpan::new(from.into(), to - from),
            line,
            column,
            bottom - top + 1,
        )))
    }
}

#[cfg(test)]
mod tests {
    use miette::{Diagnostic, LabeledSpan};
    use proptest::prelude::*;

    use crate::diag::{RapidDiagnostic, render_one_plain};
    use crate::source::{SourceId, SourceMap};

    /// A diagnostic with arbitrary labels in file 0.
    #[derive(Debug, thiserror::Error)]
    #[error("message with \u{1b}[31m in it")]
    struct Labels(Vec<(usize, usize)>);

    impl Diagnostic for Labels {
        fn labels(&self) -> Option<Box<dyn Iterator<Item = LabeledSpan> + '_>> {
            Some(Box::new(self.0.iter().map(|&(s, l)| {
                LabeledSpan::new(Some("here \u{7}".into()), s, l)
            })))
        }
    }

    impl RapidDiagnostic for Labels {
        fn source_id(&self) -> Option<SourceId> {
            Some(SourceId(0))
        }
    }

    fn render(text: &str, labels: Vec<(usize, usize)>) -> String {
        let mut map = SourceMap::new();
        map.add("t.mod", text);
        render_one_plain(&Labels(labels), &map, 80)
    }

    #[test]
    fn a_label_in_left_out_text_points_at_the_ellipsis() {
        let line = format!(
            "{}x{}y{}",
            "a".repeat(300),
            "b".repeat(300),
            "c".repeat(300)
        );
        let out = render(&line, vec![(300, 1), (601, 1)]);
        assert!(out.contains("[t.mod:1:301]"), "{out}");
        assert_eq!(out.matches('…').count(), 3, "{out}");
        assert!(!out.contains('\u{1b}') && !out.contains('\u{7}'), "{out}");
    }

    proptest! {
        /// Any text (long lines, every line end, control characters) and any labels, in range
        /// or not: the renderer never panics and never prints a line wider than a window.
        #[test]
        fn any_text_and_labels_render(
            pieces in prop::collection::vec(prop_oneof![
                Just("\n".to_string()), Just("\r".to_string()), Just("\r\n".to_string()),
                Just("\u{1b}]0;x\u{7}".to_string()), Just("\u{9b}\u{202e}\t".to_string()),
                Just("é€".to_string()), "[a-z ;]{0,20}",
                (1usize..70_000).prop_map(|n| " ".repeat(n)),
            ], 0..12),
            labels in prop::collection::vec((0usize..200_000, 0usize..100_000), 0..4),
        ) {
            let text: String = pieces.concat();
            let out = render(&text, labels);
            for line in out.lines() {
                prop_assert!(line.chars().count() < 1000, "{} wide", line.chars().count());
            }
            let clean = !out.contains('\u{1b}') && !out.contains('\u{9b}');
            prop_assert!(clean, "a control character reached the output");
        }
    }
}
