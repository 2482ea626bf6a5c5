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
