//! Stability for smooth laws: the strobe map of the Shockley model with its Jacobian and its
//! derivatives by the parameters, from the forward sensitivities of the stiff solver
//! ([`crate::stiff::sensitivity`]), periodic orbits by Newton's method with their Floquet
//! multipliers, and the sensitivities of a periodic orbit's samples for fitting.
//!
//! **The strobe map.** [`ShockleyDynamics::strobe_image`] runs the Shockley solver
//! ([`ShockleySolver::with_sensitivities`]) from a state at τ = 0 for p drive periods and
//! returns the state at τ = pT with ∂x(pT)/∂(y0, y'0) (the monodromy matrix at a fixed point)
//! and, when asked, ∂x(pT)/∂(ζ_R, β, w, φ, a, ε, r) at a fixed initial state. These are the
//! derivatives of the computed map (the integrator's own steps differentiated), so Newton's
//! method on the map converges quadratically to its fixed point, and the derivatives of a
//! fixed point are those of the fixed point the solver computes.
//!
//! **Floquet multipliers.** The multipliers are the eigenvalues of the monodromy matrix M,
//! with det M taken from the logarithm carried along the steps ([`crate::stiff::Track`]), so
//! that the smaller multiplier keeps its relative accuracy where it is tiny: det M = μ1 μ2 is
//! the phase-area contraction over the orbit. For the flow it is e^{−∫(2ζ + D'(y'))dτ}
//! (Liouville), and a diode's stop, where D' ≈ a/ε ≈ 7.5·10³ in the paper's circuit, makes
//! it tiny: e^{−8600} over one period of the paper's circuit with 1N4148 diodes driven at
//! 3 kHz and 1.5 V, no floating-point number. The computed map's determinant is the product
//! of the steps' own (the L-stable method damps the fast mode by its stability function,
//! about 1/(hD') per step, not e^{−hD'}): e^{−960} for that orbit at rtol = 10⁻¹². So the
//! second multiplier of an orbit that stops depends on the steps and is meaningful only as
//! "below the resolution of the map": the map is one-dimensional there, as the PWL model's
//! is (whose μ2 is exactly 0). The first multiplier, and both of an orbit that slides, are
//! the flow's to the solver's accuracy (tests: Richardson differences of the strobe map to
//! 10⁻⁶, and for sliding orbits Liouville's formula for det M to 10⁻⁶ relative).
//!
//! **The orbit's sensitivities** ([`ShockleyDynamics::orbit_sensitivity`]): a fixed point x*
//! of the p-fold map moves with a parameter by dx*/dp = (I − M)⁻¹(∂P/∂p + ẋ(pT) d(pT)/dp)
//! (d(pT)/dw = −2πp/w²), and a sample at τ by dy/dp = J_y(τ) dx*/dp + S_{p,y}(τ), as for the
//! PWL model ([`super::sensitivity`]).

use super::error::StabilityError;
use super::lyapunov::{measure_exponents, LyapunovExponents, LyapunovOptions};
use super::matrix::{Matrix2, Multiplier};
use super::periodic_orbit::{NewtonOptions, PeriodicOrbit};
use super::sensitivity::SENSITIVITY_PARAMETERS;
use super::strobe::StrobeImage;
use super::tangent::TangentRun;
use crate::cancel::Cancel;
use crate::error::{Error, Result};
use crate::params::{Parameter, Params, State};
use crate::scan::Monitor;
use crate::shockley::{DiodeLaw, ShockleyModel, ShockleyOptions, ShockleySolver};
use crate::solver::{run_until, Event, EventKind, Phase, Solver};
use crate::stiff::{Columns, Sensitivity, SmoothLaw};
use std::f64::consts::TAU;

/// The Shockley model's stability tools: its law and the stiff solver's options, for any
/// parameters (ζ_R, w, β, φ).
#[derive(Debug, Clone)]
pub struct ShockleyDynamics {
    law: DiodeLaw,
    /// The options of trajectories (the experiment's): transients, tangent dynamics, the
    /// samples of an orbit for fitting.
    options: ShockleyOptions,
    /// The options of the strobe map that Newton's method solves and whose Jacobian gives
    /// the Floquet multipliers ([`ShockleyDynamics::MAP_TOLERANCE`]).
    map: ShockleyOptions,
    cancel: Cancel,
}

