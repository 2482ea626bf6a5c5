//! Bifurcation diagrams, basins of attraction and continuation of periodic orbits: the
//! computations behind `stickslip.bifurcation`, `stickslip.basins` and
//! `stickslip.continuation`. Each takes the library's types from its arguments, runs without
//! the GIL (stoppable by Ctrl-C) and returns numpy arrays in a dict, with the library's
//! report where the command-line tool prints one (`--json`).

use crate::experiment::PyExperiment;
use crate::options::{count, natural};
use crate::runner::run;
use crate::{error, json_value, named, parameter};
use numpy::{PyArray1, PyReadonlyArray1};
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use pyo3::types::PyDict;
use stickslip::attractor::{AttractorKind, RecordOptions};
use stickslip::basins::{BasinMethod, BasinOptions, BasinReport, Basins};
use stickslip::bifurcation::{Bifurcation, BifurcationOptions};
use stickslip::continuation::{
    continue_orbit_of, settled_orbit, BranchReport, ContinuationOptions,
};
use stickslip::options::OptionKey;
use stickslip::scan::{Axis, ParameterRange, SweepDirection, SweepLeg};

/// Set `name` of `out` to a numpy array that takes over `data` (no copy).
fn put<T: numpy::Element>(out: &Bound<'_, PyDict>, name: &str, data: Vec<T>) -> PyResult<()> {
    out.set_item(name, PyArray1::from_vec(out.py(), data))
}

/// The kind's code: its index in `AttractorKind::ALL` (`ATTRACTOR_KINDS`).
pub(crate) fn kind_code(kind: AttractorKind) -> i8 {
    AttractorKind::ALL
        .iter()
        .position(|&k| k == kind)
        .expect("every kind is in ALL") as i8
}

/// A bifurcation diagram; see `stickslip.bifurcation`.
#[pyfunction]
#[pyo3(signature = (experiment, over, values, direction, points, transient, first_transient, max_period, progress=None))]
#[allow(clippy::too_many_arguments)]
pub fn bifurcation<'py>(
    py: Python<'py>,
    experiment: PyRef<'py, PyExperiment>,
    over: &str,
    values: PyReadonlyArray1<'py, f64>,
    direction: &str,
    points: i64,
    transient: i64,
    first_transient: i64,
    max_period: i64,
    progress: Option<Bound<'py, PyAny>>,
) -> PyResult<Bound<'py, PyDict>> {
    let e = experiment.experiment().clone();
    let values = values
        .as_slice()
        .map(<[f64]>::to_vec)
        .map_err(|_| PyValueError::new_err("values must be a contiguous, aligned float64 array"))?;
    let axis = Axis::new(parameter(over)?, values).map_err(error)?;
    let options = BifurcationOptions {
        record: RecordOptions {
            transient_periods: count(OptionKey::BifurcationTransient, transient)?,
            points: count(OptionKey::Points, points)?,
            max_period: count(OptionKey::BifurcationMaxPeriod, max_period)?,
            ..RecordOptions::default()
        },
        first_transient_periods: count(OptionKey::FirstTransient, first_transient)?,
    };
    let diagram = Bifurcation::new(&e, axis)
        .map_err(error)?
        .direction(named::<SweepDirection>("direction", direction)?)
        .options(options)
        .map_err(error)?;
    let steps = run(py, progress.as_ref(), |monitor| diagram.run(monitor))?;
    let n = options.record.points;
    let out = PyDict::new(py);
    put(&out, "value", steps.iter().map(|s| s.value).collect())?;
    put(
        &out,
        "leg",
        steps
            .iter()
            .map(|s| SweepLeg::ALL.iter().position(|&l| l == s.leg).unwrap_or(0) as i8)
            .collect::<Vec<i8>>(),
    )?;
    let mut y = Vec::with_capacity(steps.len() * n);
    let mut v = Vec::with_capacity(steps.len() * n);
    for s in &steps {
        y.extend(s.record.strobes.iter().map(|x| x.y));
        v.extend(s.record.strobes.iter().map(|x| x.v));
    }
    put(&out, "y", y)?;
    put(&out, "v", v)?;
    put(
        &out,
        "exponent",
        steps.iter().map(|s| s.record.exponent).collect(),
    )?;
    put(
        &out,
        "exponent_error",
        steps.iter().map(|s| s.record.exponent_error).collect(),
    )?;
    put(
        &out,
        "kind",
        steps
            .iter()
            .map(|s| kind_code(s.record.kind))
            .collect::<Vec<i8>>(),
    )?;
    put(
        &out,
        "period",
        steps
            .iter()
            .map(|s| s.record.period.map_or(-1, |p| p as i16))
            .collect::<Vec<i16>>(),
    )?;
    put(
        &out,
        "events",
        steps
            .iter()
            .map(|s| s.record.events as i64)
            .collect::<Vec<i64>>(),
    )?;
    put(
        &out,
        "stops",
        steps
            .iter()
            .map(|s| s.record.stops as i64)
            .collect::<Vec<i64>>(),
    )?;
    out.set_item("points", n)?;
    Ok(out)
}

