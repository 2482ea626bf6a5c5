//! `GET /api/simulate`: a run from the initial state.

use super::answer::*;
use super::caps::CAPS;
use super::request::*;
use crate::limit::Budget;
use crate::query::{option_key, ApiError, Query};
use serde::Serialize;
use std::sync::Arc;
use stickslip::experiment::Experiment;
use stickslip::options::{OptionKey, SimulateOptions};
use stickslip::report::TrajectoryReport;

/// `GET /api/simulate`.
#[derive(Debug)]
pub struct SimulateRequest {
    experiment: Experiment,
    periods: f64,
    samples: usize,
}

/// The answer of `/api/simulate`: the run from the initial state, as `stickslip simulate`
/// writes it: the experiment's description beside the library's trajectory report
/// ([`TrajectoryReport`]: `periods`, `samples_per_period`, `columns` naming every column, the
/// columns `tau`, `y`, `v`, `drive`, `phase` and the physical ones, and `events`).
#[derive(Debug, Serialize)]
pub struct SimulateAnswer {
    /// The experiment.
    #[serde(flatten)]
    pub about: About,
    /// The run.
    #[serde(flatten)]
    pub report: TrajectoryReport,
}

impl SimulateRequest {
    /// Keys: the model keys, `periods` (> 0, at most 2000, default 20), `samples` (per drive
    /// period, 1 to 10000, default 200); at most 200000 samples in all.
    ///
    /// # Errors
    /// A 400 naming the key at fault.
    pub fn parse(raw: Option<&str>) -> Result<Self, ApiError> {
        let mut q = Query::parse(raw)?;
        let experiment = q.experiment()?;
        let periods = table_default(OptionKey::SimulatePeriods);
        let options = SimulateOptions {
            periods: q
                .number(option_key(OptionKey::SimulatePeriods), Some(periods))?
                .unwrap_or(periods),
            samples_per_period: whole(
                &mut q,
                OptionKey::SimulateSamples,
                table_default(OptionKey::SimulateSamples) as usize,
            )?,
        };
        // The lab's caps first: their words are the ones a student can act on.
        CAPS.check_simulate(&options)
            .and_then(|_| options.validate())
            .map_err(|e| option_error(&e))?;
        let (periods, samples) = (options.periods, options.samples_per_period);
        q.finish(&known(
            &[OptionKey::SimulatePeriods, OptionKey::SimulateSamples],
            &[],
        ))?;
        needs_drive(&experiment)?;
        Ok(Self {
            experiment,
            periods,
            samples,
        })
    }

    /// Run from the initial state, as `stickslip simulate` does.
    ///
    /// # Errors
    /// The time limit; the library's errors.
    pub fn run(self, budget: &Arc<Budget>) -> Result<SimulateAnswer, ApiError> {
        let e = &budget.limit_experiment(&self.experiment);
        let report = e
            .trajectory(self.periods, self.samples)
            .map_err(|err| ApiError::library(&err))?
            .collect_report()
            .map_err(|err| failed(err, budget, "simulation"))?;
        Ok(SimulateAnswer {
            about: About::trajectory(e),
            report,
        })
    }
}
