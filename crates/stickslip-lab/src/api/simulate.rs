//! `GET /api/simulate`: a run from the initial state.

use super::answer::*;
use super::caps::CAPS;
use super::request::*;
use crate::limit::Budget;
use crate::query::{ApiError, Query};
use serde::Serialize;
use std::sync::Arc;
use stickslip::experiment::Experiment;
use stickslip::options::SimulateOptions;
use stickslip::solver::{grid, sample_at};

/// `GET /api/simulate`.
#[derive(Debug)]
pub struct SimulateRequest {
    experiment: Experiment,
    periods: f64,
    samples: usize,
}

/// The answer of `/api/simulate`: the run from the initial state, as `stickslip simulate`
/// writes it.
#[derive(Debug, Serialize)]
pub struct SimulateAnswer {
    /// The experiment.
    #[serde(flatten)]
    pub about: About,
    /// The samples; `phase` holds `slip+`, `slip-` or `stick` for each.
    pub trace: Trace,
    /// Phase of the motion at each sample.
    pub phase: Vec<&'static str>,
    /// Every event of the run.
    pub events: Vec<EventRow>,
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
        let options = SimulateOptions {
            periods: q.number("periods", Some(20.0))?.unwrap_or(20.0),
            samples_per_period: q.whole("samples", 200)?,
        };
        // The lab's caps first: their words are the ones a student can act on.
        CAPS.check_simulate(&options)
            .and_then(|_| options.validate())
            .map_err(|e| option_error(&e))?;
        let (periods, samples) = (options.periods, options.samples_per_period);
        q.finish(&["periods", "samples"])?;
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
        use stickslip::steady::SolverFactory;
        let e = &budget.limit_experiment(&self.experiment);
        let params = e.params().map_err(|err| ApiError::library(&err))?;
        let mut solver = e
            .factory()
            .make(params, e.initial())
            .map_err(|err| ApiError::library(&err))?;
        let total = (self.periods * self.samples as f64).ceil() as usize;
        let times = grid(0.0, self.periods * params.drive_period(), total);
        let mut events = Vec::new();
        let samples = sample_at(solver.as_mut(), &times, |ev| events.push(*ev))
            .map_err(|err| failed(err, budget, "simulation"))?;
        let rows = samples
            .iter()
            .map(|s| (s.tau, s.y, s.v, params.drive(s.tau)));
        Ok(SimulateAnswer {
            about: About::new(e),
            trace: Trace {
                samples_per_period: self.samples,
                periods: self.periods,
                start: 0.0,
                columns: columns(e, rows),
            },
            phase: samples.iter().map(|s| s.phase.label()).collect(),
            events: event_rows(&events),
        })
    }
}
