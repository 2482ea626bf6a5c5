//! `stickslip curve`: the CSV is the library's curve, the JSON its summary; no special point
//! is one line and exit status 2; bad input is refused; Ctrl-C leaves nothing.

use crate::common::*;
use stickslip::continuation::{curve, ContinuationOptions, CurveReport, CurveSpec, Follow};
use stickslip::report::{CurveTable, Table};
use stickslip::{Experiment, Parameter, State};

/// The fold of the orbit with two stops at the paper's ζ, μs = 1.5, from the sliding orbit at
/// w = 0.9, β = 1.45 ([`FOLD_CURVE`]), with its initial state, as JSON.
fn fold() -> Vec<&'static str> {
    [
        &[
            "curve", "--preset", "paper", "--mu-s", "1.5", "--y0", "0.25", "--v0", "2.1",
        ][..],
        &FOLD_CURVE,
        &["--json"],
    ]
    .concat()
}

fn library_fold() -> stickslip::continuation::Curve {
    let e = Experiment::paper()
        .with_mu_s(1.5)
        .and_then(|e| e.with_w(0.9))
        .and_then(|e| e.with_beta(1.45))
        .and_then(|e| e.with_initial(State { y: 0.25, v: 2.1 }))
        .unwrap();
    let spec = CurveSpec {
        follow: Follow::Fold,
        vary: Parameter::Beta,
        vary_to: 1.2,
        over: Parameter::W,
        from: 0.8,
        to: 1.0,
    };
    curve(&e, &spec, &ContinuationOptions::default(), &())
        .unwrap()
        .unwrap()
}

#[test]
fn the_csv_and_json_are_the_library_curve() {
    let (dir, out) = run(&[&fold()[..], &["--out", "fold.csv", "--plot", "fold.png"]].concat());
    assert!(out.status.success(), "{}", stderr(&out));
    let c = library_fold();
    let csv = std::fs::read_to_string(dir.path().join("fold.csv")).unwrap();
    assert_eq!(csv, CurveTable { curve: &c }.csv());
    assert!(csv.starts_with(
        "w,beta,y,v,period,stops_per_period,turns,mu1_re,mu1_im,mu2_re,mu2_im,\
         largest_multiplier,stability,arclength,special\n"
    ));
    let rows: Vec<&str> = csv.lines().skip(1).collect();
    assert_eq!(rows.len(), c.points.len());
    assert_eq!(rows.iter().filter(|r| r.ends_with(",start")).count(), 1);
    let json: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    assert_eq!(json, serde_json::to_value(CurveReport::from(&c)).unwrap());
    assert_eq!(json["points"].as_u64(), Some(rows.len() as u64));
    assert_eq!(json["end"]["reason"], "boundary");
    assert!(json["codim2"].is_array());
    let png = std::fs::read(dir.path().join("fold.png")).unwrap();
    assert!(png.starts_with(b"\x89PNG") && png.len() > 10_000);
    // Without --out and --json, the CSV goes to standard output.
    let fold = fold();
    let (_dir, out) = run(&fold[..fold.len() - 1]);
    assert!(out.status.success(), "{}", stderr(&out));
    assert_eq!(stdout(&out), csv);
}

#[test]
fn no_special_point_of_the_kind_is_one_line_and_status_2() {
    let mut args = fold();
    assert_eq!((args[13], args[17]), ("--follow", "--vary-to"));
    args[14] = "period-doubling";
    args[18] = "1.44";
    let dir = tempfile::tempdir().unwrap();
    let out = run_in(dir.path(), &[&args[..], &["--out", "pd.csv"]].concat());
    assert_usage_error(dir.path(), &out, "no period doubling");
    let err = stderr(&out);
    assert!(err.contains("beta from 1.45 towards 1.44"), "{err}");
}

#[test]
fn a_neimark_sacker_curve_is_one_line_naming_why_and_status_2() {
    // The Coulomb model has none (det M < 1 on every orbit: docs/bifurcation.md).
    let mut args = fold();
    assert_eq!(args[13], "--follow");
    args[14] = "neimark-sacker";
    let dir = tempfile::tempdir().unwrap();
    let out = run_in(dir.path(), &[&args[..], &["--out", "ns.csv"]].concat());
    assert_usage_error(dir.path(), &out, "has no Neimark–Sacker point");
    let err = stderr(&out);
    assert!(
        err.contains("det M = 1") && err.contains("below 1"),
        "{err}"
    );
}

#[test]
fn bad_input_is_refused_naming_the_flag() {
    let model = [
        "curve", "--preset", "paper", "--w", "1.2", "--beta", "3", "--follow", "grazing",
    ];
    assert_usage_errors(
        &model,
        &[
            (
                &[
                    "--vary",
                    "beta",
                    "--vary-to",
                    "0.5",
                    "--over",
                    "w",
                    "--from",
                    "1",
                    "--to",
                    "1",
                ],
                "--to",
            ),
            (
                &[
                    "--vary",
                    "w",
                    "--vary-to",
                    "0.5",
                    "--over",
                    "w",
                    "--from",
                    "1",
                    "--to",
                    "2",
                ],
                "invalid --vary: must differ from --over",
            ),
            (
                &[
                    "--vary",
                    "beta",
                    "--vary-to",
                    "3",
                    "--over",
                    "w",
                    "--from",
                    "1",
                    "--to",
                    "2",
                ],
                "--vary-to",
            ),
            (
                &[
                    "--vary",
                    "beta",
                    "--vary-to",
                    "0.5",
                    "--over",
                    "w",
                    "--from",
                    "1.5",
                    "--to",
                    "2",
                ],
                "between from and to",
            ),
            (
                &[
                    "--vary",
                    "beta",
                    "--vary-to",
                    "0.5",
                    "--over",
                    "w",
                    "--from",
                    "1",
                    "--to",
                    "2",
                    "--max-step",
                    "0",
                ],
                "--max-step",
            ),
            (
                &[
                    "--vary",
                    "beta",
                    "--vary-to",
                    "0.5",
                    "--over",
                    "w",
                    "--from",
                    "1",
                    "--to",
                    "2",
                    "--model",
                    "shockley",
                ],
                "piecewise-linear",
            ),
        ],
    );
}

#[test]
fn ctrl_c_leaves_no_file() {
    // A grazing curve of many small steps: a slide touching rest at ζ = 0, μs = 3, β = 9.
    assert_ctrl_c_leaves_nothing(&[
        "curve",
        "--zeta",
        "0",
        "--mu-s",
        "3",
        "--w",
        "0.27",
        "--beta",
        "9",
        "--follow",
        "grazing",
        "--vary",
        "w",
        "--vary-to",
        "0.34",
        "--over",
        "beta",
        "--from",
        "8.5",
        "--to",
        "9.5",
        "--out",
        "g.csv",
        "--plot",
        "g.png",
    ]);
}
