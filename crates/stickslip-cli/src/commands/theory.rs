//! `stickslip theory`: the paper's series solution against the exact periodic solution, and
//! stick-slip boundary or gain curves.

use crate::choice::choice;
use crate::flags::{help, reject_swept_flags};
use crate::model::ModelArgs;
use crate::output::{check_plot_path, usage, Sink};
use crate::plot::{Figure, Legend, Panel, Quantity};
use anyhow::Result;
use std::path::PathBuf;
use stickslip::experiment::Key;
use stickslip::report::{TheoryRow, TheoryTable};
use stickslip::theory::curves::{
    theory_curve, CurveKind as Curve, CurveRange, Theory, TheoryQuantity,
};
use stickslip::theory::TheoryReport;
use stickslip::{DiodeModel, Experiment, OptionKey, Parameter, Unsupported};

/// The paper's series solution (its eqs. 9–11, 13) next to the exact non-sticking periodic
/// solution (Den Hartog 1930 for ζ = 0, its damped generalisation otherwise).
///
/// At one (ζ, w, β): A1, A3, A5, the phase lag of the fundamental behind the drive, the gain
/// of the fundamental G1 = A1/β and the stick-slip boundary β_c of both, with the relative
/// error of the paper's approximation; --json prints
///   {"paper": {"A1", "A3", "A5", "phi0", "gain1", "beta_c"},
///    "exact": {"exists", "peak", "A1", "A3", "A5", "phase", "gain1", "beta_c", ...}}
/// where a value that does not exist is null and "note" says why. Phases are in radians.
///
/// With --curve, a CSV over w (ζ and μs from the model flags):
///   boundary: w,beta_c_paper,beta_c_exact       gain1 (needs --beta): w,gain1_paper,gain1_exact
/// (G1 = A1/β, the gain of the fundamental; `--curve gain`, its name before, still works).
/// An empty cell is a value that does not exist there.
///
/// Examples:
///   stickslip theory --zeta 0.0468 --w 0.9 --beta 2 --json
///   stickslip theory --preset paper --curve boundary --w-min 0.05 --w-max 10 --log --plot b.png
#[derive(Debug, clap::Args)]
#[command(verbatim_doc_comment)]
pub struct Args {
    #[command(flatten)]
    model: ModelArgs,
    /// Print JSON instead of a table (single point only).
    #[arg(long, conflicts_with = "curve", help_heading = "Theory")]
    json: bool,
    /// Write a curve over w instead of one point: `boundary` or `gain1`.
    #[arg(long, value_parser = choice::<Curve>(), help_heading = "Theory")]
    curve: Option<Curve>,
    #[arg(long = OptionKey::CurveWMin.flag(), help = help(OptionKey::CurveWMin), help_heading = "Theory", value_parser = crate::model::finite, allow_hyphen_values = true)]
    w_min: Option<f64>,
    #[arg(long = OptionKey::CurveWMax.flag(), help = help(OptionKey::CurveWMax), help_heading = "Theory", value_parser = crate::model::finite, allow_hyphen_values = true)]
    w_max: Option<f64>,
    #[arg(long, help = help(OptionKey::CurveSteps), help_heading = "Theory", allow_hyphen_values = true)]
    steps: Option<i64>,
    /// Space the frequencies of the curve logarithmically (and plot them on a logarithmic
    /// axis; the boundary's β_c axis is logarithmic in any case).
    #[arg(long, help_heading = "Theory")]
    log: bool,
    /// Curve CSV file [default: standard output].
    #[arg(long, short, help_heading = "Theory")]
    out: Option<PathBuf>,
    /// Plot of the curve (.png or .svg).
    #[arg(long, value_name = "FILE", help_heading = "Theory")]
    plot: Option<PathBuf>,
}

/// Run `stickslip theory`.
pub fn run(args: Args) -> Result<()> {
    let m = &args.model;
    for key in [Key::Y0, Key::V0, Key::Uc0, Key::I0] {
        if m.given(key) {
            usage!(
                "{} is not used by theory: it computes steady states, not a run from an initial state",
                crate::model::flag(key)
            );
        }
    }
    if m.diode == Some(DiodeModel::Shockley) {
        usage!("theory covers the piecewise-linear diode (Coulomb friction) model; --model shockley is not supported");
    }
    match args.curve {
        None => {
            let curve_flags = [
                (args.w_min.is_some(), "--w-min"),
                (args.w_max.is_some(), "--w-max"),
                (args.steps.is_some(), "--steps"),
                (args.log, "--log"),
                (args.out.is_some(), "--out"),
                (args.plot.is_some(), "--plot"),
            ];
            if let Some((_, flag)) = curve_flags.iter().find(|(given, _)| *given) {
                usage!("{flag} belongs to a curve: add --curve boundary or --curve gain1");
            }
            point(&args)
        }
        Some(curve) => curve_over_w(&args, curve),
    }
}