/// The image of a state under the Shockley model's strobe map with the forward
/// sensitivities ([`ShockleyDynamics::strobe_image`]).
#[derive(Debug, Clone, PartialEq)]
pub struct SmoothImage {
    /// The state, the Jacobian ∂x(pT)/∂x(0), ln|det| of the Jacobian (from the steps), the
    /// events on the way and whether the motion is in a stop at either end.
    pub image: StrobeImage,
    /// ∂x(pT)/∂(y0, y'0, p), the columns of [`Columns`].
    pub sensitivity: Sensitivity,
    /// The velocity field ẋ = (y', β cos(w pT + φ) − y − 2ζ_R y' − D(y')) at τ = pT.
    pub field: [f64; 2],
}

/// One sample of a periodic orbit of a smooth law with its sensitivities
/// ([`ShockleyDynamics::orbit_sensitivity`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SmoothOrbitSample {
    /// Time τ since the strobe of the fixed point.
    pub tau: f64,
    /// Position y(τ).
    pub y: f64,
    /// Velocity y'(τ).
    pub v: f64,
    /// ∂y(τ)/∂(ζ, β, w, φ, μs) along the periodic orbit (the fixed point moving with the
    /// parameters), at fixed τ, in the order of [`SENSITIVITY_PARAMETERS`] as for the PWL
    /// model ([`super::OrbitSample`]); ζ is ζ_R, and μs, which the smooth law does not use,
    /// has derivative 0.
    pub dy: [f64; 5],
    /// ∂y(τ)/∂θ by the law's own parameters, in the order of [`SmoothLaw::PARAMETERS`] (a
    /// diode pair: a = n V_T/U_t, ε = 2 I_s √(L/C)/U_t, r = R_s/√(L/C)).
    pub dlaw: [f64; 3],
}

/// The eigenvalues of `m`, the smaller real one from `det` (which may be known more
/// accurately than the entries of `m` show).
fn multipliers(m: &Matrix2, det: f64) -> [Multiplier; 2] {
    let [first, second] = m.eigenvalues();
    if first.is_real() && first.re != 0.0 {
        [first, Multiplier::real(det / first.re)]
    } else {
        [first, second]
    }
}

impl ShockleyDynamics {
    /// The relative and absolute tolerance of the strobe map that Newton's method solves and
    /// differentiates (or the trajectories' own, when tighter). The Jacobian of the computed
    /// map converges more slowly with the tolerance than the map itself: through a turn the
    /// diode's slope peaks at a/ε over a time of the order of ε/|y''|, which loose steps do not
    /// resolve. At the paper's 9.97 kHz and 1.498 V the first multiplier of the map at
    /// rtol = atol = 10⁻⁶ is 3.4·10⁻³ from the flow's, at 10⁻⁹ 6·10⁻⁶, and at this tolerance
    /// 1.4·10⁻⁷ (test `multipliers_converge_with_the_tolerance`, against Richardson
    /// differences of the map at 10⁻¹²).
    pub const MAP_TOLERANCE: f64 = 1e-10;

    /// The stability tools of the Shockley model with `law`: trajectories integrated with
    /// `options`, the strobe map of Newton's method at [`ShockleyDynamics::MAP_TOLERANCE`]
    /// (or `options`' tolerances, when tighter).
    ///
    /// # Errors
    /// When the law or the options are invalid.
    pub fn new(law: DiodeLaw, options: ShockleyOptions) -> Result<Self> {
        let options = options.validate()?;
        let map = options
            .with_rtol(options.rtol.min(Self::MAP_TOLERANCE))?
            .with_atol(options.atol.min(Self::MAP_TOLERANCE))?;
        Ok(Self {
            law: SmoothLaw::validate(&law)?,
            options,
            map,
            cancel: Cancel::never(),
        })
    }

    /// The same with the strobe map of Newton's method integrated with `map` instead (for
    /// studies of its accuracy).
    ///
    /// # Errors
    /// When the options are invalid.
    pub fn with_map_options(mut self, map: ShockleyOptions) -> Result<Self> {
        self.map = map.validate()?;
        Ok(self)
    }

    /// The same, its solvers checking `cancel`.
    pub fn with_cancel(mut self, cancel: Cancel) -> Self {
        self.cancel = cancel;
        self
    }

    /// The law.
    pub fn law(&self) -> &DiodeLaw {
        &self.law
    }

    /// The stiff solver's options for trajectories.
    pub fn options(&self) -> &ShockleyOptions {
        &self.options
    }

    /// The stiff solver's options for the strobe map of Newton's method (see
    /// [`ShockleyDynamics::MAP_TOLERANCE`]).
    pub fn map_options(&self) -> &ShockleyOptions {
        &self.map
    }

