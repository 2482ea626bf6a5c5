//! The TOML experiment reader on any text: `ExperimentSpec::from_toml` and `build`.
#![no_main]

#[path = "../cases/toml.rs"]
mod case;

libfuzzer_sys::fuzz_target!(|data: &[u8]| {
    if let Ok(text) = std::str::from_utf8(data) {
        case::check(text);
    }
});
