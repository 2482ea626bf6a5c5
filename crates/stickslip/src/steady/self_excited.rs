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
//!   sticking (y at the stick event, y' = vb).
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
//!   y'' + (2ζ + μ'(|vb|)) y' + y = 0, then takes it there. A damped Coulomb belt is decided
//!   at the first turning point nearer y_e than |vb|: from there its slide can never stick
//!   again (its energy falls), so it is the linear one and decays onto y_e.
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
    let mut solver = factory.make(*params, initial)?;
    self_excited_state(solver.as_mut(), options)
}

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
    let options = options.validate()?;
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

    let mut sticks = Sections::default();
    let mut reversals = Sections::default();
    let mut turning = Sections::default();
    let mut log: VecDeque<Mark> = VecDeque::new();
    // |y − y_e| at the last turning points, for the decay towards steady sliding.
    let mut distances: VecDeque<f64> = VecDeque::with_capacity(4);

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
        equilibrium,
        damping,
        cap - start,
    ))
}

/// Whether a damped Coulomb belt's slide from a turning point at `distance` from steady
/// sliding ends there, exactly: while the slip keeps its sign the slide is the linear
/// y'' + 2ζ y' + y = y_e, whose energy (y − y_e)² + y'² falls at the rate 4ζ y'², so from a
/// turning point (y' = 0) on |y'| ≤ `distance`; below |vb| the slip s = y' − vb never
/// reaches 0, the block never sticks again and the slide decays onto y_e (ζ > 0). (The
/// geometric test of [`decays`] waits for the distance to fall below 10⁻² of the scale;
/// this one decides a map's sliding points several natural periods sooner, with the same
/// class.)
fn never_sticks(params: &Params, distance: f64) -> bool {
    params.law.is_coulomb() && params.zeta > 0.0 && distance < params.vb.abs()
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
    let mut stuck = 0.0;
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
                            stuck += e.tau - s;
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
    let min_stop = options.min_stop_fraction * TAU;
    let counted = stops.iter().filter(|&&d| d > min_stop).count();
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
    equilibrium: f64,
    damping: f64,
    length: f64,
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
    let stops = events.iter().filter(|e| e.kind == EventKind::Stick).count();
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
