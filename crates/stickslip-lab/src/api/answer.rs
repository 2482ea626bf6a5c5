//! What every answer holds: the experiment's description and scales, traces as named
//! columns, events, and the message of a computation that failed.

use crate::limit::Budget;
use crate::query::ApiError;
use axum::http::StatusCode;
use serde::ser::SerializeMap;
use serde::{Serialize, Serializer};
use std::f64::consts::TAU;
use stickslip::experiment::{Conversion, Experiment};
use stickslip::physical::{Scales, System};
use stickslip::{DiodeModel, Error, Event};

/// What every answer says about its experiment.
#[derive(Debug, Serialize)]
pub struct About {
    /// The one-line description (as the command-line tool prints on standard error).
    pub experiment: String,
    /// `pwl` or `shockley`.
    pub model: &'static str,
    /// `circuit`, `mechanics` or `dimensionless`.
    pub system: &'static str,
    /// ω0, f0, α, ζ, Q (and w, β) of a physical description (`stickslip convert --json`).
    pub conversion: Option<Conversion>,
    /// The drive in physical units, when the description is physical and has a drive.
    pub drive: Option<Drive>,
    /// Physical units per dimensionless unit: `position` (V or m per unit of y), `velocity`
    /// (A or m/s per unit of y'), `force` (V or N per unit of β), `omega0` (rad/s).
    pub scales: Option<Scales>,
    /// Names of the physical columns of traces: `t_s, uc_V, i_A, u_V` or `t_s, r_m, rdot_m_s, F_N`
    /// (left out where the answer's own `columns` lists every column, as in `/api/simulate`).
    #[serde(skip_serializing_if = "PhysicalColumns::omitted")]
    pub columns: PhysicalColumns,
}

/// The names of the physical columns of traces (`null` for a dimensionless description), or
/// nothing where the answer is a trajectory report, whose own `columns` lists every column.
#[derive(Debug)]
pub struct PhysicalColumns {
    /// The four names, if the description is physical.
    pub names: Option<[&'static str; 4]>,
    /// Left out of the answer.
    pub omit: bool,
}

impl PhysicalColumns {
    fn omitted(&self) -> bool {
        self.omit
    }
}

impl Serialize for PhysicalColumns {
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        self.names.serialize(s)
    }
}

/// The drive in physical units.
#[derive(Debug, Serialize)]
pub struct Drive {
    /// Frequency f in Hz.
    #[serde(rename = "f_Hz")]
    pub f_hz: f64,
    /// Angular frequency Ω in rad/s.
    pub omega: f64,
    /// Amplitude U (V) or F (N).
    pub amplitude: f64,
    /// `V` or `N`.
    pub unit: &'static str,
}

impl About {
    pub(crate) fn new(e: &Experiment) -> Self {
        let scales = e.scales();
        let unit = match e.system() {
            Some(System::Mechanics(_)) => "N",
            _ => "V",
        };
        Self {
            experiment: e.to_string(),
            model: e.diode_model().label(),
            system: e.system_kind().label(),
            conversion: e.conversion(),
            drive: scales.zip(e.w().zip(e.beta())).map(|(s, (w, beta))| Drive {
                f_hz: s.drive_omega(w) / TAU,
                omega: s.drive_omega(w),
                amplitude: s.drive_amplitude(beta),
                unit,
            }),
            scales,
            columns: PhysicalColumns {
                names: e.units().map(|u| u.columns()),
                omit: false,
            },
        }
    }

    /// The description beside a trajectory report ([`stickslip::report::TrajectoryReport`]),
    /// whose `columns` names every column (the physical ones among them).
    pub(crate) fn trajectory(e: &Experiment) -> Self {
        let mut about = Self::new(e);
        about.columns.omit = true;
        about
    }
}

