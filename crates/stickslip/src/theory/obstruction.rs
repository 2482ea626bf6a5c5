//! Why the exact symmetric periodic motion does not exist ([`Obstruction`]). A leaf: it
//! imports nothing of the crate, so [`crate::error`] can carry it.

use serde::{Deserialize, Serialize};

/// Why the symmetric non-sticking periodic solution does not exist.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub enum Obstruction {
    /// ζ = 0 and w = 1/k for odd k: the friction's k-th harmonic (k = 1: the drive itself)
    /// excites the undamped oscillator at resonance; no periodic solution.
    Resonance {
        /// The resonant odd harmonic k.
        order: u32,
    },
    /// β is below β_min = √D·|r|/w: the matching equations have no real root.
    BelowFold {
        /// The smallest β with a real root.
        beta_min: f64,
    },
    /// The root has Y ≤ 0: no motion of that shape.
    NoMotion {
        /// The root's peak value.
        peak: f64,
    },
    /// The net force at the turning point, β cos θ + Y, is within static friction: the
    /// oscillator would stop there.
    StopsAtTurn {
        /// Net force at the turning point (≤ μs).
        force: f64,
    },
    /// The velocity vanishes inside the half period: the oscillator stops (or turns) mid-swing.
    StopsMidSwing {
        /// Local time after the turning point, as a fraction of the half period.
        fraction: f64,
    },
}

impl std::fmt::Display for Obstruction {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Obstruction::Resonance { order: 1 } => write!(
                f,
                "ζ = 0 and w = 1: the undamped oscillator is driven at resonance (secular growth)"
            ),
            Obstruction::Resonance { order } => write!(
                f,
                "ζ = 0 and w = 1/{order}: the friction's harmonic {order} drives the undamped \
                 oscillator at resonance"
            ),
            Obstruction::BelowFold { beta_min } => write!(
                f,
                "no symmetric periodic motion: β is below {beta_min:.6}, where the matching \
                 equations have no real root"
            ),
            Obstruction::NoMotion { peak } => write!(
                f,
                "no symmetric periodic motion: the matching gives the amplitude {peak:.6}, \
                 not a positive one"
            ),
            Obstruction::StopsAtTurn { force } => write!(
                f,
                "the motion would stop at its turning points: net force {force:.6} does not \
                 exceed static friction μs"
            ),
            Obstruction::StopsMidSwing { fraction } => write!(
                f,
                "the velocity vanishes mid-swing ({:.1}% into the half period): the motion stops",
                100.0 * fraction
            ),
        }
    }
}
