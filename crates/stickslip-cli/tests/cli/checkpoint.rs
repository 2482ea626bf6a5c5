//! `--checkpoint`: a map or a sweep killed part way resumes, does only the work left, and
//! writes what an uninterrupted run writes, byte for byte; a checkpoint of other parameters
//! or a damaged one is refused.

use crate::common::*;
use std::path::Path;
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

const MAP: &[&str] = &[
    "phase-diagram",
    "--preset",
    "paper",
    "--w-min",
    "0.2",
    "--w-max",
    "2.4",
    "--w-steps",
    "300",
    "--beta-min",
    "0.5",
    "--beta-max",
    "4",
    "--beta-steps",
    "200",
    "--out",
    "map.csv",
    "--plot",
    "map.png",
];

const SWEEP: &[&str] = &[
    "sweep",
    "--preset",
    "paper",
    "--beta",
    "2.14",
    "--over",
    "w",
    "--from",
    "0.2",
    "--to",
    "2",
    "--steps",
    "400",
    "--direction",
    "both",
    "--out",
    "sweep.csv",
];

/// Start `args` in `dir` (one thread: slow enough to be caught part way), wait until the
/// checkpoint holds `units` more units (of `unit_bytes` each) than at its first save, and
/// kill the process with SIGKILL while it still runs.
fn kill_part_way(dir: &Path, args: &[&str], units: u64, unit_bytes: u64) {
    let mut child = Command::new(env!("CARGO_BIN_EXE_stickslip"))
        .args(args)
        .env("RAYON_NUM_THREADS", "1")
        .current_dir(dir)
        .stdout(Stdio::null())
        .stderr(Stdio::null())
        .spawn()
        .unwrap();
    let ckpt = dir.join("run.ckpt");
    let started = Instant::now();
    let mut first = None;
    loop {
        assert!(
            child.try_wait().unwrap().is_none(),
            "the run finished before it could be killed; make it longer"
        );
        if let Ok(m) = std::fs::metadata(&ckpt) {
            let first = *first.get_or_insert(m.len());
            if m.len() >= first + units * unit_bytes {
                break;
            }
        }
        assert!(
            started.elapsed() < Duration::from_secs(300),
            "no checkpoint saved"
        );
        std::thread::sleep(Duration::from_millis(1));
    }
    child.kill().unwrap();
    let status = child.wait().unwrap();
    use std::os::unix::process::ExitStatusExt;
    assert_eq!(status.signal(), Some(9), "killed by SIGKILL");
}

/// Bytes of a saved row of the map (200 points of 34 bytes, index and length) and of a
/// sweep step (57 bytes, then y_max, y_min, the self-excited period and stick fraction).
const ROW: u64 = 200 * 34 + 16;
const STEP: u64 = 57 + 4 * 8 + 16;

fn with_checkpoint<'a>(args: &[&'a str]) -> Vec<&'a str> {
    let mut v = args.to_vec();
    v.extend(["--checkpoint", "run.ckpt", "--checkpoint-every", "0"]);
    v
}

/// The number after `needle` in `text`, e.g. "resuming from run.ckpt: 37 of 300".
fn number_after(text: &str, needle: &str) -> usize {
    let at = text
        .find(needle)
        .unwrap_or_else(|| panic!("'{needle}' not in: {text}"));
    text[at + needle.len()..]
        .split(|c: char| !c.is_ascii_digit())
        .next()
        .and_then(|n| n.parse().ok())
        .unwrap_or_else(|| panic!("no number after '{needle}' in: {text}"))
}