/// The experiment of the model flags, which must describe the PWL model.
fn pwl_experiment(args: &Args) -> Result<Experiment> {
    let experiment = args.model.experiment()?;
    if experiment.diode_model() == DiodeModel::Shockley {
        return Err(stickslip::Error::Unsupported(Unsupported::TheoryNeedsPwl).into());
    }
    Ok(experiment)
}

fn point(args: &Args) -> Result<()> {
    let experiment = pwl_experiment(args)?;
    let params = experiment.params()?;
    eprintln!("theory: {experiment}");
    let report = TheoryReport::new(&params)?;
    if args.json {
        return crate::output::print(&format!("{}\n", serde_json::to_string_pretty(&report)?));
    }
    let (paper, exact) = (&report.paper, &report.exact);
    let cell = |v: Option<f64>| v.map_or_else(|| "—".to_string(), |x| format!("{x:.6}"));
    let error = |paper: Option<f64>, exact: Option<f64>| match (paper, exact) {
        (Some(a), Some(b)) if b != 0.0 => format!("{:+.2}%", 100.0 * (a - b) / b),
        _ => "—".to_string(),
    };
    let rows: [(&str, Option<f64>, Option<f64>); 7] = [
        ("A1", paper.a1, exact.a1),
        ("A3", paper.a3, exact.a3),
        ("A5", paper.a5, exact.a5),
        ("phase lag (rad)", paper.phi0, exact.phase),
        ("gain G1 = A1/β", paper.gain1, exact.gain1),
        ("β_c", paper.beta_c, exact.beta_c),
        ("peak |y|", None, exact.peak),
    ];
    let mut text = String::new();
    text.push_str(&format!(
        "{:<16} {:>14} {:>14} {:>12}\n",
        "", "paper", "exact", "paper error"
    ));
    for (name, p, e) in rows {
        text.push_str(&format!(
            "{name:<16} {:>14} {:>14} {:>12}\n",
            cell(p),
            cell(e),
            error(p, e)
        ));
    }
    text.push_str(&format!(
        "exact solution: {}\n",
        match (exact.peak, exact.spectral_radius) {
            (Some(peak), Some(radius)) => format!(
                "exists (turning points ±{peak:.6}, spectral radius {radius:.4}: {})",
                if radius < 1.0 {
                    "attracting"
                } else {
                    "not attracting"
                }
            ),
            _ => "does not exist".into(),
        }
    ));
    for note in &paper.notes {
        text.push_str(&format!("note (paper): {note}\n"));
    }
    for note in &exact.notes {
        text.push_str(&format!("note (exact): {note}\n"));
    }
    text.push_str(
        "paper: eqs. (11) and (13) of the paper with ω0 = 1, Ω = w, α = 2ζ; \
         exact: Den Hartog's matching, damped\n",
    );
    crate::output::print(&text)
}

