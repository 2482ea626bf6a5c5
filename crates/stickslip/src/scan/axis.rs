//! The values a parameter takes in a sweep or on one side of a grid.

use super::range::ParameterRange;
use crate::error::{Error, Result};
use crate::options::{Allowed, OptionKey};
use crate::params::{Parameter, Params};
use serde::{Deserialize, Serialize};

impl ParameterRange {
    /// A range whose ends and count are options of a computation (a map's `--w-min`,
    /// `--w-max`, `--w-steps`): each end within its option's range, the upper end not below
    /// the lower one (else the upper end is at fault: `invalid --beta-max 0: must not be below
    /// --beta-min 0.5`), then the count as for [`ParameterRange::new`].
    ///
    /// # Errors
    /// [`Error::InvalidOption`] naming the option at fault, which each front end spells its
    /// own way.
    pub fn between(
        (min, from): (OptionKey, f64),
        (max, to): (OptionKey, f64),
        (count, steps): (OptionKey, usize),
    ) -> Result<Self> {
        min.check(from)?;
        max.check(to)?;
        if to < from {
            return Err(Error::InvalidOption {
                option: max,
                value: to,
                allowed: Allowed::NotBelow {
                    other: min,
                    value: from,
                },
            });
        }
        count.check_count(steps)?;
        if steps == 1 && from != to {
            return Err(Error::InvalidOption {
                option: count,
                value: 1.0,
                allowed: Allowed::Text("a range from one value to another needs at least 2 points"),
            });
        }
        ParameterRange::new("range", from, to, steps)
    }
}

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

#[cfg(test)]
mod tests {
    use super::*;

    /// A pool's threads are checked against the option table's row, as Python checks them
    /// (1 to 1024), by maps and basin maps alike.
    #[test]
    fn threads_take_their_rows_range() {
        use crate::basins::Basins;
        use crate::experiment::Experiment;
        let e = Experiment::paper()
            .with_w(0.95)
            .unwrap()
            .with_beta(2.14)
            .unwrap();
        let grid = || {
            crate::scan::Grid::new(
                &e,
                Axis::new(Parameter::W, vec![1.0]).unwrap(),
                Axis::new(Parameter::Beta, vec![2.0]).unwrap(),
            )
            .unwrap()
        };
        let range = ParameterRange::new("y0", -1.0, 1.0, 3).unwrap();
        let basins = || Basins::new(&e, &range, &range).unwrap();
        for n in [0, 1025] {
            let err = grid().threads(n).unwrap_err();
            assert_eq!(err.option(), Some(OptionKey::Threads), "{n}");
            assert_eq!(
                err.to_string(),
                format!("invalid threads = {n}: must be from 1 to 1024")
            );
            let err = basins().threads(n).unwrap_err();
            assert_eq!(err.option(), Some(OptionKey::Threads), "{n}");
        }
        assert!(grid().threads(1024).is_ok() && basins().threads(2).is_ok());
    }

    /// The upper end below the lower is the upper end's fault (issue 38: the lab marked
    /// β-min for β-max = 0).
    #[test]
    fn a_range_of_options_names_the_end_at_fault() {
        let map = |from, to, steps| {
            ParameterRange::between(
                (OptionKey::MapBetaMin, from),
                (OptionKey::MapBetaMax, to),
                (OptionKey::MapBetaSteps, steps),
            )
        };
        let r = map(0.5, 4.0, 50).unwrap();
        assert_eq!((r.from(), r.to(), r.steps()), (0.5, 4.0, 50));
        let e = map(0.5, 0.0, 50).unwrap_err();
        assert_eq!(e.option(), Some(OptionKey::MapBetaMax));
        assert_eq!(
            e.to_string(),
            "invalid beta_max = 0: must not be below beta_min 0.5"
        );
        assert_eq!(
            map(-1.0, 4.0, 50).unwrap_err().option(),
            Some(OptionKey::MapBetaMin)
        );
        assert_eq!(
            map(0.5, 2e9, 50).unwrap_err().option(),
            Some(OptionKey::MapBetaMax)
        );
        assert_eq!(
            map(0.5, 4.0, 0).unwrap_err().option(),
            Some(OptionKey::MapBetaSteps)
        );
        assert_eq!(
            map(0.5, 4.0, 1).unwrap_err().option(),
            Some(OptionKey::MapBetaSteps)
        );
        assert_eq!(map(2.0, 2.0, 1).unwrap().values(), [2.0]);
    }
}
