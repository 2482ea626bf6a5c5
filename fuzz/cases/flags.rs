//! The property of the command line's flag parsing that the fuzz target `model_flags` and
//! the property test `crates/stickslip-cli/tests/fuzz_props.rs` both check (included by
//! both): any arguments are parsed without a panic, by every command's parser and by the
//! model flags' path to an experiment; a refusal is one line; an experiment that builds has
//! parameters inside the documented ranges.

#![allow(dead_code)]

use clap::Parser;
use stickslip_cli::{Cli, ModelFlags};

/// Arguments from bytes: NUL-separated words (invalid UTF-8 replaced).
pub fn arguments(data: &[u8]) -> Vec<String> {
    String::from_utf8_lossy(data)
        .split('\0')
        .filter(|s| !s.is_empty())
        .map(String::from)
        .collect()
}

/// Check one command line (without the program's name).
pub fn check(args: &[String]) {
    let argv = || std::iter::once("stickslip".to_string()).chain(args.iter().cloned());
    // Every command's flags: parsed or refused, never a panic.
    let _ = Cli::try_parse_from(argv());
    let Ok(flags) = ModelFlags::try_parse_from(argv()) else {
        return;
    };
    // A config file would be read from disk: the reader is the TOML target's.
    if flags.model.config.is_some() {
        return;
    }
    match flags.model.experiment() {
        Ok(experiment) => {
            if let Ok(params) = experiment.params() {
                params.validate().expect("parameters inside the ranges");
            }
            stickslip::limits::check_state(experiment.initial().y, experiment.initial().v)
                .expect("initial state inside the ranges");
        }
        Err(e) => {
            let message = format!("{e:#}");
            assert!(!message.contains('\n'), "two lines: {message:?}");
        }
    }
}
