//! The options of the computations, defined once: for each its spellings (command-line flag
//! and lab query `max-period`, Python keyword `max_period`), what it belongs to, its range in
//! numbers and in words, its default and its one-line help ([`OptionKey::table`]).
//!
//! The options types ([`crate::SteadyOptions`], [`crate::stability::LyapunovOptions`],
//! [`OrbitOptions`], [`SimulateOptions`], [`crate::basins::BasinOptions`],
//! [`crate::bifurcation::BifurcationOptions`], [`crate::continuation::ContinuationOptions`],
//! the counts of sweeps and maps) check their fields against this table in their
//! `validate()`, and report a bad one as [`Error::InvalidOption`] naming the [`OptionKey`], so
//! that each front end renders the name its own way ([`Error::render`] with a [`Spelling`])
//! and keeps no range check of its own.
//!
//! The same flag may belong to several computations with different ranges (`--max-period` is
//! 1 to 64 for a steady state, 1 to 1000 for a bifurcation diagram): each is its own key.

pub mod key;
mod newton;
mod run;

pub use key::{Allowed, Bound, OptionGroup, OptionInfo, OptionKey, OptionKind, Rule, Spelling};
pub use newton::NewtonOptions;
pub use run::{OrbitOptions, SimulateOptions, MAX_SIMULATE_SAMPLES};

use crate::error::{Error, Number, Result};

impl OptionKey {
    /// Every option's row, for `/api/options`, the Python stubs and the documentation.
    pub fn table() -> Vec<OptionInfo> {
        Self::ALL.iter().map(|k| k.info()).collect()
    }

    /// Spelling on the command line (without dashes) and in the lab's query: `max-period`.
    pub fn flag(self) -> &'static str {
        self.info().flag
    }

    /// Python keyword and the name in the library's messages: `max_period`.
    pub fn name(self) -> &'static str {
        self.info().name
    }

    /// The option as `spelling` writes it: `--max-period`, `max_period`, `max-period`.
    pub fn spelled(self, spelling: Spelling) -> String {
        match spelling {
            Spelling::Flag => format!("--{}", self.flag()),
            Spelling::Python => self.name().to_string(),
            Spelling::Query => self.flag().to_string(),
        }
    }

    /// The computation it belongs to.
    pub fn group(self) -> OptionGroup {
        self.info().group
    }

    /// What is allowed, in words.
    pub fn allowed(self) -> &'static str {
        self.info().allowed
    }

    /// One-line help.
    pub fn help(self) -> &'static str {
        self.info().help
    }

    /// The default, if it does not depend on the experiment.
    pub fn default_value(self) -> Option<f64> {
        self.info().default
    }

    /// The options of `group`, in the order of the table.
    pub fn of(group: OptionGroup) -> Vec<OptionKey> {
        Self::ALL
            .iter()
            .copied()
            .filter(|k| k.group() == group)
            .collect()
    }

    /// Whether `value` is allowed by the table (finite, in range, whole for a count, and the
    /// option's rule).
    pub fn allows(self, value: f64) -> bool {
        let info = self.info();
        if !value.is_finite() {
            return false;
        }
        if info.kind == OptionKind::Count && value.fract() != 0.0 {
            return false;
        }
        if info.rule == Rule::ZeroIsOff && value == 0.0 {
            return true;
        }
        let above = info.min.is_none_or(|b| {
            if b.inclusive {
                value >= b.value
            } else {
                value > b.value
            }
        });
        let below = info.max.is_none_or(|b| {
            if b.inclusive {
                value <= b.value
            } else {
                value < b.value
            }
        });
        let rule = match info.rule {
            Rule::Even => value % 2.0 == 0.0,
            Rule::PowerOfTwo => (value as u64).is_power_of_two(),
            Rule::Range | Rule::ZeroIsOff => true,
        };
        above && below && rule
    }

    /// Check `value` against the table.
    ///
    /// # Errors
    /// [`Error::InvalidOption`] naming this option.
    pub fn check(self, value: f64) -> Result<f64> {
        if self.allows(value) {
            Ok(value)
        } else {
            Err(self.invalid(value))
        }
    }

    /// Check a count against the table.
    ///
    /// # Errors
    /// [`Error::InvalidOption`] naming this option.
    pub fn check_count(self, value: usize) -> Result<usize> {
        self.check(value as f64).map(|_| value)
    }

    /// The message of a bad `value` of this option, one line, with options spelled by
    /// `spelling` (see [`Error::render`]).
    pub fn message(self, value: f64, allowed: &Allowed, spelling: Spelling) -> String {
        render_invalid(self, value, allowed, spelling)
    }

    /// A whole number as a front end receives it (signed, so that `-4` is this option's
    /// error, not a parser's), without the table's range: for a count whose range depends on
    /// other fields, which the options type's `validate()` checks.
    ///
    /// # Errors
    /// [`Error::InvalidOption`] naming this option for a negative number.
    pub fn whole(self, value: i64) -> Result<usize> {
        usize::try_from(value).map_err(|_| self.invalid(value as f64))
    }

    /// The error of a bad value of this option (the table's words).
    pub fn invalid(self, value: f64) -> Error {
        Error::InvalidOption {
            option: self,
            value,
            allowed: Allowed::Table,
        }
    }
}

