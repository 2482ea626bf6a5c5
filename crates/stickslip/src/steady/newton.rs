//! Settling by Newton on the stroboscopic map.
//!
//! When [`SteadyOptions::newton`](super::SteadyOptions::newton) is on (the default; the exact solver or a smooth law's,
//! with a factory and [`SteadyOptions::accelerate`](super::SteadyOptions::accelerate); see the end for smooth laws): from the
//! third strobe x_2 on, whenever the strobe
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
//! shorten the trajectory: a motion that does not settle runs [`SteadyOptions::max_periods`](super::SteadyOptions::max_periods)
//! strobe periods and is recorded exactly as without Newton (its `periods_to_settle` is the
//! cap); an attempt is made only while the cap leaves room for its longest run.
//!
//! **Smooth laws** (a factory whose [`super::SolverFactory::smooth_dynamics`] has a strobe map
//! at the solvers' own options, [`Dynamics::settling`]: the Shockley diode pair). Newton's
//! method runs on the stiff solver's strobe map at the trajectories' rtol and atol, with the
//! monodromy from the solver's forward sensitivities, which do not steer its steps: the map's
//! image of a state is where a solver of the factory started there lands, to the bit (test
//! `the_smooth_settling_map_is_the_solvers_own`), so the cycle recorded from the fixed point
//! is that map's cycle and its repetition check (below) holds it to the search's tolerance.
//! The map is evaluated at x_k itself (the trajectory's solver carries no tangent), and that
//! first image P(x_k) is a strobe step in its own right: the period a solver of the factory
//! started afresh at x_k runs, which differs from the trajectory's next period only by the
//! solver's tolerance (its steps do not restart at a strobe). So the step x_k → P(x_k) is
//! checked as the trajectory's steps are, right after the attempt: when it and the
//! trajectory's step x_{k−1} → x_k both pass, the orbit is accepted without running the
//! trajectory's next period (when it fails, the trajectory's own next step is checked as
//! before; see `NewtonSettling::check_first_image`). Newton's iteration stops as for the
//! exact solver, at a residual of 10⁻⁶·max(1, |x|)·max(1, |M|) where ρ ≤ 0.9, and takes one
//! more step without evaluating the map (`ShockleyDynamics::settling_orbit`; the recorded
//! period checks x* as above). The acceptance asks the same two checks of two consecutive
//! strobe steps; the flow is smooth,
//! so the map has no pieces and the remainder is quadratic everywhere, but its constant K
//! grows where the motion changes its character: where a near-stop (the velocity held within
//! the solver's stop threshold, the diode barely conducting) forms or vanishes. So the
//! comparison of events asks the period just run to have the orbit's events of the same
//! kinds in the same order (turns, and the stops and slips the solver marks), without the
//! margins in the force, which a smooth law has no threshold for. The strobes of a
//! trajectory follow the map only to about the solver's tolerance (its steps do not restart
//! at a strobe), which can only fail the first check near the fixed point, never pass it
//! wrongly far from it. What shows it holds: the report's Fig. 7 (b) map with a 1N4148 pair
//! (`crates/stickslip/tests/newton_settling.rs`), the same classes, periods, stops and
//! symmetry as the plain iteration at every point where that repeats, the gains within
//! 10 rtol; where it does not (a sliding orbit whose strobes wander within the solver's
//! accuracy), Newton settles the point on the period-1 orbit its strobes wander around.

use super::cycle::distance;
use crate::params::{Params, State};
use crate::solver::{Event, EventKind, Hints};
use crate::stability::periodic_orbit::{find_periodic_orbit_finished, Finish};
use crate::stability::{Dynamics, NewtonOptions, PeriodicOrbit, Stability, StrobeImage};
use std::collections::VecDeque;

/// Newton's method on the stroboscopic map (see [`SteadyOptions::newton`](super::SteadyOptions::newton) and the module
/// documentation): the stable period-1 orbit it found, and whether the trajectory has been
/// seen within its basin.
pub(super) struct NewtonSettling {
    /// The strobe map of a smooth law at the trajectories' options
    /// ([`Dynamics::settling`]); `None` for the exact solver.
    smooth: Option<Box<dyn Dynamics>>,
    /// The orbit found by the last attempt (stable), if any.
    orbit: Option<PeriodicOrbit>,
    /// Its events, as the comparison with the trajectory's reads them.
    orbit_events: Vec<OrbitEvent>,
    /// The hints of the last evaluation of the map near the orbit, for the solver that
    /// records the cycle from it.
    pub(super) hints: Option<Hints>,
    /// The guess of the last attempt on a smooth law's map and its image there (the map's
    /// first evaluation), until [`NewtonSettling::check_first_image`] reads them.
    first: Option<(State, StrobeImage)>,
    /// Attempts made.
    attempts: usize,
    /// Tangent periods run by the attempts (counted in `periods_to_settle`).
    pub(super) periods: usize,
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
    /// Settling for the exact solver, or for a smooth law's solver with `smooth`, the
    /// law's strobe map at the trajectories' options ([`Dynamics::settling`]).
    pub(super) fn new(smooth: Option<Box<dyn Dynamics>>) -> Self {
        Self {
            smooth,
            orbit: None,
            orbit_events: Vec::new(),
            hints: None,
            first: None,
            attempts: 0,
            periods: 0,
            passes: 0,
            last_step: f64::INFINITY,
        }
    }

