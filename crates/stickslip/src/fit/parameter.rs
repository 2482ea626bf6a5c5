//! The parameters a fit may free.

use super::FitError;
use crate::experiment::{DiodeModel, Experiment};
use crate::physical::{Circuit, Diode, Mechanics, System};
use serde::{Deserialize, Serialize};

/// A parameter of the circuit or of the mechanical oscillator that a fit may free, named as
/// the command-line flag that sets it: a circuit's `resistance`, `ut`, `rd`, `diode-is`,
/// `diode-n`, `diode-rs`, `inductance`, `capacitance`; a mechanical oscillator's `damping`
/// (γ), `friction` (F0), `mass` (m), `stiffness` (k); either's `mu-s`.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum FitParameter {
    /// Series resistance R (Ω).
    Resistance,
    /// PWL turn-on voltage U_t (V).
    Ut,
    /// PWL forward resistance R_D (Ω).
    Rd,
    /// Shockley saturation current I_s of one diode (A).
    DiodeIs,
    /// Shockley emission coefficient n.
    DiodeN,
    /// Shockley series resistance R_s of one diode (Ω).
    DiodeRs,
    /// Inductance L (H).
    Inductance,
    /// Capacitance C (F).
    Capacitance,
    /// Static-to-kinetic friction ratio μs (PWL circuits and mechanics).
    MuS,
    /// Viscous damping γ of a mechanical oscillator (N·s/m).
    Damping,
    /// Kinetic friction force F0 of a mechanical oscillator (N).
    Friction,
    /// Mass m of a mechanical oscillator (kg).
    Mass,
    /// Spring constant k of a mechanical oscillator (N/m).
    Stiffness,
}

impl FitParameter {
    /// Every parameter, in the order of reports.
    pub const ALL: [FitParameter; 13] = [
        FitParameter::Resistance,
        FitParameter::Ut,
        FitParameter::Rd,
        FitParameter::DiodeIs,
        FitParameter::DiodeN,
        FitParameter::DiodeRs,
        FitParameter::Inductance,
        FitParameter::Capacitance,
        FitParameter::MuS,
        FitParameter::Damping,
        FitParameter::Friction,
        FitParameter::Mass,
        FitParameter::Stiffness,
    ];

    /// The parameters of a circuit, in the order of reports.
    pub const CIRCUIT: [FitParameter; 9] = [
        FitParameter::Resistance,
        FitParameter::Ut,
        FitParameter::Rd,
        FitParameter::DiodeIs,
        FitParameter::DiodeN,
        FitParameter::DiodeRs,
        FitParameter::Inductance,
        FitParameter::Capacitance,
        FitParameter::MuS,
    ];

    /// The parameters of a mechanical oscillator, in the order of reports.
    pub const MECHANICS: [FitParameter; 5] = [
        FitParameter::Damping,
        FitParameter::Friction,
        FitParameter::Mass,
        FitParameter::Stiffness,
        FitParameter::MuS,
    ];

