//! Tests of `stickslip theory`.

use crate::common::*;
use std::f64::consts::PI;

fn json_of(args: &[&str]) -> serde_json::Value {
    let (_dir, out) = run(args);
    assert!(out.status.success(), "{}", stderr(&out));
    serde_json::from_str(&stdout(&out)).expect("valid JSON")
}

/// A1 of the paper's eq. (11) with ω0 = 1, Ω = w, α = 2ζ, written out here independently.
fn eq11_a1(zeta: f64, w: f64, beta: f64) -> f64 {
    let alpha = 2.0 * zeta;
    let z2 = (1.0 - w * w).powi(2) + alpha * alpha * w * w;
    (-4.0 * alpha * w + (PI * PI * beta * beta * z2 - 16.0 * (w * w - 1.0).powi(2)).sqrt())
        / (PI * z2)
}

#[test]
fn json_point_has_both_solutions() {
    let (_dir, out) = run(&[
        "theory", "--zeta", "0.0468", "--w", "0.9", "--beta", "2", "--json",
    ]);
    assert!(out.status.success(), "{}", stderr(&out));
    assert!(stderr(&out).contains("dimensionless"), "{}", stderr(&out));
    let v: serde_json::Value = serde_json::from_str(&stdout(&out)).unwrap();
    let paper = &v["paper"];
    let exact = &v["exact"];
    for key in ["A1", "A3", "A5", "phi0", "gain1", "beta_c"] {
        assert!(paper[key].is_f64(), "paper.{key}: {paper}");
    }
    assert_eq!(exact["exists"], true);
    for key in ["peak", "A1", "A3", "A5", "phase", "gain1", "beta_c"] {
        assert!(exact[key].is_f64(), "exact.{key}: {exact}");
    }
    let a1 = paper["A1"].as_f64().unwrap();
    assert!((a1 - eq11_a1(0.0468, 0.9, 2.0)).abs() < 1e-12 * a1);
    assert!((paper["gain1"].as_f64().unwrap() - a1 / 2.0).abs() < 1e-15);
    // The superharmonic amplitudes of eq. (11) are exact; A1 is not.
    let (pa3, ea3) = (paper["A3"].as_f64().unwrap(), exact["A3"].as_f64().unwrap());
    assert!((pa3 - ea3).abs() < 1e-12 * pa3);
    let ea1 = exact["A1"].as_f64().unwrap();
    assert!((a1 - ea1).abs() > 1e-3 * ea1);
    // Above both boundaries, nothing to note.
    assert!(paper.get("note").is_none() && exact.get("note").is_none());
    assert!(exact["beta_c"].as_f64().unwrap() < 2.0);
}

#[test]
fn values_that_do_not_exist_are_null_with_a_note() {
    // Undamped resonance: neither solution exists.
    let v = json_of(&["theory", "--zeta", "0", "--w", "1", "--beta", "4", "--json"]);
    assert!(v["paper"]["A1"].is_null() && v["paper"]["beta_c"].is_null());
    assert!(v["paper"]["note"].as_str().unwrap().contains("Z = 0"));
    assert_eq!(v["exact"]["exists"], false);
    assert!(v["exact"]["A1"].is_null() && v["exact"]["peak"].is_null());
    assert!(v["exact"]["note"].as_str().unwrap().contains("resonance"));
    // The paper's own low drive β = 1.07 < 4/π at w = 0.95: A1 < 0 in eq. (11); the exact
    // motion sticks, but the boundaries exist.
    let v = json_of(&[
        "theory", "--preset", "paper", "--w", "0.95", "--beta", "1.07", "--json",
    ]);
    assert!(v["paper"]["A1"].is_null() && v["paper"]["beta_c"].is_f64());
    assert!(v["paper"]["note"].as_str().unwrap().contains("4/π"));
    assert_eq!(v["exact"]["exists"], false);
    assert!(v["exact"]["beta_c"].as_f64().unwrap() > 1.07);
    assert!(v["exact"]["note"].is_string());
}

#[test]
fn text_shows_the_relative_error_of_the_paper() {
    let (_dir, out) = run(&[
        "theory", "--preset", "paper", "--w", "0.95", "--beta", "2.14",
    ]);
    assert!(out.status.success(), "{}", stderr(&out));
    assert!(stderr(&out).contains("preset paper"), "{}", stderr(&out));
    let text = stdout(&out);
    assert!(text.contains("paper error"), "{text}");
    let a1_row = text.lines().find(|l| l.starts_with("A1")).unwrap();
    let cells: Vec<&str> = a1_row.split_whitespace().collect();
    let (paper, exact): (f64, f64) = (cells[1].parse().unwrap(), cells[2].parse().unwrap());
    let shown: f64 = cells[3].trim_end_matches('%').parse().unwrap();
    assert!(
        (shown - 100.0 * (paper - exact) / exact).abs() < 0.01,
        "{a1_row}"
    );
    assert!(text.contains("β_c") && text.contains("exists"));
}

