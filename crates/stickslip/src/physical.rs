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

use crate::error::{check, invalid, Result};
use crate::params::Params;
use crate::shockley::{DiodePair, ShockleyModel};
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

/// A Shockley diode pair in a circuit, with the reference voltage U_t that sets the unit of
/// y = u_C/U_t and of β = U/U_t (the PWL turn-on voltage of the same circuit, 0.7 V in the
/// paper, so that β means the same drive with either diode law).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct ShockleyDiode {
    /// The two anti-parallel diodes.
    pub pair: DiodePair,
    /// Reference voltage U_t in volts (> 0).
    pub reference_voltage: f64,
}

impl ShockleyDiode {
    /// Validated Shockley diode pair with reference voltage U_t (volts).
    ///
    /// # Errors
    /// When the pair is invalid or U_t is not finite and > 0.
    pub fn new(pair: DiodePair, reference_voltage: f64) -> Result<Self> {
        Ok(Self {
            pair: pair.validate()?,
            reference_voltage: check(
                "U_t",
                reference_voltage,
                reference_voltage > 0.0,
                "must be finite and > 0 (volts)",
            )?,
        })
    }
}

/// The diode pair of a [`Circuit`]: the paper's piecewise-linear model (solved exactly) or
/// the Shockley law (solved by the stiff solver).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(tag = "law", rename_all = "lowercase")]
pub enum Diode {
    /// U_t sgn(i) + R_D i.
    Pwl(PwlDiode),
    /// n V_T asinh(i/(2 I_s)) + R_s i.
    Shockley(ShockleyDiode),
}

impl Diode {
    /// The voltage that sets the unit of y and β: U_t (PWL turn-on, or the Shockley
    /// reference).
    pub fn reference_voltage(&self) -> f64 {
        match self {
            Diode::Pwl(d) => d.turn_on,
            Diode::Shockley(d) => d.reference_voltage,
        }
    }

    /// The part of the diodes' resistance that enters ζ: R_D for the PWL model, 0 for the
    /// Shockley law (its R_s is part of the nonlinear law).
    pub fn linear_resistance(&self) -> f64 {
        match self {
            Diode::Pwl(d) => d.resistance,
            Diode::Shockley(_) => 0.0,
        }
    }

    fn validate(&self) -> Result<Self> {
        Ok(match self {
            Diode::Pwl(d) => Diode::Pwl(PwlDiode::new(d.turn_on, d.resistance)?),
            Diode::Shockley(d) => Diode::Shockley(ShockleyDiode::new(d.pair, d.reference_voltage)?),
        })
    }
}

/// A series RLC circuit damped by a pair of anti-parallel diodes.
///
/// In dimensionless form (y = u_C/U_t, τ = ω0 t):
/// - PWL diodes: y'' + 2ζ y' + y + sgn(y') = β cos(wτ + φ) with 2ζ = (R + R_D)√(C/L);
/// - Shockley diodes: y'' + 2ζ_R y' + y + D(y') = β cos(wτ + φ) with 2ζ_R = R√(C/L) and D
///   the dimensionless diode law ([`crate::shockley::DiodeLaw`]).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Circuit {
    /// Inductance L in henry (> 0).
    pub inductance: f64,
    /// Capacitance C in farad (> 0).
    pub capacitance: f64,
    /// Series resistance R in ohms, without the diodes (≥ 0).
    pub resistance: f64,
    /// The diode pair.
    pub diode: Diode,
}

impl Circuit {
    /// Validated circuit.
    ///
    /// # Errors
    /// When L ≤ 0, C ≤ 0, R < 0, the diode is invalid, or any value is not finite.
    pub fn new(inductance: f64, capacitance: f64, resistance: f64, diode: Diode) -> Result<Self> {
        Self {
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
            diode: diode.validate()?,
        }
        .with_finite_scales()
    }

    /// This circuit, if its scales are finite and positive numbers; else the part furthest
    /// from the paper's circuit is to blame (C = 1e308 with the paper's L: C).
    fn with_finite_scales(self) -> Result<Self> {
        if self.scales().finite() {
            return Ok(self);
        }
        let paper = Circuit::paper();
        let parts = [
            (
                "L",
                self.inductance,
                paper.inductance,
                "with this C gives no finite ω0 = 1/√(LC) or impedance √(L/C) (henry)",
            ),
            (
                "C",
                self.capacitance,
                paper.capacitance,
                "with this L gives no finite ω0 = 1/√(LC) or impedance √(L/C) (farad)",
            ),
            (
                "U_t",
                self.diode.reference_voltage(),
                paper.diode.reference_voltage(),
                "with this L and C gives no finite current scale U_t/√(L/C) (volts)",
            ),
        ];
        let &(name, value, _, allowed) = furthest(&parts);
        invalid(name, value, allowed)
    }

