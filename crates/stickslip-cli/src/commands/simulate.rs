//! `stickslip simulate`: one trajectory, written as CSV, with its events and a plot.

use crate::flags::{help, int, num};
use crate::model::ModelArgs;
use crate::output::{check_plot_path, AtomicFile, Sink};
use crate::plot::{Figure, Legend, Panel, Quantity};
use anyhow::Result;
use std::io::Write;
use std::path::PathBuf;
use stickslip::options::SimulateOptions;
use stickslip::report::{EventRow, TrajectoryRecord};
use stickslip::EventKind;
use stickslip::OptionKey;

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
    #[arg(long, help = help(OptionKey::SimulatePeriods), default_value_t = num(OptionKey::SimulatePeriods), value_parser = crate::model::finite, allow_hyphen_values = true)]
    periods: f64,
    #[arg(long = OptionKey::SimulateSamples.flag(), help = help(OptionKey::SimulateSamples), default_value_t = int(OptionKey::SimulateSamples) as _, allow_hyphen_values = true)]
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
    /// A scope record (CSV, as `fit --data`) drawn in the plot beside the computed trace: its
    /// u_C and drive, shifted so that its drive's phase (from its sine fit) meets the
    /// computed drive's, as late in the run as it fits. Needs a circuit and --plot.
    #[arg(long, value_name = "FILE", help_heading = "Measurements")]
    data: Option<String>,
    #[command(flatten)]
    channels: crate::commands::fit::RecordChannels,
}

/// Run `stickslip simulate`.
pub fn run(args: Args) -> Result<()> {
    SimulateOptions {
        periods: args.periods,
        samples_per_period: usize::try_from(args.samples_per_period).unwrap_or(usize::MAX),
    }
    .validate()?;
    if let Some(p) = &args.plot {
        check_plot_path(p)?;
    }
    for path in [&args.out, &args.events] {
        Sink::check(path.as_deref())?;
    }
    let experiment = args.model.experiment()?;
    let params = experiment.params()?;
    // Before any work: a run longer than the solvers resolve is refused (exit code 2).
    stickslip::limits::check_horizon(&params, args.periods)?;
    let record = crate::commands::fit::record_to_draw(
        args.data.as_deref(),
        &args.channels,
        &experiment,
        args.plot.as_deref(),
    )?;
    eprintln!("simulate: {experiment}");

    let period = params.drive_period();
    let t_end = args.periods * period;
    let units = experiment.units();

    // Samples and events are written as they are computed: memory stays flat however long
    // the run. Both files are temporary until the run has finished.
    let keep_going = |_: usize, _: usize| !crate::output::interrupted();
    let run = experiment
        .trajectory(args.periods, args.samples_per_period as usize)?
        .monitor(&keep_going);
    let mut sink = Sink::open(args.out.as_deref())?;
    let mut events_file = args.events.as_deref().map(AtomicFile::create).transpose()?;
    writeln!(sink, "{}", run.columns().header())?;
    if let Some(file) = &mut events_file {
        writeln!(file, "{}", EventRow::COLUMNS.join(","))?;
    }
    let mut trace = args.plot.as_ref().map(|_| PlotTrace::new(t_end));
    let (mut samples, mut events) = (0u64, 0u64);
    let mut line = String::new();
    for record in run {
        let record = match record {
            Ok(record) => record,
            Err(err) => {
                crate::output::check_interrupt()?;
                return Err(err.into());
            }
        };
        line.clear();
        match record {
            TrajectoryRecord::Sample(s) => {
                samples += 1;
                s.write_row(&mut line);
                sink.write_all(line.as_bytes())?;
                if let Some(t) = &mut trace {
                    t.sample(s.tau, s.y, s.drive);
                }
            }
            TrajectoryRecord::Event(e) => {
                events += 1;
                if let Some(file) = &mut events_file {
                    e.write_row(&mut line);
                    file.write_all(line.as_bytes())?;
                }
                if let (Some(t), EventKind::Stick) = (&mut trace, e.kind) {
                    t.stop(e.tau, e.y);
                }
            }
        }
    }
    sink.finish()?;
    if let Some(file) = events_file {
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
        let trace = trace.expect("kept for the plot");
        let scale = |points: Vec<(f64, f64)>| -> Vec<(f64, f64)> {
            points.into_iter().map(|(t, y)| (t * tx, y * yx)).collect()
        };
        let (drive, stops, trace) = (
            scale(trace.drive.points()),
            scale(trace.stops.points()),
            scale(trace.y.points()),
        );
        let circuit = units.is_some_and(|u| u.circuit);
        let mut series =
            vec![Quantity::Drive.series(if circuit { "drive U" } else { "drive" }, drive)];
        // The record under the computed u_C.
        if let Some(record) = &record {
            // The axis is in ms (τ·tx): the computed drive is cos(w·t/tx + φ).
            let aligned =
                crate::measured::align(record, params.w / tx, params.phi, 1e3, t_end * tx);
            note_drive_mismatch("simulate", record, &experiment);
            series.extend(crate::measured::record_series(&aligned, &record.file));
        }
        series.push(Quantity::Response.series(if circuit { "u_C" } else { "y" }, trace));
        series.push(Quantity::Stops.series("stops", stops));
        let panel = Panel {
            title: format!(
                "w = {:.3}, β = {:.3}, ζ = {:.4}",
                params.w, params.beta, params.zeta
            ),
            x_label: x_label.into(),
            y_label: y_label.into(),
            series,
            legend: Some(Legend::UpperRight),
            ..Default::default()
        };
        Figure::single(panel, (1000, 480)).render(path)?;
    }
    eprintln!(
        "simulate: {} samples over {} drive periods, {} events{}",
        samples,
        args.periods,
        events,
        args.out
            .as_ref()
            .map(|p| format!(", trajectory in {}", p.display()))
            .unwrap_or_default()
    );
    Ok(())
}

