//! Running to the steady state and recording one cycle.
//!
//! **Convergence.** The state is taken once per drive period at τ_k = kT (T = 2π/w), where
//! the drive phase is φ again (the stroboscopic map). The motion has settled on a cycle of
//! period p when |x_k − x_{k−p}| ≤ tol·scale (max norm over y and y') for p + 1 consecutive k,
//! i.e. over a whole cycle and once more; p is the smallest such period up to
//! [`SteadyOptions::max_period`], `scale` is the largest |y| or |y'| of the last strobes, at
//! least 1 (the kinetic friction force). A period p > 1 also needs the strobes p/d apart to
//! differ by more than √tol·scale for every divisor d: otherwise the motion is still
//! converging, alternately, to a cycle of the shorter period. An oscillator stuck for a whole period without an
//! event has x_k = x_{k−1} exactly, so "stuck for ever" (β + |y| ≤ μs) is found after two
//! periods without a special case. Without a period within [`SteadyOptions::max_periods`]
//! the motion is called non-periodic.
//!
//! **Settling by Newton**: see the `newton` module (a stable fixed point of the strobe map,
//! found by Newton and checked against the trajectory's own steps, settles the motion early;
//! the exact solver's map, or a smooth law's at the solvers' options).
//!
//! **Motions that do not repeat** are then measured, when the solver follows the exact
//! piecewise-linear model ([`Solver::is_exact`]) and [`SteadyOptions::lyapunov`] asks for it:
//! the Lyapunov exponents of the motion from the final state of the record, by the exact
//! tangent dynamics ([`crate::stability::lyapunov_exponents`]); with a smooth law (a factory
//! whose [`super::SolverFactory::smooth_dynamics`] has them, as an experiment's with Shockley
//! diodes) by the tangent dynamics of the stiff solver's computed solution
//! ([`crate::stability::ShockleyDynamics::lyapunov_exponents`]). A largest exponent positive
//! beyond its error makes the motion [`MotionClass::Chaotic`]; otherwise it keeps its class
//! from the event log, with the exponents in [`SteadyState::lyapunov`] (a motion contracting
//! onto a periodic attractor not reached within the cap, or one on a torus, or one not
//! settled). Motions that repeat are not measured: they cost what they always did.
//!
//! **Recording**: see the `record` module (p whole periods, their events, strobes and
//! samples, from the strobe the solver stands at).
//!
//! **One search for every front end.** A map's point (which computes no spectrum), a sweep's
//! first step, `stickslip steady`, Python's `steady` and the lab's steady endpoint all settle
//! a point from its initial state by [`steady_state_from`] with the experiment's factory and
//! options; since the spectrum changes nothing in the record, a map's point is the steady
//! state of the same point to the bit, whether it settled by Newton or by repetition (test
//! `a_map_point_is_the_steady_state_of_the_same_point`). That is why Newton can be on by
//! default: the cycle it records from the fixed point differs from the plain iteration's in
//! the last bits (within 10⁻⁹ relative on the paper's map), but the same way everywhere.

use super::classify::MotionClass;
use super::newton::NewtonSettling;
use super::options::SteadyOptions;
use super::record::record;
use super::state::SteadyState;
use super::SolverFactory;
use crate::cancel::Cancel;
use crate::error::{Error, Result};
use crate::exact::ExactSolver;
use crate::params::{Params, State};
use crate::solver::{run_until, Event, Solver};
use crate::stability::strobe::image_along;
use crate::stability::{
    lyapunov_exponents, lyapunov_exponents_monitored, Dynamics, NonperiodicClassification,
    NonperiodicVerdict, StabilityError,
};
use std::collections::VecDeque;

/// Whether the motion is self-excited: a belt moves and nothing drives the block (see
/// [`super::self_excited`], which finds its own period).
pub(crate) fn is_self_excited(params: &Params) -> bool {
    params.vb != 0.0 && params.beta == 0.0
}

/// Largest |component| difference of two states.
pub(super) fn distance(a: State, b: State) -> f64 {
    (a.y - b.y).abs().max((a.v - b.v).abs())
}

