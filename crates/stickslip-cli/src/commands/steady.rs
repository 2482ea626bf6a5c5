//! `stickslip steady`: run to the steady state and report its class, period, spectrum and gain.

use crate::flags::{help, int, SteadyFlags};
use crate::model::ModelArgs;
use crate::output::{check_plot_path, outln, AtomicFile};
use crate::plot::{Figure, Legend, Panel, Quantity, Series, Style};
use anyhow::Result;
use std::path::PathBuf;
use stickslip::measure::Measurement;
use stickslip::options::OptionKey;
use stickslip::report::SteadyTrace;
use stickslip::stability::{NonperiodicClassification, NonperiodicVerdict};
use stickslip::steady::{SteadyReport, SteadyState};
use stickslip::Scales;

/// Run to the steady state from the initial state and report it.
///
/// The state once per drive period is followed until it repeats with a period p ≤ 16 drive
/// periods (relative tolerance 1e-10), then p whole periods are recorded. The class
/// (sliding, periodic-stick, nonperiodic-stick, static) comes from the exact event log;
/// harmonics A_k of y from a real FFT of the recorded periods; gain = (max y − min y)/(2β);
/// phase_lag = lag of the fundamental behind the drive (radians).
///
/// A motion that does not repeat within --max-periods is then measured (with --model shockley
/// by the tangent dynamics of the stiff solver's computed solution):
/// its largest Lyapunov exponent λ1 over --lyapunov-periods more periods, with a standard
/// error σ from 20 blocks. λ1 > 4σ: nearby motions separate exponentially, the class is
/// `chaotic`. Otherwise the class is `undecided` (not decided within the budget; sliding
/// without stops) and the exponent says why: λ1 < −4σ contracting onto a periodic motion not yet reached (or of
/// a period above --max-period), |λ1| ≤ 4σ quasi-periodic, halves disagreeing: undecided.
///
/// JSON keys: class, period (null if none), stops_per_period (stops per drive period),
/// symmetric, peak (max |y|), gain (G = (y_max − y_min)/(2β)), gain1 (G1 = A1/β),
/// phase_lag, harmonics [A1, A2, ...], harmonic_phases, current_harmonics (of y' = current
/// or velocity, dimensionless), subharmonic, mean, periods_to_settle, samples_per_period;
/// for a motion that does not repeat also lambda1, lambda1_error, lambda1_per_period,
/// lambda1_error_per_period (λ1 and σ per unit τ = ω0·t and per drive period),
/// lambda1_periods, lambda1_converged and verdict (chaotic, quasi-periodic, contracting or
/// undecided).
///
/// Example: stickslip steady --preset paper --w 0.6 --beta 1.2 --json --plot steady.png
#[derive(Debug, clap::Args)]
#[command(verbatim_doc_comment)]
pub struct Args {
    #[command(flatten)]
    model: ModelArgs,
    #[command(flatten)]
    steady: SteadyFlags,
    #[arg(long, help = help(OptionKey::ReportHarmonics), default_value_t = int(OptionKey::ReportHarmonics) as _, allow_hyphen_values = true)]
    harmonics: i64,
    /// Print JSON instead of text.
    #[arg(long)]
    json: bool,
    /// X-Y data of the recorded cycle as CSV `tau,drive,y,v` (the oscilloscope's X-Y mode).
    #[arg(long, value_name = "FILE")]
    xy: Option<PathBuf>,
    /// Plot of the cycle, its X-Y picture and its harmonics (.png or .svg).
    #[arg(long, value_name = "FILE")]
    plot: Option<PathBuf>,
    /// A scope record (CSV, as `fit --data`) drawn in the plot beside the cycle (and in its
    /// X-Y picture): its u_C and drive, shifted so that its drive's phase (from its sine fit)
    /// meets the computed drive's; the plot is then in volts. Needs a circuit and --plot.
    #[arg(long, value_name = "FILE", help_heading = "Measurements")]
    data: Option<String>,
    #[command(flatten)]
    channels: crate::commands::fit::RecordChannels,
}

