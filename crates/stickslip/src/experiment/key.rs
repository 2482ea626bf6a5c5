//! The named values of an experiment description: one table, one row per key, from which
//! every front end takes its spellings, units, ranges, help and messages.
//!
//! A row holds the key's canonical name (the TOML key and the Python keyword, [`Key::name`]),
//! its spelling on the command line and in the lab's query ([`Key::flag`]), its other
//! spellings ([`Key::aliases`], [`Key::name_aliases`]), its unit and how its value is written
//! (a plain number, or a number with an SI prefix and the key's unit), its range and the
//! words for it, its group, its one-line help, its default, its TOML section and, for a
//! physical value, the dimensionless value it gives and the scale that converts it. Adding a
//! key is one row here plus its physics (where [`ExperimentSpec::build`] uses it).
//!
//! [`ExperimentSpec::build`]: super::ExperimentSpec::build

pub use super::keys::Key;
use super::{DiodeModel, Preset};
use crate::error::{check, Error, Result};
use crate::friction::{
    FrictionLawKind, DELTA_ALLOWED, DELTA_MAX, ETA_ALLOWED, K1_ALLOWED, K3_ALLOWED, LAW_MAX,
    VB_ALLOWED, VB_MAX, VS_ALLOWED,
};
use crate::limits;
use crate::physical::{Circuit, Scales, SystemKind};
use crate::shockley::diode::ZERO_CELSIUS;
use crate::shockley::DiodePair;
use crate::units::{parse_plain, parse_si, NumberError, UNITS};
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

/// Which part of an experiment a key describes (the lab groups its form by it).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum KeyGroup {
    /// The oscillator or circuit: ζ, μs, the circuit's or the mechanical oscillator's parts,
    /// the preset.
    System,
    /// The drive: its frequency, amplitude and phase.
    Drive,
    /// The diode law and the Shockley diodes' parameters.
    Diode,
    /// The belt under a mechanical oscillator and the friction law: vb, the law and its
    /// parameters.
    Friction,
    /// The initial state.
    Initial,
    /// Options of a computation (no key of an experiment belongs here; options have their
    /// own table).
    Options,
}

impl KeyGroup {
    /// Every group, in the order of forms and tables.
    pub const ALL: [KeyGroup; 6] = [
        KeyGroup::System,
        KeyGroup::Drive,
        KeyGroup::Diode,
        KeyGroup::Friction,
        KeyGroup::Initial,
        KeyGroup::Options,
    ];

    /// `system`, `drive`, `diode`, `friction`, `initial` or `options`.
    pub fn label(self) -> &'static str {
        match self {
            KeyGroup::System => "system",
            KeyGroup::Drive => "drive",
            KeyGroup::Diode => "diode",
            KeyGroup::Friction => "friction",
            KeyGroup::Initial => "initial",
            KeyGroup::Options => "options",
        }
    }
}

impl std::fmt::Display for KeyGroup {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.label())
    }
}

/// How a key's value is written.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum KeyForm {
    /// A plain finite number (`0.95`, `-1e-3`): the dimensionless values, the emission
    /// coefficient and the temperature.
    Plain,
    /// A finite number with an optional SI prefix and the key's unit (`11.5m`, `20nF`,
    /// `9.97kHz`): the physical values.
    Si,
    /// One of a few names ([`KeyInfo::choices`]): the diode law, the preset.
    Choice,
}

/// The TOML section a key is written in.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Section {
    /// `[circuit]`: L, C, R, U_t, R_D.
    Circuit,
    /// `[mechanics]`: m, k, gamma, F0.
    Mechanics,
    /// `[drive]`: U (or F), f, omega, w, beta, phi.
    Drive,
    /// `[model]`: zeta, mu_s, y0, v0, uc0, i0, diode.
    Model,
    /// `[shockley]`: Is, n, Rs, temperature.
    Shockley,
}

impl Section {
    /// Every section, in the order of the file.
    pub const ALL: [Section; 5] = [
        Section::Circuit,
        Section::Mechanics,
        Section::Drive,
        Section::Model,
        Section::Shockley,
    ];

    /// The section's name in the file (`circuit`, ...).
    pub const fn name(self) -> &'static str {
        match self {
            Section::Circuit => "circuit",
            Section::Mechanics => "mechanics",
            Section::Drive => "drive",
            Section::Model => "model",
            Section::Shockley => "shockley",
        }
    }

    /// The keys of the section, in the table's order, each under every name the file may
    /// give it ([`Key::name`] and [`Key::name_aliases`]).
    pub fn entries(self) -> impl Iterator<Item = (Key, &'static str)> {
        Key::ALL
            .into_iter()
            .filter(move |k| k.section() == Some(self))
            .flat_map(|k| std::iter::once(k.name()).chain(k.name_aliases().iter().copied()))
            .map(|name| (Key::from_name(name).expect("a key's own name"), name))
    }
}

/// The range of a number: finite, and above `min` (or at it, when `min_inclusive`) and below
/// `max` (or at it, when `max_inclusive`). An infinite bound is no bound.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct KeyRange {
    /// Lower bound (−∞: none).
    pub min: f64,
    /// Whether `min` itself is allowed.
    pub min_inclusive: bool,
    /// Upper bound (+∞: none).
    pub max: f64,
    /// Whether `max` itself is allowed.
    pub max_inclusive: bool,
}

impl KeyRange {
    /// From `min` to `max`, both allowed.
    pub const fn closed(min: f64, max: f64) -> Self {
        Self {
            min,
            min_inclusive: true,
            max,
            max_inclusive: true,
        }
    }

    /// Above `min` (not at it), any size.
    pub const fn positive_from(min: f64) -> Self {
        Self {
            min,
            min_inclusive: false,
            max: f64::INFINITY,
            max_inclusive: true,
        }
    }

    /// Every finite number.
    pub const ANY: KeyRange = KeyRange::closed(f64::NEG_INFINITY, f64::INFINITY);

    /// No number (the keys whose values are names).
    pub const NONE: KeyRange = KeyRange {
        min: f64::INFINITY,
        min_inclusive: false,
        max: f64::NEG_INFINITY,
        max_inclusive: false,
    };

    /// Whether `x` is finite and in the range.
    pub fn contains(&self, x: f64) -> bool {
        let above = if self.min_inclusive {
            x >= self.min
        } else {
            x > self.min
        };
        let below = if self.max_inclusive {
            x <= self.max
        } else {
            x < self.max
        };
        x.is_finite() && above && below
    }
}

/// A key's default value, where it has one.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
#[serde(untagged)]
pub enum KeyDefault {
    /// A number, in the key's unit.
    Number(f64),
    /// A name (the diode law's `pwl`).
    Name(&'static str),
}

impl std::fmt::Display for KeyDefault {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match *self {
            KeyDefault::Number(x) => write!(f, "{}", crate::Number(x)),
            KeyDefault::Name(name) => f.write_str(name),
        }
    }
}

/// A physical value's dimensionless image: the value divided by a scale of the system.
#[derive(Clone, Copy)]
struct Image {
    /// The dimensionless key it gives.
    of: Key,
    /// The scale (physical units per unit of the dimensionless value).
    scale: fn(&Scales) -> f64,
}

/// Which physical description a key belongs to.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Part {
    /// None: dimensionless, a value that needs any physical description, a part of the
    /// Shockley diodes (which need a circuit) or the preset.
    Any,
    /// A part of a circuit.
    Circuit,
    /// A part of a mechanical oscillator.
    Mechanics,
}

/// One row of the table.
struct Row {
    key: Key,
    name: &'static str,
    symbol: &'static str,
    name_aliases: &'static [&'static str],
    flag: &'static str,
    aliases: &'static [&'static str],
    metavar: &'static str,
    group: KeyGroup,
    section: Option<Section>,
    part: Part,
    form: KeyForm,
    unit: Option<&'static str>,
    units: &'static [&'static str],
    range: KeyRange,
    allowed: &'static str,
    description: &'static str,
    help: &'static str,
    default: Option<fn() -> KeyDefault>,
    /// For a dimensionless key given also by physical values: the quantity's name.
    quantity: Option<&'static str>,
    image: Option<Image>,
    /// For a value a fit may free: where and how.
    fit: Option<FitRole>,
}

