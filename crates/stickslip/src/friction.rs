//! Friction laws of the slip against a moving belt.
//!
//! The mechanical oscillator may rest on a belt that moves at the (dimensionless) speed vb;
//! friction then acts on the slip s = y' − vb, the speed of the block relative to the belt:
//!
//! ```text
//! slipping, s ≠ 0:   y'' + 2ζ y' + y + sgn(s) μ(|s|) = β cos(w τ + φ)
//! stuck,    s = 0:   y' = vb, held while |β cos(w τ + φ) − y − 2ζ vb| ≤ μs
//! ```
//!
//! (τ = ω0·t; y = k·r/F_k with F_k the kinetic friction level, so the laws below tend to 1,
//! or start from μs, in these units). Three laws of the slip speed |s| ≥ 0 ([`FrictionLaw`]):
//!
//! ```text
//! coulomb:   μ(s) = 1                                   (the paper's law when vb = 0)
//! stribeck:  μ(s) = 1 + (μs − 1) exp(−(s/vs)^δ) + η s   (Stribeck's fall, viscous rise)
//! cubic:     μ(s) = μs − k1 s + k3 s³                     (Thomsen & Fidlin's law)
//! ```
//!
//! Each law starts from the static level at zero slip except Coulomb's (1 for any s > 0, with
//! the static level μs ≥ 1 on its own), and none may go negative: a law that pulls the block
//! along its slip is refused ([`FrictionLaw::validate`]). Steady sliding, the equilibrium
//! y' = 0, y = sgn(vb) μ(|vb|) of the undriven belt (β = 0), is stable where
//! 2ζ + μ'(|vb|) > 0 ([`FrictionLaw::sliding_damping`]): a law that falls with the slip speed
//! feeds the oscillation.

use crate::error::{check, invalid, Result};
use serde::{Deserialize, Serialize};

/// Largest |vb|, the dimensionless belt speed.
pub const VB_MAX: f64 = 1e6;
/// What [`VB_MAX`] allows, in words.
pub(crate) const VB_ALLOWED: &str = "must be finite and from -1e6 to 1e6 (docs/limits.md)";
/// Largest Stribeck speed vs, viscous coefficient η and cubic coefficients |k1|, k3.
pub const LAW_MAX: f64 = 1e6;
/// What the Stribeck speed allows.
pub(crate) const VS_ALLOWED: &str = "must be finite, > 0 and at most 1e6 (docs/limits.md)";
/// Largest Stribeck exponent δ.
pub const DELTA_MAX: f64 = 100.0;
/// What the Stribeck exponent allows.
pub(crate) const DELTA_ALLOWED: &str = "must be finite, > 0 and at most 100 (docs/limits.md)";
/// What the viscous coefficient allows (a negative one would make the law go negative).
pub(crate) const ETA_ALLOWED: &str =
    "must be finite and from 0 to 1e6 (a negative viscous term makes the law go negative)";
/// What k1 allows on its own.
pub(crate) const K1_ALLOWED: &str = "must be finite and from -1e6 to 1e6 (docs/limits.md)";
/// What k3 allows (a negative one makes the law go negative).
pub(crate) const K3_ALLOWED: &str =
    "must be finite and from 0 to 1e6 (a negative cubic term makes the law go negative)";
/// What the cubic law asks of k1 and k3 together.
pub(crate) const CUBIC_ALLOWED: &str =
    "makes the cubic law μs − k1·s + k3·s³ go negative: it needs 4·k1³ ≤ 27·μs²·k3";

/// The name of a friction law, as users type it (`--friction-law stribeck`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum FrictionLawKind {
    /// μ(s) = 1: Coulomb's law (with the static level μs).
    #[default]
    Coulomb,
    /// μ(s) = 1 + (μs − 1) exp(−(s/vs)^δ) + η s.
    Stribeck,
    /// μ(s) = μs − k1 s + k3 s³.
    Cubic,
}

