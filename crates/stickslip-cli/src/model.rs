//! The model flags shared by every command: dimensionless (`--zeta --w --beta ...`) or a
//! physical description (`--preset paper`, `--config FILE.toml`, `--inductance ...`). The flags
//! become one layer of a library [`ExperimentSpec`] (over the file's, which the library reads
//! from the file's text); the library checks and builds the [`Experiment`].

use crate::output::UsageError;
use anyhow::Result;
use std::path::PathBuf;
use stickslip::experiment::{
    DiodeModel as LibraryDiode, Experiment, ExperimentSpec, Key, Preset as LibraryPreset,
};

/// Parse a number with an optional SI prefix and unit: `0.02u`, `20nF`, `11.5mH`, `9.9kHz`,
/// `68ohm`, `1e-3`.
pub fn si_value(text: &str) -> Result<f64, String> {
    stickslip::units::parse_si(text).map_err(|e| e.to_string())
}

/// Parse a finite plain number (dimensionless flags).
pub fn finite(text: &str) -> Result<f64, String> {
    stickslip::units::parse_plain(text).map_err(|e| e.to_string())
}

/// Read the value of the flag of `key` as that flag does: a plain number for the
/// dimensionless values, the emission coefficient and the temperature, a number with an
/// optional SI prefix and unit for the physical values. (The lab reads query values with it,
/// so that its keys take what the flags take.)
///
/// # Errors
/// The parser's one-line message; [`Key::Preset`] and [`Key::Diode`] are not numbers.
pub fn parse_value(key: Key, text: &str) -> Result<f64, String> {
    match key {
        Key::Zeta
        | Key::W
        | Key::Beta
        | Key::Phi
        | Key::MuS
        | Key::Y0
        | Key::V0
        | Key::Emission
        | Key::Temperature => finite(text),
        Key::Preset | Key::Diode => Err(format!("{} is not a number", flag_name(key))),
        _ => si_value(text),
    }
}

/// Which law the diode pair follows.
#[derive(Debug, Clone, Copy, PartialEq, Eq, clap::ValueEnum, Default)]
pub enum DiodeModel {
    /// Piecewise linear: U_t sgn(i) + R_D i (the paper's model; solved exactly).
    #[default]
    Pwl,
    /// Shockley law of two anti-parallel diodes: n V_T asinh(i/2I_s) + R_s i (stiff solver).
    Shockley,
}

/// Model flags, as typed. Dimensionless flags override values derived from a physical
/// description; physical flags override the preset or the config file.
#[derive(Debug, Clone, Default, clap::Args)]
pub struct ModelArgs {
    /// Damping ratio ζ = α/(2ω0) ≥ 0 [default: the paper's circuit, 0.0468].
    #[arg(long, value_parser = finite, allow_hyphen_values = true, help_heading = "Model (dimensionless)")]
    pub zeta: Option<f64>,
    /// Drive frequency w = Ω/ω0 > 0.
    #[arg(long, value_parser = finite, allow_hyphen_values = true, help_heading = "Model (dimensionless)")]
    pub w: Option<f64>,
    /// Drive amplitude β = U/U_t (circuit) or F/F0 (mechanics), ≥ 0.
    #[arg(long, value_parser = finite, allow_hyphen_values = true, help_heading = "Model (dimensionless)")]
    pub beta: Option<f64>,
    /// Drive phase φ in radians at τ = 0 [default: 0].
    #[arg(long, value_parser = finite, allow_hyphen_values = true, help_heading = "Model (dimensionless)")]
    pub phi: Option<f64>,
    /// Static-to-kinetic friction ratio μs ≥ 1 [default: 1, as in the paper].
    #[arg(long = "mu-s", value_parser = finite, allow_hyphen_values = true, help_heading = "Model (dimensionless)")]
    pub mu_s: Option<f64>,
    /// Initial position y0 = u_C/U_t [default: 0].
    #[arg(long, value_parser = finite, allow_hyphen_values = true, help_heading = "Model (dimensionless)")]
    pub y0: Option<f64>,
    /// Initial velocity v0 = y'(0) [default: 0].
    #[arg(long, value_parser = finite, allow_hyphen_values = true, help_heading = "Model (dimensionless)")]
    pub v0: Option<f64>,

