//! The model flags shared by every command: dimensionless (`--zeta --w --beta ...`) or a
//! physical description (`--preset paper`, `--config FILE.toml`, `--inductance ...`), in two
//! stages: the flags as typed ([`ModelArgs`]) and the validated [`Model`] they build.

use crate::output::{usage, UsageError};
use anyhow::Result;
use std::path::PathBuf;
use stickslip::{Circuit, Mechanics, Params, PwlDiode, State, System};

/// Parse a number with an optional SI prefix and unit: `0.02u`, `20nF`, `11.5mH`, `9.9kHz`,
/// `68ohm`, `1e-3`.
pub fn si_value(text: &str) -> Result<f64, String> {
    let t = text.trim();
    let units = ["Hz", "ohm", "Ohm", "Ω", "H", "F", "V", "A", "s", "N"];
    let mut body = t;
    for u in units {
        if let Some(rest) = body.strip_suffix(u) {
            body = rest;
            break;
        }
    }
    let prefixes = [
        ('f', 1e-15),
        ('p', 1e-12),
        ('n', 1e-9),
        ('u', 1e-6),
        ('µ', 1e-6),
        ('m', 1e-3),
        ('k', 1e3),
        ('M', 1e6),
        ('G', 1e9),
    ];
    let mut scale = 1.0;
    if let Some(last) = body.chars().last() {
        if let Some(&(_, s)) = prefixes.iter().find(|(c, _)| *c == last) {
            scale = s;
            body = &body[..body.len() - last.len_utf8()];
        }
    }
    match body.trim().parse::<f64>() {
        Ok(x) if x.is_finite() => Ok(x * scale),
        Ok(_) => Err(format!("'{text}' is not a finite number")),
        Err(_) => Err(format!(
            "'{text}' is not a number (plain, or with an SI prefix such as 20n, 11.5m, 9.9k)"
        )),
    }
}

