//! Stability for the smooth friction laws (Stribeck, cubic) of a forced belt: the tangent
//! dynamics of [`crate::friction_solver::FrictionSolver`], its strobe map with the monodromy
//! matrix, periodic orbits by Newton's method and Lyapunov exponents ([`FrictionDynamics`]).
//!
//! **Slip phases** are differentiated on the stiff integrator's own steps, as for the
//! Shockley model ([`crate::stiff::sensitivity`]: each accepted step's stage equations
//! differentiated at their converged stages), so the state-transition matrix is the exact
//! derivative of the computed slip phase. **Stick phases** are exact: a stuck block moves as
//! y = y_s + vb (τ − τ_s), y' = vb, so a stop maps every perturbation onto the stuck
//! manifold, δy(τ) = δy(τ_s), δy' = 0: its transition is diag(1, 0).
//!
//! **Saltation matrices.** At an event the vector field switches from f⁻ to f⁺ on a surface
//! h(x, τ) = 0, and a perturbation jumps by S = I + (f⁺ − f⁻) ∇hᵀ / (∇h·f⁻ + ∂h/∂τ)
//! ([`super::saltation`]). With x = (y, y'), F(τ) = β cos(wτ + φ), the net force on a block
//! at the belt's speed f = F − y − 2ζ vb, the slip field of direction σ is
//! (y', F − y − 2ζ y' − D_σ(y')) with D_σ(vb) = σ μ(0), and the stuck field is (vb, 0):
//!
//! - **Stick onset** (slip σ ends at s = y' − vb = 0 with |f| ≤ μs): h = y' − vb,
//!   ∇h = (0, 1), f⁻ = (vb, a⁻) with a⁻ = f − σ μ(0), f⁺ = (vb, 0):
//!   S = I − (0, a⁻)ᵀ(0, 1)/a⁻ = diag(1, 0) (applied without dividing by a⁻).
//! - **Reversal of s** (slip σ ends at s = 0 with σ f < −μs, and slips on in direction −σ):
//!   h = y' − vb, f⁺ − f⁻ = (0, a⁺ − a⁻) with a∓ = f − D_{±σ}(vb) = f ∓ σ μ(0):
//!   S = diag(1, a⁺/a⁻) = diag(1, (f + σμ(0))/(f − σμ(0))).
//! - **Slip onset** (the net force reaches σ μs, leaving in direction σ): the event function
//!   is h = σ f(τ, y) − μs, ∇h = (−σ, 0), ∂h/∂τ = σ F'(τ); f⁻ = (vb, 0), so
//!   ∇h·f⁻ + ∂h/∂τ = σ (F' − vb), and f⁺ − f⁻ = (0, a⁺) with a⁺ = f − σμ(0) = σ(μs − μ(0)):
//!   S = [[1, 0], [−σ(μs − μ(0))/(F' − vb), 1]].
//!   Both smooth laws start from the static level, μ(0) = μs, so a⁺ = 0 and S = I: the
//!   friction force is continuous at the release, and the shift of the release time has no
//!   first-order effect (as for the PWL model at μs = 1). The identity is taken without
//!   forming the quotient, which would read 0/0 at a tangential release (F' = vb).
//!
//! A stick onset and a release at one instant (a zero-duration stop) give diag(1, 0), which
//! is the reversal's matrix at |f| = μs too: the flow is differentiable there.
//!
//! **Parameter derivatives** ([`FrictionDynamics::strobe_sensitivity`]): ∂P^p/∂λ for λ in
//! ζ, β, w, φ, μs, vb and the law's own parameters (vs, δ, η; k1, k3), carried as columns
//! beside the state's. On slip steps they are the stiff integrator's parameter columns
//! ([`crate::stiff::sensitivity`]; the law D(v) = σ μ(σ(v − vb)) gives ∂D/∂vb = −μ'(s) and
//! σ ∂μ/∂θ at fixed s for μs and θ). On a stop y = y_s + vb (τ − τ_s), y' = vb, so a column
//! keeps δy, gains ∂vb/∂λ·(τ − τ_s) in it, and has δy' = ∂vb/∂λ. At an event on h(x, τ, λ) = 0
//! a perturbation δx⁻ (at fixed time) of a parameter that moves the surface jumps by
//!
//! ```text
//! δx⁺ = δx⁻ + (f⁻ − f⁺) δτ_e,   δτ_e = −(∇h·δx⁻ + ∂h/∂λ)/(∇h·f⁻ + ∂h/∂τ)
//! ```
//!
//! (the perturbed motion reaches the surface δτ_e later: the first-order expansion of
//! h(x⁻ + δx⁻ + f⁻δτ_e, τ_e + δτ_e, λ + δλ) = 0; with ∂h/∂λ = 0 this is the saltation
//! matrix above), so the parameter adds (f⁻ − f⁺)·∂τ_e/∂λ with ∂τ_e/∂λ = −(∂h/∂λ)/ḣ:
//!
//! - **Stick onset**: h = y' − vb, ∂h/∂λ = −∂vb/∂λ, ḣ = a⁻, f⁻ − f⁺ = (0, a⁻):
//!   δy'⁺ = δy'⁻ − (δy'⁻ − ∂vb/∂λ) = ∂vb/∂λ, δy⁺ = δy⁻: the stuck manifold of the new vb.
//! - **Reversal**: the same h, f⁻ − f⁺ = (0, a⁻ − a⁺): δy'⁺ = r δy'⁻ + (1 − r) ∂vb/∂λ with
//!   r = a⁺/a⁻ the saltation matrix's entry.
//! - **Release**: h = σ f(τ, y; λ) − μs moves with every parameter but f⁻ = f⁺ (the friction
//!   force is continuous, μ(0) = μs for any parameters), so no jump, whatever ∂τ_r/∂λ.
//!
//! At the end the strobe time pT = 2πp/w moves with w: ẋ(pT)·d(pT)/dw, d(pT)/dw = −2πp/w²,
//! is added to the w column. A state stuck at the strobe (y' = vb) stays stuck as vb moves,
//! as on the Coulomb belt ([`super::strobe_map_parameter_derivative`]): its columns start
//! with δy' = ∂vb/∂λ. The test `friction_stability.rs` checks every column against
//! Richardson-extrapolated central differences of the strobe map.
//!
//! **Floquet multipliers** are the eigenvalues of the monodromy matrix; an orbit that sticks
//! has det M = 0 (the stop erases δy'), so its multipliers are tr M and exactly 0, as for the
//! PWL model.
//! For an orbit that slides throughout, det M is carried as a logarithm (steps and reversals)
//! and the smaller multiplier taken from it
//! ([`ShockleyDynamics::multipliers`](super::ShockleyDynamics::multipliers)).
//!
//! The test `friction_stability.rs` checks the multipliers against Richardson-extrapolated
//! central differences of the strobe map, and λ1 = ln|μ1|/T against the measured exponent.

