//! The stickslip side of the benchmark harness (`bench/run`): runs one workload and prints
//! one JSON document on standard output.
//!
//! ```text
//! bench_workloads trajectory --w 0.9 --beta 1.6 --periods 300 --samples-per-period 20
//! bench_workloads phase-diagram --w-steps 40 --beta-steps 40
//! bench_workloads shockley --w 0.95 --beta 2.14 --periods 300 --rtol 1e-6
//! ```
//!
//! Wall times are measured inside the process with `std::time::Instant` around the solver
//! calls only; a short workload is repeated until it has run for `--min-seconds` (and at least
//! `--min-repeats` times), and the minimum and median of the repetitions are reported.
//! Work counters come from `Solver::stats()` (summed over a scan's solvers by the
//! experiment's `Cancel` token).

use anyhow::{Context, Result};
use clap::{Parser, Subcommand};
use rayon::prelude::*;
use serde_json::{json, Value};
use std::time::Instant;
use stickslip::cancel::Cancel;
use stickslip::scan::{Axis, Grid, ParameterRange};
use stickslip::shockley::{self, NetlistOptions, ShockleyModel, ShockleyOptions, ShockleySolver};
use stickslip::solver::{grid, run_until, sample_at};
use stickslip::steady::SteadyOptions;
use stickslip::{
    Circuit, Event, EventKind, ExactSolver, Experiment, Parameter, Params, Phase, Sample, Solver,
    State, Stats,
};

#[derive(Debug, Parser)]
#[command(about = "Benchmark workloads of stickslip, printed as JSON")]
struct Cli {
    #[command(subcommand)]
    workload: Workload,
}

#[derive(Debug, Subcommand)]
enum Workload {
    /// One trajectory from rest, sampled on a grid (workload (a)).
    Trajectory(TrajectoryArgs),
    /// Motion classes on a (w, β) grid, every point from rest (workload (b)).
    PhaseDiagram(PhaseDiagramArgs),
    /// The paper's circuit with Shockley diodes, the last period sampled (workload (c)).
    Shockley(ShockleyArgs),
    /// The same circuit as an ngspice netlist from `stickslip::shockley::netlist` (default
    /// options, output by `wrdata` to `out.txt`), printed as JSON {"netlist": text}.
    Netlist(NetlistArgs),
}

#[derive(Debug, clap::Args)]
struct NetlistArgs {
    /// Drive frequency w.
    #[arg(long)]
    w: f64,
    /// Drive amplitude β = U/0.7 V.
    #[arg(long)]
    beta: f64,
    /// Drive periods.
    #[arg(long, default_value_t = 300.0)]
    periods: f64,
}

#[derive(Debug, clap::Args)]
struct Timing {
    /// Repeat until the repetitions add up to this many seconds.
    #[arg(long, default_value_t = 0.5)]
    min_seconds: f64,
    /// Repeat at least this many times.
    #[arg(long, default_value_t = 3)]
    min_repeats: usize,
    /// Repeat at most this many times.
    #[arg(long, default_value_t = 1000)]
    max_repeats: usize,
}

#[derive(Debug, clap::Args)]
struct TrajectoryArgs {
    /// Damping ratio ζ [default: the paper's circuit].
    #[arg(long)]
    zeta: Option<f64>,
    /// Drive frequency w.
    #[arg(long)]
    w: f64,
    /// Drive amplitude β.
    #[arg(long)]
    beta: f64,
    /// Drive periods to run.
    #[arg(long, default_value_t = 300.0)]
    periods: f64,
    /// Samples of (y, y') per drive period.
    #[arg(long, default_value_t = 20)]
    samples_per_period: usize,
    /// How the samples are taken: `dense` (advance event to event and read the dense output
    /// of each interval) or `sample-at` (the library's `solver::sample_at`, which advances to
    /// every sample time).
    #[arg(long, value_enum, default_value_t = Sampling::Dense)]
    sampling: Sampling,
    /// Also count the events of the last this many periods apart (for classification).
    #[arg(long, default_value_t = 50.0)]
    tail: f64,
    /// Leave the samples out of the output (the counters and final state stay).
    #[arg(long)]
    no_samples: bool,
    #[command(flatten)]
    timing: Timing,
}

