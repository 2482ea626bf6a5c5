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
    assert_eq!(lines[0], "w,beta,class,period,stops_per_cycle,gain");
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
    ];
    for (args, needle) in cases {
        let dir = tempfile::tempdir().unwrap();
        let mut full = vec!["phase-diagram"];
        full.extend_from_slice(args);
        let out = run_in(dir.path(), &full);
        assert_usage_error(dir.path(), &out, needle);
    }
}

#[test]
fn ctrl_c_leaves_no_output_file() {
    let dir = tempfile::tempdir().unwrap();
    let child = std::process::Command::new(env!("CARGO_BIN_EXE_stickslip"))
        .args([
            "phase-diagram",
            "--w-steps",
            "1000",
            "--beta-steps",
            "1000",
            "--out",
            "map.csv",
            "--plot",
            "map.png",
        ])
        .current_dir(dir.path())
        .stdout(std::process::Stdio::null())
        .stderr(std::process::Stdio::piped())
        .spawn()
        .unwrap();
    std::thread::sleep(std::time::Duration::from_millis(700));
    let status = std::process::Command::new("kill")
        .args(["-INT", &child.id().to_string()])
        .status()
        .unwrap();
    assert!(status.success());
    let out = child.wait_with_output().unwrap();
    assert!(!out.status.success());
    assert!(stderr(&out).contains("interrupted"), "{}", stderr(&out));
    let left: Vec<_> = std::fs::read_dir(dir.path()).unwrap().collect();
    assert!(left.is_empty(), "files left behind: {left:?}");
}
