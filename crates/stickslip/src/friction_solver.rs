//! The solver of a smooth friction law on a moving belt: the Stribeck and cubic laws of
//! [`crate::friction`].
//!
//! ```text
//! slipping, s = y' − vb ≠ 0:   y'' + 2ζ y' + y + sgn(s) μ(|s|) = β cos(w τ + φ)
//! stuck,    y' = vb:           holds while |β cos(w τ + φ) − y − 2ζ vb| ≤ μs
//! ```
//!
//! A switch model. **Slip phases** are integrated by the stiff integrator of smooth laws
//! ([`crate::stiff::Radau5`]) with the law D(v) = sgn·μ(sgn·(v − vb)) of the phase's slip
//! direction, which is smooth while the slip keeps its sign (the law's value and slope,
//! [`FrictionLaw::value_and_slope`]). **Stick phases** are exact: y = y_s + vb (τ − τ_s),
//! and the stop ends where the net force first reaches ±μs (in closed form without a belt,
//! and by the exact solver's bracketed search of a cosine minus a ramp with one).
//!
//! **Events.** The end of a slip phase (s = 0) is found on the step's dense output and then
//! polished by Newton's method on the step size: the integrator's own step from the last
//! accepted state, of exactly the size that puts s at zero (|s| ≤ 1e-12 at the event, and
//! the event time to 1e-12 for any transversal crossing). There the net force
//! f = β cos(w τ + φ) − y − 2ζ vb decides: |f| ≤ μs sticks (a `stick` event), otherwise the
//! slip reverses (a `turn`). A stop ends in a `slip` event. Each law starts from the static
//! level at zero slip, μ(0) = μs, so the friction force is continuous at every switch.

use crate::cancel::Cancel;
use crate::error::{Error, Result};
use crate::friction::FrictionLaw;
use crate::params::{Params, State};
use crate::solver::{Event, EventKind, Phase, Sample, Solver, Stats};
use crate::stiff::dop853::Attempt;
use crate::stiff::{Dop853, DopStep, Radau5, Settings, SmoothLaw, Step};
use std::f64::consts::TAU;

/// Relative and absolute tolerance of the slip phases' integration.
pub const FRICTION_TOLERANCE: f64 = 1e-12;
/// Largest step of a slip phase (τ).
const MAX_STEP: f64 = 0.25;
/// Zero-length phases in a row at one instant before a stop is taken as final (a tangency
/// of the net force with the static limit).
const MAX_REPEATS: u32 = 4;

/// The friction force of one slip direction as a smooth law of the velocity v = y':
/// D(v) = sgn·μ(sgn·(v − vb)), continued beyond s = 0 by its tangent (only Newton's iterates
/// go there: the phase ends at s = 0).
#[derive(Debug, Clone, Copy)]
pub struct SlipLaw {
    law: FrictionLaw,
    mu_s: f64,
    vb: f64,
    sign: f64,
}

impl SlipLaw {
    /// The law of a slip in direction `sign` (±1) with the friction law, μs and vb of
    /// `params`.
    pub(crate) fn new(params: &Params, sign: f64) -> Self {
        Self {
            law: params.law,
            mu_s: params.mu_s,
            vb: params.vb,
            sign,
        }
    }

    /// μ and μ' at slip speed s ≥ 0, the slope kept finite (a Stribeck law with δ < 1 is
    /// infinitely steep at s = 0: its slope is taken a hair away).
    fn mu(&self, s: f64) -> (f64, f64) {
        let (value, slope) = self.law.value_and_slope(self.mu_s, s);
        if slope.is_finite() {
            (value, slope)
        } else {
            let h = 1e-12;
            (value, self.law.value_and_slope(self.mu_s, h).1)
        }
    }
}

