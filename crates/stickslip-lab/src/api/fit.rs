//! `POST /api/fit`: the circuit's free parameters fitted to one scope record, as
//! `stickslip fit --data FILE --free KEYS --json` fits them (the library's
//! [`fit_records`]), with the fitted experiment's keys and the record's u_C beside the
//! fitted model over two drive periods for the plot.

use super::answer::Columns;
use super::upload::{RecordKeys, Upload, RECORD_FIELD, RECORD_KEYS};
use crate::limit::Budget;
use crate::query::{api_name, circuit_keys, ApiError, Query};
use axum::http::StatusCode;
use serde::Serialize;
use std::collections::BTreeMap;
use std::f64::consts::{PI, TAU};
use std::sync::Arc;
use stickslip::experiment::{DiodeModel, Experiment, Key, Preset};
use stickslip::fit::{fit_records, FitError, FitOptions, FitParameter, FitReportJson};
use stickslip::SystemKind;

/// `POST /api/fit`.
#[derive(Debug)]
pub struct FitRequest {
    experiment: Experiment,
    free: Vec<FitParameter>,
    keys: RecordKeys,
    upload: Upload,
}

/// The answer of `/api/fit`: every key of `stickslip fit --json` for the same record and
/// free parameters, and what the page needs beside them.
#[derive(Debug, Serialize)]
pub struct FitAnswer {
    /// What `stickslip fit --json` prints.
    #[serde(flatten)]
    pub report: FitReportJson,
    /// The fitted experiment's one-line description.
    pub experiment: String,
    /// The fitted experiment as query keys (numbers in SI units): every fit parameter of
    /// its diode law (`inductance`, `capacitance`, `resistance`, and `ut`, `rd` or
    /// `diode-is`, `diode-n`, `diode-rs`; `mu-s` when it was free), and the record's drive
    /// as fitted: `freq` (Hz), `amplitude` (V) and `phi` (rad, the drive's phase at the
    /// record's first sample plus the fitted time shift between the channels).
    pub keys: BTreeMap<&'static str, f64>,
    /// The noise of u_C estimated from the record (V), to compare with `rms_residual_V`.
    #[serde(rename = "noise_V")]
    pub noise_v: Option<f64>,
    /// The record's u_C and the fitted model over (at most) its first two drive periods, at
    /// the samples the fit used: `t_s` (s since the first sample), `measured_V`, `model_V`,
    /// `residual_V` (model − measured), the columns of `stickslip fit --out`.
    pub plot: Columns,
}

/// The free parameters of a circuit's fit when `free` is not given: the library's default
/// free set of the diode law (`stickslip::fit::FitParameter::defaults`, as `stickslip fit`
/// and Python's `fit` free them).
pub fn default_free(model: DiodeModel) -> Vec<FitParameter> {
    FitParameter::defaults(SystemKind::Circuit, model)
}

/// The drive's keys, refused: each record's drive is as measured.
const DRIVE_KEYS: [Key; 6] = [
    Key::W,
    Key::Beta,
    Key::Frequency,
    Key::Omega,
    Key::Amplitude,
    Key::Phi,
];

impl FitRequest {
    /// Keys: the model keys without the drive (the starting values and the diode law),
    /// `free` (comma-separated fit parameters: `resistance`, `ut`, `rd`, `diode-is`,
    /// `diode-n`, `diode-rs`, `inductance`, `capacitance`, `mu-s`; default
    /// [`default_free`]), `file`, `drive`, `response` ([`RecordKeys`]). The body: the CSV
    /// text, given by [`Self::with_upload`].
    ///
    /// # Errors
    /// A 400 naming the key at fault.
    pub fn parse(raw: Option<&str>) -> Result<Self, ApiError> {
        let mut q = Query::parse(raw)?;
        if let Some(&key) = DRIVE_KEYS.iter().find(|&&k| q.has_model(k)) {
            let name = api_name(key);
            return Err(ApiError::field(
                &name,
                format!(
                    "the fit takes the drive (frequency, amplitude, phase) from the record: \
                     drop {name}"
                ),
            ));
        }
        let experiment = q.experiment()?;
        let free_text = q
            .take("free")
            .unwrap_or_else(|| FitParameter::list(&default_free(experiment.diode_model())));
        let mut free = Vec::new();
        for name in free_text
            .split(',')
            .map(str::trim)
            .filter(|s| !s.is_empty())
        {
            let p: FitParameter = name
                .parse()
                .map_err(|e: FitError| ApiError::field("free", format!("invalid free: {e}")))?;
            if !p.applies_to(experiment.diode_model()) {
                return Err(ApiError::field(
                    "free",
                    format!(
                        "invalid free: {}",
                        FitError::WrongLaw {
                            parameter: p,
                            model: experiment.diode_model()
                        }
                    ),
                ));
            }
            if free.contains(&p) {
                return Err(ApiError::field(
                    "free",
                    format!("invalid free: {p} is named twice"),
                ));
            }
            free.push(p);
        }
        if free.is_empty() {
            let names: Vec<&str> = FitParameter::CIRCUIT.iter().map(|p| p.label()).collect();
            return Err(ApiError::field(
                "free",
                format!(
                    "invalid free: name at least one parameter ({})",
                    names.join(", ")
                ),
            ));
        }
        let keys = RecordKeys::take(&mut q)?;
        q.finish(&["free", RECORD_KEYS[0], RECORD_KEYS[1], RECORD_KEYS[2]])?;
        if experiment.circuit_ref().is_none() {
            return Err(ApiError::bad(format!(
                "fitting needs a circuit ({}={}, or {}): a record is of u_C and the drive in \
                 volts",
                api_name(Key::Preset),
                Preset::Paper,
                circuit_keys()
            )));
        }
        Ok(Self {
            experiment,
            free,
            keys,
            upload: Upload::None,
        })
    }

