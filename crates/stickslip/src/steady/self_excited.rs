//! Self-excited motion on a moving belt: without a drive (β = 0) a block on a belt at speed
//! vb ≠ 0 settles on a cycle whose period is its own, found here, not given.
//!
//! **What it settles on.** Three motions ([`MotionClass`]):
//!
//! - a **stick-slip cycle** ([`MotionClass::StickSlipCycle`]): the block sticks to the belt,
//!   is carried until the spring's force exceeds the static limit, slips, and sticks again.
//!   Without a drive every stop ends at the same state, y = sgn(vb)·μs − 2ζ vb with y' = vb
//!   (where the net force −y − 2ζ vb reaches ∓μs), so the motion from there is one and the
//!   same: after its second stop the block is on the cycle. The section is the onset of
//!   sticking (y at the stick event, y' = vb). A "stop" that ends within
//!   [`SteadyOptions::min_stop_fraction`] of 2π is a touch of the belt's speed, not a stop
//!   (the undamped Coulomb belt with μs = 1 touches it once a period, tangentially, where
//!   only rounding places the stick event): it opens no cycle, and the slide's sections go on
//!   through it (`is_touch`).
//! - a **pure-slip cycle** ([`MotionClass::PureSlipCycle`]): the block never sticks. Where the
//!   slip s = y' − vb changes sign (a reversal without a stop) the section is there, s = 0 with
//!   s rising; where it never does (an oscillation about steady sliding with s of one sign, as
//!   a friction law that falls with the slip speed grows one) the section is the turning point
//!   y' = 0 with y at a maximum. The cycle is found when the section repeats (period p ≤
//!   [`SteadyOptions::max_period`] crossings) to [`SteadyOptions::tolerance`]·scale.
//! - **steady sliding** ([`MotionClass::SteadySliding`]): the equilibrium y' = 0,
//!   y = y_e = sgn(vb)·μ(|vb|), reached when the turning points' distance from y_e falls below
//!   the tolerance, or decays geometrically (three ratios of successive distances agreeing to
//!   10⁻³, all below 1, the distance below 10⁻² of the scale): the linearisation about y_e,
//!   y'' + (2ζ + μ'(|vb|)) y' + y = 0, then takes it there. Sooner, by energy: with
//!   E = ½ y'² + ½ (y − y_e)², dE/dτ = y'²·(c(y') − 2ζ) while the slip keeps the sign of
//!   steady sliding's, c(v) = (μ(|vb| − v) − μ(|vb|))/v the chord of the law; so a turning
//!   point at a distance r < |vb| from y_e such that c < 2ζ for all 0 < |v| ≤ r decides
//!   steady sliding: from there |y'| ≤ r, the block never sticks again, and E falls onto
//!   y_e (a damped Coulomb belt, c = 0, at the first turning point nearer y_e than |vb|; the
//!   bound of the chord for the smooth laws is computed in closed form, see `chord_bound`).
//!
//! Beside the class every answer carries the equilibrium y_e and its stability: small
//! oscillations about steady sliding are damped by 2ζ + μ'(|vb|) (stable where positive,
//! unstable where negative, neutral at 0), whether or not the motion settled there.
//!
//! **The record.** One cycle from the last section but p to the last: its period, events,
//! time stuck (the stick fraction), and the extremes of y: at stops (a stop moves with the
//! belt, so y has its extremes at its ends, which are events) and inside slides, where y' = 0
//! (found in the dense output of each slide).
//!
//! **Length.** The search runs at most [`SteadyOptions::max_periods`] natural periods 2π (of
//! τ = ω0·t: there is no drive period).

use super::classify::MotionClass;
use super::extremes::velocity_zeros;
use super::options::SteadyOptions;
use super::state::SteadyState;
use super::SolverFactory;
use crate::error::Result;
use crate::friction::FrictionLaw;
use crate::params::{Params, State};
use crate::solver::{Event, EventKind, Phase, Solver};
use serde::{Deserialize, Serialize};
use std::collections::VecDeque;
use std::f64::consts::TAU;

/// Spacing of the samples that bracket the turning points of y (in τ; a natural period is
/// 2π).
const SPACING: f64 = 0.2;

/// The stability of steady sliding: the sign of the damping 2ζ + μ'(|vb|) of small
/// oscillations about it.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum SlidingStability {
    /// 2ζ + μ'(|vb|) > 0: small oscillations die out.
    Stable,
    /// 2ζ + μ'(|vb|) < 0: small oscillations grow (the friction law's fall feeds them).
    Unstable,
    /// 2ζ + μ'(|vb|) = 0 (Coulomb's law without damping): a family of neutral oscillations.
    Neutral,
}

