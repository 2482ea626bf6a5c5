//! The computations: simulate, steady, theory, boundary, sweep, grid, orbit and lyapunov.
//! Each takes the library's types from its arguments, runs without the GIL and returns numpy
//! arrays (in a dict, for the Python layer to wrap) or the library's serialised report.

use crate::experiment::PyExperiment;
use crate::options::{self, count};
use crate::runner::{run, run_with};
use crate::{error, json_value, named, parameter};
use numpy::{PyArray1, PyReadonlyArray1};
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use pyo3::types::PyDict;
use std::time::Instant;
use stickslip::options::OptionKey;
use stickslip::report::{SweepReport, TrajectoryReport};
use stickslip::scan::{Axis, Grid, Sweep, SweepDirection};
use stickslip::stability::{LyapunovOptions, LyapunovReport, NewtonOptions, OrbitReport};
use stickslip::steady::{MotionClass, SteadyReport};
use stickslip::theory::curves::{theory_value, Theory, TheoryQuantity};
use stickslip::theory::TheoryReport;
use stickslip::{DiodeModel, Error, EventKind, Experiment, Params, Phase, Unsupported};

/// The values of a contiguous, aligned float64 array (the Python layer makes them so).
fn values(name: &str, array: &PyReadonlyArray1<'_, f64>) -> PyResult<Vec<f64>> {
    array.as_slice().map(<[f64]>::to_vec).map_err(|_| {
        PyValueError::new_err(format!(
            "{name} must be a contiguous, aligned float64 array (np.require(a, np.float64, ['C', 'A']))"
        ))
    })
}

/// The motion class's code: its index in `MotionClass::ALL` (`MOTION_CLASSES`).
fn class_code(class: MotionClass) -> i8 {
    MotionClass::ALL
        .iter()
        .position(|&c| c == class)
        .expect("every class is in ALL") as i8
}

/// The period's code: the period in drive periods, -1 when none was found.
fn period_code(period: Option<usize>) -> i16 {
    period.map_or(-1, |p| p as i16)
}

/// The event kinds in the order of their codes (`EVENT_KINDS`).
pub(crate) const EVENT_KINDS: [EventKind; 3] = [EventKind::Turn, EventKind::Stick, EventKind::Slip];
/// The phases of the motion (`PHASE_LABELS`, by their codes, [`phase_code`]).
pub(crate) const PHASES: [Phase; 3] = [Phase::SlipPositive, Phase::SlipNegative, Phase::Stick];

/// The event kind's code: its index in [`EVENT_KINDS`].
fn event_code(kind: EventKind) -> i8 {
    EVENT_KINDS
        .iter()
        .position(|&k| k == kind)
        .expect("every kind is in EVENT_KINDS") as i8
}

/// The phase's code: the sliding direction, +1, -1 or 0 when stuck.
pub(crate) fn phase_code(phase: Phase) -> i8 {
    phase.sign() as i8
}

/// Set `name` of `out` to a numpy array that takes over `data` (no copy).
fn put<T: numpy::Element>(out: &Bound<'_, PyDict>, name: &str, data: Vec<T>) -> PyResult<()> {
    out.set_item(name, PyArray1::from_vec(out.py(), data))
}

