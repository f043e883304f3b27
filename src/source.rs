//! Source files, spans and the source map that diagnostics render against.
//!
//! Every AST node carries a [`Span`]: a byte range into one file of the [`SourceMap`].
//! Spans are plain data (no text); source is attached only when a diagnostic is rendered.

use std::fmt;
use std::sync::Arc;

/// Identifies one file in a [`SourceMap`].
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord, Default)]
pub struct SourceId(pub u32);

/// A byte range `start..end` in one source file.
#[derive(Clone, Copy, PartialEq, Eq, Hash, Default)]
pub struct Span {
    /// The file.
    pub source: SourceId,
    /// First byte (inclusive).
    pub start: u32,
    /// Last byte (exclusive).
    pub end: u32,
}

impl fmt::Debug for Span {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}..{}", self.start, self.end)
    }
}

impl Span {
    /// A span in `source` covering `start..end`.
    pub fn new(source: SourceId, start: usize, end: usize) -> Span {
        Span {
            source,
            start: start as u32,
            end: end as u32,
        }
    }

    /// The smallest span covering both (which must be in the same file).
    pub fn merge(self, other: Span) -> Span {
        Span {
            source: self.source,
            start: self.start.min(other.start),
            end: self.end.max(other.end),
        }
    }

    /// Length in bytes.
    pub fn len(&self) -> usize {
        (self.end - self.start) as usize
    }

    /// True when the span covers no bytes.
    pub fn is_empty(&self) -> bool {
        self.end == self.start
    }

    /// An empty span at the start of this one.
    pub fn start_point(self) -> Span {
        Span {
            end: self.start,
            ..self
        }
    }

    /// An empty span at the end of this one.
    pub fn end_point(self) -> Span {
        Span {
            start: self.end,
            ..self
        }
    }
}

impl From<Span> for miette::SourceSpan {
    fn from(s: Span) -> Self {
        miette::SourceSpan::new((s.start as usize).into(), s.len())
    }
}

/// A value with the span it was written at.
#[derive(Clone, Copy, PartialEq, Eq, Hash)]
pub struct Spanned<T> {
    /// The value.
    pub node: T,
    /// Where it was written.
    pub span: Span,
}

impl<T: fmt::Debug> fmt::Debug for Spanned<T> {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{:?}@{:?}", self.node, self.span)
    }
}

impl<T> Spanned<T> {
    /// Wrap `node` with `span`.
    pub fn new(node: T, span: Span) -> Self {
        Spanned { node, span }
    }

    /// Transform the value, keeping the span.
    pub fn map<U>(self, f: impl FnOnce(T) -> U) -> Spanned<U> {
        Spanned {
            node: f(self.node),
            span: self.span,
        }
    }

    /// Borrow the value, keeping the span.
    pub fn as_ref(&self) -> Spanned<&T> {
        Spanned {
            node: &self.node,
            span: self.span,
        }
    }
}

impl<T> std::ops::Deref for Spanned<T> {
    type Target = T;
    fn deref(&self) -> &T {
        &self.node
    }
}

/// The text of one source file, shared (cloning it copies no text). It keeps the `String`
/// the file was decoded into: a file's text is held once for the whole run (an `Arc<str>`
/// would be a second copy), and the syntax tree refers to it rather than copying parts of it
/// (see [`crate::ast::File::text`]).
#[derive(Clone, Default, PartialEq, Eq)]
pub struct SourceText(Arc<String>);

impl SourceText {
    /// The text.
    pub fn as_str(&self) -> &str {
        self.0.as_str()
    }

    /// True when both are the same text (one of them a clone of the other).
    pub fn ptr_eq(a: &SourceText, b: &SourceText) -> bool {
        Arc::ptr_eq(&a.0, &b.0)
    }
}

impl std::ops::Deref for SourceText {
    type Target = str;
    fn deref(&self) -> &str {
        self.0.as_str()
    }
}

impl fmt::Debug for SourceText {
    /// Only the length: a syntax tree's debug output would otherwise hold its whole file.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "SourceText({} bytes)", self.0.len())
    }
}

impl fmt::Display for SourceText {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.as_str())
    }
}

/// What can become a [`SourceText`]: a `String` or a `SourceText` is taken as it is (no copy);
/// `&SourceText` is shared; any other text is copied.
pub trait IntoSourceText {
    /// The text as a [`SourceText`].
    fn into_source_text(self) -> SourceText;
}

