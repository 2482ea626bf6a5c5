//! `stickslip theory`: the paper's series solution against the exact periodic solution, and
//! stick-slip boundary or gain curves.

use crate::model::{DiodeModel, ModelArgs};
use crate::output::{check_plot_path, usage, Sink};
use crate::plot::{Figure, Legend, Panel, Series, Style, PALETTE};
use anyhow::Result;
use serde_json::{json, Map, Value};
use std::io::Write;
use std::path::PathBuf;
use stickslip::solver::grid;
use stickslip::theory::{
    paper_boundary, stick_slip_boundary, PaperHarmonic, PaperSeries, PeriodicSolution,
};
use stickslip::{Error, Params};

/// The paper's series solution (its eqs. 9–11, 13) next to the exact non-sticking periodic
/// solution (Den Hartog 1930 for ζ = 0, its damped generalisation otherwise).
///
/// At one (ζ, w, β): A1, A3, A5, the phase lag of the fundamental behind the drive, the gain
/// A1/β and the stick-slip boundary β_c of both, with the relative error of the paper's
/// approximation; --json prints
///   {"paper": {"A1", "A3", "A5", "phi0", "gain", "beta_c"},
///    "exact": {"exists", "peak", "A1", "A3", "A5", "phase", "gain", "beta_c", ...}}
/// where a value that does not exist is null and "note" says why. Phases are in radians.
///
/// With --curve, a CSV over w (ζ and μs from the model flags):
///   boundary: w,beta_c_paper,beta_c_exact       gain (needs --beta): w,gain_paper,gain_exact
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
    /// Write a curve over w instead of one point: `boundary` or `gain`.
    #[arg(long, value_enum, help_heading = "Theory")]
    curve: Option<Curve>,
    /// Smallest w of the curve (> 0) [default: 0.2].
    #[arg(long = "w-min", help_heading = "Theory", value_parser = crate::model::finite, allow_hyphen_values = true)]
    w_min: Option<f64>,
    /// Largest w of the curve (> --w-min) [default: 3].
    #[arg(long = "w-max", help_heading = "Theory", value_parser = crate::model::finite, allow_hyphen_values = true)]
    w_max: Option<f64>,
    /// Number of intervals of the curve: it has steps + 1 rows (1 to 100000) [default: 200].
    #[arg(long, help_heading = "Theory", allow_hyphen_values = true)]
    steps: Option<u64>,
    /// Space the frequencies of the curve logarithmically (and plot log10 w, log10 β_c).
    #[arg(long, help_heading = "Theory")]
    log: bool,
    /// Curve CSV file [default: standard output].
    #[arg(long, short, help_heading = "Theory")]
    out: Option<PathBuf>,
    /// Plot of the curve (.png or .svg).
    #[arg(long, value_name = "FILE", help_heading = "Theory")]
    plot: Option<PathBuf>,
}

/// Which curve `--curve` writes.
#[derive(Debug, Clone, Copy, PartialEq, Eq, clap::ValueEnum)]
pub enum Curve {
    /// β_c over w: `w,beta_c_paper,beta_c_exact`.
    Boundary,
    /// Gain A1/β over w at the given β: `w,gain_paper,gain_exact`.
    Gain,
}

/// Run `stickslip theory`.
pub fn run(args: Args) -> Result<()> {
    let m = &args.model;
    for (given, name) in [
        (m.y0.is_some(), "y0"),
        (m.v0.is_some(), "v0"),
        (m.uc0.is_some(), "uc0"),
        (m.i0.is_some(), "i0"),
    ] {
        if given {
            usage!("--{name} is not used by theory: it computes steady states, not a run from an initial state");
        }
    }
    if m.model == Some(DiodeModel::Shockley) {
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
                usage!("{flag} belongs to a curve: add --curve boundary or --curve gain");
            }
            point(&args)
        }
        Some(curve) => curve_over_w(&args, curve),
    }
}

/// `Some(x)` for finite x; `None` and a note otherwise.
fn value(result: Result<f64, Error>, what: &str, notes: &mut Vec<String>) -> Option<f64> {
    match result {
        Ok(x) if x.is_finite() => Some(x),
        Ok(x) => {
            notes.push(format!("{what}: not finite ({x})"));
            None
        }
        Err(e) => {
            notes.push(format!("{what}: {}", reason(&e)));
            None
        }
    }
}

/// The reason of a library error, without the "does not exist" preamble of NoSolution.
fn reason(e: &Error) -> String {
    match e {
        Error::NoSolution { reason, .. } => reason.clone(),
        other => other.to_string(),
    }
}