impl SlidingStability {
    /// The stability of damping `damping`.
    pub fn of(damping: f64) -> Self {
        if damping > 0.0 {
            SlidingStability::Stable
        } else if damping < 0.0 {
            SlidingStability::Unstable
        } else {
            SlidingStability::Neutral
        }
    }

    /// `stable`, `unstable` or `neutral`.
    pub fn label(self) -> &'static str {
        match self {
            SlidingStability::Stable => "stable",
            SlidingStability::Unstable => "unstable",
            SlidingStability::Neutral => "neutral",
        }
    }

    /// The label, and for a neutral equilibrium what it means for the belt of `params`: a
    /// centre, with Coulomb's law (ζ = 0) the centre of a family of pure-slip cycles, the
    /// circles about it of radius up to |vb| (period 2π), of which a pure-slip cycle found
    /// there is one, not an attracting cycle (`crate::theory::belt`).
    pub fn description(self, params: &Params) -> &'static str {
        match self {
            SlidingStability::Neutral if params.law.is_coulomb() => {
                "neutral (a centre: every circle about it of radius up to |vb| is a pure-slip \
                 cycle of period 2π, neither attracting nor repelling; the largest touches \
                 the belt's speed)"
            }
            SlidingStability::Neutral => {
                "neutral (small oscillations about it neither grow nor decay to first order)"
            }
            other => other.label(),
        }
    }
}

/// Where the cycle of a self-excited motion was recognised (see the module documentation).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum CycleSection {
    /// The onset of sticking: y at a stick event (y' = vb).
    StickOnset,
    /// A reversal of the slip without a stop: s = y' − vb = 0 with s rising.
    Reversal,
    /// A turning point of y: y' = 0 with y at a maximum.
    TurningPoint,
}

impl CycleSection {
    /// `stick-onset`, `reversal` or `turning-point`.
    pub fn label(self) -> &'static str {
        match self {
            CycleSection::StickOnset => "stick-onset",
            CycleSection::Reversal => "reversal",
            CycleSection::TurningPoint => "turning-point",
        }
    }
}

/// What a self-excited motion settled on, beside its [`SteadyState`] (see the module
/// documentation). Dimensionless: times in τ = ω0·t.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct SelfExcited {
    /// The period of the cycle in τ; `None` for steady sliding, or when no cycle was found.
    pub period: Option<f64>,
    /// The fraction of the period stuck to the belt (0 without stops).
    pub stick_fraction: f64,
    /// The section the cycle was recognised at; `None` for steady sliding.
    pub section: Option<CycleSection>,
    /// The position of steady sliding, y_e = sgn(vb)·μ(|vb|).
    pub equilibrium: f64,
    /// The damping 2ζ + μ'(|vb|) of small oscillations about steady sliding.
    pub sliding_damping: f64,
    /// Its sign: whether steady sliding is stable.
    pub sliding_stability: SlidingStability,
    /// τ from the start to the end of the recorded cycle (or to the arrival at steady
    /// sliding).
    pub time_to_settle: f64,
}

/// Something that happened, logged for the record of a cycle.
#[derive(Debug, Clone, Copy)]
enum Mark {
    /// An event of the solver.
    Event(Event),
    /// An extreme of y inside a slide (y' = 0).
    Extreme { tau: f64, y: f64 },
}

impl Mark {
    fn tau(&self) -> f64 {
        match self {
            Mark::Event(e) => e.tau,
            Mark::Extreme { tau, .. } => *tau,
        }
    }
}

/// A point of a section: time, position and the state there.
#[derive(Debug, Clone, Copy)]
struct Point {
    tau: f64,
    state: State,
}

/// The sections of one kind, the last few, with the repetition test.
#[derive(Debug, Default)]
struct Sections {
    points: VecDeque<Point>,
}

impl Sections {
    fn push(&mut self, point: Point, keep: usize) {
        self.points.push_back(point);
        while self.points.len() > keep {
            self.points.pop_front();
        }
    }

    fn clear(&mut self) {
        self.points.clear();
    }

