//! The summary of a branch that `stickslip continue --json` prints.

use super::{Branch, BranchEnd, Side, SpecialKind};
use serde::Serialize;

/// What a branch reports besides its points: exactly what `stickslip continue --json` prints
/// and what the Python package's `continuation` returns as its summary. Build it with
/// `BranchReport::from(&branch)`.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct BranchReport {
    /// The continued parameter (`w`, `beta`, `zeta` or `mu_s`).
    pub parameter: &'static str,
    /// Period of the orbits in drive periods.
    pub period: usize,
    /// Number of points of the branch.
    pub points: usize,
    /// How the branch ends before its first point.
    pub begin: BranchEnd,
    /// How it ends after its last point.
    pub end: BranchEnd,
    /// `end` in words.
    pub end_text: String,
    /// The special points in order along the branch.
    pub special: Vec<SpecialReport>,
}

/// A special point in a [`BranchReport`].
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct SpecialReport {
    /// `fold`, `branch-point`, `period-doubling`, `neimark-sacker` or `grazing`.
    pub kind: SpecialKind,
    /// The parameter's value.
    pub value: f64,
    /// The strobe point (y, y').
    pub y: f64,
    /// See `y`.
    pub v: f64,
    /// Width of the final bracket in arclength (bounds the error of `value`).
    pub width: f64,
    /// Whether the bracket reached the locating tolerance.
    pub located: bool,
    /// The orbit at the end of the bracket before it.
    pub before: SideReport,
    /// The orbit at the end of the bracket after it.
    pub after: SideReport,
}

/// One side of a special point in a [`BranchReport`].
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct SideReport {
    /// The parameter's value.
    pub value: f64,
    /// The strobe point (y, y').
    pub y: f64,
    /// See `y`.
    pub v: f64,
    /// Stops per orbit period.
    pub stops: usize,
    /// Turning points per orbit period.
    pub turns: usize,
    /// Floquet multipliers as [re, im] pairs, the larger first.
    pub multipliers: [[f64; 2]; 2],
    /// Whether the larger multiplier has modulus below 1.
    pub stable: bool,
}

impl From<&Side> for SideReport {
    fn from(s: &Side) -> Self {
        let m = &s.multipliers;
        Self {
            value: s.value,
            y: s.state.y,
            v: s.state.v,
            stops: s.stops,
            turns: s.turns,
            multipliers: [[m[0].re, m[0].im], [m[1].re, m[1].im]],
            stable: m[0].modulus() < 1.0,
        }
    }
}

impl From<&Branch> for BranchReport {
    fn from(branch: &Branch) -> Self {
        Self {
            parameter: branch.parameter.label(),
            period: branch.period,
            points: branch.points.len(),
            begin: branch.begin.clone(),
            end: branch.end.clone(),
            end_text: branch.end.to_string(),
            special: branch
                .special
                .iter()
                .map(|s| SpecialReport {
                    kind: s.kind,
                    value: s.value,
                    y: s.state.y,
                    v: s.state.v,
                    width: s.width,
                    located: s.located,
                    before: SideReport::from(&s.before),
                    after: SideReport::from(&s.after),
                })
                .collect(),
        }
    }
}
