//! Structural checks that need the whole tree but no types: duplicate names per scope
//! (module items, routine parameters and data, record components) and placeholder warnings.

use std::collections::HashMap;
use std::collections::hash_map::Entry;
use std::hash::{Hash, Hasher};

use super::error::{ParseError, ParseErrorKind};
use crate::ast::{
    Arg, ArgKind, DataDecl, Expr, ExprKind, File, Ident, ModuleItem, Placeholder, Routine, Stmt,
    StmtKind,
};
use crate::diag::Diagnostics;
use crate::parse::{ParseOptions, jobs};
use crate::source::Span;

pub(crate) fn check(file: &File, diags: &mut Diagnostics, options: &ParseOptions) {
    let source = file.span.source;
    let threads = if file.span.len() >= options.parallel_min_bytes {
        options.threads
    } else {
        1
    };
    for m in &file.modules {
        let scope = Scope("module", &m.name.node);
        // The checks inside each item, on several threads for a large module: for each item
        // that has any, its diagnostics (in the order one thread finds them).
        let parallel = threads > 1 && m.items.len() > 1;
        let inside = if parallel {
            items_in_parallel(&m.items, source, &file.text, threads)
        } else {
            Vec::new()
        };
        let mut inside = inside.into_iter().peekable();
        // (Sized for every item up front: growing the map would hash every name again.)
        let mut names = Names::with_capacity(m.items.len());
        for (i, item) in m.items.iter().enumerate() {
            // The module-level duplicate first, then what is inside the item, as one thread
            // reports them.
            if let Some(name) = item.name(source, &file.text) {
                let mut c = Checker {
                    diags: &mut *diags,
                    file: source,
                    text: &file.text,
                };
                names.add_at(&mut c, name, scope);
            }
            if parallel {
                if let Some((_, d)) = inside.next_if(|(at, _)| *at == i) {
                    diags.extend(d);
                }
            } else {
                let mut c = Checker {
                    diags: &mut *diags,
                    file: source,
                    text: &file.text,
                };
                c.item(item);
            }
        }
    }
}

/// The checks inside `items`, cut into `threads` runs checked at the same time: the index and
/// diagnostics of every item that has any, in item order.
fn items_in_parallel(
    items: &[ModuleItem],
    source: crate::source::SourceId,
    text: &str,
    threads: usize,
) -> Vec<(usize, Diagnostics)> {
    let run = |from: usize, items: &[ModuleItem]| {
        let mut found = Vec::new();
        for (k, item) in items.iter().enumerate() {
            let mut d = Diagnostics::new();
            Checker {
                diags: &mut d,
                file: source,
                text,
            }
            .item(item);
            if !d.is_empty() {
                found.push((from + k, d));
            }
        }
        found
    };
    let per = items.len().div_ceil(threads);
    let chunks: Vec<(usize, &[ModuleItem])> = items
        .chunks(per)
        .enumerate()
        .map(|(n, c)| (n * per, c))
        .collect();
    let (_, found) = jobs::run(threads, chunks.clone(), |(from, c)| run(from, c), || ());
    chunks
        .into_iter()
        .zip(found)
        // (A checker run that failed is run again here.)
        .flat_map(|((from, c), f)| f.unwrap_or_else(|| run(from, c)))
        .collect()
}

struct Checker<'d> {
    diags: &'d mut Diagnostics,
    file: crate::source::SourceId,
    /// The file's text (packed call arguments are read from it).
    text: &'d str,
}

/// A scope for duplicate names: its kind and name, written out only for a message.
#[derive(Clone, Copy)]
struct Scope<'a>(&'static str, &'a str);

impl Scope<'_> {
    fn describe(self) -> String {
        format!("{} `{}`", self.0, self.1)
    }
}

/// A name compared and hashed case-insensitively (ASCII), borrowed from the tree.
#[derive(Clone, Copy)]
struct Folded<'a>(&'a str);

impl PartialEq for Folded<'_> {
    fn eq(&self, other: &Self) -> bool {
        self.0.eq_ignore_ascii_case(other.0)
    }
}

impl Eq for Folded<'_> {}

