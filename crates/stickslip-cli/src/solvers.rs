//! The solver a model asks for: exact (PWL diode / Coulomb friction) or stiff (Shockley).

use crate::model::{DiodeModel, Model};
use anyhow::Result;
use stickslip::{ExactSolver, Solver};

/// A boxed solver for `model`, starting from its initial state at τ = 0.
pub fn solver_for(model: &Model) -> Result<Box<dyn Solver + Send>> {
    match model.diode {
        DiodeModel::Pwl => Ok(Box::new(ExactSolver::new(model.params, model.initial))),
        DiodeModel::Shockley => {
            anyhow::bail!("--model shockley is not available in this version")
        }
    }
}
