//! The named values of an experiment description, with their units and allowed ranges.

use crate::error::{check, Result};
use crate::limits;
use crate::shockley::diode::ZERO_CELSIUS;
use serde::{Deserialize, Serialize};

/// Largest resistance R or R_D (Ω): far beyond any ζ the solvers take with real parts, and
/// small enough that ζ = (R + R_D)/2·√(C/L) stays finite (1e308 overflowed it).
const RESISTANCE_MAX: f64 = 1e9;
/// Range of the Shockley saturation current (A): real junctions lie between about 1e-18 A
/// and 1e-6 A; beyond 1 A the knee voltage of the law is no longer finite.
const SATURATION_MIN: f64 = 1e-30;
const SATURATION_MAX: f64 = 1.0;
/// Range of the emission coefficient (real diodes: 1 to 2); beyond it the thermal voltage
/// n·V_T makes a stiff law the integrator cannot start on.
const EMISSION_MIN: f64 = 0.1;
const EMISSION_MAX: f64 = 100.0;
/// Largest Shockley series resistance (Ω).
const SERIES_RESISTANCE_MAX: f64 = 1e6;
/// Highest diode temperature (°C): silicon junctions fail below 200 °C.
const TEMPERATURE_MAX: f64 = 1000.0;

/// One value of an experiment description. Its [`Key::name`] is the key of the TOML file and
/// the keyword of the Python package; the command-line tool has its own flag for each.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord, Serialize, Deserialize)]
#[non_exhaustive]
pub enum Key {
    /// Damping ratio ζ (dimensionless description only).
    Zeta,
    /// Drive frequency w = Ω/ω0.
    W,
    /// Drive amplitude β.
    Beta,
    /// Drive phase φ in radians.
    Phi,
    /// Static-to-kinetic friction ratio μs.
    MuS,
    /// Initial position y0.
    Y0,
    /// Initial velocity v0.
    V0,
    /// Inductance L (H).
    Inductance,
    /// Capacitance C (F).
    Capacitance,
    /// Series resistance R without the diodes (Ω).
    Resistance,
    /// Diode turn-on voltage U_t (V), also the reference voltage of y and β.
    TurnOn,
    /// PWL diode resistance R_D (Ω).
    DiodeResistance,
    /// Mass m (kg).
    Mass,
    /// Spring constant k (N/m).
    Stiffness,
    /// Viscous damping γ (N·s/m).
    Damping,
    /// Kinetic friction force F0 (N).
    Friction,
    /// Drive amplitude U (V) or F (N).
    Amplitude,
    /// Drive frequency f (Hz).
    Frequency,
    /// Drive angular frequency Ω (rad/s).
    Omega,
    /// Initial capacitor voltage u_C(0) (V), or initial position r(0) (m).
    Uc0,
    /// Initial current i(0) (A), or initial velocity ṙ(0) (m/s).
    I0,
    /// Shockley saturation current I_s (A).
    SaturationCurrent,
    /// Shockley emission coefficient n.
    Emission,
    /// Shockley series resistance R_s (Ω).
    SeriesResistance,
    /// Diode temperature (°C).
    Temperature,
    /// The diode law, `pwl` or `shockley`.
    Diode,
    /// A built-in physical description (`paper`).
    Preset,
}

impl Key {
    /// Every key.
    pub const ALL: [Key; 27] = [
        Key::Zeta,
        Key::W,
        Key::Beta,
        Key::Phi,
        Key::MuS,
        Key::Y0,
        Key::V0,
        Key::Inductance,
        Key::Capacitance,
        Key::Resistance,
        Key::TurnOn,
        Key::DiodeResistance,
        Key::Mass,
        Key::Stiffness,
        Key::Damping,
        Key::Friction,
        Key::Amplitude,
        Key::Frequency,
        Key::Omega,
        Key::Uc0,
        Key::I0,
        Key::SaturationCurrent,
        Key::Emission,
        Key::SeriesResistance,
        Key::Temperature,
        Key::Diode,
        Key::Preset,
    ];

