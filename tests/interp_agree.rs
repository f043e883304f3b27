//! The interpreter's two engines agree (issue 11): the compiled closures with their fast
//! paths (`src/interp/compile/`) and the tree-walking reference (`src/interp/expr.rs`,
//! `src/interp/stmt.rs`) must give the same TP output, the same final data, the same errors
//! (number, text, line, call stack) and the same step count.
//!
//! * Every RAPID file of the repository is run by the command-line tool once per engine
//!   (`RAPIDVC_ENGINE`); exit code, stdout and stderr must be identical.
//! * Generated programs (proptest) over num/dnum/bool/string arithmetic, records, arrays,
//!   IF/WHILE/FOR/TEST/GOTO, calls with every parameter mode, ERROR handlers with
//!   RETRY/TRYNEXT/RAISE/RETURN and simple (inlined) functions run in this process on both
//!   engines and are compared in full.

use rapidvc_testkit::rapidvc;
use std::path::{Path, PathBuf};

use rapidvc_testkit::summary;
use summary::without_wall_time;

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

/// Run the command-line tool in `dir` on `engine`: (exit code, stdout, stderr without the
/// wall-clock part of the motion summary).
fn run_tool(dir: &Path, args: &[String], engine: &str) -> (i32, String, String) {
    let out = rapidvc!()
        .args(args)
        .current_dir(dir)
        .env("COLUMNS", "80")
        .env("NO_COLOR", "1")
        .env("RAPIDVC_ENGINE", engine)
        .output()
        .expect("run rapidvc");
    (
        out.status.code().unwrap_or(-1),
        String::from_utf8_lossy(&out.stdout).into_owned(),
        without_wall_time(&String::from_utf8_lossy(&out.stderr)),
    )
}

/// Every `.mod` file under `dir`, sorted.
fn rapid_files(dir: &Path, out: &mut Vec<PathBuf>) {
    let Ok(entries) = std::fs::read_dir(dir) else {
        return;
    };
    let mut paths: Vec<PathBuf> = entries.flatten().map(|e| e.path()).collect();
    paths.sort();
    for p in paths {
        if p.is_dir() {
            rapid_files(&p, out);
        } else if p.extension().is_some_and(|e| e.eq_ignore_ascii_case("mod")) {
            out.push(p);
        }
    }
}

/// How the repository runs a file: `test` for RAPID test modules, else `run` with the
/// options of its `! args:` line; every run bounded by a step budget.
fn invocation(path: &Path) -> Vec<String> {
    let text = std::fs::read_to_string(path).unwrap_or_default();
    let name = path.to_string_lossy().into_owned();
    if text.to_ascii_lowercase().contains("proc test_") {
        return vec!["test".into(), "--max-steps".into(), "1000000".into(), name];
    }
    let mut args = vec!["run".to_string()];
    if let Some(extra) = text.lines().find_map(|l| l.strip_prefix("! args:")) {
        args.extend(extra.split_whitespace().map(String::from));
    }
    if !args.iter().any(|a| a == "--max-steps") {
        args.extend(["--max-steps".into(), "1000000".into()]);
    }
    args.push(name);
    args
}

#[test]
fn every_rapid_file_runs_the_same_on_both_engines() {
    let root = root();
    let mut files = Vec::new();
    for dir in ["tests", "programs", "benches"] {
        rapid_files(&root.join(dir), &mut files);
    }
    assert!(files.len() > 60, "only {} RAPID files found", files.len());
    // A program with sockets binds fixed loopback ports: its two runs go one after the
    // other, or each would find the other's server on its ports.
    let mut programs: Vec<(PathBuf, Vec<String>, bool)> = files
        .iter()
        .map(|f| {
            let sockets = std::fs::read_to_string(f)
                .unwrap_or_default()
                .contains("SocketCreate");
            (
                f.parent().unwrap_or(&root).to_path_buf(),
                invocation(f),
                sockets,
            )
        })
        .collect();
    // Multi-module programs: a directory of modules is one program.
    programs.push((
        root.join("tests/run"),
        vec!["run".into(), "multi_module".into()],
        false,
    ));
    let mut differ = Vec::new();
    for (dir, args, sockets) in &programs {
        let (compiled, reference) = if *sockets {
            (
                run_tool(dir, args, "compiled"),
                run_tool(dir, args, "tree-walk"),
            )
        } else {
            std::thread::scope(|s| {
                let c = s.spawn(|| run_tool(dir, args, "compiled"));
                let r = run_tool(dir, args, "tree-walk");
                (c.join().expect("compiled run"), r)
            })
        };
        if compiled != reference {
            differ.push(format!(
                "{}: {args:?}\n--- compiled (exit {})\n{}{}--- tree-walk (exit {})\n{}{}",
                dir.display(),
                compiled.0,
                compiled.1,
                compiled.2,
                reference.0,
                reference.1,
                reference.2
            ));
        }
    }
    assert!(
        differ.is_empty(),
        "{} of {} programs differ:\n{}",
        differ.len(),
        programs.len(),
        differ.join("\n")
    );
}

