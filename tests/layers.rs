//! The layer rule of `docs/architecture.md` ("Layers"), kept by a test: every path by which a
//! file of `src/` names another top-level module (`crate::x::…` anywhere, in use trees, types,
//! expressions, patterns and macro bodies; `super::…` that climbs out of its module) must
//! point at a module its own module may use. The table is read from the document itself, so
//! the rule users read is the rule the test keeps. Comments and strings are not code: a doc
//! link may name any module.
//!
//! The only paths allowed against the rule are [`EXCEPTIONS`]: references that exist today
//! and that issue 11 item 3 removes. Each must still occur (an exception nobody needs any
//! more fails the test, so it is deleted with the reference it allowed).

use std::collections::{BTreeMap, BTreeSet};
use std::path::Path;

use proc_macro2::{TokenStream, TokenTree};
use syn::visit::{self, Visit};

use rapidvc_testkit::src_files;
use src_files::{root, rust_files};

/// A reference allowed against the layer rule until the change named in `why` removes it.
struct Exception {
    /// The top-level module the reference is in.
    from: &'static str,
    /// What it names, as a path below `crate` (a prefix: `egm::registry` covers
    /// `egm::registry::RunArgs`).
    to: &'static str,
    /// Which change removes it.
    why: &'static str,
}

/// None today: issue 11 item 3 removed the last ones (egm reading config). A reference that
/// must go against the rule for a while is listed here with the change that removes it.
const EXCEPTIONS: &[Exception] = &[];

/// The "may use" table of `docs/architecture.md`: module → the modules it names directly.
fn layer_table() -> BTreeMap<String, BTreeSet<String>> {
    let doc = std::fs::read_to_string(root().join("docs/architecture.md"))
        .expect("docs/architecture.md is readable");
    let section = doc
        .split("\n## ")
        .find(|s| s.starts_with("Layers"))
        .expect("docs/architecture.md has a section \"## Layers\"");
    let mut table = BTreeMap::new();
    for line in section.lines() {
        let cells: Vec<&str> = line.trim().trim_matches('|').split('|').collect();
        let [module, uses] = cells[..] else { continue };
        let Some(module) = module
            .trim()
            .strip_prefix('`')
            .and_then(|m| m.strip_suffix('`'))
        else {
            continue;
        };
        let uses: BTreeSet<String> = uses
            .split(',')
            .filter_map(|u| u.trim().strip_prefix('`')?.strip_suffix('`'))
            .map(str::to_string)
            .collect();
        assert!(
            table.insert(module.to_string(), uses).is_none(),
            "`{module}` is listed twice in the layer table"
        );
    }
    assert!(
        !table.is_empty(),
        "the layer table of docs/architecture.md is empty"
    );
    table
}

/// Everything `module` may use: what it names directly, and what those may use.
fn closure(table: &BTreeMap<String, BTreeSet<String>>) -> BTreeMap<String, BTreeSet<String>> {
    table
        .keys()
        .map(|m| {
            let mut seen = BTreeSet::new();
            let mut todo: Vec<&String> = table[m].iter().collect();
            while let Some(u) = todo.pop() {
                assert!(u != m, "the layer table has a cycle through `{m}`");
                if seen.insert(u.clone()) {
                    todo.extend(table.get(u).into_iter().flatten());
                }
            }
            (m.clone(), seen)
        })
        .collect()
}

/// The module path of a file: `src/a/b.rs` → `[a, b]`.
fn module_of(file: &Path) -> Vec<String> {
    let rel = file.strip_prefix(root().join("src")).expect("below src/");
    rel.with_extension("")
        .components()
        .map(|c| c.as_os_str().to_string_lossy().into_owned())
        .collect()
}

/// One reference from a file to another top-level module.
#[derive(Debug)]
struct Reference {
    file: String,
    line: usize,
    /// The path below `crate`, e.g. `egm::registry::RunArgs`.
    target: Vec<String>,
}

/// Collects the references of one file.
struct Collector<'a> {
    file: &'a str,
    /// The module the visitor is in (the file's, plus inline `mod`s).
    module: Vec<String>,
    refs: Vec<Reference>,
}

