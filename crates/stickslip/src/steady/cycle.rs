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
//! **Settling by Newton** ([`SteadyOptions::newton`], on by default; exact solver, with a
//! factory and [`SteadyOptions::accelerate`]). From the third strobe x_2 on, whenever the strobe
//! step |x_k − x_{k−1}| is shorter than the one before (and at most a quarter of the step at the
//! last attempt, at most three attempts of six steps each), Newton's method on the strobe map
//! ([`crate::stability::find_periodic_orbit`], period 1) is started from x_k. Its first
//! image P(x_k), with the Jacobian, is the trajectory's own next period, run with the tangent
//! dynamics along (`stability::strobe::image_along`): the attempt is made at the next strobe,
//! followed by the checks below of the step to x_k that would have followed it at x_k, so
//! every decision is the one an attempt at x_k would take. A stable fixed
//! point x* (monodromy M, spectral radius ρ < 1) is kept, and the motion is settled on it as
//! soon as two consecutive strobe steps (three strobes) each pass two checks:
//!
//! ```text
//! |e_k − M e_{k−1}| ≤ ½(1 − ρ)|e_{k−1}|   and   |e_k| < |e_{k−1}|,      e = x − x* (max norm),
//! ```
//!
//! and the period just run went through the orbit's events, in order and of the same kinds,
//! each within half its margin of the orbit's (see `same_events`: the net force at a turn is
//! beyond μs and at a stop inside it, by a margin the trajectory's event must not use up).
//!
//! Why: P(x* + e) = x* + M e + R(e), where on the smooth piece of P around x* (the same
//! sequence of events) the remainder is quadratic, |R(e)| ≤ ½K|e|². The first condition
//! measures R(e_{k−1}) = e_k − M e_{k−1}; taking it as the estimate of K, every e with
//! |e| ≤ |e_{k−1}| has |R(e)| ≤ ½(1 − ρ)|e|, so P differs from its linearisation by less than
//! half the spectral gap and contracts at a rate of at most (1 + ρ)/2 < 1 there (in a norm
//! adapted to M; the second condition asks the distance to have shrunk in the max norm as
//! well). The comparison of events asks the trajectory to be on that smooth piece: a stop
//! that appears or vanishes, or a turn that becomes a stop, is where the piece ends (the
//! basin of a sliding orbit can end where a stop appears, however linear one strobe step
//! looks). Two consecutive steps, because one can follow the linearisation by chance far
//! from the orbit. This is still a check, not a proof: K comes from the steps seen, and a
//! grazing (a velocity minimum mid-swing reaching zero) that the trajectory has not yet
//! touched is not seen. What shows it holds is the comparison with the plain iteration
//! (`crates/stickslip/tests/newton_settling.rs`): the paper's 400 × 400 map (same classes,
//! periods, stops and symmetry at all 160 000 points, gains to 2·10⁻¹⁰ relative), and the
//! chaos map at ζ = 0, μs = 3 (w 0.2–0.6, β 3–14), where the check on one step and without
//! the events had settled 34 cells on orbits the trajectory leaves. The cycle is then
//! recorded from x*, with period 1, on the search's solver started again there in place;
//! motions of longer period, and points where Newton fails or the checks never pass, are
//! settled by the repetition test as before. Newton's iteration stops at a residual of
//! 10⁻⁶·max(1, |x|)·max(1, |M|) where ρ ≤ 0.9 (10⁻⁸ where the orbit contracts more slowly)
//! and takes one more step without evaluating the map there (its error is quadratic in that
//! residual, about 10⁻¹², a hundredth of the default repetition tolerance): that saves the
//! map's last evaluations. The recorded period checks
//! x*: it must repeat to tol·scale·(1 − ρ) (which puts x* within about tol·scale of the
//! orbit), or the point is settled again without Newton.
//!
//! **What the solvers learn of the motion** ([`crate::Hints`]: how long its slides of each
//! kind last, where the exact solver's search for the next velocity zero looks first) is
//! handed from the trajectory to Newton's evaluations of the map, from each evaluation to the
//! next, and from the last to the solver that records the cycle: each would otherwise start
//! from guesses of the drive frequency alone. The hints change where the search looks, not
//! what it proves; the events it finds are the same to rounding.
//!
//! `periods_to_settle` of a motion that settles counts the strobe periods run and the periods
//! of the Newton attempts (one per step, and the image at the guess where the trajectory did
//! not compute it along its own period). The attempts do not
//! shorten the trajectory: a motion that does not settle runs [`SteadyOptions::max_periods`]
//! strobe periods and is recorded exactly as without Newton (its `periods_to_settle` is the
//! cap); an attempt is made only while the cap leaves room for its longest run.
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
//! **Recording.** Then p whole periods (or `max_period` periods for a non-periodic motion) are
//! recorded: the exact event log, the states at every strobe and half-period, and optionally
//! N samples per period of the dense output for the [`Spectrum`]. Extremes of y are exact:
//! y has its extremes where y' = 0, that is at events, which the log holds with their exact y.
//! The solver is advanced to the same half-period and period ends with or without the samples,
//! which are read from the dense output of the intervals it advances through, and the
//! extremes are taken from the events and strobes alone: the record, and with it the class,
//! period, stops, symmetry and gain, does not depend on [`SteadyOptions::spectrum`].
//!
//! **One search for every front end.** A map's point (which computes no spectrum), a sweep's
//! first step, `stickslip steady`, Python's `steady` and the lab's steady endpoint all settle
//! a point from its initial state by [`steady_state_from`] with the experiment's factory and
//! options; since the spectrum changes nothing in the record, a map's point is the steady
//! state of the same point to the bit, whether it settled by Newton or by repetition (test
//! `a_map_point_is_the_steady_state_of_the_same_point`). That is why Newton can be on by
//! default: the cycle it records from the fixed point differs from the plain iteration's in
//! the last bits (within 10⁻⁹ relative on the paper's map), but the same way everywhere.
//!
//! **Symmetry.** The equation is unchanged by (y, y', τ) → (−y, −y', τ + T/2), so a cycle is
//! symmetric when the state half a period after a strobe is minus the state at some strobe of
//! the cycle. Symmetric motions have no even harmonics.
//!
//! **Samples for the spectrum.** Between events y is smooth but y'' jumps at every event (by 2
//! at a turn), so the Fourier amplitudes of y fall off like J/(πk³) with J the sum of the jumps
//! of d²y/dθ² (θ = wτ) over a period, and aliasing with N samples per period perturbs the low
//! harmonics by about 0.8·J/N³. By default N is the smallest power of two (512 to 65536) that
//! makes this 10⁻¹⁰·scale, with J bounded from the events of the cycle by (1 + μs)/w² per event.

