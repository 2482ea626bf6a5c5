//! Tests of `stickslip phase-diagram`.

use crate::common::*;

#[test]
fn csv_and_plot_on_a_small_grid() {
    let (dir, out) = run(&[
        "phase-diagram",
        "--preset",
        "paper",
        "--w-min",
        "0.6",
        "--w-max",
        "0.9",
        "--w-steps",
        "2",
        "--beta-min",
        "1.0",
        "--beta-max",
        "1.6",
        "--beta-steps",
        "3",
        "--out",
        "map.csv",
        "--plot",
        "map.png",
    ]);
    assert!(out.status.success(), "{}", stderr(&out));
    let csv = std::fs::read_to_string(dir.path().join("map.csv")).unwrap();
    let lines: Vec<&str> = csv.lines().collect();
    assert_eq!(lines[0], "w,beta,class,period,stops_per_period,gain");
    assert_eq!(lines.len(), 7);
    let class = |w: &str, beta: &str| -> String {
        lines
            .iter()
            .find(|l| l.starts_with(&format!("{w},{beta},")))
            .unwrap()
            .split(',')
            .nth(2)
            .unwrap()
            .to_string()
    };
    assert_eq!(class("0.6", "1"), "static");
    assert_eq!(class("0.9", "1.6"), "sliding");
    assert_eq!(class("0.6", "1.3"), "periodic-stick");
    let png = std::fs::read(dir.path().join("map.png")).unwrap();
    assert_eq!(&png[1..4], b"PNG");
}

#[test]
fn bad_grids_give_one_line_and_exit_code_2() {
    let cases: &[(&[&str], &str)] = &[
        (&["--w-min", "2", "--w-max", "1"], "--w-min"),
        (&["--beta-min", "3", "--beta-max", "2"], "--beta-min"),
        (&["--w-steps", "0"], "--w-steps"),
        (&["--beta-steps", "0"], "--beta-steps"),
        (&["--w-min", "nan"], "--w-min"),
        (&["--beta-max", "inf"], "--beta-max"),
        (&["--w-min", "0"], "--w-min"),
        (&["--w-min", "-1"], "--w-min"),
        (&["--beta-min", "-1"], "--beta-min"),
        (&["--w", "1"], "--w"),
        (&["--w-steps", "1"], "--w-steps"),
        (&["--plot", "map.bmp"], "map.bmp"),
        // A map kept whole (for the plot, in a checkpoint) is capped by its memory.
        (
            &[
                "--w-steps",
                "2001",
                "--beta-steps",
                "2000",
                "--plot",
                "m.png",
            ],
            "--w-steps × --beta-steps = 4002000 points kept in memory (with a plot or a checkpoint): at most 4000000 allowed",
        ),
        (
            &[
                "--w-steps",
                "2001",
                "--beta-steps",
                "2000",
                "--checkpoint",
                "run.ckpt",
            ],
            "--w-steps × --beta-steps = 4002000 points kept in memory (with a plot or a checkpoint): at most 4000000 allowed",
        ),
    ];
    assert_usage_errors(&["phase-diagram"], cases);
}

/// Streamed to its file or kept for the plot, a map stopped by Ctrl-C leaves no file (the
/// streamed rows went to a temporary file, removed).
#[test]
fn ctrl_c_leaves_no_output_file() {
    let map = ["phase-diagram", "--w-steps", "1000", "--beta-steps", "1000"];
    assert_ctrl_c_leaves_nothing(&[&map[..], &["--out", "map.csv", "--plot", "map.png"]].concat());
    // Without the plot: 3000 × 3000, beyond the cap of a kept map.
    assert_ctrl_c_leaves_nothing(&[
        "phase-diagram",
        "--w-steps",
        "3000",
        "--beta-steps",
        "3000",
        "--out",
        "map.csv",
    ]);
}

