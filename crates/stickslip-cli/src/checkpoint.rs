//! `--checkpoint FILE`: a long computation saves its finished units (rows of a map, steps
//! of a sweep) as it goes, and a rerun of the same command with the same file resumes.
//!
//! The format and its checks are the library's ([`stickslip::checkpoint`]); this module
//! reads and writes the file. Saving writes a temporary file beside it (`.NAME.partial`) and
//! renames it over the checkpoint, so the file on disk is always a whole checkpoint, whenever
//! the process is stopped (even by SIGKILL). Saves come at most every `--checkpoint-every`
//! seconds, and never more often than twenty times the last save took, so that saving costs
//! at most about 5 % of the time. The checkpoint is removed once the command's output is
//! written; it stays when the command fails or is interrupted, for the rerun. A run holds a
//! lock on `.NAME.lock` beside the checkpoint, so that a second run on the same file is
//! refused with one line instead of mixing its rows in.

use crate::flags::{help, num};
use crate::output::{usage, UsageError};
use anyhow::{Context, Result};
use std::io::Write;
use std::path::{Path, PathBuf};
use std::time::{Duration, Instant};
use stickslip::checkpoint::{Checkpoint, Identity};
use stickslip::OptionKey;

/// Flags of a command that can save its work and resume.
#[derive(Debug, Clone, clap::Args)]
#[command(next_help_heading = "Resuming")]
pub struct CheckpointFlags {
    /// Save finished work in FILE as the run goes; rerun the same command with the same FILE
    /// to resume where it stopped (interrupted, killed, or out of time). FILE is refused if
    /// it belongs to other parameters or is damaged, and removed once the output is written.
    #[arg(long, value_name = "FILE")]
    pub checkpoint: Option<PathBuf>,
    #[arg(long = OptionKey::CheckpointEvery.flag(), help = help(OptionKey::CheckpointEvery), default_value_t = num(OptionKey::CheckpointEvery), value_name = "SECONDS", value_parser = crate::model::finite, allow_hyphen_values = true)]
    pub every: f64,
}

impl CheckpointFlags {
    /// Check the flags before any work.
    pub fn check(&self) -> Result<()> {
        stickslip::options::OptionKey::CheckpointEvery.check(self.every)?;
        if let Some(path) = &self.checkpoint {
            crate::output::check_output_path(path)?;
            if path.is_dir() {
                usage!("invalid --checkpoint {}: a directory", path.display());
            }
        }
        Ok(())
    }

    /// Open the checkpoint of a computation of `total` units identified by `identity`: the
    /// saved one when FILE exists (checked), else an empty one. `None` without
    /// `--checkpoint`.
    pub fn open(&self, identity: Identity, total: usize) -> Result<Option<CheckpointFile>> {
        let Some(path) = &self.checkpoint else {
            return Ok(None);
        };
        let lock = lock(path)?;
        let checkpoint = match std::fs::read(path) {
            Ok(bytes) => {
                let checkpoint = Checkpoint::from_bytes(&bytes, &identity).map_err(|e| {
                    UsageError(format!(
                        "cannot resume from checkpoint {}: {e}; delete it or give another file",
                        path.display()
                    ))
                })?;
                if checkpoint.total() != total {
                    usage!(
                        "cannot resume from checkpoint {}: it has {} units, this run {total}; \
                         delete it or give another file",
                        path.display(),
                        checkpoint.total()
                    );
                }
                checkpoint
            }
            Err(e) if e.kind() == std::io::ErrorKind::NotFound => Checkpoint::new(identity, total),
            Err(e) => {
                return Err(
                    UsageError(format!("cannot read checkpoint {}: {e}", path.display())).into(),
                )
            }
        };
        Ok(Some(CheckpointFile {
            lock,
            temp: temp_path(path),
            path: path.clone(),
            checkpoint,
            every: Duration::from_secs_f64(self.every),
            last_save: Instant::now(),
            last_cost: Duration::ZERO,
            unsaved: false,
        }))
    }
}

/// `.NAME.partial` beside `path`: always the same name, so that a save cut short by a kill
/// is overwritten by the next one.
fn temp_path(path: &Path) -> PathBuf {
    beside(path, "partial")
}

