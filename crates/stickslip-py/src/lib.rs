//! `stickslip._core`: the compiled part of the `stickslip` Python package, a thin layer over
//! the `stickslip` library.
//!
//! Every function here turns its Python arguments into library types, releases the GIL, calls
//! the library, and hands back numpy arrays (built from the library's vectors without a copy,
//! or with one pass from rows to columns) or the library's serialised reports. The Python
//! modules of the package (`stickslip/__init__.py`, `stickslip/dask.py`) give them their
//! documented signatures and result objects. Library errors become `ValueError` with the
//! library's one-line message; a long computation stopped by Ctrl-C raises
//! `KeyboardInterrupt` (see the `runner` module).

mod compute;
mod curve;
mod dynamics;
mod experiment;
mod fit;
mod options;
mod runner;

use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use pyo3::types::PyDict;
use stickslip::names::NameError;
use stickslip::options::Spelling;
use stickslip::report::{BasinsTable, BifurcationRow, BranchTable, MapRow, SweepRow};
use stickslip::scan::SweepLeg;
use stickslip::steady::MotionClass;
use stickslip::Parameter;

/// The library's error as a Python `ValueError` with its one-line message, options named by
/// their Python keywords (`invalid max_period = 65: must be from 1 to 64`).
pub(crate) fn error(e: stickslip::Error) -> PyErr {
    PyValueError::new_err(e.render(Spelling::Python))
}

/// The names of `names` as a Python message lists them: `'up', 'down' or 'both'`.
pub(crate) fn either<'a>(names: impl IntoIterator<Item = &'a str>) -> String {
    let quoted: Vec<String> = names.into_iter().map(|n| format!("'{n}'")).collect();
    match quoted.split_last() {
        Some((last, rest)) if !rest.is_empty() => format!("{} or {last}", rest.join(", ")),
        _ => quoted.concat(),
    }
}

/// `text` as a value of the library's enum `T` (its `FromStr`); a name it does not know is a
/// `ValueError` naming the argument `what` as Python calls it: `invalid direction
/// 'sideways': must be 'up', 'down' or 'both'`.
pub(crate) fn named<T: std::str::FromStr<Err = NameError>>(what: &str, text: &str) -> PyResult<T> {
    text.parse().map_err(|e: NameError| {
        PyValueError::new_err(format!(
            "invalid {what} '{}': must be {}",
            e.text,
            either(e.allowed.iter().copied())
        ))
    })
}

/// The parameter that sweeps and maps vary, by its Python name (`mu_s`; the library also
/// takes the flag's `mu-s`).
pub(crate) fn parameter(name: &str) -> PyResult<Parameter> {
    name.parse().map_err(|e: NameError| {
        PyValueError::new_err(format!(
            "unknown parameter '{}': must be {}",
            e.text,
            either(Parameter::ALL.iter().map(|p| p.label()))
        ))
    })
}

/// A serialisable library value as Python objects, through its JSON (the same text the
/// command-line tool prints with `--json`).
pub(crate) fn json_value<'py>(
    py: Python<'py>,
    value: &impl serde::Serialize,
) -> PyResult<Bound<'py, PyAny>> {
    let text = serde_json::to_string(value)
        .map_err(|e| PyValueError::new_err(format!("cannot serialise the result: {e}")))?;
    py.import("json")?.call_method1("loads", (text,))
}

/// The compiled core of the `stickslip` package. Use the package (`import stickslip`), whose
/// functions document their arguments; this module's names may change.
#[pymodule]
fn _core(m: &Bound<'_, PyModule>) -> PyResult<()> {
    let py = m.py();
    m.add("__version__", env!("CARGO_PKG_VERSION"))?;
    m.add(
        "MOTION_CLASSES",
        MotionClass::ALL.map(MotionClass::label).to_vec(),
    )?;
    let names = PyDict::new(py);
    for p in Parameter::ALL {
        names.set_item(p.label(), p.long_name())?;
    }
    m.add("PARAMETER_LONG_NAMES", names)?;
    m.add(
        "EVENT_KINDS",
        compute::EVENT_KINDS.map(|k| k.label()).to_vec(),
    )?;
    let phases = PyDict::new(py);
    for p in compute::PHASES {
        phases.set_item(compute::phase_code(p), p.label())?;
    }
    m.add("PHASE_LABELS", phases)?;
    m.add("SWEEP_LEGS", SweepLeg::ALL.map(|l| l.to_string()).to_vec())?;
    // The library's report tables: their CSV columns and JSON fields, for the result types to
    // build their columns and dicts from (`Table::columns()`).
    m.add("MAP_COLUMNS", MapRow::COLUMNS.to_vec())?;
    m.add("MAP_EXPONENT_COLUMNS", MapRow::EXPONENT_COLUMNS.to_vec())?;
    m.add("SWEEP_COLUMNS", SweepRow::COLUMNS.to_vec())?;
    m.add("SWEEP_FIELDS", SweepRow::FIELDS.to_vec())?;
    m.add("BIFURCATION_COLUMNS", BifurcationRow::COLUMNS.to_vec())?;
    m.add("BIFURCATION_FIELDS", BifurcationRow::FIELDS.to_vec())?;
    m.add("BASIN_COLUMNS", BasinsTable::COLUMNS.to_vec())?;
    m.add("BRANCH_COLUMNS", BranchTable::COLUMNS.to_vec())?;
    m.add("KEYS", experiment::key_table(py)?)?;
    m.add("OPTIONS", options::table(py)?)?;
    m.add_function(wrap_pyfunction!(options::check_option, m)?)?;
    m.add_function(wrap_pyfunction!(options::steady_option_kinds, m)?)?;
    m.add_class::<experiment::PyExperiment>()?;
    m.add_function(wrap_pyfunction!(experiment::with_diode, m)?)?;
    m.add_function(wrap_pyfunction!(compute::simulate, m)?)?;
    m.add_function(wrap_pyfunction!(compute::steady, m)?)?;
    m.add_function(wrap_pyfunction!(compute::theory, m)?)?;
    m.add_function(wrap_pyfunction!(compute::boundary, m)?)?;
    m.add_function(wrap_pyfunction!(compute::sweep, m)?)?;
    m.add_function(wrap_pyfunction!(compute::grid, m)?)?;
    m.add_function(wrap_pyfunction!(compute::orbit, m)?)?;
    m.add_function(wrap_pyfunction!(compute::lyapunov, m)?)?;
    m.add("ATTRACTOR_KINDS", dynamics::attractor_kinds())?;
    m.add_function(wrap_pyfunction!(dynamics::bifurcation, m)?)?;
    m.add_function(wrap_pyfunction!(dynamics::basins, m)?)?;
    m.add_function(wrap_pyfunction!(dynamics::continuation, m)?)?;
    m.add_function(wrap_pyfunction!(curve::curve, m)?)?;
    m.add_function(wrap_pyfunction!(fit::read_scope, m)?)?;
    m.add_function(wrap_pyfunction!(fit::read_amplitudes, m)?)?;
    m.add_function(wrap_pyfunction!(fit::fit, m)?)?;
    Ok(())
}