#[test]
fn a_killed_map_resumes_to_the_same_bytes_with_less_work() {
    let reference = tempfile::tempdir().unwrap();
    let out = run_in(reference.path(), MAP);
    assert!(out.status.success(), "{}", stderr(&out));
    assert_eq!(
        number_after(&stderr(&out), "points ("),
        60_000,
        "all computed"
    );

    let dir = tempfile::tempdir().unwrap();
    let args = with_checkpoint(MAP);
    // About a tenth of the rows.
    kill_part_way(dir.path(), &args, 30, ROW);
    assert!(
        !dir.path().join("map.csv").exists(),
        "no output from the killed run"
    );

    let out = run_in(dir.path(), &args);
    let err = stderr(&out);
    assert!(out.status.success(), "{err}");
    let reused = number_after(&err, "resuming from run.ckpt: ");
    assert!((30..300).contains(&reused), "{reused} rows reused: {err}");
    let computed = number_after(&err, "points (");
    assert_eq!(computed, (300 - reused) * 200, "{err}");
    for file in ["map.csv", "map.png"] {
        let a = std::fs::read(reference.path().join(file)).unwrap();
        let b = std::fs::read(dir.path().join(file)).unwrap();
        assert!(a == b, "{file} differs from the uninterrupted run's");
    }
    assert!(
        !dir.path().join("run.ckpt").exists(),
        "removed after success"
    );
    let left: Vec<_> = std::fs::read_dir(dir.path())
        .unwrap()
        .map(|e| e.unwrap().file_name().into_string().unwrap())
        .filter(|n| n.starts_with('.'))
        .collect();
    assert!(left.is_empty(), "temporary files left: {left:?}");
}

#[test]
fn a_killed_sweep_resumes_to_the_same_bytes_with_less_work() {
    let reference = tempfile::tempdir().unwrap();
    let out = run_in(reference.path(), SWEEP);
    assert!(out.status.success(), "{}", stderr(&out));

    let dir = tempfile::tempdir().unwrap();
    let args = with_checkpoint(SWEEP);
    // About 150 of the 800 steps.
    kill_part_way(dir.path(), &args, 150, STEP);
    let out = run_in(dir.path(), &args);
    let err = stderr(&out);
    assert!(out.status.success(), "{err}");
    let reused = number_after(&err, "resuming from run.ckpt: ");
    assert!((150..800).contains(&reused), "{reused} steps reused: {err}");
    let a = std::fs::read(reference.path().join("sweep.csv")).unwrap();
    let b = std::fs::read(dir.path().join("sweep.csv")).unwrap();
    assert!(a == b, "sweep.csv differs from the uninterrupted run's");
    assert!(!dir.path().join("run.ckpt").exists());
}

/// A map of exponents at μs = 3 (chaos, periodic orbits and rest): its rows carry λ1.
const EXPONENT_MAP: &[&str] = &[
    "phase-diagram",
    "--zeta",
    "0",
    "--mu-s",
    "3",
    "--w-min",
    "0.2",
    "--w-max",
    "0.55",
    "--w-steps",
    "40",
    "--beta-min",
    "3",
    "--beta-max",
    "14",
    "--beta-steps",
    "45",
    "--max-periods",
    "2000",
    "--lyapunov-periods",
    "2000",
    "--color",
    "lambda1",
    "--out",
    "map.csv",
    "--plot",
    "map.png",
];