/// Time of strobe k: kT computed in one rounding.
pub(super) fn strobe(k: u64, period: f64) -> f64 {
    k as f64 * period
}

/// How far the stroboscopic map got: the period found (if any), where the solver stands.
pub(super) struct Settled {
    /// Period p, or None at the cap.
    pub(super) found: Option<usize>,
    /// Drive periods simulated in all (over restarts).
    pub(super) periods_run: usize,
    /// Index k of the strobe τ = kT at which the current solver stands.
    pub(super) strobe_index: u64,
    /// Scale of the state for the tolerances.
    pub(super) scale: f64,
    /// Events per period over the last cycle (for the automatic sample count).
    pub(super) events_per_period: f64,
    /// The spectral radius ρ of the monodromy of the orbit Newton's method settled the motion
    /// on (the record starts at its fixed point, which the record's own period must
    /// confirm); `None` when settled by repetition.
    pub(super) by_newton: Option<f64>,
}

/// Where to restart after an extrapolation of the stroboscopic map, if the last strobes
/// (oldest first) show linear convergence to a fixed point (see [`SteadyOptions::accelerate`]).
fn extrapolate(history: &VecDeque<State>, tolerance: f64, scale: f64) -> Option<State> {
    let n = history.len();
    if n < 5 {
        return None;
    }
    // The last five strobes and their four differences, on the stack (this runs after every
    // strobe of a transient).
    let x: [[f64; 2]; 5] = std::array::from_fn(|i| {
        let s = history[n - 5 + i];
        [s.y, s.v]
    });
    let d: [[f64; 2]; 4] = std::array::from_fn(|i| [x[i + 1][0] - x[i][0], x[i + 1][1] - x[i][1]]);
    let norm = |a: [f64; 2]| a[0].abs().max(a[1].abs());
    let last = d[3];
    // Nearly converged already: plain iteration finishes in a few periods.
    if norm(last) <= 1e3 * tolerance * scale {
        return None;
    }
    // Fit d_{i+1} = J d_i on (d0 → d1, d1 → d2); check it predicts d3 from d2.
    let det0 = d[0][0] * d[1][1] - d[0][1] * d[1][0];
    let step = if det0.abs() > 1e-6 * norm(d[0]) * norm(d[1]) {
        // J = [d1 d2] [d0 d1]^{-1}
        let inv = [
            [d[1][1] / det0, -d[1][0] / det0],
            [-d[0][1] / det0, d[0][0] / det0],
        ];
        let j = [
            [
                d[1][0] * inv[0][0] + d[2][0] * inv[1][0],
                d[1][0] * inv[0][1] + d[2][0] * inv[1][1],
            ],
            [
                d[1][1] * inv[0][0] + d[2][1] * inv[1][0],
                d[1][1] * inv[0][1] + d[2][1] * inv[1][1],
            ],
        ];
        let apply = |m: [[f64; 2]; 2], a: [f64; 2]| {
            [
                m[0][0] * a[0] + m[0][1] * a[1],
                m[1][0] * a[0] + m[1][1] * a[1],
            ]
        };
        let predicted = apply(j, d[2]);
        if norm([predicted[0] - last[0], predicted[1] - last[1]]) > 0.02 * norm(last) {
            return None;
        }
        // Both eigenvalues of J well inside the unit circle.
        let (tr, det) = (j[0][0] + j[1][1], j[0][0] * j[1][1] - j[0][1] * j[1][0]);
        let disc = tr * tr - 4.0 * det;
        let radius = if disc >= 0.0 {
            0.5 * (tr.abs() + disc.sqrt())
        } else {
            det.sqrt()
        };
        if !(radius < 0.98) {
            return None;
        }
        // x* = x + (I − J)^{-1} J d3.
        let jd = apply(j, last);
        let (a, b, c, e) = (1.0 - j[0][0], -j[0][1], -j[1][0], 1.0 - j[1][1]);
        let det_ij = a * e - b * c;
        [
            (e * jd[0] - b * jd[1]) / det_ij,
            (a * jd[1] - c * jd[0]) / det_ij,
        ]
    } else {
        // The differences are parallel (one real mode dominates): scalar ratio along them.
        let dot = |a: [f64; 2], b: [f64; 2]| a[0] * b[0] + a[1] * b[1];
        let r = dot(d[2], d[1]) / dot(d[1], d[1]);
        let predicted = [r * d[2][0], r * d[2][1]];
        if !(r.abs() < 0.98)
            || norm([predicted[0] - last[0], predicted[1] - last[1]]) > 0.02 * norm(last)
        {
            return None;
        }
        let f = r / (1.0 - r);
        [f * last[0], f * last[1]]
    };
    // Only small corrections: far from the fixed point the linear model is not to be trusted.
    if !(norm(step) <= 1e-2 * scale) {
        return None;
    }
    Some(State {
        y: x[4][0] + step[0],
        v: x[4][1] + step[1],
    })
}