/// Say on standard error when a record drawn beside a computed trace was driven otherwise
/// than the model (by more than 1 % in frequency or 5 % in amplitude): the two are then
/// aligned at the record's start only.
pub(crate) fn note_drive_mismatch(
    command: &str,
    record: &stickslip::measure::Measurement,
    experiment: &stickslip::Experiment,
) {
    let (Some(scales), Ok(params)) = (experiment.scales(), experiment.params()) else {
        return;
    };
    let f = params.w * scales.f0();
    let u = params.beta * scales.force;
    let (rf, ru) = (record.drive.frequency, record.drive.amplitude);
    if (rf / f - 1.0).abs() > 0.01 || (ru / u - 1.0).abs() > 0.05 {
        eprintln!(
            "{command}: note: {} was driven at {rf:.6} Hz, {ru:.4} V; the model at {f:.6} Hz, \
             {u:.4} V (give --freq {rf:.6} --amplitude {ru:.4} to compare like with like)",
            record.file
        );
    }
}

/// Most points of a plotted curve kept as they are; a longer curve is drawn from the
/// smallest and the largest value in each of `MAX_PLOT_POINTS / 2` equal stretches of time,
/// which at the plot's resolution draws the same picture, with memory that does not grow.
const MAX_PLOT_POINTS: usize = 200_000;

/// A point (τ, value) of a plotted curve.
type Point = (f64, f64);

/// A curve for the plot: every point while there are at most [`MAX_PLOT_POINTS`], else the
/// extremes of each stretch of time.
struct Curve {
    /// Every point, until there are too many.
    all: Vec<(f64, f64)>,
    /// Per stretch of time, the points of smallest and largest value (empty while `all`
    /// holds every point).
    buckets: Vec<Option<(Point, Point)>>,
    /// Stretches per unit of τ.
    per_tau: f64,
}

impl Curve {
    fn new(t_end: f64) -> Self {
        Self {
            all: Vec::new(),
            buckets: Vec::new(),
            per_tau: if t_end > 0.0 {
                (MAX_PLOT_POINTS / 2) as f64 / t_end
            } else {
                0.0
            },
        }
    }

    fn push(&mut self, t: f64, value: f64) {
        if self.buckets.is_empty() {
            if self.all.len() < MAX_PLOT_POINTS {
                self.all.push((t, value));
                return;
            }
            self.buckets = vec![None; MAX_PLOT_POINTS / 2];
            for (t, value) in std::mem::take(&mut self.all) {
                self.bucket(t, value);
            }
        }
        self.bucket(t, value);
    }

    fn bucket(&mut self, t: f64, value: f64) {
        let i = ((t * self.per_tau) as usize).min(self.buckets.len() - 1);
        let slot = &mut self.buckets[i];
        match slot {
            None => *slot = Some(((t, value), (t, value))),
            Some((low, high)) => {
                if value < low.1 {
                    *low = (t, value);
                }
                if value > high.1 {
                    *high = (t, value);
                }
            }
        }
    }

    /// The points in time order.
    fn points(self) -> Vec<(f64, f64)> {
        if self.buckets.is_empty() {
            return self.all;
        }
        self.buckets
            .into_iter()
            .flatten()
            .flat_map(|(a, b)| if a.0 <= b.0 { [a, b] } else { [b, a] })
            .collect()
    }
}

/// What the plot of a run needs: y, the drive and the stops, each a [`Curve`].
struct PlotTrace {
    y: Curve,
    drive: Curve,
    stops: Curve,
}

impl PlotTrace {
    fn new(t_end: f64) -> Self {
        Self {
            y: Curve::new(t_end),
            drive: Curve::new(t_end),
            stops: Curve::new(t_end),
        }
    }

    fn sample(&mut self, tau: f64, y: f64, drive: f64) {
        self.y.push(tau, y);
        self.drive.push(tau, drive);
    }

    fn stop(&mut self, tau: f64, y: f64) {
        self.stops.push(tau, y);
    }
}
