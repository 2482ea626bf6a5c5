//! `stickslip basins`: the attractor reached from each initial state of a grid.

use crate::checkpoint::CheckpointFlags;
use crate::choice::choice;
use crate::flags::{count, help, int, range_from_flags};
use crate::model::{finite, flag, ModelArgs};
use crate::output::{check_plot_path, usage, Sink};
use anyhow::Result;
use std::io::Write;
use std::path::PathBuf;
use stickslip::basins::{BasinMap, BasinMethod, BasinOptions, BasinReport, Basins, Cell};
use stickslip::checkpoint::{Checkpoint, Identity, UnitReader, UnitWriter};
use stickslip::experiment::{Experiment, Key, Origin};
use stickslip::report::BasinsTable;
use stickslip::scan::ParameterRange;
use stickslip::OptionKey;

/// Basins of attraction: which motion the oscillator settles on from each initial state
/// (y0, y0') of a grid, given at drive phase --phase. The attractors are found and numbered
/// in the order of the cells (rows of y0, then y0'): a periodic orbit by its period and its
/// fixed point (refined by Newton's method), rest by never moving again, chaos by a positive
/// largest Lyapunov exponent and its strobe set, quasi-periodic motion by an exponent within
/// its error of zero. Cells that settle on nothing within the caps are undecided. With
/// --model shockley every cell runs on the stiff solver, and strobe states repeat (and fixed
/// points match) within its rtol.
///
/// --method recurrence (the default) follows each initial state on a grid of the strobe
/// map's state space with --resolution cells across the map, until it lands on cells already
/// labelled with an attractor or its basin, or comes back to its own cells often enough to
/// declare a new attractor, which is then classified once (cells in order, one thread).
/// --method exhaustive runs every cell to its steady state and classifies it on its own, in
/// parallel (the reference; costly where the motion is chaotic).
///
/// Output CSV columns: y0,v0,attractor,class,period
/// (attractor = its number, empty when undecided; class = periodic|static|chaotic|
/// quasiperiodic|undecided; period in drive periods, empty without one).
/// --json prints a summary: the model, the grid, and "attractors", each with id, class,
/// period (null without one), fraction (of the grid), cells, state (a representative state
/// at the strobe: the fixed point of a periodic orbit), strobes (its strobe points, at most
/// 64), lambda1 (largest Lyapunov exponent per unit τ), multipliers ([re, im] pairs, periodic
/// only), rest_range ([min, max] of the rest positions, rest only); and "undecided".
///
/// Example: stickslip basins --zeta 0 --mu-s 3 --w 0.6 --beta 3.269 --y0-min -8 --y0-max 8 \
///          --v0-min -8 --v0-max 8 --steps 200 --plot basins.png --json
#[derive(Debug, clap::Args)]
#[command(verbatim_doc_comment)]
pub struct Args {
    #[command(flatten)]
    model: ModelArgs,
    /// Smallest initial position y0.
    #[arg(long, value_parser = finite, allow_hyphen_values = true)]
    y0_min: f64,
    /// Largest initial position y0.
    #[arg(long, value_parser = finite, allow_hyphen_values = true)]
    y0_max: f64,
    /// Smallest initial velocity y0'.
    #[arg(long, value_parser = finite, allow_hyphen_values = true)]
    v0_min: f64,
    /// Largest initial velocity y0'.
    #[arg(long, value_parser = finite, allow_hyphen_values = true)]
    v0_max: f64,
    #[arg(long, help = help(OptionKey::BasinSteps), default_value_t = int(OptionKey::BasinSteps) as _, allow_hyphen_values = true)]
    steps: i64,
    /// Drive phase φ (radians) at which the initial states are given (the same as --phi)
    /// [default: 0].
    #[arg(long, value_parser = finite, allow_hyphen_values = true)]
    phase: Option<f64>,
    #[arg(long = OptionKey::BasinMaxPeriods.flag(), help = help(OptionKey::BasinMaxPeriods), default_value_t = int(OptionKey::BasinMaxPeriods) as _, allow_hyphen_values = true)]
    max_periods: i64,
    #[arg(long = OptionKey::BasinMaxPeriod.flag(), help = help(OptionKey::BasinMaxPeriod), default_value_t = int(OptionKey::BasinMaxPeriod) as _, allow_hyphen_values = true)]
    max_period: i64,
    #[arg(long = OptionKey::BasinLyapunovPeriods.flag(), help = help(OptionKey::BasinLyapunovPeriods), default_value_t = int(OptionKey::BasinLyapunovPeriods) as _, allow_hyphen_values = true)]
    lyapunov_periods: i64,
    /// How each cell's attractor is found: recurrence (cells stop on a labelled cell of the
    /// state-space grid; attractors classified once) or exhaustive (every cell run to its
    /// steady state and classified).
    #[arg(long, value_parser = choice::<BasinMethod>(), default_value_t = BasinMethod::Recurrence)]
    method: BasinMethod,
    #[arg(long, help = help(OptionKey::Resolution), default_value_t = int(OptionKey::Resolution) as _, allow_hyphen_values = true)]
    resolution: i64,
    /// CSV file [default: standard output, unless --json].
    #[arg(long, short)]
    out: Option<PathBuf>,
    /// Map of the basins (.png or .svg).
    #[arg(long, value_name = "FILE")]
    plot: Option<PathBuf>,
    /// Print the summary as JSON on standard output.
    #[arg(long)]
    json: bool,
    #[command(flatten)]
    checkpoint: CheckpointFlags,
}

