//! Packed literal aggregates (`ast::ExprKind::PackedAggregate`: a robtarget or tooldata
//! literal kept as its text instead of a tree of some twenty nodes) and packed call arguments
//! (`ast::CallArgs::Packed`: `MoveL p10, v500, z10, tool0;` kept as its text) and packed data
//! declarations (`ast::ModuleItem::PackedData`: `PERS robtarget p := [...];` kept as its
//! text) change nothing but memory:
//! the same AST dump, the same diagnostics (rendered and as JSON), the same lowered program
//! (what both interpreter engines run) whether the parser packs them or not, and a diagnostic
//! about one element of a packed aggregate points at that element.
#![allow(clippy::unwrap_used, clippy::expect_used)]

use proptest::prelude::*;
use rapidvc::ast::{CallArgs, ExprKind, ModuleItem, RoutineKind, StmtKind};
use rapidvc::diag::Diagnostics;
use rapidvc::parse::ParseOptions;
use rapidvc::sema;
use rapidvc::source::SourceMap;

/// Everything the front end makes of `text`.
#[derive(PartialEq)]
struct Outcome {
    dump: String,
    rendered: String,
    json: String,
    program: String,
}

/// Where two outcomes differ, as a short text (the lowered program alone is long).
impl std::fmt::Debug for Outcome {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "{}\n{}", self.dump, self.rendered)
    }
}

/// The first difference between two outcomes, with some context.
fn difference(a: &Outcome, b: &Outcome) -> Option<String> {
    for (what, x, y) in [
        ("dump", &a.dump, &b.dump),
        ("diagnostics", &a.rendered, &b.rendered),
        ("JSON diagnostics", &a.json, &b.json),
        ("lowered program", &a.program, &b.program),
    ] {
        if x != y {
            let at = x
                .bytes()
                .zip(y.bytes())
                .position(|(p, q)| p != q)
                .unwrap_or(x.len().min(y.len()));
            let around = |s: &str| -> String {
                s.char_indices()
                    .skip_while(|(i, _)| *i + 200 < at)
                    .take_while(|(i, _)| *i < at + 200)
                    .map(|(_, c)| c)
                    .collect()
            };
            return Some(format!(
                "the {what} differs at byte {at}:\n{}\n--- not packed ---\n{}",
                around(x),
                around(y)
            ));
        }
    }
    None
}

fn options(pack: bool) -> ParseOptions {
    ParseOptions {
        pack_literal_aggregates: pack,
        pack_simple_calls: pack,
        ..ParseOptions::single_thread()
    }
}

/// Parse `text` (packing literal aggregates and simple calls' arguments, or neither), check its structure and analyse it with
/// the stdlib.
fn outcome(text: &str, pack: bool) -> (Outcome, rapidvc::ast::File) {
    let mut map = SourceMap::new();
    let mut diags = Diagnostics::new();
    let mut std_diags = Diagnostics::new();
    let stdlib: Vec<rapidvc::ast::File> = rapidvc::interp::stdlib::SOURCES
        .iter()
        .map(|(name, t)| rapidvc::parse::parse_file(map.add(*name, *t), t, &mut std_diags))
        .collect();
    let id = map.add("packed.mod", text);
    let file = rapidvc::parse::parse_file_with(id, text, &mut diags, &options(pack));
    rapidvc::parse::check_structure(&file, &mut diags);
    let mut inputs: Vec<sema::Input<'_>> = stdlib
        .iter()
        .map(|file| sema::Input { file, stdlib: true })
        .collect();
    inputs.push(sema::Input {
        file: &file,
        stdlib: false,
    });
    let natives = rapidvc::interp::Registry::standard().signatures();
    let (program, errors) = sema::analyze_to_vec(&inputs, natives, &sema::Env::default());
    for e in errors {
        diags.push(e);
    }
    let out = Outcome {
        dump: file.dump(),
        rendered: diags.render_plain(&map, 120),
        json: diags.to_json(&map),
        // (What the engines run; the maps are left out: their order is not fixed.)
        program: match program {
            Some(p) => {
                let mut procs: Vec<_> = p.procs_by_name.iter().collect();
                procs.sort_by_key(|(name, _)| name.as_str());
                format!(
                    "{:?}",
                    (&p.modules, &p.globals, &p.routines, &p.init_order, procs)
                )
            }
            None => "no program".into(),
        },
    };
    (out, file)
}

