//! The operator behind the dialogs (`TPReadFK`, `TPReadNum`, `UIMessageBox`, …): where
//! their answers come from.
//!
//! * An answers file (`--answers FILE`): one answer per dialog, in the order the dialogs
//!   appear. The format (also in `docs/rapid.md`, "Operator dialogs"):
//!   - one answer per line; blank lines and lines whose first non-blank character is `#`
//!     are skipped; leading and trailing blanks are trimmed;
//!   - an answer may start with the dialog's name and a colon (`TPReadFK: 2`); the dialog
//!     asking must then be that one (a check that the file and the program agree);
//!   - text in double quotes keeps its blanks (`"  a b "`; `""` is the empty text, `\"`
//!     a quote, `\\` a backslash);
//!   - `!noanswer`: the operator does not answer this dialog, so its `\MaxTime` and break
//!     conditions decide how it ends;
//!   - `[name]` starts a section: `rapidvc test` gives each test the section named after
//!     it, and the answers before the first section to the tests without one.
//! * The terminal, when standard input is one: the dialog is shown and a line is read.
//! * Nobody: every dialog ends by its `\MaxTime` or break conditions, or raises
//!   `ERR_TP_NO_CLIENT`.

use std::io::BufRead;
use std::path::Path;

/// The answer a dialog asked for.
#[derive(Clone, Debug, PartialEq)]
pub enum Reply {
    /// The operator's text, with where it came from (`answers.txt:3`, or `terminal`).
    Text {
        /// The answer as written (quotes removed).
        text: String,
        /// `FILE:LINE` or `terminal`.
        origin: String,
    },
    /// The operator does not answer this dialog (`!noanswer`, the end of the terminal's
    /// input): (where that was said).
    Silent(String),
    /// Nobody can answer (no answers file, no terminal).
    Nobody,
}

/// One answer of an answers file.
#[derive(Clone, Debug, PartialEq)]
struct Answer {
    line: usize,
    dialog: Option<String>,
    text: Option<String>,
}

/// A parsed answers file.
#[derive(Clone, Debug, PartialEq)]
pub struct AnswersFile {
    path: String,
    /// Answers before the first section.
    common: Vec<Answer>,
    /// `[name]` sections.
    sections: Vec<(String, Vec<Answer>)>,
}

impl AnswersFile {
    /// Read and parse a file; the error names the file and line.
    pub fn read(path: &Path) -> Result<AnswersFile, String> {
        let text = std::fs::read_to_string(path)
            .map_err(|e| format!("cannot read the answers file {}: {e}", path.display()))?;
        AnswersFile::parse(&path.display().to_string(), &text)
    }

    /// Parse the text of an answers file called `path`.
    pub fn parse(path: &str, text: &str) -> Result<AnswersFile, String> {
        let mut file = AnswersFile {
            path: path.to_string(),
            common: Vec::new(),
            sections: Vec::new(),
        };
        for (i, raw) in text.lines().enumerate() {
            let line = i + 1;
            let s = raw.trim();
            if s.is_empty() || s.starts_with('#') {
                continue;
            }
            if let Some(name) = s.strip_prefix('[').and_then(|r| r.strip_suffix(']')) {
                let name = name.trim();
                if name.is_empty() {
                    return Err(format!(
                        "{path}:{line}: a section needs a name: `[test_name]`"
                    ));
                }
                file.sections.push((name.to_string(), Vec::new()));
                continue;
            }
            let answer = parse_answer(s).map_err(|e| format!("{path}:{line}: {e}"))?;
            let answer = Answer {
                line,
                dialog: answer.0,
                text: answer.1,
            };
            match file.sections.last_mut() {
                Some((_, list)) => list.push(answer),
                None => file.common.push(answer),
            }
        }
        Ok(file)
    }

    /// Does the file have sections?
    pub fn has_sections(&self) -> bool {
        !self.sections.is_empty()
    }

    /// The answers for a run (those before the first section).
    pub fn for_run(&self) -> Operator {
        self.queue(self.common.clone())
    }

