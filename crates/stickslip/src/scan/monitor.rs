//! Progress and cancellation of long computations.

use std::ops::ControlFlow;

/// Watches a long computation (a [`super::Sweep`] or a [`super::Grid`]): told after every
/// finished step or point, from whichever thread finished it, and able to stop the work.
///
/// `()` watches nothing; any `Fn(done, total) -> bool + Sync` is a monitor that cancels by
/// returning `false`.
pub trait Monitor: Sync {
    /// `done` of `total` steps or points are finished. [`ControlFlow::Break`] stops the
    /// computation, which then returns [`crate::Error::Cancelled`].
    fn step(&self, done: usize, total: usize) -> ControlFlow<()>;
}

impl Monitor for () {
    fn step(&self, _: usize, _: usize) -> ControlFlow<()> {
        ControlFlow::Continue(())
    }
}

impl<F: Fn(usize, usize) -> bool + Sync> Monitor for F {
    fn step(&self, done: usize, total: usize) -> ControlFlow<()> {
        if self(done, total) {
            ControlFlow::Continue(())
        } else {
            ControlFlow::Break(())
        }
    }
}

/// Compute `item(0) … item(total − 1)` in parallel and collect them in order; `monitor` sees
/// every finished item and can stop the work. With `threads`, the work runs on a pool of that
/// many threads; otherwise on rayon's global pool. Each item is computed on its own, so the
/// result does not depend on the number of threads.
///
/// # Errors
/// [`crate::Error::Cancelled`] when the monitor stops the work; the first error of `item`;
/// [`crate::Error::InvalidParameter`] when a pool of `threads` cannot be started.
pub(crate) fn run_parallel<T: Send>(
    total: usize,
    threads: Option<usize>,
    monitor: &dyn Monitor,
    item: impl Fn(usize) -> crate::Result<T> + Sync,
) -> crate::Result<Vec<T>> {
    use crate::Error;
    use rayon::prelude::*;
    use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering};
    let stop = AtomicBool::new(false);
    let done = AtomicUsize::new(0);
    let work = || -> crate::Result<Vec<T>> {
        (0..total)
            .into_par_iter()
            .map(|k| {
                if stop.load(Ordering::Relaxed) {
                    return Err(Error::Cancelled {
                        done: done.load(Ordering::Relaxed),
                        total,
                    });
                }
                let value = item(k)?;
                let finished = done.fetch_add(1, Ordering::Relaxed) + 1;
                if monitor.step(finished, total) == ControlFlow::Break(()) {
                    stop.store(true, Ordering::Relaxed);
                    return Err(Error::Cancelled {
                        done: finished,
                        total,
                    });
                }
                Ok(value)
            })
            .collect()
    };
    match threads {
        None => work(),
        Some(n) => rayon::ThreadPoolBuilder::new()
            .num_threads(n)
            .build()
            .map_err(|_| Error::InvalidParameter {
                name: "threads",
                value: n as f64,
                allowed: "a thread pool of this size could not be started",
            })?
            .install(work),
    }
}
