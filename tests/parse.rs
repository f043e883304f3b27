//! Parser golden tests (AST dumps of `tests/parse/ok/*.mod`, rendered diagnostics of
//! `tests/parse/err/*.mod`), every file under `programs/` checking clean, robustness against
//! hostile input, and property tests (never panics, never overflows the stack).

use std::path::{Path, PathBuf};

use rapidvc::diag::Diagnostics;
use rapidvc::parse;
use rapidvc::source::{SourceId, SourceMap};

use rapidvc_testkit::gen_program;

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
    let id = rapidvc::program::rapid_files::load_file(&mut map, path).expect("readable test input");
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
    let files = rapidvc::program::rapid_files::find_rapid_files(&[root])
        .expect("programs/ holds RAPID files");
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

    /// Codes of the diagnostics of `text`, parsed on a 2 MiB stack.
    fn codes(text: String) -> Vec<String> {
        on_small_stack(move || {
            let (_, d, _) = check("input.mod", &text);
            d.iter()
                .filter_map(|x| miette::Diagnostic::code(x).map(|c| c.to_string()))
                .collect()
        })
    }

    #[test]
    fn nesting_beyond_the_limit_is_an_error() {
        let n = 1000;
        for text in [
            wrap_stmt(&format!("x := {}1{};", "(".repeat(n), ")".repeat(n))),
            wrap_stmt(&format!("x := {}1{};", "[".repeat(n), "]".repeat(n))),
            wrap_stmt(&format!("x := {}a{};", "f(".repeat(n), ")".repeat(n))),
            wrap_stmt(&format!(
                "{}x := 1;{}",
                "IF a THEN ".repeat(n),
                " ENDIF".repeat(n)
            )),
            wrap_stmt(&format!("{}x := 1;", "WHILE a DO ".repeat(n))),
            wrap_stmt(&"(".repeat(n)),
            "(".repeat(100_000),
        ] {
            assert_eq!(codes(text), ["rapidvc::parse::nesting_too_deep"]);
        }
    }

    #[test]
    fn long_chains_are_bounded() {
        let n = 100_000;
        for text in [
            wrap_stmt(&format!("x := 1{};", " + 1".repeat(n))),
            wrap_stmt(&format!("x := {}1;", "-".repeat(n))),
            wrap_stmt(&format!("x := p{};", ".x".repeat(n))),
            wrap_stmt(&format!("x := a{};", "{1}".repeat(n))),
        ] {
            assert_eq!(codes(text), ["rapidvc::parse::expression_too_complex"]);
        }
        // Long but flat: fine.
        let args = vec!["1"; n].join(", ");
        assert!(codes(wrap_stmt(&format!("Call {args};"))).is_empty());
        assert!(codes(wrap_stmt(&format!("x := [{args}];"))).is_empty());
    }

    #[test]
    fn hundred_thousand_lines() {
        let mut text = gen_program::program(1 << 20);
        while text.lines().count() < 100_000 {
            text = gen_program::program(text.len() * 2);
        }
        assert!(codes(text).is_empty());
    }

    #[test]
    fn ten_megabyte_single_line() {
        let stmt = "x := x + 1; MoveL p, v100, z10, t\\WObj:=w; ";
        let body = stmt.repeat((10 << 20) / stmt.len() + 1);
        let text = format!("MODULE m PROC p() {body} ENDPROC ENDMODULE");
        assert!(text.len() >= 10 << 20 && !text.contains('\n'));
        assert!(codes(text).is_empty());
        // One enormous token of each kind.
        let big = 10 << 20;
        assert!(codes(format!("MODULE m VAR num {};ENDMODULE", "a".repeat(big))).is_empty());
        assert_eq!(
            codes(format!(
                "MODULE m CONST string s := \"{};ENDMODULE",
                "a".repeat(big)
            )),
            ["rapidvc::parse::unterminated_string"]
        );
        assert_eq!(
            codes(format!(
                "MODULE m CONST num n := {};ENDMODULE",
                "9".repeat(big)
            )),
            ["rapidvc::parse::number_out_of_range"]
        );
    }

    /// A deterministic byte sequence (64-bit LCG).
    fn pseudo_random(len: usize, seed: u64) -> Vec<u8> {
        let mut x = seed;
        (0..len)
            .map(|_| {
                x = x
                    .wrapping_mul(6364136223846793005)
                    .wrapping_add(1442695040888963407);
                (x >> 33) as u8
            })
            .collect()
    }

    #[test]
    fn binary_garbage() {
        let all: Vec<u8> = (0..=255u8).cycle().take(64 * 1024).collect();
        for bytes in [pseudo_random(256 * 1024, 1), pseudo_random(4096, 2), all] {
            let text = rapidvc::source::decode_bytes(&bytes);
            let errors = on_small_stack(move || check("bin.mod", &text).1.error_count());
            assert!((1..=parse::MAX_ERRORS_PER_FILE + 1).contains(&errors));
        }
    }

    #[test]
    fn truncated_programs() {
        for path in manual_programs() {
            let text = std::fs::read_to_string(&path).expect("program");
            let texts: Vec<String> = (0..text.len())
                .step_by(7)
                .filter(|&i| text.is_char_boundary(i))
                .map(|i| text[..i].to_string())
                .collect();
            on_small_stack(move || {
                for t in texts {
                    let (_, d, _) = check("cut.mod", &t);
                    assert!(
                        t.trim().is_empty()
                            || d.has_errors()
                            || t.trim_end().ends_with("ENDMODULE")
                    );
                }
            });
        }
    }

    #[test]
    fn many_errors_are_capped() {
        let text = wrap_stmt(&"x := ;\n".repeat(20_000));
        let errors = on_small_stack(move || check("many.mod", &text).1.len());
        assert_eq!(errors, parse::MAX_ERRORS_PER_FILE + 1);
    }
}