/// How a trajectory is sampled.
#[derive(Debug, Clone, Copy, PartialEq, Eq, clap::ValueEnum)]
enum Sampling {
    /// Event to event, samples from the dense output of each interval.
    Dense,
    /// `stickslip::solver::sample_at`: one `advance` per sample time.
    SampleAt,
}

/// How the phase diagram is computed.
#[derive(Debug, Clone, Copy, PartialEq, Eq, clap::ValueEnum)]
enum DiagramMode {
    /// `stickslip::scan::Grid`.
    Steady,
    /// A fixed number of periods per point.
    Fixed,
}

#[derive(Debug, clap::Args)]
struct PhaseDiagramArgs {
    /// Damping ratio ζ [default: the paper's circuit].
    #[arg(long)]
    zeta: Option<f64>,
    /// Smallest drive frequency w.
    #[arg(long, default_value_t = 0.1)]
    w_from: f64,
    /// Largest drive frequency w.
    #[arg(long, default_value_t = 2.5)]
    w_to: f64,
    /// Grid points along w.
    #[arg(long, default_value_t = 40)]
    w_steps: usize,
    /// Smallest drive amplitude β.
    #[arg(long, default_value_t = 0.5)]
    beta_from: f64,
    /// Largest drive amplitude β.
    #[arg(long, default_value_t = 4.0)]
    beta_to: f64,
    /// Grid points along β.
    #[arg(long, default_value_t = 40)]
    beta_steps: usize,
    /// `steady`: the library's `scan::Grid` (each point run until its
    /// stroboscopic map repeats, default `SteadyOptions`); `fixed`: a fixed number of periods
    /// per point, classified from the exact events of the last `--tail` periods (the same
    /// work as the peers do).
    #[arg(long, value_enum, default_value_t = DiagramMode::Steady)]
    mode: DiagramMode,
    /// Drive periods run at every point (`--mode fixed`).
    #[arg(long, default_value_t = 300)]
    periods: usize,
    /// Drive periods at the end in which the motion is classified (`--mode fixed`).
    #[arg(long, default_value_t = 50)]
    tail: usize,
    #[command(flatten)]
    timing: Timing,
}

fn paper_zeta() -> f64 {
    Circuit::paper().scales().zeta()
}

/// Run `work` repeatedly as `timing` asks; returns (min, median, repeats) of the wall times
/// and the last result.
fn timed<T>(timing: &Timing, mut work: impl FnMut() -> Result<T>) -> Result<(Value, T)> {
    let mut times = Vec::new();
    let mut total = 0.0;
    let mut last = None;
    while times.len() < timing.max_repeats.max(1)
        && (times.len() < timing.min_repeats.max(1) || total < timing.min_seconds)
    {
        let start = Instant::now();
        let out = work()?;
        let dt = start.elapsed().as_secs_f64();
        last = Some(out);
        times.push(dt);
        total += dt;
    }
    times.sort_by(f64::total_cmp);
    let median = times[times.len() / 2];
    Ok((
        json!({"min": times[0], "median": median, "repeats": times.len()}),
        last.expect("at least one repetition"),
    ))
}

fn stats_json(s: &Stats) -> Value {
    json!({
        "events": s.events,
        "evaluations": s.evaluations,
        "steps": s.steps,
        "rejected": s.rejected,
    })
}

#[derive(Default, Clone, Copy)]
struct EventCounts {
    turn: u64,
    stick: u64,
    slip: u64,
}

impl EventCounts {
    fn add(&mut self, kind: EventKind) {
        match kind {
            EventKind::Turn => self.turn += 1,
            EventKind::Stick => self.stick += 1,
            EventKind::Slip => self.slip += 1,
        }
    }

    fn json(&self) -> Value {
        json!({"turn": self.turn, "stick": self.stick, "slip": self.slip})
    }
}

/// Samples at the sorted `times` (from τ = 0): advance from event to event up to the last
/// time and read every sample inside each advanced interval from the dense output.
fn sample_dense<S: Solver>(
    solver: &mut S,
    times: &[f64],
    mut on_event: impl FnMut(&Event),
) -> Result<Vec<Sample>> {
    let t_end = *times.last().context("no sample times")?;
    let mut out = Vec::with_capacity(times.len());
    let mut next = times.iter().peekable();
    while next.next_if(|&&t| t <= solver.time()).is_some() {
        let s = solver.state();
        out.push(Sample {
            tau: solver.time(),
            y: s.y,
            v: s.v,
            phase: solver.phase(),
        });
    }
    while solver.time() < t_end {
        if let Some(e) = solver.advance(t_end)? {
            on_event(&e);
        }
        let (_, to) = solver.interval();
        while let Some(&t) = next.next_if(|&&t| t <= to) {
            out.push(solver.dense(t));
        }
    }
    Ok(out)
}