#[test]
fn a_killed_map_of_exponents_resumes_to_the_same_bytes() {
    let reference = tempfile::tempdir().unwrap();
    let out = run_in(reference.path(), EXPONENT_MAP);
    assert!(out.status.success(), "{}", stderr(&out));
    let csv = std::fs::read_to_string(reference.path().join("map.csv")).unwrap();
    assert!(csv.contains(",chaotic,"), "the map holds chaos");

    let dir = tempfile::tempdir().unwrap();
    let args = with_checkpoint(EXPONENT_MAP);
    // A row without exponents is 45 × 35 + 16 bytes, with them 45 × 67 + 16: at least 4 rows.
    kill_part_way(dir.path(), &args, 4, 45 * 35 + 16);
    let out = run_in(dir.path(), &args);
    let err = stderr(&out);
    assert!(out.status.success(), "{err}");
    let reused = number_after(&err, "resuming from run.ckpt: ");
    assert!((2..40).contains(&reused), "{reused} rows reused: {err}");
    for file in ["map.csv", "map.png"] {
        let a = std::fs::read(reference.path().join(file)).unwrap();
        let b = std::fs::read(dir.path().join(file)).unwrap();
        assert!(a == b, "{file} differs from the uninterrupted run's");
    }

    // A checkpoint of the map of classes is not one of the map of exponents.
    let dir = tempfile::tempdir().unwrap();
    let classes: Vec<&str> = args
        .iter()
        .copied()
        .filter(|a| *a != "--color" && *a != "lambda1")
        .collect();
    kill_part_way(dir.path(), &classes, 0, 45 * 34 + 16);
    let out = run_in(dir.path(), &args);
    assert_eq!(out.status.code(), Some(2), "{}", stderr(&out));
    assert!(
        stderr(&out).contains("lyapunov"),
        "names the difference: {}",
        stderr(&out)
    );
}

/// A checkpoint left by an interrupted small map.
fn interrupted_checkpoint(dir: &Path, args: &[&str]) {
    kill_part_way(dir, args, 0, ROW);
    assert!(dir.join("run.ckpt").is_file());
}

#[test]
fn other_parameters_and_damage_are_refused() {
    let dir = tempfile::tempdir().unwrap();
    let args = with_checkpoint(MAP);
    interrupted_checkpoint(dir.path(), &args);
    let saved = std::fs::read(dir.path().join("run.ckpt")).unwrap();

    // Other parameters: every value that determines the map.
    let refusals: &[(&str, &str, &str)] = &[
        ("--beta-max", "4", "3.9"),
        ("--w-steps", "300", "301"),
        ("--preset", "paper", "paper --mu-s 1.2"),
    ];
    for &(flag, from, to) in refusals {
        let mut changed: Vec<String> = Vec::new();
        let mut i = 0;
        while i < args.len() {
            if args[i] == flag && args[i + 1] == from {
                changed.push(flag.into());
                changed.extend(to.split(' ').map(String::from));
                i += 2;
            } else {
                changed.push(args[i].into());
                i += 1;
            }
        }
        let changed: Vec<&str> = changed.iter().map(String::as_str).collect();
        let out = run_in(dir.path(), &changed);
        let err = stderr(&out);
        assert_eq!(out.status.code(), Some(2), "{flag}: {err}");
        assert_eq!(err.trim_end().lines().count(), 1, "{err}");
        assert!(
            err.contains("cannot resume from checkpoint run.ckpt: checkpoint of other parameters"),
            "{err}"
        );
        assert_eq!(
            std::fs::read(dir.path().join("run.ckpt")).unwrap(),
            saved,
            "kept as it was"
        );
    }
    let mut more = args.clone();
    more.extend(["--max-periods", "4000"]);
    let out = run_in(dir.path(), &more);
    assert_eq!(out.status.code(), Some(2), "{}", stderr(&out));
    assert!(
        stderr(&out).contains("its options differs"),
        "{}",
        stderr(&out)
    );

    // A sweep's command given a map's checkpoint.
    let mut sweep = SWEEP.to_vec();
    sweep.extend(["--checkpoint", "run.ckpt"]);
    let out = run_in(dir.path(), &sweep);
    assert_eq!(out.status.code(), Some(2));
    assert!(stderr(&out).contains("its computation is phase-diagram, this run's is sweep"));

    // Damaged: one bit flipped; cut short; not a checkpoint at all.
    let mut flipped = saved.clone();
    let middle = flipped.len() / 2;
    flipped[middle] ^= 0x04;
    let damaged: [(&[u8], &str); 3] = [
        (&flipped, "damaged checkpoint (checksum mismatch)"),
        (&saved[..saved.len() - 9], "damaged checkpoint"),
        (
            b"w,beta,class\n0.1,1,static\n",
            "not a stickslip checkpoint",
        ),
    ];
    for (bytes, message) in damaged {
        std::fs::write(dir.path().join("run.ckpt"), bytes).unwrap();
        let out = run_in(dir.path(), &args);
        let err = stderr(&out);
        assert_eq!(out.status.code(), Some(2), "{err}");
        assert_eq!(err.trim_end().lines().count(), 1, "{err}");
        assert!(err.contains(message), "{message}: {err}");
        assert_eq!(
            std::fs::read(dir.path().join("run.ckpt")).unwrap(),
            bytes,
            "untouched"
        );
        assert!(!dir.path().join("map.csv").exists());
    }
}