/// One run of an experiment from its initial state; see `stickslip.simulate`.
#[pyfunction]
#[pyo3(signature = (experiment, periods, samples_per_period, progress=None))]
pub fn simulate<'py>(
    py: Python<'py>,
    experiment: PyRef<'py, PyExperiment>,
    periods: f64,
    samples_per_period: i64,
    progress: Option<Bound<'py, PyAny>>,
) -> PyResult<Bound<'py, PyDict>> {
    let samples = count(OptionKey::SimulateSamples, samples_per_period)?;
    let e: Experiment = experiment.experiment().clone();
    let (report, computed) = run(py, progress.as_ref(), |monitor| {
        let started = Instant::now();
        let report = e
            .trajectory(periods, samples)?
            .monitor(monitor)
            .collect_report()?;
        Ok((report, started.elapsed().as_secs_f64()))
    })?;
    let converting = Instant::now();
    let TrajectoryReport {
        columns,
        tau,
        y,
        v,
        drive,
        phase,
        physical,
        events,
        ..
    } = report;
    let out = PyDict::new(py);
    put(&out, "event_tau", events.iter().map(|e| e.tau).collect())?;
    put(&out, "event_y", events.iter().map(|e| e.y).collect())?;
    put(
        &out,
        "event_kind",
        events.iter().map(|e| event_code(e.kind)).collect(),
    )?;
    put(&out, "tau", tau)?;
    put(&out, "y", y)?;
    put(&out, "v", v)?;
    put(&out, "drive", drive)?;
    put::<i8>(
        &out,
        "phase",
        phase.iter().map(|&p| phase_code(p)).collect(),
    )?;
    let names = pyo3::types::PyList::empty(py);
    if let (Some(units), Some(data)) = (columns.units, physical) {
        for (name, column) in units.columns().into_iter().zip(data) {
            put(&out, name, column)?;
            names.append(name)?;
        }
    }
    out.set_item("physical", names)?;
    // For the benchmark of returning a trajectory (bench/python): seconds spent in the
    // library's run and in handing its result to numpy.
    out.set_item("_seconds", (computed, converting.elapsed().as_secs_f64()))?;
    Ok(out)
}

/// The steady state reached from the initial state; see `stickslip.steady`.
#[pyfunction]
#[pyo3(signature = (experiment, options=None))]
pub fn steady<'py>(
    py: Python<'py>,
    experiment: PyRef<'py, PyExperiment>,
    options: Option<&Bound<'py, PyDict>>,
) -> PyResult<Bound<'py, PyDict>> {
    let e = experiment.experiment().clone();
    let options = options::steady(e.steady_options(), options, true)?;
    e.params().map_err(error)?;
    let s = run_with(py, None, |_, cancel| {
        e.with_cancel(cancel.clone()).steady_with(&options)
    })?;
    let out = PyDict::new(py);
    out.set_item("report", json_value(py, &SteadyReport::from(&s))?)?;
    let (drive, y): (Vec<f64>, Vec<f64>) = s.xy().into_iter().unzip();
    put(&out, "xy_drive", drive)?;
    put(&out, "xy_y", y)?;
    put(&out, "trace_tau", s.trace.iter().map(|p| p.tau).collect())?;
    put(&out, "trace_y", s.trace.iter().map(|p| p.y).collect())?;
    put(&out, "trace_v", s.trace.iter().map(|p| p.v).collect())?;
    put(
        &out,
        "trace_phase",
        s.trace
            .iter()
            .map(|p| phase_code(p.phase))
            .collect::<Vec<i8>>(),
    )?;
    put(&out, "event_tau", s.events.iter().map(|e| e.tau).collect())?;
    put(&out, "event_y", s.events.iter().map(|e| e.y).collect())?;
    put(
        &out,
        "event_kind",
        s.events
            .iter()
            .map(|e| event_code(e.kind))
            .collect::<Vec<i8>>(),
    )?;
    out.set_item("start", s.start)?;
    out.set_item("recorded_periods", s.recorded_periods)?;
    out.set_item("y_min", s.y_min)?;
    out.set_item("y_max", s.y_max)?;
    out.set_item("longest_stop", s.longest_stop)?;
    out.set_item("stops", s.stops)?;
    Ok(out)
}

/// The experiment, which must use the piecewise-linear law.
fn pwl(experiment: &Experiment) -> PyResult<()> {
    if experiment.diode_model() == DiodeModel::Shockley {
        return Err(error(Error::Unsupported(Unsupported::TheoryNeedsPwl)));
    }
    Ok(())
}

/// Both theories at the experiment's point; see `stickslip.theory`.
#[pyfunction]
pub fn theory<'py>(
    py: Python<'py>,
    experiment: PyRef<'py, PyExperiment>,
) -> PyResult<Bound<'py, PyAny>> {
    let e = experiment.experiment().clone();
    pwl(&e)?;
    let params = e.params().map_err(error)?;
    let report = py.detach(|| TheoryReport::new(&params)).map_err(error)?;
    json_value(py, &report)
}

