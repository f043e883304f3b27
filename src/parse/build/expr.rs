//! Expressions and arguments: precedence climbing (levels in `parse/pratt.rs`), primaries,
//! component and element access, function calls, aggregates, and the depth limit.

use std::iter::Peekable;

use pest::iterators::Pairs;

use super::Builder;
use crate::ast::{Arg, ArgKind, BinOp, Expr, ExprKind, Placeholder, UnaryOp};
use crate::parse::MAX_EXPR_DEPTH;
use crate::parse::error::ParseErrorKind;
use crate::parse::grammar::{Pair, Rule};
use crate::parse::pratt::{self, LEVEL_AND, LEVEL_REL};
use crate::source::Span;

/// An expression and the depth of its tree.
type Built = Option<(Expr, usize)>;

type Stream<'i> = Peekable<Pairs<'i, Rule>>;

impl Builder<'_, '_> {
    /// Build an `expr` pair; `None` (after reporting) when it is too deep.
    pub(crate) fn expr(&mut self, p: Pair<'_>) -> Option<Expr> {
        self.expr_at(p, 0).map(|(e, _)| e)
    }

    /// Build an `expr` (or `simple_operand`) pair nested `depth` levels deep.
    fn expr_at(&mut self, p: Pair<'_>, depth: usize) -> Built {
        let span = self.span(&p);
        if p.as_rule() == Rule::simple_operand {
            let kind = if self
                .text_of(&p)
                .starts_with(|c: char| c.is_ascii_alphabetic())
            {
                ExprKind::Name(self.ident(&p))
            } else {
                ExprKind::Num(self.number(&p))
            };
            return Some((Expr { kind, span }, 1));
        }
        let mut it = p.into_inner().peekable();
        let built = self.climb(&mut it, 0, true, depth + 1, span)?;
        Some(built)
    }

    fn too_deep(&mut self, span: Span) -> Built {
        self.error(ParseErrorKind::ExpressionTooComplex {
            span,
            limit: MAX_EXPR_DEPTH,
        });
        None
    }

    /// Operators of level `min` and above, starting with an operand.
    fn climb(
        &mut self,
        it: &mut Stream<'_>,
        min: u8,
        at_start: bool,
        depth: usize,
        whole: Span,
    ) -> Built {
        if depth > MAX_EXPR_DEPTH {
            return self.too_deep(whole);
        }
        let (mut lhs, mut lhs_depth) = self.operand(it, min, at_start, depth, whole)?;
        let mut last_rel = false;
        while let Some(op) = it.peek() {
            if op.as_rule() != Rule::infix_op {
                break;
            }
            let Some((bin, level)) = pratt::infix(self.text_of(op)) else {
                break;
            };
            if level < min {
                break;
            }
            let op_span = self.span(op);
            it.next();
            if level == LEVEL_REL && last_rel {
                self.error(ParseErrorKind::ChainedComparison { span: op_span });
            }
            last_rel = level == LEVEL_REL;
            let (rhs, rhs_depth) = self.climb(it, level + 1, false, depth + 1, whole)?;
            lhs_depth = 1 + lhs_depth.max(rhs_depth);
            if lhs_depth > MAX_EXPR_DEPTH {
                return self.too_deep(whole);
            }
            lhs = binary(bin, lhs, rhs);
        }
        Some((lhs, lhs_depth))
    }

    /// An operand: prefix operators, then a primary with its accesses.
    fn operand(
        &mut self,
        it: &mut Stream<'_>,
        min: u8,
        at_start: bool,
        depth: usize,
        whole: Span,
    ) -> Built {
        let p = it.next()?;
        let span = self.span(&p);
        let unary = match (p.as_rule(), self.text_of(&p)) {
            (Rule::prefix_op, "-") => Some((UnaryOp::Neg, pratt::sign_operand_level(min))),
            (Rule::prefix_op, "+") => Some((UnaryOp::Plus, pratt::sign_operand_level(min))),
            (Rule::prefix_op, _) => {
                if !at_start {
                    self.error(ParseErrorKind::MisplacedNot { span });
                }
                Some((UnaryOp::Not, LEVEL_AND.max(min)))
            }
            _ => None,
        };
        if let Some((op, level)) = unary {
            let (e, d) = self.climb(it, level, false, depth + 1, whole)?;
            let span = span.merge(e.span);
            return Some((
                Expr {
                    kind: ExprKind::Unary {
                        op,
                        expr: Box::new(e),
                    },
                    span,
                },
                d + 1,
            ));
        }
        self.primary(p, it, depth)
    }

