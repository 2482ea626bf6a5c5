//! `GET /api/sweep`: the gain swept up and down over one parameter, beside the theory's.

use super::answer::*;
use super::caps::CAPS;
use super::request::*;
use crate::limit::Budget;
use crate::query::{option_key, ApiError, Query};
use serde::Serialize;
use std::sync::Arc;
use stickslip::experiment::Experiment;
use stickslip::report::SweepReport;
use stickslip::scan::{Axis, ParameterRange, Sweep, SweepDirection};
use stickslip::steady::SteadyOptions;
use stickslip::theory::curves::SweepTheory;
use stickslip::DiodeModel;
use stickslip::OptionKey;
use stickslip::{Error, Parameter};

/// `GET /api/sweep`.
#[derive(Debug)]
pub struct SweepRequest {
    experiment: Experiment,
    parameter: Parameter,
    range: ParameterRange,
    direction: SweepDirection,
    options: SteadyOptions,
}

/// The answer of `/api/sweep`: the experiment's description, the library's sweep report
/// ([`SweepReport`]: `over`, `direction` and the rows `points`, as `stickslip sweep --json`
/// writes them) and the theory's curves.
#[derive(Debug, Serialize)]
pub struct SweepAnswer {
    /// The experiment.
    #[serde(flatten)]
    pub about: About,
    /// The swept parameter (`w`, `beta`, `zeta` or `mu_s`), the direction asked for (`up`,
    /// `down` or `both`) and the steps in the order they were computed.
    #[serde(flatten)]
    pub report: SweepReport,
    /// The theory's gains over the range (null where there is none).
    pub theory: SweepTheoryCurves,
}

/// The theory's gain curves beside a sweep (those `stickslip sweep --plot` draws).
#[derive(Debug, Serialize)]
pub struct SweepTheoryCurves {
    /// Values of the swept parameter.
    pub x: Vec<f64>,
    /// The paper's eq. (11): the gain of the fundamental G1 = A1/β.
    pub paper_gain1: Vec<f64>,
    /// The exact sliding orbit's gain G = (y_max − y_min)/(2β) (its peak/β), as the
    /// simulated `gain`.
    pub exact_gain: Vec<f64>,
    /// `PWL theory: ` with Shockley diodes (the theory is that of the PWL model), else empty.
    pub prefix: &'static str,
}

impl SweepRequest {
    /// Keys: the model keys (without a value of the swept parameter), `over` (`w`, `beta`,
    /// `zeta` or `mu-s`, default `w`), `from`, `to` (default 0.2 to 2), `steps` (1 to 400,
    /// default 60), `direction` (`up`, `down` or `both`, the default), `tolerance`,
    /// `max-periods`, `max-period`.
    ///
    /// # Errors
    /// A 400 naming the key at fault.
    pub fn parse(raw: Option<&str>) -> Result<Self, ApiError> {
        let mut q = Query::parse(raw)?;
        let parameter = q.name("over", Parameter::W)?;
        reject_swept(&q, parameter, "a sweep")?;
        let experiment = q.experiment()?;
        let range = range(
            &mut q,
            parameter,
            ["from", "to", option_key(OptionKey::SweepSteps)],
            (0.2, 2.0, 60),
            &|n| CAPS.check_sweep(n),
        )?;
        let direction = q.name("direction", SweepDirection::Both)?;
        let options = steady_options(&mut q, &experiment)?
            .with_harmonics(3)
            .map_err(|e| ApiError::library(&e))?;
        q.finish(&known(
            &STEADY_OPTIONS,
            &[
                "over",
                "from",
                "to",
                option_key(OptionKey::SweepSteps),
                "direction",
            ],
        ))?;
        // The experiment must be complete but for the swept parameter.
        Axis::range(parameter, &range)
            .and_then(|axis| Sweep::new(&experiment, axis))
            .map_err(|e| ApiError::library(&e))?;
        Ok(Self {
            experiment,
            parameter,
            range,
            direction,
            options,
        })
    }

    /// Sweep up and/or down with continuation, as `stickslip sweep` does.
    ///
    /// # Errors
    /// The time limit; the library's errors.
    pub fn run(self, budget: &Arc<Budget>) -> Result<SweepAnswer, ApiError> {
        let e = &budget.limit_experiment(&self.experiment);
        let library = |err: Error| ApiError::library(&err);
        let sweep = Sweep::new(
            e,
            Axis::range(self.parameter, &self.range).map_err(library)?,
        )
        .map_err(library)?
        .direction(self.direction)
        .options(self.options)
        .map_err(library)?;
        budget.start(sweep.plan().len());
        let points = sweep
            .run(&budget.keep_going())
            .map_err(|err| failed(err, budget, "sweep"))?;
        // The theory's gains over the range, as `stickslip sweep --plot` draws them.
        let base = e
            .params_with(&[(self.parameter, self.range.from())])
            .map_err(|err| ApiError::bad(err.to_string()))?;
        let theory = SweepTheory::new(
            &base,
            self.parameter,
            (self.range.from(), self.range.to(), self.range.steps()),
            e.diode_model() == DiodeModel::Shockley,
        );
        Ok(SweepAnswer {
            about: About::new(e),
            report: SweepReport::new(e, self.parameter, self.direction, &points),
            theory: SweepTheoryCurves {
                x: theory.paper.x,
                paper_gain1: theory.paper.y,
                exact_gain: theory.exact.y,
                prefix: theory.prefix,
            },
        })
    }
}