/// Generated programs: a fixed frame of data and routines, and generated bodies. The
/// generator reads its choices from a byte string (proptest shrinks it toward shorter
/// strings and smaller bytes, and a missing byte picks the simplest alternative), so a
/// failing case shrinks to a small program.
mod generated {
    use std::sync::{Arc, Mutex};

    use proptest::prelude::*;
    use rapidvc::interp::{Engine, Interp, Output, VirtualHost};
    use rapidvc::program;

    /// Where a generated statement is: which data and routines it may use.
    #[derive(Clone, Copy, PartialEq)]
    enum Scope {
        Main,
        /// `PROC p<k>` (k = 0, 1): may call `p0` when k = 1, and `f0`.
        Proc(u8),
        /// `FUNC num f0`: calls no generated routine.
        Func,
    }

    struct Gen<'a> {
        bytes: &'a [u8],
        pos: usize,
        out: String,
        scope: Scope,
        labels: usize,
        /// Nesting of the statement being generated (bounded).
        depth: usize,
    }

    impl Gen<'_> {
        fn pick(&mut self, n: usize) -> usize {
            let b = self.bytes.get(self.pos).copied().unwrap_or(0);
            self.pos += 1;
            b as usize % n
        }

        fn line(&mut self, indent: usize, text: &str) {
            for _ in 0..indent {
                self.out.push_str("  ");
            }
            self.out.push_str(text);
            self.out.push('\n');
        }

        /// An array index: mostly in bounds, sometimes not.
        fn index(&mut self, d: usize) -> String {
            match self.pick(6) {
                0 => "1".into(),
                1 => "2".into(),
                2 => "3".into(),
                3 => self.num(d + 2),
                4 => "gx".into(),
                _ => ["0", "4", "6", "1.5"][self.pick(4)].into(),
            }
        }

        /// A place holding a `num`.
        fn num_place(&mut self, d: usize) -> String {
            let local = match self.scope {
                Scope::Main => ["x", "y", "it.n", "arr{IDX}"][self.pick(4)],
                Scope::Proc(_) | Scope::Func => ["w", "b", "w", "b"][self.pick(4)],
            };
            let p = match self.pick(7) {
                0 => "gx",
                1 => "gp",
                2 => "g{IDX}",
                3 => "gi.n",
                4 => "gis{IDX}.n",
                _ => local,
            };
            if p.contains("IDX") {
                let i = self.index(d);
                p.replace("IDX", &i)
            } else {
                p.to_string()
            }
        }

        fn str_place(&mut self, d: usize) -> String {
            let local = match self.scope {
                Scope::Main => ["t", "it.s"][self.pick(2)],
                Scope::Proc(_) => "s",
                Scope::Func => "gs",
            };
            match self.pick(4) {
                0 => "gs".into(),
                1 => "gi.s".into(),
                2 => format!("gis{{{}}}.s", self.index(d)),
                _ => local.into(),
            }
        }

        fn bool_place(&mut self) -> String {
            let local = match self.scope {
                Scope::Main => ["f", "it.b"][self.pick(2)],
                _ => "gb",
            };
            match self.pick(3) {
                0 => "gb".into(),
                1 => "gi.b".into(),
                _ => local.into(),
            }
        }

        fn record_place(&mut self, d: usize) -> String {
            match (self.pick(3), self.scope) {
                (0, Scope::Main) => "it".into(),
                (1, _) => format!("gis{{{}}}", self.index(d)),
                _ => "gi".into(),
            }
        }

        fn num(&mut self, d: usize) -> String {
            if d > 3 {
                return ["1", "2", "x0", "0.5"][self.pick(4)]
                    .replace("x0", "gx")
                    .to_string();
            }
            match self.pick(16) {
                0 => ["0", "1", "2", "3", "-1", "0.5", "7", "1E30", "100"][self.pick(9)].into(),
                1..=3 => self.num_place(d + 1),
                4..=6 => {
                    let op = ["+", "-", "*", "/", "DIV", "MOD"][self.pick(6)];
                    format!("({} {op} {})", self.num(d + 1), self.num(d + 1))
                }
                7 => format!(
                    "({} MOD {})",
                    self.num(d + 1),
                    ["3", "2", "-4"][self.pick(3)]
                ),
                8 => format!("-{}", self.num(d + 1)),
                9 => format!("sq({})", self.num(d + 1)),
                10 => format!("quot({}, {})", self.num(d + 1), self.num(d + 1)),
                11 => format!("garr({})", self.num(d + 1)),
                12 => format!("StrLen({})", self.string(d + 1)),
                13 if self.scope != Scope::Func => {
                    let a = self.num(d + 1);
                    let b = self.num_place(d + 1);
                    match self.pick(2) {
                        0 => format!("f0({a}, {b})"),
                        _ => format!("f0({a}, {b} \\o:={})", self.num(d + 1)),
                    }
                }
                14 => match self.pick(4) {
                    0 => format!("Abs({})", self.num(d + 1)),
                    1 => {
                        let f = ["Round", "Trunc"][self.pick(2)];
                        format!("{f}({})", self.num(d + 1))
                    }
                    2 => {
                        let f = ["Sqrt", "Sin", "Cos", "Exp", "ACos"][self.pick(5)];
                        format!("{f}({})", self.num(d + 1))
                    }
                    _ => format!("mk({}, {}).n", self.num(d + 1), self.string(d + 1)),
                },
                _ => format!("DnumToNum(gd * {})", self.num(d + 1)),
            }
        }

        fn cond(&mut self, d: usize) -> String {
            if d > 3 {
                return ["TRUE", "FALSE", "gb"][self.pick(3)].into();
            }
            match self.pick(10) {
                0 => ["TRUE", "FALSE"][self.pick(2)].into(),
                1 => self.bool_place(),
                2..=4 => {
                    let op = ["<", "<=", "=", "<>", ">", ">="][self.pick(6)];
                    format!("{} {op} {}", self.num(d + 1), self.num(d + 1))
                }
                5 => {
                    let op = ["AND", "OR", "XOR"][self.pick(3)];
                    format!("({}) {op} ({})", self.cond(d + 1), self.cond(d + 1))
                }
                6 => format!("NOT ({})", self.cond(d + 1)),
                7 => format!("{} = {}", self.string(d + 1), self.string(d + 1)),
                8 => format!(
                    "{} = {}",
                    self.record_place(d + 1),
                    self.record_place(d + 1)
                ),
                _ => match self.scope {
                    Scope::Proc(_) => ["Present(o)", "Present(sw)"][self.pick(2)].into(),
                    Scope::Func => "Present(o)".into(),
                    Scope::Main => "gd > 4".into(),
                },
            }
        }

        fn string(&mut self, d: usize) -> String {
            if d > 3 {
                return ["\"a\"", "gs"][self.pick(2)].into();
            }
            match self.pick(8) {
                0 => [
                    "\"\"",
                    "\"a\"",
                    "\"xyz\"",
                    "\"0123456789012345678901234567890123456789\"",
                ][self.pick(4)]
                .into(),
                1 | 2 => self.str_place(d + 1),
                3 | 4 => format!("{} + {}", self.string(d + 1), self.string(d + 1)),
                5 => format!("NumToStr({}, {})", self.num(d + 1), self.pick(3)),
                6 => format!(
                    "StrPart({}, {}, {})",
                    self.string(d + 1),
                    self.num(d + 1),
                    self.num(d + 1)
                ),
                _ => format!("ValToStr({})", self.num(d + 1)),
            }
        }

        /// The arguments of a call of `p0`/`p1` (value, INOUT, VAR string, PERS, optional,
        /// switch).
        fn proc_args(&mut self, d: usize) -> String {
            let mut a = format!(
                "{}, {}, {}, gp",
                self.num(d),
                self.num_place(d),
                self.str_place(d)
            );
            if self.pick(2) == 1 {
                a.push_str(&format!(" \\o:={}", self.num(d)));
            }
            if self.pick(2) == 1 {
                a.push_str(" \\sw");
            }
            a
        }

        fn block(&mut self, indent: usize, n: usize) {
            let n = 1 + self.pick(n);
            for _ in 0..n {
                self.stmt(indent);
            }
        }

        fn stmt(&mut self, ind: usize) {
            let nested = self.depth < 3;
            let k = self.pick(24);
            match k {
                0..=3 => {
                    let l = self.num_place(0);
                    let r = self.num(0);
                    self.line(ind, &format!("{l} := {r};"));
                }
                4 => {
                    let l = self.str_place(0);
                    let r = self.string(0);
                    self.line(ind, &format!("{l} := {r};"));
                }
                5 => {
                    let l = self.bool_place();
                    let r = self.cond(0);
                    self.line(ind, &format!("{l} := {r};"));
                }
                6 => {
                    let l = self.record_place(0);
                    let r = match self.pick(3) {
                        0 => self.record_place(0),
                        1 => format!("mk({}, {})", self.num(1), self.string(1)),
                        _ => format!("[{}, {}, {}]", self.num(1), self.string(1), self.cond(1)),
                    };
                    self.line(ind, &format!("{l} := {r};"));
                }
                7 => {
                    let r = self.num(0);
                    self.line(ind, &format!("gd := gd * 2 + {r};"));
                }
                8 if nested => {
                    let c = self.cond(0);
                    self.line(ind, &format!("IF {c} THEN"));
                    self.depth += 1;
                    self.block(ind + 1, 3);
                    if self.pick(2) == 1 {
                        let c = self.cond(0);
                        self.line(ind, &format!("ELSEIF {c} THEN"));
                        self.block(ind + 1, 2);
                    }
                    if self.pick(2) == 1 {
                        self.line(ind, "ELSE");
                        self.block(ind + 1, 2);
                    }
                    self.depth -= 1;
                    self.line(ind, "ENDIF");
                }
                9 if nested => {
                    let c = self.cond(0);
                    self.line(ind, &format!("WHILE {c} AND guard < 40 DO"));
                    self.line(ind + 1, "guard := guard + 1;");
                    self.depth += 1;
                    self.block(ind + 1, 3);
                    self.depth -= 1;
                    self.line(ind, "ENDWHILE");
                }
                10 if nested => {
                    let v = format!("i{}", self.depth);
                    let (a, b) = (self.num(2), self.num(2));
                    let step = match self.pick(3) {
                        0 => format!(" STEP {}", self.num(2)),
                        _ => String::new(),
                    };
                    self.line(ind, &format!("FOR {v} FROM {a} TO {b}{step} DO"));
                    self.line(ind + 1, &format!("gx := gx + {v};"));
                    self.depth += 1;
                    self.block(ind + 1, 2);
                    self.depth -= 1;
                    self.line(ind, "ENDFOR");
                }
                11 if nested => {
                    let on_str = self.pick(2) == 1;
                    let subject = if on_str { self.string(1) } else { self.num(1) };
                    self.line(ind, &format!("TEST {subject}"));
                    self.depth += 1;
                    for _ in 0..1 + self.pick(3) {
                        let mut vals = Vec::new();
                        for _ in 0..1 + self.pick(2) {
                            vals.push(if on_str { self.string(2) } else { self.num(2) });
                        }
                        self.line(ind, &format!("CASE {}:", vals.join(", ")));
                        self.block(ind + 1, 2);
                    }
                    if self.pick(2) == 1 {
                        self.line(ind, "DEFAULT:");
                        self.block(ind + 1, 2);
                    }
                    self.depth -= 1;
                    self.line(ind, "ENDTEST");
                }
                12 if nested => {
                    // A backward GOTO, bounded by the guard.
                    self.labels += 1;
                    let l = format!("again{}", self.labels);
                    self.line(ind, &format!("{l}:"));
                    self.depth += 1;
                    self.block(ind, 2);
                    self.depth -= 1;
                    self.line(ind, "IF guard < 30 THEN");
                    self.line(ind + 1, "guard := guard + 1;");
                    self.line(ind + 1, &format!("GOTO {l};"));
                    self.line(ind, "ENDIF");
                }
                13 | 14 => match self.scope {
                    Scope::Main | Scope::Proc(1) => {
                        let callee = if self.scope == Scope::Main && self.pick(2) == 1 {
                            "p1"
                        } else {
                            "p0"
                        };
                        let args = self.proc_args(0);
                        if self.pick(3) == 0 {
                            // Never a recursion: how deep one may go depends on the Rust
                            // stack each engine uses per call.
                            let k = if self.scope == Scope::Main {
                                self.pick(2)
                            } else {
                                0
                            };
                            let name = format!("\"p\" + NumToStr({k}, 0)");
                            self.line(ind, &format!("%{name}% {args};"));
                        } else {
                            self.line(ind, &format!("{callee} {args};"));
                        }
                    }
                    _ => {
                        let l = self.num_place(0);
                        self.line(ind, &format!("Incr {l};"));
                    }
                },
                15 => {
                    let r = self.num(0);
                    self.line(ind, &format!("TPWrite \"n \" \\Num:={r};"));
                }
                16 => {
                    let r = self.string(0);
                    self.line(ind, &format!("TPWrite {r};"));
                }
                17 => {
                    let r = self.num(1);
                    let k = self.pick(4);
                    let n = ["7", "12", "ERR_DIVZERO", &r][k].to_string();
                    self.line(ind, &format!("RAISE {n};"));
                }
                18 => {
                    let l = self.num_place(0);
                    self.line(ind, &format!("Incr {l};"));
                }
                19 if self.scope == Scope::Func => {
                    let r = self.num(0);
                    self.line(ind, &format!("RETURN {r};"));
                }
                19 if matches!(self.scope, Scope::Proc(_)) => self.line(ind, "RETURN;"),
                _ => {
                    let l = self.num_place(0);
                    let r = self.num(0);
                    self.line(ind, &format!("{l} := {r};"));
                }
            }
        }

        /// An ERROR handler: statements, then RETRY (bounded), TRYNEXT, RETURN or RAISE.
        fn handler(&mut self) {
            self.line(1, "ERROR");
            self.line(2, "TPWrite \"err \" \\Num:=ERRNO;");
            if self.pick(3) == 0 {
                self.depth = 3;
                self.block(2, 2);
            }
            match self.pick(6) {
                0 => {
                    self.line(2, "IF retries < 3 THEN");
                    self.line(3, "retries := retries + 1;");
                    self.line(3, "RETRY;");
                    self.line(2, "ENDIF");
                    self.line(2, "TRYNEXT;");
                }
                1 | 4 => self.line(2, "TRYNEXT;"),
                2 if self.scope == Scope::Func => self.line(2, "RETURN -1;"),
                2 => self.line(2, "RETURN;"),
                3 => self.line(2, "RAISE;"),
                _ => {}
            }
        }

        fn routine_body(&mut self, scope: Scope, stmts: usize) {
            self.scope = scope;
            self.depth = 0;
            self.block(2, stmts);
        }
    }

    /// A whole program from the choices in `bytes` (main's body first, so that it gets the
    /// first choices).
    pub fn program(bytes: &[u8]) -> String {
        let mut g = Gen {
            bytes,
            pos: 0,
            out: String::new(),
            scope: Scope::Main,
            labels: 0,
            depth: 0,
        };
        g.line(1, "PROC main()");
        g.out.push_str(MAIN_DATA);
        g.routine_body(Scope::Main, 10);
        g.out.push_str(MAIN_END);
        if g.pick(4) != 0 {
            g.handler();
        }
        g.line(1, "ENDPROC");
        let main = std::mem::take(&mut g.out);
        g.out.push_str(HEAD);
        g.line(1, "FUNC num f0(num a, INOUT num b, \\num o)");
        g.line(2, "VAR num w := 2;");
        g.routine_body(Scope::Func, 3);
        let r = g.num(1);
        g.line(2, &format!("RETURN {r};"));
        if g.pick(2) == 1 {
            g.handler();
        }
        g.line(1, "ENDFUNC");
        for k in 0..2u8 {
            g.line(
                1,
                &format!(
                    "PROC p{k}(num a, INOUT num b, VAR string s, PERS num q, \\num o, \\switch sw)"
                ),
            );
            g.line(2, "VAR num w := 1;");
            g.routine_body(Scope::Proc(k), 4);
            if g.pick(2) == 1 {
                g.handler();
            }
            g.line(1, "ENDPROC");
        }
        g.out.push_str(&main);
        g.out.push_str("ENDMODULE\n");
        g.out
    }

    const HEAD: &str = r#"MODULE agree
  RECORD item
    num n;
    string s;
    bool b;
  ENDRECORD
  VAR num g{5} := [1, 2, 3, 4, 5];
  VAR num gx := 2;
  VAR dnum gd := 3;
  VAR string gs := "ab";
  VAR bool gb := TRUE;
  VAR item gi := [7, "it", FALSE];
  VAR item gis{3};
  PERS num gp := 1;
  VAR num guard := 0;
  VAR num retries := 0;
  FUNC num sq(num x)
    RETURN x * 2 + 1;
  ENDFUNC
  FUNC num quot(num x, num y)
    RETURN x / y;
  ENDFUNC
  FUNC num garr(num i)
    RETURN g{i};
  ENDFUNC
  FUNC item mk(num n, string s)
    VAR item r;
    VAR num k{2};
    r.n := n + k{1};
    r.s := s;
    r.b := n > 2;
    k{2} := n;
    RETURN r;
  ENDFUNC
