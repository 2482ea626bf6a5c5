//! Issue 36: the mechanical oscillator on a moving belt, with its friction law. The form's
//! belt and law fields come from the key table; a self-excited belt's steady state is the
//! library's, with its one cycle as the trace; its bad laws are 400s naming their field.

use super::{experiment, get, refused, same_keys};
use axum::http::StatusCode;
use serde_json::Value;
use stickslip::steady::{self_excited_trace, steady_state_from, SteadyReport};

/// The example's oscillator (m = 0.5 kg, k = 200 N/m, γ = 0.94 N·s/m, F0 = 1 N: 0.1 m/s per
/// unit of y') on a belt at 3 cm/s (vb = 0.3), μs = 1.5, without a drive.
const BELT: &str =
    "mass=0.5&stiffness=200&damping=0.94&friction=1&mu-s=1.5&belt-speed=0.03&freq=3&amplitude=0";

fn numbers(value: &Value) -> Vec<f64> {
    value
        .as_array()
        .unwrap_or_else(|| panic!("an array: {value}"))
        .iter()
        .map(|v| v.as_f64().unwrap())
        .collect()
}

#[tokio::test]
async fn the_mechanical_form_takes_the_belt_and_the_laws_from_the_key_table() {
    let (status, keys) = get("/api/keys").await;
    assert_eq!(status, StatusCode::OK);
    let mechanics: Vec<&Value> = keys["form"]
        .as_array()
        .unwrap()
        .iter()
        .filter(|f| f["fieldset"] == "mechanics")
        .collect();
    let flags: Vec<&str> = mechanics
        .iter()
        .map(|f| f["flag"].as_str().unwrap())
        .collect();
    // The parts, μs, and the belt and law in physical units where the table has them (no
    // dimensionless vb, vs, eta, k1, k3 beside the mechanical parts).
    assert_eq!(
        flags,
        [
            "mu-s",
            "mass",
            "stiffness",
            "damping",
            "friction",
            "belt-speed",
            "friction-law",
            "stribeck-speed",
            "delta",
            "viscous-friction",
            "cubic-k1",
            "cubic-k3"
        ]
    );
    let field = |flag: &str| *mechanics.iter().find(|f| f["flag"] == flag).unwrap();
    let law = field("friction-law");
    assert_eq!(law["chooses_law"], true);
    assert_eq!(
        law["choices"],
        serde_json::json!(["coulomb", "stribeck", "cubic"])
    );
    assert_eq!(law["value"], "coulomb");
    assert_eq!(field("delta")["value"], "2");
    for (flag, law, unit) in [
        ("stribeck-speed", Some("stribeck"), "m/s"),
        ("delta", Some("stribeck"), ""),
        ("viscous-friction", Some("stribeck"), "N·s/m"),
        ("cubic-k1", Some("cubic"), "N·s/m"),
        ("cubic-k3", Some("cubic"), "N·s³/m³"),
        ("belt-speed", None, "m/s"),
        ("friction-law", None, ""),
        ("mass", None, "kg"),
    ] {
        assert_eq!(field(flag)["law"].as_str(), law, "{flag}");
        assert_eq!(field(flag)["unit"], unit, "{flag}");
        assert_eq!(field(flag)["chooses_law"], flag == "friction-law", "{flag}");
    }
}

