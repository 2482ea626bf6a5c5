//! Running the real binary in a temporary directory.

use std::path::Path;
use std::process::{Command, Output};

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