use super::classify::{classify, MotionClass};
use super::extremes::velocity_zeros;
use super::options::SteadyOptions;
use super::spectrum::Spectrum;
use super::state::SteadyState;
use super::SolverFactory;
use crate::cancel::Cancel;
use crate::error::{Error, Result};
use crate::exact::ExactSolver;
use crate::params::{Params, State};
use crate::solver::{run_steps, run_until, Event, EventKind, Hints, Phase, Sample, Solver};
use crate::stability::periodic_orbit::{find_periodic_orbit_finished, Finish};
use crate::stability::strobe::image_along;
use crate::stability::{
    lyapunov_exponents, lyapunov_exponents_monitored, Dynamics, NewtonOptions,
    NonperiodicClassification, NonperiodicVerdict, PeriodicOrbit, Stability, StabilityError,
    StrobeImage,
};
use std::collections::VecDeque;

/// Whether the motion is self-excited: a belt moves and nothing drives the block (see
/// [`super::self_excited`], which finds its own period).
pub(crate) fn is_self_excited(params: &Params) -> bool {
    params.vb != 0.0 && params.beta == 0.0
}

/// Largest |component| difference of two states.
fn distance(a: State, b: State) -> f64 {
    (a.y - b.y).abs().max((a.v - b.v).abs())
}

/// Time of strobe k: kT computed in one rounding.
fn strobe(k: u64, period: f64) -> f64 {
    k as f64 * period
}

