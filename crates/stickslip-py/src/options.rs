//! The options of the computations, from the library's option table ([`OptionKey::table`]):
//! their names and kinds for the Python layer's type checks, and their ranges checked by the
//! library with its words (the Python spelling: `invalid max_period = 65: must be from 1 to
//! 64`).

use crate::{error, json_value};
use pyo3::exceptions::{PyKeyError, PyTypeError, PyValueError};
use pyo3::prelude::*;
use pyo3::types::PyDict;
use stickslip::options::{OptionGroup, OptionKey, OptionKind, Spelling};
use stickslip::stability::LyapunovOptions;
use stickslip::steady::SteadyOptions;
use stickslip::Error;

/// Options of the steady state that belong to its spectrum (steady states and sweeps take
/// them; a map computes no spectrum).
const SPECTRUM: [OptionKey; 2] = [OptionKey::Harmonics, OptionKey::SpectrumSamples];

/// The option table (`_core.OPTIONS`): one dict per option.
pub(crate) fn table(py: Python<'_>) -> PyResult<Bound<'_, PyAny>> {
    json_value(py, &OptionKey::table())
}

/// The group's name as the table writes it (`steady`, `basins`, ...).
fn group_name(group: OptionGroup) -> String {
    serde_json::to_value(group)
        .ok()
        .and_then(|v| v.as_str().map(str::to_string))
        .unwrap_or_default()
}

/// The kind's name as the table writes it (`count`, `number`, `switch`).
fn kind_name(kind: OptionKind) -> String {
    serde_json::to_value(kind)
        .ok()
        .and_then(|v| v.as_str().map(str::to_string))
        .unwrap_or_default()
}

/// The option `name` (Python spelling) of the computation `group`.
fn option(group: &str, name: &str) -> PyResult<OptionKey> {
    OptionKey::ALL
        .iter()
        .copied()
        .find(|k| k.name() == name && group_name(k.group()) == group)
        .ok_or_else(|| PyKeyError::new_err(format!("no option {name} of {group}")))
}

/// Check `value` (a Python int or float) of the option `name` of the computation `group`
/// against the library's table: `ValueError` with the library's message when it is out of
/// range, the value written as Python writes it (every digit of a large int).
#[pyfunction]
pub fn check_option(group: &str, name: &str, value: &Bound<'_, PyAny>) -> PyResult<()> {
    let option = option(group, name)?;
    let number: f64 = value.extract()?;
    match option.check(number) {
        Ok(_) => Ok(()),
        Err(Error::InvalidOption { allowed, .. }) => Err(PyValueError::new_err(format!(
            "invalid {name} = {}: {}",
            value.str()?,
            allowed.render(option, Spelling::Python)
        ))),
        Err(e) => Err(error(e)),
    }
}

/// The steady state's option keys, in the table's order (with those of the spectrum).
fn steady_keys(spectrum: bool) -> Vec<OptionKey> {
    OptionKey::of(OptionGroup::Steady)
        .into_iter()
        .filter(|k| spectrum || !SPECTRUM.contains(k))
        .collect()
}

/// The steady state's options, name to kind (`count`, `number`, `switch`), in the table's
/// order; with `spectrum`, those of the spectrum too.
#[pyfunction]
pub fn steady_option_kinds(py: Python<'_>, spectrum: bool) -> PyResult<Bound<'_, PyDict>> {
    let out = PyDict::new(py);
    for key in steady_keys(spectrum) {
        out.set_item(key.name(), kind_name(key.info().kind))?;
    }
    Ok(out)
}

/// A count given as a Python int for `option`, checked against the table.
pub(crate) fn count(option: OptionKey, value: i64) -> PyResult<usize> {
    option.check(value as f64).map_err(error)?;
    natural(option, value)
}

/// A count given as a Python int for `option`, whose range the library checks afterwards
/// (with words of its own, such as the basins' `along each axis`).
pub(crate) fn natural(option: OptionKey, value: i64) -> PyResult<usize> {
    usize::try_from(value).map_err(|_| error(option.invalid(value as f64)))
}

/// `base` with the caller's options over it (the Python names of the table's steady-state
/// options; with `spectrum`, those of the spectrum too), validated by the library.
pub(crate) fn steady(
    base: SteadyOptions,
    options: Option<&Bound<'_, PyDict>>,
    spectrum: bool,
) -> PyResult<SteadyOptions> {
    let mut o = base;
    let Some(options) = options else {
        return Ok(o);
    };
    let keys = steady_keys(spectrum);
    for (k, v) in options.iter() {
        let name: String = k.extract()?;
        let Some(key) = keys.iter().copied().find(|key| key.name() == name) else {
            let names: Vec<&str> = keys.iter().map(|k| k.name()).collect();
            return Err(PyTypeError::new_err(format!(
                "unknown option '{name}': the options are {}",
                names.join(", ")
            )));
        };
        if v.is_none() {
            continue;
        }
        let whole = |v: &Bound<'_, PyAny>| -> PyResult<usize> {
            let n: i64 = v
                .extract()
                .map_err(|_| PyTypeError::new_err(format!("{name} must be a whole number")))?;
            count(key, n)
        };
        match key {
            OptionKey::Tolerance => o.tolerance = v.extract()?,
            OptionKey::MaxPeriods => o.max_periods = whole(&v)?,
            OptionKey::MaxPeriod => o.max_period = whole(&v)?,
            OptionKey::MinStopFraction => o.min_stop_fraction = v.extract()?,
            OptionKey::Accelerate => o.accelerate = v.extract()?,
            OptionKey::LyapunovPeriods => {
                o.lyapunov = match whole(&v)? {
                    0 => None,
                    periods => Some(LyapunovOptions {
                        periods,
                        ..SteadyOptions::DEFAULT_LYAPUNOV
                    }),
                }
            }
            OptionKey::Harmonics => o.harmonics = whole(&v)?,
            OptionKey::SpectrumSamples => o.samples_per_period = Some(whole(&v)?),
            _ => {
                return Err(PyTypeError::new_err(format!(
                    "the option '{name}' is not one of the steady state"
                )))
            }
        }
    }
    o.validate().map_err(error)
}