    /// The model at `params` (ζ is ζ_R).
    ///
    /// # Errors
    /// When `params` is invalid.
    pub fn model(&self, params: &Params) -> Result<ShockleyModel> {
        ShockleyModel::new(*params, self.law)
    }

    /// A solver from `state` at τ = 0 without sensitivities (as the experiment's factory
    /// builds).
    ///
    /// # Errors
    /// Invalid parameters or state; what the solver reports.
    pub fn plain_solver(&self, params: &Params, state: State) -> Result<ShockleySolver> {
        ShockleySolver::with_cancel(
            self.model(params)?,
            state,
            self.options,
            self.cancel.clone(),
        )
    }

    /// A solver from `state` at τ = 0 with the trajectories' options, carrying the
    /// sensitivities of `columns`.
    ///
    /// # Errors
    /// Invalid parameters or state; what the solver reports.
    pub fn solver(
        &self,
        params: &Params,
        state: State,
        columns: Columns,
    ) -> Result<ShockleySolver> {
        self.carrying(params, state, columns, self.options)
    }

    fn carrying(
        &self,
        params: &Params,
        state: State,
        columns: Columns,
        options: ShockleyOptions,
    ) -> Result<ShockleySolver> {
        ShockleySolver::with_sensitivities(
            self.model(params)?,
            state,
            options,
            self.cancel.clone(),
            columns,
        )
    }

    /// The image of `state` (at a strobe, drive phase φ) under the p-fold strobe map with its
    /// sensitivities (see the module documentation), integrated with the map's options
    /// ([`ShockleyDynamics::map_options`]).
    ///
    /// # Errors
    /// [`Error::InvalidParameter`] for invalid parameters, state or p = 0; what the solver
    /// reports.
    pub fn strobe_image(
        &self,
        params: &Params,
        state: State,
        periods: usize,
        columns: Columns,
    ) -> Result<SmoothImage> {
        if periods == 0 {
            return Err(Error::InvalidParameter {
                name: "periods",
                value: 0.0,
                allowed: "must be at least 1",
            });
        }
        let mut solver = self.carrying(params, state, columns, self.map)?;
        let stuck_at_start = solver.phase() == Phase::Stick;
        let end = periods as f64 * params.drive_period();
        let mut events: Vec<Event> = Vec::with_capacity(8);
        run_until(&mut solver, end, |e| events.push(*e))?;
        let sensitivity = solver.sensitivity().expect("carried")?;
        let (log_det, _) = solver.log_det().expect("carried")?;
        let x = solver.state();
        let (d, _) = self.law.value_and_slope(x.v);
        let field = [x.v, params.drive(end) - x.y - 2.0 * params.zeta * x.v - d];
        Ok(SmoothImage {
            image: StrobeImage {
                state: x,
                jacobian: Matrix2(sensitivity.state()),
                log_det: Some(log_det),
                events,
                stuck_at_start,
                stuck_at_end: solver.phase() == Phase::Stick,
            },
            sensitivity,
            field,
        })
    }

    /// The p-fold strobe map with its Jacobian (as [`crate::stability::strobe_map`] for the
    /// PWL model).
    ///
    /// # Errors
    /// As [`ShockleyDynamics::strobe_image`].
    pub fn strobe_map(&self, params: &Params, state: State, periods: usize) -> Result<StrobeImage> {
        Ok(self
            .strobe_image(params, state, periods, Columns::State)?
            .image)
    }

    /// ∂P^p/∂λ at `state` for λ = ζ, w or β (for w with the strobe time pT = 2πp/w moving:
    /// ẋ(pT)·d(pT)/dw added), from one run with the sensitivities.
    ///
    /// # Errors
    /// [`Error::InvalidParameter`] for μs, which the Shockley law does not use; as
    /// [`ShockleyDynamics::strobe_image`].
    pub fn strobe_parameter_derivative(
        &self,
        params: &Params,
        state: State,
        periods: usize,
        parameter: Parameter,
    ) -> Result<[f64; 2]> {
        // Columns: y0, v0, ζ, β, w, φ, ...
        let column = match parameter {
            Parameter::Zeta => 2,
            Parameter::Beta => 3,
            Parameter::W => 4,
            Parameter::MuS => {
                return Err(Error::InvalidParameter {
                    name: "mu_s",
                    value: params.mu_s,
                    allowed: "is no parameter of the Shockley law (a smooth diode has no static \
                              threshold): take w, beta or zeta",
                })
            }
            other => {
                return Err(Error::InvalidParameter {
                    name: other.label(),
                    value: other.get(params),
                    allowed: "is no parameter of the Shockley law (a circuit has no belt nor \
                              friction law): take w, beta or zeta",
                })
            }
        };
        let image = self.strobe_image(params, state, periods, Columns::Parameters)?;
        let mut d = image.sensitivity.column(column);
        if parameter == Parameter::W {
            let moving = -TAU * periods as f64 / (params.w * params.w);
            d[0] += image.field[0] * moving;
            d[1] += image.field[1] * moving;
        }
        Ok(d)
    }