    /// The least p ≤ `max_period` with |y_k − y_{k−p}| ≤ `limit` for the last p + 1 points
    /// (a whole cycle and once more), where k is the last; with `once`, for the last point
    /// alone (the stick onsets of an undriven belt: every stop ends at the same state, so
    /// the motion after one stop is the cycle).
    fn period(&self, max_period: usize, limit: f64, once: bool) -> Option<usize> {
        let n = self.points.len();
        let checks = |p: usize| if once { 1 } else { p + 1 };
        (1..=max_period).find(|&p| {
            n >= p + checks(p)
                && (0..checks(p)).all(|j| {
                    let a = self.points[n - 1 - j].state;
                    let b = self.points[n - 1 - j - p].state;
                    (a.y - b.y).abs() <= limit
                })
        })
    }
}

/// The steady state of a self-excited motion from `initial` (at τ = 0) by a solver of
/// `factory` (see the module documentation); `params` has β = 0 and vb ≠ 0.
///
/// # Errors
/// As [`self_excited_state`].
pub(crate) fn settle_self_excited<F: SolverFactory + ?Sized>(
    factory: &F,
    params: &Params,
    initial: State,
    options: &SteadyOptions,
) -> Result<SteadyState> {
    let options = options.validate()?;
    let mut solver = factory.make_searching(*params, initial)?;
    let make = |state: State| factory.make_searching(*params, state);
    let restart: Option<&Restart> = if options.newton { Some(&make) } else { None };
    search(solver.as_mut(), &options, restart)
}

/// A new solver of the same parameters from a state (at τ = 0), for Newton's method on the
/// section map.
type Restart<'a> = dyn Fn(State) -> Result<Box<dyn Solver + Send>> + 'a;

/// The steady state of the self-excited motion of `solver` (its parameters have β = 0 and
/// vb ≠ 0), from where it stands: see the module documentation.
///
/// # Errors
/// [`crate::Error::HorizonTooLong`] when [`SteadyOptions::max_periods`] natural periods reach
/// past the time range the solvers resolve; whatever the solver reports.
pub fn self_excited_state<S: Solver + ?Sized>(
    solver: &mut S,
    options: &SteadyOptions,
) -> Result<SteadyState> {
    search(solver, &options.validate()?, None)
}