use super::lyapunov::{measure_exponents, LyapunovExponents, LyapunovOptions};
use super::matrix::Matrix2;
use super::periodic_orbit::{NewtonOptions, PeriodicOrbit};
use super::strobe::StrobeImage;
use super::tangent::TangentRun;
use super::Dynamics;
use crate::cancel::Cancel;
use crate::error::{Error, Result};
use crate::friction_solver::{FrictionSolver, SlipLaw};
use crate::params::{Parameter, Params, State};
use crate::scan::Monitor;
use crate::solver::{Event, EventKind, Phase, Solver};
use crate::stiff::{Sensitivity, SmoothLaw, StepDerivative};

/// The relative accuracy of the friction solver's strobe map: its slip phases are integrated
/// to [`crate::friction_solver::FRICTION_TOLERANCE`] (10⁻¹²) and its events located to 10⁻¹², and over a drive period
/// the errors of its steps add up to some 10⁻¹¹. States that repeat to this are taken as
/// repeating, and Newton's method stops when a step no longer helps within it.
pub const FRICTION_MAP_ACCURACY: f64 = 1e-10;

/// The stability tools of a smooth friction law (Stribeck or cubic, on a belt or not) with a
/// harmonic drive: the friction solver, its strobe map with the monodromy matrix (see the
/// module documentation), Newton's method for periodic orbits and Lyapunov exponents.
#[derive(Debug, Clone, Default)]
pub struct FrictionDynamics {
    cancel: Cancel,
}

impl FrictionDynamics {
    /// The tools, never cancelled.
    pub fn new() -> Self {
        Self {
            cancel: Cancel::never(),
        }
    }

    /// The same, its solvers checking `cancel`.
    pub fn with_cancel(mut self, cancel: Cancel) -> Self {
        self.cancel = cancel;
        self
    }

