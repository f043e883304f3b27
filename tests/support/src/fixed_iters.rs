//! The benchmarks' fixed-iteration mode, for counting instructions with callgrind
//! (`benches/callgrind.sh`, figures in `docs/performance.md`).
//!
//! Criterion picks its iteration counts from wall time, so they change from run to run. With
//! `RAPIDVC_BENCH_ITERS=N` set, a bench built on [`Runner`] (or on [`Fixed`]) runs instead
//! exactly one function, named by `RAPIDVC_BENCH_ONLY`: its setup, one warm-up call, then
//! exactly `N` calls between two calls of a boundary function. Callgrind started with
//! `--dump-before='*fixed_iters::boundary*'` writes its counters at each boundary, so the
//! second of the three dumps holds the `N` calls alone (every thread). With
//! `RAPIDVC_BENCH_ITERS` set and no `RAPIDVC_BENCH_ONLY`, the bench prints the names it
//! knows (`bench: NAME`, one a line) and runs none.

use std::hint::black_box;
use std::sync::atomic::{AtomicBool, AtomicU64, Ordering};
use std::time::Duration;

use criterion::measurement::WallTime;
use criterion::{BatchSize, Bencher, BenchmarkGroup, Criterion};

/// Whether [`mark`] is a boundary now (only inside a measured stretch of the fixed mode).
static ARMED: AtomicBool = AtomicBool::new(false);
/// Boundaries passed (printed at the end of a measured stretch, to check the dumps).
static BOUNDARIES: AtomicU64 = AtomicU64::new(0);

/// Where callgrind dumps its counters: never inlined, never folded with another function
/// (it counts).
#[inline(never)]
fn boundary() {
    black_box(BOUNDARIES.fetch_add(1, Ordering::Relaxed));
}

/// The start or the end of the measured part of a function that times itself
/// ([`Runner::iter_custom`], [`Fixed::run`]): a boundary in the fixed mode's measured call,
/// a load of a flag otherwise.
pub fn mark() {
    if ARMED.load(Ordering::Relaxed) {
        boundary();
    }
}

/// The fixed-iteration mode: how many iterations, and of which function.
pub struct Fixed {
    iters: u64,
    only: Option<String>,
}

impl Fixed {
    /// The mode asked for by `RAPIDVC_BENCH_ITERS` (a positive count) and
    /// `RAPIDVC_BENCH_ONLY`, or `None` (criterion's own mode).
    pub fn from_env() -> Option<Fixed> {
        let iters = std::env::var("RAPIDVC_BENCH_ITERS").ok()?;
        let Some(iters) = iters.trim().parse::<u64>().ok().filter(|&n| n > 0) else {
            panic!("RAPIDVC_BENCH_ITERS must be a positive count, not `{iters}`");
        };
        let only = std::env::var("RAPIDVC_BENCH_ONLY").ok();
        Some(Fixed { iters, only })
    }

    /// Whether `name` is the function to run (with no selection: list it, run none).
    pub fn wants(&self, name: &str) -> bool {
        match &self.only {
            Some(only) => only == name,
            None => {
                println!("bench: {name}");
                false
            }
        }
    }

    /// `f(N)` with its own [`mark`]s at the start and end of what it measures, after a
    /// warm-up `f(1)` whose marks are no boundaries.
    pub fn run(&self, name: &str, mut f: impl FnMut(u64)) {
        if !self.wants(name) {
            return;
        }
        f(1);
        ARMED.store(true, Ordering::Relaxed);
        f(self.iters);
        ARMED.store(false, Ordering::Relaxed);
        self.report(name);
    }

    /// `routine` once (warm-up), then `N` times between two boundaries.
    pub fn iter<O>(&self, name: &str, mut routine: impl FnMut() -> O) {
        self.run(name, |n| {
            mark();
            for _ in 0..n {
                black_box(routine());
            }
            mark();
        });
    }

    /// As criterion's `iter_batched`: the inputs are made before the first boundary and the
    /// outputs dropped after the second.
    pub fn iter_batched<I, O>(
        &self,
        name: &str,
        mut setup: impl FnMut() -> I,
        mut routine: impl FnMut(I) -> O,
    ) {
        self.run(name, |n| {
            let inputs: Vec<I> = (0..n).map(|_| setup()).collect();
            let mut outputs = Vec::with_capacity(inputs.len());
            mark();
            for input in inputs {
                outputs.push(black_box(routine(input)));
            }
            mark();
            drop(outputs);
        });
    }

    fn report(&self, name: &str) {
        println!(
            "fixed: {name}: {} iterations, {} boundaries",
            self.iters,
            BOUNDARIES.load(Ordering::Relaxed)
        );
    }
}

/// Where a [`Runner`] registers criterion functions: the `Criterion` itself or a group.
pub trait Target {
    /// `bench_function(name, f)` of criterion.
    fn function(&mut self, name: &str, f: impl FnMut(&mut Bencher<'_, WallTime>));
}

impl Target for Criterion {
    fn function(&mut self, name: &str, f: impl FnMut(&mut Bencher<'_, WallTime>)) {
        self.bench_function(name, f);
    }
}

impl Target for BenchmarkGroup<'_, WallTime> {
    fn function(&mut self, name: &str, f: impl FnMut(&mut Bencher<'_, WallTime>)) {
        self.bench_function(name, f);
    }
}

/// Criterion's bench functions, or the same routines in the fixed mode when it is asked for.
pub struct Runner<'a, T> {
    target: &'a mut T,
    fixed: Option<Fixed>,
}

impl<'a, T: Target> Runner<'a, T> {
    /// Functions registered on `target`, or run in the fixed mode (see [`Fixed::from_env`]).
    pub fn new(target: &'a mut T) -> Self {
        Runner {
            target,
            fixed: Fixed::from_env(),
        }
    }

    /// The fixed mode, if it was asked for.
    pub fn fixed(&self) -> Option<&Fixed> {
        self.fixed.as_ref()
    }

    /// Criterion's `bench_function(name, |b| b.iter(routine))`.
    pub fn iter<O>(&mut self, name: &str, mut routine: impl FnMut() -> O) {
        match &self.fixed {
            Some(fixed) => fixed.iter(name, routine),
            None => self.target.function(name, |b| b.iter(&mut routine)),
        }
    }

    /// Criterion's `bench_function(name, |b| b.iter_batched(setup, routine, size))`.
    pub fn iter_batched<I, O>(
        &mut self,
        name: &str,
        mut setup: impl FnMut() -> I,
        mut routine: impl FnMut(I) -> O,
        size: BatchSize,
    ) {
        match &self.fixed {
            Some(fixed) => fixed.iter_batched(name, setup, routine),
            None => self
                .target
                .function(name, |b| b.iter_batched(&mut setup, &mut routine, size)),
        }
    }

    /// Criterion's `bench_function(name, |b| b.iter_custom(f))`; `f` calls [`mark`] where
    /// its timing starts and ends.
    pub fn iter_custom(&mut self, name: &str, mut f: impl FnMut(u64) -> Duration) {
        match &self.fixed {
            Some(fixed) => fixed.run(name, |n| {
                f(n);
            }),
            None => self.target.function(name, |b| b.iter_custom(&mut f)),
        }
    }
}
