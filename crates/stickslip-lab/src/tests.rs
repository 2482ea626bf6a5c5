//! Requests straight to the router (no socket): answers equal the library's (and so the
//! command-line tool's) for the same point; bad input, caps and unknown paths are refused
//! with one line of JSON; the time limit stops a computation.

mod belt;
mod connections;
mod curve;
mod orbit;
mod page_keys;

use super::router::{router, Lab, Settings};
use axum::body::Body;
use axum::http::{Request, StatusCode};
use serde_json::Value;
use std::time::Duration;
use stickslip::experiment::{DiodeModel, Experiment, ExperimentSpec, Key, Preset};
use stickslip::report::{MapReport, SweepReport};
use stickslip::scan::{Axis, Grid, ParameterRange, Sweep, SweepDirection};
use stickslip::solver::{grid, sample_at};
use stickslip::steady::SteadyReport;
use stickslip::theory::TheoryReport;
use stickslip::Parameter;
use stickslip_testkit::{
    driven, quantise, rigol, sample_steady, truth, Rng, Synthetic, TRUE_R, TRUE_UT,
};
use tower::ServiceExt;

/// The experiment of a preset, a diode law and values, as the library builds it.
fn spec(preset: Option<Preset>, diode: Option<DiodeModel>, values: &[(Key, f64)]) -> Experiment {
    let mut spec = ExperimentSpec::new();
    if let Some(p) = preset {
        spec.set_preset(p);
    }
    if let Some(d) = diode {
        spec.set_diode(d);
    }
    for &(key, value) in values {
        spec.set(key, value).unwrap();
    }
    spec.build().unwrap()
}

/// The experiment of a query's model keys, as the library builds it from the same texts.
fn experiment(query: &str) -> Experiment {
    let mut spec = ExperimentSpec::new();
    for (name, text) in form_urlencoded::parse(query.as_bytes()) {
        let key = Key::ALL
            .into_iter()
            .find(|k| k.flag() == name)
            .unwrap_or_else(|| panic!("{name} is a model key"));
        spec.set_text(key, &text).unwrap();
    }
    spec.build().unwrap()
}

fn lab(time_limit: Duration) -> Lab {
    Lab::new(Settings {
        time_limit,
        jobs: 2,
        verbose: false,
        hosts: vec!["192.0.2.7".into(), "lab.school.example".into()],
        hold: None,
    })
}

/// Wait until `lab` runs `count` computations (polled). A stop takes one check of the
/// solvers; the bound (600 s) is on a hang, not on the machine's load.
async fn until_active(lab: &Lab, count: usize) -> bool {
    let give_up = tokio::time::Instant::now() + Duration::from_secs(600);
    while lab.active() != count {
        if tokio::time::Instant::now() > give_up {
            return false;
        }
        tokio::time::sleep(Duration::from_millis(20)).await;
    }
    true
}

/// GET `uri` from a fresh router; status, content type and body.
async fn get_with(lab: &Lab, uri: &str) -> (StatusCode, String, Vec<u8>) {
    let response = router(lab.clone())
        .oneshot(Request::get(uri).body(Body::empty()).unwrap())
        .await
        .unwrap();
    let status = response.status();
    let content_type = response
        .headers()
        .get("content-type")
        .map(|v| v.to_str().unwrap().to_string())
        .unwrap_or_default();
    let body = axum::body::to_bytes(response.into_body(), usize::MAX)
        .await
        .unwrap()
        .to_vec();
    (status, content_type, body)
}

async fn get(uri: &str) -> (StatusCode, Value) {
    let (status, content_type, body) = get_with(&lab(Duration::from_secs(60)), uri).await;
    assert_eq!(content_type, "application/json", "{uri}");
    (status, serde_json::from_slice(&body).unwrap())
}

/// A 400 (or `status`) with one line of error, naming `needle`.
async fn refused(uri: &str, status: StatusCode, needle: &str) -> Value {
    let (got, body) = get(uri).await;
    assert_eq!(got, status, "{uri}: {body}");
    let message = body["error"].as_str().expect("an error message");
    assert!(!message.contains('\n'), "{uri}: {message}");
    assert!(
        message.contains(needle),
        "{uri}: '{needle}' not in '{message}'"
    );
    body
}

/// Every key of `expected` has the same value in `answer`.
fn same_keys(answer: &Value, expected: &Value) {
    let expected = expected.as_object().unwrap();
    assert!(!expected.is_empty());
    for (key, value) in expected {
        assert_eq!(&answer[key], value, "key {key}");
    }
}

#[tokio::test]
async fn steady_equals_the_library_and_the_cli_for_the_same_point() {
    // Dimensionless keys on the paper's circuit.
    let (status, answer) = get("/api/steady?preset=paper&w=0.95&beta=2.14").await;
    assert_eq!(status, StatusCode::OK, "{answer}");
    let e = Experiment::paper()
        .with_w(0.95)
        .unwrap()
        .with_beta(2.14)
        .unwrap();
    let steady = e.steady().unwrap();
    same_keys(
        &answer,
        &serde_json::to_value(SteadyReport::from(&steady)).unwrap(),
    );
    assert_eq!(answer["class"], "sliding");

    // Physical keys with SI prefixes, against the experiment the library builds from the same
    // values (`stickslip steady --preset paper --freq 9.97k --amplitude 1.498 --json`).
    let (status, answer) =
        get("/api/steady?preset=paper&freq=9.97k&amplitude=1.498&samples=256").await;
    assert_eq!(status, StatusCode::OK, "{answer}");
    let e = spec(
        Some(Preset::Paper),
        None,
        &[(Key::Frequency, 9970.0), (Key::Amplitude, 1.498)],
    );
    let steady = e.steady().unwrap();
    same_keys(
        &answer,
        &serde_json::to_value(SteadyReport::from(&steady)).unwrap(),
    );
    assert_eq!(answer["experiment"], e.to_string());
    assert_eq!(answer["drive"]["f_Hz"].as_f64().unwrap(), 9970.0);

    // The trace: the recorded cycle at 256 samples per period, in volts and amperes too.
    let trace = &answer["trace"];
    assert_eq!(trace["samples_per_period"], 256);
    let column = |name: &str| -> Vec<f64> {
        trace["columns"][name]
            .as_array()
            .unwrap_or_else(|| panic!("column {name}"))
            .iter()
            .map(|v| v.as_f64().unwrap())
            .collect()
    };
    let (y, uc, i, v) = (column("y"), column("uc_V"), column("i_A"), column("v"));
    assert_eq!(y.len(), 256 * steady.recorded_periods);
    let stride = steady.trace.len() / y.len();
    let scales = e.scales().unwrap();
    for k in 0..y.len() {
        assert_eq!(y[k], steady.trace[k * stride].y);
        assert_eq!(uc[k], y[k] * scales.position);
        assert_eq!(i[k], v[k] * scales.velocity);
    }
    assert_eq!(answer["columns"][1], "uc_V");
}

#[tokio::test]
async fn shockley_and_mechanics_answer_as_the_library() {
    let (status, answer) =
        get("/api/steady?preset=paper&model=shockley&w=0.95&beta=2.14&diode-n=1.8").await;
    assert_eq!(status, StatusCode::OK, "{answer}");
    let e = spec(
        Some(Preset::Paper),
        Some(DiodeModel::Shockley),
        &[(Key::W, 0.95), (Key::Beta, 2.14), (Key::Emission, 1.8)],
    );
    let steady = e.steady().unwrap();
    same_keys(
        &answer,
        &serde_json::to_value(SteadyReport::from(&steady)).unwrap(),
    );
    assert_eq!(answer["model"], "shockley");
    // A Shockley motion that has not repeated is measured by the stiff solver's tangent
    // dynamics, as the library's steady state (`stickslip steady --json`).
    let (status, answer) =
        get("/api/steady?preset=paper&model=shockley&w=1.1&beta=3.61&max-periods=2").await;
    assert_eq!(status, StatusCode::OK, "{answer}");
    let e = spec(
        Some(Preset::Paper),
        Some(DiodeModel::Shockley),
        &[(Key::W, 1.1), (Key::Beta, 3.61)],
    );
    let options = e.steady_options().with_max_periods(2).unwrap();
    let report =
        serde_json::to_value(SteadyReport::from(&e.steady_with(&options).unwrap())).unwrap();
    assert!(answer["period"].is_null() && answer["lambda1"].as_f64().unwrap() < 0.0);
    for key in ["lambda1", "lambda1_error", "verdict"] {
        assert_eq!(answer[key], report[key], "{key}");
    }

    let query = "mass=0.5&stiffness=200&damping=0.94&friction=1&mu-s=1.5&w=0.7&beta=1.4";
    let (status, answer) = get(&format!("/api/steady?{query}")).await;
    assert_eq!(status, StatusCode::OK, "{answer}");
    let e = experiment(query);
    let steady = e.steady().unwrap();
    same_keys(
        &answer,
        &serde_json::to_value(SteadyReport::from(&steady)).unwrap(),
    );
    assert_eq!(answer["system"], "mechanics");
    assert_eq!(answer["columns"][1], "r_m");
}

