//! Curves of special points in two parameters: the computation behind `stickslip.curve`. It
//! takes the library's types from its arguments, runs without the GIL (stoppable by Ctrl-C)
//! and returns the library's curve table as numpy arrays (named and typed by
//! [`Columns`]: the CSV's columns and numbers) with the summary that `stickslip curve --json`
//! prints.

use crate::experiment::PyExperiment;
use crate::options::count;
use crate::runner::run_with;
use crate::{error, json_value, named, parameter};
use numpy::PyArray1;
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use pyo3::types::PyDict;
use stickslip::continuation::{
    check_spec, curve as follow, ContinuationOptions, CurveReport, CurveSpec,
};
use stickslip::options::OptionKey;
use stickslip::report::{Column, Columns, CurveTable};

/// A curve of special points; see `stickslip.curve`.
#[pyfunction]
#[pyo3(signature = (experiment, follow_kind, vary, vary_to, over, start, to, max_points, max_step, progress=None))]
#[allow(clippy::too_many_arguments)]
pub fn curve<'py>(
    py: Python<'py>,
    experiment: PyRef<'py, PyExperiment>,
    follow_kind: &str,
    vary: &str,
    vary_to: f64,
    over: &str,
    start: f64,
    to: f64,
    max_points: i64,
    max_step: f64,
    progress: Option<Bound<'py, PyAny>>,
) -> PyResult<Bound<'py, PyDict>> {
    let spec = CurveSpec {
        follow: named("follow", follow_kind)?,
        vary: parameter(vary)?,
        vary_to,
        over: parameter(over)?,
        from: start,
        to,
    };
    check_spec(&spec).map_err(error)?;
    let options = ContinuationOptions {
        max_points: count(OptionKey::TwoParameterMaxPoints, max_points)?,
        ..ContinuationOptions::default()
    }
    .with_max_step(
        OptionKey::TwoParameterMaxStep
            .check(max_step)
            .map_err(error)?,
    );
    let e = experiment.experiment().clone();
    let computed = run_with(py, progress.as_ref(), |monitor, cancel| {
        follow(&e.with_cancel(cancel.clone()), &spec, &options, monitor)
    })?;
    // No special point of the kind: the command-line tool's one line.
    let c = computed.map_err(|no| PyValueError::new_err(no.to_string()))?;
    let out = PyDict::new(py);
    out.set_item("report", json_value(py, &CurveReport::from(&c))?)?;
    let columns = PyDict::new(py);
    for (name, column) in Columns::of(&CurveTable { curve: &c }).columns {
        match column {
            Column::Integer(v) => columns.set_item(name, PyArray1::from_vec(py, v))?,
            Column::Number(v) => columns.set_item(name, PyArray1::from_vec(py, v))?,
            Column::Text(v) => columns.set_item(name, v)?,
        }
    }
    out.set_item("columns", columns)?;
    Ok(out)
}
