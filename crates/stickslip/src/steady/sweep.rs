//! Sweeps of w or β with continuation, as when turning a knob of the experiment.
//!
//! Each step starts from the final state of the step before. That state is taken at a whole
//! number of drive periods, where the drive phase is φ again, so the next solver starts at
//! τ = 0 with the same φ and the drive is continuous across the step (only its frequency or
//! amplitude changes). Where two steady motions coexist, the up and the down sweeps follow
//! different branches: hysteresis.

use super::cycle::{steady_state_from, SteadyOptions, SteadyState};
use super::range::ParameterRange;
use super::SolverFactory;
use crate::error::{Error, Result};
use crate::params::{Params, State};
use serde::{Deserialize, Serialize};

/// The swept parameter.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum SweepParameter {
    /// The drive frequency w = Ω/ω0.
    W,
    /// The drive amplitude β.
    Beta,
}

impl SweepParameter {
    /// `w` or `beta`.
    pub fn label(self) -> &'static str {
        match self {
            SweepParameter::W => "w",
            SweepParameter::Beta => "beta",
        }
    }

    /// `params` with this parameter set to `value`.
    ///
    /// # Errors
    /// [`Error::InvalidParameter`] when the value is out of range (w ≤ 0, β < 0).
    pub fn set(self, params: Params, value: f64) -> Result<Params> {
        let mut p = params;
        match self {
            SweepParameter::W => p.w = value,
            SweepParameter::Beta => p.beta = value,
        }
        p.validate()
    }
}

/// Which way(s) to sweep.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum SweepDirection {
    /// From the low end of the range to the high end.
    Up,
    /// From the high end to the low end.
    Down,
    /// Up, then down again starting where the up sweep ended.
    Both,
}

/// One leg of a sweep.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum SweepLeg {
    /// Increasing parameter.
    Up,
    /// Decreasing parameter.
    Down,
}

impl SweepLeg {
    /// `up` or `down`.
    pub fn label(self) -> &'static str {
        match self {
            SweepLeg::Up => "up",
            SweepLeg::Down => "down",
        }
    }
}

/// One step of a sweep.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct SweepPoint {
    /// Parameters of this step.
    pub params: Params,
    /// The leg the step belongs to.
    pub leg: SweepLeg,
    /// The steady motion found (its `trace` is left empty to keep sweeps small).
    pub steady: SteadyState,
}

/// Sweep `parameter` over `range` in `direction`, starting from `initial` with the other
/// parameters of `base`.
///
/// `on_step` sees every finished step with its index and the total number of steps; returning
/// `false` stops the sweep with [`Error::Cancelled`].
///
/// # Errors
/// [`Error::InvalidParameter`] when a swept value is out of range for the model or the options
/// are invalid; [`Error::Cancelled`]; whatever the solvers report.
pub fn sweep<F: SolverFactory + ?Sized>(
    factory: &F,
    base: Params,
    initial: State,
    parameter: SweepParameter,
    range: &ParameterRange,
    direction: SweepDirection,
    options: &SteadyOptions,
    on_step: &mut dyn FnMut(&SweepPoint, usize, usize) -> bool,
) -> Result<Vec<SweepPoint>> {
    let options = options.validate()?;
    let values = range.values();
    let mut plan: Vec<(f64, SweepLeg)> = Vec::new();
    if matches!(direction, SweepDirection::Up | SweepDirection::Both) {
        plan.extend(values.iter().map(|&v| (v, SweepLeg::Up)));
    }
    if matches!(direction, SweepDirection::Down | SweepDirection::Both) {
        plan.extend(values.iter().rev().map(|&v| (v, SweepLeg::Down)));
    }
    // Check every value before the first (possibly long) step.
    for &(value, _) in &plan {
        parameter.set(base, value)?;
    }
    let total = plan.len();
    let mut state = initial;
    let mut out = Vec::with_capacity(total);
    for (i, (value, leg)) in plan.into_iter().enumerate() {
        let params = parameter.set(base, value)?;
        let mut steady = steady_state_from(factory, &params, state, &options)?;
        state = steady.final_state();
        steady.trace = Vec::new();
        let point = SweepPoint {
            params,
            leg,
            steady,
        };
        if !on_step(&point, i, total) {
            return Err(Error::Cancelled { done: i + 1, total });
        }
        out.push(point);
    }
    Ok(out)
}
