//! Every command gives the same bytes with 1, 2 and 8 threads.

use crate::common::*;
use std::path::Path;
use std::process::Command;

/// Every file under `dir` (relative path → bytes), sorted.
fn files(dir: &Path) -> Vec<(String, Vec<u8>)> {
    let mut out = Vec::new();
    let mut stack = vec![dir.to_path_buf()];
    while let Some(d) = stack.pop() {
        for entry in std::fs::read_dir(&d).unwrap() {
            let path = entry.unwrap().path();
            if path.is_dir() {
                stack.push(path);
            } else {
                let name = path.strip_prefix(dir).unwrap().display().to_string();
                out.push((name, std::fs::read(&path).unwrap()));
            }
        }
    }
    out.sort();
    out
}

/// Standard output and every file written, with `threads` threads.
fn outputs(args: &[&str], threads: &str) -> (Vec<u8>, Vec<(String, Vec<u8>)>) {
    let dir = tempfile::tempdir().unwrap();
    let out = Command::new(env!("CARGO_BIN_EXE_stickslip"))
        .args(args)
        .env("RAYON_NUM_THREADS", threads)
        .current_dir(dir.path())
        .output()
        .unwrap();
    assert!(out.status.success(), "{args:?}: {}", stderr(&out));
    (out.stdout, files(dir.path()))
}

#[test]
fn every_command_gives_the_same_bytes_with_1_2_and_8_threads() {
    let commands: &[&[&str]] = &[
        &[
            "simulate",
            "--preset",
            "paper",
            "--w",
            "0.7",
            "--beta",
            "1.2",
            "--periods",
            "40",
            "--out",
            "t.csv",
            "--events",
            "e.csv",
            "--plot",
            "t.svg",
        ],
        &[
            "simulate",
            "--w",
            "0.9",
            "--beta",
            "1.6",
            "--model",
            "pwl",
            "--periods",
            "3",
        ],
        &[
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
            "5",
        ],
        &[
            "steady", "--preset", "paper", "--w", "0.6", "--beta", "1.2", "--json", "--xy",
            "xy.csv",
        ],
        &["steady", "--w", "0.29", "--beta", "2.14"],
        &[
            "sweep", "--preset", "paper", "--beta", "2.14", "--over", "w", "--from", "0.3", "--to",
            "1.8", "--steps", "31", "--out", "s.csv", "--plot", "s.svg",
        ],
        &[
            "sweep",
            "--zeta",
            "0.05",
            "--w",
            "0.8",
            "--over",
            "beta",
            "--from",
            "1",
            "--to",
            "3",
            "--steps",
            "11",
            "--direction",
            "up",
            "--checkpoint",
            "run.ckpt",
        ],
        &[
            "phase-diagram",
            "--preset",
            "paper",
            "--w-steps",
            "41",
            "--beta-steps",
            "37",
            "--out",
            "m.csv",
            "--plot",
            "m.svg",
        ],
        // Streamed to standard output in blocks of rows whose size follows the threads.
        &[
            "phase-diagram",
            "--preset",
            "paper",
            "--w-steps",
            "90",
            "--beta-steps",
            "12",
        ],
        &[
            "phase-diagram",
            "--zeta",
            "0.1",
            "--mu-s",
            "1.3",
            "--w-steps",
            "23",
            "--beta-steps",
            "19",
            "--checkpoint",
            "run.ckpt",
            "--checkpoint-every",
            "0",
        ],
        &[
            "theory", "--preset", "paper", "--w", "0.95", "--beta", "2.14", "--json",
        ],
        &[
            "theory", "--zeta", "0.0468", "--curve", "boundary", "--w-min", "0.2", "--w-max",
            "2.5", "--steps", "60", "--out", "b.csv",
        ],
        &[
            "convert",
            "--preset",
            "paper",
            "--amplitude",
            "1.498",
            "--freq",
            "9.97k",
            "--json",
        ],
        &[
            "netlist", "--preset", "paper", "--w", "0.95", "--beta", "2.14",
        ],
        &[
            "phase-diagram",
            "--zeta",
            "0",
            "--mu-s",
            "3",
            "--w-min",
            "0.25",
            "--w-max",
            "0.5",
            "--w-steps",
            "11",
            "--beta-min",
            "6",
            "--beta-max",
            "9",
            "--beta-steps",
            "4",
            "--lyapunov-periods",
            "1000",
            "--color",
            "lyapunov",
            "--out",
            "l.csv",
            "--plot",
            "l.svg",
            "--checkpoint",
            "run.ckpt",
            "--checkpoint-every",
            "0",
        ],
        &[
            "orbit",
            "--zeta",
            "0",
            "--mu-s",
            "3",
            "--w",
            "0.33",
            "--beta",
            "9",
            "--period",
            "1",
            "--transient",
            "500",
            "--json",
        ],
        &["orbit", "--preset", "paper", "--w", "0.7", "--beta", "1.2"],
        &[
            "lyapunov",
            "--zeta",
            "0",
            "--mu-s",
            "3",
            "--w",
            "0.33",
            "--beta",
            "9",
            "--transient",
            "200",
            "--periods",
            "1000",
            "--json",
        ],
        &["reproduce", "--quick", "--out", "report"],
        &[
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
            "0.25",
            "--to",
            "0.35",
            "--steps",
            "12",
            "--points",
            "40",
            "--out",
            "bif.csv",
            "--plot",
            "bif.svg",
        ],
        &[
            "basins",
            "--zeta",
            "0",
            "--mu-s",
            "3",
            "--w",
            "0.6",
            "--beta",
            "3.269",
            "--y0-min",
            "-8",
            "--y0-max",
            "8",
            "--v0-min",
            "-8",
            "--v0-max",
            "8",
            "--steps",
            "24",
            "--out",
            "basins.csv",
            "--plot",
            "basins.svg",
            "--json",
        ],
        &[
            "continue",
            "--preset",
            "paper",
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
            "1.25",
            "--out",
            "branch.csv",
            "--plot",
            "branch.svg",
            "--json",
        ],
    ];
    for args in commands {
        let one = outputs(args, "1");
        assert!(
            !one.0.is_empty() || !one.1.is_empty(),
            "{args:?} wrote nothing"
        );
        for threads in ["2", "8"] {
            let other = outputs(args, threads);
            assert!(
                one.0 == other.0,
                "{args:?}: standard output differs with {threads} threads"
            );
            let names: Vec<&String> = one.1.iter().map(|f| &f.0).collect();
            let other_names: Vec<&String> = other.1.iter().map(|f| &f.0).collect();
            assert_eq!(names, other_names, "{args:?} with {threads} threads");
            for (a, b) in one.1.iter().zip(&other.1) {
                assert!(
                    a.1 == b.1,
                    "{args:?}: {} differs with {threads} threads",
                    a.0
                );
            }
        }
    }
}
