//! What the stability tools ask of a model, whatever its law: [`Dynamics`].
//!
//! Periodic orbits, Lyapunov exponents, branches, bifurcation diagrams and basins are written
//! once against this trait. The exact PWL model ([`ExactDynamics`]: the closed-form segments
//! with their saltation matrices) and the Shockley model ([`super::ShockleyDynamics`]: the
//! stiff solver with its forward sensitivities) implement it; a new law implements it with
//! its own solver and gets every tool.

use super::lyapunov::{lyapunov_exponents_monitored, LyapunovExponents, LyapunovOptions};
use super::periodic_orbit::{find_periodic_orbit, NewtonOptions, PeriodicOrbit};
use super::smooth::ShockleyDynamics;
use super::strobe::{strobe_map, StrobeImage};
use super::tangent::{TangentRun, TangentSolver};
use crate::error::Result;
use crate::exact::ExactSolver;
use crate::params::{Parameter, Params, State};
use crate::scan::Monitor;
use crate::solver::Solver;

/// A model's dynamics as the stability tools use them: its solver, its strobe map with the
/// Jacobian, Newton's method for its periodic orbits, its tangent dynamics and Lyapunov
/// exponents. `params` are the dimensionless ζ, w, β, φ, μs of [`Params`] (a smooth law's ζ is
/// that of the linear resistance alone, and μs is not used).
pub trait Dynamics: Send + Sync + std::fmt::Debug {
    /// Whether this is the exact PWL model, whose orbits can stick at a strobe and whose
    /// branches can end at a grazing (the tools that follow those ask for it).
    fn is_exact(&self) -> bool;

    /// Whether orbits of this model can stick (rest with y' = vb on a stop of the friction
    /// law for a while, their strobe map's Jacobian singular there): the exact Coulomb model
    /// and the Stribeck and cubic laws of [`super::FrictionDynamics`]; not a smooth diode law.
    /// The tools that treat stuck strobes and the stops' edges ask for this, not for
    /// [`Dynamics::is_exact`] (which says the map is exact to rounding).
    fn sticks(&self) -> bool {
        self.is_exact()
    }

    /// A solver of the model from `initial` at τ = 0.
    ///
    /// # Errors
    /// Invalid parameters or state; what building the solver reports.
    fn solver(&self, params: &Params, initial: State) -> Result<Box<dyn Solver + Send>>;

    /// The p-fold strobe map with its Jacobian ([`super::strobe_map`]).
    ///
    /// # Errors
    /// Invalid parameters, state or p = 0; what the solver reports.
    fn strobe_map(&self, params: &Params, state: State, periods: usize) -> Result<StrobeImage>;

    /// The periodic orbit of period `period` near `guess` by Newton's method
    /// ([`super::find_periodic_orbit`]).
    ///
    /// # Errors
    /// As [`super::find_periodic_orbit`].
    fn find_periodic_orbit(
        &self,
        params: &Params,
        guess: State,
        period: usize,
        options: &NewtonOptions,
    ) -> Result<PeriodicOrbit>;

    /// The Lyapunov exponents of the motion from `initial` ([`super::lyapunov_exponents`]),
    /// `monitor` told the drive periods run.
    ///
    /// # Errors
    /// As [`super::lyapunov_exponents_monitored`].
    fn lyapunov_exponents(
        &self,
        params: &Params,
        initial: State,
        options: &LyapunovOptions,
        monitor: &dyn Monitor,
    ) -> Result<LyapunovExponents>;

    /// The tangent dynamics of the motion from `initial` at τ = 0.
    ///
    /// # Errors
    /// Invalid parameters or state; what building the solver reports.
    fn tangent(&self, params: &Params, initial: State) -> Result<Box<dyn TangentRun + Send>>;

    /// The relative distance within which strobe states are taken to repeat, for a tool whose
    /// tolerance with the exact model is `tolerance`: the exact model repeats to rounding, a
    /// stiff solver only to about its own relative tolerance.
    fn repeat_tolerance(&self, tolerance: f64) -> f64;

    /// The residual tolerance of Newton's method on the strobe map, for a tool whose
    /// tolerance with the exact model is `tolerance`: at least the relative accuracy of the
    /// computed map (the exact model's is rounding).
    fn map_tolerance(&self, tolerance: f64) -> f64 {
        tolerance
    }

    /// ∂P^p/∂λ of the p-fold strobe map at `state` by the parameter λ (the strobe time
    /// moving with w included), when the model has it from its own sensitivities; `None`
    /// when the caller should difference the map (the exact model: its map is exact to
    /// rounding, so a central difference serves).
    ///
    /// # Errors
    /// [`crate::Error::InvalidParameter`] for a parameter the model does not have; what the
    /// solver reports.
    fn parameter_derivative(
        &self,
        params: &Params,
        state: State,
        periods: usize,
        parameter: Parameter,
    ) -> Option<Result<[f64; 2]>> {
        let _ = (params, state, periods, parameter);
        None
    }

    /// The same dynamics with the strobe map of [`Dynamics::find_periodic_orbit`] integrated
    /// as the trajectories are (a solver started at the strobe with the trajectories' own
    /// options), for Newton settling of a steady state ([`crate::SteadyOptions::newton`]):
    /// its fixed point is the state from which the recorded cycle repeats. `None` (the
    /// default) when the model has no such map (the exact model settles by its own).
    fn settling(&self) -> Option<Box<dyn Dynamics>> {
        None
    }