    /// The request with the record (the body, read after the keys were checked).
    pub fn with_upload(mut self, upload: Upload) -> Self {
        self.upload = upload;
        self
    }

    /// Read the record and fit, as `stickslip fit` does, stopping with the budget (the
    /// library's token: the time limit, or a client that went away).
    ///
    /// # Errors
    /// The reader's refusal (400 naming the file and line), the fit's (400), the time limit
    /// (503), a model that cannot be computed (the library's status).
    pub fn run(self, budget: &Arc<Budget>) -> Result<FitAnswer, ApiError> {
        let (_, m) = self.keys.read(&self.upload)?;
        let e = self.experiment.with_cancel(budget.cancel());
        let report = fit_records(
            &e,
            std::slice::from_ref(&m),
            &self.free,
            &FitOptions::default(),
        )
        .map_err(|err| fit_error(err, budget))?;
        let fitted = &report.experiment;
        let model = fitted.diode_model();
        let mut keys = BTreeMap::new();
        for p in FitParameter::ALL {
            if p.applies_to(model) && (p != FitParameter::MuS || self.free.contains(&p)) {
                if let Ok(v) = p.get(fitted) {
                    keys.insert(p.label(), v);
                }
            }
        }
        let r = &report.records[0];
        keys.insert("freq", r.freq_hz);
        keys.insert("amplitude", r.amplitude_v);
        keys.insert(
            "phi",
            wrap(m.drive.phase + TAU * r.freq_hz * r.time_shift_s),
        );
        let two_periods = 2.0 / r.freq_hz;
        let n = r.time.iter().take_while(|&&t| t <= two_periods).count();
        let mut plot = Columns::default();
        plot.push("t_s", r.time[..n].to_vec());
        plot.push(
            "measured_V",
            (0..n).map(|i| r.model[i] - r.residuals[i]).collect(),
        );
        plot.push("model_V", r.model[..n].to_vec());
        plot.push("residual_V", r.residuals[..n].to_vec());
        Ok(FitAnswer {
            report: report.to_json(),
            experiment: fitted.to_string(),
            keys,
            noise_v: report.noise_v,
            plot,
        })
    }
}

/// A phase in (−π, π].
fn wrap(phase: f64) -> f64 {
    let p = phase.rem_euclid(TAU);
    if p > PI {
        p - TAU
    } else {
        p
    }
}

/// A fit's refusal as an answer: the record's faults and the free list are 400s naming
/// their field, a stop by the budget the time limit's 503, a model that cannot be computed
/// the library's status with the fit's words.
fn fit_error(err: FitError, budget: &Budget) -> ApiError {
    // Past the time limit, or with nobody waiting, whatever failed failed because the token
    // stopped the solvers (a stopped evaluation inside a step can read as a failed model).
    if budget.spent() {
        return stopped(budget);
    }
    let message = err.to_string();
    match err {
        FitError::Measure(_) | FitError::TooFewSamples { .. } | FitError::NoData => {
            ApiError::field(RECORD_FIELD, message)
        }
        FitError::UnknownParameter(_) | FitError::WrongLaw { .. } | FitError::FreeParameters(_) => {
            ApiError::field("free", message)
        }
        FitError::Stopped(_) => stopped(budget),
        FitError::Model { error, .. } => match error {
            stickslip::Error::Cancelled { .. }
            | stickslip::Error::DeadlineExceeded
            | stickslip::Error::BudgetExceeded { .. } => stopped(budget),
            other => ApiError {
                message,
                ..ApiError::library(&other)
            },
        },
        _ => ApiError::bad(message),
    }
}

/// The fit was stopped: by the time limit, or because nobody waits for it.
fn stopped(budget: &Budget) -> ApiError {
    ApiError::status(
        StatusCode::SERVICE_UNAVAILABLE,
        if budget.abandoned() && !budget.timed_out() {
            "the fit was stopped: the request was dropped".to_string()
        } else {
            format!(
                "the fit took longer than the lab's time limit of {} s: free fewer \
                 parameters, or send a shorter record",
                budget.limit().as_secs_f64()
            )
        },
    )
}
