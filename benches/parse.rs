//! Throughput of parse + structural check on a generated multi-MB program mixing every
//! construct. Run: `cargo bench --bench parse` (criterion reports MB/s).

use criterion::{Criterion, Throughput, criterion_group, criterion_main};
use rapidvc::diag::Diagnostics;
use rapidvc::parse;
use rapidvc::source::SourceId;

#[path = "../tests/support/gen_program.rs"]
mod gen_program;

fn bench(c: &mut Criterion) {
    let text = gen_program::program(4 << 20);
    let mut g = c.benchmark_group("parse");
    g.throughput(Throughput::Bytes(text.len() as u64));
    g.sample_size(10);
    g.bench_function("parse_and_check_4MB", |b| {
        b.iter(|| {
            let mut diags = Diagnostics::new();
            let file = parse::parse_file(SourceId(0), &text, &mut diags);
            parse::check_structure(&file, &mut diags);
            assert!(diags.is_empty(), "the generated program must be clean");
            file
        })
    });
    g.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
