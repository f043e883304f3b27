//! Parser golden tests (AST dumps of `tests/parse/ok/*.mod`, rendered diagnostics of
//! `tests/parse/err/*.mod`), every file under `programs/` checking clean, robustness against
//! hostile input, and property tests (never panics, never overflows the stack).

use std::path::{Path, PathBuf};

use rapidvc::diag::Diagnostics;
use rapidvc::parse;
use rapidvc::source::{SourceId, SourceMap};

#[path = "support/gen_program.rs"]
mod gen_program;

/// Parse + structure check of `text`; the AST and the diagnostics rendered colour-free at 80
/// columns.
fn check(name: &str, text: &str) -> (rapidvc::ast::File, Diagnostics, SourceMap) {
    let mut map = SourceMap::new();
    let id = map.add(name, text);
    let mut diags = Diagnostics::new();
    let file = parse::parse_file(id, text, &mut diags);
    parse::check_structure(&file, &mut diags);
    (file, diags, map)
}

/// Run `f` on a thread with a 2 MiB stack (the default of test threads), so stack limits are
/// the same whatever runs the test.
fn on_small_stack<T: Send + 'static>(f: impl FnOnce() -> T + Send + 'static) -> T {
    std::thread::Builder::new()
        .stack_size(2 << 20)
        .spawn(f)
        .expect("spawn")
        .join()
        .expect("the parser must not panic")
}

/// Load `path` like the CLI does (UTF-8, else Latin-1), parse and check it.
fn check_path(path: &Path) -> (rapidvc::ast::File, Diagnostics, SourceMap) {
    let mut map = SourceMap::new();
    let id = rapidvc::load::load_file(&mut map, path).expect("readable test input");
    let name = path
        .file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_default();
    let text = map.get(id).text.clone();
    // Re-add under the bare file name so snapshots do not depend on the checkout path.
    let mut named = SourceMap::new();
    let id = named.add(name, text.clone());
    let mut diags = Diagnostics::new();
    let file = parse::parse_file(id, &text, &mut diags);
    parse::check_structure(&file, &mut diags);
    (file, diags, named)
}

mod golden {
    use super::*;

    /// `tests/parse/ok/*.mod`: the AST dump (and any warnings); no errors allowed.
    #[test]
    fn ok() {
        insta::glob!("parse/ok/*.mod", |path| {
            let (file, diags, map) = check_path(path);
            let rendered = diags.render_plain(&map, 80);
            assert!(!diags.has_errors(), "{}:\n{rendered}", path.display());
            let mut out = file.dump();
            if !diags.is_empty() {
                out.push_str("----- WARNINGS\n");
                out.push_str(&rendered);
            }
            insta::assert_snapshot!(out);
        });
    }

    /// `tests/parse/err/*.mod`: the source and the rendered diagnostics; errors required.
    #[test]
    fn err() {
        insta::glob!("parse/err/*.mod", |path| {
            let (_, diags, map) = check_path(path);
            assert!(
                diags.has_errors(),
                "{} parses without errors",
                path.display()
            );
            let source = &map.get(SourceId(0)).text;
            let out = format!(
                "----- SOURCE CODE\n{source}\n----- ERROR\n{}",
                diags.render_plain(&map, 80)
            );
            insta::assert_snapshot!(out);
        });
    }
}

/// Every RAPID file under `programs/` parses and passes the structural checks.
#[test]
fn programs_check_clean() {
    let root = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("programs");
    let files = rapidvc::load::find_rapid_files(&[root]).expect("programs/ holds RAPID files");
    assert!(files.len() >= 3);
    for path in files {
        let (file, diags, map) = check_path(&path);
        assert!(
            diags.is_empty(),
            "{}:\n{}",
            path.display(),
            diags.render_plain(&map, 80)
        );
        assert!(!file.modules.is_empty());
    }
}

mod robustness {
    use super::*;

    fn wrap_stmt(stmt: &str) -> String {
        format!("MODULE m\n  PROC p()\n    {stmt}\n  ENDPROC\nENDMODULE\n")
    }

    #[test]
    fn nesting_at_the_limit_parses() {
        let n = parse::MAX_NESTING - 2;
        let parens = wrap_stmt(&format!("x := {}1{};", "(".repeat(n), ")".repeat(n)));
        let aggs = wrap_stmt(&format!("x := {}1{};", "[".repeat(n), "]".repeat(n)));
        let mixed = wrap_stmt(&format!(
            "x := {}a{};",
            "f([".repeat(n / 2),
            "])".repeat(n / 2)
        ));
        let ifs = wrap_stmt(&format!(
            "{}x := 1;{}",
            "IF a THEN ".repeat(n),
            " ENDIF".repeat(n)
        ));
        for text in [parens, aggs, mixed, ifs] {
            let (errors, len, shown) = on_small_stack(move || {
                let (f, d, m) = check("deep.mod", &text);
                (d.error_count(), f.modules.len(), d.render_plain(&m, 80))
            });
            assert_eq!((errors, len), (0, 1), "{shown}");
        }
    }
}
