//! The exact solver with its tangent dynamics: the 2×2 Jacobian of the flow carried along an
//! exact trajectory.

use super::matrix::Matrix2;
use super::segment::SlidingTransition;
use crate::error::{Error, Result};
use crate::exact::ExactSolver;
use crate::params::{Params, State};
use crate::solver::{Event, EventKind, Phase, Solver};

/// Outside [SCALE_BELOW, SCALE_ABOVE] the entries of J are rescaled into `log_scale`.
const SCALE_BELOW: f64 = 1e-100;
const SCALE_ABOVE: f64 = 1e100;

/// Below this the running product of turn saltation determinants is folded into its logarithm.
const FOLD_BELOW: f64 = 1e-150;

/// An [`ExactSolver`] that carries the Jacobian J = ∂x(τ)/∂x(τ₀) of its flow, x = (y, y'),
/// from the time τ₀ of the last [`TangentSolver::reset`] (or of its construction).
///
/// Every [`TangentSolver::advance`] advances the solver and multiplies J by the segment's
/// state-transition matrix ([`super::segment`]) and, at an event, by its saltation matrix
/// ([`super::saltation`]). The saltations read the numbers the solver decided the event with
/// (the acceleration and drive rate at the start of the new segment), so the tangent dynamics
/// follow the trajectory's own events exactly. The cost is one `exp` and one `sin_cos` per
/// sliding segment; the solver itself is untouched, so it runs as fast as ever when no
/// tangents are needed. Segment durations are differences of the solver's absolute times,
/// exact to ulp(τ) (about 10⁻¹¹ at τ ~ 10⁵).
///
/// Alongside J it keeps ln|det J| as a sum (−2ζ per unit of sliding time, ln(a⁺/a⁻) per turn),
/// so that the phase-area contraction is known even when J itself is renormalised, and
/// whether a stop has made J singular.
///
/// ```
/// use stickslip::stability::TangentSolver;
/// use stickslip::{Params, State};
/// // Free undamped motion far from the friction limit: J is a rotation until the first turn.
/// let params = Params::new(0.0, 1.0, 0.0).unwrap();
/// let mut tangent = TangentSolver::new(params, State { y: 5.0, v: 1.0 });
/// tangent.run_until(0.1, |_| {}).unwrap();
/// let j = tangent.jacobian().0;
/// assert!((j[0][0] - 0.1f64.cos()).abs() < 1e-15 && (j[1][0] + 0.1f64.sin()).abs() < 1e-15);
/// ```
#[derive(Debug, Clone)]
pub struct TangentSolver {
    solver: ExactSolver,
    tangent: Tangent,
}

/// The tangent dynamics alone: the Jacobian J carried along the advances of an exact solver
/// it does not own (see [`TangentSolver`], which owns its solver, for the method). The
/// steady-state search carries it along its own trajectory for the period whose image
/// starts Newton's method.
#[derive(Debug, Clone)]
pub(crate) struct Tangent {
    transition: SlidingTransition,
    zeta: f64,
    mu_s: f64,
    jacobian: Matrix2,
    /// ln of the factor taken out of `jacobian` to keep its entries within 10^±100.
    log_scale: f64,
    /// Sliding time since the reset (its share of ln|det J| is −2ζ times it).
    sliding_time: f64,
    /// Σ ln(a⁺/a⁻) of the turns folded so far.
    turn_log: f64,
    /// Π(a⁺/a⁻) of the turns not yet folded into `turn_log`.
    turn_product: f64,
    /// Stops since the reset (a motion that starts stuck counts one).
    stops: u64,
    /// Time of the first tangential release since the reset (J is not finite from there on).
    grazing: Option<f64>,
}

impl TangentSolver {
    /// A solver starting at τ = 0 from `initial`, with J = I.
    ///
    /// # Panics
    /// As [`ExactSolver::new`], for a friction law other than Coulomb's (the tools that take
    /// a user's law check it first and refuse).
    pub fn new(params: Params, initial: State) -> Self {
        Self::from_solver(ExactSolver::new(params, initial))
    }

    /// Carry the Jacobian along an existing solver from its current time on, with J = I there
    /// (for example after a transient run without tangents).
    pub fn from_solver(solver: ExactSolver) -> Self {
        let tangent = Tangent::new(&solver);
        Self { solver, tangent }
    }

