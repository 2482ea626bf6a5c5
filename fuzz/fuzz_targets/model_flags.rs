//! The command line's flags on any arguments: clap's parsing of every command, and the model
//! flags' path to a library `Experiment`.
#![no_main]

#[path = "../cases/flags.rs"]
mod case;

libfuzzer_sys::fuzz_target!(|data: &[u8]| {
    case::check(&case::arguments(data));
});