/// [`self_excited_state`] with validated `options`; with `restart`, settling a pure-slip
/// cycle by Newton's method on its turning-point map ([`settle_by_newton`]).
fn search<S: Solver + ?Sized>(
    solver: &mut S,
    options: &SteadyOptions,
    restart: Option<&Restart>,
) -> Result<SteadyState> {
    let options = *options;
    let params = *solver.params();
    let start = solver.time();
    let cap = start + options.max_periods as f64 * TAU;
    crate::params::check_time(&params, cap)?;
    let law = params.law;
    let equilibrium = law.sliding_equilibrium(params.mu_s, params.vb);
    let damping = law.sliding_damping(params.zeta, params.mu_s, params.vb);
    let scale = 1f64
        .max(equilibrium.abs())
        .max(params.vb.abs())
        .max(params.mu_s);
    let limit = options.tolerance * scale;
    let keep = 2 * options.max_period + 2;
    let min_stop = options.min_stop_fraction * TAU;

    let mut sticks = Sections::default();
    let mut reversals = Sections::default();
    let mut turning = Sections::default();
    let mut log: VecDeque<Mark> = VecDeque::new();
    // |y − y_e| at the last turning points, for the decay towards steady sliding.
    let mut distances: VecDeque<f64> = VecDeque::with_capacity(4);
    // Newton's tries on the turning-point map, and the turning points since the last.
    let (mut tries, mut since_try) = (0, 0);

    let finish = |kind: CycleSection, sections: &Sections, p: usize, log: &VecDeque<Mark>| {
        let n = sections.points.len();
        let (a, b) = (sections.points[n - 1 - p], sections.points[n - 1]);
        record_cycle(&params, &options, kind, a, b, log, equilibrium, damping)
    };

    while solver.time() < cap {
        let t_end = (solver.time() + TAU).min(cap);
        let event = solver.advance(t_end)?;
        // Turning points of y inside the stretch just covered.
        let mut maxima = Vec::new();
        velocity_zeros(solver, SPACING, |s, maximum| {
            log.push_back(Mark::Extreme { tau: s.tau, y: s.y });
            if maximum {
                maxima.push(Point {
                    tau: s.tau,
                    state: State { y: s.y, v: 0.0 },
                });
            }
        });
        if let Some(e) = event {
            log.push_back(Mark::Event(e));
            let here = Point {
                tau: e.tau,
                state: solver.state(),
            };
            match e.kind {
                // A touch of the belt's speed is no stop: the slide goes on, and so do its
                // sections (see `is_touch`).
                EventKind::Stick if is_touch(&params, e.y, min_stop) => {}
                EventKind::Stick => {
                    sticks.push(here, keep);
                    reversals.clear();
                    turning.clear();
                    distances.clear();
                    if let Some(p) = sticks.period(options.max_period, limit, true) {
                        return finish(CycleSection::StickOnset, &sticks, p, &log);
                    }
                }
                EventKind::Turn if solver.phase() == Phase::SlipPositive => {
                    reversals.push(here, keep);
                    turning.clear();
                    distances.clear();
                    if let Some(p) = reversals.period(options.max_period, limit, false) {
                        return finish(CycleSection::Reversal, &reversals, p, &log);
                    }
                }
                _ => {}
            }
        }
        for point in maxima {
            turning.push(point, keep);
            let distance = (point.state.y - equilibrium).abs();
            if distances.len() == 4 {
                distances.pop_front();
            }
            distances.push_back(distance);
            // (Only turning points since the last stop or reversal are kept.)
            if let Some(p) = turning.period(options.max_period, limit, false) {
                if distance > limit {
                    return finish(CycleSection::TurningPoint, &turning, p, &log);
                }
            }
            if distance <= limit || decays(&distances, scale) || never_sticks(&params, distance) {
                return Ok(sliding(&params, point.tau, equilibrium, damping));
            }
            since_try += 1;
            if let Some(restart) = restart.filter(|_| tries < NEWTON_TRIES && since_try >= 4) {
                if let Some(guess) = geometric_limit(&turning, equilibrium, limit, scale) {
                    tries += 1;
                    since_try = 0;
                    let last = turning.points[turning.points.len() - 1].state.y;
                    let remaining = ((cap - point.tau) / TAU).floor() as usize;
                    if let Some(found) =
                        settle_by_newton(restart, &options, guess, last, limit, remaining)?
                    {
                        return Ok(shifted(found, point.tau));
                    }
                }
            }
        }
        // A motion that creeps onto steady sliding without turning (overdamped).
        let now = solver.state();
        if event.is_none()
            && (now.y - equilibrium).abs() <= limit
            && now.v.abs() <= limit
            && solver.phase() != Phase::Stick
        {
            return Ok(sliding(&params, solver.time(), equilibrium, damping));
        }
        // Keep the log to the oldest section point any test may look back to.
        let oldest = [&sticks, &reversals, &turning]
            .iter()
            .filter_map(|s| s.points.front().map(|p| p.tau))
            .fold(solver.time(), f64::min);
        while log.front().is_some_and(|m| m.tau() < oldest) {
            log.pop_front();
        }
    }
    // No cycle within the cap.
    Ok(unsettled(
        &params,
        solver,
        &log,
        (equilibrium, damping),
        cap - start,
        min_stop,
    ))
}

/// Whether a stop that starts at `y` (a stick event) ends within `min_stop`
/// ([`SteadyOptions::min_stop_fraction`] of 2π), so that it is no stop but a touch of the
/// belt's speed. Without a drive a stop ends where the net force −y − 2ζ vb reaches the
/// static limit, at y_r = sgn(vb)·μs − 2ζ vb, after (y_r − y)/vb. A slide that reaches the
/// belt's speed tangentially (y'' = 0 there) does so at y_r itself: at ζ = 0 and μs = 1 every
/// stick-slip cycle is the circle of radius |vb| about steady sliding, which leaves the belt's
/// speed at its top and comes back to it there (`crate::theory::CoulombBeltCycle`: the stop
/// shrinks to an instant). Its stick event is then placed by rounding only, up to √ε from the
/// tangency (a few 10⁻⁸ in τ and in y), and so is the "stop" that follows; the motion after
/// it is the same circle. Such touches neither open a cycle nor end the sections of the
/// slide, whose turning points then find the cycle (the period 2π to rounding, where the
/// stick events would repeat only to some 10⁻⁸), and they count neither as stops nor as time
/// stuck, as in the record of the driven oscillator ([`super::classify()`]).
fn is_touch(params: &Params, y: f64, min_stop: f64) -> bool {
    let release = params.mu_s.copysign(params.vb) - params.belt_force();
    (release - y) / params.vb <= min_stop
}

