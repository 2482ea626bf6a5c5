//! Tests of `stickslip bifurcation`, `stickslip basins` and `stickslip continue`.

use crate::common::*;
use stickslip::attractor::RecordOptions;
use stickslip::bifurcation::{Bifurcation, BifurcationOptions};
use stickslip::scan::{Axis, ParameterRange, SweepDirection};
use stickslip::{Experiment, Parameter};

const CHAOS: [&str; 6] = ["--zeta", "0", "--mu-s", "3", "--beta", "9"];

fn csv_rows(text: &str) -> Vec<Vec<String>> {
    text.lines()
        .skip(1)
        .map(|l| l.split(',').map(str::to_string).collect())
        .collect()
}

#[test]
fn bifurcation_csv_is_the_library_s_diagram() {
    let mut args = vec!["bifurcation"];
    args.extend(CHAOS);
    args.extend([
        "--over",
        "w",
        "--from",
        "0.33",
        "--to",
        "0.42",
        "--steps",
        "4",
        "--points",
        "30",
        "--transient",
        "100",
        "--out",
        "bif.csv",
        "--plot",
        "bif.png",
    ]);
    let (dir, out) = run(&args);
    assert!(out.status.success(), "{}", stderr(&out));
    let csv = std::fs::read_to_string(dir.path().join("bif.csv")).unwrap();
    assert_eq!(
        csv.lines().next().unwrap(),
        "w,y,v,direction,lambda1,class,period"
    );
    let rows = csv_rows(&csv);
    assert_eq!(rows.len(), 4 * 2 * 30);
    // The same numbers, bit for bit, as the library's diagram.
    let e = Experiment::dimensionless(0.0, 0.3, 9.0)
        .unwrap()
        .with_mu_s(3.0)
        .unwrap();
    let steps = Bifurcation::new(
        &e,
        Axis::range(
            Parameter::W,
            &ParameterRange::new("w", 0.33, 0.42, 4).unwrap(),
        )
        .unwrap(),
    )
    .unwrap()
    .direction(SweepDirection::Both)
    .options(BifurcationOptions {
        record: RecordOptions {
            points: 30,
            transient_periods: 100,
            ..RecordOptions::default()
        },
        ..BifurcationOptions::default()
    })
    .unwrap()
    .run(&())
    .unwrap();
    let mut k = 0;
    for s in &steps {
        for x in &s.record.strobes {
            let r = &rows[k];
            assert_eq!(r[0].parse::<f64>().unwrap(), s.value);
            assert_eq!(r[1].parse::<f64>().unwrap(), x.y);
            assert_eq!(r[2].parse::<f64>().unwrap(), x.v);
            assert_eq!(r[3], s.leg.label());
            assert_eq!(r[4].parse::<f64>().unwrap(), s.record.exponent);
            assert_eq!(r[5], s.record.kind.label());
            k += 1;
        }
    }
    // w = 0.33 is chaotic, w = 0.42 a period-3 orbit: three distinct points.
    let at = |w: &str| {
        rows.iter()
            .filter(|r| r[0] == w && r[3] == "up")
            .collect::<Vec<_>>()
    };
    assert!(at("0.33")
        .iter()
        .all(|r| r[5] == "chaotic" && r[6].is_empty()));
    assert!(at("0.42").iter().all(|r| r[5] == "periodic" && r[6] == "3"));
    let png = std::fs::read(dir.path().join("bif.png")).unwrap();
    assert_eq!(&png[1..4], b"PNG");
    assert!(stderr(&out).contains("branches of periodic orbits continued"));
}

#[test]
fn bifurcation_plot_draws_branches_and_special_points() {
    let (dir, out) = run(&[
        "bifurcation",
        "--zeta",
        "0",
        "--mu-s",
        "3",
        "--beta",
        "3.269",
        "--over",
        "w",
        "--from",
        "0.6",
        "--to",
        "0.66",
        "--steps",
        "13",
        "--direction",
        "up",
        "--first-transient",
        "3000",
        "--out",
        "bif.csv",
        "--plot",
        "bif.svg",
    ]);
    assert!(out.status.success(), "{}", stderr(&out));
    let svg = std::fs::read_to_string(dir.path().join("bif.svg")).unwrap();
    for text in [
        "stable orbit (continuation)",
        "unstable orbit (continuation)",
        "period doubling",
        "largest Lyapunov exponent",
    ] {
        assert!(svg.contains(text), "'{text}' not in the plot");
    }
    assert!(
        stderr(&out).contains("period-doubling at 0.6411"),
        "{}",
        stderr(&out)
    );
}