/// Everything shown for one point.
struct Point {
    paper: [Option<f64>; 6], // A1, A3, A5, phi0, gain, beta_c
    paper_notes: Vec<String>,
    exact: Option<PeriodicSolution>,
    exact_beta_c: Option<f64>,
    exact_notes: Vec<String>,
}

fn evaluate(params: &Params) -> Result<Point> {
    let (zeta, w, beta) = (params.zeta, params.w, params.beta);
    let mut paper_notes = Vec::new();
    let series = PaperSeries::new(zeta, w, beta);
    let a1 = value(
        series.clone().map(|s| s.a1),
        "A1 (eq. 11)",
        &mut paper_notes,
    );
    let phi0 = series.as_ref().ok().map(|s| s.phi0);
    let harmonic = |order: u32, notes: &mut Vec<String>| {
        value(
            PaperHarmonic::new(zeta, w, order).map(|h| h.amplitude),
            &format!("A{order} (eq. 11)"),
            notes,
        )
    };
    let a3 = harmonic(3, &mut paper_notes);
    let a5 = harmonic(5, &mut paper_notes);
    let paper_beta_c = value(paper_boundary(zeta, w), "beta_c (eq. 13)", &mut paper_notes);
    if params.mu_s != 1.0 {
        paper_notes.push(format!(
            "eq. (13) takes static friction equal to kinetic (μs = 1), not μs = {}",
            params.mu_s
        ));
    }
    if let (Ok(s), Some(_)) = (&series, paper_beta_c) {
        if !s.slides_by_eq13() {
            paper_notes.push(
                "β is below the paper's own boundary (eq. 13): by its criterion the motion sticks"
                    .into(),
            );
        }
    }

    let mut exact_notes = Vec::new();
    let exact = match PeriodicSolution::new(params) {
        Ok(s) => Some(s),
        Err(Error::NoSolution { reason, .. }) => {
            exact_notes.push(format!("no non-sticking periodic solution: {reason}"));
            None
        }
        Err(e) => return Err(e.into()),
    };
    let exact_beta_c = match stick_slip_boundary(zeta, w, params.mu_s) {
        Ok(b) => {
            if exact.is_none() {
                if let Some(n) = b.continuum {
                    exact_notes.push(continuum_note(n));
                }
            }
            Some(b.beta_c)
        }
        Err(Error::NoSolution { reason, .. }) => {
            if !exact_notes.iter().any(|n| n.contains(&reason)) {
                exact_notes.push(format!("beta_c: {reason}"));
            }
            None
        }
        Err(e) => return Err(e.into()),
    };
    if let Some(s) = &exact {
        if let Some(n) = s.continuum {
            exact_notes.push(continuum_note(n));
        }
    }
    Ok(Point {
        paper: [a1, a3, a5, phi0, a1.map(|a| a / beta), paper_beta_c],
        paper_notes,
        exact,
        exact_beta_c,
        exact_notes,
    })
}

fn continuum_note(n: u32) -> String {
    let at = if n == 1 {
        "1/2".to_string()
    } else {
        format!("1/{}", 2 * n)
    };
    format!(
        "w is near {at} with little damping: there the symmetric solution is one of a \
         continuum of periodic motions, most of them asymmetric (exactly so at ζ = 0, \
         w = {at}), and attracts only weakly; a simulation may settle elsewhere"
    )
}