impl SmoothLaw for SlipLaw {
    /// μs, vb, then the friction law's own: vs, δ, η (Stribeck) or k1, k3 (cubic; the
    /// fifth column is then zero).
    const PARAMETERS: &'static [&'static str] = &["mu_s", "vb", "vs|k1", "delta|k3", "eta"];

    fn validate(&self) -> Result<Self> {
        self.law.validate(self.mu_s)?;
        Ok(*self)
    }

    fn value_and_slope(&self, v: f64) -> (f64, f64) {
        let s = self.sign * (v - self.vb);
        if s >= 0.0 {
            let (mu, slope) = self.mu(s);
            (self.sign * mu, slope)
        } else {
            let (mu0, slope0) = self.mu(0.0);
            (self.sign * (mu0 + slope0 * s), slope0)
        }
    }

    /// ∂D/∂(μs, vb, θ) of D(v) = σ μ(s), s = σ(v − vb): ∂D/∂vb = −μ'(s), and σ ∂μ/∂θ at
    /// fixed s for the others. Beyond s = 0 (only Newton's iterates go there) the values at
    /// s = 0 with the tangent's slope for vb.
    fn parameter_derivatives(&self, v: f64, out: &mut [f64]) {
        let s = (self.sign * (v - self.vb)).max(0.0);
        out.iter_mut().for_each(|x| *x = 0.0);
        let slope = self.mu(s).1;
        let mut d = [0.0, -slope / self.sign, 0.0, 0.0, 0.0];
        match self.law {
            FrictionLaw::Coulomb => d[0] = 1.0,
            FrictionLaw::Stribeck { vs, delta, eta: _ } => {
                let x = s / vs;
                let power = x.powf(delta);
                let fall = (-power).exp();
                d[0] = fall;
                d[2] = (self.mu_s - 1.0) * fall * delta * power / vs;
                d[3] = if x > 0.0 {
                    -(self.mu_s - 1.0) * fall * power * x.ln()
                } else {
                    0.0
                };
                d[4] = s;
            }
            FrictionLaw::Cubic { .. } => {
                d[0] = 1.0;
                d[2] = -s;
                d[3] = s * s * s;
            }
        }
        for (o, x) in out.iter_mut().zip(d) {
            *o = self.sign * x;
        }
    }
}

/// The integrator of the slip phases ([`FrictionSolver::with_integrator`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum SlipIntegrator {
    /// Radau IIA of order 5 ([`Radau5`]): the steps the stability tools differentiate
    /// ([`crate::stability::FrictionDynamics`]).
    #[default]
    Radau,
    /// The explicit Dormand–Prince pair of order 8 ([`Dop853`]) at the same tolerance: several
    /// times cheaper on the slips of these laws, which are not stiff; no tangent dynamics
    /// (its steps are not differentiated). The steady-state search of a self-excited
    /// belt uses it.
    Explicit,
}

/// A slip phase's integrator.
#[derive(Debug, Clone)]
enum Integrator {
    Radau(Box<Radau5<SlipLaw>>),
    Explicit(Box<Dop853<SlipLaw>>),
}

/// A step of either integrator.
#[derive(Debug, Clone, Copy)]
enum SlipStep {
    Radau(Step),
    Explicit(DopStep),
}

impl SlipStep {
    fn t1(&self) -> f64 {
        match self {
            SlipStep::Radau(s) => s.t1(),
            SlipStep::Explicit(s) => s.t1(),
        }
    }

    fn x1(&self) -> [f64; 2] {
        match self {
            SlipStep::Radau(s) => s.x1,
            SlipStep::Explicit(s) => s.x1,
        }
    }

    fn eval(&self, t: f64) -> [f64; 2] {
        match self {
            SlipStep::Radau(s) => s.eval(t),
            SlipStep::Explicit(s) => s.eval(t),
        }
    }
}

/// A slip phase's step not yet reported to its end: the step (ending at an event when
/// `event` is set) and what the event leads to.
#[derive(Debug, Clone, Copy)]
struct Pending {
    step: SlipStep,
    event: Option<EventKind>,
}

/// What the solver is doing.
#[derive(Debug, Clone)]
enum Mode {
    /// Slipping in direction `sign` (s = y' − vb of that sign), on the integrator.
    Slip {
        sign: f64,
        integrator: Integrator,
        pending: Option<Pending>,
        /// Whether the phase began at s = 0 and has not yet left it (its first step).
        from_zero: bool,
    },
    /// Stuck to the belt since `tau0` at `y0`; the stop ends at `exit` (infinite: never) in
    /// direction `exit_sign`.
    Stick {
        tau0: f64,
        y0: f64,
        exit: f64,
        exit_sign: f64,
    },
}

