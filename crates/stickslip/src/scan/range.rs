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

    /// The i-th value, computed without accumulating rounding (the last one is `to` exactly),
    /// and written as the shortest decimal within a few rounding errors of it (see
    /// [`grid_value`]): 0.2 to 2 in 73 steps gives 0.425, not 0.42500000000000004.
    pub fn value(&self, i: usize) -> f64 {
        if self.steps == 1 {
            self.from
        } else {
            grid_value(self.from, self.to, i, self.steps - 1)
        }
    }

    /// All values in increasing order.
    pub fn values(&self) -> Vec<f64> {
        (0..self.steps).map(|i| self.value(i)).collect()
    }
}

/// The i-th of `intervals + 1` evenly spaced values from `from` to `to` (both ends exact),
/// without float noise: when a decimal of at most 12 significant digits lies within a few
/// rounding errors of from + (to − from)·i/intervals, that decimal (the shortest one), so
/// that a grid of round values prints round (0.425, not 0.42500000000000004); otherwise the
/// computed value itself (a value such as 1 + 7/36 has no short decimal, and a longer one
/// would not be closer to it). The value moves by at most 8 ε·max(|from|, |to|), the size of
/// the rounding error it removes.
pub fn grid_value(from: f64, to: f64, i: usize, intervals: usize) -> f64 {
    if intervals == 0 || i == 0 {
        return from;
    }
    if i >= intervals {
        return to;
    }
    let raw = from + (to - from) * (i as f64 / intervals as f64);
    let tolerance = 8.0 * f64::EPSILON * from.abs().max(to.abs());
    shortest_decimal_near(raw, tolerance)
}

/// The decimal with the fewest significant digits, at most 12, within `tolerance` of `value`
/// (`value` itself when there is none).
fn shortest_decimal_near(value: f64, tolerance: f64) -> f64 {
    if !value.is_finite() || value == 0.0 {
        return value;
    }
    for digits in 1..=12 {
        let text = format!("{value:.*e}", digits - 1);
        if let Ok(rounded) = text.parse::<f64>() {
            if (rounded - value).abs() <= tolerance {
                return rounded;
            }
        }
    }
    value
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn round_grids_print_round() {
        // The two values of fig4.csv that printed with float noise.
        let range = ParameterRange::new("w", 0.2, 2.0, 73).unwrap();
        let text: Vec<String> = range.values().iter().map(|v| v.to_string()).collect();
        assert!(text.contains(&"0.425".to_string()), "{text:?}");
        assert!(text.contains(&"0.775".to_string()), "{text:?}");
        for (i, t) in text.iter().enumerate() {
            // 0.2 + 0.025 i has at most four decimals.
            assert!(t.len() <= 5, "value {i}: {t}");
            let exact = 0.2 + 0.025 * i as f64;
            assert!((range.value(i) - exact).abs() < 1e-15, "value {i}: {t}");
        }
        assert_eq!(range.value(0), 0.2);
        assert_eq!(range.value(72), 2.0);
    }

    #[test]
    fn values_that_are_not_round_stay_within_rounding_of_the_formula() {
        // Thirds have no short decimal: the value keeps its digits.
        for (from, to, n) in [
            (0.0, 1.0, 3),
            (0.1, 2.5, 199),
            (-3.0, 7.0, 7),
            (1e-3, 2e-3, 9),
        ] {
            for i in 0..=n {
                let raw = from + (to - from) * (i as f64 / n as f64);
                let v = grid_value(from, to, i, n);
                let bound = 8.0 * f64::EPSILON * f64::max(f64::abs(from), f64::abs(to));
                assert!(
                    (v - raw).abs() <= bound,
                    "{from}..{to}/{n} #{i}: {v} vs {raw}"
                );
            }
        }
        assert_eq!(grid_value(0.0, 1.0, 1, 3), 1.0 / 3.0);
        // A value with no short decimal keeps all its digits (fig5.csv's β grid).
        let raw = 1.0 + 14.0 * (1.0 / 72.0);
        assert_eq!(grid_value(1.0, 15.0, 1, 72), raw);
        assert_eq!(
            grid_value(1.0, 15.0, 1, 72).to_string(),
            "1.1944444444444444"
        );
        // Monotone on a fine grid.
        let values: Vec<f64> = (0..=1000).map(|i| grid_value(0.1, 2.5, i, 1000)).collect();
        assert!(values.windows(2).all(|w| w[0] < w[1]));
    }
}
