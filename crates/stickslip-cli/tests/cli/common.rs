//! Running the real binary in a temporary directory.

use std::path::Path;
use std::process::{Command, Output, Stdio};
use std::time::{Duration, Instant};

/// Run `stickslip` with `args` in `dir`.
pub fn run_in(dir: &Path, args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_stickslip"))
        .args(args)
        .current_dir(dir)
        .output()
        .expect("the stickslip binary runs")
}

/// Run `stickslip` with `args` in a fresh temporary directory; returns the directory too.
pub fn run(args: &[&str]) -> (tempfile::TempDir, Output) {
    let dir = tempfile::tempdir().expect("temp dir");
    let out = run_in(dir.path(), args);
    (dir, out)
}

/// Standard output as text.
pub fn stdout(o: &Output) -> String {
    String::from_utf8_lossy(&o.stdout).into_owned()
}

/// Standard error as text.
pub fn stderr(o: &Output) -> String {
    String::from_utf8_lossy(&o.stderr).into_owned()
}

/// Assert a usage error: exit code 2, one line on stderr naming `needle`, nothing on stdout,
/// and no files left in `dir`.
pub fn assert_usage_error(dir: &Path, out: &Output, needle: &str) {
    let err = stderr(out);
    assert_eq!(out.status.code(), Some(2), "stderr: {err}");
    assert_eq!(
        err.trim_end().lines().count(),
        1,
        "one line expected, got: {err}"
    );
    assert!(err.contains(needle), "'{needle}' not in: {err}");
    assert!(out.stdout.is_empty(), "stdout not empty");
    let left: Vec<_> = std::fs::read_dir(dir).expect("dir").collect();
    assert!(left.is_empty(), "files left behind: {left:?}");
}

/// Assert that `command` followed by each case's arguments is a usage error naming the case's
/// needle (see [`assert_usage_error`]), each run in a fresh directory.
pub fn assert_usage_errors(command: &[&str], cases: &[(&[&str], &str)]) {
    for (args, needle) in cases {
        let dir = tempfile::tempdir().expect("temp dir");
        let out = run_in(dir.path(), &[command, args].concat());
        assert_usage_error(dir.path(), &out, needle);
    }
}

/// Start `stickslip` with `args` in `dir`, send it SIGINT (Ctrl-C) once it catches the signal
/// (its handler is installed before it computes) and a moment later, and wait for it to end;
/// returns its output and the work it did after the signal: the CPU time of all its threads
/// (Linux: from `/proc/<pid>/stat`, read as the signal is sent and once the binary has ended;
/// elsewhere the wall time). A loaded machine stretches the wall time of a stop, not the work
/// in it. On a loaded machine a fixed delay could send the signal before the handler is there
/// (the default action then kills the binary without a word): the handler is waited for,
/// however long it takes.
pub fn interrupt_in(dir: &Path, args: &[&str]) -> (Output, Duration) {
    let mut child = Command::new(env!("CARGO_BIN_EXE_stickslip"))
        .args(args)
        .current_dir(dir)
        .stdout(Stdio::piped())
        .stderr(Stdio::piped())
        .spawn()
        .expect("the stickslip binary starts");
    wait_until_ctrl_c_is_caught(&mut child);
    // A moment into the computation (the checks hold however far it got).
    std::thread::sleep(Duration::from_millis(300));
    let cpu_at_signal = cpu_time(child.id());
    let signalled = Instant::now();
    let status = Command::new("kill")
        .args(["-INT", &child.id().to_string()])
        .status()
        .expect("kill runs");
    assert!(status.success());
    // Read the pipes meanwhile (a binary blocked on a full pipe would never end).
    let drain = |pipe: Option<Box<dyn std::io::Read + Send>>| {
        std::thread::spawn(move || {
            let mut bytes = Vec::new();
            if let Some(mut pipe) = pipe {
                std::io::Read::read_to_end(&mut pipe, &mut bytes).expect("the pipe reads");
            }
            bytes
        })
    };
    let stdout = drain(child.stdout.take().map(|p| Box::new(p) as _));
    let stderr = drain(child.stderr.take().map(|p| Box::new(p) as _));
    // The CPU time of the ended binary, read before it is reaped (a zombie keeps its counts).
    let cpu_at_end = cpu_at_signal.and_then(|_| loop {
        match process_state(child.id()) {
            Some('Z') | None => break cpu_time(child.id()),
            Some(_) => std::thread::sleep(Duration::from_millis(5)),
        }
    });
    let status = child.wait().expect("the stickslip binary ends");
    let out = Output {
        status,
        stdout: stdout.join().expect("stdout is read"),
        stderr: stderr.join().expect("stderr is read"),
    };
    let stopping = match (cpu_at_signal, cpu_at_end) {
        (Some(start), Some(end)) => end.saturating_sub(start),
        _ => signalled.elapsed(),
    };
    (out, stopping)
}

