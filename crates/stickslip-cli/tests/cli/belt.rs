//! A block on a moving belt at the command line: the self-excited steady state of the
//! undamped Coulomb belt against its closed form, the mechanical twin's belt speed in m/s,
//! a sweep of the belt speed up and down (hysteresis), and bad belt input refused in one
//! line.

use crate::common::*;

fn json(args: &[&str]) -> serde_json::Value {
    let (_dir, out) = run(args);
    assert!(out.status.success(), "{args:?}: {}", stderr(&out));
    serde_json::from_str(&stdout(&out)).unwrap()
}

/// The CSV that a run of `args` prints, the run checked to succeed and the CSV to begin with
/// `header`: its text (for messages) and the cells of its rows.
fn csv_rows(args: &[&str], header: &str) -> (String, Vec<Vec<String>>) {
    let (_dir, out) = run(args);
    assert!(out.status.success(), "{args:?}: {}", stderr(&out));
    let text = stdout(&out);
    let mut lines = text.lines();
    assert_eq!(lines.next().unwrap(), header, "{args:?}");
    let rows = lines
        .map(|l| l.split(',').map(String::from).collect())
        .collect();
    (text, rows)
}

/// ζ = 0, μs = 1.5, vb = 0.5: a circle of radius R = √((μs − 1)² + vb²) about y = 1 and a
/// stop of 2(μs − 1)/vb (`stickslip::theory::belt`).
#[test]
fn steady_finds_the_undamped_coulomb_belts_cycle() {
    let v = json(&[
        "steady", "--zeta", "0", "--mu-s", "1.5", "--vb", "0.5", "--json",
    ]);
    let (mu_s, vb) = (1.5f64, 0.5f64);
    let r = ((mu_s - 1.0).powi(2) + vb * vb).sqrt();
    let period = std::f64::consts::PI + 2.0 * vb.atan2(mu_s - 1.0) + 2.0 * (mu_s - 1.0) / vb;
    let close = |key: &str, want: f64| {
        let got = v[key].as_f64().unwrap_or_else(|| panic!("{key}: {v}"));
        assert!((got - want).abs() < 1e-12, "{key}: {got} against {want}");
    };
    close("y_max", 1.0 + r);
    close("y_min", 1.0 - r);
    close("cycle_period_tau", period);
    close("stick_fraction", 2.0 * (mu_s - 1.0) / (vb * period));
    assert_eq!(v["class"], "stick-slip-cycle");
    assert_eq!(v["sliding_stability"], "neutral");
}

/// The belt speed in m/s is vb·F0/(k)·ω0: the same motion as the dimensionless model's, its
/// period also in seconds.
#[test]
fn the_mechanical_belt_speed_is_the_dimensionless_one_in_metres_per_second() {
    // m = 0.1 kg, k = 1000 N/m, F0 = 2 N: ω0 = 100 rad/s, a unit of y' is 0.2 m/s.
    let mech = [
        "steady",
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
    ];
    let a = json(&[&mech[..], &["--json"]].concat());
    let b = json(&[
        "steady", "--zeta", "0.025", "--mu-s", "1.4", "--vb", "0.1", "--json",
    ]);
    for key in ["y_max", "y_min", "cycle_period_tau", "stick_fraction"] {
        let (x, y) = (a[key].as_f64().unwrap(), b[key].as_f64().unwrap());
        assert!((x - y).abs() < 1e-12 * x.abs().max(1.0), "{key}: {x} {y}");
    }
    let (_dir, out) = run(&mech);
    let text = stdout(&out);
    let line = text
        .lines()
        .find(|l| l.starts_with("cycle period"))
        .unwrap();
    let seconds: f64 = line
        .split(", ")
        .nth(1)
        .unwrap()
        .trim_end_matches(" s")
        .parse()
        .unwrap();
    let tau = a["cycle_period_tau"].as_f64().unwrap();
    assert!((seconds - tau / 100.0).abs() < 1e-6 * seconds, "{line}");
}

