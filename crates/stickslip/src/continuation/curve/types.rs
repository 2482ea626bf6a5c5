//! A curve of special points in two parameters: its points, its codimension-two points and
//! why it ends.

use super::{BorderKind, Codim2Kind, Follow};
use crate::continuation::Obstacle;
use crate::params::{Parameter, Params, State};
use crate::stability::{Multiplier, PeriodicOrbit, Stability};
use serde::{Deserialize, Serialize};

/// A point of a curve: the orbit with its special point at (Q, P) = (`over`, `vary`).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct CurvePoint {
    /// The value of the parameter the curve is followed over (Q).
    pub over: f64,
    /// The value of the parameter that follows it (P).
    pub vary: f64,
    /// Arclength from the first point, in (y, y', Q, P).
    pub arclength: f64,
    /// The orbit: strobe state, events, stops, monodromy matrix, multipliers.
    pub orbit: PeriodicOrbit,
    /// Turning points per orbit period.
    pub turns: usize,
    /// Stops per orbit period.
    pub stops: usize,
    /// What the orbit does apart from the followed special point: on a fold or period
    /// doubling curve the other multiplier's modulus against 1, on a grazing curve the larger
    /// multiplier's (the orbit on the side where the event has not appeared), on a
    /// Neimark–Sacker curve [`Stability::Neutral`] (both multipliers on the unit circle).
    pub stability: Stability,
}

impl CurvePoint {
    /// The largest multiplier modulus.
    pub fn largest_multiplier(&self) -> f64 {
        self.orbit.multipliers[0].modulus()
    }

    /// Stops per drive period.
    pub fn stops_per_period(&self) -> f64 {
        self.stops as f64 / self.orbit.period as f64
    }
}

/// The orbit at one end of the bracket of a codimension-two point.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct CurveSide {
    /// Q there.
    pub over: f64,
    /// P there.
    pub vary: f64,
    /// The strobe state.
    pub state: State,
    /// The Floquet multipliers.
    pub multipliers: [Multiplier; 2],
    /// Turning points per orbit period.
    pub turns: usize,
    /// Stops per orbit period.
    pub stops: usize,
}

impl CurveSide {
    pub(crate) fn of(point: &CurvePoint) -> Self {
        Self {
            over: point.over,
            vary: point.vary,
            state: point.orbit.state,
            multipliers: point.orbit.multipliers,
            turns: point.turns,
            stops: point.stops,
        }
    }
}

/// A codimension-two point of a curve, located between two orbits of the curve at most
/// `width` apart in (y, y', Q, P).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Codim2Point {
    /// What meets there.
    pub kind: Codim2Kind,
    /// Q (the middle of the bracket).
    pub over: f64,
    /// P (the middle of the bracket).
    pub vary: f64,
    /// The strobe state (the middle of the bracket).
    pub state: State,
    /// Width of the final bracket: it bounds the error of `over`, `vary` and `state`.
    pub width: f64,
    /// Whether the bracket reached the locating tolerance.
    pub located: bool,
    /// Index of the curve point just before it.
    pub after_point: usize,
    /// The orbit at the end of the bracket before it (along the curve).
    pub before: CurveSide,
    /// The orbit at the end of the bracket after it.
    pub after: CurveSide,
}

/// Where the stability of the curve's orbits changes between two neighbouring points (see
/// [`CurvePoint::stability`]).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct StabilityChange {
    /// Index of the point before the change.
    pub after_point: usize,
    /// Q midway between the two points.
    pub over: f64,
    /// P midway between the two points.
    pub vary: f64,
    /// The stability before.
    pub from: Stability,
    /// The stability after.
    pub to: Stability,
}