/// A solver, and possibly the means to replace it by one started from another state.
trait Holder {
    /// The solver type.
    type S: Solver + ?Sized;
    /// The current solver.
    fn solver(&mut self) -> &mut Self::S;
    /// Replace the solver by one starting from `state` at τ = 0; false if not possible.
    fn restart(&mut self, state: State) -> Result<bool>;
    /// Whether [`Holder::restart`] can start a new solver.
    fn can_restart(&self) -> bool;
    /// The token the solvers check (charged with the work of Newton's tangent periods too).
    fn cancel(&self) -> Cancel;
    /// The strobe map of a smooth law at the solvers' options, for Newton settling
    /// ([`Dynamics::settling`]); `None` for the exact solver or without a factory.
    fn settling(&self) -> Option<Box<dyn Dynamics>> {
        None
    }
}

/// A solver that cannot be restarted.
struct Plain<'a, S: Solver + ?Sized>(&'a mut S);

impl<S: Solver + ?Sized> Holder for Plain<'_, S> {
    type S = S;
    fn solver(&mut self) -> &mut S {
        self.0
    }
    fn restart(&mut self, _: State) -> Result<bool> {
        Ok(false)
    }
    fn can_restart(&self) -> bool {
        false
    }
    fn cancel(&self) -> Cancel {
        Cancel::never()
    }
}

/// Solvers from a factory.
struct FromFactory<'a, F: SolverFactory + ?Sized> {
    factory: &'a F,
    params: Params,
    solver: Box<dyn Solver + Send>,
}

impl<F: SolverFactory + ?Sized> Holder for FromFactory<'_, F> {
    type S = dyn Solver + Send + 'static;
    fn solver(&mut self) -> &mut (dyn Solver + Send + 'static) {
        self.solver.as_mut()
    }
    fn restart(&mut self, state: State) -> Result<bool> {
        match exact_of(self.solver.as_mut()) {
            // The exact solver starts again in place: what the factory built, without building
            // it again.
            Some(exact) if *exact.params() == self.params => {
                exact.restart_at(State::new(state.y, state.v)?, None);
            }
            _ => self.solver = self.factory.make(self.params, state)?,
        }
        Ok(true)
    }
    fn can_restart(&self) -> bool {
        true
    }
    fn cancel(&self) -> Cancel {
        self.factory.cancel()
    }
    fn settling(&self) -> Option<Box<dyn Dynamics>> {
        self.factory.smooth_dynamics()?.settling()
    }
}

