//! Tests of `stickslip convert`.

use crate::common::*;

fn json(args: &[&str]) -> serde_json::Value {
    let (_dir, out) = run(args);
    assert!(out.status.success(), "{}", stderr(&out));
    serde_json::from_str(&stdout(&out)).expect("valid JSON")
}

#[test]
fn paper_preset_gives_the_papers_numbers() {
    let v = json(&["convert", "--preset", "paper", "--json"]);
    assert_eq!(format!("{:.1}", v["omega0"].as_f64().unwrap()), "65938.0");
    assert_eq!(format!("{:.1}", v["alpha"].as_f64().unwrap()), "6173.9");
    let zeta = v["zeta"].as_f64().unwrap();
    assert!((zeta - 6173.913043478261 / (2.0 * 65938.0473395787)).abs() < 1e-12);
    assert!((v["Q"].as_f64().unwrap() - 1.0 / (2.0 * zeta)).abs() < 1e-9);
    assert!((v["f0"].as_f64().unwrap() - 65938.0473395787 / std::f64::consts::TAU).abs() < 1e-6);
    assert!(
        v.get("w").is_none() && v.get("beta").is_none(),
        "no drive, no w/beta"
    );
}

#[test]
fn drive_in_physical_units_converts_to_w_and_beta() {
    let f0 = 65938.0473395787 / std::f64::consts::TAU;
    let freq = format!("{}", 0.95 * f0);
    let v = json(&[
        "convert",
        "--preset",
        "paper",
        "--amplitude",
        "1.498",
        "--freq",
        &freq,
        "--json",
    ]);
    assert!((v["w"].as_f64().unwrap() - 0.95).abs() < 1e-9);
    assert!((v["beta"].as_f64().unwrap() - 2.14).abs() < 1e-12);
}

#[test]
fn components_with_si_prefixes_and_mechanics() {
    let v = json(&[
        "convert",
        "--inductance",
        "11.5mH",
        "--capacitance",
        "20nF",
        "--resistance",
        "68",
        "--ut",
        "0.7",
        "--rd",
        "3",
        "--json",
    ]);
    assert_eq!(format!("{:.1}", v["omega0"].as_f64().unwrap()), "65938.0");
    let m = json(&[
        "convert",
        "--mass",
        "2",
        "--stiffness",
        "8",
        "--damping",
        "0.4",
        "--friction",
        "0.5",
        "--json",
    ]);
    assert_eq!(m["omega0"].as_f64().unwrap(), 2.0);
    assert!((m["zeta"].as_f64().unwrap() - 0.05).abs() < 1e-15);
}

#[test]
fn text_output_names_the_values() {
    let (_dir, out) = run(&["convert", "--preset", "paper"]);
    assert!(out.status.success());
    let text = stdout(&out);
    for key in ["omega0", "f0", "alpha", "zeta", "Q"] {
        assert!(text.contains(key), "{key} missing in {text}");
    }
}

#[test]
fn bad_input_is_a_one_line_usage_error() {
    let cases: &[(&[&str], &str)] = &[
        (&["convert"], "physical description"),
        (&["convert", "--inductance", "1m"], "--capacitance"),
        (
            &["convert", "--preset", "paper", "--freq", "1k"],
            "amplitude",
        ),
        (
            &["convert", "--preset", "paper", "--resistance", "-5"],
            "--resistance",
        ),
        (&["convert", "--preset", "paper", "--ut", "0"], "--ut"),
        (
            &[
                "convert",
                "--mass",
                "1",
                "--stiffness",
                "1",
                "--damping",
                "0",
            ],
            "--friction",
        ),
        (
            &["convert", "--preset", "paper", "--mass", "1"],
            "mechanical",
        ),
    ];
    assert_usage_errors(&[], cases);
}

/// The description goes to standard error, as with every command; standard output holds the
/// numbers (text or JSON) alone.
#[test]
fn description_goes_to_standard_error_with_and_without_json() {
    for json in [false, true] {
        let mut args = vec!["convert", "--preset", "paper"];
        if json {
            args.push("--json");
        }
        let (_dir, out) = run(&args);
        assert!(out.status.success(), "{}", stderr(&out));
        let (text, err) = (stdout(&out), stderr(&out));
        assert!(err.starts_with("convert: "), "{err}");
        assert!(err.contains("11.5 mH") || err.contains("0.0115"), "{err}");
        assert!(!text.contains("convert:"), "{text}");
        if !json {
            assert!(text.starts_with("omega0 = "), "{text}");
        }
    }
}
