//! The model flags shared by every command: one flag per key of the library's table
//! ([`Key::table`]), with the key's spelling, aliases, value name, help and heading, so that a
//! new key is one row of the library's table and nothing here. The flags become one layer of
//! a library [`ExperimentSpec`] (over the config file's, which the library reads from the
//! file's text); the library checks and builds the [`Experiment`].

use crate::choice::choice;
use crate::output::UsageError;
use anyhow::Result;
use clap::{Arg, ArgAction, ArgMatches, Command};
use std::collections::BTreeMap;
use std::path::PathBuf;
use stickslip::experiment::{DiodeModel, Experiment, ExperimentSpec, Key, KeyForm, Preset};
use stickslip::friction::FrictionLawKind;
use stickslip::units::NumberError;
use stickslip::Spelling;

/// The id and flag of the config file (a file of keys, not a key).
const CONFIG: &str = "config";

/// Model flags, as typed: the values of the keys given, the preset, the diode law and the
/// config file. Dimensionless flags override values derived from a physical description;
/// physical flags override the preset or the config file.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct ModelArgs {
    /// The numbers given, by key (in the key's unit, as typed: SI prefixes applied).
    pub values: BTreeMap<Key, f64>,
    /// `--preset`.
    pub preset: Option<Preset>,
    /// `--model`: the diode law.
    pub diode: Option<DiodeModel>,
    /// `--friction-law`: the friction law of a block on a belt.
    pub law: Option<FrictionLawKind>,
    /// `--config`: a TOML experiment file.
    pub config: Option<PathBuf>,
}

/// The flag of `key` as the user types it, with its dashes: `--mu-s`.
pub fn flag(key: Key) -> String {
    format!("--{}", key.flag())
}

/// Parse a finite plain number (the options' values): the library's
/// [`stickslip::units::parse_plain`].
pub fn finite(text: &str) -> Result<f64, NumberError> {
    stickslip::units::parse_plain(text)
}

/// The flag of a number key.
fn number_arg(key: Key) -> Arg {
    Arg::new(key.flag())
        .long(key.flag())
        .aliases(key.aliases())
        .value_name(key.metavar())
        .help(key.help())
        .help_heading(key.heading())
        .allow_hyphen_values(true)
        .action(ArgAction::Set)
        // The library reads the text ([`Key::read`]: a plain number or one with an SI prefix
        // and the key's unit); its range is checked when the flags become a description.
        .value_parser(move |text: &str| key.read(text))
}

/// The flag of a key that takes a name (`--preset`, `--model`).
fn choice_arg(key: Key) -> Arg {
    let arg = Arg::new(key.flag())
        .long(key.flag())
        .aliases(key.aliases())
        .value_name(key.metavar())
        .help(key.help())
        .help_heading(key.heading())
        .action(ArgAction::Set);
    match key {
        Key::Preset => arg.value_parser(choice::<Preset>()),
        Key::Diode => arg.value_parser(choice::<DiodeModel>()),
        Key::FrictionLaw => arg.value_parser(choice::<FrictionLawKind>()),
        other => unreachable!("{other} is not a key of names"),
    }
}

/// `--config FILE`, after `--preset`: the other physical description that is not a key.
fn config_arg() -> Arg {
    Arg::new(CONFIG)
        .long(CONFIG)
        .value_name("FILE")
        .help(
            "A TOML experiment file (sections `[circuit]` or `[mechanics]`, `[drive]`, \
             `[model]`, `[shockley]`); see the README for an example",
        )
        .help_heading(Key::Preset.heading())
        .action(ArgAction::Set)
        .value_parser(clap::value_parser!(PathBuf))
}

/// The keys in the order of the help: heading by heading (in the order the table first
/// names them), the keys of names first, then the numbers in the table's order.
fn help_order() -> Vec<Key> {
    let mut headings: Vec<&str> = Vec::new();
    for key in Key::ALL {
        if !headings.contains(&key.heading()) {
            headings.push(key.heading());
        }
    }
    let mut order = Vec::with_capacity(Key::ALL.len());
    for heading in headings {
        let keys = Key::ALL.into_iter().filter(|k| k.heading() == heading);
        let (names, numbers): (Vec<Key>, Vec<Key>) =
            keys.partition(|k| k.form() == KeyForm::Choice);
        order.extend(names);
        order.extend(numbers);
    }
    order
}

impl clap::Args for ModelArgs {
    fn augment_args(mut cmd: Command) -> Command {
        for key in help_order() {
            if key.form() == KeyForm::Choice {
                cmd = cmd.arg(choice_arg(key));
            } else {
                cmd = cmd.arg(number_arg(key));
            }
            if key == Key::Preset {
                cmd = cmd.arg(config_arg());
            }
        }
        cmd
    }

    fn augment_args_for_update(cmd: Command) -> Command {
        Self::augment_args(cmd)
    }
}

impl clap::FromArgMatches for ModelArgs {
    fn from_arg_matches(matches: &ArgMatches) -> Result<Self, clap::Error> {
        let mut args = Self::default();
        args.update_from_arg_matches(matches)?;
        Ok(args)
    }