#[test]
fn basins_find_the_mirror_pair() {
    let (dir, out) = run(&[
        &["basins"][..],
        &MIRROR,
        &BASIN_BOX,
        &[
            "--steps",
            "12",
            "--json",
            "--out",
            "basins.csv",
            "--plot",
            "basins.png",
        ],
    ]
    .concat());
    assert!(out.status.success(), "{}", stderr(&out));
    let summary: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    let attractors = summary["attractors"].as_array().unwrap();
    assert_eq!(attractors.len(), 2);
    let mut total = 0.0;
    for a in attractors {
        assert_eq!(a["class"], "periodic");
        assert_eq!(a["period"], 1);
        total += a["fraction"].as_f64().unwrap();
        assert!(a["state"]["y"].is_f64() && a["state"]["v"].is_f64());
        assert_eq!(a["multipliers"].as_array().unwrap().len(), 2);
    }
    assert!((total - 1.0).abs() < 1e-12);
    assert_eq!(summary["undecided"], 0);
    let csv = std::fs::read_to_string(dir.path().join("basins.csv")).unwrap();
    assert_eq!(csv.lines().next().unwrap(), "y0,v0,attractor,class,period");
    let rows = csv_rows(&csv);
    assert_eq!(rows.len(), 144);
    let zeros = rows.iter().filter(|r| r[2] == "0").count() as f64;
    assert!((zeros / 144.0 - attractors[0]["fraction"].as_f64().unwrap()).abs() < 1e-12);
    let png = std::fs::read(dir.path().join("basins.png")).unwrap();
    assert_eq!(&png[1..4], b"PNG");
}

#[test]
fn continue_finds_the_grazing_and_the_fold() {
    let (dir, out) = run(&[
        "continue",
        "--zeta",
        "0.046816",
        "--mu-s",
        "1.5",
        "--w",
        "0.9",
        "--y0",
        "0.25",
        "--v0",
        "2.1",
        "--over",
        "beta",
        "--from",
        "1.45",
        "--to",
        "1.2",
        "--json",
        "--out",
        "branch.csv",
        "--plot",
        "branch.png",
    ]);
    assert!(out.status.success(), "{}", stderr(&out));
    let summary: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    let special = summary["special"].as_array().unwrap();
    let kinds: Vec<&str> = special
        .iter()
        .map(|s| s["kind"].as_str().unwrap())
        .collect();
    assert_eq!(kinds, ["grazing", "fold"]);
    let grazing = &special[0];
    assert!((grazing["value"].as_f64().unwrap() - 1.41329).abs() < 1e-5);
    assert_eq!(
        (
            grazing["before"]["stops"].as_u64(),
            grazing["after"]["stops"].as_u64()
        ),
        (Some(0), Some(2))
    );
    let fold = &special[1];
    assert!((fold["value"].as_f64().unwrap() - 1.30382).abs() < 1e-5);
    assert_eq!(fold["before"]["stable"], true);
    assert_eq!(fold["after"]["stable"], false);
    assert_eq!(summary["end"]["reason"], "stalled");
    let csv = std::fs::read_to_string(dir.path().join("branch.csv")).unwrap();
    assert_eq!(
        csv.lines().next().unwrap(),
        "beta,y,v,amplitude,period,stops_per_period,turns,mu1_re,mu1_im,mu2_re,mu2_im,stable,arclength"
    );
    let rows = csv_rows(&csv);
    assert_eq!(rows.len() as u64, summary["points"].as_u64().unwrap());
    assert!(rows.iter().any(|r| r[11] == "false") && rows.iter().any(|r| r[11] == "true"));
    let png = std::fs::read(dir.path().join("branch.png")).unwrap();
    assert_eq!(&png[1..4], b"PNG");
    assert!(
        stderr(&out).contains("fold at beta = 1.30382"),
        "{}",
        stderr(&out)
    );
}