    /// A built-in physical description: `paper` (L = 11.5 mH, C = 0.02 µF, R = 68 Ω,
    /// U_t = 0.7 V, R_D = 3.0 Ω).
    #[arg(long, value_enum, help_heading = "Model (physical)")]
    pub preset: Option<Preset>,
    /// A TOML experiment file (sections `[circuit]` or `[mechanics]`, `[drive]`, `[model]`, `[shockley]`);
    /// see the README for an example.
    #[arg(long, value_name = "FILE", help_heading = "Model (physical)")]
    pub config: Option<PathBuf>,
    /// Inductance L in henry (SI prefixes allowed: 11.5m).
    #[arg(long, alias = "L", value_parser = si_value, help_heading = "Model (physical)", allow_hyphen_values = true)]
    pub inductance: Option<f64>,
    /// Capacitance C in farad (0.02u).
    #[arg(long, alias = "C", value_parser = si_value, help_heading = "Model (physical)", allow_hyphen_values = true)]
    pub capacitance: Option<f64>,
    /// Series resistance R in ohms, without the diodes.
    #[arg(long, alias = "R", value_parser = si_value, help_heading = "Model (physical)", allow_hyphen_values = true)]
    pub resistance: Option<f64>,
    /// Diode turn-on voltage U_t in volts (PWL model).
    #[arg(long = "ut", value_parser = si_value, help_heading = "Model (physical)", allow_hyphen_values = true)]
    pub turn_on: Option<f64>,
    /// Diode forward resistance R_D in ohms (PWL model).
    #[arg(long = "rd", value_parser = si_value, help_heading = "Model (physical)", allow_hyphen_values = true)]
    pub diode_resistance: Option<f64>,
    /// Mass m in kg (mechanical twin).
    #[arg(long, value_parser = si_value, help_heading = "Model (physical)", allow_hyphen_values = true)]
    pub mass: Option<f64>,
    /// Spring constant k in N/m (mechanical twin).
    #[arg(long, value_parser = si_value, help_heading = "Model (physical)", allow_hyphen_values = true)]
    pub stiffness: Option<f64>,
    /// Viscous damping γ in N·s/m (mechanical twin).
    #[arg(long, value_parser = si_value, help_heading = "Model (physical)", allow_hyphen_values = true)]
    pub damping: Option<f64>,
    /// Kinetic friction force F0 in N (mechanical twin).
    #[arg(long, value_parser = si_value, help_heading = "Model (physical)", allow_hyphen_values = true)]
    pub friction: Option<f64>,
    /// Drive amplitude: U in volts (circuit) or F in newtons (mechanics).
    #[arg(long, alias = "U", value_parser = si_value, help_heading = "Model (physical)", allow_hyphen_values = true)]
    pub amplitude: Option<f64>,
    /// Drive frequency f in Hz.
    #[arg(long, value_parser = si_value, help_heading = "Model (physical)", allow_hyphen_values = true)]
    pub freq: Option<f64>,
    /// Drive angular frequency Ω in rad/s.
    #[arg(long, value_parser = si_value, help_heading = "Model (physical)", allow_hyphen_values = true)]
    pub omega: Option<f64>,
    /// Initial capacitor voltage u_C(0) in volts (circuit; instead of --y0).
    #[arg(long, value_parser = si_value, allow_hyphen_values = true, help_heading = "Model (physical)")]
    pub uc0: Option<f64>,
    /// Initial current i(0) in amperes (circuit; instead of --v0).
    #[arg(long, value_parser = si_value, allow_hyphen_values = true, help_heading = "Model (physical)")]
    pub i0: Option<f64>,