    fn primary(&mut self, p: Pair<'_>, it: &mut Stream<'_>, depth: usize) -> Built {
        let span = self.span(&p);
        let leaf = |kind| Some((Expr { kind, span }, 1));
        match p.as_rule() {
            Rule::number => {
                let v = self.number(&p);
                leaf(ExprKind::Num(v))
            }
            Rule::string => {
                let s = self.string(&p);
                leaf(ExprKind::Str(s))
            }
            Rule::kw_true => leaf(ExprKind::Bool(true)),
            Rule::kw_false => leaf(ExprKind::Bool(false)),
            Rule::ph_expr => leaf(ExprKind::Placeholder(placeholder(self.text_of(&p)))),
            Rule::paren => {
                let inner = p.into_inner().next()?;
                let (e, d) = self.expr_at(inner, depth)?;
                Some((
                    Expr {
                        kind: ExprKind::Paren(Box::new(e)),
                        span,
                    },
                    d + 1,
                ))
            }
            Rule::literal_aggregate => self.literal_aggregate(&p, depth),
            Rule::aggregate => {
                let (items, d) = self.expr_list(p.into_inner(), depth)?;
                Some((
                    Expr {
                        kind: ExprKind::Aggregate(items),
                        span,
                    },
                    d + 1,
                ))
            }
            Rule::ident => {
                let name = self.ident(&p);
                let (mut e, mut d) = match it.peek().map(|n| n.as_rule()) {
                    Some(Rule::call_args) => {
                        let args_pair = it.next()?;
                        let end = self.span(&args_pair);
                        let (args, d) = self.args(args_pair.into_inner(), depth)?;
                        (
                            Expr {
                                kind: ExprKind::Call {
                                    name: Box::new(name),
                                    args,
                                },
                                span: span.merge(end),
                            },
                            d + 1,
                        )
                    }
                    _ => (
                        Expr {
                            kind: ExprKind::Name(name),
                            span,
                        },
                        1,
                    ),
                };
                while let Some(Rule::component | Rule::index) = it.peek().map(|n| n.as_rule()) {
                    let Some(post) = it.next() else { break };
                    (e, d) = self.postfix(e, d, post, depth)?;
                }
                Some((e, d))
            }
            // The grammar guarantees one of the above; anything else is a builder bug that
            // must not crash: treat the operand as missing.
            _ => None,
        }
    }

    /// Apply one `component` or `index` pair to `base`.
    pub(crate) fn postfix(
        &mut self,
        base: Expr,
        base_depth: usize,
        post: Pair<'_>,
        depth: usize,
    ) -> Built {
        let d = base_depth + 1;
        if d > MAX_EXPR_DEPTH {
            return self.too_deep(base.span);
        }
        let span = base.span.merge(self.span(&post));
        match post.as_rule() {
            Rule::component => {
                let field = self.ident(&post.into_inner().next()?);
                Some((
                    Expr {
                        kind: ExprKind::Component {
                            base: Box::new(base),
                            field: Box::new(field),
                        },
                        span,
                    },
                    d,
                ))
            }
            _ => {
                let (indices, id) = self.expr_list(post.into_inner(), depth)?;
                Some((
                    Expr {
                        kind: ExprKind::Index {
                            base: Box::new(base),
                            indices,
                        },
                        span,
                    },
                    d.max(id + 1),
                ))
            }
        }
    }