    /// Whether it settles a smooth law's motion (whose Newton runs charge their own steps to
    /// the factory's token).
    pub(super) fn is_smooth(&self) -> bool {
        self.smooth.is_some()
    }

    /// After strobe x_k (the last of `history`, oldest first): whether to try Newton from x_k,
    /// and the strobe step |x_k − x_{k−1}| that decided it. Tried when the strobes contract
    /// and no orbit is at hand.
    pub(super) fn wants_attempt(&self, history: &VecDeque<State>, budget: usize) -> Option<f64> {
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
    pub(super) fn attempt(
        &mut self,
        params: &Params,
        x: State,
        step: f64,
        hints: Option<Hints>,
        first: Option<Option<StrobeImage>>,
    ) {
        self.attempts += 1;
        self.last_step = step;
        self.first = None;
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
        let mut first_image = None;
        let found = match &self.smooth {
            // (A smooth law's map is evaluated at x: its solvers carry no tangent along the
            // trajectory. Its image there is kept for `check_first_image`.)
            Some(dynamics) => {
                match dynamics.settling_orbit(params, x, &SETTLING_NEWTON, SETTLING_LOOSE) {
                    Some(found) => found.map(|(orbit, image)| {
                        first_image = Some((x, image));
                        (orbit, None)
                    }),
                    None => dynamics
                        .find_periodic_orbit(params, x, 1, &SETTLING_NEWTON)
                        .map(|orbit| (orbit, None)),
                }
            }
            None => {
                let finish = Finish {
                    hints,
                    first,
                    loose: SETTLING_LOOSE,
                };
                find_periodic_orbit_finished(params, x, 1, &SETTLING_NEWTON, finish)
            }
        };
        match found {
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
                    self.first = first_image;
                }
            }
            // A failed attempt costs at most its steps and halvings.
            Err(_) => self.periods += MOST_NEWTON_PERIODS - along,
        }
    }

    /// After the strobe step x_{k−1} → x_k (with the events of the period between, times
    /// from its first strobe): the orbit, when it is stable and the trajectory is within its
    /// basin (see [`within_basin`] and [`same_events`]).
    pub(super) fn check(
        &mut self,
        params: &Params,
        previous: State,
        x: State,
        events: impl Iterator<Item = Event>,
    ) -> Option<PeriodicOrbit> {
        let orbit = self.orbit.as_ref()?;
        let passed = within_basin(orbit, previous, x)
            && if self.smooth.is_some() {
                same_kinds(&self.orbit_events, events)
            } else {
                same_events(params, &self.orbit_events, events)
            };
        self.passes = if passed { self.passes + 1 } else { 0 };
        // (Accepted, the orbit is handed on: the search ends with it.)
        if self.passes >= BASIN_PASSES {
            self.orbit.take()
        } else {
            None
        }
    }
}

impl NewtonSettling {
    /// After an attempt from x_k on a smooth law's map that found a stable orbit, and the
    /// check of the trajectory's step x_{k−1} → x_k (see [`NewtonSettling::check`]): the
    /// map's first image P(x_k) is the strobe step x_k → P(x_k) that a trajectory started
    /// afresh at x_k takes (the map is the solvers' own); the orbit, when that step passes
    /// the same checks ([`within_basin`] and [`same_kinds`]) after a step that passed, so
    /// that two consecutive strobe steps followed the orbit's linearisation. A step that
    /// fails leaves the count of the trajectory's steps as it was (the trajectory's own next
    /// step may still pass).
    pub(super) fn check_first_image(&mut self) -> Option<PeriodicOrbit> {
        let (x, image) = self.first.take()?;
        let orbit = self.orbit.as_ref()?;
        let passed = self.passes + 1 >= BASIN_PASSES
            && within_basin(orbit, x, image.state)
            && same_kinds(&self.orbit_events, image.events.iter().copied());
        if passed {
            self.passes += 1;
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

/// Whether the trajectory's last period ran through the same kinds of events as the orbit of
/// a smooth law, in the same order (see the module documentation): its turns, and the stops
/// and slips the solver marks where the velocity stays within its stop threshold.
fn same_kinds(orbit: &[OrbitEvent], events: impl Iterator<Item = Event>) -> bool {
    let mut orbit_events = orbit.iter();
    for e in events {
        match orbit_events.next() {
            Some(o) if o.kind == e.kind => {}
            _ => return false,
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
