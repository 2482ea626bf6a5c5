//! Flag groups shared by several commands (the model flags are in [`crate::model`]): the
//! steady-state search, parameter ranges, and the rule that a swept parameter takes no value
//! of its own.

use crate::model::{flag, ModelArgs};
use crate::output::{usage, UsageError};
use anyhow::Result;
use stickslip::scan::ParameterRange;
use stickslip::stability::LyapunovOptions;
use stickslip::steady::SteadyOptions;
use stickslip::{Experiment, OptionKey, Parameter};

/// Flags of the steady-state search, shared by `steady`, `sweep` and `phase-diagram`.
#[derive(Debug, Clone, clap::Args)]
#[command(next_help_heading = "Steady state")]
pub struct SteadyFlags {
    #[arg(long, help = help(OptionKey::Tolerance), value_parser = crate::model::finite, allow_hyphen_values = true)]
    pub tolerance: Option<f64>,
    #[arg(long = OptionKey::MaxPeriods.flag(), help = help(OptionKey::MaxPeriods), default_value_t = int(OptionKey::MaxPeriods) as _, allow_hyphen_values = true)]
    pub max_periods: i64,
    #[arg(long = OptionKey::MaxPeriod.flag(), help = help(OptionKey::MaxPeriod), default_value_t = int(OptionKey::MaxPeriod) as _, allow_hyphen_values = true)]
    pub max_period: i64,
    #[arg(long = OptionKey::Accelerate.flag(), help = help(OptionKey::Accelerate))]
    pub no_extrapolation: bool,
    #[arg(long = OptionKey::LyapunovPeriods.flag(), help = help(OptionKey::LyapunovPeriods), default_value_t = int(OptionKey::LyapunovPeriods) as _, allow_hyphen_values = true)]
    pub lyapunov_periods: i64,
}

impl SteadyFlags {
    /// Validated library options (spectrum on) for the experiment's solver: its own
    /// defaults ([`Experiment::steady_options`]) with the flags over them, each checked
    /// against the library's option table.
    pub fn options(&self, experiment: &Experiment) -> Result<SteadyOptions> {
        let defaults = experiment.steady_options();
        let tolerance = number(
            OptionKey::Tolerance,
            self.tolerance.unwrap_or(defaults.tolerance),
        )?;
        let max_periods = count(OptionKey::MaxPeriods, self.max_periods)?;
        let max_period = count(OptionKey::MaxPeriod, self.max_period)?;
        Ok(defaults
            .with_tolerance(tolerance)?
            .with_max_periods(max_periods)?
            .with_max_period(max_period)?
            .with_accelerate(!self.no_extrapolation)
            .with_lyapunov(self.lyapunov()?)?)
    }

    /// The measurement of motions that do not repeat (`None` for `--lyapunov-periods 0`).
    pub fn lyapunov(&self) -> Result<Option<LyapunovOptions>> {
        let periods = count(OptionKey::LyapunovPeriods, self.lyapunov_periods)?;
        Ok((periods > 0).then_some(LyapunovOptions {
            periods,
            ..SteadyOptions::DEFAULT_LYAPUNOV
        }))
    }
}

/// The help of `option`'s flag: the option table's one line, without its final period (as
/// the tool's help is written).
pub fn help(option: OptionKey) -> &'static str {
    let text = option.help();
    text.strip_suffix('.').unwrap_or(text)
}

/// The default of `option`'s flag from the option table (a whole number).
///
/// # Panics
/// When the row has no default: a flag with a default of its own has one in the table.
pub fn int(option: OptionKey) -> i64 {
    option
        .default_value()
        .unwrap_or_else(|| panic!("{option:?} has a default in the option table")) as i64
}

/// The default of `option`'s flag from the option table (a number).
///
/// # Panics
/// When the row has no default.
pub fn num(option: OptionKey) -> f64 {
    option
        .default_value()
        .unwrap_or_else(|| panic!("{option:?} has a default in the option table"))
}

/// A whole number given to the flag of `option`, checked against the library's option table
/// (typed as a signed number, so that `-4` is refused by the table's range, not by the
/// parser).
///
/// # Errors
/// [`stickslip::Error::InvalidOption`], which the tool renders with the flag's name.
pub fn count(option: OptionKey, value: i64) -> Result<usize> {
    Ok(option.check(value as f64)? as usize)
}

/// A number given to the flag of `option`, checked against the library's option table.
///
/// # Errors
/// [`stickslip::Error::InvalidOption`], which the tool renders with the flag's name.
pub fn number(option: OptionKey, value: f64) -> Result<f64> {
    Ok(option.check(value)?)
}

/// A range of `name` given by flags `--{from_flag}`, `--{to_flag}` and the count `steps` of
/// `steps_option`: the count is checked against the library's option table, the range by the
/// library ([`ParameterRange::new`]), whose message names the flags.
pub fn range_from_flags(
    name: &'static str,
    (from_flag, from): (&str, f64),
    (to_flag, to): (&str, f64),
    (steps_option, steps): (OptionKey, i64),
) -> Result<ParameterRange> {
    let steps = count(steps_option, steps)?;
    ParameterRange::new(name, from, to, steps).map_err(|e| match e {
        stickslip::Error::InvalidParameter {
            name: field,
            value,
            allowed,
        } => {
            let flag = if field != name {
                steps_option.flag()
            } else if value == from {
                from_flag
            } else {
                to_flag
            };
            let value = stickslip::Number(value);
            UsageError(format!("invalid --{flag} {value}: {allowed}")).into()
        }
        other => other.into(),
    })
}

/// Refuse flags that give a value of the swept parameter (`--over w` with `--w`, say).
pub fn reject_swept_flags(model: &ModelArgs, over: Parameter, command: &str) -> Result<()> {
    if let Some(&key) = over.keys().iter().find(|&&k| model.given(k)) {
        usage!(
            "{command} sets {} from its range: drop {}",
            over.label(),
            flag(key)
        );
    }
    Ok(())
}
