//! Tests of `stickslip sweep`.

use crate::common::*;

#[test]
fn csv_columns_and_both_legs() {
    let (dir, out) = run(&[
        "sweep", "--over", "w", "--beta", "1.6", "--from", "0.8", "--to", "1.0", "--steps", "3",
        "--out", "s.csv", "--plot", "s.png",
    ]);
    assert!(out.status.success(), "{}", stderr(&out));
    let csv = std::fs::read_to_string(dir.path().join("s.csv")).unwrap();
    let lines: Vec<&str> = csv.lines().collect();
    assert_eq!(
        lines[0],
        "w,beta,direction,gain,gain1,A1,A3,class,stops_per_period"
    );
    assert_eq!(lines.len(), 7);
    assert!(lines[1].starts_with("0.8,1.6,up,"));
    assert!(lines[3].starts_with("1,1.6,up,"));
    assert!(lines[4].starts_with("1,1.6,down,"));
    assert!(lines[6].starts_with("0.8,1.6,down,"));
    let png = std::fs::read(dir.path().join("s.png")).unwrap();
    assert_eq!(&png[1..4], b"PNG");
}

/// With μs = 1.5 the oscillator stays at rest when β rises from rest to 1.4 but keeps moving
/// when β falls from 2 to 1.4: two coexisting motions, two branches.
#[test]
fn hysteresis_shows_two_branches() {
    let (_dir, out) = run(&[
        "sweep",
        "--over",
        "beta",
        "--w",
        "0.9",
        "--mu-s",
        "1.5",
        "--from",
        "1.0",
        "--to",
        "2.0",
        "--steps",
        "11",
        "--direction",
        "both",
    ]);
    assert!(out.status.success(), "{}", stderr(&out));
    let text = stdout(&out);
    let row = |leg: &str| -> Vec<String> {
        text.lines()
            .find(|l| l.starts_with(&format!("0.9,1.4,{leg},")))
            .unwrap_or_else(|| panic!("no {leg} row at 1.4 in {text}"))
            .split(',')
            .map(String::from)
            .collect()
    };
    let (up, down) = (row("up"), row("down"));
    assert_eq!(up[7], "static");
    assert_ne!(down[7], "static");
    let gain: f64 = down[3].parse().unwrap();
    assert!(gain > 1.0, "{gain}");
    assert!(stderr(&out).contains("differ"), "{}", stderr(&out));
}

#[test]
fn bad_ranges_give_one_line_and_exit_code_2() {
    let base = ["sweep", "--over", "w", "--beta", "2"];
    let cases: &[(&[&str], &str)] = &[
        (&["--from", "2", "--to", "1", "--steps", "5"], "--from"),
        (&["--from", "1", "--to", "2", "--steps", "0"], "--steps"),
        (&["--from", "1", "--to", "2", "--steps", "-1"], "--steps"),
        (&["--from", "1", "--to", "2", "--steps", "1"], "--steps"),
        (&["--from", "nan", "--to", "2", "--steps", "5"], "--from"),
        (&["--from", "1", "--to", "inf", "--steps", "5"], "--to"),
        (&["--from", "0", "--to", "2", "--steps", "5"], "w"),
        (&["--from", "1", "--to", "2"], "required"),
        (
            &["--from", "1", "--to", "2", "--steps", "3", "--w", "1"],
            "--w",
        ),
        (
            &[
                "--from",
                "1",
                "--to",
                "2",
                "--steps",
                "3",
                "--direction",
                "sideways",
            ],
            "--direction",
        ),
        (
            &[
                "--from",
                "1",
                "--to",
                "2",
                "--steps",
                "3",
                "--out",
                "nope/s.csv",
            ],
            "nope",
        ),
    ];
    assert_usage_errors(&base, cases);
    let dir = tempfile::tempdir().unwrap();
    let out = run_in(
        dir.path(),
        &[
            "sweep", "--over", "beta", "--from", "1", "--to", "2", "--steps", "3",
        ],
    );
    assert_usage_error(dir.path(), &out, "--w");
}