/// Field `n` (1-based, as proc(5) numbers them) of `/proc/<pid>/stat`, where that file is.
fn stat_field(pid: u32, n: usize) -> Option<String> {
    let stat = std::fs::read_to_string(format!("/proc/{pid}/stat")).ok()?;
    // The command name (field 2) is in parentheses and may hold spaces: count after it.
    let rest = &stat[stat.rfind(')')? + 1..];
    rest.split_whitespace()
        .nth(n.checked_sub(3)?)
        .map(String::from)
}

/// The state letter of process `pid` (`Z` once it has ended and is not yet reaped).
fn process_state(pid: u32) -> Option<char> {
    stat_field(pid, 3)?.chars().next()
}

/// The user and system CPU time of process `pid`, all its threads (fields 14 and 15 of
/// `/proc/<pid>/stat`, in the kernel's USER_HZ = 100 ticks a second).
fn cpu_time(pid: u32) -> Option<Duration> {
    let ticks = |n| stat_field(pid, n)?.parse::<u64>().ok();
    Some(Duration::from_millis((ticks(14)? + ticks(15)?) * 10))
}

/// Wait until `child` catches SIGINT (Linux: the `SigCgt` mask of `/proc/<pid>/status`), or
/// has ended; elsewhere, 700 ms.
pub fn wait_until_ctrl_c_is_caught(child: &mut std::process::Child) {
    if cfg!(target_os = "linux") {
        loop {
            if let Ok(Some(_)) = child.try_wait() {
                return;
            }
            let status =
                std::fs::read_to_string(format!("/proc/{}/status", child.id())).unwrap_or_default();
            let caught = status
                .lines()
                .find_map(|l| l.strip_prefix("SigCgt:"))
                .and_then(|mask| u64::from_str_radix(mask.trim(), 16).ok());
            // SIGINT is signal 2: bit 1 of the mask.
            if caught.is_some_and(|mask| mask & 0b10 != 0) {
                return;
            }
            std::thread::sleep(Duration::from_millis(5));
        }
    } else {
        std::thread::sleep(Duration::from_millis(700));
    }
}

/// Assert that `stickslip` with `args`, interrupted by Ctrl-C while it computes, fails,
/// says it was interrupted and leaves no file behind; returns its output and the work it did
/// after the signal ([`interrupt_in`]), for more checks.
pub fn assert_ctrl_c_leaves_nothing(args: &[&str]) -> (Output, Duration) {
    let dir = tempfile::tempdir().expect("temp dir");
    let (out, stopping) = interrupt_in(dir.path(), args);
    assert!(!out.status.success(), "{}", args[0]);
    assert!(stderr(&out).contains("interrupted"), "{}", stderr(&out));
    let left: Vec<_> = std::fs::read_dir(dir.path()).expect("dir").collect();
    assert!(left.is_empty(), "files left behind: {left:?}");
    (out, stopping)
}

/// The chaotic point of the dry-friction oscillator the dynamics tests measure: ζ = 0,
/// μs = 3, w = 0.33, β = 9.
pub const CHAOTIC: [&str; 8] = ["--zeta", "0", "--mu-s", "3", "--w", "0.33", "--beta", "9"];

/// The point with two coexisting mirror orbits: ζ = 0, μs = 3, w = 0.6, β = 3.269.
pub const MIRROR: [&str; 8] = [
    "--zeta", "0", "--mu-s", "3", "--w", "0.6", "--beta", "3.269",
];

/// The box of initial states a basin map covers in these tests: y0 and v0 from -8 to 8.
pub const BASIN_BOX: [&str; 8] = [
    "--y0-min", "-8", "--y0-max", "8", "--v0-min", "-8", "--v0-max", "8",
];

/// `curve`'s fold from the sliding orbit at w = 0.9, β = 1.45 (the orbit with two stops at
/// the paper's ζ and μs = 1.5), followed in β (towards 1.2) over w from 0.8 to 1.
pub const FOLD_CURVE: [&str; 16] = [
    "--w",
    "0.9",
    "--beta",
    "1.45",
    "--follow",
    "fold",
    "--vary",
    "beta",
    "--vary-to",
    "1.2",
    "--over",
    "w",
    "--from",
    "0.8",
    "--to",
    "1",
];

/// The paper's circuit (PWL diodes) at w = 0.7, β = 1.2, where most commands are tried.
pub const PAPER: [&str; 6] = ["--preset", "paper", "--w", "0.7", "--beta", "1.2"];