    /// Diode law: `pwl` (exact solver) or `shockley` (stiff solver).
    #[arg(long, value_enum, help_heading = "Diode model")]
    pub model: Option<DiodeModel>,
    /// Shockley saturation current I_s in amperes [default: 4.352n, 1N4148].
    #[arg(long = "diode-is", value_parser = si_value, help_heading = "Diode model", allow_hyphen_values = true)]
    pub diode_is: Option<f64>,
    /// Shockley emission coefficient n [default: 1.906, 1N4148].
    #[arg(long = "diode-n", value_parser = finite, help_heading = "Diode model", allow_hyphen_values = true)]
    pub diode_n: Option<f64>,
    /// Shockley series resistance R_s in ohms [default: 0.6458, 1N4148].
    #[arg(long = "diode-rs", value_parser = si_value, help_heading = "Diode model", allow_hyphen_values = true)]
    pub diode_rs: Option<f64>,
    /// Diode temperature in °C [default: 27, as SPICE].
    #[arg(long, value_parser = finite, allow_hyphen_values = true, help_heading = "Diode model")]
    pub temperature: Option<f64>,
}

/// Built-in physical descriptions.
#[derive(Debug, Clone, Copy, PartialEq, Eq, clap::ValueEnum)]
pub enum Preset {
    /// The paper's experiment.
    Paper,
}

/// The flag that sets `key`, as the user types it.
pub fn flag_name(key: Key) -> String {
    let flag = match key {
        Key::Zeta => "zeta",
        Key::W => "w",
        Key::Beta => "beta",
        Key::Phi => "phi",
        Key::MuS => "mu-s",
        Key::Y0 => "y0",
        Key::V0 => "v0",
        Key::Inductance => "inductance",
        Key::Capacitance => "capacitance",
        Key::Resistance => "resistance",
        Key::TurnOn => "ut",
        Key::DiodeResistance => "rd",
        Key::Mass => "mass",
        Key::Stiffness => "stiffness",
        Key::Damping => "damping",
        Key::Friction => "friction",
        Key::Amplitude => "amplitude",
        Key::Frequency => "freq",
        Key::Omega => "omega",
        Key::Uc0 => "uc0",
        Key::I0 => "i0",
        Key::SaturationCurrent => "diode-is",
        Key::Emission => "diode-n",
        Key::SeriesResistance => "diode-rs",
        Key::Temperature => "temperature",
        Key::Diode => "model",
        Key::Preset => "preset",
        _ => key.name(),
    };
    format!("--{flag}")
}

impl ModelArgs {
    /// The flags' values, key by key.
    fn values(&self) -> [(Key, Option<f64>); 25] {
        [
            (Key::Zeta, self.zeta),
            (Key::W, self.w),
            (Key::Beta, self.beta),
            (Key::Phi, self.phi),
            (Key::MuS, self.mu_s),
            (Key::Y0, self.y0),
            (Key::V0, self.v0),
            (Key::Inductance, self.inductance),
            (Key::Capacitance, self.capacitance),
            (Key::Resistance, self.resistance),
            (Key::TurnOn, self.turn_on),
            (Key::DiodeResistance, self.diode_resistance),
            (Key::Mass, self.mass),
            (Key::Stiffness, self.stiffness),
            (Key::Damping, self.damping),
            (Key::Friction, self.friction),
            (Key::Amplitude, self.amplitude),
            (Key::Frequency, self.freq),
            (Key::Omega, self.omega),
            (Key::Uc0, self.uc0),
            (Key::I0, self.i0),
            (Key::SaturationCurrent, self.diode_is),
            (Key::Emission, self.diode_n),
            (Key::SeriesResistance, self.diode_rs),
            (Key::Temperature, self.temperature),
        ]
    }

    /// Whether the flag of `key` was given.
    pub fn given(&self, key: Key) -> bool {
        match key {
            Key::Preset => self.preset.is_some(),
            Key::Diode => self.model.is_some(),
            _ => self.values().iter().any(|(k, v)| *k == key && v.is_some()),
        }
    }