#[tokio::test]
async fn theory_equals_the_library() {
    let (status, answer) = get("/api/theory?preset=paper&w=0.9&beta=1.43").await;
    assert_eq!(status, StatusCode::OK, "{answer}");
    let params = Experiment::paper()
        .with_w(0.9)
        .unwrap()
        .with_beta(1.43)
        .unwrap()
        .params()
        .unwrap();
    let expected = serde_json::to_value(TheoryReport::new(&params).unwrap()).unwrap();
    assert_eq!(answer, expected);
}

/// The keys of `answer` that `report` has, with their values: the report inside an answer
/// beside the experiment's description.
fn report_part(answer: &Value, report: &Value) -> Value {
    let answer = answer.as_object().unwrap();
    let report = report.as_object().unwrap();
    Value::Object(
        report
            .keys()
            .filter_map(|k| answer.get(k).map(|v| (k.clone(), v.clone())))
            .collect(),
    )
}

#[tokio::test]
async fn simulate_is_the_library_trajectory_report() {
    let (status, answer) =
        get("/api/simulate?preset=paper&w=0.7&beta=1.2&periods=3&samples=50").await;
    assert_eq!(status, StatusCode::OK, "{answer}");
    let e = Experiment::paper()
        .with_w(0.7)
        .unwrap()
        .with_beta(1.2)
        .unwrap();
    // The report's shape, every key: the answer is the library's trajectory report beside the
    // description.
    let report = e.trajectory(3.0, 50).unwrap().collect_report().unwrap();
    let expected = serde_json::to_value(&report).unwrap();
    assert_eq!(report_part(&answer, &expected), expected);
    // The paper's circuit: the physical columns follow the dimensionless ones.
    assert_eq!(
        answer["columns"],
        serde_json::json!(["tau", "y", "v", "drive", "phase", "t_s", "uc_V", "i_A", "u_V"])
    );
    // The samples and events of one pass of the solver over the grid.
    let mut solver = e.solver().unwrap();
    let times = grid(0.0, 3.0 * e.params().unwrap().drive_period(), 150);
    let mut events = Vec::new();
    let samples = sample_at(solver.as_mut(), &times, |ev| events.push(*ev)).unwrap();
    let y: Vec<f64> = answer["y"]
        .as_array()
        .unwrap()
        .iter()
        .map(|v| v.as_f64().unwrap())
        .collect();
    assert_eq!(y, samples.iter().map(|s| s.y).collect::<Vec<_>>());
    assert_eq!(answer["events"].as_array().unwrap().len(), events.len());
    assert!(events.iter().any(|e| e.kind == stickslip::EventKind::Stick));
    assert_eq!(answer["phase"][0], samples[0].phase.label());
    assert_eq!(answer["experiment"], e.to_string());

    // A physical description: the physical columns at the top level, named in `columns`.
    let (status, answer) =
        get("/api/simulate?preset=paper&freq=9.97k&amplitude=1.498&periods=2&samples=40").await;
    assert_eq!(status, StatusCode::OK, "{answer}");
    let e = spec(
        Some(Preset::Paper),
        None,
        &[(Key::Frequency, 9970.0), (Key::Amplitude, 1.498)],
    );
    let expected =
        serde_json::to_value(e.trajectory(2.0, 40).unwrap().collect_report().unwrap()).unwrap();
    assert_eq!(report_part(&answer, &expected), expected);
    assert_eq!(answer["columns"][6], "uc_V");
    assert_eq!(answer["uc_V"].as_array().unwrap().len(), 81);
    assert!(answer.get("trace").is_none());
}

#[tokio::test]
async fn sweep_and_map_equal_the_library() {
    let (status, answer) =
        get("/api/sweep?preset=paper&beta=3.61&over=w&from=0.5&to=1.5&steps=5&direction=both")
            .await;
    assert_eq!(status, StatusCode::OK, "{answer}");
    let e = Experiment::paper().with_beta(3.61).unwrap();
    let range = ParameterRange::new("w", 0.5, 1.5, 5).unwrap();
    let options = e.steady_options().with_harmonics(3).unwrap();
    let points = Sweep::new(&e, Axis::range(Parameter::W, &range).unwrap())
        .unwrap()
        .direction(SweepDirection::Both)
        .options(options)
        .unwrap()
        .run(&())
        .unwrap();
    // The library's sweep report, row for row and key for key (`stickslip sweep --json`).
    let report = serde_json::to_value(SweepReport::new(
        &e,
        Parameter::W,
        SweepDirection::Both,
        &points,
    ))
    .unwrap();
    assert_eq!(report_part(&answer, &report), report);
    let rows = answer["points"].as_array().unwrap();
    assert_eq!(rows.len(), points.len());
    for (row, p) in rows.iter().zip(&points) {
        assert_eq!(row["value"].as_f64().unwrap(), p.value);
        assert_eq!(row["direction"], p.leg.label());
        assert_eq!(row["gain"].as_f64().unwrap(), p.steady.gain);
        assert_eq!(row["A1"].as_f64(), p.steady.harmonic(1));
        assert_eq!(row["class"], p.steady.class.label());
    }
    assert_eq!(answer["over"], "w");
    assert_eq!(answer["direction"], "both");
    assert!(answer["theory"]["x"].as_array().unwrap().len() >= 200);

    let (status, answer) = get(
        "/api/map?preset=paper&w-min=0.3&w-max=1.5&w-steps=4&beta-min=0.8&beta-max=3&beta-steps=3",
    )
    .await;
    assert_eq!(status, StatusCode::OK, "{answer}");
    let w = ParameterRange::new("w", 0.3, 1.5, 4).unwrap();
    let beta = ParameterRange::new("beta", 0.8, 3.0, 3).unwrap();
    let map = Grid::new(
        &Experiment::paper(),
        Axis::range(Parameter::W, &w).unwrap(),
        Axis::range(Parameter::Beta, &beta).unwrap(),
    )
    .unwrap()
    .run(&())
    .unwrap();
    // The library's map report itself, key for key and row for row (the shape of
    // `stickslip phase-diagram`'s CSV), beside the grid's axes.
    let report = serde_json::to_value(MapReport::new(&map.points, false)).unwrap();
    assert_eq!(report_part(&answer, &report), report);
    let rows = answer["points"].as_array().unwrap();
    assert_eq!(rows.len(), 12);
    let nb = answer["beta"].as_array().unwrap().len();
    for (k, row) in rows.iter().enumerate() {
        assert_eq!(answer["w"][k / nb], row["w"], "point {k}");
        assert_eq!(answer["beta"][k % nb], row["beta"], "point {k}");
        let keys: Vec<&str> = row
            .as_object()
            .unwrap()
            .keys()
            .map(String::as_str)
            .collect();
        let mut columns = stickslip::report::MapRow::columns(false);
        columns.sort_unstable();
        assert_eq!(keys, columns, "{row}");
    }
    // No columns of its own beside the report's.
    for old in ["classes", "class", "period", "stops_per_period", "gain"] {
        assert!(answer.get(old).is_none(), "{old}");
    }
}

#[tokio::test]
async fn bad_input_is_refused_with_one_line_naming_the_key() {
    let bad = StatusCode::BAD_REQUEST;
    let body = refused("/api/steady?preset=paper&w=-1&beta=2", bad, "invalid w -1").await;
    assert_eq!(body["field"], "w");
    refused("/api/steady?preset=paper&freq=abc&amplitude=1", bad, "freq").await;
    refused(
        "/api/steady?preset=paper&w=0.9",
        bad,
        "missing drive amplitude",
    )
    .await;
    refused(
        "/api/steady?w=0.9&beta=1&amplitude=2",
        bad,
        "amplitude is a physical",
    )
    .await;
    refused(
        "/api/steady?preset=paper&w=0.9&beta=1&colour=red",
        bad,
        "unknown key 'colour'",
    )
    .await;
    refused(
        "/api/steady?preset=paper&w=0.9&w=1&beta=1",
        bad,
        "given twice",
    )
    .await;
    refused(
        "/api/steady?config=/etc/passwd&w=1&beta=1",
        bad,
        "reads no files",
    )
    .await;
    refused("/api/steady?preset=lab&w=1&beta=1", bad, "invalid preset").await;
    refused(
        "/api/theory?preset=paper&model=shockley&w=1&beta=1",
        bad,
        "piecewise-linear",
    )
    .await;
    refused(
        "/api/theory?preset=paper&w=1&beta=1&y0=1",
        bad,
        "not used by theory",
    )
    .await;
    refused("/api/sweep?preset=paper&over=w&w=1&beta=2", bad, "drop w").await;
    refused(
        "/api/sweep?preset=paper&beta=2&from=2&to=1",
        bad,
        "invalid from 2: range start must not exceed the range end",
    )
    .await;
    refused(
        "/api/sweep?preset=paper&beta=2&over=gamma",
        bad,
        "invalid over",
    )
    .await;
    refused("/api/map?preset=paper&freq=1k", bad, "drop freq").await;
    refused("/api/presets?x=1", bad, "takes no keys").await;
    // Percent-encoding that is not UTF-8, control characters: still one line.
    refused("/api/steady?w=%FF%FE&beta=%0A", bad, "w").await;
}

