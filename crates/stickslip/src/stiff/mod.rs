//! The stiff integrator of smooth laws: y'' + 2ζ y' + y + D(y') = β cos(w τ + φ) for any
//! smooth law D ([`SmoothLaw`]), by the three-stage Radau IIA method of order 5
//! ([`Radau5`]: L-stable, full Newton on the stage equations with a second chart where the
//! law is steep, the error estimate and step control of RADAU5, the collocation polynomial
//! as dense output).
//!
//! The law is the seam: the Shockley diode pair ([`crate::shockley::DiodeLaw`]) is the first
//! law; friction laws of the slip against a moving belt fit the same trait (see
//! [`SmoothLaw`]). The PWL law keeps its exact solver ([`crate::ExactSolver`]).
//!
//! - [`law`]: the trait.
//! - [`radau`]: the integrator, its steps ([`Step`]) and their dense output.
//! - [`sensitivity`]: forward sensitivities on the integrator's own steps, by the initial
//!   state (the tangent dynamics) and by the parameters.
//! - [`cubic`]: the dense output's cubics: range and level crossings.
//! - [`dop853`]: an explicit integrator of order 8 for laws that are not stiff (the slips of
//!   a friction law on a belt), with a dense output of order 7.

pub mod cubic;
pub mod dop853;
pub mod law;
pub mod radau;
pub mod sensitivity;

pub use dop853::{Dop853, DopStep};
pub use law::{SmoothLaw, MAX_LAW_PARAMETERS};
pub use radau::{Counters, Radau5, Settings, Step};
pub use sensitivity::{Columns, Sensitivity, StepDerivative, Track};
