//! Output plumbing: files that appear whole or not at all, Ctrl-C handling, usage errors.

use anyhow::{Context, Result};
use std::fs::File;
use std::io::{BufWriter, Write};
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicBool, Ordering};

/// An error in what the user typed (bad flag value, conflicting flags): exit code 2.
#[derive(Debug)]
pub struct UsageError(pub String);

impl std::fmt::Display for UsageError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(&self.0)
    }
}

impl std::error::Error for UsageError {}

/// A command that wrote its output but ends with an exit status of its own, having said why
/// on standard error (`stickslip fit` whose fit did not converge: [`NOT_CONVERGED`]).
#[derive(Debug)]
pub struct ExitStatus(pub u8);

impl std::fmt::Display for ExitStatus {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "exit status {}", self.0)
    }
}

impl std::error::Error for ExitStatus {}

/// The exit status of `stickslip fit` when a fit did not converge (its report is printed,
/// and a warning on standard error says why).
pub const NOT_CONVERGED: u8 = 3;

/// Return a usage error (exit code 2) with this message.
macro_rules! usage {
    ($($arg:tt)*) => {
        return Err(anyhow::Error::new($crate::output::UsageError(format!($($arg)*))))
    };
}
pub(crate) use usage;

/// Append one line to a `String` of text output (`writeln!` that cannot fail).
macro_rules! outln {
    ($text:expr, $($arg:tt)*) => {{
        use std::fmt::Write as _;
        let _ = writeln!($text, $($arg)*);
    }};
}
pub(crate) use outln;

/// Write `text` to standard output, reporting errors (a closed pipe among them, which
/// `main` turns into a quiet exit) instead of panicking as `print!` does.
pub fn print(text: &str) -> Result<()> {
    let mut out = std::io::stdout().lock();
    out.write_all(text.as_bytes())?;
    out.flush()?;
    Ok(())
}

/// Whether an error comes from writing to a pipe whose reader has gone (`head` after its
/// first lines, say): the tool then stops quietly, as command-line tools do.
pub fn is_broken_pipe(err: &anyhow::Error) -> bool {
    err.chain().any(|cause| {
        cause
            .downcast_ref::<std::io::Error>()
            .is_some_and(|e| e.kind() == std::io::ErrorKind::BrokenPipe)
    })
}

static INTERRUPTED: AtomicBool = AtomicBool::new(false);

/// Make Ctrl-C set a flag that long computations poll (see [`check_interrupt`]), so they stop
/// cleanly and remove their unfinished output files.
pub fn install_interrupt_handler() {
    let _ = ctrlc::set_handler(|| {
        if INTERRUPTED.swap(true, Ordering::SeqCst) {
            // Second Ctrl-C: leave at once.
            std::process::exit(130);
        }
    });
}

/// Whether Ctrl-C was pressed.
pub fn interrupted() -> bool {
    INTERRUPTED.load(Ordering::Relaxed)
}

/// Fail with "interrupted" if Ctrl-C was pressed.
pub fn check_interrupt() -> Result<()> {
    if interrupted() {
        anyhow::bail!("interrupted; no output file was written");
    }
    Ok(())
}

/// A file written under a temporary name in the same directory and renamed into place by
/// [`AtomicFile::commit`]; dropped without commit, the temporary file is removed. So an
/// output file is either complete or absent. A path that exists and is no regular file (a
/// device such as `/dev/null`, a named pipe) is written in place: a rename would replace it.
pub struct AtomicFile {
    path: PathBuf,
    temp: PathBuf,
    writer: Option<BufWriter<File>>,
    in_place: bool,
}

impl AtomicFile {
    /// Start writing `path`.
    pub fn create(path: &Path) -> Result<Self> {
        let dir = path
            .parent()
            .filter(|p| !p.as_os_str().is_empty())
            .unwrap_or(Path::new("."));
        check_output_path(path)?;
        if std::fs::metadata(path).is_ok_and(|m| !m.is_file() && !m.is_dir()) {
            let file = std::fs::OpenOptions::new()
                .write(true)
                .open(path)
                .with_context(|| format!("cannot write {}", path.display()))?;
            return Ok(Self {
                path: path.to_path_buf(),
                temp: path.to_path_buf(),
                writer: Some(BufWriter::new(file)),
                in_place: true,
            });
        }
        let name = path
            .file_name()
            .with_context(|| format!("{} is not a file name", path.display()))?;
        // The extension stays last so that writers choosing a format by it still work.
        let temp = dir.join(format!(
            ".partial-{}-{}",
            std::process::id(),
            name.to_string_lossy()
        ));
        let file =
            File::create(&temp).with_context(|| format!("cannot create {}", temp.display()))?;
        Ok(Self {
            path: path.to_path_buf(),
            temp,
            writer: Some(BufWriter::new(file)),
            in_place: false,
        })
    }

