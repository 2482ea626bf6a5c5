//! Failures of the stability analysis, with the numbers that tell what went wrong.

use thiserror::Error;

/// What can go wrong in [`crate::stability`]. Reaches callers as
/// [`crate::Error::Stability`].
#[derive(Debug, Clone, PartialEq, Error)]
#[non_exhaustive]
pub enum StabilityError {
    /// The Jacobian is not finite: a tangential release (μs > 1 and the drive's rate zero
    /// when the net force reaches the static limit), where the flow is not differentiable.
    #[error("the Jacobian is not finite after a tangential release at tau = {tau}")]
    NonFiniteJacobian {
        /// Time (dimensionless τ) of the release.
        tau: f64,
    },
}