/// Run `stickslip steady`.
pub fn run(args: Args) -> Result<()> {
    // The report's floor of 9 is its own row of the table (Python's `steady` allows 1).
    let harmonics = crate::flags::count(OptionKey::ReportHarmonics, args.harmonics)?;
    if let Some(p) = &args.plot {
        check_plot_path(p)?;
    }
    if let Some(p) = &args.xy {
        crate::output::check_output_path(p)?;
    }
    let experiment = args.model.experiment()?;
    let params = experiment.params()?;
    let options = args
        .steady
        .options(&experiment)?
        .with_harmonics(harmonics)?;
    stickslip::steady::check_horizon(&params, &options, 0.0)?;
    let record = crate::commands::fit::record_to_draw(
        args.data.as_deref(),
        &args.channels,
        &experiment,
        args.plot.as_deref(),
    )?;
    eprintln!("steady: {experiment}");
    let steady = experiment.steady_with(&options)?;
    crate::output::check_interrupt()?;

    if args.json {
        let report = SteadyReport::from(&steady);
        crate::output::print(&format!("{}\n", serde_json::to_string_pretty(&report)?))?;
    } else {
        let omega0 = experiment.scales().map(|s| s.omega0);
        crate::output::print(&text(&steady, omega0))?;
    }
    if let Some(path) = &args.xy {
        let mut file = AtomicFile::create(path)?;
        crate::output::write_table(&mut file, &SteadyTrace { steady: &steady })?;
        file.commit()?;
    }
    if let Some(path) = &args.plot {
        let record = match (&record, experiment.scales()) {
            (Some(r), Some(scales)) => {
                crate::commands::simulate::note_drive_mismatch("steady", r, &experiment);
                Some((r, scales))
            }
            _ => None,
        };
        plot(&steady, path, record)?;
    }
    Ok(())
}

/// The steady state as text.
///
/// `omega0`: ω0 in rad/s of a physical model, to give times in seconds too.
fn text(steady: &SteadyState, omega0: Option<f64>) -> String {
    let mut text = String::new();
    let params = &steady.params;
    let period = steady
        .period
        .map(|p| p.to_string())
        .unwrap_or_else(|| "none found".into());
    outln!(text, "class             {}", steady.class.label());
    if let Some(cycle) = &steady.self_excited {
        self_excited_text(&mut text, steady, cycle, omega0);
        return text;
    }
    outln!(text, "period            {period} (drive periods)");
    outln!(text, "stops per period  {}", steady.stops_per_period);
    outln!(text, "symmetric         {}", steady.symmetric);
    outln!(text, "peak |y|          {:.10}", steady.peak);
    outln!(text, "gain              {:.10}", steady.gain);
    match steady.phase_lag() {
        Some(lag) => outln!(
            text,
            "phase lag         {:.10} rad ({:.4}°)",
            lag,
            lag.to_degrees()
        ),
        None => outln!(text, "phase lag         none (no fundamental)"),
    }
    outln!(text, "periods to settle {}", steady.periods_to_settle);
    if params.vb != 0.0 {
        // (Without a belt, peak |y| says it for the symmetric orbits; --json has both.)
        outln!(
            text,
            "y max / y min     {:.10} / {:.10}",
            steady.y_max,
            steady.y_min
        );
    }
    if let Some(c) = &steady.lyapunov {
        let l = c.exponents.largest;
        outln!(
            text,
            "Lyapunov λ1       {:+.6e} ± {:.1e} per unit τ ({:+.6e} ± {:.1e} per drive period), \
             over {} more periods",
            l.per_tau,
            l.error_per_tau,
            l.per_period,
            l.error_per_period,
            c.exponents.periods
        );
        outln!(text, "verdict           {}", verdict_text(c));
    }
    if let Some(s) = &steady.spectrum {
        outln!(
            text,
            "harmonics of y (N = {} samples per period, mean {:.3e}, subharmonic {:.3e}):",
            s.samples_per_period,
            s.mean,
            s.subharmonic
        );
        outln!(
            text,
            "  k  amplitude A_k          phase θ_k (rad)   current k·w·A_k"
        );
        for (h, d) in s.harmonics.iter().zip(s.derivative(params.w)) {
            outln!(
                text,
                "{:3}  {:<22.15e} {:>+.10}   {:.6e}",
                h.order,
                h.amplitude,
                h.phase,
                d.amplitude
            );
        }
    }
    text
}

