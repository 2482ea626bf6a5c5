//! Tests of `stickslip orbit`.

use crate::common::*;
use stickslip::experiment::Experiment;
use stickslip::stability::{NewtonOptions, OrbitReport};
use stickslip::SteadyOptions;

fn json(args: &[&str]) -> serde_json::Value {
    let mut full = vec!["orbit", "--json"];
    full.extend_from_slice(args);
    let (_dir, out) = run(&full);
    assert!(out.status.success(), "{}", stderr(&out));
    serde_json::from_str(&stdout(&out)).expect("valid JSON")
}

#[test]
fn json_is_the_librarys_report_with_the_keys_of_the_issue() {
    let v = json(&["--preset", "paper", "--w", "0.7", "--beta", "1.2"]);
    for key in [
        "period",
        "multipliers",
        "stable",
        "iterations",
        "residuals",
        "events",
        "stops",
        "monodromy",
        "lambda1",
    ] {
        assert!(v.get(key).is_some(), "missing {key}: {v}");
    }
    assert_eq!(
        (v["period"].as_u64(), v["least_period"].as_u64()),
        (Some(1), Some(1))
    );
    assert_eq!(v["stable"], true);
    assert_eq!(v["stops_per_period"], 2.0);
    assert!(v["iterations"].as_u64().unwrap() <= 6);
    let mu = &v["multipliers"];
    assert!(mu[0]["re"].as_f64().unwrap() > 0.0 && mu[0]["im"] == 0.0);
    // The same numbers as the library, bit for bit.
    let e = Experiment::paper()
        .with_w(0.7)
        .unwrap()
        .with_beta(1.2)
        .unwrap();
    let orbit = e
        .periodic_orbit(
            None,
            0,
            &SteadyOptions::default(),
            &NewtonOptions::default(),
            &(),
        )
        .unwrap();
    let report = OrbitReport::new(&orbit, &e.params().unwrap()).unwrap();
    assert_eq!(v, serde_json::to_value(&report).unwrap());
}

#[test]
fn an_unstable_orbit_in_a_chaotic_window_is_found_with_a_period_and_a_guess() {
    let chaotic = CHAOTIC;
    // Without --period the motion does not repeat: a clear error, no output.
    let mut args = vec!["orbit"];
    args.extend_from_slice(&chaotic);
    let (_dir, out) = run(&args);
    assert_eq!(out.status.code(), Some(1));
    let err = stderr(&out);
    assert!(
        err.contains("found no period") && err.contains("--period"),
        "{err}"
    );
    // It says what the motion's exponent says.
    assert!(err.contains("chaotic: nearby motions separate"), "{err}");
    assert!(out.stdout.is_empty());
    // With it, from the state after a transient: the unstable period-1 orbit.
    let mut args = chaotic.to_vec();
    args.extend(["--period", "1", "--transient", "2000"]);
    let v = json(&args);
    assert_eq!(v["stable"], false);
    assert_eq!(v["stability"], "unstable");
    assert!(v["moduli"][0].as_f64().unwrap() > 1.0);
    assert!(v["lambda1"].as_f64().unwrap() > 0.0);
    // Asked for period 2, the same orbit twice: the report says it repeats after 1.
    let mut args = chaotic.to_vec();
    args.extend(["--period", "2", "--transient", "2000"]);
    let twice = json(&args);
    assert_eq!(
        (twice["period"].as_u64(), twice["least_period"].as_u64()),
        (Some(2), Some(1))
    );
    let square = v["moduli"][0].as_f64().unwrap().powi(2);
    assert!((twice["moduli"][0].as_f64().unwrap() - square).abs() < 1e-8 * square);
}

#[test]
fn text_output_explains_the_multipliers() {
    let (_dir, out) = run(&["orbit", "--preset", "paper", "--w", "0.7", "--beta", "1.2"]);
    assert!(out.status.success(), "{}", stderr(&out));
    let text = stdout(&out);
    for needle in [
        "periodic orbit of period 1 drive period",
        "multipliers",
        "stable",
        "attracts",
        "a stop erases the velocity perturbation",
    ] {
        assert!(text.contains(needle), "'{needle}' not in {text}");
    }
    // The description of the experiment goes to standard error.
    assert!(stderr(&out).contains("preset paper"));
    // Physical flags work as everywhere: the paper's circuit at 7346.056 Hz, 0.84 V.
    let v = json(&[
        "--preset",
        "paper",
        "--freq",
        "7346.056",
        "--amplitude",
        "0.84",
    ]);
    assert_eq!(v["stable"], true);
}

