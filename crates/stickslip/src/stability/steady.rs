//! The largest Lyapunov exponent of a steady motion, however it repeats or not.

use super::lyapunov::{lyapunov_exponents, Estimate, LyapunovOptions};
use super::periodic_orbit::{periodic_orbit_from_steady, NewtonOptions};
use super::StabilityError;
use crate::error::{Error, Result};
use crate::steady::SteadyState;

/// The largest Lyapunov exponent of a steady motion of the exact model.
///
/// - A motion that repeats (period p): ln|μ₁|/(pT) of its periodic orbit, refined by Newton's
///   method from the recorded cycle ([`periodic_orbit_from_steady`]), with μ₁ the Floquet
///   multiplier of largest modulus. The value is exact to rounding, so its error is 0; it is
///   −∞ when both multipliers vanish, and 0 for rest (μ = 1: a continuum of rest positions).
///   Should Newton's method fail, the exponent is measured as below.
/// - A motion that does not repeat: its measurement [`SteadyState::lyapunov`] when it has
///   one, else a measurement from its final state with `options`
///   ([`super::lyapunov_exponents`]), with the error from its blocks.
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
    let params = &steady.params;
    if steady.period.is_some() {
        if let Ok(orbit) = periodic_orbit_from_steady(params, steady, &NewtonOptions::default()) {
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
    match lyapunov_exponents(params, steady.final_state(), options) {
        Ok(exponents) => Ok(Some(exponents.largest)),
        Err(Error::Stability(StabilityError::NonFiniteJacobian { .. })) => Ok(None),
        Err(e) => Err(e),
    }
}
