//! Fitting the circuit (or the mechanical oscillator) to measurements: least squares of the model's steady state against
//! scope records ([`fit_records`]) or a table of measured amplitudes ([`fit_table`]), one
//! record at a time ([`fit_per_record`]), and the PWL law against the Shockley law on the
//! same data ([`compare_models`]).
//!
//! **The model of a record.** For each record the drive is taken as measured: a sine
//! U cos(2πf·s + φ_d) + c_d fitted to the drive channel (started from its sine fit,
//! [`crate::measure::SineFit`], and fitted again together with everything else, so that its
//! uncertainty is part of the error bars). The circuit, with the free parameters at their
//! current values, is driven at (f, U) with phase φ = φ_d + ψ; its steady state is found from
//! rest ([`Experiment::steady_with`]) and the cycle is run from its strobe on, sampled at
//! τ = ω0·s for the record's times s since its first sample; the model of u_C is U_t·y + c.
//! Nuisance parameters per record: the drive's U, f, φ_d and c_d, the DC offset c of the u_C
//! channel and a time shift δ = ψ/(2πf) between the channels (a trigger delay). The residuals
//! are model − measurement at every sample that is not clipped, of both channels, each
//! divided by its channel's noise: first the noise estimated from the data
//! ([`crate::measure::Measurement::noise`]), then, in a second pass from the first pass's
//! solution, the channel's RMS residual (records taken at different scope settings have
//! different noise, and an unweighted fit would give wrong error bars).
//!
//! **The fit.** Levenberg–Marquardt, written here (Marquardt's scaling by diag(JᵀJ); a
//! rejected step when the values leave a parameter's range). The `levenberg-marquardt` crate
//! (a port of MINPACK's lmder) was considered: it brings nalgebra, wants its own problem
//! trait and matrix types, has no notion of a step outside the model's domain, and does not
//! report (JᵀJ)⁻¹ for the error bars; the problems here are small and dense (a few to a few
//! tens of unknowns), which 150 lines over a Cholesky solver handle. It runs over the free
//! parameters (scaled by their starting values) and the nuisance
//! parameters. The Jacobian: the drive's columns on the drive samples and the offsets'
//! columns exactly. The response's columns, with PWL diodes wherever every record's model is
//! a periodic orbit, from the exact tangent dynamics with respect to the parameters
//! ([`crate::stability::periodic_orbit_sensitivity`]: the closed-form slides, the saltations,
//! the releases' moving times and dx*/dp = (I − M)⁻¹ ∂P/∂p), carried through the circuit's
//! scales (ζ = (R + R_D)/2·√(C/L), ω0 = 1/√(LC), w = 2πf/ω0, β = U/U_t, τ = ω0·s,
//! u_C = U_t·y), from the steady states the residuals were computed with. Otherwise (Shockley
//! diodes, a model that does not repeat, a tangential release, a multiplier 1) by forward
//! differences (step 10⁻⁶ with PWL diodes, whose
//! exact solver gives the steady state to 10⁻¹²; 10⁻⁴ with Shockley diodes, whose stiff
//! solver is accurate to its tolerance; relative to a free parameter's value, but never
//! smaller than that fraction of its starting value, so that a value fitted near zero, such
//! as a diode's R_s, keeps a step above the solver's error), a record's own nuisance columns
//! from that record only. The report says which served at the solution ([`Jacobian`]).
//!
//! **What is reported** ([`FitReport`]): each free parameter's value, standard error from
//! s²(JᵀJ)⁻¹ with s² the weighted SSR/(N − P) (N residuals, P fitted values with the nuisance
//! ones), 95 % interval value ± t(0.975, N − P)·stderr, the correlation of the free
//! parameters; the RMS residual of u_C per record and overall; χ²/dof = Σ r²/σ² over N − P
//! with σ each channel's noise estimated from the data alone (near 1 when the model explains
//! the data to the noise; the estimate from second differences needs the noise to exceed
//! the waveform's curvature between samples, true of 8-bit records, not of records with
//! almost no noise); the iterations of both passes and whether the fit converged;
//! AIC = Σ_g N_g ln(SSR_g/N_g) + 2P and BIC (P ln N instead of 2P) over the channels g, for
//! comparing models.
//!
//! **Mechanics.** A mechanical oscillator (mass, spring, viscous and dry friction) is fitted
//! in the same way to records of its drive force F (N) and displacement r (m), with the
//! free parameters `damping` (γ), `friction` (F0), `mass` (m), `stiffness` (k) and `mu-s`
//! ([`FitParameter::MECHANICS`]); its scales take the circuit's place (ζ = γ/(2√(km)),
//! ω0 = √(k/m), β = F/F0, r = (F0/k)·y), and its Coulomb law is the PWL law, so that its
//! Jacobian is exact wherever every record's model is a periodic orbit. The record's channels
//! must say their units (`N` and `m`: a plain CSV's header `time_s,F (N),r (m)`), a circuit's
//! parameter on a mechanical oscillator (or the other way round) is refused naming the
//! parameters allowed, and so is a table of amplitudes (read in volts). The report's fields
//! named in volts then hold newtons (the drive) and metres (the response):
//! [`FitReport::units`].
//!
//! **Tables** ([`fit_table`]): the residual of a row is the steady amplitude (half the
//! peak-to-peak of u_C) minus the measured one. Rows with a `direction` are computed along
//! their sweep (rows of one leg and one drive amplitude sorted by frequency, up or down, each
//! settling from the motion of the row before, as the measurement was made), the others from
//! rest. There is no nuisance parameter and no noise estimate independent of the fit:
//! χ²/dof is not reported.

mod json;
pub(crate) mod linalg;
mod lm;
mod parameter;

pub use json::{ComparisonJson, FitReportJson, ParameterJson, RecordJson, RowJson, UnitsJson};
pub use parameter::FitParameter;

use crate::experiment::{DiodeModel, Experiment};
use crate::measure::{AmplitudeTable, Direction, MeasureError, Measurement};
use crate::params::{Params, State};
use crate::physical::System;
use crate::scan::Monitor;
use crate::shockley::DiodePair;
use crate::solver::sample_at;
use crate::stability::{periodic_orbit_sensitivity, OrbitSample};
use crate::steady::SolverFactory;
use crate::steady::{MotionClass, SteadyOptions};
use rayon::prelude::*;
use serde::{Deserialize, Serialize};
use std::f64::consts::{PI, TAU};
use std::ops::ControlFlow;
use thiserror::Error;

/// What can go wrong in a fit.
#[derive(Debug, Clone, PartialEq, Error)]
#[non_exhaustive]
pub enum FitError {
    /// A measurement that cannot be used.
    #[error(transparent)]
    Measure(#[from] MeasureError),
    /// A name that is no fit parameter.
    #[error(
        "unknown fit parameter \"{0}\" (the parameters are {circuit} for a circuit; \
         {mechanics} for a mechanical oscillator)",
        circuit = FitParameter::names(&FitParameter::CIRCUIT),
        mechanics = FitParameter::names(&FitParameter::MECHANICS)
    )]
    UnknownParameter(String),
    /// The experiment is neither a circuit nor a mechanical oscillator.
    #[error(
        "fitting needs a circuit or a mechanical oscillator (give its parts or a preset), not \
         dimensionless parameters alone"
    )]
    NeedsCircuit,
    /// A circuit's parameter on a mechanical oscillator, or the other way round.
    #[error(
        "{parameter} is not a parameter of {} (its parameters are {})",
        if *mechanics { "a mechanical oscillator" } else { "a circuit" },
        FitParameter::names(if *mechanics { &FitParameter::MECHANICS } else { &FitParameter::CIRCUIT })
    )]
    WrongSystem {
        /// The parameter.
        parameter: FitParameter,
        /// Whether the experiment is a mechanical oscillator (else a circuit).
        mechanics: bool,
    },
    /// A record whose channels' units do not fit the experiment (a mechanical oscillator
    /// needs the force in N and the displacement in m).
    #[error("{file}: {message}")]
    Units {
        /// The record.
        file: String,
        /// What is wrong and what is allowed.
        message: String,
    },
    /// A table of amplitudes (read in volts) given for a mechanical oscillator.
    #[error(
        "a table of amplitudes is read in volts (U_V, response_V): a mechanical oscillator is \
         fitted to records (a force in N and a displacement in m)"
    )]
    TableNeedsCircuit,
    /// A parameter of the other diode law.
    #[error("{parameter} is not a parameter of the {} diode law", model.label())]
    WrongLaw {
        /// The parameter.
        parameter: FitParameter,
        /// The law of the experiment.
        model: DiodeModel,
    },
    /// No free parameter, or one given twice.
    #[error("{0}")]
    FreeParameters(&'static str),
    /// No record or row to fit.
    #[error("nothing to fit: no record or row was given")]
    NoData,
    /// Fewer residuals than fitted values.
    #[error("{residuals} samples cannot fit {values} values")]
    TooFewSamples {
        /// Residuals.
        residuals: usize,
        /// Fitted values (free and nuisance).
        values: usize,
    },
    /// The experiment's cancellation token stopped the fit ([`Experiment::with_cancel`]).
    #[error(transparent)]
    Stopped(crate::Error),
    /// The model cannot be computed at the starting values.
    #[error("{file}: the model cannot be computed at the starting values: {error}")]
    Model {
        /// The record or table.
        file: String,
        /// What the library reported.
        error: crate::Error,
    },
}