#[test]
fn plot_carries_the_boundaries_inside_the_beta_range() {
    let grid = [
        "phase-diagram",
        "--preset",
        "paper",
        "--w-min",
        "0.3",
        "--w-max",
        "1.5",
        "--w-steps",
        "3",
        "--beta-min",
        "1.0",
        "--beta-max",
        "2.5",
        "--beta-steps",
        "3",
        "--out",
        "map.csv",
    ];
    let counts = |err: &str| -> (usize, usize, usize) {
        let line = err
            .lines()
            .find(|l| l.contains("theory on the plot"))
            .unwrap_or_else(|| panic!("no theory line in {err}"));
        let n: Vec<usize> = line
            .split(|c: char| !c.is_ascii_digit())
            .filter_map(|s| s.parse().ok())
            .collect();
        assert_eq!(n.len(), 3, "{line}");
        (n[0], n[1], n[2])
    };
    let mut args = grid.to_vec();
    args.extend(["--plot", "map.svg"]);
    let (dir, out) = run(&args);
    assert!(out.status.success(), "{}", stderr(&out));
    // Near w = 0.3 both boundaries lie far above β = 2.5 (+ half a cell): the curves are
    // cut there, and present over the rest of the range.
    let (paper, exact, n) = counts(&stderr(&out));
    assert_eq!(n, 200);
    assert!(paper > n / 2 && paper < n, "{paper}");
    assert!(exact > n / 2 && exact < n, "{exact}");
    let svg = std::fs::read_to_string(dir.path().join("map.svg")).unwrap();
    assert!(svg.contains("paper boundary, eq. (13)"));
    assert!(svg.contains("exact boundary β_c"));
    assert!(!svg.contains("PWL theory"));
    assert_eq!(
        std::fs::read_to_string(dir.path().join("map.csv"))
            .unwrap()
            .lines()
            .count(),
        10
    );

    let mut args = grid.to_vec();
    args.extend(["--model", "shockley", "--plot", "map.png"]);
    let (dir, out) = run(&args);
    assert!(out.status.success(), "{}", stderr(&out));
    assert!(counts(&stderr(&out)).1 > 0);
    let png = std::fs::read(dir.path().join("map.png")).unwrap();
    assert_eq!(&png[1..4], b"PNG");
    let mut args = grid.to_vec();
    args.extend(["--model", "shockley", "--plot", "map.svg"]);
    let (dir, out) = run(&args);
    assert!(out.status.success(), "{}", stderr(&out));
    let svg = std::fs::read_to_string(dir.path().join("map.svg")).unwrap();
    assert!(svg.contains("PWL theory: paper boundary, eq. (13)"));
    assert!(svg.contains("PWL theory: exact boundary β_c"));
}

#[test]
fn a_map_of_the_largest_exponent_with_the_chaotic_class() {
    let (dir, out) = run(&[
        "phase-diagram",
        "--zeta",
        "0",
        "--mu-s",
        "3",
        "--w-min",
        "0.25",
        "--w-max",
        "0.40",
        "--w-steps",
        "4",
        "--beta-min",
        "2",
        "--beta-max",
        "9",
        "--beta-steps",
        "2",
        "--color",
        "lambda1",
        "--out",
        "map.csv",
        "--plot",
        "map.svg",
    ]);
    assert!(out.status.success(), "{}", stderr(&out));
    let csv = std::fs::read_to_string(dir.path().join("map.csv")).unwrap();
    let lines: Vec<&str> = csv.lines().collect();
    assert_eq!(
        lines[0],
        "w,beta,class,period,stops_per_period,gain,lambda1,lambda1_error"
    );
    assert_eq!(lines.len(), 9);
    for line in &lines[1..] {
        let cells: Vec<&str> = line.split(',').collect();
        let (class, lambda, error) = (
            cells[2],
            cells[6].parse::<f64>().unwrap(),
            cells[7].parse::<f64>().unwrap(),
        );
        match class {
            // β = 2 < μs: rest, exponent 0 exactly.
            "static" => assert_eq!(lambda, 0.0, "{line}"),
            "chaotic" => assert!(lambda > 4.0 * error && error > 0.0, "{line}"),
            "periodic-stick" => assert!(lambda < 0.0 && error == 0.0, "{line}"),
            other => panic!("unexpected class {other}: {line}"),
        }
    }
    assert!(lines.iter().any(|l| l.contains(",chaotic,")), "{csv}");
    // The classes are those of the plain map.
    let (dir2, out) = run(&[
        "phase-diagram",
        "--zeta",
        "0",
        "--mu-s",
        "3",
        "--w-min",
        "0.25",
        "--w-max",
        "0.40",
        "--w-steps",
        "4",
        "--beta-min",
        "2",
        "--beta-max",
        "9",
        "--beta-steps",
        "2",
        "--out",
        "plain.csv",
    ]);
    assert!(out.status.success(), "{}", stderr(&out));
    let plain = std::fs::read_to_string(dir2.path().join("plain.csv")).unwrap();
    // The classes of the plain map; a chaotic cell is decided after a shortened search
    // (`steady_state_with_exponent`), so its record (stops, gain) is of another stretch of
    // the chaotic motion, and only its class and period are compared.
    for (a, b) in plain.lines().zip(csv.lines()).skip(1) {
        if a.contains(",chaotic,") {
            let head = |s: &str| s.split(',').take(4).collect::<Vec<_>>().join(",");
            assert_eq!(head(a), head(b));
        } else {
            assert!(b.starts_with(a), "{a} against {b}");
        }
    }
    let svg = std::fs::read_to_string(dir.path().join("map.svg")).unwrap();
    assert!(svg.contains("largest Lyapunov exponent") && svg.contains("λ1 per unit τ"));
    assert!(plain.contains(",chaotic,"), "{plain}");
}