/// Parse a finite plain number (dimensionless flags).
pub fn finite(text: &str) -> Result<f64, String> {
    match text.trim().parse::<f64>() {
        Ok(x) if x.is_finite() => Ok(x),
        _ => Err(format!("'{text}' is not a finite number")),
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

/// Shockley diode settings as given (validated by the library when used).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ShockleySettings {
    /// Saturation current I_s (A).
    pub saturation_current: f64,
    /// Emission coefficient n.
    pub emission: f64,
    /// Series resistance R_s (Ω).
    pub series_resistance: f64,
    /// Temperature (°C).
    pub temperature_c: f64,
}

impl Default for ShockleySettings {
    fn default() -> Self {
        Self {
            saturation_current: 4.352e-9,
            emission: 1.906,
            series_resistance: 0.6458,
            temperature_c: 27.0,
        }
    }
}

/// A validated model: dimensionless parameters, initial state, and the physical twin if one
/// was described.
#[derive(Debug, Clone)]
pub struct Model {
    /// Dimensionless parameters.
    pub params: Params,
    /// Initial state (dimensionless).
    pub initial: State,
    /// The physical description, if any.
    pub system: Option<System>,
    /// Diode law.
    pub diode: DiodeModel,
    /// Shockley diode settings (used with `--model shockley`).
    pub shockley: ShockleySettings,
    /// One line saying which description was used, for the user.
    pub summary: String,
}

/// Values read from a TOML experiment file, all optional.
#[derive(Debug, Default)]
struct FileValues {
    circuit: Option<[Option<f64>; 5]>,
    mechanics: Option<[Option<f64>; 4]>,
    amplitude: Option<f64>,
    freq: Option<f64>,
    omega: Option<f64>,
    w: Option<f64>,
    beta: Option<f64>,
    phi: Option<f64>,
    mu_s: Option<f64>,
    y0: Option<f64>,
    v0: Option<f64>,
    diode: Option<DiodeModel>,
    shockley: [Option<f64>; 4],
}

fn read_config(path: &PathBuf) -> Result<FileValues> {
    let text = std::fs::read_to_string(path)
        .map_err(|e| UsageError(format!("cannot read config file {}: {e}", path.display())))?;
    let table: toml::Table = text
        .parse()
        .map_err(|e: toml::de::Error| UsageError(format!("{}: {}", path.display(), e.message())))?;
    let mut v = FileValues::default();
    let number = |section: &str, key: &str, value: &toml::Value| -> Result<f64> {
        let x = match value {
            toml::Value::Float(x) => *x,
            toml::Value::Integer(i) => *i as f64,
            toml::Value::String(s) => si_value(s)
                .map_err(|e| UsageError(format!("{}: [{section}] {key}: {e}", path.display())))?,
            other => usage!(
                "{}: [{section}] {key} must be a number, not {}",
                path.display(),
                other.type_str()
            ),
        };
        Ok(x)
    };
    for (section, body) in &table {
        let Some(body) = body.as_table() else {
            usage!(
                "{}: '{section}' must be a [section] (circuit, mechanics, drive, model, shockley)",
                path.display()
            );
        };
        for (key, value) in body {
            let unknown = || -> anyhow::Error {
                anyhow::Error::new(UsageError(format!(
                    "{}: unknown key '{key}' in [{section}]",
                    path.display()
                )))
            };
            match section.as_str() {
                "circuit" => {
                    let slot = match key.as_str() {
                        "L" => 0,
                        "C" => 1,
                        "R" => 2,
                        "U_t" => 3,
                        "R_D" => 4,
                        _ => return Err(unknown()),
                    };
                    v.circuit.get_or_insert([None; 5])[slot] = Some(number(section, key, value)?);
                }
                "mechanics" => {
                    let slot = match key.as_str() {
                        "m" => 0,
                        "k" => 1,
                        "gamma" => 2,
                        "F0" => 3,
                        _ => return Err(unknown()),
                    };
                    v.mechanics.get_or_insert([None; 4])[slot] = Some(number(section, key, value)?);
                }
                "drive" => {
                    let x = Some(number(section, key, value)?);
                    match key.as_str() {
                        "U" | "F" => v.amplitude = x,
                        "f" => v.freq = x,
                        "omega" => v.omega = x,
                        "w" => v.w = x,
                        "beta" => v.beta = x,
                        "phi" => v.phi = x,
                        _ => return Err(unknown()),
                    }
                }
                "model" => {
                    if key == "diode" {
                        v.diode = match value.as_str() {
                            Some("pwl") => Some(DiodeModel::Pwl),
                            Some("shockley") => Some(DiodeModel::Shockley),
                            _ => usage!(
                                "{}: [model] diode must be \"pwl\" or \"shockley\"",
                                path.display()
                            ),
                        };
                        continue;
                    }
                    let x = Some(number(section, key, value)?);
                    match key.as_str() {
                        "zeta" => usage!(
                            "{}: [model] zeta: give ζ on the command line (--zeta) or describe the \
                             circuit; a config file describes physical parts",
                            path.display()
                        ),
                        "mu_s" => v.mu_s = x,
                        "y0" => v.y0 = x,
                        "v0" => v.v0 = x,
                        _ => return Err(unknown()),
                    }
                }
                "shockley" => {
                    let slot = match key.as_str() {
                        "Is" => 0,
                        "n" => 1,
                        "Rs" => 2,
                        "temperature" => 3,
                        _ => return Err(unknown()),
                    };
                    v.shockley[slot] = Some(number(section, key, value)?);
                }
                _ => usage!(
                    "{}: unknown section [{section}] (allowed: circuit, mechanics, drive, model, \
                     shockley)",
                    path.display()
                ),
            }
        }
    }
    if v.circuit.is_some() && v.mechanics.is_some() {
        usage!(
            "{}: describe either [circuit] or [mechanics], not both",
            path.display()
        );
    }
    Ok(v)
}

impl ModelArgs {
    /// Whether any physical description was given.
    fn physical(&self) -> bool {
        self.preset.is_some()
            || self.config.is_some()
            || [
                self.inductance,
                self.capacitance,
                self.resistance,
                self.turn_on,
                self.diode_resistance,
                self.mass,
                self.stiffness,
                self.damping,
                self.friction,
            ]
            .iter()
            .any(Option::is_some)
    }

    /// Validate the flags and build the model. `need_drive`: whether w and β are required.
    pub fn build(&self) -> Result<Model> {
        let file = match &self.config {
            Some(p) => read_config(p)?,
            None => FileValues::default(),
        };
        let mut system: Option<System> = None;
        let mut summary = String::new();
        if self.physical() {
            let mechanical = file.mechanics.is_some()
                || [self.mass, self.stiffness, self.damping, self.friction]
                    .iter()
                    .any(Option::is_some);
            if mechanical {
                if self.preset.is_some() || file.circuit.is_some() {
                    usage!("the mechanical flags (--mass --stiffness --damping --friction) cannot be combined with a circuit description");
                }
                let f = file.mechanics.unwrap_or([None; 4]);
                let pick = |flag: Option<f64>, slot: usize, name: &str| -> Result<f64> {
                    flag.or(f[slot]).ok_or_else(|| {
                        anyhow::Error::new(UsageError(format!(
                            "a mechanical description needs --{name}"
                        )))
                    })
                };
                let m = Mechanics::new(
                    pick(self.mass, 0, "mass")?,
                    pick(self.stiffness, 1, "stiffness")?,
                    pick(self.damping, 2, "damping")?,
                    pick(self.friction, 3, "friction")?,
                )?;
                summary = format!(
                    "mechanics: m = {} kg, k = {} N/m, γ = {} N·s/m, F0 = {} N",
                    m.mass, m.stiffness, m.damping, m.friction
                );
                system = Some(System::Mechanics(m));
            } else {
                let base = if self.preset.is_some() {
                    Some(Circuit::paper())
                } else {
                    None
                };
                let f = file.circuit.unwrap_or([None; 5]);
                let pick = |flag: Option<f64>, slot: usize, from_base: Option<f64>, name: &str| {
                    flag.or(f[slot]).or(from_base).ok_or_else(|| {
                        anyhow::Error::new(UsageError(format!(
                            "a circuit description needs --{name} (or use --preset paper)"
                        )))
                    })
                };
                let c = Circuit::new(
                    pick(self.inductance, 0, base.map(|b| b.inductance), "inductance")?,
                    pick(
                        self.capacitance,
                        1,
                        base.map(|b| b.capacitance),
                        "capacitance",
                    )?,
                    pick(self.resistance, 2, base.map(|b| b.resistance), "resistance")?,
                    PwlDiode::new(
                        pick(self.turn_on, 3, base.map(|b| b.diode.turn_on), "ut")?,
                        pick(
                            self.diode_resistance,
                            4,
                            base.map(|b| b.diode.resistance),
                            "rd",
                        )?,
                    )?,
                )?;
                let origin = match (self.preset, &self.config) {
                    (Some(_), _) => "preset paper".to_string(),
                    (None, Some(p)) => p.display().to_string(),
                    (None, None) => "flags".to_string(),
                };
                summary = format!(
                    "circuit ({origin}): L = {} H, C = {} F, R = {} Ω, U_t = {} V, R_D = {} Ω",
                    c.inductance, c.capacitance, c.resistance, c.diode.turn_on, c.diode.resistance
                );
                system = Some(System::Circuit(c));
            }
        } else {
            for (given, name) in [
                (self.amplitude, "amplitude"),
                (self.freq, "freq"),
                (self.omega, "omega"),
                (self.uc0, "uc0"),
                (self.i0, "i0"),
            ] {
                if given.is_some() {
                    usage!("--{name} is a physical value: also describe the system (--preset paper, --config FILE, or --inductance/--capacitance/...)");
                }
            }
        }

        // ζ
        let zeta = match (system, self.zeta) {
            (Some(_), Some(_)) => usage!(
                "--zeta conflicts with a physical description (ζ follows from its parts); \
                 change --resistance instead"
            ),
            (Some(s), None) => s.scales().zeta(),
            (None, Some(z)) => z,
            (None, None) => Circuit::paper().scales().zeta(),
        };

        // Drive: dimensionless flags win over physical ones, flags over the file.
        let scales = system.map(|s| s.scales());
        if self.freq.is_some() && self.omega.is_some() {
            usage!("give the drive frequency once: --freq (Hz) or --omega (rad/s)");
        }
        let w = if let Some(w) = self.w {
            Some(w)
        } else if let (Some(s), Some(omega)) = (
            scales,
            self.omega
                .or(self.freq.map(|f| f * std::f64::consts::TAU))
                .or(file.omega)
                .or(file.freq.map(|f| f * std::f64::consts::TAU)),
        ) {
            Some(omega / s.omega0)
        } else {
            file.w
        };
        let beta = if let Some(b) = self.beta {
            Some(b)
        } else if let (Some(s), Some(u)) = (scales, self.amplitude.or(file.amplitude)) {
            Some(u / s.force)
        } else {
            file.beta
        };
        let Some(w) = w else {
            usage!("missing drive frequency: give --w (Ω/ω0), or --freq/--omega with a physical description")
        };
        let Some(beta) = beta else {
            usage!("missing drive amplitude: give --beta (U/U_t), or --amplitude with a physical description")
        };
        let params = Params::new(zeta, w, beta)?
            .with_phi(self.phi.or(file.phi).unwrap_or(0.0))?
            .with_mu_s(self.mu_s.or(file.mu_s).unwrap_or(1.0))?;

        let mut y0 = self.y0.or(file.y0).unwrap_or(0.0);
        let mut v0 = self.v0.or(file.v0).unwrap_or(0.0);
        if let Some(s) = scales {
            if let Some(u) = self.uc0 {
                if self.y0.is_some() {
                    usage!("give the initial position once: --y0 or --uc0");
                }
                y0 = u / s.position;
            }
            if let Some(i) = self.i0 {
                if self.v0.is_some() {
                    usage!("give the initial velocity once: --v0 or --i0");
                }
                v0 = i / s.velocity;
            }
        }
        let initial = State::new(y0, v0)?;

        let d = ShockleySettings::default();
        let shockley = ShockleySettings {
            saturation_current: self
                .diode_is
                .or(file.shockley[0])
                .unwrap_or(d.saturation_current),
            emission: self.diode_n.or(file.shockley[1]).unwrap_or(d.emission),
            series_resistance: self
                .diode_rs
                .or(file.shockley[2])
                .unwrap_or(d.series_resistance),
            temperature_c: self
                .temperature
                .or(file.shockley[3])
                .unwrap_or(d.temperature_c),
        };
        let diode = self.model.or(file.diode).unwrap_or_default();
        if diode == DiodeModel::Shockley && !matches!(system, Some(System::Circuit(_))) {
            usage!("--model shockley needs a circuit description (e.g. --preset paper)");
        }

        let dimensionless = format!(
            "ζ = {:.6}, w = {:.6}, β = {:.6}, φ = {}, μs = {}, y0 = {}, v0 = {}",
            params.zeta, params.w, params.beta, params.phi, params.mu_s, y0, v0
        );
        let summary = if let (Some(s), false) = (scales, summary.is_empty()) {
            format!(
                "{summary}; ω0 = {:.1} rad/s (f0 = {:.2} Hz); drive {:.6} {} at {:.3} Hz; \
                 dimensionless: {dimensionless}",
                s.omega0,
                s.f0(),
                s.drive_amplitude(beta),
                if matches!(system, Some(System::Mechanics(_))) {
                    "N"
                } else {
                    "V"
                },
                s.drive_omega(w) / std::f64::consts::TAU
            )
        } else {
            format!("dimensionless: {dimensionless}")
        };
        let summary = match (diode, system) {
            (DiodeModel::Shockley, Some(System::Circuit(c))) => format!(
                "{summary}; Shockley diodes I_s = {} A, n = {}, R_s = {} Ω at {} °C (R_D unused; ζ_R = R√(C/L)/2 = {:.6})",
                shockley.saturation_current,
                shockley.emission,
                shockley.series_resistance,
                shockley.temperature_c,
                0.5 * c.resistance / c.impedance()
            ),
            _ => summary,
        };
        Ok(Model {
            params,
            initial,
            system,
            diode,
            shockley,
            summary,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn si_values() {
        assert_eq!(si_value("11.5m").unwrap(), 11.5e-3);
        assert!((si_value("0.02uF").unwrap() - 0.02e-6).abs() < 1e-22);
        assert_eq!(si_value("68ohm").unwrap(), 68.0);
        assert_eq!(si_value("9.9kHz").unwrap(), 9900.0);
        assert_eq!(si_value("-1e-3").unwrap(), -1e-3);
        assert!(si_value("abc").is_err());
        assert!(si_value("nan").is_err());
    }

    #[test]
    fn preset_with_dimensionless_drive() {
        let args = ModelArgs {
            preset: Some(Preset::Paper),
            w: Some(0.95),
            beta: Some(2.14),
            ..Default::default()
        };
        let m = args.build().unwrap();
        assert!((m.params.zeta - 71.0 / 2.0 * (0.02e-6f64 / 11.5e-3).sqrt()).abs() < 1e-15);
        assert!(m.summary.contains("preset paper"));
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
        assert!(args.build().is_err());
    }
}