/// How a fit runs. The defaults are listed field by field.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(default)]
pub struct FitOptions {
    /// Most Levenberg–Marquardt iterations. Default 50.
    pub max_iterations: usize,
    /// Converged when a step lowers the sum of squares by less than this fraction, or moves
    /// every (scaled) value by less than this. Default 1e-9.
    pub tolerance: f64,
    /// Fit a time shift between the channels of each record. Default true.
    pub time_shift: bool,
    /// Fit a DC offset of each record's u_C channel. Default true.
    pub offset: bool,
    /// Jacobians of records from the exact tangent dynamics wherever they serve ([`Jacobian`]);
    /// false: finite differences always (to compare). Default true.
    pub exact_jacobian: bool,
}

impl Default for FitOptions {
    fn default() -> Self {
        Self {
            max_iterations: 50,
            tolerance: 1e-9,
            time_shift: true,
            offset: true,
            exact_jacobian: true,
        }
    }
}

/// A fit's progress, told to a [`FitMonitor`] after every Levenberg–Marquardt iteration.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FitProgress {
    /// Iterations done, over every pass and (per record) every record so far.
    pub iteration: usize,
    /// The most iterations the fit may take (the passes' and records' maxima together); the
    /// fit usually converges well before.
    pub total: usize,
    /// The sum of squares of the weighted residuals reached (records: dimensionless, each
    /// residual in units of its channel's noise; a table: V²).
    pub sum_squares: f64,
}

/// Watches a fit: told after every iteration, and able to stop it (the fit then returns
/// [`FitError::Stopped`] with [`crate::Error::Cancelled`]). Every scan monitor
/// ([`crate::scan::Monitor`], such as `()` or a closure `Fn(done, total) -> bool`) is one and
/// sees (iterations done, most iterations).
pub trait FitMonitor: Sync {
    /// `progress` was reached; [`ControlFlow::Break`] stops the fit.
    fn iteration(&self, progress: &FitProgress) -> ControlFlow<()>;
}

impl<M: Monitor + ?Sized> FitMonitor for M {
    fn iteration(&self, progress: &FitProgress) -> ControlFlow<()> {
        self.step(progress.iteration, progress.total)
    }
}

/// Where a problem's iterations stand in the whole fit, and who watches.
#[derive(Clone, Copy)]
struct Watch<'a> {
    monitor: &'a dyn FitMonitor,
    /// Iterations done before this minimisation.
    before: usize,
    total: usize,
}

impl Watch<'_> {
    fn tell(&self, iteration: usize, sum_squares: f64) -> Result<(), FitError> {
        let progress = FitProgress {
            iteration: self.before + iteration,
            total: self.total,
            sum_squares,
        };
        match self.monitor.iteration(&progress) {
            ControlFlow::Continue(()) => Ok(()),
            ControlFlow::Break(()) => Err(FitError::Stopped(crate::Error::Cancelled {
                done: progress.iteration,
                total: progress.total,
            })),
        }
    }
}

/// How a fit's Jacobian was computed.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
#[non_exhaustive]
pub enum Jacobian {
    /// From the exact tangent dynamics with respect to the parameters
    /// ([`crate::stability::periodic_orbit_sensitivity`]): PWL diodes, every record's model a
    /// periodic orbit.
    Exact,
    /// By finite differences: Shockley diodes, a model that does not repeat (chaos) or whose
    /// orbit's derivative does not exist there (a tangential release), or a table.
    FiniteDifferences,
}

impl Jacobian {
    /// The label in reports: `exact` or `finite-differences`.
    pub fn label(self) -> &'static str {
        match self {
            Jacobian::Exact => "exact",
            Jacobian::FiniteDifferences => "finite-differences",
        }
    }
}

/// A fitted free parameter.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct FittedParameter {
    /// Which.
    pub parameter: FitParameter,
    /// The fitted value (SI units, [`FitParameter::unit`]).
    pub value: f64,
    /// Its standard error (NaN when JᵀJ is singular).
    pub stderr: f64,
    /// The 95 % interval [lo, hi].
    pub ci95: [f64; 2],
    /// The starting value.
    pub initial: f64,
}

/// The fit of one record.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct RecordFit {
    /// The record's file name.
    pub file: String,
    /// Drive frequency from the sine fit (Hz).
    pub freq_hz: f64,
    /// Drive amplitude from the sine fit (V, peak).
    pub amplitude_v: f64,
    /// Dimensionless drive frequency w = Ω/ω0 at the fitted values.
    pub w: f64,
    /// Dimensionless drive amplitude β = U/U_t at the fitted values.
    pub beta: f64,
    /// The model's motion class at the fitted values.
    pub class: MotionClass,
    /// Whole drive periods in the record.
    pub periods: usize,
    /// Samples left out as clipped.
    pub clipped: usize,
    /// RMS residual of the record (V).
    pub rms_residual_v: f64,
    /// The fitted DC offset of u_C (V).
    pub offset_v: f64,
    /// The fitted time shift δ (s).
    pub time_shift_s: f64,
    /// The noise of u_C estimated from the data (V).
    pub noise_v: f64,
    /// Times of the samples used (s since the record's first sample).
    pub time: Vec<f64>,
    /// The model of u_C at those times (V), offset included.
    pub model: Vec<f64>,
    /// Model − measurement at those times (V).
    pub residuals: Vec<f64>,
}

/// The fit of one row of an amplitude table.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct RowFit {
    /// The row's line in the file.
    pub line: usize,
    /// Drive frequency (Hz).
    pub freq_hz: f64,
    /// Drive amplitude (V).
    pub drive_v: f64,
    /// The leg of the sweep, if any.
    pub direction: Option<Direction>,
    /// Measured response amplitude (V).
    pub measured_v: f64,
    /// Model response amplitude at the fitted values (V).
    pub model_v: f64,
    /// The model's motion class there.
    pub class: MotionClass,
}

/// The result of a fit. See the module documentation for each number.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct FitReport {
    /// The diode law fitted.
    pub model: DiodeModel,
    /// The free parameters.
    pub parameters: Vec<FittedParameter>,
    /// Correlation matrix of the free parameters (row-major by `parameters`).
    pub correlation: Vec<Vec<f64>>,
    /// Per record (a fit of records).
    pub records: Vec<RecordFit>,
    /// Per row (a fit of a table).
    pub rows: Vec<RowFit>,
    /// RMS residual over every sample or row (V).
    pub rms_residual_v: f64,
    /// The noise estimated from the data (V, pooled over the records; `None` for a table).
    pub noise_v: Option<f64>,
    /// χ²/dof with that noise (`None` for a table).
    pub chi2_dof: Option<f64>,
    /// Degrees of freedom N − P.
    pub dof: usize,
    /// Residuals N.
    pub residuals: usize,
    /// Fitted values P (free and nuisance).
    pub fitted_values: usize,
    /// Akaike's information criterion N ln(SSR/N) + 2P.
    pub aic: f64,
    /// The Bayesian information criterion N ln(SSR/N) + P ln N.
    pub bic: f64,
    /// Levenberg–Marquardt iterations.
    pub iterations: usize,
    /// Whether the fit met its tolerance within the iterations.
    pub converged: bool,
    /// How the Jacobian at the solution, the one the error bars come from, was computed.
    pub jacobian: Jacobian,
    /// The experiment with the fitted values.
    pub experiment: Experiment,
}

impl FitReport {
    /// The fitted value of `parameter`, if it was free.
    pub fn value(&self, parameter: FitParameter) -> Option<&FittedParameter> {
        self.parameters.iter().find(|p| p.parameter == parameter)
    }

    /// Whether the fitted experiment is a mechanical oscillator: then the fields and keys
    /// named in volts hold the drive's force in N (`amplitude_v`) and the displacement in m
    /// (the residuals, the model, the offset and the noise).
    pub fn is_mechanics(&self) -> bool {
        matches!(self.experiment.system(), Some(System::Mechanics(_)))
    }

    /// The units of the drive and of the response: (`V`, `V`) for a circuit, (`N`, `m`) for
    /// a mechanical oscillator.
    pub fn units(&self) -> (&'static str, &'static str) {
        if self.is_mechanics() {
            ("N", "m")
        } else {
            ("V", "V")
        }
    }
}

