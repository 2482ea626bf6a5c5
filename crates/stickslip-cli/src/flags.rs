//! Flag groups shared by several commands (the model flags are in [`crate::model`]): the
//! steady-state search, parameter ranges, and the rule that a swept parameter takes no value
//! of its own.

use crate::model::{flag, ModelArgs};
use crate::output::usage;
use anyhow::Result;
use stickslip::experiment::Key;
use stickslip::scan::ParameterRange;
use stickslip::stability::LyapunovOptions;
use stickslip::steady::SteadyOptions;
use stickslip::{Experiment, Parameter};

/// Flags of the steady-state search, shared by `steady`, `sweep` and `phase-diagram`.
#[derive(Debug, Clone, clap::Args)]
#[command(next_help_heading = "Steady state")]
pub struct SteadyFlags {
    /// Relative tolerance of the once-per-period (stroboscopic) repetition [default: 1e-10
    /// with the exact PWL solver, 1e-6 (its rtol) with the Shockley solver].
    #[arg(long, value_parser = crate::model::finite, allow_hyphen_values = true)]
    pub tolerance: Option<f64>,
    /// Drive periods run at most before calling the motion non-periodic.
    #[arg(
        long = "max-periods",
        default_value_t = 5000,
        allow_hyphen_values = true
    )]
    pub max_periods: i64,
    /// Longest period looked for, in drive periods (1 to 64).
    #[arg(long = "max-period", default_value_t = 16, allow_hyphen_values = true)]
    pub max_period: i64,
    /// Never extrapolate the stroboscopic map to its fixed point nor settle it by Newton's
    /// method (slower; finds the same cycle).
    #[arg(long = "no-extrapolation")]
    pub no_extrapolation: bool,
    /// Drive periods over which a motion that does not repeat is measured by its largest
    /// Lyapunov exponent (exact PWL model; after 100 periods that align the tangent, in 20
    /// blocks): chaotic when it is positive beyond 4 standard errors. 0: not measured.
    #[arg(
        long = "lyapunov-periods",
        default_value_t = 5000,
        allow_hyphen_values = true
    )]
    pub lyapunov_periods: i64,
}

impl SteadyFlags {
    /// Validated library options (spectrum on) for the experiment's solver: its own
    /// defaults ([`Experiment::steady_options`]) with the flags over them.
    pub fn options(&self, experiment: &Experiment) -> Result<SteadyOptions> {
        let defaults = experiment.steady_options();
        let tolerance = self.tolerance.unwrap_or(defaults.tolerance);
        if !(tolerance > 0.0 && tolerance < 1.0) {
            usage!("invalid --tolerance {tolerance}: must be > 0 and < 1");
        }
        if !(1..=100_000_000).contains(&self.max_periods) {
            usage!(
                "invalid --max-periods {}: must be from 1 to 1e8",
                self.max_periods
            );
        }
        if !(1..=64).contains(&self.max_period) {
            usage!(
                "invalid --max-period {}: must be from 1 to 64",
                self.max_period
            );
        }
        Ok(defaults
            .with_tolerance(tolerance)?
            .with_max_periods(self.max_periods as usize)?
            .with_max_period(self.max_period as usize)?
            .with_accelerate(!self.no_extrapolation)
            .with_lyapunov(self.lyapunov()?)?)
    }

    /// The measurement of motions that do not repeat (`None` for `--lyapunov-periods 0`).
    pub fn lyapunov(&self) -> Result<Option<LyapunovOptions>> {
        let periods = self.lyapunov_periods;
        if periods == 0 {
            return Ok(None);
        }
        if !(20..=100_000_000).contains(&periods) {
            usage!("invalid --lyapunov-periods {periods}: must be 0 (off) or from 20 to 1e8");
        }
        Ok(Some(LyapunovOptions {
            periods: periods as usize,
            ..SteadyOptions::DEFAULT_LYAPUNOV
        }))
    }
}

/// Validate a range given by flags `--{from_flag}`, `--{to_flag}`, `--{steps_flag}`.
pub fn range_from_flags(
    name: &'static str,
    (from_flag, from): (&str, f64),
    (to_flag, to): (&str, f64),
    (steps_flag, steps): (&str, i64),
) -> Result<ParameterRange> {
    if from > to {
        usage!("invalid range: --{from_flag} {from} is above --{to_flag} {to}");
    }
    if !(1..=100_000).contains(&steps) {
        usage!("invalid --{steps_flag} {steps}: must be from 1 to 100000");
    }
    if steps == 1 && from != to {
        usage!("invalid --{steps_flag} 1: a range from {from} to {to} needs at least 2 points");
    }
    Ok(ParameterRange::new(name, from, to, steps as usize)?)
}

/// The keys that give a value of `parameter`: the library's [`Parameter::keys`] (for the
/// lab, until it calls the library itself).
#[doc(hidden)]
pub fn keys_of(parameter: Parameter) -> &'static [Key] {
    parameter.keys()
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
