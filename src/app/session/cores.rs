//! The window's tracing pool, which the session owns: one worker per core the
//! app may run on, each kept on a core of its own (Linux). Left to the
//! scheduler, two workers of a 2-core machine at times share one core while
//! the other idles until the next tick (4 ms) moves one of them; presenting's
//! short bursts on the main thread and the display server keep waking threads
//! onto busy cores. A pool of fewer workers than cores, or of more, is not
//! pinned: the scheduler places it.

/// A rayon pool of `threads` workers (0: one per core the app may use), each
/// kept on its own core when there is one per core.
///
/// # Errors
/// When the operating system refuses the threads.
pub fn pool(threads: usize) -> Result<rayon::ThreadPool, rayon::ThreadPoolBuildError> {
    let cores = allowed_cores();
    let n = match threads {
        0 => std::thread::available_parallelism().map_or(1, usize::from),
        n => n,
    };
    let pinned = pinned_cores(n, cores);
    rayon::ThreadPoolBuilder::new()
        .num_threads(n)
        .start_handler(move |i| {
            if let Some(&core) = pinned.get(i)
                && let Err(e) = pin(core)
            {
                tracing::debug!("tracing thread {i} not kept on core {core}: {e}");
            }
        })
        .build()
}

/// The core each of `n` workers is kept on: the `cores` the app may use, in
/// order, when there are exactly `n`; none otherwise.
fn pinned_cores(n: usize, cores: Vec<usize>) -> Vec<usize> {
    if cores.len() == n && n > 1 {
        cores
    } else {
        Vec::new()
    }
}

/// The cores the calling thread may run on (called before the pool starts:
/// the app's); none where that is unknown.
#[cfg(target_os = "linux")]
fn allowed_cores() -> Vec<usize> {
    use rustix::thread::{CpuSet, sched_getaffinity};
    sched_getaffinity(None)
        .map(|set| (0..CpuSet::MAX_CPU).filter(|&c| set.is_set(c)).collect())
        .unwrap_or_default()
}

/// Keeps the calling thread on `core`.
#[cfg(target_os = "linux")]
fn pin(core: usize) -> std::io::Result<()> {
    use rustix::thread::{CpuSet, sched_setaffinity};
    let mut set = CpuSet::new();
    set.set(core);
    sched_setaffinity(None, &set).map_err(std::io::Error::from)
}

#[cfg(not(target_os = "linux"))]
fn allowed_cores() -> Vec<usize> {
    Vec::new()
}

#[cfg(not(target_os = "linux"))]
fn pin(_core: usize) -> std::io::Result<()> {
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn workers_are_pinned_only_one_to_each_core() {
        assert_eq!(pinned_cores(2, vec![0, 1]), vec![0, 1]);
        assert_eq!(pinned_cores(3, vec![2, 5, 7]), vec![2, 5, 7]);
        // Fewer or more workers than cores, or one alone: the scheduler places them.
        assert!(pinned_cores(2, vec![0, 1, 2, 3]).is_empty());
        assert!(pinned_cores(4, vec![0, 1]).is_empty());
        assert!(pinned_cores(1, vec![3]).is_empty());
        assert!(pinned_cores(2, Vec::new()).is_empty());
    }

    #[test]
    fn the_pool_has_the_threads_asked_for_and_traces() {
        let pool = pool(2).expect("a pool");
        assert_eq!(pool.current_num_threads(), 2);
        let sum: u64 = pool.install(|| {
            use rayon::prelude::*;
            (1..=1000u64).into_par_iter().sum()
        });
        assert_eq!(sum, 500_500);
    }

    #[cfg(target_os = "linux")]
    #[test]
    fn a_pinned_worker_runs_on_its_core_alone() {
        let cores = allowed_cores();
        let pool = pool(0).expect("a pool");
        if cores.len() < 2 || pool.current_num_threads() != cores.len() {
            // One core, or a quota below the cores allowed: nothing is pinned.
            return;
        }
        // On a worker, `allowed_cores` reads that worker's own set.
        for (i, on) in pool.broadcast(|ctx| (ctx.index(), allowed_cores())) {
            assert_eq!(on, vec![cores[i]], "worker {i}");
        }
    }
}