/// Samples per period for an aliasing error of the low harmonics below 1e-10·scale, from the
/// number of events per period (see the module documentation).
fn auto_samples(events_per_period: f64, params: &Params, harmonics: usize, scale: f64) -> usize {
    let jumps = events_per_period.max(2.0) * (1.0 + params.mu_s) / (params.w * params.w);
    let needed = harmonics as f64 + (0.8 * jumps / (1e-10 * scale)).cbrt();
    (needed.ceil() as usize)
        .next_power_of_two()
        .clamp(512, 1 << 16)
}

/// How far the stroboscopic map got: the period found (if any), where the solver stands.
struct Settled {
    /// Period p, or None at the cap.
    found: Option<usize>,
    /// Drive periods simulated in all (over restarts).
    periods_run: usize,
    /// Index k of the strobe τ = kT at which the current solver stands.
    strobe_index: u64,
    /// Scale of the state for the tolerances.
    scale: f64,
    /// Events per period over the last cycle (for the automatic sample count).
    events_per_period: f64,
    /// The spectral radius ρ of the monodromy of the orbit Newton's method settled the motion
    /// on (the record starts at its fixed point, which the record's own period must
    /// confirm); `None` when settled by repetition.
    by_newton: Option<f64>,
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
}

/// Newton's method on the stroboscopic map (see [`SteadyOptions::newton`] and the module
/// documentation): the stable period-1 orbit it found, and whether the trajectory has been
/// seen within its basin.
struct NewtonSettling {
    /// The orbit found by the last attempt (stable), if any.
    orbit: Option<PeriodicOrbit>,
    /// Its events, as the comparison with the trajectory's reads them.
    orbit_events: Vec<OrbitEvent>,
    /// The hints of the last evaluation of the map near the orbit, for the solver that
    /// records the cycle from it.
    hints: Option<Hints>,
    /// Attempts made.
    attempts: usize,
    /// Tangent periods run by the attempts (counted in `periods_to_settle`).
    periods: usize,
    /// Consecutive strobe steps that passed the checks of the basin.
    passes: usize,
    /// Strobe step |x_k − x_{k−1}| when Newton was last tried (a new attempt waits until the
    /// step has shrunk well below it).
    last_step: f64,
}

/// Consecutive strobe steps that must pass the checks of the basin ([`within_basin`] and
/// [`same_events`]) before the orbit is accepted: one step can follow the linearisation by
/// chance far from the orbit (ζ = 0, μs = 3, w = 0.26, β = 7.25 from rest: the second strobe
/// passes both checks of a stable period-1 stick-slip orbit, and the trajectory goes on to
/// a period-3 cycle).
const BASIN_PASSES: usize = 2;

/// Most Newton attempts per steady state.
const MAX_NEWTON_ATTEMPTS: usize = 3;

/// Newton's options for settling: an attempt that does not converge quickly is abandoned (the
/// trajectory goes on), so few steps and halvings.
const SETTLING_NEWTON: NewtonOptions = NewtonOptions {
    tolerance: 1e-8,
    max_iterations: 6,
    max_halvings: 2,
    neutral_band: 1e-9,
};

/// Where the orbit contracts by 0.9 a period or faster, Newton's iteration for settling stops
/// at a residual of 1e-6: the finishing step then lands within about 1e-12 of the orbit
/// (quadratic in the residual), and the record's repetition check, to tol·scale·(1 − ρ),
/// passes. A slower orbit needs x* closer: the iteration goes on to 1e-8.
const SETTLING_LOOSE: (f64, f64) = (1e-6, 0.9);

/// Most periods one attempt counts: its steps with every halving, and the first image.
const MOST_NEWTON_PERIODS: usize =
    SETTLING_NEWTON.max_iterations * (1 + SETTLING_NEWTON.max_halvings) + 1;

impl NewtonSettling {
    fn new() -> Self {
        Self {
            orbit: None,
            orbit_events: Vec::new(),
            hints: None,
            attempts: 0,
            periods: 0,
            passes: 0,
            last_step: f64::INFINITY,
        }
    }