    /// The description: the config file's layer (if any) with the flags' layer over it.
    pub fn spec(&self) -> Result<ExperimentSpec> {
        let file = match &self.config {
            Some(path) => {
                let text = std::fs::read_to_string(path).map_err(|e| {
                    UsageError(format!("cannot read config file {}: {e}", path.display()))
                })?;
                ExperimentSpec::from_toml(&text, &path.display().to_string())?
            }
            None => ExperimentSpec::new(),
        };
        let mut flags = ExperimentSpec::new();
        for (key, value) in self.values() {
            if let Some(v) = value {
                if let Err(stickslip::Error::InvalidParameter { allowed, .. }) = flags.set(key, v) {
                    return Err(UsageError(format!(
                        "invalid {} {}: {allowed}",
                        flag_name(key),
                        stickslip::Number(v)
                    ))
                    .into());
                }
            }
        }
        if let Some(Preset::Paper) = self.preset {
            flags.set_preset(LibraryPreset::Paper);
        }
        if let Some(model) = self.model {
            flags.set_diode(match model {
                DiodeModel::Pwl => LibraryDiode::Pwl,
                DiodeModel::Shockley => LibraryDiode::Shockley,
            });
        }
        Ok(file.overlay(&flags))
    }

    /// The experiment the flags describe.
    pub fn experiment(&self) -> Result<Experiment> {
        Ok(self.spec()?.build()?)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn si_values() {
        assert_eq!(si_value("11.5m").unwrap(), 11.5e-3);
        assert!(si_value("abc").is_err());
        assert!(finite("nan").is_err());
    }

    #[test]
    fn preset_with_dimensionless_drive() {
        let args = ModelArgs {
            preset: Some(Preset::Paper),
            w: Some(0.95),
            beta: Some(2.14),
            ..Default::default()
        };
        let e = args.experiment().unwrap();
        let p = e.params().unwrap();
        assert!((p.zeta - 71.0 / 2.0 * (0.02e-6f64 / 11.5e-3).sqrt()).abs() < 1e-15);
        assert!(e.to_string().contains("preset paper"));
    }

    #[test]
    fn zeta_conflicts_with_physical() {
        let args = ModelArgs {
            preset: Some(Preset::Paper),
            zeta: Some(0.1),
            w: Some(0.95),
            beta: Some(2.14),
            ..Default::default()
        };
        assert!(args.experiment().is_err());
    }

    /// `parse_value` reads every value as its flag does (the flags' parsers are attributes,
    /// so this test keeps the two in step).
    #[test]
    fn parse_value_reads_values_as_the_flags_do() {
        #[derive(clap::Parser)]
        struct Flags {
            #[command(flatten)]
            model: ModelArgs,
        }
        use clap::Parser;
        for key in Key::ALL {
            if matches!(key, Key::Preset | Key::Diode) {
                assert!(parse_value(key, "1").is_err());
                continue;
            }
            for text in ["1k", "0.25", "2e-3", "-1", "abc", "20nF", "inf"] {
                let flag = flag_name(key);
                let clap = Flags::try_parse_from(["stickslip", &format!("{flag}={text}")]);
                assert_eq!(
                    clap.is_ok(),
                    parse_value(key, text).is_ok(),
                    "{flag} {text}: {:?}",
                    clap.err().map(|e| e.to_string())
                );
                if let Ok(flags) = clap {
                    let mut spec_from_flags = flags.model.values().into_iter();
                    let value = spec_from_flags.find(|(k, _)| *k == key).and_then(|kv| kv.1);
                    assert_eq!(value, parse_value(key, text).ok(), "{flag} {text}");
                }
            }
        }
    }

    #[test]
    fn every_key_has_a_flag_of_its_own() {
        let mut flags: Vec<String> = Key::ALL.iter().map(|&k| flag_name(k)).collect();
        flags.sort();
        flags.dedup();
        assert_eq!(flags.len(), Key::ALL.len());
    }
}
