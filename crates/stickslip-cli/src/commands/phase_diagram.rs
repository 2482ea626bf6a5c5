//! `stickslip phase-diagram`: motion classes on a grid of two keys ((w, β) by default), each
//! point from rest.

use crate::checkpoint::CheckpointFlags;
use crate::choice::choice;
use crate::diagrams::symbol;
use crate::flags::{count, help, int, num, range_from_flags, reject_swept_flags, SteadyFlags};
use crate::model::{finite, ModelArgs};
use crate::output::{check_plot_path, Sink};
use crate::plot::{class_color, Cell, ColorBar, Figure, Legend, Panel, Quantity, Series};
use anyhow::Result;
use std::io::Write;
use std::path::PathBuf;
use stickslip::checkpoint::{Checkpoint, Identity, UnitReader, UnitWriter};
use stickslip::experiment::Origin;
use stickslip::report::{AxisCells, MapRow};
use stickslip::scan::{Axis, Grid, GridPoint, MapColor as Color, ParameterRange};
use stickslip::stability::Estimate;
use stickslip::steady::MotionClass;
use stickslip::theory::curves::{abscissae, theory_curve, Theory, TheoryQuantity};
use stickslip::{DiodeModel, Experiment, OptionKey, Parameter};

/// Classify the steady motion on a grid of drive frequencies w and amplitudes β, each point
/// started from the initial state (rest by default), in parallel: sliding, periodic-stick
/// or static (the paper's Figs. 6 and 7), chaotic (a motion that does not repeat and whose
/// largest Lyapunov exponent is positive beyond 4 standard errors), or
/// undecided (no period found within the budget, and not chaotic: the paper's non-periodic
/// class lands here; see `stickslip steady --help`).
///
/// With --color lambda1 every point also gets its largest Lyapunov exponent λ1 per unit
/// τ = ω0·t: exactly, ln|μ1|/(pT) from the Floquet multiplier μ1 of its periodic orbit
/// (refined by Newton's method) where the motion repeats, and measured over
/// --lyapunov-periods where it does not; the plot maps λ1 (red: chaos, blue: contraction,
/// white: 0, e.g. rest). With --model shockley the multipliers and the tangent dynamics are
/// those of the stiff solver's computed solution (as `orbit` and `lyapunov` give them).
///
/// Any two keys instead of (w, β): --x KEY --x-from A --x-to B --x-steps N and the same with
/// --y (as `sweep --over`), e.g. the self-excited belt's (vb, μs) map without a drive: its
/// classes stick-slip-cycle, pure-slip-cycle and steady-sliding. The CSV's first two columns
/// are then the keys' names (vb,mu_s,class,...) and the plot's axes are named by them.
///
/// Output CSV columns: w,beta,class,period,stops_per_period,gain, and with --color lambda1
/// also lambda1,lambda1_error (λ1 and its standard error per unit τ; 0 error for an exact
/// Floquet exponent, -inf where both multipliers vanish). Period empty when none ≤
/// --max-period was found.
///
/// The CSV is written block of rows by block of rows while the rest computes, so memory stays
/// flat and a map may have up to 100000 × 100000 points; with --plot or --checkpoint the map
/// is kept in memory, at most 4000000 points (docs/limits.md).
///
/// Example: stickslip phase-diagram --preset paper --w-steps 200 --beta-steps 200 \
///          --out map.csv --plot map.png
///          stickslip phase-diagram --zeta 0 --mu-s 3 --w-min 0.2 --w-max 0.55 \
///          --beta-min 6 --beta-max 12 --color lambda1 --plot lambda1.png
///          stickslip phase-diagram --beta 0 --x vb --x-from 0.05 --x-to 2 --x-steps 100 \
///          --y mu-s --y-from 1 --y-to 3 --y-steps 100 --plot belt-map.png
#[derive(Debug, clap::Args)]
#[command(verbatim_doc_comment)]
pub struct Args {
    #[command(flatten)]
    model: ModelArgs,
    #[command(flatten)]
    steady: SteadyFlags,
    #[arg(long = OptionKey::MapWMin.flag(), help = help(OptionKey::MapWMin), default_value_t = num(OptionKey::MapWMin), value_parser = finite, allow_hyphen_values = true)]
    w_min: f64,
    #[arg(long = OptionKey::MapWMax.flag(), help = help(OptionKey::MapWMax), default_value_t = num(OptionKey::MapWMax), value_parser = finite, allow_hyphen_values = true)]
    w_max: f64,
    #[arg(long = OptionKey::MapWSteps.flag(), help = help(OptionKey::MapWSteps), default_value_t = int(OptionKey::MapWSteps) as _, allow_hyphen_values = true)]
    w_steps: i64,
    #[arg(long = OptionKey::MapBetaMin.flag(), help = help(OptionKey::MapBetaMin), default_value_t = num(OptionKey::MapBetaMin), value_parser = finite, allow_hyphen_values = true)]
    beta_min: f64,
    #[arg(long = OptionKey::MapBetaMax.flag(), help = help(OptionKey::MapBetaMax), default_value_t = num(OptionKey::MapBetaMax), value_parser = finite, allow_hyphen_values = true)]
    beta_max: f64,
    #[arg(long = OptionKey::MapBetaSteps.flag(), help = help(OptionKey::MapBetaSteps), default_value_t = int(OptionKey::MapBetaSteps) as _, allow_hyphen_values = true)]
    beta_steps: i64,
    /// The map's first key (its rows and the plot's x axis) instead of w: any parameter
    /// `sweep --over` takes; with --y.
    #[arg(long, value_parser = choice::<Parameter>(), requires_all = ["y", "x_from", "x_to"], conflicts_with_all = ["w_min", "w_max", "w_steps", "beta_min", "beta_max", "beta_steps"])]
    x: Option<Parameter>,
    /// First value of --x (dimensionless).
    #[arg(long, value_parser = finite, allow_hyphen_values = true, requires = "x")]
    x_from: Option<f64>,
    /// Last value of --x (dimensionless, ≥ --x-from).
    #[arg(long, value_parser = finite, allow_hyphen_values = true, requires = "x")]
    x_to: Option<f64>,
    #[arg(long = OptionKey::MapXSteps.flag(), help = help(OptionKey::MapXSteps), default_value_t = int(OptionKey::MapXSteps) as _, allow_hyphen_values = true)]
    x_steps: i64,
    /// The map's second key (its columns and the plot's y axis) instead of β; with --x.
    #[arg(long, value_parser = choice::<Parameter>(), requires_all = ["x", "y_from", "y_to"])]
    y: Option<Parameter>,
    /// First value of --y (dimensionless).
    #[arg(long, value_parser = finite, allow_hyphen_values = true, requires = "y")]
    y_from: Option<f64>,
    /// Last value of --y (dimensionless, ≥ --y-from).
    #[arg(long, value_parser = finite, allow_hyphen_values = true, requires = "y")]
    y_to: Option<f64>,
    #[arg(long = OptionKey::MapYSteps.flag(), help = help(OptionKey::MapYSteps), default_value_t = int(OptionKey::MapYSteps) as _, allow_hyphen_values = true)]
    y_steps: i64,
    /// CSV file [default: standard output].
    #[arg(long, short)]
    out: Option<PathBuf>,
    /// Map of the classes as coloured cells, with the paper's and the exact stick-slip
    /// boundary where they exist inside the β range (.png or .svg).
    #[arg(long, value_name = "FILE")]
    plot: Option<PathBuf>,
    /// What the cells show: the motion class, or the largest Lyapunov exponent (computed at
    /// every point, and written to the CSV as lambda1,lambda1_error; `lyapunov`, its name
    /// before, still works).
    #[arg(long, value_parser = choice::<Color>(), default_value_t = Color::Class)]
    color: Color,
    #[command(flatten)]
    checkpoint: CheckpointFlags,
}