/// PWL against Shockley on the same data.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct ModelComparison {
    /// The fit with PWL diodes.
    pub pwl: FitReport,
    /// The fit with Shockley diodes.
    pub shockley: FitReport,
    /// The law with the lower AIC.
    pub preferred: DiodeModel,
    /// AIC(Shockley) − AIC(PWL): negative when Shockley is preferred.
    pub delta_aic: f64,
}

/// The two-sided 95 % quantile of Student's t with `dof` degrees of freedom (Cornish–Fisher
/// expansion about the normal quantile 1.959964; better than 10⁻³ relative from 3 degrees of
/// freedom on).
pub fn t_quantile_975(dof: usize) -> f64 {
    let z: f64 = 1.959_963_984_540_054;
    let n = dof.max(1) as f64;
    let (z3, z5, z7) = (z.powi(3), z.powi(5), z.powi(7));
    z + (z3 + z) / (4.0 * n)
        + (5.0 * z5 + 16.0 * z3 + 3.0 * z) / (96.0 * n * n)
        + (3.0 * z7 + 19.0 * z5 + 17.0 * z3 - 15.0 * z) / (384.0 * n * n * n)
}

/// Everything a fit keeps fixed: the experiment's circuit or mechanical oscillator and
/// options and the free list.
struct Setup {
    experiment: Experiment,
    system: System,
    free: Vec<FitParameter>,
    scale: Vec<f64>,
    steady: SteadyOptions,
    step: f64,
}

impl Setup {
    fn new(experiment: &Experiment, free: &[FitParameter]) -> Result<Self, FitError> {
        let system = *experiment.system().ok_or(FitError::NeedsCircuit)?;
        if free.is_empty() {
            return Err(FitError::FreeParameters(
                "no free parameter: name at least one",
            ));
        }
        for (i, p) in free.iter().enumerate() {
            if free[..i].contains(p) {
                return Err(FitError::FreeParameters("a free parameter is named twice"));
            }
        }
        let scale = free
            .iter()
            .map(|p| p.get(experiment).map(|v| if v != 0.0 { v } else { 1.0 }))
            .collect::<Result<Vec<_>, _>>()?;
        let model = experiment.diode_model();
        let steady = SteadyOptions {
            tolerance: if model == DiodeModel::Pwl {
                1e-12
            } else {
                experiment.steady_options().tolerance
            },
            spectrum: false,
            lyapunov: None,
            ..experiment.steady_options()
        };
        Ok(Self {
            experiment: experiment.clone(),
            system,
            free: free.to_vec(),
            scale,
            steady,
            step: if model == DiodeModel::Pwl { 1e-6 } else { 1e-4 },
        })
    }

    /// The experiment at scaled values `x` (value = x·scale), or `None` outside the
    /// parameters' ranges.
    fn at(&self, x: &[f64]) -> Option<Experiment> {
        let mut system = self.system;
        let mut mu_s = self.experiment.mu_s();
        for ((p, &x), &s) in self.free.iter().zip(x).zip(&self.scale) {
            let v = x * s;
            match (*p, &mut system) {
                (FitParameter::MuS, _) => mu_s = v,
                (p, System::Circuit(c)) => p.set(c, v),
                (p, System::Mechanics(m)) => p.set_mechanics(m, v),
            }
        }
        let e = match system {
            System::Circuit(c) => Experiment::circuit(c).ok()?,
            System::Mechanics(m) => Experiment::mechanics(m).ok()?,
        };
        let e = e
            .with_shockley_options(*self.experiment.shockley_options())
            .ok()?;
        // The rebuilt experiment keeps the caller's cancellation token.
        e.with_mu_s(mu_s)
            .ok()
            .map(|e| e.with_cancel(self.experiment.cancel().clone()))
    }

    /// `Err(FitError::Stopped)` once the caller's token stops the fit (Ctrl-C, a deadline):
    /// checked before each evaluation, since a stopped model only looks like a failed step.
    fn check_stop(&self) -> Result<(), FitError> {
        match self.experiment.cancel().stopped() {
            Some(stop) => Err(FitError::Stopped(stop.error())),
            None => Ok(()),
        }
    }

    fn values(&self, x: &[f64]) -> Vec<f64> {
        x.iter().zip(&self.scale).map(|(x, s)| x * s).collect()
    }
}

/// The model of one record: u_C at the used times, and the motion's class, w and β; the
/// dimensionless parameters, the steady state's strobe state and period (what the exact
/// Jacobian starts from).
struct Evaluated {
    model: Vec<f64>,
    class: MotionClass,
    w: f64,
    beta: f64,
    params: Params,
    strobe: State,
    period: Option<usize>,
}

fn wrap(phase: f64) -> f64 {
    let p = phase.rem_euclid(TAU);
    if p > PI {
        p - TAU
    } else {
        p
    }
}

/// The steady u_C of `experiment` driven at `frequency` (Hz), `amplitude` (V) and `phase`
/// (radians, at s = 0), at the times `time` (s), without an offset.
fn evaluate(
    experiment: &Experiment,
    frequency: f64,
    amplitude: f64,
    phase: f64,
    time: &[f64],
    options: &SteadyOptions,
) -> Result<Evaluated, crate::Error> {
    let e = experiment
        .clone()
        .with_frequency(frequency)?
        .with_amplitude(amplitude)?
        .with_phi(wrap(phase))?;
    let steady = e.steady_with(options)?;
    let scales = e.scales().expect("a circuit has scales");
    let params = e.params()?;
    let mut solver = e.factory().make(params, steady.final_state())?;
    let taus: Vec<f64> = time.iter().map(|&s| s * scales.omega0).collect();
    let samples = sample_at(solver.as_mut(), &taus, |_| {})?;
    Ok(Evaluated {
        model: samples.iter().map(|s| s.y * scales.position).collect(),
        class: steady.class,
        w: params.w,
        beta: params.beta,
        params,
        strobe: steady.final_state(),
        period: steady.period,
    })
}

/// How a free parameter enters the dimensionless model, for the chain rule of the exact
/// Jacobian.
#[derive(Debug, Clone, Copy)]
enum Link {
    /// Through ζ, ω0 and the position scale (∂ζ/∂p, ∂ω0/∂p, ∂position/∂p).
    Scales {
        zeta: f64,
        omega0: f64,
        position: f64,
    },
    /// As the force scale that divides the drive (U_t, F0), β = drive/force; with the position
    /// scale proportional to it.
    Force,
    /// As μs.
    MuS,
}

/// The chain rule from a system's parameters to (ζ, β, w, φ, μs) and the position scale.
struct Chain {
    system: System,
    zeta: f64,
    omega0: f64,
}

impl Chain {
    fn new(system: &System, zeta: f64, omega0: f64) -> Self {
        Self {
            system: *system,
            zeta,
            omega0,
        }
    }

    /// How `p` enters, or `None` where the exact Jacobian does not serve.
    fn of(&self, p: FitParameter) -> Option<Link> {
        let (zeta, omega0) = (self.zeta, self.omega0);
        let scales = |zeta, omega0, position| {
            Some(Link::Scales {
                zeta,
                omega0,
                position,
            })
        };
        match (self.system, p) {
            (_, FitParameter::MuS) => Some(Link::MuS),
            // Circuit: ζ = (R + R_D)/2·√(C/L), ω0 = 1/√(LC), position U_t.
            (System::Circuit(c), FitParameter::Resistance | FitParameter::Rd) => {
                scales(0.5 * (c.capacitance / c.inductance).sqrt(), 0.0, 0.0)
            }
            (System::Circuit(_), FitParameter::Ut) => Some(Link::Force),
            (System::Circuit(c), FitParameter::Inductance) => scales(
                -zeta / (2.0 * c.inductance),
                -omega0 / (2.0 * c.inductance),
                0.0,
            ),
            (System::Circuit(c), FitParameter::Capacitance) => scales(
                zeta / (2.0 * c.capacitance),
                -omega0 / (2.0 * c.capacitance),
                0.0,
            ),
            // Mechanics: ζ = γ/(2√(km)), ω0 = √(k/m), position F0/k.
            (System::Mechanics(m), FitParameter::Damping) => {
                scales(0.5 / (m.stiffness * m.mass).sqrt(), 0.0, 0.0)
            }
            (System::Mechanics(_), FitParameter::Friction) => Some(Link::Force),
            (System::Mechanics(m), FitParameter::Mass) => {
                scales(-zeta / (2.0 * m.mass), -omega0 / (2.0 * m.mass), 0.0)
            }
            (System::Mechanics(m), FitParameter::Stiffness) => scales(
                -zeta / (2.0 * m.stiffness),
                omega0 / (2.0 * m.stiffness),
                -m.friction / (m.stiffness * m.stiffness),
            ),
            _ => None,
        }
    }
}