impl FrictionLawKind {
    /// Every law, Coulomb's first.
    pub const ALL: [FrictionLawKind; 3] = [
        FrictionLawKind::Coulomb,
        FrictionLawKind::Stribeck,
        FrictionLawKind::Cubic,
    ];

    /// `coulomb`, `stribeck` or `cubic`.
    pub fn label(self) -> &'static str {
        match self {
            FrictionLawKind::Coulomb => "coulomb",
            FrictionLawKind::Stribeck => "stribeck",
            FrictionLawKind::Cubic => "cubic",
        }
    }

    /// The law in one line.
    pub fn description(self) -> &'static str {
        match self {
            FrictionLawKind::Coulomb => {
                "Coulomb: μ(s) = 1 while slipping, μs at rest (solved exactly)"
            }
            FrictionLawKind::Stribeck => "Stribeck: μ(s) = 1 + (μs − 1)·exp(−(s/vs)^δ) + η·s",
            FrictionLawKind::Cubic => "cubic: μ(s) = μs − k1·s + k3·s³ (Thomsen & Fidlin)",
        }
    }
}

/// A friction law μ(s) of the slip speed s = |y' − vb| ≥ 0, with its own parameters
/// (dimensionless: speeds in units of F_k/(k)·ω0, the unit of y'); the static level μs is the
/// model's ([`crate::Params::mu_s`]). See the module documentation.
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum FrictionLaw {
    /// μ(s) = 1 (the paper's law).
    #[default]
    Coulomb,
    /// μ(s) = 1 + (μs − 1) exp(−(s/vs)^δ) + η s.
    Stribeck {
        /// Stribeck speed vs > 0.
        vs: f64,
        /// Exponent δ > 0 (2: Gaussian fall).
        delta: f64,
        /// Viscous coefficient η ≥ 0.
        eta: f64,
    },
    /// μ(s) = μs − k1 s + k3 s³.
    Cubic {
        /// Initial slope −k1 of the law (k1 > 0: friction falls with the slip speed).
        k1: f64,
        /// Cubic coefficient k3 ≥ 0.
        k3: f64,
    },
}

impl FrictionLaw {
    /// Whether this is Coulomb's law (the exact solver's).
    pub fn is_coulomb(&self) -> bool {
        matches!(self, FrictionLaw::Coulomb)
    }

    /// The law's name.
    pub fn kind(&self) -> FrictionLawKind {
        match self {
            FrictionLaw::Coulomb => FrictionLawKind::Coulomb,
            FrictionLaw::Stribeck { .. } => FrictionLawKind::Stribeck,
            FrictionLaw::Cubic { .. } => FrictionLawKind::Cubic,
        }
    }

    /// The law checked on its own and with the static level `mu_s`: vs > 0, 0 < δ ≤ 100,
    /// η ≥ 0, k3 ≥ 0, and a cubic law that never goes negative (4·k1³ ≤ 27·μs²·k3).
    ///
    /// # Errors
    /// [`crate::Error::InvalidParameter`] naming the parameter (`vs`, `delta`, `eta`, `k1`,
    /// `k3`): for a cubic law that goes negative, `k1`.
    pub fn validate(self, mu_s: f64) -> Result<Self> {
        match self {
            FrictionLaw::Coulomb => {}
            FrictionLaw::Stribeck { vs, delta, eta } => {
                check("vs", vs, vs > 0.0 && vs <= LAW_MAX, VS_ALLOWED)?;
                check(
                    "delta",
                    delta,
                    delta > 0.0 && delta <= DELTA_MAX,
                    DELTA_ALLOWED,
                )?;
                check("eta", eta, (0.0..=LAW_MAX).contains(&eta), ETA_ALLOWED)?;
            }
            FrictionLaw::Cubic { k1, k3 } => {
                check("k1", k1, k1.abs() <= LAW_MAX, K1_ALLOWED)?;
                check("k3", k3, (0.0..=LAW_MAX).contains(&k3), K3_ALLOWED)?;
                if k1 > 0.0 && 4.0 * k1 * k1 * k1 > 27.0 * mu_s * mu_s * k3 {
                    return invalid("k1", k1, CUBIC_ALLOWED);
                }
            }
        }
        Ok(self)
    }