/// The solver of a smooth friction law (see the module documentation).
///
/// ```
/// use stickslip::friction::FrictionLaw;
/// use stickslip::friction_solver::FrictionSolver;
/// use stickslip::{solver::run_until, Params, State, EventKind};
/// // A Stribeck belt without a drive: stick-slip from rest.
/// let law = FrictionLaw::Stribeck { vs: 0.5, delta: 2.0, eta: 0.0 };
/// let params = Params::new(0.05, 1.0, 0.0).unwrap().with_mu_s(1.5).unwrap()
///     .with_vb(0.2).unwrap().with_law(law).unwrap();
/// let mut solver = FrictionSolver::new(params, State::default()).unwrap();
/// let mut kinds = Vec::new();
/// run_until(&mut solver, 100.0, |e| kinds.push(e.kind)).unwrap();
/// assert!(kinds.contains(&EventKind::Stick) && kinds.contains(&EventKind::Slip));
/// ```
#[derive(Debug, Clone)]
pub struct FrictionSolver {
    params: Params,
    mode: Mode,
    now: f64,
    state: State,
    /// The interval of the last advance, its phase, and the step or stop it covered.
    interval: (f64, f64),
    interval_phase: Phase,
    last_step: Option<SlipStep>,
    last_stick: (f64, f64),
    repeats: u32,
    stats: Stats,
    cancel: Cancel,
    integrator: SlipIntegrator,
}

impl Drop for FrictionSolver {
    /// Adds the work counters to the token's ([`Cancel::work`]).
    fn drop(&mut self) {
        if !self.cancel.is_never() {
            self.cancel.add_work(Solver::stats(self));
        }
    }
}

impl FrictionSolver {
    /// A solver from `initial` at τ = 0. Starting at the belt's speed (y' = vb) the block is
    /// stuck while the net force is within ±μs.
    ///
    /// # Errors
    /// Invalid parameters or state.
    pub fn new(params: Params, initial: State) -> Result<Self> {
        Self::with_cancel(params, initial, Cancel::never())
    }

    /// As [`FrictionSolver::new`], checking `cancel` at every step.
    ///
    /// # Errors
    /// As [`FrictionSolver::new`].
    pub fn with_cancel(params: Params, initial: State, cancel: Cancel) -> Result<Self> {
        Self::with_integrator(params, initial, SlipIntegrator::Radau, cancel)
    }

    /// As [`FrictionSolver::with_cancel`], the slips on `integrator`.
    ///
    /// # Errors
    /// As [`FrictionSolver::new`].
    pub fn with_integrator(
        params: Params,
        initial: State,
        integrator: SlipIntegrator,
        cancel: Cancel,
    ) -> Result<Self> {
        let params = params.validate()?;
        let initial = State::new(initial.y, initial.v)?;
        let mut solver = Self {
            params,
            mode: Mode::Stick {
                tau0: 0.0,
                y0: initial.y,
                exit: f64::INFINITY,
                exit_sign: 0.0,
            },
            now: 0.0,
            state: initial,
            interval: (0.0, 0.0),
            interval_phase: Phase::Stick,
            last_step: None,
            last_stick: (0.0, initial.y),
            repeats: 0,
            stats: Stats::default(),
            cancel,
            integrator,
        };
        let s = initial.v - params.vb;
        if s != 0.0 {
            solver.start_slip(0.0, initial.y, initial.v, s.signum(), false);
        } else {
            let f = solver.net_force(0.0, initial.y);
            if f.abs() <= params.mu_s {
                solver.start_stick(0.0, initial.y, false);
            } else {
                solver.start_slip(0.0, initial.y, params.vb, f.signum(), true);
            }
        }
        solver.interval_phase = solver.phase();
        Ok(solver)
    }

    /// The net force β cos(w τ + φ) − y − 2ζ vb on a block at the belt's speed.
    fn net_force(&self, tau: f64, y: f64) -> f64 {
        self.params.drive(tau) - y - self.params.belt_force()
    }

    /// The integrator's step that the last advance covered (part of), when it covered a slip
    /// phase on Radau IIA: the tangent dynamics differentiate it
    /// ([`crate::stability::FrictionDynamics`]). `None` on the explicit integrator.
    pub(crate) fn slip_step(&self) -> Option<&Step> {
        match (self.interval_phase, &self.last_step) {
            (Phase::SlipPositive | Phase::SlipNegative, Some(SlipStep::Radau(step))) => Some(step),
            _ => None,
        }
    }

