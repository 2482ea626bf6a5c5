//! The paper's series solution (its eqs. (9)–(11)) and its approximate stick-slip boundary
//! (its eq. (13)), transcribed literally into our dimensionless notation.
//!
//! The paper writes ẍ + ω0²x + αẋ + sgn(ẋ) = β cos(Ωt + φ0) (its eq. (5)). With τ = ω0·t,
//! y = ω0²x, ω0 = 1, Ω → w and α → 2ζ this is our model, and its formulas read:
//!
//! ```text
//! eq. (11)  Z        = √((1 − w²)² + 4ζ²w²)
//!           A1       = (−8ζw + √(π²β²Z² − 16(w² − 1)²)) / (πZ²)          φ1 = 0
//!           A_{2n−1} = (4/((2n−1)π)) / √((1 − (2n−1)²w²)² + 4ζ²(2n−1)²w²)
//!           φ_{2n−1} = −π/2 − arctan(2ζ(2n−1)w / (1 − (2n−1)²w²))
//!           φ0       = arccos((1 − w²)A1/β)
//! eq. (9)   (ζ = 0)  A1 = √(β² − (4/π)²)/(1 − w²),
//!                    A_{2n−1} = 4/((2n−1)π((2n−1)²w² − 1)),   φ0 = arcsin(4/(βπ))
//! eq. (13)  −A1 + 1 + β cos φ0 = 0,  i.e. (with β cos φ0 = (1 − w²)A1)  w²·A1 = 1
//! ```
//!
//! The motion is `x = A1 cos(wτ) + Σ_{n≥2} A_{2n−1} cos((2n−1)wτ + φ_{2n−1})` (the paper's
//! eq. (10)) under the drive `β cos(wτ + φ0)`: the drive leads the fundamental by φ0.
//!
//! These are the harmonic balance of eq. (5) with the friction replaced by the square wave of
//! x ≈ A1 cos(wτ) (the paper's eq. (7)), which assumes the turning points sit at the extremes
//! of the fundamental. Two things about the printed formulas, checked in the tests:
//!
//! - The amplitudes A_{2n−1} (n ≥ 2) of eq. (11) are *exact* for every symmetric
//!   non-sticking motion: its friction force is exactly a square wave, whose harmonics have
//!   these amplitudes whatever its phase (see [`super::periodic`]). Only A1 and the phases are
//!   approximate.
//! - Two printed signs disagree with the harmonic balance of eq. (7): in eq. (9) A_{2n−1}
//!   should be 4/((2n−1)π(1 − (2n−1)²w²)) (opposite sign), and in eq. (11) the principal
//!   arctan puts φ_{2n−1} off by π when (2n−1)w > 1 (the two-argument arctan is meant). This
//!   module reproduces the printed formulas; [`PaperHarmonic::balance_phase`] gives the phase
//!   the harmonic balance yields.

use crate::error::{check, Error, NoSolutionReason, Quantity, Result};
use serde::{Deserialize, Serialize};
use std::f64::consts::{FRAC_PI_2, PI};

/// 4/π, the fundamental of the unit square wave sgn(sin).
const FOUR_OVER_PI: f64 = 4.0 / PI;

fn check_zeta_w(zeta: f64, w: f64) -> Result<()> {
    check("zeta", zeta, zeta >= 0.0, "must be finite and >= 0")?;
    check("w", w, w > 0.0, "must be finite and > 0")?;
    Ok(())
}

/// The paper's damped series solution, eq. (11), at one (ζ, w, β).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct PaperSeries {
    /// Damping ratio ζ (the paper's α = 2ζ).
    pub zeta: f64,
    /// Drive frequency w = Ω/ω0.
    pub w: f64,
    /// Drive amplitude β.
    pub beta: f64,
    /// Fundamental amplitude A1 of eq. (11), > 0 (same units as y).
    pub a1: f64,
    /// Drive phase φ0 = arccos((1 − w²)A1/β) of eq. (11), radians in [0, π]: the drive leads
    /// the fundamental A1 cos(wτ) by φ0 (the fundamental lags the drive by φ0).
    pub phi0: f64,
}