/// Two float64 arrays.
type Pair<'py> = (Bound<'py, PyArray1<f64>>, Bound<'py, PyArray1<f64>>);

/// The paper's and the exact stick-slip boundary β_c at each (ζ, w, μs) of three arrays of
/// one length; NaN where none exists. See `stickslip.boundary`.
#[pyfunction]
pub fn boundary<'py>(
    py: Python<'py>,
    zeta: PyReadonlyArray1<'py, f64>,
    w: PyReadonlyArray1<'py, f64>,
    mu_s: PyReadonlyArray1<'py, f64>,
) -> PyResult<Pair<'py>> {
    let (zeta, w, mu_s) = (
        values("zeta", &zeta)?,
        values("w", &w)?,
        values("mu_s", &mu_s)?,
    );
    if zeta.len() != w.len() || mu_s.len() != w.len() {
        return Err(PyValueError::new_err(
            "zeta, w and mu_s must have one length",
        ));
    }
    let (paper, exact) = py
        .detach(|| -> stickslip::Result<(Vec<f64>, Vec<f64>)> {
            let mut paper = Vec::with_capacity(w.len());
            let mut exact = Vec::with_capacity(w.len());
            for k in 0..w.len() {
                let p = Params::new(zeta[k], w[k], 0.0)?.with_mu_s(mu_s[k])?;
                let at = |t| theory_value(t, TheoryQuantity::Boundary, &p).unwrap_or(f64::NAN);
                paper.push(at(Theory::Paper));
                exact.push(at(Theory::Exact));
            }
            Ok((paper, exact))
        })
        .map_err(error)?;
    Ok((PyArray1::from_vec(py, paper), PyArray1::from_vec(py, exact)))
}

/// A sweep with continuation; see `stickslip.sweep`.
#[pyfunction]
#[pyo3(signature = (experiment, over, values, direction, options=None, progress=None))]
pub fn sweep<'py>(
    py: Python<'py>,
    experiment: PyRef<'py, PyExperiment>,
    over: &str,
    values: PyReadonlyArray1<'py, f64>,
    direction: &str,
    options: Option<&Bound<'py, PyDict>>,
    progress: Option<Bound<'py, PyAny>>,
) -> PyResult<Bound<'py, PyDict>> {
    let e = experiment.experiment().clone();
    let direction: SweepDirection = named("direction", direction)?;
    let over = parameter(over)?;
    let axis = Axis::new(over, self::values("values", &values)?).map_err(error)?;
    let options = options::steady(e.steady_options(), options, true)?;
    let sweep = Sweep::new(&e, axis)
        .map_err(error)?
        .direction(direction)
        .options(options)
        .map_err(error)?;
    let points = run(py, progress.as_ref(), |monitor| sweep.run(monitor))?;
    let h = options.harmonics;
    let out = PyDict::new(py);
    let report = SweepReport::new(&e, over, direction, &points);
    out.set_item("report", json_value(py, &report)?)?;
    let column = |f: &dyn Fn(&stickslip::scan::SweepPoint) -> f64| -> Vec<f64> {
        points.iter().map(f).collect()
    };
    put(&out, "value", column(&|p| p.value))?;
    put(&out, "w", column(&|p| p.params.w))?;
    put(&out, "beta", column(&|p| p.params.beta))?;
    put(&out, "zeta", column(&|p| p.params.zeta))?;
    put(&out, "mu_s", column(&|p| p.params.mu_s))?;
    put(&out, "gain", column(&|p| p.steady.gain))?;
    put(&out, "peak", column(&|p| p.steady.peak))?;
    put(
        &out,
        "stops_per_cycle",
        column(&|p| p.steady.stops_per_period),
    )?;
    put(
        &out,
        "phase_lag",
        column(&|p| p.steady.phase_lag().unwrap_or(f64::NAN)),
    )?;
    put(
        &out,
        "motion",
        points
            .iter()
            .map(|p| class_code(p.steady.class))
            .collect::<Vec<i8>>(),
    )?;
    put(
        &out,
        "period",
        points
            .iter()
            .map(|p| period_code(p.steady.period))
            .collect::<Vec<i16>>(),
    )?;
    put(
        &out,
        "symmetric",
        points
            .iter()
            .map(|p| p.steady.symmetric)
            .collect::<Vec<bool>>(),
    )?;
    put(
        &out,
        "periods_to_settle",
        points
            .iter()
            .map(|p| p.steady.periods_to_settle as i64)
            .collect::<Vec<i64>>(),
    )?;
    let harmonics = points
        .iter()
        .flat_map(|p| (1..=h).map(|k| p.steady.harmonic(k).unwrap_or(f64::NAN)))
        .collect();
    put(&out, "harmonics", harmonics)?;
    out.set_item("harmonic_count", h)?;
    Ok(out)
}

