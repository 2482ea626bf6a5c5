//! `continue --over vb` on a forced Coulomb belt: the branch's CSV passes through the steady
//! states `steady` settles on at the belt speeds it crosses (the library's continuation in
//! vb, its derivative from the exact pieces).

use crate::common::*;

const MODEL: [&str; 8] = [
    "--zeta", "0.05", "--w", "0.5", "--beta", "1", "--mu-s", "1.5",
];

#[test]
fn continue_over_the_belt_speed_passes_through_the_steady_states() {
    let (dir, out) = run(&[
        &["continue"][..],
        &MODEL,
        &[
            "--over",
            "vb",
            "--from",
            "0.2",
            "--to",
            "0.42",
            "--max-step",
            "0.02",
            "--out",
            "branch.csv",
        ],
    ]
    .concat());
    assert!(out.status.success(), "{}", stderr(&out));
    let text = std::fs::read_to_string(dir.path().join("branch.csv")).unwrap();
    let mut lines = text.lines();
    let header: Vec<&str> = lines.next().unwrap().split(',').collect();
    assert_eq!(header[..4], ["vb", "y", "v", "amplitude"]);
    let stops = header
        .iter()
        .position(|&h| h == "stops_per_period")
        .unwrap();
    let rows: Vec<Vec<f64>> = lines
        .map(|l| {
            l.split(',')
                .map(|c| c.parse().unwrap_or(f64::NAN))
                .collect()
        })
        .collect();
    let last = rows.last().unwrap()[0];
    assert!((last - 0.42).abs() < 1e-9, "the branch ends at vb = {last}");
    for vb in ["0.25", "0.3", "0.35", "0.4"] {
        let (_d, out) = run(&[&["steady"][..], &MODEL, &["--vb", vb, "--json"]].concat());
        assert!(out.status.success(), "{}", stderr(&out));
        let steady: serde_json::Value = serde_json::from_str(&stdout(&out)).unwrap();
        let want = (steady["y_max"].as_f64().unwrap() - steady["y_min"].as_f64().unwrap()) / 2.0;
        let x: f64 = vb.parse().unwrap();
        let pair = rows
            .windows(2)
            .find(|p| p[0][0] <= x && x <= p[1][0])
            .unwrap_or_else(|| panic!("vb = {x} not on the branch"));
        let f = (x - pair[0][0]) / (pair[1][0] - pair[0][0]);
        let amplitude = pair[0][3] + f * (pair[1][3] - pair[0][3]);
        assert!(
            (amplitude - want).abs() < 2e-3,
            "vb = {x}: branch amplitude {amplitude}, steady {want}"
        );
        assert_eq!(
            pair[0][stops],
            steady["stops_per_period"].as_f64().unwrap(),
            "vb = {x}"
        );
    }
}