/// Run `stickslip basins`.
pub fn run(args: Args) -> Result<()> {
    let y0 = range_from_flags(
        "y0",
        ("y0-min", args.y0_min),
        ("y0-max", args.y0_max),
        (OptionKey::BasinSteps, args.steps),
    )?;
    let v0 = range_from_flags(
        "v0",
        ("v0-min", args.v0_min),
        ("v0-max", args.v0_max),
        (OptionKey::BasinSteps, args.steps),
    )?;
    let max_periods = count(OptionKey::BasinMaxPeriods, args.max_periods)?;
    let max_period = count(OptionKey::BasinMaxPeriod, args.max_period)?;
    let lyapunov_periods = count(OptionKey::BasinLyapunovPeriods, args.lyapunov_periods)?;
    let resolution = count(OptionKey::Resolution, args.resolution)?;
    for key in [Key::Y0, Key::V0, Key::Uc0, Key::I0] {
        if args.model.given(key) {
            usage!(
                "basins sets the initial state from its grid: drop {}",
                flag(key)
            );
        }
    }
    if args.phase.is_some() && args.model.given(Key::Phi) {
        usage!("give the drive phase once: --phase or --phi, not both");
    }
    if let Some(p) = &args.plot {
        check_plot_path(p)?;
    }
    Sink::check(args.out.as_deref())?;
    args.checkpoint.check()?;
    let mut experiment = args.model.experiment()?;
    if let Some(phase) = args.phase {
        experiment = experiment.with_phi(phase)?;
    }
    let options = BasinOptions {
        max_periods,
        max_period,
        method: args.method,
        resolution,
        ..BasinOptions::default()
    }
    .with_lyapunov_periods(lyapunov_periods);
    let basins = Basins::new(&experiment, &y0, &v0)?.options(options)?;
    // A checkpoint of other parameters, or a damaged one, is refused before any work.
    let checkpoint = args.checkpoint.open(
        identity(&experiment, &y0, &v0, basins.basin_options())?,
        y0.steps(),
    )?;
    eprintln!(
        "basins: {experiment}; grid {} × {} of initial states (y0 {}–{}, y0' {}–{}) at drive phase {}",
        y0.steps(),
        v0.steps(),
        y0.from(),
        y0.to(),
        v0.from(),
        v0.to(),
        experiment.phi()
    );
    let (rows, cols) = basins.shape();
    let total = rows * cols;
    let started = std::time::Instant::now();
    let bar = crate::output::progress(total as u64, "basins");
    let mut checkpoint_file = None;
    let (map, computed) = match checkpoint {
        None => {
            let result = basins.run(&|_: usize, _: usize| {
                bar.inc(1);
                !crate::output::interrupted()
            });
            bar.finish_and_clear();
            crate::output::check_interrupt()?;
            (result?, total)
        }
        Some(mut file) if basins.basin_options().method == BasinMethod::Recurrence => {
            let computed = fill_recurrence(&basins, &mut file, &bar);
            bar.finish_and_clear();
            file.save()?;
            crate::output::check_interrupt()?;
            let (cells, computed) = computed?;
            let map = basins.identify(&cells)?;
            checkpoint_file = Some(file);
            (map, computed)
        }
        Some(mut file) => {
            let computed = file.fill_rows(
                "basins",
                basins.shape().1,
                4 * 16,
                &bar,
                |rows, monitor| basins.run_rows(rows, monitor),
                encode_row,
            );
            bar.finish_and_clear();
            // Whatever happened, the rows finished so far are saved for the rerun.
            file.save()?;
            crate::output::check_interrupt()?;
            let computed = computed?;
            let map = basins.identify(&rows_to_cells(&basins, file.checkpoint())?)?;
            checkpoint_file = Some(file);
            (map, computed)
        }
    };
    let seconds = started.elapsed().as_secs_f64();

    if args.out.is_some() || !args.json {
        let mut sink = Sink::open(args.out.as_deref())?;
        write_csv(&mut sink, &map)?;
        sink.finish()?;
    }
    if let Some(path) = &args.plot {
        let title = format!(
            "basins of attraction at ζ = {}, w = {}, β = {}, μs = {}, φ = {}",
            short(map.params.zeta),
            short(map.params.w),
            short(map.params.beta),
            short(map.params.mu_s),
            short(map.params.phi)
        );
        crate::plot::Figure::single(crate::diagrams::basin_panel(&map, &title), (900, 650))
            .render(path)?;
    }
    if args.json {
        let text = serde_json::to_string_pretty(&BasinReport::from(&map))?;
        let mut out = std::io::stdout().lock();
        writeln!(out, "{text}")?;
    }
    if let Some(file) = checkpoint_file {
        file.remove()?;
    }
    eprintln!(
        "basins: {total} cells ({computed} computed) in {seconds:.2} s ({:.1} µs per computed cell): {}",
        seconds * 1e6 / computed.max(1) as f64,
        describe(&map)
    );
    Ok(())
}

