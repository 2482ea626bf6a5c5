//! The TOML experiment file.
//!
//! ```toml
//! # every key optional except what the computation needs
//! [circuit]          # or [mechanics] with m, k, gamma, F0
//! L = "11.5m"        # H; numbers may be strings with SI prefixes
//! C = 0.02e-6        # F
//! R = 68             # Ω, without the diodes
//! U_t = 0.7          # V, PWL diode turn-on (the reference voltage of y and β)
//! R_D = 3.0          # Ω, PWL diode resistance
//! [drive]
//! U = 1.498          # V (F in N for mechanics); or beta = 2.14
//! f = "9.97k"        # Hz; or omega (rad/s), or w = 0.95
//! phi = 0.0          # rad
//! [model]
//! mu_s = 1.0
//! y0 = 0.0           # or uc0 (V or m)
//! v0 = 0.0           # or i0 (A or m/s)
//! diode = "pwl"      # or "shockley"
//! # vb = 0.5         # a belt under the block (mechanics or dimensionless only);
//! # friction_law = "stribeck"   # with vs, delta, eta; or "cubic" with k1, k3
//! # zeta = 0.05      # only without [circuit] or [mechanics]
//! [shockley]         # 1N4148 defaults
//! Is = 4.352e-9      # A
//! n = 1.906
//! Rs = 0.6458        # Ω
//! temperature = 27   # °C
//! ```
//!
//! Unknown sections and keys are errors; every error names the file, the line and the key.

use super::errors::ConfigError;
use super::key::{Key, Section};
use super::spec::ExperimentSpec;
use super::DiodeModel;
use crate::error::{Error, Result};
use crate::friction::FrictionLawKind;
use crate::units::parse_si;
use serde::de::{self, DeserializeSeed, Deserializer, MapAccess, Visitor};
use serde::Deserialize;
use std::sync::OnceLock;
use toml::Spanned;

/// A number: a TOML integer or float, or a string with an SI prefix (`"11.5m"`).
#[derive(Debug, Clone, Copy)]
struct Number(f64);

impl<'de> Deserialize<'de> for Number {
    fn deserialize<D: Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        struct NumberVisitor;
        impl Visitor<'_> for NumberVisitor {
            type Value = Number;
            fn expecting(&self, f: &mut std::fmt::Formatter) -> std::fmt::Result {
                f.write_str("a number, or a string with an SI prefix such as \"20n\"")
            }
            fn visit_i64<E: de::Error>(self, v: i64) -> Result<Number, E> {
                Ok(Number(v as f64))
            }
            fn visit_u64<E: de::Error>(self, v: u64) -> Result<Number, E> {
                Ok(Number(v as f64))
            }
            fn visit_f64<E: de::Error>(self, v: f64) -> Result<Number, E> {
                Ok(Number(v))
            }
            fn visit_str<E: de::Error>(self, v: &str) -> Result<Number, E> {
                parse_si(v).map(Number).map_err(E::custom)
            }
        }
        deserializer.deserialize_any(NumberVisitor)
    }
}

/// One value of the file: a number, with where it stands, or the diode law.
enum Entry {
    Number(Spanned<Number>),
    Diode(DiodeModel),
    Law(FrictionLawKind),
}

/// The file: each section given, with its values under the names the file gives them.
struct Document {
    sections: Vec<(Section, Vec<(&'static str, Entry)>)>,
}

/// The names of the sections, for messages.
const SECTION_NAMES: [&str; 5] = {
    let mut names = [""; 5];
    let mut i = 0;
    while i < Section::ALL.len() {
        names[i] = Section::ALL[i].name();
        i += 1;
    }
    names
};

/// The names a section takes ([`Section::entries`]), for messages.
fn fields(section: Section) -> &'static [&'static str] {
    static FIELDS: OnceLock<Vec<Vec<&'static str>>> = OnceLock::new();
    &FIELDS.get_or_init(|| {
        Section::ALL
            .iter()
            .map(|s| s.entries().map(|(_, name)| name).collect())
            .collect()
    })[section as usize]
}

impl<'de> Deserialize<'de> for Document {
    fn deserialize<D: Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        struct DocumentVisitor;
        impl<'de> Visitor<'de> for DocumentVisitor {
            type Value = Document;
            fn expecting(&self, f: &mut std::fmt::Formatter) -> std::fmt::Result {
                f.write_str("an experiment file")
            }
            fn visit_map<A: MapAccess<'de>>(self, mut map: A) -> Result<Document, A::Error> {
                let mut sections = Vec::new();
                let section = |name: &str| {
                    Section::ALL
                        .into_iter()
                        .find(|s| s.name() == name)
                        .ok_or(&SECTION_NAMES[..])
                };
                while let Some(section) = map.next_key_seed(Name(section))? {
                    sections.push((section, map.next_value_seed(SectionSeed(section))?));
                }
                Ok(Document { sections })
            }
        }
        deserializer.deserialize_map(DocumentVisitor)
    }
}