fn manual_programs() -> Vec<PathBuf> {
    let dir = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("programs/manual");
    rapidvc::program::rapid_files::find_rapid_files(&[dir]).expect("manual programs")
}

/// Property tests: the parser never panics, whatever the input.
mod properties {
    use super::*;
    use proptest::prelude::*;

    /// Mutations of a token list: delete, duplicate, swap or insert.
    #[derive(Debug, Clone)]
    enum Mutation {
        Delete(usize),
        Duplicate(usize),
        Swap(usize, usize),
        Insert(usize, &'static str),
    }

    const VOCABULARY: &[&str] = &[
        ";",
        ",",
        "(",
        ")",
        "[",
        "]",
        "{",
        "}",
        ":=",
        ":",
        "\\",
        "?",
        "%",
        "\"",
        "!",
        "<SMT>",
        "IF",
        "THEN",
        "ELSE",
        "ENDIF",
        "WHILE",
        "DO",
        "ENDWHILE",
        "FOR",
        "TEST",
        "CASE",
        "ENDPROC",
        "PROC",
        "FUNC",
        "ENDFUNC",
        "ENDMODULE",
        "MODULE",
        "NOT",
        "AND",
        "-",
        "*",
        "9E+09",
        ".5",
        "x",
    ];

    fn mutation() -> impl Strategy<Value = Mutation> {
        prop_oneof![
            any::<usize>().prop_map(Mutation::Delete),
            any::<usize>().prop_map(Mutation::Duplicate),
            (any::<usize>(), any::<usize>()).prop_map(|(a, b)| Mutation::Swap(a, b)),
            (any::<usize>(), prop::sample::select(VOCABULARY))
                .prop_map(|(a, t)| Mutation::Insert(a, t)),
        ]
    }

    /// Split into tokens, keeping the separators attached so the text stays readable.
    fn tokens(text: &str) -> Vec<String> {
        let mut out = Vec::new();
        let mut cur = String::new();
        for c in text.chars() {
            cur.push(c);
            if c.is_whitespace() || ",;()[]".contains(c) {
                out.push(std::mem::take(&mut cur));
            }
        }
        out.push(cur);
        out
    }

    fn apply(mut toks: Vec<String>, muts: &[Mutation]) -> String {
        for m in muts {
            let n = toks.len().max(1);
            match *m {
                Mutation::Delete(i) if !toks.is_empty() => {
                    toks.remove(i % n);
                }
                Mutation::Duplicate(i) if !toks.is_empty() => {
                    let t = toks[i % n].clone();
                    toks.insert(i % n, t);
                }
                Mutation::Swap(a, b) if !toks.is_empty() => toks.swap(a % n, b % n),
                Mutation::Insert(i, t) => toks.insert(i % (toks.len() + 1), format!(" {t} ")),
                _ => {}
            }
        }
        toks.concat()
    }