/// Run `stickslip phase-diagram`.
pub fn run(args: Args) -> Result<()> {
    let ((first, w), (second, beta)) = axes(&args)?;
    run_over(args, (first, w), (second, beta))
}

/// The map's two keys and their ranges: --x and --y, else w and β.
fn axes(args: &Args) -> Result<((Parameter, ParameterRange), (Parameter, ParameterRange))> {
    if let (Some(x), Some(y)) = (args.x, args.y) {
        if x == y {
            crate::output::usage!(
                "invalid --y {}: must differ from --x {}",
                y.label(),
                x.label()
            );
        }
        let range = |p: Parameter, from: (&str, Option<f64>), to: (&str, Option<f64>), steps| {
            range_from_flags(
                p.label(),
                (from.0, from.1.unwrap_or(f64::NAN)),
                (to.0, to.1.unwrap_or(f64::NAN)),
                steps,
            )
        };
        return Ok((
            (
                x,
                range(
                    x,
                    ("x-from", args.x_from),
                    ("x-to", args.x_to),
                    (OptionKey::MapXSteps, args.x_steps),
                )?,
            ),
            (
                y,
                range(
                    y,
                    ("y-from", args.y_from),
                    ("y-to", args.y_to),
                    (OptionKey::MapYSteps, args.y_steps),
                )?,
            ),
        ));
    }
    // The library checks each end and count against its row, and the ends' order.
    let w = ParameterRange::between(
        (OptionKey::MapWMin, args.w_min),
        (OptionKey::MapWMax, args.w_max),
        (
            OptionKey::MapWSteps,
            count(OptionKey::MapWSteps, args.w_steps)?,
        ),
    )?;
    let beta = ParameterRange::between(
        (OptionKey::MapBetaMin, args.beta_min),
        (OptionKey::MapBetaMax, args.beta_max),
        (
            OptionKey::MapBetaSteps,
            count(OptionKey::MapBetaSteps, args.beta_steps)?,
        ),
    )?;
    Ok(((Parameter::W, w), (Parameter::Beta, beta)))
}