"#;

    const MAIN_DATA: &str = r#"    VAR num x := 1;
    VAR num y := 2;
    VAR string t := "t";
    VAR bool f := FALSE;
    VAR item it;
    VAR num arr{4};
"#;

    const MAIN_END: &str = r#"    TPWrite "end " \Num:=x;
    TPWrite "end " \Num:=y;
    TPWrite "end " + t;
    TPWrite "end " \Bool:=f;
    TPWrite "end " + ValToStr(it);
    TPWrite "end " \Num:=arr{1} + 2 * arr{2} + 3 * arr{3} + 4 * arr{4};
"#;

    /// What a run leaves: outcome or error, TP output, module data, steps.
    #[derive(Debug, PartialEq)]
    struct Ended {
        result: String,
        tp: Vec<String>,
        data: String,
        steps: u64,
    }

    fn run(dir: &std::path::Path, engine: Engine) -> Result<Ended, String> {
        let loaded = program::load(&[dir.join("agree.mod")], Some(dir));
        let Some(prog) = loaded.program.clone() else {
            let diags: Vec<String> = loaded.diags.iter().map(|d| format!("{d:?}")).collect();
            return Err(diags.join("\n"));
        };
        let tp = Arc::new(Mutex::new(Vec::new()));
        let sink = tp.clone();
        let host = VirtualHost::new().with_sink(move |o| {
            if let (Output::TpWrite(s), Ok(mut t)) = (o, sink.lock()) {
                t.push(s.clone());
            }
        });
        let mut it = Interp::with_engine(prog, &loaded.registry, Box::new(host), engine);
        it.set_budget(Some(20_000));
        let result = match it.init().and_then(|_| it.run("main")) {
            Ok(o) => format!("{o:?}"),
            Err(e) => format!("{e:?}"),
        };
        let data = it
            .module_data()
            .iter()
            .map(|(n, v)| format!("{n} = {v:?}\n"))
            .collect();
        let tp = tp.lock().map(|t| t.clone()).unwrap_or_default();
        Ok(Ended {
            result,
            tp,
            data,
            steps: it.steps(),
        })
    }

    proptest! {
        #![proptest_config(ProptestConfig { cases: 200, ..ProptestConfig::default() })]

        #[test]
        fn generated_programs_run_the_same_on_both_engines(
            bytes in proptest::collection::vec(any::<u8>(), 0..1200)
        ) {
            let text = program(&bytes);
            let dir = std::env::temp_dir().join(format!(
                "rapidvc-agree-{}-{:?}",
                std::process::id(),
                std::thread::current().id()
            ));
            std::fs::create_dir_all(&dir).expect("temp dir");
            std::fs::write(dir.join("agree.mod"), &text).expect("write program");
            let compiled = run(&dir, Engine::Compiled);
            let reference = run(&dir, Engine::TreeWalk);
            let _ = std::fs::remove_dir_all(&dir);
            let compiled = match compiled {
                Ok(c) => c,
                Err(diags) => panic!("the generated program does not check:\n{text}\n{diags}"),
            };
            // `AGREE_DUMP=1 cargo test --test interp_agree -- --nocapture` shows every
            // generated program and how it ended (to see what the generator covers).
            if std::env::var_os("AGREE_DUMP").is_some() {
                eprintln!("=====\n{text}\n{compiled:?}");
            }
            prop_assert_eq!(&compiled, &reference.expect("checked once"), "program:\n{}", text);
        }
    }
}
