//! The measurement readers on any bytes: `decode`, then `read_scope`, `Measurement::new` and
//! `read_amplitudes`.
#![no_main]

#[path = "../cases/scope.rs"]
mod case;

libfuzzer_sys::fuzz_target!(|data: &[u8]| {
    case::check_bytes(data);
});
