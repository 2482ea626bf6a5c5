//! Steady-state analysis: convergence to a cycle, spectra, motion classes, sweeps and maps.
//!
//! Everything here is written against the [`Solver`] trait, so it works with the exact
//! piecewise-linear solver and with any other solver of the same model.
//!
//! - [`steady_state`] runs a solver until its stroboscopic map (the state once per drive
//!   period, at τ = kT, T = 2π/w) repeats with a period p ≤ [`SteadyOptions::max_period`], then
//!   records p whole periods: the exact event log, the extremes of y, and (optionally) samples
//!   of the dense output for the [`Spectrum`].
//! - [`MotionClass`]: sliding, periodic stick, non-periodic stick or static (the paper's
//!   Fig. 6), decided from the event log of the recorded cycle ([`classify()`]).
//! - [`Spectrum`]: amplitudes and phases of the drive harmonics of y by a real FFT over whole
//!   periods (no window, no leakage).
//!
//! Sweeps and grids of steady states are in [`crate::scan`]. Solvers are made by a
//! [`SolverFactory`] (any `Fn(Params, State) -> Result<Box<dyn Solver + Send>>` that is
//! `Sync`, or an experiment's [`crate::experiment::ExperimentFactory`]); [`exact_solver`] is
//! the factory of the exact solver.

mod classify;
mod cycle;
mod cycle_trace;
mod exponent;
pub(crate) mod extremes;
mod newton;
pub mod options;
mod record;
mod report;
pub mod self_excited;
mod self_excited_orbit;
mod spectrum;
mod state;

pub use classify::{classify, Classification, MotionClass, STATIC_GAIN};
pub(crate) use cycle::settle_from;
pub use cycle::{check_horizon, steady_state, steady_state_from};
pub use cycle_trace::self_excited_trace;
pub(crate) use exponent::settle_with_exponent;
pub use exponent::{
    periodic_orbit_from_steady, periodic_orbit_from_steady_of, steady_exponent, steady_exponent_of,
    steady_state_with_exponent, SEARCH_BEFORE_MEASURING,
};
pub use options::SteadyOptions;
pub use report::SteadyReport;
pub use self_excited::{self_excited_state, CycleSection, SelfExcited, SlidingStability};
pub use self_excited_orbit::{pure_slip_multiplier, SelfExcitedOrbit};
pub use spectrum::{Harmonic, Spectrum};
pub use state::SteadyState;

use crate::cancel::Cancel;
use crate::error::Result;
use crate::exact::ExactSolver;
use crate::params::{Params, State};
use crate::solver::Solver;
use crate::stability::Dynamics;

/// Something that builds a solver for given parameters and initial state at τ = 0.
///
/// Implemented for every `Fn(Params, State) -> Result<Box<dyn Solver + Send>> + Sync`, so a
/// closure or [`exact_solver`] can be passed wherever a factory is asked for. Sweeps and phase
/// diagrams need a factory rather than a solver because every step or grid point starts a new
/// solver (possibly on another thread).
pub trait SolverFactory: Sync {
    /// A solver for `params` starting from `initial` at τ = 0.
    ///
    /// # Errors
    /// Whatever building the solver can report (invalid parameters).
    fn make(&self, params: Params, initial: State) -> Result<Box<dyn Solver + Send>>;

    /// A solver for the steady-state search of a self-excited belt: [`SolverFactory::make`]'s
    /// unless the factory has a cheaper one of the same model and tolerance (an experiment's:
    /// the slips of a smooth friction law on the explicit integrator,
    /// [`crate::friction_solver::SlipIntegrator::Explicit`]).
    ///
    /// # Errors
    /// As [`SolverFactory::make`].
    fn make_searching(&self, params: Params, initial: State) -> Result<Box<dyn Solver + Send>> {
        self.make(params, initial)
    }

    /// The token the solvers it makes check, which the computations on them check too
    /// between their own steps (the Lyapunov measurement of a motion that does not repeat,
    /// say). [`Cancel::never`] unless the factory carries one ([`crate::Experiment::factory`]).
    fn cancel(&self) -> Cancel {
        Cancel::never()
    }

    /// The stability tools of the model its solvers follow when they are not exact (a smooth
    /// law's tangent dynamics), with which the steady-state search measures the Lyapunov
    /// exponents of a motion that does not repeat ([`SteadyOptions::lyapunov`]). `None` (the
    /// default): only the motions of exact solvers are measured, by the exact tangent
    /// dynamics.
    fn smooth_dynamics(&self) -> Option<Box<dyn Dynamics>> {
        None
    }
}

impl<F> SolverFactory for F
where
    F: Fn(Params, State) -> Result<Box<dyn Solver + Send>> + Sync,
{
    fn make(&self, params: Params, initial: State) -> Result<Box<dyn Solver + Send>> {
        self(params, initial)
    }
}

/// The factory of the exact solver: validates `params` and starts an [`ExactSolver`].
///
/// # Errors
/// [`crate::Error::InvalidParameter`] when `params` or `initial` is invalid.
pub fn exact_solver(params: Params, initial: State) -> Result<Box<dyn Solver + Send>> {
    let params = params.validate()?;
    let initial = State::new(initial.y, initial.v)?;
    if !params.law.is_coulomb() {
        return Err(crate::Error::Unsupported(
            crate::Unsupported::SmoothFrictionLaw,
        ));
    }
    Ok(Box::new(ExactSolver::new(params, initial)))
}