/// A basin map; see `stickslip.basins`.
#[pyfunction]
#[pyo3(signature = (experiment, y0, v0, steps, phase, max_periods, max_period, lyapunov_periods, threads=None, progress=None, method="recurrence"))]
#[allow(clippy::too_many_arguments)]
pub fn basins<'py>(
    py: Python<'py>,
    experiment: PyRef<'py, PyExperiment>,
    y0: (f64, f64),
    v0: (f64, f64),
    steps: (i64, i64),
    phase: Option<f64>,
    max_periods: i64,
    max_period: i64,
    lyapunov_periods: i64,
    threads: Option<usize>,
    progress: Option<Bound<'py, PyAny>>,
    method: &str,
) -> PyResult<Bound<'py, PyDict>> {
    let method: BasinMethod = named("method", method)?;
    let mut e = experiment.experiment().clone();
    if let Some(phase) = phase {
        e = e.with_phi(phase).map_err(error)?;
    }
    let y0 = ParameterRange::new("y0", y0.0, y0.1, natural(OptionKey::BasinSteps, steps.0)?)
        .map_err(error)?;
    let v0 = ParameterRange::new("v0", v0.0, v0.1, natural(OptionKey::BasinSteps, steps.1)?)
        .map_err(error)?;
    let options = BasinOptions {
        max_periods: count(OptionKey::BasinMaxPeriods, max_periods)?,
        max_period: count(OptionKey::BasinMaxPeriod, max_period)?,
        method,
        ..BasinOptions::default()
    }
    .with_lyapunov_periods(count(OptionKey::BasinLyapunovPeriods, lyapunov_periods)?);
    let mut basins = Basins::new(&e, &y0, &v0)
        .map_err(error)?
        .options(options)
        .map_err(error)?;
    if let Some(n) = threads {
        basins = basins.threads(n).map_err(error)?;
    }
    let map = run(py, progress.as_ref(), |monitor| basins.run(monitor))?;
    let out = PyDict::new(py);
    out.set_item("report", json_value(py, &BasinReport::from(&map))?)?;
    let attractor = |k: Option<usize>| k.map(|i| &map.attractors[i]);
    put(
        &out,
        "attractor",
        map.cells
            .iter()
            .map(|&k| k.map_or(-1, |i| i as i32))
            .collect::<Vec<i32>>(),
    )?;
    put(
        &out,
        "kind",
        map.cells
            .iter()
            .map(|&k| kind_code(attractor(k).map_or(AttractorKind::Undecided, |a| a.kind)))
            .collect::<Vec<i8>>(),
    )?;
    put(
        &out,
        "period",
        map.cells
            .iter()
            .map(|&k| attractor(k).and_then(|a| a.period).map_or(-1, |p| p as i16))
            .collect::<Vec<i16>>(),
    )?;
    out.set_item("shape", (map.y0.len(), map.v0.len()))?;
    put(&out, "y0", map.y0)?;
    put(&out, "v0", map.v0)?;
    Ok(out)
}