fn trajectory(args: TrajectoryArgs) -> Result<Value> {
    let params = Params::new(args.zeta.unwrap_or_else(paper_zeta), args.w, args.beta)?;
    let t_end = args.periods * params.drive_period();
    let count = (args.periods * args.samples_per_period as f64).round() as usize;
    let tail_start = (args.periods - args.tail).max(0.0) * params.drive_period();
    let (wall, (samples, counts, tail_counts, stats, final_state)) = timed(&args.timing, || {
        let times = grid(0.0, t_end, count);
        let mut solver = ExactSolver::new(params, State::default());
        let mut counts = EventCounts::default();
        let mut tail_counts = EventCounts::default();
        let mut on_event = |e: &Event| {
            counts.add(e.kind);
            if e.tau >= tail_start {
                tail_counts.add(e.kind);
            }
        };
        let samples = match args.sampling {
            Sampling::Dense => sample_dense(&mut solver, &times, &mut on_event)?,
            Sampling::SampleAt => sample_at(&mut solver, &times, &mut on_event)?,
        };
        Ok((samples, counts, tail_counts, solver.stats(), solver.state()))
    })?;
    let mut out = json!({
        "solver": "stickslip-exact",
        "w": params.w,
        "beta": params.beta,
        "zeta": params.zeta,
        "periods": args.periods,
        "samples_per_period": args.samples_per_period,
        "sampling": format!("{:?}", args.sampling).to_lowercase(),
        "wall_s": wall,
        "events": counts.json(),
        "tail_periods": args.tail,
        "tail_events": tail_counts.json(),
        "stats": stats_json(&stats),
        "final": [final_state.y, final_state.v],
    });
    if !args.no_samples {
        out["y"] = samples.iter().map(|s| s.y).collect();
        out["v"] = samples.iter().map(|s| s.v).collect();
    }
    Ok(out)
}

/// Classification of one grid point from the exact event log of its last `tail` periods.
struct PointResult {
    w: f64,
    beta: f64,
    class: &'static str,
    period: Option<usize>,
    events: EventCounts,
    stats: Stats,
}

/// Smallest p ≤ 16 with |x_k − x_{k−p}| ≤ 1e-8·scale for the last p + 1 strobes.
fn strobe_period(strobes: &[State]) -> Option<usize> {
    let scale = strobes
        .iter()
        .map(|s| s.y.abs().max(s.v.abs()))
        .fold(1.0, f64::max);
    let n = strobes.len();
    (1..=16).find(|&p| {
        n > 2 * p + 1
            && (n - p - 1..n).all(|k| {
                let (a, b) = (strobes[k], strobes[k - p]);
                (a.y - b.y).abs().max((a.v - b.v).abs()) <= 1e-8 * scale
            })
    })
}

fn classify_point(params: Params, periods: usize, tail: usize) -> Result<PointResult> {
    let period = params.drive_period();
    let mut solver = ExactSolver::new(params, State::default());
    let start_tail = periods.saturating_sub(tail);
    let mut strobes = Vec::with_capacity(tail + 1);
    let mut counts = EventCounts::default();
    let mut tail_counts = EventCounts::default();
    let (mut y_min, mut y_max) = (f64::INFINITY, f64::NEG_INFINITY);
    for k in 1..=periods {
        let in_tail = k > start_tail;
        run_until(&mut solver, k as f64 * period, |e| {
            counts.add(e.kind);
            if in_tail {
                tail_counts.add(e.kind);
                y_min = y_min.min(e.y);
                y_max = y_max.max(e.y);
            }
        })?;
        if k >= start_tail {
            strobes.push(solver.state());
        }
    }
    let stuck_for_ever = tail_counts.turn + tail_counts.stick + tail_counts.slip == 0
        && solver.phase() == Phase::Stick;
    let amplitude = if y_max >= y_min {
        0.5 * (y_max - y_min)
    } else {
        0.0
    };
    let p = strobe_period(&strobes);
    let class = if stuck_for_ever || amplitude < 0.01 * params.beta {
        "static"
    } else if tail_counts.stick == 0 {
        "sliding"
    } else if p.is_some() {
        "periodic-stick"
    } else {
        "non-periodic-stick"
    };
    Ok(PointResult {
        w: params.w,
        beta: params.beta,
        class,
        period: p,
        events: counts,
        stats: solver.stats(),
    })
}

