//! `rapidvc test PATH…`: run every `PROC test_*` of the given RAPID files. Each file is a
//! program of its own (with the stdlib); each test starts from freshly initialised data, on
//! a virtual controller. A test passes when its procedure returns (or ends with EXIT); it
//! fails on an unhandled error, a failed `Assert`, or `Stop`. One line per test, the
//! failures' details, then `N passed, N failed`. Exit code 1 when a test failed, 2 when a
//! file cannot be loaded or checked.

use std::path::PathBuf;
use std::process::ExitCode;
use std::sync::{Arc, Mutex};

use super::render;
use crate::interp::{Interp, Outcome, Output, VirtualHost};
use crate::ir::RoutineKind;
use crate::mass_storage::MassStorage;
use crate::program::{self, rapid_files};
use crate::signals::SignalTable;

/// Arguments of `rapidvc test`.
#[derive(Debug, clap::Args)]
pub struct TestArgs {
    /// RAPID files or directories holding test modules.
    #[arg(required = true)]
    pub paths: Vec<PathBuf>,
    /// Only run tests whose name contains this text (case-insensitive).
    #[arg(long)]
    pub filter: Option<String>,
    /// Abort a test after this many executed statements (at least 1).
    #[arg(long, value_name = "N", default_value_t = 50_000_000,
          value_parser = clap::value_parser!(u64).range(1..))]
    pub max_steps: u64,
    /// The controller's HOME: directory (an existing directory; RAPID's file instructions
    /// cannot leave it). Default: a fresh directory under the system's temporary directory,
    /// shared by the tests of one invocation, made when a test first uses
    /// the file system and printed at the end.
    #[arg(long, value_name = "DIR", value_parser = super::files::home_dir)]
    pub home: Option<PathBuf>,
    /// Answers to the operator dialogs: each test takes the `[test_name]` section of the
    /// file, or the answers before the first section.
    #[arg(long, value_name = "FILE")]
    pub answers: Option<PathBuf>,
}

/// Run the tests.
pub fn run(args: TestArgs) -> ExitCode {
    let files = match rapid_files::find_rapid_files(&args.paths) {
        Ok(f) => f,
        Err(e) => {
            eprintln!("error: {e}");
            return ExitCode::from(2);
        }
    };
    let answers = match super::answers::read(args.answers.as_deref()) {
        Ok(a) => a,
        Err(e) => {
            eprintln!("error: {e}");
            return ExitCode::from(2);
        }
    };
    let (mut passed, mut failed) = (0usize, 0usize);
    let mut broken = false;
    let storage = Arc::new(MassStorage::new(args.home.clone()));
    for file in &files {
        let loaded = program::load(std::slice::from_ref(file), None);
        let Some(prog) = loaded.program.clone() else {
            render::diagnostics(&loaded.diags, &loaded.sources);
            println!("test {} ... could not be loaded", file.display());
            broken = true;
            continue;
        };
        let mut tests: Vec<(String, crate::ir::RoutineId)> = prog
            .routines
            .iter()
            .enumerate()
            .filter(|(_, r)| {
                r.kind == RoutineKind::Proc
                    && r.name.to_ascii_lowercase().starts_with("test_")
                    && r.params.iter().all(|p| p.optional)
                    && !prog.modules[r.module.0 as usize].stdlib
            })
            .map(|(i, r)| (r.name.clone(), crate::ir::RoutineId(i as u32)))
            .collect();
        tests.sort_by_key(|(_, rid)| prog.routine(*rid).span.start);
        // The configuration database of the file's configuration directory, afresh for
        // every test.
        let system = crate::system::Services {
            cfg: crate::system::cfg_data::CfgData::from_files(
                &loaded.config.files,
                &loaded.sources,
            ),
            ..Default::default()
        };
        for (name, _) in tests {
            if let Some(f) = &args.filter
                && !name.to_ascii_lowercase().contains(&f.to_ascii_lowercase())
            {
                continue;
            }
            let tp = Arc::new(Mutex::new(Vec::<String>::new()));
            let sink_tp = tp.clone();
            let signals = SignalTable::new(loaded.signals.iter().map(|(_, d)| d.clone()).collect())
                .unwrap_or_else(|_| SignalTable::with_builtins());
            let host = VirtualHost::new()
                .with_signals(Arc::new(signals))
                .with_system(system.clone())
                .with_max_time(86_400.0)
                .with_sink(move |o| {
                    if let (Output::TpWrite(s), Ok(mut v)) = (o, sink_tp.lock()) {
                        v.push(s.clone());
                    }
                });
            let mut it = Interp::new(prog.clone(), &loaded.registry, Box::new(host));
            it.set_mass_storage(Arc::clone(&storage));
            it.set_budget(Some(args.max_steps));
            it.set_stack_budget(6 << 20);
            it.set_operator(super::answers::operator(answers.as_ref(), Some(&name)));
            it.set_module_loader(Box::new(
                crate::program::runtime_loader::RuntimeLoader::new(
                    &prog,
                    &loaded.sources,
                    &loaded.signals,
                ),
            ));
            let res = it.init().and_then(|_| it.run(&name));
            // Errors in modules loaded by the test point into the loader's sources.
            let sources = it.loaded_sources().unwrap_or(&loaded.sources);
            let label = format!("test {} :: {name}", file.display());
            match res {
                Ok(Outcome::Completed | Outcome::Exited | Outcome::ExitCycle) => {
                    println!("{label} ... ok");
                    passed += 1;
                }
                Ok(Outcome::Stopped) => {
                    println!("{label} ... FAILED (stopped by Stop)");
                    failed += 1;
                }
                Err(e) => {
                    println!("{label} ... FAILED");
                    println!("    {}: {}", sources.location(e.span), failure_text(&e));
                    if let Ok(lines) = tp.lock() {
                        for l in lines.iter() {
                            println!("    | {l}");
                        }
                    }
                    failed += 1;
                }
            }
        }
    }
    if let Some(roots) = storage.made_roots() {
        let shown: Vec<String> = roots
            .iter()
            .map(|(n, d)| format!("{n}: is {}", d.display()))
            .collect();
        eprintln!("note: mass storage: {}", shown.join(", "));
    }
    println!("{passed} passed, {failed} failed");
    if broken {
        ExitCode::from(2)
    } else if failed > 0 {
        ExitCode::from(1)
    } else {
        ExitCode::SUCCESS
    }
}

fn failure_text(e: &crate::interp::RuntimeError) -> String {
    match e.kind {
        crate::interp::ErrorKind::Assertion => format!("assertion failed: {}", e.message),
        crate::interp::ErrorKind::Rapid(_) if !e.message.is_empty() => {
            format!("{e}: {}", e.message)
        }
        _ => e.to_string(),
    }
}
