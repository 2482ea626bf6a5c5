//! The stability analysis of an experiment: its periodic orbits by Newton's method and its
//! Lyapunov exponents, with the model of its law ([`crate::stability::Dynamics`]: the exact
//! piecewise-linear model, or the Shockley model's stiff solver with its sensitivities).

use super::{DiodeModel, Experiment};
use crate::error::{Error, Result};
use crate::options::key::{Allowed, OptionKey};
use crate::params::{Params, State};
use crate::scan::Monitor;
use crate::stability::{
    Dynamics, LyapunovOptions, NewtonOptions, NonperiodicClassification, PeriodicOrbit,
};
use crate::steady::{periodic_orbit_from_steady_of, SelfExcitedOrbit, SteadyOptions, SteadyState};
use crate::Unsupported;
use std::ops::ControlFlow;

/// Drive periods between two reports to the monitor of a transient run.
const CHUNK: usize = 1000;

impl Experiment {
    /// The dimensionless parameters of the exact model (for tools of the PWL model alone;
    /// the stability analysis takes either law's [`Experiment::params`] with its
    /// [`Experiment::dynamics`]).
    ///
    /// # Errors
    /// [`Unsupported::StabilityNeedsPwl`] with Shockley diodes; a missing drive.
    pub fn exact_params(&self) -> Result<Params> {
        if self.diode_model() != DiodeModel::Pwl {
            return Err(Error::Unsupported(Unsupported::StabilityNeedsPwl));
        }
        if !self.friction_law().is_coulomb() {
            return Err(Error::Unsupported(Unsupported::SmoothFrictionLaw));
        }
        self.params()
    }

    /// A periodic orbit of the experiment by Newton's method on the p-fold strobe map
    /// ([`crate::stability::find_periodic_orbit`], or the Shockley model's
    /// [`crate::stability::ShockleyDynamics::find_periodic_orbit`]), with its Floquet
    /// multipliers.
    ///
    /// - `period: None`: the steady state reached from the initial state (with `steady`, no
    ///   spectrum, no Lyapunov measurement) gives the period p and the guess, its first
    ///   strobe ([`crate::steady::periodic_orbit_from_steady`]); `transient` is not used.
    ///   With Shockley diodes its tolerance is at least the stiff solver's rtol, to which
    ///   their strobe states repeat.
    /// - `period: Some(p)`: Newton's method starts from the state `transient` drive periods
    ///   after the initial state (0: the initial state itself, which can aim at an unstable
    ///   orbit). `monitor` is told the transient's progress in drive periods.
    ///
    /// ```
    /// use stickslip::experiment::Experiment;
    /// use stickslip::stability::{NewtonOptions, Stability};
    /// use stickslip::SteadyOptions;
    /// let e = Experiment::paper().with_w(0.7).unwrap().with_beta(1.2).unwrap();
    /// let orbit = e
    ///     .periodic_orbit(None, 0, &SteadyOptions::default(), &NewtonOptions::default(), &())
    ///     .unwrap();
    /// assert_eq!((orbit.period, orbit.stability), (1, Stability::Stable));
    /// ```
    ///
    /// # Errors
    /// A missing drive; [`Error::InvalidOption`] naming the period for a belt without a drive
    /// ([`Experiment::is_self_excited`]: its cycle has a period of its own, not a number of
    /// drive periods, [`Experiment::self_excited_orbit`]);
    /// [`crate::stability::StabilityError::NoPeriod`] when the steady state does not repeat;
    /// [`Error::InvalidParameter`] for p = 0; [`Error::Cancelled`]; the failures of
    /// [`crate::stability::find_periodic_orbit`].
    pub fn periodic_orbit(
        &self,
        period: Option<usize>,
        transient: usize,
        steady: &SteadyOptions,
        newton: &NewtonOptions,
        monitor: &dyn Monitor,
    ) -> Result<PeriodicOrbit> {
        if let (Some(p), true) = (period, self.is_self_excited()) {
            return Err(Error::InvalidOption {
                option: OptionKey::OrbitPeriod,
                value: p as f64,
                allowed: Allowed::Text(
                    "must be left out on a belt without a drive (beta = 0): the self-excited \
                     cycle has a period of its own, not a number of drive periods",
                ),
            });
        }
        let params = self.params()?;
        let dynamics = self.dynamics()?;
        let newton = newton.validate()?;
        match period {
            None => {
                // A motion that does not repeat is measured, so that the error says what its
                // exponent says.
                let measure = steady.lyapunov.or(Some(SteadyOptions::DEFAULT_LYAPUNOV));
                // A stiff solver's strobe states repeat only to about its rtol.
                let options = steady
                    .with_spectrum(false)
                    .with_lyapunov(measure)?
                    .with_tolerance(dynamics.repeat_tolerance(steady.tolerance))?;
                let settled = self.steady_with(&options)?;
                periodic_orbit_from_steady_of(dynamics.as_ref(), &params, &settled, &newton)
            }
            Some(p) => {
                if p == 0 {
                    return Err(Error::InvalidParameter {
                        name: "period",
                        value: 0.0,
                        allowed: "must be at least 1",
                    });
                }
                let guess = self.after_transient(dynamics.as_ref(), &params, transient, monitor)?;
                dynamics.find_periodic_orbit(&params, guess, p, &newton)
            }
        }
    }

