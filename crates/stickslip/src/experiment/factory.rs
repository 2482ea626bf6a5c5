//! The solver factory of an experiment: which solver (exact or stiff) and which stability
//! tools its law asks for.

use super::Law;
use crate::cancel::Cancel;
use crate::error::Result;
use crate::friction_solver::{FrictionSolver, SlipIntegrator};
use crate::params::{Params, State};
use crate::physical::{Circuit, Diode};
use crate::shockley::ShockleyOptions;
use crate::solver::Solver;
use crate::stability::{Dynamics, FrictionDynamics};
use crate::steady::SolverFactory;

/// The solver factory of an [`Experiment`](super::Experiment): the exact solver, or the stiff solver of the
/// experiment's Shockley circuit (ζ of the parameters is then ζ_R).
#[derive(Debug, Clone)]
pub struct ExperimentFactory {
    pub(super) circuit: Option<Circuit>,
    pub(super) options: ShockleyOptions,
    pub(super) cancel: Cancel,
}

/// The law of `circuit` (Shockley diodes), or the PWL law without one.
pub(super) fn law_of(circuit: Option<&Circuit>) -> Result<Law> {
    match circuit.map(|c| (c, c.diode)) {
        Some((c, Diode::Shockley(d))) => Ok(Law::Shockley(
            d.pair.law(d.reference_voltage, c.impedance())?,
        )),
        _ => Ok(Law::Pwl),
    }
}

impl ExperimentFactory {
    /// The law its solvers follow ([`Law`]).
    ///
    /// # Errors
    /// As [`Experiment::law`](super::Experiment::law).
    pub fn law(&self) -> Result<Law> {
        law_of(self.circuit.as_ref())
    }

    /// The stability tools of the model its solvers solve.
    ///
    /// # Errors
    /// As [`Experiment::law`](super::Experiment::law).
    pub fn dynamics(&self) -> Result<Box<dyn Dynamics>> {
        self.law()?.dynamics(self.options, self.cancel.clone())
    }
}

impl SolverFactory for ExperimentFactory {
    fn make(&self, params: Params, initial: State) -> Result<Box<dyn Solver + Send>> {
        let params = params.validate()?;
        self.law()?
            .solver(params, initial, self.options, self.cancel.clone())
    }

    /// A smooth friction law's slips on the explicit integrator; else [`SolverFactory::make`].
    fn make_searching(&self, params: Params, initial: State) -> Result<Box<dyn Solver + Send>> {
        let params = params.validate()?;
        match self.law()? {
            Law::Pwl if !params.law.is_coulomb() => Ok(Box::new(FrictionSolver::with_integrator(
                params,
                initial,
                SlipIntegrator::Explicit,
                self.cancel.clone(),
            )?)),
            _ => self.make(params, initial),
        }
    }

    fn cancel(&self) -> Cancel {
        self.cancel.clone()
    }

    /// A smooth law's [`Dynamics`] (its solvers are not exact): a Shockley circuit's, and
    /// with the PWL law those of the friction solver ([`FrictionDynamics`]), whose solvers
    /// `make` for a Stribeck or cubic law, the only ones of the PWL law that are not exact
    /// (the steady-state search asks only then). So `steady` measures the Lyapunov exponents
    /// of such a motion that does not repeat by the tangent dynamics that `lyapunov`,
    /// `bifurcation` and `basins` use, and classes it as they do. (The friction tools have no
    /// strobe map for Newton settling, [`Dynamics::settling`]: their steady states settle by
    /// repetition, as before.)
    fn smooth_dynamics(&self) -> Option<Box<dyn Dynamics>> {
        match self.law() {
            Ok(Law::Pwl) => Some(Box::new(
                FrictionDynamics::new().with_cancel(self.cancel.clone()),
            )),
            Err(_) => None,
            Ok(_) => self.dynamics().ok(),
        }
    }
}