#[test]
fn bad_input_gives_one_line_and_exit_code_2() {
    let point = ["--zeta", "0.05", "--w", "0.7", "--beta", "1.2"];
    let cases: &[(&[&str], &str)] = &[
        (&["--period", "0"], "--period"),
        (&["--period", "1001"], "--period"),
        (&["--period", "x"], "--period"),
        (&["--transient", "10"], "--transient needs --period"),
        (&["--period", "1", "--transient", "-1"], "--transient"),
        (&["--max-periods", "0"], "--max-periods"),
        (&["--max-period", "65"], "--max-period"),
        (&["--newton-tolerance", "0"], "--newton-tolerance"),
        (&["--newton-tolerance", "nan"], "--newton-tolerance"),
        (&["--max-iterations", "0"], "--max-iterations"),
        (&["--mu-s", "0.5"], "mu"),
    ];
    assert_usage_errors(&[&["orbit"][..], &point].concat(), cases);
}

/// The paper's circuit with Shockley diodes at 3 kHz, 1.5 V: a period-1 orbit with two stops
/// per period.
const SHOCKLEY_STOPS: [&str; 8] = [
    "--preset",
    "paper",
    "--model",
    "shockley",
    "--freq",
    "3k",
    "--amplitude",
    "1.5",
];

/// Shockley diodes: the orbit of the stiff solver's map, with its multipliers, and the
/// Lyapunov measurement of the same motion: λ1 is ln|μ1|/T of the orbit it reached.
#[test]
fn shockley_orbits_and_exponents_are_the_stiff_solvers() {
    let dir = tempfile::tempdir().unwrap();
    let model = SHOCKLEY_STOPS;
    let out = run_in(dir.path(), &[&["orbit", "--json"][..], &model].concat());
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let orbit: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    assert_eq!(orbit["period"], 1);
    assert_eq!(orbit["stability"], "stable");
    assert_eq!(orbit["stops_per_period"], 2.0);
    let moduli = orbit["moduli"].as_array().unwrap();
    // The second multiplier of an orbit that stops is below the resolution of the map.
    assert!(moduli[1].as_f64().unwrap() < 1e-12 * moduli[0].as_f64().unwrap());
    let out = run_in(
        dir.path(),
        &[
            &[
                "lyapunov",
                "--json",
                "--transient",
                "100",
                "--periods",
                "400",
            ][..],
            &model,
        ]
        .concat(),
    );
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let lyapunov: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    assert_eq!(lyapunov["class"], "periodic");
    let (measured, exact) = (
        lyapunov["lambda1"].as_f64().unwrap(),
        orbit["lambda1"].as_f64().unwrap(),
    );
    assert!(
        (measured - exact).abs() <= 1e-6 * exact.abs(),
        "{measured} vs {exact}"
    );
    assert!(lyapunov["lambda2"].as_f64().unwrap() < measured);
}

#[test]
fn orbit_from_rest_at_zeta_0_w_0_5_beta_5_says_what_its_exponent_says_not_may_be_chaotic() {
    // A slow drift: no period within the search, and an exponent of a few −1e-5.
    let (_dir, out) = run(&["orbit", "--zeta", "0", "--w", "0.5", "--beta", "5"]);
    assert_eq!(out.status.code(), Some(1));
    let err = stderr(&out);
    assert!(!err.contains("chaotic"), "{err}");
    assert!(err.contains("largest Lyapunov exponent is -"), "{err}");
    assert!(err.contains("contracting"), "{err}");
    let exponent: f64 = err
        .split("exponent is ")
        .nth(1)
        .and_then(|s| s.split(' ').next())
        .and_then(|s| s.parse().ok())
        .unwrap_or_else(|| panic!("{err}"));
    assert!((-1e-4..-1e-6).contains(&exponent), "{exponent}");
}

