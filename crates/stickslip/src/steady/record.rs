//! Recording one cycle from the strobe the solver stands at.
//!
//! **Recording.** Then p whole periods (or `max_period` periods for a non-periodic motion) are
//! recorded: the exact event log, the states at every strobe and half-period, and optionally
//! N samples per period of the dense output for the [`Spectrum`]. Extremes of y are exact:
//! y has its extremes where y' = 0, that is at events, which the log holds with their exact y.
//! The solver is advanced to the same half-period and period ends with or without the samples,
//! which are read from the dense output of the intervals it advances through, and the
//! extremes are taken from the events and strobes alone: the record, and with it the class,
//! period, stops, symmetry and gain, does not depend on [`SteadyOptions::spectrum`].
//!
//! **Symmetry.** The equation is unchanged by (y, y', τ) → (−y, −y', τ + T/2), so a cycle is
//! symmetric when the state half a period after a strobe is minus the state at some strobe of
//! the cycle. Symmetric motions have no even harmonics.
//!
//! **Samples for the spectrum.** Between events y is smooth but y'' jumps at every event (by 2
//! at a turn), so the Fourier amplitudes of y fall off like J/(πk³) with J the sum of the jumps
//! of d²y/dθ² (θ = wτ) over a period, and aliasing with N samples per period perturbs the low
//! harmonics by about 0.8·J/N³. By default N is the smallest power of two (512 to 65536) that
//! makes this 10⁻¹⁰·scale, with J bounded from the events of the cycle by (1 + μs)/w² per event.

use super::classify::classify;
use super::cycle::{strobe, Settled};
use super::extremes::velocity_zeros;
use super::options::SteadyOptions;
use super::spectrum::Spectrum;
use super::state::SteadyState;
use crate::error::Result;
use crate::params::Params;
use crate::solver::{run_steps, Event, Phase, Sample, Solver};

/// Samples per period for an aliasing error of the low harmonics below 1e-10·scale, from the
/// number of events per period (see the module documentation).
fn auto_samples(events_per_period: f64, params: &Params, harmonics: usize, scale: f64) -> usize {
    let jumps = events_per_period.max(2.0) * (1.0 + params.mu_s) / (params.w * params.w);
    let needed = harmonics as f64 + (0.8 * jumps / (1e-10 * scale)).cbrt();
    (needed.ceil() as usize)
        .next_power_of_two()
        .clamp(512, 1 << 16)
}