    /// Start the Jacobian afresh at the current time: J = I, ln|det J| = 0, no stops.
    pub fn reset(&mut self) {
        self.tangent.reset(&self.solver);
    }

    /// Restart ln|det J| and the stop count at the current time, keeping J (for example to
    /// measure after a transient that has aligned J with the most unstable direction).
    pub fn reset_log_det(&mut self) {
        self.tangent.reset_log_det(&self.solver);
    }

    /// The exact solver underneath (for its state, dense output and statistics).
    pub fn solver(&self) -> &ExactSolver {
        &self.solver
    }

    /// The parameters of the model.
    pub fn params(&self) -> &Params {
        self.solver.params()
    }

    /// Current time τ.
    pub fn time(&self) -> f64 {
        self.solver.time()
    }

    /// State at the current time.
    pub fn state(&self) -> State {
        self.solver.state()
    }

    /// Phase of the motion at the current time.
    pub fn phase(&self) -> Phase {
        self.solver.phase()
    }

    /// The Jacobian J = ∂(y, y')(τ)/∂(y, y')(τ₀) since the last reset, divided by the factors
    /// [`TangentSolver::renormalize`] took out, and by e^s with s =
    /// [`TangentSolver::log_scale`] (0 unless the entries left 10^±100).
    pub fn jacobian(&self) -> Matrix2 {
        self.tangent.jacobian
    }

    /// The logarithm s of the factor e^s taken out of [`TangentSolver::jacobian`] whenever its
    /// largest entry left [10⁻¹⁰⁰, 10¹⁰⁰] (checked after every slide), so that long runs
    /// neither overflow nor underflow; 0 until then. [`TangentSolver::renormalize`] includes
    /// it and sets it back to 0.
    pub fn log_scale(&self) -> f64 {
        self.tangent.log_scale
    }

    /// Stops since the last reset (a motion stuck at the reset counts one). Each makes J
    /// singular.
    pub fn stops(&self) -> u64 {
        self.tangent.stops
    }

    /// ln|det J| since the last reset (not changed by renormalisation):
    /// −2ζ·(sliding time) + Σ_turns ln(a⁺/a⁻), or `None` when a stop has made J singular
    /// (det J = 0).
    pub fn log_det(&self) -> Option<f64> {
        self.tangent.log_det()
    }

    /// Time of the first tangential release (μs > 1 and the drive's rate zero at the
    /// release) since the last reset: the flow is not differentiable there and J is not
    /// finite from then on.
    pub fn grazing(&self) -> Option<f64> {
        self.tangent.grazing
    }

    /// Go on from the current state with a new solver whose clock starts at τ = 0, keeping J,
    /// ln|det J| and the stops. Only at a strobe (a whole number of drive periods since τ = 0),
    /// where the drive phase is φ again. Absolute times then stay small in a long run: their
    /// rounding, ulp(τ), doubles at every power of two and would otherwise change the segment
    /// durations the Jacobian sees (by about 10⁻¹⁰ relative at τ ~ 10⁵) from one stretch of the
    /// run to the next.
    pub(crate) fn restart_clock(&mut self) {
        // (The search keeps what it learned of the slides: the motion goes on.)
        let hints = self.solver.hints();
        self.solver.restart_at(self.solver.state(), hints);
    }

    /// Divide J by its Frobenius norm and return the logarithm of that norm, the factor e^s
    /// of [`TangentSolver::log_scale`] included (for Lyapunov exponents: the growth since the
    /// last renormalisation). ln|det J| is kept as it was.
    pub fn renormalize(&mut self) -> f64 {
        let t = &mut self.tangent;
        let norm = t.jacobian.norm();
        t.jacobian = t.jacobian.scaled(1.0 / norm);
        let growth = norm.ln() + t.log_scale;
        t.log_scale = 0.0;
        growth
    }

    /// Advance to the next event or to `t_end`, whichever comes first, as
    /// [`Solver::advance`], carrying J along.
    ///
    /// # Errors
    /// Whatever [`ExactSolver::advance`] reports.
    pub fn advance(&mut self, t_end: f64) -> Result<Option<Event>> {
        self.tangent.advance(&mut self.solver, t_end)
    }