/// Run the map over `first` × `second`.
fn run_over(
    args: Args,
    (first, w): (Parameter, ParameterRange),
    (second, beta): (Parameter, ParameterRange),
) -> Result<()> {
    let keys = (first, second);
    // A map whose points are kept (for the plot, or in the checkpoint) is capped by its
    // memory; a streamed one only by its axes (docs/limits.md).
    if args.plot.is_some() || args.checkpoint.checkpoint.is_some() {
        stickslip::limits::check_kept_map(w.steps(), beta.steps())?;
    }
    if keys == (Parameter::W, Parameter::Beta) && args.x.is_none() {
        reject_swept_flags(&args.model, Parameter::W, "phase-diagram (--w-min/--w-max)")?;
        reject_swept_flags(
            &args.model,
            Parameter::Beta,
            "phase-diagram (--beta-min/--beta-max)",
        )?;
    } else {
        reject_swept_flags(&args.model, first, "phase-diagram (--x)")?;
        reject_swept_flags(&args.model, second, "phase-diagram (--y)")?;
    }
    if let Some(p) = &args.plot {
        check_plot_path(p)?;
    }
    Sink::check(args.out.as_deref())?;
    let lyapunov = args.color == Color::Lambda1;
    args.checkpoint.check()?;
    let mut checkpoint_file = None;
    let experiment = args.model.experiment()?;
    let options = args.steady.options(&experiment)?;
    let mut grid = Grid::new(
        &experiment,
        Axis::range(first, &w)?,
        Axis::range(second, &beta)?,
    )?
    .options(options)?;
    if lyapunov {
        grid = grid.lyapunov(options.lyapunov_for_map()?)?;
    }
    // A checkpoint of other parameters, or a damaged one, is refused before any work.
    let checkpoint = args.checkpoint.open(identity(&grid)?, w.steps())?;
    eprintln!(
        "phase-diagram: {experiment}; grid {} × {} ({} {}–{}, {} {}–{}), cap {} periods",
        w.steps(),
        beta.steps(),
        symbol(first),
        w.from(),
        w.to(),
        symbol(second),
        beta.from(),
        beta.to(),
        options.max_periods
    );
    let total = w.steps() * beta.steps();
    let bar = crate::output::progress(total as u64, "phase diagram");
    let started = std::time::Instant::now();
    let open = || -> Result<Sink> {
        let mut sink = Sink::open(args.out.as_deref())?;
        writeln!(
            sink,
            "{}",
            MapRow::columns_over(first, second, lyapunov).join(",")
        )?;
        Ok(sink)
    };
    let mut summary = Summary::new(args.plot.is_some());
    let (sink, computed) = match checkpoint {
        None => {
            // Opened before the work (a temporary file, committed once every row is
            // written; Ctrl-C removes it).
            let mut sink = open()?;
            // Rows are computed on a thread of their own and written here as they come, in
            // order: writing overlaps computing, and at most a few blocks of rows are held.
            let result = std::thread::scope(|scope| -> Result<()> {
                let (send, receive) = std::sync::mpsc::sync_channel::<Vec<GridPoint>>(2);
                let grid = &grid;
                let bar = &bar;
                let worker = scope.spawn(move || {
                    grid.run_rows(
                        &|_: usize, _: usize| {
                            bar.inc(1);
                            !crate::output::interrupted()
                        },
                        |_, points| {
                            // The writer stopped (it failed): stop too.
                            send.send(points)
                                .map_err(|_| stickslip::Error::Cancelled { done: 0, total })
                        },
                    )
                });
                let mut axes = AxisCells::default();
                let written = receive.iter().try_for_each(|points| {
                    write_points(&mut sink, &points, keys, lyapunov, &mut summary, &mut axes)
                });
                drop(receive);
                let computed = worker
                    .join()
                    .expect("the map's worker thread does not panic");
                written?;
                Ok(computed?)
            });
            bar.finish_and_clear();
            crate::output::check_interrupt()?;
            result?;
            (sink, total)
        }
        Some(mut file) => {
            let points = file.fill_rows(
                "phase-diagram",
                grid.shape().1,
                4 * 64,
                &bar,
                |rows, monitor| grid.run_block(rows, 0..grid.shape().1, monitor),
                |row| encode_row(row, grid.lyapunov_options().is_some()),
            );
            bar.finish_and_clear();
            // Whatever happened, the rows finished so far are saved for the rerun.
            file.save()?;
            crate::output::check_interrupt()?;
            let computed = points?;
            // Opened once the checkpoint is complete: a killed run leaves only the
            // checkpoint.
            let mut sink = open()?;
            let mut axes = AxisCells::default();
            for i in 0..grid.shape().0 {
                let row = row_points(&grid, file.checkpoint(), i)?;
                write_points(&mut sink, &row, keys, lyapunov, &mut summary, &mut axes)?;
            }
            checkpoint_file = Some(file);
            (sink, computed)
        }
    };
    let elapsed = started.elapsed().as_secs_f64();
    sink.finish()?;
    if let Some(path) = &args.plot {
        plot(
            &summary.kept,
            (keys, &w, &beta),
            &experiment,
            lyapunov,
            path,
        )?;
    }
    if let Some((p, l)) = summary.top {
        eprintln!(
            "phase-diagram: largest exponent λ1 = {:+.4e} ± {:.1e} per unit τ at ({}, {}) = ({}, {}), {}",
            l.per_tau,
            l.error_per_tau,
            symbol(first),
            symbol(second),
            first.get(&p.params),
            second.get(&p.params),
            p.class.label()
        );
    }
    if let Some(file) = checkpoint_file {
        file.remove()?;
    }
    let count = |c: MotionClass| {
        summary.counts[MotionClass::ALL
            .iter()
            .position(|&k| k == c)
            .expect("a class of ALL")]
    };
    eprintln!(
        "phase-diagram: {} points ({} computed) in {:.2} s ({:.1} µs per computed point): {}",
        total,
        computed,
        elapsed,
        elapsed * 1e6 / computed.max(1) as f64,
        MotionClass::ALL
            .iter()
            .map(|&c| format!("{} {}", c.label(), count(c)))
            .collect::<Vec<_>>()
            .join(", ")
    );
    Ok(())
}