/// The initial value of the first data declaration of the first module.
fn first_init(file: &rapidvc::ast::File) -> ExprKind {
    let item = file.modules[0]
        .items
        .iter()
        .find_map(|i| i.data(file.span.source, &file.text)?.init.clone())
        .expect("a data declaration with a value");
    item.kind
}

/// A literal as it may stand in a literal aggregate: numbers of every form (some out of the
/// range of `num`), signed or not, strings (one with an invalid escape) and booleans.
fn leaf() -> impl Strategy<Value = String> {
    let number = prop::sample::select(vec![
        "0",
        "1",
        "12",
        "007",
        "1.5",
        ".5",
        "1.",
        "9E+09",
        "9e9",
        "1e-3",
        "2.5E2",
        "3.4E38",
        "1E39",
        "0.000494947",
        "123456789012345678",
    ]);
    let sign = prop::sample::select(vec!["", "", "-", "+", "- "]);
    let other = prop::sample::select(vec![
        "TRUE",
        "false",
        "\"\"",
        "\"a\"\"b\"",
        "\"\\41x\"",
        "\"bad\\q\"",
    ]);
    prop_oneof![
        6 => (sign, number).prop_map(|(s, n)| format!("{s}{n}")),
        1 => other.prop_map(str::to_string),
    ]
}

/// White space and comments between the tokens of an aggregate.
fn gap() -> impl Strategy<Value = &'static str> {
    prop::sample::select(vec!["", "", "", " ", "\r\n      ", " ! note\n  "])
}

/// A literal aggregate of up to three levels.
fn aggregate() -> impl Strategy<Value = String> {
    leaf().prop_recursive(3, 24, 6, |inner| {
        (prop::collection::vec((inner, gap(), gap()), 1..6), gap()).prop_map(|(items, end)| {
            let body: Vec<String> = items
                .into_iter()
                .map(|(x, before, after)| format!("{before}{x}{after}"))
                .collect();
            format!("[{}{end}]", body.join(","))
        })
    })
}

/// A value of the shape of a type (often well-typed, so the lowering is compared too).
fn shaped(sizes: &'static [usize]) -> impl Strategy<Value = String> {
    let n: usize = sizes.iter().sum();
    prop::collection::vec((prop::sample::select(vec!["", "-"]), 0u32..2000), n).prop_map(move |v| {
        let mut it = v
            .into_iter()
            .map(|(s, x)| format!("{s}{}.{}", x / 10, x % 10));
        let groups: Vec<String> = sizes
            .iter()
            .map(|&k| {
                format!(
                    "[{}]",
                    (0..k)
                        .filter_map(|_| it.next())
                        .collect::<Vec<_>>()
                        .join(",")
                )
            })
            .collect();
        format!("[{}]", groups.join(","))
    })
}

/// A program that uses aggregates as data values, routine data, assigned values, operands
/// and arguments.
fn program() -> impl Strategy<Value = String> {
    (
        prop::collection::vec(aggregate(), 7),
        shaped(&[3, 4, 4, 6]),
        shaped(&[3, 3]),
    )
        .prop_map(|(a, robtarget, table)| {
            format!(
                "MODULE M\n  VAR robtarget p := {robtarget};\n  CONST num t{{2,3}} := {table};\n  VAR robtarget r := {};\n  PERS num n{{3}} := {};\n  VAR pos q := {};\n  PROC main()\n    VAR num k{{2}} := {};\n    r := {};\n    q := q + {};\n    TPWrite \"x\" \\Pos:={};\n    p := p;\n  ENDPROC\nENDMODULE\n",
                a[0], a[1], a[2], a[3], a[4], a[5], a[6]
            )
        })
}

