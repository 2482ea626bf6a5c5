//! `stickslip phase-diagram`: motion classes on a (w, β) grid, each point from rest.

use super::steady::SteadyFlags;
use super::sweep::range_from_flags;
use crate::model::{finite, DiodeModel, Model, ModelArgs};
use crate::output::{check_plot_path, usage, Sink};
use crate::overlay::{abscissae, boundary_curves};
use crate::plot::{Cell, Figure, Legend, Panel, Series, Style, PALETTE};
use anyhow::Result;
use plotters::style::RGBColor;
use std::io::Write;
use std::path::PathBuf;
use stickslip::steady::{phase_diagram, MotionClass, ParameterRange, PhaseDiagramPoint};

/// Classify the steady motion on a grid of drive frequencies w and amplitudes β, each point
/// started from the initial state (rest by default), in parallel: sliding, periodic-stick,
/// nonperiodic-stick or static (the paper's Figs. 6 and 7).
///
/// Output CSV columns: w,beta,class,period,stops_per_cycle,gain
/// (period empty when none ≤ --max-period was found).
///
/// Example: stickslip phase-diagram --preset paper --w-steps 200 --beta-steps 200 \
///          --out map.csv --plot map.png
#[derive(Debug, clap::Args)]
#[command(verbatim_doc_comment)]
pub struct Args {
    #[command(flatten)]
    model: ModelArgs,
    #[command(flatten)]
    steady: SteadyFlags,
    /// Lowest drive frequency w.
    #[arg(long = "w-min", default_value_t = 0.1, value_parser = finite, allow_hyphen_values = true)]
    w_min: f64,
    /// Highest drive frequency w.
    #[arg(long = "w-max", default_value_t = 2.5, value_parser = finite, allow_hyphen_values = true)]
    w_max: f64,
    /// Number of frequencies from --w-min to --w-max, both included.
    #[arg(long = "w-steps", default_value_t = 100, allow_hyphen_values = true)]
    w_steps: i64,
    /// Lowest drive amplitude β.
    #[arg(long = "beta-min", default_value_t = 0.5, value_parser = finite, allow_hyphen_values = true)]
    beta_min: f64,
    /// Highest drive amplitude β.
    #[arg(long = "beta-max", default_value_t = 4.0, value_parser = finite, allow_hyphen_values = true)]
    beta_max: f64,
    /// Number of amplitudes from --beta-min to --beta-max, both included.
    #[arg(long = "beta-steps", default_value_t = 100, allow_hyphen_values = true)]
    beta_steps: i64,
    /// CSV file [default: standard output].
    #[arg(long, short)]
    out: Option<PathBuf>,
    /// Map of the classes as coloured cells, with the paper's and the exact stick-slip
    /// boundary where they exist inside the β range (.png or .svg).
    #[arg(long, value_name = "FILE")]
    plot: Option<PathBuf>,
}

/// Colour of each class on the map.
fn color(class: MotionClass) -> RGBColor {
    match class {
        MotionClass::Sliding => RGBColor(235, 235, 235),
        MotionClass::PeriodicStick => PALETTE[0],
        MotionClass::NonperiodicStick => PALETTE[1],
        MotionClass::Static => PALETTE[2],
    }
}