/// Record one cycle (or `max_period` periods) from the strobe the solver stands at.
pub(super) fn record<S: Solver + ?Sized>(
    solver: &mut S,
    params: &Params,
    options: &SteadyOptions,
    settled: &Settled,
) -> Result<SteadyState> {
    let period = params.drive_period();
    let found = settled.found;
    let scale = settled.scale;
    let start_index = settled.strobe_index;
    let recorded = found.unwrap_or(options.max_period);
    let start = strobe(start_index, period);
    let stuck_at_start = solver.phase() == Phase::Stick;

    // (Room for the events the settling saw a period, and a few more.)
    let mut events =
        Vec::with_capacity(((settled.events_per_period * recorded as f64) as usize).min(4096) + 8);
    let mut strobes = Vec::with_capacity(recorded + 1);
    strobes.push(solver.state());
    let mut half_strobes = Vec::with_capacity(recorded);
    // The samples of the spectrum, if asked for, are read from the dense output of the
    // intervals the solver advances through anyway: the solver is advanced to the same
    // half-period and period ends with or without them, so the events, strobes and extremes
    // (and with them the class, gain, stops and symmetry) do not depend on the spectrum, and
    // a map's point (which has none) equals the steady state of the same point.
    let samples = options.spectrum.then(|| {
        options.samples_per_period.unwrap_or_else(|| {
            auto_samples(settled.events_per_period, params, options.harmonics, scale)
        })
    });
    let times: Vec<f64> = samples.map_or_else(Vec::new, |n| {
        let base = start_index * n as u64;
        (0..(recorded * n) as u64)
            .map(|j| (base + j) as f64 / n as f64 * period)
            .collect()
    });
    let mut trace = Vec::with_capacity(times.len());
    let mut next = 0;
    while next < times.len() && times[next] <= solver.time() {
        let s = solver.state();
        trace.push(Sample {
            tau: times[next],
            y: s.y,
            v: s.v,
            phase: solver.phase(),
        });
        next += 1;
    }
    // On a belt y also turns inside slides (where y' = 0, which is no event): those extremes
    // are found in the dense output of each stretch (`super::extremes`).
    let belt = params.vb != 0.0;
    let spacing = 0.2 * params.w.recip().min(1.0);
    let mut inner = (f64::INFINITY, f64::NEG_INFINITY);
    let mut run_to = |solver: &mut S, t_end: f64, events: &mut Vec<Event>| -> Result<()> {
        run_steps(solver, t_end, |solver, event| {
            events.extend(event.copied());
            if belt {
                velocity_zeros(solver, spacing, |s, _| {
                    inner = (inner.0.min(s.y), inner.1.max(s.y));
                });
            }
            let to = solver.interval().1;
            while next < times.len() && times[next] <= to {
                trace.push(solver.dense(times[next]));
                next += 1;
            }
        })
    };
    for j in 0..recorded as u64 {
        let half = (2 * (start_index + j) + 1) as f64 / 2.0 * period;
        run_to(solver, half, &mut events)?;
        half_strobes.push(solver.state());
        run_to(solver, strobe(start_index + j + 1, period), &mut events)?;
        strobes.push(solver.state());
    }
    let spectrum = match samples {
        Some(_) => {
            let y: Vec<f64> = trace.iter().map(|s| s.y).collect();
            Some(Spectrum::from_samples(
                &y,
                recorded,
                options.harmonics,
                params.phi,
            )?)
        }
        None => None,
    };

    let mut y_min = f64::INFINITY;
    let mut y_max = f64::NEG_INFINITY;
    // Extremes of y are where y' = 0, at events (and the record's ends): the samples of the
    // spectrum add nothing, and are left out so that the gain does not depend on them.
    let ys = events
        .iter()
        .map(|e| e.y)
        .chain(strobes.iter().chain(&half_strobes).map(|s| s.y));
    for y in ys {
        y_min = y_min.min(y);
        y_max = y_max.max(y);
    }
    if belt {
        y_min = y_min.min(inner.0);
        y_max = y_max.max(inner.1);
    }
    let amplitude = 0.5 * (y_max - y_min);
    let gain = if params.beta > 0.0 {
        amplitude / params.beta
    } else if amplitude == 0.0 {
        0.0
    } else {
        f64::INFINITY
    };

    // (A belt breaks the symmetry y → −y: it maps vb to −vb.)
    let symmetric = found.is_some() && !belt && {
        let limit = 1e3 * options.tolerance * scale;
        (0..recorded).any(|shift| {
            (0..recorded).all(|j| {
                let h = half_strobes[j];
                let s = strobes[(j + shift) % recorded];
                (h.y + s.y).abs().max((h.v + s.v).abs()) <= limit
            })
        })
    };

    let end = strobe(start_index + recorded as u64, period);
    let c = classify(
        &events,
        start,
        end,
        recorded,
        stuck_at_start,
        found.is_some(),
        amplitude,
        params.beta,
        options.min_stop_fraction * period,
    );
    Ok(SteadyState {
        params: *params,
        class: c.class,
        period: found,
        periods_to_settle: settled.periods_run,
        recorded_periods: recorded,
        stops: c.stops,
        stops_per_period: c.stops_per_period,
        longest_stop: c.longest_stop,
        symmetric,
        y_min,
        y_max,
        peak: y_max.abs().max(y_min.abs()),
        gain,
        start,
        events,
        strobes,
        half_strobes,
        spectrum,
        trace,
        lyapunov: None,
        self_excited: None,
    })
}
