//! Tests of `stickslip simulate`.

use crate::common::*;

#[test]
fn writes_trajectory_events_and_plot_with_physical_columns() {
    let (dir, out) = run(&[
        &["simulate"][..],
        &PAPER,
        &[
            "--periods",
            "5",
            "--samples-per-period",
            "50",
            "--out",
            "t.csv",
            "--events",
            "e.csv",
            "--plot",
            "t.png",
        ],
    ]
    .concat());
    assert!(out.status.success(), "{}", stderr(&out));
    assert!(
        stderr(&out).contains("preset paper"),
        "says which description it used"
    );
    let csv = std::fs::read_to_string(dir.path().join("t.csv")).unwrap();
    let mut lines = csv.lines();
    assert_eq!(lines.next(), Some("tau,y,v,drive,phase,t_s,uc_V,i_A,u_V"));
    assert_eq!(lines.count(), 251);
    let events = std::fs::read_to_string(dir.path().join("e.csv")).unwrap();
    assert!(events.starts_with("tau,y,kind\n"));
    assert!(events.contains(",stick") && events.contains(",slip"));
    let png = std::fs::read(dir.path().join("t.png")).unwrap();
    assert_eq!(&png[1..4], b"PNG");
}

#[test]
fn dimensionless_output_has_five_columns() {
    let (_dir, out) = run(&[
        "simulate",
        "--zeta",
        "0.1",
        "--w",
        "1.3",
        "--beta",
        "3",
        "--periods",
        "1",
        "--samples-per-period",
        "4",
    ]);
    assert!(out.status.success(), "{}", stderr(&out));
    let text = stdout(&out);
    assert!(text.starts_with("tau,y,v,drive,phase\n"), "{text}");
    assert_eq!(text.lines().count(), 6);
}

#[test]
fn bad_input_gives_one_line_and_exit_code_2() {
    let cases: &[(&[&str], &str)] = &[
        (&["--zeta", "-1", "--w", "1", "--beta", "2"], "zeta"),
        (&["--zeta", "nan", "--w", "1", "--beta", "2"], "zeta"),
        (&["--w", "0", "--beta", "2"], "w"),
        (&["--w", "abc", "--beta", "2"], "--w"),
        (&["--w", "1", "--beta", "-2"], "beta"),
        (&["--w", "1"], "--beta"),
        (&["--beta", "1"], "--w"),
        (&["--w", "1", "--beta", "2", "--mu-s", "0.5"], "--mu-s"),
        (&["--w", "1", "--beta", "2", "--phi", "inf"], "--phi"),
        (&["--w", "1", "--beta", "2", "--y0", "x"], "--y0"),
        (&["--w", "1", "--beta", "2", "--v0", ""], "--v0"),
        (&["--w", "1", "--beta", "2", "--periods", "0"], "--periods"),
        (&["--w", "1", "--beta", "2", "--periods", "-3"], "--periods"),
        (
            &["--w", "1", "--beta", "2", "--samples-per-period", "0"],
            "--samples-per-period",
        ),
        (
            &["--w", "1", "--beta", "2", "--samples-per-period", "-1"],
            "--samples-per-period",
        ),
        (&["--w", "1", "--beta", "2", "--plot", "x.jpg"], "x.jpg"),
        (
            &["--w", "1", "--beta", "2", "--out", "missing/dir/t.csv"],
            "missing/dir",
        ),
        (
            &[
                "--preset", "paper", "--zeta", "0.1", "--w", "1", "--beta", "2",
            ],
            "--zeta",
        ),
        (&["--preset", "nope", "--w", "1", "--beta", "2"], "--preset"),
        (
            &[
                "--preset",
                "paper",
                "--inductance",
                "-1m",
                "--w",
                "1",
                "--beta",
                "2",
            ],
            "--inductance",
        ),
        (
            &[
                "--preset",
                "paper",
                "--capacitance",
                "0",
                "--w",
                "1",
                "--beta",
                "2",
            ],
            "--capacitance",
        ),
        (
            &[
                "--preset", "paper", "--freq", "1k", "--omega", "5", "--beta", "2",
            ],
            "--freq",
        ),
        (&["--amplitude", "1", "--w", "1"], "--amplitude"),
        (
            &["--config", "nonexistent.toml", "--w", "1", "--beta", "2"],
            "nonexistent.toml",
        ),
        (&["--w", "1", "--beta", "2", "--bogus"], "--bogus"),
    ];
    assert_usage_errors(&["simulate"], cases);
}

#[test]
fn config_file_with_flag_override() {
    let dir = tempfile::tempdir().unwrap();
    std::fs::write(
        dir.path().join("exp.toml"),
        "[circuit]\nL = \"11.5m\"\nC = 0.02e-6\nR = 68\nU_t = 0.7\nR_D = 3.0\n[drive]\nU = 1.498\nf = \"9.97k\"\n",
    )
    .unwrap();
    let out = run_in(
        dir.path(),
        &[
            "simulate",
            "--config",
            "exp.toml",
            "--beta",
            "1.07",
            "--periods",
            "1",
            "--samples-per-period",
            "2",
        ],
    );
    assert!(out.status.success(), "{}", stderr(&out));
    let err = stderr(&out);
    assert!(err.contains("β = 1.070000"), "flag overrides file: {err}");
    assert!(err.contains("w = 0.950"), "frequency from the file: {err}");
    // A bad key in the file is named.
    std::fs::write(dir.path().join("bad.toml"), "[circuit]\nLL = 1\n").unwrap();
    let out = run_in(
        dir.path(),
        &[
            "simulate", "--config", "bad.toml", "--w", "1", "--beta", "2",
        ],
    );
    assert_eq!(out.status.code(), Some(2));
    assert!(stderr(&out).contains("LL"));
}

#[cfg(unix)]
#[test]
fn out_to_a_device_writes_in_place() {
    // `--out /dev/null` must not replace the device by a renamed file.
    let (dir, out) = run(&[
        "simulate",
        "--w",
        "0.7",
        "--beta",
        "1.2",
        "--periods",
        "1",
        "--out",
        "/dev/null",
    ]);
    assert!(out.status.success(), "{}", stderr(&out));
    use std::os::unix::fs::FileTypeExt;
    let kind = std::fs::metadata("/dev/null").unwrap().file_type();
    assert!(kind.is_char_device(), "/dev/null is no longer a device");
    assert!(std::fs::read_dir(dir.path()).unwrap().next().is_none());
}