fn phase_diagram(args: PhaseDiagramArgs) -> Result<Value> {
    match args.mode {
        DiagramMode::Steady => phase_diagram_steady(args),
        DiagramMode::Fixed => phase_diagram_fixed(args),
    }
}

fn phase_diagram_steady(args: PhaseDiagramArgs) -> Result<Value> {
    let zeta = args.zeta.unwrap_or_else(paper_zeta);
    let base = Params::new(zeta, args.w_from, args.beta_from)?;
    let w = ParameterRange::new("w", args.w_from, args.w_to, args.w_steps)?;
    let beta = ParameterRange::new("beta", args.beta_from, args.beta_to, args.beta_steps)?;
    let options = SteadyOptions::default();
    // The experiment's token adds the work counters of every solver the grid makes and drops.
    let mut token = Cancel::new();
    let (wall, points) = timed(&args.timing, || {
        token = Cancel::new();
        let experiment =
            Experiment::dimensionless(base.zeta, base.w, base.beta)?.with_cancel(token.clone());
        Ok(Grid::new(
            &experiment,
            Axis::range(Parameter::W, &w)?,
            Axis::range(Parameter::Beta, &beta)?,
        )?
        .options(options)?
        .run(&())?
        .points)
    })?;
    let points: Vec<Value> = points
        .iter()
        .map(|p| {
            // Periods simulated: to settle, then the recorded cycle (max_period without one).
            let recorded = p.period.unwrap_or(options.max_period);
            json!({
                "w": p.params.w,
                "beta": p.params.beta,
                "class": p.class,
                "period": p.period,
                "periods_run": p.periods_to_settle + recorded,
            })
        })
        .collect();
    Ok(json!({
        "solver": "stickslip-exact",
        "method": "stickslip::scan::Grid with the default SteadyOptions (each point \
                   from rest until its stroboscopic map repeats to 1e-10, at most 5000 periods, \
                   with extrapolation of linear convergence), rayon",
        "threads": rayon::current_num_threads(),
        "zeta": zeta,
        "w_steps": args.w_steps,
        "beta_steps": args.beta_steps,
        "wall_s": wall,
        "stats": stats_json(&token.work()),
        "points": points,
    }))
}

fn phase_diagram_fixed(args: PhaseDiagramArgs) -> Result<Value> {
    let zeta = args.zeta.unwrap_or_else(paper_zeta);
    let value = |from: f64, to: f64, steps: usize, i: usize| {
        if steps == 1 {
            from
        } else {
            from + (to - from) * (i as f64 / (steps - 1) as f64)
        }
    };
    let points: Vec<Params> = (0..args.w_steps * args.beta_steps)
        .map(|i| {
            let w = value(args.w_from, args.w_to, args.w_steps, i / args.beta_steps);
            let beta = value(
                args.beta_from,
                args.beta_to,
                args.beta_steps,
                i % args.beta_steps,
            );
            Params::new(zeta, w, beta).context("grid point")
        })
        .collect::<Result<_>>()?;
    let (wall, results) = timed(&args.timing, || {
        points
            .par_iter()
            .map(|&p| classify_point(p, args.periods, args.tail))
            .collect::<Result<Vec<_>>>()
    })?;
    let mut total = Stats::default();
    for r in &results {
        total.events += r.stats.events;
        total.evaluations += r.stats.evaluations;
        total.steps += r.stats.steps;
        total.rejected += r.stats.rejected;
    }
    let points: Vec<Value> = results
        .iter()
        .map(|r| {
            json!({
                "w": r.w,
                "beta": r.beta,
                "class": r.class,
                "period": r.period,
                "periods_run": args.periods,
                "events": r.events.json(),
            })
        })
        .collect();
    Ok(json!({
        "solver": "stickslip-exact",
        "method": format!(
            "fixed {} periods from rest per point, classified from the exact events of the \
             last {} (own loop over ExactSolver, rayon)",
            args.periods, args.tail
        ),
        "threads": rayon::current_num_threads(),
        "zeta": zeta,
        "w_steps": args.w_steps,
        "beta_steps": args.beta_steps,
        "wall_s": wall,
        "stats": stats_json(&total),
        "points": points,
    }))
}

