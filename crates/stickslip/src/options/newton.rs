//! The options of Newton's method on the strobe map: below the stability analysis that uses
//! them, so that the options types depend on nothing above them.

use super::OptionKey;
use crate::error::{Error, Result};
use serde::{Deserialize, Serialize};

/// Options of Newton's method on the strobe map
/// ([`crate::stability::find_periodic_orbit`]; also `crate::stability::NewtonOptions`).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct NewtonOptions {
    /// Relative tolerance of the residual (see [`crate::stability::periodic_orbit`]). Default
    /// 1e-12.
    pub tolerance: f64,
    /// Most Newton steps. Default 30.
    pub max_iterations: usize,
    /// Most halvings of one step when the residual grows. Default 12.
    pub max_halvings: usize,
    /// An orbit whose largest multiplier modulus is within this of 1 is called
    /// [`crate::stability::Stability::Neutral`]. Default 1e-9.
    pub neutral_band: f64,
}

impl Default for NewtonOptions {
    fn default() -> Self {
        Self {
            tolerance: 1e-12,
            max_iterations: 30,
            max_halvings: 12,
            neutral_band: 1e-9,
        }
    }
}

impl NewtonOptions {
    /// Check every field.
    ///
    /// # Errors
    /// [`Error::InvalidOption`] naming the tolerance or the most steps
    /// ([`crate::options`]); [`Error::InvalidParameter`] for the neutral band.
    pub fn validate(self) -> Result<Self> {
        OptionKey::NewtonTolerance.check(self.tolerance)?;
        OptionKey::MaxIterations.check_count(self.max_iterations)?;
        if !(self.neutral_band >= 0.0 && self.neutral_band < 1.0) {
            return Err(Error::InvalidParameter {
                name: "neutral_band",
                value: self.neutral_band,
                allowed: "must be >= 0 and < 1",
            });
        }
        Ok(self)
    }
}