#[test]
fn bad_belt_input_is_one_line() {
    assert_usage_errors(
        &["steady"],
        &[
            (
                &[
                    "--preset", "paper", "--w", "0.5", "--beta", "1", "--vb", "0.3",
                ],
                "--vb",
            ),
            (&["--zeta", "0.1", "--vb", "2e6"], "--vb"),
            // A law's parameter without its law; a law without its parameter.
            (
                &["--zeta", "0.1", "--vb", "0.2", "--vs", "0.2"],
                "--friction-law stribeck",
            ),
            (
                &["--zeta", "0.1", "--vb", "0.2", "--friction-law", "stribeck"],
                "--vs",
            ),
            // vs ≤ 0, δ ≤ 0.
            (
                &[
                    "--zeta",
                    "0.1",
                    "--vb",
                    "0.2",
                    "--friction-law",
                    "stribeck",
                    "--vs",
                    "0",
                ],
                "--vs",
            ),
            (
                &[
                    "--zeta",
                    "0.1",
                    "--vb",
                    "0.2",
                    "--friction-law",
                    "stribeck",
                    "--vs",
                    "0.1",
                    "--delta",
                    "-1",
                ],
                "--delta",
            ),
            // The cubic law μs − k1 s + k3 s³ with k1 = 5, k3 = 0.1 goes negative from
            // s ≈ 0.21 on (its minimum at s = √(k1/3k3) ≈ 4.08 is −12.6).
            (
                &[
                    "--zeta",
                    "0.1",
                    "--mu-s",
                    "1",
                    "--vb",
                    "0.2",
                    "--friction-law",
                    "cubic",
                    "--k1",
                    "5",
                    "--k3",
                    "0.1",
                ],
                "k1",
            ),
            (
                &["--zeta", "0.1", "--vb", "0.2", "--friction-law", "dahl"],
                "--friction-law",
            ),
            // A circuit has no friction law.
            (
                &[
                    "--preset",
                    "paper",
                    "--w",
                    "0.5",
                    "--beta",
                    "1",
                    "--friction-law",
                    "stribeck",
                ],
                "--friction-law",
            ),
        ],
    );
    assert_usage_errors(
        &["simulate"],
        &[(
            &[
                "--preset", "paper", "--w", "0.5", "--beta", "1", "--vb", "0.3",
            ],
            "--vb",
        )],
    );
}

/// A belt's trajectory: while stuck the block moves with the belt, y' = vb.
#[test]
fn simulate_on_a_belt_sticks_at_the_belts_speed() {
    let (_dir, out) = run(&[
        "simulate",
        "--zeta",
        "0.05",
        "--mu-s",
        "1.5",
        "--vb",
        "0.5",
        "--periods",
        "3",
    ]);
    assert!(out.status.success(), "{}", stderr(&out));
    let text = stdout(&out);
    let mut stuck = 0;
    for line in text.lines().skip(1) {
        let cols: Vec<&str> = line.split(',').collect();
        if cols[4] == "stick" {
            stuck += 1;
            assert_eq!(cols[2].parse::<f64>().unwrap(), 0.5, "{line}");
        }
    }
    assert!(stuck > 10, "{text}");
}

