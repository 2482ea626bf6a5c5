//! Tests of `stickslip netlist`, and of `stickslip simulate --model shockley` against the
//! netlist run in ngspice.

use crate::common::*;

#[test]
fn writes_the_paper_circuit_with_the_default_diodes() {
    let (dir, out) = run(&[
        "netlist",
        "--preset",
        "paper",
        "--w",
        "0.95",
        "--beta",
        "2.14",
        "-o",
        "paper.cir",
    ]);
    assert!(out.status.success(), "{}", stderr(&out));
    assert!(out.stdout.is_empty());
    let err = stderr(&out);
    assert!(
        err.contains("preset paper") && err.contains("n = 1.906"),
        "{err}"
    );
    let text = std::fs::read_to_string(dir.path().join("paper.cir")).unwrap();
    for line in [
        "V1 drive 0 SIN(0 1.498e0 ",
        "R1 drive n1 6.8e1\n",
        "L1 n1 n2 1.15e-2 IC=0e0\n",
        "D1 n2 uc DPAIR\nD2 uc n2 DPAIR\n",
        "C1 uc 0 2e-8 IC=0e0\n",
        ".model DPAIR D(IS=4.352e-9 N=1.906e0 RS=6.458e-1)\n",
        ".options temp=2.7e1 tnom=2.7e1\n",
        ".print tran v(uc) i(L1)\n",
        ".end\n",
    ] {
        assert!(text.contains(line), "{line:?} missing from:\n{text}");
    }
    // 300 periods of 1/(0.95 f0) by default.
    let period = 1.0 / (0.95 * 10_494.366_171_921_35);
    let tran = text.lines().find(|l| l.starts_with(".tran")).unwrap();
    let stop: f64 = tran.split_whitespace().nth(2).unwrap().parse().unwrap();
    assert!((stop / (300.0 * period) - 1.0).abs() < 1e-12, "{tran}");
}

#[test]
fn diode_temperature_tolerances_and_control_block_follow_the_flags() {
    let (_dir, out) = run(&[
        "netlist",
        "--preset",
        "paper",
        "--w",
        "0.5",
        "--beta",
        "1",
        "--diode-is",
        "2n",
        "--diode-n",
        "1.5",
        "--diode-rs",
        "1",
        "--temperature",
        "50",
        "--reltol",
        "1e-5",
        "--vntol",
        "1e-8",
        "--periods",
        "10",
        "--wrdata",
        "out.txt",
    ]);
    assert!(out.status.success(), "{}", stderr(&out));
    let text = stdout(&out);
    assert!(
        text.contains(".model DPAIR D(IS=2e-9 N=1.5e0 RS=1e0)\n"),
        "{text}"
    );
    assert!(text.contains(".options temp=5e1 tnom=5e1 reltol=1e-5 vntol=1e-8\n"));
    assert!(text.contains("run\nwrdata out.txt v(uc) i(L1)\nquit\n.endc\n"));
    assert!(!text.contains(".print"));
}

#[test]
fn bad_input_gives_one_line_and_exit_code_2() {
    let base = ["netlist", "--preset", "paper", "--w", "1", "--beta", "1"];
    let cases: &[(&[&str], &str)] = &[
        (&["--periods", "0"], "--periods"),
        (&["--periods", "nan"], "--periods"),
        (&["--max-step", "2"], "--max-step"),
        (&["--points-per-period", "0"], "--points-per-period"),
        (&["--reltol", "-1"], "--reltol"),
        (&["--wrdata", "a b"], "--wrdata"),
        (&["--diode-n", "0"], "n"),
        (&["-o", "missing/dir/x.cir"], "does not exist"),
    ];
    for (extra, needle) in cases {
        let args: Vec<&str> = base.iter().chain(extra.iter()).copied().collect();
        let (dir, out) = run(&args);
        assert_usage_error(dir.path(), &out, needle);
    }
    // Without a circuit there is nothing to write.
    let (dir, out) = run(&["netlist", "--zeta", "0.1", "--w", "1", "--beta", "1"]);
    assert_usage_error(dir.path(), &out, "circuit description");
    let (dir, out) = run(&[
        "netlist",
        "--mass",
        "1",
        "--stiffness",
        "1",
        "--damping",
        "0.1",
        "--friction",
        "1",
        "--w",
        "1",
        "--beta",
        "2",
    ]);
    assert_usage_error(dir.path(), &out, "circuit description");
}