/// What makes a key a fit parameter (`stickslip::fit::FitParameter`): a value of the system
/// that a fit may free, the systems and the diode law it belongs to, whether a fit frees it
/// when told nothing, and its place in the fit's lists. A new fit parameter is this, in its
/// key's row (and its physics: how the fit reads and sets it).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct FitRole {
    /// The systems whose value it is (μs: a circuit's and a mechanical oscillator's).
    pub systems: &'static [SystemKind],
    /// The diode law it belongs to (`None`: either). A mechanical oscillator's Coulomb law
    /// is the PWL law.
    pub law: Option<DiodeModel>,
    /// Whether a fit of its systems and law frees it when told nothing (the default free
    /// set, `FitParameter::defaults`).
    pub default: bool,
    /// Its place in the fit's lists (messages, the lab's boxes): from 0, each once, the
    /// values most often freed first.
    pub order: u8,
}

impl FitRole {
    /// Whether the value belongs to `system` with the diode law `law`.
    pub fn applies(&self, system: SystemKind, law: DiodeModel) -> bool {
        self.systems.contains(&system) && self.law.is_none_or(|l| l == law)
    }
}

const OHMS: &[&str] = &["ohm", "Ohm", "Ω"];

/// The table: one row per key, in the order of [`Key::ALL`].
const ROWS: &[Row] = &[
    Row {
        key: Key::Zeta,
        name: "zeta",
        symbol: "ζ",
        name_aliases: &[],
        flag: "zeta",
        aliases: &[],
        metavar: "ZETA",
        group: KeyGroup::System,
        section: Some(Section::Model),
        part: Part::Any,
        form: KeyForm::Plain,
        unit: None,
        units: &[],
        range: KeyRange::closed(0.0, limits::ZETA_MAX),
        allowed: limits::ZETA_ALLOWED,
        description: "damping ratio ζ",
        help: "Damping ratio ζ = α/(2ω0) ≥ 0 [default: the paper's circuit, 0.0468]",
        default: Some(|| KeyDefault::Number(Circuit::paper().scales().zeta())),
        quantity: None,
        image: None,
        fit: None,
    },
    Row {
        key: Key::W,
        name: "w",
        symbol: "w",
        name_aliases: &[],
        flag: "w",
        aliases: &[],
        metavar: "W",
        group: KeyGroup::Drive,
        section: Some(Section::Drive),
        part: Part::Any,
        form: KeyForm::Plain,
        unit: None,
        units: &[],
        range: KeyRange::closed(limits::W_MIN, limits::W_MAX),
        allowed: limits::W_ALLOWED,
        description: "drive frequency w = Ω/ω0",
        help: "Drive frequency w = Ω/ω0 > 0",
        default: None,
        quantity: Some("drive frequency"),
        image: None,
        fit: None,
    },
    Row {
        key: Key::Beta,
        name: "beta",
        symbol: "β",
        name_aliases: &[],
        flag: "beta",
        aliases: &[],
        metavar: "BETA",
        group: KeyGroup::Drive,
        section: Some(Section::Drive),
        part: Part::Any,
        form: KeyForm::Plain,
        unit: None,
        units: &[],
        range: KeyRange::closed(0.0, limits::BETA_MAX),
        allowed: limits::BETA_ALLOWED,
        description: "drive amplitude β = U/U_t or F/F0",
        help: "Drive amplitude β = U/U_t (circuit) or F/F0 (mechanics), ≥ 0",
        default: None,
        quantity: Some("drive amplitude"),
        image: None,
        fit: None,
    },
    Row {
        key: Key::Phi,
        name: "phi",
        symbol: "φ",
        name_aliases: &[],
        flag: "phi",
        aliases: &[],
        metavar: "PHI",
        group: KeyGroup::Drive,
        section: Some(Section::Drive),
        part: Part::Any,
        form: KeyForm::Plain,
        unit: Some("rad"),
        units: &[],
        range: KeyRange::closed(-limits::PHI_MAX, limits::PHI_MAX),
        allowed: limits::PHI_ALLOWED,
        description: "drive phase φ (rad)",
        help: "Drive phase φ in radians at τ = 0 [default: 0]",
        default: Some(|| KeyDefault::Number(0.0)),
        quantity: None,
        image: None,
        fit: None,
    },
    Row {
        key: Key::MuS,
        name: "mu_s",
        symbol: "μ_s",
        name_aliases: &[],
        flag: "mu-s",
        aliases: &[],
        metavar: "MU_S",
        group: KeyGroup::System,
        section: Some(Section::Model),
        part: Part::Any,
        form: KeyForm::Plain,
        unit: None,
        units: &[],
        range: KeyRange::closed(1.0, limits::MU_S_MAX),
        allowed: limits::MU_S_ALLOWED,
        description: "static-to-kinetic friction ratio μs",
        help: "Static-to-kinetic friction ratio μs ≥ 1 [default: 1, as in the paper]",
        default: Some(|| KeyDefault::Number(1.0)),
        quantity: None,
        image: None,
        fit: Some(FitRole {
            systems: &[SystemKind::Circuit, SystemKind::Mechanics],
            law: Some(DiodeModel::Pwl),
            default: false,
            order: 12,
        }),
    },
    Row {
        key: Key::Y0,
        name: "y0",
        symbol: "y_0",
        name_aliases: &[],
        flag: "y0",
        aliases: &[],
        metavar: "Y0",
        group: KeyGroup::Initial,
        section: Some(Section::Model),
        part: Part::Any,
        form: KeyForm::Plain,
        unit: None,
        units: &[],
        range: KeyRange::closed(-limits::STATE_MAX, limits::STATE_MAX),
        allowed: limits::STATE_ALLOWED,
        description: "initial position y0",
        help: "Initial position y0 = u_C/U_t [default: 0]",
        default: Some(|| KeyDefault::Number(0.0)),
        quantity: Some("initial position"),
        image: None,
        fit: None,
    },
    Row {
        key: Key::V0,
        name: "v0",
        symbol: "v_0",
        name_aliases: &[],
        flag: "v0",
        aliases: &[],
        metavar: "V0",
        group: KeyGroup::Initial,
        section: Some(Section::Model),
        part: Part::Any,
        form: KeyForm::Plain,
        unit: None,
        units: &[],
        range: KeyRange::closed(-limits::STATE_MAX, limits::STATE_MAX),
        allowed: limits::STATE_ALLOWED,
        description: "initial velocity v0",
        help: "Initial velocity v0 = y'(0) [default: 0]",
        default: Some(|| KeyDefault::Number(0.0)),
        quantity: Some("initial velocity"),
        image: None,
        fit: None,
    },
    Row {
        key: Key::Inductance,
        name: "L",
        symbol: "L",
        name_aliases: &[],
        flag: "inductance",
        aliases: &["L"],
        metavar: "INDUCTANCE",
        group: KeyGroup::System,
        section: Some(Section::Circuit),
        part: Part::Circuit,
        form: KeyForm::Si,
        unit: Some("H"),
        units: &["H"],
        range: KeyRange::positive_from(0.0),
        allowed: "must be finite and > 0 (henry)",
        description: "inductance L (H)",
        help: "Inductance L in henry (SI prefixes allowed: 11.5m)",
        default: None,
        quantity: None,
        image: None,
        fit: Some(FitRole {
            systems: &[SystemKind::Circuit],
            law: None,
            default: false,
            order: 6,
        }),
    },
    Row {
        key: Key::Capacitance,
        name: "C",
        symbol: "C",
        name_aliases: &[],
        flag: "capacitance",
        aliases: &["C"],
        metavar: "CAPACITANCE",
        group: KeyGroup::System,
        section: Some(Section::Circuit),
        part: Part::Circuit,
        form: KeyForm::Si,
        unit: Some("F"),
        units: &["F"],
        range: KeyRange::positive_from(0.0),
        allowed: "must be finite and > 0 (farad)",
        description: "capacitance C (F)",
        help: "Capacitance C in farad (0.02u)",
        default: None,
        quantity: None,
        image: None,
        fit: Some(FitRole {
            systems: &[SystemKind::Circuit],
            law: None,
            default: false,
            order: 7,
        }),
    },
    Row {
        key: Key::Resistance,
        name: "R",
        symbol: "R",
        name_aliases: &[],
        flag: "resistance",
        aliases: &["R"],
        metavar: "RESISTANCE",
        group: KeyGroup::System,
        section: Some(Section::Circuit),
        part: Part::Circuit,
        form: KeyForm::Si,
        unit: Some("ohm"),
        units: OHMS,
        range: KeyRange::closed(0.0, RESISTANCE_MAX),
        allowed: "must be finite and from 0 to 1e9 (ohms)",
        description: "series resistance R without the diodes (Ω)",
        help: "Series resistance R in ohms, without the diodes",
        default: None,
        quantity: None,
        image: None,
        fit: Some(FitRole {
            systems: &[SystemKind::Circuit],
            law: None,
            default: true,
            order: 0,
        }),
    },
    Row {
        key: Key::TurnOn,
        name: "U_t",
        symbol: "U_t",
        name_aliases: &[],
        flag: "ut",
        aliases: &[],
        metavar: "TURN_ON",
        group: KeyGroup::System,
        section: Some(Section::Circuit),
        part: Part::Circuit,
        form: KeyForm::Si,
        unit: Some("V"),
        units: &["V"],
        range: KeyRange::positive_from(0.0),
        allowed: "must be finite and > 0 (volts)",
        description: "diode turn-on voltage U_t (V)",
        help: "Diode turn-on voltage U_t in volts (PWL model)",
        default: None,
        quantity: None,
        image: None,
        fit: Some(FitRole {
            systems: &[SystemKind::Circuit],
            law: Some(DiodeModel::Pwl),
            default: true,
            order: 1,
        }),
    },
    Row {
        key: Key::DiodeResistance,
        name: "R_D",
        symbol: "R_D",
        name_aliases: &[],
        flag: "rd",
        aliases: &[],
        metavar: "DIODE_RESISTANCE",
        group: KeyGroup::System,
        section: Some(Section::Circuit),
        part: Part::Circuit,
        form: KeyForm::Si,
        unit: Some("ohm"),
        units: OHMS,
        range: KeyRange::closed(0.0, RESISTANCE_MAX),
        allowed: "must be finite and from 0 to 1e9 (ohms)",
        description: "PWL diode resistance R_D (Ω)",
        help: "Diode forward resistance R_D in ohms (PWL model)",
        default: None,
        quantity: None,
        image: None,
        fit: Some(FitRole {
            systems: &[SystemKind::Circuit],
            law: Some(DiodeModel::Pwl),
            default: false,
            order: 2,
        }),
    },
    Row {
        key: Key::Mass,
        name: "m",
        symbol: "m",
        name_aliases: &[],
        flag: "mass",
        aliases: &[],
        metavar: "MASS",
        group: KeyGroup::System,
        section: Some(Section::Mechanics),
        part: Part::Mechanics,
        form: KeyForm::Si,
        unit: Some("kg"),
        units: &[],
        range: KeyRange::positive_from(0.0),
        allowed: "must be finite and > 0 (kg)",
        description: "mass m (kg)",
        help: "Mass m in kg (mechanical twin)",
        default: None,
        quantity: None,
        image: None,
        fit: Some(FitRole {
            systems: &[SystemKind::Mechanics],
            law: Some(DiodeModel::Pwl),
            default: false,
            order: 10,
        }),
    },
    Row {
        key: Key::Stiffness,
        name: "k",
        symbol: "k",
        name_aliases: &[],
        flag: "stiffness",
        aliases: &[],
        metavar: "STIFFNESS",
        group: KeyGroup::System,
        section: Some(Section::Mechanics),
        part: Part::Mechanics,
        form: KeyForm::Si,
        unit: Some("N/m"),
        units: &[],
        range: KeyRange::positive_from(0.0),
        allowed: "must be finite and > 0 (N/m)",
        description: "spring constant k (N/m)",
        help: "Spring constant k in N/m (mechanical twin)",
        default: None,
        quantity: None,
        image: None,
        fit: Some(FitRole {
            systems: &[SystemKind::Mechanics],
            law: Some(DiodeModel::Pwl),
            default: false,
            order: 11,
        }),
    },
    Row {
        key: Key::Damping,
        name: "gamma",
        symbol: "γ",
        name_aliases: &[],
        flag: "damping",
        aliases: &[],
        metavar: "DAMPING",
        group: KeyGroup::System,
        section: Some(Section::Mechanics),
        part: Part::Mechanics,
        form: KeyForm::Si,
        unit: Some("N s/m"),
        units: &[],
        range: KeyRange::closed(0.0, f64::INFINITY),
        allowed: "must be finite and >= 0 (N s/m)",
        description: "viscous damping γ (N·s/m)",
        help: "Viscous damping γ in N·s/m (mechanical twin)",
        default: None,
        quantity: None,
        image: None,
        fit: Some(FitRole {
            systems: &[SystemKind::Mechanics],
            law: Some(DiodeModel::Pwl),
            default: true,
            order: 8,
        }),
    },
    Row {
        key: Key::Friction,
        name: "F0",
        symbol: "F_0",
        name_aliases: &[],
        flag: "friction",
        aliases: &[],
        metavar: "FRICTION",
        group: KeyGroup::System,
        section: Some(Section::Mechanics),
        part: Part::Mechanics,
        form: KeyForm::Si,
        unit: Some("N"),
        units: &["N"],
        range: KeyRange::positive_from(0.0),
        allowed: "must be finite and > 0 (N)",
        description: "kinetic friction force F0 (N)",
        help: "Kinetic friction force F0 in N (mechanical twin)",
        default: None,
        quantity: None,
        image: None,
        fit: Some(FitRole {
            systems: &[SystemKind::Mechanics],
            law: Some(DiodeModel::Pwl),
            default: true,
            order: 9,
        }),
    },
    Row {
        key: Key::Amplitude,
        name: "U",
        symbol: "U",
        name_aliases: &["F"],
        flag: "amplitude",
        aliases: &["U"],
        metavar: "AMPLITUDE",
        group: KeyGroup::Drive,
        section: Some(Section::Drive),
        part: Part::Any,
        form: KeyForm::Si,
        unit: Some("V or N"),
        units: &["V", "N"],
        range: KeyRange::closed(0.0, f64::INFINITY),
        allowed: "must be finite and >= 0 (V or N)",
        description: "drive amplitude U (V) or F (N)",
        help: "Drive amplitude: U in volts (circuit) or F in newtons (mechanics)",
        default: None,
        quantity: None,
        image: Some(Image {
            of: Key::Beta,
            scale: |s| s.force,
        }),
        fit: None,
    },
    Row {
        key: Key::Frequency,
        name: "f",
        symbol: "f",
        name_aliases: &[],
        flag: "freq",
        aliases: &[],
        metavar: "FREQ",
        group: KeyGroup::Drive,
        section: Some(Section::Drive),
        part: Part::Any,
        form: KeyForm::Si,
        unit: Some("Hz"),
        units: &["Hz"],
        range: KeyRange::positive_from(0.0),
        allowed: "must be finite and > 0 (Hz)",
        description: "drive frequency f (Hz)",
        help: "Drive frequency f in Hz",
        default: None,
        quantity: None,
        image: Some(Image {
            of: Key::W,
            scale: Scales::f0,
        }),
        fit: None,
    },
    Row {
        key: Key::Omega,
        name: "omega",
        symbol: "Ω",
        name_aliases: &[],
        flag: "omega",
        aliases: &[],
        metavar: "OMEGA",
        group: KeyGroup::Drive,
        section: Some(Section::Drive),
        part: Part::Any,
        form: KeyForm::Si,
        unit: Some("rad/s"),
        units: &[],
        range: KeyRange::positive_from(0.0),
        allowed: "must be finite and > 0 (rad/s)",
        description: "drive angular frequency Ω (rad/s)",
        help: "Drive angular frequency Ω in rad/s",
        default: None,
        quantity: None,
        image: Some(Image {
            of: Key::W,
            scale: |s| s.omega0,
        }),
        fit: None,
    },
    Row {
        key: Key::Uc0,
        name: "uc0",
        symbol: "u_C(0)",
        name_aliases: &[],
        flag: "uc0",
        aliases: &[],
        metavar: "UC0",
        group: KeyGroup::Initial,
        section: Some(Section::Model),
        part: Part::Any,
        form: KeyForm::Si,
        unit: Some("V or m"),
        units: &["V"],
        range: KeyRange::ANY,
        allowed: "must be finite",
        description: "initial capacitor voltage u_C(0) (V) or position r(0) (m)",
        help: "Initial capacitor voltage u_C(0) in volts (circuit; instead of --y0)",
        default: None,
        quantity: None,
        image: Some(Image {
            of: Key::Y0,
            scale: |s| s.position,
        }),
        fit: None,
    },
    Row {
        key: Key::I0,
        name: "i0",
        symbol: "i(0)",
        name_aliases: &[],
        flag: "i0",
        aliases: &[],
        metavar: "I0",
        group: KeyGroup::Initial,
        section: Some(Section::Model),
        part: Part::Any,
        form: KeyForm::Si,
        unit: Some("A or m/s"),
        units: &["A"],
        range: KeyRange::ANY,
        allowed: "must be finite",
        description: "initial current i(0) (A) or velocity ṙ(0) (m/s)",
        help: "Initial current i(0) in amperes (circuit; instead of --v0)",
        default: None,
        quantity: None,
        image: Some(Image {
            of: Key::V0,
            scale: |s| s.velocity,
        }),
        fit: None,
    },
    Row {
        key: Key::SaturationCurrent,
        name: "Is",
        symbol: "I_s",
        name_aliases: &[],
        flag: "diode-is",
        aliases: &[],
        metavar: "DIODE_IS",
        group: KeyGroup::Diode,
        section: Some(Section::Shockley),
        part: Part::Any,
        form: KeyForm::Si,
        unit: Some("A"),
        units: &["A"],
        range: KeyRange::closed(SATURATION_MIN, SATURATION_MAX),
        allowed: "must be finite and from 1e-30 to 1 (amperes)",
        description: "Shockley saturation current I_s (A)",
        help: "Shockley saturation current I_s in amperes [default: 4.352n, 1N4148]",
        default: Some(|| KeyDefault::Number(DiodePair::one_n4148().saturation_current)),
        quantity: None,
        image: None,
        fit: Some(FitRole {
            systems: &[SystemKind::Circuit],
            law: Some(DiodeModel::Shockley),
            default: true,
            order: 3,
        }),
    },
    Row {
        key: Key::Emission,
        name: "n",
        symbol: "n",
        name_aliases: &[],
        flag: "diode-n",
        aliases: &[],
        metavar: "DIODE_N",
        group: KeyGroup::Diode,
        section: Some(Section::Shockley),
        part: Part::Any,
        form: KeyForm::Plain,
        unit: None,
        units: &[],
        range: KeyRange::closed(EMISSION_MIN, EMISSION_MAX),
        allowed: "must be finite and from 0.1 to 100",
        description: "Shockley emission coefficient n",
        help: "Shockley emission coefficient n [default: 1.906, 1N4148]",
        default: Some(|| KeyDefault::Number(DiodePair::one_n4148().emission)),
        quantity: None,
        image: None,
        fit: Some(FitRole {
            systems: &[SystemKind::Circuit],
            law: Some(DiodeModel::Shockley),
            default: true,
            order: 4,
        }),
    },
    Row {
        key: Key::SeriesResistance,
        name: "Rs",
        symbol: "R_s",
        name_aliases: &[],
        flag: "diode-rs",
        aliases: &[],
        metavar: "DIODE_RS",
        group: KeyGroup::Diode,
        section: Some(Section::Shockley),
        part: Part::Any,
        form: KeyForm::Si,
        unit: Some("ohm"),
        units: OHMS,
        range: KeyRange::closed(0.0, SERIES_RESISTANCE_MAX),
        allowed: "must be finite and from 0 to 1e6 (ohms)",
        description: "Shockley series resistance R_s (Ω)",
        help: "Shockley series resistance R_s in ohms [default: 0.6458, 1N4148]",
        default: Some(|| KeyDefault::Number(DiodePair::one_n4148().series_resistance)),
        quantity: None,
        image: None,
        fit: Some(FitRole {
            systems: &[SystemKind::Circuit],
            law: Some(DiodeModel::Shockley),
            default: false,
            order: 5,
        }),
    },
    Row {
        key: Key::Temperature,
        name: "temperature",
        symbol: "T",
        name_aliases: &[],
        flag: "temperature",
        aliases: &[],
        metavar: "TEMPERATURE",
        group: KeyGroup::Diode,
        section: Some(Section::Shockley),
        part: Part::Any,
        form: KeyForm::Plain,
        unit: Some("°C"),
        units: &[],
        range: KeyRange {
            min: -ZERO_CELSIUS,
            min_inclusive: false,
            max: TEMPERATURE_MAX,
            max_inclusive: true,
        },
        allowed: "must be finite, above -273.15 and at most 1000 (degrees Celsius)",
        description: "diode temperature (°C)",
        help: "Diode temperature in °C [default: 27, as SPICE]",
        default: Some(|| KeyDefault::Number(DiodePair::one_n4148().temperature)),
        quantity: None,
        image: None,
        fit: None,
    },
    Row {
        key: Key::Diode,
        name: "diode",
        symbol: "",
        name_aliases: &[],
        flag: "model",
        aliases: &[],
        metavar: "MODEL",
        group: KeyGroup::Diode,
        section: Some(Section::Model),
        part: Part::Any,
        form: KeyForm::Choice,
        unit: None,
        units: &[],
        range: KeyRange::NONE,
        allowed: "is not a number",
        description: "diode law: pwl or shockley",
        help: "Diode law: `pwl` (exact solver) or `shockley` (stiff solver)",
        default: Some(|| KeyDefault::Name(DiodeModel::Pwl.label())),
        quantity: None,
        image: None,
        fit: None,
    },
    Row {
        key: Key::Preset,
        name: "preset",
        symbol: "",
        name_aliases: &[],
        flag: "preset",
        aliases: &[],
        metavar: "PRESET",
        group: KeyGroup::System,
        section: None,
        part: Part::Any,
        form: KeyForm::Choice,
        unit: None,
        units: &[],
        range: KeyRange::NONE,
        allowed: "is not a number",
        description: "built-in physical description",
        help: "A built-in physical description: `paper` (L = 11.5 mH, C = 0.02 µF, R = 68 Ω, \
               U_t = 0.7 V, R_D = 3.0 Ω)",
        default: None,
        quantity: None,
        image: None,
        fit: None,
    },
    Row {
        key: Key::Vb,
        name: "vb",
        symbol: "v_b",
        name_aliases: &[],
        flag: "vb",
        aliases: &[],
        metavar: "VB",
        group: KeyGroup::Friction,
        section: Some(Section::Model),
        part: Part::Any,
        form: KeyForm::Plain,
        unit: None,
        units: &[],
        range: KeyRange::closed(-VB_MAX, VB_MAX),
        allowed: VB_ALLOWED,
        description: "belt speed vb (dimensionless, in units of y')",
        help: "Belt speed vb in units of y' = dy/dτ: friction acts on the slip y' − vb \
               (mechanical twin or dimensionless model; a circuit has no belt) [default: 0]",
        default: Some(|| KeyDefault::Number(0.0)),
        quantity: Some("belt speed"),
        image: None,
        fit: None,
    },
    Row {
        key: Key::FrictionLaw,
        name: "friction_law",
        symbol: "",
        name_aliases: &[],
        flag: "friction-law",
        aliases: &[],
        metavar: "LAW",
        group: KeyGroup::Friction,
        section: Some(Section::Model),
        part: Part::Any,
        form: KeyForm::Choice,
        unit: None,
        units: &[],
        range: KeyRange::NONE,
        allowed: "is not a number",
        description: "friction law of the slip speed: coulomb, stribeck or cubic",
        help: "Friction law of the slip speed s: `coulomb` (1 while slipping; solved exactly), \
               `stribeck` (1 + (μs − 1)·exp(−(s/vs)^δ) + η·s) or `cubic` (μs − k1·s + k3·s³)",
        default: Some(|| KeyDefault::Name(FrictionLawKind::Coulomb.label())),
        quantity: None,
        image: None,
        fit: None,
    },
    Row {
        key: Key::Vs,
        name: "vs",
        symbol: "v_s",
        name_aliases: &[],
        flag: "vs",
        aliases: &[],
        metavar: "VS",
        group: KeyGroup::Friction,
        section: Some(Section::Model),
        part: Part::Any,
        form: KeyForm::Plain,
        unit: None,
        units: &[],
        range: KeyRange {
            min: 0.0,
            min_inclusive: false,
            max: LAW_MAX,
            max_inclusive: true,
        },
        allowed: VS_ALLOWED,
        description: "Stribeck speed vs (dimensionless, as vb)",
        help: "Stribeck speed vs > 0 of the Stribeck law, in the units of vb",
        default: None,
        quantity: Some("Stribeck speed"),
        image: None,
        fit: None,
    },
    Row {
        key: Key::Delta,
        name: "delta",
        symbol: "δ",
        name_aliases: &[],
        flag: "delta",
        aliases: &[],
        metavar: "DELTA",
        group: KeyGroup::Friction,
        section: Some(Section::Model),
        part: Part::Any,
        form: KeyForm::Plain,
        unit: None,
        units: &[],
        range: KeyRange {
            min: 0.0,
            min_inclusive: false,
            max: DELTA_MAX,
            max_inclusive: true,
        },
        allowed: DELTA_ALLOWED,
        description: "Stribeck exponent δ",
        help: "Exponent δ > 0 of the Stribeck law (2: a Gaussian fall) [default: 2]",
        default: Some(|| KeyDefault::Number(2.0)),
        quantity: None,
        image: None,
        fit: None,
    },
    Row {
        key: Key::Eta,
        name: "eta",
        symbol: "η",
        name_aliases: &[],
        flag: "eta",
        aliases: &[],
        metavar: "ETA",
        group: KeyGroup::Friction,
        section: Some(Section::Model),
        part: Part::Any,
        form: KeyForm::Plain,
        unit: None,
        units: &[],
        range: KeyRange::closed(0.0, LAW_MAX),
        allowed: ETA_ALLOWED,
        description: "viscous coefficient η of the Stribeck law (dimensionless)",
        help: "Viscous coefficient η ≥ 0 of the Stribeck law (friction η·s at slip speed s) \
               [default: 0]",
        default: Some(|| KeyDefault::Number(0.0)),
        quantity: Some("viscous friction"),
        image: None,
        fit: None,
    },
    Row {
        key: Key::K1,
        name: "k1",
        symbol: "k_1",
        name_aliases: &[],
        flag: "k1",
        aliases: &[],
        metavar: "K1",
        group: KeyGroup::Friction,
        section: Some(Section::Model),
        part: Part::Any,
        form: KeyForm::Plain,
        unit: None,
        units: &[],
        range: KeyRange::closed(-LAW_MAX, LAW_MAX),
        allowed: K1_ALLOWED,
        description: "coefficient k1 of the cubic law (dimensionless)",
        help: "Coefficient k1 of the cubic law μs − k1·s + k3·s³ (k1 > 0: friction falls with \
               the slip speed; the law must not go negative: 4·k1³ ≤ 27·μs²·k3)",
        default: None,
        quantity: Some("linear coefficient of the cubic law"),
        image: None,
        fit: None,
    },
    Row {
        key: Key::K3,
        name: "k3",
        symbol: "k_3",
        name_aliases: &[],
        flag: "k3",
        aliases: &[],
        metavar: "K3",
        group: KeyGroup::Friction,
        section: Some(Section::Model),
        part: Part::Any,
        form: KeyForm::Plain,
        unit: None,
        units: &[],
        range: KeyRange::closed(0.0, LAW_MAX),
        allowed: K3_ALLOWED,
        description: "coefficient k3 of the cubic law (dimensionless)",
        help: "Coefficient k3 ≥ 0 of the cubic law μs − k1·s + k3·s³",
        default: None,
        quantity: Some("cubic coefficient of the cubic law"),
        image: None,
        fit: None,
    },
    Row {
        key: Key::BeltSpeed,
        name: "belt_speed",
        symbol: "v_belt",
        name_aliases: &[],
        flag: "belt-speed",
        aliases: &[],
        metavar: "BELT_SPEED",
        group: KeyGroup::Friction,
        section: Some(Section::Mechanics),
        part: Part::Any,
        form: KeyForm::Si,
        unit: Some("m/s"),
        units: &[],
        range: KeyRange::ANY,
        allowed: "must be finite (m/s)",
        description: "belt speed (m/s)",
        help: "Belt speed in m/s under the mechanical oscillator (instead of --vb)",
        default: None,
        quantity: None,
        image: Some(Image {
            of: Key::Vb,
            scale: |s| s.velocity,
        }),
        fit: None,
    },
    Row {
        key: Key::StribeckSpeed,
        name: "stribeck_speed",
        symbol: "v_S",
        name_aliases: &[],
        flag: "stribeck-speed",
        aliases: &[],
        metavar: "STRIBECK_SPEED",
        group: KeyGroup::Friction,
        section: Some(Section::Mechanics),
        part: Part::Any,
        form: KeyForm::Si,
        unit: Some("m/s"),
        units: &[],
        range: KeyRange::positive_from(0.0),
        allowed: "must be finite and > 0 (m/s)",
        description: "Stribeck speed (m/s)",
        help: "Stribeck speed in m/s of the mechanical oscillator's Stribeck law (instead of \
               --vs)",
        default: None,
        quantity: None,
        image: Some(Image {
            of: Key::Vs,
            scale: |s| s.velocity,
        }),
        fit: None,
    },
    Row {
        key: Key::ViscousFriction,
        name: "viscous_friction",
        symbol: "c_v",
        name_aliases: &[],
        flag: "viscous-friction",
        aliases: &[],
        metavar: "VISCOUS_FRICTION",
        group: KeyGroup::Friction,
        section: Some(Section::Mechanics),
        part: Part::Any,
        form: KeyForm::Si,
        unit: Some("N s/m"),
        units: &[],
        range: KeyRange::closed(0.0, f64::INFINITY),
        allowed: "must be finite and >= 0 (N s/m)",
        description: "viscous friction coefficient of the Stribeck law (N·s/m)",
        help: "Viscous friction of the Stribeck law in N·s/m, a force on the slip against the \
               belt (instead of --eta; not the damping γ)",
        default: None,
        quantity: None,
        image: Some(Image {
            of: Key::Eta,
            scale: |s| s.force / s.velocity,
        }),
        fit: None,
    },
    Row {
        key: Key::CubicK1,
        name: "cubic_k1",
        symbol: "K_1",
        name_aliases: &[],
        flag: "cubic-k1",
        aliases: &[],
        metavar: "CUBIC_K1",
        group: KeyGroup::Friction,
        section: Some(Section::Mechanics),
        part: Part::Any,
        form: KeyForm::Si,
        unit: Some("N s/m"),
        units: &[],
        range: KeyRange::ANY,
        allowed: "must be finite (N s/m)",
        description: "linear coefficient of the cubic law (N·s/m)",
        help: "Linear coefficient of the cubic law F0·μs − K1·s + K3·s³ in N·s/m (instead of \
               --k1)",
        default: None,
        quantity: None,
        image: Some(Image {
            of: Key::K1,
            scale: |s| s.force / s.velocity,
        }),
        fit: None,
    },
    Row {
        key: Key::CubicK3,
        name: "cubic_k3",
        symbol: "K_3",
        name_aliases: &[],
        flag: "cubic-k3",
        aliases: &[],
        metavar: "CUBIC_K3",
        group: KeyGroup::Friction,
        section: Some(Section::Mechanics),
        part: Part::Any,
        form: KeyForm::Si,
        unit: Some("N s^3/m^3"),
        units: &[],
        range: KeyRange::closed(0.0, f64::INFINITY),
        allowed: "must be finite and >= 0 (N s^3/m^3)",
        description: "cubic coefficient of the cubic law (N·s³/m³)",
        help: "Cubic coefficient of the cubic law F0·μs − K1·s + K3·s³ in N·s³/m³ (instead of \
               --k3)",
        default: None,
        quantity: None,
        image: Some(Image {
            of: Key::K3,
            scale: |s| s.force / (s.velocity * s.velocity * s.velocity),
        }),
        fit: None,
    },
];