#[tokio::test]
async fn request_sizes_are_capped() {
    let bad = StatusCode::BAD_REQUEST;
    refused(
        "/api/steady?preset=paper&w=1&beta=2&samples=8192",
        bad,
        "from 16 to 4096",
    )
    .await;
    refused(
        "/api/steady?preset=paper&w=1&beta=2&samples=300",
        bad,
        "power of two",
    )
    .await;
    refused(
        "/api/steady?preset=paper&w=1&beta=2&max-periods=100000",
        bad,
        "max-periods",
    )
    .await;
    refused(
        "/api/steady?preset=paper&w=1&beta=2&max-period=64",
        bad,
        "max-period",
    )
    .await;
    refused(
        "/api/simulate?preset=paper&w=1&beta=2&periods=1e6",
        bad,
        "invalid periods 1e6: must be from 0 to 2000",
    )
    .await;
    refused(
        "/api/simulate?preset=paper&w=1&beta=2&periods=2000&samples=1000",
        bad,
        "at most 200000",
    )
    .await;
    refused(
        "/api/sweep?preset=paper&beta=2&steps=1000",
        bad,
        "from 1 to 400",
    )
    .await;
    refused(
        "/api/map?preset=paper&w-steps=300&beta-steps=300",
        bad,
        "w-steps × beta-steps = 90000 points: at most 40000 allowed",
    )
    .await;
    let long = format!("/api/steady?preset=paper&w=1&beta=2&x={}", "9".repeat(5000));
    refused(&long, bad, "at most 4096").await;
}