#[test]
fn simulate_runs_the_shockley_model() {
    let (dir, out) = run(&[
        "simulate",
        "--preset",
        "paper",
        "--model",
        "shockley",
        "--w",
        "0.95",
        "--beta",
        "2.14",
        "--periods",
        "30",
        "--samples-per-period",
        "20",
        "--out",
        "t.csv",
        "--events",
        "e.csv",
    ]);
    assert!(out.status.success(), "{}", stderr(&out));
    let csv = std::fs::read_to_string(dir.path().join("t.csv")).unwrap();
    assert_eq!(csv.lines().count(), 602);
    // The drive is 1.498 V: β = 2.14 against U_t = 0.7 V, as with the PWL diode.
    let second: Vec<&str> = csv.lines().nth(1).unwrap().split(',').collect();
    assert_eq!(second[8], "1.498");
    // Sliding: turns only, two per period.
    let events = std::fs::read_to_string(dir.path().join("e.csv")).unwrap();
    let kinds: Vec<&str> = events
        .lines()
        .skip(1)
        .map(|l| l.rsplit(',').next().unwrap())
        .collect();
    assert_eq!(kinds.len(), 60, "{events}");
    assert!(kinds.iter().all(|k| *k == "turn"));
}

/// Linear interpolation of sorted (t, u) rows at t.
fn interpolate(rows: &[(f64, f64)], t: f64) -> f64 {
    let k = rows.partition_point(|r| r.0 < t).clamp(1, rows.len() - 1);
    let (t0, u0) = rows[k - 1];
    let (t1, u1) = rows[k];
    u0 + (u1 - u0) * (t - t0) / (t1 - t0)
}

#[test]
fn simulate_agrees_with_ngspice_on_the_written_netlist() {
    if !matches!(
        std::process::Command::new("ngspice").arg("--version").output(),
        Ok(o) if o.status.success()
    ) {
        eprintln!("SKIPPED simulate_agrees_with_ngspice_on_the_written_netlist: ngspice not found on PATH");
        return;
    }
    let model = [
        "--preset", "paper", "--w", "0.6", "--beta", "1.2", "--phi", "0.4", "--uc0", "0.2",
    ];
    let mut args = vec!["netlist"];
    args.extend(model);
    args.extend([
        "--periods",
        "20",
        "--reltol",
        "1e-6",
        "--vntol",
        "1e-9",
        "--wrdata",
        "out.txt",
        "-o",
        "c.cir",
    ]);
    let (dir, out) = run(&args);
    assert!(out.status.success(), "{}", stderr(&out));
    let spice = std::process::Command::new("ngspice")
        .args(["-b", "c.cir"])
        .current_dir(dir.path())
        .output()
        .unwrap();
    assert!(spice.status.success());
    let rows: Vec<(f64, f64)> = std::fs::read_to_string(dir.path().join("out.txt"))
        .unwrap()
        .lines()
        .map(|l| {
            let v: Vec<f64> = l.split_whitespace().map(|x| x.parse().unwrap()).collect();
            (v[0], v[1])
        })
        .collect();
    let mut args = vec!["simulate", "--model", "shockley"];
    args.extend(model);
    args.extend([
        "--periods",
        "20",
        "--samples-per-period",
        "50",
        "--out",
        "t.csv",
    ]);
    let out = run_in(dir.path(), &args);
    assert!(out.status.success(), "{}", stderr(&out));
    let csv = std::fs::read_to_string(dir.path().join("t.csv")).unwrap();
    let samples: Vec<(f64, f64)> = csv
        .lines()
        .skip(1)
        .map(|l| {
            let v: Vec<&str> = l.split(',').collect();
            (v[5].parse().unwrap(), v[6].parse().unwrap())
        })
        .collect();
    let peak = samples.iter().fold(0.0f64, |m, s| m.max(s.1.abs()));
    let worst = samples.iter().skip(1).fold(0.0f64, |m, &(t, u)| {
        m.max((u - interpolate(&rows, t)).abs())
    });
    assert!(
        worst < 0.01 * peak,
        "deviation {worst} V against a peak of {peak} V"
    );
}
