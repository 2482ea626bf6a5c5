//! `simulate` streams: memory stays flat however long the run, the output is what the
//! library's sampler gives, and a closed pipe ends the tool quietly.

use crate::common::*;
use std::io::{BufRead, BufReader};
use std::process::{Command, Stdio};
use stickslip::solver::{grid, sample_at};
use stickslip::Experiment;

/// The CSV and event log are exactly the library's samples and events, in the format of
/// Rust's shortest round-trip numbers.
#[test]
fn streamed_output_is_the_librarys_sampling() {
    let (dir, out) = run(&[
        "simulate",
        "--zeta",
        "0.05",
        "--w",
        "0.7",
        "--beta",
        "1.2",
        "--periods",
        "12",
        "--samples-per-period",
        "37",
        "--out",
        "t.csv",
        "--events",
        "e.csv",
    ]);
    assert!(out.status.success(), "{}", stderr(&out));
    let experiment = Experiment::dimensionless(0.05, 0.7, 1.2).unwrap();
    let params = experiment.params().unwrap();
    let mut solver = experiment.solver().unwrap();
    let mut events = Vec::new();
    let times = grid(0.0, 12.0 * params.drive_period(), 12 * 37);
    let samples = sample_at(solver.as_mut(), &times, |e| events.push(*e)).unwrap();
    let mut expected = String::from("tau,y,v,drive,phase\n");
    for s in &samples {
        let drive = solver.drive(s.tau);
        expected += &format!("{},{},{},{},{}\n", s.tau, s.y, s.v, drive, s.phase.label());
    }
    let csv = std::fs::read_to_string(dir.path().join("t.csv")).unwrap();
    assert_eq!(csv, expected);
    let mut expected = String::from("tau,y,kind\n");
    for e in &events {
        expected += &format!("{},{},{}\n", e.tau, e.y, e.kind.label());
    }
    assert!(events.len() > 20);
    assert_eq!(
        std::fs::read_to_string(dir.path().join("e.csv")).unwrap(),
        expected
    );
}

/// Peak resident memory (kB) of `stickslip simulate` over `periods` drive periods, all
/// output to /dev/null but the events, written to a file (as in the report).
fn peak_memory_kb(periods: &str) -> u64 {
    let time = std::path::Path::new("/usr/bin/time");
    assert!(
        time.exists(),
        "GNU time is missing: /usr/bin/time measures the peak memory (apt-get install time)"
    );
    let dir = tempfile::tempdir().unwrap();
    let out = Command::new(time)
        .args(["-f", "%M"])
        .arg(env!("CARGO_BIN_EXE_stickslip"))
        .args([
            "simulate",
            "--w",
            "0.9",
            "--beta",
            "1.6",
            "--periods",
            periods,
            "--samples-per-period",
            "2",
            "--events",
            "events.csv",
            "--plot",
            "trace.png",
        ])
        .current_dir(dir.path())
        .stdout(Stdio::null())
        .output()
        .expect("GNU time runs");
    let err = stderr(&out);
    assert!(out.status.success(), "{err}");
    assert!(dir.path().join("events.csv").is_file() && dir.path().join("trace.png").is_file());
    err.lines()
        .last()
        .and_then(|l| l.trim().parse().ok())
        .unwrap_or_else(|| panic!("no peak memory in: {err}"))
}

/// A 2·10⁶-period run (4·10⁶ samples, 4·10⁶ events, a plot) stays under 50 MB, and uses no
/// more than a ten times shorter run, give or take 8 MB (allocator noise): memory is flat.
#[test]
fn memory_stays_flat_over_two_million_periods() {
    let long = peak_memory_kb("2000000");
    let short = peak_memory_kb("200000");
    eprintln!("peak memory: {long} kB over 2e6 periods, {short} kB over 2e5");
    assert!(long <= 50 * 1024, "{long} kB over 2e6 periods");
    assert!(
        long <= short + 8 * 1024,
        "{long} kB against {short} kB: memory grows"
    );
}

/// With standard output closed by its reader (`| head -1`), the tool dies of SIGPIPE as
/// command-line tools do: no message, status 141 in a shell, no file left behind.
#[test]
fn a_closed_pipe_ends_the_tool_quietly() {
    use std::os::unix::process::ExitStatusExt;
    let dir = tempfile::tempdir().unwrap();
    let mut child = Command::new(env!("CARGO_BIN_EXE_stickslip"))
        .args([
            "simulate",
            "--w",
            "0.9",
            "--beta",
            "1.6",
            "--periods",
            "100000",
            "--events",
            "events.csv",
        ])
        .current_dir(dir.path())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    let mut reader = BufReader::new(child.stdout.take().unwrap());
    let mut first = String::new();
    reader.read_line(&mut first).unwrap();
    assert_eq!(first, "tau,y,v,drive,phase\n");
    drop(reader);
    let out = child.wait_with_output().unwrap();
    assert_eq!(
        out.status.signal(),
        Some(13),
        "{:?}: {}",
        out.status,
        stderr(&out)
    );
    let err = stderr(&out);
    assert!(
        !err.contains("error") && !err.contains("Broken pipe"),
        "a message: {err}"
    );
    let left: Vec<_> = std::fs::read_dir(dir.path()).unwrap().collect();
    assert!(left.is_empty(), "files left behind: {left:?}");

    // The same through a shell pipeline, as a user types it.
    let line = format!(
        "'{}' simulate --w 0.9 --beta 1.6 --periods 100000 | head -1; echo \"status ${{PIPESTATUS[0]}}\"",
        env!("CARGO_BIN_EXE_stickslip")
    );
    let out = Command::new("bash").args(["-c", &line]).output().unwrap();
    assert_eq!(stdout(&out), "tau,y,v,drive,phase\nstatus 141\n");
    assert!(!stderr(&out).contains("rror"), "{}", stderr(&out));

    // Text commands too: the reader is gone before anything is written.
    for args in [
        &["steady", "--w", "0.9", "--beta", "1.6"][..],
        &["theory", "--w", "0.9", "--beta", "1.6", "--json"][..],
        &["convert", "--preset", "paper"][..],
    ] {
        // A pipe whose reader is closed before the child starts: a short computation cannot
        // write into the pipe's buffer before the reader goes.
        let (reader, writer) = std::io::pipe().unwrap();
        drop(reader);
        let child = Command::new(env!("CARGO_BIN_EXE_stickslip"))
            .args(args)
            .stdout(writer)
            .stderr(Stdio::piped())
            .spawn()
            .unwrap();
        let out = child.wait_with_output().unwrap();
        assert_eq!(out.status.signal(), Some(13), "{args:?}: {}", stderr(&out));
        assert!(
            !stderr(&out).contains("error"),
            "{args:?}: {}",
            stderr(&out)
        );
    }
}

/// A run longer than the plot keeps point by point is drawn from the extremes of each
/// stretch of time: the PNG is written whole.
#[test]
fn a_long_run_still_plots() {
    let (dir, out) = run(&[
        "simulate",
        "--w",
        "0.7",
        "--beta",
        "1.2",
        "--periods",
        "3000",
        "--samples-per-period",
        "100",
        "--out",
        "t.csv",
        "--plot",
        "t.png",
    ]);
    assert!(out.status.success(), "{}", stderr(&out));
    let png = std::fs::read(dir.path().join("t.png")).unwrap();
    assert_eq!(&png[1..4], b"PNG");
    let csv = std::fs::read_to_string(dir.path().join("t.csv")).unwrap();
    assert_eq!(csv.lines().count(), 300_002);
}