    /// Re-check all fields (for values built by struct literal or deserialised).
    ///
    /// # Errors
    /// The first invalid field, as in [`Circuit::new`].
    pub fn validate(&self) -> Result<Self> {
        Self::new(
            self.inductance,
            self.capacitance,
            self.resistance,
            self.diode,
        )
    }

    /// The paper's experiment: L = 11.5 mH, C = 0.02 µF, R = 68 Ω, U_t = 0.7 V, R_D = 3.0 Ω
    /// (total series resistance 71 Ω), giving α = 6173.9 s⁻¹ and ω0 = 65938.0 rad/s.
    pub fn paper() -> Self {
        Self {
            inductance: 11.5e-3,
            capacitance: 0.02e-6,
            resistance: 68.0,
            diode: Diode::Pwl(PwlDiode {
                turn_on: 0.7,
                resistance: 3.0,
            }),
        }
    }

    /// The paper's circuit with two 1N4148 diodes at 27 °C instead of the PWL model (U_t =
    /// 0.7 V kept as the reference voltage).
    pub fn paper_shockley() -> Self {
        Self::paper().with_shockley(DiodePair::one_n4148())
    }

    /// The same L, C and R with a Shockley diode pair: the diodes' reference voltage U_t is
    /// kept (so β keeps its meaning U/U_t), a PWL resistance R_D is dropped (the Shockley law
    /// has its own R_s).
    pub fn with_shockley(&self, pair: DiodePair) -> Self {
        Self {
            diode: Diode::Shockley(ShockleyDiode {
                pair,
                reference_voltage: self.diode.reference_voltage(),
            }),
            ..*self
        }
    }

    /// Total resistance that enters ζ, in ohms: R + R_D with PWL diodes, R with Shockley
    /// diodes.
    pub fn total_resistance(&self) -> f64 {
        self.resistance + self.diode.linear_resistance()
    }

    /// Characteristic impedance √(L/C) in ohms.
    pub fn impedance(&self) -> f64 {
        (self.inductance / self.capacitance).sqrt()
    }

    /// Scales that turn dimensionless values into volts, amperes and seconds. `alpha` is
    /// [`Circuit::total_resistance`]/L, so `zeta()` is the ζ of the dimensionless model (ζ_R
    /// with Shockley diodes).
    pub fn scales(&self) -> Scales {
        let omega0 = 1.0 / (self.inductance * self.capacitance).sqrt();
        let reference = self.diode.reference_voltage();
        Scales {
            omega0,
            alpha: self.total_resistance() / self.inductance,
            position: reference,
            velocity: reference / self.impedance(),
            force: reference,
        }
    }

    /// Dimensionless parameters of this circuit (ζ from its parts) for a dimensionless drive
    /// w = Ω/ω0, β = U/U_t and phase φ (radians), with μs = 1.
    ///
    /// # Errors
    /// When w ≤ 0, β < 0 or a value is not finite.
    pub fn params(&self, w: f64, beta: f64, phi: f64) -> Result<Params> {
        Params::new(self.scales().zeta(), w, beta)?.with_phi(phi)
    }

    /// The dimensionless Shockley model at `params` (its ζ is ζ_R, its μs is not used), or
    /// `None` with PWL diodes.
    ///
    /// # Errors
    /// When `params` is invalid.
    pub fn shockley_model(&self, params: &Params) -> Result<Option<ShockleyModel>> {
        match self.diode {
            Diode::Pwl(_) => Ok(None),
            Diode::Shockley(d) => {
                let law = d.pair.law(d.reference_voltage, self.impedance())?;
                Ok(Some(ShockleyModel::new(*params, law)?))
            }
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
        Self {
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
        }
        .with_finite_scales()
    }

    /// This oscillator, if its scales are finite and positive numbers; else the part
    /// furthest from the example oscillator ([`Mechanics::example`]) is to blame.
    fn with_finite_scales(self) -> Result<Self> {
        if self.scales().finite() {
            return Ok(self);
        }
        let example = Mechanics::example();
        let parts = [
            (
                "m",
                self.mass,
                example.mass,
                "with this k, gamma and F0 gives no finite ω0 = √(k/m), α = γ/m or F0/k (kg)",
            ),
            (
                "k",
                self.stiffness,
                example.stiffness,
                "with this m and F0 gives no finite ω0 = √(k/m) or F0/k (N/m)",
            ),
            (
                "gamma",
                self.damping,
                example.damping,
                "with this m gives no finite α = γ/m (N s/m)",
            ),
            (
                "F0",
                self.friction,
                example.friction,
                "with this k and m gives no finite position or velocity scale F0/k, F0/√(km) (N)",
            ),
        ];
        let &(name, value, _, allowed) = furthest(&parts);
        invalid(name, value, allowed)
    }

    /// A mass on a spring with dry friction whose damping ratio is the paper's circuit's
    /// (ζ = 0.94/(2·√(200·0.5)) = 0.047): m = 0.5 kg, k = 200 N/m, γ = 0.94 N·s/m,
    /// F0 = 1 N. The lab's mechanical preset, and the reference an absurd value is measured
    /// from ([`crate::experiment::ExperimentSpec::build`]'s messages).
    pub fn example() -> Self {
        Self {
            mass: 0.5,
            stiffness: 200.0,
            damping: 0.94,
            friction: 1.0,
        }
    }

    /// Re-check all fields (for values built by struct literal or deserialised).
    ///
    /// # Errors
    /// The first invalid field, as in [`Mechanics::new`].
    pub fn validate(&self) -> Result<Self> {
        Self::new(self.mass, self.stiffness, self.damping, self.friction)
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

/// Of `parts` (name, value, reference value, words), the one whose value is furthest from
/// its reference, |ln(value/reference)| (a zero value is never the furthest).
fn furthest<'a>(
    parts: &'a [(&'static str, f64, f64, &'static str)],
) -> &'a (&'static str, f64, f64, &'static str) {
    let distance = |&(_, value, reference, _): &(&str, f64, f64, &str)| {
        if value > 0.0 && reference > 0.0 {
            (value / reference).ln().abs()
        } else {
            0.0
        }
    };
    parts
        .iter()
        .max_by(|a, b| distance(a).total_cmp(&distance(b)))
        .expect("parts to choose from")
}

/// Either physical twin.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum System {
    /// The diode-damped RLC circuit.
    Circuit(Circuit),
    /// The mass-spring oscillator with dry friction.
    Mechanics(Mechanics),
}

