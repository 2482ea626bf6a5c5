//! Cancellation, deadlines and work budgets of long computations.
//!
//! A [`Cancel`] is a token shared by the caller and the computation: cloning it gives another
//! handle on the same state. The caller calls [`Cancel::cancel`] (from any thread, e.g. a
//! Ctrl-C handler or a server whose client went away), or gives the token a deadline
//! ([`Cancel::with_deadline`]) or a budget of solver steps ([`Cancel::with_budget`]) when it
//! is made. The computation checks it: the solvers built by an
//! [`crate::Experiment`] that carries the token ([`crate::Experiment::with_cancel`]) check it
//! at every step, so every computation built on them (steady states, orbits, exponents,
//! sweeps, maps, bifurcation diagrams, basins, branches) stops within one solver step and
//! returns [`crate::Error::Cancelled`], [`crate::Error::DeadlineExceeded`] or
//! [`crate::Error::BudgetExceeded`]. The token is also a [`crate::scan::Monitor`], so that a
//! scan stops between its points too.
//!
//! The token counts the steps charged to it ([`Cancel::spent`]) whether or not it has a
//! budget, and the solvers that check it add their work counters ([`crate::Stats`]) to it
//! when they are dropped ([`Cancel::work`]): a benchmark reads the work of a whole scan from
//! there.
//!
//! [`Cancel::default`] (= [`Cancel::never`]) is a token nobody holds: it never stops and costs
//! one branch per check.
//!
//! A token may carry a hook ([`Cancel::with_hook`]): the caller's code, called from
//! [`Cancel::charge`] once every [`HOOK_EVERY`] charged steps, on the thread that charges
//! them. A server uses it to let a long computation give its worker to another client for a
//! while (the hook blocks until the computation's next turn); the library itself calls
//! nothing else from it and does no I/O.
//!
//! ```
//! use stickslip::cancel::Cancel;
//! let token = Cancel::new();
//! let handle = token.clone();
//! assert!(token.check().is_ok());
//! handle.cancel();
//! assert!(token.is_cancelled());
//! assert!(matches!(token.check(), Err(stickslip::Error::Cancelled { .. })));
//! ```

use crate::error::{Error, Result};
use crate::solver::Stats;
use std::ops::ControlFlow;
use std::sync::atomic::{AtomicBool, AtomicU64, Ordering};
use std::sync::Arc;
use std::time::Instant;

/// How many charged steps pass between two looks at the clock (a deadline is honoured to
/// within this many solver steps, well under a millisecond).
const CLOCK_EVERY: u64 = 256;

/// How many charged steps pass between two calls of a token's hook ([`Cancel::with_hook`]).
pub const HOOK_EVERY: u64 = CLOCK_EVERY;

/// The caller's code that a token calls every [`HOOK_EVERY`] charged steps
/// ([`Cancel::with_hook`]).
pub type Hook = Arc<dyn Fn() + Send + Sync>;

/// A clone-able cancellation token with an optional deadline and step budget (see the
/// module documentation).
#[derive(Debug, Clone, Default)]
pub struct Cancel {
    inner: Option<Arc<Inner>>,
}

struct Inner {
    cancelled: AtomicBool,
    deadline: Option<Instant>,
    budget: Option<u64>,
    /// Called every [`HOOK_EVERY`] charged steps.
    hook: Option<Hook>,
    spent: AtomicU64,
    /// Set once the deadline has passed (so that later checks need no clock).
    expired: AtomicBool,
    /// The work counters of the solvers dropped so far: events, evaluations, steps, rejected.
    work: [AtomicU64; 4],
}

impl std::fmt::Debug for Inner {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Cancel")
            .field("cancelled", &self.cancelled)
            .field("deadline", &self.deadline)
            .field("budget", &self.budget)
            .field("hook", &self.hook.is_some())
            .field("spent", &self.spent)
            .field("expired", &self.expired)
            .field("work", &self.work)
            .finish()
    }
}