/// The durations of the stops among `events` (a stick event followed by a slip event, or by
/// the `end` of the record) that last longer than `min_stop`.
fn stops_of<'a>(events: impl Iterator<Item = &'a Event>, min_stop: f64, end: f64) -> Vec<f64> {
    let mut stops = Vec::new();
    let mut since = None;
    for e in events {
        match e.kind {
            EventKind::Stick => since = Some(e.tau),
            EventKind::Slip => {
                if let Some(s) = since.take() {
                    stops.push(e.tau - s);
                }
            }
            EventKind::Turn => {}
        }
    }
    if let Some(s) = since {
        stops.push(end - s);
    }
    stops.retain(|&d| d > min_stop);
    stops
}

/// Whether the slide from a turning point (y' = 0) at `distance` from steady sliding never
/// sticks again and decays onto steady sliding: the energy argument of the module
/// documentation. With E = ½ y'² + ½ (y − y_e)², y_e = μ(vb) (vb > 0; a negative belt speed
/// is its mirror image y → −y), the equation of the slide with s = y' − vb < 0,
/// y'' + 2ζ y' + y − μ(vb − y') = 0, gives
///
/// ```text
/// dE/dτ = y'·(μ(vb − y') − μ(vb) − 2ζ y') = y'²·(c(y') − 2ζ),   c(v) = (μ(vb − v) − μ(vb))/v
/// ```
///
/// (with s > 0, y' > vb > 0, the slide's y'' + 2ζ y' + y + μ(y' − vb) = 0 gives
/// dE/dτ = −y'·(2ζ y' + μ(y' − vb) + μ(vb)) < 0: energy falls there too). Let r = `distance`
/// < vb, the energy at the turning point ½ r². If the chord c(v) < 2ζ for every v ≠ 0 with
/// |v| ≤ r, then E cannot rise while |y'| ≤ r, and |y'| ≤ √(2E) ≤ r: so |y'| stays below vb,
/// the slip keeps its sign, the block never sticks or reverses again, and E falls strictly
/// except where y' = 0, whose only invariant point is the equilibrium (LaSalle): the slide
/// decays onto y_e. Coulomb's law has c = 0 (the linear slide with ζ > 0 of before); the
/// bound of the chord for the smooth laws is [`chord_bound`]. (The geometric test of
/// [`decays`] waits for the distance to fall below 10⁻² of the scale; this one decides a
/// map's sliding points several natural periods sooner, with the same class.)
fn never_sticks(params: &Params, distance: f64) -> bool {
    let vb = params.vb.abs();
    distance < vb && chord_bound(&params.law, params.mu_s, vb, distance) < 2.0 * params.zeta
}

/// An upper bound of the chord c(v) = (μ(vb − v) − μ(vb))/v of the friction law over
/// 0 < |v| ≤ r, for 0 ≤ r < vb (see [`never_sticks`]); computed in closed form, not sampled:
///
/// - Coulomb: c = 0.
/// - cubic, μ(s) = μs − k1 s + k3 s³: c(v) = k1 − 3 k3 vb² + 3 k3 vb v − k3 v², a concave
///   parabola whose vertex v = 3vb/2 lies beyond r, so its maximum on [−r, r] is at v = r:
///   k1 − k3 (3 vb² − 3 vb r + r²), exactly.
/// - Stribeck, μ(s) = 1 + (μs − 1) e^{−x^δ} + η s with x = s/vs: by the mean value theorem
///   c(v) = −μ'(ξ) with ξ between vb − v and vb, so c ≤ −min μ' on [vb − r, vb + r] (inside
///   s > 0). μ'(s) = η − (μs − 1) g(s) with g(s) = δ x^{δ−1} e^{−x^δ} / vs, which falls for
///   δ ≤ 1 and for δ > 1 rises to its one peak at x* = ((δ − 1)/δ)^{1/δ} and then falls; so
///   its maximum on an interval is g(x*) when the interval holds x*, else the larger of its
///   ends, and its minimum is the smaller of its ends. min μ' is η − (μs − 1)·max g for
///   μs ≥ 1 and η − (μs − 1)·min g otherwise.
///
/// The smooth laws' bounds are raised by 10⁻¹² (1 + |terms|) against rounding.
fn chord_bound(law: &FrictionLaw, mu_s: f64, vb: f64, r: f64) -> f64 {
    match *law {
        FrictionLaw::Coulomb => 0.0,
        FrictionLaw::Cubic { k1, k3 } => {
            let lower = 3.0 * vb * vb - 3.0 * vb * r + r * r;
            k1 - k3 * lower + 1e-12 * (1.0 + k1.abs() + k3 * lower)
        }
        FrictionLaw::Stribeck { vs, delta, eta } => {
            let g = |s: f64| {
                let x = s / vs;
                delta * x.powf(delta - 1.0) * (-x.powf(delta)).exp() / vs
            };
            let (a, b) = (vb - r, vb + r);
            let (ga, gb) = (g(a), g(b));
            let fall = mu_s - 1.0;
            let g_extreme = if fall >= 0.0 {
                let peak = (delta > 1.0)
                    .then(|| vs * ((delta - 1.0) / delta).powf(1.0 / delta))
                    .filter(|&s| a <= s && s <= b);
                peak.map_or(ga.max(gb), g)
            } else {
                ga.min(gb)
            };
            let bound = fall * g_extreme - eta;
            bound + 1e-12 * (1.0 + eta + (fall * g_extreme).abs())
        }
    }
}

