//! `stickslip sweep`: w or β swept up and/or down with continuation (hysteresis).

use super::steady::SteadyFlags;
use crate::model::{finite, DiodeModel, Model, ModelArgs};
use crate::output::{check_plot_path, usage, Sink};
use crate::overlay::{abscissae, gain_curves, Curve};
use crate::plot::{Figure, Legend, Panel, Series, Style, PALETTE};
use anyhow::Result;
use std::io::Write;
use std::path::PathBuf;
use stickslip::steady::{
    sweep, ParameterRange, SweepDirection, SweepLeg, SweepParameter, SweepPoint,
};
use stickslip::Params;

/// The swept parameter, as typed.
#[derive(Debug, Clone, Copy, PartialEq, Eq, clap::ValueEnum)]
pub enum Over {
    /// The drive frequency w = Ω/ω0.
    W,
    /// The drive amplitude β.
    Beta,
}

/// Sweep direction, as typed.
#[derive(Debug, Clone, Copy, PartialEq, Eq, clap::ValueEnum)]
pub enum Direction {
    /// From --from to --to.
    Up,
    /// From --to to --from.
    Down,
    /// Up, then down again from where the up sweep ended.
    Both,
}

/// Sweep w or β with the other parameter fixed; each step starts from the final state of the
/// step before, as when turning a knob, so hysteresis and coexisting motions show up.
///
/// Output CSV columns: w,beta,direction,gain,A1,A3,class,stops_per_cycle
/// (direction = up|down; A1, A3 = amplitudes of the 1st and 3rd harmonics of y).
///
/// Example: stickslip sweep --preset paper --over w --beta 2.14 --from 0.2 --to 2 --steps 91 \
///          --direction both --out sweep.csv --plot sweep.png
#[derive(Debug, clap::Args)]
#[command(verbatim_doc_comment)]
pub struct Args {
    #[command(flatten)]
    model: ModelArgs,
    #[command(flatten)]
    steady: SteadyFlags,
    /// The swept parameter (the other one comes from --w or --beta).
    #[arg(long, value_enum)]
    over: Over,
    /// First value of the swept parameter (dimensionless).
    #[arg(long, value_parser = finite, allow_hyphen_values = true)]
    from: f64,
    /// Last value of the swept parameter (dimensionless, ≥ --from).
    #[arg(long, value_parser = finite, allow_hyphen_values = true)]
    to: f64,
    /// Number of values from --from to --to, both included (≥ 2, or 1 when they are equal).
    #[arg(long, allow_hyphen_values = true)]
    steps: i64,
    /// Which way to sweep.
    #[arg(long, value_enum, default_value_t = Direction::Both)]
    direction: Direction,
    /// CSV file [default: standard output].
    #[arg(long, short)]
    out: Option<PathBuf>,
    /// Plot of the gain against the swept parameter, up and down, with the theory's gain
    /// (the paper's A1/β and the exact sliding orbit's peak/β) where it exists (.png or .svg).
    #[arg(long, value_name = "FILE")]
    plot: Option<PathBuf>,
}

/// Validate a range given by flags `--{from_flag}`, `--{to_flag}`, `--{steps_flag}`.
pub fn range_from_flags(
    name: &'static str,
    (from_flag, from): (&str, f64),
    (to_flag, to): (&str, f64),
    (steps_flag, steps): (&str, i64),
) -> Result<ParameterRange> {
    if from > to {
        usage!("invalid range: --{from_flag} {from} is above --{to_flag} {to}");
    }
    if !(1..=100_000).contains(&steps) {
        usage!("invalid --{steps_flag} {steps}: must be from 1 to 100000");
    }
    if steps == 1 && from != to {
        usage!("invalid --{steps_flag} 1: a range from {from} to {to} needs at least 2 points");
    }
    Ok(ParameterRange::new(name, from, to, steps as usize)?)
}