impl System {
    /// Which twin it is.
    pub fn kind(&self) -> SystemKind {
        match self {
            System::Circuit(_) => SystemKind::Circuit,
            System::Mechanics(_) => SystemKind::Mechanics,
        }
    }

    /// The scales of the underlying twin.
    pub fn scales(&self) -> Scales {
        match self {
            System::Circuit(c) => c.scales(),
            System::Mechanics(m) => m.scales(),
        }
    }
}

/// What an experiment describes: the dimensionless model alone, a circuit or a mechanical
/// oscillator. Its label is the one every front end shows (the lab's answers and presets,
/// Python's `Experiment.system`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum SystemKind {
    /// ζ, w, β and μs alone, no physical units.
    Dimensionless,
    /// The diode-damped RLC circuit.
    Circuit,
    /// The mass-spring oscillator with dry friction.
    Mechanics,
}

impl SystemKind {
    /// Every kind.
    pub const ALL: [SystemKind; 3] = [
        SystemKind::Dimensionless,
        SystemKind::Circuit,
        SystemKind::Mechanics,
    ];

    /// `dimensionless`, `circuit` or `mechanics`.
    pub fn label(self) -> &'static str {
        match self {
            SystemKind::Dimensionless => "dimensionless",
            SystemKind::Circuit => "circuit",
            SystemKind::Mechanics => "mechanics",
        }
    }

    /// The kind of a system, or [`SystemKind::Dimensionless`] for none.
    pub fn of(system: Option<&System>) -> Self {
        system.map_or(SystemKind::Dimensionless, System::kind)
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
    /// Whether every scale is a finite positive number (α finite and ≥ 0), as conversions
    /// both ways need.
    fn finite(&self) -> bool {
        let positive = |x: f64| x.is_finite() && x > 0.0;
        positive(self.omega0)
            && positive(self.position)
            && positive(self.velocity)
            && positive(self.force)
            && self.alpha.is_finite()
            && self.alpha >= 0.0
    }

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
            "omega",
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
    fn shockley_circuit_keeps_the_reference_and_drops_r_d() {
        let c = Circuit::paper_shockley();
        let s = c.scales();
        assert!((s.omega0 - 65_938.0).abs() < 0.1);
        assert!((2.0 * s.zeta() - 68.0 / c.impedance()).abs() < 1e-15);
        assert_eq!(s.force, 0.7);
        // β keeps its meaning: 1.498 V is β = 2.14 against U_t = 0.7 V.
        let p = s.params(1.498, 0.95 * s.omega0, 0.0).unwrap();
        assert!((p.beta - 2.14).abs() < 1e-12);
        assert!(Circuit::paper().shockley_model(&p).unwrap().is_none());
        let m = c.shockley_model(&p).unwrap().unwrap();
        assert_eq!(m.params, p);
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
        let bad = DiodePair {
            saturation_current: -1.0,
            ..DiodePair::one_n4148()
        };
        assert!(Circuit::new(1e-3, 1e-6, 1.0, Circuit::paper().with_shockley(bad).diode).is_err());
        assert!(PwlDiode::new(-0.7, 3.0).is_err());
        assert!(Mechanics::new(1.0, 1.0, -1.0, 1.0).is_err());
    }
}
