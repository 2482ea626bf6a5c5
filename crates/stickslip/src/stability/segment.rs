//! State-transition matrices of the segments between events.
//!
//! **Sliding.** On a slide with direction s the state x = (y, y') obeys
//! x' = (y', β cos(wτ + φ) − y − 2ζy' − s). The friction force −s and the drive do not depend
//! on the state, so a perturbation obeys the same linear equation for every slide,
//!
//! ```text
//! δx' = A δx,   A = [[0, 1], [−1, −2ζ]],   Φ(Δτ) = e^{AΔτ},
//! ```
//!
//! whatever the drive, its phase and the direction. In the basis of the closed form,
//! `EC(t) = e^{−ζt} C(t)`, `ES(t) = e^{−ζt} S(t)` (C = cos ω_d t, S = sin(ω_d t)/ω_d for
//! ζ < 1 with ω_d = √(1 − ζ²); C = 1, S = t at ζ = 1; C = cosh κt, S = sinh(κt)/κ for ζ > 1
//! with κ = √(ζ² − 1)), the solution from (δy₀, δv₀) is δy = δy₀(EC + ζES) + δv₀ ES, so
//!
//! ```text
//! Φ(Δτ) = [[EC + ζES,  ES      ],
//!          [−ES,       EC − ζES]]      (at t = Δτ),
//! ```
//!
//! and by Liouville's formula det Φ = e^{tr A·Δτ} = e^{−2ζΔτ}. At ζ = 0 this is the rotation
//! [[cos Δτ, sin Δτ], [−sin Δτ, cos Δτ]], also in the secular case w = 1 (only the particular
//! solution is secular). For ζ > 1 and κΔτ > 1 the entries are formed from the two modes
//! e₁ = e^{−ρΔτ}, ρ = 1/(ζ + κ), and e₂ = e^{−(ζ+κ)Δτ}, which do not cancel:
//! Φ = [[(ζ+κ)e₁ − ρe₂, e₁ − e₂], [e₂ − e₁, (ζ+κ)e₂ − ρe₁]]/(2κ).
//!
//! **Stuck.** While stuck at y_s the state is (y_s, 0). A perturbed state (y_s + δy, δv) with
//! |β cos(wτ + φ) − y_s| < 1 slides against the kinetic friction, which stops it within a time
//! of order |δv| after a displacement of order δv²: to first order δy is kept and δv erased,
//! Φ_stick = diag(1, 0). Where 1 < |β cos(wτ + φ) − y_s| ≤ μs (possible only for μs > 1) a
//! velocity perturbation along the net force is not stopped (the stiction law is not a
//! Filippov system there) and the flow is not differentiable in δv; diag(1, 0) is then the
//! one-sided derivative on the side that stays stuck. Along a trajectory a stop is always
//! entered through a stick event, whose saltation has already erased δv (see
//! [`super::saltation`]), so the choice matters only for a motion that starts stuck.

use super::matrix::Matrix2;
use crate::trig::sin_cos;

/// The state-transition matrix Φ(Δτ) of a sliding segment of (dimensionless) duration
/// `dtau` ≥ 0 at damping ratio `zeta` ≥ 0 (see the module documentation). The same for both
/// directions, every drive and every phase.
///
/// ```
/// use stickslip::stability::sliding_transition;
/// // Undamped: a rotation by Δτ.
/// let m = sliding_transition(0.0, 0.5).0;
/// assert!((m[0][0] - 0.5f64.cos()).abs() < 1e-15 && (m[0][1] - 0.5f64.sin()).abs() < 1e-15);
/// // Liouville: det Φ = e^{−2ζΔτ}.
/// let phi = sliding_transition(0.3, 2.0);
/// assert!((phi.det() - (-1.2f64).exp()).abs() < 1e-15);
/// ```
pub fn sliding_transition(zeta: f64, dtau: f64) -> Matrix2 {
    SlidingTransition::new(zeta).at(dtau)
}

/// The state-transition matrix of a stuck segment of any duration: diag(1, 0) (see the module
/// documentation).
pub fn stuck_transition() -> Matrix2 {
    Matrix2::diagonal(1.0, 0.0)
}

/// Φ(Δτ) of sliding segments at one damping ratio, with what the regime needs computed once.
#[derive(Debug, Clone, Copy)]
pub(crate) struct SlidingTransition {
    zeta: f64,
    /// ω_d (ζ < 1) or κ (ζ > 1); 0 at ζ = 1.
    omega: f64,
    /// 1/ω_d (ζ < 1) or 1/(2κ) (ζ > 1).
    inv: f64,
    /// ρ = 1/(ζ + κ), the slow decay rate (ζ > 1).
    slow: f64,
}

