//! `GET /api/theory`: both theories at one point.

use super::request::*;
use crate::limit::Budget;
use crate::query::{ApiError, Query};
use std::sync::Arc;
use stickslip::experiment::Experiment;
use stickslip::theory::TheoryReport;
use stickslip::{DiodeModel, Error, Unsupported};

/// `GET /api/theory`.
#[derive(Debug)]
pub struct TheoryRequest {
    experiment: Experiment,
}

impl TheoryRequest {
    /// Keys: the model keys (PWL diodes or Coulomb friction; no initial state, as `stickslip
    /// theory`).
    ///
    /// # Errors
    /// A 400 naming the key at fault.
    pub fn parse(raw: Option<&str>) -> Result<Self, ApiError> {
        let mut q = Query::parse(raw)?;
        for name in ["y0", "v0", "uc0", "i0"] {
            if q.has(name) {
                return Err(ApiError::field(
                    name,
                    format!(
                        "{name} is not used by theory: it computes steady states, not a run \
                         from an initial state"
                    ),
                ));
            }
        }
        let experiment = q.experiment()?;
        q.finish(&[])?;
        if experiment.diode_model() == DiodeModel::Shockley {
            return Err(ApiError::field(
                "model",
                Error::Unsupported(Unsupported::TheoryNeedsPwl).to_string(),
            ));
        }
        needs_drive(&experiment)?;
        Ok(Self { experiment })
    }

    /// Both theories at the point, as `stickslip theory --json` prints them.
    ///
    /// # Errors
    /// The library's errors.
    pub fn run(self, _budget: &Arc<Budget>) -> Result<TheoryReport, ApiError> {
        let params = self
            .experiment
            .params()
            .map_err(|e| ApiError::library(&e))?;
        TheoryReport::new(&params).map_err(|e| ApiError::library(&e))
    }
}
