//! Long computations without the GIL, stoppable by Ctrl-C.
//!
//! Python runs signal handlers (and so raises `KeyboardInterrupt`) only on its main thread and
//! only when that thread runs Python code. A computation is therefore run on a thread of its
//! own while the calling thread waits without the GIL, waking every [`POLL`] to run the signal
//! handlers ([`Python::check_signals`]) and the caller's progress callback. When either raises,
//! the computation's [`Cancel`] token and its [`Monitor`] tell the library to
//! stop, the calling thread waits for it to return (within one solver step, or one grid point
//! or sweep step for a monitor), and the exception propagates.

use pyo3::prelude::*;
use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::{Condvar, Mutex};
use std::time::Duration;
use stickslip::cancel::Cancel;
use stickslip::scan::Monitor;

/// How often the waiting thread runs the signal handlers and the progress callback.
const POLL: Duration = Duration::from_millis(50);

/// The computation's result, handed from its thread to the waiting one.
struct Slot<T> {
    value: Mutex<Option<T>>,
    ready: Condvar,
}

impl<T> Slot<T> {
    fn put(&self, value: T) {
        *self.value.lock().unwrap_or_else(|e| e.into_inner()) = Some(value);
        self.ready.notify_all();
    }

    /// The value, if it arrives within `timeout`.
    fn take(&self, timeout: Option<Duration>) -> Option<T> {
        let mut guard = self.value.lock().unwrap_or_else(|e| e.into_inner());
        loop {
            if let Some(v) = guard.take() {
                return Some(v);
            }
            match timeout {
                None => guard = self.ready.wait(guard).unwrap_or_else(|e| e.into_inner()),
                Some(t) => {
                    let (g, result) = self
                        .ready
                        .wait_timeout(guard, t)
                        .unwrap_or_else(|e| e.into_inner());
                    guard = g;
                    if result.timed_out() {
                        return guard.take();
                    }
                }
            }
        }
    }
}

/// Run `work` without the GIL on a thread of its own, handing it a monitor that stops it when
/// the caller is interrupted (Ctrl-C, or an exception raised by `progress`). `progress`, a
/// Python callable, is called as `progress(done, total)` from the calling thread whenever
/// more work is done (at most every 50 ms, and once at the end).
///
/// # Errors
/// The library's error as `ValueError`; `KeyboardInterrupt` (or whatever the signal handler or
/// `progress` raised) when interrupted.
pub(crate) fn run<T, F>(py: Python<'_>, progress: Option<&Bound<'_, PyAny>>, work: F) -> PyResult<T>
where
    T: Send,
    F: FnOnce(&dyn Monitor) -> stickslip::Result<T> + Send,
{
    run_with(py, progress, |monitor, _| work(monitor))
}

/// [`run`] for a computation that checks a [`Cancel`] token of its own (carried by its
/// experiment, [`stickslip::Experiment::with_cancel`]): `work` gets the monitor and the token,
/// which is cancelled when the caller is interrupted.
pub(crate) fn run_with<T, F>(
    py: Python<'_>,
    progress: Option<&Bound<'_, PyAny>>,
    work: F,
) -> PyResult<T>
where
    T: Send,
    F: FnOnce(&dyn Monitor, &Cancel) -> stickslip::Result<T> + Send,
{
    let stop = Cancel::new();
    let done = AtomicUsize::new(0);
    let total = AtomicUsize::new(0);
    let slot = Slot {
        value: Mutex::new(None),
        ready: Condvar::new(),
    };
    let monitor = |d: usize, t: usize| {
        done.fetch_max(d, Ordering::Relaxed);
        total.store(t, Ordering::Relaxed);
        !stop.is_cancelled()
    };
    std::thread::scope(|scope| {
        let (monitor, slot_ref, token) = (&monitor, &slot, &stop);
        let worker = scope.spawn(move || slot_ref.put(work(monitor, token)));
        // The result, waiting at most one poll; a panic of the worker resumes here.
        let wait = || -> Option<stickslip::Result<T>> {
            let result = py.detach(|| slot.take(Some(POLL)));
            if result.is_none() && worker.is_finished() {
                return Some(slot.take(Some(Duration::ZERO)).unwrap_or_else(|| {
                    std::panic::resume_unwind(Box::new("the computation's thread panicked"))
                }));
            }
            result
        };
        let mut reported = 0;
        loop {
            let result = wait();
            let now = done.load(Ordering::Relaxed);
            let mut report = || -> PyResult<()> {
                if let Some(callback) = progress {
                    if now > reported {
                        reported = now;
                        callback.call1((now, total.load(Ordering::Relaxed)))?;
                    }
                }
                Ok(())
            };
            if let Some(result) = result {
                return match result {
                    Ok(value) => report().map(|_| value),
                    Err(e) => Err(crate::error(e)),
                };
            }
            if let Err(interrupt) = py.check_signals().and_then(|_| report()) {
                stop.cancel();
                // The library returns within one point or step once told to stop.
                while wait().is_none() {}
                return Err(interrupt);
            }
        }
    })
}
