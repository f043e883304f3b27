//! Routines: heads and parameters, the body (data, statements, BACKWARD/ERROR/UNDO sections)
//! and the end keyword, with the checks the grammar leaves to the builder (section order,
//! data after statements, modifiers on routine data, ENDPROC/ENDFUNC/ENDTRAP mismatch).

use super::Builder;
use super::expr::placeholder;
use crate::ast::{
    DataDecl, ErrorHandler, Ident, Param, ParamGroup, ParamMode, Routine, RoutineKind, Stmt,
    Storage,
};
use crate::parse::error::ParseErrorKind;
use crate::parse::grammar::{Pair, Rule};
use crate::parse::recover::{self, Region};
use crate::source::Spanned;

/// Where statements of the body currently go.
#[derive(Clone, Copy, PartialEq, Eq, PartialOrd, Ord)]
enum Section {
    Body,
    Backward,
    Error,
    Undo,
}

impl Section {
    fn keyword(self) -> &'static str {
        match self {
            Section::Body => "",
            Section::Backward => "BACKWARD",
            Section::Error => "ERROR",
            Section::Undo => "UNDO",
        }
    }
}

impl Builder<'_, '_> {
    /// A `routine` pair.
    pub(crate) fn routine(&mut self, p: Pair<'_>) -> Option<Routine> {
        let span = self.span(&p);
        let start = self.start(&p);
        let errors_before = self.errors;
        let mut local = false;
        let mut head = None;
        let items = p.into_inner();
        let mut data: Vec<DataDecl> = Vec::new();
        // (At most one statement per remaining pair: no reallocation while the body grows.)
        let mut body: Vec<Stmt> = Vec::with_capacity(items.len());
        let mut backward = None;
        let mut error: Option<ErrorHandler> = None;
        let mut undo = None;
        let mut section = Section::Body;
        let mut seen_stmt = false;
        let mut end = None;
        for item in items {
            match item.as_rule() {
                Rule::kw_local => local = true,
                Rule::proc_head | Rule::func_head | Rule::trap_head => {
                    head = Some(self.routine_head(item, start)?);
                }
                Rule::data_decl => {
                    let dspan = self.span(&item);
                    if let Some(d) = self.data_decl(item) {
                        if seen_stmt || section != Section::Body {
                            self.error(ParseErrorKind::MisplacedDeclaration {
                                span: dspan,
                                what: "data declaration after statements",
                                help: "declare routine data at the start of the routine, before its statements",
                            });
                        }
                        self.check_routine_data(&d);
                        data.push(d);
                    }
                }
                Rule::statement | Rule::bad_stmt => {
                    seen_stmt = true;
                    let target = match section {
                        Section::Body => &mut body,
                        Section::Backward => backward.get_or_insert_with(Vec::new),
                        Section::Undo => undo.get_or_insert_with(Vec::new),
                        Section::Error => match error.as_mut() {
                            Some(h) => &mut h.body,
                            None => &mut body,
                        },
                    };
                    self.stmt_item(item, target);
                }
                Rule::backward_section | Rule::error_section | Rule::undo_section => {
                    let sspan = self.section_span(&item);
                    let next = match item.as_rule() {
                        Rule::backward_section => Section::Backward,
                        Rule::error_section => Section::Error,
                        _ => Section::Undo,
                    };
                    if next <= section {
                        self.error(ParseErrorKind::SectionOrder {
                            span: sspan,
                            section: next.keyword(),
                            problem: if next == section {
                                "appears twice"
                            } else {
                                "is out of order"
                            },
                        });
                    }
                    section = next;
                    match next {
                        Section::Backward => {
                            backward.get_or_insert_with(Vec::new);
                        }
                        Section::Undo => {
                            undo.get_or_insert_with(Vec::new);
                        }
                        _ => {
                            let errnos = match item.into_inner().nth(1) {
                                Some(list) => self.exprs(list.into_inner()),
                                None => None,
                            };
                            if error.is_none() {
                                error = Some(ErrorHandler {
                                    errnos,
                                    body: Vec::new(),
                                    span: sspan,
                                });
                            }
                        }
                    }
                }
                // After another error in this routine, a stray keyword is most likely a
                // consequence of it; report only the first cause.
                Rule::stray_kw if self.errors == errors_before => self.stray_keyword(&item),
                Rule::routine_end => end = item.into_inner().next(),
                _ => {}
            }
        }
        let (kind, name, params, head_span, opener) = head?;
        // (Lists of exactly their length: a large module holds many routines, and the body
        // was sized for every part of the routine.)
        data.shrink_to_fit();
        body.shrink_to_fit();
        for list in [&mut backward, &mut undo].into_iter().flatten() {
            list.shrink_to_fit();
        }
        if let Some(h) = error.as_mut() {
            h.body.shrink_to_fit();
        }
        if let Some(end) = end {
            let expected = match kind {
                RoutineKind::Proc => "ENDPROC",
                RoutineKind::Func(_) => "ENDFUNC",
                RoutineKind::Trap => "ENDTRAP",
            };
            if end.as_rule() == Rule::missing_routine_end {
                self.missing_end(&end, &opener, expected);
            } else if !self.text_of(&end).eq_ignore_ascii_case(expected) {
                self.error(ParseErrorKind::EndMismatch {
                    span: self.span(&end),
                    head_span,
                    kind: &expected[3..],
                    name: name.node.to_string(),
                    found: self.text_of(&end).to_string(),
                    expected,
                });
            }
        }
        Some(Routine {
            local,
            kind,
            name,
            params,
            data,
            body,
            backward,
            error,
            undo,
            span,
            head_span,
        })
    }

