//! `stickslip bifurcation`: strobe points and the largest Lyapunov exponent against a
//! parameter, state carried from value to value, with the branches of periodic orbits.

use crate::choice::choice;
use crate::flags::{count, help, int, range_from_flags, reject_swept_flags};
use crate::model::{finite, ModelArgs};
use crate::output::{check_plot_path, Sink};
use anyhow::Result;
use std::path::PathBuf;
use stickslip::attractor::{AttractorKind, RecordOptions};
use stickslip::bifurcation::{Bifurcation, BifurcationOptions, BifurcationStep};
use stickslip::continuation::ContinuationOptions;
use stickslip::options::check_product;
use stickslip::report::BifurcationReport;
use stickslip::scan::{Axis, SweepDirection, SweepLeg};
use stickslip::{OptionKey, Parameter};

/// Bifurcation diagram: at each value of one parameter (w, β, ζ, μs, or vb on a belt), after a
/// transient, the strobe points (y, y') once per drive period at drive phase φ, with the largest
/// Lyapunov exponent over them and what the motion settled on. Each value starts from the
/// state the one before ended in, as when turning a knob, so the two directions show
/// coexisting branches. A period-p orbit gives p points; chaos a cloud and λ1 > 0.
///
/// Output CSV columns: <param>,y,v,direction,lambda1,class,period
/// (one row per strobe point; <param> = w|beta|zeta|mu_s; direction = up|down; lambda1 = the
/// largest exponent per unit τ over the recorded periods; class = periodic|static|chaotic|
/// quasiperiodic|undecided (from the recorded periods only: the repetition of the points and
/// the sign of λ1 beyond 4 standard errors; undecided: no verdict within them); period in
/// drive periods, empty without one).
///
/// The plot (--plot) draws the points as dots, the branches of the periodic orbits found by
/// continuation on top (stable solid, unstable dashed, with folds, period doublings and
/// grazings marked) and the exponent below.
///
/// With --model shockley the points and the exponent are the stiff solver's (its tangent
/// dynamics: the variational equations on its own steps), and points repeat within its
/// rtol; μs is no parameter of the diode law.
///
/// Example: stickslip bifurcation --zeta 0 --mu-s 3 --beta 9 --over w --from 0.2 --to 0.55 \
///          --steps 500 --out bif.csv --plot bif.png
#[derive(Debug, clap::Args)]
#[command(verbatim_doc_comment)]
pub struct Args {
    #[command(flatten)]
    model: ModelArgs,
    /// The parameter stepped (the others come from the model flags).
    #[arg(long, value_parser = choice::<Parameter>())]
    over: Parameter,
    /// First value of the parameter (dimensionless).
    #[arg(long, value_parser = finite, allow_hyphen_values = true)]
    from: f64,
    /// Last value of the parameter (dimensionless, ≥ --from).
    #[arg(long, value_parser = finite, allow_hyphen_values = true)]
    to: f64,
    #[arg(long, help = help(OptionKey::BifurcationSteps), allow_hyphen_values = true)]
    steps: i64,
    /// Which way to step: up (from --from to --to), down (from --to to --from), or both (up,
    /// then down again from where the up leg ended).
    #[arg(long, value_parser = choice::<SweepDirection>(), default_value_t = SweepDirection::Both)]
    direction: SweepDirection,
    #[arg(long, help = help(OptionKey::Points), default_value_t = int(OptionKey::Points) as _, allow_hyphen_values = true)]
    points: i64,
    #[arg(long, help = help(OptionKey::BifurcationTransient), default_value_t = int(OptionKey::BifurcationTransient) as _, allow_hyphen_values = true)]
    transient: i64,
    #[arg(long = OptionKey::FirstTransient.flag(), help = help(OptionKey::FirstTransient), default_value_t = int(OptionKey::FirstTransient) as _, allow_hyphen_values = true)]
    first_transient: i64,
    #[arg(long = OptionKey::BifurcationMaxPeriod.flag(), help = help(OptionKey::BifurcationMaxPeriod), default_value_t = int(OptionKey::BifurcationMaxPeriod) as _, allow_hyphen_values = true)]
    max_period: i64,
    /// CSV file [default: standard output].
    #[arg(long, short)]
    out: Option<PathBuf>,
    /// Plot of the diagram (.png or .svg).
    #[arg(long, value_name = "FILE")]
    plot: Option<PathBuf>,
    /// Do not continue the periodic orbits for the plot (faster).
    #[arg(long)]
    no_branches: bool,
}