    /// A solver of `params` (a smooth friction law) from `initial` at τ = 0.
    ///
    /// # Errors
    /// Invalid parameters or state; [`crate::Unsupported::SmoothFrictionLaw`] is not
    /// returned: Coulomb's law is refused with [`Error::InvalidParameter`] (its tools are
    /// [`super::ExactDynamics`]').
    pub fn plain_solver(&self, params: &Params, initial: State) -> Result<FrictionSolver> {
        let params = params.validate()?;
        if params.law.is_coulomb() {
            return Err(Error::InvalidParameter {
                name: "friction_law",
                value: 0.0,
                allowed: "must be stribeck or cubic here: Coulomb's law has the exact tools",
            });
        }
        FrictionSolver::with_cancel(params, initial, self.cancel.clone())
    }

    /// The tangent dynamics of the motion from `initial` at τ = 0 ([`FrictionTangent`]).
    ///
    /// # Errors
    /// As [`FrictionDynamics::plain_solver`].
    pub fn tangent(&self, params: &Params, initial: State) -> Result<FrictionTangent> {
        Ok(FrictionTangent::new(self.plain_solver(params, initial)?))
    }

    /// The p-fold strobe map from `state` at a strobe with its Jacobian (the monodromy
    /// matrix at a fixed point), the events on the way and ln|det J| (`None` when the motion
    /// sticks on the way or at the start: J is then singular).
    ///
    /// # Errors
    /// [`Error::InvalidParameter`] for invalid parameters, state or p = 0; what the solver
    /// reports.
    pub fn strobe_map(&self, params: &Params, state: State, periods: usize) -> Result<StrobeImage> {
        if periods == 0 {
            return Err(Error::InvalidParameter {
                name: "periods",
                value: 0.0,
                allowed: "must be at least 1",
            });
        }
        let mut tangent = self.tangent(params, state)?;
        let stuck_at_start = tangent.phase() == Phase::Stick;
        let end = periods as f64 * params.drive_period();
        let mut events = Vec::with_capacity(8);
        tangent.run_until(end, &mut |e| events.push(*e))?;
        Ok(StrobeImage {
            state: tangent.state(),
            jacobian: tangent.jacobian(),
            log_det: tangent.log_det(),
            events,
            stuck_at_start,
            stuck_at_end: tangent.phase() == Phase::Stick,
        })
    }

    /// The periodic orbit of period `period` near `guess` by Newton's method on the p-fold
    /// strobe map with its Jacobian, as
    /// [`ShockleyDynamics::find_periodic_orbit`](super::ShockleyDynamics::find_periodic_orbit)
    /// (one Newton for both): steps (M − I)δ = −(P^p(x) − x), halved while the residual
    /// grows, until max(|Δy|, |Δy'|) ≤ tolerance·max(1, |y|, |y'|)·max(1, max|M_ij|); where a
    /// full step no longer reduces a residual within [`FRICTION_MAP_ACCURACY`] (times the same
    /// scale), the iterate is at the computed map's own accuracy and is taken as the orbit.
    ///
    /// # Errors
    /// [`Error::InvalidParameter`] for invalid parameters, guess, options or p = 0;
    /// [`StabilityError::NoConvergence`](super::StabilityError::NoConvergence),
    /// [`StabilityError::SingularJacobian`](super::StabilityError::SingularJacobian); what the
    /// solver reports.
    pub fn find_periodic_orbit(
        &self,
        params: &Params,
        guess: State,
        period: usize,
        options: &NewtonOptions,
    ) -> Result<PeriodicOrbit> {
        super::map_newton::find_orbit(
            |params, x| self.strobe_map(params, x, period),
            params,
            guess,
            period,
            options,
            FRICTION_MAP_ACCURACY,
            None,
        )
        .map(|(orbit, _)| orbit)
    }

    /// The Lyapunov exponents of the motion from `initial` (at a strobe), measured as for the
    /// PWL model ([`crate::stability::lyapunov`]) on the tangent dynamics of the computed
    /// solution ([`FrictionTangent`]). `monitor` is told the drive periods run.
    ///
    /// # Errors
    /// Invalid parameters, state or options; [`Error::HorizonTooLong`]; [`Error::Cancelled`];
    /// what the solver reports.
    pub fn lyapunov_exponents(
        &self,
        params: &Params,
        initial: State,
        options: &LyapunovOptions,
        monitor: &dyn Monitor,
    ) -> Result<LyapunovExponents> {
        let options = options.validate()?;
        let params = params.validate()?;
        let initial = State::new(initial.y, initial.v)?;
        options.check_horizon(&params)?;
        let mut tangent = self.tangent(&params, initial)?;
        measure_exponents(&mut tangent, &params, &options, monitor)
    }
}

