//! The lab's limits on one request: a time limit, and a stop as soon as nobody waits for
//! the answer (the page dropped a stale request). Both reach into the computation through
//! the library's cancellation token ([`stickslip::cancel::Cancel`]): the request's
//! experiment carries its [`Budget::cancel`] token ([`Experiment::with_cancel`]), whose
//! deadline is the time limit and which the budget cancels when the request is dropped, so
//! every solver the computation builds checks it as it advances; sweeps and maps also check
//! the budget between points through the library's [`Monitor`](stickslip::scan::Monitor).
//! The token's hook ([`Cancel::with_hook`]) gives the computation's turn to another client
//! every [`SLICE`] while others wait (see [`super::fair`]).
//!
//! [`Experiment::with_cancel`]: stickslip::experiment::Experiment::with_cancel

use super::fair::{Client, Fair, Turn, SLICE};
use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering};
use std::sync::{Arc, Mutex};
use std::thread::ThreadId;
use std::time::{Duration, Instant};
use stickslip::cancel::Cancel;
use stickslip::experiment::Experiment;

/// Why a computation must stop, shared between the request and its computation.
#[derive(Debug)]
pub struct Budget {
    deadline: Instant,
    limit: Duration,
    abandoned: AtomicBool,
    /// The token the computation's solvers check: the deadline, cancelled when abandoned,
    /// and a hook that calls [`Budget::share`].
    cancel: Cancel,
    /// Steps or points finished, and their number, of a sweep or a map.
    done: AtomicUsize,
    total: AtomicUsize,
    /// The computation's turn at the workers, when it takes turns.
    turns: Mutex<Option<Turns>>,
}

/// A computation's turn, given back and taken again from the thread that runs it.
struct Turns {
    fair: Arc<Fair>,
    client: Client,
    turn: Option<Turn>,
    since: Instant,
    thread: ThreadId,
    runtime: tokio::runtime::Handle,
}

impl std::fmt::Debug for Turns {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Turns")
            .field("client", &self.client)
            .field("holds", &self.turn.is_some())
            .finish()
    }
}

impl Budget {
    /// A budget of `limit` from now.
    pub fn new(limit: Duration) -> Arc<Self> {
        let deadline = Instant::now() + limit;
        Arc::new_cyclic(|budget: &std::sync::Weak<Self>| {
            let budget = budget.clone();
            Self {
                deadline,
                limit,
                abandoned: AtomicBool::new(false),
                // The hook holds the budget weakly: the budget holds the token.
                cancel: Cancel::new()
                    .with_deadline(deadline)
                    .with_hook(Arc::new(move || {
                        if let Some(budget) = budget.upgrade() {
                            budget.share();
                        }
                    })),
                done: AtomicUsize::new(0),
                total: AtomicUsize::new(0),
                turns: Mutex::new(None),
            }
        })
    }

    /// The token that stops the computation's solvers when the budget is spent, and gives
    /// the turn to waiting clients from inside them.
    pub fn cancel(&self) -> Cancel {
        self.cancel.clone()
    }

    /// `experiment` with this budget's token: every solver it builds checks the budget.
    pub fn limit_experiment(&self, experiment: &Experiment) -> Experiment {
        experiment.clone().with_cancel(self.cancel())
    }

    /// The computation runs on this thread, in `turn`: from now on [`Budget::share`] on this
    /// thread gives the turn to a waiting client every [`SLICE`] and waits for the next one.
    pub fn take_turns(
        &self,
        fair: Arc<Fair>,
        client: Client,
        turn: Turn,
        runtime: tokio::runtime::Handle,
    ) {
        *self.turns.lock().unwrap_or_else(|e| e.into_inner()) = Some(Turns {
            fair,
            client,
            turn: Some(turn),
            since: Instant::now(),
            thread: std::thread::current().id(),
            runtime,
        });
    }

    /// The computation is over: its turn goes to the next client.
    pub fn end_turns(&self) {
        self.turns.lock().unwrap_or_else(|e| e.into_inner()).take();
    }

    /// Give the turn to a waiting client when this computation has had its [`SLICE`], and
    /// wait for the next turn (at most until the deadline, or until nobody waits for the
    /// answer). Only on the thread that took the turn (never on a thread of a parallel
    /// map, which must not block); elsewhere, and without turns, nothing happens. The
    /// budget's token calls it from inside the solvers every few hundred steps.
    pub fn share(&self) {
        let Ok(mut guard) = self.turns.try_lock() else {
            return;
        };
        let Some(turns) = guard.as_mut() else {
            return;
        };
        if turns.thread != std::thread::current().id()
            || turns.since.elapsed() < SLICE
            || !turns.fair.others_wait()
        {
            return;
        }
        // Hand the turn over and queue behind the others.
        turns.turn = None;
        let fair = turns.fair.clone();
        let deadline = tokio::time::Instant::from_std(self.deadline);
        turns.turn = turns.runtime.block_on(async {
            let mut next = std::pin::pin!(fair.turn(&turns.client));
            loop {
                let wake = (tokio::time::Instant::now() + Duration::from_millis(50)).min(deadline);
                match tokio::time::timeout_at(wake, &mut next).await {
                    Ok(turn) => return Some(turn),
                    Err(_) if self.spent() => return None,
                    Err(_) => {}
                }
            }
        });
        turns.since = Instant::now();
    }