impl IntoSourceText for SourceText {
    fn into_source_text(self) -> SourceText {
        self
    }
}

impl IntoSourceText for &SourceText {
    fn into_source_text(self) -> SourceText {
        self.clone()
    }
}

impl IntoSourceText for String {
    fn into_source_text(self) -> SourceText {
        SourceText(Arc::new(self))
    }
}

impl<T: AsRef<str> + ?Sized> IntoSourceText for &T {
    fn into_source_text(self) -> SourceText {
        SourceText(Arc::new(self.as_ref().to_string()))
    }
}

impl IntoSourceText for Arc<str> {
    fn into_source_text(self) -> SourceText {
        SourceText(Arc::new(self.to_string()))
    }
}

impl miette::SourceCode for SourceText {
    fn read_span<'a>(
        &'a self,
        span: &miette::SourceSpan,
        context_lines_before: usize,
        context_lines_after: usize,
    ) -> Result<Box<dyn miette::SpanContents<'a> + 'a>, miette::MietteError> {
        self.as_str()
            .read_span(span, context_lines_before, context_lines_after)
    }
}

/// One loaded file: its display name, decoded text and line starts.
#[derive(Debug, Clone)]
pub struct SourceFile {
    /// Display name (usually the path as given).
    pub name: String,
    /// Decoded text (UTF-8, or Latin-1 mapped byte-for-char when the file is not UTF-8).
    pub text: SourceText,
    line_starts: Vec<u32>,
}

impl SourceFile {
    /// 1-based (line, column) of a byte offset; the column counts chars.
    pub fn line_col(&self, offset: u32) -> (usize, usize) {
        let line = self.line_index(offset as usize);
        let start = self.line_starts.get(line).copied().unwrap_or(0) as usize;
        let end = (offset as usize).min(self.text.len());
        let col = self
            .text
            .get(start..end)
            .map(|s| s.chars().count())
            .unwrap_or(0);
        (line + 1, col + 1)
    }

    /// The text of 1-based line `line`, without its line end.
    pub fn line_text(&self, line: usize) -> &str {
        if line == 0 || line > self.line_count() {
            return "";
        }
        let (start, end) = self.line_bounds(line - 1);
        self.text.get(start..end).unwrap_or("")
    }

    /// Number of lines (a file that ends with a line end has an empty last line).
    pub fn line_count(&self) -> usize {
        self.line_starts.len()
    }

    /// The 0-based line holding byte `offset` (the last line for offsets past the end). A
    /// line end belongs to the line it ends.
    pub fn line_index(&self, offset: usize) -> usize {
        let offset = u32::try_from(offset).unwrap_or(u32::MAX);
        match self.line_starts.binary_search(&offset) {
            Ok(i) => i,
            Err(i) => i.saturating_sub(1),
        }
    }

    /// Byte range of 0-based line `index` without its line end (LF, CR LF or a lone CR).
    pub fn line_bounds(&self, index: usize) -> (usize, usize) {
        let start = self
            .line_starts
            .get(index)
            .map_or(self.text.len(), |&s| s as usize);
        let next = self
            .line_starts
            .get(index + 1)
            .map_or(self.text.len(), |&e| e as usize);
        let line = self.text.get(start..next).unwrap_or("");
        let content = line.strip_suffix('\n').unwrap_or(line);
        let content = content.strip_suffix('\r').unwrap_or(content);
        (start, start + content.len())
    }
}

/// Byte offsets at which the lines of `text` start. LF, CR LF and a lone CR (old Mac files)
/// each end a line, the same way the parser and the diagnostics renderer see them.
fn line_starts(text: &str) -> Vec<u32> {
    let mut starts = vec![0u32];
    let b = text.as_bytes();
    for i in memchr::memchr2_iter(b'\n', b'\r', b) {
        if b[i] == b'\n' || b.get(i + 1) != Some(&b'\n') {
            starts.push(i as u32 + 1);
        }
    }
    // (Grown by doubling, it may hold twice what it needs for the whole run.)
    starts.shrink_to_fit();
    starts
}

/// [`decode_owned`] of a copy of `bytes`.
pub fn decode_bytes(bytes: &[u8]) -> String {
    decode_owned(bytes.to_vec())
}