/// What the run reports after the rows are written: the points per class, the largest
/// exponent, and (for the plot) every point.
struct Summary {
    counts: [usize; MotionClass::ALL.len()],
    top: Option<(GridPoint, Estimate)>,
    keep: bool,
    kept: Vec<GridPoint>,
}

impl Summary {
    fn new(keep: bool) -> Self {
        Self {
            counts: [0; MotionClass::ALL.len()],
            top: None,
            keep,
            kept: Vec::new(),
        }
    }

    fn add(&mut self, p: &GridPoint) {
        let class = MotionClass::ALL.iter().position(|&c| c == p.class);
        self.counts[class.expect("a class of ALL")] += 1;
        if let Some(l) = p.lyapunov {
            // The last of equal largest exponents, as a maximum over the map in order.
            if self
                .top
                .is_none_or(|(_, t)| l.per_tau.total_cmp(&t.per_tau).is_ge())
            {
                self.top = Some((*p, l));
            }
        }
        if self.keep {
            self.kept.push(*p);
        }
    }
}

/// Write rows of points as CSV lines (the text of the axes' values from `axes`) and add them
/// to the summary.
fn write_points(
    sink: &mut Sink,
    points: &[GridPoint],
    (first, second): (Parameter, Parameter),
    lyapunov: bool,
    summary: &mut Summary,
    axes: &mut AxisCells,
) -> Result<()> {
    let mut text = String::new();
    let paper = (first, second) == (Parameter::W, Parameter::Beta);
    for p in points {
        if paper {
            MapRow::from(p).write_row_with(lyapunov, axes, &mut text);
        } else {
            let at = (first.get(&p.params), second.get(&p.params));
            MapRow::from(p).write_row_over(at, lyapunov, &mut text);
        }
        summary.add(p);
    }
    sink.write_all(text.as_bytes())?;
    Ok(())
}