/// Newton's tries on the turning-point map of one motion.
const NEWTON_TRIES: usize = 3;
/// Most iterations of one try.
const NEWTON_ITERATIONS: usize = 12;
/// Natural periods the turning-point map may take to return.
const MAP_PERIODS: usize = 20;
/// Natural periods the plain search from Newton's fixed point has to confirm it.
const CONFIRM_PERIODS: usize = 10;

/// The limit of the last turning points' maxima y_k when they approach it geometrically, by
/// Aitken's extrapolation: the last three ratios of successive differences in (0, 1),
/// agreeing to 2 %, the last difference above `limit` (below it the plain test is about to
/// decide), and the limit away from steady sliding (by 10⁻³ of `scale`: a motion that decays
/// onto steady sliding is left to the tests of steady sliding).
fn geometric_limit(turning: &Sections, equilibrium: f64, limit: f64, scale: f64) -> Option<f64> {
    let n = turning.points.len();
    if n < 4 {
        return None;
    }
    let y = |k: usize| turning.points[n - 4 + k].state.y;
    let d = [y(1) - y(0), y(2) - y(1), y(3) - y(2)];
    let (r1, r2) = (d[1] / d[0], d[2] / d[1]);
    let geometric = [r1, r2].iter().all(|r| *r > 0.0 && *r < 1.0)
        && (r2 - r1).abs() <= 0.02 * r2
        && d[2].abs() > limit;
    let guess = y(3) + d[2] * r2 / (1.0 - r2);
    (geometric && (guess - equilibrium).abs() > 1e-3 * scale).then_some(guess)
}

/// The maximum of y after the next turning point of the slide from (y, 0), a maximum of y:
/// the turning-point map of a pure-slip cycle about steady sliding; `None` when the slide
/// sticks or reverses first, or does not turn within [`MAP_PERIODS`] natural periods.
fn turning_map(restart: &Restart, y: f64) -> Result<Option<f64>> {
    let mut solver = restart(State { y, v: 0.0 })?;
    let end = MAP_PERIODS as f64 * TAU;
    while solver.time() < end {
        let event = solver.advance((solver.time() + TAU).min(end))?;
        let mut next = None;
        velocity_zeros(&*solver, SPACING, |s, maximum| {
            if maximum && next.is_none() {
                next = Some(s.y);
            }
        });
        if next.is_some() {
            return Ok(next);
        }
        if event.is_some_and(|e| e.kind != EventKind::Slip) {
            return Ok(None);
        }
    }
    Ok(None)
}

