//! The block on a moving belt without a drive, in closed form where it has one.
//!
//! **The undamped Coulomb belt** (ζ = 0, Coulomb's law, β = 0, belt speed vb > 0, static
//! level μs ≥ 1). Stuck to the belt the block moves with it, y' = vb, until the spring's
//! force −y reaches the static limit −μs: it slips at y_r = μs with y' = vb. Slipping
//! behind the belt (s = y' − vb < 0) kinetic friction pushes it forward with force 1:
//!
//! ```text
//! y'' + y = 1,    (y − 1)² + y'² = R² = (μs − 1)² + vb²
//! ```
//!
//! a circle about (1, 0) through the release point. The slip ends where y' = vb again, at
//! the circle's other point on that line, y_s = 2 − μs, after the arc through the lower half
//! of the circle (where y' < vb): with the release at angle α = atan2(vb, μs − 1) above the
//! y-axis seen from the centre, the arc is π + 2α. There the net force −y_s = μs − 2 lies
//! within the static limit (|μs − 2| ≤ μs for μs ≥ 1): the block sticks, and is carried from
//! 2 − μs back to μs in 2(μs − 1)/vb. So
//!
//! ```text
//! y_max = 1 + R,   y_min = 1 − R,   T = π + 2 atan2(vb, μs − 1) + 2(μs − 1)/vb,
//! stick fraction = 2(μs − 1)/(vb T),
//! ```
//!
//! the stick-slip cycle reached after the first stop whatever the start (every stop ends at
//! the release point). At μs = 1 the stop shrinks to an instant and the cycle is the circle
//! of radius vb, T = 2π. A belt moving backwards (vb < 0) gives the mirror image y → −y.
//!
//! **Steady sliding** of any law (y' = 0, y = sgn(vb)·μ(|vb|)) is stable where
//! 2ζ + μ'(|vb|) > 0 ([`crate::friction::FrictionLaw::sliding_damping`]): the Coulomb belt's
//! is stable for every ζ > 0 and neutral at ζ = 0, where it is the centre of the family of
//! circles of radius below |vb| that never reach the belt's speed (pure-slip cycles of period
//! 2π).

use crate::error::Result;
use crate::friction::check_vb;
use crate::limits;
use serde::{Deserialize, Serialize};
use std::f64::consts::PI;

/// The undamped Coulomb belt's stick-slip cycle (see the module documentation).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct CoulombBeltCycle {
    /// Radius R = √((μs − 1)² + vb²) of the slip's circle about y = sgn(vb).
    pub radius: f64,
    /// Largest y.
    pub y_max: f64,
    /// Smallest y.
    pub y_min: f64,
    /// Where the block slips: y = sgn(vb)·μs.
    pub release_y: f64,
    /// Where it sticks: y = sgn(vb)·(2 − μs).
    pub stick_y: f64,
    /// Duration of the slip, π + 2 atan2(|vb|, μs − 1).
    pub slip_time: f64,
    /// Duration of the stop, 2(μs − 1)/|vb|.
    pub stick_time: f64,
    /// The period, slip and stop.
    pub period: f64,
    /// The fraction of the period stuck.
    pub stick_fraction: f64,
}

impl CoulombBeltCycle {
    /// The cycle at static level `mu_s` ≥ 1 and belt speed `vb` ≠ 0.
    ///
    /// # Errors
    /// [`crate::Error::InvalidParameter`] naming `mu_s` or `vb` (which must not be 0: the
    /// belt at rest has no self-excited cycle).
    pub fn new(mu_s: f64, vb: f64) -> Result<Self> {
        crate::error::check(
            "mu_s",
            mu_s,
            limits::mu_s_ok(mu_s),
            "must be finite and >= 1",
        )?;
        let vb = check_vb(vb)?;
        if vb == 0.0 {
            return crate::error::invalid(
                "vb",
                vb,
                "must not be 0: a belt at rest excites nothing",
            );
        }
        let (sign, speed) = (vb.signum(), vb.abs());
        let excess = mu_s - 1.0;
        let radius = excess.hypot(speed);
        let slip_time = PI + 2.0 * speed.atan2(excess);
        let stick_time = 2.0 * excess / speed;
        let period = slip_time + stick_time;
        let (high, low) = (1.0 + radius, 1.0 - radius);
        let (y_max, y_min) = if sign > 0.0 {
            (high, low)
        } else {
            (-low, -high)
        };
        Ok(Self {
            radius,
            y_max,
            y_min,
            release_y: sign * mu_s,
            stick_y: sign * (2.0 - mu_s),
            slip_time,
            stick_time,
            period,
            stick_fraction: stick_time / period,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_cycle_is_a_circle_joined_to_a_stop() {
        let c = CoulombBeltCycle::new(1.5, 0.5).unwrap();
        // R² = 0.25 + 0.25; the release sits 45° above the axis: the arc is π + π/2.
        assert!((c.radius - 0.5f64.sqrt()).abs() < 1e-15);
        assert!((c.slip_time - 1.5 * PI).abs() < 1e-15);
        assert!((c.stick_time - 2.0).abs() < 1e-15);
        assert_eq!((c.release_y, c.stick_y), (1.5, 0.5));
        let m = CoulombBeltCycle::new(1.5, -0.5).unwrap();
        assert_eq!((m.y_max, m.y_min), (-c.y_min, -c.y_max));
        let one = CoulombBeltCycle::new(1.0, 0.3).unwrap();
        assert!((one.period - 2.0 * PI).abs() < 1e-15 && one.stick_time == 0.0);
        assert!(CoulombBeltCycle::new(1.5, 0.0).is_err());
        assert!(CoulombBeltCycle::new(0.5, 1.0).is_err());
    }
}