fn point(args: &Args) -> Result<()> {
    let model = args.model.build()?;
    eprintln!("theory: {}", model.summary);
    let p = evaluate(&model.params)?;
    let [a1, a3, a5, phi0, gain, beta_c] = p.paper;
    let exact = p.exact.as_ref();
    let harmonic = |k: u32| exact.map(|s| s.harmonic(k).amplitude);
    if args.json {
        let mut paper = Map::new();
        for (key, v) in [
            ("A1", a1),
            ("A3", a3),
            ("A5", a5),
            ("phi0", phi0),
            ("gain", gain),
            ("beta_c", beta_c),
        ] {
            paper.insert(key.into(), json!(v));
        }
        if !p.paper_notes.is_empty() {
            paper.insert("note".into(), json!(p.paper_notes.join("; ")));
        }
        let mut exact_json = Map::new();
        exact_json.insert("exists".into(), json!(exact.is_some()));
        for (key, v) in [
            ("peak", exact.map(|s| s.peak)),
            ("A1", exact.map(|s| s.a1())),
            ("A3", harmonic(3)),
            ("A5", harmonic(5)),
            ("phase", exact.map(|s| s.phase_lag())),
            ("gain", exact.map(|s| s.gain())),
            ("beta_c", p.exact_beta_c),
            ("spectral_radius", exact.map(|s| s.spectral_radius())),
        ] {
            exact_json.insert(key.into(), json!(v));
        }
        if !p.exact_notes.is_empty() {
            exact_json.insert("note".into(), json!(p.exact_notes.join("; ")));
        }
        let out = json!({
            "params": {
                "zeta": model.params.zeta,
                "w": model.params.w,
                "beta": model.params.beta,
                "mu_s": model.params.mu_s,
            },
            "paper": Value::Object(paper),
            "exact": Value::Object(exact_json),
        });
        println!("{}", serde_json::to_string_pretty(&out)?);
        return Ok(());
    }

    let cell = |v: Option<f64>| v.map_or_else(|| "—".to_string(), |x| format!("{x:.6}"));
    let error = |paper: Option<f64>, exact: Option<f64>| match (paper, exact) {
        (Some(a), Some(b)) if b != 0.0 => format!("{:+.2}%", 100.0 * (a - b) / b),
        _ => "—".to_string(),
    };
    let rows: [(&str, Option<f64>, Option<f64>); 7] = [
        ("A1", a1, exact.map(|s| s.a1())),
        ("A3", a3, harmonic(3)),
        ("A5", a5, harmonic(5)),
        ("phase lag (rad)", phi0, exact.map(|s| s.phase_lag())),
        ("gain A1/β", gain, exact.map(|s| s.gain())),
        ("β_c", beta_c, p.exact_beta_c),
        ("peak |y|", None, exact.map(|s| s.peak)),
    ];
    let mut text = String::new();
    text.push_str(&format!(
        "{:<16} {:>14} {:>14} {:>12}\n",
        "", "paper", "exact", "paper error"
    ));
    for (name, paper, exact) in rows {
        text.push_str(&format!(
            "{name:<16} {:>14} {:>14} {:>12}\n",
            cell(paper),
            cell(exact),
            error(paper, exact)
        ));
    }
    text.push_str(&format!(
        "exact solution: {}\n",
        match exact {
            Some(s) => format!(
                "exists (turning points ±{:.6}, spectral radius {:.4}: {})",
                s.peak,
                s.spectral_radius(),
                if s.spectral_radius() < 1.0 {
                    "attracting"
                } else {
                    "not attracting"
                }
            ),
            None => "does not exist".into(),
        }
    ));
    for note in &p.paper_notes {
        text.push_str(&format!("note (paper): {note}\n"));
    }
    for note in &p.exact_notes {
        text.push_str(&format!("note (exact): {note}\n"));
    }
    text.push_str(
        "paper: eqs. (11) and (13) of the paper with ω0 = 1, Ω = w, α = 2ζ; \
         exact: Den Hartog's matching, damped\n",
    );
    print!("{text}");
    Ok(())
}