    fn start_slip(&mut self, tau: f64, y: f64, v: f64, sign: f64, from_zero: bool) {
        let p = &self.params;
        let law = SlipLaw::new(p, sign);
        let settings = Settings {
            rtol: FRICTION_TOLERANCE,
            atol: FRICTION_TOLERANCE,
            max_step: MAX_STEP,
            initial_step: 1e-3,
        };
        let integrator = match self.integrator {
            SlipIntegrator::Radau => {
                Integrator::Radau(Box::new(Radau5::new(*p, law, tau, [y, v], settings)))
            }
            SlipIntegrator::Explicit => {
                Integrator::Explicit(Box::new(Dop853::new(*p, law, tau, [y, v], settings)))
            }
        };
        self.mode = Mode::Slip {
            sign,
            integrator,
            pending: None,
            from_zero,
        };
    }

    fn start_stick(&mut self, tau: f64, y: f64, allow_now: bool) {
        let (exit, exit_sign) = stop_end(&self.params, tau, y, allow_now);
        self.mode = Mode::Stick {
            tau0: tau,
            y0: y,
            exit: tau + exit,
            exit_sign,
        };
    }

    /// Take one step of the slip phase and find whether s reaches 0 in it; the step then
    /// ends at that instant.
    fn integrate(&mut self) -> Result<Pending> {
        self.cancel.charge(1)?;
        let vb = self.params.vb;
        let Mode::Slip {
            sign,
            integrator,
            from_zero,
            ..
        } = &mut self.mode
        else {
            unreachable!("integrate is called while slipping");
        };
        let sign = *sign;
        let radau = match integrator {
            Integrator::Radau(radau) => radau,
            Integrator::Explicit(dop) => {
                let from_zero_now = *from_zero;
                *from_zero = false;
                let pending = explicit_step(dop, sign, vb, from_zero_now, &mut self.stats)?;
                return Ok(pending);
            }
        };
        let before = radau.clone();
        let step = radau.step()?;
        let (was, now) = (before.counters, radau.counters);
        self.stats.evaluations += now.rhs - was.rhs;
        self.stats.steps += now.accepted - was.accepted;
        self.stats.rejected += now.rejected - was.rejected;
        let mut cubic = step.cubic(1);
        for c in cubic.iter_mut() {
            *c *= sign;
        }
        cubic[0] -= sign * vb;
        // (The first step of a phase that starts at s = 0 leaves it: its rounding there is
        // no crossing.)
        let floor = if *from_zero { 1e-3 } else { 0.0 };
        let mut first = f64::NAN;
        crate::stiff::cubic::crossings(&cubic, 0.0, |theta| {
            if first.is_nan() && theta > floor {
                first = theta;
            }
        });
        let end_s = sign * (step.x1[1] - vb);
        if first.is_nan() && end_s <= 0.0 && !(*from_zero && end_s == 0.0) {
            first = 1.0;
        }
        *from_zero = false;
        let pending = if first.is_nan() {
            Pending {
                step: SlipStep::Radau(step),
                event: None,
            }
        } else {
            let polished = polish(&before, &step, first, sign, vb)?;
            Pending {
                step: SlipStep::Radau(polished),
                event: Some(EventKind::Stick),
            }
        };
        Ok(pending)
    }

    /// The slip ended at s = 0 at `tau` with `y`: stick, or reverse.
    fn switch_at_zero(&mut self, tau: f64, y: f64, sign: f64) -> EventKind {
        let f = self.net_force(tau, y);
        let zero_length = matches!(self.interval, (a, b) if a == b);
        self.repeats = if zero_length { self.repeats + 1 } else { 0 };
        if f.abs() <= self.params.mu_s || f.signum() == sign || self.repeats >= MAX_REPEATS {
            self.start_stick(tau, y, self.repeats < MAX_REPEATS);
            EventKind::Stick
        } else {
            self.start_slip(tau, y, self.params.vb, f.signum(), true);
            EventKind::Turn
        }
    }
}

