//! `stickslip curve`: a curve of special points (fold, period doubling, Neimark–Sacker,
//! grazing) followed in two parameters.

use crate::choice::choice;
use crate::diagrams::{parameter_label, symbol};
use crate::flags::{count, help, int, num, number};
use crate::model::{finite, ModelArgs};
use crate::output::{check_plot_path, usage, Sink};
use crate::plot::{Figure, Legend, Panel, Series, Style, PALETTE};
use anyhow::Result;
use plotters::style::RGBColor;
use std::io::Write;
use std::path::PathBuf;
use stickslip::continuation::{
    curve, ContinuationOptions, Curve, CurveEnd, CurveReport, CurveSpec, Follow,
};
use stickslip::report::CurveTable;
use stickslip::stability::Stability;
use stickslip::{OptionKey, Parameter};

/// Follow a special point of a periodic orbit in two parameters: the curve in (--over,
/// --vary) along which the orbit has a fold (a multiplier at +1), a period doubling (at −1),
/// a Neimark–Sacker point (a complex pair on the unit circle) or a grazing (a stop appears or
/// disappears). The start: the orbit the motion settles on at the model's point is continued
/// in --vary towards --vary-to until its first special point of the followed kind; that point
/// is then followed by pseudo-arclength steps on its extended system (the orbit together with
/// its defining condition, exact derivatives of the strobe map) over --over from the model's
/// value towards --to, and towards --from too when the model's value lies between them.
/// Along the curve: where the other multiplier's stability changes, the codimension-two
/// points where it meets another curve (a cusp of folds, a fold or period doubling meeting a
/// grazing, 1:1 and 1:2 resonances, fold-flip), each located, and why it ends. PWL diodes
/// with any friction law: Coulomb's (the exact model) has no Neimark–Sacker point (det M < 1
/// on every orbit: --follow neimark-sacker says why in one line, exit status 2); the
/// Stribeck and cubic laws on a belt (the stiff solver's strobe map and sensitivities) have
/// fold, period-doubling and Neimark–Sacker curves, over and in vb and the law's own
/// parameters too (--follow grazing says in one line that it needs Coulomb's law).
///
/// Output CSV columns: <over>,<vary>,y,v,period,stops_per_period,turns,mu1_re,mu1_im,mu2_re,
/// mu2_im,largest_multiplier,stability,arclength,special
/// (y, v = the strobe point of the orbit; turns = turning points per orbit period; mu = Floquet
/// multipliers, the larger first; stability = the orbit's apart from the followed multiplier;
/// special = the codimension-two points between this row and the next, and `start` on the
/// start point's row). With --json a summary goes to standard output: follow, border, over,
/// vary, period, points, start, codim2 (kind, over, vary, y, v, width, before, after),
/// stability_changes, begin and end (why the curve ends each way). When the branch has no
/// special point of the kind between the model's point and --vary-to, one line says so and
/// the exit status is 2.
///
/// Examples: stickslip curve --preset paper --w 1.2 --beta 3 --follow grazing --vary beta \
///           --vary-to 0.5 --over w --from 0.6 --to 2 --out grazing.csv --plot grazing.png
///           stickslip curve --preset paper --mu-s 1.5 --w 0.9 --beta 1.45 --y0 0.25 --v0 2.1 \
///           --follow fold --vary beta --vary-to 1.2 --over w --from 0.8 --to 1 --json
#[derive(Debug, clap::Args)]
#[command(verbatim_doc_comment)]
pub struct Args {
    #[command(flatten)]
    model: ModelArgs,
    /// The special point followed.
    #[arg(long, value_parser = choice::<Follow>())]
    follow: Follow,
    #[arg(long = OptionKey::TwoParameterVary.flag(), help = help(OptionKey::TwoParameterVary), value_parser = choice::<Parameter>())]
    vary: Parameter,
    #[arg(long = OptionKey::TwoParameterVaryTo.flag(), help = help(OptionKey::TwoParameterVaryTo), value_parser = finite, allow_hyphen_values = true)]
    vary_to: f64,
    #[arg(long = OptionKey::TwoParameterOver.flag(), help = help(OptionKey::TwoParameterOver), value_parser = choice::<Parameter>())]
    over: Parameter,
    #[arg(long, help = help(OptionKey::TwoParameterFrom), value_parser = finite, allow_hyphen_values = true)]
    from: f64,
    #[arg(long, help = help(OptionKey::TwoParameterTo), value_parser = finite, allow_hyphen_values = true)]
    to: f64,
    #[arg(long = OptionKey::TwoParameterMaxPoints.flag(), help = help(OptionKey::TwoParameterMaxPoints), default_value_t = int(OptionKey::TwoParameterMaxPoints) as _, allow_hyphen_values = true)]
    max_points: i64,
    #[arg(long = OptionKey::TwoParameterMaxStep.flag(), help = help(OptionKey::TwoParameterMaxStep), default_value_t = num(OptionKey::TwoParameterMaxStep), value_parser = finite, allow_hyphen_values = true)]
    max_step: f64,
    /// CSV file [default: standard output, unless --json].
    #[arg(long, short)]
    out: Option<PathBuf>,
    /// Plot of the curve in the (--over, --vary) plane, the orbit's stability apart from the
    /// followed multiplier (stable solid, unstable dashed), the start and the
    /// codimension-two points marked (.png or .svg).
    #[arg(long, value_name = "FILE")]
    plot: Option<PathBuf>,
    /// Print a summary as JSON on standard output.
    #[arg(long)]
    json: bool,
}

