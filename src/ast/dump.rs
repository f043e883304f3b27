//! A stable, readable text dump of the syntax tree for golden tests and debugging: one line
//! per declaration or statement with its byte span, expressions as S-expressions so that
//! precedence is visible (`(AND (NOT a) b)`).

use std::fmt::Write;

use super::*;

impl File {
    /// The dump of the whole file.
    pub fn dump(&self) -> String {
        let mut d = Dumper {
            out: String::new(),
            indent: 0,
            text: &self.text,
            source: self.span.source,
        };
        for m in &self.modules {
            d.module(m);
        }
        d.out
    }
}

impl Expr {
    /// The expression as an S-expression (`(+ a (* b c))`); `text` is the text of its file
    /// ([`File::text`]), where packed aggregates are read.
    pub fn sexpr(&self, text: &str) -> String {
        let mut s = String::new();
        sexpr(self, &mut s, text);
        s
    }
}

struct Dumper<'t> {
    out: String,
    indent: usize,
    /// The file's text (packed aggregates, data and call arguments are read from it).
    text: &'t str,
    /// The file.
    source: SourceId,
}

fn span(s: Span) -> String {
    format!("@{}..{}", s.start, s.end)
}

impl Dumper<'_> {
    fn line(&mut self, text: &str) {
        for _ in 0..self.indent {
            self.out.push_str("  ");
        }
        self.out.push_str(text);
        self.out.push('\n');
    }

    fn nested(&mut self, f: impl FnOnce(&mut Self)) {
        self.indent += 1;
        f(self);
        self.indent -= 1;
    }

    fn module(&mut self, m: &Module) {
        let t = self.text;
        let attrs: Vec<String> = m.attrs.iter().map(|a| format!("{:?}", a.node)).collect();
        let attrs = if attrs.is_empty() {
            String::new()
        } else {
            format!(" ({})", attrs.join(", "))
        };
        self.line(&format!("MODULE {}{attrs} {}", m.name.node, span(m.span)));
        self.nested(|d| {
            for item in &m.items {
                match item {
                    ModuleItem::Record(r) => {
                        d.line(&format!(
                            "{}RECORD {} {}",
                            local(r.local),
                            r.name.node,
                            span(r.span)
                        ));
                        d.nested(|d| {
                            for f in &r.fields {
                                d.line(&format!(
                                    "{} {}{} {}",
                                    f.ty.node,
                                    f.name.node,
                                    dims(&f.dims, t),
                                    span(f.span)
                                ));
                            }
                        });
                    }
                    ModuleItem::Alias(a) => d.line(&format!(
                        "{}ALIAS {} {} {}",
                        local(a.local),
                        a.base.node,
                        a.name.node,
                        span(a.span)
                    )),
                    ModuleItem::Data(x) => d.data(x),
                    ModuleItem::PackedData(x) => d.data(&x.unpack(d.source, t)),
                    ModuleItem::Routine(r) => d.routine(r),
                    ModuleItem::Placeholder(p) => {
                        d.line(&format!("{} {}", p.node.as_str(), span(p.span)))
                    }
                }
            }
        });
    }

    fn data(&mut self, x: &DataDecl) {
        let t = self.text;
        let storage = match x.storage {
            Storage::Var => "VAR",
            Storage::Pers => "PERS",
            Storage::Const => "CONST",
        };
        let init = x
            .init
            .as_ref()
            .map(|e| format!(" := {}", e.sexpr(t)))
            .unwrap_or_default();
        self.line(&format!(
            "{}{}{storage} {} {}{}{init} {}",
            local(x.local),
            if x.task { "TASK " } else { "" },
            x.ty.node,
            x.name.node,
            dims(&x.dims, t),
            span(x.span)
        ));
    }

    fn routine(&mut self, r: &Routine) {
        let t = self.text;
        let kind = match &r.kind {
            RoutineKind::Proc => "PROC".to_string(),
            RoutineKind::Func(t) => format!("FUNC {}", t.node),
            RoutineKind::Trap => "TRAP".to_string(),
        };
        let params: Vec<String> = r.params.iter().map(param_group).collect();
        let params = match r.kind {
            RoutineKind::Trap => String::new(),
            _ => format!("({})", params.join(", ")),
        };
        self.line(&format!(
            "{}{kind} {}{params} {} head {}",
            local(r.local),
            r.name.node,
            span(r.span),
            span(r.head_span)
        ));
        self.nested(|d| {
            for x in &r.data {
                d.data(x);
            }
            d.stmts(&r.body);
            if let Some(b) = &r.backward {
                d.line("BACKWARD");
                d.nested(|d| d.stmts(b));
            }
            if let Some(h) = &r.error {
                let list = h
                    .errnos
                    .as_ref()
                    .map(|l| {
                        format!(
                            " ({})",
                            l.iter().map(|e| e.sexpr(t)).collect::<Vec<_>>().join(", ")
                        )
                    })
                    .unwrap_or_default();
                d.line(&format!("ERROR{list} {}", span(h.span)));
                d.nested(|d| d.stmts(&h.body));
            }
            if let Some(b) = &r.undo {
                d.line("UNDO");
                d.nested(|d| d.stmts(b));
            }
        });
    }

    fn stmts(&mut self, stmts: &[Stmt]) {
        for s in stmts {
            self.stmt(s);
        }
    }

    fn stmt(&mut self, s: &Stmt) {
        let t = self.text;
        let at = span(s.span);
        match &s.kind {
            StmtKind::Assign { target, value } => self.line(&format!(
                "assign {} := {} {at}",
                target.sexpr(t),
                value.sexpr(t)
            )),
            StmtKind::Call { name, args } => self.line(&format!(
                "call {}{} {at}",
                name.node,
                args_text(&args.items(name, t), " ", t)
            )),
            StmtKind::LateCall { name, args } => self.line(&format!(
                "latecall %{}%{} {at}",
                name.sexpr(t),
                args_text(args, " ", t)
            )),
            StmtKind::If {
                cond,
                then_body,
                elseifs,
                else_body,
            } => {
                self.line(&format!("if {} {at}", cond.sexpr(t)));
                self.nested(|d| d.stmts(then_body));
                for (c, b) in elseifs {
                    self.line(&format!("elseif {}", c.sexpr(t)));
                    self.nested(|d| d.stmts(b));
                }
                if let Some(b) = else_body {
                    self.line("else");
                    self.nested(|d| d.stmts(b));
                }
            }
            StmtKind::CompactIf { cond, stmt } => {
                self.line(&format!("if-compact {} {at}", cond.sexpr(t)));
                self.nested(|d| d.stmt(stmt));
            }
            StmtKind::While { cond, body } => {
                self.line(&format!("while {} {at}", cond.sexpr(t)));
                self.nested(|d| d.stmts(body));
            }
            StmtKind::For {
                var,
                from,
                to,
                step,
                body,
            } => {
                let step = step
                    .as_ref()
                    .map(|s| format!(" step {}", s.sexpr(t)))
                    .unwrap_or_default();
                self.line(&format!(
                    "for {} from {} to {}{step} {at}",
                    var.node,
                    from.sexpr(t),
                    to.sexpr(t)
                ));
                self.nested(|d| d.stmts(body));
            }
            StmtKind::Test {
                subject,
                cases,
                default,
            } => {
                self.line(&format!("test {} {at}", subject.sexpr(t)));
                self.nested(|d| {
                    for c in cases {
                        let v: Vec<String> = c.values.iter().map(|e| e.sexpr(t)).collect();
                        d.line(&format!("case {} {}", v.join(", "), span(c.span)));
                        d.nested(|d| d.stmts(&c.body));
                    }
                    if let Some(b) = default {
                        d.line("default");
                        d.nested(|d| d.stmts(b));
                    }
                });
            }
            StmtKind::Label(l) => self.line(&format!("label {} {at}", l.node)),
            StmtKind::Goto(l) => self.line(&format!("goto {} {at}", l.node)),
            StmtKind::Return(e) => self.line(&format!("return{} {at}", opt(e, t))),
            StmtKind::Raise(e) => self.line(&format!("raise{} {at}", opt(e, t))),
            StmtKind::Retry => self.line(&format!("retry {at}")),
            StmtKind::TryNext => self.line(&format!("trynext {at}")),
            StmtKind::Exit => self.line(&format!("exit {at}")),
            StmtKind::Connect { target, trap } => self.line(&format!(
                "connect {} with {} {at}",
                target.sexpr(t),
                trap.node
            )),
            StmtKind::Placeholder(p) => self.line(&format!("{} {at}", p.as_str())),
        }
    }
}

