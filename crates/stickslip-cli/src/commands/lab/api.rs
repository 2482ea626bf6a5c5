//! The endpoints' work, each in two steps: `parse` reads the query (at once, on the server's
//! own threads: a bad query costs nothing) and `run` calls the library within a [`Budget`]
//! (on a worker thread). Answers are library results serialised as they are, with the
//! description of the experiment and its physical scales beside them.

use super::limit::{Budget, LimitedFactory};
use super::query::{api_name, ApiError, Query};
use crate::commands::sweep::Theory as SweepTheory;
use crate::flags::{keys_of, SteadyFlags};
use axum::http::StatusCode;
use serde::ser::SerializeMap;
use serde::{Serialize, Serializer};
use std::f64::consts::TAU;
use std::sync::Arc;
use stickslip::experiment::{Conversion, Experiment, Key};
use stickslip::physical::{Circuit, Scales, System};
use stickslip::scan::{Axis, Grid, ParameterRange, Sweep, SweepDirection};
use stickslip::solver::{grid, sample_at};
use stickslip::steady::{steady_state_from, MotionClass, SteadyOptions, SteadyReport};
use stickslip::theory::curves::{abscissae, theory_curve, Theory, TheoryQuantity};
use stickslip::theory::TheoryReport;
use stickslip::{DiodeModel, DiodePair, Error, Event, Parameter, Unsupported};

/// Caps on what one request may ask for.
pub mod caps {
    /// Most display samples per drive period of the steady cycle's trace.
    pub const STEADY_SAMPLES: usize = 4096;
    /// Longest period looked for by a steady state (drive periods).
    pub const MAX_PERIOD: usize = 16;
    /// Most drive periods run to reach a steady state.
    pub const MAX_PERIODS: usize = 5000;
    /// Most drive periods of a simulation from the initial state.
    pub const SIMULATE_PERIODS: f64 = 2000.0;
    /// Most samples per drive period of a simulation.
    pub const SIMULATE_SAMPLES: usize = 10_000;
    /// Most samples of a simulation in all.
    pub const SIMULATE_TOTAL: usize = 200_000;
    /// Most values of a sweep (each leg).
    pub const SWEEP_STEPS: usize = 400;
    /// Most values on one side of a map.
    pub const MAP_SIDE: usize = 1000;
    /// Most points of a map.
    pub const MAP_POINTS: usize = 40_000;
}

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
    /// Names of the physical columns of traces: `t_s, uc_V, i_A, u_V` or `t_s, r_m, rdot_m_s, F_N`.
    pub columns: Option<[&'static str; 4]>,
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
    fn new(e: &Experiment) -> Self {
        let scales = e.scales();
        let unit = match e.system() {
            Some(System::Mechanics(_)) => "N",
            _ => "V",
        };
        Self {
            experiment: e.to_string(),
            model: e.diode_model().label(),
            system: match e.system() {
                Some(System::Circuit(_)) => "circuit",
                Some(System::Mechanics(_)) => "mechanics",
                None => "dimensionless",
            },
            conversion: e.conversion(),
            drive: scales.zip(e.w().zip(e.beta())).map(|(s, (w, beta))| Drive {
                f_hz: s.drive_omega(w) / TAU,
                omega: s.drive_omega(w),
                amplitude: s.drive_amplitude(beta),
                unit,
            }),
            scales,
            columns: e.units().map(|u| u.columns()),
        }
    }
}