/// Iterate the stroboscopic map until it repeats (see the module documentation). With
/// `accelerate`, extrapolate when the convergence is linear and restart the solver there.
fn run_to_cycle<H: Holder>(
    holder: &mut H,
    params: &Params,
    options: &SteadyOptions,
    accelerate: bool,
) -> Result<Settled> {
    let period = params.drive_period();
    let max_period = options.max_period;

    // First strobe at or after the solver's time.
    let now = holder.solver().time();
    let mut base = (now / period).ceil().max(0.0) as u64;
    if strobe(base, period) < now {
        base += 1;
    }
    run_until(holder.solver(), strobe(base, period), |_| {})?;

    let mut history: VecDeque<State> = VecDeque::with_capacity(max_period + 1);
    history.push_back(holder.solver().state());
    // The largest |y| or |y'| of `history`, at least 1 (kept as strobes come and go, and
    // taken again over the whole history only when the largest leaves it).
    let magnitude = |s: &State| s.y.abs().max(s.v.abs());
    let largest_of = |h: &VecDeque<State>| h.iter().map(magnitude).fold(1.0f64, f64::max);
    let mut largest = largest_of(&history);
    // Consecutive strobes at which x_k matched x_{k−p}, per lag p.
    // (On the stack: a period is at most `MAX_PERIOD`.)
    let mut passes = [0usize; MAX_PERIOD + 1];
    // |x_k − x_{k−lag}| for lag = 1, 2, …: one buffer for the whole run.
    let mut gaps = [0.0f64; MAX_PERIOD];
    // The events of the period just run (times from τ = 0 of the solver), and how many
    // events each of the last periods had (period k at k mod MAX_PERIOD; 0 before the first).
    // (Room for a few events a period: most motions never grow it.)
    let mut last: Vec<Event> = Vec::with_capacity(16);
    let mut counts = [0usize; MAX_PERIOD];
    let mut found = None;
    let mut scale = 1.0f64;
    let mut local = 0usize;
    let mut restarts = 0usize;
    let mut periods_run = 0;
    // (The exact solver's own map, or a smooth law's at the solvers' options.)
    let mut newton = if !(accelerate && options.newton && holder.can_restart()) {
        None
    } else if holder.solver().is_exact() {
        Some(NewtonSettling::new(None))
    } else {
        holder.settling().map(|map| NewtonSettling::new(Some(map)))
    };
    // Newton's periods are counted in `periods_to_settle` of a motion that settles; they do
    // not shorten the trajectory, so a motion that does not settle is run and recorded as
    // without Newton.
    let spent = |newton: &Option<NewtonSettling>| newton.as_ref().map_or(0, |n| n.periods);
    // A Newton attempt decided at the last strobe x_k: x_k, the strobe step that decided it,
    // and the events of the period that ended at x_k (times from its start). The image of x_k
    // is computed along the trajectory's next period (`image_along`) instead of by a run of
    // its own, and the attempt made at the next strobe, with the check of the step to x_k
    // that would have followed it at x_k.
    let mut pending: Option<(State, f64, Vec<Event>)> = None;
    while periods_run < options.max_periods {
        periods_run += 1;
        local += 1;
        let next = strobe(base + local as u64, period);
        last.clear();
        let along = match (&pending, exact_of(holder.solver())) {
            (Some(_), Some(exact)) => {
                match image_along(exact, next, |e| last.push(*e)) {
                    Ok(image) => Some(Some(image)),
                    // (The period has run all the same; only its Jacobian is not finite.)
                    Err(Error::Stability(StabilityError::NonFiniteJacobian { .. })) => Some(None),
                    Err(e) => return Err(e),
                }
            }
            _ => {
                run_until(holder.solver(), next, |e| last.push(*e))?;
                None
            }
        };
        let events_last = last.len();
        counts[local % MAX_PERIOD] = events_last;
        let x = holder.solver().state();
        scale = largest.max(magnitude(&x));
        let limit = options.tolerance * scale;
        // A cycle of p > 1 periods must not be close to one of a divisor of p: a slow
        // alternating transient towards a 1-cycle (eigenvalue near −1) repeats after two
        // periods long before it repeats after one.
        let distinct = options.tolerance.sqrt() * scale;
        let lags = history.len().min(max_period);
        for (gap, h) in gaps.iter_mut().zip(history.iter().rev()).take(lags) {
            *gap = distance(x, *h);
        }
        // (A cycle is found only at a strobe where some lag repeats.)
        let mut repeated = false;
        for lag in 1..=lags {
            let repeats = gaps[lag - 1] <= limit
                && (1..lag)
                    .filter(|d| lag % d == 0)
                    .all(|d| gaps[d - 1] > distinct);
            passes[lag] = if repeats { passes[lag] + 1 } else { 0 };
            repeated |= repeats;
        }
        history.push_back(x);
        largest = scale;
        if history.len() > max_period.max(5) {
            let gone = history.pop_front().map_or(0.0, |s| magnitude(&s));
            if gone == largest {
                largest = largest_of(&history);
            }
        }
        if let Some(p) = repeated
            .then(|| (1..=max_period).find(|&p| passes[p] > p))
            .flatten()
        {
            found = Some(p);
            break;
        }
        let budget = options.max_periods - periods_run;
        // The events of the period just run, times from its first strobe.
        let last_start = strobe(base + local as u64 - 1, period);
        let last_period = last.iter().map(|e| Event {
            tau: e.tau - last_start,
            ..*e
        });
        let before = spent(&newton);
        // (Only Newton's runs take the trajectory's hints.)
        let hints = newton.is_some().then(|| holder.solver().hints()).flatten();
        // Where the strobes will restart after extrapolation (decided by the strobes alone).
        let target = (accelerate && restarts < MAX_RESTARTS)
            .then(|| extrapolate(&history, options.tolerance, scale))
            .flatten();
        let mut accepted = None;
        if let Some(n) = newton.as_mut() {
            let len = history.len();
            if let Some((x_k, step, events)) = pending.take() {
                n.attempt(params, x_k, step, hints, along);
                // (This check cannot accept: it is the first after the attempt.)
                n.check(params, history[len - 3], x_k, events.into_iter());
            }
            match n.wants_attempt(&history, budget) {
                // The image along the next period, unless the strobes restart elsewhere (or
                // the solver cannot carry the tangent).
                Some(step) if target.is_none() && exact_of(holder.solver()).is_some() => {
                    pending = Some((x, step, last_period.collect()));
                }
                Some(step) => {
                    n.attempt(params, x, step, hints, None);
                    accepted = n.check(params, history[len - 2], x, last_period);
                    // (A smooth law's: the map's step from x, in place of the trajectory's
                    // next period.)
                    if accepted.is_none() {
                        accepted = n.check_first_image();
                    }
                }
                None => accepted = n.check(params, history[len - 2], x, last_period),
            }
        }
        let tangent = spent(&newton) - before;
        // (A smooth law's Newton runs on solvers of the factory's law, which charge their
        // steps themselves.)
        if tangent > 0 && !newton.as_ref().is_some_and(NewtonSettling::is_smooth) {
            // Newton's periods run on a tangent solver of their own: charge them to the token
            // of the factory's solvers like the strobes' (a step an event, and one a period),
            // so that budgets, deadlines and cancellation see them.
            holder
                .cancel()
                .charge((tangent * (events_last + 1)) as u64)?;
        }
        if let Some(orbit) = accepted {
            // Record the cycle from the orbit's strobe, on a new solver started there.
            if holder.restart(orbit.state)? {
                if let Some(hints) = newton.as_ref().and_then(|n| n.hints).or(hints) {
                    holder.solver().take_hints(hints);
                }
                let tangent_periods = spent(&newton);
                return Ok(Settled {
                    found: Some(1),
                    periods_run: periods_run + tangent_periods,
                    strobe_index: 0,
                    scale: scale.max(orbit.state.y.abs()).max(orbit.state.v.abs()),
                    events_per_period: orbit.events.len() as f64,
                    by_newton: Some(orbit.multipliers[0].modulus()),
                });
            }
        }
        if let Some(target) = target {
            if holder.restart(target)? {
                restarts += 1;
                base = 0;
                local = 0;
                history.clear();
                history.push_back(holder.solver().state());
                largest = largest_of(&history);
                passes.iter_mut().for_each(|p| *p = 0);
                counts = [0; MAX_PERIOD];
            }
        }
    }
    let cycle = found.unwrap_or(max_period);
    // (The last `cycle` periods since the start or the last restart.)
    let events: usize = (local.saturating_sub(cycle) + 1..=local)
        .map(|m| counts[m % MAX_PERIOD])
        .sum();
    Ok(Settled {
        found,
        periods_run: periods_run + if found.is_some() { spent(&newton) } else { 0 },
        strobe_index: base + local as u64,
        scale,
        events_per_period: events as f64 / cycle as f64,
        by_newton: None,
    })
}

