//! Coulomb friction against a moving belt.
//!
//! The mechanical oscillator may rest on a belt that moves at the (dimensionless) speed vb;
//! friction then acts on the slip s = y' − vb, the speed of the block relative to the belt:
//!
//! ```text
//! slipping, s ≠ 0:   y'' + 2ζ y' + y + sgn(s) = β cos(w τ + φ)
//! stuck,    s = 0:   y' = vb, held while |β cos(w τ + φ) − y − 2ζ vb| ≤ μs
//! ```
//!
//! (τ = ω0·t; y = k·r/F0 with F0 the kinetic friction level.) The law is Coulomb's, the
//! paper's: 1 while slipping, the static level μs ≥ 1 at rest; with vb = 0 the model is the
//! paper's, bit for bit. Every piece stays linear, so the exact solver follows the belt
//! ([`crate::exact`]). Steady sliding, the equilibrium y' = 0, y = sgn(vb) of the undriven
//! belt (β = 0), has the damping 2ζ of small oscillations about it ([`sliding_damping`]):
//! Coulomb's law neither feeds nor damps them, so steady sliding is stable with damping and
//! neutral without.

use crate::error::{check, Result};

/// Largest |vb|, the dimensionless belt speed.
pub const VB_MAX: f64 = 1e6;
/// What [`VB_MAX`] allows, in words.
pub(crate) const VB_ALLOWED: &str = "must be finite and from -1e6 to 1e6 (docs/limits.md)";

/// Check a belt speed vb: finite, |vb| ≤ [`VB_MAX`]; −0 is read as 0.
///
/// # Errors
/// [`crate::Error::InvalidParameter`] naming `vb`.
pub fn check_vb(vb: f64) -> Result<f64> {
    let vb = check("vb", vb, vb.abs() <= VB_MAX, VB_ALLOWED)?;
    Ok(if vb == 0.0 { 0.0 } else { vb })
}

/// The equilibrium of steady sliding on a belt at speed `vb` ≠ 0 without a drive (β = 0):
/// y' = 0, y = sgn(vb) (the kinetic friction level, 1 in these units).
pub fn sliding_equilibrium(vb: f64) -> f64 {
    1f64.copysign(vb)
}

/// The damping 2ζ of small oscillations about steady sliding: Coulomb's law has no slope in
/// the slip speed, so only the viscous damping acts. Steady sliding is stable where it is
/// positive, neutral (a family of oscillations about it) where it is 0.
pub fn sliding_damping(zeta: f64) -> f64 {
    2.0 * zeta
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn belt_speeds_are_checked_and_minus_zero_is_zero() {
        assert_eq!(check_vb(-0.0).unwrap().to_bits(), 0.0f64.to_bits());
        assert_eq!(check_vb(-0.5).unwrap(), -0.5);
        assert!(check_vb(2e6).is_err());
        assert!(check_vb(f64::NAN).is_err());
        assert_eq!(sliding_equilibrium(-0.1), -1.0);
        assert_eq!(sliding_damping(0.05), 0.1);
    }
}
