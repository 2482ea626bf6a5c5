//! Special points of a branch: folds, branch points, period doublings, Neimark–Sacker
//! points and grazings, with the orbit on either side.

use crate::params::State;
use crate::stability::{Multiplier, Stability};
use serde::{Deserialize, Serialize};

/// What a special point is (see the module documentation).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum SpecialKind {
    /// A real multiplier through +1, the branch turning back in the parameter.
    Fold,
    /// A real multiplier through +1 without a turn: another branch crosses.
    BranchPoint,
    /// A real multiplier through −1.
    PeriodDoubling,
    /// A complex pair of multipliers through the unit circle.
    NeimarkSacker,
    /// The event counts of the orbit change (a stop or a turning point appears or
    /// disappears).
    Grazing,
}

impl SpecialKind {
    /// The label used in CSV and JSON: `fold`, `branch-point`, `period-doubling`,
    /// `neimark-sacker`, `grazing`.
    pub fn label(self) -> &'static str {
        match self {
            SpecialKind::Fold => "fold",
            SpecialKind::BranchPoint => "branch-point",
            SpecialKind::PeriodDoubling => "period-doubling",
            SpecialKind::NeimarkSacker => "neimark-sacker",
            SpecialKind::Grazing => "grazing",
        }
    }
}

/// The orbit on one side of a special point (one end of the final bracket).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Side {
    /// The parameter's value.
    pub value: f64,
    /// The strobe state.
    pub state: State,
    /// The Floquet multipliers.
    pub multipliers: [Multiplier; 2],
    /// The stability from the largest multiplier modulus strictly (no neutral band: the
    /// ends of a bracket lie within its width of a multiplier at ±1).
    pub stability: Stability,
    /// Turning points per orbit period.
    pub turns: usize,
    /// Stops per orbit period.
    pub stops: usize,
}

/// A special point of a branch, located between two orbits of the branch at most
/// [`SpecialPoint::width`](super::SpecialPoint::width) apart in arclength.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct SpecialPoint {
    /// What happens there.
    pub kind: SpecialKind,
    /// The parameter's value (the middle of the bracket).
    pub value: f64,
    /// The strobe state (the middle of the bracket).
    pub state: State,
    /// Width of the final bracket in arclength: it bounds the error of `value` and of
    /// `state`.
    pub width: f64,
    /// Whether the bracket reached
    /// [`ContinuationOptions::locate_tolerance`](super::ContinuationOptions::locate_tolerance)
    /// (false when the corrector failed inside it; `width` then says how well it is located).
    pub located: bool,
    /// Index of the branch point just before it.
    pub after_point: usize,
    /// The orbit at the end of the bracket before it (along the branch).
    pub before: Side,
    /// The orbit at the end of the bracket after it.
    pub after: Side,
}