/// `.NAME.SUFFIX` beside `path`.
fn beside(path: &Path, suffix: &str) -> PathBuf {
    let name = path
        .file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_else(|| "checkpoint".into());
    path.with_file_name(format!(".{name}.{suffix}"))
}

/// Take the lock of the checkpoint at `path` (an exclusive advisory lock on `.NAME.lock`
/// beside it), so that two runs never fill one checkpoint. The system releases the lock when
/// the process ends, however it ends (a SIGKILL too), so a stopped run never blocks the
/// rerun.
fn lock(path: &Path) -> Result<LockFile> {
    let lock_path = beside(path, "lock");
    let cannot = |e: std::io::Error| {
        UsageError(format!(
            "cannot lock checkpoint {}: {}: {e}",
            path.display(),
            lock_path.display()
        ))
    };
    let file = std::fs::OpenOptions::new()
        .create(true)
        .truncate(false)
        .write(true)
        .open(&lock_path)
        .map_err(cannot)?;
    match file.try_lock() {
        Ok(()) => Ok(LockFile {
            path: lock_path,
            _file: file,
        }),
        Err(std::fs::TryLockError::WouldBlock) => usage!(
            "checkpoint {} is in use by another run, which holds the lock {}; wait for that \
             run to end or give another file",
            path.display(),
            lock_path.display()
        ),
        Err(std::fs::TryLockError::Error(e)) => Err(cannot(e).into()),
    }
}

/// The held lock of a checkpoint (see [`lock`]); released when dropped.
struct LockFile {
    path: PathBuf,
    _file: std::fs::File,
}

/// A checkpoint being filled and saved (see the module documentation).
pub struct CheckpointFile {
    lock: LockFile,
    path: PathBuf,
    temp: PathBuf,
    checkpoint: Checkpoint,
    every: Duration,
    last_save: Instant,
    last_cost: Duration,
    unsaved: bool,
}

impl CheckpointFile {
    /// The checkpoint.
    pub fn checkpoint(&self) -> &Checkpoint {
        &self.checkpoint
    }

    /// The file's path.
    pub fn path(&self) -> &Path {
        &self.path
    }

    /// Store a finished unit, and save when a save is due.
    pub fn insert(&mut self, index: usize, unit: Vec<u8>) -> Result<()> {
        self.checkpoint.insert(index, unit)?;
        self.unsaved = true;
        let since = self.last_save.elapsed();
        if self.every.is_zero() || (since >= self.every && since >= 20 * self.last_cost) {
            self.save()?;
        }
        Ok(())
    }

    /// Save now (temporary file, then rename), if anything is unsaved.
    pub fn save(&mut self) -> Result<()> {
        if !self.unsaved {
            return Ok(());
        }
        let started = Instant::now();
        let bytes = self.checkpoint.to_bytes();
        let write = || -> std::io::Result<()> {
            let mut file = std::fs::File::create(&self.temp)?;
            file.write_all(&bytes)?;
            file.sync_all()?;
            std::fs::rename(&self.temp, &self.path)
        };
        write().with_context(|| format!("cannot save checkpoint {}", self.path.display()))?;
        self.unsaved = false;
        self.last_save = Instant::now();
        self.last_cost = started.elapsed();
        Ok(())
    }