/// Everything that determines the map: the experiment (whatever file or flags described it,
/// with the drive phase of the initial states), both axes, the options.
fn identity(
    experiment: &Experiment,
    y0: &ParameterRange,
    v0: &ParameterRange,
    options: &BasinOptions,
) -> Result<Identity> {
    let experiment = experiment.clone().with_origin(Origin::Parts);
    let axis = |r: &ParameterRange| format!("{:?} {:?} {}", r.from(), r.to(), r.steps());
    Ok(Identity::new("basins")
        .with("experiment", serde_json::to_string(&experiment)?)
        .with("y0", axis(y0))
        .with("v0", axis(v0))
        .with("options", serde_json::to_string(options)?))
}

/// A row of cells as a checkpoint unit: each cell as the library encodes it
/// ([`Cell::encode`]).
fn encode_row(cells: &[Cell]) -> Vec<u8> {
    let mut unit = UnitWriter::new();
    for c in cells {
        c.encode(&mut unit);
    }
    unit.finish()
}

/// The map by recurrence on a checkpoint: the saved rows (a leading run of rows, since rows
/// are computed in order) restore the labels they left; the others are computed in order and
/// saved with theirs. Returns every cell, row-major, and the number computed.
fn fill_recurrence(
    basins: &Basins,
    file: &mut crate::checkpoint::CheckpointFile,
    bar: &indicatif::ProgressBar,
) -> Result<(Vec<Cell>, usize)> {
    let (rows, columns) = basins.shape();
    let done = file.checkpoint().done();
    if done > 0 {
        eprintln!(
            "basins: resuming from {}: {} of {} rows reused",
            file.path().display(),
            done,
            rows
        );
        bar.inc((done * columns) as u64);
    }
    let damaged = || anyhow::anyhow!("checkpoint holds a malformed row");
    let mut recurrence = basins.recurrence();
    let mut cells = Vec::with_capacity(rows * columns);
    let mut computed = 0;
    for i in 0..rows {
        match file.checkpoint().unit(i) {
            Some(unit) if computed == 0 => {
                let mut r = UnitReader::new(unit);
                cells.extend(decode_row(&mut r, columns)?);
                let n = r.u64().ok_or_else(damaged)?;
                if n > 1 << 40 {
                    return Err(damaged());
                }
                let memory = (0..n)
                    .map(|_| r.u8().ok_or_else(damaged))
                    .collect::<Result<Vec<u8>>>()?;
                if !r.is_empty() {
                    return Err(damaged());
                }
                recurrence.replay(&memory)?;
            }
            // A saved row after one computed anew: rows are saved in order, so never.
            Some(_) => return Err(damaged()),
            None => {
                let row = recurrence.run_row(i * columns, &|_: usize, _: usize| {
                    bar.inc(1);
                    !crate::output::interrupted()
                })?;
                let mut unit = encode_row(&row.cells);
                let mut tail = UnitWriter::new();
                tail.u64(row.memory.len() as u64);
                for &b in &row.memory {
                    tail.u8(b);
                }
                unit.extend(tail.finish());
                file.insert(i, unit)?;
                cells.extend(row.cells);
                computed += columns;
            }
        }
    }
    Ok((cells, computed))
}

/// The cells of one saved row ([`Cell::decode`]).
fn decode_row(r: &mut UnitReader, columns: usize) -> Result<Vec<Cell>> {
    (0..columns)
        .map(|_| Cell::decode(r).ok_or_else(|| anyhow::anyhow!("checkpoint holds a malformed row")))
        .collect()
}

/// Every cell of the grid, row-major, from the rows of a complete checkpoint.
fn rows_to_cells(basins: &Basins, checkpoint: &Checkpoint) -> Result<Vec<Cell>> {
    let (rows, columns) = basins.shape();
    let mut cells = Vec::with_capacity(rows * columns);
    let damaged = || anyhow::anyhow!("checkpoint holds a malformed row");
    for i in 0..rows {
        let mut r = UnitReader::new(checkpoint.unit(i).ok_or_else(damaged)?);
        cells.extend(decode_row(&mut r, columns)?);
        if !r.is_empty() {
            return Err(damaged());
        }
    }
    Ok(cells)
}

fn short(x: f64) -> String {
    crate::commands::bifurcation::short(x)
}

/// The CSV of the map, one row per cell.
pub fn write_csv(out: &mut dyn Write, map: &BasinMap) -> Result<()> {
    crate::output::write_table(out, &BasinsTable { map })
}

/// "2 attractors: #0 period 1 (58.3 %), #1 period 1 (41.7 %); 0 undecided".
pub fn describe(map: &BasinMap) -> String {
    let list: Vec<String> = map
        .attractors
        .iter()
        .map(crate::diagrams::attractor_label)
        .collect();
    format!(
        "{} attractor{}: {}; {} undecided",
        map.attractors.len(),
        if map.attractors.len() == 1 { "" } else { "s" },
        list.join(", "),
        map.undecided
    )
}
