//! The solver trait shared by the exact piecewise-linear solver and the stiff Shockley solver,
//! and generic drivers (run to a time, sample on a grid) written once against it.

use crate::error::{Error, Result};
use crate::params::{Params, State};
use serde::{Deserialize, Serialize};

/// How the oscillator moves at an instant.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize, Deserialize)]
pub enum Phase {
    /// Sliding with y' > 0.
    SlipPositive,
    /// Sliding with y' < 0.
    SlipNegative,
    /// Stuck: y' = 0 held by static friction (for a smooth diode: |y'| below the stop threshold).
    Stick,
}

impl Phase {
    /// The label used in CSV files: `slip+`, `slip-` or `stick`.
    pub fn label(self) -> &'static str {
        match self {
            Phase::SlipPositive => "slip+",
            Phase::SlipNegative => "slip-",
            Phase::Stick => "stick",
        }
    }

    /// The sliding direction: +1, −1, or 0 when stuck.
    pub fn sign(self) -> f64 {
        match self {
            Phase::SlipPositive => 1.0,
            Phase::SlipNegative => -1.0,
            Phase::Stick => 0.0,
        }
    }
}

/// What happened at an event.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize, Deserialize)]
pub enum EventKind {
    /// The velocity reverses without stopping (a turning point of the motion).
    Turn,
    /// The motion stops: static friction holds the oscillator.
    Stick,
    /// The motion resumes after a stop.
    Slip,
}

impl EventKind {
    /// The label used in CSV files: `turn`, `stick` or `slip`.
    pub fn label(self) -> &'static str {
        match self {
            EventKind::Turn => "turn",
            EventKind::Stick => "stick",
            EventKind::Slip => "slip",
        }
    }
}

/// A switching event of the motion.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Event {
    /// Dimensionless time τ of the event.
    pub tau: f64,
    /// Position y at the event.
    pub y: f64,
    /// What happened.
    pub kind: EventKind,
}

/// The state of the oscillator at a requested time (dense output).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Sample {
    /// Dimensionless time τ.
    pub tau: f64,
    /// Position y.
    pub y: f64,
    /// Velocity y'.
    pub v: f64,
    /// Phase of the motion at τ.
    pub phase: Phase,
}

/// Work counters of a solver, for benchmarks and regression tests.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize, Deserialize)]
pub struct Stats {
    /// Events (turn, stick, slip) reported.
    pub events: u64,
    /// Evaluations of the closed form (exact solver) or of the right-hand side (stiff solver).
    pub evaluations: u64,
    /// Accepted steps: search steps (exact solver) or integration steps (stiff solver).
    pub steps: u64,
    /// Rejected steps (stiff solver) or failed bracketing attempts (exact solver).
    pub rejected: u64,
}

/// What a solver has learned of its motion that spares work to another solver started on the
/// same motion: for the exact solver, how long its last slides of each kind lasted, where its
/// predicted search of the next velocity zero looks first. A hint, never a result: a solver
/// that takes it proves every event as it would without it, and finds the same events to
/// rounding (see [`Solver::take_hints`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Hints {
    /// Per kind of slide (direction, from a stop or not): the duration of the last one.
    pub(crate) slides: [f64; 4],
}

/// A solver that advances the oscillator in time, reporting switching events and offering
/// dense output over the interval it last advanced through.
///
/// All times are dimensionless (τ = ω0·t) and absolute (the solver starts at τ = 0).
pub trait Solver {
    /// The dimensionless parameters the solver was built with (for the Shockley solver, ζ is
    /// ζ_R and μs is not used).
    fn params(&self) -> &Params;

    /// Current time τ.
    fn time(&self) -> f64;

    /// State at the current time.
    fn state(&self) -> State;

    /// Phase of the motion at the current time.
    fn phase(&self) -> Phase;

    /// The drive β cos(w τ + φ) at time τ, in the same units as y.
    fn drive(&self, tau: f64) -> f64;

    /// Advance to the next event or to `t_end`, whichever comes first, and return the event
    /// if one was reached. After the call, [`Solver::dense`] is valid on [`Solver::interval`].
    ///
    /// # Errors
    /// [`Error::TimeBeforeCurrent`] when `t_end` lies before [`Solver::time`]; numerical
    /// failures of the solver.
    fn advance(&mut self, t_end: f64) -> Result<Option<Event>>;

    /// The interval `(from, to)` covered by the last call of [`Solver::advance`]
    /// (`to` equals [`Solver::time`]).
    fn interval(&self) -> (f64, f64);

    /// Dense output at `tau` inside [`Solver::interval`].
    fn dense(&self, tau: f64) -> Sample;