/// Reads a key of a table as what its function makes of the name; an unknown name is an
/// error listing the names the function gives back (raised while the key is read, so that
/// the message points at the key's line).
struct Name<F>(F);

impl<'de, T, F> DeserializeSeed<'de> for Name<F>
where
    F: Fn(&str) -> Result<T, &'static [&'static str]>,
{
    type Value = T;
    fn deserialize<D: Deserializer<'de>>(self, deserializer: D) -> Result<T, D::Error> {
        deserializer.deserialize_str(self)
    }
}

impl<T, F> Visitor<'_> for Name<F>
where
    F: Fn(&str) -> Result<T, &'static [&'static str]>,
{
    type Value = T;
    fn expecting(&self, f: &mut std::fmt::Formatter) -> std::fmt::Result {
        f.write_str("a key")
    }
    fn visit_str<E: de::Error>(self, name: &str) -> Result<T, E> {
        (self.0)(name).map_err(|expected| E::unknown_field(name, expected))
    }
}

/// Reads one section: the keys the table puts in it ([`Key::section`]), and no other.
struct SectionSeed(Section);

impl<'de> DeserializeSeed<'de> for SectionSeed {
    type Value = Vec<(&'static str, Entry)>;
    fn deserialize<D: Deserializer<'de>>(self, deserializer: D) -> Result<Self::Value, D::Error> {
        deserializer.deserialize_map(self)
    }
}

impl<'de> Visitor<'de> for SectionSeed {
    type Value = Vec<(&'static str, Entry)>;
    fn expecting(&self, f: &mut std::fmt::Formatter) -> std::fmt::Result {
        write!(f, "the [{}] section", self.0.name())
    }
    fn visit_map<A: MapAccess<'de>>(self, mut map: A) -> Result<Self::Value, A::Error> {
        let mut entries = Vec::new();
        let section = self.0;
        let entry = |name: &str| {
            section
                .entries()
                .find(|(_, n)| *n == name)
                .ok_or(fields(section))
        };
        while let Some((key, name)) = map.next_key_seed(Name(entry))? {
            let entry = match key {
                Key::Diode => Entry::Diode(map.next_value()?),
                Key::FrictionLaw => Entry::Law(map.next_value()?),
                _ => Entry::Number(map.next_value()?),
            };
            entries.push((name, entry));
        }
        Ok(entries)
    }
}

/// Line number (from 1) of a byte offset.
fn line_of(text: &str, offset: usize) -> usize {
    text[..offset.min(text.len())].matches('\n').count() + 1
}

/// `[section] key` of the line at `offset`, read from the text around it.
fn key_at(text: &str, offset: usize) -> Option<String> {
    let offset = offset.min(text.len());
    let start = text[..offset].rfind('\n').map_or(0, |i| i + 1);
    let line = text[start..].lines().next().unwrap_or("");
    let key = line.split_once('=').map(|(k, _)| k.trim().to_string())?;
    let section = text[..start]
        .lines()
        .rev()
        .map(str::trim)
        .find(|l| l.starts_with('[') && l.ends_with(']'));
    Some(match section {
        Some(s) => format!("{s} {key}"),
        None => key,
    })
}