/// The columns of [`FrictionDynamics::strobe_sensitivity`]: y0, v0, then ζ, β, w, φ
/// ([`crate::stiff::sensitivity::EQUATION_PARAMETERS`]), then μs, vb and the law's own
/// parameters (vs, δ, η of the Stribeck law; k1, k3 of the cubic law), as [`SlipLaw`]'s.
pub const FRICTION_COLUMNS: usize = 11;
/// The column of vb in [`FRICTION_COLUMNS`].
const VB_COLUMN: usize = 7;

impl FrictionDynamics {
    /// The column of `parameter` in [`FrictionDynamics::strobe_sensitivity`] for the law of
    /// `params`.
    ///
    /// # Errors
    /// [`Error::InvalidParameter`] for a parameter of the other law.
    pub fn sensitivity_column(params: &Params, parameter: Parameter) -> Result<usize> {
        use crate::friction::FrictionLaw;
        let stribeck = matches!(params.law, FrictionLaw::Stribeck { .. });
        Ok(match parameter {
            Parameter::Zeta => 2,
            Parameter::Beta => 3,
            Parameter::W => 4,
            Parameter::MuS => 6,
            Parameter::Vb => VB_COLUMN,
            Parameter::Vs if stribeck => 8,
            Parameter::Delta if stribeck => 9,
            Parameter::Eta if stribeck => 10,
            Parameter::K1 if !stribeck => 8,
            Parameter::K3 if !stribeck => 9,
            other => {
                return Err(Error::InvalidParameter {
                    name: other.label(),
                    value: f64::NAN,
                    allowed: "is no parameter of this friction law (vs, delta, eta are the \
                              Stribeck law's; k1, k3 the cubic law's)",
                })
            }
        })
    }

    /// The p-fold strobe map from `state` with its derivatives by the initial state and the
    /// parameters ([`FRICTION_COLUMNS`]; see the module documentation): the image and
    /// ∂P^p/∂(y0, v0, ζ, β, w, φ, μs, vb, θ), the w column with the strobe time pT = 2πp/w
    /// moving (ẋ(pT)·d(pT)/dw added). A state stuck to the belt at the start stays stuck to
    /// it as vb moves (as the Coulomb belt's [`super::strobe_map_parameter_derivative`]).
    ///
    /// # Errors
    /// As [`FrictionDynamics::strobe_map`].
    pub fn strobe_sensitivity(
        &self,
        params: &Params,
        state: State,
        periods: usize,
    ) -> Result<(State, Sensitivity)> {
        if periods == 0 {
            return Err(Error::InvalidParameter {
                name: "periods",
                value: 0.0,
                allowed: "must be at least 1",
            });
        }
        let mut solver = self.plain_solver(params, state)?;
        let params = *solver.params();
        let end = periods as f64 * params.drive_period();
        // A stop (its onset, or a start on it) maps every column onto the stuck manifold:
        // δy kept, δy' = ∂vb/∂λ.
        let stick = |s: &mut Sensitivity| {
            for c in 0..FRICTION_COLUMNS {
                let [dy, _] = s.column(c);
                s.set_column(c, [dy, if c == VB_COLUMN { 1.0 } else { 0.0 }]);
            }
        };
        let mut base = Sensitivity::identity(FRICTION_COLUMNS);
        if solver.phase() == Phase::Stick {
            stick(&mut base);
        }
        let mut current = base;
        while solver.time() < end {
            let before = solver.time();
            let phase = solver.phase();
            let event = solver.advance(end)?;
            let now = solver.time();
            match phase {
                Phase::Stick => {
                    // y = y_s + vb (τ − τ_s): δy grows by ∂vb/∂λ·(τ − τ_s). A release adds
                    // no jump (the friction force is continuous there).
                    let [dy, dv] = current.column(VB_COLUMN);
                    current.set_column(VB_COLUMN, [dy + (now - before), dv]);
                    base = current;
                }
                Phase::SlipPositive | Phase::SlipNegative => {
                    let sign = if phase == Phase::SlipPositive {
                        1.0
                    } else {
                        -1.0
                    };
                    if now > before {
                        let step = *solver.slip_step().expect("a slip advance has its step");
                        let law = SlipLaw::new(&params, sign);
                        let d = StepDerivative::new(&step, &params, &law, FRICTION_COLUMNS).ok_or(
                            Error::StepSizeTooSmall {
                                tau: step.t0,
                                step: step.h,
                            },
                        )?;
                        let whole = now == step.t1();
                        let theta = if whole { 1.0 } else { (now - step.t0) / step.h };
                        current = d.apply(&base, theta);
                        if whole {
                            base = current;
                        }
                    }
                    if let Some(e) = &event {
                        if e.kind == EventKind::Stick {
                            stick(&mut current);
                        } else {
                            // A reversal: δy'⁺ = r δy'⁻ + (1 − r) ∂vb/∂λ, r = a⁺/a⁻.
                            let f = params.drive(e.tau) - e.y - params.belt_force();
                            let mu0 =
                                sign * SlipLaw::new(&params, sign).value_and_slope(params.vb).0;
                            let r = reversal(f, sign, mu0).0[1][1];
                            for c in 0..FRICTION_COLUMNS {
                                let [dy, dv] = current.column(c);
                                let moves = if c == VB_COLUMN { 1.0 } else { 0.0 };
                                current.set_column(c, [dy, r * dv + (1.0 - r) * moves]);
                            }
                        }
                        base = current;
                    }
                }
            }
        }
        let x = solver.state();
        let field = if solver.phase() == Phase::Stick {
            [params.vb, 0.0]
        } else {
            let sign = if solver.phase() == Phase::SlipPositive {
                1.0
            } else {
                -1.0
            };
            let (d, _) = SlipLaw::new(&params, sign).value_and_slope(x.v);
            [x.v, params.drive(end) - x.y - 2.0 * params.zeta * x.v - d]
        };
        let moving = -std::f64::consts::TAU * periods as f64 / (params.w * params.w);
        let [dy, dv] = current.column(4);
        current.set_column(4, [dy + field[0] * moving, dv + field[1] * moving]);
        Ok((x, current))
    }

