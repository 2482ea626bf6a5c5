//! Keys that several endpoints share: the steady-state options, ranges of a parameter, the
//! swept parameter's keys.

use super::caps::CAPS;
use crate::query::{api_name, option_key, short, ApiError, Query};
use stickslip::experiment::Experiment;
use stickslip::options::{OptionKey, Spelling};
use stickslip::scan::{Axis, ParameterRange};
use stickslip::steady::SteadyOptions;
use stickslip::{Error, Parameter};

/// A library error as an answer ([`ApiError::library`]: an option out of range or over the
/// lab's caps is a 400 naming the query key).
pub(crate) fn option_error(err: &Error) -> ApiError {
    ApiError::library(err)
}

/// The steady-state options that `steady`, `sweep` and `map` take ([`steady_options`]).
pub(crate) const STEADY_OPTIONS: [OptionKey; 3] = [
    OptionKey::Tolerance,
    OptionKey::MaxPeriods,
    OptionKey::MaxPeriod,
];

/// The query keys of `options` ([`option_key`]) and of `others` (an endpoint's own keys),
/// for [`Query::finish`].
pub(crate) fn known(options: &[OptionKey], others: &[&'static str]) -> Vec<&'static str> {
    options
        .iter()
        .map(|&o| option_key(o))
        .chain(others.iter().copied())
        .collect()
}

/// A whole number of `option` from the query, or `default`.
pub(crate) fn whole(q: &mut Query, option: OptionKey, default: usize) -> Result<usize, ApiError> {
    q.whole(option_key(option), default)
}

/// The default of `option` from the option table.
pub(crate) fn table_default(option: OptionKey) -> f64 {
    option
        .default_value()
        .unwrap_or_else(|| panic!("{option:?} has a default in the option table"))
}

/// The steady-state keys of `steady`, `sweep` and `map` (as the command-line flags of the same
/// names, within the lab's caps): `tolerance`, `max-periods`, `max-period`.
pub(crate) fn steady_options(q: &mut Query, e: &Experiment) -> Result<SteadyOptions, ApiError> {
    // The experiment's own defaults (those of `stickslip steady`) with the keys over them.
    let defaults = e.steady_options();
    let tolerance = match q.number(option_key(OptionKey::Tolerance), None)? {
        Some(t) => OptionKey::Tolerance
            .check(t)
            .map_err(|e| option_error(&e))?,
        None => defaults.tolerance,
    };
    let max_periods = whole(q, OptionKey::MaxPeriods, CAPS.max_periods)?;
    let max_period = whole(
        q,
        OptionKey::MaxPeriod,
        table_default(OptionKey::MaxPeriod) as usize,
    )?;
    let options = (|| {
        defaults
            .with_tolerance(tolerance)?
            .with_max_periods(max_periods)?
            .with_max_period(max_period)?
            .with_accelerate(true)
            .with_lyapunov(Some(SteadyOptions::DEFAULT_LYAPUNOV))
    })()
    .map_err(|err| ApiError::bad(err.to_string()))?;
    CAPS.check_steady(&options).map_err(|e| option_error(&e))?;
    Ok(options)
}

/// The experiment's dimensionless parameters, or a 400 naming the missing drive value.
pub(crate) fn needs_drive(e: &Experiment) -> Result<(), ApiError> {
    e.params()
        .map(|_| ())
        .map_err(|err| ApiError::library(&err))
}

/// Refuse model keys that give a value of a parameter the request sets itself.
pub(crate) fn reject_swept(q: &Query, parameter: Parameter, by: &str) -> Result<(), ApiError> {
    if let Some(&key) = parameter.keys().iter().find(|&&k| q.has_model(k)) {
        let name = api_name(key);
        return Err(ApiError::field(
            &name,
            format!("{by} sets {} itself: drop {name}", parameter.label()),
        ));
    }
    Ok(())
}

/// A side of a map: its ends and count are the options `ends` and `count` ([`option_key`]
/// their query keys, the ends' defaults the table's), the count within the lab's `cap` (its
/// words first: a student can act on them), all checked by the library
/// ([`ParameterRange::between`]), whose error names the option at fault.
pub(crate) fn side(
    q: &mut Query,
    [min, max]: [OptionKey; 2],
    count: OptionKey,
    default_count: usize,
    cap: &dyn Fn(usize) -> stickslip::Result<()>,
) -> Result<ParameterRange, ApiError> {
    let mut end = |option: OptionKey| {
        let default = table_default(option);
        Ok::<_, ApiError>(
            q.number(option_key(option), Some(default))?
                .unwrap_or(default),
        )
    };
    let (from, to) = (end(min)?, end(max)?);
    let steps = whole(q, count, default_count)?;
    cap(steps)
        .and_then(|_| ParameterRange::between((min, from), (max, to), (count, steps)))
        .map_err(|e| option_error(&e))
}

/// `from`, `to` and `steps` keys as a sweep's range.
pub(crate) fn range(
    q: &mut Query,
    parameter: Parameter,
    keys: [&str; 3],
    defaults: (f64, f64, usize),
    cap: &dyn Fn(usize) -> stickslip::Result<()>,
) -> Result<ParameterRange, ApiError> {
    let from = q.number(keys[0], Some(defaults.0))?.unwrap_or(defaults.0);
    let to = q.number(keys[1], Some(defaults.1))?.unwrap_or(defaults.1);
    let steps = q.whole(keys[2], defaults.2)?;
    // The lab's cap first (its range, 1 to 400, is the one to tell), then the table's.
    cap(steps)
        .and_then(|_| OptionKey::SweepSteps.check_count(steps))
        .map_err(|e| match e {
            // The library's range of the count, under this range's key.
            Error::InvalidOption { value, allowed, .. } => ApiError::field(
                keys[2],
                format!(
                    "invalid {} {}: {}",
                    keys[2],
                    short(value),
                    allowed.render(OptionKey::SweepSteps, Spelling::Query)
                ),
            ),
            other => option_error(&other),
        })?;
    // Each end within the parameter's own range, named by the key that gave it.
    let key = parameter.key();
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
    // The order of the ends and the points a range needs are the library's
    // (`ParameterRange::new`); its error is named by the key that gave the value.
    ParameterRange::new(parameter.label(), from, to, steps).map_err(|e| match e {
        Error::InvalidParameter {
            name,
            value,
            allowed,
        } => {
            let key = if name != parameter.label() {
                keys[2]
            } else if value == from {
                keys[0]
            } else {
                keys[1]
            };
            ApiError::field(key, format!("invalid {key} {}: {allowed}", short(value)))
        }
        other => ApiError::library(&other),
    })
}

/// The axis of a map's range.
pub(crate) fn grid_axis(range: &ParameterRange, parameter: Parameter) -> Result<Axis, ApiError> {
    Axis::range(parameter, range).map_err(|err| ApiError::library(&err))
}
