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
//! 2π). [`SteadySliding`] is that equilibrium with its linearisation.
//!
//! **The cubic law's cycles to first order** ([`CubicBeltApproximation`]): the approximation
//! of Thomsen & Fidlin (2003, "Analytical approximations for stick–slip vibration
//! amplitudes", Int. J. Non-Linear Mech. 38, 389–403) for the law μ(s) = μs − k1 s + k3 s³.
//! Their paper could not be read here (only its abstract): the formulas below are derived
//! here by the method the abstract names, a first-order analysis of the slip phase matched
//! to the stick phase through continuity and periodicity, and are not a transcription.
//!
//! *Assumptions* (in our dimensionless form, vb > 0; vb < 0 is the mirror image): the
//! friction varies little over the cycle's slip speeds beside the spring's force over the
//! amplitude, ε = max(k1, 2ζ, k3 vb²) ≪ 1; β = 0; the law is the cubic one, continuous at
//! the stick (μ(0) = μs), so that the block leaves a stop where the net force vanishes,
//! y_r = μs − 2ζ vb, with y'' = 0. Write y = y_r + r cos θ, y' = −r sin θ: sliding, with the
//! slip speed x = vb − y' ≥ 0,
//!
//! ```text
//! (y − y_r)'' + (y − y_r) = G(x) = −a x + k3 x³,    a = k1 − 2ζ,
//! ```
//!
//! G vanishes at the release. To zeroth order the slide is the circle of radius vb about
//! y_r, leaving the stop at its top (x = vb(1 + sin θ), from θ = −π/2) and coming back to it
//! tangentially after 2π. To first order r′ = −G sin θ; over the revolution
//! Δr = π vb (a − (15/4) k3 vb²) =: π vb b, and the phase gains nothing. Where b > 0 the
//! circle has grown past the belt's speed: the block reaches y' = vb a little before the top,
//! at y_r − vb √(2π b), sticks, and is carried back to y_r in √(2π b) (the stop's length is
//! of order √ε, the slide's lost arc the same, so the period is 2π to that order). The
//! displacement's half range takes r at θ = 0 and θ = π, whose first-order gains add up to
//! Δr by the symmetry of sin θ about π/2:
//!
//! ```text
//! stick-slip (b > 0):   A = (y_max − y_min)/2 ≈ vb (1 + π b / 2),   stop ≈ √(2π b)
//! pure slip:            A ≈ 2 √((a − 3 k3 vb²)/(3 k3))   where 0 < a − 3 k3 vb² and b ≤ 0
//! steady sliding:       A = 0                             where a − 3 k3 vb² ≤ 0
//! ```
//!
//! The pure-slip amplitude is the averaging of the full revolution about steady sliding
//! (energy balance (a − 3k3 vb²) r²/2 = 3 k3 r⁴/8), which reaches vb exactly where b = 0: the
//! two branches meet at vb² = 4a/(15 k3), and steady sliding loses its stability at
//! vb² = a/(3 k3) (where 2ζ + μ'(vb) = 0). How far these are from the exact cycle is measured
//! in `tests/belt_theory.rs` and drawn in the report's chapter "Friction-induced vibration".

use crate::error::Result;
use crate::friction::{check_vb, FrictionLaw};
use crate::limits;
use crate::params::Params;
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

/// Steady sliding of the undriven belt (β = 0, vb ≠ 0): the equilibrium y' = 0,
/// y_e = sgn(vb)·μ(|vb|), and its linearisation y'' + d y' + y = 0 with d = 2ζ + μ'(|vb|)
/// (the law's slope adds to the viscous damping). Dimensionless: rates per unit τ.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct SteadySliding {
    /// Position of the equilibrium, y_e = sgn(vb)·μ(|vb|).
    pub equilibrium: f64,
    /// The damping d = 2ζ + μ'(|vb|) of small oscillations about it.
    pub damping: f64,
    /// The real part of the linearisation's eigenvalues where they are complex (|d| < 2),
    /// −d/2; else the larger real eigenvalue −d/2 + √(d²/4 − 1). Negative: stable.
    pub growth_rate: f64,
    /// The angular frequency √(1 − d²/4) of small oscillations (0 where |d| ≥ 2).
    pub frequency: f64,
}