fn local(l: bool) -> &'static str {
    if l { "LOCAL " } else { "" }
}

fn opt(e: &Option<Box<Expr>>, t: &str) -> String {
    e.as_ref()
        .map(|e| format!(" {}", e.sexpr(t)))
        .unwrap_or_default()
}

fn dims(d: &[Expr], t: &str) -> String {
    if d.is_empty() {
        String::new()
    } else {
        format!(
            "{{{}}}",
            d.iter().map(|e| e.sexpr(t)).collect::<Vec<_>>().join(", ")
        )
    }
}

fn param_group(g: &ParamGroup) -> String {
    g.alternatives
        .iter()
        .map(param)
        .collect::<Vec<_>>()
        .join(" | ")
}

fn param(p: &Param) -> String {
    if let Some(ph) = p.placeholder {
        return ph.as_str().to_string();
    }
    let mode = match p.mode {
        ParamMode::In => "",
        ParamMode::InOut => "INOUT ",
        ParamMode::Var => "VAR ",
        ParamMode::Pers => "PERS ",
    };
    let open = match p.open_dims {
        0 => String::new(),
        n => format!("{{{}}}", vec!["*"; n as usize].join(",")),
    };
    format!(
        "{}{mode}{} {}{open}",
        if p.optional { "\\" } else { "" },
        p.ty.node,
        p.name.node
    )
}

