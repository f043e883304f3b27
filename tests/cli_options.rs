//! Property tests of what a user types: every numeric command-line option, with any text as
//! its value, is either refused by clap or gives a value inside the option's documented
//! range from which the run's durations follow without overflow; and `--pers` files of
//! random declarations, comments and values are read, rewritten in place and read back.
#![allow(clippy::unwrap_used, clippy::expect_used, clippy::indexing_slicing)]

use clap::Parser;
use proptest::prelude::*;
use rapidvc::cli::bench::BenchKind;
use rapidvc::cli::num::{self, Range};
use rapidvc::cli::{Cli, Command};
use rapidvc::interp::Value;
use rapidvc::interp::pers::{self, PersValue};

/// Texts a user (or a script gone wrong) might pass as a number.
fn number_text() -> impl Strategy<Value = String> {
    prop_oneof![
        any::<f64>().prop_map(|x| format!("{x}")),
        any::<f64>().prop_map(|x| format!("{x:e}")),
        any::<u64>().prop_map(|x| x.to_string()),
        any::<i64>().prop_map(|x| x.to_string()),
        (-1e12f64..1e12).prop_map(|x| format!("{x}")),
        (0.0f64..200.0).prop_map(|x| format!("{x}")),
        prop::sample::select(vec![
            "nan", "NaN", "inf", "-inf", "infinity", "1e400", "-0", "0", "1e9", "1e20", "1e30", "",
            " ", "1_000", "0x10", "5s", "1e-400", "+7",
        ])
        .prop_map(String::from),
        "[-+0-9.eE]{0,14}",
    ]
}

/// Parse `rapidvc ARGS…` where the last argument is `--option=value`.
fn parse(prefix: &[&str], option: &str, value: &str) -> Result<Cli, clap::Error> {
    let mut args: Vec<String> = vec!["rapidvc".into()];
    args.extend(prefix.iter().map(|s| s.to_string()));
    args.push(format!("{option}={value}"));
    Cli::try_parse_from(args)
}

/// The real-valued options: where they are, their range.
fn real_options() -> Vec<(&'static [&'static str], &'static str, Range)> {
    vec![
        (&["run", "x.mod"], "--max-time", num::MAX_TIME),
        (&["run", "x.mod"], "--period", num::PERIOD_MS),
        (
            &["bench", "virtual"],
            "--seconds",
            num::BENCH_VIRTUAL_SECONDS,
        ),
        (&["bench", "realtime"], "--seconds", num::BENCH_WALL_SECONDS),
        (&["bench", "egm"], "--seconds", num::BENCH_WALL_SECONDS),
        (&["sensor"], "--duration", num::SENSOR_DURATION),
        (&["sensor"], "--amplitude", num::SENSOR_OFFSET),
        (&["sensor"], "--y", num::SENSOR_OFFSET),
        (&["sensor"], "--z", num::SENSOR_OFFSET),
        (&["sensor"], "--radius", num::SENSOR_RADIUS),
        (&["sensor"], "--frequency", num::SENSOR_FREQUENCY),
        (&["sensor"], "--ramp-time", num::SENSOR_RAMP_TIME),
    ]
}

/// The integer options: where they are, and the accepted range.
fn integer_options() -> Vec<(&'static [&'static str], &'static str, u64, u64)> {
    vec![
        (&["run", "x.mod"], "--max-steps", 1, u64::MAX),
        (&["run", "x.mod"], "--cycles", 1, u64::from(u32::MAX)),
        (&["run", "x.mod"], "--lockstep-timeout", 1, 600_000),
        (&["test", "x.mod"], "--max-steps", 1, u64::MAX),
        (&["bench", "realtime"], "--load", 0, 256),
        (&["bench", "realtime"], "--spin-us", 0, 4_000),
        (&["sensor"], "--count", 1, u64::MAX),
        (&["sensor"], "--port", 0, 65_535),
    ]
}

