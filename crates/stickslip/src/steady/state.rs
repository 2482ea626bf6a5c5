//! The steady motion found by the steady-state search ([`SteadyState`]): its class, period,
//! extremes, record of events and strobes, and spectrum.

use super::classify::MotionClass;
use super::self_excited::SelfExcited;
use super::spectrum::Spectrum;
use crate::params::{Params, State};
use crate::solver::{Event, Sample};
use crate::stability::NonperiodicClassification;
use serde::{Deserialize, Serialize};

/// The steady motion found by [`steady_state`](super::steady_state).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct SteadyState {
    /// The parameters of the motion.
    pub params: Params,
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
    /// Gain G = (y_max − y_min)/(2β), the paper's G of its Table 1 (0 when β = 0 and nothing
    /// moves); [`SteadyState::gain1`] is the gain of the fundamental.
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
    /// The Lyapunov exponents of a motion that did not repeat, measured from the final state
    /// ([`SteadyOptions::lyapunov`](super::SteadyOptions::lyapunov)), and what they say; `None` for a motion that repeats,
    /// with a solver other than the exact one, without the option, or when the measurement
    /// met a tangential release (where the flow has no derivative).
    pub lyapunov: Option<NonperiodicClassification>,
    /// What a self-excited motion (on a moving belt without a drive) settled on: its own
    /// period, stick fraction and the stability of steady sliding
    /// ([`super::self_excited`]); `None` for a driven motion.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub self_excited: Option<SelfExcited>,
}

impl SteadyState {
    /// Half the peak-to-peak excursion, (y_max − y_min)/2.
    pub fn amplitude(&self) -> f64 {
        0.5 * (self.y_max - self.y_min)
    }

    /// State at the end of the record (a whole number of drive periods after τ = 0, so the
    /// drive phase there is φ).
    pub fn final_state(&self) -> State {
        *self
            .strobes
            .last()
            .expect("a record has at least its first strobe")
    }

    /// Lag of the fundamental behind the drive (radians, in (−π, π]), from the spectrum.
    pub fn phase_lag(&self) -> Option<f64> {
        self.spectrum.as_ref().and_then(Spectrum::phase_lag)
    }

    /// Amplitude of the k-th drive harmonic of y, from the spectrum.
    pub fn harmonic(&self, k: usize) -> Option<f64> {
        self.spectrum.as_ref().and_then(|s| s.amplitude(k))
    }

    /// The gain of the fundamental G1 = A1/β (`None` without a spectrum, or at β = 0): the
    /// gain the paper's formula (its eq. 11) gives. [`SteadyState::gain`] is the gain
    /// G = (y_max − y_min)/(2β); the two agree for a sinusoidal motion only.
    pub fn gain1(&self) -> Option<f64> {
        let beta = self.params.beta;
        self.harmonic(1).filter(|_| beta > 0.0).map(|a1| a1 / beta)
    }

    /// The oscilloscope's X-Y picture: (drive, y) at every sample of the trace.
    pub fn xy(&self) -> Vec<(f64, f64)> {
        self.trace
            .iter()
            .map(|s| (self.params.drive(s.tau), s.y))
            .collect()
    }
}