/// Run `stickslip sweep`.
pub fn run(args: Args) -> Result<()> {
    let range = range_from_flags(
        args.over_label(),
        ("from", args.from),
        ("to", args.to),
        ("steps", args.steps),
    )?;
    let parameter = match args.over {
        Over::W => SweepParameter::W,
        Over::Beta => SweepParameter::Beta,
    };
    let mut model_args = args.model.clone();
    match parameter {
        SweepParameter::W => {
            if model_args.w.is_some() || model_args.freq.is_some() || model_args.omega.is_some() {
                usage!(
                    "--over w sweeps the frequency: give --from/--to, not --w, --freq or --omega"
                );
            }
            model_args.w = Some(range.from().max(f64::MIN_POSITIVE));
        }
        SweepParameter::Beta => {
            if model_args.beta.is_some() || model_args.amplitude.is_some() {
                usage!(
                    "--over beta sweeps the amplitude: give --from/--to, not --beta or --amplitude"
                );
            }
            model_args.beta = Some(range.from().max(0.0));
        }
    }
    if let Some(p) = &args.plot {
        check_plot_path(p)?;
    }
    Sink::check(args.out.as_deref())?;
    let model = model_args.build()?;
    let options = args.steady.options(&model)?.with_harmonics(3)?;
    // Every swept value must be valid for the model (w > 0, β ≥ 0).
    for value in [range.from(), range.to()] {
        parameter.set(model.params, value)?;
    }
    eprintln!(
        "sweep: {} over {} from {} to {} in {} steps, {}",
        model.summary,
        parameter.label(),
        range.from(),
        range.to(),
        range.steps(),
        match args.direction {
            Direction::Up => "up",
            Direction::Down => "down",
            Direction::Both => "up and down",
        }
    );
    let direction = match args.direction {
        Direction::Up => SweepDirection::Up,
        Direction::Down => SweepDirection::Down,
        Direction::Both => SweepDirection::Both,
    };
    let factory = crate::solvers::factory_for(&model)?;
    let legs = if direction == SweepDirection::Both {
        2
    } else {
        1
    };
    let bar = crate::output::progress((range.steps() * legs) as u64, "sweep");
    let result = sweep(
        &factory,
        model.params,
        model.initial,
        parameter,
        &range,
        direction,
        &options,
        &mut |_, _, _| {
            bar.inc(1);
            !crate::output::interrupted()
        },
    );
    bar.finish_and_clear();
    crate::output::check_interrupt()?;
    let points = result?;

    let mut sink = Sink::open(args.out.as_deref())?;
    writeln!(sink, "w,beta,direction,gain,A1,A3,class,stops_per_cycle")?;
    for p in &points {
        let s = &p.steady;
        writeln!(
            sink,
            "{},{},{},{},{},{},{},{}",
            p.params.w,
            p.params.beta,
            p.leg.label(),
            s.gain,
            s.harmonic(1).unwrap_or(f64::NAN),
            s.harmonic(3).unwrap_or(f64::NAN),
            s.class.label(),
            s.stops_per_period
        )?;
    }
    sink.finish()?;
    if let Some(path) = &args.plot {
        let theory = Theory::new(&model, parameter, &range);
        eprintln!(
            "sweep: theory on the plot: paper's gain at {} and exact sliding orbit at {} of {} values",
            theory.paper.present,
            theory.exact.present,
            theory.paper.points.len()
        );
        plot(&points, parameter, &theory, path)?;
    }
    let differ = branches_differ(&points, parameter);
    eprintln!(
        "sweep: {} steps{}",
        points.len(),
        if differ > 0 {
            format!(", up and down differ at {differ} values (coexisting motions)")
        } else {
            String::new()
        }
    );
    Ok(())
}

impl Args {
    fn over_label(&self) -> &'static str {
        match self.over {
            Over::W => "w",
            Over::Beta => "beta",
        }
    }
}

fn swept(p: &SweepPoint, parameter: SweepParameter) -> f64 {
    match parameter {
        SweepParameter::W => p.params.w,
        SweepParameter::Beta => p.params.beta,
    }
}

