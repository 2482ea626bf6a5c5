//! Support for the measurement tests that run ngspice as an external program (the records
//! themselves come from the `stickslip-testkit` crate).
//!
//! Included with `mod support;` by the tests; not every user takes every item.
#![allow(dead_code)]

use std::io::Write;
use std::path::{Path, PathBuf};
use std::process::Command;

/// Whether ngspice runs. When it does not: fails if `STICKSLIP_REQUIRE_NGSPICE` is set (and
/// not `0`), else says on standard error, past the harness's capture, why the test is skipped.
pub fn ngspice_available(test: &str) -> bool {
    if let Ok(out) = Command::new("ngspice").arg("--version").output() {
        if out.status.success() {
            return true;
        }
    }
    let required = std::env::var("STICKSLIP_REQUIRE_NGSPICE").is_ok_and(|v| v != "0");
    assert!(
        !required,
        "{test}: ngspice not found on PATH, and STICKSLIP_REQUIRE_NGSPICE is set"
    );
    let _ = writeln!(
        std::io::stderr(),
        "SKIPPED {test}: ngspice not found on PATH (apt-get install ngspice to run it; \
         STICKSLIP_REQUIRE_NGSPICE=1 makes this a failure)"
    );
    false
}

/// A fresh directory `name` under the target's temporary directory.
pub fn work_dir(name: &str) -> PathBuf {
    let dir = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join(name);
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).expect("create the work directory");
    dir
}

/// Run ngspice in batch mode on `netlist` (whose `wrdata` writes `out.txt`) in `dir`, and
/// return the rows it wrote (t in s, the first saved vector).
pub fn run_ngspice(dir: &Path, netlist: &str) -> Vec<(f64, f64)> {
    std::fs::write(dir.join("circuit.cir"), netlist).unwrap();
    let out = Command::new("ngspice")
        .args(["-b", "circuit.cir"])
        .current_dir(dir)
        .output()
        .expect("ngspice runs");
    assert!(
        out.status.success(),
        "ngspice failed: {}",
        String::from_utf8_lossy(&out.stderr)
    );
    let data = std::fs::read_to_string(dir.join("out.txt")).expect("ngspice wrote its output");
    data.lines()
        .filter(|l| !l.trim().is_empty())
        .map(|l| {
            let v: Vec<f64> = l
                .split_whitespace()
                .map(|x| x.parse().expect("a number"))
                .collect();
            (v[0], v[1])
        })
        .collect()
}

/// Linear interpolation of ngspice's points at `t` (with its steps at most 1/1000 of a
/// period the error is below 10⁻⁵ of the amplitude, far under one 8-bit step).
pub fn interpolate(points: &[(f64, f64)], t: f64) -> f64 {
    let k = points
        .partition_point(|p| p.0 <= t)
        .clamp(1, points.len() - 1);
    let ((t0, y0), (t1, y1)) = (points[k - 1], points[k]);
    y0 + (y1 - y0) * (t - t0) / (t1 - t0)
}