/// Why a curve ends.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case", tag = "reason")]
pub enum CurveEnd {
    /// The point the curve started from (the start of a one-way curve).
    Start,
    /// Q reached an end of its range (or P an end of its range, when the curve was asked to
    /// keep P within one: [`follow_curve_within`](super::follow_curve_within)).
    Boundary {
        /// The end of the range.
        value: f64,
    },
    /// P (or Q) left the values the model allows (β < 0, μs < 1, w ≤ 0, ...).
    ParameterLimit {
        /// Q of the last point.
        over: f64,
        /// P of the last point.
        vary: f64,
    },
    /// The most points allowed
    /// ([`ContinuationOptions::max_points`](crate::continuation::ContinuationOptions::max_points)).
    MaxPoints,
    /// The curve came back to its first point.
    Closed,
    /// A codimension-two point past which the followed special point does not go on with this
    /// event sequence (a fold, period doubling or Neimark–Sacker curve meeting a grazing).
    Codim2 {
        /// What meets there.
        kind: Codim2Kind,
        /// Q there.
        over: f64,
        /// P there.
        vary: f64,
    },
    /// Another event of the grazing orbit appears or disappears (its event counts change,
    /// apart from the followed event).
    EventSequence {
        /// Q there.
        over: f64,
        /// P there.
        vary: f64,
        /// (turns, stops) per orbit period before.
        before: (usize, usize),
        /// (turns, stops) after.
        after: (usize, usize),
    },
    /// The steps stayed at or below the crawling step for 25 points.
    Stalled {
        /// Q of the last point.
        over: f64,
        /// P of the last point.
        vary: f64,
        /// The largest multiplier modulus there.
        multiplier: f64,
        /// What the last orbit is closest to.
        obstacle: Obstacle,
    },
    /// No step, however small, could be corrected onto the curve.
    Failed {
        /// Q of the last point.
        over: f64,
        /// P of the last point.
        vary: f64,
        /// What the last orbit is closest to.
        obstacle: Obstacle,
    },
}

impl std::fmt::Display for CurveEnd {
    /// Why the curve ends, in words (one line).
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            CurveEnd::Start => f.write_str("the start point"),
            CurveEnd::Boundary { value } => write!(f, "the end of the range at {value}"),
            CurveEnd::ParameterLimit { over, vary } => write!(
                f,
                "the parameters leave the model's range past ({over:.8}, {vary:.8})"
            ),
            CurveEnd::MaxPoints => f.write_str("the most points allowed (max points)"),
            CurveEnd::Closed => f.write_str("back at its first point (a closed curve)"),
            CurveEnd::Codim2 { kind, over, vary } => write!(
                f,
                "a codimension-two point, {kind}, at ({over:.8}, {vary:.8}): past it the \
                 special point does not go on with this sequence of events"
            ),
            CurveEnd::EventSequence {
                over,
                vary,
                before,
                after,
            } => write!(
                f,
                "another event sequence at ({over:.8}, {vary:.8}): {} turns and {} stops per \
                 orbit period become {} and {}",
                before.0, before.1, after.0, after.1
            ),
            CurveEnd::Stalled {
                over,
                vary,
                multiplier,
                obstacle,
            } => write!(
                f,
                "no progress near ({over:.8}, {vary:.8}) (largest multiplier modulus \
                 {multiplier:.3e}){obstacle}"
            ),
            CurveEnd::Failed {
                over,
                vary,
                obstacle,
            } => write!(
                f,
                "no point could be corrected onto the curve past ({over:.8}, {vary:.8}){obstacle}"
            ),
        }
    }
}

/// The followed condition of a grazing curve: which event, and on which side.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Border {
    /// The kind of event.
    pub kind: BorderKind,
    /// For [`BorderKind::TurnAtLimit`]: the velocity zero is a turning point on the followed
    /// side (else the start of a stop); for [`BorderKind::ReleaseTangential`]: the drive's
    /// extremum falls inside the stop (else after its release). Unused otherwise.
    pub variant: bool,
    /// The sign σ that makes the condition's value σ·h positive on the followed side.
    pub sign: f64,
    /// Whether the orbits on either side of the border join continuously (the branch of one
    /// parameter went through it): then the curve also watches the orbit on the other side
    /// for folds, period doublings and Neimark–Sacker points that meet it there.
    pub continuous: bool,
}

/// A curve of special points in two parameters (see the module documentation).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Curve {
    /// What it follows.
    pub follow: Follow,
    /// For a grazing curve: the event that appears, and the side the orbits are taken on.
    pub border: Option<Border>,
    /// The parameter the curve is followed over (Q).
    pub over: Parameter,
    /// The parameter that follows it (P).
    pub vary: Parameter,
    /// The parameters of the start point (Q and P vary along the curve).
    pub params: Params,
    /// Period p of the orbits in drive periods.
    pub period: usize,
    /// The points in order along the curve.
    pub points: Vec<CurvePoint>,
    /// Index of the start point among `points`.
    pub start: usize,
    /// The codimension-two points in order along the curve.
    pub codim2: Vec<Codim2Point>,
    /// Where the stability of the orbits changes, in order along the curve.
    pub stability_changes: Vec<StabilityChange>,
    /// How the curve ends before its first point.
    pub begin: CurveEnd,
    /// How the curve ends after its last point.
    pub end: CurveEnd,
}