fn args_text(args: &[Arg], lead: &str, t: &str) -> String {
    if args.is_empty() {
        return String::new();
    }
    let v: Vec<String> = args.iter().map(|a| arg(a, t)).collect();
    format!("{lead}{}", v.join(", "))
}

fn arg(a: &Arg, t: &str) -> String {
    match &a.kind {
        ArgKind::Positional(e) => e.sexpr(t),
        ArgKind::Named { name, value } => format!("{}:={}", name.node, value.sexpr(t)),
        ArgKind::Optional { name, value: None } => format!("\\{}", name.node),
        ArgKind::Optional {
            name,
            value: Some(v),
        } => format!("\\{}:={}", name.node, v.sexpr(t)),
        ArgKind::Conditional { name, param } => format!("\\{}?{}", name.node, param.node),
        ArgKind::Placeholder(p) => p.as_str().to_string(),
    }
}

fn sexpr(e: &Expr, s: &mut String, t: &str) {
    match &e.kind {
        ExprKind::Num(v) => {
            let _ = write!(s, "{v}");
        }
        ExprKind::Str(v) => {
            let _ = write!(s, "{v:?}");
        }
        ExprKind::Bool(b) => s.push_str(if *b { "TRUE" } else { "FALSE" }),
        ExprKind::Name(n) => s.push_str(&n.node),
        ExprKind::Component { base, field } => {
            sexpr(base, s, t);
            s.push('.');
            s.push_str(&field.node);
        }
        ExprKind::Index { base, indices } => {
            sexpr(base, s, t);
            s.push('{');
            for (i, x) in indices.iter().enumerate() {
                if i > 0 {
                    s.push_str(", ");
                }
                sexpr(x, s, t);
            }
            s.push('}');
        }
        ExprKind::Call { name, args } => {
            s.push_str(&name.node);
            s.push('(');
            s.push_str(&args_text(args, "", t));
            s.push(')');
        }
        ExprKind::Aggregate(items) => {
            s.push('[');
            for (i, x) in items.iter().enumerate() {
                if i > 0 {
                    s.push_str(", ");
                }
                sexpr(x, s, t);
            }
            s.push(']');
        }
        ExprKind::Unary { op, expr } => {
            s.push_str(match op {
                UnaryOp::Neg => "(neg ",
                UnaryOp::Plus => "(plus ",
                UnaryOp::Not => "(NOT ",
            });
            sexpr(expr, s, t);
            s.push(')');
        }
        ExprKind::Binary { op, lhs, rhs } => {
            s.push('(');
            s.push_str(op.as_str());
            s.push(' ');
            sexpr(lhs, s, t);
            s.push(' ');
            sexpr(rhs, s, t);
            s.push(')');
        }
        ExprKind::Paren(x) => {
            s.push_str("(paren ");
            sexpr(x, s, t);
            s.push(')');
        }
        ExprKind::Placeholder(p) => s.push_str(p.as_str()),
        ExprKind::PackedAggregate(p) => sexpr(&p.unpack(t, e.span), s, t),
    }
}