    proptest! {
        #![proptest_config(ProptestConfig { cases: 256, ..ProptestConfig::default() })]

        #[test]
        fn arbitrary_bytes_never_panic(bytes in prop::collection::vec(any::<u8>(), 0..2048)) {
            let text = rapidvc::source::decode_bytes(&bytes);
            let (_, d, m) = check("bytes.mod", &text);
            // Rendering must not panic either.
            let _ = d.render_plain(&m, 80);
            let _ = d.to_json(&m);
        }

        #[test]
        fn arbitrary_text_never_panics(text in "(MODULE m|PROC p\\(\\)|[ -~\n\t]|ENDPROC|ENDMODULE|IF |THEN|:=|<SMT>){0,120}") {
            let (_, d, m) = check("text.mod", &text);
            let _ = d.render_plain(&m, 80);
        }
    }

    proptest! {
        #![proptest_config(ProptestConfig { cases: 128, ..ProptestConfig::default() })]

        #[test]
        fn mutated_programs_never_panic(
            which in 0usize..3,
            muts in prop::collection::vec(mutation(), 1..8),
        ) {
            let programs = manual_programs();
            let text = std::fs::read_to_string(&programs[which % programs.len()]).expect("program");
            let mutated = apply(tokens(&text), &muts);
            let (_, d, m) = check("mutated.mod", &mutated);
            let _ = d.render_plain(&m, 80);
        }
    }
}

/// The AST dump and rendered diagnostics of `text` parsed and checked with `options`.
fn outcome(text: &str, options: &parse::ParseOptions) -> (String, String) {
    let mut map = SourceMap::new();
    let id = map.add("same.mod", text);
    let mut diags = Diagnostics::new();
    let file = parse::parse_file_with(id, text, &mut diags, options);
    parse::check_structure_with(&file, &mut diags, options);
    (file.dump(), diags.render_plain(&map, 80))
}

/// Every RAPID file of the repository's programs, stdlib and test inputs: name and text.
fn repository_texts() -> Vec<(String, String)> {
    let root = PathBuf::from(env!("CARGO_MANIFEST_DIR"));
    let dirs = [
        "programs",
        "stdlib",
        "tests/parse/ok",
        "tests/parse/err",
        "tests/run",
        "tests/rapid",
    ];
    let files = rapidvc::program::rapid_files::find_rapid_files(&dirs.map(|d| root.join(d)))
        .expect("RAPID files in the repository");
    assert!(files.len() > 20);
    files
        .into_iter()
        .map(|path| {
            let mut map = SourceMap::new();
            let id = rapidvc::program::rapid_files::load_file(&mut map, &path).expect("readable");
            (path.display().to_string(), map.get(id).text.to_string())
        })
        .collect()
}

/// A module body cut into pieces parsed (and marked, and structure-checked) on several
/// threads gives the same AST and the same diagnostics, in the same order, as one thread,
/// for clean and broken programs alike.
mod parallel {
    use super::*;
    use proptest::prelude::*;
    use rapidvc::parse::ParseOptions;

    /// Every routine start is a cut, on three threads.
    fn cut_everywhere() -> ParseOptions {
        ParseOptions {
            threads: 3,
            parallel_min_bytes: 1,
            ..ParseOptions::default()
        }
    }

    fn assert_same(name: &str, text: &str) {
        let one = outcome(text, &ParseOptions::single_thread());
        let cut = outcome(text, &cut_everywhere());
        assert!(
            one == cut,
            "{name}: a cut parse differs from a one-piece parse"
        );
    }

    #[test]
    fn large_generated_program() {
        let text = gen_program::program(600 << 10);
        // (Large enough to be cut with the default options too.)
        let one = outcome(&text, &ParseOptions::single_thread());
        assert!(one.1.is_empty(), "{}", one.1);
        assert!(one == outcome(&text, &ParseOptions::default()));
        assert!(
            one == outcome(
                &text,
                &ParseOptions {
                    threads: 8,
                    ..ParseOptions::default()
                }
            )
        );
        assert!(one == outcome(&text, &cut_everywhere()));
    }

    #[test]
    fn every_program_and_test_input() {
        for (name, text) in repository_texts() {
            assert_same(&name, &text);
        }
    }

    /// Lines a cut is made at, or that make a cut wrong, inserted at line starts.
    const LINES: &[&str] = &[
        "PROC q()",
        "LOCAL PROC q()",
        "  func num f()",
        "TRAP t",
        "ENDPROC",
        "ENDFUNC",
        "ENDMODULE",
        "MODULE n",
        "\"",
        "! PROC in a comment",
        "VAR num x;",
        "IF TRUE THEN",
        "<SMT>",
        "PROC",
    ];

