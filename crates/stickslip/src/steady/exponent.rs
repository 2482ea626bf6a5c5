//! The stability of a steady motion: its periodic orbit refined by Newton's method, and its
//! largest Lyapunov exponent, however it repeats or not. The steady-state search builds on
//! [`crate::stability`] (Newton's method settles it, the Lyapunov exponents classify the
//! motions that do not repeat); what joins the two is here, so that `stability` does not
//! depend on `steady`.

use super::{settle_from, MotionClass, SolverFactory, SteadyOptions, SteadyState};
use crate::error::{Error, Result};
use crate::params::{Params, State};
use crate::stability::{
    lyapunov_exponents, Dynamics, Estimate, ExactDynamics, LyapunovExponents, LyapunovOptions,
    NewtonOptions, NonperiodicClassification, NonperiodicVerdict, PeriodicOrbit, StabilityError,
};

/// The periodic orbit of a settled steady state (its period and first recorded strobe as the
/// guess), refined by [`crate::stability::find_periodic_orbit`].
///
/// # Errors
/// [`StabilityError::NoPeriod`] when the steady state has no period; as
/// [`crate::stability::find_periodic_orbit`].
pub fn periodic_orbit_from_steady(
    params: &Params,
    steady: &SteadyState,
    options: &NewtonOptions,
) -> Result<PeriodicOrbit> {
    periodic_orbit_from_steady_of(&ExactDynamics, params, steady, options)
}

/// [`periodic_orbit_from_steady`] on the model `dynamics` (a steady state of the same model).
///
/// # Errors
/// As [`periodic_orbit_from_steady`].
pub fn periodic_orbit_from_steady_of(
    dynamics: &dyn Dynamics,
    params: &Params,
    steady: &SteadyState,
    options: &NewtonOptions,
) -> Result<PeriodicOrbit> {
    let (Some(period), Some(&guess)) = (steady.period, steady.strobes.first()) else {
        let measured = steady.lyapunov.as_ref();
        return Err(StabilityError::NoPeriod {
            periods_run: steady.periods_to_settle,
            exponent: measured.map(|c| {
                (
                    c.exponents.largest.per_tau,
                    c.exponents.largest.error_per_tau,
                )
            }),
            verdict: measured.map(|c| c.verdict),
        }
        .into());
    };
    dynamics.find_periodic_orbit(params, guess, period, options)
}

/// The largest Lyapunov exponent of a steady motion of the exact model.
///
/// - A motion that repeats (period p): ln|μ₁|/(pT) of its periodic orbit, refined by Newton's
///   method from the recorded cycle ([`periodic_orbit_from_steady`]), with μ₁ the Floquet
///   multiplier of largest modulus. The value is exact to rounding, so its error is 0; it is
///   −∞ when both multipliers vanish, and 0 for rest (μ = 1: a continuum of rest positions).
///   Should Newton's method fail, the exponent is measured as below.
/// - A motion that does not repeat: its measurement [`SteadyState::lyapunov`] when it has
///   one, else a measurement from its final state with `options`
///   ([`crate::stability::lyapunov_exponents`]), with the error from its blocks.
///
/// `None` when the measurement meets a tangential release, where the flow has no derivative.
///
/// ```
/// use stickslip::stability::{steady_exponent, LyapunovOptions};
/// use stickslip::steady::{exact_solver, steady_state_from, SteadyOptions};
/// use stickslip::{Params, State};
/// let params = Params::new(0.0468, 0.7, 1.2).unwrap();
/// let steady = steady_state_from(&exact_solver, &params, State::default(), &SteadyOptions::default()).unwrap();
/// let lambda = steady_exponent(&steady, &LyapunovOptions::default()).unwrap().unwrap();
/// assert!(lambda.per_tau < 0.0 && lambda.error_per_tau == 0.0);
/// ```
///
/// # Errors
/// Invalid options; whatever the solver reports.
pub fn steady_exponent(
    steady: &SteadyState,
    options: &LyapunovOptions,
) -> Result<Option<Estimate>> {
    steady_exponent_of(&ExactDynamics, steady, options)
}

/// [`steady_exponent`] on the model `dynamics` (a steady state of the same model): with a
/// smooth law ([`crate::stability::ShockleyDynamics`]) the orbit's Floquet multipliers and the
/// tangent dynamics are those of the stiff solver's computed solution, so the exponent of a
/// periodic orbit is exact to the solver's tolerance rather than to rounding (its stated
/// error is still 0: it is not a statistical estimate).
///
/// # Errors
/// As [`steady_exponent`].
pub fn steady_exponent_of(
    dynamics: &dyn Dynamics,
    steady: &SteadyState,
    options: &LyapunovOptions,
) -> Result<Option<Estimate>> {
    let params = &steady.params;
    if steady.period.is_some() {
        if let Ok(orbit) =
            periodic_orbit_from_steady_of(dynamics, params, steady, &NewtonOptions::default())
        {
            let per_tau = orbit.exponent();
            return Ok(Some(Estimate {
                per_tau,
                error_per_tau: 0.0,
                per_period: per_tau * orbit.drive_period,
                error_per_period: 0.0,
            }));
        }
    } else if let Some(measured) = &steady.lyapunov {
        return Ok(Some(measured.exponents.largest));
    }
    match measure_from(dynamics, params, steady.final_state(), options) {
        Ok(exponents) => Ok(Some(exponents.largest)),
        Err(Error::Stability(StabilityError::NonFiniteJacobian { .. })) => Ok(None),
        Err(e) => Err(e),
    }
}