    /// The name: the flag's, without its dashes in front (`diode-is`).
    pub fn label(self) -> &'static str {
        match self {
            FitParameter::Resistance => "resistance",
            FitParameter::Ut => "ut",
            FitParameter::Rd => "rd",
            FitParameter::DiodeIs => "diode-is",
            FitParameter::DiodeN => "diode-n",
            FitParameter::DiodeRs => "diode-rs",
            FitParameter::Inductance => "inductance",
            FitParameter::Capacitance => "capacitance",
            FitParameter::MuS => "mu-s",
            FitParameter::Damping => "damping",
            FitParameter::Friction => "friction",
            FitParameter::Mass => "mass",
            FitParameter::Stiffness => "stiffness",
        }
    }

    /// The symbol's name in the experiment's key table (`gamma`, `F0`, `m`, `k`) for a
    /// mechanical parameter, also accepted by [`std::str::FromStr`].
    fn key_name(self) -> Option<&'static str> {
        match self {
            FitParameter::Damping => Some("gamma"),
            FitParameter::Friction => Some("f0"),
            FitParameter::Mass => Some("m"),
            FitParameter::Stiffness => Some("k"),
            _ => None,
        }
    }

    /// Whether the parameter belongs to a mechanical oscillator (`mu-s` belongs to both).
    pub fn is_mechanical(self) -> bool {
        FitParameter::MECHANICS.contains(&self)
    }

    /// Whether the parameter belongs to a circuit (`mu-s` belongs to both).
    pub fn is_circuit(self) -> bool {
        FitParameter::CIRCUIT.contains(&self)
    }

    /// The names of `list`, comma-separated.
    pub(crate) fn names(list: &[FitParameter]) -> String {
        list.iter()
            .map(|p| p.label())
            .collect::<Vec<_>>()
            .join(", ")
    }

    /// The SI unit of the value (empty for a pure number).
    pub fn unit(self) -> &'static str {
        match self {
            FitParameter::Resistance | FitParameter::Rd | FitParameter::DiodeRs => "ohm",
            FitParameter::Ut => "V",
            FitParameter::DiodeIs => "A",
            FitParameter::Inductance => "H",
            FitParameter::Capacitance => "F",
            FitParameter::Damping => "N s/m",
            FitParameter::Friction => "N",
            FitParameter::Mass => "kg",
            FitParameter::Stiffness => "N/m",
            FitParameter::DiodeN | FitParameter::MuS => "",
        }
    }

    /// Whether the parameter belongs to the diode law `model` (`ut`, `rd`, `mu-s` and the
    /// mechanical ones, whose Coulomb law is the PWL law: PWL; `diode-*`: Shockley; the
    /// others: both).
    pub fn applies_to(self, model: DiodeModel) -> bool {
        match self {
            FitParameter::Ut
            | FitParameter::Rd
            | FitParameter::MuS
            | FitParameter::Damping
            | FitParameter::Friction
            | FitParameter::Mass
            | FitParameter::Stiffness => model == DiodeModel::Pwl,
            FitParameter::DiodeIs | FitParameter::DiodeN | FitParameter::DiodeRs => {
                model == DiodeModel::Shockley
            }
            _ => true,
        }
    }

    /// The parameter's value in `experiment` (a circuit or a mechanical oscillator).
    ///
    /// # Errors
    /// [`FitError::NeedsCircuit`] without a physical system; [`FitError::WrongSystem`] for a
    /// circuit's parameter on a mechanical oscillator or the other way round;
    /// [`FitError::WrongLaw`] for a parameter of the other diode law.
    pub fn get(self, experiment: &Experiment) -> Result<f64, FitError> {
        match experiment.system().ok_or(FitError::NeedsCircuit)? {
            System::Mechanics(m) => {
                if !self.is_mechanical() {
                    return Err(FitError::WrongSystem {
                        parameter: self,
                        mechanics: true,
                    });
                }
                Ok(match self {
                    FitParameter::Damping => m.damping,
                    FitParameter::Friction => m.friction,
                    FitParameter::Mass => m.mass,
                    FitParameter::Stiffness => m.stiffness,
                    _ => experiment.mu_s(),
                })
            }
            System::Circuit(c) => {
                if !self.is_circuit() {
                    return Err(FitError::WrongSystem {
                        parameter: self,
                        mechanics: false,
                    });
                }
                self.check_law(experiment.diode_model())?;
                Ok(match (self, c.diode) {
                    (FitParameter::Resistance, _) => c.resistance,
                    (FitParameter::Inductance, _) => c.inductance,
                    (FitParameter::Capacitance, _) => c.capacitance,
                    (FitParameter::MuS, _) => experiment.mu_s(),
                    (FitParameter::Ut, Diode::Pwl(d)) => d.turn_on,
                    (FitParameter::Rd, Diode::Pwl(d)) => d.resistance,
                    (FitParameter::DiodeIs, Diode::Shockley(d)) => d.pair.saturation_current,
                    (FitParameter::DiodeN, Diode::Shockley(d)) => d.pair.emission,
                    (FitParameter::DiodeRs, Diode::Shockley(d)) => d.pair.series_resistance,
                    _ => unreachable!("the law was checked"),
                })
            }
        }
    }

    fn check_law(self, model: DiodeModel) -> Result<(), FitError> {
        if self.applies_to(model) {
            Ok(())
        } else {
            Err(FitError::WrongLaw {
                parameter: self,
                model,
            })
        }
    }

    /// `circuit` with this parameter set to `value` (μs is not a part of the circuit and is
    /// left to the caller).
    pub(crate) fn set(self, circuit: &mut Circuit, value: f64) {
        match (self, &mut circuit.diode) {
            (FitParameter::Resistance, _) => circuit.resistance = value,
            (FitParameter::Inductance, _) => circuit.inductance = value,
            (FitParameter::Capacitance, _) => circuit.capacitance = value,
            (FitParameter::Ut, Diode::Pwl(d)) => d.turn_on = value,
            (FitParameter::Rd, Diode::Pwl(d)) => d.resistance = value,
            (FitParameter::DiodeIs, Diode::Shockley(d)) => d.pair.saturation_current = value,
            (FitParameter::DiodeN, Diode::Shockley(d)) => d.pair.emission = value,
            (FitParameter::DiodeRs, Diode::Shockley(d)) => d.pair.series_resistance = value,
            _ => {}
        }
    }

    /// `mechanics` with this parameter set to `value` (μs is left to the caller).
    pub(crate) fn set_mechanics(self, mechanics: &mut Mechanics, value: f64) {
        match self {
            FitParameter::Damping => mechanics.damping = value,
            FitParameter::Friction => mechanics.friction = value,
            FitParameter::Mass => mechanics.mass = value,
            FitParameter::Stiffness => mechanics.stiffness = value,
            _ => {}
        }
    }
}

