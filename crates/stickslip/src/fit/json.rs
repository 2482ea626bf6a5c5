//! The reports' JSON shape, in one place: what `stickslip fit --json` prints and what the
//! Python package's `FitResult.to_dict()` returns.

use super::{FitReport, ModelComparison};
use crate::measure::Direction;
use serde::Serialize;
use std::collections::BTreeMap;

/// A fitted parameter in the JSON report. Where there is no error bar (a parameter held or
/// not seen, a singular fit) `stderr` and `ci95` are null and a warning says why.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct ParameterJson {
    /// The fitted value, in the parameter's unit ([`super::FitParameter::unit`]).
    pub value: f64,
    /// Its standard error, in the same unit; null where there is none.
    pub stderr: Option<f64>,
    /// The 95 % confidence interval `[lo, hi]`; null where there is none.
    pub ci95: [Option<f64>; 2],
    /// How the interval was found: `linear` (value ± t·stderr, in ln I_s for I_s, checked at
    /// both ends), `profile` (the profile likelihood), `held` or `none` (no interval).
    pub interval: &'static str,
}

/// A warning in the JSON report: its kind (`not-converged`, `not-identified`, `unseen`,
/// `correlated`, `at-bound`, `clipped`), the parameters it is about and its one line.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct WarningJson {
    /// The kind ([`super::FitWarning::kind`]).
    pub kind: &'static str,
    /// The parameters it names, by their names.
    pub parameters: Vec<&'static str>,
    /// The warning in words, one line.
    pub message: String,
}

/// A record of a fit in the JSON report.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct RecordJson {
    /// The record's file name, as given.
    pub file: String,
    /// The drive's frequency (Hz).
    #[serde(rename = "freq_Hz")]
    pub freq_hz: f64,
    /// The drive's amplitude (V, peak).
    #[serde(rename = "amplitude_V")]
    pub amplitude_v: f64,
    /// The dimensionless drive frequency w.
    pub w: f64,
    /// The dimensionless drive amplitude β.
    pub beta: f64,
    /// The motion class of the fitted model's steady state.
    pub class: &'static str,
    /// Whole drive periods in the record.
    pub periods: usize,
    /// Clipped samples, excluded from the fit.
    pub clipped: usize,
    /// RMS of the u_C residuals (V).
    #[serde(rename = "rms_residual_V")]
    pub rms_residual_v: f64,
    /// The fitted DC offset of u_C (V).
    #[serde(rename = "offset_V")]
    pub offset_v: f64,
    /// The fitted time shift between the channels (s).
    #[serde(rename = "time_shift_s")]
    pub time_shift_s: f64,
}

/// A row of an amplitude table in the JSON report.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct RowJson {
    /// The row's line in the file (1-based).
    pub line: usize,
    /// Drive frequency (Hz).
    #[serde(rename = "freq_Hz")]
    pub freq_hz: f64,
    /// Drive amplitude (V, peak).
    #[serde(rename = "U_V")]
    pub drive_v: f64,
    /// The leg of the sweep, when the table says.
    pub direction: Option<Direction>,
    /// The measured response amplitude (V).
    #[serde(rename = "measured_V")]
    pub measured_v: f64,
    /// The fitted model's response amplitude (V).
    #[serde(rename = "model_V")]
    pub model_v: f64,
    /// The motion class of the fitted model's steady state.
    pub class: &'static str,
}

/// The units of a mechanical fit's channels in the JSON report: the keys named in volts
/// (`amplitude_V`, `rms_residual_V`, `offset_V`) hold the drive's force in `drive` (N) and
/// the displacement in `response` (m).
#[derive(Debug, Clone, PartialEq, Eq, Serialize)]
pub struct UnitsJson {
    /// The drive's unit (`N`).
    pub drive: &'static str,
    /// The response's unit (`m`).
    pub response: &'static str,
}

