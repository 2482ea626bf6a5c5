//! Sweeps with continuation, as when turning a knob of the experiment.
//!
//! Each step starts from the final state of the step before. That state is taken at a whole
//! number of drive periods, where the drive phase is φ again, so the next solver starts at
//! τ = 0 with the same φ and the drive is continuous across the step (only the swept
//! parameter changes). Where two steady motions coexist, the up and the down sweeps follow
//! different branches: hysteresis.

use super::axis::Axis;
use super::monitor::Monitor;
use crate::error::{Error, Result};
use crate::experiment::Experiment;
use crate::params::{Parameter, Params, State};
use crate::steady::{check_horizon, steady_state_from, SolverFactory, SteadyOptions, SteadyState};
use serde::{Deserialize, Serialize};
use std::ops::ControlFlow;
use std::sync::Arc;

/// Which way(s) to sweep.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum SweepDirection {
    /// The axis's values in order.
    Up,
    /// The axis's values in reverse order.
    Down,
    /// Up, then down again starting where the up sweep ended.
    #[default]
    Both,
}

impl SweepDirection {
    /// `up`, `down` or `both`.
    pub fn label(self) -> &'static str {
        match self {
            SweepDirection::Up => "up",
            SweepDirection::Down => "down",
            SweepDirection::Both => "both",
        }
    }
}

/// One leg of a sweep.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum SweepLeg {
    /// The axis's values in order (increasing for a range).
    Up,
    /// In reverse order.
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
    /// The swept parameter's value.
    pub value: f64,
    /// The leg the step belongs to.
    pub leg: SweepLeg,
    /// The steady motion found (its `trace` is left empty to keep sweeps small).
    pub steady: SteadyState,
}

impl std::fmt::Debug for Sweep {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Sweep")
            .field("experiment", &self.experiment)
            .field("axis", &self.axis)
            .field("direction", &self.direction)
            .field("options", &self.options)
            .finish_non_exhaustive()
    }
}

/// A sweep of one parameter of an experiment (see the module documentation).
///
/// Defaults: [`SweepDirection::Both`], the experiment's steady-state options
/// ([`Experiment::steady_options`]).
#[derive(Clone)]
pub struct Sweep {
    experiment: Experiment,
    factory: Arc<dyn SolverFactory + Send>,
    axis: Axis,
    direction: SweepDirection,
    options: SteadyOptions,
}

impl Sweep {
    /// Sweep `axis` of `experiment`, starting from its initial state. The experiment needs no
    /// value of the swept parameter.
    ///
    /// # Errors
    /// A value out of range for the model; a drive value missing that is not swept.
    pub fn new(experiment: &Experiment, axis: Axis) -> Result<Self> {
        for &v in axis.values() {
            experiment.params_with(&[(axis.parameter(), v)])?;
        }
        let sweep = Self {
            options: experiment.steady_options(),
            factory: Arc::new(experiment.factory()),
            experiment: experiment.clone(),
            axis,
            direction: SweepDirection::Both,
        };
        sweep.check_horizons()?;
        Ok(sweep)
    }

    /// Check that every step's longest run stays within the time range the solvers resolve
    /// ([`crate::steady::check_horizon`]).
    fn check_horizons(&self) -> Result<()> {
        for &v in self.axis.values() {
            let params = self.experiment.params_with(&[(self.axis.parameter(), v)])?;
            check_horizon(&params, &self.options, 0.0)?;
        }
        Ok(())
    }

    /// Sweep up, down or both ways.
    pub fn direction(mut self, direction: SweepDirection) -> Self {
        self.direction = direction;
        self
    }

    /// Build solvers with `factory` instead of the experiment's own (for another solver of the
    /// same model).
    pub fn with_factory(mut self, factory: impl SolverFactory + Send + 'static) -> Self {
        self.factory = Arc::new(factory);
        self
    }

    /// Use these steady-state options.
    ///
    /// # Errors
    /// When the options are invalid.
    pub fn options(mut self, options: SteadyOptions) -> Result<Self> {
        self.options = options.validate()?;
        self.check_horizons()?;
        Ok(self)
    }

    /// The steady-state options used.
    pub fn steady_options(&self) -> &SteadyOptions {
        &self.options
    }

    /// The swept axis.
    pub fn axis(&self) -> &Axis {
        &self.axis
    }

    /// The steps in order: value and leg.
    pub fn plan(&self) -> Vec<(f64, SweepLeg)> {
        let values = self.axis.values();
        let mut plan = Vec::new();
        if matches!(self.direction, SweepDirection::Up | SweepDirection::Both) {
            plan.extend(values.iter().map(|&v| (v, SweepLeg::Up)));
        }
        if matches!(self.direction, SweepDirection::Down | SweepDirection::Both) {
            plan.extend(values.iter().rev().map(|&v| (v, SweepLeg::Down)));
        }
        plan
    }

    /// Run the sweep; `monitor` sees every finished step and can stop the sweep.
    ///
    /// # Errors
    /// [`Error::Cancelled`]; whatever the solvers report.
    pub fn run(&self, monitor: &dyn Monitor) -> Result<Vec<SweepPoint>> {
        let total = self.plan().len();
        let mut out = Vec::with_capacity(total);
        self.run_from(0, self.experiment.initial(), &mut |i, point| {
            out.push(point);
            monitor.step(i + 1, total)
        })?;
        Ok(out)
    }

    /// The parameters of step `index` of the [`Sweep::plan`].
    ///
    /// # Errors
    /// A value out of range (never for a sweep built by [`Sweep::new`]).
    ///
    /// # Panics
    /// When `index` is past the plan.
    pub fn params(&self, index: usize) -> Result<Params> {
        let (value, _) = self.plan()[index];
        self.experiment
            .params_with(&[(self.axis.parameter(), value)])
    }

    /// The experiment the sweep varies.
    pub fn experiment(&self) -> &Experiment {
        &self.experiment
    }

    /// Run the steps `start..` of the [`Sweep::plan`], the first from `state` (the experiment's
    /// initial state for `start` = 0, else the [`SteadyState::final_state`] of step
    /// `start − 1`), handing each finished step and its index to `each`, which may stop the
    /// sweep. A sweep resumed this way gives the same steps, bit for bit, as one run at once:
    /// front ends that save steps as they go (in a [`crate::checkpoint::Checkpoint`]) resume
    /// from the final state of the last step saved.
    ///
    /// # Errors
    /// [`Error::Cancelled`] when `each` stops the sweep; whatever the solvers report.
    pub fn run_from(
        &self,
        start: usize,
        state: State,
        each: &mut dyn FnMut(usize, SweepPoint) -> ControlFlow<()>,
    ) -> Result<()> {
        let factory = self.factory.as_ref();
        let parameter: Parameter = self.axis.parameter();
        let plan = self.plan();
        let total = plan.len();
        let mut state = State::new(state.y, state.v)?;
        for (i, (value, leg)) in plan.into_iter().enumerate().skip(start) {
            let params = self.experiment.params_with(&[(parameter, value)])?;
            let mut steady = steady_state_from(factory, &params, state, &self.options)?;
            state = steady.final_state();
            steady.trace = Vec::new();
            let point = SweepPoint {
                params,
                value,
                leg,
                steady,
            };
            if each(i, point) == ControlFlow::Break(()) {
                return Err(Error::Cancelled { done: i + 1, total });
            }
        }
        Ok(())
    }
}