/// The step from `before`'s state whose end has s = sign·(v − vb) = 0, near θ = `guess` of
/// `step`: Newton's method on the step size ([`newton_on_step_size`]), each iterate the
/// integrator's own step of that size (a size it cannot take halves the bracket).
fn polish(before: &Radau5<SlipLaw>, step: &Step, guess: f64, sign: f64, vb: f64) -> Result<Step> {
    let found = newton_on_step_size(
        before.params(),
        before.law(),
        step.h,
        guess * step.h,
        sign,
        vb,
        |h| {
            let mut trial = before.clone();
            let candidate = trial.fixed_step(h)?;
            let (end, t) = (candidate.x1, candidate.t1());
            Some((candidate, end, t))
        },
    );
    let mut found = found.ok_or(Error::StepSizeTooSmall {
        tau: step.t0,
        step: step.h,
    })?;
    // At the event the block moves with the belt.
    found.x1[1] = vb;
    Ok(found)
}

/// Newton's method on the size h of a step from a slip's state for the end at
/// s = sign·(v − vb) = 0 (ds/dh = sign·y'' there), from h = `guess`, each iterate kept inside
/// the bracket (0, `size`) that the signs of s at the ends taken so far narrow (bisection
/// where Newton's iterate leaves it); at most 60 iterates, to |s| ≤ 1e-13·max(1, |vb|) or a
/// bracket of 1e-14·max(1, |τ|). `end(h)` takes the integrator's own step of size h: what it
/// found, the end state (y, y') and time, or `None` where no step of that size is taken (the
/// bracket is then halved). The last step taken, `None` if none was.
fn newton_on_step_size<T>(
    params: &Params,
    law: &SlipLaw,
    size: f64,
    guess: f64,
    sign: f64,
    vb: f64,
    mut end: impl FnMut(f64) -> Option<(T, [f64; 2], f64)>,
) -> Option<T> {
    let (mut lo, mut hi) = (0.0, size);
    let mut h = guess;
    let mut best = None;
    for _ in 0..60 {
        let Some((found, [y, v], t)) = end(h) else {
            h = 0.5 * (lo + hi);
            continue;
        };
        let s = sign * (v - vb);
        // ds/dh = sign·y''.
        let (d, _) = law.value_and_slope(v);
        let accel = params.drive(t) - y - 2.0 * params.zeta * v - d;
        if s > 0.0 {
            lo = h;
        } else {
            hi = h;
        }
        best = Some(found);
        if s.abs() <= 1e-13 * 1f64.max(vb.abs()) || hi - lo <= 1e-14 * 1f64.max(t.abs()) {
            break;
        }
        let newton = h - s / (sign * accel);
        h = if accel != 0.0 && newton > lo && newton < hi {
            newton
        } else {
            0.5 * (lo + hi)
        };
    }
    best
}

/// Samples of s per explicit step in the search for its first zero.
const ZERO_SAMPLES: usize = 16;

/// The first θ in (`floor`, 1] of an explicit step where s = sign·(v − vb) reaches 0: the
/// first of [`ZERO_SAMPLES`] samples of the dense output at or below 0 (or the end), the
/// zero placed between it and the sample before by bisection on the dense output to 10⁻¹³
/// in θ; `None` where s stays positive. (A pair of zeros closer than 1/16 of a step, s
/// touching zero, can be missed, as on the stiff integrator's cubics it cannot.)
fn first_zero(step: &DopStep, sign: f64, vb: f64, floor: f64, from_zero: bool) -> Option<f64> {
    // Where s starts further from 0 than the dense output can move in the step
    // ([`DopStep::reach`], with the rounding of x0 + Δ and of the difference with vb), every
    // sample below is positive: no zero, and no need to sample (most steps of a slip).
    let (v0, reach) = (step.x0[1], step.reach(1));
    if sign * (v0 - vb) > reach + 4.0 * f64::EPSILON * (v0.abs() + vb.abs() + reach) {
        return None;
    }
    let s = |theta: f64| sign * (step.component(1, theta) - vb);
    let mut previous = floor;
    for i in 1..=ZERO_SAMPLES {
        let theta = i as f64 / ZERO_SAMPLES as f64;
        if theta <= floor {
            continue;
        }
        let value = s(theta);
        // (The first step of a phase that starts at s = 0 leaves it: its rounding at the
        // start is no crossing; nor is an end exactly at s = 0 of such a step.)
        if value < 0.0 || (value == 0.0 && !(from_zero && i == ZERO_SAMPLES)) {
            let (mut lo, mut hi) = (previous, theta);
            while hi - lo > 1e-13 {
                let mid = 0.5 * (lo + hi);
                if s(mid) > 0.0 {
                    lo = mid;
                } else {
                    hi = mid;
                }
            }
            return Some(hi);
        }
        previous = theta;
    }
    None
}