    /// ∂P^p/∂λ at `state` for the parameter λ (ζ, w, β, μs, vb or the law's own), from
    /// [`FrictionDynamics::strobe_sensitivity`].
    ///
    /// # Errors
    /// As [`FrictionDynamics::sensitivity_column`] and
    /// [`FrictionDynamics::strobe_sensitivity`].
    pub fn strobe_parameter_derivative(
        &self,
        params: &Params,
        state: State,
        periods: usize,
        parameter: Parameter,
    ) -> Result<[f64; 2]> {
        let column = Self::sensitivity_column(params, parameter)?;
        Ok(self
            .strobe_sensitivity(params, state, periods)?
            .1
            .column(column))
    }
}

impl Dynamics for FrictionDynamics {
    fn is_exact(&self) -> bool {
        false
    }

    fn sticks(&self) -> bool {
        true
    }

    fn solver(&self, params: &Params, initial: State) -> Result<Box<dyn Solver + Send>> {
        Ok(Box::new(self.plain_solver(params, initial)?))
    }

    fn strobe_map(&self, params: &Params, state: State, periods: usize) -> Result<StrobeImage> {
        FrictionDynamics::strobe_map(self, params, state, periods)
    }

    fn find_periodic_orbit(
        &self,
        params: &Params,
        guess: State,
        period: usize,
        options: &NewtonOptions,
    ) -> Result<PeriodicOrbit> {
        FrictionDynamics::find_periodic_orbit(self, params, guess, period, options)
    }

    fn lyapunov_exponents(
        &self,
        params: &Params,
        initial: State,
        options: &LyapunovOptions,
        monitor: &dyn Monitor,
    ) -> Result<LyapunovExponents> {
        FrictionDynamics::lyapunov_exponents(self, params, initial, options, monitor)
    }

    fn tangent(&self, params: &Params, initial: State) -> Result<Box<dyn TangentRun + Send>> {
        Ok(Box::new(FrictionDynamics::tangent(self, params, initial)?))
    }

    /// [`FRICTION_MAP_ACCURACY`], or `tolerance` when that is larger.
    fn repeat_tolerance(&self, tolerance: f64) -> f64 {
        tolerance.max(FRICTION_MAP_ACCURACY)
    }

    /// [`FRICTION_MAP_ACCURACY`], or `tolerance` when that is larger.
    fn map_tolerance(&self, tolerance: f64) -> f64 {
        tolerance.max(FRICTION_MAP_ACCURACY)
    }

