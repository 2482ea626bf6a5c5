//! The solvers on random parameters anywhere in the documented ranges, over a bounded
//! horizon: no panic, no error, every event by the rules (libFuzzer's -timeout bounds the
//! time of a case).
#![no_main]

#[path = "../cases/solver.rs"]
mod case;

libfuzzer_sys::fuzz_target!(|data: &[u8]| {
    case::check(&case::Case::from_bytes(data));
});
