//! `stickslip reproduce`: every figure and table of the paper from the paper's circuit, as PNG
//! and SVG with the data behind each as CSV, an `index.html` and a `summary.json`; then the
//! chapter "Beyond the paper".

mod belt;
mod beyond;
mod figures;
mod report;

/// The columns of the report's own CSV files, each written once beside its figure (the files
/// that hold a library result take their columns from the library's table).
pub mod columns {
    pub use super::belt::{APPROXIMATION_COLUMNS, BELT_SWEEP_COLUMNS, CLOSED_FORM_COLUMNS};
    pub use super::beyond::SPECIAL_COLUMNS;
    pub use super::figures::{
        ACCURACY_COLUMNS, DIODE_COLUMNS, FIG5_LEADING, FRICTION_COLUMNS, SPECTRA_COLUMNS,
        TABLE1_COLUMNS, XY_COLUMNS,
    };
}

use crate::output::{interrupted, progress};
use anyhow::{anyhow, bail, Result};
use report::Report;
use std::path::PathBuf;
use std::sync::Mutex;
use std::thread::JoinHandle;
use stickslip::experiment::Experiment;
use stickslip::{Circuit, Diode, PwlDiode, Scales};

/// Regenerate every figure and table of the paper, with an HTML report, and the chapter
/// "Beyond the paper" (chaos with static friction above kinetic, Lyapunov exponents).
///
/// Writes DIR/index.html (opens from disk), DIR/summary.json (key numbers), and for each
/// figure DIR/figN.png, DIR/figN.svg and the CSV data behind it.
///
/// Example: stickslip reproduce --out stickslip-report
#[derive(Debug, clap::Args)]
#[command(verbatim_doc_comment)]
pub struct Args {
    /// Output directory (created if missing; files of the report are replaced).
    #[arg(long, short, default_value = "stickslip-report")]
    out: PathBuf,
    /// Coarser grids and sweeps (for a quick look; the numbers in summary.json keep their
    /// meaning but maps are less detailed).
    #[arg(long)]
    quick: bool,
}

/// Settings shared by the figures.
pub struct Context {
    /// The paper's experiment (PWL diodes), without a drive: each figure sets its own.
    pub paper: Experiment,
    /// The paper's circuit.
    pub circuit: Circuit,
    /// Its PWL diode pair.
    pub diode: PwlDiode,
    /// Its scales (ω0, α, U_t, ...).
    pub scales: Scales,
    /// Whether to use coarse grids.
    pub quick: bool,
    /// The paper's map with the largest Lyapunov exponent of every point, computed once for
    /// fig. 7 (a) and the chapter "Beyond the paper" ([`beyond::paper_exponent_map`]).
    pub paper_exponents: std::sync::OnceLock<Vec<stickslip::scan::GridPoint>>,
    /// The Shockley map of fig. 7 (b), computed alongside the other figures ([`Later`]).
    pub shockley_map: Later<figures::ShockleyMap>,
    /// The chaos map of the chapter "Beyond the paper", computed alongside the other figures
    /// ([`Later`]).
    pub chaos_map: Later<beyond::ChaosMap>,
    /// The bifurcation diagram of the chapter "Beyond the paper" and its branches, computed
    /// alongside the other figures ([`Later`]).
    pub bifurcation: Later<beyond::BifurcationDiagram>,
    /// The basin map of the chapter "Beyond the paper", computed alongside the other figures
    /// ([`Later`]).
    pub basins: Later<beyond::BasinMap>,
}

pub(crate) type Job = (&'static str, fn(&mut Report, &Context) -> Result<()>);

/// A result computed on a thread of its own from the start of `reproduce`, for the figure
/// that shows it to take when its turn comes. The report's largest pieces of work that need
/// nothing from the other figures (fig. 7 (b)'s map, the chaos map, the bifurcation diagram
/// with its branches, the basin map) are computed alongside them: their work goes to the
/// pool's threads whenever the others leave one idle (a figure drawn, a branch followed, a
/// basin map run on one thread). Their results are the same for any number of threads, so
/// the report is the same, byte for byte.
pub struct Later<T>(Mutex<Option<JoinHandle<Result<T>>>>);

impl<T: Send + 'static> Later<T> {
    /// Start computing.
    pub fn start(compute: impl FnOnce() -> Result<T> + Send + 'static) -> Self {
        Self(Mutex::new(Some(std::thread::spawn(compute))))
    }

    /// The result, once computed (an error if taken already or if its thread failed).
    pub fn take(&self) -> Result<T> {
        let handle = self
            .0
            .lock()
            .map_err(|_| anyhow!("a background computation's lock was poisoned"))?
            .take()
            .ok_or_else(|| anyhow!("a background computation was taken twice"))?;
        handle
            .join()
            .map_err(|_| anyhow!("a background computation panicked"))?
    }
}

/// Run `stickslip reproduce`.
pub fn run(args: Args) -> Result<()> {
    let mut report = Report::create(&args.out)?;
    let circuit = Circuit::paper();
    let Diode::Pwl(diode) = circuit.diode else {
        unreachable!("the paper's circuit has PWL diodes")
    };
    let paper = Experiment::paper();
    let ctx = Context {
        shockley_map: figures::ShockleyMap::start(paper.clone(), args.quick),
        paper,
        circuit,
        diode,
        scales: circuit.scales(),
        quick: args.quick,
        paper_exponents: std::sync::OnceLock::new(),
        chaos_map: beyond::ChaosMap::start(args.quick),
        bifurcation: beyond::BifurcationDiagram::start(args.quick),
        basins: beyond::BasinMap::start(args.quick),
    };
    let mut jobs: Vec<Job> = vec![
        ("Table 1", figures::table1),
        ("Fig. 1", figures::fig1),
        ("Fig. 3", figures::fig3),
        ("Fig. 4", figures::fig4),
        ("Fig. 5", figures::fig5),
        ("Fig. 6", figures::fig6),
        ("Fig. 7", figures::fig7),
        ("accuracy", figures::accuracy),
    ];
    // The chapter "Beyond the paper": its heading, then its figures.
    jobs.extend_from_slice(beyond::JOBS);
    // The chapter "Friction-induced vibration": the block on a moving belt.
    jobs.extend_from_slice(belt::JOBS);
    eprintln!(
        "reproduce: the paper's circuit (preset paper): L = 11.5 mH, C = 0.02 µF, R = 68 Ω, \
         U_t = 0.7 V, R_D = 3.0 Ω; writing {}",
        args.out.display()
    );
    let started = std::time::Instant::now();
    let bar = progress(jobs.len() as u64, "reproduce");
    for (name, job) in &jobs {
        bar.set_message(name.to_string());
        let done = job(&mut report, &ctx);
        if interrupted() {
            // Whatever the job's own error says (a grid counts the points it finished, and
            // the grids computed alongside may have barely started), the reader wants this.
            bar.finish_and_clear();
            bail!(
                "interrupted during {name}; the report was not written ({} is as it was)",
                args.out.display()
            );
        }
        done?;
        bar.inc(1);
    }
    bar.finish_and_clear();
    // (The time taken goes to standard error only: the report is the same, byte for byte,
    // on every run and with any number of threads.)
    let dir = report.finish()?;
    eprintln!(
        "reproduce: done in {:.1} s; open {}",
        started.elapsed().as_secs_f64(),
        dir.join("index.html").display()
    );
    Ok(())
}
