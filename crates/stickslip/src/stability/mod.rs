//! Stability and chaos, exactly: the tangent dynamics of the exact solution, periodic orbits
//! by Newton's method with their Floquet multipliers, and Lyapunov exponents.
//!
//! Everything is dimensionless (τ = ω0·t), on the model
//!
//! ```text
//! y'' + 2ζ y' + y + sgn(y') = F(τ) = β cos(w τ + φ)     while sliding,
//! y' = 0 and |F(τ) − y| ≤ μs                             while stuck,
//! ```
//!
//! with the state x = (y, y') and perturbations δx = (δy, δy').
//!
//! # Tangent dynamics
//!
//! The derivative of the exact flow, J = ∂x(τ)/∂x(τ₀), is a product of the state-transition
//! matrices of the segments and the saltation matrices of the events between them, in time
//! order:
//!
//! ```text
//! J = Φ_N · S_N · Φ_{N−1} · … · S_1 · Φ_0.
//! ```
//!
//! - [`segment`]: every slide has Φ(Δτ) = e^{AΔτ}, A = [[0, 1], [−1, −2ζ]] (the friction and
//!   the drive do not depend on the state), in the closed-form basis of every damping regime,
//!   with det Φ = e^{−2ζΔτ}; a stuck segment has diag(1, 0).
//! - [`saltation`]: from S = I + (f⁺ − f⁻)∇hᵀ/(∇h·f⁻ + ∂h/∂τ), a turn gives
//!   diag(1, a⁺/a⁻) with a∓ = F − y − s∓ (always a contraction, |a⁻| > μs + 1), a stop
//!   diag(1, 0) (rank one), a release in direction s [[1, 0], [−(μs − 1)/(sF'), 1]] (the
//!   static limit moves with the drive; at μs = 1 the field is continuous there and S = I), and
//!   a zero-duration stop the product of the last two, one side of a kink for μs > 1 and
//!   smooth at μs = 1.
//! - [`TangentSolver`]: an [`crate::ExactSolver`] that carries J (and ln|det J|) along its
//!   trajectory, reading every saltation from the numbers the solver decided the event with.
//!   The solver itself is unchanged, so runs without tangents cost what they always did.
//!
//! # Periodic orbits
//!
//! [`strobe_map`] is the p-fold strobe map P^p (the state at τ = kT, T = 2π/w, to the state p
//! periods later) with its exact Jacobian; [`find_periodic_orbit`] solves P^p(x) = x by
//! Newton's method (quadratic convergence, stable and unstable orbits alike, the rank-one
//! Jacobian of orbits that stick handled as its module explains) and returns the orbit's
//! events and stops, its monodromy matrix, Floquet multipliers and [`Stability`].
//! [`periodic_orbit_from_steady`] starts it from a settled [`crate::SteadyState`].
//!
//! # Parameter sensitivities
//!
//! [`periodic_orbit_sensitivity`] carries, beside J, the derivatives of the flow by the
//! parameters (ζ, β, w, φ, μs) through the closed-form slides and the events (a release's
//! time moves with the drive and μs), and gives the derivatives of a periodic orbit's samples
//! through dx*/dp = (I − M)⁻¹ ∂P/∂p: the exact Jacobians of [`crate::fit`].
//!
//! # Lyapunov exponents
//!
//! [`lyapunov_exponents`] gives the largest exponent from the renormalised tangent, per unit τ
//! and per drive period, with a standard error from block means and a convergence check, and
//! the second exponent from ln|det J| (−∞ once the motion stops: a stop erases the velocity
//! perturbation). [`two_trajectory_exponent`] is the classical two-trajectory estimate on the
//! same solver, an independent check. [`classify_nonperiodic`] tells chaos from
//! quasi-periodic and contracting motion by the sign of the exponent beyond its error; the
//! steady-state analysis does so for every motion that does not repeat
//! ([`crate::steady::SteadyOptions::lyapunov`], [`crate::MotionClass::Chaotic`]), and
//! [`steady_exponent`] gives the largest exponent of any steady motion (maps of it:
//! [`crate::scan::Grid::lyapunov`]).

pub mod dynamics;
pub(crate) mod error;
pub mod friction;
pub mod lyapunov;
mod map_newton;
mod matrix;
pub mod nonperiodic;
pub mod periodic_orbit;
pub mod report;
pub mod saltation;
pub mod segment;
pub mod sensitivity;
pub mod smooth;
pub mod strobe;
pub mod tangent;
pub mod two_trajectory;
pub(crate) mod verdict;

pub use dynamics::{Dynamics, ExactDynamics};
pub use error::StabilityError;
pub use friction::{FrictionDynamics, FrictionTangent, FRICTION_COLUMNS};
pub use lyapunov::{
    lyapunov_exponents, lyapunov_exponents_monitored, Estimate, LyapunovExponents, LyapunovOptions,
    SecondExponent,
};
pub use matrix::{Matrix2, Multiplier};
pub use nonperiodic::{
    classify_nonperiodic, strobe_period, strobe_period_of, NonperiodicClassification,
    NonperiodicVerdict,
};
pub use periodic_orbit::{find_periodic_orbit, NewtonOptions, PeriodicOrbit, Stability, Stop};
pub use report::{ExponentValue, LyapunovReport, OrbitReport};
pub use segment::{sliding_transition, stuck_transition};
pub use sensitivity::{
    periodic_orbit_sensitivity, strobe_map_parameter_derivative, strobe_map_parameter_derivatives,
    OrbitSample, SENSITIVITY_PARAMETERS,
};
pub use smooth::{ShockleyDynamics, ShockleyTangent, SmoothImage, SmoothOrbitSample};
pub use strobe::{strobe_map, StrobeImage};
pub use tangent::{TangentRun, TangentSolver};
pub use two_trajectory::{two_trajectory_exponent, TwoTrajectoryEstimate};

// What joins a steady state to its stability lives in `crate::steady`, which builds on this
// module (never the other way round); these names stay here for the paths users know.
pub use crate::steady::{
    periodic_orbit_from_steady, steady_exponent, steady_exponent_of, steady_state_with_exponent,
    SEARCH_BEFORE_MEASURING,
};