impl std::fmt::Display for FitParameter {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.label())
    }
}

impl std::str::FromStr for FitParameter {
    type Err = FitError;

    /// A parameter by its name ([`FitParameter::label`]); `mu_s`, `diode_is` … with
    /// underscores are accepted too, and the mechanical parameters by their symbols in the
    /// key table (`gamma`, `F0`, `m`, `k`).
    fn from_str(s: &str) -> Result<Self, FitError> {
        let wanted = s.trim().replace('_', "-").to_ascii_lowercase();
        FitParameter::ALL
            .into_iter()
            .find(|p| p.label() == wanted || p.key_name() == Some(wanted.as_str()))
            .ok_or_else(|| FitError::UnknownParameter(s.trim().chars().take(40).collect()))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn names_round_trip() {
        for p in FitParameter::ALL {
            assert_eq!(p.label().parse::<FitParameter>().unwrap(), p);
            assert_eq!(p.to_string(), p.label());
        }
        assert_eq!("mu_s".parse::<FitParameter>().unwrap(), FitParameter::MuS);
        let err = "zeta".parse::<FitParameter>().unwrap_err().to_string();
        assert!(err.contains("zeta") && err.contains("resistance"), "{err}");
        assert!(
            err.contains("damping") && err.contains("stiffness"),
            "{err}"
        );
        for (symbol, p) in [
            ("gamma", FitParameter::Damping),
            ("F0", FitParameter::Friction),
            ("m", FitParameter::Mass),
            ("k", FitParameter::Stiffness),
        ] {
            assert_eq!(symbol.parse::<FitParameter>().unwrap(), p);
        }
        // Every parameter belongs to a circuit or to mechanics, and only μs to both.
        for p in FitParameter::ALL {
            assert!(p.is_circuit() || p.is_mechanical(), "{p}");
            assert_eq!(p.is_circuit() && p.is_mechanical(), p == FitParameter::MuS);
        }
    }
}
