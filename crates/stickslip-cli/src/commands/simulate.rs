//! `stickslip simulate`: one trajectory, written as CSV, with its events and a plot.

use crate::model::ModelArgs;
use crate::output::{check_plot_path, usage, AtomicFile, Sink};
use crate::plot::{Figure, Legend, Panel, Series, Style, PALETTE};
use anyhow::Result;
use std::io::Write;
use std::path::PathBuf;

/// Integrate the motion exactly from the initial state and write the trajectory.
///
/// Output CSV columns: `tau,y,v,drive,phase` (dimensionless, phase = slip+|slip-|stick); with a
/// circuit also `t_s,uc_V,i_A,u_V`, with a mechanical oscillator `t_s,r_m,rdot_m_s,F_N`.
///
/// Example: stickslip simulate --preset paper --w 0.7 --beta 1.2 --periods 30 --plot trace.png
#[derive(Debug, clap::Args)]
#[command(verbatim_doc_comment)]
pub struct Args {
    #[command(flatten)]
    model: ModelArgs,
    /// Number of drive periods to simulate (> 0).
    #[arg(long, default_value_t = 20.0, value_parser = crate::model::finite, allow_hyphen_values = true)]
    periods: f64,
    /// Samples per drive period in the CSV (≥ 1).
    #[arg(
        long = "samples-per-period",
        default_value_t = 200,
        allow_hyphen_values = true
    )]
    samples_per_period: u64,
    /// Trajectory CSV file [default: standard output].
    #[arg(long, short)]
    out: Option<PathBuf>,
    /// Event log CSV `tau,y,kind` (kind = turn|stick|slip).
    #[arg(long, value_name = "FILE")]
    events: Option<PathBuf>,
    /// Plot of the trace (.png or .svg).
    #[arg(long, value_name = "FILE")]
    plot: Option<PathBuf>,
}

/// Run `stickslip simulate`.
pub fn run(args: Args) -> Result<()> {
    if !(args.periods > 0.0) || args.periods > 1e7 {
        usage!(
            "invalid --periods {}: must be > 0 and at most 1e7",
            args.periods
        );
    }
    if args.samples_per_period == 0 || args.samples_per_period > 100_000 {
        usage!(
            "invalid --samples-per-period {}: must be from 1 to 100000",
            args.samples_per_period
        );
    }
    let total = (args.periods * args.samples_per_period as f64).ceil();
    if total > 5e7 {
        usage!("--periods × --samples-per-period = {total} samples: at most 5e7 allowed");
    }
    if let Some(p) = &args.plot {
        check_plot_path(p)?;
    }
    for path in [&args.out, &args.events] {
        Sink::check(path.as_deref())?;
    }
    let experiment = args.model.experiment()?;
    let params = experiment.params()?;
    eprintln!("simulate: {experiment}");

    let run = experiment.simulate(args.periods, args.samples_per_period as usize, &|_, _| {
        !crate::output::interrupted()
    });
    crate::output::check_interrupt()?;
    let run = run?;

    let units = experiment.units();
    let mut sink = Sink::open(args.out.as_deref())?;
    let mut w = csv::Writer::from_writer(&mut sink);
    let mut header = vec!["tau", "y", "v", "drive", "phase"];
    if let Some(u) = &units {
        header.extend(u.columns());
    }
    w.write_record(&header)?;
    for k in 0..run.len() {
        let (tau, y, v, drive) = (run.tau[k], run.y[k], run.v[k], run.drive[k]);
        let mut row = vec![
            fmt(tau),
            fmt(y),
            fmt(v),
            fmt(drive),
            run.phase[k].label().to_string(),
        ];
        if let Some(u) = &units {
            row.extend(u.convert(tau, y, v, drive).map(fmt));
        }
        w.write_record(&row)?;
    }
    w.flush()?;
    drop(w);
    sink.finish()?;

    if let Some(path) = &args.events {
        let mut file = AtomicFile::create(path)?;
        writeln!(file, "tau,y,kind")?;
        for e in &run.events {
            writeln!(file, "{},{},{}", fmt(e.tau), fmt(e.y), e.kind.label())?;
        }
        file.commit()?;
    }

    if let Some(path) = &args.plot {
        let (tx, yx, x_label, y_label) = match units {
            Some(u) if u.circuit => (
                1e3 / u.scales.omega0,
                u.scales.position,
                "t (ms)",
                "voltage (V)",
            ),
            Some(u) => (
                1.0 / u.scales.omega0,
                u.scales.position,
                "t (s)",
                "r (m), F·k/F0 (m)",
            ),
            None => (1.0, 1.0, "τ = ω0 t", "y, drive"),
        };
        let scaled = |column: &[f64]| -> Vec<(f64, f64)> {
            run.tau
                .iter()
                .zip(column)
                .map(|(tau, x)| (tau * tx, x * yx))
                .collect()
        };
        let (trace, drive) = (scaled(&run.y), scaled(&run.drive));
        let stops: Vec<(f64, f64)> = run
            .events
            .iter()
            .filter(|e| e.kind == stickslip::EventKind::Stick)
            .map(|e| (e.tau * tx, e.y * yx))
            .collect();
        let circuit = units.is_some_and(|u| u.circuit);
        let panel = Panel {
            title: format!(
                "w = {:.3}, β = {:.3}, ζ = {:.4}",
                params.w, params.beta, params.zeta
            ),
            x_label: x_label.into(),
            y_label: y_label.into(),
            series: vec![
                Series::new(
                    if circuit { "drive U" } else { "drive" },
                    drive,
                    PALETTE[1],
                    Style::Line(2),
                ),
                Series::new(
                    if circuit { "u_C" } else { "y" },
                    trace,
                    PALETTE[0],
                    Style::Line(1),
                ),
                Series::new("stops", stops, PALETTE[6], Style::Markers(3)),
            ],
            legend: Some(Legend::UpperRight),
            ..Default::default()
        };
        Figure::single(panel, (1000, 480)).render(path)?;
    }
    eprintln!(
        "simulate: {} samples over {} drive periods, {} events{}",
        run.len(),
        args.periods,
        run.events.len(),
        args.out
            .as_ref()
            .map(|p| format!(", trajectory in {}", p.display()))
            .unwrap_or_default()
    );
    Ok(())
}

/// Shortest text that reads back as the same f64.
pub fn fmt(x: f64) -> String {
    format!("{x}")
}