impl Allowed {
    /// The words, with other options spelled by `spelling`.
    pub fn render(&self, option: OptionKey, spelling: Spelling) -> String {
        match *self {
            Allowed::Table => option.allowed().to_string(),
            Allowed::Text(text) => text.to_string(),
            Allowed::FromOption { other, value, to } => format!(
                "must be from {} ({}) to {to}",
                other.spelled(spelling),
                Number(value)
            ),
            Allowed::Cap { min, max } => {
                format!("must be from {} to {}", Number(min), Number(max))
            }
            Allowed::Differs { other } => format!("must differ from {}", other.spelled(spelling)),
            Allowed::Needs { other, why } => format!("needs {} ({why})", other.spelled(spelling)),
            Allowed::NotOff { why } => format!("must not be 0 ({why})"),
            Allowed::Above { other, value } => format!(
                "must be greater than {} {}",
                other.spelled(spelling),
                Number(value)
            ),
            Allowed::NotBelow { other, value } => format!(
                "must not be below {} {}",
                other.spelled(spelling),
                Number(value)
            ),
        }
    }
}

/// Render an option error with the option's name spelled by `spelling`:
/// `invalid --max-period 65: must be from 1 to 64` (flag), `invalid max_period = 65: …`
/// (Python), `invalid max-period = 65: …` (query).
pub(crate) fn render_invalid(
    option: OptionKey,
    value: f64,
    allowed: &Allowed,
    spelling: Spelling,
) -> String {
    let rendered = allowed.render(option, spelling);
    // A rule between two options reads as one: `--transient needs --period (...)`.
    if let Allowed::Needs { .. } | Allowed::NotOff { .. } = allowed {
        return format!("{} {rendered}", option.spelled(spelling));
    }
    let allowed = rendered;
    // A name (not a number): `invalid --wrdata: must be a file name ...`.
    if option.info().kind == OptionKind::Text {
        return format!("invalid {}: {allowed}", option.spelled(spelling));
    }
    match spelling {
        Spelling::Flag => format!("invalid --{} {}: {allowed}", option.flag(), Number(value)),
        Spelling::Python | Spelling::Query => format!(
            "invalid {} = {}: {allowed}",
            option.spelled(spelling),
            Number(value)
        ),
    }
}

/// The counts of a sweep or a map: `steps` values of one axis.
///
/// # Errors
/// [`Error::InvalidOption`] naming `option`.
pub fn check_steps(option: OptionKey, steps: usize) -> Result<usize> {
    option.check_count(steps)
}