/// A block of a grid of two parameters, every point from the initial state; see
/// `stickslip.phase_diagram` and `stickslip.dask`. `block` = (row start, row end, column
/// start, column end), the whole grid by default; `fixed` = values of other parameters set
/// before the grid is built (the outer parameters of a stack of maps); `threads`: a pool of its own of that many threads (default:
/// rayon's global pool, one thread per core).
#[pyfunction]
#[pyo3(signature = (experiment, first, first_values, second, second_values, options=None, threads=None, block=None, fixed=None, progress=None, lyapunov=false))]
pub fn grid<'py>(
    py: Python<'py>,
    experiment: PyRef<'py, PyExperiment>,
    first: &str,
    first_values: PyReadonlyArray1<'py, f64>,
    second: &str,
    second_values: PyReadonlyArray1<'py, f64>,
    options: Option<&Bound<'py, PyDict>>,
    threads: Option<usize>,
    block: Option<(usize, usize, usize, usize)>,
    fixed: Option<Vec<(String, f64)>>,
    progress: Option<Bound<'py, PyAny>>,
    lyapunov: bool,
) -> PyResult<Bound<'py, PyDict>> {
    let mut e = experiment.experiment().clone();
    for (name, value) in fixed.unwrap_or_default() {
        e = e.with_parameter(parameter(&name)?, value).map_err(error)?;
    }
    let first = Axis::new(parameter(first)?, values(first, &first_values)?).map_err(error)?;
    let second = Axis::new(parameter(second)?, values(second, &second_values)?).map_err(error)?;
    let (rows, cols) = (first.len(), second.len());
    let options = options::steady(e.steady_options().with_spectrum(false), options, false)?;
    let mut grid = Grid::new(&e, first, second)
        .map_err(error)?
        .options(options)
        .map_err(error)?;
    if let Some(n) = threads {
        grid = grid.threads(n).map_err(error)?;
    }
    if lyapunov {
        // As the tool's --color lyapunov: the measurement of the steady-state options.
        grid = grid
            .lyapunov(options.lyapunov_for_map().map_err(error)?)
            .map_err(error)?;
    }
    let (r0, r1, c0, c1) = block.unwrap_or((0, rows, 0, cols));
    let points = run(py, progress.as_ref(), |monitor| {
        grid.run_block(r0..r1, c0..c1, monitor)
    })?;
    let out = PyDict::new(py);
    put(
        &out,
        "motion",
        points
            .iter()
            .map(|p| class_code(p.class))
            .collect::<Vec<i8>>(),
    )?;
    put(
        &out,
        "period",
        points
            .iter()
            .map(|p| period_code(p.period))
            .collect::<Vec<i16>>(),
    )?;
    put(
        &out,
        "stops_per_cycle",
        points
            .iter()
            .map(|p| p.stops_per_period)
            .collect::<Vec<f64>>(),
    )?;
    put(
        &out,
        "gain",
        points.iter().map(|p| p.gain).collect::<Vec<f64>>(),
    )?;
    put(
        &out,
        "symmetric",
        points.iter().map(|p| p.symmetric).collect::<Vec<bool>>(),
    )?;
    put(
        &out,
        "periods_to_settle",
        points
            .iter()
            .map(|p| p.periods_to_settle as i64)
            .collect::<Vec<i64>>(),
    )?;
    if lyapunov {
        let (value, error): (Vec<f64>, Vec<f64>) = points
            .iter()
            .map(|p| {
                p.lyapunov
                    .map_or((f64::NAN, f64::NAN), |l| (l.per_tau, l.error_per_tau))
            })
            .unzip();
        put(&out, "lyapunov", value)?;
        put(&out, "lyapunov_error", error)?;
    }
    out.set_item("shape", (r1.saturating_sub(r0), c1.saturating_sub(c0)))?;
    Ok(out)
}