    /// Compute the rows of a map that the checkpoint lacks and store each finished row;
    /// returns the number of cells computed. `command` names the work in the resume message;
    /// `per_thread` is the number of cells per thread handed to `compute` at once (enough to
    /// keep every thread busy); `compute(rows, monitor)` computes whole rows, row-major,
    /// and `encode` turns one row into a checkpoint unit. The bar counts cells; Ctrl-C stops
    /// the work (what is finished stays saved).
    pub fn fill_rows<T>(
        &mut self,
        command: &str,
        columns: usize,
        per_thread: usize,
        bar: &indicatif::ProgressBar,
        compute: impl Fn(
            std::ops::Range<usize>,
            &dyn stickslip::scan::Monitor,
        ) -> stickslip::Result<Vec<T>>,
        encode: impl Fn(&[T]) -> Vec<u8>,
    ) -> Result<usize> {
        let done = self.checkpoint.done();
        if done > 0 {
            eprintln!(
                "{command}: resuming from {}: {} of {} rows reused",
                self.path.display(),
                done,
                self.checkpoint.total()
            );
            bar.inc((done * columns) as u64);
        }
        let block_rows = (per_thread * rayon::current_num_threads())
            .div_ceil(columns.max(1))
            .max(1);
        let missing: Vec<usize> = self.checkpoint.missing().collect();
        let mut computed = 0;
        for block in missing.chunk_by(|a, b| b == &(a + 1)) {
            for rows in block.chunks(block_rows) {
                let (first, last) = (rows[0], rows[rows.len() - 1]);
                let cells = compute(first..last + 1, &|_: usize, _: usize| {
                    bar.inc(1);
                    !crate::output::interrupted()
                })?;
                for (row, chunk) in rows.iter().zip(cells.chunks(columns)) {
                    self.insert(*row, encode(chunk))?;
                }
                computed += cells.len();
            }
        }
        Ok(computed)
    }

    /// The output is written: remove the checkpoint.
    pub fn remove(self) -> Result<()> {
        let _ = std::fs::remove_file(&self.temp);
        // Removed while still held: a run that starts now creates and locks a new one.
        let _ = std::fs::remove_file(&self.lock.path);
        match std::fs::remove_file(&self.path) {
            Err(e) if e.kind() != std::io::ErrorKind::NotFound => {
                Err(e).with_context(|| format!("cannot remove checkpoint {}", self.path.display()))
            }
            _ => Ok(()),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn flags(path: &Path, every: f64) -> CheckpointFlags {
        CheckpointFlags {
            checkpoint: Some(path.to_path_buf()),
            every,
        }
    }

    #[test]
    fn saves_resumes_and_refuses_other_runs() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("run.ckpt");
        let id = || Identity::new("test").with("grid", "3 rows");
        let mut file = flags(&path, 0.0).open(id(), 3).unwrap().unwrap();
        file.insert(1, vec![1, 2, 3]).unwrap();
        assert!(path.exists(), "saved after the unit (every 0 s)");
        assert!(!temp_path(&path).exists(), "renamed into place");
        drop(file);

        let resumed = flags(&path, 10.0).open(id(), 3).unwrap().unwrap();
        assert_eq!(resumed.checkpoint().unit(1), Some(&[1u8, 2, 3][..]));
        assert_eq!(
            resumed.checkpoint().missing().collect::<Vec<_>>(),
            vec![0, 2]
        );
        // A second run while this one holds the checkpoint.
        let err = flags(&path, 0.0).open(id(), 3).err().unwrap().to_string();
        assert!(err.contains("is in use by another run"), "{err}");
        drop(resumed);

        let other = Identity::new("test").with("grid", "4 rows");
        let err = flags(&path, 0.0).open(other, 3).err().unwrap().to_string();
        assert!(
            err.contains("its grid is 3 rows, this run's is 4 rows"),
            "{err}"
        );
        let err = flags(&path, 0.0).open(id(), 4).err().unwrap().to_string();
        assert!(err.contains("it has 3 units, this run 4"), "{err}");

        let mut bytes = std::fs::read(&path).unwrap();
        let last = bytes.len() - 7;
        bytes[last] ^= 0x10;
        std::fs::write(&path, &bytes).unwrap();
        let err = flags(&path, 0.0).open(id(), 3).err().unwrap().to_string();
        assert!(err.contains("damaged checkpoint"), "{err}");

        std::fs::remove_file(&path).unwrap();
        let fresh = flags(&path, 0.0).open(id(), 3).unwrap().unwrap();
        assert!(fresh.checkpoint().missing().eq(0..3), "a new checkpoint");
        fresh.remove().unwrap();
        assert!(!path.exists());
        assert!(
            !beside(&path, "lock").exists(),
            "the lock is removed with it"
        );
    }

    #[test]
    fn saves_are_spaced() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("run.ckpt");
        let mut file = flags(&path, 3600.0)
            .open(Identity::new("test"), 2)
            .unwrap()
            .unwrap();
        file.insert(0, vec![]).unwrap();
        assert!(!path.exists(), "not due yet");
        file.save().unwrap();
        assert!(path.exists());
    }
}