/// An argument of a procedure call: names, literals (some out of range or with a bad
/// escape), optional arguments with and without a value, and forms that are never packed
/// (conditional and named arguments, expressions, aggregates, placeholders).
fn call_arg() -> impl Strategy<Value = String> {
    let name = prop::sample::select(vec![
        "p10", "v500", "z10", "tool0", "n", "x_1", "TRUE", "False", "wobj0", "tBench",
    ]);
    let other = prop::sample::select(vec![
        "Offs(p10, 0, 0, 5)",
        "Offs(p10,-1, 2.5 ,-0)",
        "Offs (RelTool(p10, 0, 0, 1 \\Rz:=90), 0, 0, 5)",
        "Abs()",
        "NumToStr(n, 0)",
        "Offs(p10, 0, 0, n + 1)",
        "CRobT(\\Tool:=tool0 \\WObj:=wobj0)",
        "n + 1",
        "-n",
        "(n)",
        "x{1}",
        "p10.trans",
        "\\A?B",
        "n:=1",
        "<ARG>",
        "\\Num:=n * 2",
        "\\Conc",
        "\\ WObj := wobj0",
    ]);
    prop_oneof![
        3 => name.clone().prop_map(str::to_string),
        3 => leaf(),
        2 => (name.clone(), prop_oneof![name.clone().prop_map(str::to_string), leaf()])
            .prop_map(|(n, v)| format!("\\{n}:={v}")),
        1 => name.prop_map(|n| format!("\\{n}")),
        1 => aggregate(),
        1 => other.prop_map(str::to_string),
    ]
}

/// A routine of calls to instructions, to a user procedure and to unknown names, with
/// arguments separated by commas or (before an optional one) by nothing, and white space or
/// comments between the tokens.
fn calls() -> impl Strategy<Value = String> {
    let callee = prop::sample::select(vec!["MoveL", "TPWrite", "WaitTime", "mine", "Nothing"]);
    let call = (
        callee,
        prop::collection::vec((gap(), call_arg(), gap(), prop::bool::ANY), 0..6),
        gap(),
    )
        .prop_map(|(callee, args, end)| {
            let mut s = format!("    {callee}");
            for (k, (before, a, after, comma)) in args.into_iter().enumerate() {
                let sep = if k == 0 || (!comma && a.starts_with('\\')) {
                    " "
                } else {
                    ","
                };
                s.push_str(&format!("{sep}{before}{a}{after}"));
            }
            s.push_str(&format!("{end};\n"));
            s
        });
    prop::collection::vec(call, 1..8).prop_map(|body| {
        format!(
            "MODULE M\n  VAR num n := 1;\n  VAR num x{{2}};\n  VAR robtarget p10;\n  PROC mine(num a, \\switch s, \\num b)\n  ENDPROC\n  PROC main()\n{}  ENDPROC\nENDMODULE\n",
            body.concat()
        )
    })
}

/// A module data declaration of every form: keywords in any case (some repeated or out of
/// order), white space and comments between every token, values that are packed (none,
/// names, literals, literal aggregates) and values that are not (expressions, calls, array
/// dimensions, placeholders), some with a diagnostic, some duplicated names.
fn data_decl() -> impl Strategy<Value = String> {
    let head = prop::sample::select(vec![
        "VAR",
        "PERS",
        "CONST",
        "var",
        "Pers",
        "LOCAL VAR",
        "LOCAL PERS",
        "TASK PERS",
        "LOCAL CONST",
        "TASK VAR",
        "LOCAL TASK PERS",
        "TASK LOCAL PERS",
        "LOCAL LOCAL VAR",
    ]);
    let ty = prop::sample::select(vec![
        "num",
        "robtarget",
        "pos",
        "string",
        "bool",
        "benchnum",
        "Nope",
    ]);
    let name = prop::sample::select(vec!["a", "b", "target_10", "n", "PI", "<ID>"]);
    let other = prop::sample::select(vec![
        "n + 1",
        "-n",
        "(3)",
        "Abs(-1)",
        "[n, 2, 3]",
        "<EXP>",
        "p.trans",
        "-  -2",
    ]);
    let value = prop_oneof![
        2 => Just(String::new()),
        3 => leaf(),
        2 => aggregate(),
        1 => prop::sample::select(vec!["n", "TRUE", "false", "wobj0"]).prop_map(str::to_string),
        1 => other.prop_map(str::to_string),
    ];
    let dims = prop::sample::select(vec!["", "", "", "{2}", "{n}"]);
    (head, gap(), ty, gap(), name, dims, gap(), value, gap()).prop_map(
        |(head, g1, ty, g2, name, dims, g3, value, g4)| {
            let value = if value.is_empty() {
                String::new()
            } else {
                format!("{g3}:={g4}{value}")
            };
            format!("  {head} {g1}{ty} {g2}{name}{dims}{value}{g4};\n")
        },
    )
}