#[test]
fn orbit_at_the_edge_of_the_neutral_family_at_zeta_0_w_half_is_neutral_not_stable() {
    let args = [
        "--period",
        "1",
        "--zeta",
        "0",
        "--w",
        "0.5",
        "--beta",
        "5",
        "--phi",
        "3.64159265358979",
        "--y0=-6.4",
        "--v0=1.0",
    ];
    let v = json(&args);
    assert_eq!(v["stability"], "neutral", "{v}");
    let (_dir, out) = run(&[&["orbit"][..], &args[..]].concat());
    assert!(out.status.success(), "{}", stderr(&out));
    let text = stdout(&out);
    assert!(
        text.contains("goes to 1 as Newton's method goes on"),
        "{text}"
    );
}

/// The JSON of any command (`--json` added).
fn command_json(args: &[&str]) -> serde_json::Value {
    let mut full = args.to_vec();
    full.push("--json");
    let (_dir, out) = run(&full);
    assert!(out.status.success(), "{full:?}: {}", stderr(&out));
    serde_json::from_str(&stdout(&out)).expect("valid JSON")
}

/// Without a drive on a belt (β = 0) the orbit is `steady`'s self-excited cycle: its own
/// period (in seconds too for the mechanical oscillator), the multipliers 1 and exactly 0;
/// steady sliding with its eigenvalues; `lyapunov` names a limit cycle, not a torus; --period
/// (drive periods) refused.
#[test]
fn a_self_excited_belts_orbit_is_steadys_cycle() {
    let belt = [
        "--vb", "0.3", "--mu-s", "1.5", "--zeta", "0.05", "--beta", "0",
    ];
    let orbit = command_json(&[&["orbit"], &belt[..]].concat());
    let steady = command_json(&[&["steady"], &belt[..]].concat());
    let tau = orbit["cycle_period_tau"].as_f64().unwrap();
    let want = steady["cycle_period_tau"].as_f64().unwrap();
    assert!((tau - want).abs() < 1e-8, "{tau} against {want}");
    for key in ["y_max", "y_min", "stick_fraction"] {
        let (a, b) = (orbit[key].as_f64().unwrap(), steady[key].as_f64().unwrap());
        assert!((a - b).abs() < 1e-8, "{key}: {a} against {b}");
    }
    assert_eq!(orbit["class"], "stick-slip-cycle");
    let summary = orbit["summary"].as_str().unwrap();
    assert!(
        summary.starts_with("self-excited cycle, period 7.18283"),
        "{summary}"
    );
    let mu = &orbit["multipliers"];
    assert_eq!(
        (mu[0]["re"].as_f64(), mu[1]["re"].as_f64()),
        (Some(1.0), Some(0.0))
    );
    assert_eq!(orbit["release_y"].as_f64(), Some(1.5 - 2.0 * 0.05 * 0.3));
    let (_dir, out) = run(&[&["orbit"], &belt[..]].concat());
    assert!(out.status.success(), "{}", stderr(&out));
    let text = stdout(&out);
    assert!(
        text.starts_with("self-excited cycle, period 7.18283"),
        "{text}"
    );
    assert!(text.contains("μ2 = 0 exactly"), "{text}");
    // No drive: no drive periods to count (the library's refusal, a usage error).
    let (_dir, out) = run(&[&["orbit"], &belt[..], &["--period", "1"]].concat());
    assert_eq!(out.status.code(), Some(2));
    assert!(
        stderr(&out).contains("invalid --period 1: must be left out on a belt without a drive"),
        "{}",
        stderr(&out)
    );
    // lyapunov: a limit cycle (λ1 = 0 within its error, λ2 = −∞ from the stops).
    let l = command_json(&[&["lyapunov"], &belt[..]].concat());
    assert_eq!(
        (&l["class"], &l["verdict"]),
        (&"limit-cycle".into(), &"limit-cycle".into())
    );
    assert!(l["lambda2"].is_null() && l["period"].is_null(), "{l}");
    // Faster than the static friction falls off (vb = 2): steady sliding, both exponents
    // negative, and its eigenvalues −ζ ± i√(1 − ζ²) in orbit.
    let sliding = [
        "--vb", "2", "--mu-s", "1.5", "--zeta", "0.05", "--beta", "0",
    ];
    let l = command_json(&[&["lyapunov"], &sliding[..]].concat());
    assert_eq!(l["class"], "equilibrium");
    for key in ["lambda1", "lambda2"] {
        let x = l[key].as_f64().unwrap();
        assert!((x + 0.05).abs() < 1e-4, "{key}: {x}");
    }
    let o = command_json(&[&["orbit"], &sliding[..]].concat());
    assert_eq!(
        (&o["class"], &o["stability"]),
        (&"steady-sliding".into(), &"stable".into())
    );
    let e = &o["sliding_eigenvalues"][0];
    assert_eq!(e["re"].as_f64(), Some(-0.05));
    assert!((e["im"].as_f64().unwrap() - (1.0f64 - 0.0025).sqrt()).abs() < 1e-15);
}

