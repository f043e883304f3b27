//! The one way the front end spreads work over the machine's cores: a list of jobs taken in
//! turn by scoped threads, the calling thread among them. Used for the pieces of a large
//! module, the pre-pass runs, the structural check of a large module's items and the files
//! of `rapidvc check`.

use std::panic::AssertUnwindSafe;
use std::sync::Mutex;
use std::sync::atomic::{AtomicUsize, Ordering};

/// Stack of a job thread: like the main thread's, so the nesting bound of
/// [`crate::parse::MAX_NESTING`] holds there too (only the pages used are committed).
const STACK: usize = 8 << 20;

/// Run `work` on every job on up to `threads` threads and return what `here` returned and each
/// job's result, in job order. The calling thread runs `here` first (meanwhile the other
/// threads start on the jobs), then takes jobs too. A thread that cannot be started leaves its
/// share to the others; a job whose run panicked has no result (`None`), on whichever thread
/// it ran.
pub(crate) fn run<T: Send, R: Send, H>(
    threads: usize,
    jobs: Vec<T>,
    work: impl Fn(T) -> R + Sync,
    here: impl FnOnce() -> H,
) -> (H, Vec<Option<R>>) {
    let n = jobs.len();
    let jobs: Vec<Mutex<Option<T>>> = jobs.into_iter().map(|j| Mutex::new(Some(j))).collect();
    let results: Vec<Mutex<Option<R>>> = (0..n).map(|_| Mutex::new(None)).collect();
    let next = AtomicUsize::new(0);
    let worker = || {
        loop {
            let i = next.fetch_add(1, Ordering::Relaxed);
            let Some(slot) = jobs.get(i) else { break };
            let Some(job) = slot.lock().ok().and_then(|mut j| j.take()) else {
                continue;
            };
            // (A panic is a bug; it costs this job its result, not the run.)
            let Ok(r) = std::panic::catch_unwind(AssertUnwindSafe(|| work(job))) else {
                continue;
            };
            if let Some(Ok(mut out)) = results.get(i).map(Mutex::lock) {
                *out = Some(r);
            }
        }
    };
    let h = std::thread::scope(|scope| {
        let helpers: Vec<_> = (1..threads.min(n))
            .filter_map(|_| {
                std::thread::Builder::new()
                    .name("rapidvc-parse".into())
                    .stack_size(STACK)
                    .spawn_scoped(scope, worker)
                    .ok()
            })
            .collect();
        let h = here();
        worker();
        for t in helpers {
            let _ = t.join();
        }
        h
    });
    let results = results
        .into_iter()
        .map(|m| m.into_inner().ok().flatten())
        .collect();
    (h, results)
}

#[cfg(test)]
mod tests {
    use super::run;

    #[test]
    fn results_in_job_order_whatever_the_threads() {
        for threads in [1, 2, 5] {
            let (h, out) = run(threads, (0..40).collect(), |k: u64| k * k, || "here");
            assert_eq!(h, "here");
            let want: Vec<Option<u64>> = (0..40).map(|k| Some(k * k)).collect();
            assert_eq!(out, want);
        }
        let (_, none) = run(3, Vec::<u8>::new(), |k| k, || ());
        assert!(none.is_empty());
    }
}
