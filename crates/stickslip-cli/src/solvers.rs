//! The solver a model asks for: exact (PWL diode / Coulomb friction) or stiff (Shockley).

use crate::model::{DiodeModel, Model, ShockleySettings};
use crate::output::usage;
use anyhow::Result;
use stickslip::shockley::{DiodePair, ShockleyCircuit, ShockleyModel, ShockleyOptions};
use stickslip::{ExactSolver, ShockleySolver, Solver, System};

/// A boxed solver for `model`, starting from its initial state at τ = 0.
pub fn solver_for(model: &Model) -> Result<Box<dyn Solver + Send>> {
    match model.diode {
        DiodeModel::Pwl => Ok(Box::new(ExactSolver::new(model.params, model.initial))),
        DiodeModel::Shockley => {
            let shockley = shockley_model(model)?;
            Ok(Box::new(ShockleySolver::new(
                shockley,
                model.initial,
                ShockleyOptions::default(),
            )?))
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
            // ζ of the PWL model is not used: the Shockley circuit has its own, from R alone.
            let circuit = shockley_circuit(model)?;
            Ok(Box::new(move |params: stickslip::Params, initial| {
                let m = circuit.model_dimensionless(params.w, params.beta, params.phi)?;
                let solver = ShockleySolver::new(m, initial, ShockleyOptions::default())?;
                Ok(Box::new(solver) as Box<dyn Solver + Send>)
            }))
        }
    }
}

/// The Shockley circuit of `model`: its L, C and R, its U_t as the reference voltage (so β
/// means the same drive as with the PWL diode), and the `--diode-*` parts; the PWL R_D is not
/// used (the diode law has its own R_s).
pub fn shockley_circuit(model: &Model) -> Result<ShockleyCircuit> {
    let Some(System::Circuit(circuit)) = model.system else {
        usage!("the Shockley diode model needs a circuit description (e.g. --preset paper)");
    };
    let ShockleySettings {
        saturation_current,
        emission,
        series_resistance,
        temperature_c,
    } = model.shockley;
    let diode = DiodePair::new(
        saturation_current,
        emission,
        series_resistance,
        temperature_c,
    )?;
    Ok(ShockleyCircuit::from_circuit(&circuit, diode)?)
}

/// The dimensionless Shockley model of `model` (ζ_R from R alone; w, β, φ as given).
pub fn shockley_model(model: &Model) -> Result<ShockleyModel> {
    let p = &model.params;
    Ok(shockley_circuit(model)?.model_dimensionless(p.w, p.beta, p.phi)?)
}
