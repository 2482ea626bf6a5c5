//! Physical descriptions of the two twins and their exact conversion to the dimensionless model.
//!
//! The correspondence is the paper's Table 1, written in our notation (τ = ω0·t, α = 2ζω0):
//!
//! | dimensionless | circuit (series RLC + diode pair)      | mechanics (mass, spring, dry friction) |
//! |---------------|----------------------------------------|----------------------------------------|
//! | ω0            | 1/√(LC)                                | √(k/m)                                 |
//! | 2ζ = α/ω0     | (R + R_D)·√(C/L)                       | γ/(m ω0)                               |
//! | β             | U/U_t                                  | F/F0                                   |
//! | w             | Ω/ω0                                   | Ω/ω0                                   |
//! | y             | u_C/U_t                                | k·r/F0                                 |
//! | y'            | i·√(L/C)/U_t                           | ṙ·k/(F0 ω0)                            |

use crate::error::{check, Result};
use crate::params::Params;
use serde::{Deserialize, Serialize};

/// Piecewise-linear model of two anti-parallel diodes: an ideal diode, a voltage source U_t
/// and a resistor R_D in series, in each direction (the paper's Fig. 2b).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct PwlDiode {
    /// Turn-on voltage U_t in volts (> 0).
    pub turn_on: f64,
    /// Forward resistance R_D in ohms (≥ 0).
    pub resistance: f64,
}

impl PwlDiode {
    /// Validated PWL diode.
    ///
    /// # Errors
    /// When U_t ≤ 0 or R_D < 0 or either is not finite.
    pub fn new(turn_on: f64, resistance: f64) -> Result<Self> {
        Ok(Self {
            turn_on: check(
                "U_t",
                turn_on,
                turn_on > 0.0,
                "must be finite and > 0 (volts)",
            )?,
            resistance: check(
                "R_D",
                resistance,
                resistance >= 0.0,
                "must be finite and >= 0 (ohms)",
            )?,
        })
    }

    /// Voltage across the pair at current `i` (A): sgn(i)·(U_t + R_D |i|); 0 at i = 0, where
    /// the pair blocks any voltage between −U_t and U_t.
    pub fn voltage(&self, i: f64) -> f64 {
        if i == 0.0 {
            0.0
        } else {
            i.signum() * self.turn_on + self.resistance * i
        }
    }
}

/// A series RLC circuit damped by a pair of anti-parallel diodes (PWL model).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Circuit {
    /// Inductance L in henry (> 0).
    pub inductance: f64,
    /// Capacitance C in farad (> 0).
    pub capacitance: f64,
    /// Series resistance R in ohms, without the diodes (≥ 0).
    pub resistance: f64,
    /// The diode pair.
    pub diode: PwlDiode,
}

impl Circuit {
    /// Validated circuit.
    ///
    /// # Errors
    /// When L ≤ 0, C ≤ 0, R < 0 or any value is not finite.
    pub fn new(
        inductance: f64,
        capacitance: f64,
        resistance: f64,
        diode: PwlDiode,
    ) -> Result<Self> {
        Ok(Self {
            inductance: check(
                "L",
                inductance,
                inductance > 0.0,
                "must be finite and > 0 (henry)",
            )?,
            capacitance: check(
                "C",
                capacitance,
                capacitance > 0.0,
                "must be finite and > 0 (farad)",
            )?,
            resistance: check(
                "R",
                resistance,
                resistance >= 0.0,
                "must be finite and >= 0 (ohms)",
            )?,
            diode: PwlDiode::new(diode.turn_on, diode.resistance)?,
        })
    }

    /// The paper's experiment: L = 11.5 mH, C = 0.02 µF, R = 68 Ω, U_t = 0.7 V, R_D = 3.0 Ω
    /// (total series resistance 71 Ω), giving α = 6173.9 s⁻¹ and ω0 = 65938.0 rad/s.
    pub fn paper() -> Self {
        Self {
            inductance: 11.5e-3,
            capacitance: 0.02e-6,
            resistance: 68.0,
            diode: PwlDiode {
                turn_on: 0.7,
                resistance: 3.0,
            },
        }
    }

    /// Total series resistance R + R_D in ohms.
    pub fn total_resistance(&self) -> f64 {
        self.resistance + self.diode.resistance
    }

    /// Characteristic impedance √(L/C) in ohms.
    pub fn impedance(&self) -> f64 {
        (self.inductance / self.capacitance).sqrt()
    }

    /// Scales that turn dimensionless values into volts, amperes and seconds.
    pub fn scales(&self) -> Scales {
        let omega0 = 1.0 / (self.inductance * self.capacitance).sqrt();
        Scales {
            omega0,
            alpha: self.total_resistance() / self.inductance,
            position: self.diode.turn_on,
            velocity: self.diode.turn_on / self.impedance(),
            force: self.diode.turn_on,
        }
    }
}

/// A mass on a spring with viscous and dry (Coulomb) friction.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Mechanics {
    /// Mass m in kg (> 0).
    pub mass: f64,
    /// Spring constant k in N/m (> 0).
    pub stiffness: f64,
    /// Viscous damping coefficient γ in N·s/m (≥ 0).
    pub damping: f64,
    /// Kinetic (sliding) friction force F0 in N (> 0).
    pub friction: f64,
}