#[test]
fn near_w_one_half_the_continuum_is_noted() {
    let v = json_of(&[
        "theory", "--zeta", "0", "--w", "0.5", "--beta", "4", "--json",
    ]);
    assert_eq!(v["exact"]["exists"], true);
    assert!(v["exact"]["note"].as_str().unwrap().contains("continuum"));
    // Den Hartog at w = 1/2: β_c = (1 − w²)/w² = 3.
    assert!((v["exact"]["beta_c"].as_f64().unwrap() - 3.0).abs() < 1e-12);
}

#[test]
fn boundary_curve_writes_csv_and_plot() {
    let (dir, out) = run(&[
        "theory", "--zeta", "0.0468", "--curve", "boundary", "--w-min", "0.05", "--w-max", "10",
        "--steps", "40", "--log", "--out", "b.csv", "--plot", "b.png",
    ]);
    assert!(out.status.success(), "{}", stderr(&out));
    assert!(out.stdout.is_empty());
    let csv = std::fs::read_to_string(dir.path().join("b.csv")).unwrap();
    let mut lines = csv.lines();
    assert_eq!(lines.next(), Some("w,beta_c_paper,beta_c_exact"));
    let rows: Vec<Vec<f64>> = lines
        .map(|l| l.split(',').map(|c| c.parse().unwrap()).collect())
        .collect();
    // --steps counts points, as in every command.
    assert_eq!(rows.len(), 40);
    assert_eq!((rows[0][0], rows[39][0]), (0.05, 10.0));
    for r in &rows {
        let (w, paper, exact) = (r[0], r[1], r[2]);
        // Eq. (13) in closed form: β² = Z²/w⁴ + 16ζ/(πw) + 16/π².
        let z2 = (1.0 - w * w).powi(2) + (2.0 * 0.0468 * w).powi(2);
        let want = (z2 / w.powi(4) + 16.0 * 0.0468 / (PI * w) + 16.0 / (PI * PI)).sqrt();
        assert!((paper - want).abs() < 1e-12 * want, "w {w}");
        assert!(exact > 1.0 && exact.is_finite());
    }
    // Low frequencies: the exact boundary lies far above the paper's.
    assert!(rows[0][2] > 1.5 * rows[0][1]);
    let png = std::fs::read(dir.path().join("b.png")).unwrap();
    assert_eq!(&png[1..4], b"PNG");
}

#[test]
fn gain_curve_leaves_cells_empty_where_there_is_no_solution() {
    let (_dir, out) = run(&[
        "theory", "--zeta", "0.0468", "--curve", "gain1", "--beta", "1.5", "--w-min", "0.3",
        "--w-max", "2", "--steps", "17", "--plot", "g.svg",
    ]);
    assert!(out.status.success(), "{}", stderr(&out));
    let text = stdout(&out);
    let mut lines = text.lines();
    assert_eq!(lines.next(), Some("w,gain1_paper,gain1_exact"));
    let rows: Vec<Vec<&str>> = lines.map(|l| l.split(',').collect()).collect();
    assert_eq!(rows.len(), 17);
    assert!(rows.iter().all(|r| r.len() == 3));
    // β = 1.5 sticks at low w (empty exact cell) and slides near resonance.
    assert_eq!(rows[0][2], "");
    let near_one = rows
        .iter()
        .find(|r| (r[0].parse::<f64>().unwrap() - 1.0).abs() < 0.06)
        .unwrap();
    let (paper, exact): (f64, f64) = (near_one[1].parse().unwrap(), near_one[2].parse().unwrap());
    assert!(paper > 1.0 && exact > 1.0);
    let w: f64 = near_one[0].parse().unwrap();
    assert!((paper - eq11_a1(0.0468, w, 1.5) / 1.5).abs() < 1e-12);
}

#[test]
fn bad_input_gives_one_line_and_exit_code_2() {
    let cases: &[(&[&str], &str)] = &[
        (&["--zeta", "-1", "--w", "1", "--beta", "2"], "zeta"),
        (&["--zeta", "0.1", "--beta", "2"], "--w"),
        (&["--zeta", "0.1", "--w", "0", "--beta", "2"], "w"),
        (&["--w", "1", "--beta", "2", "--y0", "1"], "--y0"),
        (
            &[
                "--preset", "paper", "--w", "1", "--beta", "2", "--model", "shockley",
            ],
            "shockley",
        ),
        (&["--w", "1", "--beta", "2", "--w-min", "0.1"], "--w-min"),
        (
            &["--curve", "boundary", "--json", "--zeta", "0.1"],
            "--json",
        ),
        (&["--curve", "boundary", "--w-min", "0"], "--w-min"),
        (
            &["--curve", "boundary", "--w-min", "2", "--w-max", "1"],
            "--w-max",
        ),
        (&["--curve", "boundary", "--steps", "0"], "--steps"),
        (&["--curve", "boundary", "--steps", "1"], "--steps"),
        (&["--curve", "boundary", "--beta", "2"], "--beta"),
        (&["--curve", "boundary", "--w", "1"], "--w"),
        (&["--curve", "gain1"], "--beta"),
        (&["--curve", "boundary", "--plot", "b.txt"], "b.txt"),
        (
            &["--curve", "boundary", "--out", "missing/dir/b.csv"],
            "missing/dir",
        ),
        (&["--curve", "sideways"], "--curve"),
    ];
    assert_usage_errors(&["theory"], cases);
}