/// The value an accepted real option got.
fn real_value(cli: &Cli, option: &str) -> f64 {
    match &cli.command {
        Command::Run(a) => {
            // The durations of the run follow without panicking.
            let t = a.timing();
            assert!(t.period > std::time::Duration::ZERO);
            assert!(t.max_wait > std::time::Duration::ZERO);
            match option {
                "--max-time" => a.max_time,
                _ => a.period,
            }
        }
        Command::Sensor(s) => match option {
            "--duration" => s.duration.unwrap(),
            "--amplitude" => s.amplitude.unwrap(),
            "--y" => s.y.unwrap(),
            "--z" => s.z.unwrap(),
            "--radius" => s.radius.unwrap(),
            "--frequency" => s.frequency.unwrap(),
            _ => s.ramp_time.unwrap(),
        },
        Command::Bench(b) => match b.what {
            BenchKind::Virtual { seconds, .. }
            | BenchKind::Realtime { seconds, .. }
            | BenchKind::Egm { seconds, .. }
            | BenchKind::LoadWorker { seconds } => seconds,
        },
        other => panic!("unexpected command {other:?}"),
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(512))]

    /// A real-valued option is accepted exactly when its text is a number inside the range,
    /// and then holds that number.
    #[test]
    fn real_options_accept_exactly_their_range(value in number_text(), which in 0usize..12) {
        let (prefix, option, range) = real_options()[which];
        let wanted = value.trim().parse::<f64>().ok().filter(|x| range.contains(*x));
        match (parse(prefix, option, &value), wanted) {
            (Ok(cli), Some(x)) => prop_assert_eq!(real_value(&cli, option), x),
            (Err(e), None) => {
                let text = e.to_string();
                prop_assert!(text.contains(option) && text.contains("invalid value"), "{}", text);
            }
            (Ok(cli), None) => prop_assert!(false, "{option}={value} accepted: {cli:?}"),
            (Err(e), Some(_)) => prop_assert!(false, "{option}={value} refused: {e}"),
        }
    }

    /// An integer option never accepts a value outside its range, and accepts every value
    /// inside it.
    #[test]
    fn integer_options_stay_in_their_range(value in number_text(), n in any::<u64>(), which in 0usize..8) {
        let (prefix, option, lo, hi) = integer_options()[which];
        if let Ok(cli) = parse(prefix, option, &value) {
            let x: i128 = value.trim().parse().unwrap();
            prop_assert!((i128::from(lo)..=i128::from(hi)).contains(&x), "{option}={value} accepted: {cli:?}");
        }
        let inside = lo + n % (hi - lo).saturating_add(1).max(1);
        prop_assert!(parse(prefix, option, &inside.to_string()).is_ok(), "{option}={inside}");
    }
}

/// Texts a user might pass as `--date`: well-formed dates (valid or not), near misses and
/// garbage.
fn date_text() -> impl Strategy<Value = String> {
    prop_oneof![
        (
            0u32..12000,
            0u32..15,
            0u32..34,
            0u32..26,
            0u32..62,
            0u32..62
        )
            .prop_map(|(y, mo, d, h, mi, s)| format!(
                "{y:04}-{mo:02}-{d:02} {h:02}:{mi:02}:{s:02}"
            )),
        (1960u32..9100, 1u32..13, 1u32..32).prop_map(|(y, mo, d)| format!("{y}-{mo}-{d}T00:00:00")),
        prop::sample::select(vec![
            "now",
            "NOW",
            "",
            " ",
            "today",
            "2025-01-01",
            "2025-01-01 00:00",
            "2025-01-01 00:00:00.5",
            "+2025-01-01 00:00:00",
            "2025-01-01  00:00:00",
            "1e9",
            "2025/01/01 00:00:00",
        ])
        .prop_map(String::from),
        "[-0-9: Tn]{0,22}",
    ]
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(512))]

    /// `run --date` is accepted exactly when it is `now` or a real date and time of the years
    /// 1970 to 9000 written `YYYY-MM-DD HH:MM:SS` (or with a `T`), and the run then starts its
    /// calendar there.
    #[test]
    fn date_option_accepts_exactly_real_dates(value in date_text()) {
        let t = value.trim();
        let now = t.eq_ignore_ascii_case("now");
        let parsed = chrono::NaiveDateTime::parse_from_str(&t.replacen('T', " ", 1), "%Y-%m-%d %H:%M:%S")
            .ok()
            .filter(|d| {
                t.len() == 19
                    && (1970..=9000).contains(&chrono::Datelike::year(d))
                    && chrono::Timelike::nanosecond(d) < 1_000_000_000
            });
        match (parse(&["run", "x.mod"], "--date", &value), parsed) {
            (Ok(cli), Some(d)) => {
                let Command::Run(a) = &cli.command else { panic!("run") };
                prop_assert_eq!(a.date.unwrap().start(), d);
            }
            (Ok(_), None) => prop_assert!(now, "--date={value} accepted"),
            (Err(e), None) => {
                let text = e.to_string();
                prop_assert!(!now, "--date=now refused: {}", text);
                prop_assert!(text.contains("--date") && text.contains("invalid value"), "{}", text);
            }
            (Err(e), Some(_)) => prop_assert!(false, "--date={value} refused: {e}"),
        }
    }
}

// ---------------------------------------------------------------------------------------
// `--pers` files.

/// A `num` value as rapidvc stores them (finite single precision).
fn num_value() -> impl Strategy<Value = f32> {
    prop_oneof![
        any::<f32>().prop_filter("finite", |x| x.is_finite()),
        (-1000i32..1000).prop_map(|x| x as f32),
    ]
}

/// A string value of up to 80 characters, with quotes, backslashes and control characters.
fn string_value() -> impl Strategy<Value = String> {
    prop::collection::vec(
        prop_oneof![
            Just('"'),
            Just('\\'),
            Just('!'),
            Just(';'),
            Just('\u{7}'),
            Just('\u{e9}'),
            prop::char::range(' ', '~'),
        ],
        0..80,
    )
    .prop_map(|v| v.into_iter().collect())
}