/// Everything about one key, as [`Key::table`] gives it (serialisable: the lab's
/// `/api/keys`, the Python package's stubs and the documentation's table are made from it).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct KeyInfo {
    /// The key.
    #[serde(skip)]
    pub key: Key,
    /// TOML key and Python keyword ([`Key::name`]).
    pub name: &'static str,
    /// The symbol in formulas, `_` opening a subscript that runs to a `(` or the end (`U_t`,
    /// `μ_s`, `u_C(0)`); empty for a key whose value is a name ([`Key::symbol`]).
    pub symbol: &'static str,
    /// Other names the TOML file and the Python package accept ([`Key::name_aliases`]).
    pub name_aliases: &'static [&'static str],
    /// Command-line flag without the dashes, and the lab's query key ([`Key::flag`]).
    pub flag: &'static str,
    /// Other flags ([`Key::aliases`]).
    pub aliases: &'static [&'static str],
    /// The flag's value name in help texts ([`Key::metavar`]).
    pub metavar: &'static str,
    /// Which part of the experiment ([`Key::group`]).
    pub group: KeyGroup,
    /// The TOML section ([`Key::section`]); none for the preset, which files do not take.
    pub section: Option<&'static str>,
    /// How the value is written ([`Key::form`]).
    pub form: KeyForm,
    /// The unit, if any ([`Key::unit`]).
    pub unit: Option<&'static str>,
    /// Units a value may be written with ([`Key::units`]).
    pub units: &'static [&'static str],
    /// Smallest value; none when unbounded (or for a name).
    pub min: Option<f64>,
    /// Whether `min` itself is allowed.
    pub min_inclusive: bool,
    /// Largest value; none when unbounded (or for a name).
    pub max: Option<f64>,
    /// Whether `max` itself is allowed.
    pub max_inclusive: bool,
    /// The range in words, as error messages give it ([`Key::allowed`]).
    pub allowed: &'static str,
    /// The names a [`KeyForm::Choice`] takes ([`Key::choices`]).
    pub choices: Vec<&'static str>,
    /// What the key means, with its unit ([`Key::description`]).
    pub description: &'static str,
    /// One line of help ([`Key::help`]).
    pub help: &'static str,
    /// The default, if the key has one ([`Key::default_value`]).
    pub default: Option<KeyDefault>,
}