/// Why a computation was stopped by its [`Cancel`] token.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Stop {
    /// [`Cancel::cancel`] was called.
    Cancelled,
    /// The deadline passed.
    Deadline,
    /// The step budget is used up.
    Budget(u64),
}

impl Stop {
    /// The error a computation returns when stopped for this reason.
    pub fn error(self) -> Error {
        match self {
            Stop::Cancelled => Error::Cancelled { done: 0, total: 1 },
            Stop::Deadline => Error::DeadlineExceeded,
            Stop::Budget(budget) => Error::BudgetExceeded { budget },
        }
    }
}

impl Cancel {
    /// A token that can be cancelled, without deadline or budget.
    pub fn new() -> Self {
        Self {
            inner: Some(Arc::new(Inner {
                cancelled: AtomicBool::new(false),
                deadline: None,
                budget: None,
                hook: None,
                spent: AtomicU64::new(0),
                expired: AtomicBool::new(false),
                work: Default::default(),
            })),
        }
    }

    /// The token nobody holds: never stops, counts nothing.
    pub const fn never() -> Self {
        Self { inner: None }
    }

    /// A new token like this one (cancellable) that also stops at `deadline`. The token is a
    /// new one: cancelling the old one does not reach it.
    pub fn with_deadline(self, deadline: Instant) -> Self {
        let (budget, cancelled) = self.parts();
        Self::build(cancelled, Some(deadline), budget, self.hook())
    }

    /// A new token like this one (cancellable) that also stops after `steps` solver steps
    /// (events of the exact solver, accepted or rejected steps of the stiff one) charged in
    /// all, over every solver sharing it.
    pub fn with_budget(self, steps: u64) -> Self {
        let deadline = self.inner.as_ref().and_then(|i| i.deadline);
        let (_, cancelled) = self.parts();
        Self::build(cancelled, deadline, Some(steps), self.hook())
    }

    /// A new token like this one (cancellable, with its deadline and budget) that also calls
    /// `hook` from [`Cancel::charge`] once every [`HOOK_EVERY`] charged steps, on the thread
    /// that charges them (the first call after the first [`HOOK_EVERY`] steps). The hook may
    /// block (the computation waits) and may cancel a clone of the token; it must not hold a
    /// clone of the token it is given to (that would keep the token alive for ever), so hold
    /// whatever it needs by a weak reference. Checks without a hook cost nothing more.
    pub fn with_hook(self, hook: Hook) -> Self {
        let deadline = self.deadline();
        let (budget, cancelled) = self.parts();
        Self::build(cancelled, deadline, budget, Some(hook))
    }

    fn parts(&self) -> (Option<u64>, bool) {
        match &self.inner {
            None => (None, false),
            Some(i) => (i.budget, i.cancelled.load(Ordering::Relaxed)),
        }
    }

    fn hook(&self) -> Option<Hook> {
        self.inner.as_ref().and_then(|i| i.hook.clone())
    }

    fn build(
        cancelled: bool,
        deadline: Option<Instant>,
        budget: Option<u64>,
        hook: Option<Hook>,
    ) -> Self {
        Self {
            inner: Some(Arc::new(Inner {
                cancelled: AtomicBool::new(cancelled),
                deadline,
                budget,
                hook,
                spent: AtomicU64::new(0),
                expired: AtomicBool::new(false),
                work: Default::default(),
            })),
        }
    }

    /// Stop every computation checking this token (or a clone of it).
    pub fn cancel(&self) {
        if let Some(i) = &self.inner {
            i.cancelled.store(true, Ordering::Relaxed);
        }
    }

    /// Whether [`Cancel::cancel`] was called, the deadline has passed or the budget is spent.
    pub fn is_cancelled(&self) -> bool {
        self.stopped().is_some()
    }

    /// The deadline, if any.
    pub fn deadline(&self) -> Option<Instant> {
        self.inner.as_ref().and_then(|i| i.deadline)
    }

