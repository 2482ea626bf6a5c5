//! `GET /api/steady`: the steady state at one point, with its cycle's trace.

use super::answer::*;
use super::caps::CAPS;
use super::request::*;
use crate::limit::Budget;
use crate::query::{ApiError, Query};
use serde::Serialize;
use std::sync::Arc;
use stickslip::experiment::Experiment;
use stickslip::options::OptionKey;
use stickslip::steady::{steady_state_from, SteadyOptions, SteadyReport};

/// `GET /api/steady`.
#[derive(Debug)]
pub struct SteadyRequest {
    experiment: Experiment,
    options: SteadyOptions,
    samples: usize,
}

/// The answer of `/api/steady`: the keys and numbers of `stickslip steady --json`, the
/// description, and the steady cycle's trace and events.
#[derive(Debug, Serialize)]
pub struct SteadyAnswer {
    /// What `stickslip steady --json` prints.
    #[serde(flatten)]
    pub report: SteadyReport,
    /// The experiment.
    #[serde(flatten)]
    pub about: About,
    /// The recorded cycle, decimated to `samples` per drive period.
    pub trace: Trace,
    /// Events inside the recorded cycle.
    pub events: Vec<EventRow>,
}

impl SteadyRequest {
    /// Keys: the model keys, `harmonics` (9 to 256, default 16, as `--harmonics`), `samples`
    /// (display samples per drive period, a power of two from 16 to 4096, default 512),
    /// `tolerance`, `max-periods` (1 to 5000), `max-period` (1 to 16).
    ///
    /// # Errors
    /// A 400 naming the key at fault.
    pub fn parse(raw: Option<&str>) -> Result<Self, ApiError> {
        let mut q = Query::parse(raw)?;
        let experiment = q.experiment()?;
        let harmonics = whole(
            &mut q,
            OptionKey::ReportHarmonics,
            table_default(OptionKey::ReportHarmonics) as usize,
        )?;
        OptionKey::ReportHarmonics
            .check_count(harmonics)
            .map_err(|e| ApiError::library(&e))?;
        let samples = whole(
            &mut q,
            OptionKey::TraceSamples,
            table_default(OptionKey::TraceSamples) as usize,
        )?;
        let samples = CAPS
            .check_trace_samples(samples)
            .map_err(|e| ApiError::library(&e))?;
        let options = steady_options(&mut q, &experiment)?
            .with_harmonics(harmonics)
            .map_err(|e| ApiError::library(&e))?;
        q.finish(&known(
            &[
                &[OptionKey::ReportHarmonics, OptionKey::TraceSamples][..],
                &STEADY_OPTIONS,
            ]
            .concat(),
            &[],
        ))?;
        needs_drive(&experiment)?;
        Ok(Self {
            experiment,
            options,
            samples,
        })
    }

    /// Run to the steady state, as `stickslip steady` does.
    ///
    /// # Errors
    /// The time limit; the library's errors.
    pub fn run(self, budget: &Arc<Budget>) -> Result<SteadyAnswer, ApiError> {
        let e = &budget.limit_experiment(&self.experiment);
        let params = e.params().map_err(|err| ApiError::library(&err))?;
        let steady = steady_state_from(&e.factory(), &params, e.initial(), &self.options)
            .map_err(|err| failed(err, budget, "steady state"))?;
        let per_period = steady.spectrum.as_ref().map_or(1, |s| s.samples_per_period);
        let stride = (per_period / self.samples).max(1);
        let rows = steady
            .trace
            .iter()
            .step_by(stride)
            .map(|s| (s.tau, s.y, s.v, params.drive(s.tau)));
        Ok(SteadyAnswer {
            report: SteadyReport::from(&steady),
            about: About::new(e),
            trace: Trace {
                samples_per_period: per_period / stride,
                periods: steady.recorded_periods as f64,
                start: steady.start,
                columns: columns(e, rows),
            },
            events: event_rows(&steady.events),
        })
    }
}
