//! The measurement readers on any text: `read_scope`, `Measurement::new` and
//! `read_amplitudes`.
#![no_main]

#[path = "../cases/scope.rs"]
mod case;

libfuzzer_sys::fuzz_target!(|data: &[u8]| {
    if let Ok(text) = std::str::from_utf8(data) {
        case::check(text);
    }
});