    /// A name with component/element accesses: the target of an assignment or CONNECT.
    pub(crate) fn target<'i>(
        &mut self,
        first: Pair<'i>,
        rest: &mut Peekable<Pairs<'i, Rule>>,
    ) -> Option<Expr> {
        let span = self.span(&first);
        if first.as_rule() == Rule::ph_expr {
            return Some(Expr {
                kind: ExprKind::Placeholder(placeholder(self.text_of(&first))),
                span,
            });
        }
        let mut e = Expr {
            kind: ExprKind::Name(self.ident(&first)),
            span,
        };
        let mut d = 1;
        while let Some(Rule::component | Rule::index) = rest.peek().map(|n| n.as_rule()) {
            let post = rest.next()?;
            (e, d) = self.postfix(e, d, post, 1)?;
        }
        Some(e)
    }

    /// Expressions of a comma list (aggregate items, indices, dimensions) and the deepest.
    fn expr_list<'i>(
        &mut self,
        pairs: impl IntoIterator<Item = Pair<'i>>,
        depth: usize,
    ) -> Option<(Vec<Expr>, usize)> {
        let pairs = pairs.into_iter();
        let mut out = Vec::with_capacity(pairs.size_hint().0);
        let mut max = 0;
        for p in pairs {
            let (e, d) = self.expr_at(p, depth + 1)?;
            max = max.max(d);
            out.push(e);
        }
        Some((out, max))
    }

    /// Expressions of a list at the top level (dimensions, error numbers, CASE values).
    pub(crate) fn exprs<'i>(
        &mut self,
        pairs: impl IntoIterator<Item = Pair<'i>>,
    ) -> Option<Vec<Expr>> {
        self.expr_list(pairs, 0).map(|(v, _)| v)
    }

    /// Call arguments (`opt_arg`, `named_arg` or `expr` pairs) and the deepest.
    pub(crate) fn args<'i>(
        &mut self,
        pairs: impl IntoIterator<Item = Pair<'i>>,
        depth: usize,
    ) -> Option<(Box<[Arg]>, usize)> {
        let pairs = pairs.into_iter();
        let mut out = Vec::with_capacity(pairs.size_hint().0);
        let mut max = 0;
        for p in pairs {
            // Spans are built from the parts: a pair's own span would include the white
            // space pest skips after a trailing optional part.
            let start = self.span(&p).start_point();
            let (kind, d, span) = match p.as_rule() {
                Rule::opt_arg => {
                    let mut inner = p.into_inner();
                    let name = self.ident(&inner.next()?);
                    match inner.next() {
                        None => {
                            let span = start.merge(name.span);
                            (ArgKind::Optional { name, value: None }, 1, span)
                        }
                        Some(v) if v.as_rule() == Rule::cond_arg => {
                            let param = self.ident(&v.into_inner().next()?);
                            let span = start.merge(param.span);
                            (
                                ArgKind::Conditional {
                                    name,
                                    param: Box::new(param),
                                },
                                1,
                                span,
                            )
                        }
                        Some(v) => {
                            let (value, d) = self.expr_at(v, depth + 1)?;
                            let span = start.merge(value.span);
                            (
                                ArgKind::Optional {
                                    name,
                                    value: Some(Box::new(value)),
                                },
                                d,
                                span,
                            )
                        }
                    }
                }
                Rule::named_arg => {
                    let mut inner = p.into_inner();
                    let name = self.ident(&inner.next()?);
                    let (value, d) = self.expr_at(inner.next()?, depth + 1)?;
                    let span = start.merge(value.span);
                    (
                        ArgKind::Named {
                            name,
                            value: Box::new(value),
                        },
                        d,
                        span,
                    )
                }
                _ => {
                    let (e, d) = self.expr_at(p, depth + 1)?;
                    let span = e.span;
                    match e.kind {
                        ExprKind::Placeholder(Placeholder::Arg) => {
                            (ArgKind::Placeholder(Placeholder::Arg), 1, span)
                        }
                        _ => (ArgKind::Positional(e), d, span),
                    }
                }
            };
            max = max.max(d);
            out.push(Arg { kind, span });
        }
        Some((out.into_boxed_slice(), max))
    }

    /// Arguments of a procedure call statement.
    pub(crate) fn call_args<'i>(
        &mut self,
        pairs: impl IntoIterator<Item = Pair<'i>>,
    ) -> Option<Box<[Arg]>> {
        self.args(pairs, 0).map(|(a, _)| a)
    }
}

fn binary(op: BinOp, lhs: Expr, rhs: Expr) -> Expr {
    let span = lhs.span.merge(rhs.span);
    Expr {
        kind: ExprKind::Binary {
            op,
            lhs: Box::new(lhs),
            rhs: Box::new(rhs),
        },
        span,
    }
}

/// The placeholder a `<…>` token stands for.
pub(crate) fn placeholder(text: &str) -> Placeholder {
    let inner = text.trim_start_matches('<').trim_end_matches('>');
    match inner.to_ascii_uppercase().as_str() {
        "TDN" => Placeholder::Tdn,
        "DDN" => Placeholder::Ddn,
        "RDN" => Placeholder::Rdn,
        "PAR" => Placeholder::Par,
        "ALT" => Placeholder::Alt,
        "DIM" => Placeholder::Dim,
        "SMT" => Placeholder::Smt,
        "VAR" => Placeholder::Var,
        "EIT" => Placeholder::Eit,
        "CSE" => Placeholder::Cse,
        "ARG" => Placeholder::Arg,
        "ID" => Placeholder::Id,
        _ => Placeholder::Exp,
    }
}