/// Everything that determines the map: the experiment (whatever file or flags described
/// it), both axes, the steady-state options, and with --color lambda1 the options of the
/// exponents (a map of classes and one of exponents never share a checkpoint).
fn identity(grid: &Grid) -> Result<Identity> {
    let experiment = grid.experiment().clone().with_origin(Origin::Parts);
    let identity = Identity::new("phase-diagram")
        .with("experiment", serde_json::to_string(&experiment)?)
        .with("rows", serde_json::to_string(grid.first())?)
        .with("columns", serde_json::to_string(grid.second())?)
        .with("options", serde_json::to_string(grid.steady_options())?);
    Ok(match grid.lyapunov_options() {
        Some(l) => identity.with("lyapunov", serde_json::to_string(l)?),
        None => identity,
    })
}

/// A row of points as a checkpoint unit: per point its class, period (0: none), stops per
/// period, gain, symmetry and periods to settle (the parameters follow from the grid), and in
/// a map of exponents whether the point has one (1) or not (0), then its four numbers.
fn encode_row(points: &[GridPoint], exponents: bool) -> Vec<u8> {
    let mut unit = UnitWriter::new();
    for p in points {
        let class = MotionClass::ALL
            .iter()
            .position(|&c| c == p.class)
            .expect("a class of ALL");
        unit.u8(class as u8)
            .u64(p.period.map_or(0, |p| p as u64))
            .f64(p.stops_per_period)
            .f64(p.gain)
            .u8(u8::from(p.symmetric))
            .u64(p.periods_to_settle as u64);
        if let Some(l) = p.lyapunov {
            unit.u8(1)
                .f64(l.per_tau)
                .f64(l.error_per_tau)
                .f64(l.per_period)
                .f64(l.error_per_period);
        } else if exponents {
            unit.u8(0);
        }
    }
    unit.finish()
}

/// The points of row `i` of the grid, from its unit in a complete checkpoint.
fn row_points(grid: &Grid, checkpoint: &Checkpoint, i: usize) -> Result<Vec<GridPoint>> {
    let columns = grid.shape().1;
    let exponents = grid.lyapunov_options().is_some();
    let mut points = Vec::with_capacity(columns);
    let damaged = || anyhow::anyhow!("checkpoint holds a malformed row");
    let mut r = UnitReader::new(checkpoint.unit(i).ok_or_else(damaged)?);
    for j in 0..columns {
        let class = *MotionClass::ALL
            .get(r.u8().ok_or_else(damaged)? as usize)
            .ok_or_else(damaged)?;
        let period = r.u64().ok_or_else(damaged)?;
        points.push(GridPoint {
            params: grid.params(i, j)?,
            class,
            period: (period > 0).then_some(period as usize),
            stops_per_period: r.f64().ok_or_else(damaged)?,
            gain: r.f64().ok_or_else(damaged)?,
            symmetric: r.u8().ok_or_else(damaged)? != 0,
            periods_to_settle: r.u64().ok_or_else(damaged)? as usize,
            lyapunov: if exponents && r.u8().ok_or_else(damaged)? != 0 {
                Some(Estimate {
                    per_tau: r.f64().ok_or_else(damaged)?,
                    error_per_tau: r.f64().ok_or_else(damaged)?,
                    per_period: r.f64().ok_or_else(damaged)?,
                    error_per_period: r.f64().ok_or_else(damaged)?,
                })
            } else {
                None
            },
        });
    }
    if !r.is_empty() {
        return Err(damaged());
    }
    Ok(points)
}