#[test]
fn bad_checkpoint_flags_give_one_line_and_exit_code_2() {
    for (extra, needle) in [
        (
            &["--checkpoint", "no/such/dir/run.ckpt"][..],
            "does not exist",
        ),
        (
            &["--checkpoint", "run.ckpt", "--checkpoint-every", "-1"][..],
            "--checkpoint-every",
        ),
    ] {
        let mut args = MAP.to_vec();
        args.extend(extra);
        let (dir, out) = run(&args);
        assert_usage_error(dir.path(), &out, needle);
    }
}

/// A basin map whose every cell is chaotic (the costliest kind), short caps, by the
/// exhaustive method (every cell on its own, in parallel).
fn basins() -> Vec<&'static str> {
    [
        &["basins", "--method", "exhaustive"][..],
        &CHAOTIC,
        &BASIN_BOX,
        &[
            "--steps",
            "40",
            "--max-periods",
            "300",
            "--lyapunov-periods",
            "300",
            "--out",
            "basins.csv",
            "--plot",
            "basins.png",
            "--json",
        ],
    ]
    .concat()
}

/// Bytes of a saved row of that map: 40 chaotic cells with 64 strobe points each, index
/// and length.
const BASIN_ROW: u64 = 40 * (1 + 4 * 8 + 64 * 16) + 16;

#[test]
fn a_killed_basin_map_resumes_to_the_same_bytes_with_less_work() {
    let reference = tempfile::tempdir().unwrap();
    let first = run_in(reference.path(), &basins());
    assert!(first.status.success(), "{}", stderr(&first));
    assert_eq!(
        number_after(&stderr(&first), "cells ("),
        1600,
        "all computed"
    );

    let dir = tempfile::tempdir().unwrap();
    let args = with_checkpoint(&basins());
    kill_part_way(dir.path(), &args, 4, BASIN_ROW);
    assert!(!dir.path().join("basins.csv").exists(), "no output yet");
    let saved = std::fs::read(dir.path().join("run.ckpt")).unwrap();

    // Another drive phase is another map: refused before any work.
    let mut other = args.clone();
    other.extend(["--phase", "0.5"]);
    let out = run_in(dir.path(), &other);
    assert_eq!(out.status.code(), Some(2), "{}", stderr(&out));
    assert!(
        stderr(&out).contains("cannot resume from checkpoint run.ckpt"),
        "{}",
        stderr(&out)
    );
    assert!(std::fs::read(dir.path().join("run.ckpt")).unwrap() == saved);

    let out = run_in(dir.path(), &args);
    let err = stderr(&out);
    assert!(out.status.success(), "{err}");
    let reused = number_after(&err, "resuming from run.ckpt: ");
    assert!((4..40).contains(&reused), "{reused} rows reused: {err}");
    assert_eq!(number_after(&err, "cells ("), (40 - reused) * 40, "{err}");
    assert!(out.stdout == first.stdout, "the JSON summary differs");
    for file in ["basins.csv", "basins.png"] {
        let a = std::fs::read(reference.path().join(file)).unwrap();
        let b = std::fs::read(dir.path().join(file)).unwrap();
        assert!(a == b, "{file} differs from the uninterrupted run's");
    }
    assert!(
        !dir.path().join("run.ckpt").exists(),
        "removed after success"
    );
}