/// One step of a slip phase on the explicit integrator `dop` in direction `sign`, ending at
/// s = sign·(v − vb) = 0 where the slip ends in it. An accepted step whose dense output
/// reaches s = 0 ([`first_zero`]) is cut there ([`polish_explicit`]); an attempt rejected
/// past s = 0 (the law's kink there spoils its error estimate) is replaced by the step that
/// ends at s = 0, when the error estimate accepts that one (else the step control goes on
/// with a smaller step). `from_zero`: the phase starts at s = 0 and this is its first step.
fn explicit_step(
    dop: &mut Dop853<SlipLaw>,
    sign: f64,
    vb: f64,
    from_zero: bool,
    stats: &mut Stats,
) -> Result<Pending> {
    let s = |x: &[f64; 2]| sign * (x[1] - vb);
    loop {
        let before = dop.clone();
        let attempt = dop.step_until(|x| !from_zero && s(x) <= 0.0)?;
        let (was, now) = (before.counters, dop.counters);
        stats.evaluations += now.rhs - was.rhs;
        stats.steps += now.accepted - was.accepted;
        stats.rejected += now.rejected - was.rejected;
        let mut work = 0;
        let found = match attempt {
            Attempt::Accepted(step) => {
                let floor = if from_zero { 1e-3 } else { 0.0 };
                let Some(theta) = first_zero(&step, sign, vb, floor, from_zero) else {
                    return Ok(Pending {
                        step: SlipStep::Explicit(step),
                        event: None,
                    });
                };
                polish_explicit(&before, step.h, theta * step.h, sign, vb, false, &mut work)?
            }
            Attempt::Crossed { h, end } => {
                let (s0, s1) = (s(&before.state()), s(&end));
                let guess = h * s0 / (s0 - s1);
                polish_explicit(&before, h, guess, sign, vb, true, &mut work)?
            }
        };
        stats.evaluations += work;
        // (The phase ends at the event: the integrator is not moved on to it.)
        if let Some(step) = found {
            return Ok(Pending {
                step: SlipStep::Explicit(step),
                event: Some(EventKind::Stick),
            });
        }
    }
}

/// [`polish`] on the explicit integrator: the step from `before`'s state whose end has
/// s = 0, by Newton's method on the step size ([`newton_on_step_size`]) from `guess`, each
/// iterate the integrator's own step of that size, inside the bracket (0, `size`) of a step
/// whose end is past s = 0; with `checked`, only a step its error estimate accepts
/// (`None` otherwise). `work` counts the right-hand sides it evaluated.
fn polish_explicit(
    before: &Dop853<SlipLaw>,
    size: f64,
    guess: f64,
    sign: f64,
    vb: f64,
    checked: bool,
    work: &mut u64,
) -> Result<Option<DopStep>> {
    let t0 = before.time();
    let mut trial = before.clone();
    let h = newton_on_step_size(before.params(), before.law(), size, guess, sign, vb, |h| {
        let end = trial.end_of(h);
        *work += 11;
        Some((h, end, t0 + h))
    });
    let h = h.ok_or(Error::StepSizeTooSmall {
        tau: t0,
        step: size,
    })?;
    let found = if checked {
        trial.checked_step(h)
    } else {
        Some(trial.fixed_step(h))
    };
    *work += 15;
    // At the event the block moves with the belt.
    Ok(found.map(|mut step| {
        step.x1[1] = vb;
        step
    }))
}