    /// The key's name in the TOML file and the Python package.
    pub fn name(self) -> &'static str {
        match self {
            Key::Zeta => "zeta",
            Key::W => "w",
            Key::Beta => "beta",
            Key::Phi => "phi",
            Key::MuS => "mu_s",
            Key::Y0 => "y0",
            Key::V0 => "v0",
            Key::Inductance => "L",
            Key::Capacitance => "C",
            Key::Resistance => "R",
            Key::TurnOn => "U_t",
            Key::DiodeResistance => "R_D",
            Key::Mass => "m",
            Key::Stiffness => "k",
            Key::Damping => "gamma",
            Key::Friction => "F0",
            Key::Amplitude => "U",
            Key::Frequency => "f",
            Key::Omega => "omega",
            Key::Uc0 => "uc0",
            Key::I0 => "i0",
            Key::SaturationCurrent => "Is",
            Key::Emission => "n",
            Key::SeriesResistance => "Rs",
            Key::Temperature => "temperature",
            Key::Diode => "diode",
            Key::Preset => "preset",
        }
    }

    /// The key named `name` ([`Key::name`]), or `None`. `F` (newtons) names the drive
    /// amplitude as `U` (volts) does.
    pub fn from_name(name: &str) -> Option<Key> {
        if name == "F" {
            return Some(Key::Amplitude);
        }
        Key::ALL.into_iter().find(|k| k.name() == name)
    }

    /// What the key means, with its unit.
    pub fn description(self) -> &'static str {
        match self {
            Key::Zeta => "damping ratio ζ",
            Key::W => "drive frequency w = Ω/ω0",
            Key::Beta => "drive amplitude β = U/U_t or F/F0",
            Key::Phi => "drive phase φ (rad)",
            Key::MuS => "static-to-kinetic friction ratio μs",
            Key::Y0 => "initial position y0",
            Key::V0 => "initial velocity v0",
            Key::Inductance => "inductance L (H)",
            Key::Capacitance => "capacitance C (F)",
            Key::Resistance => "series resistance R without the diodes (Ω)",
            Key::TurnOn => "diode turn-on voltage U_t (V)",
            Key::DiodeResistance => "PWL diode resistance R_D (Ω)",
            Key::Mass => "mass m (kg)",
            Key::Stiffness => "spring constant k (N/m)",
            Key::Damping => "viscous damping γ (N·s/m)",
            Key::Friction => "kinetic friction force F0 (N)",
            Key::Amplitude => "drive amplitude U (V) or F (N)",
            Key::Frequency => "drive frequency f (Hz)",
            Key::Omega => "drive angular frequency Ω (rad/s)",
            Key::Uc0 => "initial capacitor voltage u_C(0) (V) or position r(0) (m)",
            Key::I0 => "initial current i(0) (A) or velocity ṙ(0) (m/s)",
            Key::SaturationCurrent => "Shockley saturation current I_s (A)",
            Key::Emission => "Shockley emission coefficient n",
            Key::SeriesResistance => "Shockley series resistance R_s (Ω)",
            Key::Temperature => "diode temperature (°C)",
            Key::Diode => "diode law: pwl or shockley",
            Key::Preset => "built-in physical description",
        }
    }

    /// Check a value of this key on its own: the same ranges as the types it builds (e.g.
    /// L > 0, R ≥ 0, 1 ≤ μs ≤ 1e9), with the same messages. Dimensionless values must lie in
    /// the range the solvers support ([`crate::limits`]); physical values are checked against
    /// it through their dimensionless images when the experiment is built
    /// ([`crate::Error::ImageOutOfRange`]).
    ///
    /// # Errors
    /// [`crate::Error::InvalidParameter`] naming the value and what is allowed.
    pub fn check(self, value: f64) -> Result<f64> {
        let (name, ok, allowed): (&'static str, bool, &'static str) = match self {
            Key::Zeta => ("zeta", limits::zeta_ok(value), limits::ZETA_ALLOWED),
            Key::W => ("w", limits::w_ok(value), limits::W_ALLOWED),
            Key::Beta => ("beta", limits::beta_ok(value), limits::BETA_ALLOWED),
            Key::Phi => ("phi", limits::phi_ok(value), limits::PHI_ALLOWED),
            Key::MuS => ("mu_s", limits::mu_s_ok(value), limits::MU_S_ALLOWED),
            Key::Y0 => ("y0", limits::state_ok(value), limits::STATE_ALLOWED),
            Key::V0 => ("v0", limits::state_ok(value), limits::STATE_ALLOWED),
            Key::Inductance => ("L", value > 0.0, "must be finite and > 0 (henry)"),
            Key::Capacitance => ("C", value > 0.0, "must be finite and > 0 (farad)"),
            Key::Resistance => (
                "R",
                (0.0..=RESISTANCE_MAX).contains(&value),
                "must be finite and from 0 to 1e9 (ohms)",
            ),
            Key::TurnOn => ("U_t", value > 0.0, "must be finite and > 0 (volts)"),
            Key::DiodeResistance => (
                "R_D",
                (0.0..=RESISTANCE_MAX).contains(&value),
                "must be finite and from 0 to 1e9 (ohms)",
            ),
            Key::Mass => ("m", value > 0.0, "must be finite and > 0 (kg)"),
            Key::Stiffness => ("k", value > 0.0, "must be finite and > 0 (N/m)"),
            Key::Damping => ("gamma", value >= 0.0, "must be finite and >= 0 (N s/m)"),
            Key::Friction => ("F0", value > 0.0, "must be finite and > 0 (N)"),
            Key::Amplitude => ("U", value >= 0.0, "must be finite and >= 0 (V or N)"),
            Key::Frequency => ("f", value > 0.0, "must be finite and > 0 (Hz)"),
            Key::Omega => ("Omega", value > 0.0, "must be finite and > 0 (rad/s)"),
            Key::Uc0 => ("uc0", true, "must be finite"),
            Key::I0 => ("i0", true, "must be finite"),
            Key::SaturationCurrent => (
                "I_s",
                (SATURATION_MIN..=SATURATION_MAX).contains(&value),
                "must be finite and from 1e-30 to 1 (amperes)",
            ),
            Key::Emission => (
                "n",
                (EMISSION_MIN..=EMISSION_MAX).contains(&value),
                "must be finite and from 0.1 to 100",
            ),
            Key::SeriesResistance => (
                "R_s",
                (0.0..=SERIES_RESISTANCE_MAX).contains(&value),
                "must be finite and from 0 to 1e6 (ohms)",
            ),
            Key::Temperature => (
                "temperature",
                value > -ZERO_CELSIUS && value <= TEMPERATURE_MAX,
                "must be finite, above -273.15 and at most 1000 (degrees Celsius)",
            ),
            Key::Diode | Key::Preset => (self.name(), false, "is not a number"),
        };
        check(name, value, ok, allowed)
    }
}

