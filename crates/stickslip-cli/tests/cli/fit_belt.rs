//! `stickslip fit` of a mechanical oscillator on a belt with its friction law's parameters
//! free (the fit itself: the library's tests/fit_belt.rs, and docs/fit.md's worked example,
//! which the docs' test runs): a law's parameter that the oscillator's law does not have, or
//! on a circuit, is refused in one line with exit status 2, before a file is read.

use super::common::assert_usage_errors;

const OSCILLATOR: [&str; 10] = [
    "--mass",
    "0.5",
    "--stiffness",
    "200",
    "--damping",
    "0.8",
    "--friction",
    "0.3",
    "--belt-speed",
    "0.009",
];

#[test]
fn a_friction_laws_parameter_without_that_law_is_refused_in_one_line() {
    let coulomb = [&OSCILLATOR[..], &["--data", "stick.csv"]].concat();
    let with =
        |free: &'static str| -> Vec<&'static str> { [&coulomb[..], &["--free", free]].concat() };
    let (a, b) = (with("mu-s,stribeck-speed"), with("viscous-friction"));
    assert_usage_errors(
        &["fit"],
        &[
            (
                &a,
                "stribeck-speed is a parameter of the stribeck friction law, and this \
                 oscillator's law is coulomb (a coulomb belt's friction is fitted by friction \
                 and mu-s)",
            ),
            (
                &b,
                "viscous-friction is a parameter of the stribeck friction law",
            ),
            (
                &[
                    "--preset",
                    "paper",
                    "--free",
                    "stribeck-speed",
                    "--data",
                    "x.csv",
                ],
                "stribeck-speed is not a parameter of a circuit",
            ),
        ],
    );
}

/// Undriven records (the displacement alone): refused in one line, exit status 2, beside a
/// driven record, on an oscillator without a belt, and with starting values whose motion
/// is steady sliding; --from-rest and a record's own belt speed (FILE@SPEED) given with a
/// driven record (the fit itself: the library's tests/fit_belt_free.rs and docs/fit.md's
/// worked example).
#[test]
fn undriven_records_the_fit_cannot_take_are_refused_in_one_line() {
    let root = std::path::PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../..");
    let free = root.join("examples/fit/undriven/stribeck.csv");
    let driven = root.join("examples/fit/belt/stick.csv");
    let (free, driven) = (free.to_str().unwrap(), driven.to_str().unwrap());
    let belt = [&OSCILLATOR[..], &["--free", "mu-s", "--data", free]].concat();
    let mixed = [&belt[..], &["--data", driven]].concat();
    let still = [&OSCILLATOR[..8], &["--free", "mu-s", "--data", free]].concat();
    let sliding = [
        &OSCILLATOR[..8],
        &[
            "--belt-speed",
            "0.09",
            "--friction-law",
            "stribeck",
            "--stribeck-speed",
            "0.015",
            "--mu-s",
            "1.5",
            "--free",
            "mu-s",
            "--data",
            free,
        ],
    ]
    .concat();
    assert_usage_errors(
        &["fit"],
        &[
            (&mixed, "has no drive and"),
            (
                &still,
                "an undriven record needs a moving belt (--belt-speed)",
            ),
            (
                &sliding,
                "at the starting values the block slides steadily on the belt",
            ),
        ],
    );
    // --from-rest and a record's own belt speed (FILE@SPEED) are for undriven records.
    let from_rest = [
        &OSCILLATOR[..],
        &["--free", "mu-s", "--from-rest", "--data", driven],
    ]
    .concat();
    let own_speed = format!("{driven}@0.018");
    let driven_speed = [&OSCILLATOR[..], &["--free", "mu-s", "--data", &own_speed]].concat();
    assert_usage_errors(
        &["fit"],
        &[
            (&from_rest, "--from-rest is for records of an undriven belt"),
            (
                &driven_speed,
                "a belt speed of its own (FILE@SPEED) is for a record of an undriven belt",
            ),
        ],
    );
}