impl Mechanics {
    /// Validated mechanical oscillator.
    ///
    /// # Errors
    /// When m ≤ 0, k ≤ 0, γ < 0, F0 ≤ 0 or any value is not finite.
    pub fn new(mass: f64, stiffness: f64, damping: f64, friction: f64) -> Result<Self> {
        Ok(Self {
            mass: check("m", mass, mass > 0.0, "must be finite and > 0 (kg)")?,
            stiffness: check(
                "k",
                stiffness,
                stiffness > 0.0,
                "must be finite and > 0 (N/m)",
            )?,
            damping: check(
                "gamma",
                damping,
                damping >= 0.0,
                "must be finite and >= 0 (N s/m)",
            )?,
            friction: check("F0", friction, friction > 0.0, "must be finite and > 0 (N)")?,
        })
    }

    /// Scales that turn dimensionless values into metres, m/s, newtons and seconds.
    pub fn scales(&self) -> Scales {
        let omega0 = (self.stiffness / self.mass).sqrt();
        Scales {
            omega0,
            alpha: self.damping / self.mass,
            position: self.friction / self.stiffness,
            velocity: self.friction / self.stiffness * omega0,
            force: self.friction,
        }
    }
}

/// Either twin.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub enum System {
    /// The diode-damped RLC circuit.
    Circuit(Circuit),
    /// The mass-spring oscillator with dry friction.
    Mechanics(Mechanics),
}

impl System {
    /// The scales of the underlying twin.
    pub fn scales(&self) -> Scales {
        match self {
            System::Circuit(c) => c.scales(),
            System::Mechanics(m) => m.scales(),
        }
    }
}

/// Conversion factors between the dimensionless model and physical units of one twin.
///
/// Physical = dimensionless × scale: t = τ/ω0; position (V or m) = y·`position`;
/// velocity-like (A or m/s) = y'·`velocity`; force-like (V or N) = β·`force`.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Scales {
    /// Natural angular frequency ω0 in rad/s.
    pub omega0: f64,
    /// The paper's α = 2ζω0 in 1/s.
    pub alpha: f64,
    /// Volts (u_C) or metres (r) per unit of y.
    pub position: f64,
    /// Amperes (i) or m/s (ṙ) per unit of y'.
    pub velocity: f64,
    /// Volts (U) or newtons (F) per unit of β.
    pub force: f64,
}

impl Scales {
    /// Natural frequency f0 = ω0/2π in Hz.
    pub fn f0(&self) -> f64 {
        self.omega0 / std::f64::consts::TAU
    }

    /// Damping ratio ζ = α/(2ω0).
    pub fn zeta(&self) -> f64 {
        self.alpha / (2.0 * self.omega0)
    }

    /// Quality factor Q = ω0/α = 1/(2ζ).
    pub fn quality_factor(&self) -> f64 {
        self.omega0 / self.alpha
    }

    /// Dimensionless parameters for a drive of amplitude `amplitude` (V or N) at angular
    /// frequency `omega` (rad/s) and phase `phase` (rad), with μs = 1.
    ///
    /// # Errors
    /// When the resulting w or β is out of range (e.g. Ω ≤ 0, U < 0).
    pub fn params(&self, amplitude: f64, omega: f64, phase: f64) -> Result<Params> {
        check(
            "U",
            amplitude,
            amplitude >= 0.0,
            "must be finite and >= 0 (V or N)",
        )?;
        check(
            "Omega",
            omega,
            omega > 0.0,
            "must be finite and > 0 (rad/s)",
        )?;
        Params::new(self.zeta(), omega / self.omega0, amplitude / self.force)?.with_phi(phase)
    }

    /// Physical drive amplitude (V or N) for a dimensionless β.
    pub fn drive_amplitude(&self, beta: f64) -> f64 {
        beta * self.force
    }

    /// Physical drive angular frequency Ω (rad/s) for a dimensionless w.
    pub fn drive_omega(&self, w: f64) -> f64 {
        w * self.omega0
    }

    /// Time in seconds for dimensionless τ.
    pub fn time(&self, tau: f64) -> f64 {
        tau / self.omega0
    }

    /// Dimensionless τ for a time in seconds.
    pub fn tau(&self, seconds: f64) -> f64 {
        seconds * self.omega0
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn paper_preset_gives_the_printed_alpha_and_omega0() {
        let s = Circuit::paper().scales();
        assert_eq!(format!("{:.1}", s.alpha), "6173.9");
        assert_eq!(format!("{:.1}", s.omega0), "65938.0");
    }

    #[test]
    fn circuit_round_trip() {
        let c = Circuit::paper();
        let s = c.scales();
        let p = s.params(1.498, 0.95 * s.omega0, 0.3).unwrap();
        assert!((p.beta - 1.498 / 0.7).abs() < 1e-14);
        assert!((p.w - 0.95).abs() < 1e-14);
        assert!((s.drive_amplitude(p.beta) - 1.498).abs() < 1e-14);
        assert!((s.drive_omega(p.w) - 0.95 * s.omega0).abs() < 1e-9);
        // 2ζ = R_tot √(C/L)
        assert!((2.0 * p.zeta - 71.0 * (0.02e-6f64 / 11.5e-3).sqrt()).abs() < 1e-15);
    }

    #[test]
    fn mechanics_scales() {
        let m = Mechanics::new(2.0, 8.0, 0.4, 0.5).unwrap();
        let s = m.scales();
        assert_eq!(s.omega0, 2.0);
        assert!((s.zeta() - 0.4 / (2.0 * 2.0 * 2.0)).abs() < 1e-15);
        let p = s.params(1.5, 3.0, 0.0).unwrap();
        assert_eq!(p.beta, 3.0);
        assert_eq!(p.w, 1.5);
    }

    #[test]
    fn rejects_bad_components() {
        assert!(Circuit::new(0.0, 1e-6, 1.0, Circuit::paper().diode).is_err());
        assert!(PwlDiode::new(-0.7, 3.0).is_err());
        assert!(Mechanics::new(1.0, 1.0, -1.0, 1.0).is_err());
    }
}