impl std::fmt::Display for Key {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.name())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn names_are_unique() {
        let mut names: Vec<&str> = Key::ALL.iter().map(|k| k.name()).collect();
        names.sort_unstable();
        names.dedup();
        assert_eq!(names.len(), Key::ALL.len());
        for k in Key::ALL {
            assert_eq!(Key::from_name(k.name()), Some(k));
        }
        assert_eq!(Key::from_name("F"), Some(Key::Amplitude));
        assert_eq!(Key::from_name("Q"), None);
    }

    #[test]
    fn checks_match_the_types() {
        assert!(Key::Inductance.check(0.0).is_err());
        assert!(Key::Resistance.check(0.0).is_ok());
        assert!(Key::MuS.check(0.99).is_err());
        assert!(Key::Temperature.check(-300.0).is_err());
        assert!(Key::Phi.check(f64::NAN).is_err());
        assert!(Key::Diode.check(1.0).is_err());
    }

    /// Values the solvers could not start from (1e308 made ζ overflow or the Shockley law
    /// stiff beyond the integrator) are refused by the key that gives them; the ends of each
    /// range are accepted.
    #[test]
    fn circuit_and_diode_values_have_finite_ranges() {
        for (key, inside, outside) in [
            (Key::Resistance, [0.0, 1e9], 1.1e9),
            (Key::DiodeResistance, [0.0, 1e9], 1e308),
            (Key::SaturationCurrent, [1e-30, 1.0], 1e308),
            (Key::Emission, [0.1, 100.0], 1e308),
            (Key::SeriesResistance, [0.0, 1e6], 1e308),
            (Key::Temperature, [-273.0, 1000.0], 1e308),
        ] {
            for v in inside {
                assert_eq!(key.check(v).unwrap(), v, "{key} {v}");
            }
            let err = key.check(outside).unwrap_err().to_string();
            assert!(err.contains("must be finite"), "{key}: {err}");
        }
        assert!(Key::SaturationCurrent.check(1e-31).is_err());
        assert!(Key::Emission.check(0.09).is_err());
    }
}
