//! The option flags are made from the library's option table: each flag's help text is its
//! row's (without the final period) and its default is the row's, in every command of the
//! row's group, so that `--help` cannot drift from the library.

use clap::CommandFactory;
use stickslip::options::{OptionGroup, OptionKind};
use stickslip::{Number, OptionKey};
use stickslip_cli::Cli;

/// The commands whose flags a group's rows are.
fn commands(group: OptionGroup) -> &'static [&'static str] {
    match group {
        OptionGroup::Simulate => &["simulate"],
        OptionGroup::Steady => &["steady", "sweep", "phase-diagram"],
        OptionGroup::Orbit => &["orbit"],
        OptionGroup::Lyapunov => &["lyapunov"],
        OptionGroup::Sweep => &["sweep"],
        OptionGroup::Map => &["phase-diagram"],
        OptionGroup::Bifurcation => &["bifurcation"],
        OptionGroup::Basins => &["basins"],
        OptionGroup::Continuation => &["continue"],
        OptionGroup::Curve => &["theory"],
        OptionGroup::TwoParameter => &["curve"],
        OptionGroup::SteadyReport => &["steady"],
        OptionGroup::Checkpoint => &["sweep", "phase-diagram", "basins"],
        OptionGroup::Netlist => &["netlist"],
        OptionGroup::Lab => &["lab"],
        OptionGroup::Pool => &[],
    }
}

/// Rows that are no flag of the command line: the lab's and Python's alone.
const NOT_FLAGS: &[OptionKey] = &[
    OptionKey::Harmonics,
    OptionKey::MinStopFraction,
    OptionKey::SpectrumSamples,
    OptionKey::TraceSamples,
];

#[test]
fn every_option_flag_has_its_rows_help_and_default() {
    let cli = Cli::command();
    let mut checked = 0;
    for row in OptionKey::table() {
        if NOT_FLAGS.contains(&row.key) {
            continue;
        }
        for &name in commands(row.group) {
            let command = cli
                .find_subcommand(name)
                .unwrap_or_else(|| panic!("no command {name}"));
            let arg = command
                .get_arguments()
                .find(|a| a.get_long() == Some(row.flag))
                .unwrap_or_else(|| panic!("{name} has no --{} ({:?})", row.flag, row.key));
            let help = arg.get_help().map(|h| h.to_string()).unwrap_or_default();
            assert_eq!(
                help,
                row.help.strip_suffix('.').unwrap_or(row.help),
                "{name} --{}: help is not the row's",
                row.flag
            );
            let defaults: Vec<String> = arg
                .get_default_values()
                .iter()
                .map(|v| v.to_string_lossy().into_owned())
                .collect();
            match (row.kind, row.default) {
                (OptionKind::Switch, _) => {}
                (_, Some(d)) if defaults.is_empty() => {
                    // An optional flag says its default in words.
                    let words = format!("[default: {}]", Number(d));
                    assert!(
                        help.contains(&words),
                        "{name} --{}: no default, and the help does not say {words}",
                        row.flag
                    );
                }
                (_, Some(d)) => assert_eq!(
                    defaults,
                    vec![d.to_string()],
                    "{name} --{}: default is not the row's",
                    row.flag
                ),
                (_, None) => assert!(
                    defaults.is_empty(),
                    "{name} --{}: a default the row does not have: {defaults:?}",
                    row.flag
                ),
            }
            checked += 1;
        }
    }
    assert!(checked >= 45, "only {checked} flags checked");
}

#[test]
fn rows_that_are_no_flag_are_not_offered_under_their_own_help() {
    let cli = Cli::command();
    for key in NOT_FLAGS {
        let row = key.info();
        for sub in cli.get_subcommands() {
            for arg in sub.get_arguments() {
                if arg.get_long() == Some(row.flag) {
                    let help = arg.get_help().map(|h| h.to_string()).unwrap_or_default();
                    assert_ne!(
                        help,
                        row.help.strip_suffix('.').unwrap_or(row.help),
                        "{} --{} is a flag: take {key:?} out of NOT_FLAGS",
                        sub.get_name(),
                        row.flag
                    );
                }
            }
        }
    }
}