    /// The temporary path being written (for libraries that write files themselves).
    pub fn temp_path(&self) -> &Path {
        &self.temp
    }

    /// Flush and move the file into place.
    pub fn commit(mut self) -> Result<()> {
        if let Some(mut w) = self.writer.take() {
            w.flush()
                .with_context(|| format!("cannot write {}", self.path.display()))?;
        }
        check_interrupt()?;
        if self.in_place {
            return Ok(());
        }
        std::fs::rename(&self.temp, &self.path)
            .with_context(|| format!("cannot write {}", self.path.display()))?;
        Ok(())
    }
}

impl Write for AtomicFile {
    fn write(&mut self, buf: &[u8]) -> std::io::Result<usize> {
        self.writer.as_mut().expect("writer present").write(buf)
    }
    fn flush(&mut self) -> std::io::Result<()> {
        self.writer.as_mut().expect("writer present").flush()
    }
}

impl Drop for AtomicFile {
    fn drop(&mut self) {
        // A device or pipe written in place is never removed.
        if self.in_place {
            return;
        }
        if self.writer.is_some() || self.temp.exists() {
            self.writer = None;
            let _ = std::fs::remove_file(&self.temp);
        }
    }
}

/// Where text output goes: a file given by the user, or standard output.
pub enum Sink {
    /// A file written atomically.
    File(AtomicFile),
    /// Standard output, buffered.
    Stdout(BufWriter<std::io::StdoutLock<'static>>),
}

impl Sink {
    /// `Some(path)` → that file (atomically), `None` or `-` → standard output.
    pub fn open(path: Option<&Path>) -> Result<Self> {
        match path {
            Some(p) if p != Path::new("-") => Ok(Sink::File(AtomicFile::create(p)?)),
            _ => Ok(Sink::Stdout(BufWriter::with_capacity(
                1 << 16,
                std::io::stdout().lock(),
            ))),
        }
    }

    /// Check, before any work, that [`Sink::open`] will be able to create `path` (nothing to
    /// check for standard output: `None` or `-`).
    pub fn check(path: Option<&Path>) -> Result<()> {
        match path {
            Some(p) if p != Path::new("-") => check_output_path(p),
            _ => Ok(()),
        }
    }

    /// Finish: commit the file, or flush standard output.
    pub fn finish(self) -> Result<()> {
        match self {
            Sink::File(f) => f.commit(),
            Sink::Stdout(mut s) => {
                s.flush()?;
                Ok(())
            }
        }
    }
}

impl Write for Sink {
    fn write(&mut self, buf: &[u8]) -> std::io::Result<usize> {
        match self {
            Sink::File(f) => f.write(buf),
            Sink::Stdout(s) => s.write(buf),
        }
    }
    fn flush(&mut self) -> std::io::Result<()> {
        match self {
            Sink::File(f) => f.flush(),
            Sink::Stdout(s) => s.flush(),
        }
    }
}

/// Check that an output file can be created: its directory exists (a usage error otherwise).
pub fn check_output_path(path: &Path) -> Result<()> {
    let dir = path
        .parent()
        .filter(|p| !p.as_os_str().is_empty())
        .unwrap_or(Path::new("."));
    if !dir.is_dir() {
        usage!(
            "cannot write {}: directory {} does not exist",
            path.display(),
            dir.display()
        );
    }
    Ok(())
}

/// Check that an output path has an extension we can write (`png` or `svg`).
pub fn check_plot_path(path: &Path) -> Result<()> {
    match path.extension().and_then(|e| e.to_str()) {
        Some(e) if e.eq_ignore_ascii_case("png") || e.eq_ignore_ascii_case("svg") => {
            Ok::<(), anyhow::Error>(())
        }
        _ => usage!(
            "invalid plot file {}: the name must end in .png or .svg",
            path.display()
        ),
    }?;
    check_output_path(path)
}

/// A progress bar on standard error when it is a terminal, hidden otherwise.
pub fn progress(len: u64, what: &str) -> indicatif::ProgressBar {
    use std::io::IsTerminal;
    if !std::io::stderr().is_terminal() {
        return indicatif::ProgressBar::hidden();
    }
    let bar = indicatif::ProgressBar::new(len);
    bar.set_style(
        indicatif::ProgressStyle::with_template(
            "{msg:>14} [{elapsed_precise}] {wide_bar} {pos}/{len} (eta {eta})",
        )
        .expect("valid template"),
    );
    bar.set_message(what.to_string());
    bar
}

/// Write a report as CSV, its header then its rows one at a time (no copy of the whole
/// table in memory).
pub fn write_table(out: &mut dyn Write, table: &dyn stickslip::report::Table) -> Result<()> {
    let mut line = table.header();
    line.push('\n');
    out.write_all(line.as_bytes())?;
    for i in 0..table.len() {
        line.clear();
        table.write_row(i, &mut line);
        out.write_all(line.as_bytes())?;
    }
    Ok(())
}