impl SlidingTransition {
    pub(crate) fn new(zeta: f64) -> Self {
        if zeta < 1.0 {
            let omega = ((1.0 - zeta) * (1.0 + zeta)).sqrt();
            Self {
                zeta,
                omega,
                inv: 1.0 / omega,
                slow: zeta,
            }
        } else if zeta == 1.0 {
            Self {
                zeta,
                omega: 0.0,
                inv: 0.0,
                slow: 1.0,
            }
        } else {
            let kappa = ((zeta - 1.0) * (zeta + 1.0)).sqrt();
            Self {
                zeta,
                omega: kappa,
                inv: 0.5 / kappa,
                slow: 1.0 / (zeta + kappa),
            }
        }
    }

    /// Φ(t) for t ≥ 0.
    #[inline]
    pub(crate) fn at(&self, t: f64) -> Matrix2 {
        let z = self.zeta;
        let (ec, es) = if z < 1.0 {
            let e = (-z * t).exp();
            let (s, c) = sin_cos(self.omega * t);
            (e * c, e * s * self.inv)
        } else if z == 1.0 {
            let e = (-t).exp();
            (e, e * t)
        } else {
            let k = self.omega;
            if k * t > 1.0 {
                let fast_rate = z + k;
                let e1 = (-self.slow * t).exp();
                let e2 = (-fast_rate * t).exp();
                return Matrix2([
                    [
                        (fast_rate * e1 - self.slow * e2) * self.inv,
                        (e1 - e2) * self.inv,
                    ],
                    [
                        (e2 - e1) * self.inv,
                        (fast_rate * e2 - self.slow * e1) * self.inv,
                    ],
                ]);
            }
            let e = (-z * t).exp();
            (e * (k * t).cosh(), e * (k * t).sinh() / k)
        };
        Matrix2([[ec + z * es, es], [-es, ec - z * es]])
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Φ against a fine RK4 integration of δx' = A δx, and Liouville, in every regime and on
    /// both sides of the switch between the two overdamped forms.
    #[test]
    fn transition_matches_the_variational_equation() {
        for &zeta in &[0.0, 0.05, 0.7, 0.999_999, 1.0, 1.000_001, 1.5, 12.0] {
            for &t in &[0.0, 0.01, 0.3, 1.0 / 3.0, 2.0, 9.0] {
                let phi = sliding_transition(zeta, t);
                let steps = 20_000;
                let h = t / steps as f64;
                let f = |x: [f64; 2]| [x[1], -x[0] - 2.0 * zeta * x[1]];
                for col in 0..2 {
                    let mut x = [0.0; 2];
                    x[col] = 1.0;
                    for _ in 0..steps {
                        let k1 = f(x);
                        let k2 = f([x[0] + 0.5 * h * k1[0], x[1] + 0.5 * h * k1[1]]);
                        let k3 = f([x[0] + 0.5 * h * k2[0], x[1] + 0.5 * h * k2[1]]);
                        let k4 = f([x[0] + h * k3[0], x[1] + h * k3[1]]);
                        for i in 0..2 {
                            x[i] += h / 6.0 * (k1[i] + 2.0 * k2[i] + 2.0 * k3[i] + k4[i]);
                        }
                    }
                    for row in 0..2 {
                        // RK4 error ~ (h·max rate)⁴ with rate up to 2ζ: 1e-12 here.
                        assert!(
                            (phi.0[row][col] - x[row]).abs() < 1e-11,
                            "zeta {zeta} t {t} [{row}][{col}]: {} vs {}",
                            phi.0[row][col],
                            x[row]
                        );
                    }
                }
                let liouville = (-2.0 * zeta * t).exp();
                assert!(
                    (phi.det() - liouville).abs() < 1e-13 * (1.0 + liouville),
                    "zeta {zeta} t {t}: det {} vs {liouville}",
                    phi.det()
                );
            }
        }
    }

    #[test]
    fn transition_is_a_semigroup() {
        for &zeta in &[0.0, 0.3, 1.0, 4.0] {
            let (a, b) = (0.7, 1.9);
            let product = sliding_transition(zeta, b) * sliding_transition(zeta, a);
            let direct = sliding_transition(zeta, a + b);
            for (p, d) in product.0.iter().flatten().zip(direct.0.iter().flatten()) {
                assert!(
                    (p - d).abs() < 1e-14,
                    "zeta {zeta}: {product:?} vs {direct:?}"
                );
            }
        }
    }
}
