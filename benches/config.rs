//! Loading an `EIO.cfg` of 20,000 and of 200,000 signals (read, parse, check, merge with the
//! built-in signals, build the signal table): `cargo bench --bench config`. The two figures
//! come from one run, so their ratio shows whether loading stays linear (about 10×) on a busy
//! machine where single wall times do not.

use std::path::{Path, PathBuf};

use criterion::{Criterion, criterion_group, criterion_main};
use rapidvc::config;
use rapidvc::diag::Diagnostics;
use rapidvc::source::SourceMap;

/// A directory with an EIO.cfg of `n` signals of every type.
fn eio_dir(n: usize) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("rapidvc-bench-eio-{n}-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("scratch directory");
    let mut text = String::from("EIO:CFG_1.0:6:1::\n#\nEIO_SIGNAL:\n\n");
    for i in 0..n {
        let line = match i % 6 {
            0 => format!("  -Name \"sig_{i}\" -SignalType \"DI\" -Device \"d652\"\n\n"),
            1 => format!("  -Name \"sig_{i}\" -SignalType \"DO\" -Device \"d652\"\n\n"),
            2 => format!("  -Name \"sig_{i}\" -SignalType \"AI\" -MinLog -100 -MaxLog 100\n\n"),
            3 => format!("  -Name \"sig_{i}\" -SignalType \"AO\" -MinLog -100 -MaxLog 100\n\n"),
            4 => format!("  -Name \"sig_{i}\" -SignalType \"GI\" -DeviceMap \"0-7\"\n\n"),
            _ => format!("  -Name \"sig_{i}\" -SignalType \"GO\" -DeviceMap \"0-7\"\n\n"),
        };
        text.push_str(&line);
    }
    std::fs::write(dir.join("EIO.cfg"), text).expect("write EIO.cfg");
    dir
}

fn load(dir: &Path) -> usize {
    let mut map = SourceMap::new();
    let mut diags = Diagnostics::new();
    let cfg = config::load_dir(dir, &mut map, &mut diags);
    assert!(diags.is_empty());
    cfg.signal_table().expect("signal table").len()
}

fn eio_load(c: &mut Criterion) {
    let mut g = c.benchmark_group("eio_load");
    g.sample_size(10);
    for n in [20_000, 200_000] {
        let dir = eio_dir(n);
        g.bench_function(format!("{n}_signals"), |b| b.iter(|| load(&dir)));
        let _ = std::fs::remove_dir_all(&dir);
    }
    g.finish();
}

criterion_group!(benches, eio_load);
criterion_main!(benches);
