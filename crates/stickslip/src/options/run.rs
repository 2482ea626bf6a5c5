//! The options of the runs that have no options type of their own elsewhere.

use super::{Allowed, OptionKey};
use crate::error::{Error, Result};
use serde::Serialize;

/// The options of a run from the initial state (`simulate`).
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct SimulateOptions {
    /// Drive periods run (> 0). Default 20.
    pub periods: f64,
    /// Samples per drive period. Default 200.
    pub samples_per_period: usize,
}

impl Default for SimulateOptions {
    fn default() -> Self {
        Self {
            periods: 20.0,
            samples_per_period: 200,
        }
    }
}

/// Most samples of a run in all (periods × samples per period).
pub const MAX_SIMULATE_SAMPLES: f64 = 5e7;

impl SimulateOptions {
    /// The samples of the run: ⌈periods × samples per period⌉ + 1 (both ends).
    pub fn samples(&self) -> f64 {
        (self.periods * self.samples_per_period as f64).ceil() + 1.0
    }

    /// Check every field, and that the run has at most 5·10⁷ samples.
    ///
    /// # Errors
    /// [`Error::InvalidOption`] naming the first bad field; [`Error::OptionProduct`] for too
    /// many samples.
    pub fn validate(self) -> Result<Self> {
        OptionKey::SimulatePeriods.check(self.periods)?;
        OptionKey::SimulateSamples.check_count(self.samples_per_period)?;
        let total = (self.periods * self.samples_per_period as f64).ceil();
        if total > MAX_SIMULATE_SAMPLES {
            return Err(Error::OptionProduct {
                what: "samples",
                first: OptionKey::SimulatePeriods,
                second: OptionKey::SimulateSamples,
                product: total,
                max: "5e7",
            });
        }
        Ok(self)
    }
}

/// The options of a periodic orbit found by Newton's method (`orbit`).
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct OrbitOptions {
    /// Period of the orbit in drive periods; `None`: that of the steady state.
    pub period: Option<usize>,
    /// With a period: drive periods run from the initial state before Newton's method. Default 0.
    pub transient: usize,
    /// Without a period: drive periods run at most to find the steady state. Default 5000.
    pub max_periods: usize,
    /// Without a period: longest period looked for. Default 16.
    pub max_period: usize,
    /// Newton's method.
    pub newton: super::NewtonOptions,
}

impl Default for OrbitOptions {
    fn default() -> Self {
        Self {
            period: None,
            transient: 0,
            max_periods: 5000,
            max_period: 16,
            newton: super::NewtonOptions::default(),
        }
    }
}

impl OrbitOptions {
    /// Check every field.
    ///
    /// # Errors
    /// [`Error::InvalidOption`] naming the first bad field.
    pub fn validate(self) -> Result<Self> {
        if let Some(p) = self.period {
            OptionKey::OrbitPeriod.check_count(p)?;
        }
        OptionKey::OrbitTransient.check_count(self.transient)?;
        if self.period.is_none() && self.transient != 0 {
            return Err(Error::InvalidOption {
                option: OptionKey::OrbitTransient,
                value: self.transient as f64,
                allowed: Allowed::Needs {
                    other: OptionKey::OrbitPeriod,
                    why: "without it the steady state gives the guess",
                },
            });
        }
        OptionKey::OrbitMaxPeriods.check_count(self.max_periods)?;
        OptionKey::OrbitMaxPeriod.check_count(self.max_period)?;
        OptionKey::NewtonTolerance.check(self.newton.tolerance)?;
        OptionKey::MaxIterations.check_count(self.newton.max_iterations)?;
        self.newton.validate()?;
        Ok(self)
    }
}