    /// The answers for test `name`: its section, or the answers before the first section.
    pub fn for_test(&self, name: &str) -> Operator {
        let list = self
            .sections
            .iter()
            .find(|(n, _)| n.eq_ignore_ascii_case(name))
            .map(|(_, l)| l.clone())
            .unwrap_or_else(|| self.common.clone());
        self.queue(list)
    }

    fn queue(&self, list: Vec<Answer>) -> Operator {
        Operator {
            source: Source::File {
                path: self.path.clone(),
                answers: list,
                next: 0,
            },
        }
    }
}

/// The dialogs that take answers (an answer may name one: `TPReadFK: 2`).
pub const DIALOGS: &[&str] = &[
    "TPReadFK",
    "TPReadNum",
    "TPReadDnum",
    "UIMsgBox",
    "UIMessageBox",
    "UINumEntry",
    "UINumTune",
    "UIAlphaEntry",
    "UIListView",
];

/// `[Dialog:] answer` → (dialog, text); `None` text for `!noanswer`.
type Parsed = (Option<String>, Option<String>);

fn parse_answer(s: &str) -> Result<Parsed, String> {
    let (dialog, rest) = match s.split_once(':') {
        Some((head, rest)) if DIALOGS.iter().any(|d| d.eq_ignore_ascii_case(head.trim())) => {
            (Some(head.trim().to_string()), rest.trim())
        }
        _ => (None, s),
    };
    if rest.eq_ignore_ascii_case("!noanswer") {
        return Ok((dialog, None));
    }
    if let Some(inner) = rest.strip_prefix('"') {
        let mut out = String::new();
        let mut chars = inner.chars();
        loop {
            match chars.next() {
                None => return Err(format!("the quoted answer `{rest}` has no closing `\"`")),
                Some('"') => break,
                Some('\\') => match chars.next() {
                    Some(c @ ('"' | '\\')) => out.push(c),
                    _ => return Err(format!("in `{rest}`: write `\\\"` or `\\\\` after `\\`")),
                },
                Some(c) => out.push(c),
            }
        }
        let tail: String = chars.collect();
        if !tail.trim().is_empty() {
            return Err(format!(
                "unexpected `{}` after the quoted answer",
                tail.trim()
            ));
        }
        return Ok((dialog, Some(out)));
    }
    if rest.is_empty() {
        return Err(format!(
            "`{s}` has no answer after the dialog name (write `\"\"` for an empty text)"
        ));
    }
    Ok((dialog, Some(rest.to_string())))
}

#[derive(Clone, Debug, Default, PartialEq)]
enum Source {
    /// Nobody answers.
    #[default]
    Nobody,
    /// Lines read from standard input (a terminal).
    Terminal,
    /// An answers file.
    File {
        path: String,
        answers: Vec<Answer>,
        next: usize,
    },
}

/// Where a program's dialogs get their answers.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Operator {
    source: Source,
}

/// Why an answer cannot be used: a fatal error naming the dialog.
#[derive(Clone, Debug, PartialEq)]
pub struct OperatorError(pub String);

impl Operator {
    /// Nobody answers (the default).
    pub fn nobody() -> Operator {
        Operator::default()
    }

    /// Answers read from the terminal (standard input).
    pub fn terminal() -> Operator {
        Operator {
            source: Source::Terminal,
        }
    }

    /// Can answers come (`UIClientExist`)?
    pub fn present(&self) -> bool {
        !matches!(self.source, Source::Nobody)
    }

    /// Is this the terminal (an invalid answer is asked again rather than fatal)?
    pub fn interactive(&self) -> bool {
        matches!(self.source, Source::Terminal)
    }

    /// The answers of the file not used (for a warning at the end of a run): (file, first
    /// unused line, how many).
    pub fn unused(&self) -> Option<(String, usize, usize)> {
        match &self.source {
            Source::File {
                path,
                answers,
                next,
            } if *next < answers.len() => {
                Some((path.clone(), answers[*next].line, answers.len() - *next))
            }
            _ => None,
        }
    }