    /// The period-1 orbit near `guess` for Newton settling, finished by a Newton step
    /// without evaluating the map where the residual is below `loose.0` (relative) and the
    /// orbit contracts by `loose.1` or faster, with the map's image of `guess` (see
    /// `ShockleyDynamics::settling_orbit`); `None` (the default) when the model has no such
    /// search.
    ///
    /// # Errors
    /// As [`Dynamics::find_periodic_orbit`].
    fn settling_orbit(
        &self,
        params: &Params,
        guess: State,
        options: &NewtonOptions,
        loose: (f64, f64),
    ) -> Option<Result<(PeriodicOrbit, StrobeImage)>> {
        let _ = (params, guess, options, loose);
        None
    }
}

/// The exact PWL model (Coulomb friction): [`crate::ExactSolver`] and the tools of
/// [`crate::stability`] as they are.
#[derive(Debug, Clone, Copy, Default, PartialEq, Eq)]
pub struct ExactDynamics;

impl Dynamics for ExactDynamics {
    fn is_exact(&self) -> bool {
        true
    }

    fn solver(&self, params: &Params, initial: State) -> Result<Box<dyn Solver + Send>> {
        crate::exact::check_coulomb(params)?;
        Ok(Box::new(ExactSolver::new(
            params.validate()?,
            State::new(initial.y, initial.v)?,
        )))
    }

    fn strobe_map(&self, params: &Params, state: State, periods: usize) -> Result<StrobeImage> {
        strobe_map(params, state, periods)
    }

    fn find_periodic_orbit(
        &self,
        params: &Params,
        guess: State,
        period: usize,
        options: &NewtonOptions,
    ) -> Result<PeriodicOrbit> {
        find_periodic_orbit(params, guess, period, options)
    }

    fn lyapunov_exponents(
        &self,
        params: &Params,
        initial: State,
        options: &LyapunovOptions,
        monitor: &dyn Monitor,
    ) -> Result<LyapunovExponents> {
        lyapunov_exponents_monitored(params, initial, options, monitor)
    }

    fn tangent(&self, params: &Params, initial: State) -> Result<Box<dyn TangentRun + Send>> {
        crate::exact::check_coulomb(params)?;
        Ok(Box::new(TangentSolver::new(
            params.validate()?,
            State::new(initial.y, initial.v)?,
        )))
    }

    fn repeat_tolerance(&self, tolerance: f64) -> f64 {
        tolerance
    }

    /// Exact for the belt speed vb, from the pieces ([`super::strobe_map_parameter_derivative`]:
    /// a difference would start a state stuck to the belt sliding at vb ± h); `None`, a
    /// central difference of the exact map, for the others.
    fn parameter_derivative(
        &self,
        params: &Params,
        state: State,
        periods: usize,
        parameter: Parameter,
    ) -> Option<Result<[f64; 2]>> {
        (parameter == Parameter::Vb).then(|| {
            super::sensitivity::strobe_map_parameter_derivative(params, state, periods, parameter)
        })
    }
}

impl Dynamics for ShockleyDynamics {
    fn is_exact(&self) -> bool {
        false
    }

    fn solver(&self, params: &Params, initial: State) -> Result<Box<dyn Solver + Send>> {
        Ok(Box::new(self.plain_solver(params, initial)?))
    }

    fn strobe_map(&self, params: &Params, state: State, periods: usize) -> Result<StrobeImage> {
        ShockleyDynamics::strobe_map(self, params, state, periods)
    }

    fn find_periodic_orbit(
        &self,
        params: &Params,
        guess: State,
        period: usize,
        options: &NewtonOptions,
    ) -> Result<PeriodicOrbit> {
        ShockleyDynamics::find_periodic_orbit(self, params, guess, period, options)
    }

    fn lyapunov_exponents(
        &self,
        params: &Params,
        initial: State,
        options: &LyapunovOptions,
        monitor: &dyn Monitor,
    ) -> Result<LyapunovExponents> {
        ShockleyDynamics::lyapunov_exponents(self, params, initial, options, monitor)
    }

    fn tangent(&self, params: &Params, initial: State) -> Result<Box<dyn TangentRun + Send>> {
        Ok(Box::new(ShockleyDynamics::tangent(self, params, initial)?))
    }

    /// The solver's relative tolerance, or `tolerance` when that is larger (the steady-state
    /// search of a Shockley experiment takes the same, [`crate::Experiment::steady_options`]).
    fn repeat_tolerance(&self, tolerance: f64) -> f64 {
        tolerance.max(self.options().rtol)
    }

    /// The map's relative tolerance ([`ShockleyDynamics::map_options`]), or `tolerance` when
    /// that is larger.
    fn map_tolerance(&self, tolerance: f64) -> f64 {
        tolerance.max(self.map_options().rtol)
    }

    /// From the forward sensitivities (a difference of the computed map would see its jumps,
    /// of the order of the solver's tolerance, divided by the step).
    fn parameter_derivative(
        &self,
        params: &Params,
        state: State,
        periods: usize,
        parameter: Parameter,
    ) -> Option<Result<[f64; 2]>> {
        Some(self.strobe_parameter_derivative(params, state, periods, parameter))
    }

    /// The map at the trajectories' options (the sensitivities do not steer the steps, so
    /// the map's states are those of a plain solver from the same strobe, to the bit).
    fn settling(&self) -> Option<Box<dyn Dynamics>> {
        let options = *self.options();
        Some(Box::new(self.clone().with_map_options(options).ok()?))
    }

    fn settling_orbit(
        &self,
        params: &Params,
        guess: State,
        options: &NewtonOptions,
        loose: (f64, f64),
    ) -> Option<Result<(PeriodicOrbit, StrobeImage)>> {
        Some(ShockleyDynamics::settling_orbit(
            self, params, guess, options, loose,
        ))
    }
}