    /// From the forward sensitivities ([`FrictionDynamics::strobe_parameter_derivative`]).
    fn parameter_derivative(
        &self,
        params: &Params,
        state: State,
        periods: usize,
        parameter: Parameter,
    ) -> Option<Result<[f64; 2]>> {
        Some(self.strobe_parameter_derivative(params, state, periods, parameter))
    }
}

/// The saltation matrix of a reversal of the slip from direction `sign_before` with the net
/// force `net_force` = F − y − 2ζ vb and the law's level `mu0` = μ(0) at zero slip:
/// diag(1, (f + σμ(0))/(f − σμ(0))) (see the module documentation).
pub fn reversal(net_force: f64, sign_before: f64, mu0: f64) -> Matrix2 {
    let before = net_force - sign_before * mu0;
    let after = net_force + sign_before * mu0;
    Matrix2::diagonal(1.0, after / before)
}

/// The saltation matrix of a release (stick → slip in direction `sign_after`) where the
/// drive changes at `drive_rate` = F'(τ_r), on a belt of speed `vb`, with the jump
/// μs − μ(0) of the friction force: [[1, 0], [−σ(μs − μ(0))/(F' − vb), 1]], exactly the
/// identity when the law starts from the static level (see the module documentation).
pub fn release(sign_after: f64, drive_rate: f64, vb: f64, jump: f64) -> Matrix2 {
    if jump == 0.0 {
        return Matrix2::IDENTITY;
    }
    Matrix2([[1.0, 0.0], [-sign_after * jump / (drive_rate - vb), 1.0]])
}

/// The tangent dynamics of a smooth friction law along a motion: the friction solver with
/// J = ∂x(τ)/∂x(τ0) carried over its slip steps (their own derivatives), its stops
/// (diag(1, 0)) and its events (the saltation matrices of the module documentation). Its
/// clock is not restarted: [`TangentRun::restart_clock`] only moves the origin the times
/// are counted from.
#[derive(Debug)]
pub struct FrictionTangent {
    solver: FrictionSolver,
    /// J at `base_time`: the start of the slip step in progress, or the solver's time.
    base: Matrix2,
    base_time: f64,
    /// J at the solver's time.
    current: Matrix2,
    /// ln|det J| since the last reset at `base_time` and at the solver's time (`None` once
    /// the motion stuck: J is singular).
    log_det_base: Option<f64>,
    log_det: Option<f64>,
    /// ln|det| of the part of the slip step in progress run so far (0 at `base_time`).
    partial_log_det: f64,
    origin: f64,
    stops: u64,
}

/// The projection onto the stuck manifold, diag(1, 0): a stop's transition and saltation.
const STUCK: Matrix2 = Matrix2::diagonal(1.0, 0.0);

impl FrictionTangent {
    fn new(solver: FrictionSolver) -> Self {
        let stuck = solver.phase() == Phase::Stick;
        let j = if stuck { STUCK } else { Matrix2::IDENTITY };
        let log_det = (!stuck).then_some(0.0);
        Self {
            base_time: solver.time(),
            solver,
            base: j,
            current: j,
            log_det_base: log_det,
            log_det,
            partial_log_det: 0.0,
            origin: 0.0,
            stops: u64::from(stuck),
        }
    }

    /// The solver underneath.
    pub fn solver(&self) -> &FrictionSolver {
        &self.solver
    }

    /// J since the start (or the last [`TangentRun::reset`]), divided by the factors
    /// renormalisations took out.
    pub fn jacobian(&self) -> Matrix2 {
        self.current
    }

    /// Apply the saltation matrix `s` at the solver's time (an event).
    fn jump(&mut self, s: Matrix2, log_det: Option<f64>) {
        self.current = s * self.current;
        self.base = self.current;
        self.base_time = self.solver.time();
        self.log_det = match (self.log_det, log_det) {
            (Some(a), Some(b)) => Some(a + b),
            _ => None,
        };
        self.log_det_base = self.log_det;
        self.partial_log_det = 0.0;
    }