    proptest! {
        #![proptest_config(ProptestConfig { cases: 96, ..ProptestConfig::default() })]

        #[test]
        fn mutated_programs_parse_the_same_cut_or_not(
            seed in 0usize..4,
            inserts in prop::collection::vec((any::<usize>(), prop::sample::select(LINES)), 0..4),
            deletes in prop::collection::vec(any::<usize>(), 0..3),
        ) {
            let mut text = match seed {
                0 => gen_program::program(24 << 10),
                _ => {
                    let programs = manual_programs();
                    std::fs::read_to_string(&programs[seed % programs.len()]).expect("program")
                }
            };
            let mut lines: Vec<String> = text.split_inclusive('\n').map(String::from).collect();
            for (at, line) in inserts {
                let n = lines.len() + 1;
                lines.insert(at % n, format!("{line}\n"));
            }
            for at in deletes {
                if !lines.is_empty() {
                    let n = lines.len();
                    lines.remove(at % n);
                }
            }
            text = lines.concat();
            let one = outcome(&text, &ParseOptions::single_thread());
            let cut = outcome(&text, &cut_everywhere());
            prop_assert!(one == cut, "cut parse differs:\n{}\n--- vs ---\n{}", one.1, cut.1);
        }
    }
}

/// The lexical pre-pass (`parse/marks.rs`) changes nothing but speed: the same AST and the
/// same diagnostics with and without it, for clean, broken and binary input.
mod lexical_marks {
    use super::*;
    use proptest::prelude::*;
    use rapidvc::parse::ParseOptions;

    fn assert_same(name: &str, text: &str) -> Result<(), TestCaseError> {
        let marks = |lexical_marks| ParseOptions {
            lexical_marks,
            ..ParseOptions::single_thread()
        };
        let (with, without) = (outcome(text, &marks(true)), outcome(text, &marks(false)));
        prop_assert!(
            with == without,
            "{name}: the pre-pass changed the result\n{}\n--- without ---\n{}",
            with.1,
            without.1
        );
        Ok(())
    }

    #[test]
    fn every_program_and_test_input() {
        for (name, text) in repository_texts() {
            assert_same(&name, &text).expect("same result");
        }
        assert_same("generated", &gen_program::program(200 << 10)).expect("same result");
    }

    /// Text that looks like RAPID where names, numbers, aggregates, components and
    /// placeholders meet every kind of neighbour.
    const PIECES: &[&str] = &[
        "x",
        "ab_1",
        "If",
        "endif",
        "NOT",
        "a.b",
        "1.e5",
        "1e5",
        "0x1F",
        ".5",
        "1.",
        "9E+09",
        "[",
        "]",
        "[1,2]",
        "[[1,2],[3]]",
        "[a,b]",
        "[-1,+2.5]",
        "{",
        "}",
        "(",
        ")",
        "<ID>",
        "<EXP>",
        "<SMT>",
        "\\",
        "\\Sw",
        ":=",
        ":",
        ";",
        ",",
        ".",
        "?",
        "%",
        "\"",
        "\"s\"",
        "!c\n",
        "\n",
        " ",
        "\t",
        "\r\n",
        "\u{1}",
        "\u{3}",
        "é",
        "MODULE m\n",
        "PROC p()\n",
        "ENDPROC\n",
        "ENDMODULE\n",
        "VAR num n:=",
        "CONST robtarget p:=",
        "MoveL ",
        "TRUE",
        "_x",
        "x_",
        "1_",
        "a1.x",
        "f(a).x",
        "a{1}.x",
    ];

    proptest! {
        #![proptest_config(ProptestConfig { cases: 512, ..ProptestConfig::default() })]

        #[test]
        fn token_soup(pieces in prop::collection::vec(prop::sample::select(PIECES), 0..60)) {
            let text = format!("MODULE m\nPROC p()\n{}\nENDPROC\nENDMODULE\n", pieces.concat());
            assert_same("soup", &text)?;
            assert_same("bare soup", &pieces.concat())?;
        }

        #[test]
        fn mutated_programs(
            which in 0usize..3,
            edits in prop::collection::vec((any::<usize>(), any::<u8>(), 0u8..3), 1..6),
        ) {
            let programs = manual_programs();
            let text = std::fs::read_to_string(&programs[which % programs.len()]).expect("program");
            let mut bytes = text.into_bytes();
            for (at, byte, kind) in edits {
                let at = at % (bytes.len() + 1);
                match kind {
                    0 => bytes.insert(at, byte),
                    1 if at < bytes.len() => { bytes.remove(at); }
                    _ if at < bytes.len() => bytes[at] = byte,
                    _ => {}
                }
            }
            assert_same("mutated", &rapidvc::source::decode_bytes(&bytes))?;
        }
    }
}
