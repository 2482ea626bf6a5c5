//! The property of the TOML experiment reader that the fuzz target `toml_experiment` and the
//! property test `crates/stickslip/tests/fuzz_props.rs` both check (included by both): any
//! text is read without a panic; a refusal is one line naming the file; an experiment that
//! builds has parameters inside the documented ranges.

#![allow(dead_code)]

use stickslip::experiment::ExperimentSpec;

/// Check one text.
pub fn check(text: &str) {
    let spec = match ExperimentSpec::from_toml(text, "fuzz.toml") {
        Ok(spec) => spec,
        Err(e) => {
            let message = e.to_string();
            assert!(!message.contains('\n'), "two lines: {message:?}");
            assert!(
                message.starts_with("fuzz.toml"),
                "the file is not named: {message}"
            );
            return;
        }
    };
    let experiment = match spec.build() {
        Ok(e) => e,
        Err(e) => {
            let message = e.to_string();
            assert!(!message.contains('\n'), "two lines: {message:?}");
            return;
        }
    };
    let description = experiment.to_string();
    assert!(!description.contains('\n'), "{description:?}");
    if let Ok(params) = experiment.params() {
        params
            .validate()
            .expect("built parameters are inside the ranges");
        stickslip::limits::check_state(experiment.initial().y, experiment.initial().v)
            .expect("the initial state is inside the ranges");
        // The solver starts, and the units convert to finite numbers.
        let solver = experiment.solver().expect("a solver for valid parameters");
        assert_eq!(solver.time(), 0.0);
        if let Some(units) = experiment.units() {
            for x in units.convert(1.0, 1.0, 1.0, 1.0) {
                assert!(x.is_finite(), "{experiment}");
            }
        }
    }
}