    /// One advance of the solver to at most `t_end` (absolute), J carried along.
    fn advance(&mut self, t_end: f64) -> Result<Option<Event>> {
        let before = self.solver.time();
        let phase = self.solver.phase();
        let event = self.solver.advance(t_end)?;
        let now = self.solver.time();
        let params = *self.solver.params();
        match phase {
            Phase::Stick => {
                self.current = STUCK * self.current;
                self.base = self.current;
                self.base_time = now;
                self.partial_log_det = 0.0;
                if let Some(e) = &event {
                    // A release (the only event that ends a stop).
                    let sign = match self.solver.phase() {
                        Phase::SlipNegative => -1.0,
                        _ => 1.0,
                    };
                    let rate = -params.beta * params.w * (params.w * e.tau + params.phi).sin();
                    let law = SlipLaw::new(&params, sign);
                    let mu0 = sign * law.value_and_slope(params.vb).0;
                    let mut jump = params.mu_s - mu0;
                    // Both smooth laws start from μs: their μ(0) differs from it by rounding.
                    if jump.abs() <= 8.0 * f64::EPSILON * params.mu_s {
                        jump = 0.0;
                    }
                    self.jump(release(sign, rate, params.vb, jump), None);
                }
            }
            Phase::SlipPositive | Phase::SlipNegative => {
                let sign = if phase == Phase::SlipPositive {
                    1.0
                } else {
                    -1.0
                };
                if now > before {
                    let step = *self
                        .solver
                        .slip_step()
                        .expect("a slip advance has its step");
                    debug_assert_eq!(step.t0, self.base_time, "the tangent follows every step");
                    let law = SlipLaw::new(&params, sign);
                    let d = StepDerivative::new(&step, &params, &law, 2).ok_or(
                        Error::StepSizeTooSmall {
                            tau: step.t0,
                            step: step.h,
                        },
                    )?;
                    let whole = now == step.t1();
                    let theta = if whole { 1.0 } else { (now - step.t0) / step.h };
                    let g = Matrix2(d.state_jacobian(theta));
                    self.current = g * self.base;
                    self.partial_log_det = g.det().abs().ln();
                    self.log_det = self.log_det_base.map(|l| l + self.partial_log_det);
                    if whole {
                        self.base = self.current;
                        self.base_time = now;
                        self.log_det_base = self.log_det;
                        self.partial_log_det = 0.0;
                    }
                }
                if let Some(e) = &event {
                    match e.kind {
                        EventKind::Stick => {
                            self.stops += 1;
                            self.jump(STUCK, None);
                        }
                        _ => {
                            let f = params.drive(e.tau) - e.y - params.belt_force();
                            let mu0 =
                                sign * SlipLaw::new(&params, sign).value_and_slope(params.vb).0;
                            let s = reversal(f, sign, mu0);
                            let l = s.det().abs().ln();
                            self.jump(s, Some(l));
                        }
                    }
                }
            }
        }
        Ok(event)
    }
}

impl TangentRun for FrictionTangent {
    fn run_until(&mut self, t_end: f64, on_event: &mut dyn FnMut(&Event)) -> Result<()> {
        let end = self.origin + t_end;
        if end < self.solver.time() {
            return Err(Error::TimeBeforeCurrent {
                requested: t_end,
                current: self.solver.time() - self.origin,
            });
        }
        while self.solver.time() < end {
            if let Some(e) = self.advance(end)? {
                on_event(&Event {
                    tau: e.tau - self.origin,
                    ..e
                });
            }
        }
        Ok(())
    }

    fn restart_clock(&mut self) {
        self.origin = self.solver.time();
    }

    fn renormalize(&mut self) -> f64 {
        let norm = self.current.norm();
        if norm > 0.0 && norm.is_finite() {
            self.current = self.current.scaled(1.0 / norm);
            self.base = self.base.scaled(1.0 / norm);
        }
        norm.ln()
    }

    fn grazing(&self) -> Option<f64> {
        None
    }

    /// Not needed: the flow of a smooth law is differentiable at its events
    /// ([`TangentRun::grazing`] is `None`).
    fn reset(&mut self) {}

    fn reset_log_det(&mut self) {
        let stuck = self.solver.phase() == Phase::Stick;
        self.stops = u64::from(stuck);
        let fresh = (!stuck).then_some(0.0);
        self.log_det = fresh;
        // (`base` lies before the reset by the part of the step run so far.)
        self.log_det_base = fresh.map(|l| l - self.partial_log_det);
    }

    fn log_det(&self) -> Option<f64> {
        self.log_det
    }

    fn stops(&self) -> u64 {
        self.stops
    }

    fn phase(&self) -> Phase {
        self.solver.phase()
    }

    fn state(&self) -> State {
        self.solver.state()
    }
}