    /// The step budget, if any.
    pub fn budget(&self) -> Option<u64> {
        self.inner.as_ref().and_then(|i| i.budget)
    }

    /// Solver steps charged so far ([`Cancel::charge`]); 0 for [`Cancel::never`].
    pub fn spent(&self) -> u64 {
        self.inner
            .as_ref()
            .map_or(0, |i| i.spent.load(Ordering::Relaxed))
    }

    /// Why the token stops work, or `None` while it lets it run. Looks at the clock.
    pub fn stopped(&self) -> Option<Stop> {
        let i = self.inner.as_ref()?;
        if i.cancelled.load(Ordering::Relaxed) {
            return Some(Stop::Cancelled);
        }
        if let Some(budget) = i.budget {
            if i.spent.load(Ordering::Relaxed) > budget {
                return Some(Stop::Budget(budget));
            }
        }
        if i.expired.load(Ordering::Relaxed) {
            return Some(Stop::Deadline);
        }
        if let Some(deadline) = i.deadline {
            if Instant::now() >= deadline {
                i.expired.store(true, Ordering::Relaxed);
                return Some(Stop::Deadline);
            }
        }
        None
    }

    /// Check the token.
    ///
    /// # Errors
    /// [`Error::Cancelled`], [`Error::DeadlineExceeded`] or [`Error::BudgetExceeded`].
    pub fn check(&self) -> Result<()> {
        match self.stopped() {
            None => Ok(()),
            Some(stop) => Err(stop.error()),
        }
    }

    /// Charge `steps` solver steps to the token and check it (the clock is read once every
    /// few hundred steps, and the hook, if any, called as often: [`Cancel::with_hook`]). What
    /// every solver calls at every step.
    ///
    /// # Errors
    /// As [`Cancel::check`].
    #[inline]
    pub fn charge(&self, steps: u64) -> Result<()> {
        let Some(i) = &self.inner else {
            return Ok(());
        };
        let before = i.spent.fetch_add(steps, Ordering::Relaxed);
        let after = before + steps;
        if i.cancelled.load(Ordering::Relaxed) {
            return Err(Stop::Cancelled.error());
        }
        if let Some(budget) = i.budget {
            if after > budget {
                return Err(Stop::Budget(budget).error());
            }
        }
        if (i.deadline.is_some() || i.hook.is_some())
            && (before / CLOCK_EVERY != after / CLOCK_EVERY || before == 0)
        {
            if let Some(hook) = &i.hook {
                if before != 0 {
                    hook();
                }
            }
            if let Some(stop) = self.stopped() {
                return Err(stop.error());
            }
        }
        if i.expired.load(Ordering::Relaxed) {
            return Err(Stop::Deadline.error());
        }
        Ok(())
    }

    /// Add a solver's work counters to the token's ([`Cancel::work`]); what the solvers that
    /// check the token do when they are dropped. Nothing for [`Cancel::never`].
    pub fn add_work(&self, stats: Stats) {
        if let Some(i) = &self.inner {
            for (total, n) in
                i.work
                    .iter()
                    .zip([stats.events, stats.evaluations, stats.steps, stats.rejected])
            {
                total.fetch_add(n, Ordering::Relaxed);
            }
        }
    }

    /// The work counters of every solver that checked this token and has been dropped.
    pub fn work(&self) -> Stats {
        let Some(i) = &self.inner else {
            return Stats::default();
        };
        let [events, evaluations, steps, rejected] =
            std::array::from_fn(|k| i.work[k].load(Ordering::Relaxed));
        Stats {
            events,
            evaluations,
            steps,
            rejected,
        }
    }

    /// Whether this is [`Cancel::never`].
    pub fn is_never(&self) -> bool {
        self.inner.is_none()
    }
}