/// Check the size of a product of two counts (`steps × points` rows, say) against `max`.
///
/// # Errors
/// [`Error::OptionProduct`] when it is larger.
pub fn check_product(
    what: &'static str,
    (first, a): (OptionKey, usize),
    (second, b): (OptionKey, usize),
    max: f64,
    max_words: &'static str,
) -> Result<f64> {
    let product = a as f64 * b as f64;
    if product > max {
        Err(Error::OptionProduct {
            what,
            first,
            second,
            product,
            max: max_words,
        })
    } else {
        Ok(product)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_row_is_consistent() {
        for info in OptionKey::table() {
            let k = info.key;
            assert_eq!(k.info(), info);
            assert!(
                !info.flag.starts_with('-') && !info.flag.contains('_'),
                "{k:?}"
            );
            assert!(!info.name.contains('-'), "{k:?}");
            assert!(
                !info.help.is_empty() && info.allowed.starts_with("must"),
                "{k:?}"
            );
            if let Some(d) = info.default {
                if info.kind != OptionKind::Switch {
                    assert!(k.allows(d), "{k:?}: default {d} refused by its own range");
                }
            }
            if let (Some(lo), Some(hi)) = (info.min, info.max) {
                assert!(lo.value < hi.value, "{k:?}");
                if info.kind == OptionKind::Count && lo.inclusive && hi.inclusive {
                    assert!(k.allows(lo.value) && k.allows(hi.value), "{k:?}");
                    assert!(
                        !k.allows(lo.value - 1.0) && !k.allows(hi.value + 1.0),
                        "{k:?}"
                    );
                }
            }
            assert!(!k.allows(f64::NAN) && !k.allows(f64::INFINITY), "{k:?}");
        }
    }

    #[test]
    fn messages_spell_the_option_for_each_front_end() {
        let e = OptionKey::MaxPeriod.check(65.0).unwrap_err();
        assert_eq!(
            e.to_string(),
            "invalid max_period = 65: must be from 1 to 64"
        );
        assert_eq!(
            e.render(Spelling::Flag),
            "invalid --max-period 65: must be from 1 to 64"
        );
        assert_eq!(
            e.render(Spelling::Query),
            "invalid max-period = 65: must be from 1 to 64"
        );
        assert_eq!(e.option(), Some(OptionKey::MaxPeriod));
    }

    #[test]
    fn the_rules_beyond_the_range() {
        assert!(OptionKey::LyapunovPeriods.allows(0.0));
        assert!(!OptionKey::LyapunovPeriods.allows(19.0));
        assert!(OptionKey::LyapunovPeriods.allows(20.0));
        assert!(!OptionKey::Blocks.allows(5.0) && OptionKey::Blocks.allows(6.0));
        assert!(OptionKey::SpectrumSamples.allows(1024.0));
        assert!(!OptionKey::SpectrumSamples.allows(1000.0));
        assert!(!OptionKey::Tolerance.allows(0.0) && !OptionKey::Tolerance.allows(1.0));
        assert!(!OptionKey::MaxPeriods.allows(2.5));
        assert!(OptionKey::MaxStep.allows(10.0) && !OptionKey::MaxStep.allows(0.0));
    }

    #[test]
    fn simulate_counts_its_samples() {
        let ok = SimulateOptions {
            periods: 100.0,
            samples_per_period: 500_000,
        };
        assert!(ok.validate().is_ok());
        let e = SimulateOptions {
            periods: 120.0,
            samples_per_period: 500_000,
        }
        .validate()
        .unwrap_err();
        assert_eq!(
            e.to_string(),
            "invalid samples = 60000000: periods × samples_per_period must be at most 5e7"
        );
        assert_eq!(
            e.render(Spelling::Flag),
            "--periods × --samples-per-period = 60000000 samples: at most 5e7 allowed"
        );
        let e = SimulateOptions {
            periods: 0.0,
            ..Default::default()
        }
        .validate()
        .unwrap_err();
        assert_eq!(e.to_string(), "invalid periods = 0: must be finite and > 0");
    }

    #[test]
    fn an_orbit_transient_needs_a_period() {
        let e = OrbitOptions {
            transient: 5,
            ..Default::default()
        }
        .validate()
        .unwrap_err();
        assert_eq!(e.option(), Some(OptionKey::OrbitTransient));
        assert!(OrbitOptions {
            period: Some(2),
            transient: 5,
            ..Default::default()
        }
        .validate()
        .is_ok());
    }
}