    fn stray_keyword(&mut self, item: &Pair<'_>) {
        let kw = self.text_of(item).to_string();
        let opener = match kw.to_ascii_uppercase().as_str() {
            "ENDWHILE" => "WHILE",
            "ENDFOR" => "FOR",
            "ENDTEST" | "CASE" | "DEFAULT" | "<CSE>" => "TEST",
            _ => "IF",
        };
        let help = (opener == "IF").then_some(
            "did you forget `THEN`? `IF cond stmt;` is a complete compact IF, without ENDIF",
        );
        self.error(ParseErrorKind::StrayKeyword {
            span: self.span(item),
            keyword: kw,
            opener,
            help,
        });
    }

    /// A routine head: kind, name, parameters, head span and the PROC/FUNC/TRAP keyword.
    #[allow(clippy::type_complexity)]
    fn routine_head<'i>(
        &mut self,
        p: Pair<'i>,
        routine_start: usize,
    ) -> Option<(
        RoutineKind,
        Ident,
        Vec<ParamGroup>,
        crate::source::Span,
        Pair<'i>,
    )> {
        let rule = p.as_rule();
        let mut head_span = self.span(&p).start_point();
        let mut inner = p.into_inner();
        let kw = inner.next()?;
        head_span = head_span.merge(self.span(&kw));
        let mut names = Vec::new();
        let mut params = Vec::new();
        let mut bad = false;
        for item in inner {
            head_span = head_span.merge(self.span(&item));
            match item.as_rule() {
                Rule::ident | Rule::ph_id => names.push(self.ident(&item)),
                Rule::params => params = self.params(item),
                Rule::bad_head => {
                    bad = true;
                    let kind = recover::diagnose(
                        self.file,
                        self.text,
                        routine_start,
                        self.end(&item),
                        Region::RoutineHead,
                    );
                    self.error(kind);
                }
                _ => {}
            }
        }
        let missing = || Spanned::new(Default::default(), head_span.end_point());
        let mut names = names.into_iter();
        let kind = match rule {
            Rule::proc_head => RoutineKind::Proc,
            Rule::trap_head => RoutineKind::Trap,
            _ => RoutineKind::Func(if bad { missing() } else { names.next()? }),
        };
        let name = if bad { missing() } else { names.next()? };
        let head_span = crate::source::Span::new(self.file, routine_start, head_span.end as usize);
        Some((kind, name, params, head_span, kw))
    }

    fn params(&mut self, p: Pair<'_>) -> Vec<ParamGroup> {
        let mut groups = Vec::new();
        for g in p.into_inner() {
            let mut gspan = self.span(&g).start_point();
            let mut alternatives = Vec::new();
            let mut optional = false;
            for a in g.into_inner() {
                match a.as_rule() {
                    Rule::optional_mark => optional = true,
                    _ => {
                        if let Some(param) = self.param(a, optional) {
                            gspan = gspan.merge(param.span);
                            alternatives.push(param);
                        }
                        optional = false;
                    }
                }
            }
            if alternatives.len() > 1 {
                for a in &mut alternatives {
                    a.optional = true;
                }
            }
            // (Exactly their length: a list grown by pushing holds four at least.)
            alternatives.shrink_to_fit();
            groups.push(ParamGroup {
                alternatives,
                span: gspan,
            });
        }
        groups.shrink_to_fit();
        groups
    }

    fn param(&mut self, p: Pair<'_>, optional: bool) -> Option<Param> {
        let mut span = self.span(&p).start_point();
        let mut mode = ParamMode::In;
        let mut names = Vec::new();
        let mut open_dims = 0u8;
        let mut ph = None;
        for item in p.into_inner() {
            match item.as_rule() {
                Rule::kw_inout => mode = ParamMode::InOut,
                Rule::kw_var => mode = ParamMode::Var,
                Rule::kw_pers => mode = ParamMode::Pers,
                Rule::open_dims => {
                    let dspan = self.span(&item);
                    span = span.merge(dspan);
                    let n = item.into_inner().count();
                    if n > 3 {
                        self.error(ParseErrorKind::TooManyDimensions {
                            span: dspan,
                            count: n,
                        });
                    }
                    open_dims = n.min(u8::MAX as usize) as u8;
                }
                Rule::ph_par => {
                    ph = Some(placeholder(self.text_of(&item)));
                    span = span.merge(self.span(&item));
                    names.push(self.ident(&item));
                }
                _ => {
                    span = span.merge(self.span(&item));
                    names.push(self.ident(&item));
                }
            }
        }
        let (ty, name) = if ph.is_some() {
            let n = names.into_iter().next()?;
            (Spanned::new(Default::default(), n.span.start_point()), n)
        } else {
            let mut names = names.into_iter();
            (names.next()?, names.next()?)
        };
        Some(Param {
            optional,
            mode,
            ty,
            name,
            open_dims,
            placeholder: ph,
            span,
        })
    }

    /// The span of a section head: the keyword and its error-number list.
    fn section_span(&self, p: &Pair<'_>) -> crate::source::Span {
        let mut span = self.span(p).start_point();
        for i in p.clone().into_inner() {
            span = span.merge(self.span(&i));
        }
        span
    }

    /// Routine data is VAR or CONST, without LOCAL or TASK.
    fn check_routine_data(&mut self, d: &DataDecl) {
        let text = self.text;
        let word_span = |kw: &str| {
            let s = &text[d.span.start as usize..d.span.end as usize];
            let off = s.to_ascii_uppercase().find(kw).unwrap_or(0);
            crate::source::Span::new(
                d.span.source,
                d.span.start as usize + off,
                d.span.start as usize + off + kw.len(),
            )
        };
        if d.local {
            self.error(ParseErrorKind::InvalidModifier {
                span: word_span("LOCAL"),
                keyword: "LOCAL".into(),
                help: "LOCAL is only allowed on module-level data and routines",
            });
        }
        if d.task {
            self.error(ParseErrorKind::InvalidModifier {
                span: word_span("TASK"),
                keyword: "TASK".into(),
                help: "TASK is only allowed on module-level data",
            });
        }
        if d.storage == Storage::Pers {
            self.error(ParseErrorKind::InvalidModifier {
                span: word_span("PERS"),
                keyword: "PERS".into(),
                help: "routine data is VAR or CONST; declare persistents at module level",
            });
        }
    }
}