/// Decode file bytes: UTF-8 when valid, otherwise Latin-1 (each byte one char), as RAPID
/// files written by older controllers are ISO-8859-1. Valid UTF-8 becomes the text in the
/// bytes' own buffer (a byte-order mark is removed in place), so reading a file holds one
/// copy of it; only Latin-1 needs a new buffer.
pub fn decode_owned(bytes: Vec<u8>) -> String {
    match String::from_utf8(bytes) {
        Ok(mut s) => {
            if s.starts_with('\u{feff}') {
                s.drain(..'\u{feff}'.len_utf8());
            }
            s
        }
        Err(e) => e.as_bytes().iter().map(|&b| b as char).collect(),
    }
}

/// All files of one program (and the embedded stdlib), addressed by [`SourceId`].
#[derive(Debug, Default, Clone)]
pub struct SourceMap {
    files: Vec<SourceFile>,
}

impl SourceMap {
    /// An empty map.
    pub fn new() -> Self {
        Self::default()
    }

    /// Add a file and return its id.
    pub fn add(&mut self, name: impl Into<String>, text: impl IntoSourceText) -> SourceId {
        let text = text.into_source_text();
        let line_starts = line_starts(&text);
        let id = SourceId(self.files.len() as u32);
        self.files.push(SourceFile {
            name: name.into(),
            text,
            line_starts,
        });
        id
    }

    /// The file with this id.
    ///
    /// Ids are only created by [`SourceMap::add`], so a missing id is a caller bug; it yields
    /// an empty placeholder file rather than a panic.
    pub fn get(&self, id: SourceId) -> &SourceFile {
        static EMPTY: std::sync::OnceLock<SourceFile> = std::sync::OnceLock::new();
        self.files.get(id.0 as usize).unwrap_or_else(|| {
            EMPTY.get_or_init(|| SourceFile {
                name: "<unknown>".into(),
                text: SourceText::default(),
                line_starts: vec![0],
            })
        })
    }

    /// The text a span covers.
    pub fn snippet(&self, span: Span) -> &str {
        self.get(span.source)
            .text
            .get(span.start as usize..span.end as usize)
            .unwrap_or("")
    }

    /// `name:line:col` of the start of a span.
    pub fn location(&self, span: Span) -> String {
        let f = self.get(span.source);
        let (l, c) = f.line_col(span.start);
        format!("{}:{}:{}", f.name, l, c)
    }

    /// A miette source for rendering a diagnostic about file `id`.
    pub fn named_source(&self, id: SourceId) -> miette::NamedSource<SourceText> {
        let f = self.get(id);
        miette::NamedSource::new(f.name.clone(), f.text.clone())
    }

    /// Number of files.
    pub fn len(&self) -> usize {
        self.files.len()
    }

    /// True when no file was added.
    pub fn is_empty(&self) -> bool {
        self.files.is_empty()
    }

    /// Iterate over (id, file).
    pub fn iter(&self) -> impl Iterator<Item = (SourceId, &SourceFile)> {
        self.files
            .iter()
            .enumerate()
            .map(|(i, f)| (SourceId(i as u32), f))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn line_col_and_latin1() {
        let mut m = SourceMap::new();
        let id = m.add("a.mod", "ab\r\ncd\nef");
        let f = m.get(id);
        assert_eq!(f.line_col(0), (1, 1));
        assert_eq!(f.line_col(4), (2, 1));
        assert_eq!(f.line_col(5), (2, 2));
        assert_eq!(f.line_text(1), "ab");
        assert_eq!(f.line_text(3), "ef");
        assert_eq!(decode_owned(b"x\xe9y".to_vec()), "x\u{e9}y");
        assert_eq!(decode_owned(b"\xef\xbb\xbfa\xc3\xa9".to_vec()), "a\u{e9}");
        assert_eq!(
            decode_bytes(b"\xef\xbb\xbfx\xe9"),
            "\u{ef}\u{bb}\u{bf}x\u{e9}"
        );
    }

    #[test]
    fn lone_cr_crlf_and_lf_all_end_lines() {
        let mut m = SourceMap::new();
        let id = m.add("a.mod", "a\rb\r\nc\nd\r\re");
        let f = m.get(id);
        let lines: Vec<&str> = (1..=f.line_count()).map(|l| f.line_text(l)).collect();
        assert_eq!(lines, ["a", "b", "c", "d", "", "e"]);
        assert_eq!(f.line_col(2), (2, 1));
        assert_eq!(f.line_col(5), (3, 1));
        assert_eq!(f.line_index(3), 1);
        assert_eq!(f.line_bounds(1), (2, 3));
    }
}