#[tokio::test]
async fn a_self_excited_belt_is_the_library_cycle_with_its_trace() {
    let query = format!("{BELT}&friction-law=stribeck&stribeck-speed=0.05");
    let (status, answer) = get(&format!("/api/steady?{query}&samples=256")).await;
    assert_eq!(status, StatusCode::OK, "{answer}");
    let e = experiment(&query);
    assert!(e.is_self_excited());
    let params = e.params().unwrap();
    let steady = e.steady().unwrap();
    same_keys(
        &answer,
        &serde_json::to_value(SteadyReport::from(&steady)).unwrap(),
    );
    assert_eq!(answer["class"], "stick-slip-cycle");
    assert_eq!(answer["friction_law"], "stribeck");
    assert_eq!(answer["vb"].as_f64().unwrap(), params.vb);
    let cycle = steady.self_excited.unwrap();
    let period = cycle.period.unwrap();
    let omega0 = e.scales().unwrap().omega0;
    assert_eq!(answer["cycle_period_s"].as_f64().unwrap(), period / omega0);
    // The trace: the one cycle, 256 samples from its section, as the library runs it again.
    let trace = &answer["trace"];
    assert_eq!(trace["samples_per_period"], 256);
    assert_eq!(trace["periods"], 1.0);
    assert_eq!(trace["span_tau"].as_f64().unwrap(), period);
    assert_eq!(trace["span_s"].as_f64().unwrap(), period / omega0);
    assert_eq!(trace["start"].as_f64().unwrap(), steady.start);
    let samples = self_excited_trace(&e.factory(), &steady, 256)
        .unwrap()
        .unwrap();
    let (tau, y, v) = (
        numbers(&trace["columns"]["tau"]),
        numbers(&trace["columns"]["y"]),
        numbers(&trace["columns"]["v"]),
    );
    assert_eq!(tau, samples.iter().map(|s| s.tau).collect::<Vec<_>>());
    assert_eq!(y, samples.iter().map(|s| s.y).collect::<Vec<_>>());
    assert_eq!(numbers(&trace["columns"]["drive"]), vec![0.0; 256]);
    // It rides on the belt (y' = vb to the last bit) for its stick fraction of the cycle,
    // and stays within the cycle's extremes.
    let stuck = v.iter().filter(|&&v| v == params.vb).count() as f64 / 256.0;
    assert!(
        (stuck - cycle.stick_fraction).abs() <= 2.0 / 256.0,
        "{stuck} against {}",
        cycle.stick_fraction
    );
    assert!(y
        .iter()
        .all(|&y| y >= steady.y_min - 1e-9 && y <= steady.y_max + 1e-9));
    let r = numbers(&trace["columns"]["r_m"]);
    let scales = e.scales().unwrap();
    assert_eq!(r[7], y[7] * scales.position);
}

#[tokio::test]
async fn a_forced_belt_and_a_run_on_the_belt_are_the_library_answers() {
    // A forced Stribeck belt: the steady state with its drive-period quantities, y_max and
    // y_min, and the trace of its drive periods.
    let query = BELT.replace("amplitude=0", "amplitude=0.8")
        + "&friction-law=stribeck&stribeck-speed=0.05&viscous-friction=0.5";
    let (status, answer) = get(&format!("/api/steady?{query}")).await;
    assert_eq!(status, StatusCode::OK, "{answer}");
    let e = experiment(&query);
    assert!(!e.is_self_excited());
    let params = e.params().unwrap();
    let steady = steady_state_from(
        &e.factory(),
        &params,
        e.initial(),
        &e.steady_options()
            .with_accelerate(true)
            .with_lyapunov(Some(stickslip::SteadyOptions::DEFAULT_LYAPUNOV))
            .unwrap(),
    )
    .unwrap();
    let report = serde_json::to_value(SteadyReport::from(&steady)).unwrap();
    for key in [
        "class",
        "period",
        "y_max",
        "y_min",
        "vb",
        "friction_law",
        "gain",
    ] {
        assert_eq!(answer[key], report[key], "{key}");
    }
    assert!(answer.get("cycle_period_s").is_none());
    let span = answer["trace"]["span_tau"].as_f64().unwrap();
    assert_eq!(span, steady.recorded_periods as f64 * params.drive_period());

    // The run from rest on the belt: the library's trajectory report.
    let query = format!("{BELT}&friction-law=cubic&cubic-k1=10&cubic-k3=500");
    let (status, answer) = get(&format!("/api/simulate?{query}&periods=2&samples=100")).await;
    assert_eq!(status, StatusCode::OK, "{answer}");
    let report = experiment(&query)
        .trajectory(2.0, 100)
        .unwrap()
        .collect_report()
        .unwrap();
    let expected = serde_json::to_value(&report).unwrap();
    for key in ["tau", "y", "v", "phase", "r_m", "events"] {
        assert_eq!(answer[key], expected[key], "{key}");
    }
    assert!(answer["phase"]
        .as_array()
        .unwrap()
        .iter()
        .any(|p| p == "stick"));
}