    /// The next answer for `dialog`.
    pub fn next(&mut self, dialog: &str) -> Result<Reply, OperatorError> {
        match &mut self.source {
            Source::Nobody => Ok(Reply::Nobody),
            Source::Terminal => {
                let mut line = String::new();
                let stdin = std::io::stdin();
                match stdin.lock().read_line(&mut line) {
                    Ok(0) | Err(_) => Ok(Reply::Silent("the end of the terminal's input".into())),
                    Ok(_) => {
                        let s = line.trim();
                        match parse_answer(s) {
                            Ok((_, None)) => Ok(Reply::Silent("terminal".into())),
                            Ok((_, Some(text))) => Ok(Reply::Text {
                                text,
                                origin: "terminal".into(),
                            }),
                            Err(_) => Ok(Reply::Text {
                                text: s.to_string(),
                                origin: "terminal".into(),
                            }),
                        }
                    }
                }
            }
            Source::File {
                path,
                answers,
                next,
            } => {
                let Some(a) = answers.get(*next) else {
                    return Err(OperatorError(format!(
                        "{dialog} waits for an answer, but the answers file {path} has no \
                         answer left ({} used)",
                        answers.len()
                    )));
                };
                *next += 1;
                if let Some(d) = &a.dialog
                    && !d.eq_ignore_ascii_case(dialog)
                {
                    return Err(OperatorError(format!(
                        "{path}:{}: the answer is meant for {d}, but the dialog asking is {dialog}",
                        a.line
                    )));
                }
                Ok(match &a.text {
                    Some(t) => Reply::Text {
                        text: t.clone(),
                        origin: format!("{path}:{}", a.line),
                    },
                    None => Reply::Silent(format!("{path}:{}", a.line)),
                })
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn answers_file_format() {
        let f = AnswersFile::parse(
            "a.txt",
            "# comment\n\n2\nTPReadNum: 3.5\n\"  spaced \"\n!noanswer\nUIListView: !noanswer\n[test_x]\nYes\n",
        )
        .unwrap();
        let mut op = f.for_run();
        let text = |t: &str, l: usize| Reply::Text {
            text: t.into(),
            origin: format!("a.txt:{l}"),
        };
        assert_eq!(op.next("TPReadFK"), Ok(text("2", 3)));
        assert_eq!(op.next("TPReadNum"), Ok(text("3.5", 4)));
        assert_eq!(op.next("UIAlphaEntry"), Ok(text("  spaced ", 5)));
        assert_eq!(op.next("TPReadFK"), Ok(Reply::Silent("a.txt:6".into())));
        assert_eq!(op.next("UIListView"), Ok(Reply::Silent("a.txt:7".into())));
        assert!(
            op.next("TPReadFK")
                .unwrap_err()
                .0
                .contains("no answer left (5 used)")
        );
        let url = AnswersFile::parse("b.txt", "http://x\nTPReadFK : 1\n").unwrap();
        let mut u = url.for_run();
        let b = |t: &str, l: usize| Reply::Text {
            text: t.into(),
            origin: format!("b.txt:{l}"),
        };
        assert_eq!(
            u.next("UIAlphaEntry"),
            Ok(b("http://x", 1)),
            "not a dialog name"
        );
        assert_eq!(u.next("TPReadFK"), Ok(b("1", 2)));
        let mut t = f.for_test("TEST_X");
        assert_eq!(t.next("UIMsgBox"), Ok(text("Yes", 9)));
        assert_eq!(f.for_test("test_y").next("TPReadFK"), Ok(text("2", 3)));
    }

    #[test]
    fn answers_file_errors_name_the_line() {
        let e = AnswersFile::parse("a.txt", "1\n\"open\n").unwrap_err();
        assert!(e.starts_with("a.txt:2: "), "{e}");
        let e = AnswersFile::parse("a.txt", "TPReadNum:\n").unwrap_err();
        assert!(e.starts_with("a.txt:1: "), "{e}");
        let e = AnswersFile::parse("a.txt", "[]\n").unwrap_err();
        assert!(e.starts_with("a.txt:1: "), "{e}");
        let mut op = AnswersFile::parse("a.txt", "TPReadNum: 1\n")
            .unwrap()
            .for_run();
        let e = op.next("TPReadFK").unwrap_err().0;
        assert!(
            e.contains("a.txt:1: the answer is meant for TPReadNum"),
            "{e}"
        );
        assert!(!Operator::nobody().present());
        assert!(Operator::terminal().present());
    }
}