#[derive(Debug, clap::Args)]
struct ShockleyArgs {
    /// Drive frequency w.
    #[arg(long)]
    w: f64,
    /// Drive amplitude β = U/0.7 V.
    #[arg(long)]
    beta: f64,
    /// Drive periods to run.
    #[arg(long, default_value_t = 300)]
    periods: usize,
    /// Relative tolerance of the stiff solver.
    #[arg(long, default_value_t = 1e-6)]
    rtol: f64,
    /// Absolute tolerance [default: equal to rtol].
    #[arg(long)]
    atol: Option<f64>,
    /// Largest step in τ [default: the library's, `ShockleyOptions::default().max_step`].
    #[arg(long)]
    max_step: Option<f64>,
    /// Samples of the last period, from its dense output.
    #[arg(long, default_value_t = 200)]
    samples: usize,
    #[command(flatten)]
    timing: Timing,
}

/// The paper's circuit with two 1N4148 diodes from rest: run to the last period, then sample
/// it from the dense output.
/// The paper's circuit with 1N4148 diodes, and its dimensionless model at (w, β).
fn paper_shockley(w: f64, beta: f64) -> Result<(Circuit, ShockleyModel)> {
    let circuit = Circuit::paper_shockley();
    let model = circuit
        .shockley_model(&circuit.params(w, beta, 0.0)?)?
        .context("a Shockley circuit has a Shockley model")?;
    Ok((circuit, model))
}

fn shockley(args: ShockleyArgs) -> Result<Value> {
    let (_, model) = paper_shockley(args.w, args.beta)?;
    let mut options = ShockleyOptions::default()
        .with_rtol(args.rtol)?
        .with_atol(args.atol.unwrap_or(args.rtol))?;
    if let Some(h) = args.max_step {
        options = options.with_max_step(h)?;
    }
    let period = model.params.drive_period();
    let start = (args.periods - 1) as f64 * period;
    let times = grid(start, args.periods as f64 * period, args.samples);
    let (wall, (samples, counts, stats, newton)) = timed(&args.timing, || {
        let mut solver = ShockleySolver::new(model, State::default(), options)?;
        let mut counts = EventCounts::default();
        run_until(&mut solver, start, |e| counts.add(e.kind))?;
        let samples = sample_dense(&mut solver, &times, |e| counts.add(e.kind))?;
        Ok((samples, counts, solver.stats(), solver.newton_iterations()))
    })?;
    Ok(json!({
        "solver": "stickslip-shockley",
        "w": args.w,
        "beta": args.beta,
        "periods": args.periods,
        "rtol": options.rtol,
        "atol": options.atol,
        "max_step": options.max_step,
        "wall_s": wall,
        "events": counts.json(),
        "stats": stats_json(&stats),
        "newton_iterations": newton,
        "last_period": {
            "tau": samples.iter().map(|s| s.tau).collect::<Vec<_>>(),
            "y": samples.iter().map(|s| s.y).collect::<Vec<_>>(),
            "v": samples.iter().map(|s| s.v).collect::<Vec<_>>(),
        },
    }))
}

fn spice_netlist(args: NetlistArgs) -> Result<Value> {
    let (circuit, model) = paper_shockley(args.w, args.beta)?;
    let options = NetlistOptions {
        periods: args.periods,
        wrdata: Some("out.txt".into()),
        ..NetlistOptions::default()
    };
    let text = shockley::netlist(&circuit, &model.params, State::default(), &options)?;
    Ok(json!({
        "netlist": text,
        "periods": options.periods,
        "points_per_period": options.points_per_period,
        "max_step_fraction": options.max_step_fraction,
    }))
}

fn main() -> Result<()> {
    let cli = Cli::parse();
    let out = match cli.workload {
        Workload::Trajectory(a) => trajectory(a)?,
        Workload::PhaseDiagram(a) => phase_diagram(a)?,
        Workload::Shockley(a) => shockley(a)?,
        Workload::Netlist(a) => spice_netlist(a)?,
    };
    println!("{out}");
    Ok(())
}