    fn update_from_arg_matches(&mut self, matches: &ArgMatches) -> Result<(), clap::Error> {
        for key in Key::ALL {
            if key.form() != KeyForm::Choice {
                if let Some(&value) = matches.get_one::<f64>(key.flag()) {
                    self.values.insert(key, value);
                }
            }
        }
        if let Some(&preset) = matches.get_one::<Preset>(Key::Preset.flag()) {
            self.preset = Some(preset);
        }
        if let Some(&diode) = matches.get_one::<DiodeModel>(Key::Diode.flag()) {
            self.diode = Some(diode);
        }
        if let Some(&law) = matches.get_one::<FrictionLawKind>(Key::FrictionLaw.flag()) {
            self.law = Some(law);
        }
        if let Some(path) = matches.get_one::<PathBuf>(CONFIG) {
            self.config = Some(path.clone());
        }
        Ok(())
    }
}

impl ModelArgs {
    /// These flags with `key` set to `value` (a number key).
    pub fn with(mut self, key: Key, value: f64) -> Self {
        self.values.insert(key, value);
        self
    }

    /// These flags with `--preset`.
    pub fn with_preset(mut self, preset: Preset) -> Self {
        self.preset = Some(preset);
        self
    }

    /// These flags with `--model`.
    pub fn with_diode(mut self, diode: DiodeModel) -> Self {
        self.diode = Some(diode);
        self
    }

    /// Whether the flag of `key` was given.
    pub fn given(&self, key: Key) -> bool {
        match key {
            Key::Preset => self.preset.is_some(),
            Key::Diode => self.diode.is_some(),
            Key::FrictionLaw => self.law.is_some(),
            _ => self.values.contains_key(&key),
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
        for (&key, &value) in &self.values {
            if let Err(e) = flags.set(key, value) {
                return Err(UsageError(e.render(Spelling::Flag)).into());
            }
        }
        if let Some(preset) = self.preset {
            flags.set_preset(preset);
        }
        if let Some(diode) = self.diode {
            flags.set_diode(diode);
        }
        if let Some(law) = self.law {
            flags.set_law(law);
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
    use clap::Parser;

    #[derive(clap::Parser)]
    struct Flags {
        #[command(flatten)]
        model: ModelArgs,
    }

    #[test]
    fn preset_with_dimensionless_drive() {
        let args = ModelArgs::default()
            .with_preset(Preset::Paper)
            .with(Key::W, 0.95)
            .with(Key::Beta, 2.14);
        let e = args.experiment().unwrap();
        let p = e.params().unwrap();
        assert!((p.zeta - 71.0 / 2.0 * (0.02e-6f64 / 11.5e-3).sqrt()).abs() < 1e-15);
        assert!(e.to_string().contains("preset paper"));
    }

    #[test]
    fn zeta_conflicts_with_physical() {
        let args = ModelArgs::default()
            .with_preset(Preset::Paper)
            .with(Key::Zeta, 0.1)
            .with(Key::W, 0.95)
            .with(Key::Beta, 2.14);
        assert!(args.experiment().is_err());
    }

    /// Every key's flag and aliases read its value as the library reads the key's text, and
    /// the flags of names take the library's names.
    #[test]
    fn the_flags_read_values_as_the_library_does() {
        for key in Key::ALL {
            let spellings = std::iter::once(key.flag()).chain(key.aliases().iter().copied());
            for spelling in spellings {
                if key.form() == KeyForm::Choice {
                    for name in key.choices() {
                        let flags =
                            Flags::try_parse_from(["stickslip", &format!("--{spelling}={name}")])
                                .unwrap_or_else(|e| panic!("--{spelling} {name}: {e}"));
                        assert!(flags.model.given(key), "--{spelling} {name}");
                    }
                    assert!(
                        Flags::try_parse_from(["stickslip", &format!("--{spelling}=nothing")])
                            .is_err()
                    );
                    continue;
                }
                for text in ["1k", "0.25", "2e-3", "-1", "abc", "20nF", "9.97kHz", "inf"] {
                    let clap =
                        Flags::try_parse_from(["stickslip", &format!("--{spelling}={text}")]);
                    let library = key.read(text).ok();
                    assert_eq!(
                        clap.as_ref()
                            .ok()
                            .and_then(|f| f.model.values.get(&key).copied()),
                        library,
                        "--{spelling} {text}"
                    );
                }
            }
        }
    }

    /// clap's own checks of every command (in a debug build): no flag of a command clashes
    /// with a model flag.
    #[test]
    fn every_command_takes_the_model_flags_without_a_clash() {
        use clap::CommandFactory;
        crate::Cli::command().debug_assert();
    }

    #[test]
    fn every_key_has_a_flag_of_its_own() {
        let mut flags: Vec<&str> = Key::ALL.iter().map(|k| k.flag()).collect();
        flags.extend(Key::ALL.iter().flat_map(|k| k.aliases().iter().copied()));
        flags.push(CONFIG);
        let count = flags.len();
        flags.sort_unstable();
        flags.dedup();
        assert_eq!(flags.len(), count);
    }
}
