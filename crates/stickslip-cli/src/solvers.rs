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

/// Something that starts solvers of `model`'s diode law for any parameters and initial state,
/// for commands that run many (sweeps, phase diagrams).
pub type Factory = Box<
    dyn Fn(stickslip::Params, stickslip::State) -> stickslip::Result<Box<dyn Solver + Send>> + Sync,
>;

/// The solver factory for `model`'s diode law.
pub fn factory_for(model: &Model) -> Result<Factory> {
    match model.diode {
        DiodeModel::Pwl => Ok(Box::new(stickslip::steady::exact_solver)),
        DiodeModel::Shockley => {
            anyhow::bail!("--model shockley is not available in this version")
        }
    }
}