#[test]
fn the_exponent_map_needs_a_measurement() {
    let dir = tempfile::tempdir().unwrap();
    let small = ["--w-steps", "2", "--beta-steps", "2", "--color", "lambda1"];
    let mut args = vec!["phase-diagram", "--lyapunov-periods", "0"];
    args.extend_from_slice(&small);
    let out = run_in(dir.path(), &args);
    assert_usage_error(dir.path(), &out, "--lyapunov-periods");
    let out = run_in(dir.path(), &["phase-diagram", "--color", "rainbow"]);
    assert_usage_error(dir.path(), &out, "rainbow");
}

/// The names retired (`--color lyapunov`, `theory --curve gain`) still work, the same, with a
/// note on standard error giving the name now.
#[test]
fn retired_names_still_work_with_a_note() {
    let dir = tempfile::tempdir().unwrap();
    let map = |color: &str| {
        run_in(
            dir.path(),
            &[
                "phase-diagram",
                "--zeta",
                "0",
                "--mu-s",
                "3",
                "--w-steps",
                "2",
                "--beta-min",
                "8",
                "--beta-max",
                "9",
                "--beta-steps",
                "2",
                "--lyapunov-periods",
                "200",
                "--color",
                color,
            ],
        )
    };
    let (old, new) = (map("lyapunov"), map("lambda1"));
    assert!(
        old.status.success() && new.status.success(),
        "{}",
        stderr(&old)
    );
    assert_eq!(old.stdout, new.stdout);
    assert!(stdout(&new).starts_with("w,beta,class,period,stops_per_period,gain,lambda1,"));
    assert!(
        stderr(&old).contains("note: --color lyapunov is now called --color lambda1"),
        "{}",
        stderr(&old)
    );
    assert!(!stderr(&new).contains("note:"), "{}", stderr(&new));
    let curve = |name: &str| {
        run_in(
            dir.path(),
            &[
                "theory", "--zeta", "0.0468", "--curve", name, "--beta", "1.5",
            ],
        )
    };
    let (old, new) = (curve("gain"), curve("gain1"));
    assert!(old.status.success(), "{}", stderr(&old));
    assert_eq!(old.stdout, new.stdout);
    assert!(stderr(&old).contains("--curve gain is now called --curve gain1"));
    // The help lists the current names only.
    let help = stdout(&run_in(dir.path(), &["phase-diagram", "--help"]));
    assert!(
        help.contains("lambda1") && !help.contains("lyapunov:"),
        "{help}"
    );
}

/// With Shockley diodes the map of exponents is that of the stiff solver's tangent dynamics:
/// each cell's λ1 is ln|μ1|/T of the orbit `orbit --json` finds there, the same for any
/// number of threads.
#[test]
fn a_shockley_map_of_exponents_is_the_orbits() {
    let dir = tempfile::tempdir().unwrap();
    let map = |threads: &str| {
        let out = std::process::Command::new(env!("CARGO_BIN_EXE_stickslip"))
            .args([
                "phase-diagram",
                "--preset",
                "paper",
                "--model",
                "shockley",
                "--w-min",
                "0.9",
                "--w-max",
                "1.1",
                "--w-steps",
                "2",
                "--beta-min",
                "2",
                "--beta-max",
                "3.61",
                "--beta-steps",
                "2",
                "--color",
                "lambda1",
            ])
            .env("RAYON_NUM_THREADS", threads)
            .current_dir(dir.path())
            .output()
            .unwrap();
        assert!(out.status.success(), "{}", stderr(&out));
        stdout(&out)
    };
    let csv = map("1");
    assert_eq!(csv, map("2"));
    let mut lines = csv.lines();
    assert_eq!(
        lines.next().unwrap(),
        "w,beta,class,period,stops_per_period,gain,lambda1,lambda1_error"
    );
    let mut cells = 0;
    for line in lines {
        let f: Vec<&str> = line.split(',').collect();
        let (lambda, error): (f64, f64) = (f[6].parse().unwrap(), f[7].parse().unwrap());
        assert_eq!((f[3], error), ("1", 0.0), "{line}");
        let out = run_in(
            dir.path(),
            &[
                "orbit", "--preset", "paper", "--model", "shockley", "--w", f[0], "--beta", f[1],
                "--json",
            ],
        );
        assert!(out.status.success(), "{}", stderr(&out));
        let json: serde_json::Value = serde_json::from_str(&stdout(&out)).unwrap();
        let orbit = json["lambda1"].as_f64().unwrap();
        assert!(
            (lambda - orbit).abs() <= 1e-6 * orbit.abs(),
            "{line}: the orbit's lambda1 {orbit}"
        );
        cells += 1;
    }
    assert_eq!(cells, 4);
}
