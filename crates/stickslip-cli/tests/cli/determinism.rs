//! Every command gives the same bytes with 1, 2 and 8 threads, and the same bytes as the
//! golden files in `tests/golden/determinism` (the outputs before the request layer; rewrite
//! them with `STICKSLIP_BLESS=1` only for a change that is meant and listed in CHANGELOG.md).

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

/// Files larger than this are kept in the golden directory as their length and hash.
const GOLDEN_INLINE_MAX: usize = 64 * 1024;

/// FNV-1a, 64 bits: enough to tell a changed file from the golden one.
fn fnv1a(bytes: &[u8]) -> u64 {
    let mut h: u64 = 0xcbf2_9ce4_8422_2325;
    for &b in bytes {
        h ^= u64::from(b);
        h = h.wrapping_mul(0x0000_0100_0000_01b3);
    }
    h
}

/// What the golden directory holds for one output: the bytes, or `len hash` for a large one.
fn golden_form(name: &str, bytes: &[u8]) -> (String, Vec<u8>) {
    if bytes.len() > GOLDEN_INLINE_MAX {
        (
            format!("{name}.fnv"),
            format!("{} {:016x}\n", bytes.len(), fnv1a(bytes)).into_bytes(),
        )
    } else {
        (name.to_string(), bytes.to_vec())
    }
}

/// Compare the outputs of command `index` with its golden directory (or write it when
/// `STICKSLIP_BLESS=1`).
fn check_golden(index: usize, args: &[&str], out: &(Vec<u8>, Vec<(String, Vec<u8>)>)) {
    let root = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/golden/determinism");
    let dir = root.join(format!("{index:02}-{}", args[0]));
    let mut expected: Vec<(String, Vec<u8>)> = vec![golden_form("stdout", &out.0)];
    for (name, bytes) in &out.1 {
        expected.push(golden_form(&format!("files/{name}"), bytes));
    }
    expected.sort();
    if std::env::var_os("STICKSLIP_BLESS").is_some_and(|v| v == "1") {
        let _ = std::fs::remove_dir_all(&dir);
        for (name, bytes) in &expected {
            let path = dir.join(name);
            std::fs::create_dir_all(path.parent().unwrap()).unwrap();
            std::fs::write(&path, bytes).unwrap();
        }
        return;
    }
    assert!(
        dir.is_dir(),
        "{args:?}: no golden directory {} (write it with STICKSLIP_BLESS=1)",
        dir.display()
    );
    let golden = files(&dir);
    let names: Vec<&String> = expected.iter().map(|f| &f.0).collect();
    let golden_names: Vec<&String> = golden.iter().map(|f| &f.0).collect();
    assert_eq!(
        names,
        golden_names,
        "{args:?}: files differ from {}",
        dir.display()
    );
    for (a, b) in expected.iter().zip(&golden) {
        assert!(
            a.1 == b.1,
            "{args:?}: {} differs from its golden file in {}",
            a.0,
            dir.display()
        );
    }
}

#[test]
fn every_command_gives_the_same_bytes_with_1_2_and_8_threads() {
    let commands: &[&[&str]] = &[
        &[
            &["simulate"][..],
            &PAPER,
            &[
                "--periods",
                "40",
                "--out",
                "t.csv",
                "--events",
                "e.csv",
                "--plot",
                "t.svg",
            ],
        ]
        .concat(),
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
            "lambda1",
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
            &["orbit"][..],
            &CHAOTIC,
            &["--period", "1", "--transient", "500", "--json"],
        ]
        .concat(),
        &["orbit", "--preset", "paper", "--w", "0.7", "--beta", "1.2"],
        &[
            &["lyapunov"][..],
            &CHAOTIC,
            &["--transient", "200", "--periods", "1000", "--json"],
        ]
        .concat(),
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
            &["basins"][..],
            &MIRROR,
            &BASIN_BOX,
            &[
                "--steps",
                "24",
                "--out",
                "basins.csv",
                "--plot",
                "basins.svg",
                "--json",
            ],
        ]
        .concat(),
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
    for (index, args) in commands.iter().enumerate() {
        let one = outputs(args, "1");
        check_golden(index, args, &one);
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
