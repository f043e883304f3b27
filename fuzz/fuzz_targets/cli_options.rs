//! Fuzz the command line: any argument list must parse or be refused by clap without
//! panicking, and an accepted `run` gives durations without overflow. The first byte picks
//! a numeric option, so most inputs exercise a value parser; the rest are argument lists
//! split at NUL bytes.
#![no_main]

use clap::Parser;
use libfuzzer_sys::fuzz_target;
use rapidvc::cli::{Cli, Command};

/// `(subcommand and operands, option)` of every numeric option.
const OPTIONS: &[(&[&str], &str)] = &[
    (&["run", "x.mod"], "--max-time"),
    (&["run", "x.mod"], "--period"),
    (&["run", "x.mod"], "--lockstep-timeout"),
    (&["run", "x.mod"], "--cycles"),
    (&["run", "x.mod"], "--max-steps"),
    (&["run", "x.mod"], "--start"),
    (&["test", "x.mod"], "--max-steps"),
    (&["bench", "virtual"], "--seconds"),
    (&["bench", "realtime"], "--seconds"),
    (&["bench", "realtime"], "--load"),
    (&["bench", "realtime"], "--spin-us"),
    (&["bench", "egm"], "--seconds"),
    (&["sensor"], "--port"),
    (&["sensor"], "--amplitude"),
    (&["sensor"], "--frequency"),
    (&["sensor"], "--radius"),
    (&["sensor"], "--y"),
    (&["sensor"], "--z"),
    (&["sensor"], "--ramp-time"),
    (&["sensor"], "--count"),
    (&["sensor"], "--duration"),
    (&["sensor"], "--print-every"),
];

fuzz_target!(|data: &[u8]| {
    let Some((&pick, rest)) = data.split_first() else {
        return;
    };
    let text = String::from_utf8_lossy(rest);
    let mut args: Vec<String> = vec!["rapidvc".into()];
    match OPTIONS.get(usize::from(pick)) {
        Some((prefix, option)) => {
            args.extend(prefix.iter().map(|s| s.to_string()));
            args.push(format!("{option}={text}"));
        }
        None => args.extend(text.split('\0').map(String::from)),
    }
    if let Ok(cli) = Cli::try_parse_from(&args)
        && let Command::Run(run) = &cli.command
    {
        let t = run.timing();
        assert!(!t.period.is_zero() && !t.max_wait.is_zero() && !t.reply_timeout.is_zero());
    }
});
