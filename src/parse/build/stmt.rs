//! Statements: simple ones (assignment, calls, GOTO, RETURN, …) and compound ones (IF,
//! WHILE, FOR, TEST), with recovery for skipped statements and missing end keywords.

use super::Builder;
use super::expr::placeholder;
use crate::ast::Arg;
use crate::ast::literal;
use crate::ast::{CallArgs, Expr, Ident, PackedArgs, Stmt, StmtKind, TestCase};
use crate::parse::error::ParseErrorKind;
use crate::parse::grammar::{Pair, Rule};
use crate::parse::recover::Region;

impl Builder<'_, '_> {
    /// One element of a statement list: a statement, or a skipped region (reported).
    pub(crate) fn stmt_item(&mut self, p: Pair<'_>, out: &mut Vec<Stmt>) {
        match p.as_rule() {
            Rule::bad_stmt => self.skipped(&p, Region::Statement),
            _ => {
                if let Some(s) = self.statement(p) {
                    out.push(s);
                }
            }
        }
    }

    /// A `statement` pair, or the `simple_stmt` of a compact IF.
    pub(crate) fn statement(&mut self, p: Pair<'_>) -> Option<Stmt> {
        let errors = self.errors;
        let span = self.span(&p);
        let mut inner = p.into_inner();
        let first = inner.next()?;
        let kind = if first.as_rule() == Rule::ident {
            // A call, an assignment or a label: the name, then what follows it.
            let tail = inner.next()?;
            self.name_stmt(first, tail)
        } else {
            self.stmt_kind(first)
        };
        if kind.is_none() && self.errors == errors {
            // A shape the grammar should not produce; never drop a statement silently.
            self.error(ParseErrorKind::Limit {
                span,
                reason: "this statement could not be built".into(),
            });
        }
        Some(Stmt { kind: kind?, span })
    }

    /// The arguments of a call to `name` that ends (with its `;`) at byte `end`, packed as
    /// their text when reading the text back gives exactly the tree built
    /// ([`CallArgs::Packed`]).
    fn pack_call_args(&self, name: &Ident, args: Box<[Arg]>, end: usize) -> CallArgs {
        let from = name.span.end as usize;
        // (No arguments take no memory as a tree.)
        let Some(text) = self.text.get(from..end).filter(|_| !args.is_empty()) else {
            return CallArgs::Tree(args);
        };
        match literal::read_call_args(self.file, text, from) {
            Some(read) if *read == *args => CallArgs::Packed(PackedArgs::new(end)),
            _ => CallArgs::Tree(args),
        }
    }

    /// A statement that starts with a name: `call_tail`, `assign_tail` or `label_tail`.
    fn name_stmt(&mut self, name: Pair<'_>, tail: Pair<'_>) -> Option<StmtKind> {
        Some(match tail.as_rule() {
            Rule::call_tail => {
                let name = self.ident(&name);
                let errors = self.errors;
                let end = self.end(&tail);
                let args = self.call_args(tail.into_inner())?;
                let args = if self.pack_calls && self.errors == errors {
                    self.pack_call_args(&name, args, end)
                } else {
                    CallArgs::Tree(args)
                };
                StmtKind::Call { name, args }
            }
            Rule::assign_tail => {
                let mut inner = tail.into_inner().peekable();
                let target = self.target(name, &mut inner)?;
                let value = self.expr(inner.next()?)?;
                StmtKind::Assign {
                    target: Box::new(target),
                    value: Box::new(value),
                }
            }
            _ => StmtKind::Label(self.ident(&name)),
        })
    }

    fn stmt_kind(&mut self, p: Pair<'_>) -> Option<StmtKind> {
        let rule = p.as_rule();
        let mut inner = p.into_inner().peekable();
        Some(match rule {
            Rule::ph_assign => {
                let first = inner.next()?;
                let target = self.target(first, &mut inner)?;
                let value = self.expr(inner.next()?)?;
                StmtKind::Assign {
                    target: Box::new(target),
                    value: Box::new(value),
                }
            }
            Rule::late_call => {
                let name = self.expr(inner.next()?)?;
                StmtKind::LateCall {
                    name: Box::new(name),
                    args: self.call_args(inner)?,
                }
            }
            Rule::placeholder_stmt => {
                StmtKind::Placeholder(placeholder(self.text_of(&inner.next()?)))
            }
            Rule::goto_stmt => {
                inner.next();
                StmtKind::Goto(self.ident(&inner.next()?))
            }
            Rule::return_stmt => {
                inner.next();
                StmtKind::Return(match inner.next() {
                    Some(e) => Some(Box::new(self.expr(e)?)),
                    None => None,
                })
            }
            Rule::raise_stmt => {
                inner.next();
                StmtKind::Raise(match inner.next() {
                    Some(e) => Some(Box::new(self.expr(e)?)),
                    None => None,
                })
            }
            Rule::retry_stmt => StmtKind::Retry,
            Rule::trynext_stmt => StmtKind::TryNext,
            Rule::exit_stmt => StmtKind::Exit,
            Rule::connect_stmt => {
                inner.next();
                let first = inner.next()?;
                let target = self.target(first, &mut inner)?;
                inner.next(); // WITH
                let trap = self.ident(&inner.next()?);
                StmtKind::Connect {
                    target: Box::new(target),
                    trap,
                }
            }
            Rule::if_stmt => {
                let opener = inner.next()?;
                return self.if_stmt(opener, inner);
            }
            Rule::while_stmt => {
                let opener = inner.next()?;
                let cond = self.expr(inner.next()?)?;
                inner.next(); // DO
                let body = self.block(&opener, &mut inner, "ENDWHILE");
                StmtKind::While {
                    cond: Box::new(cond),
                    body,
                }
            }
            Rule::for_stmt => {
                let opener = inner.next()?;
                let var = self.ident(&inner.next()?);
                inner.next(); // FROM
                let from = self.expr(inner.next()?)?;
                inner.next(); // TO
                let to = self.expr(inner.next()?)?;
                let step = match inner.next()?.as_rule() {
                    Rule::kw_step => {
                        let s = self.expr(inner.next()?)?;
                        inner.next(); // DO
                        Some(s)
                    }
                    _ => None,
                };
                let body = self.block(&opener, &mut inner, "ENDFOR");
                StmtKind::For {
                    var: Box::new(var),
                    from: Box::new(from),
                    to: Box::new(to),
                    step: step.map(Box::new),
                    body,
                }
            }
            Rule::test_stmt => return self.test_stmt(inner),
            _ => return None,
        })
    }