    /// Work counters so far.
    fn stats(&self) -> Stats;

    /// Whether the solver follows the exact piecewise-linear model, the one whose tangent
    /// dynamics [`crate::stability`] knows, so that its motions can be measured by Lyapunov
    /// exponents (see [`crate::steady::SteadyOptions::lyapunov`]). [`crate::ExactSolver`]
    /// does; the stiff solver does not; a wrapper around a solver says what the solver it
    /// wraps says. No default: a wrapper that forgot it would silently turn off the
    /// measurement.
    fn is_exact(&self) -> bool;

    /// What this solver has learned that spares work to another one on the same motion
    /// ([`Hints`]); `None` for solvers that learn nothing.
    fn hints(&self) -> Option<Hints> {
        None
    }

    /// Take the [`Hints`] of another solver on the same motion (solvers that learn nothing
    /// ignore them). They change where the solver looks for its events first, not which
    /// events it finds: those stay the same to rounding.
    fn take_hints(&mut self, _hints: Hints) {}

    /// This solver as [`Any`](std::any::Any), for code that does more with a solver type it
    /// knows (the steady-state search carries the exact solver's tangent dynamics along it);
    /// `None` by default (a wrapper then loses only that shortcut).
    fn as_any_mut(&mut self) -> Option<&mut dyn std::any::Any> {
        None
    }
}

/// Advance `solver` to `t_end`, handing every event to `on_event`.
///
/// # Errors
/// Whatever [`Solver::advance`] reports.
pub fn run_until<S: Solver + ?Sized>(
    solver: &mut S,
    t_end: f64,
    mut on_event: impl FnMut(&Event),
) -> Result<()> {
    run_steps(solver, t_end, |_, event| {
        if let Some(event) = event {
            on_event(event);
        }
    })
}

/// Advance `solver` to `t_end`, handing `on_step` the solver after every step (its
/// [`Solver::interval`] is the stretch just covered, where [`Solver::dense`] holds) and the
/// event that ended the step, if any.
///
/// # Errors
/// [`Error::TimeBeforeCurrent`] when `t_end` is before the solver's time; whatever
/// [`Solver::advance`] reports.
pub fn run_steps<S: Solver + ?Sized>(
    solver: &mut S,
    t_end: f64,
    mut on_step: impl FnMut(&S, Option<&Event>),
) -> Result<()> {
    if t_end < solver.time() {
        return Err(Error::TimeBeforeCurrent {
            requested: t_end,
            current: solver.time(),
        });
    }
    while solver.time() < t_end {
        let event = solver.advance(t_end)?;
        on_step(solver, event.as_ref());
    }
    Ok(())
}

/// Sample the motion at the sorted times `times` (each ≥ the solver's current time), handing
/// every event on the way to `on_event`. The solver ends at the last requested time.
///
/// # Errors
/// [`Error::TimeBeforeCurrent`] when `times` is not sorted or starts before the solver's time;
/// whatever [`Solver::advance`] reports.
pub fn sample_at<S: Solver + ?Sized>(
    solver: &mut S,
    times: &[f64],
    mut on_event: impl FnMut(&Event),
) -> Result<Vec<Sample>> {
    let mut out = Vec::with_capacity(times.len());
    let mut previous = solver.time();
    for &tau in times {
        if tau < previous || tau.is_nan() {
            return Err(Error::TimeBeforeCurrent {
                requested: tau,
                current: previous,
            });
        }
        previous = tau;
        if tau == solver.time() {
            let s = solver.state();
            out.push(Sample {
                tau,
                y: s.y,
                v: s.v,
                phase: solver.phase(),
            });
            continue;
        }
        run_until(solver, tau, &mut on_event)?;
        out.push(solver.dense(tau));
    }
    Ok(out)
}

/// `count + 1` evenly spaced times from `from` to `to` inclusive, computed without
/// accumulating rounding.
pub fn grid(from: f64, to: f64, count: usize) -> Vec<f64> {
    if count == 0 {
        return vec![from];
    }
    (0..=count).map(|k| grid_time(from, to, count, k)).collect()
}

/// The k-th of the `count + 1` times of [`grid`].
fn grid_time(from: f64, to: f64, count: usize, k: usize) -> f64 {
    if count == 0 {
        from
    } else {
        from + (to - from) * (k as f64 / count as f64)
    }
}

/// One item of a [`Stream`]: a sample of the motion or an event, in time order.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub enum Record {
    /// The state at one of the requested times.
    Sample(Sample),
    /// A switching event, handed out before the samples that follow it.
    Event(Event),
}

