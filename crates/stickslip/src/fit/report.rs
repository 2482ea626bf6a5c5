//! What a fit reports: each fitted value with its interval, per record or row, the whole
//! fit's figures of merit, and the comparison of two laws on the same data.

use super::*;
use crate::experiment::{DiodeModel, Experiment};
use crate::measure::Direction;
use crate::physical::System;
use crate::steady::MotionClass;
use serde::{Deserialize, Serialize};

/// How a fit's Jacobian was computed.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
#[non_exhaustive]
pub enum Jacobian {
    /// From the exact tangent dynamics with respect to the parameters
    /// ([`crate::stability::periodic_orbit_sensitivity`]): PWL diodes, every record's model a
    /// periodic orbit.
    Exact,
    /// By finite differences: a model that does not repeat (chaos) or whose orbit's
    /// derivative does not exist there (a tangential release), or a table.
    FiniteDifferences,
    /// From the stiff solver's forward sensitivities along a smooth law's periodic orbit
    /// ([`crate::stability::ShockleyDynamics::orbit_sensitivity`]): Shockley diodes, every
    /// record's model a periodic orbit.
    Sensitivities,
    /// By central differences of the whole model, the friction solver at its tolerance of
    /// 10⁻¹² (`central.rs`): a mechanical oscillator on a belt or with the Stribeck or cubic
    /// friction law, whose solvers have no sensitivities.
    CentralDifferences,
}

impl Jacobian {
    /// The label in reports: `exact`, `finite-differences`, `sensitivities` or
    /// `central-differences`.
    pub fn label(self) -> &'static str {
        match self {
            Jacobian::Exact => "exact",
            Jacobian::FiniteDifferences => "finite-differences",
            Jacobian::Sensitivities => "sensitivities",
            Jacobian::CentralDifferences => "central-differences",
        }
    }
}

/// How a fitted value's 95 % interval was found.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
#[non_exhaustive]
pub enum Interval {
    /// value ± t·stderr in the value's coordinate (ln I_s for I_s): the linear approximation,
    /// checked at both ends.
    Linear,
    /// The profile likelihood at one end or both, where the linear approximation fails (or
    /// the interval meets the value's range).
    Profile,
    /// No interval: a parameter the records cannot separate from others, held at its
    /// starting value ([`FitWarning::NotIdentified`]).
    Held,
    /// No interval: the records do not determine the value ([`FitWarning::Unseen`]).
    None,
}

impl Interval {
    /// The label in reports: `linear`, `profile`, `held`, `none`.
    pub fn label(self) -> &'static str {
        match self {
            Interval::Linear => "linear",
            Interval::Profile => "profile",
            Interval::Held => "held",
            Interval::None => "none",
        }
    }
}

/// A fitted free parameter.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct FittedParameter {
    /// Which.
    pub parameter: FitParameter,
    /// The fitted value (SI units, [`FitParameter::unit`]); a held parameter's starting value.
    pub value: f64,
    /// Its standard error (NaN where there is none: a held or unseen parameter, a singular
    /// fit; the report's warnings say why).
    pub stderr: f64,
    /// The 95 % interval [lo, hi] (NaN where there is none).
    pub ci95: [f64; 2],
    /// The starting value.
    pub initial: f64,
    /// How the interval was found.
    pub interval: Interval,
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
    /// Whether the fit converged: the step and the gradient criteria hold at the solution
    /// and no restart from elsewhere found a lower χ² (else a [`FitWarning::NotConverged`]
    /// says why).
    pub converged: bool,
    /// How the Jacobian at the solution, the one the error bars come from, was computed.
    pub jacobian: Jacobian,
    /// The experiment with the fitted values.
    pub experiment: Experiment,
    /// What the fit warns of ([`FitWarning`]): not converged, parameters the records cannot
    /// separate or do not see, strong correlations, values at the edge of their range,
    /// clipped samples.
    pub warnings: Vec<FitWarning>,
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