#[test]
fn bad_input_gives_one_line_and_exit_code_2() {
    let chaos = |extra: &[&'static str]| {
        let mut v: Vec<&'static str> = vec!["--zeta", "0", "--mu-s", "3", "--beta", "9"];
        v.extend_from_slice(extra);
        v
    };
    let cases: Vec<(&str, Vec<&str>, &str)> = vec![
        (
            "bifurcation",
            chaos(&[
                "--over", "w", "--from", "0.4", "--to", "0.3", "--steps", "5",
            ]),
            "--from",
        ),
        (
            "bifurcation",
            chaos(&[
                "--over", "w", "--from", "0.3", "--to", "0.4", "--steps", "0",
            ]),
            "--steps",
        ),
        (
            "bifurcation",
            chaos(&[
                "--over", "w", "--from", "0.3", "--to", "0.4", "--steps", "5", "--points", "0",
            ]),
            "--points",
        ),
        (
            "bifurcation",
            chaos(&[
                "--over",
                "w",
                "--from",
                "0.3",
                "--to",
                "0.4",
                "--steps",
                "5",
                "--transient",
                "-1",
            ]),
            "--transient",
        ),
        (
            "bifurcation",
            chaos(&[
                "--over", "w", "--w", "0.3", "--from", "0.3", "--to", "0.4", "--steps", "5",
            ]),
            "--w",
        ),
        (
            "bifurcation",
            chaos(&["--over", "w", "--from", "-1", "--to", "0.4", "--steps", "5"]),
            "w",
        ),
        (
            "bifurcation",
            chaos(&[
                "--over", "w", "--from", "0.3", "--to", "0.4", "--steps", "5", "--plot", "a.bmp",
            ]),
            "a.bmp",
        ),
        (
            "continue",
            vec![
                "--preset", "paper", "--model", "shockley", "--w", "0.9", "--beta", "2", "--over",
                "mu-s", "--from", "1", "--to", "1.5",
            ],
            "mu_s",
        ),
        (
            "basins",
            vec![
                "--w", "0.6", "--beta", "3", "--y0-min", "1", "--y0-max", "0", "--v0-min", "0",
                "--v0-max", "1",
            ],
            "--y0-min",
        ),
        (
            "basins",
            vec![
                "--w", "0.6", "--beta", "3", "--y0-min", "0", "--y0-max", "1", "--v0-min", "0",
                "--v0-max", "1", "--steps", "0",
            ],
            "--steps",
        ),
        (
            "basins",
            vec![
                "--w",
                "0.6",
                "--beta",
                "3",
                "--y0-min",
                "0",
                "--y0-max",
                "1",
                "--v0-min",
                "0",
                "--v0-max",
                "1",
                "--resolution",
                "8",
            ],
            "--resolution",
        ),
        (
            "basins",
            vec![
                "--w", "0.6", "--beta", "3", "--y0-min", "0", "--y0-max", "1", "--v0-min", "0",
                "--v0-max", "1", "--method", "fast",
            ],
            "--method",
        ),
        (
            "basins",
            vec![
                "--w", "0.6", "--beta", "3", "--y0", "1", "--y0-min", "0", "--y0-max", "1",
                "--v0-min", "0", "--v0-max", "1",
            ],
            "--y0",
        ),
        (
            "basins",
            vec![
                "--w", "0.6", "--beta", "3", "--phi", "1", "--phase", "1", "--y0-min", "0",
                "--y0-max", "1", "--v0-min", "0", "--v0-max", "1",
            ],
            "--phase",
        ),
        (
            "basins",
            vec![
                "--beta", "3", "--y0-min", "0", "--y0-max", "1", "--v0-min", "0", "--v0-max", "1",
            ],
            "w",
        ),
        (
            "continue",
            vec![
                "--w", "0.9", "--beta", "1.4", "--over", "beta", "--from", "1.4", "--to", "1.3",
            ],
            "--beta",
        ),
        (
            "continue",
            vec![
                "--w", "0.9", "--over", "beta", "--from", "1.4", "--to", "1.4",
            ],
            "--to",
        ),
        (
            "continue",
            vec![
                "--w", "0.9", "--over", "mu_s", "--beta", "2", "--from", "1", "--to", "0.5",
            ],
            "mu_s",
        ),
    ];
    for (command, args, needle) in cases {
        let dir = tempfile::tempdir().unwrap();
        let mut full = vec![command];
        full.extend(args.iter().copied());
        full.extend(["--out", "x.csv"]);
        let out = run_in(dir.path(), &full);
        assert_usage_error(dir.path(), &out, needle);
    }
}

#[test]
fn continue_from_rest_says_what_to_do() {
    let (dir, out) = run(&[
        "continue", "--w", "0.9", "--mu-s", "1.5", "--over", "beta", "--from", "1.4", "--to",
        "1.3", "--out", "x.csv",
    ]);
    assert_eq!(out.status.code(), Some(1));
    assert!(stderr(&out).contains("comes to rest at beta = 1.4: nothing to continue"));
    assert!(std::fs::read_dir(dir.path()).unwrap().next().is_none());
}

#[test]
fn ctrl_c_leaves_no_output_file() {
    for args in [
        vec![
            "bifurcation",
            "--zeta",
            "0",
            "--mu-s",
            "3",
            "--beta",
            "9",
            "--over",
            "w",
            "--from",
            "0.2",
            "--to",
            "0.55",
            "--steps",
            "100000",
            "--points",
            "10",
            "--out",
            "bif.csv",
            "--plot",
            "bif.png",
        ],
        [
            &["basins"][..],
            &CHAOTIC,
            &BASIN_BOX,
            &[
                "--steps",
                "2000",
                "--out",
                "basins.csv",
                "--plot",
                "basins.png",
            ],
        ]
        .concat(),
    ] {
        assert_ctrl_c_leaves_nothing(&args);
    }
}

