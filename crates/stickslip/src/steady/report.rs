//! A steady state as a flat record of numbers: what `stickslip steady --json` prints, what
//! the Python package's `steady(...).to_dict()` and the lab's `/api/steady` return.

use super::state::SteadyState;
use serde::Serialize;

/// The numbers of a [`SteadyState`], dimensionless (y in units of the friction force over the
/// stiffness; phases in radians). A motion that did not repeat and was measured
/// ([`SteadyState::lyapunov`]) has the keys of its largest Lyapunov exponent too; a motion
/// that repeats has none of them.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct SteadyReport {
    /// Motion class label: `sliding`, `periodic-stick`, `undecided`, `static` or `chaotic`.
    pub class: &'static str,
    /// Period in drive periods (`None`: none found within the cap).
    pub period: Option<usize>,
    /// Stops of non-zero duration per drive period.
    pub stops_per_period: f64,
    /// Whether the cycle is mapped onto itself by (y, y', τ) → (−y, −y', τ + T/2).
    pub symmetric: bool,
    /// Largest |y|.
    pub peak: f64,
    /// Gain G = (y_max − y_min)/(2β) (`None` where it is infinite: β = 0 with motion).
    pub gain: Option<f64>,
    /// Gain of the fundamental G1 = A1/β (`None` without a spectrum, or at β = 0).
    pub gain1: Option<f64>,
    /// Lag of the fundamental behind the drive (radians), from the spectrum.
    pub phase_lag: Option<f64>,
    /// Amplitudes A_1, A_2, … of the drive harmonics of y.
    pub harmonics: Vec<f64>,
    /// Phases θ_1, θ_2, … of the drive harmonics of y (radians).
    pub harmonic_phases: Vec<f64>,
    /// Amplitudes k·w·A_k of the harmonics of y' (the current or velocity, dimensionless).
    pub current_harmonics: Vec<f64>,
    /// Largest amplitude at a frequency that is not a multiple of the drive's.
    pub subharmonic: Option<f64>,
    /// Mean of y over the recorded periods.
    pub mean: Option<f64>,
    /// Drive periods run before the cycle was recognised.
    pub periods_to_settle: usize,
    /// Samples per drive period of the spectrum.
    pub samples_per_period: Option<usize>,
    /// Drive frequency w.
    pub w: f64,
    /// Drive amplitude β.
    pub beta: f64,
    /// Damping ratio ζ (ζ_R with Shockley diodes).
    pub zeta: f64,
    /// Static-to-kinetic friction ratio μs.
    pub mu_s: f64,
    /// Largest Lyapunov exponent λ1 per unit τ (motions that do not repeat only).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub lambda1: Option<f64>,
    /// Its standard error per unit τ.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub lambda1_error: Option<f64>,
    /// λ1 per drive period.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub lambda1_per_period: Option<f64>,
    /// Its standard error per drive period.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub lambda1_error_per_period: Option<f64>,
    /// Drive periods over which λ1 was measured.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub lambda1_periods: Option<usize>,
    /// Whether the two halves of the measurement of λ1 agree.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub lambda1_converged: Option<bool>,
    /// What the exponent says: `chaotic`, `quasi-periodic`, `contracting` or `undecided`
    /// ([`crate::stability::NonperiodicVerdict`]).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub verdict: Option<&'static str>,
    /// Largest y over the recorded cycle (periods).
    pub y_max: f64,
    /// Smallest y over the recorded cycle (periods).
    pub y_min: f64,
    /// Belt speed vb (a belt only).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub vb: Option<f64>,
    /// The friction law's name (a law other than Coulomb's only).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub friction_law: Option<&'static str>,
    /// The period of a self-excited cycle in τ (a belt without a drive; null for steady
    /// sliding).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub cycle_period_tau: Option<Option<f64>>,
    /// The fraction of the self-excited cycle stuck to the belt.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub stick_fraction: Option<f64>,
    /// The section a self-excited cycle was found at: `stick-onset`, `reversal` or
    /// `turning-point` (null for steady sliding).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub section: Option<Option<&'static str>>,
    /// The position y_e = sgn(vb)·μ(|vb|) of steady sliding (a belt without a drive).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub sliding_y: Option<f64>,
    /// The damping 2ζ + μ'(|vb|) of small oscillations about steady sliding.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub sliding_damping: Option<f64>,
    /// Whether steady sliding is `stable`, `unstable` or `neutral`.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub sliding_stability: Option<&'static str>,
}

impl From<&SteadyState> for SteadyReport {
    fn from(steady: &SteadyState) -> Self {
        let spectrum = steady.spectrum.as_ref();
        let p = &steady.params;
        let lyapunov = steady.lyapunov.as_ref();
        let cycle = steady.self_excited.as_ref();
        let of = |f: fn(&super::Harmonic) -> f64| -> Vec<f64> {
            spectrum
                .map(|s| s.harmonics.iter().map(f).collect())
                .unwrap_or_default()
        };
        Self {
            class: steady.class.label(),
            period: steady.period,
            stops_per_period: steady.stops_per_period,
            symmetric: steady.symmetric,
            peak: steady.peak,
            gain: steady.gain.is_finite().then_some(steady.gain),
            gain1: steady.gain1(),
            phase_lag: steady.phase_lag(),
            harmonics: of(|h| h.amplitude),
            harmonic_phases: of(|h| h.phase),
            current_harmonics: spectrum
                .map(|s| s.derivative(p.w).iter().map(|h| h.amplitude).collect())
                .unwrap_or_default(),
            subharmonic: spectrum.map(|s| s.subharmonic),
            mean: spectrum.map(|s| s.mean),
            periods_to_settle: steady.periods_to_settle,
            samples_per_period: spectrum.map(|s| s.samples_per_period),
            w: p.w,
            beta: p.beta,
            zeta: p.zeta,
            mu_s: p.mu_s,
            lambda1: lyapunov.map(|l| l.exponents.largest.per_tau),
            lambda1_error: lyapunov.map(|l| l.exponents.largest.error_per_tau),
            lambda1_per_period: lyapunov.map(|l| l.exponents.largest.per_period),
            lambda1_error_per_period: lyapunov.map(|l| l.exponents.largest.error_per_period),
            lambda1_periods: lyapunov.map(|l| l.exponents.periods),
            lambda1_converged: lyapunov.map(|l| l.exponents.converged),
            verdict: lyapunov.map(|l| l.verdict.label()),
            y_max: steady.y_max,
            y_min: steady.y_min,
            vb: (p.vb != 0.0).then_some(p.vb),
            friction_law: (!p.law.is_coulomb()).then(|| p.law.kind().label()),
            cycle_period_tau: cycle.map(|c| c.period),
            stick_fraction: cycle.map(|c| c.stick_fraction),
            section: cycle.map(|c| c.section.map(|s| s.label())),
            sliding_y: cycle.map(|c| c.equilibrium),
            sliding_damping: cycle.map(|c| c.sliding_damping),
            sliding_stability: cycle.map(|c| c.sliding_stability.label()),
        }
    }
}
