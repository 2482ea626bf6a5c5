//! A branch of periodic orbits: its points and why it ends.

use super::{Obstacle, Side, SlideMinimum, SpecialPoint};
use crate::params::{Parameter, Params, State};
use crate::stability::PeriodicOrbit;
use serde::{Deserialize, Serialize};

/// A point of a branch: a periodic orbit and where it sits on the branch.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct BranchPoint {
    /// The continued parameter's value.
    pub value: f64,
    /// Arclength from the first point of the branch, in (y, y', λ).
    pub arclength: f64,
    /// The orbit: strobe state (the fixed point of P^p), events, stops, monodromy matrix,
    /// Floquet multipliers, stability.
    pub orbit: PeriodicOrbit,
    /// The p strobe points of the orbit: x, P(x), …, P^{p−1}(x).
    pub strobes: Vec<State>,
    /// Smallest y over the orbit.
    pub y_min: f64,
    /// Largest y over the orbit.
    pub y_max: f64,
    /// Turning points per orbit period.
    pub turns: usize,
    /// Stops (stick events, zero-duration stops included) per orbit period.
    pub stops: usize,
}

impl BranchPoint {
    /// Half the peak-to-peak excursion, (y_max − y_min)/2.
    pub fn amplitude(&self) -> f64 {
        0.5 * (self.y_max - self.y_min)
    }

    /// Stops per drive period.
    pub fn stops_per_period(&self) -> f64 {
        self.stops as f64 / self.orbit.period as f64
    }

    /// Whether the orbit is stable: its larger Floquet multiplier has modulus below 1.
    pub fn stable(&self) -> bool {
        self.orbit.multipliers[0].modulus() < 1.0
    }
}

/// A branch of periodic orbits (see the module documentation).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Branch {
    /// The parameters of the start orbit (the continued one varies along the branch).
    pub params: Params,
    /// The continued parameter.
    pub parameter: Parameter,
    /// Period p of the orbits in drive periods.
    pub period: usize,
    /// The points in order along the branch.
    pub points: Vec<BranchPoint>,
    /// The special points in order along the branch.
    pub special: Vec<SpecialPoint>,
    /// How the branch ends before its first point.
    pub begin: BranchEnd,
    /// How the branch ends after its last point.
    pub end: BranchEnd,
}

/// Why a branch ends.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case", tag = "reason")]
pub enum BranchEnd {
    /// The orbit the continuation started from (the start of a one-way branch).
    Start,
    /// The parameter reached an end of the range.
    Boundary {
        /// The end of the range.
        value: f64,
    },
    /// [`ContinuationOptions::max_points`](super::ContinuationOptions::max_points) points.
    MaxPoints,
    /// The branch came back to its first point: a closed curve (an isola).
    Closed,
    /// The orbit came to rest (no events: a continuum of rest positions, not a branch).
    Rest {
        /// The parameter's value.
        value: f64,
    },
    /// The steps stayed at or below
    /// [`ContinuationOptions::crawl_step`](super::ContinuationOptions::crawl_step) for 25 points:
    /// the branch approaches a point it cannot pass.
    Stalled {
        /// The parameter's value of the last point.
        value: f64,
        /// The largest multiplier modulus there.
        multiplier: f64,
        /// What the last orbit is closest to.
        obstacle: Obstacle,
    },
    /// A slide of the last orbit grazes rest with the net force within the static limit
    /// (μs > 1): a stop of finite length appears mid-swing there and the strobe map jumps, so
    /// the branch ends (its orbit ceases to exist past it; the motion goes to another orbit,
    /// or chaos).
    Grazing {
        /// Where the slide's lowest speed reaches zero, by the secant of the last two points
        /// (the last point's value when it cannot be extrapolated).
        value: f64,
        /// The parameter's value of the last point.
        last: f64,
        /// The largest multiplier modulus there.
        multiplier: f64,
        /// The slide that grazes, at the last point.
        slide: SlideMinimum,
        /// An orbit of the same period with the new stop just past the grazing (by Newton's
        /// method from the last strobe state and from its image), when there is one: it lies
        /// on another branch, a finite jump away.
        beyond: Option<Side>,
    },
    /// No step, however small, could be corrected onto the branch.
    Failed {
        /// The parameter's value of the last point.
        value: f64,
        /// What the last orbit is closest to.
        obstacle: Obstacle,
    },
}

impl std::fmt::Display for BranchEnd {
    /// Why the branch ends, in words (one line).
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            BranchEnd::Start => f.write_str("the start orbit"),
            BranchEnd::Boundary { value } => write!(f, "the end of the range at {value}"),
            BranchEnd::MaxPoints => f.write_str("the most points allowed (max points)"),
            BranchEnd::Closed => f.write_str("back at its first point (a closed branch)"),
            BranchEnd::Rest { value } => write!(f, "the orbit comes to rest at {value}"),
            BranchEnd::Stalled {
                value,
                multiplier,
                obstacle,
            } => write!(
                f,
                "no progress near {value:.8} (largest multiplier modulus {multiplier:.3e}){obstacle}"
            ),
            BranchEnd::Grazing {
                value,
                last,
                multiplier,
                slide,
                beyond,
            } => {
                write!(
                    f,
                    "a grazing at {value:.8} (last point {last:.8}, largest multiplier modulus \
                     {multiplier:.3e}): {}, within the static limit; a stop of finite length \
                     appears mid-swing there and the strobe map jumps",
                    slide.describe()
                )?;
                match beyond {
                    Some(s) => write!(
                        f,
                        "; past it lies another orbit of this period with the new stop, on a \
                         branch of its own ({} stops, {} turns, strobe y = {:.6}, y' = {:.6}, \
                         |μ1| = {:.4})",
                        s.stops,
                        s.turns,
                        s.state.y,
                        s.state.v,
                        s.multipliers[0].modulus()
                    ),
                    None => f.write_str("; no orbit of this period with the new stop lies just past it"),
                }
            }
            BranchEnd::Failed { value, obstacle } => write!(
                f,
                "no orbit could be corrected past {value:.8}: the strobe map breaks there{obstacle}"
            ),
        }
    }
}
