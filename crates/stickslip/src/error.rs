//! Typed errors of the library.

use thiserror::Error;

/// Everything that can go wrong in the library, with the offending value in the variant.
#[derive(Debug, Clone, PartialEq, Error)]
#[non_exhaustive]
pub enum Error {
    /// A parameter is NaN, infinite or outside its allowed range.
    #[error("invalid {name} = {value}: {allowed}")]
    InvalidParameter {
        /// Name of the parameter as the user knows it (e.g. `zeta`, `L`).
        name: &'static str,
        /// The rejected value.
        value: f64,
        /// What is allowed, in words (e.g. "must be finite and >= 0").
        allowed: &'static str,
    },
    /// A requested time lies before the solver's current time.
    #[error("requested time {requested} lies before the solver's current time {current}")]
    TimeBeforeCurrent {
        /// The requested time (dimensionless τ).
        requested: f64,
        /// The solver's current time (dimensionless τ).
        current: f64,
    },
    /// An event search could not bracket or converge (a numerical failure, reported not hidden).
    #[error("event search failed at tau = {tau}: {reason}")]
    EventSearch {
        /// Time (dimensionless τ) at which the failure happened.
        tau: f64,
        /// What failed.
        reason: &'static str,
    },
    /// A stiff integrator could not continue (step size underflow, too many failures).
    #[error("integrator failed at tau = {tau}: {reason}")]
    Integrator {
        /// Time (dimensionless τ) at which the failure happened.
        tau: f64,
        /// What failed.
        reason: String,
    },
    /// A quantity requested from a theory does not exist for these parameters.
    #[error("{what} does not exist: {reason}")]
    NoSolution {
        /// What was asked for.
        what: &'static str,
        /// Why it does not exist.
        reason: String,
    },
    /// A long computation (a sweep or a phase diagram) was stopped by its caller.
    #[error("cancelled after {done} of {total} points")]
    Cancelled {
        /// Points finished when the computation stopped.
        done: usize,
        /// Points requested.
        total: usize,
    },
    /// A stability analysis failed (Newton's method, a non-finite Jacobian, …).
    #[error(transparent)]
    Stability(#[from] crate::stability::StabilityError),
}

/// Result alias of the library.
pub type Result<T, E = Error> = std::result::Result<T, E>;

/// Check that `value` is finite; `allowed` is the message shown otherwise.
pub(crate) fn check(
    name: &'static str,
    value: f64,
    ok: bool,
    allowed: &'static str,
) -> Result<f64> {
    if value.is_finite() && ok {
        Ok(value)
    } else {
        Err(Error::InvalidParameter {
            name,
            value,
            allowed,
        })
    }
}