/// Run `stickslip phase-diagram`.
pub fn run(args: Args) -> Result<()> {
    let w = range_from_flags(
        "w",
        ("w-min", args.w_min),
        ("w-max", args.w_max),
        ("w-steps", args.w_steps),
    )?;
    let beta = range_from_flags(
        "beta",
        ("beta-min", args.beta_min),
        ("beta-max", args.beta_max),
        ("beta-steps", args.beta_steps),
    )?;
    if w.from() <= 0.0 {
        usage!("invalid --w-min {}: must be > 0", w.from());
    }
    if beta.from() < 0.0 {
        usage!("invalid --beta-min {}: must be >= 0", beta.from());
    }
    if w.steps() * beta.steps() > 4_000_000 {
        usage!(
            "--w-steps × --beta-steps = {}: at most 4000000 points",
            w.steps() * beta.steps()
        );
    }
    let mut model_args = args.model.clone();
    if model_args.w.is_some()
        || model_args.beta.is_some()
        || model_args.freq.is_some()
        || model_args.omega.is_some()
        || model_args.amplitude.is_some()
    {
        usage!("phase-diagram sets w and β from the grid: use --w-min/--w-max and --beta-min/--beta-max, not --w, --beta, --freq, --omega or --amplitude");
    }
    model_args.w = Some(w.from());
    model_args.beta = Some(beta.from());
    if let Some(p) = &args.plot {
        check_plot_path(p)?;
    }
    Sink::check(args.out.as_deref())?;
    let model = model_args.build()?;
    let options = args.steady.options(&model)?;
    eprintln!(
        "phase-diagram: {}; grid {} × {} (w {}–{}, β {}–{}), cap {} periods",
        model.summary,
        w.steps(),
        beta.steps(),
        w.from(),
        w.to(),
        beta.from(),
        beta.to(),
        options.max_periods
    );
    let factory = crate::solvers::factory_for(&model)?;
    let total = w.steps() * beta.steps();
    let bar = crate::output::progress(total as u64, "phase diagram");
    let started = std::time::Instant::now();
    let result = phase_diagram(
        &factory,
        model.params,
        model.initial,
        &w,
        &beta,
        &options,
        &|| {
            bar.inc(1);
            !crate::output::interrupted()
        },
    );
    bar.finish_and_clear();
    crate::output::check_interrupt()?;
    let points = result?;
    let elapsed = started.elapsed().as_secs_f64();

    let mut sink = Sink::open(args.out.as_deref())?;
    writeln!(sink, "w,beta,class,period,stops_per_cycle,gain")?;
    for p in &points {
        writeln!(
            sink,
            "{},{},{},{},{},{}",
            p.w,
            p.beta,
            p.class.label(),
            p.period.map(|x| x.to_string()).unwrap_or_default(),
            p.stops_per_period,
            p.gain
        )?;
    }
    sink.finish()?;
    if let Some(path) = &args.plot {
        plot(&points, &w, &beta, &model, path)?;
    }
    let count = |c: MotionClass| points.iter().filter(|p| p.class == c).count();
    eprintln!(
        "phase-diagram: {} points in {:.2} s ({:.1} µs per point): {}",
        total,
        elapsed,
        elapsed * 1e6 / total as f64,
        MotionClass::ALL
            .iter()
            .map(|&c| format!("{} {}", c.label(), count(c)))
            .collect::<Vec<_>>()
            .join(", ")
    );
    Ok(())
}

fn plot(
    points: &[PhaseDiagramPoint],
    w: &ParameterRange,
    beta: &ParameterRange,
    model: &Model,
    path: &std::path::Path,
) -> Result<()> {
    let params = &model.params;
    // Cells centred on the grid points; a single row or column gets a unit-less width.
    let half = |r: &ParameterRange| {
        if r.steps() > 1 {
            0.5 * r.spacing()
        } else {
            0.05 * r.from().abs().max(1.0)
        }
    };
    let (hw, hb) = (half(w), half(beta));
    let cells = points
        .iter()
        .map(|p| Cell {
            x: (p.w - hw, p.w + hw),
            y: (p.beta - hb, p.beta + hb),
            color: color(p.class),
        })
        .collect();
    let cell_legend = MotionClass::ALL
        .iter()
        .filter(|&&c| points.iter().any(|p| p.class == c))
        .map(|&c| (c.label().to_string(), color(c)))
        .collect();
    // The boundaries of the piecewise-linear theory, where they exist inside the β range.
    let (beta_lo, beta_hi) = (beta.from() - hb, beta.to() + hb);
    // Across the cells' full width, but w > 0.
    let ws = abscissae((w.from() - hw).max(0.5 * w.from()), w.to() + hw, w.steps());
    let (paper, exact) = boundary_curves(params.zeta, params.mu_s, &ws, (beta_lo, beta_hi));
    eprintln!(
        "phase-diagram: theory on the plot: paper's boundary at {} and exact boundary at {} of {} frequencies inside the β range",
        paper.present,
        exact.present,
        ws.len()
    );
    let prefix = match model.diode {
        DiodeModel::Pwl => "",
        DiodeModel::Shockley => "PWL theory: ",
    };
    let mut series = Vec::new();
    if paper.present > 0 {
        series.push(Series::new(
            format!("{prefix}paper boundary, eq. (13)"),
            paper.points,
            PALETTE[3],
            Style::Dashed(3),
        ));
    }
    if exact.present > 0 {
        series.push(Series::new(
            format!("{prefix}exact boundary β_c"),
            exact.points,
            PALETTE[6],
            Style::Line(2),
        ));
    }
    let panel = Panel {
        series,
        title: format!(
            "motion classes from rest, ζ = {:.4}, μs = {}",
            params.zeta, params.mu_s
        ),
        x_label: "w = Ω/ω0".into(),
        y_label: "β = U/U_t".into(),
        cells,
        cell_legend,
        x_range: Some((w.from() - hw, w.to() + hw)),
        y_range: Some((beta.from() - hb, beta.to() + hb)),
        legend: Some(Legend::UpperRight),
    };
    Figure::single(panel, (900, 700)).render(path)
}