/// Periods the strobe search of [`steady_state_with_exponent`] runs before a motion that has
/// not repeated is measured.
pub const SEARCH_BEFORE_MEASURING: usize = 300;

/// The steady state reached from `initial` and its largest Lyapunov exponent, for maps of
/// the exponent: the result of [`crate::steady::steady_state_from`] followed by
/// [`steady_exponent`], except that a motion which has not repeated after
/// [`SEARCH_BEFORE_MEASURING`] drive periods of the search is measured there (with
/// `options.lyapunov`, normally sequential: [`crate::stability::lyapunov`]) and, when its
/// verdict is decided (chaotic or contracting beyond the stated significance), is reported so
/// at once instead of running the rest of `options.max_periods` first: a chaotic motion as
/// [`crate::MotionClass::Chaotic`], a contracting one with the class of the shortened search
/// (non-periodic: it has not reached its orbit yet), each with the record of the shortened
/// search and the measured exponent with its error. Every other motion gets exactly the full
/// search's result. The shortcut differs from the full search in the verdict only for a
/// chaotic transient that ends in a periodic motion between the two lengths (or the reverse);
/// in the class also where a contracting motion reaches its orbit between the two lengths
/// (the full search then calls it periodic, with the exact exponent of its orbit).
///
/// The solvers from `factory` must be exact ([`crate::Solver::is_exact`]; a map of a smooth
/// law's exponents, [`crate::scan::Grid::lyapunov`], takes its law's dynamics); without
/// `options.lyapunov` this is the full search and [`steady_exponent`] with
/// `fallback` for motions that do not repeat.
///
/// # Errors
/// As [`crate::steady::steady_state_from`] and [`steady_exponent`].
pub fn steady_state_with_exponent<F: SolverFactory + ?Sized>(
    factory: &F,
    params: &Params,
    initial: State,
    options: &SteadyOptions,
    fallback: &LyapunovOptions,
) -> Result<(SteadyState, Option<Estimate>)> {
    settle_with_exponent(
        factory,
        &ExactDynamics,
        params,
        initial,
        &options.validate()?,
        fallback,
    )
}

/// The Lyapunov exponents of the motion from `initial` by `dynamics`: the exact model's by
/// [`lyapunov_exponents`] itself (unmonitored), any other's by its own tangent dynamics.
fn measure_from(
    dynamics: &dyn Dynamics,
    params: &Params,
    initial: State,
    options: &LyapunovOptions,
) -> Result<LyapunovExponents> {
    if dynamics.is_exact() {
        lyapunov_exponents(params, initial, options)
    } else {
        dynamics.lyapunov_exponents(params, initial, options, &())
    }
}

/// [`steady_state_with_exponent`] with `options` already validated (a map's points share
/// them: they are checked once, when the map is built), on the model `dynamics` whose
/// solvers `factory` makes (the exact one's, or a smooth law's: a Shockley map of exponents).
pub(crate) fn settle_with_exponent<F: SolverFactory + ?Sized>(
    factory: &F,
    dynamics: &dyn Dynamics,
    params: &Params,
    initial: State,
    options: &SteadyOptions,
    fallback: &LyapunovOptions,
) -> Result<(SteadyState, Option<Estimate>)> {
    let full = |options: &SteadyOptions| -> Result<(SteadyState, Option<Estimate>)> {
        let steady = settle_from(factory, params, initial, options)?;
        let exponent = steady_exponent_of(dynamics, &steady, fallback)?;
        Ok((steady, exponent))
    };
    let Some(measure) = options.lyapunov else {
        return full(options);
    };
    if options.max_periods <= SEARCH_BEFORE_MEASURING {
        return full(options);
    }
    let short = SteadyOptions {
        max_periods: SEARCH_BEFORE_MEASURING,
        lyapunov: None,
        ..*options
    };
    let mut steady = settle_from(factory, params, initial, &short)?;
    if steady.period.is_some() {
        // The search is causal: the full one finds the same cycle at the same strobe.
        let exponent = steady_exponent_of(dynamics, &steady, fallback)?;
        return Ok((steady, exponent));
    }
    match measure_from(dynamics, params, steady.final_state(), &measure) {
        Ok(exponents) => {
            let c = NonperiodicClassification::new(exponents, measure.significance);
            let decided = matches!(
                c.verdict,
                NonperiodicVerdict::Chaotic | NonperiodicVerdict::Contracting
            );
            if decided {
                let largest = c.exponents.largest;
                if c.verdict == NonperiodicVerdict::Chaotic {
                    steady.class = MotionClass::Chaotic;
                }
                steady.lyapunov = Some(c);
                return Ok((steady, Some(largest)));
            }
            full(options)
        }
        Err(Error::Stability(StabilityError::NonFiniteJacobian { .. })) => full(options),
        Err(e) => Err(e),
    }
}