    /// The Floquet multipliers of the monodromy matrix of an image at a fixed point (see the
    /// module documentation: det M from its logarithm).
    pub fn multipliers(image: &StrobeImage) -> [Multiplier; 2] {
        let det = image.log_det.map_or(image.jacobian.det(), |l| {
            image.jacobian.det().signum() * l.exp()
        });
        multipliers(&image.jacobian, det)
    }

    /// The periodic orbit of period `period` near `guess` by Newton's method on the p-fold
    /// strobe map with its Jacobian, as [`crate::stability::find_periodic_orbit`] for the PWL
    /// model: steps (M − I)δ = −(P^p(x) − x), halved while the residual grows, until
    /// max(|Δy|, |Δy'|) ≤ tolerance·max(1, |y|, |y'|)·max(1, max|M_ij|).
    ///
    /// The map is the solver's: smooth in the state where the solver's decisions (its step
    /// sizes, rejections and Newton iterations) do not change, with jumps of the order of its
    /// tolerance where they do. Most orbits reach the tolerance (10⁻¹² by default) all the
    /// same; where a full Newton step no longer reduces a residual that is within the
    /// solver's relative tolerance rtol (times the same scale), the iterate is at the map's
    /// own accuracy and is taken as the orbit, as it is when the steps run out there.
    ///
    /// # Errors
    /// [`Error::InvalidParameter`] for invalid parameters, guess, options or p = 0;
    /// [`StabilityError::NoConvergence`], [`StabilityError::SingularJacobian`]; what the
    /// solver reports.
    pub fn find_periodic_orbit(
        &self,
        params: &Params,
        guess: State,
        period: usize,
        options: &NewtonOptions,
    ) -> Result<PeriodicOrbit> {
        Ok(self.find_orbit(params, guess, period, options, None)?.0)
    }

    /// The period-1 orbit near `guess` for Newton settling of a steady state
    /// ([`crate::SteadyOptions::newton`]), with the image of `guess` (the map's first
    /// evaluation, a strobe step the settling checks as it checks the trajectory's): as
    /// [`ShockleyDynamics::find_periodic_orbit`], but the iteration stops at the looser
    /// residual `loose.0`·max(1, |y|, |y'|)·max(1, max|M_ij|) where the largest multiplier's
    /// modulus is at most `loose.1`, and then takes one more Newton step from the last iterate
    /// without evaluating the map there: the orbit's state is that step's end, its monodromy,
    /// events and multipliers those of the last image (one step before). Near the orbit the
    /// step's error is quadratic in the last residual (as for the exact model's settling,
    /// `find_periodic_orbit_finished`); the caller checks the state it gets by the repetition
    /// of the cycle recorded from it.
    ///
    /// # Errors
    /// As [`ShockleyDynamics::find_periodic_orbit`].
    pub(crate) fn settling_orbit(
        &self,
        params: &Params,
        guess: State,
        options: &NewtonOptions,
        loose: (f64, f64),
    ) -> Result<(PeriodicOrbit, StrobeImage)> {
        self.find_orbit(params, guess, 1, options, Some(loose))
    }

    /// [`ShockleyDynamics::find_periodic_orbit`], finished as
    /// [`ShockleyDynamics::settling_orbit`] describes when `loose` is given; with the image
    /// of the guess. The map's accuracy is the solver's relative tolerance rtol.
    fn find_orbit(
        &self,
        params: &Params,
        guess: State,
        period: usize,
        options: &NewtonOptions,
        loose: Option<(f64, f64)>,
    ) -> Result<(PeriodicOrbit, StrobeImage)> {
        super::map_newton::find_orbit(
            |params, x| self.strobe_map(params, x, period),
            params,
            guess,
            period,
            options,
            self.map.rtol,
            loose,
        )
    }