/// The self-excited motion of a block on a belt without a drive: its own period, extremes,
/// time stuck and the stability of steady sliding.
fn self_excited_text(
    text: &mut String,
    steady: &SteadyState,
    cycle: &stickslip::steady::SelfExcited,
    omega0: Option<f64>,
) {
    match (cycle.period, omega0) {
        (Some(t), Some(omega0)) => outln!(
            text,
            "cycle period      {t:.10} (τ = ω0·t), {:.6e} s",
            t / omega0
        ),
        (Some(t), None) => outln!(text, "cycle period      {t:.10} (τ = ω0·t)"),
        (None, _) => outln!(text, "cycle period      none (no cycle)"),
    }
    outln!(text, "stops per cycle   {}", steady.stops_per_period);
    outln!(text, "stick fraction    {:.10}", cycle.stick_fraction);
    outln!(
        text,
        "y max / y min     {:.10} / {:.10}",
        steady.y_max,
        steady.y_min
    );
    if let Some(section) = cycle.section {
        outln!(text, "section           {}", section.label());
    }
    outln!(
        text,
        "steady sliding    y = {:.10}, damping 2ζ + μ'(|vb|) = {:+.6e}: {}",
        cycle.equilibrium,
        cycle.sliding_damping,
        cycle.sliding_stability.description(&steady.params)
    );
}

/// What the exponent of a motion that does not repeat says, in words.
fn verdict_text(c: &NonperiodicClassification) -> String {
    let k = stickslip::SteadyOptions::DEFAULT_LYAPUNOV.significance;
    match c.verdict {
        NonperiodicVerdict::Chaotic => {
            format!("chaotic: λ1 > {k}σ, nearby motions separate by e^(λ1 τ)")
        }
        NonperiodicVerdict::Contracting => format!(
            "contracting (λ1 < −{k}σ): the motion settles onto a periodic one not reached \
             within the cap, or of a longer period than --max-period; not chaos"
        ),
        NonperiodicVerdict::QuasiPeriodic => format!(
            "quasi-periodic (|λ1| ≤ {k}σ): neither growth nor decay of perturbations; not chaos"
        ),
        NonperiodicVerdict::LimitCycle => format!(
            "a limit cycle (|λ1| ≤ {k}σ along it, λ2 < 0 across it): an undriven motion; not chaos"
        ),
        NonperiodicVerdict::Equilibrium => {
            format!("an equilibrium (λ1 < −{k}σ): every perturbation decays; not chaos")
        }
        NonperiodicVerdict::Undecided => {
            "undecided: the two halves of the measurement disagree (a transient, or chaos \
             that ends); try more --lyapunov-periods or --max-periods"
                .to_string()
        }
    }
}