impl PaperSeries {
    /// Evaluate eq. (11) at (ζ, w, β).
    ///
    /// # Errors
    /// - [`Error::InvalidParameter`] for ζ < 0, w ≤ 0, β < 0 or non-finite values.
    /// - [`Error::NoSolution`] where eq. (11) has no real positive A1: at ζ = 0, w = 1 (Z = 0,
    ///   the formula is 0/0); where π²β²Z² < 16(w² − 1)² (square root of a negative number);
    ///   and where A1 < 0, which happens exactly when β < 4/π (the friction's square wave
    ///   outweighs the drive).
    pub fn new(zeta: f64, w: f64, beta: f64) -> Result<Self> {
        check_zeta_w(zeta, w)?;
        check("beta", beta, beta >= 0.0, "must be finite and >= 0")?;
        let a1 = eq11_a1(zeta, w, beta)?;
        if a1 < 0.0 {
            return Err(Error::NoSolution {
                what: Quantity::PaperA1,
                reason: NoSolutionReason::NegativeAmplitude { a1, beta },
            });
        }
        // Rounding can push the cosine a hair past ±1 when the drive barely beats friction.
        let cos_phi0 = ((1.0 - w) * (1.0 + w) * a1 / beta).clamp(-1.0, 1.0);
        Ok(Self {
            zeta,
            w,
            beta,
            a1,
            phi0: cos_phi0.acos(),
        })
    }

    /// Gain of the fundamental G1 = A1/β: what eq. (11) gives for the paper's G (its Table 1:
    /// U_C0/U for the circuit, ω0²r0/(F/m) for the oscillator), which for a motion that is
    /// not sinusoidal is the gain G = (y_max − y_min)/(2β) of a steady state only
    /// approximately.
    pub fn gain1(&self) -> f64 {
        self.a1 / self.beta
    }

    /// The former name of [`PaperSeries::gain1`].
    #[deprecated(note = "A1/β is `gain1` (G1); `gain` is G = (y_max − y_min)/(2β)")]
    pub fn gain(&self) -> f64 {
        self.gain1()
    }

    /// The superharmonic A_{2n−1}, φ_{2n−1} of eq. (11), for n ≥ 2 (order 3, 5, …).
    ///
    /// # Errors
    /// [`Error::NoSolution`] at ζ = 0, (2n−1)w = 1, where the amplitude is infinite.
    ///
    /// # Panics
    /// When n < 2 (A1 is [`PaperSeries::a1`]).
    pub fn harmonic(&self, n: u32) -> Result<PaperHarmonic> {
        assert!(n >= 2, "superharmonics start at n = 2 (order 3)");
        PaperHarmonic::new(self.zeta, self.w, 2 * n - 1)
    }

    /// Whether β lies above the paper's own stick-slip boundary, i.e. w²·A1 > 1 (eq. (13)).
    pub fn slides_by_eq13(&self) -> bool {
        self.w * self.w * self.a1 > 1.0
    }
}

/// A1 of eq. (11) as printed, which may be negative.
fn eq11_a1(zeta: f64, w: f64, beta: f64) -> Result<f64> {
    let detune = (1.0 - w) * (1.0 + w);
    let z2 = detune * detune + 4.0 * zeta * zeta * w * w;
    if z2 == 0.0 {
        return Err(Error::NoSolution {
            what: Quantity::PaperA1,
            reason: NoSolutionReason::ZeroImpedance,
        });
    }
    let radicand = PI * PI * beta * beta * z2 - 16.0 * detune * detune;
    if radicand < 0.0 {
        return Err(Error::NoSolution {
            what: Quantity::PaperA1,
            reason: NoSolutionReason::NegativeRadicand {
                radicand,
                beta,
                beta_min: FOUR_OVER_PI * detune.abs() / z2.sqrt(),
            },
        });
    }
    Ok((-8.0 * zeta * w + radicand.sqrt()) / (PI * z2))
}