impl Hash for Folded<'_> {
    fn hash<H: Hasher>(&self, state: &mut H) {
        // Eight upper-cased bytes at a time (a hasher call per byte costs more than the rest).
        for chunk in self.0.as_bytes().chunks(8) {
            let mut word = [0u8; 8];
            for (w, b) in word.iter_mut().zip(chunk) {
                *w = b.to_ascii_uppercase();
            }
            state.write_u64(u64::from_le_bytes(word));
        }
        state.write_usize(self.0.len());
    }
}

/// First declaration of each case-folded name in one scope.
#[derive(Default)]
struct Names<'a> {
    first: HashMap<Folded<'a>, Span>,
}

impl<'a> Names<'a> {
    fn with_capacity(n: usize) -> Self {
        Names {
            first: HashMap::with_capacity(n),
        }
    }

    fn add(&mut self, c: &mut Checker<'_>, name: &'a Ident, scope: Scope<'_>) {
        self.add_at(c, (&name.node, name.span), scope);
    }

    /// [`Names::add`] for a name and where it is written.
    fn add_at(&mut self, c: &mut Checker<'_>, (name, span): (&'a str, Span), scope: Scope<'_>) {
        if name.is_empty() || name.starts_with('<') {
            return;
        }
        match self.first.entry(Folded(name)) {
            Entry::Occupied(first) => c.push(ParseErrorKind::DuplicateName {
                span,
                first: *first.get(),
                name: name.to_string(),
                scope: scope.describe(),
            }),
            Entry::Vacant(v) => {
                v.insert(span);
            }
        }
    }
}