/// The number of keys a fit may free.
const fn fit_count() -> usize {
    let mut n = 0;
    let mut i = 0;
    while i < ROWS.len() {
        if ROWS[i].fit.is_some() {
            n += 1;
        }
        i += 1;
    }
    n
}

impl Key {
    /// Every key, in the table's order.
    pub const ALL: [Key; ROWS.len()] = {
        let mut all = [Key::Zeta; ROWS.len()];
        let mut i = 0;
        while i < ROWS.len() {
            all[i] = ROWS[i].key;
            i += 1;
        }
        all
    };

    /// The keys a fit may free ([`Key::fit_role`]), in the fit's order ([`FitRole::order`]).
    pub const FIT: [Key; fit_count()] = {
        let mut keys = [Key::Zeta; fit_count()];
        let mut place = 0;
        while place < keys.len() {
            let mut i = 0;
            while i < ROWS.len() {
                if let Some(role) = &ROWS[i].fit {
                    if role.order as usize == place {
                        keys[place] = ROWS[i].key;
                    }
                }
                i += 1;
            }
            place += 1;
        }
        keys
    };

    /// The systems a fit parameter belongs to ([`FitRole::systems`]; none for a key a fit
    /// does not free), for constant contexts.
    pub(crate) const fn fit_systems(self) -> &'static [SystemKind] {
        match &ROWS[self as usize].fit {
            Some(role) => role.systems,
            None => &[],
        }
    }

    /// The key's row.
    fn row(self) -> &'static Row {
        let row = &ROWS[self as usize];
        debug_assert_eq!(row.key, self);
        row
    }

    /// The key's name in the TOML file and the Python package: `mu_s`, `L`, `f`, `Is`, ...
    /// Messages of the library name keys by it.
    pub fn name(self) -> &'static str {
        self.row().name
    }

    /// The key's symbol in formulas, as the paper writes it: `_` opens a subscript that runs
    /// to a `(` or the end (`U_t`, `R_D`, `μ_s`, `F_0`, `u_C(0)`); empty for a key whose
    /// value is a name (the diode law, the preset). The lab labels its form with it.
    pub fn symbol(self) -> &'static str {
        self.row().symbol
    }

    /// Other names the TOML file and the Python package accept: `F` (newtons) for the drive
    /// amplitude `U` (volts).
    pub fn name_aliases(self) -> &'static [&'static str] {
        self.row().name_aliases
    }

    /// The key named `name` ([`Key::name`] or one of [`Key::name_aliases`]), or `None`.
    pub fn from_name(name: &str) -> Option<Key> {
        Key::ALL
            .into_iter()
            .find(|k| k.name() == name || k.name_aliases().contains(&name))
    }

    /// The key's spelling on the command line (without the dashes) and in the lab's query:
    /// `mu-s`, `freq`, `ut`, `rd`, `diode-is`, `model`, `preset`, ...
    pub fn flag(self) -> &'static str {
        self.row().flag
    }

    /// Other command-line flags of the key: `L`, `C`, `R`, `U`.
    pub fn aliases(self) -> &'static [&'static str] {
        self.row().aliases
    }

    /// The key whose flag is `flag` ([`Key::flag`] or one of [`Key::aliases`]), or `None`.
    pub fn from_flag(flag: &str) -> Option<Key> {
        Key::ALL
            .into_iter()
            .find(|k| k.flag() == flag || k.aliases().contains(&flag))
    }

    /// The value name of the flag in help texts (`ZETA`, `TURN_ON`, `DIODE_IS`, ...).
    pub fn metavar(self) -> &'static str {
        self.row().metavar
    }

    /// Which part of the experiment the key describes.
    pub fn group(self) -> KeyGroup {
        self.row().group
    }

    /// The heading of the key's flag in the command line's help: `Model (dimensionless)`,
    /// `Model (physical)` or `Diode model`.
    pub fn heading(self) -> &'static str {
        match (self.group(), self.form()) {
            (KeyGroup::Diode, _) => "Diode model",
            (KeyGroup::Friction, _) => "Belt and friction law (mechanical)",
            (_, KeyForm::Plain) => "Model (dimensionless)",
            _ => "Model (physical)",
        }
    }

    /// The TOML section the key is written in (none for [`Key::Preset`]).
    pub fn section(self) -> Option<Section> {
        self.row().section
    }

    /// How the key's value is written.
    pub fn form(self) -> KeyForm {
        self.row().form
    }

    /// The key's unit: `H`, `F`, `ohm`, `V`, `A`, `Hz`, `rad/s`, `rad`, `kg`, `N/m`,
    /// `N s/m`, `N`, `°C`, `V or N` (the drive amplitude of a circuit or of a mechanical
    /// oscillator), ...; `None` for a dimensionless key.
    pub fn unit(self) -> Option<&'static str> {
        self.row().unit
    }

    /// The key's unit as figures and pages write it: `Ω` for `ohm`, `N·s/m` for `N s/m`,
    /// `N·s³/m³` for `N s^3/m^3`,
    /// the others as [`Key::unit`]; `None` for a dimensionless key.
    pub fn shown_unit(self) -> Option<&'static str> {
        self.unit().map(|unit| match unit {
            "ohm" => "Ω",
            "N s/m" => "N·s/m",
            "N s^3/m^3" => "N·s³/m³",
            unit => unit,
        })
    }

    /// The units a value of the key may be written with (`20nF`, `68ohm`); any other unit
    /// after a number is refused ([`Key::check_unit`]).
    pub fn units(self) -> &'static [&'static str] {
        self.row().units
    }

    /// The key's range (empty for the keys whose values are names).
    pub fn range(self) -> KeyRange {
        self.row().range
    }

    /// The key's range in words, as error messages give it ("must be finite and > 0
    /// (henry)").
    pub fn allowed(self) -> &'static str {
        self.row().allowed
    }

    /// What the key means, with its unit.
    pub fn description(self) -> &'static str {
        self.row().description
    }

    /// One line of help: the command-line flag's help text.
    pub fn help(self) -> &'static str {
        self.row().help
    }

    /// The value the key takes when not given, if it has one (ζ: the paper's circuit's; φ, y0,
    /// v0: 0; μs: 1; the Shockley parameters: the 1N4148's; the diode law: `pwl`).
    pub fn default_value(self) -> Option<KeyDefault> {
        self.row().default.map(|f| f())
    }

    /// The names a [`KeyForm::Choice`] key takes (`pwl`, `shockley`; `paper`); empty for a
    /// number.
    pub fn choices(self) -> Vec<&'static str> {
        match self {
            Key::Diode => DiodeModel::ALL.iter().map(|d| d.label()).collect(),
            Key::Preset => Preset::ALL.iter().map(|p| p.label()).collect(),
            Key::FrictionLaw => FrictionLawKind::ALL.iter().map(|l| l.label()).collect(),
            _ => Vec::new(),
        }
    }

    /// The friction law whose parameter the key gives (or whose parameter its physical value
    /// converts to): `vs`, `delta`, `eta` and their physical twins the Stribeck law's, `k1`,
    /// `k3` and theirs the cubic law's; `None` for every other key. A law's parameters are
    /// refused with another law ([`SpecError::OtherLaw`](super::SpecError::OtherLaw)).
    pub fn law(self) -> Option<FrictionLawKind> {
        match self.image_key().unwrap_or(self) {
            Key::Vs | Key::Delta | Key::Eta => Some(FrictionLawKind::Stribeck),
            Key::K1 | Key::K3 => Some(FrictionLawKind::Cubic),
            _ => None,
        }
    }

    /// What makes the key a fit parameter, if a fit may free it: the systems and the diode
    /// law it belongs to, whether it is freed by default and its place in the fit's lists.
    pub fn fit_role(self) -> Option<FitRole> {
        self.row().fit
    }

    /// For a physical value that converts to a dimensionless one with the system's scales
    /// (U, f, Ω, u_C(0), i(0)): that dimensionless key (β, w, w, y0, v0).
    pub fn image_key(self) -> Option<Key> {
        self.row().image.map(|i| i.of)
    }

    /// The dimensionless value that `value` of this physical key gives with `scales`
    /// (f/f0 for the frequency f, U/U_t for the amplitude, ...): the one conversion of every
    /// front end. `None` for a key that is not converted ([`Key::image_key`]).
    pub fn image(self, value: f64, scales: &Scales) -> Option<f64> {
        self.row().image.map(|i| value / (i.scale)(scales))
    }

    /// The keys that give the same quantity as this one (for w: w, f and Ω), this one
    /// included, in the table's order, and the quantity's name; `None` for a key that is the
    /// only way to give its value.
    pub fn quantity(self) -> Option<(&'static str, Vec<Key>)> {
        let base = self.image_key().unwrap_or(self);
        let name = base.row().quantity?;
        let keys = Key::ALL
            .into_iter()
            .filter(|&k| k == base || k.image_key() == Some(base))
            .collect();
        Some((name, keys))
    }

    /// Whether the key is a part of a circuit that makes the description one of a circuit
    /// (L, C, R, U_t, R_D; the preset does too, and the Shockley parameters need one).
    pub fn is_circuit_part(self) -> bool {
        self.row().part == Part::Circuit
    }

    /// Whether the key is a part of a mechanical oscillator (m, k, γ, F0).
    pub fn is_mechanics_part(self) -> bool {
        self.row().part == Part::Mechanics
    }

    /// Check a value of this key on its own: the same ranges as the types it builds (e.g.
    /// L > 0, R ≥ 0, 1 ≤ μs ≤ 1e9), with the same messages. Dimensionless values must lie in
    /// the range the solvers support ([`crate::limits`]); physical values are checked against
    /// it through their dimensionless images when the experiment is built
    /// ([`crate::Error::ImageOutOfRange`]).
    ///
    /// # Errors
    /// [`crate::Error::InvalidParameter`] naming the key ([`Key::name`]), the value and what
    /// is allowed ([`Key::allowed`]).
    pub fn check(self, value: f64) -> Result<f64> {
        let row = self.row();
        check(row.name, value, row.range.contains(value), row.allowed)
    }

    /// Refuse a unit after the number that is not the key's: `9.97kV` for a frequency is
    /// refused, not read as 9.97 kHz. A number without a unit passes.
    ///
    /// # Errors
    /// [`NumberError::WrongUnit`].
    pub fn check_unit(self, text: &str) -> Result<(), NumberError> {
        let trimmed = text.trim();
        let Some(&unit) = UNITS.iter().find(|u| trimmed.ends_with(*u)) else {
            return Ok(());
        };
        if self.units().contains(&unit) {
            return Ok(());
        }
        Err(NumberError::WrongUnit {
            unit,
            allowed: self.units(),
        })
    }

    /// Read the number of `text` as the key's flag does: a plain number for
    /// [`KeyForm::Plain`], a number with an optional SI prefix and unit for [`KeyForm::Si`].
    /// Neither the unit ([`Key::check_unit`]) nor the range ([`Key::check`]) is checked.
    ///
    /// # Errors
    /// [`NumberError`]; a [`KeyForm::Choice`] key is not a number.
    pub fn number(self, text: &str) -> Result<f64, NumberError> {
        match self.form() {
            KeyForm::Plain => parse_plain(text),
            KeyForm::Si => parse_si(text),
            KeyForm::Choice => Err(NumberError::NotANumber(crate::units::shown(text))),
        }
    }

    /// Read the number of `text` as the key is written, its unit checked but not its range
    /// ([`Key::check_unit`], [`Key::number`]): what a command-line flag's parser takes.
    ///
    /// # Errors
    /// [`NumberError`].
    pub fn read(self, text: &str) -> Result<f64, NumberError> {
        self.check_unit(text)?;
        self.number(text)
    }

    /// Read a value of the key from text: a plain number or one with an SI prefix and the
    /// key's unit ([`Key::number`]), a unit that fits the key ([`Key::check_unit`]), in the
    /// key's range ([`Key::check`]).
    ///
    /// ```
    /// use stickslip::experiment::Key;
    /// assert_eq!(Key::Inductance.parse("11.5mH").unwrap(), 11.5e-3);
    /// assert!(Key::Frequency.parse("9.97kV").is_err());
    /// assert_eq!(
    ///     Key::W.parse("-1").unwrap_err().to_string(),
    ///     "invalid w = -1: must be finite and from 1e-5 to 1e5 (docs/limits.md)"
    /// );
    /// ```
    ///
    /// # Errors
    /// [`Error::InvalidText`] when the text is not a number of the key;
    /// [`Error::InvalidParameter`] when the number is out of range.
    pub fn parse(self, text: &str) -> Result<f64> {
        let value = self
            .read(text)
            .map_err(|error| Error::InvalidText { key: self, error })?;
        self.check(value)
    }

    /// The table: everything about every key, in the order of [`Key::ALL`].
    pub fn table() -> Vec<KeyInfo> {
        Key::ALL.into_iter().map(Key::info).collect()
    }

    /// Everything about this key.
    pub fn info(self) -> KeyInfo {
        let row = self.row();
        let bound = |x: f64| x.is_finite().then_some(x);
        KeyInfo {
            key: self,
            name: row.name,
            symbol: row.symbol,
            name_aliases: row.name_aliases,
            flag: row.flag,
            aliases: row.aliases,
            metavar: row.metavar,
            group: row.group,
            section: row.section.map(Section::name),
            form: row.form,
            unit: row.unit,
            units: row.units,
            min: bound(row.range.min),
            min_inclusive: row.range.min_inclusive,
            max: bound(row.range.max),
            max_inclusive: row.range.max_inclusive,
            allowed: row.allowed,
            choices: self.choices(),
            description: row.description,
            help: row.help,
            default: self.default_value(),
        }
    }

    /// The table of keys of `docs/limits.md`, in Markdown: one line per key with its TOML
    /// and Python name, its flag, its unit, its range and its default.
    pub fn markdown_table() -> String {
        let mut out = String::from(
            "| key (TOML, Python) | flag, lab query | group | unit | allowed | default |\n\
             |---|---|---|---|---|---|\n",
        );
        for info in Key::table() {
            let names = std::iter::once(info.name)
                .chain(info.name_aliases.iter().copied())
                .map(|n| format!("`{n}`"))
                .collect::<Vec<_>>()
                .join(", ");
            let flags = std::iter::once(info.flag)
                .chain(info.aliases.iter().copied())
                .map(|f| format!("`--{f}`"))
                .collect::<Vec<_>>()
                .join(", ");
            let allowed = if info.choices.is_empty() {
                info.allowed.to_string()
            } else {
                format!("one of {}", info.choices.join(", "))
            };
            let default = info.default.map(|d| d.to_string()).unwrap_or_default();
            out.push_str(&format!(
                "| {names} | {flags} | {} | {} | {allowed} | {default} |\n",
                info.group,
                info.unit.unwrap_or(""),
            ));
        }
        out
    }
}