fn curve_over_w(args: &Args, curve: Curve) -> Result<()> {
    let (lo, hi) = (args.w_min.unwrap_or(0.2), args.w_max.unwrap_or(3.0));
    let steps = args.steps.unwrap_or(200);
    if !(lo > 0.0) {
        usage!("invalid --w-min {lo}: must be > 0");
    }
    if !(hi > lo) {
        usage!("invalid --w-max {hi}: must be greater than --w-min {lo}");
    }
    if steps == 0 || steps > 100_000 {
        usage!("invalid --steps {steps}: must be from 1 to 100000");
    }
    if let Some(p) = &args.plot {
        check_plot_path(p)?;
    }
    Sink::check(args.out.as_deref())?;
    let mut m = args.model.clone();
    if m.w.is_some() || m.freq.is_some() || m.omega.is_some() {
        usage!("--curve sweeps w: give --w-min and --w-max instead of --w, --freq or --omega");
    }
    let has_beta = m.beta.is_some() || m.amplitude.is_some();
    match curve {
        Curve::Boundary if has_beta => {
            usage!("--curve boundary finds β_c itself: drop --beta/--amplitude")
        }
        Curve::Gain if !has_beta => {
            usage!("--curve gain needs the drive amplitude: give --beta (or --amplitude with a physical description)")
        }
        _ => {}
    }
    // Placeholders for what the curve sweeps or finds; the model supplies ζ, μs (and β).
    m.w = Some(1.0);
    if curve == Curve::Boundary {
        m.beta = Some(0.0);
    }
    let model = m.build()?;
    let params = model.params;
    let described = model
        .summary
        .split("; ω0")
        .next()
        .filter(|_| model.system.is_some())
        .map(|s| format!("{s}; "))
        .unwrap_or_default();
    eprintln!(
        "theory: {described}ζ = {:.6}, μs = {}{}; w from {lo} to {hi} ({} steps{})",
        params.zeta,
        params.mu_s,
        if curve == Curve::Gain {
            format!(", β = {:.6}", params.beta)
        } else {
            String::new()
        },
        steps,
        if args.log { ", logarithmic" } else { "" }
    );

    let ws: Vec<f64> = if args.log {
        let mut ws: Vec<f64> = grid(lo.ln(), hi.ln(), steps as usize)
            .into_iter()
            .map(f64::exp)
            .collect();
        // The ends exactly as given, not through ln and exp.
        ws[0] = lo;
        *ws.last_mut().expect("at least two points") = hi;
        ws
    } else {
        grid(lo, hi, steps as usize)
    };
    let mut rows: Vec<Row> = Vec::with_capacity(ws.len());
    let bar = crate::output::progress(ws.len() as u64, "theory");
    for &w in &ws {
        crate::output::check_interrupt()?;
        let row = match curve {
            Curve::Boundary => (
                w,
                absent_if_no_solution(paper_boundary(params.zeta, w))?,
                absent_if_no_solution(
                    stick_slip_boundary(params.zeta, w, params.mu_s).map(|b| b.beta_c),
                )?,
            ),
            Curve::Gain => {
                let p = Params { w, ..params };
                (
                    w,
                    absent_if_no_solution(PaperSeries::new(p.zeta, w, p.beta).map(|s| s.gain()))?,
                    absent_if_no_solution(PeriodicSolution::new(&p).map(|s| s.gain()))?,
                )
            }
        };
        rows.push(row);
        bar.inc(1);
    }
    bar.finish_and_clear();

    let names = match curve {
        Curve::Boundary => ["beta_c_paper", "beta_c_exact"],
        Curve::Gain => ["gain_paper", "gain_exact"],
    };
    let mut sink = Sink::open(args.out.as_deref())?;
    writeln!(sink, "w,{},{}", names[0], names[1])?;
    let cell = |v: Option<f64>| v.map(|x| format!("{x}")).unwrap_or_default();
    for &(w, a, b) in &rows {
        writeln!(sink, "{w},{},{}", cell(a), cell(b))?;
    }
    sink.finish()?;

    if let Some(path) = &args.plot {
        // With --log the boundary spans decades: plot log10 of w (and of β_c).
        let log_y = args.log && curve == Curve::Boundary;
        let axis = |x: f64, log: bool| if log { x.log10() } else { x };
        let points = |pick: fn(&Row) -> Option<f64>| {
            rows.iter()
                .map(|r| {
                    (
                        axis(r.0, args.log),
                        pick(r).map_or(f64::NAN, |v| axis(v, log_y)),
                    )
                })
                .collect::<Vec<_>>()
        };
        let (paper_label, exact_label, y_label, title) = match curve {
            Curve::Boundary => (
                "paper, eq. (13)",
                "exact",
                if args.log {
                    "log10 β_c (drive / friction)"
                } else {
                    "β_c (drive / friction)"
                },
                format!(
                    "stick-slip boundary, ζ = {:.4}, μs = {}",
                    params.zeta, params.mu_s
                ),
            ),
            Curve::Gain => (
                "paper, eq. (11)",
                "exact",
                "gain A1/β",
                format!("gain, ζ = {:.4}, β = {:.4}", params.zeta, params.beta),
            ),
        };
        let panel = Panel {
            title,
            x_label: if args.log {
                "log10 w, w = Ω/ω0".into()
            } else {
                "w = Ω/ω0".into()
            },
            y_label: y_label.into(),
            series: vec![
                Series::new(paper_label, points(|r| r.1), PALETTE[1], Style::Dashed(2)),
                Series::new(exact_label, points(|r| r.2), PALETTE[0], Style::Line(2)),
            ],
            legend: Some(Legend::UpperRight),
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

/// `Ok(None)` for a value that does not exist; other errors pass through.
fn absent_if_no_solution(result: Result<f64, Error>) -> Result<Option<f64>> {
    match result {
        Ok(x) if x.is_finite() => Ok(Some(x)),
        Ok(_) | Err(Error::NoSolution { .. }) => Ok(None),
        Err(e) => Err(e.into()),
    }
}
