//! `/api/orbit`: the periodic orbit and its Floquet multipliers for the PWL and the Shockley
//! diodes and the mechanical oscillator, equal to the last bit to what `stickslip orbit
//! --json` computes (the same library calls), with the row of the orbits' table; an orbit
//! not found is `converged: false` with the library's line; bad options are a 400 naming the
//! key, a law the stability tools do not follow a 400 with the library's line; a belt
//! without a drive answers its self-excited cycle (with one period of it for the phase
//! plane) or steady sliding.

use super::{get, refused, spec};
use crate::api::CYCLE_SAMPLES;
use crate::query::{api_name, option_key, Query};
use axum::http::StatusCode;
use serde_json::Value;
use stickslip::experiment::{DiodeModel, Experiment, Key, Preset};
use stickslip::options::OptionKey;
use stickslip::physical::Mechanics;
use stickslip::report::{Columns, OrbitTable, Table};
use stickslip::stability::{NewtonOptions, OrbitReport};
use stickslip::steady::self_excited_trace;
use stickslip::Error;

/// The report of `stickslip orbit --json` with its default options for `e`: the same calls
/// as the command (`crates/stickslip-cli/src/commands/orbit.rs`).
fn cli_orbit(e: &Experiment) -> Result<OrbitReport, Error> {
    let default = |o: OptionKey| o.default_value().unwrap();
    let params = e.params()?;
    let dynamics = e.dynamics()?;
    let steady = e
        .steady_options()
        .with_max_periods(default(OptionKey::OrbitMaxPeriods) as usize)?
        .with_max_period(default(OptionKey::OrbitMaxPeriod) as usize)?;
    let newton = NewtonOptions {
        tolerance: default(OptionKey::NewtonTolerance),
        max_iterations: default(OptionKey::MaxIterations) as usize,
        ..NewtonOptions::default()
    };
    let orbit = e.periodic_orbit(None, 0, &steady, &newton, &())?;
    OrbitReport::of(&orbit, &params, dynamics.as_ref())
}

/// The mechanical example at the Fig. 3 point, as keys of the query and of the library.
fn mechanics() -> Vec<(Key, f64)> {
    let m = Mechanics::example();
    vec![
        (Key::Mass, m.mass),
        (Key::Stiffness, m.stiffness),
        (Key::Damping, m.damping),
        (Key::Friction, m.friction),
        (Key::W, 0.95),
        (Key::Beta, 2.14),
    ]
}

fn query(values: &[(Key, f64)]) -> String {
    values
        .iter()
        .map(|&(k, v)| format!("{}={v}", api_name(k)))
        .collect::<Vec<_>>()
        .join("&")
}

/// The answer's orbit is the library's report, bit for bit, and its table row and
/// arguments follow from it.
fn same_orbit(answer: &Value, report: &OrbitReport, what: &str) {
    assert_eq!(answer["converged"], true, "{what}: {answer}");
    assert_eq!(answer["reason"], Value::Null, "{what}");
    assert_eq!(
        answer["orbit"],
        serde_json::to_value(report).unwrap(),
        "{what}"
    );
    let table = OrbitTable {
        orbits: std::slice::from_ref(report),
    };
    assert_eq!(
        answer["table"],
        serde_json::to_value(Columns::of(&table)).unwrap(),
        "{what}"
    );
    let names: Vec<&str> = answer["table"]
        .as_object()
        .unwrap()
        .keys()
        .map(String::as_str)
        .collect();
    let mut expected = table.columns();
    let mut names: Vec<String> = names.into_iter().map(String::from).collect();
    names.sort_unstable();
    expected.sort_unstable();
    assert_eq!(names, expected, "{what}");
    for (k, m) in report.multipliers.iter().enumerate() {
        assert_eq!(
            answer["arguments"][k].as_f64().unwrap(),
            m.im.atan2(m.re),
            "{what}: arg μ{}",
            k + 1
        );
    }
}

#[tokio::test]
async fn the_orbit_is_the_cli_s_for_both_diode_laws_and_the_mechanical_oscillator() {
    let fig3 = [(Key::W, 0.95), (Key::Beta, 2.14)];
    for model in [DiodeModel::Pwl, DiodeModel::Shockley] {
        let uri = format!(
            "/api/orbit?preset=paper&{}&{}={}",
            query(&fig3),
            api_name(Key::Diode),
            model.label()
        );
        let (status, answer) = get(&uri).await;
        assert_eq!(status, StatusCode::OK, "{uri}: {answer}");
        let e = spec(Some(Preset::Paper), Some(model), &fig3);
        let report = cli_orbit(&e).unwrap();
        same_orbit(&answer, &report, model.label());
        assert_eq!(answer["model"], model.label());
        // The Fig. 3 (2b) orbit slides: a stable complex pair inside the unit circle.
        assert_eq!(report.period, 1);
        assert!(report.stable && report.moduli[0] < 1.0);
        assert!(report.multipliers[0].im > 0.0, "{:?}", report.multipliers);
    }
    let values = mechanics();
    let uri = format!("/api/orbit?{}", query(&values));
    let (status, answer) = get(&uri).await;
    assert_eq!(status, StatusCode::OK, "{uri}: {answer}");
    same_orbit(
        &answer,
        &cli_orbit(&spec(None, None, &values)).unwrap(),
        "mechanics",
    );
    assert_eq!(answer["system"], "mechanics");
}

