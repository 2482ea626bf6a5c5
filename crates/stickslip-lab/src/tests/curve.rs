//! `/api/curve`: the library's curve, its points as the columns of its table (the CSV of
//! `stickslip curve`, by name and number), its summary; no special point is an answer that
//! says so; bad input is a 400 naming the key.

use super::{get, get_with, lab, refused};
use axum::http::StatusCode;
use serde_json::Value;
use std::time::Duration;
use stickslip::continuation::{curve, ContinuationOptions, CurveReport, CurveSpec, Follow};
use stickslip::report::{Columns, CurveTable, Table};
use stickslip::theory::stick_slip_boundary;
use stickslip::{Experiment, Parameter};

/// The grazing curve of the paper's sliding orbit found from (w, β) = (0.7, 4) going down in
/// β, followed over w from 0.3 to 1.5: the exact stick-slip boundary.
const GRAZING: &str = "/api/curve?preset=paper&w=0.7&beta=4&follow=grazing&vary=beta&\
                       vary-to=0.5&over=w&from=0.3&to=1.5";

#[tokio::test]
async fn the_curve_is_the_librarys_table_and_report() {
    let (status, answer) = get(GRAZING).await;
    assert_eq!(status, StatusCode::OK, "{answer}");
    let experiment = Experiment::paper()
        .with_w(0.7)
        .unwrap()
        .with_beta(4.0)
        .unwrap();
    let spec = CurveSpec {
        follow: Follow::Grazing,
        vary: Parameter::Beta,
        vary_to: 0.5,
        over: Parameter::W,
        from: 0.3,
        to: 1.5,
    };
    let c = curve(&experiment, &spec, &ContinuationOptions::default(), &())
        .unwrap()
        .unwrap();
    let table = CurveTable { curve: &c };
    assert_eq!(answer["follow"], "grazing");
    assert_eq!(answer["none"], Value::Null);
    assert_eq!(
        answer["report"],
        serde_json::to_value(CurveReport::from(&c)).unwrap()
    );
    // The columns are the table's, in its order (the answer's text holds them so), cell for
    // cell the CSV's numbers.
    let (_, _, body) = get_with(&lab(Duration::from_secs(60)), GRAZING).await;
    let text = String::from_utf8(body).unwrap();
    let columns = serde_json::to_string(&Columns::of(&table)).unwrap();
    assert!(columns.starts_with(r#"{"w":[0.47"#), "{columns}");
    assert!(text.contains(&format!(r#""points":{columns}"#)));
    let points = answer["points"].as_object().unwrap();
    let mut names: Vec<String> = points.keys().cloned().collect();
    let mut expected = table.columns();
    names.sort_unstable();
    expected.sort_unstable();
    assert_eq!(names, expected);
    for i in 0..table.len() {
        for (name, cell) in table.columns().iter().zip(table.row(i)) {
            let value = &points[name][i];
            let same = match value {
                Value::String(text) => *text == cell,
                Value::Number(n) if n.is_f64() => n.as_f64() == cell.parse::<f64>().ok(),
                Value::Number(n) => n.as_i64() == cell.parse::<i64>().ok(),
                _ => false,
            };
            assert!(same, "row {i}, {name}: {value} against the CSV's {cell}");
        }
    }
    // What the map draws: β_c(w) exactly, over the map's w range.
    let w = points["w"].as_array().unwrap();
    let beta = points["beta"].as_array().unwrap();
    assert!(w.len() > 20);
    for (w, beta) in w.iter().zip(beta) {
        let (w, beta) = (w.as_f64().unwrap(), beta.as_f64().unwrap());
        assert!((0.3..=1.5).contains(&w), "{w}");
        let exact = stick_slip_boundary(c.params.zeta, w, 1.0).unwrap().beta_c;
        assert!(
            (beta - exact).abs() < 1e-8,
            "w = {w}: {beta} against {exact}"
        );
    }
    assert!(answer["experiment"]
        .as_str()
        .unwrap()
        .contains("preset paper"));
}

#[tokio::test]
async fn no_special_point_of_the_kind_says_so() {
    let (status, answer) = get(&GRAZING.replace("follow=grazing", "follow=fold")).await;
    assert_eq!(status, StatusCode::OK, "{answer}");
    assert_eq!(answer["points"], Value::Null);
    assert_eq!(answer["report"], Value::Null);
    let none = answer["none"].as_str().unwrap();
    assert!(
        none.starts_with("no fold on the branch") && none.contains("beta from 4 towards 0.5"),
        "{none}"
    );
}

#[tokio::test]
async fn bad_input_is_a_400_naming_the_key() {
    let bad = StatusCode::BAD_REQUEST;
    for (change, field, needle) in [
        (
            ("follow=grazing", "follow=touch"),
            "follow",
            "invalid follow 'touch'",
        ),
        (("vary=beta", "vary=gamma"), "vary", "invalid vary 'gamma'"),
        // The two parameters named by their query keys, not the command line's flags.
        (
            ("vary=beta", "vary=w"),
            "vary",
            "invalid vary: must differ from over",
        ),
        (("to=1.5", "to=0.3"), "to", "must differ from from"),
        (("from=0.3", "from=x"), "from", "invalid from"),
        (("vary-to=0.5", "vary-to=4"), "vary-to", "invalid vary-to 4"),
        (
            ("over=w", "over=w&max-step=0"),
            "max-step",
            "invalid max-step 0",
        ),
        (
            ("over=w", "over=w&max-points=1"),
            "max-points",
            "invalid max-points 1",
        ),
        (("over=w", "over=w&steps=3"), "steps", "unknown key 'steps'"),
        (
            ("preset=paper", "preset=paper&inductance=-1"),
            "inductance",
            "inductance",
        ),
    ] {
        let uri = GRAZING.replace(change.0, change.1);
        assert_ne!(uri, GRAZING, "{change:?}");
        let body = refused(&uri, bad, needle).await;
        assert_eq!(body["field"], field, "{uri}: {body}");
    }
    // A missing end and a missing drive value name their keys.
    let body = refused(&GRAZING.replace("&to=1.5", ""), bad, "to").await;
    assert_eq!(body["field"], "to");
    let body = refused(&GRAZING.replace("&beta=4", ""), bad, "beta").await;
    assert_eq!(body["field"], "beta", "{body}");
    // The model's w outside from..to, and Shockley diodes, as the command-line tool says.
    refused(&GRAZING.replace("w=0.7", "w=2"), bad, "between from and to").await;
    refused(
        &GRAZING.replace("preset=paper", "preset=paper&model=shockley"),
        bad,
        "piecewise-linear",
    )
    .await;
    // The Coulomb model has no Neimark–Sacker point (docs/bifurcation.md): why, in one line.
    refused(
        &GRAZING.replace("follow=grazing", "follow=neimark-sacker"),
        bad,
        "has no Neimark–Sacker point",
    )
    .await;
}

/// A mechanical oscillator on a belt with the Stribeck law (ζ = 0.047, μs = 1.5, vb = 0.05,
/// vs = 0.3, η = 0.05 in the model's units): its stick-slip branch over w folds near w = 0.9.
const STRIBECK_BELT: &str = "mass=0.5&stiffness=200&damping=0.94&friction=1&mu-s=1.5&\
                             belt-speed=0.005&friction-law=stribeck&stribeck-speed=0.03&\
                             viscous-friction=0.5&w=0.7&beta=1.45";

/// A smooth law's fold curve is the library's; its grazing curve a 400 naming the law.
#[tokio::test]
async fn a_stribeck_belts_fold_curve_is_the_librarys_and_its_grazing_is_refused() {
    let uri = format!(
        "/api/curve?{STRIBECK_BELT}&follow=fold&vary=w&vary-to=1.2&over=beta&from=1.44&to=1.46"
    );
    let (status, answer) = get(&uri).await;
    assert_eq!(status, StatusCode::OK, "{answer}");
    let experiment = super::experiment(STRIBECK_BELT);
    let spec = CurveSpec {
        follow: Follow::Fold,
        vary: Parameter::W,
        vary_to: 1.2,
        over: Parameter::Beta,
        from: 1.44,
        to: 1.46,
    };
    let c = curve(&experiment, &spec, &ContinuationOptions::default(), &())
        .unwrap()
        .unwrap();
    assert!(c.points.len() > 4, "{} points", c.points.len());
    assert_eq!(answer["none"], Value::Null);
    assert_eq!(
        answer["report"],
        serde_json::to_value(CurveReport::from(&c)).unwrap()
    );
    let w = answer["points"]["w"].as_array().unwrap();
    assert_eq!(w.len(), c.points.len());
    refused(
        &uri.replace("follow=fold", "follow=grazing"),
        StatusCode::BAD_REQUEST,
        "with the stribeck law a curve follows a fold",
    )
    .await;
}
