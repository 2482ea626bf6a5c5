//! `continue` with the Stribeck law on a forced belt: where a turning point reaches the static
//! limit the branch passes a grazing point (the law starts from μs, so the map stays
//! continuous) and goes on to the end of its range; the point's value agrees with the zero
//! of the turn's margin |f| − μs on the orbits `orbit --json` finds beside it.

use crate::common::*;

const MODEL: [&str; 16] = [
    "--zeta",
    "0.05",
    "--w",
    "1",
    "--vb",
    "0.5",
    "--mu-s",
    "1.5",
    "--friction-law",
    "stribeck",
    "--vs",
    "0.3",
    "--delta",
    "2",
    "--eta",
    "0.05",
];

/// |f| − μs, f = β cos(wτ) − y − 2ζ vb, at the turning point of `orbit --json` at β.
fn turn_margin(beta: f64) -> f64 {
    let b = beta.to_string();
    let (_d, out) = run(&[&["orbit"][..], &MODEL, &["--beta", &b, "--json"]].concat());
    assert!(out.status.success(), "{}", stderr(&out));
    let orbit: serde_json::Value = serde_json::from_str(&stdout(&out)).unwrap();
    let events = orbit["events"].as_array().unwrap();
    let turns: Vec<f64> = events
        .iter()
        .filter(|e| e["kind"] == "turn")
        .map(|e| {
            let (tau, y) = (e["tau"].as_f64().unwrap(), e["y"].as_f64().unwrap());
            (beta * tau.cos() - y - 2.0 * 0.05 * 0.5).abs() - 1.5
        })
        .collect();
    assert_eq!(turns.len(), 2, "β = {beta}: {events:?}");
    turns
        .into_iter()
        .min_by(|a, b| a.abs().total_cmp(&b.abs()))
        .unwrap()
}

#[test]
fn continue_with_the_stribeck_law_passes_a_turning_point_at_the_static_limit() {
    let (_d, out) = run(&[
        &["continue"][..],
        &MODEL,
        &[
            "--over",
            "beta",
            "--from",
            "2",
            "--to",
            "1.5",
            "--max-step",
            "0.05",
            "--json",
        ],
    ]
    .concat());
    assert!(out.status.success(), "{}", stderr(&out));
    let report: serde_json::Value = serde_json::from_str(&stdout(&out)).unwrap();
    assert_eq!(report["end"]["reason"], "boundary", "{}", report["end"]);
    assert_eq!(report["end_text"], "the end of the range at 1.5");
    let grazing: Vec<&serde_json::Value> = report["special"]
        .as_array()
        .unwrap()
        .iter()
        .filter(|s| s["kind"] == "grazing")
        .collect();
    assert_eq!(grazing.len(), 1, "{}", report["special"]);
    let g = grazing[0];
    let counts = |side: &serde_json::Value| (side["turns"].as_u64(), side["stops"].as_u64());
    assert_eq!(counts(&g["before"]), (Some(2), Some(0)));
    assert_eq!(counts(&g["after"]), (Some(1), Some(1)));
    assert_eq!(g["located"], true);
    let value = g["value"].as_f64().unwrap();
    assert!(
        stderr(&out).contains(&format!("grazing at beta = {value:.10}")),
        "{}",
        stderr(&out)
    );
    // The margin falls linearly to zero there: the secant through β + 1e-4 and β + 2e-4.
    let (b1, b2) = (value + 1e-4, value + 2e-4);
    let (m1, m2) = (turn_margin(b1), turn_margin(b2));
    let zero = b1 - m1 * (b2 - b1) / (m2 - m1);
    println!("grazing at {value}, margins {m1:e} at {b1}, {m2:e} at {b2}: zero at {zero}");
    assert!(m1 > 0.0 && m2 > m1, "{m1} {m2}");
    assert!((zero - value).abs() <= 1e-6, "{zero} against {value}");
}