/// A basin map by recurrence (rows in order, each saved with the labels it left): two
/// coexisting orbits.
fn recurrence() -> Vec<&'static str> {
    [
        &["basins"][..],
        &MIRROR,
        &BASIN_BOX,
        &["--steps", "150", "--out", "basins.csv", "--json"],
    ]
    .concat()
}

/// Least bytes of a saved row of that map: 150 periodic cells with one strobe point each,
/// index and length (the labels it left come on top).
const RECURRENCE_ROW: u64 = 150 * (1 + 4 * 8 + 16) + 16;

#[test]
fn a_killed_recurrence_basin_map_resumes_to_the_same_bytes() {
    let reference = tempfile::tempdir().unwrap();
    let first = run_in(reference.path(), &recurrence());
    assert!(first.status.success(), "{}", stderr(&first));

    let dir = tempfile::tempdir().unwrap();
    let args = with_checkpoint(&recurrence());
    kill_part_way(dir.path(), &args, 3, RECURRENCE_ROW);
    let out = run_in(dir.path(), &args);
    let err = stderr(&out);
    assert!(out.status.success(), "{err}");
    let reused = number_after(&err, "resuming from run.ckpt: ");
    assert!((3..150).contains(&reused), "{reused} rows reused: {err}");
    assert_eq!(number_after(&err, "cells ("), (150 - reused) * 150, "{err}");
    assert!(out.stdout == first.stdout, "the JSON summary differs");
    let a = std::fs::read(reference.path().join("basins.csv")).unwrap();
    let b = std::fs::read(dir.path().join("basins.csv")).unwrap();
    assert!(a == b, "basins.csv differs from the uninterrupted run's");
}

/// A second run on a checkpoint that a running run fills is refused with one line (exit code
/// 2) and changes nothing; the first run then finishes as if alone.
#[test]
fn a_checkpoint_in_use_is_refused() {
    let dir = tempfile::tempdir().unwrap();
    let args = with_checkpoint(MAP);
    let mut first = Command::new(env!("CARGO_BIN_EXE_stickslip"))
        .args(&args)
        .env("RAYON_NUM_THREADS", "1")
        .current_dir(dir.path())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .unwrap();
    let ckpt = dir.path().join("run.ckpt");
    let started = Instant::now();
    while !ckpt.exists() {
        assert!(
            first.try_wait().unwrap().is_none(),
            "the first run ended before its first save"
        );
        assert!(started.elapsed() < Duration::from_secs(300), "no save");
        std::thread::sleep(Duration::from_millis(1));
    }
    let second = run_in(dir.path(), &args);
    let err = stderr(&second);
    assert!(
        first.try_wait().unwrap().is_none(),
        "the first run ended before the second started; make it longer"
    );
    assert_eq!(second.status.code(), Some(2), "{err}");
    assert_eq!(err.trim_end().lines().count(), 1, "one line: {err}");
    assert!(err.contains("in use by another run"), "{err}");
    assert!(second.stdout.is_empty());

    let out = first.wait_with_output().unwrap();
    assert!(out.status.success(), "{}", stderr(&out));
    let reference = tempfile::tempdir().unwrap();
    let alone = run_in(reference.path(), MAP);
    assert!(alone.status.success(), "{}", stderr(&alone));
    for file in ["map.csv", "map.png"] {
        let a = std::fs::read(reference.path().join(file)).unwrap();
        let b = std::fs::read(dir.path().join(file)).unwrap();
        assert!(a == b, "{file} differs from a run alone");
    }
    let left: Vec<_> = std::fs::read_dir(dir.path())
        .unwrap()
        .map(|e| e.unwrap().file_name().into_string().unwrap())
        .filter(|n| n.starts_with('.') || n == "run.ckpt")
        .collect();
    assert!(left.is_empty(), "checkpoint files left: {left:?}");
}
