//! `GET /api/curve`: a curve of special points (grazing, fold, period doubling,
//! Neimark–Sacker) followed in two parameters, as `stickslip curve` computes it; the map
//! view draws it over the map.

use super::answer::*;
use super::request::*;
use crate::limit::Budget;
use crate::query::{option_key, ApiError, Query};
use serde::Serialize;
use std::sync::Arc;
use stickslip::continuation::{
    check_spec, curve, ContinuationOptions, CurveReport, CurveSpec, Follow,
};
use stickslip::experiment::Experiment;
use stickslip::options::Spelling;
use stickslip::report::{Columns, CurveTable};
use stickslip::{Error, OptionKey, Parameter};

/// The options of a curve, in the order of the query keys' documentation.
const CURVE_OPTIONS: [OptionKey; 7] = [
    OptionKey::TwoParameterVary,
    OptionKey::TwoParameterVaryTo,
    OptionKey::TwoParameterOver,
    OptionKey::TwoParameterFrom,
    OptionKey::TwoParameterTo,
    OptionKey::TwoParameterMaxPoints,
    OptionKey::TwoParameterMaxStep,
];

/// `GET /api/curve`.
#[derive(Debug)]
pub struct CurveRequest {
    experiment: Experiment,
    spec: CurveSpec,
    options: ContinuationOptions,
}

/// The answer of `/api/curve`: the library's curve, its points as the columns of `stickslip
/// curve`'s CSV (the library's curve table: the same names and numbers) and its summary as
/// `stickslip curve --json` prints it; or, when the branch searched has no special point of
/// the kind, `none` saying so (in the tool's words) and both null.
#[derive(Debug, Serialize)]
pub struct CurveAnswer {
    /// The experiment.
    #[serde(flatten)]
    pub about: About,
    /// What was followed (`grazing`, `fold`, `period-doubling`, `neimark-sacker`).
    pub follow: Follow,
    /// The points: column name → array (`<over>`, `<vary>`, `y`, `v`, `period`,
    /// `stops_per_period`, `turns`, `mu1_re`, ..., `stability`, `arclength`, `special`).
    pub points: Option<Columns>,
    /// The summary (`over`, `vary`, `codim2`, `begin`, `end`, ...).
    pub report: Option<CurveReport>,
    /// Why there is no curve: no special point of the kind on the branch searched.
    pub none: Option<String>,
}

impl CurveRequest {
    /// Keys: the model keys (with both parameters' values: the point where the search
    /// starts), `follow` (`grazing`, the default, `fold`, `period-doubling`,
    /// `neimark-sacker`), `vary` (default `beta`), `vary-to`, `over` (default `w`), `from`,
    /// `to`, `max-points`, `max-step` (as the command-line flags of `stickslip curve`).
    ///
    /// # Errors
    /// A 400 naming the key at fault.
    pub fn parse(raw: Option<&str>) -> Result<Self, ApiError> {
        let mut q = Query::parse(raw)?;
        let follow = q.name("follow", Follow::Grazing)?;
        let vary = q.name(option_key(OptionKey::TwoParameterVary), Parameter::Beta)?;
        let over = q.name(option_key(OptionKey::TwoParameterOver), Parameter::W)?;
        let experiment = q.experiment()?;
        let mut number = |option: OptionKey| -> Result<f64, ApiError> {
            let key = option_key(option);
            match q.number(key, option.default_value())? {
                Some(x) => Ok(x),
                None => Err(ApiError::field(key, format!("{key} is needed"))),
            }
        };
        let spec = CurveSpec {
            follow,
            vary,
            vary_to: number(OptionKey::TwoParameterVaryTo)?,
            over,
            from: number(OptionKey::TwoParameterFrom)?,
            to: number(OptionKey::TwoParameterTo)?,
        };
        let max_step = number(OptionKey::TwoParameterMaxStep)?;
        let max_points = whole(
            &mut q,
            OptionKey::TwoParameterMaxPoints,
            table_default(OptionKey::TwoParameterMaxPoints) as usize,
        )?;
        q.finish(&known(&CURVE_OPTIONS, &["follow"]))?;
        // The ends and the option table's ranges; two parameters that are one is `vary`'s
        // fault.
        check_spec(&spec).map_err(|e| match e {
            Error::InvalidOption {
                option: OptionKey::TwoParameterVary,
                ..
            } => ApiError::field(
                option_key(OptionKey::TwoParameterVary),
                e.render(Spelling::Query),
            ),
            other => ApiError::library(&other),
        })?;
        OptionKey::TwoParameterMaxPoints
            .check_count(max_points)
            .and_then(|_| OptionKey::TwoParameterMaxStep.check(max_step))
            .map_err(|e| ApiError::library(&e))?;
        needs_drive(&experiment)?;
        let options = ContinuationOptions {
            max_points,
            ..ContinuationOptions::default()
        }
        .with_max_step(max_step);
        Ok(Self {
            experiment,
            spec,
            options,
        })
    }

    /// Follow the curve, as `stickslip curve` does.
    ///
    /// # Errors
    /// The time limit; the library's errors (Shockley diodes, a grazing with a smooth friction
    /// law, a model value of `over` outside `from`..`to`).
    pub fn run(self, budget: &Arc<Budget>) -> Result<CurveAnswer, ApiError> {
        let e = &budget.limit_experiment(&self.experiment);
        budget.start(self.options.max_points);
        let computed = curve(e, &self.spec, &self.options, &budget.keep_going())
            .map_err(|err| failed(err, budget, "curve"))?;
        let (points, report, none) = match computed {
            Ok(c) => (
                Some(Columns::of(&CurveTable { curve: &c })),
                Some(CurveReport::from(&c)),
                None,
            ),
            Err(no) => (None, None, Some(no.to_string())),
        };
        Ok(CurveAnswer {
            about: About::new(e),
            follow: self.spec.follow,
            points,
            report,
            none,
        })
    }
}