/// A pure-slip cycle about steady sliding settled by Newton's method on the turning-point
/// map P (the maximum y of the next turning point from a maximum y, [`turning_map`]), from
/// `guess` (Aitken's limit of the maxima, [`geometric_limit`], the last of which is `last`):
/// x ← x + (P(x) − x)/(1 − P'), with P' by central differences of the solver at its own
/// tolerance (1e-12) a step 10⁻⁵ of the scale apart, computed again where the steps do not
/// shrink threefold, until a step is below 10⁻² of `limit`. The fixed point is accepted
/// where it is stable (0 ≤ P' < 1: the map of a planar flow does not fall), lies beyond the
/// last maximum in the direction the maxima move, and within half the remaining distance of
/// Aitken's limit; and then only as the plain search confirms it: the search from (x, 0),
/// without Newton and within [`CONFIRM_PERIODS`] natural periods (or the `remaining` ones of
/// the search, if fewer), must repeat at the
/// turning point within 10³ `limit` of x, and its record is the answer (its times from its
/// own start). `None` otherwise: the search goes on as without Newton.
fn settle_by_newton(
    restart: &Restart,
    options: &SteadyOptions,
    guess: f64,
    last: f64,
    limit: f64,
    remaining: usize,
) -> Result<Option<SteadyState>> {
    let scale = limit / options.tolerance;
    let h = 1e-5 * scale;
    let (mut x, mut slope, mut previous) = (guess, None, f64::INFINITY);
    let mut converged = false;
    for _ in 0..NEWTON_ITERATIONS {
        let d = match slope {
            Some(d) => d,
            None => {
                let (Some(up), Some(down)) =
                    (turning_map(restart, x + h)?, turning_map(restart, x - h)?)
                else {
                    return Ok(None);
                };
                let d = (up - down) / (2.0 * h);
                if !(-1e-6..1.0).contains(&d) {
                    return Ok(None);
                }
                slope = Some(d);
                d
            }
        };
        let Some(image) = turning_map(restart, x)? else {
            return Ok(None);
        };
        let step = (image - x) / (1.0 - d);
        x += step;
        if !x.is_finite() {
            return Ok(None);
        }
        if step.abs() <= 1e-2 * limit {
            converged = true;
            break;
        }
        if step.abs() > previous / 3.0 {
            slope = None;
        }
        previous = step.abs();
    }
    let toward = (x - last) * (guess - last) > 0.0;
    if !converged || !toward || (x - guess).abs() > 0.5 * (guess - last).abs() + limit {
        return Ok(None);
    }
    if remaining < 2 {
        return Ok(None);
    }
    let mut plain = *options;
    plain.max_periods = remaining.min(CONFIRM_PERIODS);
    let mut solver = restart(State { y: x, v: 0.0 })?;
    let found = search(solver.as_mut(), &plain, None)?;
    let confirmed = found.self_excited.is_some_and(|c| {
        c.section == Some(CycleSection::TurningPoint)
            && (found.strobes[0].y - x).abs() <= 1e3 * limit
    });
    Ok(confirmed.then_some(found))
}

/// `steady`, found by a search started at τ = 0, with its times moved on by `offset`.
fn shifted(mut steady: SteadyState, offset: f64) -> SteadyState {
    steady.start += offset;
    for e in &mut steady.events {
        e.tau += offset;
    }
    if let Some(cycle) = steady.self_excited.as_mut() {
        cycle.time_to_settle += offset;
        steady.periods_to_settle =
            (cycle.time_to_settle / steady.params.drive_period()).ceil() as usize;
    }
    steady
}

/// Whether the last distances from steady sliding decay geometrically (see the module
/// documentation).
fn decays(distances: &VecDeque<f64>, scale: f64) -> bool {
    if distances.len() < 4 || distances[3] > 1e-2 * scale {
        return false;
    }
    let ratios: Vec<f64> = (1..4).map(|i| distances[i] / distances[i - 1]).collect();
    ratios.iter().all(|&r| r > 0.0 && r < 1.0)
        && ratios
            .windows(2)
            .all(|pair| (pair[1] - pair[0]).abs() <= 1e-3 * pair[0])
}

/// The record of the cycle from section point `a` to `b`.
#[allow(clippy::too_many_arguments)]
fn record_cycle(
    params: &Params,
    options: &SteadyOptions,
    section: CycleSection,
    a: Point,
    b: Point,
    log: &VecDeque<Mark>,
    equilibrium: f64,
    damping: f64,
) -> Result<SteadyState> {
    let period = b.tau - a.tau;
    let mut events = Vec::new();
    let (mut y_min, mut y_max) = (a.state.y.min(b.state.y), a.state.y.max(b.state.y));
    let mut stuck_since = (section == CycleSection::StickOnset).then_some(a.tau);
    let mut stops = Vec::new();
    for mark in log.iter().filter(|m| m.tau() > a.tau && m.tau() <= b.tau) {
        match *mark {
            Mark::Event(e) => {
                y_min = y_min.min(e.y);
                y_max = y_max.max(e.y);
                match e.kind {
                    EventKind::Stick => stuck_since = Some(e.tau),
                    EventKind::Slip => {
                        if let Some(s) = stuck_since.take() {
                            stops.push(e.tau - s);
                        }
                    }
                    EventKind::Turn => {}
                }
                if e.tau < b.tau {
                    events.push(e);
                }
            }
            Mark::Extreme { y, .. } => {
                y_min = y_min.min(y);
                y_max = y_max.max(y);
            }
        }
    }
    // The stick at the section point itself opens the cycle: its event leads the record.
    if section == CycleSection::StickOnset {
        events.insert(
            0,
            Event {
                tau: a.tau,
                y: a.state.y,
                kind: EventKind::Stick,
            },
        );
    }
    // (Touches of the belt's speed, `is_touch`, are neither stops nor time stuck.)
    let min_stop = options.min_stop_fraction * TAU;
    stops.retain(|&d| d > min_stop);
    let counted = stops.len();
    let stuck = stops.iter().fold(0.0, |sum, d| sum + d);
    let class = if counted > 0 {
        MotionClass::StickSlipCycle
    } else {
        MotionClass::PureSlipCycle
    };
    let cycle = SelfExcited {
        period: Some(period),
        stick_fraction: if period > 0.0 { stuck / period } else { 0.0 },
        section: Some(section),
        equilibrium,
        sliding_damping: damping,
        sliding_stability: SlidingStability::of(damping),
        time_to_settle: b.tau,
    };
    Ok(steady_state(
        params,
        class,
        cycle,
        (y_min, y_max),
        a.tau,
        events,
        [a.state, b.state],
        (counted, stops.iter().copied().fold(0.0, f64::max)),
    ))
}

