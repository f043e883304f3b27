//! Throughput of parse + structural check on a generated multi-MB program mixing every
//! construct. Run: `cargo bench --bench parse` (criterion reports MB/s).
//!
//! Three figures: `parse_and_check_4MB` as `rapidvc check` parses (the module body cut at
//! routine starts and parsed on every core, see `parse::ParseOptions`), and
//! `parse_and_check_4MB_one_thread` on the calling thread only, and
//! `parse_and_check_4MB_one_thread_unpacked` without packing literal aggregates (as trees, as
//! before they were packed: the ratio of the two is the cost or gain of packing). All with the
//! binary's allocator (mimalloc), and all include freeing the tree.

#[global_allocator]
static ALLOCATOR: mimalloc::MiMalloc = mimalloc::MiMalloc;

use criterion::{Criterion, Throughput, criterion_group, criterion_main};
use rapidvc::diag::Diagnostics;
use rapidvc::parse::{self, ParseOptions};
use rapidvc::source::SourceId;

use rapidvc_testkit::fixed_iters::Runner;
use rapidvc_testkit::gen_program;

fn bench(c: &mut Criterion) {
    let text = gen_program::program(4 << 20);
    let mut g = c.benchmark_group("parse");
    g.throughput(Throughput::Bytes(text.len() as u64));
    g.sample_size(10);
    for (name, options) in [
        ("parse_and_check_4MB", ParseOptions::default()),
        (
            "parse_and_check_4MB_one_thread",
            ParseOptions::single_thread(),
        ),
        (
            "parse_and_check_4MB_one_thread_calls_unpacked",
            ParseOptions {
                pack_simple_calls: false,
                ..ParseOptions::single_thread()
            },
        ),
        (
            "parse_and_check_4MB_one_thread_unpacked",
            ParseOptions {
                pack_literal_aggregates: false,
                pack_simple_calls: false,
                ..ParseOptions::single_thread()
            },
        ),
    ] {
        Runner::new(&mut g).iter(name, || {
            let mut diags = Diagnostics::new();
            let file = parse::parse_file_with(SourceId(0), &text, &mut diags, &options);
            parse::check_structure_with(&file, &mut diags, &options);
            assert!(diags.is_empty(), "the generated program must be clean");
            file
        });
    }
    g.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