/// Per record, where its values sit in x.
#[derive(Debug, Clone, Copy)]
struct Slots {
    /// u_C offset (V), when fitted.
    offset: Option<usize>,
    /// Extra drive phase of the response ψ = 2πfδ (radians), when fitted.
    shift: Option<usize>,
    /// Drive amplitude / its sine-fit value, drive frequency / its sine-fit value, drive
    /// phase (radians), drive offset (V).
    drive: usize,
}

/// The least-squares problem of records: for each record the drive samples (against the
/// drive's sine) and the response samples (against the model), each divided by its channel's
/// noise.
struct Records<'a> {
    setup: &'a Setup,
    data: &'a [Measurement],
    slots: Vec<Slots>,
    /// Used times, drive and response samples of each record.
    time: Vec<Vec<f64>>,
    drive: Vec<Vec<f64>>,
    response: Vec<Vec<f64>>,
    /// 1/σ of the drive and response channels of each record.
    weights: Vec<(f64, f64)>,
    /// The values of the last evaluation of the residuals and each record's orbit there
    /// (Levenberg–Marquardt asks for the Jacobian where it last accepted a step).
    orbits: Option<(Vec<f64>, Vec<Orbit>)>,
    /// Whether to try the exact Jacobian ([`FitOptions::exact_jacobian`]).
    exact: bool,
    /// How the last Jacobian was computed.
    jacobian: Jacobian,
    /// Who is told of each iteration.
    watch: Watch<'a>,
}

/// Where the exact Jacobian of a record starts: the dimensionless parameters of its model,
/// the steady state's strobe state and its period.
#[derive(Debug, Clone, Copy)]
struct Orbit {
    params: Params,
    strobe: State,
    period: Option<usize>,
}

/// A record's drive as the values x hold it.
#[derive(Debug, Clone, Copy)]
struct Drive {
    amplitude: f64,
    frequency: f64,
    phase: f64,
    offset: f64,
}

impl Records<'_> {
    fn drive(&self, x: &[f64], j: usize) -> Drive {
        let k = self.slots[j].drive;
        let sine = &self.data[j].drive;
        Drive {
            amplitude: x[k] * sine.amplitude,
            frequency: x[k + 1] * sine.frequency,
            phase: x[k + 2],
            offset: x[k + 3],
        }
    }

    fn offset_and_shift(&self, x: &[f64], j: usize) -> (f64, f64) {
        (
            self.slots[j].offset.map_or(0.0, |i| x[i]),
            self.slots[j].shift.map_or(0.0, |i| x[i]),
        )
    }

    /// The response model of record j (without the offset).
    fn response_model(
        &self,
        experiment: &Experiment,
        x: &[f64],
        j: usize,
    ) -> Result<Evaluated, crate::Error> {
        let d = self.drive(x, j);
        let (_, shift) = self.offset_and_shift(x, j);
        evaluate(
            experiment,
            d.frequency,
            d.amplitude,
            d.phase + shift,
            &self.time[j],
            &self.setup.steady,
        )
    }

    /// Weighted residuals of record j: its drive samples, then its response samples; and the
    /// orbit of its model.
    fn record_residuals(
        &self,
        experiment: &Experiment,
        x: &[f64],
        j: usize,
    ) -> Option<(Vec<f64>, Orbit)> {
        let e = self.response_model(experiment, x, j).ok()?;
        let d = self.drive(x, j);
        let (offset, _) = self.offset_and_shift(x, j);
        let (wd, wr) = self.weights[j];
        let mut out = Vec::with_capacity(2 * self.time[j].len());
        for (s, v) in self.time[j].iter().zip(&self.drive[j]) {
            let model = d.offset + d.amplitude * (TAU * d.frequency * s + d.phase).cos();
            out.push(wd * (model - v));
        }
        for (m, v) in e.model.iter().zip(&self.response[j]) {
            out.push(wr * (m + offset - v));
        }
        let orbit = Orbit {
            params: e.params,
            strobe: e.strobe,
            period: e.period,
        };
        Some((out, orbit))
    }

    /// Every record's residuals and orbit at x.
    fn evaluate_all(&self, x: &[f64]) -> Option<Vec<(Vec<f64>, Orbit)>> {
        let experiment = self.setup.at(&x[..self.setup.free.len()])?;
        (0..self.data.len())
            .into_par_iter()
            .map(|j| self.record_residuals(&experiment, x, j))
            .collect()
    }

    fn all(&self, x: &[f64]) -> Option<Vec<Vec<f64>>> {
        self.evaluate_all(x)
            .map(|records| records.into_iter().map(|(r, _)| r).collect())
    }

    /// The drive channels' columns, exact (the sine's derivatives), and the offsets' columns.
    fn fill_drive_columns(&self, x: &[f64], columns: &mut [Vec<f64>]) {
        for (j, &(start, len)) in self.spans().iter().enumerate() {
            let half = len / 2;
            let (wd, wr) = self.weights[j];
            let slots = self.slots[j];
            let d = self.drive(x, j);
            let sine = &self.data[j].drive;
            for (t, s) in self.time[j].iter().enumerate() {
                let (sn, cs) = (TAU * d.frequency * s + d.phase).sin_cos();
                columns[slots.drive][start + t] = wd * cs * sine.amplitude;
                columns[slots.drive + 1][start + t] =
                    -wd * d.amplitude * sn * TAU * s * sine.frequency;
                columns[slots.drive + 2][start + t] = -wd * d.amplitude * sn;
                columns[slots.drive + 3][start + t] = wd;
            }
            if let Some(i) = slots.offset {
                columns[i][start + half..start + len].fill(wr);
            }
        }
    }

    /// The Jacobian from the exact tangent dynamics with respect to the parameters
    /// ([`crate::stability::periodic_orbit_sensitivity`]), or `None` where it cannot serve:
    /// Shockley diodes, a record whose model has no period (chaos), a tangential release, a
    /// multiplier 1.
    fn exact_jacobian(&self, x: &[f64]) -> Option<Vec<Vec<f64>>> {
        if !self.exact || self.setup.experiment.diode_model() != DiodeModel::Pwl {
            return None;
        }
        let free = self.setup.free.len();
        let orbits = match &self.orbits {
            Some((at, orbits)) if at.as_slice() == x => orbits.clone(),
            _ => self.evaluate_all(x)?.into_iter().map(|(_, o)| o).collect(),
        };
        let experiment = self.setup.at(&x[..free])?;
        let system = *experiment.system()?;
        let scales = system.scales();
        let (omega0, zeta, position, force) =
            (scales.omega0, scales.zeta(), scales.position, scales.force);
        let chain = Chain::new(&system, zeta, omega0);
        let links: Vec<Link> = self
            .setup
            .free
            .iter()
            .map(|&p| chain.of(p))
            .collect::<Option<_>>()?;
        let sensitivities: Vec<Vec<OrbitSample>> = (0..self.data.len())
            .into_par_iter()
            .map(|j| {
                let orbit = orbits[j];
                let taus: Vec<f64> = self.time[j].iter().map(|&s| s * omega0).collect();
                periodic_orbit_sensitivity(&orbit.params, orbit.strobe, orbit.period?, &taus).ok()
            })
            .collect::<Option<_>>()?;
        let n_res = 2 * self.time.iter().map(Vec::len).sum::<usize>();
        let mut columns = vec![vec![0.0; n_res]; x.len()];
        self.fill_drive_columns(x, &mut columns);
        for (j, &(start, len)) in self.spans().iter().enumerate() {
            let half = len / 2;
            let wr = self.weights[j].1;
            let slots = self.slots[j];
            let params = orbits[j].params;
            let sine = &self.data[j].drive;
            for (i, (sample, &seconds)) in sensitivities[j].iter().zip(&self.time[j]).enumerate() {
                let [dz, db, dw, dphi, dmu] = sample.dy;
                let row = start + half + i;
                // dy/dω0 at a fixed time in seconds: w = Ω/ω0 and τ = ω0·s.
                let along = |zeta_p: f64, omega_p: f64| {
                    dz * zeta_p + (sample.v * seconds - dw * params.w / omega0) * omega_p
                };
                for (k, link) in links.iter().enumerate() {
                    let du = match *link {
                        // u = position·y with y(ζ(p), β(p), w(p), τ(p)) and position(p).
                        Link::Scales {
                            zeta: zeta_p,
                            omega0: omega_p,
                            position: position_p,
                        } => position * along(zeta_p, omega_p) + position_p * sample.y,
                        // u_C = U_t·y(β = U/U_t); r = (F0/k)·y(β = F/F0).
                        Link::Force => (sample.y - params.beta * db) * position / force,
                        Link::MuS => position * dmu,
                    };
                    columns[k][row] = wr * du * self.setup.scale[k];
                }
                columns[slots.drive][row] = wr * position * db * sine.amplitude / force;
                columns[slots.drive + 1][row] = wr * position * dw * TAU * sine.frequency / omega0;
                columns[slots.drive + 2][row] = wr * position * dphi;
                if let Some(k) = slots.shift {
                    columns[k][row] = wr * position * dphi;
                }
            }
        }
        Some(columns)
    }

    /// Where each record's residuals start, and how many it has.
    fn spans(&self) -> Vec<(usize, usize)> {
        let mut start = 0;
        self.time
            .iter()
            .map(|t| {
                let span = (start, 2 * t.len());
                start += 2 * t.len();
                span
            })
            .collect()
    }
}