impl PartialEq for Cancel {
    /// Two handles are equal when they are the same token (or both [`Cancel::never`]).
    fn eq(&self, other: &Self) -> bool {
        match (&self.inner, &other.inner) {
            (None, None) => true,
            (Some(a), Some(b)) => Arc::ptr_eq(a, b),
            _ => false,
        }
    }
}

impl crate::scan::Monitor for Cancel {
    fn step(&self, _done: usize, _total: usize) -> ControlFlow<()> {
        if self.is_cancelled() {
            ControlFlow::Break(())
        } else {
            ControlFlow::Continue(())
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::sync::Mutex;
    use std::time::Duration;

    #[test]
    fn never_never_stops_and_counts_nothing() {
        let t = Cancel::never();
        for _ in 0..1000 {
            t.charge(1).unwrap();
        }
        t.cancel();
        assert!(!t.is_cancelled());
        assert_eq!(t.spent(), 0);
    }

    #[test]
    fn a_clone_cancels_the_original() {
        let t = Cancel::new();
        let u = t.clone();
        assert!(t.charge(5).is_ok());
        u.cancel();
        assert_eq!(t.charge(1), Err(Error::Cancelled { done: 0, total: 1 }));
        assert_eq!(u.spent(), 6);
        assert_eq!(t, u);
        assert_ne!(t, Cancel::new());
    }

    #[test]
    fn the_budget_stops_after_the_steps() {
        let t = Cancel::new().with_budget(10);
        for _ in 0..10 {
            t.charge(1).unwrap();
        }
        assert_eq!(t.charge(1), Err(Error::BudgetExceeded { budget: 10 }));
        assert_eq!(t.stopped(), Some(Stop::Budget(10)));
    }

    #[test]
    fn the_hook_is_called_every_so_many_steps_and_may_cancel() {
        use std::sync::atomic::AtomicUsize;
        use std::sync::Weak;
        let calls = Arc::new(AtomicUsize::new(0));
        let seen = calls.clone();
        let t = Cancel::new()
            .with_budget(100 * HOOK_EVERY)
            .with_hook(Arc::new(move || {
                seen.fetch_add(1, Ordering::Relaxed);
            }));
        assert_eq!(t.budget(), Some(100 * HOOK_EVERY));
        for _ in 0..10 * HOOK_EVERY {
            t.charge(1).unwrap();
        }
        // Once each time the steps charged reach a multiple of HOOK_EVERY.
        assert_eq!(calls.load(Ordering::Relaxed), 10);
        // The hook survives a new deadline; one that cancels stops the next check.
        let t = t.with_deadline(Instant::now() + Duration::from_secs(3600));
        let slot: Arc<Mutex<Weak<Inner>>> = Arc::default();
        let weak = slot.clone();
        let t = t.with_hook(Arc::new(move || {
            if let Some(inner) = weak.lock().unwrap().upgrade() {
                inner.cancelled.store(true, Ordering::Relaxed);
            }
        }));
        *slot.lock().unwrap() = Arc::downgrade(t.inner.as_ref().unwrap());
        let stopped = (0..2 * HOOK_EVERY).find(|_| t.charge(1).is_err());
        assert_eq!(stopped, Some(HOOK_EVERY - 1));
        assert_eq!(t.check(), Err(Error::Cancelled { done: 0, total: 1 }));
    }

    #[test]
    fn a_past_deadline_stops_at_the_first_charge() {
        let t = Cancel::new().with_deadline(Instant::now());
        assert_eq!(t.charge(1), Err(Error::DeadlineExceeded));
        let later = Cancel::new().with_deadline(Instant::now() + Duration::from_secs(3600));
        for _ in 0..10_000 {
            later.charge(1).unwrap();
        }
        assert!(!later.is_cancelled());
        // A deadline and a budget together: whichever comes first.
        let both = later.with_budget(3);
        assert!(both.deadline().is_some());
        assert_eq!(both.charge(4), Err(Error::BudgetExceeded { budget: 3 }));
    }
}