/// The plot of the steady state; with a scope record (and the experiment's scales) the
/// record is drawn beside the cycle and in the X-Y picture, and the figure is in volts.
fn plot(
    steady: &SteadyState,
    path: &std::path::Path,
    record: Option<(&Measurement, Scales)>,
) -> Result<()> {
    let params = &steady.params;
    let t0 = steady.start;
    let period = params.drive_period();
    // Volts per unit of y and of the drive with a record, else dimensionless.
    let (volts, drive_volts) = record.map_or((1.0, 1.0), |(_, s)| (s.position, s.force));
    let trace: Vec<(f64, f64)> = steady
        .trace
        .iter()
        .map(|s| ((s.tau - t0) / period, s.y * volts))
        .collect();
    let drive: Vec<(f64, f64)> = steady
        .trace
        .iter()
        .map(|s| ((s.tau - t0) / period, params.drive(s.tau) * drive_volts))
        .collect();
    let stops: Vec<(f64, f64)> = steady
        .events
        .iter()
        .filter(|e| e.kind == stickslip::EventKind::Stick)
        .map(|e| ((e.tau - t0) / period, e.y * volts))
        .collect();
    let end = trace.last().map_or(1.0, |p| p.0);
    // The axis counts drive periods from the record's start τ0: the computed drive is
    // cos(2π·x + w·τ0 + φ), and a second is w·ω0/2π periods.
    let aligned = record.map(|(r, scales)| {
        (
            r,
            crate::measured::align(
                r,
                std::f64::consts::TAU,
                params.w * t0 + params.phi,
                params.w * scales.omega0 / std::f64::consts::TAU,
                end,
            ),
        )
    });
    let title = format!(
        "{}: w = {:.3}, β = {:.3}, ζ = {:.4}",
        match steady.class {
            stickslip::steady::MotionClass::Static => "static (amplitude < β/100)",
            other => other.label(),
        },
        params.w,
        params.beta,
        params.zeta
    );
    let volts_label = |dimensionless: &'static str, physical: &'static str| {
        if record.is_some() {
            physical
        } else {
            dimensionless
        }
    };
    let mut series = vec![Quantity::Drive.series(volts_label("drive", "drive U"), drive)];
    let mut xy_series = vec![Quantity::Response.series(
        "",
        steady
            .xy()
            .into_iter()
            .map(|(x, y)| (x * drive_volts, y * volts))
            .collect(),
    )];
    if let Some((r, aligned)) = &aligned {
        // The record under the computed u_C.
        series.extend(crate::measured::record_series(aligned, &r.file));
        xy_series.insert(
            0,
            Quantity::Measured.series(
                r.file.clone(),
                r.drive_values
                    .iter()
                    .copied()
                    .zip(r.response.iter().copied())
                    .collect(),
            ),
        );
        xy_series[1].label = "computed".into();
    }
    series.push(Quantity::Response.series(volts_label("y", "u_C"), trace));
    series.push(Quantity::Stops.series("stops", stops));
    let time = Panel {
        title,
        x_label: "drive periods".into(),
        y_label: volts_label("y, drive", "u_C, U (V)").into(),
        series,
        legend: Some(Legend::UpperRight),
        ..Default::default()
    };
    let xy = Panel {
        title: volts_label("X-Y: y against the drive", "X-Y: u_C against the drive U").into(),
        x_label: volts_label("drive β cos(wτ + φ)", "drive U (V)").into(),
        y_label: volts_label("y", "u_C (V)").into(),
        series: xy_series,
        legend: record.map(|_| Legend::UpperLeft),
        ..Default::default()
    };
    let bars: Vec<(f64, f64)> = steady
        .spectrum
        .iter()
        .flat_map(|s| {
            s.harmonics
                .iter()
                .map(|h| (h.order as f64, h.amplitude * volts))
        })
        .collect();
    let spectrum = Panel {
        title: volts_label("harmonics of y", "harmonics of u_C").into(),
        x_label: "k (multiple of the drive frequency)".into(),
        y_label: volts_label("A_k", "A_k (V)").into(),
        series: vec![Series::new(
            "",
            bars,
            Quantity::Response.color(),
            Style::Bars(0.6),
        )],
        ..Default::default()
    };
    Figure {
        panels: vec![time, xy, spectrum],
        columns: 3,
        panel_size: (560, 440),
    }
    .render(path)
}
