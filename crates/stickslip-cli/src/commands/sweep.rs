//! `stickslip sweep`: w, β, ζ or μs swept up and/or down with continuation (hysteresis).

use crate::checkpoint::{CheckpointFile, CheckpointFlags};
use crate::choice::choice;
use crate::flags::{help, range_from_flags, reject_swept_flags, SteadyFlags};
use crate::model::{finite, ModelArgs};
use crate::output::{check_plot_path, Sink};
use crate::plot::{Figure, Legend, Panel, Quantity, Series, Style};
use anyhow::Result;
use std::ops::ControlFlow;
use std::path::PathBuf;
use stickslip::checkpoint::{Checkpoint, Identity, UnitReader, UnitWriter};
use stickslip::experiment::Origin;
use stickslip::report::{SweepReport, SweepRow};
use stickslip::scan::{Axis, ParameterRange, Sweep, SweepDirection, SweepLeg, SweepPoint};
use stickslip::steady::MotionClass;
use stickslip::theory::curves::{
    abscissae, theory_curve, Theory as TheoryKind, TheoryCurve, TheoryQuantity,
};
use stickslip::{DiodeModel, Experiment, OptionKey, Parameter, Params, State};

/// Sweep one parameter (w, β, ζ, μs or vb) with the others fixed; each step starts from the
/// final state of the step before, as when turning a knob, so hysteresis and coexisting
/// motions show up.
///
/// Output CSV columns: w,beta,direction,gain,gain1,A1,A3,class,stops_per_period
/// (direction = up|down; A1, A3 = amplitudes of the 1st and 3rd harmonics of y); a sweep of
/// zeta, mu_s or vb (the belt speed) puts the swept value first: zeta,w,beta,... Without a
/// drive a belt's motion is self-excited: sweep vb up and down for its stick-slip cycles and
/// steady sliding (and where they coexist). Its columns are those of the classic amplitude
/// against belt speed: vb,direction,amplitude,y_max,y_min,cycle_period_tau,stick_fraction,
/// class (amplitude = (y_max − y_min)/2; the cycle's period in τ = ω0·t, empty for steady
/// sliding; cycle_period_s after cycle_period_tau for a mechanical oscillator), and --plot
/// draws the amplitude up and down.
///
/// Example: stickslip sweep --preset paper --over w --beta 2.14 --from 0.2 --to 2 --steps 91 \
///          --direction both --out sweep.csv --plot sweep.png
///          stickslip sweep --over vb --from 0.05 --to 2 --steps 40 --beta 0 --mu-s 1.5 \
///          --friction-law stribeck --vs 0.3 --plot belt.png
#[derive(Debug, clap::Args)]
#[command(verbatim_doc_comment)]
pub struct Args {
    #[command(flatten)]
    model: ModelArgs,
    #[command(flatten)]
    steady: SteadyFlags,
    /// The swept parameter (the others come from the model flags).
    #[arg(long, value_parser = choice::<Parameter>())]
    over: Parameter,
    /// First value of the swept parameter (dimensionless).
    #[arg(long, value_parser = finite, allow_hyphen_values = true)]
    from: f64,
    /// Last value of the swept parameter (dimensionless, ≥ --from).
    #[arg(long, value_parser = finite, allow_hyphen_values = true)]
    to: f64,
    #[arg(long, help = help(OptionKey::SweepSteps), allow_hyphen_values = true)]
    steps: i64,
    /// Which way to sweep: up (from --from to --to), down (from --to to --from), or both (up,
    /// then down again from where the up sweep ended).
    #[arg(long, value_parser = choice::<SweepDirection>(), default_value_t = SweepDirection::Both)]
    direction: SweepDirection,
    /// CSV file [default: standard output, unless --json].
    #[arg(long, short)]
    out: Option<PathBuf>,
    /// Print the sweep as JSON on standard output: `over`, `direction` and one record per
    /// step in `points` (the CSV's columns and what the CSV leaves out).
    #[arg(long)]
    json: bool,
    /// Plot of the gain of the fundamental G1 = A1/β against the swept parameter, up and
    /// down, with the paper's G1 (eq. 11) and the exact sliding orbit's G1 where it exists
    /// (.png or .svg). The CSV has both gains: `gain` is G = (y_max − y_min)/(2β), `gain1` G1.
    #[arg(long, value_name = "FILE")]
    plot: Option<PathBuf>,
    #[command(flatten)]
    checkpoint: CheckpointFlags,
}