/// A module of data declarations (used by a routine, so their values are lowered too).
fn datas() -> impl Strategy<Value = String> {
    prop::collection::vec(data_decl(), 1..10).prop_map(|decls| {
        format!(
            "MODULE M\n  ALIAS num benchnum;\n{}  PROC main()\n    TPWrite \"x\" \\Num:=n;\n  ENDPROC\nENDMODULE\n",
            decls.concat()
        )
    })
}

/// The items of the first module of a parsed file that are packed data declarations.
fn packed_data(file: &rapidvc::ast::File) -> Vec<bool> {
    file.modules[0]
        .items
        .iter()
        .filter(|i| matches!(i, ModuleItem::Data(_) | ModuleItem::PackedData(_)))
        .map(|i| matches!(i, ModuleItem::PackedData(_)))
        .collect()
}

/// A module data declaration of names and literals is kept as its text; one with array
/// dimensions, an expression, a placeholder or a diagnostic is not; without the option none
/// is. Either way the front end and the interpreters see the same.
#[test]
fn simple_data_declarations_are_packed() {
    let text = "MODULE M\n  VAR num n := 1;\n  LOCAL PERS robtarget p := [[1,2,3],[1,0,0,0],[0,0,0,0],[9E9,9E9,9E9,9E9,9E9,9E9]];\n  TASK PERS string s := \"a\"\"b\";\n  CONST num m := -2.5;\n  VAR pos q;\n  VAR num k{2} := [1, 2];\n  VAR num e := n + 1;\n  VAR num big := 1E39;\n  VAR num <ID> := 1;\n  CONST bool t := TRUE;\n  VAR num d := n;\n  PROC main()\n    TPWrite s \\Num:=n + m + e + d + k{1} + big;\n  ENDPROC\nENDMODULE\n";
    let (packed, file) = outcome(text, true);
    assert_eq!(
        packed_data(&file),
        [
            true, true, true, true, true, false, false, false, false, true, true
        ]
    );
    let (plain, file) = outcome(text, false);
    assert!(packed_data(&file).iter().all(|p| !p));
    let diff = difference(&packed, &plain);
    assert!(diff.is_none(), "{}", diff.unwrap_or_default());
}

/// The calls of the routine `main` of a parsed file.
fn main_calls(file: &rapidvc::ast::File) -> Vec<&CallArgs> {
    file.modules[0]
        .items
        .iter()
        .filter_map(|i| match i {
            ModuleItem::Routine(r) if r.name.is("main") && matches!(r.kind, RoutineKind::Proc) => {
                Some(&r.body)
            }
            _ => None,
        })
        .flatten()
        .filter_map(|s| match &s.kind {
            StmtKind::Call { args, .. } => Some(args),
            _ => None,
        })
        .collect()
}

