//! `stickslip continue`: a branch of periodic orbits by pseudo-arclength continuation.

use crate::choice::choice;
use crate::flags::{count, help, int, num, number, reject_swept_flags};
use crate::model::{finite, ModelArgs};
use crate::output::{check_plot_path, Sink};
use anyhow::Result;
use std::io::Write;
use std::path::PathBuf;
use stickslip::continuation::{
    continue_orbit_of, settled_orbit, Branch, BranchEnd, BranchReport, ContinuationOptions, Side,
};
use stickslip::report::BranchTable;
use stickslip::{OptionKey, Parameter};

/// Follow a branch of periodic orbits as one parameter (w, β, ζ, μs, or vb on a belt) goes
/// from --from to --to, stable and unstable alike. It starts from the periodic orbit the motion settles on
/// at --from (from the initial state), refined by Newton's method, and continues the fixed
/// point of the p-fold strobe map in (y, y', parameter) by pseudo-arclength steps, so it goes
/// round folds. The exact solver finds the events of every orbit afresh, so the branch goes
/// on where a stop appears or disappears. Special points, each located to 1e-9 in arclength:
/// fold (a multiplier through +1, the branch turns back), branch point (through +1 without
/// turning), period doubling (through −1), grazing (the turning points or stops per period
/// change), each with the stability on either side.
///
/// With --model shockley (w, β or ζ; μs is no parameter of the diode law) the strobe map is
/// the stiff solver's, with its Jacobian and ∂P/∂λ from the variational equations on its own
/// steps, and its points are fixed points to the accuracy its map repeats (the solver's
/// rtol). A smooth law has no grazing: its stops are a threshold of the current,
/// not a switch of the equation, so no grazing is reported and a change of the stops does not
/// split the branch; folds, period doublings and Neimark–Sacker points are found as above.
///
/// Output CSV columns: <param>,y,v,amplitude,period,stops_per_period,turns,mu1_re,mu1_im,
/// mu2_re,mu2_im,stable,arclength
/// (y, v = the strobe point (fixed point of the p-fold map); amplitude = (max y − min y)/2;
/// turns = turning points per orbit period; mu = Floquet multipliers, the larger first;
/// stable = true when the larger has modulus below 1; arclength in (y, y', parameter)).
/// Special points go to standard error, and with --json a summary goes to standard output:
/// parameter, period, points, begin and end (why the branch ends there), special (kind,
/// value, y, v, width, before and after: value, stops, turns, multipliers, stable).
///
/// Examples: stickslip continue --preset paper --mu-s 1.5 --w 0.9 --over beta --from 1.45 \
///           --to 1.2 --out branch.csv --plot branch.png
///           stickslip continue --preset paper --model shockley --beta 3.61 --over w \
///           --from 1.2 --to 0.6 --out branch.csv
#[derive(Debug, clap::Args)]
#[command(verbatim_doc_comment)]
pub struct Args {
    #[command(flatten)]
    model: ModelArgs,
    /// The continued parameter (the others come from the model flags).
    #[arg(long, value_parser = choice::<Parameter>())]
    over: Parameter,
    #[arg(long, help = help(OptionKey::ContinuationFrom), value_parser = finite, allow_hyphen_values = true)]
    from: f64,
    #[arg(long, help = help(OptionKey::ContinuationTo), value_parser = finite, allow_hyphen_values = true)]
    to: f64,
    #[arg(long = OptionKey::MaxPoints.flag(), help = help(OptionKey::MaxPoints), default_value_t = int(OptionKey::MaxPoints) as _, allow_hyphen_values = true)]
    max_points: i64,
    #[arg(long = OptionKey::MaxStep.flag(), help = help(OptionKey::MaxStep), default_value_t = num(OptionKey::MaxStep), value_parser = finite, allow_hyphen_values = true)]
    max_step: f64,
    /// CSV file [default: standard output, unless --json].
    #[arg(long, short)]
    out: Option<PathBuf>,
    /// Plot of the branch: amplitude (stable solid, unstable dashed) with its special points,
    /// and the largest multiplier below (.png or .svg).
    #[arg(long, value_name = "FILE")]
    plot: Option<PathBuf>,
    /// Print a summary as JSON on standard output.
    #[arg(long)]
    json: bool,
}