/// The exact solver `solver` is, if it is one.
fn exact_of<S: Solver + ?Sized>(solver: &mut S) -> Option<&mut ExactSolver> {
    solver.as_any_mut()?.downcast_mut::<ExactSolver>()
}

/// The longest period [`SteadyOptions::max_period`] allows (the repetition test's counters
/// live on the stack; test `the_longest_period_is_the_options_limit`).
const MAX_PERIOD: usize = 64;

/// Most extrapolations of the stroboscopic map in one run.
const MAX_RESTARTS: usize = 6;

/// Check that the longest run the options allow, from time `start` (at most
/// `max_periods` periods to settle and `max_period` to record), and the Lyapunov measurement
/// of a motion that does not repeat ([`SteadyOptions::lyapunov`], a run of its own from τ = 0)
/// stay within the time range the solvers resolve ([`crate::limits::check_horizon`]).
///
/// # Errors
/// [`Error::HorizonTooLong`].
pub fn check_horizon(params: &Params, options: &SteadyOptions, start: f64) -> Result<()> {
    let periods = (options.max_periods + options.max_period + 1) as f64
        + (start / params.drive_period()).ceil();
    crate::limits::check_horizon(params, periods)?;
    // The measurement of a motion that does not repeat starts again at τ = 0.
    match options.lyapunov {
        Some(l) => l.check_horizon(params),
        None => Ok(()),
    }
}