/// A call whose arguments are names, literals and calls of functions with such arguments is
/// packed; one without arguments, with an expression, or with a diagnostic in an argument is
/// not; without the option nothing is.
#[test]
fn simple_calls_are_packed() {
    let text = "MODULE M\n  PROC main()\n    MoveL p10, v500, z10, tool0\\WObj:=wobj0;\n    TPWrite \"a\"\"b\" \\Num:=-1.5E3;\n    Stop;\n    MoveL Offs(p10, 0, 0, 5), v500, fine, tool0;\n    TPWrite \"bad\\q\";\n    WaitTime 1E39;\n    MoveL Offs(p10, 0, 0, n + 5), v500, fine, tool0;\n    MoveL Offs (RelTool(p10, 0, -1, 2 \\Rz:=90), 0,0,5)\\Conc, v500, fine, tool0;\n  ENDPROC\nENDMODULE\n";
    let (packed, file) = outcome(text, true);
    let kinds: Vec<bool> = main_calls(&file)
        .iter()
        .map(|a| matches!(a, CallArgs::Packed(_)))
        .collect();
    assert_eq!(kinds, [true, true, false, true, false, false, false, true]);
    let (plain, file) = outcome(text, false);
    assert!(
        main_calls(&file)
            .iter()
            .all(|a| matches!(a, CallArgs::Tree(_)))
    );
    let diff = difference(&packed, &plain);
    assert!(diff.is_none(), "{}", diff.unwrap_or_default());
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 96, ..ProptestConfig::default() })]

    /// Packing call arguments changes nothing the front end or the interpreters see.
    #[test]
    fn packing_calls_changes_nothing(text in calls()) {
        let (packed, _) = outcome(&text, true);
        let (plain, _) = outcome(&text, false);
        let diff = difference(&packed, &plain);
        prop_assert!(diff.is_none(), "{}\n{}", text, diff.unwrap_or_default());
    }

    /// Packing data declarations changes nothing the front end or the interpreters see.
    #[test]
    fn packing_data_changes_nothing(text in datas()) {
        let (packed, _) = outcome(&text, true);
        let (plain, _) = outcome(&text, false);
        let diff = difference(&packed, &plain);
        prop_assert!(diff.is_none(), "{}\n{}", text, diff.unwrap_or_default());
    }

    /// Packing changes nothing the front end or the interpreters see.
    #[test]
    fn packing_changes_nothing(text in program()) {
        let (packed, _) = outcome(&text, true);
        let (plain, _) = outcome(&text, false);
        let diff = difference(&packed, &plain);
        prop_assert!(diff.is_none(), "{}\n{}", text, diff.unwrap_or_default());
    }
}

/// The repository's programs and test inputs, packed or not.
#[test]
fn every_program_is_the_same_packed() {
    let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR"));
    let mut stack = vec![root.join("tests"), root.join("programs")];
    let mut n = 0;
    while let Some(d) = stack.pop() {
        for e in std::fs::read_dir(&d).into_iter().flatten().flatten() {
            let p = e.path();
            if p.is_dir() {
                stack.push(p);
            } else if p
                .extension()
                .is_some_and(|x| x == "mod" || x == "prg" || x == "sys")
            {
                let text = std::fs::read_to_string(&p).unwrap_or_default();
                assert_eq!(
                    outcome(&text, true).0,
                    outcome(&text, false).0,
                    "{}",
                    p.display()
                );
                n += 1;
            }
        }
    }
    assert!(n > 20, "found only {n} programs");
}

/// A robtarget literal is packed, and a diagnostic about one of its elements points at that
/// element (line and column), as it does when it is not packed.
#[test]
fn diagnostic_inside_a_packed_aggregate_points_at_the_element() {
    let text = "MODULE M\n  VAR robtarget p := [[1,2,3],[1,0,0,0],[0,0,0,0],[9E9,9E9,  \"x\"  ,9E9,9E9,9E9]];\nENDMODULE\n";
    let (packed, file) = outcome(text, true);
    assert!(
        matches!(first_init(&file), ExprKind::PackedAggregate(_)),
        "{:?}",
        first_init(&file)
    );
    let (plain, file) = outcome(text, false);
    assert!(matches!(first_init(&file), ExprKind::Aggregate(_)));
    assert!(difference(&packed, &plain).is_none());
    let line = text.lines().nth(1).unwrap();
    let column = line.find("\"x\"").unwrap() + 1;
    assert!(
        packed.rendered.contains(&format!("packed.mod:2:{column}")),
        "expected the element at 2:{column}:\n{}",
        packed.rendered
    );
}

/// An aggregate the parser reports something in is not packed: the diagnostic is given once,
/// at parse time, and the tree is the one built while reporting it.
#[test]
fn an_aggregate_with_a_parse_error_is_not_packed() {
    let text = "MODULE M\n  VAR pos p := [1, 1E39, 3];\nENDMODULE\n";
    let (packed, file) = outcome(text, true);
    assert!(matches!(first_init(&file), ExprKind::Aggregate(_)));
    let line = text.lines().nth(1).unwrap();
    let column = line.find("1E39").unwrap() + 1;
    assert!(
        packed.rendered.contains(&format!("packed.mod:2:{column}")),
        "{}",
        packed.rendered
    );
    let diff = difference(&packed, &outcome(text, false).0);
    assert!(diff.is_none(), "{}", diff.unwrap_or_default());
}