impl ExperimentSpec {
    /// Read an experiment description from the text of a TOML file; `file` names it in
    /// errors and descriptions.
    ///
    /// ```
    /// use stickslip::experiment::{ExperimentSpec, Key};
    /// let text = "[circuit]\nL = \"11.5m\"\nC = 20e-9\nR = 68\nU_t = 0.7\nR_D = 3\n\
    ///             [drive]\nU = 1.498\nw = 0.95\n";
    /// let spec = ExperimentSpec::from_toml(text, "exp.toml").unwrap();
    /// assert_eq!(spec.get(Key::Inductance), Some(11.5e-3));
    /// let bad = ExperimentSpec::from_toml("[circuit]\nQ = 3\n", "exp.toml").unwrap_err();
    /// assert!(bad.to_string().starts_with("exp.toml, line 2, [circuit] Q: unknown field `Q`"));
    /// ```
    ///
    /// # Errors
    /// [`Error::Config`] for a syntax error, an unknown section or key, a value that is not a
    /// number or out of its key's range, or a file that describes both a circuit and a
    /// mechanical oscillator, or a drive amplitude twice.
    pub fn from_toml(text: &str, file: &str) -> Result<Self> {
        let fail = |line: Option<usize>, key: Option<String>, message: String| {
            Error::Config(ConfigError {
                file: file.to_string(),
                line,
                key,
                message,
            })
        };
        let doc: Document = toml::from_str(text).map_err(|e| {
            let at = e.span().map(|s| s.start);
            fail(
                at.map(|o| line_of(text, o)),
                at.and_then(|o| key_at(text, o)),
                e.message().to_string(),
            )
        })?;
        let has = |section: Section| doc.sections.iter().any(|(s, _)| *s == section);
        if has(Section::Circuit) && has(Section::Mechanics) {
            return Err(fail(
                None,
                None,
                "describe either [circuit] or [mechanics], not both".into(),
            ));
        }
        let mut spec = ExperimentSpec::new();
        spec.set_source(file);
        for section in Section::ALL {
            let Some((_, entries)) = doc.sections.iter().find(|(s, _)| *s == section) else {
                continue;
            };
            let mut given: Vec<(Key, &str)> = Vec::new();
            for (key, name) in section.entries() {
                let Some((_, entry)) = entries.iter().find(|(n, _)| *n == name) else {
                    continue;
                };
                let value = match entry {
                    Entry::Diode(diode) => {
                        spec.set_diode(*diode);
                        continue;
                    }
                    Entry::Law(law) => {
                        spec.set_law(*law);
                        continue;
                    }
                    Entry::Number(value) => value,
                };
                let here = |message: String| {
                    fail(
                        Some(line_of(text, value.span().start)),
                        Some(format!("[{}] {name}", section.name())),
                        message,
                    )
                };
                if let Some((_, first)) = given.iter().find(|(k, _)| *k == key) {
                    let what = key.quantity().map_or(key.description(), |(what, _)| what);
                    return Err(here(format!("give the {what} once: {first} or {name}")));
                }
                given.push((key, name));
                spec.set(key, value.get_ref().0)
                    .map_err(|e| here(e.to_string()))?;
            }
        }
        Ok(spec)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn err(text: &str) -> String {
        ExperimentSpec::from_toml(text, "x.toml")
            .unwrap_err()
            .to_string()
    }

    #[test]
    fn reads_every_section() {
        let text = "[circuit]\nL = \"11.5mH\"\nC = 0.02e-6\nR = 68\nU_t = 0.7\nR_D = 3.0\n\
                    [drive]\nU = 1.498\nf = \"9.97k\"\nphi = 0.5\n\
                    [model]\nmu_s = 1.5\ny0 = 0.1\nv0 = -0.2\ndiode = \"shockley\"\n\
                    [shockley]\nIs = \"2n\"\nn = 1.5\nRs = 1\ntemperature = 50\n";
        let s = ExperimentSpec::from_toml(text, "x.toml").unwrap();
        for (key, value) in [
            (Key::Inductance, 11.5e-3),
            (Key::Capacitance, 0.02e-6),
            (Key::Resistance, 68.0),
            (Key::Amplitude, 1.498),
            (Key::Frequency, 9970.0),
            (Key::Phi, 0.5),
            (Key::MuS, 1.5),
            (Key::V0, -0.2),
            (Key::SaturationCurrent, 2e-9),
            (Key::Temperature, 50.0),
        ] {
            assert_eq!(s.get(key), Some(value), "{key}");
        }
        assert_eq!(s.diode(), Some(DiodeModel::Shockley));
        assert!(s.build().is_ok());
    }

    #[test]
    fn errors_name_the_file_the_line_and_the_key() {
        assert_eq!(
            err("[circuit]\nL = 1\nQ = 3\n"),
            "x.toml, line 3, [circuit] Q: unknown field `Q`, expected one of `L`, `C`, `R`, \
             `U_t`, `R_D`"
        );
        assert_eq!(
            err("[circuit]\nC = -1\n"),
            "x.toml, line 2, [circuit] C: invalid C = -1: must be finite and > 0 (farad)"
        );
        let text = err("[drive]\nf = \"fast\"\n");
        assert!(
            text.starts_with("x.toml, line 2, [drive] f: 'fast' is not a number"),
            "{text}"
        );
        let text = err("[model]\ndiode = \"ideal\"\n");
        assert!(
            text.contains("line 2") && text.contains("unknown variant `ideal`"),
            "{text}"
        );
        let text = err("[wiring]\nx = 1\n");
        assert!(text.contains("unknown field `wiring`"), "{text}");
        assert!(err("[circuit]\nL = 1\n[mechanics]\nm = 1\n").contains("not both"));
        assert_eq!(
            err("[drive]\nU = 1\nF = 2\n"),
            "x.toml, line 3, [drive] F: give the drive amplitude once: U or F"
        );
        let text = err("[circuit\nL = 1\n");
        assert!(text.starts_with("x.toml, line 1"), "{text}");
    }

    /// The fuzz target `toml_experiment` found it: a quoted value with a line break gave a
    /// message of two lines.
    #[test]
    fn regression_a_line_break_in_a_value_keeps_the_message_on_one_line() {
        let text = err("[circuit]\nL = \"\\n!1.5m\"\nC = 0.02e-6\n");
        assert_eq!(text.lines().count(), 1, "{text}");
        assert!(
            text.starts_with("x.toml, line 2, [circuit] L: '\\n!1.5m' is not a number"),
            "{text}"
        );
    }
}
