//! Accuracy and stop-detection settings of the Shockley solver.

use crate::error::{check, Result};
use serde::{Deserialize, Serialize};

/// Settings of [`crate::shockley::ShockleySolver`]. Build from [`Default`] and the validated
/// `with_*` setters.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct ShockleyOptions {
    /// Relative tolerance of the local error per step, on y and y'. Default 1e-6 (over 300
    /// periods of the paper's circuit at w = 0.95, β = 2.14 the waveform then stays within
    /// about 3e-7 of its peak).
    pub rtol: f64,
    /// Absolute tolerance of the local error per step, on y and y' (dimensionless: 1e-6 is
    /// 0.7 µV on u_C and 0.9 nA on i in the paper's circuit, a thousandth of the stop
    /// threshold). Default 1e-6.
    pub atol: f64,
    /// Largest step in τ. Default 0.25 (1/25 of a natural period): the dense output between
    /// steps is a cubic, and this keeps it accurate to about 1e-6 of the amplitude even where
    /// the error estimate alone would allow longer steps.
    pub max_step: f64,
    /// A stop is an interval where the dimensionless current |y'| stays below this threshold
    /// (for the circuit: |i| < threshold·U_t/√(L/C)). Default 1e-3.
    pub stop_threshold: f64,
    /// ... for longer than this fraction of the drive period 2π/w. Default 0.01.
    pub min_stop_fraction: f64,
}

impl Default for ShockleyOptions {
    fn default() -> Self {
        Self {
            rtol: 1e-6,
            atol: 1e-6,
            max_step: 0.25,
            stop_threshold: 1e-3,
            min_stop_fraction: 0.01,
        }
    }
}

impl ShockleyOptions {
    /// Set the relative tolerance.
    ///
    /// # Errors
    /// [`crate::Error::InvalidParameter`] unless 1e-14 ≤ rtol ≤ 0.1.
    pub fn with_rtol(mut self, rtol: f64) -> Result<Self> {
        self.rtol = check(
            "rtol",
            rtol,
            (1e-14..=0.1).contains(&rtol),
            "must be from 1e-14 to 0.1",
        )?;
        Ok(self)
    }

    /// Set the absolute tolerance.
    ///
    /// # Errors
    /// [`crate::Error::InvalidParameter`] unless 0 < atol ≤ 0.1.
    pub fn with_atol(mut self, atol: f64) -> Result<Self> {
        self.atol = check(
            "atol",
            atol,
            atol > 0.0 && atol <= 0.1,
            "must be > 0 and at most 0.1",
        )?;
        Ok(self)
    }

    /// Set the largest step in τ.
    ///
    /// # Errors
    /// [`crate::Error::InvalidParameter`] unless max_step > 0.
    pub fn with_max_step(mut self, max_step: f64) -> Result<Self> {
        self.max_step = check(
            "max_step",
            max_step,
            max_step > 0.0,
            "must be finite and > 0",
        )?;
        Ok(self)
    }

    /// Set the stop threshold on |y'|.
    ///
    /// # Errors
    /// [`crate::Error::InvalidParameter`] unless the threshold is > 0.
    pub fn with_stop_threshold(mut self, threshold: f64) -> Result<Self> {
        self.stop_threshold = check(
            "stop_threshold",
            threshold,
            threshold > 0.0,
            "must be finite and > 0",
        )?;
        Ok(self)
    }

    /// Set the shortest stop as a fraction of the drive period.
    ///
    /// # Errors
    /// [`crate::Error::InvalidParameter`] unless 0 ≤ fraction ≤ 1.
    pub fn with_min_stop_fraction(mut self, fraction: f64) -> Result<Self> {
        self.min_stop_fraction = check(
            "min_stop_fraction",
            fraction,
            (0.0..=1.0).contains(&fraction),
            "must be from 0 to 1",
        )?;
        Ok(self)
    }

    /// Re-check all fields (for values built by struct literal or deserialised).
    ///
    /// # Errors
    /// The first invalid field, as in the setters.
    pub fn validate(&self) -> Result<Self> {
        Self::default()
            .with_rtol(self.rtol)?
            .with_atol(self.atol)?
            .with_max_step(self.max_step)?
            .with_stop_threshold(self.stop_threshold)?
            .with_min_stop_fraction(self.min_stop_fraction)
    }
}