    /// Advance to `t_end`, handing every event to `on_event`.
    ///
    /// # Errors
    /// [`Error::TimeBeforeCurrent`] when `t_end` lies before the current time; whatever
    /// [`ExactSolver::advance`] reports.
    pub fn run_until(&mut self, t_end: f64, on_event: impl FnMut(&Event)) -> Result<()> {
        self.tangent.run_until(&mut self.solver, t_end, on_event)
    }
}

/// The tangent dynamics along a motion, drive period by drive period, as the Lyapunov
/// measurement ([`super::lyapunov`]) and the strobe record ([`crate::attractor`]) use them:
/// the exact model's [`TangentSolver`], or a smooth law's
/// ([`super::smooth::ShockleyTangent`]).
pub trait TangentRun {
    /// Advance to `t_end` on the current clock (see [`TangentRun::restart_clock`]), carrying
    /// J along and handing every event (times on that clock) to `on_event`.
    ///
    /// # Errors
    /// [`Error::TimeBeforeCurrent`] when `t_end` lies before the current time; whatever the
    /// solver reports.
    fn run_until(&mut self, t_end: f64, on_event: &mut dyn FnMut(&Event)) -> Result<()>;

    /// Start the clock afresh at the current time (a strobe), keeping J, ln|det J| and the
    /// stops.
    fn restart_clock(&mut self);

    /// Divide J by its Frobenius norm and return the logarithm of the norm (the growth since
    /// the last renormalisation); ln|det J| is kept.
    fn renormalize(&mut self) -> f64;

    /// Time of the first point since the last reset where the flow has no derivative (the
    /// exact model's tangential release); `None` for a smooth law.
    fn grazing(&self) -> Option<f64>;

    /// J = I, ln|det J| = 0 and no stops at the current time (after a grazing).
    fn reset(&mut self);

    /// Restart ln|det J| and the stop count at the current time, keeping J.
    fn reset_log_det(&mut self);

    /// ln|det J| since the last reset of it, `None` when J is singular (a stop of the exact
    /// model).
    fn log_det(&self) -> Option<f64>;

    /// Stops since the last reset of ln|det J| (a motion stuck at the reset counts one).
    fn stops(&self) -> u64;

    /// The phase of the motion at the current time.
    fn phase(&self) -> Phase;

    /// The state at the current time.
    fn state(&self) -> State;
}

impl TangentRun for TangentSolver {
    fn run_until(&mut self, t_end: f64, on_event: &mut dyn FnMut(&Event)) -> Result<()> {
        TangentSolver::run_until(self, t_end, |e| on_event(e))
    }

    fn restart_clock(&mut self) {
        TangentSolver::restart_clock(self);
    }

    fn renormalize(&mut self) -> f64 {
        TangentSolver::renormalize(self)
    }

    fn grazing(&self) -> Option<f64> {
        TangentSolver::grazing(self)
    }

    fn reset(&mut self) {
        TangentSolver::reset(self);
    }

    fn reset_log_det(&mut self) {
        TangentSolver::reset_log_det(self);
    }

    fn log_det(&self) -> Option<f64> {
        TangentSolver::log_det(self)
    }

    fn stops(&self) -> u64 {
        TangentSolver::stops(self)
    }

    fn phase(&self) -> Phase {
        TangentSolver::phase(self)
    }

    fn state(&self) -> State {
        TangentSolver::state(self)
    }
}

impl Tangent {
    /// J = I at the current time of `solver`.
    pub(crate) fn new(solver: &ExactSolver) -> Self {
        let params = *solver.params();
        let mut tangent = Self {
            transition: SlidingTransition::new(params.zeta),
            zeta: params.zeta,
            mu_s: params.mu_s,
            jacobian: Matrix2::IDENTITY,
            log_scale: 0.0,
            sliding_time: 0.0,
            turn_log: 0.0,
            turn_product: 1.0,
            stops: 0,
            grazing: None,
        };
        tangent.reset(solver);
        tangent
    }

    /// See [`TangentSolver::reset`].
    fn reset(&mut self, solver: &ExactSolver) {
        self.jacobian = Matrix2::IDENTITY;
        self.log_scale = 0.0;
        self.reset_log_det(solver);
        self.grazing = None;
    }