impl std::fmt::Display for Key {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.name())
    }
}

impl Error {
    /// The key of an experiment description that the error is about, if it is about one: a
    /// value out of range ([`Error::InvalidParameter`] naming a key), text that is not a
    /// value of a key ([`Error::InvalidText`]), a physical value whose dimensionless image is
    /// out of range ([`Error::ImageOutOfRange`]) or a description that is incomplete or
    /// contradicts itself ([`Error::Spec`], [`super::SpecError::key`]). A front end renders
    /// the key its own way (a flag, a query key, a keyword).
    pub fn key(&self) -> Option<Key> {
        match self {
            Error::InvalidParameter { name, .. } => {
                Key::ALL.into_iter().find(|k| k.name() == *name)
            }
            Error::InvalidText { key, .. }
            | Error::InvalidName { key, .. }
            | Error::ImageOutOfRange { key, .. } => Some(*key),
            Error::Spec(spec) => spec.key(),
            _ => None,
        }
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
            assert_eq!(Key::from_flag(k.flag()), Some(k));
        }
        assert_eq!(Key::from_name("F"), Some(Key::Amplitude));
        assert_eq!(Key::from_name("Q"), None);
        assert_eq!(Key::from_flag("L"), Some(Key::Inductance));
        assert_eq!(Key::from_flag("mu_s"), None);
    }

    /// Every variant has its row (a new variant fails to compile here until it is listed,
    /// and fails the test until its row is added).
    #[test]
    fn every_variant_has_its_row() {
        let listed = |k: Key| match k {
            Key::Zeta
            | Key::W
            | Key::Beta
            | Key::Phi
            | Key::MuS
            | Key::Y0
            | Key::V0
            | Key::Inductance
            | Key::Capacitance
            | Key::Resistance
            | Key::TurnOn
            | Key::DiodeResistance
            | Key::Mass
            | Key::Stiffness
            | Key::Damping
            | Key::Friction
            | Key::Amplitude
            | Key::Frequency
            | Key::Omega
            | Key::Uc0
            | Key::I0
            | Key::SaturationCurrent
            | Key::Emission
            | Key::SeriesResistance
            | Key::Temperature
            | Key::Diode
            | Key::Preset
            | Key::Vb
            | Key::FrictionLaw
            | Key::Vs
            | Key::Delta
            | Key::Eta
            | Key::K1
            | Key::K3
            | Key::BeltSpeed
            | Key::StribeckSpeed
            | Key::ViscousFriction
            | Key::CubicK1
            | Key::CubicK3 => k as usize,
        };
        assert_eq!(listed(Key::CubicK3) + 1, ROWS.len());
    }

    #[test]
    fn rows_are_in_the_order_of_the_enum() {
        for (i, k) in Key::ALL.into_iter().enumerate() {
            assert_eq!(k as usize, i);
            assert_eq!(ROWS[i].key, k);
        }
    }

    /// Every number has a symbol and every name none; a subscript follows a letter.
    #[test]
    fn symbols_are_given_for_numbers() {
        for k in Key::ALL {
            let symbol = k.symbol();
            assert_eq!(symbol.is_empty(), k.form() == KeyForm::Choice, "{k}");
            assert!(
                !symbol.starts_with('_') && !symbol.ends_with('_'),
                "{k}: {symbol}"
            );
        }
        assert_eq!(Key::TurnOn.symbol(), "U_t");
        assert_eq!(Key::MuS.info().symbol, "μ_s");
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

    /// Errors name each key by its one name (they said `Omega`, `I_s` and `R_s` before).
    #[test]
    fn errors_name_the_key_by_its_name() {
        for (key, bad) in [
            (Key::Omega, -1.0),
            (Key::SaturationCurrent, 2.0),
            (Key::SeriesResistance, -1.0),
        ] {
            let err = key.check(bad).unwrap_err();
            assert!(
                err.to_string()
                    .starts_with(&format!("invalid {} = ", key.name())),
                "{err}"
            );
            assert_eq!(err.key(), Some(key));
        }
    }

    #[test]
    fn units_are_checked_as_the_lab_checks_them() {
        assert_eq!(Key::Frequency.parse("9.97kHz").unwrap(), 9970.0);
        assert_eq!(Key::Frequency.parse("9.97k").unwrap(), 9970.0);
        let err = Key::Frequency.parse("9.97kV").unwrap_err();
        assert_eq!(err.key(), Some(Key::Frequency));
        assert_eq!(
            err.to_string(),
            "invalid f: the unit V does not fit: write Hz or the number alone"
        );
        assert_eq!(
            Key::W.parse("1Hz").unwrap_err().to_string(),
            "invalid w: the unit Hz does not fit: write the number alone"
        );
        assert_eq!(Key::Resistance.parse("68Ω").unwrap(), 68.0);
        assert_eq!(Key::Amplitude.parse("2N").unwrap(), 2.0);
        assert!(Key::W.parse("1k").is_err());
        assert!(Key::Diode.parse("1").is_err());
        assert_eq!(Key::Inductance.number("1kV").unwrap(), 1e3);
    }
}