/// `continue`, `bifurcation` and `basins` with --model shockley agree with `orbit` at the same
/// drive: the branch ends on its fixed point with its multipliers, the diagram's points lie on
/// it with its exponent, the basin map finds it as the one attractor.
#[test]
fn shockley_continue_bifurcation_and_basins_agree_with_the_orbit() {
    let model = ["--preset", "paper", "--model", "shockley", "--beta", "3.61"];
    let json = |out: &std::process::Output| -> serde_json::Value {
        assert!(out.status.success(), "{}", stderr(out));
        serde_json::from_slice(&out.stdout).unwrap()
    };
    let (_dir, out) = run(&[&["orbit", "--json", "--w", "1.1"][..], &model].concat());
    let orbit = json(&out);
    let (y, v) = (orbit["y"].as_f64().unwrap(), orbit["v"].as_f64().unwrap());
    let modulus = orbit["moduli"][0].as_f64().unwrap();
    let exponent = orbit["lambda1"].as_f64().unwrap();
    assert_eq!((orbit["period"].as_u64(), modulus < 1.0), (Some(1), true));
    // The fixed point's accuracy is the map's (rtol 1e-10), its multipliers the Jacobian's
    // (about 1e-7, ShockleyDynamics::MAP_TOLERANCE); states scaled by max(1, |y|, |y'|).
    let scale = 1f64.max(y.abs()).max(v.abs());
    let near =
        |ya: f64, va: f64, tolerance: f64| (ya - y).abs().max((va - v).abs()) <= tolerance * scale;
    let (dir, out) = run(&[
        &[
            "continue", "--over", "w", "--from", "1.2", "--to", "1.1", "--json",
        ][..],
        &["--out", "branch.csv"],
        &model,
    ]
    .concat());
    let branch = json(&out);
    assert_eq!(branch["end"]["reason"], "boundary");
    assert_eq!(branch["special"].as_array().unwrap().len(), 0);
    let csv = std::fs::read_to_string(dir.path().join("branch.csv")).unwrap();
    let rows = csv_rows(&csv);
    assert_eq!(rows.len() as u64, branch["points"].as_u64().unwrap());
    let last = rows.last().unwrap();
    let f = |k: usize| last[k].parse::<f64>().unwrap();
    assert_eq!(f(0), 1.1);
    assert!(near(f(1), f(2), 1e-8), "{last:?} vs ({y}, {v})");
    assert!(
        (f(7).hypot(f(8)) - modulus).abs() < 1e-6,
        "{last:?} vs {modulus}"
    );
    assert!(rows.iter().all(|r| r[11] == "true" && r[4] == "1"));
    let (dir, out) = run(&[
        &[
            "bifurcation",
            "--over",
            "w",
            "--from",
            "1.0",
            "--to",
            "1.1",
            "--steps",
            "2",
        ][..],
        &["--points", "100", "--transient", "100", "--out", "bif.csv"],
        &model,
    ]
    .concat());
    assert!(out.status.success(), "{}", stderr(&out));
    let csv = std::fs::read_to_string(dir.path().join("bif.csv")).unwrap();
    let at = csv_rows(&csv)
        .into_iter()
        .filter(|r| r[0] == "1.1")
        .collect::<Vec<_>>();
    assert_eq!(at.len(), 200);
    for r in &at {
        let g = |k: usize| r[k].parse::<f64>().unwrap();
        assert_eq!((r[5].as_str(), r[6].as_str()), ("periodic", "1"));
        assert!(near(g(1), g(2), 1e-8), "{r:?} vs ({y}, {v})");
        // The exponent of 100 recorded periods: the tangent of a focus (a complex pair of
        // multipliers) beats about its mean over a finite run, here by 7e-4 of it.
        assert!(
            (g(4) - exponent).abs() <= 1e-2 * exponent.abs(),
            "{r:?} vs {exponent}"
        );
    }
    let (_dir, out) = run(&[
        &["basins", "--w", "1.1", "--y0-min", "-2", "--y0-max", "2"][..],
        &["--v0-min", "-2", "--v0-max", "2", "--steps", "3", "--json"],
        &model,
    ]
    .concat());
    let map = json(&out);
    let attractors = map["attractors"].as_array().unwrap();
    assert_eq!(attractors.len(), 1);
    let a = &attractors[0];
    assert_eq!(
        (
            a["class"].as_str(),
            a["period"].as_u64(),
            a["cells"].as_u64()
        ),
        (Some("periodic"), Some(1), Some(9))
    );
    let s = |k: &str| a["state"][k].as_f64().unwrap();
    assert!(near(s("y"), s("v"), 1e-8), "{a} vs ({y}, {v})");
    let mu = &a["multipliers"][0];
    let m = mu[0].as_f64().unwrap().hypot(mu[1].as_f64().unwrap());
    assert!((m - modulus).abs() < 1e-6, "{m} vs {modulus}");
}