/// One superharmonic of eq. (11).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct PaperHarmonic {
    /// Order k = 2n − 1 (3, 5, …).
    pub order: u32,
    /// Amplitude A_k of eq. (11), > 0.
    pub amplitude: f64,
    /// Phase φ_k of eq. (11) as printed, −π/2 − arctan(2ζkw/(1 − k²w²)) with the principal
    /// arctan, radians, relative to the paper's time origin (x's fundamental is A1 cos wτ).
    pub phase: f64,
}

impl PaperHarmonic {
    /// A_k and φ_k of eq. (11) for the odd order k ≥ 3.
    ///
    /// # Errors
    /// [`Error::InvalidParameter`] for bad ζ or w; [`Error::NoSolution`] at ζ = 0, kw = 1,
    /// where A_k is infinite.
    ///
    /// # Panics
    /// When k is even or below 3.
    pub fn new(zeta: f64, w: f64, order: u32) -> Result<Self> {
        check_zeta_w(zeta, w)?;
        assert!(order >= 3 && order % 2 == 1, "order must be odd and >= 3");
        let k = f64::from(order);
        let detune = (1.0 - k * w) * (1.0 + k * w);
        let damp = 2.0 * zeta * k * w;
        let modulus = detune.hypot(damp);
        if modulus == 0.0 {
            return Err(Error::NoSolution {
                what: Quantity::PaperHarmonic,
                reason: NoSolutionReason::HarmonicResonance { order },
            });
        }
        Ok(Self {
            order,
            amplitude: 4.0 / (k * PI) / modulus,
            phase: -FRAC_PI_2 - (damp / detune).atan(),
        })
    }

    /// The phase that the harmonic balance of eq. (7) gives, −π/2 − atan2(2ζkw, 1 − k²w²):
    /// equal to [`PaperHarmonic::phase`] for kw < 1 and off by π from it for kw > 1.
    pub fn balance_phase(&self, zeta: f64, w: f64) -> f64 {
        let k = f64::from(self.order);
        -FRAC_PI_2 - (2.0 * zeta * k * w).atan2((1.0 - k * w) * (1.0 + k * w))
    }
}

/// The paper's undamped series solution, eq. (9) (ζ = 0): x = A1 cos(wτ) +
/// Σ_{n≥2} A_{2n−1} sin((2n−1)wτ) under the drive β cos(wτ + φ0).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct UndampedSeries {
    /// Drive frequency w.
    pub w: f64,
    /// Drive amplitude β.
    pub beta: f64,
    /// A1 = √(β² − (4/π)²)/(1 − w²) of eq. (9): signed, negative above resonance (w > 1).
    pub a1: f64,
    /// φ0 = arcsin(4/(βπ)) of eq. (9), radians in [0, π/2].
    pub phi0: f64,
}

impl UndampedSeries {
    /// Evaluate eq. (9) at (w, β).
    ///
    /// # Errors
    /// [`Error::InvalidParameter`] for w ≤ 0, β < 0 or non-finite values;
    /// [`Error::NoSolution`] for β < 4/π (square root of a negative number, and
    /// arcsin of a number above 1) and at w = 1 (division by zero).
    pub fn new(w: f64, beta: f64) -> Result<Self> {
        check("w", w, w > 0.0, "must be finite and > 0")?;
        check("beta", beta, beta >= 0.0, "must be finite and >= 0")?;
        let radicand = beta * beta - FOUR_OVER_PI * FOUR_OVER_PI;
        if radicand < 0.0 {
            return Err(Error::NoSolution {
                what: Quantity::PaperUndampedA1,
                reason: NoSolutionReason::BelowFourOverPi { radicand, beta },
            });
        }
        let detune = (1.0 - w) * (1.0 + w);
        if detune == 0.0 {
            return Err(Error::NoSolution {
                what: Quantity::PaperUndampedA1,
                reason: NoSolutionReason::UndampedResonance,
            });
        }
        Ok(Self {
            w,
            beta,
            a1: radicand.sqrt() / detune,
            phi0: (FOUR_OVER_PI / beta).min(1.0).asin(),
        })
    }