/// The local time after `tau` and the direction at which a stop at `y` ends (infinite
/// time: never): the first outward crossing of ±μs by the net force.
fn stop_end(p: &Params, tau: f64, y: f64, allow_now: bool) -> (f64, f64) {
    let theta = (p.w * tau + p.phi).rem_euclid(TAU);
    if p.vb != 0.0 {
        let c = y + p.belt_force();
        return crate::exact::belt::stop_end(p.beta, p.w, theta, p.mu_s, c, p.vb, allow_now);
    }
    if p.beta == 0.0 {
        if y.abs() > p.mu_s && allow_now {
            return (0.0, -y.signum());
        }
        return (f64::INFINITY, 0.0);
    }
    let ahead = |psi: f64| {
        let d = (psi - theta).rem_euclid(TAU);
        if allow_now && d > TAU - 1e-12 {
            0.0
        } else {
            d
        }
    };
    let up = (y + p.mu_s) / p.beta;
    let down = (y - p.mu_s) / p.beta;
    if up <= -1.0 {
        return (0.0, 1.0);
    }
    if down >= 1.0 {
        return (0.0, -1.0);
    }
    let mut best = (f64::INFINITY, 0.0);
    if up < 1.0 {
        best = (ahead(TAU - up.acos()), 1.0);
    }
    if down > -1.0 {
        let d = ahead(down.acos());
        if d < best.0 {
            best = (d, -1.0);
        }
    }
    (best.0 / p.w, best.1)
}

impl Solver for FrictionSolver {
    fn params(&self) -> &Params {
        &self.params
    }

    fn time(&self) -> f64 {
        self.now
    }

    fn state(&self) -> State {
        self.state
    }

    fn phase(&self) -> Phase {
        match self.mode {
            Mode::Slip { sign, .. } if sign > 0.0 => Phase::SlipPositive,
            Mode::Slip { .. } => Phase::SlipNegative,
            Mode::Stick { .. } => Phase::Stick,
        }
    }

    fn drive(&self, tau: f64) -> f64 {
        self.params.drive(tau)
    }

    fn advance(&mut self, t_end: f64) -> Result<Option<Event>> {
        if t_end < self.now || t_end.is_nan() {
            return Err(Error::TimeBeforeCurrent {
                requested: t_end,
                current: self.now,
            });
        }
        let from = self.now;
        self.interval_phase = self.phase();
        match self.mode {
            Mode::Stick {
                tau0,
                y0,
                exit,
                exit_sign,
            } => {
                self.cancel.charge(1)?;
                let vb = self.params.vb;
                let target = t_end.min(exit);
                let y = y0 + vb * (target - tau0);
                self.now = target;
                self.state = State { y, v: vb };
                self.interval = (from, target);
                self.last_step = None;
                self.last_stick = (tau0, y0);
                if exit > t_end {
                    return Ok(None);
                }
                self.repeats = if target == tau0 { self.repeats + 1 } else { 0 };
                self.start_slip(target, y, vb, exit_sign, true);
                self.stats.events += 1;
                Ok(Some(Event {
                    tau: target,
                    y,
                    kind: EventKind::Slip,
                }))
            }
            Mode::Slip { sign, .. } => {
                if t_end == from {
                    self.interval = (from, from);
                    return Ok(None);
                }
                let pending = match &self.mode {
                    Mode::Slip {
                        pending: Some(p), ..
                    } if p.step.t1() > from => *p,
                    _ => {
                        let p = self.integrate()?;
                        if let Mode::Slip { pending, .. } = &mut self.mode {
                            *pending = Some(p);
                        }
                        p
                    }
                };
                let step = pending.step;
                let end = step.t1();
                let target = t_end.min(end);
                let x = if target == end {
                    step.x1()
                } else {
                    step.eval(target)
                };
                self.now = target;
                self.state = State { y: x[0], v: x[1] };
                self.interval = (from, target);
                self.last_step = Some(step);
                if target < end || pending.event.is_none() {
                    return Ok(None);
                }
                // The slip ends here (s = 0).
                let kind = self.switch_at_zero(end, x[0], sign);
                self.stats.events += 1;
                Ok(Some(Event {
                    tau: end,
                    y: x[0],
                    kind,
                }))
            }
        }
    }

    fn interval(&self) -> (f64, f64) {
        self.interval
    }

    fn dense(&self, tau: f64) -> Sample {
        let (y, v) = match (&self.last_step, self.interval_phase) {
            (Some(step), Phase::SlipPositive | Phase::SlipNegative) => {
                let x = step.eval(tau);
                (x[0], x[1])
            }
            _ => {
                let (tau0, y0) = self.last_stick;
                (y0 + self.params.vb * (tau - tau0), self.params.vb)
            }
        };
        Sample {
            tau,
            y,
            v,
            phase: self.interval_phase,
        }
    }

    fn stats(&self) -> Stats {
        self.stats
    }

    fn is_exact(&self) -> bool {
        false
    }
}
