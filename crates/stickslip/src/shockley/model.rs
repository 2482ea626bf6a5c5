//! The dimensionless model of the series RLC circuit with a Shockley diode pair.
//!
//! Kirchhoff's voltage law around the loop, with q the capacitor charge and i = q̇:
//!
//! ```text
//! L q̈ + R q̇ + q/C + U_D(q̇) = U cos(Ω t + φ),     U_D(i) = n V_T asinh(i/(2 I_s)) + R_s i.
//! ```
//!
//! With a reference voltage U_t (the PWL turn-on voltage of the same circuit, 0.7 V in the
//! paper), y = u_C/U_t, τ = ω0 t, v = y' = i·√(L/C)/U_t:
//!
//! ```text
//! y'' + 2ζ_R y' + y + D(y') = β cos(w τ + φ),      2ζ_R = R √(C/L),  β = U/U_t,  w = Ω/ω0,
//! ```
//!
//! with D the [`DiodeLaw`]. Unlike the PWL model, ζ_R contains the circuit resistance R only:
//! the diodes' own resistance R_s is part of D. The circuit itself is a
//! [`crate::Circuit`] whose diode is [`crate::physical::Diode::Shockley`]; its
//! [`crate::Circuit::shockley_model`] gives this model.

use super::diode::DiodeLaw;
use crate::error::Result;
use crate::params::Params;
use serde::{Deserialize, Serialize};

/// The dimensionless Shockley model y'' + 2ζ_R y' + y + D(y') = β cos(w τ + φ).
///
/// `params.zeta` is ζ_R (circuit resistance only); `params.mu_s` is not used (a smooth diode
/// has no separate static threshold).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct ShockleyModel {
    /// ζ_R, w, β and φ.
    pub params: Params,
    /// The diode law D.
    pub law: DiodeLaw,
}

impl ShockleyModel {
    /// Validated model.
    ///
    /// # Errors
    /// When a parameter or the law is invalid.
    pub fn new(params: Params, law: DiodeLaw) -> Result<Self> {
        Ok(Self {
            params: params.validate()?,
            law: DiodeLaw::new(law.scale, law.knee, law.resistance)?,
        })
    }

    /// Right-hand side of the first-order system x = (y, v):
    /// (v, β cos(w τ + φ) − y − 2ζ_R v − D(v)).
    #[inline]
    pub fn rhs(&self, tau: f64, y: f64, v: f64) -> [f64; 2] {
        let p = &self.params;
        [v, p.drive(tau) - y - 2.0 * p.zeta * v - self.law.value(v)]
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::Circuit;

    #[test]
    fn paper_model_numbers() {
        let c = Circuit::paper_shockley();
        let p = c.params(0.95, 2.14, 0.0).unwrap();
        let m = c.shockley_model(&p).unwrap().unwrap();
        assert!((2.0 * m.params.zeta - 68.0 / c.impedance()).abs() < 1e-15);
        assert_eq!(m.params.w, 0.95);
        // rhs at rest: only the drive acts.
        let f = m.rhs(0.0, 0.0, 0.0);
        assert_eq!(f, [0.0, 2.14]);
    }

    #[test]
    fn rejects_bad_parameters() {
        let law = Circuit::paper_shockley()
            .shockley_model(&Params::new(0.0, 1.0, 1.0).unwrap())
            .unwrap()
            .unwrap()
            .law;
        let bad = Params {
            w: -1.0,
            ..Params::new(0.0, 1.0, 1.0).unwrap()
        };
        assert!(ShockleyModel::new(bad, law).is_err());
    }
}
