//! The values a parameter takes in a sweep or on one side of a grid.

use super::range::ParameterRange;
use crate::error::{Error, Result};
use crate::params::{Parameter, Params};
use serde::{Deserialize, Serialize};

/// A parameter and the values it takes, in order.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Axis {
    parameter: Parameter,
    values: Vec<f64>,
}

impl Axis {
    /// `parameter` at `values`, in the given order.
    ///
    /// # Errors
    /// [`Error::InvalidParameter`] for no values, or a value out of the parameter's range
    /// (ζ ≥ 0, w > 0, β ≥ 0, μs ≥ 1, finite).
    pub fn new(parameter: Parameter, values: Vec<f64>) -> Result<Self> {
        if values.is_empty() {
            return Err(Error::InvalidParameter {
                name: "steps",
                value: 0.0,
                allowed: "the number of points must be at least 1",
            });
        }
        let any = Params::new(0.0, 1.0, 0.0)?;
        for &v in &values {
            parameter.set(any, v)?;
        }
        Ok(Self { parameter, values })
    }

    /// `parameter` at the evenly spaced values of `range`.
    ///
    /// # Errors
    /// As [`Axis::new`].
    pub fn range(parameter: Parameter, range: &ParameterRange) -> Result<Self> {
        Self::new(parameter, range.values())
    }

    /// The parameter.
    pub fn parameter(&self) -> Parameter {
        self.parameter
    }

    /// The values, in order.
    pub fn values(&self) -> &[f64] {
        &self.values
    }

    /// Number of values.
    pub fn len(&self) -> usize {
        self.values.len()
    }

    /// Whether there are no values (never, for an axis from [`Axis::new`]).
    pub fn is_empty(&self) -> bool {
        self.values.is_empty()
    }
}