    /// μ(s) for a slip speed s ≥ 0 (while slipping; Coulomb's law gives 1 for every s).
    pub fn value(&self, mu_s: f64, s: f64) -> f64 {
        self.value_and_slope(mu_s, s).0
    }

    /// μ(s) and μ'(s) = dμ/ds for a slip speed s ≥ 0 (the slope at s = 0 is the one-sided
    /// derivative; infinite for a Stribeck law with δ < 1).
    pub fn value_and_slope(&self, mu_s: f64, s: f64) -> (f64, f64) {
        match *self {
            FrictionLaw::Coulomb => (1.0, 0.0),
            FrictionLaw::Stribeck { vs, delta, eta } => {
                let x = s / vs;
                // The default δ = 2 and δ = 1 without `powf` (x·x and x: the same values to
                // an ulp; `powf` was a third of a Stribeck map's time).
                let power = if delta == 2.0 {
                    x * x
                } else if delta == 1.0 {
                    x
                } else {
                    x.powf(delta)
                };
                let fall = (mu_s - 1.0) * (-power).exp();
                // d/ds (s/vs)^δ = δ (s/vs)^δ / s, written without dividing by s = 0.
                let rate = if delta == 1.0 {
                    1.0 / vs
                } else if delta == 2.0 {
                    2.0 * x / vs
                } else {
                    delta * x.powf(delta - 1.0) / vs
                };
                (1.0 + fall + eta * s, eta - fall * rate)
            }
            FrictionLaw::Cubic { k1, k3 } => {
                (mu_s - k1 * s + k3 * s * s * s, -k1 + 3.0 * k3 * s * s)
            }
        }
    }

    /// The friction force sgn(s)·μ(|s|) of the equation of motion at slip s ≠ 0, and its
    /// derivative by s (μ'(|s|) on both sides).
    pub fn force_and_slope(&self, mu_s: f64, s: f64) -> (f64, f64) {
        let (value, slope) = self.value_and_slope(mu_s, s.abs());
        (value.copysign(s), slope)
    }

    /// The equilibrium of steady sliding on a belt at speed `vb` ≠ 0 without a drive (β = 0):
    /// y' = 0, y = sgn(vb)·μ(|vb|).
    pub fn sliding_equilibrium(&self, mu_s: f64, vb: f64) -> f64 {
        self.value(mu_s, vb.abs()).copysign(vb)
    }

    /// The damping 2ζ + μ'(|vb|) of small oscillations about steady sliding at belt speed
    /// `vb` ≠ 0 (the friction law's slope adds to the viscous damping): steady sliding is
    /// stable where it is positive, unstable where it is negative.
    pub fn sliding_damping(&self, zeta: f64, mu_s: f64, vb: f64) -> f64 {
        2.0 * zeta + self.value_and_slope(mu_s, vb.abs()).1
    }

    /// The law's own parameters as (name, value), in the order of the keys (`vs`, `delta`,
    /// `eta`; `k1`, `k3`); none for Coulomb's.
    pub fn parameters(&self) -> Vec<(&'static str, f64)> {
        match *self {
            FrictionLaw::Coulomb => Vec::new(),
            FrictionLaw::Stribeck { vs, delta, eta } => {
                vec![("vs", vs), ("delta", delta), ("eta", eta)]
            }
            FrictionLaw::Cubic { k1, k3 } => vec![("k1", k1), ("k3", k3)],
        }
    }
}