/// Count from the line "theory on the plot: paper's gain at P and exact sliding orbit at E of
/// N values" on standard error.
fn theory_counts(err: &str, what: &str) -> (usize, usize, usize) {
    let line = err
        .lines()
        .find(|l| l.contains("theory on the plot"))
        .unwrap_or_else(|| panic!("no theory line in {err}"));
    let numbers: Vec<usize> = line
        .split(|c: char| !c.is_ascii_digit())
        .filter_map(|s| s.parse().ok())
        .collect();
    assert_eq!(numbers.len(), 3, "{what}: {line}");
    (numbers[0], numbers[1], numbers[2])
}

#[test]
fn plot_over_w_carries_the_theorys_gain_curves() {
    // β = 2.14 from w = 0.2 (stops, no sliding orbit) to 2 (sliding): the exact curve
    // exists over part of the range only, the paper's everywhere.
    let (dir, out) = run(&[
        "sweep",
        "--over",
        "w",
        "--beta",
        "2.14",
        "--from",
        "0.2",
        "--to",
        "2",
        "--steps",
        "4",
        "--direction",
        "up",
        "--out",
        "s.csv",
        "--plot",
        "s.svg",
    ]);
    assert!(out.status.success(), "{}", stderr(&out));
    let (paper, exact, n) = theory_counts(&stderr(&out), "over w");
    assert_eq!(n, 200);
    assert_eq!(paper, n);
    assert!(exact > n / 2 && exact < n, "{exact}");
    let svg = std::fs::read_to_string(dir.path().join("s.svg")).unwrap();
    // One gain on the axis: the simulated points, the paper's formula and the exact orbit
    // all as G1 = A1/β (not the gain G beside G1), said in the legend and the axis label.
    assert!(svg.contains("paper, eq. (11): G1"));
    assert!(svg.contains("exact sliding orbit: G1"));
    assert!(svg.contains("G1 = A1/β"));
    assert!(!svg.contains("gain G "));
    assert!(!svg.contains("peak"));
    assert!(!svg.contains("PWL theory"));
    // Symbols as in every other plot.
    assert!(
        svg.contains("β = 2.140") && !svg.contains("beta ="),
        "title"
    );
    assert_eq!(
        std::fs::read_to_string(dir.path().join("s.csv"))
            .unwrap()
            .lines()
            .count(),
        5
    );
}

#[test]
fn plot_over_beta_carries_the_theory_and_shockley_labels_it_pwl() {
    let (dir, out) = run(&[
        "sweep",
        "--over",
        "beta",
        "--w",
        "0.9",
        "--from",
        "0.5",
        "--to",
        "3",
        "--steps",
        "3",
        "--direction",
        "down",
        "--plot",
        "b.png",
        "--out",
        "b.csv",
    ]);
    assert!(out.status.success(), "{}", stderr(&out));
    let (paper, exact, n) = theory_counts(&stderr(&out), "over beta");
    // Below β_c ≈ 1.33 there is no sliding orbit; the paper's A1 needs β > 4/π.
    assert!(exact > 0 && exact < n && paper > 0 && paper < n);
    let png = std::fs::read(dir.path().join("b.png")).unwrap();
    assert_eq!(&png[1..4], b"PNG");

    let (dir, out) = run(&[
        "sweep",
        "--preset",
        "paper",
        "--model",
        "shockley",
        "--over",
        "w",
        "--beta",
        "2",
        "--from",
        "0.8",
        "--to",
        "1.0",
        "--steps",
        "2",
        "--direction",
        "up",
        "--plot",
        "s.svg",
        "--out",
        "s.csv",
    ]);
    assert!(out.status.success(), "{}", stderr(&out));
    let svg = std::fs::read_to_string(dir.path().join("s.svg")).unwrap();
    assert!(svg.contains("PWL theory: paper, eq. (11): G1"));
    assert!(svg.contains("PWL theory: exact sliding orbit: G1"));
}
