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

/// The accessors of an integrator's place between steps, the same for [`Radau5`] and
/// [`Dop853`] (each keeps the fields `t`, `x`, `params` and `law`): written once here, and
/// expanded in each one's `impl`.
macro_rules! integrator_accessors {
    ($integrator:ident) => {
        /// Current time (end of the last accepted step).
        pub fn time(&self) -> f64 {
            self.t
        }

        #[doc = concat!("The state at [`", stringify!($integrator), "::time`].")]
        pub fn state(&self) -> Vector {
            self.x
        }

        /// The parameters ζ, w, β, φ of the equation.
        pub fn params(&self) -> &Params {
            &self.params
        }

        /// The law.
        pub fn law(&self) -> &L {
            &self.law
        }
    };
}

pub mod cubic;
pub mod dop853;
pub mod law;
pub mod radau;
pub mod sensitivity;

pub use dop853::{Dop853, DopStep};
pub use law::{SmoothLaw, MAX_LAW_PARAMETERS};
pub use radau::{Counters, Radau5, Settings, Step};
pub use sensitivity::{Columns, Sensitivity, StepDerivative, Track};