    /// The periodic orbit through `fixed_point` (the state at a strobe that the
    /// `period`-fold strobe map keeps) sampled at the sorted times `taus` ≥ 0, with the
    /// derivatives of y by the parameters (see the module documentation): the same shape as
    /// [`crate::stability::periodic_orbit_sensitivity`] gives for the PWL model, with the
    /// law's own parameters beside. The samples are those of a solver started at
    /// `fixed_point` with the trajectories' options (as [`crate::Experiment::factory`]'s),
    /// to the bit, and so are the monodromy and ∂P/∂p of the fixed-point correction: the
    /// derivatives of the computed samples.
    ///
    /// The fixed point is taken as given: a state that repeats to a tolerance ε gives the
    /// derivatives of the orbit it approximates to about ε relative.
    ///
    /// # Errors
    /// [`Error::InvalidParameter`] for invalid parameters, p = 0; [`Error::TimeBeforeCurrent`]
    /// for unsorted or negative times; [`StabilityError::SingularJacobian`] when I − M is
    /// singular (a multiplier 1); what the solver reports.
    pub fn orbit_sensitivity(
        &self,
        params: &Params,
        fixed_point: State,
        period: usize,
        taus: &[f64],
    ) -> Result<Vec<SmoothOrbitSample>> {
        let params = params.validate()?;
        super::sensitivity::check_orbit_samples(period, taus)?;
        let strobe = period as f64 * params.drive_period();
        let mut solver = self.solver(&params, fixed_point, Columns::Parameters)?;
        let columns = Columns::Parameters.count::<DiodeLaw>();
        let mut rows: Vec<(f64, f64, f64, Sensitivity)> = Vec::with_capacity(taus.len());
        let mut at_strobe: Option<(Sensitivity, [f64; 2])> = None;
        let mut next = 0;
        while next < taus.len() || at_strobe.is_none() {
            let target = match (taus.get(next), at_strobe.is_none()) {
                (Some(&tau), true) => tau.min(strobe),
                (Some(&tau), false) => tau,
                (None, _) => strobe,
            };
            run_until(&mut solver, target, |_| {})?;
            let s = solver.sensitivity().expect("carried")?;
            let x = solver.state();
            if at_strobe.is_none() && target == strobe {
                let (d, _) = self.law.value_and_slope(x.v);
                let field = [
                    x.v,
                    params.drive(strobe) - x.y - 2.0 * params.zeta * x.v - d,
                ];
                at_strobe = Some((s, field));
            }
            while next < taus.len() && taus[next] == target {
                rows.push((target, x.y, x.v, s));
                next += 1;
            }
        }
        let (s_strobe, field) = at_strobe.expect("the strobe was reached");
        let m = s_strobe.state();
        let a = [[1.0 - m[0][0], -m[0][1]], [-m[1][0], 1.0 - m[1][1]]];
        let det = a[0][0] * a[1][1] - a[0][1] * a[1][0];
        let scale = 1.0 + m.iter().flatten().fold(0.0f64, |s, v| s.max(v.abs()));
        if !(det.abs() > 1e-12 * scale * scale) {
            return Err(StabilityError::SingularJacobian {
                y: fixed_point.y,
                v: fixed_point.v,
                determinant: det,
            }
            .into());
        }
        // Columns 2.. of the sensitivity: ζ, β, w, φ, then a, ε, r.
        let parameters = columns - 2;
        let period_by_w = -TAU * period as f64 / (params.w * params.w);
        let mut moved = [[0.0; 7]; 2];
        for p in 0..parameters {
            let mut b = s_strobe.column(2 + p);
            if p == 2 {
                b[0] += field[0] * period_by_w;
                b[1] += field[1] * period_by_w;
            }
            moved[0][p] = (a[1][1] * b[0] - a[0][1] * b[1]) / det;
            moved[1][p] = (a[0][0] * b[1] - a[1][0] * b[0]) / det;
        }
        Ok(rows
            .into_iter()
            .map(|(tau, y, v, s)| {
                let row = s.row(0);
                let mut d = [0.0; 7];
                for (p, x) in d.iter_mut().enumerate().take(parameters) {
                    *x = row[0] * moved[0][p] + row[1] * moved[1][p] + row[2 + p];
                }
                SmoothOrbitSample {
                    tau,
                    y,
                    v,
                    dy: [d[0], d[1], d[2], d[3], 0.0],
                    dlaw: [d[4], d[5], d[6]],
                }
            })
            .collect())
    }
}

