//! The Shockley diode-pair model and its stiff solver.
//!
//! The PWL law U_t sgn(i) + R_D i of the paper is replaced by the physical law of two
//! anti-parallel diodes ([`DiodePair`]),
//!
//! ```text
//! U_D(i) = n V_T asinh(i/(2 I_s)) + R_s i,          V_T = k T/q,
//! ```
//!
//! in the series circuit L q̈ + R q̇ + q/C + U_D(q̇) = U cos(Ω t + φ) (a [`crate::Circuit`]
//! whose diode is [`crate::physical::Diode::Shockley`]).
//! In the dimensionless variables of the crate (y = u_C/U_t with the PWL turn-on voltage U_t
//! kept as the reference, so that β = U/U_t means the same drive in both models):
//!
//! ```text
//! y'' + 2ζ_R y' + y + D(y') = β cos(w τ + φ),    D(v) = a asinh(v/ε) + r v
//! ```
//!
//! ([`ShockleyModel`], [`DiodeLaw`]). The paper's eq. (14) drops the factor a = n V_T/U_t in
//! front of the asinh; see [`diode`] for the difference.
//!
//! D is smooth but its slope at v = 0 is a/ε ≈ 7.5·10³ for a 1N4148 in the paper's circuit
//! against about 0.07 at the working currents: the problem is stiff exactly where the current
//! reverses. [`ShockleySolver`] integrates it with the stiff integrator of smooth laws
//! ([`crate::stiff`]: a three-stage Radau IIA method of order 5, L-stable; full Newton on the
//! stage equations; error estimate and step control of RADAU5; collocation polynomial as
//! dense output), for which [`DiodeLaw`] is a [`crate::stiff::SmoothLaw`], behind the
//! [`crate::Solver`] trait, so everything written against the trait works with either diode
//! model.
//!
//! **Stops of a smooth diode.** The current never stays at exactly zero; a stop is an interval
//! where |y'| stays below [`ShockleyOptions::stop_threshold`] (default 1e-3, i.e.
//! |i| < 1e-3·U_t/√(L/C) ≈ 0.92 µA in the paper's circuit) for longer than
//! [`ShockleyOptions::min_stop_fraction`] of the drive period (default 1 %). Events:
//!
//! - `Stick` at the time |y'| fell below the threshold, reported (in time order) once the
//!   dip has lasted the minimum duration; `Slip` when |y'| reaches the threshold again;
//! - `Turn` at the first zero of y' inside a shorter dip, when the current leaves the dip
//!   with the sign opposite to the one it entered with.
//!
//! The phase is `Stick` during a stop, otherwise the sign of y' (within a short dip the phase
//! changes once, at the turn). From rest at τ = 0 a stop is the initial phase, not an event,
//! as for the exact solver.
//!
//! [`netlist()`] writes the same circuit for SPICE, for cross-checks in ngspice or any SPICE.

pub mod diode;
pub mod model;
pub mod netlist;
pub mod options;
pub mod solver;
mod stops;

#[cfg(test)]
mod tests;

pub use diode::{DiodeLaw, DiodePair};
pub use model::ShockleyModel;
pub use netlist::{netlist, NetlistOptions};
pub use options::ShockleyOptions;
pub use solver::ShockleySolver;
