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
use stickslip::steady::{self_excited_trace, steady_state_from, SteadyOptions, SteadyReport};

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
    /// The period of a self-excited cycle in seconds (`cycle_period_tau` / ω0; a physical
    /// description of a belt without a drive only).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub cycle_period_s: Option<f64>,
    /// The recorded cycle, decimated to `samples` per drive period (a self-excited motion:
    /// its one cycle in `samples` samples).
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
        let factory = e.factory();
        let steady = steady_state_from(&factory, &params, e.initial(), &self.options)
            .map_err(|err| failed(err, budget, "steady state"))?;
        let span_s = |tau: f64| e.scales().map(|s| tau / s.omega0);
        // A self-excited motion (a belt without a drive) has no drive period: its trace is
        // its one cycle, `samples` samples run again from its section (the library's
        // `self_excited_trace`).
        let cycle = self_excited_trace(&factory, &steady, self.samples)
            .map_err(|err| failed(err, budget, "steady state"))?;
        let trace = match (cycle, steady.self_excited) {
            (Some(samples), Some(c)) => {
                let span = c.period.unwrap_or(std::f64::consts::TAU);
                let rows = samples
                    .iter()
                    .map(|s| (s.tau, s.y, s.v, params.drive(s.tau)));
                Trace {
                    samples_per_period: samples.len(),
                    periods: 1.0,
                    start: steady.start,
                    span_tau: span,
                    span_s: span_s(span),
                    columns: columns(e, rows),
                }
            }
            _ => {
                let per_period = steady.spectrum.as_ref().map_or(1, |s| s.samples_per_period);
                let stride = (per_period / self.samples).max(1);
                let rows = steady
                    .trace
                    .iter()
                    .step_by(stride)
                    .map(|s| (s.tau, s.y, s.v, params.drive(s.tau)));
                let span = steady.recorded_periods as f64 * params.drive_period();
                Trace {
                    samples_per_period: per_period / stride,
                    periods: steady.recorded_periods as f64,
                    start: steady.start,
                    span_tau: span,
                    span_s: span_s(span),
                    columns: columns(e, rows),
                }
            }
        };
        Ok(SteadyAnswer {
            report: SteadyReport::from(&steady),
            about: About::new(e),
            cycle_period_s: steady.self_excited.and_then(|c| c.period).and_then(span_s),
            trace,
            events: event_rows(&steady.events),
        })
    }
}
