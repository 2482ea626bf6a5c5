//! Tests of `stickslip lyapunov`.

use crate::common::*;
use stickslip::experiment::Experiment;
use stickslip::stability::{LyapunovOptions, LyapunovReport};

fn json(args: &[&str]) -> serde_json::Value {
    let mut full = vec!["lyapunov", "--json"];
    full.extend_from_slice(args);
    let (_dir, out) = run(&full);
    assert!(out.status.success(), "{}", stderr(&out));
    serde_json::from_str(&stdout(&out)).expect("valid JSON")
}

#[test]
fn a_chaotic_point_has_a_positive_exponent_beyond_its_error() {
    let mut args = CHAOTIC.to_vec();
    args.extend(["--transient", "500", "--periods", "4000", "--blocks", "10"]);
    let v = json(&args);
    for key in [
        "lambda1",
        "lambda1_per_period",
        "lambda1_error",
        "class",
        "stops_per_period",
        "lambda2",
    ] {
        assert!(v.get(key).is_some(), "missing {key}: {v}");
    }
    assert_eq!(v["class"], "chaotic");
    let (lambda, error) = (
        v["lambda1"].as_f64().unwrap(),
        v["lambda1_error"].as_f64().unwrap(),
    );
    assert!(lambda > 4.0 * error && lambda > 1e-3, "{lambda} ± {error}");
    // It stops, so λ2 = −∞: null with the reason (JSON has no infinity).
    assert_eq!(v["lambda2"], serde_json::Value::Null);
    assert_eq!(v["lambda2_per_period"], serde_json::Value::Null);
    assert!(v["lambda2_reason"].as_str().unwrap().contains("stopped"));
    assert!(v["stops_per_period"].as_f64().unwrap() > 1.0);
    assert_eq!(v["block_means"].as_array().unwrap().len(), 10);
    // The library's report for the same input, bit for bit.
    let e = Experiment::dimensionless(0.0, 0.33, 9.0)
        .unwrap()
        .with_mu_s(3.0)
        .unwrap();
    let options = LyapunovOptions {
        transient_periods: 500,
        periods: 4000,
        blocks: 10,
        significance: 4.0,
        sequential: true,
    };
    let c = e.lyapunov(&options, &()).unwrap();
    let report = LyapunovReport::new(&c, &options, &e.params().unwrap()).unwrap();
    assert_eq!(v, serde_json::to_value(&report).unwrap());
}

#[test]
fn a_sliding_motion_contracts_with_a_finite_second_exponent() {
    let v = json(&[
        "--preset",
        "paper",
        "--w",
        "0.9",
        "--beta",
        "1.6",
        "--transient",
        "200",
        "--periods",
        "400",
    ]);
    // It has reached its period-1 sliding orbit.
    assert_eq!(
        (v["class"].as_str(), v["period"].as_u64()),
        (Some("periodic"), Some(1))
    );
    assert_eq!(v["verdict"], "contracting");
    assert_eq!(v["stops_per_period"], 0.0);
    let l2 = v["lambda2"].as_f64().expect("a number");
    assert!(l2 < v["lambda1"].as_f64().unwrap());
    assert_eq!(v["lambda2_reason"], serde_json::Value::Null);
}

#[test]
fn text_output_says_what_the_exponent_means() {
    let mut args = vec!["lyapunov"];
    args.extend_from_slice(&CHAOTIC);
    args.extend(["--transient", "200", "--periods", "2000"]);
    let (_dir, out) = run(&args);
    assert!(out.status.success(), "{}", stderr(&out));
    let text = stdout(&out);
    for needle in [
        "λ1 =",
        "chaotic",
        "λ2 = −∞",
        "stops per period",
        "halves agree: yes",
    ] {
        assert!(text.contains(needle), "'{needle}' not in {text}");
    }
    // With a physical description, the rate per second too.
    let (_dir, out) = run(&[
        &["lyapunov"][..],
        &PAPER,
        &["--periods", "400", "--transient", "100"],
    ]
    .concat());
    assert!(out.status.success(), "{}", stderr(&out));
    assert!(stdout(&out).contains("per second"), "{}", stdout(&out));
}

#[test]
fn bad_input_gives_one_line_and_exit_code_2() {
    let cases: &[(&[&str], &str)] = &[
        (&["--blocks", "3"], "--blocks"),
        (&["--blocks", "2"], "--blocks"),
        (&["--periods", "10"], "--periods"),
        (&["--periods", "0"], "--periods"),
        (&["--transient", "-5"], "--transient"),
        (&["--significance", "0"], "--significance"),
        (&["--significance", "nan"], "--significance"),
        (&["--beta", "-1"], "beta"),
        // Beyond the time range the solvers resolve (2^32/(2π)·w periods at w < 1).
        (&["--periods", "1000000000"], "too long"),
    ];
    assert_usage_errors(&[&["lyapunov"][..], &CHAOTIC].concat(), cases);
    let dir = tempfile::tempdir().unwrap();
    // A missing drive is named.
    let out = run_in(dir.path(), &["lyapunov", "--zeta", "0.1", "--w", "0.7"]);
    assert_usage_error(dir.path(), &out, "--beta");
}

