//! An experiment in one line: its description in SI units with prefixes, its natural
//! frequency and drive, and the dimensionless numbers.

use super::{Experiment, Origin};
use crate::physical::{Diode, System};
use std::f64::consts::TAU;

/// `value` with an SI prefix and `unit`, to 6 significant digits (`11.5 mH`, `20 nF`,
/// `0.7 V`).
fn si(value: f64, unit: &str) -> String {
    const PREFIXES: [(f64, &str); 9] = [
        (1e9, "G"),
        (1e6, "M"),
        (1e3, "k"),
        (1.0, ""),
        (1e-3, "m"),
        (1e-6, "µ"),
        (1e-9, "n"),
        (1e-12, "p"),
        (1e-15, "f"),
    ];
    let magnitude = value.abs();
    // No prefix from 0.1 to 1000: 0.7 V, not 700 mV.
    let (scale, prefix) = if (0.1..1e3).contains(&magnitude) {
        (1.0, "")
    } else {
        PREFIXES
            .iter()
            .copied()
            .find(|&(scale, _)| magnitude >= scale)
            .filter(|_| magnitude > 0.0 && magnitude < 1e12)
            .unwrap_or((1.0, ""))
    };
    let scaled = value / scale;
    // Six significant digits, without trailing zeros.
    let digits = (5 - scaled.abs().log10().floor().max(0.0) as i32).max(0) as usize;
    let text = format!("{scaled:.digits$}");
    let text = if text.contains('.') {
        text.trim_end_matches('0').trim_end_matches('.').to_string()
    } else {
        text
    };
    format!("{text} {prefix}{unit}")
}

impl std::fmt::Display for Experiment {
    /// One line: which description this is, its natural frequency and drive in physical
    /// units, and the dimensionless numbers.
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let origin = match &self.origin {
            Origin::Preset(p) => format!("preset {}", p.label()),
            Origin::File(name) => name.clone(),
            Origin::Parts | Origin::Parameters => "flags".into(),
        };
        match &self.system {
            Some(System::Circuit(c)) => {
                write!(
                    f,
                    "circuit ({origin}): L = {}, C = {}, R = {}, ",
                    si(c.inductance, "H"),
                    si(c.capacitance, "F"),
                    si(c.resistance, "Ω")
                )?;
                match c.diode {
                    Diode::Pwl(d) => write!(
                        f,
                        "U_t = {}, R_D = {}; ",
                        si(d.turn_on, "V"),
                        si(d.resistance, "Ω")
                    )?,
                    Diode::Shockley(d) => write!(
                        f,
                        "Shockley diodes I_s = {}, n = {}, R_s = {} at {} °C, U_t = {} \
                         (reference); ",
                        si(d.pair.saturation_current, "A"),
                        d.pair.emission,
                        si(d.pair.series_resistance, "Ω"),
                        d.pair.temperature,
                        si(d.reference_voltage, "V")
                    )?,
                }
            }
            Some(System::Mechanics(m)) => write!(
                f,
                "mechanics ({origin}): m = {}, k = {}, γ = {}, F0 = {}; ",
                si(m.mass, "kg"),
                si(m.stiffness, "N/m"),
                si(m.damping, "N·s/m"),
                si(m.friction, "N")
            )?,
            None => {}
        }
        if let Some(s) = self.scales() {
            write!(f, "ω0 = {:.1} rad/s (f0 = {:.2} Hz); ", s.omega0, s.f0())?;
            if let (Some(w), Some(beta)) = (self.w, self.beta) {
                let unit = if matches!(self.system, Some(System::Mechanics(_))) {
                    "N"
                } else {
                    "V"
                };
                write!(
                    f,
                    "drive {:.6} {unit} at {:.3} Hz; ",
                    s.drive_amplitude(beta),
                    s.drive_omega(w) / TAU
                )?;
            }
        }
        let value =
            |x: Option<f64>| x.map_or_else(|| "(not set)".to_string(), |x| format!("{x:.6}"));
        write!(
            f,
            "dimensionless: ζ = {:.6}, w = {}, β = {}, φ = {}, μs = {}, y0 = {}, v0 = {}",
            self.zeta,
            value(self.w),
            value(self.beta),
            self.phi,
            self.mu_s,
            self.initial.y,
            self.initial.v
        )?;
        if self.vb != 0.0 {
            write!(f, ", vb = {}", self.vb)?;
        }
        if !self.law.is_coulomb() {
            write!(f, "; friction law {}", self.law.kind().label())?;
            for (name, value) in self.law.parameters() {
                write!(f, ", {name} = {value}")?;
            }
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn descriptions_use_si_prefixes() {
        assert_eq!(si(11.5e-3, "H"), "11.5 mH");
        assert_eq!(si(0.02e-6, "F"), "20 nF");
        assert_eq!(si(68.0, "Ω"), "68 Ω");
        assert_eq!(si(4.352e-9, "A"), "4.352 nA");
        assert_eq!(si(0.0, "Ω"), "0 Ω");
        assert_eq!(si(65938.0, "Hz"), "65.938 kHz");
        let text = Experiment::paper().to_string();
        assert!(text.starts_with("circuit (preset paper): L = 11.5 mH, C = 20 nF, R = 68 Ω, U_t = 0.7 V, R_D = 3 Ω; ω0 = 65938.0 rad/s"), "{text}");
    }
}
