//! Running to the steady state and recording one cycle.
//!
//! **Convergence.** The state is taken once per drive period at τ_k = kT (T = 2π/w), where
//! the drive phase is φ again (the stroboscopic map). The motion has settled on a cycle of
//! period p when |x_k − x_{k−p}| ≤ tol·scale (max norm over y and y') for p + 1 consecutive k,
//! i.e. over a whole cycle and once more; p is the smallest such period up to
//! [`SteadyOptions::max_period`], `scale` is the largest |y| or |y'| of the last strobes, at
//! least 1 (the kinetic friction force). An oscillator stuck for a whole period without an
//! event has x_k = x_{k−1} exactly, so "stuck for ever" (β + |y| ≤ μs) is found after two
//! periods without a special case. Without a period within [`SteadyOptions::max_periods`]
//! the motion is called non-periodic.
//!
//! **Recording.** Then p whole periods (or `max_period` periods for a non-periodic motion) are
//! recorded: the exact event log, the states at every strobe and half-period, and optionally
//! N samples per period of the dense output for the [`Spectrum`]. Extremes of y are exact:
//! y has its extremes where y' = 0, that is at events, which the log holds with their exact y.
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

use super::classify::{classify, MotionClass};
use super::spectrum::Spectrum;
use crate::error::{Error, Result};
use crate::params::{Params, State};
use crate::solver::{run_until, sample_at, Event, Phase, Sample, Solver};
use serde::{Deserialize, Serialize};
use std::collections::VecDeque;

/// How [`steady_state`] decides convergence and what it records.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct SteadyOptions {
    /// Relative tolerance of the stroboscopic map's repetition. Default 1e-10.
    pub tolerance: f64,
    /// Cap on the drive periods run before calling the motion non-periodic. Default 5000.
    pub max_periods: usize,
    /// Longest period p (in drive periods) looked for. Default 16.
    pub max_period: usize,
    /// Shortest stop that counts, as a fraction of the drive period. Default 1e-8 (see
    /// [`super::classify`]).
    pub min_stop_fraction: f64,
    /// Whether to sample the recorded cycle and compute its [`Spectrum`]. Default true.
    pub spectrum: bool,
    /// Samples per drive period for the spectrum, a power of two ≥ 16; `None` (the default)
    /// chooses it from the event log (see the module documentation).
    pub samples_per_period: Option<usize>,
    /// Number of drive harmonics reported. Default 16.
    pub harmonics: usize,
}

impl Default for SteadyOptions {
    fn default() -> Self {
        Self {
            tolerance: 1e-10,
            max_periods: 5000,
            max_period: 16,
            min_stop_fraction: 1e-8,
            spectrum: true,
            samples_per_period: None,
            harmonics: 16,
        }
    }
}

fn invalid(name: &'static str, value: f64, allowed: &'static str) -> Error {
    Error::InvalidParameter {
        name,
        value,
        allowed,
    }
}

impl SteadyOptions {
    /// Set the relative tolerance.
    ///
    /// # Errors
    /// When it is not finite and > 0.
    pub fn with_tolerance(mut self, tolerance: f64) -> Result<Self> {
        self.tolerance = tolerance;
        self.validate()
    }

    /// Set the cap on drive periods.
    ///
    /// # Errors
    /// When it is 0.
    pub fn with_max_periods(mut self, max_periods: usize) -> Result<Self> {
        self.max_periods = max_periods;
        self.validate()
    }

    /// Set the longest period looked for.
    ///
    /// # Errors
    /// When it is 0 or above 64.
    pub fn with_max_period(mut self, max_period: usize) -> Result<Self> {
        self.max_period = max_period;
        self.validate()
    }

    /// Set the shortest stop that counts (fraction of the drive period).
    ///
    /// # Errors
    /// When it is not finite, negative, or 1 or more.
    pub fn with_min_stop_fraction(mut self, fraction: f64) -> Result<Self> {
        self.min_stop_fraction = fraction;
        self.validate()
    }