impl SteadySliding {
    /// Steady sliding for the parameters' law, ζ, μs and vb.
    ///
    /// # Errors
    /// [`crate::Error::InvalidParameter`] naming `vb` when it is 0 (no belt, no sliding) or
    /// `beta` when it is not 0 (a driven belt has no equilibrium).
    pub fn new(params: &Params) -> Result<Self> {
        if params.vb == 0.0 {
            return crate::error::invalid(
                "vb",
                params.vb,
                "must not be 0: steady sliding needs a moving belt",
            );
        }
        if params.beta != 0.0 {
            return crate::error::invalid(
                "beta",
                params.beta,
                "must be 0: a driven belt has no equilibrium",
            );
        }
        let law = params.law;
        let damping = law.sliding_damping(params.zeta, params.mu_s, params.vb);
        let half = 0.5 * damping;
        let (growth_rate, frequency) = if half.abs() < 1.0 {
            (-half, (1.0 - half * half).sqrt())
        } else {
            (-half + (half * half - 1.0).sqrt(), 0.0)
        };
        Ok(Self {
            equilibrium: law.sliding_equilibrium(params.mu_s, params.vb),
            damping,
            growth_rate,
            frequency,
        })
    }

    /// Whether small oscillations die out (d > 0).
    pub fn is_stable(&self) -> bool {
        self.damping > 0.0
    }

    /// Whether small oscillations grow (d < 0).
    pub fn is_unstable(&self) -> bool {
        self.damping < 0.0
    }
}

/// What the first-order approximation says the undriven cubic belt settles on (see the
/// module documentation).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum CubicBeltMotion {
    /// b = a − (15/4) k3 vb² > 0.
    StickSlip,
    /// b ≤ 0 < a − 3 k3 vb².
    PureSlip,
    /// a − 3 k3 vb² ≤ 0.
    SteadySliding,
}

/// The undriven cubic belt's cycle to first order: Thomsen & Fidlin's approximation, derived
/// in the module documentation (which states its assumptions).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct CubicBeltApproximation {
    /// Which motion.
    pub motion: CubicBeltMotion,
    /// The half range (y_max − y_min)/2 of y (0 for steady sliding).
    pub amplitude: f64,
    /// The duration of the stop in τ (0 without one).
    pub stick_time: f64,
    /// The period in τ: 2π to this order; `None` for steady sliding.
    pub period: Option<f64>,
    /// The belt speed where stick-slip gives way to pure slip, √(4a/(15 k3)) (infinite for
    /// k3 = 0; `None` where a ≤ 0: no self-excitation at all).
    pub vb_stick_slip: Option<f64>,
    /// The belt speed where steady sliding turns stable, √(a/(3 k3)).
    pub vb_hopf: Option<f64>,
}

impl CubicBeltApproximation {
    /// The approximation at damping `zeta`, static level `mu_s`, law coefficients `k1`, `k3`
    /// and belt speed `vb` ≠ 0 (the amplitude is the same for −vb).
    ///
    /// # Errors
    /// [`crate::Error::InvalidParameter`] naming `zeta` (negative), `vb` (0 or out of
    /// range), or the law's `k1`/`k3` when the law goes negative
    /// ([`FrictionLaw::validate`]).
    pub fn new(zeta: f64, mu_s: f64, k1: f64, k3: f64, vb: f64) -> Result<Self> {
        crate::error::check(
            "zeta",
            zeta,
            zeta.is_finite() && zeta >= 0.0,
            "must be finite and >= 0",
        )?;
        crate::error::check(
            "mu_s",
            mu_s,
            limits::mu_s_ok(mu_s),
            "must be finite and >= 1",
        )?;
        FrictionLaw::Cubic { k1, k3 }.validate(mu_s)?;
        let vb = check_vb(vb)?;
        if vb == 0.0 {
            return crate::error::invalid(
                "vb",
                vb,
                "must not be 0: a belt at rest excites nothing",
            );
        }
        let speed = vb.abs();
        let a = k1 - 2.0 * zeta;
        let b = a - 3.75 * k3 * speed * speed;
        let linear = a - 3.0 * k3 * speed * speed;
        let speed_at = |c: f64| {
            (a > 0.0).then(|| {
                if k3 > 0.0 {
                    (a / (c * k3)).sqrt()
                } else {
                    f64::INFINITY
                }
            })
        };
        let (motion, amplitude, stick_time, period) = if b > 0.0 {
            let b_pi = std::f64::consts::PI * b;
            (
                CubicBeltMotion::StickSlip,
                speed * (1.0 + 0.5 * b_pi),
                (2.0 * b_pi).sqrt(),
                Some(2.0 * PI),
            )
        } else if linear > 0.0 {
            (
                CubicBeltMotion::PureSlip,
                2.0 * (linear / (3.0 * k3)).sqrt(),
                0.0,
                Some(2.0 * PI),
            )
        } else {
            (CubicBeltMotion::SteadySliding, 0.0, 0.0, None)
        };
        Ok(Self {
            motion,
            amplitude,
            stick_time,
            period,
            vb_stick_slip: speed_at(3.75),
            vb_hopf: speed_at(3.0),
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
