//! Evenly spaced parameter values for sweeps and phase diagrams.

use crate::error::{Error, Result};

/// `steps` evenly spaced values from `from` to `to`, both included.
///
/// A single point (`steps` = 1) needs `from` = `to`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ParameterRange {
    from: f64,
    to: f64,
    steps: usize,
}

impl ParameterRange {
    /// A validated range; `name` is the parameter's name for the error message.
    ///
    /// # Errors
    /// [`Error::InvalidParameter`] when `from` or `to` is not finite, `from` > `to`,
    /// `steps` = 0, or `steps` = 1 with `from` ≠ `to` (named `<name>` for a bound and `steps`
    /// for the count).
    pub fn new(name: &'static str, from: f64, to: f64, steps: usize) -> Result<Self> {
        let bad = |value: f64, allowed: &'static str| Error::InvalidParameter {
            name,
            value,
            allowed,
        };
        if !from.is_finite() {
            return Err(bad(from, "range start must be finite"));
        }
        if !to.is_finite() {
            return Err(bad(to, "range end must be finite"));
        }
        if from > to {
            return Err(bad(from, "range start must not exceed the range end"));
        }
        if steps == 0 {
            return Err(Error::InvalidParameter {
                name: "steps",
                value: 0.0,
                allowed: "the number of points must be at least 1",
            });
        }
        if steps == 1 && from != to {
            return Err(Error::InvalidParameter {
                name: "steps",
                value: 1.0,
                allowed: "a range from one value to another needs at least 2 points",
            });
        }
        Ok(Self { from, to, steps })
    }

    /// First value.
    pub fn from(&self) -> f64 {
        self.from
    }

    /// Last value.
    pub fn to(&self) -> f64 {
        self.to
    }

    /// Number of values.
    pub fn steps(&self) -> usize {
        self.steps
    }

    /// Spacing between neighbouring values (0 for a single point).
    pub fn spacing(&self) -> f64 {
        if self.steps > 1 {
            (self.to - self.from) / (self.steps - 1) as f64
        } else {
            0.0
        }
    }

    /// The i-th value, computed without accumulating rounding (the last one is `to` exactly).
    pub fn value(&self, i: usize) -> f64 {
        if self.steps == 1 || i == 0 {
            self.from
        } else if i + 1 == self.steps {
            self.to
        } else {
            self.from + (self.to - self.from) * (i as f64 / (self.steps - 1) as f64)
        }
    }

    /// All values in increasing order.
    pub fn values(&self) -> Vec<f64> {
        (0..self.steps).map(|i| self.value(i)).collect()
    }
}
