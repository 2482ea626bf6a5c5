//! Text to a description, and errors back to text: the one entry every front end sets a key
//! through from the text it received ([`ExperimentSpec::set_text`]: a flag's value, a lab
//! query's, a Python string), and the one rendering of the errors, each key and option
//! spelled the front end's way ([`Error::render`] with a [`Spelling`]).

use super::key::Key;
use super::{DiodeModel, ExperimentSpec, Preset};
use crate::error::{Error, Number, Result};
use crate::options::{render_invalid, Spelling};

impl Key {
    /// The key as `spelling` writes it: `--freq` (a flag), `f` (Python, TOML and the
    /// library's own messages), `freq` (the lab's query).
    pub fn spelled(self, spelling: Spelling) -> String {
        match spelling {
            Spelling::Flag => format!("--{}", self.flag()),
            Spelling::Python => self.name().to_string(),
            Spelling::Query => self.flag().to_string(),
        }
    }

    /// The value of a key whose values are names (the diode law, the preset) read from
    /// `text`, as the index of the name in [`Key::choices`].
    ///
    /// # Errors
    /// [`Error::InvalidName`] listing the names.
    fn choice(self, text: &str) -> Result<usize> {
        let choices = self.choices();
        choices
            .iter()
            .position(|&c| c == text.trim())
            .ok_or_else(|| Error::InvalidName {
                key: self,
                text: crate::units::shown(text.trim()),
                allowed: choices,
            })
    }
}

impl ExperimentSpec {
    /// Set `key` from the text a front end received for it: a number of the key ([`Key::parse`]:
    /// plain or with an SI prefix and the key's unit, a decimal comma where it is
    /// unambiguous, in the key's range), or for the diode law and the preset one of their
    /// names ([`Key::choices`]).
    ///
    /// ```
    /// use stickslip::experiment::{ExperimentSpec, Key};
    /// use stickslip::Spelling;
    /// let mut spec = ExperimentSpec::new();
    /// spec.set_text(Key::Preset, "paper").unwrap();
    /// spec.set_text(Key::Frequency, "9,97k").unwrap();
    /// assert_eq!(spec.get(Key::Frequency), Some(9970.0));
    /// let err = spec.set_text(Key::Frequency, "9.97kV").unwrap_err();
    /// assert_eq!(
    ///     err.render(Spelling::Flag),
    ///     "invalid --freq: the unit V does not fit: write Hz or the number alone"
    /// );
    /// ```
    ///
    /// # Errors
    /// [`Error::InvalidText`] for text that is not a number of the key,
    /// [`Error::InvalidParameter`] for a number out of its range, [`Error::InvalidName`] for
    /// a name the key does not take; each names the key ([`Error::key`]).
    pub fn set_text(&mut self, key: Key, text: &str) -> Result<&mut Self> {
        match key {
            Key::Preset => {
                let i = key.choice(text)?;
                self.set_preset(Preset::ALL[i]);
            }
            Key::Diode => {
                let i = key.choice(text)?;
                self.set_diode(DiodeModel::ALL[i]);
            }
            Key::FrictionLaw => {
                let i = key.choice(text)?;
                self.set_law(crate::friction::FrictionLawKind::ALL[i]);
            }
            _ => {
                let value = key.parse(text)?;
                self.set(key, value)?;
            }
        }
        Ok(self)
    }
}

/// `'a', 'b' or 'c'`: names as Python's messages list them.
fn either(names: &[&str]) -> String {
    let quoted: Vec<String> = names.iter().map(|n| format!("'{n}'")).collect();
    match quoted.split_last() {
        Some((last, rest)) if !rest.is_empty() => format!("{} or {last}", rest.join(", ")),
        _ => quoted.concat(),
    }
}