impl Collector<'_> {
    /// A path as written (`crate`/`super`/`self` first) at `line`.
    fn path(&mut self, segments: Vec<String>, line: usize) {
        let Some(first) = segments.first() else {
            return;
        };
        let target: Vec<String> = match first.as_str() {
            "crate" => segments[1..].to_vec(),
            "super" => {
                let ups = segments.iter().take_while(|s| *s == "super").count();
                if ups > self.module.len() {
                    return;
                }
                let mut t = self.module[..self.module.len() - ups].to_vec();
                t.extend(segments[ups..].iter().cloned());
                t
            }
            _ => return,
        };
        if target.is_empty() || target.first() == self.module.first() {
            return;
        }
        self.refs.push(Reference {
            file: self.file.to_string(),
            line,
            target,
        });
    }

    /// Every `crate::…` or `super::…` path in a macro's tokens.
    fn tokens(&mut self, tokens: TokenStream) {
        let trees: Vec<TokenTree> = tokens.into_iter().collect();
        let mut i = 0;
        while i < trees.len() {
            match &trees[i] {
                TokenTree::Group(g) => self.tokens(g.stream()),
                TokenTree::Ident(id) if id == "crate" || id == "super" => {
                    let line = id.span().start().line;
                    let mut segments = vec![id.to_string()];
                    let mut j = i + 1;
                    while let (Some(TokenTree::Punct(a)), Some(TokenTree::Punct(b))) =
                        (trees.get(j), trees.get(j + 1))
                    {
                        let (true, Some(TokenTree::Ident(next))) =
                            (a.as_char() == ':' && b.as_char() == ':', trees.get(j + 2))
                        else {
                            break;
                        };
                        segments.push(next.to_string());
                        j += 3;
                    }
                    if segments.len() > 1 {
                        self.path(segments, line);
                    }
                    i = j.max(i + 1);
                    continue;
                }
                _ => {}
            }
            i += 1;
        }
    }

    /// The leaves of a use tree, each as a full path.
    fn use_tree(&mut self, prefix: &mut Vec<String>, tree: &syn::UseTree) {
        match tree {
            syn::UseTree::Path(p) => {
                prefix.push(p.ident.to_string());
                self.use_tree(prefix, &p.tree);
                prefix.pop();
            }
            syn::UseTree::Name(n) => self.leaf(prefix, &n.ident),
            syn::UseTree::Rename(r) => self.leaf(prefix, &r.ident),
            syn::UseTree::Glob(g) => self.path(prefix.clone(), g.star_token.spans[0].start().line),
            syn::UseTree::Group(g) => {
                for t in &g.items {
                    self.use_tree(prefix, t);
                }
            }
        }
    }

    fn leaf(&mut self, prefix: &[String], ident: &syn::Ident) {
        let mut segments = prefix.to_vec();
        if ident != "self" {
            segments.push(ident.to_string());
        }
        self.path(segments, ident.span().start().line);
    }
}

impl<'ast> Visit<'ast> for Collector<'_> {
    fn visit_item_use(&mut self, item: &'ast syn::ItemUse) {
        self.use_tree(&mut Vec::new(), &item.tree);
    }

    fn visit_item_mod(&mut self, item: &'ast syn::ItemMod) {
        if item.content.is_some() {
            self.module.push(item.ident.to_string());
            visit::visit_item_mod(self, item);
            self.module.pop();
        }
    }

    fn visit_path(&mut self, path: &'ast syn::Path) {
        if path.leading_colon.is_none() {
            let segments = path.segments.iter().map(|s| s.ident.to_string()).collect();
            let line = path
                .segments
                .first()
                .map_or(0, |s| s.ident.span().start().line);
            self.path(segments, line);
        }
        visit::visit_path(self, path);
    }

    fn visit_macro(&mut self, mac: &'ast syn::Macro) {
        self.tokens(mac.tokens.clone());
        visit::visit_macro(self, mac);
    }
}