#[tokio::test]
async fn a_period_and_a_transient_look_for_the_orbit_asked_for() {
    // The paper's circuit at (0.7, 1.2) from rest, Newton's method on the 1-fold map after 50
    // drive periods: `stickslip orbit --preset paper --w 0.7 --beta 1.2 --period 1
    // --transient 50`.
    let values = [(Key::W, 0.7), (Key::Beta, 1.2)];
    let uri = format!(
        "/api/orbit?preset=paper&{}&{}=1&{}=50",
        query(&values),
        option_key(OptionKey::OrbitPeriod),
        option_key(OptionKey::OrbitTransient)
    );
    let (status, answer) = get(&uri).await;
    assert_eq!(status, StatusCode::OK, "{uri}: {answer}");
    let e = spec(Some(Preset::Paper), None, &values);
    let orbit = e
        .periodic_orbit(
            Some(1),
            50,
            &e.steady_options(),
            &NewtonOptions::default(),
            &(),
        )
        .unwrap();
    let report =
        OrbitReport::of(&orbit, &e.params().unwrap(), e.dynamics().unwrap().as_ref()).unwrap();
    same_orbit(&answer, &report, "period 1 after 50");
}

#[tokio::test]
async fn no_orbit_found_is_not_converged_with_the_library_s_line() {
    // One Newton step cannot reach the tolerance from rest.
    let values = [(Key::W, 0.95), (Key::Beta, 2.14)];
    let uri = format!(
        "/api/orbit?preset=paper&{}&{}=1&{}=1",
        query(&values),
        option_key(OptionKey::OrbitPeriod),
        option_key(OptionKey::MaxIterations)
    );
    let (status, answer) = get(&uri).await;
    assert_eq!(status, StatusCode::OK, "{uri}: {answer}");
    let e = spec(Some(Preset::Paper), None, &values);
    let newton = NewtonOptions {
        max_iterations: 1,
        ..NewtonOptions::default()
    };
    let err = e
        .periodic_orbit(Some(1), 0, &e.steady_options(), &newton, &())
        .unwrap_err();
    assert!(matches!(err, Error::Stability(_)), "{err}");
    assert_eq!(answer["converged"], false);
    assert_eq!(answer["orbit"], Value::Null);
    assert_eq!(answer["table"], Value::Null);
    assert_eq!(answer["reason"], err.to_string());
    assert!(err.to_string().contains("did not converge"), "{err}");
    // The description is there all the same.
    assert_eq!(answer["model"], "pwl");
}

#[tokio::test]
async fn bad_options_name_their_key_and_a_refused_law_says_the_library_s_line() {
    let base = "/api/orbit?preset=paper&w=0.95&beta=2.14";
    for (option, value, needle) in [
        (OptionKey::OrbitPeriod, "0", "must be"),
        (OptionKey::OrbitPeriod, "two", "whole number"),
        (OptionKey::MaxIterations, "0", "must be"),
        (OptionKey::NewtonTolerance, "1", "must be"),
        (OptionKey::OrbitMaxPeriods, "5001", "5000"),
        (OptionKey::OrbitTransient, "100000", "5000"),
    ] {
        let key = option_key(option);
        let body = refused(
            &format!("{base}&{key}={value}"),
            StatusCode::BAD_REQUEST,
            needle,
        )
        .await;
        assert_eq!(body["field"], key, "{body}");
    }
    // A transient without a period (the steady state gives the guess): the rule between two
    // options, named as the query names them.
    let key = option_key(OptionKey::OrbitTransient);
    let body = refused(
        &format!("{base}&{key}=10"),
        StatusCode::BAD_REQUEST,
        option_key(OptionKey::OrbitPeriod),
    )
    .await;
    assert_eq!(body["field"], key);
    // A key's value, and a key no endpoint knows.
    let body = refused(
        "/api/orbit?preset=paper&w=0.95&beta=-1",
        StatusCode::BAD_REQUEST,
        "beta",
    )
    .await;
    assert_eq!(body["field"], "beta");
    refused(
        &format!("{base}&samples=64"),
        StatusCode::BAD_REQUEST,
        "samples",
    )
    .await;
    // The mechanical oscillator with the Stribeck law: the library's verdict on the same
    // experiment, its line if it refuses (a 400), its report if it follows the law.
    let mut q = query(&mechanics());
    q.push_str(&format!(
        "&{}=stribeck&{}=0.5",
        api_name(Key::FrictionLaw),
        api_name(Key::StribeckSpeed)
    ));
    let e = Query::parse(Some(&q)).unwrap().experiment().unwrap();
    let uri = format!("/api/orbit?{q}");
    match cli_orbit(&e) {
        Err(err @ Error::Unsupported(_)) => {
            let line = err.render(stickslip::options::Spelling::Query);
            let body = refused(&uri, StatusCode::BAD_REQUEST, &line).await;
            assert_eq!(body["error"], line);
        }
        Err(other) => panic!("{other}"),
        Ok(report) => same_orbit(&get(&uri).await.1, &report, "stribeck"),
    }
    // No drive: the missing value named.
    refused(
        "/api/orbit?preset=paper&w=0.95",
        StatusCode::BAD_REQUEST,
        "beta",
    )
    .await;
}

