//! The model flags walk the library's key table: every key is accepted under its flag and
//! each of its aliases and reaches the experiment with its value; a value outside the key's
//! range is refused with the library's words, exit code 2, before any work.

use crate::common::*;
use stickslip::experiment::{ExperimentSpec, Key, KeyForm, Preset};
use stickslip::{DiodeModel, Number};

/// The parameters of the Stribeck and cubic friction laws: they need their law chosen, which
/// the descriptions below do not (tests/cli/belt.rs gives them).
const SMOOTH_LAW_KEYS: [Key; 9] = [
    Key::Vs,
    Key::Delta,
    Key::Eta,
    Key::K1,
    Key::K3,
    Key::StribeckSpeed,
    Key::ViscousFriction,
    Key::CubicK1,
    Key::CubicK3,
];

/// One value of a description: the key, its text on the command line and the number it
/// stands for (written out, so that the SI prefixes are checked too).
type Value = (Key, &'static str, f64);

/// Complete descriptions that, between them, give every numeric key a value other than its
/// default: dimensionless, a circuit with Shockley diodes, a mechanical oscillator.
fn descriptions() -> Vec<(Vec<Value>, Option<DiodeModel>)> {
    vec![
        (
            vec![
                (Key::Zeta, "0.05", 0.05),
                (Key::W, "0.9", 0.9),
                (Key::Beta, "2", 2.0),
                (Key::Phi, "0.1", 0.1),
                (Key::MuS, "1.2", 1.2),
                (Key::Y0, "0.1", 0.1),
                (Key::V0, "-0.2", -0.2),
                (Key::Vb, "0.3", 0.3),
            ],
            None,
        ),
        (
            vec![
                (Key::Inductance, "10m", 10e-3),
                (Key::Capacitance, "0.02u", 0.02e-6),
                (Key::Resistance, "60", 60.0),
                (Key::TurnOn, "0.6", 0.6),
                (Key::DiodeResistance, "2", 2.0),
                (Key::Amplitude, "1.5", 1.5),
                (Key::Frequency, "9.97k", 9.97e3),
                (Key::Uc0, "0.1", 0.1),
                (Key::I0, "1m", 1e-3),
                (Key::SaturationCurrent, "4n", 4e-9),
                (Key::Emission, "1.8", 1.8),
                (Key::SeriesResistance, "0.5", 0.5),
                (Key::Temperature, "30", 30.0),
            ],
            Some(DiodeModel::Shockley),
        ),
        (
            vec![
                (Key::Mass, "0.5", 0.5),
                (Key::Stiffness, "200", 200.0),
                (Key::Damping, "0.94", 0.94),
                (Key::Friction, "1", 1.0),
                (Key::Omega, "14", 14.0),
                (Key::Amplitude, "1.4", 1.4),
                (Key::BeltSpeed, "0.05", 0.05),
            ],
            None,
        ),
    ]
}

/// The experiment the library builds from these values, as every command describes it.
fn described(values: &[Value], diode: Option<DiodeModel>, preset: bool) -> String {
    let mut spec = ExperimentSpec::new();
    for &(key, _, value) in values {
        spec.set(key, value).expect("a value inside its range");
    }
    if let Some(diode) = diode {
        spec.set_diode(diode);
    }
    if preset {
        spec.set_preset(Preset::Paper);
    }
    spec.build().expect("a complete description").to_string()
}

/// Run `simulate` briefly with these flags; its description of the experiment (the first
/// line on standard error, after the command's name).
fn simulate_description(flags: &[String]) -> String {
    let mut args = vec!["simulate", "--periods", "0.1", "--samples-per-period", "1"];
    args.extend(flags.iter().map(String::as_str));
    let (_dir, out) = run(&args);
    let err = stderr(&out);
    assert_eq!(out.status.code(), Some(0), "{flags:?}: {err}");
    let first = err.lines().next().unwrap_or_default();
    first
        .strip_prefix("simulate: ")
        .unwrap_or_else(|| panic!("{flags:?}: {err}"))
        .to_string()
}

#[test]
fn every_key_is_accepted_under_its_flag_and_aliases_and_reaches_the_experiment() {
    let descriptions = descriptions();
    // The walk covers the table: every key a user types a number for has a value above,
    // the two named keys are given too.
    for key in Key::ALL {
        // The Stribeck and cubic laws' parameters need their law chosen (tests/cli/belt.rs).
        if SMOOTH_LAW_KEYS.contains(&key) {
            continue;
        }
        let numeric = key.form() != KeyForm::Choice;
        let covered = descriptions
            .iter()
            .any(|(values, _)| values.iter().any(|v| v.0 == key));
        assert_eq!(covered, numeric, "{key}: no value in the walk");
    }
    for (values, diode) in &descriptions {
        let mut flags: Vec<String> = Vec::new();
        for &(key, text, _) in values {
            flags.push(format!("--{}", key.flag()));
            flags.push(text.to_string());
        }
        if let Some(diode) = diode {
            flags.push(format!("--{}", Key::Diode.flag()));
            flags.push(diode.to_string());
        }
        let expected = described(values, *diode, false);
        assert_eq!(simulate_description(&flags), expected);
        // Each alias in place of the flag gives the same experiment.
        for (i, &(key, _, _)) in values.iter().enumerate() {
            for alias in key.aliases() {
                let mut spelled = flags.clone();
                spelled[2 * i] = format!("--{alias}");
                assert_eq!(simulate_description(&spelled), expected, "--{alias}");
            }
        }
    }
    // The preset, under its flag, with a drive over it.
    let drive = [(Key::W, "0.95", 0.95), (Key::Beta, "2.14", 2.14)];
    let flags: Vec<String> = [
        format!("--{}", Key::Preset.flag()),
        "paper".into(),
        "--w".into(),
        "0.95".into(),
        "--beta".into(),
        "2.14".into(),
    ]
    .into();
    assert_eq!(simulate_description(&flags), described(&drive, None, true));
}

/// A value outside the range of `key`, from the library's table, if it has one.
fn outside(key: Key) -> Option<f64> {
    let range = key.range();
    if range.min.is_finite() {
        Some(if range.min_inclusive {
            range.min - range.min.abs().max(1.0)
        } else {
            range.min
        })
    } else if range.max.is_finite() {
        Some(if range.max_inclusive {
            range.max + range.max.abs().max(1.0)
        } else {
            range.max
        })
    } else {
        None
    }
}

#[test]
fn every_key_refuses_a_value_outside_its_range_with_the_librarys_words() {
    for key in Key::ALL {
        if key.form() == KeyForm::Choice {
            continue;
        }
        let Some(value) = outside(key) else {
            // Only the initial state in volts and amperes takes any finite number: its
            // image in y0, v0 is checked when the experiment is built; so do the belt speed
            // and the cubic law's linear coefficient in physical units (their images vb, k1).
            assert!(
                matches!(key, Key::Uc0 | Key::I0 | Key::BeltSpeed | Key::CubicK1),
                "{key} has no range"
            );
            continue;
        };
        assert!(key.check(value).is_err(), "{key} {value}");
        let expected = format!(
            "invalid --{} {}: {}",
            key.flag(),
            Number(value),
            key.allowed()
        );
        let text = format!("{value:e}");
        let mut spellings = vec![key.flag()];
        spellings.extend(key.aliases());
        for spelling in spellings {
            let (dir, out) = run(&["steady", &format!("--{spelling}"), &text]);
            assert_usage_error(dir.path(), &out, &expected);
        }
    }
}

#[test]
fn a_value_that_is_not_a_number_is_refused_naming_the_flag() {
    for key in Key::ALL {
        if key.form() == KeyForm::Choice {
            continue;
        }
        let (dir, out) = run(&["steady", &format!("--{}", key.flag()), "nan"]);
        assert_usage_error(dir.path(), &out, &format!("--{}", key.flag()));
        assert!(stderr(&out).contains("'nan'"), "{}", stderr(&out));
    }
}

#[test]
fn a_name_that_is_not_the_librarys_is_refused_naming_the_flag() {
    for key in Key::ALL {
        if key.form() != KeyForm::Choice {
            continue;
        }
        let (dir, out) = run(&["steady", &format!("--{}", key.flag()), "nothing"]);
        assert_usage_error(dir.path(), &out, &format!("--{}", key.flag()));
        assert!(stderr(&out).contains("'nothing'"), "{}", stderr(&out));
        // Every name the library lists is taken.
        for name in key.choices() {
            let out = run_in(dir.path(), &["convert", &format!("--{}", key.flag()), name]);
            assert!(
                !stderr(&out).contains(&format!("invalid value '{name}'")),
                "{}",
                stderr(&out)
            );
        }
    }
}

/// A unit that is not the key's is refused, not read as the key's: `--freq 9.97kV`.
#[test]
fn a_unit_that_is_not_the_keys_is_refused() {
    let units = ["Hz", "ohm", "H", "F", "V", "A", "s", "N"];
    for key in Key::ALL {
        if key.form() != KeyForm::Si {
            continue;
        }
        let wrong = units
            .iter()
            .find(|u| !key.units().contains(u))
            .expect("a unit that is not the key's");
        let text = format!("2{wrong}");
        let (dir, out) = run(&["steady", &format!("--{}", key.flag()), &text]);
        assert_usage_error(dir.path(), &out, &format!("--{}", key.flag()));
        assert!(stderr(&out).contains(&text), "{}", stderr(&out));
        if let Some(&right) = key.units().first() {
            assert_eq!(key.number(&format!("2{right}")).unwrap(), 2.0);
        }
    }
}