    /// After strobe x_k (the last of `history`, oldest first): whether to try Newton from x_k,
    /// and the strobe step |x_k − x_{k−1}| that decided it. Tried when the strobes contract
    /// and no orbit is at hand.
    fn wants_attempt(&self, history: &VecDeque<State>, budget: usize) -> Option<f64> {
        let n = history.len();
        if n < 2 {
            return None;
        }
        let (x, previous) = (history[n - 1], history[n - 2]);
        let step = distance(x, previous);
        // Not from x_1: the acceptance needs two checked steps after x_1 anyway (the step from
        // the initial state rarely follows the orbit's linearisation), and from x_2, closer to
        // the orbit, Newton's method needs fewer evaluations (the paper's map: 5 % fewer
        // instructions a point).
        let contracting = n >= 3 && step < distance(previous, history[n - 3]);
        (self.orbit.is_none()
            && self.attempts < MAX_NEWTON_ATTEMPTS
            && step > 0.0
            && contracting
            && step <= 0.25 * self.last_step
            && budget >= MOST_NEWTON_PERIODS)
            .then_some(step)
    }

    /// Newton's method from x (decided with strobe step `step`), its map's evaluations
    /// starting from the trajectory's `hints`. `first` is the image of x when the trajectory
    /// has computed it along its own next period (`Some(None)` when that period grazed, which
    /// fails the attempt); `None` when the map must be evaluated at x.
    fn attempt(
        &mut self,
        params: &Params,
        x: State,
        step: f64,
        hints: Option<Hints>,
        first: Option<Option<StrobeImage>>,
    ) {
        self.attempts += 1;
        self.last_step = step;
        // The period of the trajectory that gave the first image is counted as a strobe.
        let along = usize::from(first.is_some());
        let first = match first {
            Some(Some(image)) => Some(image),
            Some(None) => {
                self.periods += MOST_NEWTON_PERIODS - along;
                return;
            }
            None => None,
        };
        let finish = Finish {
            hints,
            first,
            loose: SETTLING_LOOSE,
        };
        match find_periodic_orbit_finished(params, x, 1, &SETTLING_NEWTON, finish) {
            Ok((orbit, hints)) => {
                self.periods += orbit.residuals.len() - along;
                if orbit.stability == Stability::Stable {
                    self.orbit_events = orbit
                        .events
                        .iter()
                        .map(|e| OrbitEvent::new(params, e))
                        .collect();
                    self.orbit = Some(orbit);
                    self.hints = hints;
                }
            }
            // A failed attempt costs at most its steps and halvings.
            Err(_) => self.periods += MOST_NEWTON_PERIODS - along,
        }
    }

    /// After the strobe step x_{k−1} → x_k (with the events of the period between, times
    /// from its first strobe): the orbit, when it is stable and the trajectory is within its
    /// basin (see [`within_basin`] and [`same_events`]).
    fn check(
        &mut self,
        params: &Params,
        previous: State,
        x: State,
        events: impl Iterator<Item = Event>,
    ) -> Option<PeriodicOrbit> {
        let orbit = self.orbit.as_ref()?;
        let passed =
            within_basin(orbit, previous, x) && same_events(params, &self.orbit_events, events);
        self.passes = if passed { self.passes + 1 } else { 0 };
        // (Accepted, the orbit is handed on: the search ends with it.)
        if self.passes >= BASIN_PASSES {
            self.orbit.take()
        } else {
            None
        }
    }
}

/// Whether the strobes x_{k−1} → x_k show the trajectory inside the basin of the stable orbit
/// (fixed point x*, monodromy M, spectral radius ρ < 1): the step follows the orbit's
/// linearisation, |e_k − M e_{k−1}| ≤ ½(1 − ρ)|e_{k−1}| with e = x − x* (max norm), and the
/// distance shrinks, |e_k| < |e_{k−1}| (see the module documentation for why this bounds the
/// rest of the trajectory).
fn within_basin(orbit: &PeriodicOrbit, previous: State, x: State) -> bool {
    let star = orbit.state;
    let e0 = [previous.y - star.y, previous.v - star.v];
    let e1 = [x.y - star.y, x.v - star.v];
    let size = |e: [f64; 2]| e[0].abs().max(e[1].abs());
    let m = orbit.monodromy.0;
    let predicted = [
        m[0][0] * e0[0] + m[0][1] * e0[1],
        m[1][0] * e0[0] + m[1][1] * e0[1],
    ];
    let radius = orbit.multipliers[0].modulus();
    let remainder = size([e1[0] - predicted[0], e1[1] - predicted[1]]);
    radius < 1.0 && remainder <= 0.5 * (1.0 - radius) * size(e0) && size(e1) < size(e0)
}

