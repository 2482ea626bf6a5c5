//! The parameters a fit may free.

use super::FitError;
use crate::experiment::{DiodeModel, Experiment};
use crate::physical::{Circuit, Diode};
use serde::{Deserialize, Serialize};

/// A parameter of the circuit that a fit may free, named as the command-line flag that sets
/// it (`resistance`, `ut`, `rd`, `diode-is`, `diode-n`, `diode-rs`, `inductance`,
/// `capacitance`, `mu-s`).
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
    /// Static-to-kinetic friction ratio μs (PWL only).
    MuS,
}

impl FitParameter {
    /// Every parameter, in the order of reports.
    pub const ALL: [FitParameter; 9] = [
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
        }
    }

    /// The SI unit of the value (empty for a pure number).
    pub fn unit(self) -> &'static str {
        match self {
            FitParameter::Resistance | FitParameter::Rd | FitParameter::DiodeRs => "ohm",
            FitParameter::Ut => "V",
            FitParameter::DiodeIs => "A",
            FitParameter::Inductance => "H",
            FitParameter::Capacitance => "F",
            FitParameter::DiodeN | FitParameter::MuS => "",
        }
    }

    /// Whether the parameter belongs to the diode law `model` (`ut`, `rd`, `mu-s`: PWL;
    /// `diode-*`: Shockley; the others: both).
    pub fn applies_to(self, model: DiodeModel) -> bool {
        match self {
            FitParameter::Ut | FitParameter::Rd | FitParameter::MuS => model == DiodeModel::Pwl,
            FitParameter::DiodeIs | FitParameter::DiodeN | FitParameter::DiodeRs => {
                model == DiodeModel::Shockley
            }
            _ => true,
        }
    }

    /// The parameter's value in `experiment` (a circuit).
    ///
    /// # Errors
    /// [`FitError::NeedsCircuit`] without a circuit; [`FitError::WrongLaw`] for a parameter of
    /// the other diode law.
    pub fn get(self, experiment: &Experiment) -> Result<f64, FitError> {
        let c = experiment.circuit_ref().ok_or(FitError::NeedsCircuit)?;
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
}

impl std::fmt::Display for FitParameter {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.label())
    }
}

impl std::str::FromStr for FitParameter {
    type Err = FitError;

    /// A parameter by its name ([`FitParameter::label`]); `mu_s`, `diode_is` … with
    /// underscores are accepted too.
    fn from_str(s: &str) -> Result<Self, FitError> {
        let wanted = s.trim().replace('_', "-").to_ascii_lowercase();
        FitParameter::ALL
            .into_iter()
            .find(|p| p.label() == wanted)
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
    }
}