fn no_value(file: &str, value: f64) -> FitError {
    FitError::Model {
        file: file.to_string(),
        error: crate::Error::InvalidParameter {
            name: "fit parameter",
            value,
            allowed: "the model has no value on either side of this value",
        },
    }
}

impl lm::Problem for Records<'_> {
    type Error = FitError;

    fn residuals(&mut self, x: &[f64]) -> Result<Option<Vec<f64>>, FitError> {
        self.setup.check_stop()?;
        let Some(records) = self.evaluate_all(x) else {
            return Ok(None);
        };
        let (residuals, orbits): (Vec<Vec<f64>>, Vec<Orbit>) = records.into_iter().unzip();
        self.orbits = Some((x.to_vec(), orbits));
        Ok(Some(residuals.concat()))
    }

    fn jacobian(&mut self, x: &[f64], r: &[f64]) -> Result<Vec<Vec<f64>>, FitError> {
        self.setup.check_stop()?;
        if let Some(columns) = self.exact_jacobian(x) {
            self.jacobian = Jacobian::Exact;
            return Ok(columns);
        }
        self.jacobian = Jacobian::FiniteDifferences;
        self.finite_difference_jacobian(x, r)
    }

    fn iteration(&mut self, iteration: usize, sum_squares: f64) -> Result<(), FitError> {
        self.watch.tell(iteration, sum_squares)
    }
}

impl Records<'_> {
    /// The Jacobian by finite differences (see the module documentation).
    fn finite_difference_jacobian(&self, x: &[f64], r: &[f64]) -> Result<Vec<Vec<f64>>, FitError> {
        let n = x.len();
        let spans = self.spans();
        let mut columns = vec![vec![0.0; r.len()]; n];
        let h = self.setup.step;
        for (k, column) in columns.iter_mut().enumerate().take(self.setup.free.len()) {
            let mut xp = x.to_vec();
            let mut dx = h * x[k].abs().max(1.0);
            xp[k] += dx;
            let mut rp = self.all(&xp);
            if rp.is_none() {
                // At the edge of the range: the backward difference.
                xp[k] = x[k] - dx;
                dx = -dx;
                rp = self.all(&xp);
            }
            let rp = rp.ok_or_else(|| no_value(&self.data[0].file, x[k] * self.setup.scale[k]))?;
            for (i, v) in rp.concat().iter().enumerate() {
                column[i] = (v - r[i]) / dx;
            }
        }
        let experiment = self
            .setup
            .at(&x[..self.setup.free.len()])
            .ok_or_else(|| no_value(&self.data[0].file, f64::NAN))?;
        // Per record, the response's derivatives by the drive amplitude, frequency and phase
        // (the time shift's column is the phase's: the response sees φ + ψ).
        let steps = [h, h, h];
        let derivatives: Vec<Option<[Vec<f64>; 3]>> = (0..self.data.len())
            .into_par_iter()
            .map(|j| {
                let k = self.slots[j].drive;
                let (start, len) = spans[j];
                let half = len / 2;
                let base = &r[start + half..start + len];
                let mut out: [Vec<f64>; 3] = Default::default();
                for (q, step) in steps.iter().enumerate() {
                    let mut xp = x.to_vec();
                    xp[k + q] += step;
                    let (rp, _) = self.record_residuals(&experiment, &xp, j)?;
                    out[q] = rp[half..]
                        .iter()
                        .zip(base)
                        .map(|(a, b)| (a - b) / step)
                        .collect();
                }
                Some(out)
            })
            .collect();
        self.fill_drive_columns(x, &mut columns);
        for j in 0..self.data.len() {
            let (start, len) = spans[j];
            let half = len / 2;
            let slots = self.slots[j];
            let dr = derivatives[j]
                .as_ref()
                .ok_or_else(|| no_value(&self.data[j].file, self.drive(x, j).frequency))?;
            for q in 0..3 {
                columns[slots.drive + q][start + half..start + len].copy_from_slice(&dr[q]);
            }
            if let Some(i) = slots.shift {
                columns[i][start + half..start + len].copy_from_slice(&dr[2]);
            }
        }
        Ok(columns)
    }
}

/// Standard errors, intervals and correlation of the free values from the solution; the
/// weighted residuals' variance s² scales (JᵀJ)⁻¹.
fn uncertainties(
    setup: &Setup,
    solution: &lm::Solution,
    n_values: usize,
) -> (Vec<FittedParameter>, Vec<Vec<f64>>, usize) {
    let n = solution.residuals.len();
    let dof = n.saturating_sub(n_values).max(1);
    let s2 = solution.sum_squares / dof as f64;
    let t = t_quantile_975(dof);
    let free = setup.free.len();
    let cov = |i: usize, k: usize| {
        solution.inverse_normal.as_ref().map_or(f64::NAN, |inv| {
            s2 * inv[i * n_values + k] * setup.scale[i] * setup.scale[k]
        })
    };
    let values = setup.values(&solution.x[..free]);
    let parameters = (0..free)
        .map(|i| {
            let stderr = cov(i, i).abs().sqrt();
            FittedParameter {
                parameter: setup.free[i],
                value: values[i],
                stderr,
                ci95: [values[i] - t * stderr, values[i] + t * stderr],
                initial: setup.scale[i],
            }
        })
        .collect::<Vec<_>>();
    let correlation = (0..free)
        .map(|i| {
            (0..free)
                .map(|k| cov(i, k) / (cov(i, i) * cov(k, k)).sqrt())
                .collect()
        })
        .collect();
    (parameters, correlation, dof)
}

/// AIC and BIC of Gaussian residuals with a variance of their own per group (channel):
/// −2 ln L = Σ N_g ln(SSR_g/N_g) up to a constant.
fn criteria(groups: &[(f64, usize)], p: usize) -> (f64, f64) {
    let n: usize = groups.iter().map(|g| g.1).sum();
    let base: f64 = groups
        .iter()
        .map(|&(ssr, count)| {
            let c = count.max(1) as f64;
            c * (ssr / c).max(f64::MIN_POSITIVE).ln()
        })
        .sum();
    (
        base + 2.0 * p as f64,
        base + p as f64 * (n.max(1) as f64).ln(),
    )
}

/// The RMS of `values`.
fn rms(values: &[f64]) -> f64 {
    (values.iter().map(|v| v * v).sum::<f64>() / values.len().max(1) as f64).sqrt()
}

impl<'a> Records<'a> {
    /// The problem of `data` with the free parameters of `setup`, and the starting values
    /// (free values scaled to 1, then each record's nuisance values).
    fn new(
        setup: &'a Setup,
        data: &'a [Measurement],
        options: &FitOptions,
        watch: Watch<'a>,
    ) -> Result<(Self, Vec<f64>), FitError> {
        let free = &setup.free;
        for m in data {
            check_units(&setup.system, m)?;
        }
        let mut x: Vec<f64> = vec![1.0; free.len()];
        let pick = |values: &[f64], used: &[bool]| -> Vec<f64> {
            values
                .iter()
                .zip(used)
                .filter(|(_, &u)| u)
                .map(|(&v, _)| v)
                .collect()
        };
        let time: Vec<Vec<f64>> = data.iter().map(|m| pick(&m.time, &m.used)).collect();
        let drive: Vec<Vec<f64>> = data
            .iter()
            .map(|m| pick(&m.drive_values, &m.used))
            .collect();
        let response: Vec<Vec<f64>> = data.iter().map(|m| pick(&m.response, &m.used)).collect();
        let mut slots = Vec::with_capacity(data.len());
        for (m, values) in data.iter().zip(&response) {
            let offset = options.offset.then(|| {
                x.push(values.iter().sum::<f64>() / values.len().max(1) as f64);
                x.len() - 1
            });
            let shift = options.time_shift.then(|| {
                x.push(0.0);
                x.len() - 1
            });
            slots.push(Slots {
                offset,
                shift,
                drive: x.len(),
            });
            x.extend([1.0, 1.0, m.drive.phase, m.drive.offset]);
        }
        let n_res: usize = 2 * time.iter().map(Vec::len).sum::<usize>();
        if n_res <= x.len() {
            return Err(FitError::TooFewSamples {
                residuals: n_res,
                values: x.len(),
            });
        }
        let start = setup.at(&x[..free.len()]).ok_or(FitError::FreeParameters(
            "the starting values are outside the parameters' ranges",
        ))?;
        for (m, t) in data.iter().zip(&time) {
            evaluate(
                &start,
                m.drive.frequency,
                m.drive.amplitude,
                m.drive.phase,
                t,
                &setup.steady,
            )
            .map_err(|error| FitError::Model {
                file: m.file.clone(),
                error,
            })?;
        }
        let weights = data
            .iter()
            .zip(drive.iter().zip(&response))
            .map(|(m, (d, r))| {
                (
                    1.0 / noise_floor(m.drive_noise, d, None),
                    1.0 / noise_floor(m.noise, r, m.resolution),
                )
            })
            .collect();
        let problem = Records {
            setup,
            data,
            slots,
            time,
            drive,
            response,
            weights,
            orbits: None,
            exact: options.exact_jacobian,
            jacobian: Jacobian::FiniteDifferences,
            watch,
        };
        Ok((problem, x))
    }
}