/// A branch of periodic orbits; see `stickslip.continuation`.
#[pyfunction]
#[pyo3(signature = (experiment, over, start, to, max_points, max_step, progress=None))]
#[allow(clippy::too_many_arguments)]
pub fn continuation<'py>(
    py: Python<'py>,
    experiment: PyRef<'py, PyExperiment>,
    over: &str,
    start: f64,
    to: f64,
    max_points: i64,
    max_step: f64,
    progress: Option<Bound<'py, PyAny>>,
) -> PyResult<Bound<'py, PyDict>> {
    let parameter = parameter(over)?;
    let e = experiment
        .experiment()
        .clone()
        .with_parameter(parameter, start)
        .map_err(error)?;
    let options = ContinuationOptions {
        max_points: count(OptionKey::MaxPoints, max_points)?,
        ..ContinuationOptions::default()
    }
    .with_max_step(max_step)
    .validate()
    .map_err(error)?;
    stickslip::continuation::check_parameter(&e, parameter).map_err(error)?;
    let computed = run(py, progress.as_ref(), |monitor| {
        let (params, orbit) = settled_orbit(&e)?;
        if orbit.is_rest() {
            return Ok(None);
        }
        let dynamics = e.dynamics()?;
        let branch = continue_orbit_of(
            dynamics.as_ref(),
            &params,
            parameter,
            &orbit,
            to,
            &options,
            monitor,
        )?;
        Ok(Some((branch, orbit)))
    })?;
    // As the command-line tool says it: rest is no branch, and what to do instead.
    let Some((branch, start_orbit)) = computed else {
        let initial = e.initial();
        return Err(PyValueError::new_err(format!(
            "from y0 = {}, v0 = {} the motion comes to rest at {} = {start}: nothing to \
             continue; start from a moving state (experiment.replace(y0=..., v0=...)) or at \
             another start",
            initial.y,
            initial.v,
            parameter.label()
        )));
    };
    let out = PyDict::new(py);
    out.set_item("report", json_value(py, &BranchReport::from(&branch))?)?;
    let points = &branch.points;
    let column = |f: &dyn Fn(&stickslip::continuation::BranchPoint) -> f64| -> Vec<f64> {
        points.iter().map(f).collect()
    };
    put(&out, "value", column(&|p| p.value))?;
    put(&out, "y", column(&|p| p.orbit.state.y))?;
    put(&out, "v", column(&|p| p.orbit.state.v))?;
    put(&out, "amplitude", column(&|p| p.amplitude()))?;
    put(
        &out,
        "period",
        points
            .iter()
            .map(|p| p.orbit.period as i64)
            .collect::<Vec<i64>>(),
    )?;
    put(&out, "stops_per_period", column(&|p| p.stops_per_period()))?;
    put(
        &out,
        "turns",
        points.iter().map(|p| p.turns as i64).collect::<Vec<i64>>(),
    )?;
    put(&out, "mu1_re", column(&|p| p.orbit.multipliers[0].re))?;
    put(&out, "mu1_im", column(&|p| p.orbit.multipliers[0].im))?;
    put(&out, "mu2_re", column(&|p| p.orbit.multipliers[1].re))?;
    put(&out, "mu2_im", column(&|p| p.orbit.multipliers[1].im))?;
    put(
        &out,
        "stable",
        points.iter().map(|p| p.stable()).collect::<Vec<bool>>(),
    )?;
    put(&out, "arclength", column(&|p| p.arclength))?;
    out.set_item(
        "start",
        (
            start_orbit.state.y,
            start_orbit.state.v,
            start_orbit.period,
            start_orbit.stops.len(),
        ),
    )?;
    Ok(out)
}

/// The label of every attractor kind, in the order of their codes.
pub(crate) fn attractor_kinds() -> Vec<&'static str> {
    AttractorKind::ALL.map(AttractorKind::label).to_vec()
}