/// The motion sampled at evenly spaced times, and its events, computed as they are asked
/// for: memory stays the same however long the run (see [`stream`]).
///
/// The samples are those of [`sample_at`] on [`grid`]`(from, to, count)`, bit for bit, and
/// every event comes before the first sample after it. After an error the stream ends.
pub struct Stream<'a, S: Solver + ?Sized> {
    solver: &'a mut S,
    cursor: Cursor,
}

/// Where a [`Stream`] stands on its grid of times, apart from the solver it advances (so that
/// an owner of a solver can stream it too: [`crate::report::TrajectoryRun`]).
#[derive(Debug, Clone, Copy)]
pub(crate) struct Cursor {
    from: f64,
    to: f64,
    count: usize,
    /// Index of the next sample.
    next: usize,
    /// Whether the solver has started advancing towards the next sample.
    advancing: bool,
    /// Whether an error ended the stream.
    ended: bool,
}

/// Stream `count + 1` samples at evenly spaced times from `from` to `to` (both included)
/// and the events between them, advancing `solver` piece by piece (see [`Stream`]).
///
/// ```
/// use stickslip::solver::{stream, Record};
/// use stickslip::{ExactSolver, Params, State};
/// let params = Params::new(0.0468, 0.7, 1.2).unwrap();
/// let mut solver = ExactSolver::new(params, State::default());
/// let (mut samples, mut events) = (0, 0);
/// for record in stream(&mut solver, 0.0, 30.0 * params.drive_period(), 6000).unwrap() {
///     match record.unwrap() {
///         Record::Sample(_) => samples += 1,
///         Record::Event(_) => events += 1,
///     }
/// }
/// assert_eq!(samples, 6001);
/// assert!(events > 60);
/// ```
///
/// # Errors
/// [`Error::TimeBeforeCurrent`] when `from` lies before the solver's time or `to` before
/// `from`; [`Error::HorizonTooLong`] when `to` lies beyond the time range the solvers
/// resolve ([`crate::limits::check_horizon`]). Solver failures come as items of the stream.
pub fn stream<S: Solver + ?Sized>(
    solver: &mut S,
    from: f64,
    to: f64,
    count: usize,
) -> Result<Stream<'_, S>> {
    let cursor = Cursor::new(&*solver, from, to, count)?;
    Ok(Stream { solver, cursor })
}

impl<S: Solver + ?Sized> Stream<'_, S> {
    /// The solver (its time is that of the last record handed out).
    pub fn solver(&self) -> &S {
        self.solver
    }
}

impl<S: Solver + ?Sized> Iterator for Stream<'_, S> {
    type Item = Result<Record>;

    fn next(&mut self) -> Option<Result<Record>> {
        self.cursor.next(self.solver)
    }
}

impl Cursor {
    /// A cursor over `count + 1` times from `from` to `to` for `solver` (see [`stream`]).
    pub(crate) fn new<S: Solver + ?Sized>(
        solver: &S,
        from: f64,
        to: f64,
        count: usize,
    ) -> Result<Self> {
        if !(from >= solver.time()) {
            return Err(Error::TimeBeforeCurrent {
                requested: from,
                current: solver.time(),
            });
        }
        if !(to >= from) {
            return Err(Error::TimeBeforeCurrent {
                requested: to,
                current: from,
            });
        }
        crate::limits::check_time(solver.params(), to)?;
        Ok(Self {
            from,
            to,
            count,
            next: 0,
            advancing: false,
            ended: false,
        })
    }

    /// Samples handed out so far.
    pub(crate) fn samples_done(&self) -> usize {
        self.next
    }

    /// The next record, advancing `solver` (the same solver every call).
    pub(crate) fn next<S: Solver + ?Sized>(&mut self, solver: &mut S) -> Option<Result<Record>> {
        if self.ended || self.next > self.count {
            return None;
        }
        let tau = grid_time(self.from, self.to, self.count, self.next);
        // As `sample_at`: a sample at the solver's own time is its state; otherwise advance,
        // one event at a time, and sample the interval that reaches the time.
        if !self.advancing && tau == solver.time() {
            self.next += 1;
            let s = solver.state();
            return Some(Ok(Record::Sample(Sample {
                tau,
                y: s.y,
                v: s.v,
                phase: solver.phase(),
            })));
        }
        self.advancing = true;
        while solver.time() < tau {
            match solver.advance(tau) {
                Ok(Some(event)) => return Some(Ok(Record::Event(event))),
                Ok(None) => {}
                Err(e) => {
                    self.ended = true;
                    return Some(Err(e));
                }
            }
        }
        self.advancing = false;
        self.next += 1;
        Some(Ok(Record::Sample(solver.dense(tau))))
    }
}