/// A fit's report as JSON: `model`, `parameters` keyed by the flag names
/// (`{"resistance": {"value", "stderr", "ci95", "interval"}}`), `correlation`, `records`
/// (records only), `rows` (a table only), `rms_residual_V`, `chi2_dof`, `converged`,
/// `iterations`, `jacobian`, `aic`, `bic`, `warnings` ([`WarningJson`]), and for a
/// mechanical oscillator `units` ([`UnitsJson`]).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct FitReportJson {
    /// The diode law.
    pub model: &'static str,
    /// The fitted parameters by name.
    pub parameters: BTreeMap<&'static str, ParameterJson>,
    /// The correlation matrix of the free parameters, in the order of `--free` (null for a
    /// parameter without an error bar).
    pub correlation: Vec<Vec<Option<f64>>>,
    /// Per record (omitted for a table).
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub records: Vec<RecordJson>,
    /// Per row of a table (omitted for records).
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub rows: Vec<RowJson>,
    /// RMS of all residuals (V).
    #[serde(rename = "rms_residual_V")]
    pub rms_residual_v: f64,
    /// χ²/dof with the noise estimated from the data; null when unknown.
    pub chi2_dof: Option<f64>,
    /// Whether the fit converged: the step and gradient criteria hold and no restart found a
    /// lower χ² (else a `not-converged` warning says why).
    pub converged: bool,
    /// Its iterations.
    pub iterations: usize,
    /// How the Jacobian at the solution was computed: `exact` or `finite-differences`.
    pub jacobian: &'static str,
    /// Akaike's information criterion.
    pub aic: f64,
    /// The Bayesian information criterion.
    pub bic: f64,
    /// What the fit warns of, in the order found.
    pub warnings: Vec<WarningJson>,
    /// A mechanical oscillator's channel units (omitted for a circuit, whose keys in volts
    /// mean volts).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub units: Option<UnitsJson>,
}

/// A model comparison as JSON: `pwl`, `shockley` (each a [`FitReportJson`]), `preferred`
/// and `delta_aic` (AIC Shockley − PWL).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct ComparisonJson {
    /// The PWL fit.
    pub pwl: FitReportJson,
    /// The Shockley fit.
    pub shockley: FitReportJson,
    /// The law with the lower AIC.
    pub preferred: &'static str,
    /// AIC Shockley − PWL.
    pub delta_aic: f64,
}

/// A number, or `None` when it is not finite (a singular fit's error bars).
fn finite(v: f64) -> Option<f64> {
    v.is_finite().then_some(v)
}

impl FitReport {
    /// The report in its JSON shape.
    pub fn to_json(&self) -> FitReportJson {
        FitReportJson {
            model: self.model.label(),
            parameters: self
                .parameters
                .iter()
                .map(|p| {
                    (
                        p.parameter.label(),
                        ParameterJson {
                            value: p.value,
                            stderr: finite(p.stderr),
                            ci95: [finite(p.ci95[0]), finite(p.ci95[1])],
                            interval: p.interval.label(),
                        },
                    )
                })
                .collect(),
            correlation: self
                .correlation
                .iter()
                .map(|row| row.iter().map(|&c| finite(c)).collect())
                .collect(),
            records: self
                .records
                .iter()
                .map(|rec| RecordJson {
                    file: rec.file.clone(),
                    freq_hz: rec.freq_hz,
                    amplitude_v: rec.amplitude_v,
                    w: rec.w,
                    beta: rec.beta,
                    class: rec.class.label(),
                    periods: rec.periods,
                    clipped: rec.clipped,
                    rms_residual_v: rec.rms_residual_v,
                    offset_v: rec.offset_v,
                    time_shift_s: rec.time_shift_s,
                })
                .collect(),
            rows: self
                .rows
                .iter()
                .map(|row| RowJson {
                    line: row.line,
                    freq_hz: row.freq_hz,
                    drive_v: row.drive_v,
                    direction: row.direction,
                    measured_v: row.measured_v,
                    model_v: row.model_v,
                    class: row.class.label(),
                })
                .collect(),
            rms_residual_v: self.rms_residual_v,
            chi2_dof: self.chi2_dof,
            converged: self.converged,
            iterations: self.iterations,
            jacobian: self.jacobian.label(),
            aic: self.aic,
            bic: self.bic,
            warnings: self
                .warnings
                .iter()
                .map(|w| WarningJson {
                    kind: w.kind(),
                    parameters: w.parameters().iter().map(|p| p.label()).collect(),
                    message: w.to_string(),
                })
                .collect(),
            units: self.is_mechanics().then(|| {
                let (drive, response) = self.units();
                UnitsJson { drive, response }
            }),
        }
    }
}

impl ModelComparison {
    /// The comparison in its JSON shape.
    pub fn to_json(&self) -> ComparisonJson {
        ComparisonJson {
            pwl: self.pwl.to_json(),
            shockley: self.shockley.to_json(),
            preferred: self.preferred.label(),
            delta_aic: self.delta_aic,
        }
    }
}