    /// The orbit of a self-excited motion (β = 0 on a belt, [`Experiment::is_self_excited`]):
    /// the cycle `steady` settles on from the initial state, its period in τ (and seconds for
    /// a physical model) and its multipliers (1 and exactly 0 for a stick-slip cycle, 1 and
    /// the return map's derivative from the tangent dynamics for a pure-slip cycle), or
    /// steady sliding with the eigenvalues of its linearisation ([`SelfExcitedOrbit`]).
    ///
    /// ```
    /// use stickslip::experiment::Experiment;
    /// use stickslip::SteadyOptions;
    /// let e = Experiment::dimensionless(0.05, 1.0, 0.0).unwrap()
    ///     .with_mu_s(1.5).unwrap().with_vb(0.3).unwrap();
    /// let orbit = e.self_excited_orbit(&e.steady_options()).unwrap();
    /// let [trivial, other] = orbit.multipliers.unwrap();
    /// assert_eq!((trivial.re, other.re), (1.0, 0.0));
    /// assert!(orbit.cycle_period_tau.unwrap() > 0.0);
    /// ```
    ///
    /// # Errors
    /// As [`SelfExcitedOrbit::from_steady`]; as [`Experiment::steady_with`].
    pub fn self_excited_orbit(&self, steady: &SteadyOptions) -> Result<SelfExcitedOrbit> {
        let settled = self.steady_with(&steady.with_spectrum(false))?;
        self.self_excited_orbit_of(&settled)
    }

    /// [`Experiment::self_excited_orbit`] of a steady state this experiment settled on
    /// ([`Experiment::steady_with`]), for a caller that keeps the steady state too (to run
    /// its cycle again, [`crate::steady::self_excited_trace`]).
    ///
    /// # Errors
    /// As [`SelfExcitedOrbit::from_steady`] and [`SelfExcitedOrbit::with_tangent`].
    pub fn self_excited_orbit_of(&self, settled: &SteadyState) -> Result<SelfExcitedOrbit> {
        SelfExcitedOrbit::from_steady(settled, self.scales().map(|s| s.omega0))?
            .with_tangent(self.dynamics()?.as_ref(), &settled.params)
    }

    /// The state `periods` drive periods after the initial state, by the model's solver.
    fn after_transient(
        &self,
        dynamics: &dyn Dynamics,
        params: &Params,
        periods: usize,
        monitor: &dyn Monitor,
    ) -> Result<State> {
        let mut state = self.initial();
        let mut done = 0;
        while done < periods {
            let chunk = CHUNK.min(periods - done);
            // A solver per chunk, started at τ = 0 at a strobe: absolute times stay small.
            let mut solver = dynamics.solver(params, state)?;
            crate::solver::run_until(
                solver.as_mut(),
                chunk as f64 * params.drive_period(),
                |_| {},
            )?;
            state = solver.state();
            done += chunk;
            if monitor.step(done, periods) == ControlFlow::Break(()) {
                return Err(Error::Cancelled {
                    done,
                    total: periods,
                });
            }
        }
        Ok(state)
    }

    /// The Lyapunov exponents of the motion from the initial state, and what they say about
    /// it ([`crate::stability::lyapunov_exponents`], [`NonperiodicClassification`]).
    /// `monitor` is told the drive periods run (transient and measurement).
    ///
    /// ```
    /// use stickslip::experiment::Experiment;
    /// use stickslip::stability::{LyapunovOptions, NonperiodicVerdict};
    /// let e = Experiment::dimensionless(0.0, 0.33, 9.0).unwrap().with_mu_s(3.0).unwrap();
    /// let options = LyapunovOptions { transient_periods: 500, periods: 2000, ..Default::default() };
    /// let c = e.lyapunov(&options, &()).unwrap();
    /// assert_eq!(c.verdict, NonperiodicVerdict::Chaotic);
    /// ```
    ///
    /// With Shockley diodes the tangent dynamics are those of the stiff solver's computed
    /// solution ([`crate::stability::ShockleyDynamics::lyapunov_exponents`]).
    ///
    /// # Errors
    /// A missing drive; invalid options; [`Error::Cancelled`]; the failures of the
    /// measurement.
    pub fn lyapunov(
        &self,
        options: &LyapunovOptions,
        monitor: &dyn Monitor,
    ) -> Result<NonperiodicClassification> {
        let params = self.params()?;
        let exponents =
            self.dynamics()?
                .lyapunov_exponents(&params, self.initial(), options, monitor)?;
        let c = NonperiodicClassification::new(exponents, options.significance);
        Ok(if self.is_self_excited() {
            c.autonomous(options.significance)
        } else {
            c
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::options::Spelling;

    /// A period counts drive periods: on a belt without a drive the orbit's entry point
    /// refuses one, naming it, before any work; each front end spells it its way.
    #[test]
    fn a_belt_without_a_drive_refuses_a_period() {
        let e = Experiment::dimensionless(0.05, 1.0, 0.0)
            .and_then(|e| e.with_mu_s(1.5))
            .and_then(|e| e.with_vb(0.3))
            .unwrap();
        assert!(e.is_self_excited());
        let err = e
            .periodic_orbit(
                Some(2),
                0,
                &SteadyOptions::default(),
                &NewtonOptions::default(),
                &(),
            )
            .unwrap_err();
        assert_eq!(err.option(), Some(OptionKey::OrbitPeriod));
        let rest = ": must be left out on a belt without a drive (beta = 0): the self-excited \
                    cycle has a period of its own, not a number of drive periods";
        assert_eq!(
            err.render(Spelling::Flag),
            format!("invalid --period 2{rest}")
        );
        assert_eq!(err.to_string(), format!("invalid period = 2{rest}"));
    }
}