/// Whether the trajectory's last period (`events`, times from its first strobe) ran through
/// the same events as the orbit, in the same order, each close enough to the orbit's to keep
/// its kind: the net force f = β cos(wτ + φ) − y at a turn exceeds μs and at a stop is inside
/// it, by a margin |f| − μs (turn) or μs − |f| (stop) on the orbit; the trajectory's event
/// must differ from the orbit's by at most half of it, |Δf| ≤ ½·margin with
/// |Δf| ≤ β|cos(wτ' + φ) − cos(wτ + φ)| + |y' − y|. A slip is where |f| reaches μs, which
/// moves with the stop before it and has no margin of its own. A stop that appears or
/// vanishes, or a turn that becomes a stop (the edge of a sliding orbit's basin), fails this
/// test: see the module documentation.
fn same_events(params: &Params, orbit: &[OrbitEvent], events: impl Iterator<Item = Event>) -> bool {
    let mut orbit_events = orbit.iter();
    for e in events {
        let Some(o) = orbit_events.next() else {
            return false;
        };
        if e.kind != o.kind {
            return false;
        }
        if o.kind == EventKind::Slip {
            continue;
        }
        let shift = (params.drive(e.tau) - o.drive).abs() + (e.y - o.y).abs();
        if !(o.margin > 0.0 && shift <= 0.5 * o.margin) {
            return false;
        }
    }
    orbit_events.next().is_none()
}

/// An event of the orbit as [`same_events`] reads it, its drive computed once per orbit.
#[derive(Debug, Clone, Copy)]
struct OrbitEvent {
    kind: EventKind,
    y: f64,
    /// The drive β cos(wτ + φ) at the event.
    drive: f64,
    /// |f| − μs at a turn, μs − |f| at a stop (f the net force drive − y); unused at a slip.
    margin: f64,
}