/// Values at which the up and the down leg found different motions (gain or class).
fn branches_differ(points: &[SweepPoint], parameter: SweepParameter) -> usize {
    let up: Vec<&SweepPoint> = points.iter().filter(|p| p.leg == SweepLeg::Up).collect();
    let down: Vec<&SweepPoint> = points.iter().filter(|p| p.leg == SweepLeg::Down).collect();
    up.iter()
        .filter(|u| {
            down.iter().any(|d| {
                swept(d, parameter) == swept(u, parameter)
                    && (d.steady.class != u.steady.class
                        || (d.steady.gain - u.steady.gain).abs() > 1e-6 * u.steady.gain.abs())
            })
        })
        .count()
}

/// The theory's gain curves over the swept range, at the sweep's fixed parameter.
struct Theory {
    paper: Curve,
    exact: Curve,
    /// Legend prefix: the theory is that of the piecewise-linear model.
    prefix: &'static str,
}

impl Theory {
    fn new(model: &Model, parameter: SweepParameter, range: &ParameterRange) -> Self {
        let xs = abscissae(range.from(), range.to(), range.steps());
        let (paper, exact) = gain_curves(&model.params, &xs, |p, x| Params {
            w: if parameter == SweepParameter::W {
                x
            } else {
                p.w
            },
            beta: if parameter == SweepParameter::Beta {
                x
            } else {
                p.beta
            },
            ..p
        });
        Self {
            paper,
            exact,
            prefix: match model.diode {
                DiodeModel::Pwl => "",
                DiodeModel::Shockley => "PWL theory: ",
            },
        }
    }
}

fn plot(
    points: &[SweepPoint],
    parameter: SweepParameter,
    theory: &Theory,
    path: &std::path::Path,
) -> Result<()> {
    let leg = |which: SweepLeg| -> Vec<(f64, f64)> {
        points
            .iter()
            .filter(|p| p.leg == which)
            .map(|p| (swept(p, parameter), p.steady.gain))
            .collect()
    };
    let stick = |which: SweepLeg| -> Vec<(f64, f64)> {
        points
            .iter()
            .filter(|p| p.leg == which && p.steady.stops > 0)
            .map(|p| (swept(p, parameter), p.steady.gain))
            .collect()
    };
    let first = points.first().map(|p| p.params);
    let title = match (parameter, first) {
        (SweepParameter::W, Some(p)) => format!("gain against w at β = {:.3}", p.beta),
        (SweepParameter::Beta, Some(p)) => format!("gain against β at w = {:.3}", p.w),
        _ => "gain".into(),
    };
    let mut series = Vec::new();
    for (which, color, style, label) in [
        (SweepLeg::Up, PALETTE[0], Style::Line(2), "sweep up"),
        (SweepLeg::Down, PALETTE[1], Style::Dashed(2), "sweep down"),
    ] {
        let data = leg(which);
        if !data.is_empty() {
            series.push(Series::new(label, data, color, style));
        }
    }
    series.push(Series::new(
        "with stops (up)",
        stick(SweepLeg::Up),
        PALETTE[0],
        Style::Squares(4),
    ));
    series.push(Series::new(
        "with stops (down)",
        stick(SweepLeg::Down),
        PALETTE[1],
        Style::Markers(2),
    ));
    // The simulated gain is the peak over β; on a sliding orbit that is the exact orbit's
    // peak/β (not its A1/β). The paper's gain is its A1/β, eq. (11).
    let prefix = theory.prefix;
    if theory.paper.present > 0 {
        series.push(Series::new(
            format!("{prefix}paper, eq. (11): A1/β"),
            theory.paper.points.clone(),
            PALETTE[2],
            Style::Dashed(2),
        ));
    }
    if theory.exact.present > 0 {
        series.push(Series::new(
            format!("{prefix}exact sliding orbit: peak/β"),
            theory.exact.points.clone(),
            PALETTE[6],
            Style::Line(1),
        ));
    }
    let panel = Panel {
        title,
        x_label: parameter.label().into(),
        y_label: "gain G = (max y − min y)/(2β)".into(),
        series,
        legend: Some(Legend::UpperRight),
        ..Default::default()
    };
    Figure::single(panel, (900, 560)).render(path)
}