impl Checker<'_> {
    /// The checks inside one module item (its own name's duplicate is the module's business).
    fn item(&mut self, item: &ModuleItem) {
        match item {
            ModuleItem::Record(r) => {
                let rscope = Scope("record", &r.name.node);
                let mut fields = Names::default();
                for f in &r.fields {
                    fields.add(self, &f.name, rscope);
                    self.ident(&f.ty);
                    self.ident(&f.name);
                    self.exprs(&f.dims);
                }
                self.ident(&r.name);
            }
            ModuleItem::Alias(a) => {
                self.ident(&a.name);
                self.ident(&a.base);
            }
            ModuleItem::Data(d) => self.data(d),
            // (Names and literals only: nothing in it to check.)
            ModuleItem::PackedData(_) => {}
            ModuleItem::Routine(r) => self.routine(r),
            ModuleItem::Placeholder(p) => self.placeholder(p.node, p.span),
        }
    }

    fn push(&mut self, kind: ParseErrorKind) {
        self.diags.push(ParseError::new(self.file, kind));
    }

    fn placeholder(&mut self, p: Placeholder, span: Span) {
        let what = match p {
            Placeholder::Tdn => "a type definition",
            Placeholder::Ddn => "a data declaration",
            Placeholder::Rdn => "a routine declaration",
            Placeholder::Par => "a parameter",
            Placeholder::Alt => "an alternative parameter",
            Placeholder::Dim => "an array dimension",
            Placeholder::Smt => "a statement",
            Placeholder::Var => "a data reference",
            Placeholder::Eit => "an ELSEIF clause",
            Placeholder::Cse => "a CASE clause",
            Placeholder::Exp => "an expression",
            Placeholder::Arg => "an argument",
            Placeholder::Id => "a name",
        };
        self.push(ParseErrorKind::Placeholder {
            span,
            text: p.as_str().to_string(),
            what,
        });
    }

    fn ident(&mut self, id: &Ident) {
        if id.node.starts_with('<') {
            self.placeholder(Placeholder::Id, id.span);
        }
    }

    fn data(&mut self, d: &DataDecl) {
        self.ident(&d.ty);
        self.ident(&d.name);
        self.exprs(&d.dims);
        if let Some(e) = &d.init {
            self.expr(e);
        }
    }

    fn routine(&mut self, r: &Routine) {
        self.ident(&r.name);
        let scope = Scope("routine", &r.name.node);
        let mut names = Names::default();
        for g in &r.params {
            for p in &g.alternatives {
                match p.placeholder {
                    Some(ph) => self.placeholder(ph, p.span),
                    None => {
                        names.add(self, &p.name, scope);
                        self.ident(&p.ty);
                        self.ident(&p.name);
                    }
                }
            }
        }
        for d in &r.data {
            names.add(self, &d.name, scope);
            self.data(d);
        }
        self.stmts(&r.body);
        for s in [&r.backward, &r.undo].into_iter().flatten() {
            self.stmts(s);
        }
        if let Some(h) = &r.error {
            if let Some(e) = &h.errnos {
                self.exprs(e);
            }
            self.stmts(&h.body);
        }
    }

    fn stmts(&mut self, stmts: &[Stmt]) {
        for s in stmts {
            self.stmt(s);
        }
    }

    fn stmt(&mut self, s: &Stmt) {
        match &s.kind {
            StmtKind::Assign { target, value } => {
                self.expr(target);
                self.expr(value);
            }
            StmtKind::Call { name, args } => {
                self.ident(name);
                self.args(&args.items(name, self.text));
            }
            StmtKind::LateCall { name, args } => {
                self.expr(name);
                self.args(args);
            }
            StmtKind::If {
                cond,
                then_body,
                elseifs,
                else_body,
            } => {
                self.expr(cond);
                self.stmts(then_body);
                for (c, b) in elseifs {
                    self.expr(c);
                    self.stmts(b);
                }
                if let Some(b) = else_body {
                    self.stmts(b);
                }
            }
            StmtKind::CompactIf { cond, stmt } => {
                self.expr(cond);
                self.stmt(stmt);
            }
            StmtKind::While { cond, body } => {
                self.expr(cond);
                self.stmts(body);
            }
            StmtKind::For {
                from,
                to,
                step,
                body,
                ..
            } => {
                self.expr(from);
                self.expr(to);
                if let Some(s) = step {
                    self.expr(s);
                }
                self.stmts(body);
            }
            StmtKind::Test {
                subject,
                cases,
                default,
            } => {
                self.expr(subject);
                for c in cases {
                    self.exprs(&c.values);
                    self.stmts(&c.body);
                }
                if let Some(b) = default {
                    self.stmts(b);
                }
            }
            StmtKind::Return(Some(e)) | StmtKind::Raise(Some(e)) => self.expr(e),
            StmtKind::Connect { target, trap } => {
                self.expr(target);
                self.ident(trap);
            }
            StmtKind::Placeholder(p) => self.placeholder(*p, s.span),
            StmtKind::Label(_)
            | StmtKind::Goto(_)
            | StmtKind::Return(None)
            | StmtKind::Raise(None)
            | StmtKind::Retry
            | StmtKind::TryNext
            | StmtKind::Exit => {}
        }
    }

    fn args(&mut self, args: &[Arg]) {
        for a in args {
            match &a.kind {
                ArgKind::Positional(e) => self.expr(e),
                ArgKind::Named { value: e, .. } => self.expr(e),
                ArgKind::Optional { value: Some(e), .. } => self.expr(e),
                ArgKind::Optional { value: None, .. } | ArgKind::Conditional { .. } => {}
                ArgKind::Placeholder(p) => self.placeholder(*p, a.span),
            }
        }
    }

    fn exprs(&mut self, es: &[Expr]) {
        for e in es {
            self.expr(e);
        }
    }

    fn expr(&mut self, e: &Expr) {
        match &e.kind {
            ExprKind::Placeholder(p) => self.placeholder(*p, e.span),
            ExprKind::Component { base, .. } => self.expr(base),
            ExprKind::Index { base, indices } => {
                self.expr(base);
                self.exprs(indices);
            }
            ExprKind::Call { args, .. } => self.args(args),
            ExprKind::Aggregate(items) => self.exprs(items),
            ExprKind::Unary { expr, .. } | ExprKind::Paren(expr) => self.expr(expr),
            ExprKind::Binary { lhs, rhs, .. } => {
                self.expr(lhs);
                self.expr(rhs);
            }
            // (A packed aggregate holds literals only: no placeholder.)
            ExprKind::Num(_)
            | ExprKind::Str(_)
            | ExprKind::Bool(_)
            | ExprKind::Name(_)
            | ExprKind::PackedAggregate(_) => {}
        }
    }
}