/// Named columns of numbers, serialised as a JSON object in this order.
#[derive(Debug, Default)]
pub struct Columns(Vec<(&'static str, Vec<f64>)>);

impl Columns {
    fn push(&mut self, name: &'static str, values: Vec<f64>) {
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
fn columns(e: &Experiment, rows: impl Iterator<Item = (f64, f64, f64, f64)> + Clone) -> Columns {
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

fn event_rows(events: &[Event]) -> Vec<EventRow> {
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
fn failed(err: Error, budget: &Budget, what: &str) -> ApiError {
    match err {
        Error::Cancelled { .. } if budget.timed_out() || !budget.abandoned() => {
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
        Error::Cancelled { .. } => ApiError::status(
            StatusCode::SERVICE_UNAVAILABLE,
            format!("the {what} was stopped: the request was dropped"),
        ),
        other => ApiError::library(&other),
    }
}

/// The steady-state keys of `steady`, `sweep` and `map` (as the command-line flags of the same
/// names, with the lab's caps): `tolerance`, `max-periods`, `max-period`.
fn steady_options(q: &mut Query, e: &Experiment) -> Result<SteadyOptions, ApiError> {
    let tolerance = q.number("tolerance", None)?;
    if let Some(t) = tolerance {
        if !(t > 0.0 && t < 1.0) {
            return Err(ApiError::field(
                "tolerance",
                format!("invalid tolerance {t}: must be > 0 and < 1"),
            ));
        }
    }
    let max_periods = q.count("max-periods", caps::MAX_PERIODS, 1, caps::MAX_PERIODS)?;
    let max_period = q.count("max-period", 16, 1, caps::MAX_PERIOD)?;
    let flags = SteadyFlags {
        tolerance,
        max_periods: max_periods as i64,
        max_period: max_period as i64,
        no_extrapolation: false,
        lyapunov_periods: stickslip::SteadyOptions::DEFAULT_LYAPUNOV.periods as i64,
    };
    flags
        .options(e)
        .map_err(|err| ApiError::bad(err.to_string()))
}

/// The experiment's dimensionless parameters, or a 400 naming the missing drive value.
fn needs_drive(e: &Experiment) -> Result<(), ApiError> {
    e.params()
        .map(|_| ())
        .map_err(|err| ApiError::library(&err))
}

/// `GET /api/steady`.
#[derive(Debug)]
pub struct SteadyRequest {
    experiment: Experiment,
    options: SteadyOptions,
    samples: usize,
}

/// The answer of `/api/steady`: the keys and numbers of `stickslip steady --json`, the
/// description, and the steady cycle's trace and events.
#[derive(Debug, Serialize)]
pub struct SteadyAnswer {
    /// What `stickslip steady --json` prints.
    #[serde(flatten)]
    pub report: SteadyReport,
    /// The experiment.
    #[serde(flatten)]
    pub about: About,
    /// The recorded cycle, decimated to `samples` per drive period.
    pub trace: Trace,
    /// Events inside the recorded cycle.
    pub events: Vec<EventRow>,
}

/// A trace: columns of samples.
#[derive(Debug, Serialize)]
pub struct Trace {
    /// Samples per drive period.
    pub samples_per_period: usize,
    /// Drive periods covered.
    pub periods: f64,
    /// τ of the first sample.
    pub start: f64,
    /// `tau, y, v, drive` (dimensionless) and the physical columns.
    pub columns: Columns,
}

impl SteadyRequest {
    /// Keys: the model keys, `harmonics` (9 to 256, default 16, as `--harmonics`), `samples`
    /// (display samples per drive period, a power of two from 16 to 4096, default 512),
    /// `tolerance`, `max-periods` (1 to 5000), `max-period` (1 to 16).
    ///
    /// # Errors
    /// A 400 naming the key at fault.
    pub fn parse(raw: Option<&str>) -> Result<Self, ApiError> {
        let mut q = Query::parse(raw)?;
        let experiment = q.experiment()?;
        let harmonics = q.count("harmonics", 16, 9, 256)?;
        let samples = q.count("samples", 512, 16, caps::STEADY_SAMPLES)?;
        if !samples.is_power_of_two() {
            return Err(ApiError::field(
                "samples",
                format!(
                    "invalid samples {samples}: must be a power of two from 16 to {}",
                    caps::STEADY_SAMPLES
                ),
            ));
        }
        let options = steady_options(&mut q, &experiment)?
            .with_harmonics(harmonics)
            .map_err(|e| ApiError::library(&e))?;
        q.finish(&[
            "harmonics",
            "samples",
            "tolerance",
            "max-periods",
            "max-period",
        ])?;
        needs_drive(&experiment)?;
        Ok(Self {
            experiment,
            options,
            samples,
        })
    }

    /// Run to the steady state, as `stickslip steady` does.
    ///
    /// # Errors
    /// The time limit; the library's errors.
    pub fn run(self, budget: &Arc<Budget>) -> Result<SteadyAnswer, ApiError> {
        let e = &self.experiment;
        let params = e.params().map_err(|err| ApiError::library(&err))?;
        let factory = LimitedFactory::new(e.factory(), budget.clone());
        let steady = steady_state_from(&factory, &params, e.initial(), &self.options)
            .map_err(|err| failed(err, budget, "steady state"))?;
        let per_period = steady.spectrum.as_ref().map_or(1, |s| s.samples_per_period);
        let stride = (per_period / self.samples).max(1);
        let rows = steady
            .trace
            .iter()
            .step_by(stride)
            .map(|s| (s.tau, s.y, s.v, params.drive(s.tau)));
        Ok(SteadyAnswer {
            report: SteadyReport::from(&steady),
            about: About::new(e),
            trace: Trace {
                samples_per_period: per_period / stride,
                periods: steady.recorded_periods as f64,
                start: steady.start,
                columns: columns(e, rows),
            },
            events: event_rows(&steady.events),
        })
    }
}

/// `GET /api/simulate`.
#[derive(Debug)]
pub struct SimulateRequest {
    experiment: Experiment,
    periods: f64,
    samples: usize,
}

/// The answer of `/api/simulate`: the run from the initial state, as `stickslip simulate`
/// writes it.
#[derive(Debug, Serialize)]
pub struct SimulateAnswer {
    /// The experiment.
    #[serde(flatten)]
    pub about: About,
    /// The samples; `phase` holds `slip+`, `slip-` or `stick` for each.
    pub trace: Trace,
    /// Phase of the motion at each sample.
    pub phase: Vec<&'static str>,
    /// Every event of the run.
    pub events: Vec<EventRow>,
}

impl SimulateRequest {
    /// Keys: the model keys, `periods` (> 0, at most 2000, default 20), `samples` (per drive
    /// period, 1 to 10000, default 200); at most 200000 samples in all.
    ///
    /// # Errors
    /// A 400 naming the key at fault.
    pub fn parse(raw: Option<&str>) -> Result<Self, ApiError> {
        let mut q = Query::parse(raw)?;
        let experiment = q.experiment()?;
        let periods = q.number("periods", Some(20.0))?.unwrap_or(20.0);
        if !(periods > 0.0 && periods <= caps::SIMULATE_PERIODS) {
            return Err(ApiError::field(
                "periods",
                format!(
                    "invalid periods {periods}: must be > 0 and at most {}",
                    caps::SIMULATE_PERIODS
                ),
            ));
        }
        let samples = q.count("samples", 200, 1, caps::SIMULATE_SAMPLES)?;
        let total = (periods * samples as f64).ceil();
        if total > caps::SIMULATE_TOTAL as f64 {
            return Err(ApiError::field(
                "samples",
                format!(
                    "periods × samples = {total} samples: at most {} allowed",
                    caps::SIMULATE_TOTAL
                ),
            ));
        }
        q.finish(&["periods", "samples"])?;
        needs_drive(&experiment)?;
        Ok(Self {
            experiment,
            periods,
            samples,
        })
    }

    /// Run from the initial state, as `stickslip simulate` does.
    ///
    /// # Errors
    /// The time limit; the library's errors.
    pub fn run(self, budget: &Arc<Budget>) -> Result<SimulateAnswer, ApiError> {
        use stickslip::steady::SolverFactory;
        let e = &self.experiment;
        let params = e.params().map_err(|err| ApiError::library(&err))?;
        let mut solver = LimitedFactory::new(e.factory(), budget.clone())
            .make(params, e.initial())
            .map_err(|err| ApiError::library(&err))?;
        let total = (self.periods * self.samples as f64).ceil() as usize;
        let times = grid(0.0, self.periods * params.drive_period(), total);
        let mut events = Vec::new();
        let samples = sample_at(solver.as_mut(), &times, |ev| events.push(*ev))
            .map_err(|err| failed(err, budget, "simulation"))?;
        let rows = samples
            .iter()
            .map(|s| (s.tau, s.y, s.v, params.drive(s.tau)));
        Ok(SimulateAnswer {
            about: About::new(e),
            trace: Trace {
                samples_per_period: self.samples,
                periods: self.periods,
                start: 0.0,
                columns: columns(e, rows),
            },
            phase: samples.iter().map(|s| s.phase.label()).collect(),
            events: event_rows(&events),
        })
    }
}

/// `GET /api/sweep`.
#[derive(Debug)]
pub struct SweepRequest {
    experiment: Experiment,
    parameter: Parameter,
    range: ParameterRange,
    direction: SweepDirection,
    options: SteadyOptions,
}

/// One step of a sweep: the columns of `stickslip sweep`'s CSV.
#[derive(Debug, Serialize)]
pub struct SweepRow {
    /// The swept parameter's value.
    pub value: f64,
    /// `up` or `down`.
    pub leg: &'static str,
    /// w of the step.
    pub w: f64,
    /// β of the step.
    pub beta: f64,
    /// Gain (y_max − y_min)/(2β).
    pub gain: f64,
    /// Amplitude of the fundamental of y.
    #[serde(rename = "A1")]
    pub a1: Option<f64>,
    /// Amplitude of the third harmonic of y.
    #[serde(rename = "A3")]
    pub a3: Option<f64>,
    /// Motion class.
    pub class: &'static str,
    /// Stops per drive period.
    pub stops_per_cycle: f64,
    /// Period in drive periods (`null`: none found).
    pub period: Option<usize>,
    /// Drive frequency in Hz, for a physical description.
    #[serde(rename = "f_Hz")]
    pub f_hz: Option<f64>,
}

/// The answer of `/api/sweep`.
#[derive(Debug, Serialize)]
pub struct SweepAnswer {
    /// The experiment.
    #[serde(flatten)]
    pub about: About,
    /// The swept parameter: `w`, `beta`, `zeta` or `mu-s`.
    pub over: String,
    /// `up`, `down` or `both`.
    pub direction: &'static str,
    /// The steps in the order they were computed.
    pub points: Vec<SweepRow>,
    /// The theory's gains over the range (null where there is none).
    pub theory: SweepTheoryCurves,
}

/// The theory's gain curves beside a sweep (those `stickslip sweep --plot` draws).
#[derive(Debug, Serialize)]
pub struct SweepTheoryCurves {
    /// Values of the swept parameter.
    pub x: Vec<f64>,
    /// The paper's gain A1/β, eq. (11).
    pub paper_gain: Vec<f64>,
    /// The exact sliding orbit's peak/β.
    pub exact_peak_gain: Vec<f64>,
    /// `PWL theory: ` with Shockley diodes (the theory is that of the PWL model), else empty.
    pub prefix: &'static str,
}

/// `over=` values and the parameters they name.
const OVER: [(&str, Parameter); 4] = [
    ("w", Parameter::W),
    ("beta", Parameter::Beta),
    ("zeta", Parameter::Zeta),
    ("mu-s", Parameter::MuS),
];

/// Refuse model keys that give a value of a parameter the request sets itself.
fn reject_swept(q: &Query, parameter: Parameter, by: &str) -> Result<(), ApiError> {
    if let Some(&key) = keys_of(parameter).iter().find(|&&k| q.has_model(k)) {
        let name = api_name(key);
        return Err(ApiError::field(
            &name,
            format!("{by} sets {} itself: drop {name}", parameter.label()),
        ));
    }
    Ok(())
}

/// A number as a message shows it: huge and tiny ones in exponent form.
fn short(x: f64) -> String {
    if x != 0.0 && !(1e-4..1e6).contains(&x.abs()) {
        format!("{x:e}")
    } else {
        x.to_string()
    }
}

/// `from`, `to` and `steps` keys (with prefix, e.g. `w-`) as a range.
fn range(
    q: &mut Query,
    parameter: Parameter,
    keys: [&str; 3],
    defaults: (f64, f64, usize),
    max_steps: usize,
) -> Result<ParameterRange, ApiError> {
    let from = q.number(keys[0], Some(defaults.0))?.unwrap_or(defaults.0);
    let to = q.number(keys[1], Some(defaults.1))?.unwrap_or(defaults.1);
    let steps = q.count(keys[2], defaults.2, 1, max_steps)?;
    // Each end within the parameter's own range, named by the key that gave it.
    let key = match parameter {
        Parameter::W => Key::W,
        Parameter::Beta => Key::Beta,
        Parameter::Zeta => Key::Zeta,
        _ => Key::MuS,
    };
    for (end, value) in [(keys[0], from), (keys[1], to)] {
        if let Err(Error::InvalidParameter { allowed, .. }) = key.check(value) {
            return Err(ApiError::field(
                end,
                format!(
                    "invalid {end} {}: {} {allowed}",
                    short(value),
                    api_name(key)
                ),
            ));
        }
    }
    if from > to {
        return Err(ApiError::field(
            keys[0],
            format!(
                "invalid range: {} {from} is above {} {to}",
                keys[0], keys[1]
            ),
        ));
    }
    if steps == 1 && from != to {
        return Err(ApiError::field(
            keys[2],
            format!(
                "invalid {} 1: a range from {from} to {to} needs at least 2 points",
                keys[2]
            ),
        ));
    }
    ParameterRange::new(parameter.label(), from, to, steps)
        .map_err(|e| ApiError::field(keys[0], e.to_string()))
}

impl SweepRequest {
    /// Keys: the model keys (without a value of the swept parameter), `over` (`w`, `beta`,
    /// `zeta` or `mu-s`, default `w`), `from`, `to` (default 0.2 to 2), `steps` (1 to 400,
    /// default 60), `direction` (`up`, `down` or `both`, the default), `tolerance`,
    /// `max-periods`, `max-period`.
    ///
    /// # Errors
    /// A 400 naming the key at fault.
    pub fn parse(raw: Option<&str>) -> Result<Self, ApiError> {
        let mut q = Query::parse(raw)?;
        let parameter = q.choice("over", &OVER, Parameter::W)?;
        reject_swept(&q, parameter, "a sweep")?;
        let experiment = q.experiment()?;
        let range = range(
            &mut q,
            parameter,
            ["from", "to", "steps"],
            (0.2, 2.0, 60),
            caps::SWEEP_STEPS,
        )?;
        let direction = q.choice(
            "direction",
            &[
                ("up", SweepDirection::Up),
                ("down", SweepDirection::Down),
                ("both", SweepDirection::Both),
            ],
            SweepDirection::Both,
        )?;
        let options = steady_options(&mut q, &experiment)?
            .with_harmonics(3)
            .map_err(|e| ApiError::library(&e))?;
        q.finish(&[
            "over",
            "from",
            "to",
            "steps",
            "direction",
            "tolerance",
            "max-periods",
            "max-period",
        ])?;
        // The experiment must be complete but for the swept parameter.
        Axis::range(parameter, &range)
            .and_then(|axis| Sweep::new(&experiment, axis))
            .map_err(|e| ApiError::library(&e))?;
        Ok(Self {
            experiment,
            parameter,
            range,
            direction,
            options,
        })
    }

    /// Sweep up and/or down with continuation, as `stickslip sweep` does.
    ///
    /// # Errors
    /// The time limit; the library's errors.
    pub fn run(self, budget: &Arc<Budget>) -> Result<SweepAnswer, ApiError> {
        let e = &self.experiment;
        let library = |err: Error| ApiError::library(&err);
        let sweep = Sweep::new(
            e,
            Axis::range(self.parameter, &self.range).map_err(library)?,
        )
        .map_err(library)?
        .direction(self.direction)
        .options(self.options)
        .map_err(library)?
        .with_factory(LimitedFactory::new(e.factory(), budget.clone()));
        budget.start(sweep.plan().len());
        let points = sweep
            .run(&budget.keep_going())
            .map_err(|err| failed(err, budget, "sweep"))?;
        let theory = SweepTheory::new(e, self.parameter, &self.range)
            .map_err(|err| ApiError::bad(err.to_string()))?;
        let scales = e.scales();
        Ok(SweepAnswer {
            about: About::new(e),
            over: OVER
                .iter()
                .find(|o| o.1 == self.parameter)
                .map_or("w", |o| o.0)
                .to_string(),
            direction: self.direction.label(),
            points: points
                .iter()
                .map(|p| SweepRow {
                    value: p.value,
                    leg: p.leg.label(),
                    w: p.params.w,
                    beta: p.params.beta,
                    gain: p.steady.gain,
                    a1: p.steady.harmonic(1),
                    a3: p.steady.harmonic(3),
                    class: p.steady.class.label(),
                    stops_per_cycle: p.steady.stops_per_period,
                    period: p.steady.period,
                    f_hz: scales.map(|s| s.drive_omega(p.params.w) / TAU),
                })
                .collect(),
            theory: SweepTheoryCurves {
                x: theory.paper.x.clone(),
                paper_gain: theory.paper.y,
                exact_peak_gain: theory.exact.y,
                prefix: theory.prefix,
            },
        })
    }
}

/// `GET /api/map`.
#[derive(Debug)]
pub struct MapRequest {
    experiment: Experiment,
    w: ParameterRange,
    beta: ParameterRange,
    options: SteadyOptions,
}

/// The answer of `/api/map`: motion classes on a (w, β) grid, each point from the initial
/// state, as `stickslip phase-diagram` computes them.
#[derive(Debug, Serialize)]
pub struct MapAnswer {
    /// The experiment.
    #[serde(flatten)]
    pub about: About,
    /// The frequencies w (rows).
    pub w: Vec<f64>,
    /// The amplitudes β (columns).
    pub beta: Vec<f64>,
    /// Class labels; `class` holds indices into this list.
    pub classes: Vec<&'static str>,
    /// Class of point (w_i, β_j) at i·(number of β) + j.
    pub class: Vec<u8>,
    /// Period in drive periods (null: none found), in the same order.
    pub period: Vec<Option<usize>>,
    /// Stops per drive period, in the same order.
    pub stops_per_cycle: Vec<f64>,
    /// Gain, in the same order.
    pub gain: Vec<f64>,
    /// The stick-slip boundaries over w inside the β range (null elsewhere).
    pub boundary: Boundary,
}

/// Stick-slip boundaries β_c over w.
#[derive(Debug, Serialize)]
pub struct Boundary {
    /// Frequencies.
    pub w: Vec<f64>,
    /// The paper's eq. (13).
    pub paper: Vec<f64>,
    /// The exact β_c(w, ζ, μs).
    pub exact: Vec<f64>,
    /// `PWL theory: ` with Shockley diodes, else empty.
    pub prefix: &'static str,
}

impl MapRequest {
    /// Keys: the model keys (without w or β), `w-min`, `w-max`, `w-steps` (default 0.1 to
    /// 2.5 in 60), `beta-min`, `beta-max`, `beta-steps` (default 0.5 to 4 in 50), at most
    /// 1000 on a side and 40000 points; `tolerance`, `max-periods`, `max-period`.
    ///
    /// # Errors
    /// A 400 naming the key at fault.
    pub fn parse(raw: Option<&str>) -> Result<Self, ApiError> {
        let mut q = Query::parse(raw)?;
        reject_swept(&q, Parameter::W, "a map")?;
        reject_swept(&q, Parameter::Beta, "a map")?;
        let experiment = q.experiment()?;
        let w = range(
            &mut q,
            Parameter::W,
            ["w-min", "w-max", "w-steps"],
            (0.1, 2.5, 60),
            caps::MAP_SIDE,
        )?;
        let beta = range(
            &mut q,
            Parameter::Beta,
            ["beta-min", "beta-max", "beta-steps"],
            (0.5, 4.0, 50),
            caps::MAP_SIDE,
        )?;
        if w.steps() * beta.steps() > caps::MAP_POINTS {
            return Err(ApiError::field(
                "w-steps",
                format!(
                    "w-steps × beta-steps = {}: at most {} points",
                    w.steps() * beta.steps(),
                    caps::MAP_POINTS
                ),
            ));
        }
        let options = steady_options(&mut q, &experiment)?;
        q.finish(&[
            "w-min",
            "w-max",
            "w-steps",
            "beta-min",
            "beta-max",
            "beta-steps",
            "tolerance",
            "max-periods",
            "max-period",
        ])?;
        let axis = |p, r: &ParameterRange| {
            Axis::range(p, r).map_err(|err| {
                let key = if p == Parameter::W {
                    "w-min"
                } else {
                    "beta-min"
                };
                ApiError::field(key, err.to_string())
            })
        };
        Grid::new(
            &experiment,
            axis(Parameter::W, &w)?,
            axis(Parameter::Beta, &beta)?,
        )
        .map_err(|e| ApiError::library(&e))?;
        Ok(Self {
            experiment,
            w,
            beta,
            options,
        })
    }

    /// Classify every point, as `stickslip phase-diagram` does.
    ///
    /// # Errors
    /// The time limit; the library's errors.
    pub fn run(self, budget: &Arc<Budget>) -> Result<MapAnswer, ApiError> {
        let e = &self.experiment;
        let library = |err: Error| ApiError::library(&err);
        let grid = Grid::new(
            e,
            Axis::range(Parameter::W, &self.w).map_err(library)?,
            Axis::range(Parameter::Beta, &self.beta).map_err(library)?,
        )
        .map_err(library)?
        .options(self.options)
        .map_err(library)?
        .with_factory(LimitedFactory::new(e.factory(), budget.clone()));
        let (rows, cols) = grid.shape();
        let total = rows * cols;
        budget.start(total);
        // Block by block (a grid computed so equals the grid computed at once), so that the
        // map gives its turn to other clients between blocks of about one slice: the blocks'
        // points run on the parallel pool, whose threads must never wait for a turn.
        let keep_going = budget.keep_going();
        let mut points = Vec::with_capacity(total);
        let mut size = 2 * rayon::current_num_threads();
        while points.len() < total {
            let next = points.len();
            let (row, col) = (next / cols, next % cols);
            let (block_rows, block_cols) = if col == 0 && size >= cols {
                (row..(row + size / cols).min(rows), 0..cols)
            } else {
                (row..row + 1, col..(col + size).min(cols))
            };
            let n = block_rows.len() * block_cols.len();
            let started = std::time::Instant::now();
            points.extend(
                grid.run_block(block_rows, block_cols, &|done, _| {
                    keep_going(next + done, total)
                })
                .map_err(|err| failed(err, budget, "map"))?,
            );
            let per_point = started.elapsed().as_secs_f64() / n as f64;
            size =
                ((super::fair::SLICE.as_secs_f64() / per_point.max(1e-9)) as usize).clamp(1, total);
            budget.share();
        }
        let map = stickslip::scan::GridMap {
            first: grid_axis(&self.w, Parameter::W)?,
            second: grid_axis(&self.beta, Parameter::Beta)?,
            points,
        };
        let index = |c: MotionClass| {
            MotionClass::ALL
                .iter()
                .position(|&k| k == c)
                .unwrap_or_default() as u8
        };
        // The boundaries of the PWL theory, where they lie inside the β range.
        let ws = abscissae(self.w.from(), self.w.to(), self.w.steps());
        let base = e
            .params_with(&[
                (Parameter::W, self.w.from()),
                (Parameter::Beta, self.beta.from()),
            ])
            .map_err(library)?;
        let boundary = |theory| {
            theory_curve(theory, TheoryQuantity::Boundary, &base, Parameter::W, &ws)
                .within(self.beta.from(), self.beta.to())
                .y
        };
        Ok(MapAnswer {
            about: About::new(e),
            w: map.first.values().to_vec(),
            beta: map.second.values().to_vec(),
            classes: MotionClass::ALL.iter().map(|c| c.label()).collect(),
            class: map.points.iter().map(|p| index(p.class)).collect(),
            period: map.points.iter().map(|p| p.period).collect(),
            stops_per_cycle: map.points.iter().map(|p| p.stops_per_period).collect(),
            gain: map.points.iter().map(|p| p.gain).collect(),
            boundary: Boundary {
                paper: boundary(Theory::Paper),
                exact: boundary(Theory::Exact),
                w: ws,
                prefix: match e.diode_model() {
                    DiodeModel::Pwl => "",
                    DiodeModel::Shockley => "PWL theory: ",
                },
            },
        })
    }
}

/// The axis of a map's range.
fn grid_axis(range: &ParameterRange, parameter: Parameter) -> Result<Axis, ApiError> {
    Axis::range(parameter, range).map_err(|err| ApiError::library(&err))
}

/// `GET /api/theory`.
#[derive(Debug)]
pub struct TheoryRequest {
    experiment: Experiment,
}

impl TheoryRequest {
    /// Keys: the model keys (PWL diodes or Coulomb friction; no initial state, as `stickslip
    /// theory`).
    ///
    /// # Errors
    /// A 400 naming the key at fault.
    pub fn parse(raw: Option<&str>) -> Result<Self, ApiError> {
        let mut q = Query::parse(raw)?;
        for name in ["y0", "v0", "uc0", "i0"] {
            if q.has(name) {
                return Err(ApiError::field(
                    name,
                    format!(
                        "{name} is not used by theory: it computes steady states, not a run \
                         from an initial state"
                    ),
                ));
            }
        }
        let experiment = q.experiment()?;
        q.finish(&[])?;
        if experiment.diode_model() == DiodeModel::Shockley {
            return Err(ApiError::field(
                "model",
                Error::Unsupported(Unsupported::TheoryNeedsPwl).to_string(),
            ));
        }
        needs_drive(&experiment)?;
        Ok(Self { experiment })
    }

    /// Both theories at the point, as `stickslip theory --json` prints them.
    ///
    /// # Errors
    /// The library's errors.
    pub fn run(self, _budget: &Arc<Budget>) -> Result<TheoryReport, ApiError> {
        let params = self
            .experiment
            .params()
            .map_err(|e| ApiError::library(&e))?;
        TheoryReport::new(&params).map_err(|e| ApiError::library(&e))
    }
}

/// The points of the paper's Fig. 3: (label, w = Ω/ω0, β), panels (1a)–(2c).
pub const FIG3_POINTS: [(&str, f64, f64); 6] = [
    ("1a", 0.29, 1.07),
    ("1b", 0.95, 1.07),
    ("1c", 1.43, 1.07),
    ("2a", 0.29, 2.14),
    ("2b", 0.95, 2.14),
    ("2c", 1.43, 2.14),
];

/// One preset of the page: values of its fields, by query key.
#[derive(Debug, Serialize)]
pub struct PresetRow {
    /// Identifier.
    pub id: String,
    /// What the page shows.
    pub label: String,
    /// `circuit` or `mechanics`.
    pub system: &'static str,
    /// Values by query key (numbers in SI units); `preset=paper` stands for the paper's parts.
    pub values: Vec<(String, f64)>,
    /// Whether the preset is the paper's circuit (`preset=paper` describes it exactly).
    pub paper: bool,
}

/// `GET /api/presets`: the paper's circuit, its Fig. 3 points, the 1N4148 Shockley
/// parameters and a mechanical oscillator with the paper's damping ratio.
pub fn presets() -> serde_json::Value {
    use stickslip::experiment::Key;
    use stickslip::physical::Diode;
    let paper = Circuit::paper();
    let (turn_on, rd) = match paper.diode {
        Diode::Pwl(d) => (d.turn_on, d.resistance),
        Diode::Shockley(d) => (d.reference_voltage, 0.0),
    };
    let parts = vec![
        (api_name(Key::Inductance), paper.inductance),
        (api_name(Key::Capacitance), paper.capacitance),
        (api_name(Key::Resistance), paper.resistance),
        (api_name(Key::TurnOn), turn_on),
        (api_name(Key::DiodeResistance), rd),
    ];
    let mut rows = vec![PresetRow {
        id: "paper".into(),
        label: "the paper's circuit (L = 11.5 mH, C = 20 nF, R = 68 Ω, U_t = 0.7 V, R_D = 3 Ω)"
            .into(),
        system: "circuit",
        values: parts.clone(),
        paper: true,
    }];
    for (panel, w, beta) in FIG3_POINTS {
        let mut values = parts.clone();
        values.push((api_name(Key::W), w));
        values.push((api_name(Key::Beta), beta));
        rows.push(PresetRow {
            id: format!("fig3-{panel}"),
            label: format!("paper, Fig. 3 ({panel}): Ω/ω0 = {w}, β = {beta}"),
            system: "circuit",
            values,
            paper: true,
        });
    }
    // A mass on a spring with dry friction, ζ = 0.94/(2·√(200·0.5)) = 0.047 as the paper's.
    rows.push(PresetRow {
        id: "mechanics".into(),
        label: "a mass on a spring with dry friction (m = 0.5 kg, k = 200 N/m, γ = 0.94 N·s/m, \
                F0 = 1 N)"
            .into(),
        system: "mechanics",
        values: vec![
            (api_name(Key::Mass), 0.5),
            (api_name(Key::Stiffness), 200.0),
            (api_name(Key::Damping), 0.94),
            (api_name(Key::Friction), 1.0),
            (api_name(Key::MuS), 1.0),
            (api_name(Key::W), 0.95),
            (api_name(Key::Beta), 2.14),
        ],
        paper: false,
    });
    let d = DiodePair::one_n4148();
    serde_json::json!({
        "presets": rows.iter().map(|r| serde_json::json!({
            "id": r.id,
            "label": r.label,
            "system": r.system,
            "paper": r.paper,
            "values": r.values.iter().map(|(k, v)| (k.clone(), serde_json::json!(v)))
                .collect::<serde_json::Map<_, _>>(),
        })).collect::<Vec<_>>(),
        "shockley": {
            api_name(Key::SaturationCurrent): d.saturation_current,
            api_name(Key::Emission): d.emission,
            api_name(Key::SeriesResistance): d.series_resistance,
            api_name(Key::Temperature): d.temperature,
        },
        "caps": {
            "steady_samples": caps::STEADY_SAMPLES,
            "max_period": caps::MAX_PERIOD,
            "max_periods": caps::MAX_PERIODS,
            "simulate_periods": caps::SIMULATE_PERIODS,
            "simulate_samples": caps::SIMULATE_SAMPLES,
            "simulate_total": caps::SIMULATE_TOTAL,
            "sweep_steps": caps::SWEEP_STEPS,
            "map_side": caps::MAP_SIDE,
            "map_points": caps::MAP_POINTS,
        },
    })
}