impl OrbitEvent {
    fn new(params: &Params, e: &Event) -> Self {
        let drive = params.drive(e.tau);
        let force = drive - e.y - params.belt_force();
        let margin = match e.kind {
            EventKind::Turn => force.abs() - params.mu_s,
            EventKind::Stick => params.mu_s - force.abs(),
            EventKind::Slip => 0.0,
        };
        Self {
            kind: e.kind,
            y: e.y,
            drive,
            margin,
        }
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
    let mut newton =
        (accelerate && options.newton && holder.can_restart() && holder.solver().is_exact())
            .then(NewtonSettling::new);
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
                }
                None => accepted = n.check(params, history[len - 2], x, last_period),
            }
        }
        let tangent = spent(&newton) - before;
        if tangent > 0 {
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

/// Record one cycle (or `max_period` periods) from the strobe the solver stands at.
fn record<S: Solver + ?Sized>(
    solver: &mut S,
    params: &Params,
    options: &SteadyOptions,
    settled: &Settled,
) -> Result<SteadyState> {
    let period = params.drive_period();
    let found = settled.found;
    let scale = settled.scale;
    let start_index = settled.strobe_index;
    let recorded = found.unwrap_or(options.max_period);
    let start = strobe(start_index, period);
    let stuck_at_start = solver.phase() == Phase::Stick;

    // (Room for the events the settling saw a period, and a few more.)
    let mut events =
        Vec::with_capacity(((settled.events_per_period * recorded as f64) as usize).min(4096) + 8);
    let mut strobes = Vec::with_capacity(recorded + 1);
    strobes.push(solver.state());
    let mut half_strobes = Vec::with_capacity(recorded);
    // The samples of the spectrum, if asked for, are read from the dense output of the
    // intervals the solver advances through anyway: the solver is advanced to the same
    // half-period and period ends with or without them, so the events, strobes and extremes
    // (and with them the class, gain, stops and symmetry) do not depend on the spectrum, and
    // a map's point (which has none) equals the steady state of the same point.
    let samples = options.spectrum.then(|| {
        options.samples_per_period.unwrap_or_else(|| {
            auto_samples(settled.events_per_period, params, options.harmonics, scale)
        })
    });
    let times: Vec<f64> = samples.map_or_else(Vec::new, |n| {
        let base = start_index * n as u64;
        (0..(recorded * n) as u64)
            .map(|j| (base + j) as f64 / n as f64 * period)
            .collect()
    });
    let mut trace = Vec::with_capacity(times.len());
    let mut next = 0;
    while next < times.len() && times[next] <= solver.time() {
        let s = solver.state();
        trace.push(Sample {
            tau: times[next],
            y: s.y,
            v: s.v,
            phase: solver.phase(),
        });
        next += 1;
    }
    // On a belt y also turns inside slides (where y' = 0, which is no event): those extremes
    // are found in the dense output of each stretch (`super::extremes`).
    let belt = params.vb != 0.0;
    let spacing = 0.2 * params.w.recip().min(1.0);
    let mut inner = (f64::INFINITY, f64::NEG_INFINITY);
    let mut run_to = |solver: &mut S, t_end: f64, events: &mut Vec<Event>| -> Result<()> {
        run_steps(solver, t_end, |solver, event| {
            events.extend(event.copied());
            if belt {
                velocity_zeros(solver, spacing, |s, _| {
                    inner = (inner.0.min(s.y), inner.1.max(s.y));
                });
            }
            let to = solver.interval().1;
            while next < times.len() && times[next] <= to {
                trace.push(solver.dense(times[next]));
                next += 1;
            }
        })
    };
    for j in 0..recorded as u64 {
        let half = (2 * (start_index + j) + 1) as f64 / 2.0 * period;
        run_to(solver, half, &mut events)?;
        half_strobes.push(solver.state());
        run_to(solver, strobe(start_index + j + 1, period), &mut events)?;
        strobes.push(solver.state());
    }
    let spectrum = match samples {
        Some(_) => {
            let y: Vec<f64> = trace.iter().map(|s| s.y).collect();
            Some(Spectrum::from_samples(
                &y,
                recorded,
                options.harmonics,
                params.phi,
            )?)
        }
        None => None,
    };

    let mut y_min = f64::INFINITY;
    let mut y_max = f64::NEG_INFINITY;
    // Extremes of y are where y' = 0, at events (and the record's ends): the samples of the
    // spectrum add nothing, and are left out so that the gain does not depend on them.
    let ys = events
        .iter()
        .map(|e| e.y)
        .chain(strobes.iter().chain(&half_strobes).map(|s| s.y));
    for y in ys {
        y_min = y_min.min(y);
        y_max = y_max.max(y);
    }
    if belt {
        y_min = y_min.min(inner.0);
        y_max = y_max.max(inner.1);
    }
    let amplitude = 0.5 * (y_max - y_min);
    let gain = if params.beta > 0.0 {
        amplitude / params.beta
    } else if amplitude == 0.0 {
        0.0
    } else {
        f64::INFINITY
    };

    // (A belt breaks the symmetry y → −y: it maps vb to −vb.)
    let symmetric = found.is_some() && !belt && {
        let limit = 1e3 * options.tolerance * scale;
        (0..recorded).any(|shift| {
            (0..recorded).all(|j| {
                let h = half_strobes[j];
                let s = strobes[(j + shift) % recorded];
                (h.y + s.y).abs().max((h.v + s.v).abs()) <= limit
            })
        })
    };

    let end = strobe(start_index + recorded as u64, period);
    let c = classify(
        &events,
        start,
        end,
        recorded,
        stuck_at_start,
        found.is_some(),
        amplitude,
        params.beta,
        options.min_stop_fraction * period,
    );
    Ok(SteadyState {
        params: *params,
        class: c.class,
        period: found,
        periods_to_settle: settled.periods_run,
        recorded_periods: recorded,
        stops: c.stops,
        stops_per_period: c.stops_per_period,
        longest_stop: c.longest_stop,
        symmetric,
        y_min,
        y_max,
        peak: y_max.abs().max(y_min.abs()),
        gain,
        start,
        events,
        strobes,
        half_strobes,
        spectrum,
        trace,
        lyapunov: None,
        self_excited: None,
    })
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