impl Error {
    /// The message, one line, with options and keys spelled by `spelling`: `invalid
    /// --max-period 65: must be from 1 to 64` and `invalid --freq -1: must be finite and > 0
    /// (Hz)` on the command line, `invalid max_period = 65: …` and `invalid f = -1: …` in
    /// Python (the same as `to_string()`), `invalid max-period = 65: …` and `invalid freq -1:
    /// …` in the lab's query. Errors that name neither are their `to_string()`.
    pub fn render(&self, spelling: Spelling) -> String {
        match self {
            Error::InvalidOption {
                option,
                value,
                allowed,
            } => render_invalid(*option, *value, allowed, spelling),
            Error::OptionProduct {
                what,
                first,
                second,
                product,
                max,
            } => match spelling {
                Spelling::Flag => format!(
                    "{} × {} = {} {what}: at most {max} allowed",
                    first.spelled(spelling),
                    second.spelled(spelling),
                    Number(*product)
                ),
                Spelling::Python | Spelling::Query => format!(
                    "invalid {what} = {}: {} × {} must be at most {max}",
                    Number(*product),
                    first.spelled(spelling),
                    second.spelled(spelling)
                ),
            },
            _ if spelling == Spelling::Python => self.to_string(),
            Error::Spec(spec) => spec.render(&|k| k.spelled(spelling)),
            Error::InvalidText { key, error } => {
                format!("invalid {}: {error}", key.spelled(spelling))
            }
            Error::InvalidName { key, text, allowed } => {
                format!(
                    "invalid {} '{text}': one of {}",
                    key.spelled(spelling),
                    allowed.join(", ")
                )
            }
            Error::ImageOutOfRange {
                key,
                value,
                image,
                image_value,
                allowed,
            } => format!(
                "invalid {} {}: it gives {image} = {}, which {allowed}",
                key.spelled(spelling),
                Number(*value),
                Number(*image_value)
            ),
            Error::InvalidParameter { value, allowed, .. } => match self.key() {
                Some(key) => format!(
                    "invalid {} {}: {allowed}",
                    key.spelled(spelling),
                    Number(*value)
                ),
                None => self.to_string(),
            },
            other => other.to_string(),
        }
    }

    /// The message of an [`Error::InvalidName`] as Python writes it, in the words of the
    /// key's help: `invalid diode 'spice': must be 'pwl' (exact solver) or 'shockley' (stiff
    /// solver)`, the key named `name` (the argument that took it). `None` for another error.
    pub fn render_name_for_python(&self, name: &str) -> Option<String> {
        let Error::InvalidName { key, text, allowed } = self else {
            return None;
        };
        let words = key
            .help()
            .split_once(": ")
            .map_or_else(|| either(allowed), |(_, words)| words.replace('`', "'"));
        Some(format!("invalid {name} '{text}': must be {words}"))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_key_is_set_from_its_text() {
        let mut spec = ExperimentSpec::new();
        spec.set_text(Key::Preset, " paper ").unwrap();
        spec.set_text(Key::Diode, "shockley").unwrap();
        spec.set_text(Key::Inductance, "11.5mH").unwrap();
        spec.set_text(Key::W, "0,95").unwrap();
        assert_eq!(spec.preset(), Some(Preset::Paper));
        assert_eq!(spec.diode(), Some(DiodeModel::Shockley));
        assert_eq!(spec.get(Key::Inductance), Some(11.5e-3));
        assert_eq!(spec.get(Key::W), Some(0.95));
        let err = spec.set_text(Key::Diode, "spice").unwrap_err();
        assert_eq!(err.key(), Some(Key::Diode));
        assert_eq!(
            err.to_string(),
            "invalid diode 'spice': one of pwl, shockley"
        );
        assert_eq!(
            err.render(Spelling::Query),
            "invalid model 'spice': one of pwl, shockley"
        );
        assert_eq!(
            err.render_name_for_python("model").unwrap(),
            "invalid model 'spice': must be 'pwl' (exact solver) or 'shockley' (stiff solver)"
        );
    }

    /// One wording, each key spelled the front end's way; Python's is the error's own text.
    #[test]
    fn errors_name_keys_the_front_ends_way() {
        let mut spec = ExperimentSpec::new();
        let range = spec.set_text(Key::W, "-1").unwrap_err();
        let text = spec.set_text(Key::Frequency, "ten kHz").unwrap_err();
        for (spelling, expected) in [
            (
                Spelling::Flag,
                [
                    "invalid --w -1: must be finite and from 1e-5 to 1e5 (docs/limits.md)",
                    "invalid --freq: 'ten kHz' is not a number",
                ],
            ),
            (
                Spelling::Python,
                [
                    "invalid w = -1: must be finite and from 1e-5 to 1e5 (docs/limits.md)",
                    "invalid f: 'ten kHz' is not a number",
                ],
            ),
            (
                Spelling::Query,
                [
                    "invalid w -1: must be finite and from 1e-5 to 1e5 (docs/limits.md)",
                    "invalid freq: 'ten kHz' is not a number",
                ],
            ),
        ] {
            assert_eq!(range.render(spelling), expected[0]);
            assert!(
                text.render(spelling).starts_with(expected[1]),
                "{spelling:?}"
            );
        }
        assert_eq!(range.render(Spelling::Python), range.to_string());
        let spec_error = Error::Spec(super::super::SpecError::ZetaWithPhysical);
        assert!(spec_error
            .render(Spelling::Flag)
            .starts_with("--zeta conflicts with a physical description"));
    }
}