#[test]
fn ctrl_c_stops_a_long_measurement() {
    let dir = tempfile::tempdir().unwrap();
    let args = [
        &["lyapunov"][..],
        &CHAOTIC,
        &["--periods", "100000000", "--json"],
    ]
    .concat();
    let (out, stopping) = interrupt_in(dir.path(), &args);
    assert!(!out.status.success());
    assert!(stderr(&out).contains("interrupted"), "{}", stderr(&out));
    assert!(out.stdout.is_empty());
    // It stops within 1000 periods, not at the end of 1e8 periods: counted in CPU time after
    // the signal (`interrupt_in`), which load does not stretch.
    assert!(
        stopping < std::time::Duration::from_secs(20),
        "{stopping:?} of CPU after the signal"
    );
}

#[test]
fn lyapunov_json_writes_null_not_the_string_minus_inf_for_lambda2() {
    let mut args = CHAOTIC.to_vec();
    args.extend(["--transient", "200", "--periods", "2000"]);
    let v = json(&args);
    assert!(v["lambda2"].is_null(), "{v}");
    assert!(v["lambda2_error"].is_null(), "{v}");
    assert!(v["lambda2_per_period"].is_null(), "{v}");
    assert!(
        v["lambda2_reason"].as_str().unwrap().contains("det J = 0"),
        "{v}"
    );
    assert!(!serde_json::to_string(&v).unwrap().contains("inf"));
}

#[test]
fn the_measurement_stops_when_the_verdict_is_decided_and_fixed_runs_to_the_cap() {
    let mut args = CHAOTIC.to_vec();
    args.extend(["--transient", "500", "--periods", "20000"]);
    let v = json(&args);
    assert_eq!(v["class"], "chaotic");
    assert_eq!(v["sequential"], true);
    assert_eq!(v["cap_periods"], 20000);
    let measured = v["periods"].as_u64().unwrap();
    assert!(measured < 20000, "stopped at {measured}");
    assert_eq!(v["block_means"].as_array().unwrap().len(), 20);
    // --fixed: the fixed measurement of the same length gives the same numbers.
    let measured = measured.to_string();
    args.extend(["--fixed"]);
    let fixed_args: Vec<&str> = args
        .iter()
        .map(|a| if *a == "20000" { measured.as_str() } else { a })
        .collect();
    let f = json(&fixed_args);
    assert_eq!(f["sequential"], false);
    assert_eq!(f["periods"], v["periods"]);
    assert_eq!(f["lambda1"], v["lambda1"]);
    assert_eq!(f["lambda1_error"], v["lambda1_error"]);
    // Text: says it stopped early.
    let mut text_args = vec!["lyapunov"];
    text_args.extend_from_slice(&CHAOTIC);
    text_args.extend(["--transient", "500", "--periods", "20000"]);
    let (_dir, out) = run(&text_args);
    assert!(stdout(&out).contains("stopped early"), "{}", stdout(&out));
}

#[test]
fn lyapunov_on_a_period_3_stick_slip_orbit_says_periodic_with_its_period() {
    // ζ = 0, μs = 3, β = 9, w = 0.42: from rest the motion reaches a period-3 orbit with
    // stops; it used to be called "contracting: ... not reached".
    let args = ["--zeta", "0", "--mu-s", "3", "--w", "0.42", "--beta", "9"];
    let v = json(&args);
    assert_eq!(v["class"], "periodic", "{v}");
    assert_eq!(v["period"], 3, "{v}");
    assert_eq!(v["verdict"], "contracting", "{v}");
    let lambda = v["lambda1"].as_f64().unwrap();
    assert!((-0.12..-0.10).contains(&lambda), "{lambda}");
    let mut text = vec!["lyapunov"];
    text.extend_from_slice(&args);
    let (_dir, out) = run(&text);
    let text = stdout(&out);
    assert!(
        text.contains("periodic with period 3 drive periods"),
        "{text}"
    );
    assert!(!text.contains("not reached"), "{text}");
    // A chaotic motion has no period.
    let v = json(&CHAOTIC);
    assert_eq!(
        (v["class"].as_str(), v["period"].is_null()),
        (Some("chaotic"), true)
    );
}