/// Run `solver` to its steady state and record one cycle.
///
/// The solver's own parameters ([`Solver::params`]) define the strobes (drive frequency and
/// phase) and the gain (β). The solver may start at any time; strobes are at whole multiples
/// of the drive period. Afterwards the solver stands at the end of the record. This form
/// never extrapolates ([`SteadyOptions::accelerate`] needs [`steady_state_from`], which can
/// start new solvers).
///
/// ```
/// use stickslip::steady::{steady_state, MotionClass, SteadyOptions};
/// use stickslip::{ExactSolver, Params, State};
/// let params = Params::new(0.0468, 0.9, 1.6).unwrap();
/// let mut solver = ExactSolver::new(params, State::default());
/// let steady = steady_state(&mut solver, &SteadyOptions::default()).unwrap();
/// assert_eq!(steady.class, MotionClass::Sliding);
/// assert_eq!(steady.period, Some(1));
/// assert!(steady.symmetric);
/// ```
///
/// # Errors
/// [`Error::InvalidParameter`] for invalid options; [`Error::HorizonTooLong`] when
/// `max_periods` drive periods reach beyond the time range the solvers resolve
/// ([`crate::limits`]); whatever the solver reports.
pub fn steady_state<S: Solver + ?Sized>(
    solver: &mut S,
    options: &SteadyOptions,
) -> Result<SteadyState> {
    let options = options.validate()?;
    let params = *solver.params();
    if is_self_excited(&params) {
        return super::self_excited::self_excited_state(solver, &options);
    }
    check_horizon(&params, &options, solver.time())?;
    let mut holder = Plain(solver);
    let settled = run_to_cycle(&mut holder, &params, &options, false)?;
    let exact = holder.0.is_exact();
    let steady = record(holder.0, &params, &options, &settled)?;
    measure(steady, exact, None, &options, &Cancel::never())
}

