//! What a fit warns of: a fit that did not converge, a combination of parameters that the
//! records cannot separate, a strong correlation, a value at the edge of its range, a
//! parameter the records do not see, clipped samples. Each warning is one line
//! ([`std::fmt::Display`]); the report lists them ([`super::FitReport::warnings`]), the
//! command line prints each on standard error, the JSON report has them as `warnings`.

use super::FitParameter;
use serde::{Deserialize, Serialize};
use std::fmt;

/// Why a fit is not called converged.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case", tag = "reason")]
#[non_exhaustive]
pub enum NotConverged {
    /// The iterations ran out before the step and gradient criteria held.
    Iterations {
        /// The most iterations of a pass.
        limit: usize,
    },
    /// No step lowers the sum of squares, yet the gradient says the minimum lies elsewhere
    /// (the Jacobian does not describe the residuals there).
    Stalled {
        /// The decrease of χ² a Gauss–Newton step predicts (in units of the residuals'
        /// variance); the criterion is 10⁻³.
        predicted: f64,
    },
    /// A restart from elsewhere found a lower χ².
    Restart {
        /// By how much lower (χ², in units of the residuals' variance).
        lower_by: f64,
    },
}

/// A warning of a fit.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case", tag = "kind")]
#[non_exhaustive]
pub enum FitWarning {
    /// The fit did not converge: its values and error bars are not a minimum's.
    NotConverged {
        /// Why.
        why: NotConverged,
    },
    /// Parameters that enter the model only through fewer combinations than there are of
    /// them (R and R_s only as R + R_s; L, C and R only through ω0 and ζ): the records cannot
    /// separate them, whatever they are. The fit holds `held` at its starting value and
    /// fits the others.
    NotIdentified {
        /// The parameters of the combination, in the order they were named.
        parameters: Vec<FitParameter>,
        /// The combinations the model sees, in words (`R + R_s`).
        combination: String,
        /// The parameter held at its starting value.
        held: FitParameter,
    },
    /// A parameter the records do not see at these values (its column of the Jacobian is
    /// zero: μs when no record sticks, the Stribeck speed when no slip comes near zero): no
    /// error bar.
    Unseen {
        /// The parameter.
        parameter: FitParameter,
    },
    /// Two fitted parameters correlated beyond ±0.99: the records fix a combination of them
    /// far better than either.
    Correlated {
        /// The first parameter.
        first: FitParameter,
        /// The second parameter.
        second: FitParameter,
        /// Their correlation.
        correlation: f64,
    },
    /// A value at the edge of its range (R_s = 0): the minimum presses against it, and its
    /// interval is one-sided.
    AtBound {
        /// The parameter.
        parameter: FitParameter,
        /// The edge (the parameter's unit).
        bound: f64,
    },
    /// Samples left out of a record as clipped (at the screen's edge).
    Clipped {
        /// The record.
        file: String,
        /// Samples left out.
        samples: usize,
        /// Samples of the record.
        of: usize,
    },
}

impl FitWarning {
    /// The kind's label: `not-converged`, `not-identified`, `unseen`, `correlated`,
    /// `at-bound`, `clipped`.
    pub fn kind(&self) -> &'static str {
        match self {
            FitWarning::NotConverged { .. } => "not-converged",
            FitWarning::NotIdentified { .. } => "not-identified",
            FitWarning::Unseen { .. } => "unseen",
            FitWarning::Correlated { .. } => "correlated",
            FitWarning::AtBound { .. } => "at-bound",
            FitWarning::Clipped { .. } => "clipped",
        }
    }

    /// The parameters the warning is about (none for a record's or the fit's own).
    pub fn parameters(&self) -> Vec<FitParameter> {
        match self {
            FitWarning::NotIdentified { parameters, .. } => parameters.clone(),
            FitWarning::Unseen { parameter } | FitWarning::AtBound { parameter, .. } => {
                vec![*parameter]
            }
            FitWarning::Correlated { first, second, .. } => vec![*first, *second],
            FitWarning::NotConverged { .. } | FitWarning::Clipped { .. } => Vec::new(),
        }
    }
}

fn names(list: &[FitParameter]) -> String {
    match list {
        [] => String::new(),
        [one] => one.label().to_string(),
        [init @ .., last] => format!(
            "{} and {}",
            init.iter()
                .map(|p| p.label())
                .collect::<Vec<_>>()
                .join(", "),
            last.label()
        ),
    }
}

impl fmt::Display for FitWarning {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            FitWarning::NotConverged { why } => {
                write!(f, "the fit did not converge: ")?;
                match why {
                    NotConverged::Iterations { limit } => write!(
                        f,
                        "{limit} iterations were not enough; its values and error bars are \
                         not those of a minimum"
                    ),
                    NotConverged::Stalled { predicted } => write!(
                        f,
                        "no step lowers χ², yet the gradient predicts a decrease of {predicted:.3} \
                         (the criterion is 0.001); its values and error bars are not those of a \
                         minimum"
                    ),
                    NotConverged::Restart { lower_by } => write!(
                        f,
                        "a restart from elsewhere ended {lower_by:.3} lower in χ²; the values \
                         reported are the lower ones, but another minimum may lie lower still"
                    ),
                }
            }
            FitWarning::NotIdentified {
                parameters,
                combination,
                held,
            } => write!(
                f,
                "{} enter the model only as {combination}: the records cannot separate them; \
                 {held} is held at its starting value (free fewer of them)",
                names(parameters)
            ),
            FitWarning::Unseen { parameter } => write!(
                f,
                "the records do not change with {parameter} at these values (with mu-s: no \
                 record sticks; with stribeck-speed: no slip comes near zero): they do not \
                 determine it, and it has no error bar"
            ),
            FitWarning::Correlated {
                first,
                second,
                correlation,
            } => write!(
                f,
                "{first} and {second} are correlated (r = {correlation:.4}): the records fix a \
                 combination of them far better than either, and their error bars are wide"
            ),
            FitWarning::AtBound { parameter, bound } => write!(
                f,
                "{parameter} ended at the edge of its range ({bound}): its 95 % interval is \
                 one-sided"
            ),
            FitWarning::Clipped { file, samples, of } => write!(
                f,
                "{file}: {samples} of {of} samples are clipped at the screen's edge and left out \
                 (set the scope so that the trace stays on the screen)"
            ),
        }
    }
}