/// The units a record's drive and response must carry for `system`: a mechanical
/// oscillator's force in N and displacement in m (a plain CSV names them in its header,
/// `F (N)`, `r (m)`); a circuit's channels in anything but those.
fn check_units(system: &System, m: &Measurement) -> Result<(), FitError> {
    let (drive, response) = (m.drive_unit.as_str(), m.response_unit.as_str());
    let message = match system {
        System::Mechanics(_) if drive != "N" || response != "m" => format!(
            "a mechanical oscillator is fitted to a drive force in N and a displacement in m \
             (name the columns with their units, e.g. `F (N)` and `r (m)`); the record gives \
             the drive {} in {drive} and the response {} in {response}",
            m.drive_channel, m.response_channel
        ),
        System::Circuit(_) if drive == "N" || response == "m" => format!(
            "a circuit is fitted to voltages; the record gives the drive {} in {drive} and the \
             response {} in {response} (a mechanical record: give the mechanical oscillator's \
             parts)",
            m.drive_channel, m.response_channel
        ),
        _ => return Ok(()),
    };
    Err(FitError::Units {
        file: m.file.clone(),
        message,
    })
}

/// A floor under a channel's noise σ: a noise-free record must not get an infinite weight
/// (a twelfth of the resolution's variance, 10⁻⁹ of the channel's scale).
fn noise_floor(sigma: f64, values: &[f64], q: Option<f64>) -> f64 {
    let scale = values.iter().fold(0.0f64, |a, v| a.max(v.abs()));
    let quantum = q.unwrap_or(0.0) / 12f64.sqrt();
    sigma.max(quantum).max(1e-9 * scale).max(f64::MIN_POSITIVE)
}

/// Fit the free parameters of `experiment` (a circuit, PWL or Shockley) to every record of
/// `data` at once. The experiment's values are the starting point; its drive is not used
/// (each record has its own).
///
/// Each record's drive enters as measured: its amplitude, frequency, phase and offset are
/// fitted together with everything else to the drive channel's samples (starting from the
/// sine fit), so that their uncertainty is part of the error bars. Every channel's residuals
/// are divided by its noise: first as estimated from the data
/// ([`Measurement::noise`]), then, in a second pass from the first pass's solution, as the
/// RMS residual of that channel.
///
/// # Errors
/// No record; a free parameter named twice, of the other diode law, or none; not a circuit;
/// fewer samples than values; a model that cannot be computed at the starting values.
pub fn fit_records(
    experiment: &Experiment,
    data: &[Measurement],
    free: &[FitParameter],
    options: &FitOptions,
) -> Result<FitReport, FitError> {
    fit_records_monitored(experiment, data, free, options, &())
}

/// [`fit_records`], telling `monitor` of every iteration (of both passes: at most
/// 2·[`FitOptions::max_iterations`]), which can stop the fit.
///
/// # Errors
/// As [`fit_records`]; [`FitError::Stopped`] when the monitor stops the fit.
pub fn fit_records_monitored(
    experiment: &Experiment,
    data: &[Measurement],
    free: &[FitParameter],
    options: &FitOptions,
    monitor: &dyn FitMonitor,
) -> Result<FitReport, FitError> {
    let watch = Watch {
        monitor,
        before: 0,
        total: 2 * options.max_iterations,
    };
    records_watched(experiment, data, free, options, watch)
}

fn records_watched(
    experiment: &Experiment,
    data: &[Measurement],
    free: &[FitParameter],
    options: &FitOptions,
    watch: Watch<'_>,
) -> Result<FitReport, FitError> {
    if data.is_empty() {
        return Err(FitError::NoData);
    }
    let setup = Setup::new(experiment, free)?;
    let (mut problem, x) = Records::new(&setup, data, options, watch)?;
    let n_values = x.len();
    let settings = lm::Settings {
        max_iterations: options.max_iterations,
        tolerance: options.tolerance,
    };
    let failed = || FitError::Model {
        file: data[0].file.clone(),
        error: crate::Error::InvalidParameter {
            name: "fit",
            value: f64::NAN,
            allowed: "a model that can be computed at the starting values",
        },
    };
    let first = lm::minimise(&mut problem, x, settings)?.ok_or_else(failed)?;
    // Second pass: each channel weighted by its RMS residual of the first.
    let spans = problem.spans();
    let weights = spans
        .iter()
        .zip(&problem.weights)
        .zip(data.iter().zip(problem.drive.iter().zip(&problem.response)))
        .map(|((&(start, len), &(wd, wr)), (m, (d, r)))| {
            let half = len / 2;
            let sd = rms(&first.residuals[start..start + half]) / wd;
            let sr = rms(&first.residuals[start + half..start + len]) / wr;
            (
                1.0 / noise_floor(sd, d, None),
                1.0 / noise_floor(sr, r, m.resolution),
            )
        })
        .collect();
    problem.weights = weights;
    problem.watch.before += first.iterations;
    let second = lm::minimise(&mut problem, first.x.clone(), settings)?.ok_or_else(failed)?;
    let iterations = first.iterations + second.iterations;
    let solution = second;
    let (parameters, correlation, dof) = uncertainties(&setup, &solution, n_values);
    let fitted = setup.at(&solution.x[..free.len()]).ok_or_else(failed)?;
    let mut records = Vec::with_capacity(data.len());
    let mut chi2 = 0.0;
    let mut groups = Vec::new();
    let mut all_response = Vec::new();
    for (j, m) in data.iter().enumerate() {
        let (offset, shift) = problem.offset_and_shift(&solution.x, j);
        let d = problem.drive(&solution.x, j);
        let e = problem
            .response_model(&fitted, &solution.x, j)
            .map_err(|error| FitError::Model {
                file: m.file.clone(),
                error,
            })?;
        let (start, len) = spans[j];
        let half = len / 2;
        let (wd, wr) = problem.weights[j];
        let drive_residuals: Vec<f64> = solution.residuals[start..start + half]
            .iter()
            .map(|r| r / wd)
            .collect();
        let residuals: Vec<f64> = solution.residuals[start + half..start + len]
            .iter()
            .map(|r| r / wr)
            .collect();
        let ssr_d: f64 = drive_residuals.iter().map(|r| r * r).sum();
        let ssr_r: f64 = residuals.iter().map(|r| r * r).sum();
        chi2 += ssr_d / noise_floor(m.drive_noise, &problem.drive[j], None).powi(2)
            + ssr_r / noise_floor(m.noise, &problem.response[j], m.resolution).powi(2);
        groups.push((ssr_d, half));
        groups.push((ssr_r, half));
        all_response.extend_from_slice(&residuals);
        records.push(RecordFit {
            file: m.file.clone(),
            freq_hz: d.frequency,
            amplitude_v: d.amplitude,
            w: e.w,
            beta: e.beta,
            class: e.class,
            periods: m.drive.periods,
            clipped: m.clipped,
            rms_residual_v: rms(&residuals),
            offset_v: offset,
            time_shift_s: shift / (TAU * d.frequency),
            noise_v: m.noise,
            time: problem.time[j].clone(),
            model: e.model.iter().map(|v| v + offset).collect(),
            residuals,
        });
    }
    let n = solution.residuals.len();
    let noise = (data
        .iter()
        .zip(&problem.time)
        .map(|(m, t)| m.noise * m.noise * t.len() as f64)
        .sum::<f64>()
        / all_response.len() as f64)
        .sqrt();
    let (aic, bic) = criteria(&groups, n_values);
    Ok(FitReport {
        model: experiment.diode_model(),
        parameters,
        correlation,
        records,
        rows: vec![],
        rms_residual_v: rms(&all_response),
        noise_v: Some(noise),
        chi2_dof: Some(chi2 / dof as f64),
        dof,
        residuals: n,
        fitted_values: n_values,
        aic,
        bic,
        iterations,
        converged: solution.converged,
        jacobian: problem.jacobian,
        experiment: fitted,
    })
}

