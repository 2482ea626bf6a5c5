//! The lab's limits on one request: a time limit, and a stop as soon as nobody waits for
//! the answer (the page dropped a stale request). Both reach into the computation: every
//! solver the request builds checks its [`Budget`] as it advances, and sweeps and maps check
//! it between points through the library's [`Monitor`](stickslip::scan::Monitor). The same
//! checks give the computation's turn to another client every [`SLICE`] while others wait
//! (see [`super::fair`]).

use super::fair::{Fair, Turn, SLICE};
use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering};
use std::sync::{Arc, Mutex};
use std::thread::ThreadId;
use std::time::{Duration, Instant};
use stickslip::cancel::Cancel;
use stickslip::steady::SolverFactory;
use stickslip::{Error, Event, Params, Phase, Result, Sample, Solver, State, Stats};

/// Why a computation must stop, shared between the request and its computation.
#[derive(Debug)]
pub struct Budget {
    deadline: Instant,
    limit: Duration,
    abandoned: AtomicBool,
    /// Steps or points finished, and their number, of a sweep or a map.
    done: AtomicUsize,
    total: AtomicUsize,
    /// The computation's turn at the workers, when it takes turns.
    turns: Mutex<Option<Turns>>,
    /// The library's token of the same budget, for computations that check an
    /// experiment's token rather than a wrapped solver (the fit): it passes its deadline with
    /// the budget and is cancelled when the budget is abandoned.
    cancel: Cancel,
}

/// A computation's turn, given back and taken again from the thread that runs it.
struct Turns {
    fair: Arc<Fair>,
    client: String,
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
        Arc::new(Self {
            deadline,
            cancel: Cancel::new().with_deadline(deadline),
            limit,
            abandoned: AtomicBool::new(false),
            done: AtomicUsize::new(0),
            total: AtomicUsize::new(0),
            turns: Mutex::new(None),
        })
    }

    /// The computation runs on this thread, in `turn`: from now on [`Budget::share`] on this
    /// thread gives the turn to a waiting client every [`SLICE`] and waits for the next one.
    pub fn take_turns(
        &self,
        fair: Arc<Fair>,
        client: String,
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
    /// map, which must not block); elsewhere, and without turns, nothing happens.
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

    /// The library's cancellation token of this budget ([`Cancel`]): past the deadline, or
    /// once nobody waits for the answer, every solver of an experiment carrying it
    /// ([`stickslip::Experiment::with_cancel`]) stops within a step.
    pub fn cancel(&self) -> &Cancel {
        &self.cancel
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

/// Solver calls between two looks at the clock: a look costs about as much as a few events
/// of the exact solver, so the clock is read once per this many calls.
const CALLS_PER_CHECK: u32 = 64;

/// A solver that stops with [`Error::Cancelled`] once its budget is spent; otherwise it is
/// the solver it wraps, call for call (results are bit-identical).
pub struct Limited {
    inner: Box<dyn Solver + Send>,
    budget: Arc<Budget>,
    calls: u32,
}

impl Solver for Limited {
    fn params(&self) -> &Params {
        self.inner.params()
    }
    fn time(&self) -> f64 {
        self.inner.time()
    }
    fn state(&self) -> State {
        self.inner.state()
    }
    fn phase(&self) -> Phase {
        self.inner.phase()
    }
    fn drive(&self, tau: f64) -> f64 {
        self.inner.drive(tau)
    }
    fn advance(&mut self, t_end: f64) -> Result<Option<Event>> {
        self.calls = self.calls.wrapping_add(1);
        if self.calls.is_multiple_of(CALLS_PER_CHECK) {
            if self.budget.spent() {
                return Err(Error::Cancelled { done: 0, total: 1 });
            }
            self.budget.share();
        }
        self.inner.advance(t_end)
    }
    fn interval(&self) -> (f64, f64) {
        self.inner.interval()
    }
    fn dense(&self, tau: f64) -> Sample {
        self.inner.dense(tau)
    }
    fn stats(&self) -> Stats {
        self.inner.stats()
    }
    fn is_exact(&self) -> bool {
        self.inner.is_exact()
    }
}

/// A factory whose solvers are [`Limited`] by one budget.
#[derive(Clone)]
pub struct LimitedFactory<F> {
    inner: F,
    budget: Arc<Budget>,
}

impl<F: SolverFactory> LimitedFactory<F> {
    /// Solvers of `inner`, limited by `budget`.
    pub fn new(inner: F, budget: Arc<Budget>) -> Self {
        Self { inner, budget }
    }
}

impl<F: SolverFactory> SolverFactory for LimitedFactory<F> {
    fn make(&self, params: Params, initial: State) -> Result<Box<dyn Solver + Send>> {
        Ok(Box::new(Limited {
            inner: self.inner.make(params, initial)?,
            budget: self.budget.clone(),
            calls: 0,
        }))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use stickslip::experiment::Experiment;
    use stickslip::steady::steady_state_from;

    #[test]
    fn a_limited_solver_gives_the_same_steady_state() {
        let e = Experiment::paper()
            .with_w(0.29)
            .unwrap()
            .with_beta(2.14)
            .unwrap();
        let budget = Budget::new(Duration::from_secs(600));
        let limited = LimitedFactory::new(e.factory(), budget);
        let s = steady_state_from(
            &limited,
            &e.params().unwrap(),
            e.initial(),
            &e.steady_options(),
        )
        .unwrap();
        assert_eq!(s, e.steady().unwrap());
    }

    #[test]
    fn a_spent_budget_stops_the_solver() {
        let e = Experiment::paper()
            .with_w(0.95)
            .unwrap()
            .with_beta(2.14)
            .unwrap();
        let budget = Budget::new(Duration::from_secs(600));
        budget.abandon();
        let limited = LimitedFactory::new(e.factory(), budget);
        let err = steady_state_from(
            &limited,
            &e.params().unwrap(),
            e.initial(),
            &e.steady_options(),
        )
        .unwrap_err();
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
        let err = e
            .clone()
            .with_cancel(budget.cancel().clone())
            .steady()
            .unwrap_err();
        assert!(matches!(err, Error::Cancelled { .. }), "{err}");
        // Past its deadline: the same.
        let budget = Budget::new(Duration::from_millis(1));
        std::thread::sleep(Duration::from_millis(5));
        let err = e.with_cancel(budget.cancel().clone()).steady().unwrap_err();
        assert!(matches!(err, Error::DeadlineExceeded), "{err}");
    }
}
