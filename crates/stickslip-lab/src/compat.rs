//! Stand-ins for the library's key table until it lands (`Key::flag`, `Key::parse`,
//! `Parameter::keys`): the same names and parsers as the command-line flags.

use stickslip::experiment::Key;
use stickslip::Parameter;

/// The key table's methods the lab uses.
pub trait KeyExt {
    /// The spelling on the command line and in the lab's query, without dashes.
    fn flag(self) -> &'static str;
    /// Read a value as its flag does (plain number, or SI prefix and unit).
    fn parse_text(self, text: &str) -> Result<f64, String>;
}

impl KeyExt for Key {
    fn flag(self) -> &'static str {
        match self {
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
            _ => self.name(),
        }
    }

    fn parse_text(self, text: &str) -> Result<f64, String> {
        match self {
            Key::Zeta
            | Key::W
            | Key::Beta
            | Key::Phi
            | Key::MuS
            | Key::Y0
            | Key::V0
            | Key::Emission
            | Key::Temperature => stickslip::units::parse_plain(text).map_err(|e| e.to_string()),
            Key::Preset | Key::Diode => Err(format!("--{} is not a number", self.flag())),
            _ => stickslip::units::parse_si(text).map_err(|e| e.to_string()),
        }
    }
}

/// The keys that give a value of a parameter.
pub fn keys_of(parameter: Parameter) -> &'static [Key] {
    match parameter {
        Parameter::W => &[Key::W, Key::Frequency, Key::Omega],
        Parameter::Beta => &[Key::Beta, Key::Amplitude],
        Parameter::Zeta => &[Key::Zeta],
        Parameter::MuS => &[Key::MuS],
    }
}