/// Named columns of numbers, serialised as a JSON object in this order.
#[derive(Debug, Default)]
pub struct Columns(Vec<(&'static str, Vec<f64>)>);

impl Columns {
    pub(crate) fn push(&mut self, name: &'static str, values: Vec<f64>) {
        self.0.push((name, values));
    }
}

impl Serialize for Columns {
    fn serialize<S: Serializer>(&self, s: S) -> Result<S::Ok, S::Error> {
        let mut map = s.serialize_map(Some(self.0.len()))?;
        for (name, values) in &self.0 {
            map.serialize_entry(name, values)?;
        }
        map.end()
    }
}

/// `tau, y, v, drive` and, for a physical description, its four physical columns.
pub(crate) fn columns(
    e: &Experiment,
    rows: impl Iterator<Item = (f64, f64, f64, f64)> + Clone,
) -> Columns {
    let mut c = Columns::default();
    c.push("tau", rows.clone().map(|r| r.0).collect());
    c.push("y", rows.clone().map(|r| r.1).collect());
    c.push("v", rows.clone().map(|r| r.2).collect());
    c.push("drive", rows.clone().map(|r| r.3).collect());
    if let Some(units) = e.units() {
        for (k, name) in units.columns().into_iter().enumerate() {
            c.push(
                name,
                rows.clone()
                    .map(|(tau, y, v, d)| units.convert(tau, y, v, d)[k])
                    .collect(),
            );
        }
    }
    c
}

/// An event of the motion.
#[derive(Debug, Serialize)]
pub struct EventRow {
    /// Dimensionless time τ.
    pub tau: f64,
    /// Position y.
    pub y: f64,
    /// `turn`, `stick` or `slip`.
    pub kind: &'static str,
}

pub(crate) fn event_rows(events: &[Event]) -> Vec<EventRow> {
    events
        .iter()
        .map(|e| EventRow {
            tau: e.tau,
            y: e.y,
            kind: e.kind.label(),
        })
        .collect()
}

/// Turn a library error of a computation into an answer: the time limit and a dropped request
/// say so; anything else is the library's message.
pub(crate) fn failed(err: Error, budget: &Budget, what: &str) -> ApiError {
    match err {
        Error::Cancelled { .. } | Error::DeadlineExceeded
            if budget.timed_out() || !budget.abandoned() =>
        {
            let progress = match budget.progress() {
                (done, total) if total > 1 => format!(" ({done} of {total} done)"),
                _ => String::new(),
            };
            ApiError::status(
                StatusCode::SERVICE_UNAVAILABLE,
                format!(
                    "the {what} took longer than the lab's time limit of {} s{progress}: ask for \
                     less (fewer points, steps or periods)",
                    budget.limit().as_secs_f64()
                ),
            )
        }
        Error::Cancelled { .. } | Error::DeadlineExceeded => ApiError::status(
            StatusCode::SERVICE_UNAVAILABLE,
            format!("the {what} was stopped: the request was dropped"),
        ),
        other => ApiError::library(&other),
    }
}

/// `PWL theory: ` with Shockley diodes (the theory is that of the PWL model), else empty.
pub(crate) fn pwl_prefix(e: &Experiment) -> &'static str {
    match e.diode_model() {
        DiodeModel::Pwl => "",
        DiodeModel::Shockley => "PWL theory: ",
    }
}

/// A trace: columns of samples.
#[derive(Debug, Serialize)]
pub struct Trace {
    /// Samples per drive period.
    pub samples_per_period: usize,
    /// Drive periods covered (a self-excited motion: 1, its one cycle).
    pub periods: f64,
    /// τ of the first sample.
    pub start: f64,
    /// The τ the record covers, from its first sample to where it repeats (the drive's
    /// periods, or the self-excited cycle's period, 2π where there is none); the page's scope
    /// repeats the record with this period.
    pub span_tau: f64,
    /// The span in seconds (`span_tau` / ω0) of a physical description; null for a
    /// dimensionless one.
    pub span_s: Option<f64>,
    /// `tau, y, v, drive` (dimensionless) and the physical columns.
    pub columns: Columns,
}