#[tokio::test]
async fn coulomb_at_rest_sent_in_full_is_todays_answer() {
    // The page sends the belt's speed and the law with every mechanical query: at 0 m/s and
    // Coulomb's law the answer is the one without them, to the bit.
    let base = "mass=0.5&stiffness=200&damping=0.94&friction=1&mu-s=1.5&w=0.95&beta=2.14";
    let (_, plain) = get(&format!("/api/steady?{base}")).await;
    let (status, full) = get(&format!(
        "/api/steady?{base}&belt-speed=0&friction-law=coulomb&delta=2"
    ))
    .await;
    assert_eq!(
        status,
        StatusCode::BAD_REQUEST,
        "δ belongs to the Stribeck law: {full}"
    );
    assert_eq!(full["field"], "delta");
    let (status, full) = get(&format!(
        "/api/steady?{base}&belt-speed=0&friction-law=coulomb"
    ))
    .await;
    assert_eq!(status, StatusCode::OK, "{full}");
    assert_eq!(plain, full);
    assert_eq!(full["experiment"], experiment(base).to_string());
}

/// Issue 36, item 3: a bad law from the mechanical form is a 400 naming the field the page
/// shows (the physical key typed), with the library's words.
#[tokio::test]
async fn the_mechanical_laws_bad_values_are_400s_naming_their_field() {
    let bad = StatusCode::BAD_REQUEST;
    for (law, key, needle) in [
        (
            "friction-law=stribeck&stribeck-speed=0",
            "stribeck-speed",
            "stribeck-speed",
        ),
        (
            "friction-law=stribeck&stribeck-speed=-0.01",
            "stribeck-speed",
            "> 0",
        ),
        (
            "friction-law=stribeck&stribeck-speed=0.05&delta=0",
            "delta",
            "delta",
        ),
        (
            "friction-law=stribeck&stribeck-speed=0.05&delta=-1",
            "delta",
            "delta",
        ),
        // 4·k1³ > 27·μs²·k3: the law goes negative (k1 = 5, k3 = 0.5 dimensionless).
        (
            "friction-law=cubic&cubic-k1=50&cubic-k3=500",
            "cubic-k1",
            "go negative",
        ),
        (
            "friction-law=cubic&cubic-k1=10&cubic-k3=-1",
            "cubic-k3",
            "cubic-k3",
        ),
        ("friction-law=dry", "friction-law", "coulomb"),
        ("friction-law=coulomb&cubic-k1=10", "cubic-k1", "cubic"),
        ("belt-speed=fast", "belt-speed", "fast"),
    ] {
        for endpoint in ["steady", "simulate"] {
            // (The belt's own speed replaced where the case gives it.)
            let base = if law.starts_with("belt-speed") {
                BELT.replace("&belt-speed=0.03", "")
            } else {
                BELT.to_string()
            };
            let uri = format!("/api/{endpoint}?{base}&{law}");
            let body = refused(&uri, bad, needle).await;
            assert_eq!(body["field"], key, "{uri}: {body}");
        }
    }
    // A circuit has no belt.
    let body = refused(
        "/api/steady?preset=paper&w=1&beta=2&belt-speed=0.1",
        bad,
        "belt",
    )
    .await;
    assert_eq!(body["field"], "belt-speed");
}

#[tokio::test]
async fn the_belt_presets_stick_and_slip_on_their_own() {
    let (status, presets) = get("/api/presets").await;
    assert_eq!(status, StatusCode::OK);
    let rows = presets["presets"].as_array().unwrap();
    let mechanics = rows.iter().find(|r| r["id"] == "mechanics").unwrap();
    assert_eq!(mechanics["values"]["friction-law"], "coulomb");
    assert_eq!(mechanics["values"]["belt-speed"], 0.0);
    for law in ["stribeck", "cubic"] {
        let row = rows
            .iter()
            .find(|r| r["id"] == format!("belt-{law}"))
            .unwrap_or_else(|| panic!("a {law} belt preset"));
        assert_eq!(row["system"], "mechanics");
        let query = row["values"]
            .as_object()
            .unwrap()
            .iter()
            .map(|(k, v)| match v {
                Value::String(s) => format!("{k}={s}"),
                v => format!("{k}={v}"),
            })
            .collect::<Vec<_>>()
            .join("&");
        let (status, steady) = get(&format!("/api/steady?{query}")).await;
        assert_eq!(status, StatusCode::OK, "{query}: {steady}");
        assert_eq!(steady["class"], "stick-slip-cycle", "{query}");
        assert_eq!(steady["sliding_stability"], "unstable", "{query}");
        assert_eq!(steady["vb"].as_f64().unwrap(), 0.3, "{query}");
        assert_eq!(row["drive"], steady["drive"], "{query}");
        // The starting values of the law's fields are the preset's.
        for (k, v) in presets["laws"][law].as_object().unwrap() {
            assert_eq!(&row["values"][k], v, "{law}: {k}");
        }
    }
}