/// The steady state reached from `initial` (at τ = 0) by solvers from `factory`.
///
/// With [`SteadyOptions::accelerate`] (the default), once the stroboscopic map converges
/// linearly to a fixed point, the fixed point is extrapolated from the last strobes and a new
/// solver is started there; the cycle is then recognised by the same test as without
/// extrapolation, on the new solver's strobes, so the result satisfies the same tolerance.
/// `periods_to_settle` counts every period simulated.
///
/// # Errors
/// [`Error::InvalidParameter`] for invalid options or parameters; [`Error::HorizonTooLong`]
/// as [`steady_state`]; whatever the solvers report.
pub fn steady_state_from<F: SolverFactory + ?Sized>(
    factory: &F,
    params: &Params,
    initial: State,
    options: &SteadyOptions,
) -> Result<SteadyState> {
    settle_from(factory, params, initial, &options.validate()?)
}

/// [`steady_state_from`] with `options` already validated (a map's points share them: they
/// are checked once, when the map is built).
pub(crate) fn settle_from<F: SolverFactory + ?Sized>(
    factory: &F,
    params: &Params,
    initial: State,
    options: &SteadyOptions,
) -> Result<SteadyState> {
    if is_self_excited(params) {
        return super::self_excited::settle_self_excited(factory, params, initial, options);
    }
    check_horizon(params, options, 0.0)?;
    let mut holder = FromFactory {
        factory,
        params: *params,
        solver: factory.make(*params, initial)?,
    };
    let settled = run_to_cycle(&mut holder, params, options, options.accelerate)?;
    let exact = holder.solver.is_exact();
    let steady = record(holder.solver.as_mut(), params, options, &settled)?;
    if settled.by_newton.is_some_and(|radius| {
        distance(steady.strobes[0], steady.strobes[1])
            > options.tolerance * settled.scale * (1.0 - radius)
    }) {
        // Newton's fixed point ends in a step the map was not evaluated at (see
        // `find_periodic_orbit_finished`): the period recorded from it must repeat to
        // tol·scale·(1 − ρ), which puts it within tol·scale of the orbit (to first order,
        // |x − x*| ≤ |P(x) − x|/(1 − ρ)), or the point is settled without Newton.
        drop(holder);
        return settle_from(factory, params, initial, &options.with_newton(false));
    }
    let smooth = if exact {
        None
    } else {
        factory.smooth_dynamics()
    };
    measure(steady, exact, smooth.as_deref(), options, &factory.cancel())
}

/// Measure a motion that did not repeat (see the module documentation): by the exact tangent
/// dynamics when the solver is `exact`, else by `smooth`'s, else not.
fn measure(
    mut steady: SteadyState,
    exact: bool,
    smooth: Option<&dyn Dynamics>,
    options: &SteadyOptions,
    cancel: &Cancel,
) -> Result<SteadyState> {
    let Some(lyapunov) = options
        .lyapunov
        .filter(|_| (exact || smooth.is_some()) && steady.period.is_none())
    else {
        return Ok(steady);
    };
    let measured = if let (false, Some(dynamics)) = (exact, smooth) {
        dynamics
            .lyapunov_exponents(&steady.params, steady.final_state(), &lyapunov, cancel)
            .map_err(|e| cancel.stopped().map_or(e, |stop| stop.error()))
    } else if cancel.is_never() {
        lyapunov_exponents(&steady.params, steady.final_state(), &lyapunov)
    } else {
        lyapunov_exponents_monitored(&steady.params, steady.final_state(), &lyapunov, cancel)
            .map_err(|e| cancel.stopped().map_or(e, |stop| stop.error()))
    };
    match measured {
        Ok(exponents) => {
            let c = NonperiodicClassification::new(exponents, lyapunov.significance);
            if c.verdict == NonperiodicVerdict::Chaotic {
                steady.class = MotionClass::Chaotic;
            }
            steady.lyapunov = Some(c);
            Ok(steady)
        }
        Err(Error::Stability(StabilityError::NonFiniteJacobian { .. })) => Ok(steady),
        Err(e) => Err(e),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_longest_period_is_the_options_limit() {
        assert!(SteadyOptions::default().with_max_period(MAX_PERIOD).is_ok());
        assert!(SteadyOptions::default()
            .with_max_period(MAX_PERIOD + 1)
            .is_err());
    }
}
