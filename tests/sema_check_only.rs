//! `sema::check_only` (what `rapidvc check` runs) against the full analysis: the same
//! diagnostics on every RAPID file of the repository's tests and programs.
#![allow(clippy::unwrap_used, clippy::expect_used)]

use rapidvc::sema;

/// `check_only` drops the lowered code as it goes; its diagnostics are exactly those of
/// the full analysis, on every RAPID file of the repository's tests and programs.
#[test]
fn check_only_reports_what_the_full_analysis_reports() {
    let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR"));
    let mut paths = Vec::new();
    for dir in ["tests/run", "tests/rapid", "programs"] {
        let mut stack = vec![root.join(dir)];
        while let Some(d) = stack.pop() {
            for e in std::fs::read_dir(&d).into_iter().flatten().flatten() {
                let p = e.path();
                if p.is_dir() {
                    stack.push(p);
                } else if p.extension().is_some_and(|x| x == "mod") {
                    paths.push(p);
                }
            }
        }
    }
    assert!(paths.len() > 20, "found only {} programs", paths.len());
    let natives = rapidvc::interp::Registry::standard().signatures();
    let mut diags = rapidvc::diag::Diagnostics::new();
    let mut map = rapidvc::source::SourceMap::new();
    let stdlib: Vec<rapidvc::ast::File> = rapidvc::interp::stdlib::SOURCES
        .iter()
        .map(|(name, text)| rapidvc::parse::parse_file(map.add(*name, *text), text, &mut diags))
        .collect();
    for path in paths {
        let text = std::fs::read_to_string(&path).unwrap_or_default();
        let file = rapidvc::parse::parse_file(map.add("p", text.as_str()), &text, &mut diags);
        let mut inputs: Vec<sema::Input<'_>> = stdlib
            .iter()
            .map(|file| sema::Input { file, stdlib: true })
            .collect();
        inputs.push(sema::Input {
            file: &file,
            stdlib: false,
        });
        let env = sema::Env::default();
        let full = sema::analyze_to_vec(&inputs, natives.clone(), &env).1;
        let only = sema::check_only(&inputs, natives.clone(), &env);
        assert_eq!(
            format!("{full:?}"),
            format!("{only:?}"),
            "{}",
            path.display()
        );
    }
}