    /// See [`TangentSolver::reset_log_det`].
    fn reset_log_det(&mut self, solver: &ExactSolver) {
        self.sliding_time = 0.0;
        self.turn_log = 0.0;
        self.turn_product = 1.0;
        self.stops = u64::from(solver.phase() == Phase::Stick);
    }

    /// See [`TangentSolver::jacobian`].
    pub(crate) fn jacobian(&self) -> Matrix2 {
        self.jacobian
    }

    /// See [`TangentSolver::grazing`].
    pub(crate) fn grazing(&self) -> Option<f64> {
        self.grazing
    }

    /// See [`TangentSolver::log_det`].
    pub(crate) fn log_det(&self) -> Option<f64> {
        if self.stops > 0 || self.turn_product == 0.0 {
            None
        } else {
            Some(-2.0 * self.zeta * self.sliding_time + self.turn_log + self.turn_product.ln())
        }
    }

    /// Advance `solver` (the one this tangent started on) as [`TangentSolver::advance`].
    pub(crate) fn advance(
        &mut self,
        solver: &mut ExactSolver,
        t_end: f64,
    ) -> Result<Option<Event>> {
        let sign = solver.phase().sign();
        let from = solver.time();
        let event = solver.advance(t_end)?;
        let elapsed = solver.time() - from;
        if sign == 0.0 {
            self.erase_velocity();
        } else if elapsed > 0.0 {
            self.jacobian = self.transition.at(elapsed) * self.jacobian;
            self.sliding_time += elapsed;
            let size = self.jacobian.max_abs();
            if !(SCALE_BELOW..=SCALE_ABOVE).contains(&size) && size > 0.0 && size.is_finite() {
                self.jacobian = self.jacobian.scaled(1.0 / size);
                self.log_scale += size.ln();
            }
        }
        if let Some(e) = &event {
            self.jump(solver, e);
        }
        Ok(event)
    }

    /// Advance `solver` as [`TangentSolver::run_until`].
    pub(crate) fn run_until(
        &mut self,
        solver: &mut ExactSolver,
        t_end: f64,
        mut on_event: impl FnMut(&Event),
    ) -> Result<()> {
        if t_end < solver.time() || t_end.is_nan() {
            return Err(Error::TimeBeforeCurrent {
                requested: t_end,
                current: solver.time(),
            });
        }
        while solver.time() < t_end {
            if let Some(event) = self.advance(solver, t_end)? {
                on_event(&event);
            }
        }
        Ok(())
    }

    /// The stuck transition diag(1, 0) (and the stick saltation, the same matrix).
    #[inline]
    fn erase_velocity(&mut self) {
        self.jacobian.0[1] = [0.0, 0.0];
    }

    /// The saltation of `event`, from the start of the segment `solver` has just begun.
    #[inline]
    fn jump(&mut self, solver: &ExactSolver, event: &Event) {
        match event.kind {
            EventKind::Stick => {
                self.erase_velocity();
                self.stops += 1;
            }
            EventKind::Turn => {
                let (sign, d) = solver.slide_start().expect("a turn starts a slide");
                // a⁺ = y'' at the start of the new slide; a⁻ = a⁺ + s⁺ − s⁻ = a⁺ + 2s⁺.
                let ratio = d[2] / (d[2] + 2.0 * sign);
                self.jacobian.0[1][0] *= ratio;
                self.jacobian.0[1][1] *= ratio;
                self.turn_product *= ratio;
                if self.turn_product < FOLD_BELOW && self.turn_product > 0.0 {
                    self.turn_log += self.turn_product.ln();
                    self.turn_product = 1.0;
                }
            }
            EventKind::Slip => {
                if self.mu_s == 1.0 {
                    // S_release = I (see `saltation`).
                    return;
                }
                let (sign, d) = solver.slide_start().expect("a release starts a slide");
                // F'(τ_r) from y''' = F' − y' − 2ζy'' at the start, where y' = 0.
                let rate = sign * (d[3] + 2.0 * self.zeta * d[2]);
                let shear = if rate > 0.0 {
                    -(self.mu_s - 1.0) / rate
                } else {
                    self.grazing.get_or_insert(event.tau);
                    f64::NAN
                };
                let [row0, row1] = &mut self.jacobian.0;
                row1[0] += shear * row0[0];
                row1[1] += shear * row0[1];
            }
        }
    }
}