impl ShockleyDynamics {
    /// The tangent dynamics of the motion from `initial` at τ = 0 ([`ShockleyTangent`]),
    /// integrated with the map's options ([`ShockleyDynamics::map_options`]: a tangent
    /// carried through the turns at loose tolerances is as far off as the map's Jacobian; at
    /// rtol 10⁻⁶ the exponent of the paper's circuit at w = 0.9, β = 3.61 came out 3 % from
    /// its orbit's over 100 periods).
    ///
    /// # Errors
    /// Invalid parameters or state; what the solver reports.
    pub fn tangent(&self, params: &Params, initial: State) -> Result<ShockleyTangent> {
        Ok(ShockleyTangent::new(self.carrying(
            params,
            initial,
            Columns::State,
            self.map,
        )?))
    }

    /// The Lyapunov exponents of the motion from `initial` (at a strobe), measured as for the
    /// PWL model ([`crate::stability::lyapunov`]: blocks, looks, the convergence check) on the
    /// tangent dynamics of the computed solution ([`ShockleyTangent`]). ln|det J| is always
    /// finite (a smooth law never erases a perturbation), so the second exponent is too.
    /// `monitor` is told the drive periods run.
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

/// The tangent dynamics of the Shockley model along a motion: one solver carrying
/// J = ∂x(τ)/∂x(τ0) on its own steps ([`ShockleySolver::with_sensitivities`]), whose clock
/// is not restarted (a smooth solver has no event search whose rounding would grow with τ):
/// [`TangentRun::restart_clock`] only moves the origin the times are counted from.
#[derive(Debug)]
pub struct ShockleyTangent {
    solver: ShockleySolver,
    /// The absolute time the clock counts from.
    origin: f64,
    /// ln|det J| at the last reset of it.
    at_reset: f64,
    /// Stops (stick events) since the last reset of ln|det J|.
    stops: u64,
    /// The first failure of the sensitivities (a step whose Newton matrix is singular), kept
    /// until the next advance reports it.
    failed: Option<Error>,
}

impl ShockleyTangent {
    fn new(solver: ShockleySolver) -> Self {
        let stops = u64::from(solver.phase() == Phase::Stick);
        Self {
            solver,
            origin: 0.0,
            at_reset: 0.0,
            stops,
            failed: None,
        }
    }

    /// The solver underneath.
    pub fn solver(&self) -> &ShockleySolver {
        &self.solver
    }

    /// J since the last reset, divided by the factors renormalisations took out.
    ///
    /// # Errors
    /// [`Error::StepSizeTooSmall`] at a step whose Newton matrix is singular.
    pub fn jacobian(&self) -> Result<Matrix2> {
        Ok(Matrix2(
            self.solver.sensitivity().expect("carried")?.state(),
        ))
    }

    fn total_log_det(&self) -> Result<f64> {
        Ok(self.solver.log_det().expect("carried")?.0)
    }
}

impl TangentRun for ShockleyTangent {
    fn run_until(&mut self, t_end: f64, on_event: &mut dyn FnMut(&Event)) -> Result<()> {
        if let Some(e) = self.failed.take() {
            return Err(e);
        }
        let origin = self.origin;
        let stops = &mut self.stops;
        run_until(&mut self.solver, origin + t_end, |e| {
            *stops += u64::from(e.kind == EventKind::Stick);
            on_event(&Event {
                tau: e.tau - origin,
                ..*e
            });
        })
    }

    fn restart_clock(&mut self) {
        self.origin = self.solver.time();
    }

    fn renormalize(&mut self) -> f64 {
        match self.solver.renormalize_sensitivity().expect("carried") {
            Ok(growth) => growth,
            Err(e) => {
                self.failed = Some(e);
                f64::NAN
            }
        }
    }

    fn grazing(&self) -> Option<f64> {
        None
    }

    /// Not needed: a smooth law has no grazing ([`TangentRun::grazing`] is `None`).
    fn reset(&mut self) {}

    fn reset_log_det(&mut self) {
        match self.total_log_det() {
            Ok(l) => self.at_reset = l,
            Err(e) => self.failed = Some(e),
        }
        self.stops = u64::from(self.solver.phase() == Phase::Stick);
    }

    fn log_det(&self) -> Option<f64> {
        Some(self.total_log_det().ok()? - self.at_reset)
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

/// The names of [`SmoothOrbitSample::dy`] and then [`SmoothOrbitSample::dlaw`], in order.
pub fn smooth_sensitivity_parameters() -> Vec<&'static str> {
    SENSITIVITY_PARAMETERS
        .iter()
        .chain(DiodeLaw::PARAMETERS)
        .copied()
        .collect()
}
