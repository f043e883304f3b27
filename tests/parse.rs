//! Parser golden tests (AST dumps of `tests/parse/ok/*.mod`, rendered diagnostics of
//! `tests/parse/err/*.mod`), every file under `programs/` checking clean, robustness against
//! hostile input, and property tests (never panics, never overflows the stack).

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