/// Run `stickslip sweep`.
pub fn run(args: Args) -> Result<()> {
    let parameter = args.over;
    let range = range_from_flags(
        parameter.label(),
        ("from", args.from),
        ("to", args.to),
        (OptionKey::SweepSteps, args.steps),
    )?;
    reject_swept_flags(&args.model, parameter, "--over")?;
    if let Some(p) = &args.plot {
        check_plot_path(p)?;
    }
    Sink::check(args.out.as_deref())?;
    args.checkpoint.check()?;
    let experiment = args.model.experiment()?;
    let options = args.steady.options(&experiment)?.with_harmonics(3)?;
    let direction = args.direction;
    let sweep = Sweep::new(&experiment, Axis::range(parameter, &range)?)?
        .direction(direction)
        .options(options)?;
    // A checkpoint of other parameters, or a damaged one, is refused before any work.
    let mut file = args
        .checkpoint
        .open(identity(&sweep)?, sweep.plan().len())?;
    eprintln!(
        "sweep: {experiment}; over {} from {} to {} in {} steps, {}",
        parameter.label(),
        range.from(),
        range.to(),
        range.steps(),
        match args.direction {
            SweepDirection::Up => "up",
            SweepDirection::Down => "down",
            SweepDirection::Both => "up and down",
        }
    );
    let total = sweep.plan().len();
    let bar = crate::output::progress(total as u64, "sweep");
    let points = match &mut file {
        None => {
            let result = sweep.run(&|_: usize, _: usize| {
                bar.inc(1);
                !crate::output::interrupted()
            });
            bar.finish_and_clear();
            crate::output::check_interrupt()?;
            result?.iter().map(Row::from).collect::<Vec<_>>()
        }
        Some(file) => {
            let result = run_steps(&sweep, file, &bar);
            bar.finish_and_clear();
            // Whatever happened, the steps finished so far are saved for the rerun.
            file.save()?;
            crate::output::check_interrupt()?;
            result?;
            steps_to_rows(&sweep, file.checkpoint())?
        }
    };

    let report = SweepReport {
        over: parameter,
        direction,
        points: points.iter().map(|p| p.report_row(&experiment)).collect(),
    };
    if args.out.is_some() || !args.json {
        let mut sink = Sink::open(args.out.as_deref())?;
        crate::output::write_table(&mut sink, &report)?;
        sink.finish()?;
    }
    if args.json {
        crate::output::print(&format!("{}\n", serde_json::to_string_pretty(&report)?))?;
    }
    if let Some(path) = &args.plot {
        if report.self_excited() {
            plot_self_excited(&report, path)?;
        } else {
            let theory = Theory::new(&experiment, parameter, &range)?;
            let exact_a1 = Theory::exact_a1(&experiment, parameter, &range)?;
            eprintln!(
            "sweep: theory on the plot: paper's gain at {} and exact sliding orbit at {} of {} values",
            theory.paper.present(),
            exact_a1.present(),
            theory.paper.x.len()
        );
            plot(&points, parameter, &theory, &exact_a1, path)?;
        }
    }
    if let Some(file) = file {
        file.remove()?;
    }
    let differ = branches_differ(&points);
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

/// Values at which the up and the down leg found different motions (gain or class).
fn branches_differ(points: &[Row]) -> usize {
    let up: Vec<&Row> = points.iter().filter(|p| p.leg == SweepLeg::Up).collect();
    let down: Vec<&Row> = points.iter().filter(|p| p.leg == SweepLeg::Down).collect();
    up.iter()
        .filter(|u| {
            down.iter().any(|d| {
                d.value == u.value
                    && (d.class != u.class || (d.gain - u.gain).abs() > 1e-6 * u.gain.abs())
            })
        })
        .count()
}

/// What the output of a sweep step needs (the CSV, the plot, the summary), and the state
/// the next step starts from.
#[derive(Debug, Clone, PartialEq)]
struct Row {
    params: Params,
    value: f64,
    leg: SweepLeg,
    gain: f64,
    a1: f64,
    a3: f64,
    class: MotionClass,
    stops_per_period: f64,
    stops: usize,
    final_state: State,
    /// y_max, y_min, the self-excited cycle's period in τ (NaN: none) and its stick fraction
    /// (NaN: a forced step); `None` for a step restored from a checkpoint that did not keep
    /// them.
    extremes: Option<[f64; 4]>,
}

impl From<&SweepPoint> for Row {
    fn from(p: &SweepPoint) -> Self {
        let s = &p.steady;
        Self {
            params: p.params,
            value: p.value,
            leg: p.leg,
            gain: s.gain,
            a1: s.harmonic(1).unwrap_or(f64::NAN),
            a3: s.harmonic(3).unwrap_or(f64::NAN),
            class: s.class,
            stops_per_period: s.stops_per_period,
            stops: s.stops,
            final_state: s.final_state(),
            extremes: Some([
                s.y_max,
                s.y_min,
                s.self_excited.and_then(|c| c.period).unwrap_or(f64::NAN),
                s.self_excited.map_or(f64::NAN, |c| c.stick_fraction),
            ]),
        }
    }
}

impl Row {
    /// The row of the report (the steady state's peak, period and phase lag are not kept in
    /// a row: absent).
    fn report_row(&self, experiment: &Experiment) -> SweepRow {
        let measured = |x: f64| (!x.is_nan()).then_some(x);
        SweepRow {
            value: self.value,
            w: self.params.w,
            beta: self.params.beta,
            zeta: self.params.zeta,
            mu_s: self.params.mu_s,
            direction: self.leg,
            gain: self.gain,
            // As `SteadyState::gain1`: A1/β, absent at β = 0 or without a spectrum.
            gain1: (self.params.beta > 0.0)
                .then(|| self.a1 / self.params.beta)
                .and_then(measured),
            peak: None,
            a1: measured(self.a1),
            a3: measured(self.a3),
            class: self.class,
            stops_per_period: self.stops_per_period,
            period: None,
            phase_lag: None,
            f_hz: experiment
                .scales()
                .map(|s| s.drive_omega(self.params.w) / std::f64::consts::TAU),
            amplitude: self.extremes.map(|[max, min, ..]| 0.5 * (max - min)),
            y_max: self.extremes.map(|[max, ..]| max),
            y_min: self.extremes.map(|[_, min, ..]| min),
            cycle_period_tau: self.extremes.and_then(|[.., tau, _]| measured(tau)),
            cycle_period_s: None,
            stick_fraction: self.extremes.and_then(|[.., fraction]| measured(fraction)),
        }
        .with_seconds(experiment)
    }

    /// The row as a checkpoint unit (its parameters, value and leg follow from the sweep;
    /// the extremes, period and stick fraction last, which a checkpoint written before they
    /// were kept lacks).
    fn encode(&self) -> Vec<u8> {
        let class = MotionClass::ALL
            .iter()
            .position(|&c| c == self.class)
            .expect("a class of ALL");
        let mut unit = UnitWriter::new();
        unit.f64(self.gain)
            .f64(self.a1)
            .f64(self.a3)
            .u8(class as u8)
            .f64(self.stops_per_period)
            .u64(self.stops as u64)
            .f64(self.final_state.y)
            .f64(self.final_state.v);
        if let Some(extremes) = self.extremes {
            for x in extremes {
                unit.f64(x);
            }
        }
        unit.finish()
    }

    /// The row of step `index` from its checkpoint unit.
    fn decode(sweep: &Sweep, index: usize, unit: &[u8]) -> Result<Self> {
        let damaged = || anyhow::anyhow!("checkpoint holds a malformed sweep step");
        let mut r = UnitReader::new(unit);
        let (value, leg) = sweep.plan()[index];
        let mut row = Self {
            params: sweep.params(index)?,
            value,
            leg,
            gain: r.f64().ok_or_else(damaged)?,
            a1: r.f64().ok_or_else(damaged)?,
            a3: r.f64().ok_or_else(damaged)?,
            class: *MotionClass::ALL
                .get(r.u8().ok_or_else(damaged)? as usize)
                .ok_or_else(damaged)?,
            stops_per_period: r.f64().ok_or_else(damaged)?,
            stops: r.u64().ok_or_else(damaged)? as usize,
            final_state: State {
                y: r.f64().ok_or_else(damaged)?,
                v: r.f64().ok_or_else(damaged)?,
            },
            extremes: None,
        };
        if !r.is_empty() {
            let mut extremes = [0.0; 4];
            for x in &mut extremes {
                *x = r.f64().ok_or_else(damaged)?;
            }
            row.extremes = Some(extremes);
        }
        if !r.is_empty() {
            return Err(damaged());
        }
        Ok(row)
    }
}

/// Everything that determines the sweep: the experiment (whatever file or flags described
/// it), the axis, the direction, the steady-state options.
fn identity(sweep: &Sweep) -> Result<Identity> {
    let experiment = sweep.experiment().clone().with_origin(Origin::Parts);
    Ok(Identity::new("sweep")
        .with("experiment", serde_json::to_string(&experiment)?)
        .with("axis", serde_json::to_string(sweep.axis())?)
        .with("plan", serde_json::to_string(&sweep.plan())?)
        .with("options", serde_json::to_string(sweep.steady_options())?))
}

/// Run the steps the checkpoint lacks (a sweep resumes after its last saved step, from the
/// state that step ended in), saving each finished step.
fn run_steps(sweep: &Sweep, file: &mut CheckpointFile, bar: &indicatif::ProgressBar) -> Result<()> {
    let checkpoint = file.checkpoint();
    let start = checkpoint.missing().next().unwrap_or(checkpoint.total());
    if checkpoint.missing().any(|i| i < start) || checkpoint.done() != start {
        anyhow::bail!(
            "checkpoint {} holds steps out of order",
            file.path().display()
        );
    }
    if start == checkpoint.total() {
        return Ok(());
    }
    let state = if start == 0 {
        sweep.experiment().initial()
    } else {
        let unit = checkpoint.unit(start - 1).expect("saved step");
        Row::decode(sweep, start - 1, unit)?.final_state
    };
    if start > 0 {
        eprintln!(
            "sweep: resuming from {}: {} of {} steps reused",
            file.path().display(),
            start,
            checkpoint.total()
        );
        bar.inc(start as u64);
    }
    let mut saved: Result<()> = Ok(());
    let result = sweep.run_from(start, state, &mut |i, point| {
        bar.inc(1);
        saved = file.insert(i, Row::from(&point).encode());
        if saved.is_err() || crate::output::interrupted() {
            ControlFlow::Break(())
        } else {
            ControlFlow::Continue(())
        }
    });
    saved?;
    Ok(result?)
}

/// Every step of the sweep, from a complete checkpoint.
fn steps_to_rows(sweep: &Sweep, checkpoint: &Checkpoint) -> Result<Vec<Row>> {
    (0..checkpoint.total())
        .map(|i| {
            let unit = checkpoint
                .unit(i)
                .ok_or_else(|| anyhow::anyhow!("checkpoint lacks step {i}"))?;
            Row::decode(sweep, i, unit)
        })
        .collect()
}

/// The theory's gain curves over the swept range, at the sweep's fixed parameters (also
/// drawn by the lab's sweep view).
pub(crate) struct Theory {
    /// The paper's gain A1/β, eq. (11).
    pub(crate) paper: TheoryCurve,
    /// Legend prefix: the theory is that of the piecewise-linear model.
    pub(crate) prefix: &'static str,
}

impl Theory {
    /// The exact sliding orbit's A1/β over the swept range: the gain of the paper's
    /// definition, to compare with the paper's eq. (11) and with the simulated A1/β.
    fn exact_a1(
        experiment: &Experiment,
        parameter: Parameter,
        range: &ParameterRange,
    ) -> Result<TheoryCurve> {
        let xs = abscissae(range.from(), range.to(), range.steps());
        let base = experiment.params_with(&[(parameter, range.from())])?;
        Ok(theory_curve(
            TheoryKind::Exact,
            TheoryQuantity::Gain1,
            &base,
            parameter,
            &xs,
        ))
    }

    pub(crate) fn new(
        experiment: &Experiment,
        parameter: Parameter,
        range: &ParameterRange,
    ) -> Result<Self> {
        let xs = abscissae(range.from(), range.to(), range.steps());
        let base = experiment.params_with(&[(parameter, range.from())])?;
        // The simulated gain is the peak over β; on a sliding orbit that is the exact orbit's
        // peak/β (not its A1/β). The paper's gain is its A1/β, eq. (11).
        let curve = |theory, quantity| theory_curve(theory, quantity, &base, parameter, &xs);
        Ok(Self {
            paper: curve(TheoryKind::Paper, TheoryQuantity::Gain1),
            prefix: match experiment.diode_model() {
                DiodeModel::Pwl => "",
                DiodeModel::Shockley => "PWL theory: ",
            },
        })
    }
}

/// The plot of a sweep: the gain of the fundamental G1 = A1/β (the paper's definition) of the
/// simulated steady states, of the paper's eq. (11) and of the exact sliding orbit: one
/// definition for all three. (The CSV also has the gain G = (y_max − y_min)/(2β).)
fn plot(
    points: &[Row],
    parameter: Parameter,
    theory: &Theory,
    exact_a1: &stickslip::theory::curves::TheoryCurve,
    path: &std::path::Path,
) -> Result<()> {
    let gain = |p: &Row| p.a1 / p.params.beta;
    let leg = |which: SweepLeg| -> Vec<(f64, f64)> {
        points
            .iter()
            .filter(|p| p.leg == which)
            .map(|p| (p.value, gain(p)))
            .collect()
    };
    let stick = |which: SweepLeg| -> Vec<(f64, f64)> {
        points
            .iter()
            .filter(|p| p.leg == which && p.stops > 0)
            .map(|p| (p.value, gain(p)))
            .collect()
    };
    let title = match points.first().map(|p| p.params) {
        Some(p) => {
            let fixed: Vec<String> = Parameter::ALL
                .into_iter()
                .filter(|&q| {
                    q != parameter && q.is_set_in(&p) && (q != Parameter::MuS || p.mu_s != 1.0)
                })
                .map(|q| format!("{} = {:.3}", crate::diagrams::symbol(q), q.get(&p)))
                .collect();
            format!(
                "gain against {} at {}",
                crate::diagrams::symbol(parameter),
                fixed.join(", ")
            )
        }
        None => "gain".into(),
    };
    let mut series = Vec::new();
    // Up solid, down dashed, in the colours of the sweep's legs; the steps with stops marked
    // as everywhere: up filled dots, down open squares.
    for (which, color, style, label) in [
        (
            SweepLeg::Up,
            Quantity::SweepUp.color(),
            Style::Line(2),
            "sweep up",
        ),
        (
            SweepLeg::Down,
            Quantity::SweepDown.color(),
            Style::Dashed(2),
            "sweep down",
        ),
    ] {
        let data = leg(which);
        if !data.is_empty() {
            series.push(Series::new(label, data, color, style));
        }
    }
    series.push(Quantity::SweepDown.series("with stops (down)", stick(SweepLeg::Down)));
    series.push(Quantity::SweepUp.series("with stops (up)", stick(SweepLeg::Up)));
    let prefix = theory.prefix;
    if theory.paper.present() > 0 {
        series.push(Quantity::PaperTheory.series(
            format!("{prefix}paper, eq. (11): G1"),
            theory.paper.points(),
        ));
    }
    if exact_a1.present() > 0 {
        series.push(Quantity::ExactTheory.series(
            format!("{prefix}exact sliding orbit: G1"),
            exact_a1.points(),
        ));
    }
    let panel = Panel {
        title,
        x_label: parameter.label().into(),
        y_label: "G1 = A1/β (gain of the fundamental)".into(),
        series,
        legend: Some(Legend::Best),
        ..Default::default()
    };
    Figure::single(panel, (900, 560)).render(path)
}

/// The plot of a self-excited belt's sweep: the amplitude (y_max − y_min)/2 against the swept
/// parameter, up and down (where they differ, two motions coexist), the steps with stops
/// marked.
fn plot_self_excited(report: &SweepReport, path: &std::path::Path) -> Result<()> {
    let leg = |which: SweepLeg, stuck: bool| -> Vec<(f64, f64)> {
        report
            .points
            .iter()
            .filter(|p| p.direction == which && (!stuck || p.stick_fraction > Some(0.0)))
            .filter_map(|p| p.amplitude.map(|a| (p.value, a)))
            .collect()
    };
    let mut series = Vec::new();
    for (which, color, style, label) in [
        (
            SweepLeg::Up,
            Quantity::SweepUp.color(),
            Style::Line(2),
            "sweep up",
        ),
        (
            SweepLeg::Down,
            Quantity::SweepDown.color(),
            Style::Dashed(2),
            "sweep down",
        ),
    ] {
        let data = leg(which, false);
        if !data.is_empty() {
            series.push(Series::new(label, data, color, style));
        }
    }
    series.push(Quantity::SweepDown.series("with stops (down)", leg(SweepLeg::Down, true)));
    series.push(Quantity::SweepUp.series("with stops (up)", leg(SweepLeg::Up, true)));
    let symbol = crate::diagrams::symbol(report.over);
    let panel = Panel {
        title: format!("self-excited motion: amplitude against {symbol}"),
        x_label: report.over.label().into(),
        y_label: "amplitude (y_max − y_min)/2".into(),
        series,
        legend: Some(Legend::Best),
        ..Default::default()
    };
    Figure::single(panel, (900, 560)).render(path)
}