    /// Compute the spectrum or not.
    pub fn with_spectrum(mut self, spectrum: bool) -> Self {
        self.spectrum = spectrum;
        self
    }

    /// Set the samples per period of the spectrum (`None`: automatic).
    ///
    /// # Errors
    /// When it is not a power of two from 16 to 2²⁰.
    pub fn with_samples_per_period(mut self, samples: Option<usize>) -> Result<Self> {
        self.samples_per_period = samples;
        self.validate()
    }

    /// Set the number of harmonics reported.
    ///
    /// # Errors
    /// When it is 0.
    pub fn with_harmonics(mut self, harmonics: usize) -> Result<Self> {
        self.harmonics = harmonics;
        self.validate()
    }

    /// Check every field.
    ///
    /// # Errors
    /// [`Error::InvalidParameter`] naming the first bad field.
    pub fn validate(self) -> Result<Self> {
        if !(self.tolerance > 0.0 && self.tolerance.is_finite()) {
            return Err(invalid(
                "tolerance",
                self.tolerance,
                "must be finite and > 0",
            ));
        }
        if self.max_periods == 0 {
            return Err(invalid("max_periods", 0.0, "must be at least 1"));
        }
        if self.max_period == 0 || self.max_period > 64 {
            return Err(invalid(
                "max_period",
                self.max_period as f64,
                "must be from 1 to 64",
            ));
        }
        if !(self.min_stop_fraction >= 0.0 && self.min_stop_fraction < 1.0) {
            return Err(invalid(
                "min_stop_fraction",
                self.min_stop_fraction,
                "must be >= 0 and < 1",
            ));
        }
        if let Some(n) = self.samples_per_period {
            if !(16..=1 << 20).contains(&n) || !n.is_power_of_two() {
                return Err(invalid(
                    "samples_per_period",
                    n as f64,
                    "must be a power of two from 16 to 1048576",
                ));
            }
        }
        if self.harmonics == 0 {
            return Err(invalid("harmonics", 0.0, "must be at least 1"));
        }
        Ok(self)
    }
}

/// The steady motion found by [`steady_state`].
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct SteadyState {
    /// Motion class, from the event log of the recorded cycle.
    pub class: MotionClass,
    /// Period p in drive periods, `None` when no period ≤ `max_period` was found.
    pub period: Option<usize>,
    /// Drive periods run before the cycle was recognised (the cap when it was not).
    pub periods_to_settle: usize,
    /// Drive periods recorded: p, or `max_period` for a non-periodic motion.
    pub recorded_periods: usize,
    /// Stops of non-zero duration in the recorded periods.
    pub stops: usize,
    /// Stops per drive period.
    pub stops_per_period: f64,
    /// Longest stop in the record (dimensionless time; infinite when never moving).
    pub longest_stop: f64,
    /// Whether the cycle is mapped onto itself by (y, y', τ) → (−y, −y', τ + T/2).
    /// Always false for a non-periodic motion.
    pub symmetric: bool,
    /// Smallest y over the recorded periods.
    pub y_min: f64,
    /// Largest y over the recorded periods.
    pub y_max: f64,
    /// Largest |y| over the recorded periods.
    pub peak: f64,
    /// Gain (y_max − y_min)/(2β), the paper's G (0 when β = 0 and nothing moves).
    pub gain: f64,
    /// Time τ at which the record starts (a whole number of drive periods).
    pub start: f64,
    /// Events inside the record, in order.
    pub events: Vec<Event>,
    /// States at the strobes τ = start + jT, j = 0 … recorded periods (the last one is the
    /// final state).
    pub strobes: Vec<State>,
    /// States half a period after each strobe, τ = start + (j + ½)T.
    pub half_strobes: Vec<State>,
    /// Spectrum of y over the record (when requested).
    pub spectrum: Option<Spectrum>,
    /// The samples of the dense output behind the spectrum (empty without it).
    pub trace: Vec<Sample>,
}