    /// When the time runs out.
    pub fn deadline(&self) -> Instant {
        self.deadline
    }

    /// The time limit.
    pub fn limit(&self) -> Duration {
        self.limit
    }

    /// Nobody waits for the answer any more.
    pub fn abandon(&self) {
        self.abandoned.store(true, Ordering::Relaxed);
        self.cancel.cancel();
    }

    /// Whether nobody waits for the answer.
    pub fn abandoned(&self) -> bool {
        self.abandoned.load(Ordering::Relaxed)
    }

    /// Whether the time has run out.
    pub fn timed_out(&self) -> bool {
        Instant::now() >= self.deadline
    }

    /// Whether the computation should stop.
    pub fn spent(&self) -> bool {
        self.abandoned() || self.timed_out()
    }

    /// A monitor for sweeps and grids: it counts the finished steps or points and stops
    /// the work when the budget is spent.
    pub fn keep_going(&self) -> impl Fn(usize, usize) -> bool + Sync + '_ {
        move |done, total| {
            self.done.fetch_max(done, Ordering::Relaxed);
            self.total.store(total, Ordering::Relaxed);
            self.share();
            !self.spent()
        }
    }

    /// A sweep or map of `total` steps or points starts.
    pub fn start(&self, total: usize) {
        self.total.store(total, Ordering::Relaxed);
    }

    /// Steps or points finished and their number, as the monitor last saw them (0 of 0
    /// before the first one finished).
    pub fn progress(&self) -> (usize, usize) {
        (
            self.done.load(Ordering::Relaxed),
            self.total.load(Ordering::Relaxed),
        )
    }
}

/// Abandons its budget when dropped: held by the request's future, which the server drops
/// when the client goes away.
pub struct AbandonOnDrop(pub Arc<Budget>);

impl Drop for AbandonOnDrop {
    fn drop(&mut self) {
        self.0.abandon();
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use stickslip::Error;

    #[test]
    fn a_limited_experiment_gives_the_same_steady_state() {
        let e = Experiment::paper()
            .with_w(0.29)
            .unwrap()
            .with_beta(2.14)
            .unwrap();
        let budget = Budget::new(Duration::from_secs(600));
        let limited = budget.limit_experiment(&e);
        assert_eq!(limited.steady().unwrap(), e.steady().unwrap());
        // The solvers charged their steps to the budget's token.
        assert!(budget.cancel().spent() > 0);
    }

    #[test]
    fn a_budget_without_time_stops_the_solver_at_its_deadline() {
        let e = Experiment::paper()
            .with_w(0.95)
            .unwrap()
            .with_beta(2.14)
            .unwrap();
        let budget = Budget::new(Duration::ZERO);
        let err = budget.limit_experiment(&e).steady().unwrap_err();
        assert!(matches!(err, Error::DeadlineExceeded), "{err}");
        assert!(budget.timed_out() && !budget.abandoned());
    }

    #[test]
    fn a_spent_budget_stops_the_solver() {
        let e = Experiment::paper()
            .with_w(0.95)
            .unwrap()
            .with_beta(2.14)
            .unwrap();
        let budget = Budget::new(Duration::from_secs(600));
        let limited = budget.limit_experiment(&e);
        budget.abandon();
        let err = limited.steady().unwrap_err();
        assert!(matches!(err, Error::Cancelled { .. }), "{err}");
    }

    #[test]
    fn the_budgets_token_stops_with_it() {
        let e = Experiment::paper()
            .with_w(0.95)
            .unwrap()
            .with_beta(2.14)
            .unwrap();
        // Abandoned: the experiment carrying the token stops.
        let budget = Budget::new(Duration::from_secs(600));
        assert!(budget.cancel().check().is_ok());
        budget.abandon();
        let err = e.clone().with_cancel(budget.cancel()).steady().unwrap_err();
        assert!(matches!(err, Error::Cancelled { .. }), "{err}");
        // Past its deadline: the same.
        let budget = Budget::new(Duration::from_millis(1));
        std::thread::sleep(Duration::from_millis(5));
        let err = e.with_cancel(budget.cancel()).steady().unwrap_err();
        assert!(matches!(err, Error::DeadlineExceeded), "{err}");
    }
}