/// A persistent: a scalar num, a string, a bool, or a num array of one or two dimensions.
fn value() -> impl Strategy<Value = (String, Vec<u32>, Value)> {
    prop_oneof![
        num_value().prop_map(|x| ("num".to_string(), vec![], Value::Num(x))),
        string_value().prop_map(|s| ("string".to_string(), vec![], Value::str(&s))),
        any::<bool>().prop_map(|b| ("bool".to_string(), vec![], Value::Bool(b))),
        (
            1u32..4,
            1u32..4,
            prop::collection::vec(num_value(), 9),
            any::<bool>()
        )
            .prop_map(|(a, b, xs, two)| {
                let (dims, rank, n) = if two {
                    (vec![a, b], 2, a * b)
                } else {
                    (vec![a], 1, a)
                };
                let data = xs
                    .iter()
                    .cycle()
                    .take(n as usize)
                    .map(|&x| Value::Num(x))
                    .collect();
                let array = rapidvc::interp::value::Array {
                    dims: [a, if two { b } else { 1 }, 1],
                    rank,
                    data,
                };
                ("num".to_string(), dims, Value::Array(Box::new(array)))
            }),
    ]
}

/// Lines that are not declarations: comments and blank lines.
fn filler() -> impl Strategy<Value = String> {
    prop_oneof![
        Just(String::new()),
        "[ ]{0,4}![ -~]{0,40}",
        Just("   ".to_string()),
    ]
}

fn pers_value(i: usize, (ty, dims, value): (String, Vec<u32>, Value), task: bool) -> PersValue {
    PersValue {
        name: format!("p{i}"),
        ty,
        dims,
        task,
        value,
    }
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(256))]

    /// Any text: the reader answers (an error or entries) and never panics; a file it reads
    /// is rewritten byte for byte when the program declares nothing.
    #[test]
    fn any_text_is_read_or_refused(text in "(([ -~]{0,30}|PERS num a{1,2} := \\[\\[1,2\\]\\];|! x)\n?){0,6}") {
        if let Ok(entries) = pers::parse(&text) {
            prop_assert_eq!(pers::write(Some(&text), &[]), text.clone());
            for e in entries {
                prop_assert!(text.contains(&e.raw));
            }
        }
    }

    /// A file written from random persistents, mixed with comments, reads back to the same
    /// values; rewriting it with new values keeps every comment and line in place.
    #[test]
    fn pers_files_round_trip(
        old in prop::collection::vec((value(), any::<bool>()), 1..6),
        new in prop::collection::vec(value(), 1..6),
        comments in prop::collection::vec(filler(), 6),
    ) {
        let stored: Vec<PersValue> = old
            .into_iter()
            .enumerate()
            .map(|(i, (v, task))| pers_value(i, v, task))
            .collect();
        // Comments between the declarations.
        let fresh = pers::write(None, &stored);
        let mut text = String::new();
        let mut inserted = Vec::new();
        for (line, c) in fresh.lines().zip(comments.iter().cycle()) {
            inserted.push(c.clone());
            text.push_str(c);
            text.push('\n');
            text.push_str(line);
            text.push('\n');
        }
        let entries = pers::parse(&text).unwrap();
        prop_assert_eq!(entries.len(), stored.len());
        for (e, v) in entries.iter().zip(&stored) {
            prop_assert_eq!(&e.name, &v.name);
            prop_assert_eq!(&e.dims, &v.dims);
            let mut back = v.value.clone();
            prop_assert!(pers::fill(&mut back, &e.value), "{}", e.raw);
            prop_assert_eq!(pers::to_text(&back), pers::to_text(&v.value));
        }
        // The program now declares `new` (some names already stored, some not).
        let declared: Vec<PersValue> = new
            .into_iter()
            .enumerate()
            .map(|(i, v)| pers_value(i * 2, v, false))
            .collect();
        let rewritten = pers::write(Some(&text), &declared);
        for c in inserted.iter().filter(|c| !c.trim().is_empty()) {
            prop_assert!(rewritten.contains(c.as_str()), "comment {c:?} lost");
        }
        let again = pers::parse(&rewritten).unwrap();
        for v in &declared {
            let e = again.iter().find(|e| e.name == v.name).unwrap();
            let mut back = v.value.clone();
            prop_assert!(pers::fill(&mut back, &e.value));
            prop_assert_eq!(pers::to_text(&back), pers::to_text(&v.value));
        }
        // Stored entries the program does not declare are kept as they were.
        for e in &entries {
            if !declared.iter().any(|v| v.name == e.name) {
                prop_assert!(again.iter().any(|a| a.raw == e.raw), "{} lost", e.raw);
            }
        }
    }
}