impl SteadyState {
    /// Half the peak-to-peak excursion, (y_max − y_min)/2.
    pub fn amplitude(&self) -> f64 {
        0.5 * (self.y_max - self.y_min)
    }

    /// State at the end of the record (a whole number of drive periods after τ = 0, so the
    /// drive phase there is φ).
    pub fn final_state(&self) -> State {
        *self.strobes.last().expect("a record has at least its first strobe")
    }

    /// Lag of the fundamental behind the drive (radians, in (−π, π]), from the spectrum.
    pub fn phase_lag(&self) -> Option<f64> {
        self.spectrum.as_ref().and_then(Spectrum::phase_lag)
    }

    /// Amplitude of the k-th drive harmonic of y, from the spectrum.
    pub fn harmonic(&self, k: usize) -> Option<f64> {
        self.spectrum.as_ref().and_then(|s| s.amplitude(k))
    }

    /// The oscilloscope's X-Y picture: (drive, y) at every sample of the trace.
    pub fn xy(&self, params: &Params) -> Vec<(f64, f64)> {
        self.trace
            .iter()
            .map(|s| (params.drive(s.tau), s.y))
            .collect()
    }
}

/// Largest |component| difference of two states.
fn distance(a: State, b: State) -> f64 {
    (a.y - b.y).abs().max((a.v - b.v).abs())
}

/// Time of strobe k: kT computed in one rounding.
fn strobe(k: u64, period: f64) -> f64 {
    k as f64 * period
}

/// Samples per period for an aliasing error of the low harmonics below 1e-10·scale, from the
/// number of events per period (see the module documentation).
fn auto_samples(events_per_period: f64, params: &Params, harmonics: usize, scale: f64) -> usize {
    let jumps = events_per_period.max(2.0) * (1.0 + params.mu_s) / (params.w * params.w);
    let needed = harmonics as f64 + (0.8 * jumps / (1e-10 * scale)).cbrt();
    (needed.ceil() as usize)
        .next_power_of_two()
        .clamp(512, 1 << 16)
}