/// A periodic orbit by Newton's method; see `stickslip.orbit`. Returns the dict that
/// `stickslip orbit --json` prints: without a drive on a belt (β = 0, vb ≠ 0) the
/// self-excited cycle or steady sliding (`SelfExcitedOrbit`).
#[pyfunction]
#[pyo3(signature = (experiment, period=None, transient=0, options=None, tolerance=1e-12, max_iterations=30, progress=None))]
pub fn orbit<'py>(
    py: Python<'py>,
    experiment: PyRef<'py, PyExperiment>,
    period: Option<i64>,
    transient: i64,
    options: Option<&Bound<'py, PyDict>>,
    tolerance: f64,
    max_iterations: i64,
    progress: Option<Bound<'py, PyAny>>,
) -> PyResult<Bound<'py, PyAny>> {
    let e = experiment.experiment().clone();
    let period = period
        .map(|p| count(OptionKey::OrbitPeriod, p))
        .transpose()?;
    let transient = count(OptionKey::OrbitTransient, transient)?;
    let steady = options::steady(e.steady_options(), options, false)?;
    let newton = NewtonOptions {
        tolerance,
        max_iterations: count(OptionKey::MaxIterations, max_iterations)?,
        ..NewtonOptions::default()
    }
    .validate()
    .map_err(error)?;
    // No drive: the cycle's own period is found; a period asked for is the library's to
    // refuse (`periodic_orbit`).
    if e.is_self_excited() && period.is_none() {
        let cycle = run_with(py, progress.as_ref(), |_, cancel| {
            e.clone()
                .with_cancel(cancel.clone())
                .self_excited_orbit(&steady)
        })?;
        return json_value(py, &cycle);
    }
    let report = run(py, progress.as_ref(), |monitor| {
        let params = e.params()?;
        let dynamics = e.dynamics()?;
        let orbit = e.periodic_orbit(period, transient, &steady, &newton, monitor)?;
        OrbitReport::of(&orbit, &params, dynamics.as_ref())
    })?;
    json_value(py, &report)
}

/// The Lyapunov exponents from the initial state; see `stickslip.lyapunov`. Returns the dict
/// that `stickslip lyapunov --json` prints.
#[pyfunction]
#[pyo3(signature = (experiment, transient=1000, periods=20000, blocks=20, significance=4.0, progress=None, fixed=false))]
#[allow(clippy::too_many_arguments)]
pub fn lyapunov<'py>(
    py: Python<'py>,
    experiment: PyRef<'py, PyExperiment>,
    transient: i64,
    periods: i64,
    blocks: i64,
    significance: f64,
    progress: Option<Bound<'py, PyAny>>,
    fixed: bool,
) -> PyResult<Bound<'py, PyAny>> {
    let e = experiment.experiment().clone();
    let blocks = count(OptionKey::Blocks, blocks)?;
    let transient_periods = count(OptionKey::LyapunovTransient, transient)?;
    // The measured periods' range starts at the number of blocks: the options' own rule
    // (`validate`: `must be from blocks (20) to 1e9`).
    let options = LyapunovOptions {
        transient_periods,
        periods: OptionKey::LyapunovMeasured.whole(periods).map_err(error)?,
        blocks,
        significance,
        sequential: !fixed,
    }
    .validate()
    .map_err(error)?;
    let report = run(py, progress.as_ref(), |monitor| {
        let params = e.params()?;
        let dynamics = e.dynamics()?;
        let c = e.lyapunov(&options, monitor)?;
        LyapunovReport::of(&c, &options, &params, dynamics.as_ref())
    })?;
    json_value(py, &report)
}