fn curve_over_w(args: &Args, curve: Curve) -> Result<()> {
    let defaults = CurveRange::default();
    let range = CurveRange {
        w_min: args.w_min.unwrap_or(defaults.w_min),
        w_max: args.w_max.unwrap_or(defaults.w_max),
        steps: OptionKey::CurveSteps.whole(args.steps.unwrap_or(defaults.steps as i64))?,
        log: args.log,
    }
    .validate()?;
    let (lo, hi, steps) = (range.w_min, range.w_max, range.steps);
    if let Some(p) = &args.plot {
        check_plot_path(p)?;
    }
    Sink::check(args.out.as_deref())?;
    let m = &args.model;
    reject_swept_flags(m, Parameter::W, "--curve (--w-min/--w-max)")?;
    let has_beta = m.given(Key::Beta) || m.given(Key::Amplitude);
    match curve {
        Curve::Boundary if has_beta => {
            usage!("--curve boundary finds β_c itself: drop --beta/--amplitude")
        }
        Curve::Gain1 if !has_beta => {
            usage!("--curve gain1 needs the drive amplitude: give --beta (or --amplitude with a physical description)")
        }
        _ => {}
    }
    let experiment = pwl_experiment(args)?;
    // The curve sets w (and finds β_c); the model supplies ζ, μs (and β).
    let params = experiment.params_with(&[
        (Parameter::W, lo),
        (Parameter::Beta, experiment.beta().unwrap_or(0.0)),
    ])?;
    let text = experiment.to_string();
    let described = text
        .split("; ω0")
        .next()
        .filter(|_| experiment.system().is_some())
        .map(|s| format!("{s}; "))
        .unwrap_or_default();
    eprintln!(
        "theory: {described}ζ = {:.6}, μs = {}{}; w from {lo} to {hi} ({} points{})",
        params.zeta,
        params.mu_s,
        if curve == Curve::Gain1 {
            format!(", β = {:.6}", params.beta)
        } else {
            String::new()
        },
        steps,
        if args.log { ", logarithmic" } else { "" }
    );

    let ws = range.values();
    let quantity = match curve {
        Curve::Boundary => TheoryQuantity::Boundary,
        Curve::Gain1 => TheoryQuantity::Gain1,
    };
    let bar = crate::output::progress(ws.len() as u64, "theory");
    let mut rows: Vec<Row> = Vec::with_capacity(ws.len());
    for chunk in ws.chunks(16) {
        crate::output::check_interrupt()?;
        let of = |theory| theory_curve(theory, quantity, &params, Parameter::W, chunk).y;
        let (paper, exact) = (of(Theory::Paper), of(Theory::Exact));
        let present = |v: f64| v.is_finite().then_some(v);
        for (k, &w) in chunk.iter().enumerate() {
            rows.push((w, present(paper[k]), present(exact[k])));
        }
        bar.inc(chunk.len() as u64);
    }
    bar.finish_and_clear();

    let table = TheoryTable {
        quantity: curve.quantity_name(),
        rows: rows
            .iter()
            .map(|&(w, paper, exact)| TheoryRow { w, paper, exact })
            .collect(),
    };
    let mut sink = Sink::open(args.out.as_deref())?;
    crate::output::write_table(&mut sink, &table)?;
    sink.finish()?;

    if let Some(path) = &args.plot {
        // The boundary spans decades (β_c grows like 2/w² at low w): a logarithmic β_c axis
        // keeps the region that matters, β_c ≈ 1.3–1.8, readable. With --log, w too.
        let points = |pick: fn(&Row) -> Option<f64>| {
            rows.iter()
                .map(|r| (r.0, pick(r).unwrap_or(f64::NAN)))
                .collect::<Vec<_>>()
        };
        let (paper_label, exact_label, y_label, title) = match curve {
            Curve::Boundary => (
                "paper, eq. (13)",
                "exact",
                "β_c (drive / friction), logarithmic",
                format!(
                    "stick-slip boundary, ζ = {:.4}, μs = {}",
                    params.zeta, params.mu_s
                ),
            ),
            Curve::Gain1 => (
                "paper, eq. (11)",
                "exact",
                "G1 = A1/β (gain of the fundamental)",
                format!("G1, ζ = {:.4}, β = {:.4}", params.zeta, params.beta),
            ),
        };
        let panel = Panel {
            title,
            x_label: if args.log {
                "w = Ω/ω0, logarithmic".into()
            } else {
                "w = Ω/ω0".into()
            },
            y_label: y_label.into(),
            series: vec![
                Quantity::PaperTheory.series(paper_label, points(|r| r.1)),
                Quantity::ExactTheory.series(exact_label, points(|r| r.2)),
            ],
            legend: Some(Legend::UpperRight),
            x_log: args.log,
            y_log: curve == Curve::Boundary,
            ..Default::default()
        };
        Figure::single(panel, (900, 560)).render(path)?;
    }
    let missing = rows
        .iter()
        .filter(|r| r.1.is_none() || r.2.is_none())
        .count();
    eprintln!(
        "theory: {} rows{}{}",
        rows.len(),
        if missing > 0 {
            format!(", {missing} with an empty cell (no solution there)")
        } else {
            String::new()
        },
        args.out
            .as_ref()
            .map(|p| format!(", curve in {}", p.display()))
            .unwrap_or_default()
    );
    Ok(())
}

/// One row of a curve: w, the paper's value and the exact value (None where there is none).
type Row = (f64, Option<f64>, Option<f64>);