/// The mechanical oscillator's self-excited cycle has its period in seconds, T/ω0.
#[test]
fn a_mechanical_belts_cycle_period_is_in_seconds_too() {
    // m = 0.1 kg, k = 1000 N/m: ω0 = 100 rad/s.
    let v = command_json(&[
        "orbit",
        "--mass",
        "0.1",
        "--stiffness",
        "1000",
        "--damping",
        "0.5",
        "--friction",
        "2",
        "--mu-s",
        "1.4",
        "--belt-speed",
        "0.02",
    ]);
    let tau = v["cycle_period_tau"].as_f64().unwrap();
    let seconds = v["cycle_period_s"].as_f64().unwrap();
    assert!((seconds - tau / 100.0).abs() < 1e-12 * seconds, "{v}");
}

/// A pure-slip cycle (the cubic law about unstable steady sliding, started near it) has its
/// nontrivial multiplier: the library's (tested against its return map's differences in
/// `tests/self_excited_orbit.rs`), in the JSON and in words, between 0 and 1 (attracting).
#[test]
fn a_pure_slip_cycles_orbit_has_its_multiplier() {
    let belt = [
        "orbit",
        "--vb",
        "0.65",
        "--mu-s",
        "1.5",
        "--zeta",
        "0.05",
        "--beta",
        "0",
        "--friction-law",
        "cubic",
        "--k1",
        "0.5",
        "--k3",
        "0.3",
        "--y0",
        "1.25",
        "--v0",
        "0.05",
    ];
    let orbit = command_json(&belt);
    assert_eq!(
        (&orbit["class"], &orbit["stability"]),
        (&"pure-slip-cycle".into(), &"stable".into())
    );
    let mu = &orbit["multipliers"];
    assert_eq!(mu[0]["re"].as_f64(), Some(1.0));
    let mu2 = mu[1]["re"].as_f64().unwrap();
    assert!(0.0 < mu2 && mu2 < 1.0, "{orbit}");
    let (_dir, out) = run(&belt);
    assert!(out.status.success(), "{}", stderr(&out));
    let text = stdout(&out);
    assert!(
        text.contains("μ2 is the derivative of the return map"),
        "{text}"
    );
    assert!(!text.contains("not computed"), "{text}");
}

/// Why μ2 vanishes on an orbit that stops is told in the words of the model at hand: a cubic
/// law's orbit on a belt (the tools' cubic belt at w = 1, β = 2: two stops per period,
/// μ2 = 0) by its stops, with no word of diodes; the Shockley pair's orbit (two stops, μ2
/// below the map's resolution) by the diodes' slope.
#[test]
fn mu2_is_explained_by_the_model_at_hand() {
    use crate::belt_tools::CUBIC;
    let cubic = [&["orbit", "--w", "1", "--beta", "2"][..], CUBIC].concat();
    let json = command_json(&cubic);
    assert_eq!(json["stops_per_period"], 2.0, "{json}");
    assert_eq!(json["moduli"][1].as_f64(), Some(0.0), "{json}");
    let (_dir, out) = run(&cubic);
    assert!(out.status.success(), "{}", stderr(&out));
    let text = stdout(&out);
    assert!(
        text.contains("μ2 = 0 because the orbit stops")
            && text.contains("a stop of the friction law erases the velocity perturbation"),
        "{text}"
    );
    assert!(!text.to_lowercase().contains("diode"), "{text}");
    let (_dir, out) = run(&[&["orbit"][..], &SHOCKLEY_STOPS].concat());
    assert!(out.status.success(), "{}", stderr(&out));
    let text = stdout(&out);
    assert!(
        text.contains("μ2 ≈ 0 because the orbit stops")
            && text.contains("the diodes' slope (about n V_T/(2 I_s), megohms)"),
        "{text}"
    );
    assert!(!text.contains("friction law"), "{text}");
}