/// Fit the free parameters to each record alone (to see how a parameter drifts with the
/// drive, as the paper observes of U_t), in the order of `data`.
///
/// # Errors
/// As [`fit_records`], for the first record that fails.
pub fn fit_per_record(
    experiment: &Experiment,
    data: &[Measurement],
    free: &[FitParameter],
    options: &FitOptions,
) -> Result<Vec<FitReport>, FitError> {
    fit_per_record_monitored(experiment, data, free, options, &())
}

/// [`fit_per_record`], telling `monitor` of every iteration (at most
/// 2·[`FitOptions::max_iterations`] per record), which can stop the fits.
///
/// # Errors
/// As [`fit_per_record`]; [`FitError::Stopped`] when the monitor stops the fits.
pub fn fit_per_record_monitored(
    experiment: &Experiment,
    data: &[Measurement],
    free: &[FitParameter],
    options: &FitOptions,
    monitor: &dyn FitMonitor,
) -> Result<Vec<FitReport>, FitError> {
    if data.is_empty() {
        return Err(FitError::NoData);
    }
    let per = 2 * options.max_iterations;
    data.iter()
        .enumerate()
        .map(|(j, m)| {
            let watch = Watch {
                monitor,
                before: j * per,
                total: data.len() * per,
            };
            records_watched(experiment, std::slice::from_ref(m), free, options, watch)
        })
        .collect()
}

/// The same records fitted with PWL diodes (`experiment`, free `pwl_free`) and with the
/// Shockley pair `pair` in the same circuit (free `shockley_free`), compared by AIC.
///
/// # Errors
/// As [`fit_records`] for either fit; [`FitError::WrongLaw`] when `experiment` has Shockley
/// diodes.
pub fn compare_models(
    experiment: &Experiment,
    pair: DiodePair,
    data: &[Measurement],
    pwl_free: &[FitParameter],
    shockley_free: &[FitParameter],
    options: &FitOptions,
) -> Result<ModelComparison, FitError> {
    compare_models_monitored(
        experiment,
        pair,
        data,
        pwl_free,
        shockley_free,
        options,
        &(),
    )
}

/// [`compare_models`], telling `monitor` of every iteration of both fits (at most
/// 4·[`FitOptions::max_iterations`]), which can stop them.
///
/// # Errors
/// As [`compare_models`]; [`FitError::Stopped`] when the monitor stops the fits.
pub fn compare_models_monitored(
    experiment: &Experiment,
    pair: DiodePair,
    data: &[Measurement],
    pwl_free: &[FitParameter],
    shockley_free: &[FitParameter],
    options: &FitOptions,
    monitor: &dyn FitMonitor,
) -> Result<ModelComparison, FitError> {
    if experiment.diode_model() != DiodeModel::Pwl {
        return Err(FitError::WrongLaw {
            parameter: FitParameter::Ut,
            model: experiment.diode_model(),
        });
    }
    let shockley_experiment =
        experiment
            .clone()
            .with_shockley(pair)
            .map_err(|error| FitError::Model {
                file: "(comparison)".into(),
                error,
            })?;
    let per = 2 * options.max_iterations;
    let watch = |before| Watch {
        monitor,
        before,
        total: 2 * per,
    };
    let pwl = records_watched(experiment, data, pwl_free, options, watch(0))?;
    let shockley = records_watched(
        &shockley_experiment,
        data,
        shockley_free,
        options,
        watch(per),
    )?;
    let delta_aic = shockley.aic - pwl.aic;
    Ok(ModelComparison {
        preferred: if delta_aic < 0.0 {
            DiodeModel::Shockley
        } else {
            DiodeModel::Pwl
        },
        delta_aic,
        pwl,
        shockley,
    })
}

/// The problem of a table.
struct Table<'a> {
    setup: &'a Setup,
    table: &'a AmplitudeTable,
    /// Rows in computing order: legs (each a list of row indices, each row settling from the
    /// previous one) and single rows from rest.
    legs: Vec<Vec<usize>>,
    /// Who is told of each iteration.
    watch: Watch<'a>,
}

impl Table<'_> {
    /// (amplitude in V, class) of every row, or None outside the model's domain.
    fn amplitudes(&self, x: &[f64]) -> Option<Vec<(f64, MotionClass)>> {
        let experiment = self.setup.at(x)?;
        let legs: Vec<Option<Vec<(usize, f64, MotionClass)>>> = self
            .legs
            .par_iter()
            .map(|leg| {
                let mut state = State::default();
                let mut out = Vec::with_capacity(leg.len());
                for &i in leg {
                    let row = &self.table.rows[i];
                    let e = experiment
                        .clone()
                        .with_frequency(row.frequency)
                        .and_then(|e| e.with_amplitude(row.drive))
                        .and_then(|e| e.with_initial(state))
                        .ok()?;
                    let steady = e.steady_with(&self.setup.steady).ok()?;
                    state = steady.final_state();
                    let scale = e.scales()?.position;
                    out.push((i, steady.amplitude() * scale, steady.class));
                }
                Some(out)
            })
            .collect();
        let mut rows = vec![(0.0, MotionClass::Static); self.table.rows.len()];
        for leg in legs {
            for (i, a, c) in leg? {
                rows[i] = (a, c);
            }
        }
        Some(rows)
    }
}

impl lm::Problem for Table<'_> {
    type Error = FitError;

    fn residuals(&mut self, x: &[f64]) -> Result<Option<Vec<f64>>, FitError> {
        self.setup.check_stop()?;
        Ok(self.amplitudes(x).map(|a| {
            a.iter()
                .zip(&self.table.rows)
                .map(|((m, _), row)| m - row.response)
                .collect()
        }))
    }

    fn jacobian(&mut self, x: &[f64], r: &[f64]) -> Result<Vec<Vec<f64>>, FitError> {
        self.setup.check_stop()?;
        let h = self.setup.step;
        (0..x.len())
            .map(|k| {
                let mut xp = x.to_vec();
                let mut dx = h * x[k].abs().max(1.0);
                xp[k] += dx;
                let rp = match self.residuals(&xp)? {
                    Some(rp) => Some(rp),
                    None => {
                        xp[k] = x[k] - dx;
                        dx = -dx;
                        self.residuals(&xp)?
                    }
                };
                let rp = rp.ok_or_else(|| FitError::Model {
                    file: self.table.file.clone(),
                    error: crate::Error::InvalidParameter {
                        name: "fit parameter",
                        value: x[k] * self.setup.scale[k],
                        allowed: "the model has no value on either side",
                    },
                })?;
                Ok(rp.iter().zip(r).map(|(a, b)| (a - b) / dx).collect())
            })
            .collect()
    }

    fn iteration(&mut self, iteration: usize, sum_squares: f64) -> Result<(), FitError> {
        self.watch.tell(iteration, sum_squares)
    }
}

/// Fit the free parameters of `experiment` to a table of measured amplitudes (see the module
/// documentation).
///
/// # Errors
/// As [`fit_records`].
pub fn fit_table(
    experiment: &Experiment,
    table: &AmplitudeTable,
    free: &[FitParameter],
    options: &FitOptions,
) -> Result<FitReport, FitError> {
    fit_table_monitored(experiment, table, free, options, &())
}

