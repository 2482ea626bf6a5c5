//! A short property-test version of the fuzz target `model_flags` (docs/fuzzing.md), on the
//! same property (`fuzz/cases/flags.rs`).

#[path = "../../../../fuzz/cases/flags.rs"]
mod flags_case;

use proptest::prelude::*;

/// Words of the command line: every command and model flag, and values in and out of range.
fn word() -> impl Strategy<Value = String> {
    prop_oneof![
        prop::sample::select(vec![
            "simulate",
            "steady",
            "sweep",
            "phase-diagram",
            "theory",
            "convert",
            "netlist",
            "reproduce",
            "--zeta",
            "--w",
            "--beta",
            "--phi",
            "--mu-s",
            "--y0",
            "--v0",
            "--preset",
            "paper",
            "--inductance",
            "--capacitance",
            "--resistance",
            "--ut",
            "--rd",
            "--mass",
            "--stiffness",
            "--damping",
            "--friction",
            "--amplitude",
            "--freq",
            "--omega",
            "--uc0",
            "--i0",
            "--model",
            "pwl",
            "shockley",
            "--diode-is",
            "--diode-n",
            "--diode-rs",
            "--temperature",
            "--L",
            "--C",
            "--U",
            "--over",
            "--from",
            "--to",
            "--steps",
            "--periods",
            "--max-periods",
            "--json",
            "--checkpoint",
            "1e300",
            "-1e300",
            "1e-300",
            "1e9",
            "1e5",
            "1e-5",
            "0",
            "nan",
            "inf",
            "11.5m",
            "20n",
            "9.97kHz",
            "1G",
            "--help",
        ])
        .prop_map(String::from),
        any::<f64>().prop_map(|x| format!("{x}")),
        (-1e10..1e10f64).prop_map(|x| format!("{x}")),
        "\\PC{0,8}",
    ]
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 1500, ..ProptestConfig::default() })]

    #[test]
    fn model_flags_on_random_command_lines(words in prop::collection::vec(word(), 0..12)) {
        flags_case::check(&words);
    }
}