fn plot(
    points: &[GridPoint],
    ((first, second), w, beta): ((Parameter, Parameter), &ParameterRange, &ParameterRange),
    experiment: &Experiment,
    lyapunov: bool,
    path: &std::path::Path,
) -> Result<()> {
    // Cells centred on the grid points; a single row or column gets a unit-less width.
    let half = |r: &ParameterRange| {
        if r.steps() > 1 {
            0.5 * r.spacing()
        } else {
            0.05 * r.from().abs().max(1.0)
        }
    };
    let (hw, hb) = (half(w), half(beta));
    let color_bar = lyapunov.then(|| exponent_bar(points));
    let cells = points
        .iter()
        .map(|p| Cell {
            x: (first.get(&p.params) - hw, first.get(&p.params) + hw),
            y: (second.get(&p.params) - hb, second.get(&p.params) + hb),
            color: match &color_bar {
                Some(bar) => bar.color(p.lyapunov.map_or(f64::NAN, |l| l.per_tau)),
                None => class_color(p.class),
            },
        })
        .collect();
    let cell_legend = if lyapunov {
        Vec::new()
    } else {
        MotionClass::ALL
            .iter()
            .filter(|&&c| points.iter().any(|p| p.class == c))
            .map(|&c| (c.label().to_string(), class_color(c)))
            .collect()
    };
    // The boundaries of the piecewise-linear theory, where they exist inside the β range,
    // across the cells' full width (but w > 0).
    let (beta_lo, beta_hi) = (beta.from() - hb, beta.to() + hb);
    // The paper's boundaries are curves of the (w, β) plane: outside it the abscissae are
    // none, and so are the curves.
    let paper_plane = (first, second) == (Parameter::W, Parameter::Beta);
    let ws = if paper_plane {
        abscissae((w.from() - hw).max(0.5 * w.from()), w.to() + hw, w.steps())
    } else {
        Vec::new()
    };
    let base = experiment.params_with(&[(first, w.from()), (second, beta.from())])?;
    let boundary = |theory| {
        theory_curve(theory, TheoryQuantity::Boundary, &base, Parameter::W, &ws)
            .within(beta_lo, beta_hi)
    };
    let (paper, exact) = (boundary(Theory::Paper), boundary(Theory::Exact));
    if paper_plane {
        eprintln!(
            "phase-diagram: theory on the plot: paper's boundary at {} and exact boundary at {} of {} frequencies inside the β range",
            paper.present(),
            exact.present(),
            ws.len()
        );
    }
    let prefix = match experiment.diode_model() {
        DiodeModel::Pwl => "",
        DiodeModel::Shockley => "PWL theory: ",
    };
    let mut series = Vec::new();
    if paper.present() > 0 {
        series.push(Series::new(
            format!("{prefix}paper boundary, eq. (13)"),
            paper.points(),
            Quantity::PaperTheory.color(),
            Quantity::PaperTheory.style(),
        ));
    }
    if exact.present() > 0 {
        series.push(Series::new(
            format!("{prefix}exact boundary β_c"),
            exact.points(),
            Quantity::ExactTheory.color(),
            Quantity::ExactTheory.style(),
        ));
    }
    let what = if lyapunov {
        "largest Lyapunov exponent"
    } else {
        "motion classes"
    };
    let (title, x_label, y_label) = if paper_plane {
        (
            format!("{what} from rest, ζ = {:.4}, μs = {}", base.zeta, base.mu_s),
            "w = Ω/ω0".to_string(),
            "β = U/U_t".to_string(),
        )
    } else {
        let fixed: Vec<String> = [
            Parameter::Zeta,
            Parameter::W,
            Parameter::Beta,
            Parameter::MuS,
            Parameter::Vb,
        ]
        .into_iter()
        .filter(|&q| q != first && q != second && q.is_set_in(&base))
        // Without a drive its frequency means nothing.
        .filter(|&q| q != Parameter::W || base.beta != 0.0)
        .map(|q| format!("{} = {:.4}", symbol(q), q.get(&base)))
        .collect();
        (
            format!("{what} from rest, {}", fixed.join(", ")),
            axis_label(first),
            axis_label(second),
        )
    };
    let panel = Panel {
        series,
        title,
        x_label,
        y_label,
        cells,
        cell_legend,
        x_range: Some((w.from() - hw, w.to() + hw)),
        y_range: Some((beta.from() - hb, beta.to() + hb)),
        legend: Some(Legend::UpperRight),
        color_bar,
        ..Default::default()
    };
    let width = if lyapunov { 1040 } else { 900 };
    Figure::single(panel, (width, 700)).render(path)
}

/// The colour bar of a map of exponents (see [`ColorBar::for_values`]).
fn exponent_bar(points: &[GridPoint]) -> ColorBar {
    let values: Vec<f64> = points
        .iter()
        .filter_map(|p| p.lyapunov.map(|l| l.per_tau))
        .collect();
    ColorBar::for_values("λ1 per unit τ (ω0·t)", &values)
}

/// A key's symbol, with its name where they differ: `μs (mu_s)`, `vb`.
fn axis_label(key: Parameter) -> String {
    if symbol(key) == key.label() {
        key.label().to_string()
    } else {
        format!("{} ({})", symbol(key), key.label())
    }
}