/// The damped Coulomb belt without a drive (ζ = 0.05, μs = 1.5): from rest at a slow belt the
/// block settles on a stick-slip cycle, while steady sliding (y = 1, y' = 0) is stable at
/// every belt speed. Swept up from rest the cycle holds until it ceases to exist; swept down
/// from steady sliding, the block stays sliding where the cycle coexists with it.
#[test]
fn a_sweep_of_the_belt_speed_shows_its_hysteresis() {
    let dir = tempfile::tempdir().unwrap();
    let model = ["--zeta", "0.05", "--mu-s", "1.5"];
    let out = run_in(
        dir.path(),
        &[
            &["sweep"][..],
            &model,
            &[
                "--over",
                "vb",
                "--from",
                "0.1",
                "--to",
                "1",
                "--steps",
                "4",
                "--direction",
                "both",
                "--out",
                "sweep.csv",
            ],
        ]
        .concat(),
    );
    assert!(out.status.success(), "{}", stderr(&out));
    let csv = std::fs::read_to_string(dir.path().join("sweep.csv")).unwrap();
    let mut lines = csv.lines();
    // The columns of the classic amplitude against belt speed (a motion without a drive has
    // no gain nor harmonics of one).
    assert_eq!(
        lines.next().unwrap(),
        "vb,direction,amplitude,y_max,y_min,cycle_period_tau,stick_fraction,class"
    );
    let rows: Vec<Vec<String>> = lines
        .map(|l| l.split(',').map(String::from).collect())
        .collect();
    // (vb, direction, class) of each step, in the order run: up, then down.
    let steps: Vec<(f64, String, String)> = rows
        .iter()
        .map(|cells| {
            (
                cells[0].parse().unwrap(),
                cells[1].to_string(),
                cells[7].to_string(),
            )
        })
        .collect();
    let vbs: Vec<f64> = steps.iter().map(|s| s.0).collect();
    assert_eq!(vbs, [0.1, 0.4, 0.7, 1.0, 1.0, 0.7, 0.4, 0.1]);
    // Each class as `steady` finds it from the state the step starts in: the first step from
    // rest, as the sweep does; the last from steady sliding itself (y = 1, y' = 0), where the
    // down leg arrives.
    let class = |extra: &[&str]| {
        let v = json(&[&["steady"][..], &model, extra, &["--json"]].concat());
        v["class"].as_str().unwrap().to_string()
    };
    assert_eq!(steps[0].2, class(&["--vb", "0.1"]));
    assert_eq!(steps[0].2, "stick-slip-cycle");
    assert_eq!(
        class(&["--vb", "0.1", "--y0", "1", "--v0", "0"]),
        "steady-sliding"
    );
    assert_eq!(steps[7].2, "steady-sliding");
    assert!(steps[..4].iter().all(|s| s.1 == "up"));
    assert!(steps[4..].iter().all(|s| s.1 == "down"));
    // The hysteresis: at the slowest belt the two legs end on different motions, and the
    // fast belt slides steadily on both.
    assert_ne!(steps[0].2, steps[7].2);
    assert_eq!(steps[3].2, "steady-sliding");
    assert_eq!(steps[4].2, "steady-sliding");
    // The numbers of the first step are `steady`'s from rest: amplitude (y_max − y_min)/2,
    // the extremes, the cycle's period and stick fraction; the down leg's last step slides
    // (amplitude 0, no period, never stuck).
    let rest = json(&[&["steady"][..], &model, &["--vb", "0.1", "--json"]].concat());
    let number = |i: usize, j: usize| -> f64 { rows[i][j].parse().unwrap() };
    let (y_max, y_min) = (
        rest["y_max"].as_f64().unwrap(),
        rest["y_min"].as_f64().unwrap(),
    );
    let close = |got: f64, want: f64| assert!((got - want).abs() <= 1e-12, "{got} {want}");
    close(number(0, 2), 0.5 * (y_max - y_min));
    close(number(0, 3), y_max);
    close(number(0, 4), y_min);
    close(number(0, 5), rest["cycle_period_tau"].as_f64().unwrap());
    close(number(0, 6), rest["stick_fraction"].as_f64().unwrap());
    assert!(number(0, 2) > 0.1, "{rows:?}");
    assert_eq!(number(7, 2), 0.0);
    assert_eq!(rows[7][5], "");
    assert_eq!(number(7, 6), 0.0);
    // --json holds the same steps, beside what the CSV leaves out.
    let v = json(
        &[
            &["sweep"][..],
            &model,
            &[
                "--over", "vb", "--from", "0.1", "--to", "1", "--steps", "4", "--json",
            ],
        ]
        .concat(),
    );
    assert_eq!(v["over"], "vb");
    let points = v["points"].as_array().unwrap();
    assert_eq!(points.len(), 8);
    for (p, row) in points.iter().zip(&rows) {
        assert_eq!(p["direction"], row[1].as_str());
        assert_eq!(p["class"], row[7].as_str());
        assert_eq!(p["amplitude"].as_f64().unwrap().to_string(), row[2]);
        assert_eq!(
            p["cycle_period_tau"]
                .as_f64()
                .map(|x| x.to_string())
                .unwrap_or_default(),
            row[5]
        );
        assert!(p["cycle_period_s"].is_null());
    }
}

/// A mechanical belt's sweep has the cycle's period in seconds too: τ/ω0.
#[test]
fn a_mechanical_belt_sweep_has_the_period_in_seconds() {
    // m = 0.1 kg, k = 1000 N/m: ω0 = 100 rad/s.
    let args = [
        "sweep",
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
        "--over",
        "vb",
        "--from",
        "0.1",
        "--to",
        "0.2",
        "--steps",
        "2",
        "--direction",
        "up",
    ];
    let (text, rows) = csv_rows(
        &args,
        "vb,direction,amplitude,y_max,y_min,cycle_period_tau,cycle_period_s,stick_fraction,class",
    );
    for cells in rows {
        assert_eq!(cells[8], "stick-slip-cycle", "{text}");
        let tau: f64 = cells[5].parse().unwrap();
        let seconds: f64 = cells[6].parse().unwrap();
        assert!((seconds - tau / 100.0).abs() <= 1e-15 * tau, "{text}");
    }
}