/// Run `solver` to its steady state and record one cycle.
///
/// `params` must be the parameters the solver was built with (the drive frequency and phase
/// define the strobes; β the static threshold). The solver may start at any time; strobes are
/// at whole multiples of the drive period. Afterwards the solver stands at the end of the
/// record.
///
/// ```
/// use stickslip::steady::{steady_state, MotionClass, SteadyOptions};
/// use stickslip::{ExactSolver, Params, State};
/// let params = Params::new(0.0468, 0.9, 1.6).unwrap();
/// let mut solver = ExactSolver::new(params, State::default());
/// let steady = steady_state(&mut solver, &params, &SteadyOptions::default()).unwrap();
/// assert_eq!(steady.class, MotionClass::Sliding);
/// assert_eq!(steady.period, Some(1));
/// assert!(steady.symmetric);
/// ```
///
/// # Errors
/// [`Error::InvalidParameter`] for invalid options; whatever the solver reports.
pub fn steady_state<S: Solver + ?Sized>(
    solver: &mut S,
    params: &Params,
    options: &SteadyOptions,
) -> Result<SteadyState> {
    let options = options.validate()?;
    let period = params.drive_period();
    let max_period = options.max_period;

    // First strobe at or after the solver's time.
    let mut k = (solver.time() / period).ceil().max(0.0) as u64;
    if strobe(k, period) < solver.time() {
        k += 1;
    }
    run_until(solver, strobe(k, period), |_| {})?;

    let mut history: VecDeque<State> = VecDeque::with_capacity(max_period + 1);
    history.push_back(solver.state());
    // Consecutive strobes at which x_k matched x_{k−p}, per lag p.
    let mut passes = vec![0usize; max_period + 1];
    // Events of the last `max_period` periods, with the index of the period they fell in.
    let mut recent: VecDeque<(usize, Event)> = VecDeque::new();
    let mut found = None;
    let mut periods_run = 0;
    let mut scale = 1.0f64;
    for n in 1..=options.max_periods {
        run_until(solver, strobe(k + n as u64, period), |e| {
            recent.push_back((n, *e))
        })?;
        while recent.front().is_some_and(|(m, _)| *m + max_period <= n) {
            recent.pop_front();
        }
        periods_run = n;
        let x = solver.state();
        scale = history
            .iter()
            .fold(1.0f64, |s, h| s.max(h.y.abs()).max(h.v.abs()))
            .max(x.y.abs())
            .max(x.v.abs());
        let limit = options.tolerance * scale;
        for (lag, pass) in passes.iter_mut().enumerate().skip(1) {
            if lag > history.len() {
                break;
            }
            if distance(x, history[history.len() - lag]) <= limit {
                *pass += 1;
            } else {
                *pass = 0;
            }
        }
        history.push_back(x);
        if history.len() > max_period {
            history.pop_front();
        }
        if let Some(p) = (1..=max_period).find(|&p| passes[p] > p) {
            found = Some(p);
            break;
        }
    }
    let start_index = k + periods_run as u64;
    let recorded = found.unwrap_or(max_period);
    let start = strobe(start_index, period);
    let stuck_at_start = solver.phase() == Phase::Stick;

    let mut events = Vec::new();
    let mut strobes = vec![solver.state()];
    let mut half_strobes = Vec::with_capacity(recorded);
    let mut trace = Vec::new();
    let mut spectrum = None;
    if options.spectrum {
        let n = options.samples_per_period.unwrap_or_else(|| {
            let last = recent
                .iter()
                .filter(|(m, _)| *m + recorded > periods_run)
                .count();
            auto_samples(
                last as f64 / recorded as f64,
                params,
                options.harmonics,
                scale,
            )
        });
        let base = start_index * n as u64;
        let times: Vec<f64> = (0..(recorded * n) as u64)
            .map(|j| (base + j) as f64 / n as f64 * period)
            .collect();
        trace = sample_at(solver, &times, |e| events.push(*e))?;
        run_until(solver, strobe(start_index + recorded as u64, period), |e| {
            events.push(*e)
        })?;
        for j in 0..recorded {
            let at = |i: usize| State {
                y: trace[i].y,
                v: trace[i].v,
            };
            if j > 0 {
                strobes.push(at(j * n));
            }
            half_strobes.push(at(j * n + n / 2));
        }
        strobes.push(solver.state());
        let y: Vec<f64> = trace.iter().map(|s| s.y).collect();
        spectrum = Some(Spectrum::from_samples(
            &y,
            recorded,
            options.harmonics,
            params.phi,
        )?);
    } else {
        for j in 0..recorded as u64 {
            let half = (2 * (start_index + j) + 1) as f64 / 2.0 * period;
            run_until(solver, half, |e| events.push(*e))?;
            half_strobes.push(solver.state());
            run_until(solver, strobe(start_index + j + 1, period), |e| {
                events.push(*e)
            })?;
            strobes.push(solver.state());
        }
    }

    let mut y_min = f64::INFINITY;
    let mut y_max = f64::NEG_INFINITY;
    let ys = events
        .iter()
        .map(|e| e.y)
        .chain(strobes.iter().chain(&half_strobes).map(|s| s.y))
        .chain(trace.iter().map(|s| s.y));
    for y in ys {
        y_min = y_min.min(y);
        y_max = y_max.max(y);
    }
    let amplitude = 0.5 * (y_max - y_min);
    let gain = if params.beta > 0.0 {
        amplitude / params.beta
    } else if amplitude == 0.0 {
        0.0
    } else {
        f64::INFINITY
    };

    let symmetric = found.is_some() && {
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
        class: c.class,
        period: found,
        periods_to_settle: periods_run,
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
    })
}