/// Check a belt speed vb: finite, |vb| ≤ [`VB_MAX`]; −0 is read as 0.
///
/// # Errors
/// [`crate::Error::InvalidParameter`] naming `vb`.
pub fn check_vb(vb: f64) -> Result<f64> {
    let vb = check("vb", vb, vb.abs() <= VB_MAX, VB_ALLOWED)?;
    Ok(if vb == 0.0 { 0.0 } else { vb })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::Error;

    #[test]
    fn slopes_are_the_derivatives_of_the_values() {
        let laws = [
            FrictionLaw::Stribeck {
                vs: 0.3,
                delta: 2.0,
                eta: 0.05,
            },
            FrictionLaw::Stribeck {
                vs: 0.5,
                delta: 1.0,
                eta: 0.0,
            },
            FrictionLaw::Stribeck {
                vs: 1.5,
                delta: 0.7,
                eta: 0.2,
            },
            FrictionLaw::Cubic { k1: 1.2, k3: 0.4 },
        ];
        for law in laws {
            for s in [0.05, 0.4, 1.0, 2.5] {
                let h = 1e-6;
                let numeric = (law.value(1.6, s + h) - law.value(1.6, s - h)) / (2.0 * h);
                let (_, slope) = law.value_and_slope(1.6, s);
                assert!(
                    (numeric - slope).abs() < 1e-8,
                    "{law:?} at {s}: {numeric} {slope}"
                );
            }
            assert!((law.value(1.6, 0.0) - 1.6).abs() < 1e-15, "{law:?}");
        }
        assert_eq!(FrictionLaw::Coulomb.value_and_slope(3.0, 0.7), (1.0, 0.0));
    }

    #[test]
    fn laws_that_go_negative_are_refused_naming_the_key() {
        let name = |r: Result<FrictionLaw>| match r {
            Err(Error::InvalidParameter { name, .. }) => name,
            other => panic!("{other:?}"),
        };
        // μs − k1 s + k3 s³ has its minimum μs − (2/3)k1·√(k1/3k3): zero at 4k1³ = 27μs²k3.
        let edge = (27.0f64 * 4.0 * 0.5 / 4.0).cbrt();
        assert!(FrictionLaw::Cubic { k1: edge, k3: 0.5 }
            .validate(2.0)
            .is_ok());
        let bad = FrictionLaw::Cubic {
            k1: 1.01 * edge,
            k3: 0.5,
        };
        assert_eq!(name(bad.validate(2.0)), "k1");
        assert_eq!(
            name(FrictionLaw::Cubic { k1: 0.1, k3: 0.0 }.validate(1.0)),
            "k1"
        );
        assert!(FrictionLaw::Cubic { k1: -0.1, k3: 0.0 }
            .validate(1.0)
            .is_ok());
        assert_eq!(
            name(FrictionLaw::Cubic { k1: 0.1, k3: -1.0 }.validate(1.0)),
            "k3"
        );
        let stribeck = |vs, delta, eta| FrictionLaw::Stribeck { vs, delta, eta }.validate(1.5);
        assert_eq!(name(stribeck(0.0, 2.0, 0.0)), "vs");
        assert_eq!(name(stribeck(-1.0, 2.0, 0.0)), "vs");
        assert_eq!(name(stribeck(0.1, 0.0, 0.0)), "delta");
        assert_eq!(name(stribeck(0.1, 2.0, -0.1)), "eta");
        assert_eq!(name(stribeck(0.1, f64::NAN, 0.0)), "delta");
        assert!(stribeck(0.1, 2.0, 0.0).is_ok());
        assert_eq!(check_vb(-0.0).unwrap().to_bits(), 0.0f64.to_bits());
        assert!(check_vb(2e6).is_err());
    }

    #[test]
    fn steady_sliding_is_unstable_where_the_law_falls_faster_than_damping() {
        let law = FrictionLaw::Stribeck {
            vs: 0.5,
            delta: 1.0,
            eta: 0.0,
        };
        // μ'(vb) = −(μs − 1)/vs·e^{−vb/vs}: −0.6·e^{−0.2} at vb = 0.1.
        let d = law.sliding_damping(0.1, 1.3, 0.1);
        assert!((d - (0.2 - 0.6 * (-0.2f64).exp())).abs() < 1e-15);
        assert!(d < 0.0);
        assert!(law.sliding_damping(0.1, 1.3, 3.0) > 0.0);
        assert_eq!(law.sliding_equilibrium(1.3, -0.1), -law.value(1.3, 0.1));
    }
}