/// Steady sliding, reached at `tau`.
fn sliding(params: &Params, tau: f64, equilibrium: f64, damping: f64) -> SteadyState {
    let at = State {
        y: equilibrium,
        v: 0.0,
    };
    let cycle = SelfExcited {
        period: None,
        stick_fraction: 0.0,
        section: None,
        equilibrium,
        sliding_damping: damping,
        sliding_stability: SlidingStability::of(damping),
        time_to_settle: tau,
    };
    steady_state(
        params,
        MotionClass::SteadySliding,
        cycle,
        (equilibrium, equilibrium),
        tau,
        Vec::new(),
        [at, at],
        (0, 0.0),
    )
}

/// No cycle within the cap: the last stretch as it is, class from its stops.
fn unsettled<S: Solver + ?Sized>(
    params: &Params,
    solver: &S,
    log: &VecDeque<Mark>,
    (equilibrium, damping): (f64, f64),
    length: f64,
    min_stop: f64,
) -> SteadyState {
    let end = solver.state();
    let (mut y_min, mut y_max) = (end.y, end.y);
    let mut events = Vec::new();
    for mark in log {
        let y = match *mark {
            Mark::Event(e) => {
                events.push(e);
                e.y
            }
            Mark::Extreme { y, .. } => y,
        };
        y_min = y_min.min(y);
        y_max = y_max.max(y);
    }
    let stops = stops_of(events.iter(), min_stop, solver.time()).len();
    let class = if stops > 0 {
        MotionClass::Undecided
    } else {
        MotionClass::Sliding
    };
    let cycle = SelfExcited {
        period: None,
        stick_fraction: 0.0,
        section: None,
        equilibrium,
        sliding_damping: damping,
        sliding_stability: SlidingStability::of(damping),
        time_to_settle: length,
    };
    let start = log.front().map_or(solver.time(), Mark::tau);
    steady_state(
        params,
        class,
        cycle,
        (y_min, y_max),
        start,
        events,
        [end, end],
        (stops, 0.0),
    )
}

/// The [`SteadyState`] of a self-excited motion.
#[allow(clippy::too_many_arguments)]
fn steady_state(
    params: &Params,
    class: MotionClass,
    cycle: SelfExcited,
    (y_min, y_max): (f64, f64),
    start: f64,
    events: Vec<Event>,
    [first, last]: [State; 2],
    (stops, longest_stop): (usize, f64),
) -> SteadyState {
    let amplitude = 0.5 * (y_max - y_min);
    SteadyState {
        params: *params,
        class,
        period: None,
        periods_to_settle: (cycle.time_to_settle / params.drive_period()).ceil() as usize,
        recorded_periods: 1,
        stops,
        stops_per_period: stops as f64,
        longest_stop,
        symmetric: false,
        y_min,
        y_max,
        peak: y_max.abs().max(y_min.abs()),
        gain: if amplitude == 0.0 { 0.0 } else { f64::INFINITY },
        start,
        events,
        strobes: vec![first, last],
        half_strobes: Vec::new(),
        spectrum: None,
        trace: Vec::new(),
        lyapunov: None,
        self_excited: Some(cycle),
    }
}
