//! What can go wrong with an experiment description ([`SpecError`]) and its file
//! ([`ConfigError`]). A leaf (with [`super::keys`]): it imports nothing else of the crate, so
//! [`crate::error`] can carry these. [`SpecError::render`] and the table of keys behind its
//! messages are in `experiment/spec.rs` and `experiment/key.rs`.

use super::keys::Key;

/// An experiment description that is incomplete or contradicts itself.
///
/// `Display` names keys by [`Key::name`]; [`SpecError::render`] names them as the caller's
/// own interface does (the command-line tool's flags, say).
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
#[non_exhaustive]
pub enum SpecError {
    /// A part of a physical description is missing.
    #[error("{}", self.render(&|k: Key| k.name().to_string()))]
    Missing {
        /// The missing value.
        key: Key,
        /// Whether the description is of a circuit (else a mechanical oscillator).
        circuit: bool,
    },
    /// The drive frequency (`key` = [`Key::W`]) or amplitude ([`Key::Beta`]) is needed and
    /// was not given.
    #[error("{}", self.render(&|k: Key| k.name().to_string()))]
    MissingDrive {
        /// [`Key::W`] or [`Key::Beta`].
        key: Key,
    },
    /// Two values that give the same quantity were both given.
    #[error("{}", self.render(&|k: Key| k.name().to_string()))]
    Twice {
        /// The first value.
        first: Key,
        /// The second value.
        second: Key,
        /// The quantity they both give.
        what: &'static str,
    },
    /// ζ was given with a physical description, whose parts decide it.
    #[error("{}", self.render(&|k: Key| k.name().to_string()))]
    ZetaWithPhysical,
    /// A circuit and a mechanical oscillator were both described.
    #[error("{}", self.render(&|k: Key| k.name().to_string()))]
    CircuitAndMechanics {
        /// A mechanical value that was given.
        mechanical: Key,
    },
    /// A physical value was given without a physical description to convert it with.
    #[error("{}", self.render(&|k: Key| k.name().to_string()))]
    NeedsPhysical {
        /// The physical value.
        key: Key,
    },
    /// A belt or a friction law was given with a circuit, which has neither.
    #[error("{}", self.render(&|k: Key| k.name().to_string()))]
    NoBelt {
        /// The belt's or the law's key that was given.
        key: Key,
    },
    /// A parameter of one friction law was given with another law.
    #[error("{}", self.render(&|k: Key| k.name().to_string()))]
    OtherLaw {
        /// The parameter.
        key: Key,
        /// The law it belongs to (`stribeck`, `cubic`).
        law: &'static str,
    },
    /// A friction law was chosen without a parameter it needs.
    #[error("{}", self.render(&|k: Key| k.name().to_string()))]
    MissingLawParameter {
        /// The parameter.
        key: Key,
        /// The law (`stribeck`, `cubic`).
        law: &'static str,
    },
}

/// An experiment file that is not a valid experiment description.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
#[error("{}", self.describe())]
pub struct ConfigError {
    /// The file's name as given.
    pub file: String,
    /// Line number (from 1) of the problem, when known.
    pub line: Option<usize>,
    /// The key, as `[section] key`, when known.
    pub key: Option<String>,
    /// What is wrong.
    pub message: String,
}

impl ConfigError {
    fn describe(&self) -> String {
        let mut s = self.file.clone();
        if let Some(line) = self.line {
            s.push_str(&format!(", line {line}"));
        }
        if let Some(key) = &self.key {
            s.push_str(&format!(", {key}"));
        }
        // One line, whatever the parser's message holds.
        let message: String = self
            .message
            .lines()
            .map(str::trim)
            .filter(|l| !l.is_empty())
            .collect::<Vec<_>>()
            .join("; ");
        format!("{s}: {message}")
    }
}