/// Run `stickslip continue`.
pub fn run(args: Args) -> Result<()> {
    let parameter = args.over;
    stickslip::continuation::check_ends(args.from, args.to)?;
    let max_points = count(OptionKey::MaxPoints, args.max_points)?;
    let max_step = number(OptionKey::MaxStep, args.max_step)?;
    reject_swept_flags(&args.model, parameter, "--over")?;
    if let Some(p) = &args.plot {
        check_plot_path(p)?;
    }
    Sink::check(args.out.as_deref())?;
    let experiment = args
        .model
        .experiment()?
        .with_parameter(parameter, args.from)?;
    parameter.set(experiment.params()?, args.to)?;
    stickslip::continuation::check_parameter(&experiment, parameter)?;
    eprintln!(
        "continue: {experiment}; from the orbit settled on at {} = {}, towards {}",
        parameter.label(),
        args.from,
        args.to
    );
    let (params, orbit) = settled_orbit(&experiment)?;
    if orbit.is_rest() {
        let start = experiment.initial();
        anyhow::bail!(
            "from y0 = {}, v0 = {} the motion comes to rest at {} = {}: nothing to continue; \
             start from a moving state (--y0, --v0) or at another --from",
            start.y,
            start.v,
            parameter.label(),
            args.from
        );
    }
    eprintln!(
        "continue: start orbit of period {}, {} stops and {} events per orbit period, multipliers {}",
        orbit.period,
        orbit.stops.len(),
        orbit.events.len(),
        multipliers(&orbit.multipliers)
    );
    let options = ContinuationOptions {
        max_points,
        ..ContinuationOptions::default()
    }
    .with_max_step(max_step);
    let started = std::time::Instant::now();
    let bar = crate::output::progress(options.max_points as u64, "continue");
    let dynamics = experiment.dynamics()?;
    let result = continue_orbit_of(
        dynamics.as_ref(),
        &params,
        parameter,
        &orbit,
        args.to,
        &options,
        &|done: usize, _: usize| {
            bar.set_position(done as u64);
            !crate::output::interrupted()
        },
    );
    bar.finish_and_clear();
    crate::output::check_interrupt()?;
    let branch = result?;

    if args.out.is_some() || !args.json {
        let mut sink = Sink::open(args.out.as_deref())?;
        write_csv(&mut sink, &branch)?;
        sink.finish()?;
    }
    if let Some(path) = &args.plot {
        let title = format!(
            "branch of period-{} orbits at {}",
            branch.period,
            fixed(&branch)
        );
        crate::diagrams::branch_figure(&branch, &title).render(path)?;
    }
    if args.json {
        let text = serde_json::to_string_pretty(&BranchReport::from(&branch))?;
        writeln!(std::io::stdout().lock(), "{text}")?;
    }
    eprintln!(
        "continue: {} points in {:.2} s, {} from {} to {}; ends: {}",
        branch.points.len(),
        started.elapsed().as_secs_f64(),
        parameter.label(),
        branch.points.first().map_or(f64::NAN, |p| p.value),
        branch.points.last().map_or(f64::NAN, |p| p.value),
        end_text(&branch.end)
    );
    for s in &branch.special {
        eprintln!(
            "continue: {} at {} = {:.10} (±{:.1e}): {} → {}",
            s.kind.label(),
            parameter.label(),
            s.value,
            s.width,
            side_text(&s.before),
            side_text(&s.after)
        );
    }
    Ok(())
}

fn multipliers(m: &[stickslip::stability::Multiplier; 2]) -> String {
    let one = |x: &stickslip::stability::Multiplier| {
        if x.im == 0.0 {
            format!("{:.6}", x.re)
        } else {
            format!("{:.6}{:+.6}i", x.re, x.im)
        }
    };
    format!("{}, {}", one(&m[0]), one(&m[1]))
}

fn side_text(s: &Side) -> String {
    format!(
        "{} (μ = {}, {} turns, {} stops per orbit period)",
        if s.multipliers[0].modulus() < 1.0 {
            "stable"
        } else {
            "unstable"
        },
        multipliers(&s.multipliers),
        s.turns,
        s.stops
    )
}

/// Why a branch ends, in words (the library's text, naming the flag where one applies).
pub fn end_text(end: &BranchEnd) -> String {
    match end {
        BranchEnd::MaxPoints => "the most points (--max-points)".into(),
        other => other.to_string(),
    }
}

/// The fixed parameters of a branch, for titles: "ζ = 0, w = 0.9, μs = 1.5".
fn fixed(branch: &Branch) -> String {
    use stickslip::Parameter;
    [
        (Parameter::Zeta, "ζ"),
        (Parameter::W, "w"),
        (Parameter::Beta, "β"),
        (Parameter::MuS, "μs"),
    ]
    .iter()
    .filter(|(q, _)| *q != branch.parameter)
    .map(|(q, name)| {
        format!(
            "{name} = {}",
            crate::commands::bifurcation::short(q.get(&branch.params))
        )
    })
    .collect::<Vec<_>>()
    .join(", ")
}

/// The CSV of a branch, one row per point.
pub fn write_csv(out: &mut dyn Write, branch: &Branch) -> Result<()> {
    crate::output::write_table(out, &BranchTable { branch })
}