/// The mechanical example on a belt at 3 cm/s (vb = 0.3), μs = 1.5, without a drive.
const BELT: &str =
    "mass=0.5&stiffness=200&damping=0.94&friction=1&mu-s=1.5&belt-speed=0.03&freq=3&amplitude=0";

/// Without a drive on a belt the answer is the self-excited cycle of `stickslip orbit`
/// (the library's, to the last bit) with its period run again for the phase plane, or
/// steady sliding; a period (drive periods) is a 400 naming it.
#[tokio::test]
async fn a_belt_without_a_drive_answers_its_self_excited_cycle_or_steady_sliding() {
    let default = |o: OptionKey| o.default_value().unwrap() as usize;
    for (q, class) in [
        (BELT.to_string(), "stick-slip-cycle"),
        (
            format!("{BELT}&friction-law=stribeck&stribeck-speed=0.05"),
            "stick-slip-cycle",
        ),
        // Ten times faster (vb = 3): the block never sticks again after its release.
        (
            BELT.replace("belt-speed=0.03", "belt-speed=0.3"),
            "steady-sliding",
        ),
    ] {
        let e = Query::parse(Some(&q)).unwrap().experiment().unwrap();
        assert!(e.is_self_excited(), "{q}");
        let steady = e
            .steady_options()
            .with_max_periods(default(OptionKey::OrbitMaxPeriods))
            .unwrap()
            .with_max_period(default(OptionKey::OrbitMaxPeriod))
            .unwrap();
        let (status, answer) = get(&format!("/api/orbit?{q}")).await;
        assert_eq!(status, StatusCode::OK, "{q}: {answer}");
        assert_eq!(answer["converged"], true, "{q}");
        assert_eq!(answer["orbit"], Value::Null, "{q}");
        let settled = e.steady_with(&steady.with_spectrum(false)).unwrap();
        let library = e.self_excited_orbit(&steady).unwrap();
        assert_eq!(
            answer["self_excited"],
            serde_json::to_value(&library).unwrap(),
            "{q}"
        );
        assert_eq!(answer["self_excited"]["class"], class, "{q}");
        let Some(period) = library.cycle_period_tau else {
            // Steady sliding: no cycle to draw, its eigenvalues in the answer.
            assert_eq!(answer.get("cycle"), None, "{q}");
            assert_eq!(answer["self_excited"]["stability"], "stable");
            continue;
        };
        // The period in seconds for the mechanical oscillator, T/ω0.
        let omega0 = e.scales().unwrap().omega0;
        assert_eq!(library.cycle_period_s, Some(period / omega0));
        let multipliers = &answer["self_excited"]["multipliers"];
        assert_eq!(
            (multipliers[0]["re"].as_f64(), multipliers[1]["re"].as_f64()),
            (Some(1.0), Some(0.0))
        );
        // The phase plane: the cycle run again by the library, within its extremes.
        let samples = self_excited_trace(&e.factory(), &settled, CYCLE_SAMPLES)
            .unwrap()
            .unwrap();
        let column = |name: &str| -> Vec<f64> {
            answer["cycle"][name]
                .as_array()
                .unwrap()
                .iter()
                .map(|x| x.as_f64().unwrap())
                .collect()
        };
        assert_eq!(column("y"), samples.iter().map(|s| s.y).collect::<Vec<_>>());
        assert_eq!(column("v"), samples.iter().map(|s| s.v).collect::<Vec<_>>());
        assert_eq!(column("tau").len(), CYCLE_SAMPLES);
        assert!(column("y")
            .iter()
            .all(|&y| y >= library.y_min - 1e-9 && y <= library.y_max + 1e-9));
    }
    let body = refused(
        &format!("/api/orbit?{BELT}&{}=1", option_key(OptionKey::OrbitPeriod)),
        StatusCode::BAD_REQUEST,
        "invalid period 1: must be left out on a belt without a drive",
    )
    .await;
    assert_eq!(body["field"], option_key(OptionKey::OrbitPeriod));
}