/// The self-excited belt's map over (vb, μs): the CSV's first columns are the keys' names,
/// and each class is what `steady` finds at that point from rest.
#[test]
fn a_map_of_belt_speed_and_static_friction_has_the_steady_states_classes() {
    let args = [
        "phase-diagram",
        "--zeta",
        "0.05",
        "--beta",
        "0",
        "--x",
        "vb",
        "--x-from",
        "0.1",
        "--x-to",
        "1.5",
        "--x-steps",
        "3",
        "--y",
        "mu-s",
        "--y-from",
        "1",
        "--y-to",
        "3",
        "--y-steps",
        "3",
    ];
    let (text, rows) = csv_rows(&args, "vb,mu_s,class,period,stops_per_period,gain");
    let mut classes = Vec::new();
    for cells in rows {
        let v = json(&[
            "steady", "--zeta", "0.05", "--vb", &cells[0], "--mu-s", &cells[1], "--json",
        ]);
        assert_eq!(v["class"], cells[2], "{cells:?}");
        classes.push(cells[2].clone());
    }
    assert_eq!(classes.len(), 9);
    // Both motions are on the map: stick-slip at a slow belt with μs > 1, steady sliding at
    // the fast one.
    assert!(classes.contains(&"stick-slip-cycle".to_string()), "{text}");
    assert!(classes.contains(&"steady-sliding".to_string()), "{text}");
}

/// --x and --y come together with their ranges, and name two different keys.
#[test]
fn a_map_over_two_keys_refuses_half_an_axis() {
    let (_dir, out) = run(&["phase-diagram", "--x", "vb", "--x-from", "0", "--x-to", "1"]);
    assert_eq!(out.status.code(), Some(2), "{}", stderr(&out));
    let (_dir, out) = run(&[
        "phase-diagram",
        "--beta",
        "0",
        "--x",
        "vb",
        "--x-from",
        "0.1",
        "--x-to",
        "1",
        "--y",
        "vb",
        "--y-from",
        "0.2",
        "--y-to",
        "1",
    ]);
    assert_eq!(out.status.code(), Some(2));
    assert!(stderr(&out).contains("invalid --y vb: must differ from --x vb"));
    let (_dir, out) = run(&[
        "phase-diagram",
        "--x",
        "vb",
        "--x-from",
        "0.1",
        "--x-to",
        "1",
        "--y",
        "mu-s",
        "--y-from",
        "1",
        "--y-to",
        "2",
        "--w-min",
        "0.5",
    ]);
    assert_eq!(out.status.code(), Some(2));
}

/// A self-excited Stribeck belt at the command line: `steady` finds a stick-slip cycle, the
/// same as the library's friction solver, and the mechanical twin's physical law parameters
/// give the same cycle as the dimensionless ones.
#[test]
fn steady_takes_the_stribeck_and_cubic_laws() {
    let stribeck = [
        "steady",
        "--zeta",
        "0.05",
        "--mu-s",
        "1.5",
        "--vb",
        "0.3",
        "--friction-law",
        "stribeck",
        "--vs",
        "0.5",
        "--json",
    ];
    let a = json(&stribeck);
    assert_eq!(a["class"], "stick-slip-cycle", "{a}");
    assert_eq!(a["friction_law"], "stribeck", "{a}");
    let cubic = json(&[
        "steady",
        "--zeta",
        "0.05",
        "--mu-s",
        "1.5",
        "--vb",
        "0.3",
        "--friction-law",
        "cubic",
        "--k1",
        "1",
        "--k3",
        "0.4",
        "--json",
    ]);
    assert_eq!(cubic["class"], "stick-slip-cycle", "{cubic}");
    // m = 1 kg, k = 10⁴ N/m (ω0 = 100 rad/s), γ = 10 N·s/m (ζ = 0.05), F0 = 1 N: speeds in
    // units of F0·ω0/k = 0.01 m/s.
    let mech = json(&[
        "steady",
        "--mass",
        "1",
        "--stiffness",
        "1e4",
        "--damping",
        "10",
        "--friction",
        "1",
        "--mu-s",
        "1.5",
        "--belt-speed",
        "0.003",
        "--friction-law",
        "stribeck",
        "--stribeck-speed",
        "0.005",
        "--json",
    ]);
    for key in ["y_max", "y_min", "cycle_period_tau"] {
        let (x, y) = (a[key].as_f64().unwrap(), mech[key].as_f64().unwrap());
        assert!((x - y).abs() < 1e-9 * x.abs().max(1.0), "{key}: {x} {y}");
    }
}