    /// A_{2n−1} = 4/((2n−1)π((2n−1)²w² − 1)) of eq. (9) as printed, signed, for n ≥ 2 (the
    /// harmonic balance of eq. (7) gives the opposite sign; see the module documentation).
    ///
    /// # Errors
    /// [`Error::NoSolution`] at (2n−1)w = 1, where eq. (9) divides by zero.
    ///
    /// # Panics
    /// When n < 2.
    pub fn harmonic(&self, n: u32) -> Result<f64> {
        assert!(n >= 2, "superharmonics start at n = 2 (order 3)");
        let k = f64::from(2 * n - 1);
        let den = k * PI * (k * self.w - 1.0) * (k * self.w + 1.0);
        if den == 0.0 {
            return Err(Error::NoSolution {
                what: Quantity::PaperUndampedHarmonic,
                reason: NoSolutionReason::UndampedHarmonicResonance { order: 2 * n - 1 },
            });
        }
        Ok(4.0 / den)
    }
}

/// The paper's approximate stick-slip boundary, eq. (13), solved for β.
///
/// Eq. (13) with β cos φ0 = (1 − w²)A1 from eq. (11) reads w²·A1(w, β) = 1: no stop at a
/// turning point of x ≈ A1 cos(wτ) when w²A1 > 1. Because eq. (11) is the root of
/// Z²A1² + (16ζw/π)A1 + 16/π² − β² = 0, setting A1 = 1/w² solves it in closed form:
///
/// ```text
/// β_c^paper(w, ζ) = √( Z²/w⁴ + 16ζ/(πw) + 16/π² )
/// ```
///
/// The paper's eq. (12) uses the kinetic friction (+1) as the static limit, i.e. μs = 1.
///
/// # Errors
/// [`Error::InvalidParameter`] for ζ < 0, w ≤ 0 or non-finite values;
/// [`Error::NoSolution`] at ζ = 0, w = 1, where eq. (11) is undefined.
pub fn paper_boundary(zeta: f64, w: f64) -> Result<f64> {
    check_zeta_w(zeta, w)?;
    let detune = (1.0 - w) * (1.0 + w);
    let z2 = detune * detune + 4.0 * zeta * zeta * w * w;
    if z2 == 0.0 {
        return Err(Error::NoSolution {
            what: Quantity::PaperBoundary,
            reason: NoSolutionReason::ZeroImpedance,
        });
    }
    let w2 = w * w;
    Ok((z2 / (w2 * w2) + 16.0 * zeta / (PI * w) + FOUR_OVER_PI * FOUR_OVER_PI).sqrt())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn undamped_limit_of_eq11_is_eq9() {
        for &(w, beta) in &[(0.3, 2.0), (0.9, 1.5), (1.4, 3.0)] {
            let damped = PaperSeries::new(0.0, w, beta).unwrap();
            let undamped = UndampedSeries::new(w, beta).unwrap();
            assert!((damped.a1 - undamped.a1.abs()).abs() < 1e-14 * damped.a1);
            // Same drive phase up to the sign convention of A1 above resonance.
            let phi = if w < 1.0 {
                undamped.phi0
            } else {
                PI - undamped.phi0
            };
            assert!((damped.phi0 - phi).abs() < 1e-12, "w {w}");
        }
    }

    #[test]
    fn no_solution_is_an_error_not_nan() {
        assert!(matches!(
            PaperSeries::new(0.0, 1.0, 2.0),
            Err(Error::NoSolution { .. })
        ));
        // Below 4|1 − w²|/(πZ): square root of a negative number.
        assert!(matches!(
            PaperSeries::new(0.05, 0.5, 0.5),
            Err(Error::NoSolution { .. })
        ));
        // Real but negative A1 for β < 4/π.
        let beta = 0.99 * FOUR_OVER_PI;
        assert!(eq11_a1(0.3, 1.0, beta).unwrap() < 0.0);
        assert!(matches!(
            PaperSeries::new(0.3, 1.0, beta),
            Err(Error::NoSolution { .. })
        ));
        assert!(matches!(
            UndampedSeries::new(0.5, 1.0),
            Err(Error::NoSolution { .. })
        ));
        assert!(matches!(
            PaperHarmonic::new(0.0, 1.0 / 3.0, 3),
            Err(Error::NoSolution { .. })
        ));
    }
}