/// [`fit_table`], telling `monitor` of every iteration (at most
/// [`FitOptions::max_iterations`]), which can stop the fit.
///
/// # Errors
/// As [`fit_table`]; [`FitError::Stopped`] when the monitor stops the fit.
pub fn fit_table_monitored(
    experiment: &Experiment,
    table: &AmplitudeTable,
    free: &[FitParameter],
    options: &FitOptions,
    monitor: &dyn FitMonitor,
) -> Result<FitReport, FitError> {
    if table.rows.is_empty() {
        return Err(FitError::NoData);
    }
    let setup = Setup::new(experiment, free)?;
    if matches!(setup.system, System::Mechanics(_)) {
        return Err(FitError::TableNeedsCircuit);
    }
    if table.rows.len() <= free.len() {
        return Err(FitError::TooFewSamples {
            residuals: table.rows.len(),
            values: free.len(),
        });
    }
    // Legs: rows of one direction and one drive amplitude (to 10⁻⁶), sorted along the sweep.
    let mut legs: Vec<(Direction, f64, Vec<usize>)> = Vec::new();
    let mut singles = Vec::new();
    for (i, row) in table.rows.iter().enumerate() {
        match row.direction {
            None => singles.push(vec![i]),
            Some(d) => match legs
                .iter_mut()
                .find(|(ld, u, _)| *ld == d && (u - row.drive).abs() <= 1e-6 * u.abs())
            {
                Some(leg) => leg.2.push(i),
                None => legs.push((d, row.drive, vec![i])),
            },
        }
    }
    let mut order: Vec<Vec<usize>> = legs
        .into_iter()
        .map(|(d, _, mut rows)| {
            rows.sort_by(|&a, &b| {
                let (fa, fb) = (table.rows[a].frequency, table.rows[b].frequency);
                match d {
                    Direction::Up => fa.total_cmp(&fb),
                    Direction::Down => fb.total_cmp(&fa),
                }
            });
            rows
        })
        .collect();
    order.extend(singles);
    let mut problem = Table {
        setup: &setup,
        table,
        legs: order,
        watch: Watch {
            monitor,
            before: 0,
            total: options.max_iterations,
        },
    };
    let x = vec![1.0; free.len()];
    if problem.amplitudes(&x).is_none() {
        return Err(FitError::Model {
            file: table.file.clone(),
            error: crate::Error::InvalidParameter {
                name: "fit",
                value: f64::NAN,
                allowed: "a model that can be computed at the starting values",
            },
        });
    }
    let solution = lm::minimise(
        &mut problem,
        x,
        lm::Settings {
            max_iterations: options.max_iterations,
            tolerance: options.tolerance,
        },
    )?
    .expect("the start was evaluated");
    let n_values = free.len();
    let (parameters, correlation, dof) = uncertainties(&setup, &solution, n_values);
    let fitted = setup.at(&solution.x).expect("the solution was evaluated");
    let amplitudes = problem
        .amplitudes(&solution.x)
        .expect("the solution was evaluated");
    let rows = table
        .rows
        .iter()
        .zip(&amplitudes)
        .map(|(row, &(model, class))| RowFit {
            line: row.line,
            freq_hz: row.frequency,
            drive_v: row.drive,
            direction: row.direction,
            measured_v: row.response,
            model_v: model,
            class,
        })
        .collect();
    let n = solution.residuals.len();
    let (aic, bic) = criteria(&[(solution.sum_squares, n)], n_values);
    Ok(FitReport {
        model: experiment.diode_model(),
        parameters,
        correlation,
        records: vec![],
        rows,
        rms_residual_v: (solution.sum_squares / n as f64).sqrt(),
        noise_v: None,
        chi2_dof: None,
        dof,
        residuals: n,
        fitted_values: n_values,
        aic,
        bic,
        iterations: solution.iterations,
        converged: solution.converged,
        jacobian: Jacobian::FiniteDifferences,
        experiment: fitted,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    use crate::physical::{Circuit, Mechanics};

    #[test]
    fn t_quantiles_match_tables() {
        // Student's t, 0.975: 2.571 (5), 2.228 (10), 2.042 (30), 1.984 (100).
        for (dof, t) in [(5, 2.5706), (10, 2.2281), (30, 2.0423), (100, 1.9840)] {
            assert!((t_quantile_975(dof) - t).abs() < 2e-3 * t, "{dof}");
        }
    }
    /// A plain-CSV record of `truth` at (w, β, φ): 600 samples over 2.5 drive periods, with
    /// a deterministic ripple of 0.3 % as noise and an offset of 20 mV on u_C.
    fn record(truth: &Experiment, w: f64, beta: f64, phi: f64) -> Measurement {
        let e = truth
            .clone()
            .with_w(w)
            .and_then(|e| e.with_beta(beta))
            .and_then(|e| e.with_phi(phi))
            .unwrap();
        let steady = e.steady().unwrap();
        let scales = e.scales().unwrap();
        let mut solver = e
            .factory()
            .make(e.params().unwrap(), steady.final_state())
            .unwrap();
        let n = 600;
        let dt = 2.5 * TAU / (w * scales.omega0) / n as f64;
        let taus: Vec<f64> = (0..n).map(|k| k as f64 * dt * scales.omega0).collect();
        let samples = sample_at(solver.as_mut(), &taus, |_| {}).unwrap();
        let mut text = if e.circuit_ref().is_some() {
            "time_s,u_V,uc_V\n".to_string()
        } else {
            "time_s,F (N),r (m)\n".to_string()
        };
        for (k, (tau, s)) in taus.iter().zip(&samples).enumerate() {
            let ripple = 0.003 * ((k * k % 97) as f64 / 48.0 - 1.0);
            let drive = beta * scales.force * (w * tau + phi).cos() * (1.0 + ripple);
            let response = (s.y + ripple + 0.03) * scales.position;
            text += &format!("{:.12e},{drive:.12e},{response:.12e}\n", k as f64 * dt);
        }
        let r = crate::measure::read_scope(&text, "plain.csv").unwrap();
        Measurement::new(&r, None, None).unwrap()
    }

    /// The exact Jacobian of records against Richardson-extrapolated central differences of
    /// the residuals, column by column, for every PWL parameter and every nuisance value:
    /// sliding records and a stick-slip record with μs > 1 (the releases move with the
    /// parameters).
    #[test]
    fn the_exact_jacobian_of_records_matches_central_differences() {
        let truth = Experiment::circuit(Circuit {
            resistance: 80.0,
            ..Circuit::paper()
        })
        .unwrap()
        .with_mu_s(1.25)
        .unwrap();
        let data: Vec<Measurement> = [(0.29, 2.6, 0.4), (0.95, 2.14, -1.1), (1.43, 3.0, 2.5)]
            .iter()
            .map(|&(w, beta, phi)| record(&truth, w, beta, phi))
            .collect();
        let start = Experiment::paper().with_mu_s(1.2).unwrap();
        let free = [
            FitParameter::Resistance,
            FitParameter::Ut,
            FitParameter::Rd,
            FitParameter::Inductance,
            FitParameter::Capacitance,
            FitParameter::MuS,
        ];
        exact_matches_central_differences(&start, &free, &data);
    }

    /// Every column of the exact Jacobian of `data` at `start` against Richardson-extrapolated
    /// central differences; the records must include a sliding and a stick-slip one.
    fn exact_matches_central_differences(
        start: &Experiment,
        free: &[FitParameter],
        data: &[Measurement],
    ) {
        let setup = Setup::new(start, free).unwrap();
        let watch = Watch {
            monitor: &(),
            before: 0,
            total: 1,
        };
        let (mut problem, x) = Records::new(&setup, data, &FitOptions::default(), watch).unwrap();
        let r = lm::Problem::residuals(&mut problem, &x).unwrap().unwrap();
        let exact = problem.exact_jacobian(&x).expect("periodic PWL models");
        let classes: Vec<MotionClass> = (0..data.len())
            .map(|j| {
                problem
                    .response_model(&setup.at(&x[..free.len()]).unwrap(), &x, j)
                    .unwrap()
                    .class
            })
            .collect();
        assert!(classes.contains(&MotionClass::PeriodicStick), "{classes:?}");
        assert!(classes.contains(&MotionClass::Sliding), "{classes:?}");
        let central = |k: usize, h: f64| -> Vec<f64> {
            let mut up = x.clone();
            let mut down = x.clone();
            up[k] += h;
            down[k] -= h;
            let (a, b) = (problem.all(&up).unwrap(), problem.all(&down).unwrap());
            a.concat()
                .iter()
                .zip(&b.concat())
                .map(|(a, b)| (a - b) / (2.0 * h))
                .collect()
        };
        for k in 0..x.len() {
            let h = 1e-5 * x[k].abs().max(1.0);
            let (coarse, fine) = (central(k, h), central(k, h / 2.0));
            let size = fine.iter().fold(0.0f64, |a, v| a.max(v.abs()));
            let mut worst = 0.0f64;
            for i in 0..r.len() {
                let richardson = (4.0 * fine[i] - coarse[i]) / 3.0;
                worst = worst.max((exact[k][i] - richardson).abs());
            }
            assert!(
                worst <= 1e-6 * size,
                "column {k}: deviation {worst:e} against a largest entry {size:e}"
            );
        }
    }

    /// The same for a mechanical oscillator: γ, F0, m, k and μs through the mechanical scales
    /// (ζ = γ/(2√(km)), ω0 = √(k/m), β = F/F0, r = (F0/k)·y).
    #[test]
    fn the_exact_jacobian_of_mechanical_records_matches_central_differences() {
        let truth = Experiment::mechanics(Mechanics::new(0.5, 200.0, 0.8, 0.3).unwrap())
            .unwrap()
            .with_mu_s(1.25)
            .unwrap();
        let data: Vec<Measurement> = [(0.29, 2.6, 0.4), (0.95, 2.14, -1.1), (1.43, 3.0, 2.5)]
            .iter()
            .map(|&(w, beta, phi)| record(&truth, w, beta, phi))
            .collect();
        let start = Experiment::mechanics(Mechanics::new(0.55, 180.0, 0.7, 0.32).unwrap())
            .unwrap()
            .with_mu_s(1.2)
            .unwrap();
        let free = FitParameter::MECHANICS;
        exact_matches_central_differences(&start, &free, &data);
    }
}
