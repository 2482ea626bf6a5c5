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
mod dynamics;
mod experiment;
mod runner;

use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use pyo3::types::PyDict;
use stickslip::steady::MotionClass;
use stickslip::Parameter;

/// The library's error as a Python `ValueError` with its one-line message.
pub(crate) fn error(e: stickslip::Error) -> PyErr {
    PyValueError::new_err(e.to_string())
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
    m.add_class::<experiment::PyExperiment>()?;
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
    Ok(())
}
