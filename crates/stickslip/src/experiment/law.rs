//! The law of an experiment's dissipative element, the axis that decides its solver and its
//! stability tools: [`Law`].

use super::DiodeModel;
use crate::cancel::Cancel;
use crate::error::Result;
use crate::exact::ExactSolver;
use crate::friction_solver::FrictionSolver;
use crate::params::{Params, State};
use crate::shockley::{DiodeLaw, ShockleyModel, ShockleyOptions, ShockleySolver};
use crate::solver::Solver;
use crate::stability::{Dynamics, ExactDynamics, ShockleyDynamics};
use serde::{Deserialize, Serialize};

/// The law of the dissipative element in y'' + 2ζ y' + y + D(y') = β cos(w τ + φ), in
/// dimensionless form: the diodes of a circuit, or the friction of a mechanical oscillator.
///
/// The law decides how the experiment is solved ([`Law::solver`]) and which stability tools
/// serve it ([`Law::dynamics`]): the exact solver and the closed-form tangent dynamics for the
/// PWL law, the stiff solver ([`crate::stiff`]) and its forward sensitivities for a smooth
/// law. A new law is a variant here, with its solver and its [`Dynamics`].
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Law {
    /// The paper's piecewise-linear law, sgn(y') with the static ratio μs (PWL diodes, Coulomb
    /// friction): the exact solver. A mechanical oscillator's Stribeck or cubic friction law
    /// ([`Params::law`]) is solved by [`FrictionSolver`]: its slips on the smooth integrator,
    /// its stops exactly.
    Pwl,
    /// The Shockley law of two anti-parallel diodes, D(v) = a·asinh(v/ε) + r·v: the stiff
    /// solver.
    Shockley(DiodeLaw),
}

impl Law {
    /// The user's name of the law ([`DiodeModel`]: `pwl`, `shockley`).
    pub fn model(&self) -> DiodeModel {
        match self {
            Law::Pwl => DiodeModel::Pwl,
            Law::Shockley(_) => DiodeModel::Shockley,
        }
    }

    /// A solver of the model with `params` from `initial` at τ = 0: the exact solver, or the
    /// stiff solver with `options`; either checks `cancel`.
    ///
    /// # Errors
    /// Invalid parameters or state; what building the solver reports.
    pub fn solver(
        &self,
        params: Params,
        initial: State,
        options: ShockleyOptions,
        cancel: Cancel,
    ) -> Result<Box<dyn Solver + Send>> {
        let params = params.validate()?;
        let initial = State::new(initial.y, initial.v)?;
        match self {
            // A Stribeck or cubic friction law: slips on the smooth integrator, stops exact.
            Law::Pwl if !params.law.is_coulomb() => Ok(Box::new(FrictionSolver::with_cancel(
                params, initial, cancel,
            )?)),
            Law::Pwl => Ok(ExactSolver::boxed(params, initial, cancel)),
            Law::Shockley(law) => Ok(Box::new(ShockleySolver::with_cancel(
                ShockleyModel::new(params, *law)?,
                initial,
                options,
                cancel,
            )?)),
        }
    }

    /// The stability tools of the model ([`Dynamics`]), a smooth law's integrated with
    /// `options` and checking `cancel`.
    ///
    /// # Errors
    /// Invalid options.
    pub fn dynamics(&self, options: ShockleyOptions, cancel: Cancel) -> Result<Box<dyn Dynamics>> {
        Ok(match self {
            Law::Pwl => Box::new(ExactDynamics),
            Law::Shockley(law) => {
                Box::new(ShockleyDynamics::new(*law, options)?.with_cancel(cancel))
            }
        })
    }
}