    /// Statements up to the block's end keyword; a `missing_end` is reported.
    fn block<'i>(
        &mut self,
        opener: &Pair<'i>,
        inner: &mut impl Iterator<Item = Pair<'i>>,
        keyword: &'static str,
    ) -> Box<[Stmt]> {
        let mut body = Vec::with_capacity(inner.size_hint().0);
        for p in inner {
            match p.as_rule() {
                Rule::statement | Rule::bad_stmt => self.stmt_item(p, &mut body),
                Rule::missing_end => self.missing_end(&p, opener, keyword),
                _ => {}
            }
        }
        body.into_boxed_slice()
    }

    fn if_stmt<'i>(
        &mut self,
        opener: Pair<'i>,
        mut inner: impl Iterator<Item = Pair<'i>>,
    ) -> Option<StmtKind> {
        let cond = self.expr(inner.next()?)?;
        let next = inner.next()?;
        if next.as_rule() != Rule::kw_then {
            // Compact IF: one simple statement.
            let stmt = self.statement(next)?;
            return Some(StmtKind::CompactIf {
                cond: Box::new(cond),
                stmt: Box::new(stmt),
            });
        }
        let mut then_body = Vec::with_capacity(inner.size_hint().0);
        let mut elseifs = Vec::new();
        let mut else_body = None;
        for p in inner {
            match p.as_rule() {
                Rule::statement | Rule::bad_stmt => self.stmt_item(p, &mut then_body),
                Rule::elseif_clause => {
                    let mut c = p.into_inner().skip(1);
                    let Some(cond) = c.next().and_then(|e| self.expr(e)) else {
                        continue;
                    };
                    let mut body = Vec::new();
                    for s in c.skip(1) {
                        self.stmt_item(s, &mut body);
                    }
                    elseifs.push((cond, body));
                }
                Rule::ph_eit => {
                    let span = self.span(&p);
                    let cond = Expr {
                        kind: crate::ast::ExprKind::Placeholder(placeholder(self.text_of(&p))),
                        span,
                    };
                    elseifs.push((cond, Vec::new()));
                }
                Rule::else_clause => {
                    let mut body = Vec::new();
                    for s in p.into_inner().skip(1) {
                        self.stmt_item(s, &mut body);
                    }
                    else_body = Some(body);
                }
                Rule::missing_end => self.missing_end(&p, &opener, "ENDIF"),
                _ => {}
            }
        }
        Some(StmtKind::If {
            cond: Box::new(cond),
            then_body: then_body.into_boxed_slice(),
            elseifs: elseifs.into_boxed_slice(),
            else_body: else_body.map(Vec::into_boxed_slice),
        })
    }

    fn test_stmt<'i>(&mut self, mut inner: impl Iterator<Item = Pair<'i>>) -> Option<StmtKind> {
        let opener = inner.next()?;
        let subject = self.expr(inner.next()?)?;
        let mut cases = Vec::new();
        let mut default = None;
        for p in inner {
            match p.as_rule() {
                Rule::case_clause => {
                    let head_start = self.span(&p);
                    let mut values = Vec::new();
                    let mut body = Vec::new();
                    let mut head_end = head_start;
                    for c in p.into_inner().skip(1) {
                        match c.as_rule() {
                            Rule::expr => {
                                head_end = self.span(&c);
                                if let Some(v) = self.expr(c) {
                                    values.push(v);
                                }
                            }
                            _ => self.stmt_item(c, &mut body),
                        }
                    }
                    // (Exactly their length: a list grown by pushing holds four at least.)
                    values.shrink_to_fit();
                    body.shrink_to_fit();
                    cases.push(TestCase {
                        values,
                        body,
                        span: head_start.start_point().merge(head_end),
                    });
                }
                Rule::ph_cse => {
                    let span = self.span(&p);
                    cases.push(TestCase {
                        values: vec![Expr {
                            kind: crate::ast::ExprKind::Placeholder(placeholder(self.text_of(&p))),
                            span,
                        }],
                        body: Vec::new(),
                        span,
                    });
                }
                Rule::default_clause => {
                    let mut body = Vec::new();
                    for s in p.into_inner().skip(1) {
                        self.stmt_item(s, &mut body);
                    }
                    default = Some(body);
                }
                Rule::missing_end => self.missing_end(&p, &opener, "ENDTEST"),
                _ => {}
            }
        }
        Some(StmtKind::Test {
            subject: Box::new(subject),
            cases: cases.into_boxed_slice(),
            default: default.map(Vec::into_boxed_slice),
        })
    }
}