/// Run `stickslip bifurcation`.
pub fn run(args: Args) -> Result<()> {
    let parameter = args.over;
    let range = range_from_flags(
        parameter.label(),
        ("from", args.from),
        ("to", args.to),
        (OptionKey::BifurcationSteps, args.steps),
    )?;
    let points = count(OptionKey::Points, args.points)?;
    let transient = count(OptionKey::BifurcationTransient, args.transient)?;
    let first_transient = count(OptionKey::FirstTransient, args.first_transient)?;
    let max_period = count(OptionKey::BifurcationMaxPeriod, args.max_period)?;
    let legs = if args.direction == SweepDirection::Both {
        2
    } else {
        1
    };
    check_product(
        "rows",
        (OptionKey::BifurcationSteps, range.steps() * legs),
        (OptionKey::Points, points),
        2e7,
        "20000000",
    )?;
    reject_swept_flags(&args.model, parameter, "--over")?;
    if let Some(p) = &args.plot {
        check_plot_path(p)?;
    }
    Sink::check(args.out.as_deref())?;
    let experiment = args.model.experiment()?;
    let options = BifurcationOptions {
        record: RecordOptions {
            transient_periods: transient,
            points,
            max_period,
            ..RecordOptions::default()
        },
        first_transient_periods: first_transient,
    };
    let direction = args.direction;
    let diagram = Bifurcation::new(&experiment, Axis::range(parameter, &range)?)?
        .direction(direction)
        .options(options)?;
    eprintln!(
        "bifurcation: {experiment}; over {} from {} to {} in {} steps ({}), {} strobe points after {} periods at each ({} at the first)",
        parameter.label(),
        range.from(),
        range.to(),
        range.steps(),
        direction.label(),
        args.points,
        args.transient,
        args.first_transient
    );
    let started = std::time::Instant::now();
    let bar = crate::output::progress(diagram.len() as u64, "bifurcation");
    let result = diagram.run(&|_: usize, _: usize| {
        bar.inc(1);
        !crate::output::interrupted()
    });
    bar.finish_and_clear();
    crate::output::check_interrupt()?;
    let steps = result?;
    let seconds = started.elapsed().as_secs_f64();

    let mut sink = Sink::open(args.out.as_deref())?;
    crate::output::write_table(&mut sink, &BifurcationReport::new(parameter, &steps))?;
    sink.finish()?;
    eprintln!(
        "bifurcation: {} values in {seconds:.2} s: {}",
        steps.len(),
        summary(&steps)
    );
    if let Some(path) = &args.plot {
        let branches = if args.no_branches {
            Vec::new()
        } else {
            let started = std::time::Instant::now();
            let bar = crate::output::progress(0, "branches");
            let options = ContinuationOptions {
                max_points: 1000,
                ..ContinuationOptions::default()
            };
            let result = diagram.branches(&steps, &options, &|done: usize, _: usize| {
                bar.set_length(done as u64);
                bar.set_position(done as u64);
                !crate::output::interrupted()
            });
            bar.finish_and_clear();
            crate::output::check_interrupt()?;
            let branches = result?;
            let special: usize = branches.iter().map(|b| b.special.len()).sum();
            eprintln!(
                "bifurcation: {} branches of periodic orbits continued in {:.2} s, {special} special points{}",
                branches.len(),
                started.elapsed().as_secs_f64(),
                special_list(&branches)
            );
            branches
        };
        let title = format!("bifurcation diagram: {}", fixed(&steps, parameter));
        crate::diagrams::diagram_figure(&steps, &branches, parameter, &title).render(path)?;
    }
    Ok(())
}

/// The values of each class, per leg: "up: periodic 120 (period 1: 80, period 3: 40), chaotic 30".
fn summary(steps: &[BifurcationStep]) -> String {
    let mut legs = Vec::new();
    for leg in [SweepLeg::Up, SweepLeg::Down] {
        let of_leg: Vec<&BifurcationStep> = steps.iter().filter(|s| s.leg == leg).collect();
        if of_leg.is_empty() {
            continue;
        }
        let mut parts = Vec::new();
        for kind in AttractorKind::ALL {
            let n = of_leg.iter().filter(|s| s.record.kind == kind).count();
            if n == 0 {
                continue;
            }
            let mut part = format!("{} {n}", kind.label());
            if kind == AttractorKind::Periodic {
                let mut periods: Vec<usize> =
                    of_leg.iter().filter_map(|s| s.record.period).collect();
                periods.sort_unstable();
                periods.dedup();
                let list: Vec<String> = periods
                    .iter()
                    .take(8)
                    .map(|p| {
                        let c = of_leg
                            .iter()
                            .filter(|s| {
                                s.record.kind == AttractorKind::Periodic
                                    && s.record.period == Some(*p)
                            })
                            .count();
                        format!("period {p}: {c}")
                    })
                    .collect();
                part.push_str(&format!(" ({})", list.join(", ")));
            }
            parts.push(part);
        }
        legs.push(format!("{}: {}", leg.label(), parts.join(", ")));
    }
    legs.join("; ")
}

/// "; fold at 0.30382, grazing at 0.41329, …" (the first eight).
fn special_list(branches: &[stickslip::continuation::Branch]) -> String {
    let all: Vec<String> = branches
        .iter()
        .flat_map(|b| b.special.iter())
        .map(|s| format!("{} at {:.6}", s.kind.label(), s.value))
        .collect();
    if all.is_empty() {
        return String::new();
    }
    let more = if all.len() > 8 { ", …" } else { "" };
    format!(
        ": {}{more}",
        all.iter().take(8).cloned().collect::<Vec<_>>().join(", ")
    )
}

/// The fixed parameters, for titles: "ζ = 0, β = 9, μs = 3".
pub(crate) fn fixed(steps: &[BifurcationStep], parameter: stickslip::Parameter) -> String {
    use stickslip::Parameter;
    let Some(p) = steps.first().map(|s| s.params) else {
        return String::new();
    };
    Parameter::ALL
        .into_iter()
        .filter(|&q| q != parameter && q.is_set_in(&p))
        .map(|q| format!("{} = {}", crate::diagrams::symbol(q), short(q.get(&p))))
        .collect::<Vec<_>>()
        .join(", ")
}

/// A number with at most 6 decimals and no trailing zeros.
pub(crate) fn short(x: f64) -> String {
    let s = format!("{x:.6}");
    let s = s.trim_end_matches('0').trim_end_matches('.');
    if s.is_empty() || s == "-" {
        "0".into()
    } else {
        s.to_string()
    }
}