/// Run `stickslip curve`.
pub fn run(args: Args) -> Result<()> {
    let spec = CurveSpec {
        follow: args.follow,
        vary: args.vary,
        vary_to: args.vary_to,
        over: args.over,
        from: args.from,
        to: args.to,
    };
    stickslip::continuation::check_spec(&spec)?;
    let max_points = count(OptionKey::TwoParameterMaxPoints, args.max_points)?;
    let max_step = number(OptionKey::TwoParameterMaxStep, args.max_step)?;
    if let Some(p) = &args.plot {
        check_plot_path(p)?;
    }
    Sink::check(args.out.as_deref())?;
    let experiment = args.model.experiment()?;
    let options = ContinuationOptions {
        max_points,
        ..ContinuationOptions::default()
    }
    .with_max_step(max_step);
    let started = std::time::Instant::now();
    let bar = crate::output::progress(options.max_points as u64, "curve");
    let result = curve(&experiment, &spec, &options, &|done: usize, _: usize| {
        bar.set_position(done as u64);
        !crate::output::interrupted()
    });
    bar.finish_and_clear();
    crate::output::check_interrupt()?;
    let c = match result? {
        Ok(c) => c,
        Err(no) => usage!("{no}"),
    };

    if args.out.is_some() || !args.json {
        let mut sink = Sink::open(args.out.as_deref())?;
        crate::output::write_table(&mut sink, &CurveTable { curve: &c })?;
        sink.finish()?;
    }
    if let Some(path) = &args.plot {
        figure(&c).render(path)?;
    }
    if args.json {
        let text = serde_json::to_string_pretty(&CurveReport::from(&c))?;
        writeln!(std::io::stdout().lock(), "{text}")?;
    }
    // What was done, once the start is found (when none is, the one line says why).
    eprintln!(
        "curve: {experiment}; the {} of the orbit settled on, found at {} = {}, {} = {}",
        c.follow.words(),
        c.over.label(),
        c.points[c.start].over,
        c.vary.label(),
        c.points[c.start].vary
    );
    eprintln!(
        "curve: {} points in {:.2} s, {} from {} to {}; begins at {}; ends at {}",
        c.points.len(),
        started.elapsed().as_secs_f64(),
        c.over.label(),
        c.points.first().map_or(f64::NAN, |p| p.over),
        c.points.last().map_or(f64::NAN, |p| p.over),
        end_text(&c.begin),
        end_text(&c.end)
    );
    for x in &c.codim2 {
        eprintln!(
            "curve: {} at {} = {:.10}, {} = {:.10} (±{:.1e})",
            x.kind,
            c.over.label(),
            x.over,
            c.vary.label(),
            x.vary,
            x.width
        );
    }
    Ok(())
}

/// Why a curve ends, in words (the library's text, naming the flag where one applies).
fn end_text(end: &CurveEnd) -> String {
    match end {
        CurveEnd::MaxPoints => "the most points (--max-points)".into(),
        other => other.to_string(),
    }
}

/// The curve in the (Q, P) plane: stable stretches solid, others dashed; the start and the
/// codimension-two points marked.
fn figure(c: &Curve) -> Figure {
    let stable = |s: Stability| s == Stability::Stable;
    let mut solid = Vec::new();
    let mut dashed = Vec::new();
    for pair in c.points.windows(2) {
        let (a, b) = (&pair[0], &pair[1]);
        let into = if stable(a.stability) && stable(b.stability) {
            &mut solid
        } else {
            &mut dashed
        };
        into.push((a.over, a.vary));
        into.push((b.over, b.vary));
        into.push((f64::NAN, f64::NAN));
    }
    let mut series = vec![
        Series::new(
            format!("{} (stable apart from it)", c.follow.words()),
            solid,
            PALETTE[0],
            Style::Line(2),
        ),
        Series::new("unstable or neutral", dashed, PALETTE[0], Style::Dashed(2)),
    ];
    let start = &c.points[c.start];
    series.push(Series::new(
        "start",
        vec![(start.over, start.vary)],
        RGBColor(0, 0, 0),
        Style::Squares(5),
    ));
    for (k, x) in c.codim2.iter().enumerate() {
        series.push(Series::new(
            x.kind.label(),
            vec![(x.over, x.vary)],
            PALETTE[(k + 1) % PALETTE.len()],
            Style::Markers(5),
        ));
    }
    series.retain(|s| s.points.iter().any(|p| p.0.is_finite()));
    let panel = Panel {
        title: format!(
            "{} curve of the period-{} orbit in ({}, {})",
            c.follow.words(),
            c.period,
            symbol(c.over),
            symbol(c.vary)
        ),
        x_label: parameter_label(c.over).into(),
        y_label: parameter_label(c.vary).into(),
        series,
        legend: Some(Legend::UpperLeft),
        ..Default::default()
    };
    Figure::single(panel, (900, 600))
}
