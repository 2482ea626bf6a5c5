//! Failures of the stability analysis, with the numbers that tell what went wrong.

use super::verdict::NonperiodicVerdict;
use thiserror::Error;

/// What a measured exponent says about a motion that found no period, for
/// [`StabilityError::NoPeriod`]'s message.
fn said(exponent: &Option<(f64, f64)>, verdict: &Option<NonperiodicVerdict>) -> String {
    let (Some((lambda, error)), Some(verdict)) = (exponent, verdict) else {
        return String::new();
    };
    let meaning = match verdict {
        NonperiodicVerdict::Chaotic => "chaotic: nearby motions separate",
        NonperiodicVerdict::Contracting => {
            "contracting: the motion settles onto a periodic motion, too slowly for the search \
             or of a longer period than it looks for"
        }
        NonperiodicVerdict::QuasiPeriodic => {
            "neither growing nor contracting within its error: a torus, or a neutral family"
        }
        NonperiodicVerdict::LimitCycle => {
            "a limit cycle of an autonomous motion: zero along it, perturbations across it decay"
        }
        NonperiodicVerdict::Equilibrium => "an equilibrium: every perturbation decays",
        NonperiodicVerdict::Undecided => {
            "undecided: the halves of the measurement disagree (a transient)"
        }
    };
    format!("; its largest Lyapunov exponent is {lambda:.3e} ± {error:.1e} per unit τ, {meaning}")
}

/// What can go wrong in [`crate::stability`]. Reaches callers as
/// [`crate::Error::Stability`].
#[derive(Debug, Clone, PartialEq, Error)]
#[non_exhaustive]
pub enum StabilityError {
    /// Newton's method on the strobe map did not reach the tolerance.
    #[error(
        "Newton's method did not converge in {iterations} iterations: residual {residual:e} \
         against the tolerance {tolerance:e}"
    )]
    NoConvergence {
        /// Iterations (Jacobian evaluations) done.
        iterations: usize,
        /// Last residual max(|Δy|, |Δy'|) of the strobe map (dimensionless).
        residual: f64,
        /// The residual that would have been accepted.
        tolerance: f64,
    },
    /// The Newton matrix M − I is zero or not finite, so no step can be formed (a stuck
    /// strobe state whose map has derivative 1 in y, or a broken Jacobian).
    #[error("singular Newton matrix at y = {y}, y' = {v} (M - I has determinant {determinant:e})")]
    SingularJacobian {
        /// Position of the iterate.
        y: f64,
        /// Velocity of the iterate.
        v: f64,
        /// det(M − I).
        determinant: f64,
    },
    /// The Jacobian is not finite: a tangential release (μs > 1 and the drive's rate zero
    /// when the net force reaches the static limit), where the flow is not differentiable.
    #[error("the Jacobian is not finite after a tangential release at tau = {tau}")]
    NonFiniteJacobian {
        /// Time (dimensionless τ) of the release.
        tau: f64,
    },
    /// Newton's iterates converge onto y' = 0 where the net force lies between the kinetic
    /// and the static limit (1 < |F − y| ≤ μs), moving along it: there the strobe map jumps
    /// (a motion with y' = 0 stays stuck, one with y' a hair along the force slides away), and
    /// the limit is no orbit of the flow, which would stop there.
    #[error(
        "Newton's iterates converge onto the jump of the strobe map at y = {y}, y' = {v:e} \
         (net force {net_force} between the kinetic and the static limit): no periodic orbit"
    )]
    OnDiscontinuity {
        /// Position of the last iterate.
        y: f64,
        /// Velocity of the last iterate (within the tolerance of 0).
        v: f64,
        /// Net force β cos φ − y at the strobe.
        net_force: f64,
    },
    /// A periodic orbit was asked of a steady state that found no period.
    #[error(
        "the steady state found no period in {periods_run} drive periods{}",
        said(exponent, verdict)
    )]
    NoPeriod {
        /// Drive periods the steady-state analysis ran.
        periods_run: usize,
        /// The largest Lyapunov exponent per unit τ and its standard error, when the steady
        /// state measured it ([`crate::steady::SteadyOptions::lyapunov`]).
        exponent: Option<(f64, f64)>,
        /// What the exponent says, when measured.
        verdict: Option<NonperiodicVerdict>,
    },
    /// The two trajectories of the two-trajectory estimate became identical, so their
    /// separation cannot be renormalised.
    #[error("the two trajectories coincide after {period} drive periods")]
    SeparationLost {
        /// Drive periods of the two-trajectory run (its alignment included).
        period: usize,
    },
}