#[tokio::test]
async fn unknown_paths_are_404_and_the_page_is_served() {
    refused("/nope", StatusCode::NOT_FOUND, "no such page: /nope").await;
    refused("/api/steadyx", StatusCode::NOT_FOUND, "/api/steadyx").await;
    refused("/../../etc/passwd", StatusCode::NOT_FOUND, "no such page").await;
    let response = router(lab(Duration::from_secs(10)))
        .oneshot(
            Request::post("/api/steady?preset=paper&w=1&beta=1")
                .body(Body::empty())
                .unwrap(),
        )
        .await
        .unwrap();
    assert_eq!(response.status(), StatusCode::METHOD_NOT_ALLOWED);
    let body = axum::body::to_bytes(response.into_body(), usize::MAX)
        .await
        .unwrap();
    let body: Value = serde_json::from_slice(&body).unwrap();
    assert!(body["error"].as_str().unwrap().contains("GET"), "{body}");

    let lab = lab(Duration::from_secs(10));
    let (status, content_type, body) = get_with(&lab, "/").await;
    assert_eq!(status, StatusCode::OK);
    assert!(content_type.starts_with("text/html"));
    let html = String::from_utf8(body).unwrap();
    for hook in [
        r#"name="freq""#,
        r#"name="amplitude""#,
        r#"data-measure="gain""#,
        r#"data-measure="class""#,
        r#"data-measure="A1""#,
        r#"data-measure="A3""#,
    ] {
        assert!(html.contains(hook), "{hook}");
    }
    // Assets are local: no address of another server in the page.
    assert!(!html.contains("http://") && !html.contains("https://"));
    assert!(html.contains(r#"<script type="module" src="lab.js">"#));
    let (status, content_type, script) = get_with(&lab, "/lab.js").await;
    assert_eq!(status, StatusCode::OK);
    assert!(content_type.starts_with("text/javascript"));
    // Every module the page imports is served as JavaScript (a module script needs the type).
    let script = String::from_utf8(script).unwrap();
    let mut modules = 0;
    for line in script.lines().filter(|l| l.starts_with("import ")) {
        let path = line.split('\'').nth(1).unwrap().trim_start_matches('.');
        let (status, content_type, module) = get_with(&lab, path).await;
        assert_eq!(status, StatusCode::OK, "{path}");
        assert!(content_type.starts_with("text/javascript"), "{path}");
        assert!(!module.is_empty(), "{path}");
        modules += 1;
    }
    assert_eq!(modules, 10);
    let (status, _, _) = get_with(&lab, "/lab/nothing.js").await;
    assert_eq!(status, StatusCode::NOT_FOUND);
    let (status, _, _) = get_with(&lab, "/lab.css").await;
    assert_eq!(status, StatusCode::OK);
    let (status, presets) = get("/api/presets").await;
    assert_eq!(status, StatusCode::OK);
    assert_eq!(presets["presets"][5]["values"]["w"], 0.95);
    assert_eq!(presets["presets"][5]["values"]["beta"], 2.14);
    // Issue 38, item 2: a preset's generator setting is the drive of the steady state its
    // query asks for, in Hz and V (or N), to the bit; the paper's circuit alone has none.
    assert!(presets["presets"][0]["drive"].is_null());
    for (k, query) in [
        (5, "preset=paper&w=0.95&beta=2.14"),
        (
            7,
            "mass=0.5&stiffness=200&damping=0.94&friction=1&mu-s=1&w=0.95&beta=2.14",
        ),
    ] {
        let (status, steady) = get(&format!("/api/steady?{query}")).await;
        assert_eq!(status, StatusCode::OK, "{steady}");
        assert_eq!(presets["presets"][k]["drive"], steady["drive"], "{query}");
    }
    assert_eq!(presets["presets"][7]["drive"]["unit"], "N");
    // The Shockley diodes' starting values are the 1N4148's, by query key.
    let d = stickslip::DiodePair::one_n4148();
    assert_eq!(
        presets["shockley"],
        serde_json::json!({
            "diode-is": d.saturation_current,
            "diode-n": d.emission,
            "diode-rs": d.series_resistance,
            "temperature": d.temperature,
        })
    );
}

#[tokio::test]
async fn keys_serve_the_model_keys_the_caps_and_the_stuck_speed() {
    let (status, keys) = get("/api/keys").await;
    assert_eq!(status, StatusCode::OK, "{keys}");
    let flags: Vec<&str> = keys["keys"]
        .as_array()
        .unwrap()
        .iter()
        .map(|k| k["flag"].as_str().unwrap())
        .collect();
    assert_eq!(flags.len(), Key::ALL.len());
    for flag in ["mu-s", "freq", "ut", "rd", "diode-is", "model", "preset"] {
        assert!(flags.contains(&flag), "{flag}");
    }
    // The library's table, as it serialises it: the query takes every key under its flag.
    let table = serde_json::to_value(Key::table()).unwrap();
    assert_eq!(keys["keys"], table);
    for key in Key::ALL {
        assert!(flags.contains(&key.flag()), "{}", key.flag());
    }
    // The caps are the ones the endpoints enforce: one more is refused.
    let caps = &keys["caps"];
    assert_eq!(caps["simulate_periods"], 2000.0);
    assert_eq!(caps["max_period"], 16);
    let (_, presets) = get("/api/presets").await;
    assert_eq!(&presets["caps"], caps);
    let over = caps["max_period"].as_u64().unwrap() + 1;
    refused(
        &format!("/api/steady?w=1&beta=2&max-period={over}"),
        StatusCode::BAD_REQUEST,
        "max-period",
    )
    .await;
    let periods = caps["simulate_periods"].as_f64().unwrap() * 1.5;
    refused(
        &format!("/api/simulate?w=1&beta=2&periods={periods}&samples=1"),
        StatusCode::BAD_REQUEST,
        "periods",
    )
    .await;
    // The form: the fields of the circuit's, the diodes' and the mechanical parts and μs,
    // in the table's order, then the belt's and the friction laws' (tests/belt.rs); the fit
    // boxes are the circuit's fit parameters.
    let form: Vec<(&str, &str)> = keys["form"]
        .as_array()
        .unwrap()
        .iter()
        .map(|f| (f["flag"].as_str().unwrap(), f["fieldset"].as_str().unwrap()))
        .collect();
    let expected: Vec<&str> = Key::ALL
        .into_iter()
        .filter(|k| {
            k.is_circuit_part()
                || k.is_mechanics_part()
                || k.section() == Some(stickslip::experiment::Section::Shockley)
                || *k == Key::MuS
        })
        .map(Key::flag)
        .collect();
    let flags: Vec<&str> = form.iter().map(|f| f.0).collect();
    assert_eq!(flags[..expected.len()], expected);
    assert!(flags[expected.len()..].iter().all(|f| Key::ALL
        .into_iter()
        .any(|k| k.flag() == *f && k.group() == stickslip::experiment::KeyGroup::Friction)));
    assert!(form.contains(&("rd", "pwl")) && form.contains(&("ut", "pwl shockley")));
    assert!(form.contains(&("diode-n", "shockley")) && form.contains(&("mu-s", "mechanics")));
    let fit: Vec<&str> = keys["fit"]["parameters"]
        .as_array()
        .unwrap()
        .iter()
        .map(|p| p.as_str().unwrap())
        .collect();
    assert_eq!(fit.len(), stickslip::fit::FitParameter::CIRCUIT.len());
    assert!(fit.contains(&"rd") && fit.contains(&"diode-is") && !fit.contains(&"mass"));
    // What a fit frees when nothing is ticked, by diode law: the library's default free
    // sets, as `stickslip fit` and Python's `fit` free them (with Shockley diodes R, I_s and
    // n, not U_t, which is no parameter of that law).
    assert_eq!(
        keys["fit"]["free"],
        serde_json::json!({
            "pwl": ["resistance", "ut"],
            "shockley": ["resistance", "diode-is", "diode-n"],
        })
    );
    for law in DiodeModel::ALL {
        let expected: Vec<&str> =
            stickslip::fit::FitParameter::defaults(stickslip::SystemKind::Circuit, law)
                .iter()
                .map(|p| p.label())
                .collect();
        assert_eq!(
            keys["fit"]["free"][law.label()],
            serde_json::json!(expected)
        );
        for name in expected {
            let by_law = keys["fit"]["by_law"][law.label()].as_array().unwrap();
            assert!(by_law.contains(&serde_json::json!(name)), "{law} {name}");
        }
    }
    // By diode law: the library's circuit parameters of that law, in the order of reports.
    for law in DiodeModel::ALL {
        let expected: Vec<&str> = stickslip::fit::FitParameter::CIRCUIT
            .into_iter()
            .filter(|p| p.applies_to(law))
            .map(|p| p.label())
            .collect();
        assert_eq!(
            keys["fit"]["by_law"][law.label()],
            serde_json::json!(expected)
        );
    }
    assert_eq!(
        keys["fit"]["by_law"]["shockley"],
        serde_json::json!([
            "resistance",
            "diode-is",
            "diode-n",
            "diode-rs",
            "inductance",
            "capacitance"
        ])
    );
    assert_eq!(
        keys["fit"]["by_law"]["pwl"],
        serde_json::json!([
            "resistance",
            "ut",
            "rd",
            "inductance",
            "capacitance",
            "mu-s"
        ])
    );
    assert_eq!(keys["keys"][Key::TurnOn as usize]["symbol"], "U_t");
    assert_eq!(keys["stuck_velocity"]["pwl"], 1e-9);
    assert_eq!(keys["stuck_velocity"]["shockley"], 1e-3);
    // The library's rule for a static motion, which the page states beside the class.
    assert_eq!(keys["static_gain"], stickslip::steady::STATIC_GAIN);
    refused("/api/keys?w=1", StatusCode::BAD_REQUEST, "takes no keys").await;
}

#[tokio::test]
async fn the_time_limit_stops_a_computation() {
    let lab = lab(Duration::from_millis(300));
    // A Shockley map this size takes minutes without the limit.
    let uri = "/api/map?preset=paper&model=shockley&w-steps=40&beta-steps=40&w-min=0.1&w-max=0.6";
    let (status, _, body) = get_with(&lab, uri).await;
    assert_eq!(status, StatusCode::SERVICE_UNAVAILABLE);
    let body: Value = serde_json::from_slice(&body).unwrap();
    let message = body["error"].as_str().unwrap();
    assert!(message.contains("time limit of 0.3 s"), "{message}");
    assert!(message.contains("of 1600 done"), "{message}");
    // The workers stopped too (the answer does not wait for them).
    assert!(
        until_active(&lab, 0).await,
        "the computation kept running after its time limit"
    );
}

#[tokio::test]
async fn a_dropped_request_stops_its_computation() {
    let lab = lab(Duration::from_secs(600));
    // A Shockley map this size takes minutes.
    let uri = "/api/map?preset=paper&model=shockley&w-steps=40&beta-steps=40&w-min=0.1&w-max=0.6";
    let app = router(lab.clone());
    let request = tokio::spawn(app.oneshot(Request::get(uri).body(Body::empty()).unwrap()));
    assert!(until_active(&lab, 1).await, "the computation did not start");
    // The client goes away: the server drops the request's future.
    request.abort();
    assert!(request.await.unwrap_err().is_cancelled());
    assert!(
        until_active(&lab, 0).await,
        "the computation kept running after its client went away"
    );
}

#[tokio::test]
async fn chaos_is_a_class_of_the_map_and_of_the_steady_state_with_a_colour_of_its_own() {
    // ζ = 0, μs = 3, β = 9: chaotic at w = 0.33, periodic at 0.25 and 0.40.
    let (status, answer) = get(
        "/api/map?zeta=0&mu-s=3&w-min=0.25&w-max=0.40&w-steps=3&beta-min=9&beta-max=9&beta-steps=1",
    )
    .await;
    assert_eq!(status, StatusCode::OK, "{answer}");
    let labels: Vec<&str> = answer["points"]
        .as_array()
        .unwrap()
        .iter()
        .map(|p| p["class"].as_str().unwrap())
        .collect();
    let e = Experiment::dimensionless(0.0, 0.325, 9.0)
        .unwrap()
        .with_mu_s(3.0)
        .unwrap();
    let expected: Vec<&str> = [0.25, 0.325, 0.40]
        .iter()
        .map(|&w| e.clone().with_w(w).unwrap().steady().unwrap().class.label())
        .collect();
    assert_eq!(labels, expected);
    assert_eq!(labels[1], "chaotic");
    // The steady state says so too, with the exponent, as `stickslip steady --json`.
    let (status, answer) = get("/api/steady?zeta=0&mu-s=3&w=0.325&beta=9").await;
    assert_eq!(status, StatusCode::OK, "{answer}");
    let report = serde_json::to_value(SteadyReport::from(&e.steady().unwrap())).unwrap();
    assert_eq!(answer["class"], "chaotic");
    for key in ["lambda1", "lambda1_error", "verdict"] {
        assert_eq!(answer[key], report[key], "{key}");
    }
    // The page has a colour for every class the library can answer, in the library's order
    // (the map's legend lists the classes in the order of its colours).
    let (_, _, script) = get_with(&lab(Duration::from_secs(10)), "/lab/sweepmap.js").await;
    let script = String::from_utf8(script).unwrap();
    let colours = script
        .lines()
        .find(|l| l.contains("const CLASS_COLORS"))
        .expect("the class colours");
    let mut at = 0;
    for class in stickslip::steady::MotionClass::ALL {
        let label = class.label();
        let found = colours[at..]
            .find(&format!("'{label}':"))
            .or_else(|| colours[at..].find(&format!(" {label}:")));
        let Some(k) = found else {
            panic!("no colour for {label}, or not in the library's order, in {colours}")
        };
        at += k + label.len();
    }
}

/// Issue 21, item 9: every bad value the review found is a 400 that names the key the user
/// typed (never a 500, never another key), on every endpoint that takes it.
#[tokio::test]
async fn every_bad_value_of_the_review_is_a_400_naming_its_key() {
    let bad = StatusCode::BAD_REQUEST;
    let point = "preset=paper&w=0.95&beta=2.14";
    let sweep = "preset=paper&beta=2.14";
    let map = "preset=paper&w-steps=3&beta-steps=3";
    // Shockley parts at 1e308 made the integrator fail (500) on every endpoint.
    for key in ["diode-rs", "diode-n", "temperature", "diode-is"] {
        for (endpoint, base) in [
            ("steady", point),
            ("simulate", point),
            ("sweep", sweep),
            ("map", map),
        ] {
            let uri = format!("/api/{endpoint}?{base}&model=shockley&{key}=1e308");
            let body = refused(&uri, bad, &format!("invalid {key} 1e308")).await;
            assert_eq!(body["field"], key, "{uri}: {body}");
        }
    }
    // R or R_D at 1e308 blamed L.
    for key in ["resistance", "rd"] {
        let body = refused(
            &format!("/api/steady?{point}&{key}=1e308"),
            bad,
            &format!("invalid {key} 1e308"),
        )
        .await;
        assert_eq!(body["field"], key);
        // Within the key's range but too large for the solvers: named all the same.
        let body = refused(&format!("/api/steady?{point}&{key}=1e9"), bad, "zeta").await;
        assert_eq!(body["field"], key, "{body}");
    }
    // A capacitance that makes ζ too large is the capacitance's fault when it was given.
    let body = refused(
        &format!("/api/steady?{point}&capacitance=1e6"),
        bad,
        "invalid capacitance 1000000: it gives zeta = ",
    )
    .await;
    assert_eq!(body["field"], "capacitance", "{body}");
    // The end of a range that is out of range is named, not the other end.
    let body = refused(
        "/api/map?preset=paper&beta-max=1e308",
        bad,
        "invalid beta-max 1e308",
    )
    .await;
    assert_eq!(body["field"], "beta-max");
    let body = refused("/api/map?preset=paper&w-min=0", bad, "invalid w-min 0").await;
    assert_eq!(body["field"], "w-min");
    let body = refused(
        &format!("/api/sweep?{sweep}&to=1e308"),
        bad,
        "invalid to 1e308",
    )
    .await;
    assert_eq!(body["field"], "to");
    let body = refused(
        "/api/sweep?preset=paper&w=1&beta=2&over=mu-s&from=0.5&to=2",
        bad,
        "invalid from 0.5: mu-s must be finite and from 1",
    )
    .await;
    assert_eq!(body["field"], "from");
    // A unit that is not the key's.
    let body = refused(
        "/api/steady?preset=paper&freq=9.97kV&amplitude=1.4",
        bad,
        "the unit V does not fit",
    )
    .await;
    assert_eq!(body["field"], "freq");
    let body = refused(
        "/api/steady?preset=paper&freq=9.97k&amplitude=1.4Hz",
        bad,
        "the unit Hz does not fit",
    )
    .await;
    assert_eq!(body["field"], "amplitude");
    // The key's own unit, or none, is fine.
    for query in [
        "preset=paper&freq=9.97kHz&amplitude=1.498V",
        "preset=paper&freq=9.97k&amplitude=1.498&resistance=68ohm",
    ] {
        let (status, body) = get(&format!("/api/theory?{query}")).await;
        assert_eq!(status, StatusCode::OK, "{query}: {body}");
    }
}

/// Issue 38: absurd values blamed the wrong field or none (C = 1e308 on R, C = 1e-308 on the
/// frequency; L, k or γ = 1e308 on no field), a map's β-max = 0 marked β-min, a sweep of
/// 0 steps was told the library's range, not the lab's cap; and a decimal comma was refused.
/// The library names the value at fault, and the lab marks its field.
#[tokio::test]
async fn absurd_values_mark_their_own_field_and_decimal_commas_are_read() {
    let bad = StatusCode::BAD_REQUEST;
    let point = "preset=paper&w=0.95&beta=2.14";
    let physical = "preset=paper&freq=9.97k&amplitude=1.498";
    let mechanics = "mass=0.5&stiffness=200&damping=0.94&friction=1&omega=19&amplitude=2.14";
    for (base, key, value) in [
        (point, "capacitance", "1e308"),
        (physical, "capacitance", "1e308"),
        (physical, "capacitance", "1e-308"),
        (point, "inductance", "1e308"),
        (physical, "inductance", "1e308"),
        (physical, "inductance", "1e-308"),
        (mechanics, "stiffness", "1e308"),
        (mechanics, "damping", "1e308"),
        (mechanics, "mass", "1e308"),
        (mechanics, "stiffness", "1e-308"),
    ] {
        // The base with the key's value replaced (or added).
        let query: Vec<String> = base
            .split('&')
            .filter(|kv| !kv.starts_with(&format!("{key}=")))
            .map(String::from)
            .chain([format!("{key}={value}")])
            .collect();
        let query = query.join("&");
        for endpoint in ["steady", "simulate", "theory"] {
            let uri = format!("/api/{endpoint}?{query}");
            let body = refused(&uri, bad, &format!("invalid {key} {value}")).await;
            assert_eq!(body["field"], key, "{uri}: {body}");
        }
    }
    let body = refused(
        "/api/map?preset=paper&beta-max=0",
        bad,
        "invalid beta-max 0: must not be below beta-min 0.5",
    )
    .await;
    assert_eq!(body["field"], "beta-max");
    let body = refused(
        "/api/map?preset=paper&w-min=3",
        bad,
        "invalid w-max 2.5: must not be below w-min 3",
    )
    .await;
    assert_eq!(body["field"], "w-max");
    for (uri, key) in [
        ("/api/sweep?preset=paper&beta=2.14&steps=0", "steps"),
        ("/api/sweep?preset=paper&beta=2.14&steps=401", "steps"),
    ] {
        let body = refused(uri, bad, &format!("must be from 1 to {}", CAPS_SWEEP)).await;
        assert_eq!(body["field"], key, "{uri}");
    }
    let body = refused(
        "/api/map?preset=paper&w-steps=0",
        bad,
        "invalid w-steps 0: must be from 1 to 1000",
    )
    .await;
    assert_eq!(body["field"], "w-steps");
    // "9,97k": one comma and no point is a decimal comma, as the point would be.
    let (status, comma) = get("/api/steady?preset=paper&freq=9,97k&amplitude=1,4980").await;
    assert_eq!(status, StatusCode::OK, "{comma}");
    let (_, point) = get(&format!("/api/steady?{physical}")).await;
    assert_eq!(comma, point);
    let (status, body) = get("/api/steady?preset=paper&w=0,95&beta=2,14").await;
    assert_eq!(status, StatusCode::OK, "{body}");
    // A comma that may separate thousands is refused naming both readings.
    let body = refused(
        "/api/steady?preset=paper&freq=9,970&amplitude=1.498",
        bad,
        "'9,970' is ambiguous: 9.97 with a decimal comma, 9970 with a thousands separator",
    )
    .await;
    assert_eq!(body["field"], "freq");
    let body = refused(
        "/api/steady?preset=paper&freq=9.97k&amplitude=1,498",
        bad,
        "write 1.498 or 1498",
    )
    .await;
    assert_eq!(body["field"], "amplitude");
}

/// The lab's cap of a sweep's steps.
const CAPS_SWEEP: usize = stickslip::limits::Caps::shared_server().sweep_steps;

/// GET `uri` with a `Host` header; status and body.
async fn get_host(host: &str, uri: &str) -> (StatusCode, Value) {
    let response = router(lab(Duration::from_secs(60)))
        .oneshot(
            Request::get(uri)
                .header("host", host)
                .body(Body::empty())
                .unwrap(),
        )
        .await
        .unwrap();
    let status = response.status();
    let body = axum::body::to_bytes(response.into_body(), usize::MAX)
        .await
        .unwrap();
    (status, serde_json::from_slice(&body).unwrap_or(Value::Null))
}

/// Issue 21, item 12: a page that renames an address ("DNS rebinding") gets nothing.
#[tokio::test]
async fn only_the_labs_own_host_names_are_answered() {
    for host in [
        "localhost:8080",
        "LOCALHOST",
        "127.0.0.1:8080",
        "[::1]:8080",
        "192.0.2.7:8080",
        "lab.school.example",
        "lab.school.example.:80",
    ] {
        let (status, body) = get_host(host, "/api/presets").await;
        assert_eq!(status, StatusCode::OK, "{host}: {body}");
    }
    for host in [
        "evil.example",
        "evil.example:8080",
        "192.0.2.8",
        "[::2]:80",
        "",
    ] {
        for path in ["/", "/api/presets", "/api/theory?preset=paper&w=1&beta=1"] {
            let (status, body) = get_host(host, path).await;
            assert_eq!(status, StatusCode::FORBIDDEN, "{host} {path}");
            let message = body["error"].as_str().unwrap_or_default();
            assert!(
                message.contains("does not answer to the host") && message.contains("--allow-host"),
                "{host}: {message}"
            );
        }
    }
}

/// Every library error that names an option is a 400 naming its query key, and every stop
/// of a computation by its caller is a 503 (as the lab's own time limit): none is a 500.
#[test]
fn library_errors_about_options_and_stops_are_never_500() {
    use crate::query::ApiError;
    use stickslip::options::{check_product, OptionKey};
    use stickslip::Error;

    let e = ApiError::library(&OptionKey::MaxPeriod.check(65.0).unwrap_err());
    assert_eq!(e.status, StatusCode::BAD_REQUEST);
    assert_eq!(e.field.as_deref(), Some("max-period"));
    assert_eq!(e.message, "invalid max-period 65: must be from 1 to 64");

    // Renamed query keys: `samples` for the simulation's samples per period.
    let e = ApiError::library(&OptionKey::SimulateSamples.check(0.0).unwrap_err());
    assert_eq!(e.status, StatusCode::BAD_REQUEST);
    assert_eq!(e.field.as_deref(), Some("samples"));
    assert!(
        e.message.starts_with("invalid samples 0: "),
        "{}",
        e.message
    );

    let product = check_product(
        "points",
        (OptionKey::MapWSteps, 1000),
        (OptionKey::MapBetaSteps, 1000),
        40_000.0,
        "40000",
    )
    .unwrap_err();
    let e = ApiError::library(&product);
    assert_eq!(e.status, StatusCode::BAD_REQUEST);
    assert_eq!(e.field.as_deref(), Some("beta-steps"));
    assert_eq!(
        e.message,
        "w-steps × beta-steps = 1e6 points: at most 40000 allowed"
    );

    for stop in [
        Error::Cancelled { done: 3, total: 10 },
        Error::DeadlineExceeded,
        Error::BudgetExceeded { budget: 1000 },
    ] {
        let e = ApiError::library(&stop);
        assert_eq!(e.status, StatusCode::SERVICE_UNAVAILABLE, "{stop}");
        assert!(e.message.contains(&stop.to_string()), "{}", e.message);
        assert!(!e.message.contains('\n'));
    }
}

// ---------------------------------------------------------------- records and fits (issue 20)

/// A Rigol CSV export of the steady state of [`truth`] at (w, β, φ), made by the exact
/// solver: 1200 samples over 3.4 drive periods, each channel quantised to 8 bits of a screen
/// 1.25 times its peak-to-peak with a step of Gaussian noise, and a u_C offset of 20 mV.
fn rigol_record(w: f64, beta: f64, phi: f64) -> String {
    rigol_record_bits(w, beta, phi, 8)
}

/// [`rigol_record`] quantised to `bits` bits.
fn rigol_record_bits(w: f64, beta: f64, phi: f64, bits: i32) -> String {
    rigol(&record_bits(w, beta, phi, bits))
}

/// The record of [`rigol_record_bits`] before its export.
fn record_bits(w: f64, beta: f64, phi: f64, bits: i32) -> Synthetic {
    let e = driven(truth(), w, beta, phi);
    let n = 1200;
    let increment = 3.4 * std::f64::consts::TAU / (w * e.scales().unwrap().omega0) / n as f64;
    let s = sample_steady(&e, n, increment);
    let response: Vec<f64> = s.response.iter().map(|r| r + 0.02).collect();
    let mut rng = Rng(2026);
    let levels = 2f64.powi(bits);
    let drive = quantise(&s.drive, levels, 1.0, &mut rng);
    let response = quantise(&response, levels, 1.0, &mut rng);
    let start = -0.5 * n as f64 * increment;
    Synthetic::new(drive, response, start, increment)
}

/// POST `body` to `uri` of `lab`; status and JSON answer.
async fn post_with(lab: &Lab, uri: &str, body: Vec<u8>) -> (StatusCode, Value) {
    let response = router(lab.clone())
        .oneshot(
            Request::post(uri)
                .header("content-type", "text/csv")
                .body(Body::from(body))
                .unwrap(),
        )
        .await
        .unwrap();
    let status = response.status();
    assert_eq!(
        response.headers()["content-type"],
        "application/json",
        "{uri}"
    );
    let body = axum::body::to_bytes(response.into_body(), usize::MAX)
        .await
        .unwrap();
    (status, serde_json::from_slice(&body).unwrap())
}

async fn post(uri: &str, body: impl Into<Vec<u8>>) -> (StatusCode, Value) {
    post_with(&lab(Duration::from_secs(120)), uri, body.into()).await
}

/// A refusal of a POST: `status`, one line naming `needle`, and the field `field`.
async fn post_refused(
    uri: &str,
    body: impl Into<Vec<u8>>,
    status: StatusCode,
    needle: &str,
    field: Option<&str>,
) {
    let (got, answer) = post(uri, body).await;
    assert_eq!(got, status, "{uri}: {answer}");
    let message = answer["error"].as_str().expect("an error message");
    assert!(!message.contains('\n'), "{uri}: {message}");
    assert!(
        message.contains(needle),
        "{uri}: '{needle}' not in '{message}'"
    );
    assert_eq!(answer["field"].as_str(), field, "{uri}: {answer}");
}

#[tokio::test]
async fn a_record_is_read_by_the_librarys_readers() {
    let text = rigol_record(0.5, 2.5, 0.3);
    let (status, answer) = post("/api/record?file=run1.csv", text.clone()).await;
    assert_eq!(status, StatusCode::OK, "{answer}");
    let record = stickslip::measure::read_scope(&text, "run1.csv").unwrap();
    let m = stickslip::measure::Measurement::new(&record, None, None).unwrap();
    assert_eq!(answer["file"], "run1.csv");
    assert_eq!(answer["format"], "rigol");
    assert_eq!(answer["samples"], 1200);
    assert_eq!(answer["t0_s"], record.time[0]);
    assert_eq!(answer["t_s"], serde_json::to_value(&m.time).unwrap());
    assert_eq!(answer["channels"][0]["name"], "CH1");
    assert_eq!(
        answer["channels"][1]["values"],
        serde_json::to_value(&record.channels[1].values).unwrap()
    );
    assert_eq!(answer["drive_channel"], "CH1");
    assert_eq!(answer["response_channel"], "CH2");
    assert_eq!(answer["drive"]["f_Hz"], m.drive.frequency);
    assert_eq!(answer["drive"]["amplitude_V"], m.drive.amplitude);
    assert_eq!(answer["drive"]["phase"], m.drive.phase);
    assert_eq!(answer["drive"]["periods"], 3);
    assert_eq!(answer["clipped"], 0);
    // The drive as made: w = 0.5 of the paper's f0, β = 2.5 of U_t = 0.6 V, φ = 0.3.
    let f0 = 1.0 / (std::f64::consts::TAU * (11.5e-3f64 * 20e-9).sqrt());
    let f = answer["drive"]["f_Hz"].as_f64().unwrap();
    assert!((f / (0.5 * f0) - 1.0).abs() < 1e-3, "{f}");
    let a = answer["drive"]["amplitude_V"].as_f64().unwrap();
    assert!((a / (2.5 * TRUE_UT) - 1.0).abs() < 5e-3, "{a}");
    // Channels picked by name: the record written with u_C as CH1 and the drive as CH2.
    let s = record_bits(0.5, 2.5, 0.3, 8);
    let swapped = rigol(&Synthetic::new(s.response, s.drive, s.start, s.increment));
    let (status, answer) = post("/api/record?drive=CH2&response=1", swapped.clone()).await;
    assert_eq!(status, StatusCode::OK, "{answer}");
    assert_eq!(answer["drive_channel"], "CH2");
    assert_eq!(answer["response_channel"], "CH1");
    assert_eq!(answer["file"], "record.csv");
    assert_eq!(answer["drive"]["f_Hz"], m.drive.frequency);
    // With the default channels it is refused in one line that says how to pick them.
    post_refused(
        "/api/record",
        swapped,
        StatusCode::BAD_REQUEST,
        "swapped: give drive=CH2&response=CH1",
        Some("record"),
    )
    .await;
}

#[tokio::test]
async fn a_fit_recovers_the_circuit_of_a_record_made_by_the_exact_solver() {
    // A stick-slip record of R = 80 Ω, U_t = 0.6 V; the fit starts from the paper's
    // 68 Ω and 0.7 V. With 8 bits, one record fixes R to about 1 % (one standard error):
    // the 95 % intervals cover the truth; with 12 bits both are within 1 %.
    let uri = "/api/fit?preset=paper&free=resistance,ut&file=run1.csv";
    let (status, answer) = post(uri, rigol_record_bits(0.5, 2.5, 0.3, 12)).await;
    assert_eq!(status, StatusCode::OK, "{answer}");
    let r = answer["parameters"]["resistance"]["value"]
        .as_f64()
        .unwrap();
    let ut = answer["parameters"]["ut"]["value"].as_f64().unwrap();
    assert!((r / TRUE_R - 1.0).abs() < 0.01, "R = {r}: {answer}");
    assert!((ut / TRUE_UT - 1.0).abs() < 0.01, "U_t = {ut}: {answer}");
    let text = rigol_record(0.5, 2.5, 0.3);
    let (status, answer) = post(uri, text.clone()).await;
    assert_eq!(status, StatusCode::OK, "{answer}");
    for (name, truth) in [("resistance", TRUE_R), ("ut", TRUE_UT)] {
        let p = &answer["parameters"][name];
        let (lo, hi) = (
            p["ci95"][0].as_f64().unwrap(),
            p["ci95"][1].as_f64().unwrap(),
        );
        assert!(lo < truth && truth < hi, "{name}: {p}");
        assert!(p["stderr"].as_f64().unwrap() < 0.015 * truth, "{name}: {p}");
    }
    let r = answer["parameters"]["resistance"]["value"]
        .as_f64()
        .unwrap();
    let ut = answer["parameters"]["ut"]["value"].as_f64().unwrap();
    assert_eq!(answer["converged"], true);
    // The answer holds `stickslip fit --json` of the same record and keys, number for number:
    // the library's fit of the same text.
    let record = stickslip::measure::read_scope(&text, "run1.csv").unwrap();
    let m = stickslip::measure::Measurement::new(&record, None, None).unwrap();
    let report = stickslip::fit::fit_records(
        &spec(Some(Preset::Paper), None, &[]),
        &[m],
        &[
            stickslip::fit::FitParameter::Resistance,
            stickslip::fit::FitParameter::Ut,
        ],
        &stickslip::fit::FitOptions::default(),
    )
    .unwrap();
    same_keys(&answer, &serde_json::to_value(report.to_json()).unwrap());
    assert_eq!(answer["records"][0]["file"], "run1.csv");
    // The fitted experiment's keys: the fitted values, the paper's other parts, the drive.
    let keys = &answer["keys"];
    assert_eq!(keys["resistance"].as_f64().unwrap(), r);
    assert_eq!(keys["ut"].as_f64().unwrap(), ut);
    assert_eq!(keys["inductance"], 11.5e-3);
    assert_eq!(keys["capacitance"], 20e-9);
    assert_eq!(keys["rd"], 3.0);
    assert_eq!(keys["freq"], answer["records"][0]["freq_Hz"]);
    assert_eq!(keys["amplitude"], answer["records"][0]["amplitude_V"]);
    let phi = keys["phi"].as_f64().unwrap();
    assert!((phi - 0.3).abs() < 0.02, "φ = {phi}");
    assert!(keys.get("diode-is").is_none() && keys.get("mu-s").is_none());
    // The plot: two periods of the record, measured = model − residual, and the residual is
    // the noise.
    let plot = &answer["plot"];
    let t = plot["t_s"].as_array().unwrap();
    let f = keys["freq"].as_f64().unwrap();
    assert!(t.len() > 600 && t.len() <= 706, "{}", t.len());
    assert!(t.last().unwrap().as_f64().unwrap() <= 2.0 / f);
    let fitted = &report.records[0];
    for (i, ti) in t.iter().enumerate() {
        assert_eq!(ti.as_f64().unwrap(), fitted.time[i]);
        assert_eq!(plot["model_V"][i].as_f64().unwrap(), fitted.model[i]);
        assert_eq!(plot["residual_V"][i].as_f64().unwrap(), fitted.residuals[i]);
        let measured = plot["measured_V"][i].as_f64().unwrap();
        assert!((measured - record.channels[1].values[i]).abs() < 1e-12);
    }
    let noise = answer["noise_V"].as_f64().unwrap();
    let rms = answer["rms_residual_V"].as_f64().unwrap();
    assert!(
        rms < 1.5 * noise,
        "RMS residual {rms} against noise {noise}"
    );
}

#[tokio::test]
async fn bad_records_and_keys_are_400s_naming_the_field_and_line() {
    let bad = StatusCode::BAD_REQUEST;
    let good = rigol_record(0.95, 2.5, 0.0);
    // A garbage row: the reader's words, with the file and the line.
    let mut lines: Vec<&str> = good.lines().collect();
    lines[40] = "38,1.0e0,abc,";
    let garbage = lines.join("\n");
    let fit = "/api/fit?preset=paper&file=scope.csv";
    post_refused(
        fit,
        garbage.clone(),
        bad,
        "scope.csv: line 41:",
        Some("record"),
    )
    .await;
    post_refused(
        "/api/record?file=scope.csv",
        garbage,
        bad,
        "scope.csv: line 41:",
        Some("record"),
    )
    .await;
    // A time that goes backwards (plain CSV).
    let backwards: String = std::iter::once("t,CH1,CH2\n".to_string())
        .chain((0..30).map(|k| {
            let t = if k == 20 { 10.5e-6 } else { k as f64 * 1e-6 };
            format!("{t},{},{}\n", (k as f64).sin(), (k as f64).cos())
        }))
        .collect();
    post_refused(fit, backwards, bad, "line 22:", Some("record")).await;
    // Not a scope export; a record shorter than a drive period; one channel.
    post_refused(
        fit,
        "hello,world\n1,2\n",
        bad,
        "not a scope export",
        Some("record"),
    )
    .await;
    let short: String = std::iter::once("t,CH1,CH2\n".to_string())
        .chain((0..40).map(|k| {
            format!(
                "{},{},{}\n",
                k as f64 * 1e-6,
                (k as f64 * 0.01).sin(),
                0.1 * k as f64
            )
        }))
        .collect();
    post_refused(fit, short, bad, "scope.csv", Some("record")).await;
    let one: String = std::iter::once("t,CH1\n".to_string())
        .chain((0..40).map(|k| format!("{},{}\n", k as f64 * 1e-6, (k as f64 * 0.3).sin())))
        .collect();
    post_refused(fit, one, bad, "missing", Some("record")).await;
    // A channel that is not there.
    post_refused(
        "/api/fit?preset=paper&drive=CH7",
        good.clone(),
        bad,
        "CH7",
        Some("drive"),
    )
    .await;
    post_refused(
        "/api/record?response=volts",
        good.clone(),
        bad,
        "volts",
        Some("response"),
    )
    .await;
    // Empty and non-text bodies.
    post_refused(fit, "", bad, "no record", Some("record")).await;
    post_refused(
        fit,
        vec![0xff, 0xfe, b'a'],
        bad,
        "not UTF-16 text",
        Some("record"),
    )
    .await;
    post_refused(fit, vec![b'X', 0, b'1'], bad, "byte 2 is 0", Some("record")).await;
    // The keys: free parameters, the drive (the record's), a mechanical oscillator, others.
    post_refused(
        "/api/fit?preset=paper&free=zeta",
        good.clone(),
        bad,
        "unknown fit parameter \"zeta\"",
        Some("free"),
    )
    .await;
    post_refused(
        "/api/fit?preset=paper&free=diode-n",
        good.clone(),
        bad,
        "not a parameter of the pwl diode law",
        Some("free"),
    )
    .await;
    post_refused(
        "/api/fit?preset=paper&model=shockley&free=ut",
        good.clone(),
        bad,
        "ut is not a parameter of the shockley",
        Some("free"),
    )
    .await;
    post_refused(
        "/api/fit?preset=paper&free=resistance,resistance",
        good.clone(),
        bad,
        "twice",
        Some("free"),
    )
    .await;
    post_refused(
        "/api/fit?preset=paper&free=,",
        good.clone(),
        bad,
        "at least one",
        Some("free"),
    )
    .await;
    post_refused(
        "/api/fit?preset=paper&freq=5k",
        good.clone(),
        bad,
        "drop freq",
        Some("freq"),
    )
    .await;
    post_refused(
        "/api/fit?preset=paper&w=0.5",
        good.clone(),
        bad,
        "drop w",
        Some("w"),
    )
    .await;
    post_refused(
        "/api/fit?mass=1&stiffness=1&damping=0.1&friction=0.1",
        good.clone(),
        bad,
        "needs a circuit",
        None,
    )
    .await;
    post_refused(
        "/api/fit?preset=paper&resistance=-1",
        good.clone(),
        bad,
        "resistance",
        Some("resistance"),
    )
    .await;
    post_refused(
        "/api/fit?preset=paper&samples=3",
        good.clone(),
        bad,
        "unknown key 'samples'",
        Some("samples"),
    )
    .await;
    post_refused(
        "/api/record?preset=paper",
        good.clone(),
        bad,
        "unknown key 'preset'",
        Some("preset"),
    )
    .await;
    post_refused(
        &format!("/api/fit?file={}", "x".repeat(200)),
        good,
        bad,
        "1 to 120 characters",
        Some("file"),
    )
    .await;
    // Other methods.
    let (status, body) = get("/api/fit?preset=paper").await;
    assert_eq!(status, StatusCode::METHOD_NOT_ALLOWED, "{body}");
    assert!(body["error"]
        .as_str()
        .unwrap()
        .contains("POST at /api/record and /api/fit"));
}

/// A Rigol record's channel `k` (1 or 2) as a Tektronix file (one file per channel).
fn tektronix_file(rigol: &str, k: usize) -> String {
    let record = stickslip::measure::read_scope(rigol, "r.csv").unwrap();
    let header = [
        ("Record Length", format!("{:.6e}", record.len())),
        ("Sample Interval", format!("{:.6e}", record.sample_interval)),
        ("Trigger Point", "6.000000000000e+02".into()),
        ("", String::new()),
        ("Source", format!("CH{k}")),
        ("Vertical Units", "V".into()),
    ];
    let mut text = String::new();
    for (i, (t, v)) in record
        .time
        .iter()
        .zip(&record.channels[k - 1].values)
        .enumerate()
    {
        let (key, value) = header.get(i).cloned().unwrap_or(("", String::new()));
        text += &format!("{key},{value},,{t:.9e},{v:.6e},\r\n");
    }
    text
}

/// POST a JSON body of files.
async fn post_files(uri: &str, files: &[(&str, &str)]) -> (StatusCode, Value) {
    let body = serde_json::json!({
        "files": files.iter().map(|(n, t)| serde_json::json!({"name": n, "text": t})).collect::<Vec<_>>()
    });
    let response = router(lab(Duration::from_secs(120)))
        .oneshot(
            Request::post(uri)
                .header("content-type", "application/json")
                .body(Body::from(body.to_string()))
                .unwrap(),
        )
        .await
        .unwrap();
    let status = response.status();
    let body = axum::body::to_bytes(response.into_body(), usize::MAX)
        .await
        .unwrap();
    (status, serde_json::from_slice(&body).unwrap())
}

#[tokio::test]
async fn a_tektronix_export_is_sent_as_its_files_and_merged() {
    let rigol = rigol_record_bits(0.5, 2.5, 0.3, 12);
    let (c1, c2) = (tektronix_file(&rigol, 1), tektronix_file(&rigol, 2));
    let files = [("c1.csv", c1.as_str()), ("c2.csv", c2.as_str())];
    let (status, answer) = post_files("/api/record", &files).await;
    assert_eq!(status, StatusCode::OK, "{answer}");
    assert_eq!(answer["file"], "c1.csv+c2.csv");
    assert_eq!(answer["format"], "merged");
    assert_eq!(answer["drive_channel"], "CH1");
    assert_eq!(answer["response_channel"], "CH2");
    // The fit of the merged files is the library's fit of the same files merged, and finds
    // the circuit.
    let (status, answer) = post_files("/api/fit?preset=paper", &files).await;
    assert_eq!(status, StatusCode::OK, "{answer}");
    let merged = stickslip::measure::Record::merge(vec![
        stickslip::measure::read_scope(&c1, "c1.csv").unwrap(),
        stickslip::measure::read_scope(&c2, "c2.csv").unwrap(),
    ])
    .unwrap();
    let m = stickslip::measure::Measurement::new(&merged, None, None).unwrap();
    let report = stickslip::fit::fit_records(
        &spec(Some(Preset::Paper), None, &[]),
        &[m],
        &[
            stickslip::fit::FitParameter::Resistance,
            stickslip::fit::FitParameter::Ut,
        ],
        &stickslip::fit::FitOptions::default(),
    )
    .unwrap();
    same_keys(&answer, &serde_json::to_value(report.to_json()).unwrap());
    let r = answer["parameters"]["resistance"]["value"]
        .as_f64()
        .unwrap();
    assert!((r / TRUE_R - 1.0).abs() < 0.01, "R = {r}");
    // Files that do not share their times, bad JSON, too many files: 400s about the record.
    let short = c2.lines().take(600).collect::<Vec<_>>().join("\n");
    let (status, answer) = post_files("/api/record", &[("c1.csv", &c1), ("c2.csv", &short)]).await;
    assert_eq!(status, StatusCode::BAD_REQUEST);
    assert!(
        answer["error"]
            .as_str()
            .unwrap()
            .starts_with("c2.csv: 600 samples"),
        "{answer}"
    );
    assert_eq!(answer["field"], "record");
    let (status, answer) = post_files("/api/record", &[]).await;
    assert_eq!(status, StatusCode::BAD_REQUEST);
    assert!(
        answer["error"]
            .as_str()
            .unwrap()
            .contains("send 1 to 4 files"),
        "{answer}"
    );
    let response = router(lab(Duration::from_secs(60)))
        .oneshot(
            Request::post("/api/record")
                .header("content-type", "application/json")
                .body(Body::from(r#"{"files": [{"name": "a", "txt": "b"}]}"#))
                .unwrap(),
        )
        .await
        .unwrap();
    assert_eq!(response.status(), StatusCode::BAD_REQUEST);
    let body = axum::body::to_bytes(response.into_body(), usize::MAX)
        .await
        .unwrap();
    let answer: Value = serde_json::from_slice(&body).unwrap();
    assert!(
        answer["error"]
            .as_str()
            .unwrap()
            .contains("the JSON body must be"),
        "{answer}"
    );
}

#[tokio::test]
async fn records_over_the_upload_cap_are_refused_naming_it() {
    let cap = stickslip::limits::Caps::shared_server().upload_bytes;
    assert_eq!(cap, 2 * 1024 * 1024);
    // The page reads the cap from /api/keys.
    let (_, keys) = get("/api/keys").await;
    assert_eq!(keys["caps"]["upload_bytes"], cap);
    // One byte over (a valid record's head, then padding): 413, naming the cap.
    let mut big = rigol_record(0.95, 2.5, 0.0).into_bytes();
    big.resize(cap + 1, b'\n');
    for uri in ["/api/fit?preset=paper", "/api/record"] {
        post_refused(
            uri,
            big.clone(),
            StatusCode::PAYLOAD_TOO_LARGE,
            "cap of 2 MB (2097152 bytes)",
            None,
        )
        .await;
    }
    // Without a Content-Length (a stream): the same as soon as the cap is passed.
    let chunks: Vec<Vec<u8>> = big.chunks(64 * 1024).map(<[u8]>::to_vec).collect();
    let response = router(lab(Duration::from_secs(60)))
        .oneshot(
            Request::post("/api/record")
                .body(Body::new(Chunks(chunks.into_iter())))
                .unwrap(),
        )
        .await
        .unwrap();
    assert_eq!(response.status(), StatusCode::PAYLOAD_TOO_LARGE);
    // At the cap, a record is read (the padding is blank lines at its end).
    let mut at_cap = rigol_record(0.95, 2.5, 0.0).into_bytes();
    at_cap.resize(cap, b'\n');
    let (status, answer) = post("/api/record", at_cap).await;
    assert_eq!(status, StatusCode::OK, "{answer}");
}

/// A body of chunks of unknown length in all (no Content-Length).
struct Chunks(std::vec::IntoIter<Vec<u8>>);

impl axum::body::HttpBody for Chunks {
    type Data = axum::body::Bytes;
    type Error = std::convert::Infallible;

    fn poll_frame(
        mut self: std::pin::Pin<&mut Self>,
        _: &mut std::task::Context<'_>,
    ) -> std::task::Poll<Option<Result<hyper::body::Frame<Self::Data>, Self::Error>>> {
        std::task::Poll::Ready(
            self.0
                .next()
                .map(|c| Ok(hyper::body::Frame::data(axum::body::Bytes::from(c)))),
        )
    }
}

#[tokio::test]
async fn the_time_limit_stops_a_fit() {
    // A Shockley fit (finite differences, a numerical solver) takes seconds; the limit is a
    // few of its steady states. (A PWL fit with exact Jacobians can end within the limit.)
    let lab = lab(Duration::from_millis(20));
    let text = rigol_record(0.5, 2.5, 0.3);
    let uri = "/api/fit?preset=paper&model=shockley&free=resistance,diode-is,diode-n";
    let (status, answer) = post_with(&lab, uri, text.into_bytes()).await;
    assert_eq!(status, StatusCode::SERVICE_UNAVAILABLE, "{answer}");
    let message = answer["error"].as_str().unwrap();
    assert!(message.contains("time limit of 0.02 s"), "{message}");
    assert!(
        until_active(&lab, 0).await,
        "the fit kept running after its time limit"
    );
}

/// Issue 36: a bad friction law is a 400 naming the field (vs ≤ 0, δ ≤ 0, a cubic law that
/// goes negative), and a good one is solved.
#[tokio::test]
async fn a_bad_friction_law_is_a_400_naming_its_field() {
    let bad = StatusCode::BAD_REQUEST;
    let belt = "zeta=0.05&mu-s=1.5&vb=0.3";
    for (law, key) in [
        ("friction-law=stribeck&vs=0", "vs"),
        ("friction-law=stribeck&vs=0.1&delta=-1", "delta"),
        ("friction-law=cubic&k1=5&k3=0.1", "k1"),
    ] {
        let uri = format!("/api/steady?{belt}&{law}");
        let body = refused(&uri, bad, key).await;
        assert_eq!(body["field"], key, "{uri}: {body}");
    }
}
