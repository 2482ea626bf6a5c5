//! The summary of a curve that `stickslip curve --json` prints.

use super::{Codim2Kind, Codim2Point, Curve, CurveEnd, CurveSide, Follow, StabilityChange};
use serde::Serialize;

/// What a curve reports besides its points: exactly what `stickslip curve --json` prints and
/// what the Python package's `curve` keeps as its summary. Build it with
/// `CurveReport::from(&curve)`.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct CurveReport {
    /// What the curve follows (`grazing`, `fold`, `period-doubling`, `neimark-sacker`).
    pub follow: Follow,
    /// For a grazing curve, the event that appears (`turn-at-limit`, `slide-touches-rest`,
    /// `release-tangential`); null otherwise.
    pub border: Option<&'static str>,
    /// The parameter the curve is followed over (Q: `w`, `beta`, `zeta`, `mu_s` or `vb`).
    pub over: &'static str,
    /// The parameter that follows it (P).
    pub vary: &'static str,
    /// Period of the orbits in drive periods.
    pub period: usize,
    /// Number of points of the curve.
    pub points: usize,
    /// The start point: `over`, `vary` (its values of Q and P) and `y`, `v` (its strobe
    /// point), and `index` among the points.
    pub start: CurveStartReport,
    /// The codimension-two points in order along the curve.
    pub codim2: Vec<Codim2Report>,
    /// Where the orbits' stability changes along the curve.
    pub stability_changes: Vec<StabilityChange>,
    /// How the curve ends before its first point.
    pub begin: CurveEnd,
    /// How it ends after its last point.
    pub end: CurveEnd,
    /// `begin` in words.
    pub begin_text: String,
    /// `end` in words.
    pub end_text: String,
}

/// The start point in a [`CurveReport`].
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct CurveStartReport {
    /// Index among the curve's points.
    pub index: usize,
    /// Q.
    pub over: f64,
    /// P.
    pub vary: f64,
    /// The strobe point (y, y').
    pub y: f64,
    /// See `y`.
    pub v: f64,
}

/// A codimension-two point in a [`CurveReport`].
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Codim2Report {
    /// What meets there (`cusp`, `fold-grazing`, ...).
    pub kind: Codim2Kind,
    /// Q.
    pub over: f64,
    /// P.
    pub vary: f64,
    /// The strobe point (y, y').
    pub y: f64,
    /// See `y`.
    pub v: f64,
    /// Width of the final bracket in (y, y', Q, P): it bounds the error of the values.
    pub width: f64,
    /// Whether the bracket reached the locating tolerance.
    pub located: bool,
    /// The orbit at the end of the bracket before it.
    pub before: CurveSideReport,
    /// The orbit at the end of the bracket after it.
    pub after: CurveSideReport,
}

/// One side of a codimension-two point in a [`CurveReport`].
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct CurveSideReport {
    /// Q.
    pub over: f64,
    /// P.
    pub vary: f64,
    /// Stops per orbit period.
    pub stops: usize,
    /// Turning points per orbit period.
    pub turns: usize,
    /// Floquet multipliers as [re, im] pairs, the larger first.
    pub multipliers: [[f64; 2]; 2],
}

impl From<&CurveSide> for CurveSideReport {
    fn from(s: &CurveSide) -> Self {
        let m = &s.multipliers;
        Self {
            over: s.over,
            vary: s.vary,
            stops: s.stops,
            turns: s.turns,
            multipliers: [[m[0].re, m[0].im], [m[1].re, m[1].im]],
        }
    }
}

impl From<&Codim2Point> for Codim2Report {
    fn from(c: &Codim2Point) -> Self {
        Self {
            kind: c.kind,
            over: c.over,
            vary: c.vary,
            y: c.state.y,
            v: c.state.v,
            width: c.width,
            located: c.located,
            before: CurveSideReport::from(&c.before),
            after: CurveSideReport::from(&c.after),
        }
    }
}

impl From<&Curve> for CurveReport {
    fn from(curve: &Curve) -> Self {
        let start = &curve.points[curve.start];
        Self {
            follow: curve.follow,
            border: curve.border.map(|b| b.kind.label()),
            over: curve.over.label(),
            vary: curve.vary.label(),
            period: curve.period,
            points: curve.points.len(),
            start: CurveStartReport {
                index: curve.start,
                over: start.over,
                vary: start.vary,
                y: start.orbit.state.y,
                v: start.orbit.state.v,
            },
            codim2: curve.codim2.iter().map(Codim2Report::from).collect(),
            stability_changes: curve.stability_changes.clone(),
            begin: curve.begin.clone(),
            end: curve.end.clone(),
            begin_text: curve.begin.to_string(),
            end_text: curve.end.to_string(),
        }
    }
}
