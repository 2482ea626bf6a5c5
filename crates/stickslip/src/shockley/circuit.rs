//! The series RLC circuit with a Shockley diode pair, and its dimensionless model.
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
//! the diodes' own resistance R_s is part of D.

use super::diode::{DiodeLaw, DiodePair};
use crate::error::{check, Result};
use crate::params::Params;
use crate::physical::{Circuit, Scales};
use serde::{Deserialize, Serialize};

/// A series RLC circuit damped by two anti-parallel Shockley diodes.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct ShockleyCircuit {
    /// Inductance L in henry (> 0).
    pub inductance: f64,
    /// Capacitance C in farad (> 0).
    pub capacitance: f64,
    /// Series resistance R in ohms, without the diodes (≥ 0).
    pub resistance: f64,
    /// The diode pair.
    pub diode: DiodePair,
    /// Reference voltage U_t in volts (> 0): the unit of y and of β = U/U_t. Keeping the PWL
    /// turn-on voltage here gives β the same meaning in both diode models.
    pub reference_voltage: f64,
}

impl ShockleyCircuit {
    /// Validated circuit.
    ///
    /// # Errors
    /// [`crate::Error::InvalidParameter`] when L ≤ 0, C ≤ 0, R < 0, U_t ≤ 0, the diode is
    /// invalid, or any value is not finite.
    pub fn new(
        inductance: f64,
        capacitance: f64,
        resistance: f64,
        diode: DiodePair,
        reference_voltage: f64,
    ) -> Result<Self> {
        // The PWL circuit checks L, C and R with the same messages.
        let pwl = Circuit::new(
            inductance,
            capacitance,
            resistance,
            crate::physical::PwlDiode {
                turn_on: 1.0,
                resistance: 0.0,
            },
        )?;
        Ok(Self {
            inductance: pwl.inductance,
            capacitance: pwl.capacitance,
            resistance: pwl.resistance,
            diode: diode.validate()?,
            reference_voltage: check(
                "U_t",
                reference_voltage,
                reference_voltage > 0.0,
                "must be finite and > 0 (volts)",
            )?,
        })
    }

    /// The same circuit with a Shockley diode pair: L, C and R are kept, the PWL turn-on
    /// voltage U_t becomes the reference voltage, and the PWL resistance R_D is dropped (the
    /// Shockley law has its own R_s).
    ///
    /// # Errors
    /// When the diode is invalid.
    pub fn from_circuit(circuit: &Circuit, diode: DiodePair) -> Result<Self> {
        Self::new(
            circuit.inductance,
            circuit.capacitance,
            circuit.resistance,
            diode,
            circuit.diode.turn_on,
        )
    }

    /// The paper's circuit with two 1N4148 diodes at 27 °C: L = 11.5 mH, C = 0.02 µF,
    /// R = 68 Ω, U_t = 0.7 V.
    pub fn paper() -> Self {
        let c = Circuit::paper();
        Self {
            inductance: c.inductance,
            capacitance: c.capacitance,
            resistance: c.resistance,
            diode: DiodePair::one_n4148(),
            reference_voltage: c.diode.turn_on,
        }
    }

    /// Characteristic impedance √(L/C) in ohms.
    pub fn impedance(&self) -> f64 {
        (self.inductance / self.capacitance).sqrt()
    }

    /// Scales between the dimensionless model and volts, amperes and seconds. `alpha` is
    /// R/L (the circuit resistance only), so `zeta()` is ζ_R.
    pub fn scales(&self) -> Scales {
        let omega0 = 1.0 / (self.inductance * self.capacitance).sqrt();
        Scales {
            omega0,
            alpha: self.resistance / self.inductance,
            position: self.reference_voltage,
            velocity: self.reference_voltage / self.impedance(),
            force: self.reference_voltage,
        }
    }

    /// The dimensionless diode law D.
    pub fn law(&self) -> DiodeLaw {
        self.diode
            .law(self.reference_voltage, self.impedance())
            .expect("a validated circuit has a positive reference voltage and impedance")
    }

    /// The dimensionless model for a drive U cos(Ω t + φ): `amplitude` U in volts, `omega`
    /// Ω in rad/s, `phase` φ in radians.
    ///
    /// # Errors
    /// When U < 0, Ω ≤ 0, or a value is not finite.
    pub fn model(&self, amplitude: f64, omega: f64, phase: f64) -> Result<ShockleyModel> {
        let params = self.scales().params(amplitude, omega, phase)?;
        ShockleyModel::new(params, self.law())
    }

    /// The dimensionless model for a dimensionless drive (w = Ω/ω0, β = U/U_t, φ).
    ///
    /// # Errors
    /// When w ≤ 0, β < 0, or a value is not finite.
    pub fn model_dimensionless(&self, w: f64, beta: f64, phi: f64) -> Result<ShockleyModel> {
        let params = Params::new(self.scales().zeta(), w, beta)?.with_phi(phi)?;
        ShockleyModel::new(params, self.law())
    }
}

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

    #[test]
    fn paper_circuit_numbers() {
        let c = ShockleyCircuit::paper();
        let s = c.scales();
        assert!((s.omega0 - 65_938.0).abs() < 0.1);
        assert!((2.0 * s.zeta() - 68.0 / c.impedance()).abs() < 1e-15);
        // β keeps its meaning: 1.498 V is β = 2.14 against U_t = 0.7 V.
        let m = c.model(1.498, 0.95 * s.omega0, 0.0).unwrap();
        assert!((m.params.beta - 2.14).abs() < 1e-12);
        assert!((m.params.w - 0.95).abs() < 1e-12);
        let from = ShockleyCircuit::from_circuit(&Circuit::paper(), DiodePair::default()).unwrap();
        assert_eq!(from, c);
    }

    #[test]
    fn rejects_bad_parts() {
        let d = DiodePair::default();
        assert!(ShockleyCircuit::new(0.0, 1e-6, 1.0, d, 0.7).is_err());
        assert!(ShockleyCircuit::new(1e-3, 1e-6, 1.0, d, 0.0).is_err());
        let bad = DiodePair {
            saturation_current: -1.0,
            ..d
        };
        assert!(ShockleyCircuit::new(1e-3, 1e-6, 1.0, bad, 0.7).is_err());
    }
}