/// Every reference to another top-level module in `src/` (`lib.rs` and `main.rs`, which only
/// declare and start, excepted).
fn references() -> Vec<(String, Reference)> {
    let mut files = Vec::new();
    rust_files(&root().join("src"), &mut files);
    files.sort();
    let mut out = Vec::new();
    for file in files {
        let module = module_of(&file);
        if module == ["lib"] || module == ["main"] {
            continue;
        }
        let text = std::fs::read_to_string(&file).expect("readable source");
        let name = file
            .strip_prefix(root())
            .expect("in the crate")
            .display()
            .to_string();
        let ast = syn::parse_file(&text).unwrap_or_else(|e| panic!("{name}: {e}"));
        let mut c = Collector {
            file: &name,
            module: module.clone(),
            refs: Vec::new(),
        };
        c.visit_file(&ast);
        out.extend(c.refs.into_iter().map(|r| (module[0].clone(), r)));
    }
    out
}

#[test]
fn layers_point_down_only() {
    let table = layer_table();
    let allowed = closure(&table);
    let mut tops: BTreeSet<String> = BTreeSet::new();
    let mut files = Vec::new();
    rust_files(&root().join("src"), &mut files);
    for f in &files {
        let m = module_of(f);
        if m != ["lib"] && m != ["main"] {
            tops.insert(m[0].clone());
        }
    }
    let unlisted: Vec<&String> = tops.iter().filter(|m| !table.contains_key(*m)).collect();
    assert!(
        unlisted.is_empty(),
        "modules missing from the layer table of docs/architecture.md: {unlisted:?}"
    );
    let unknown: Vec<&String> = table.keys().filter(|m| !tops.contains(*m)).collect();
    assert!(
        unknown.is_empty(),
        "the layer table of docs/architecture.md names modules src/ does not have: {unknown:?}"
    );

    let mut used = vec![0usize; EXCEPTIONS.len()];
    let mut violations = Vec::new();
    for (from, r) in references() {
        let to = &r.target[0];
        if allowed[&from].contains(to) {
            continue;
        }
        let target = r.target.join("::");
        let exception = EXCEPTIONS.iter().position(|e| {
            e.from == from && (target == e.to || target.starts_with(&format!("{}::", e.to)))
        });
        match exception {
            Some(i) => used[i] += 1,
            None => violations.push(format!(
                "{}:{}: `{from}` uses `crate::{target}`, but `{from}` may only use {:?}",
                r.file, r.line, allowed[&from]
            )),
        }
    }
    assert!(
        violations.is_empty(),
        "references against the layer rule of docs/architecture.md:\n{}",
        violations.join("\n")
    );
    let stale: Vec<String> = EXCEPTIONS
        .iter()
        .zip(&used)
        .filter(|(_, n)| **n == 0)
        .map(|(e, _)| format!("{} → {} ({})", e.from, e.to, e.why))
        .collect();
    assert!(
        stale.is_empty(),
        "exceptions nothing needs any more (delete them): {stale:?}"
    );
}

#[test]
fn the_collector_sees_every_kind_of_path() {
    let text = r#"
        use crate::a::{b::C, d as e, self};
        use super::super::f::G;
        mod inner { use super::super::super::h; }
        fn f(x: crate::i::J) -> Vec<crate::k::L> {
            let _ = crate::m::n();
            matches!(x, crate::o::P);
            // crate::comment::Q
            let _ = "crate::string::R";
            todo!()
        }
    "#;
    let ast = syn::parse_file(text).expect("parses");
    let mut c = Collector {
        file: "t.rs",
        module: vec!["z".into(), "y".into()],
        refs: Vec::new(),
    };
    c.visit_file(&ast);
    let found: BTreeSet<String> = c.refs.iter().map(|r| r.target.join("::")).collect();
    let want: BTreeSet<String> = [
        "a::b::C", "a::d", "a", "f::G", "h", "i::J", "k::L", "m::n", "o::P",
    ]
    .into_iter()
    .map(str::to_string)
    .collect();
    assert_eq!(found, want);
}
