//! The options of the steady-state search ([`SteadyOptions`]): when the stroboscopic map
//! counts as repeating, how long to look, what to record and how to measure a motion that
//! does not repeat.

use crate::error::Result;
use crate::limits::Caps;
use crate::options::OptionKey;
use crate::stability::LyapunovOptions;
use serde::{Deserialize, Serialize};

/// How [`steady_state`](super::steady_state) decides convergence and what it records.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct SteadyOptions {
    /// Relative tolerance of the stroboscopic map's repetition. Default 1e-10.
    pub tolerance: f64,
    /// Cap on the drive periods run before calling the motion non-periodic. Default 5000.
    pub max_periods: usize,
    /// Longest period p (in drive periods) looked for. Default 16.
    pub max_period: usize,
    /// Shortest stop that counts, as a fraction of the drive period. Default 1e-8 (see
    /// [`super::classify()`]).
    pub min_stop_fraction: f64,
    /// Whether to sample the recorded cycle and compute its [`Spectrum`](super::Spectrum). Default true.
    pub spectrum: bool,
    /// Samples per drive period for the spectrum, a power of two ≥ 16; `None` (the default)
    /// chooses it from the event log (see the documentation of `steady/cycle.rs`).
    pub samples_per_period: Option<usize>,
    /// Number of drive harmonics reported. Default 16.
    pub harmonics: usize,
    /// Whether [`steady_state_from`](super::steady_state_from) (and so sweeps and phase diagrams) may extrapolate the
    /// stroboscopic map to its fixed point and restart there when it converges linearly.
    /// Default true. The cycle is always confirmed by the plain repetition test afterwards.
    pub accelerate: bool,
    /// Whether [`steady_state_from`](super::steady_state_from) (and so every front end's
    /// steady state, sweeps, phase diagrams and basins) may settle the motion by Newton's
    /// method on the stroboscopic map once its strobes contract (the exact solver, or a
    /// smooth law's solver whose factory has its stability tools, such as an experiment's
    /// with Shockley diodes; together with [`SteadyOptions::accelerate`]): the stable fixed
    /// point found is accepted when the trajectory is within its basin by the checks of the
    /// documentation of `steady/newton.rs` (two strobe steps that follow the orbit's
    /// linearisation through the orbit's events), and the cycle is recorded from it. Default true. A map's point and
    /// the steady state of the same point go through the same search with the same options
    /// (the spectrum, which a map does not compute, changes nothing in the record), so they
    /// are equal whichever way the motion settles.
    #[serde(default = "default_newton")]
    pub newton: bool,
    /// How a motion that does not repeat within the cap is measured (by the exact model's
    /// tangent dynamics, or a smooth law's where the factory has them,
    /// [`super::SolverFactory::smooth_dynamics`]; see the documentation of `steady/cycle.rs`):
    /// its Lyapunov exponents from the final state of the record.
    /// `None`: not measured. Default [`SteadyOptions::DEFAULT_LYAPUNOV`]: 100 periods to
    /// align the tangent, 5000 measured in 20 blocks, chaos beyond 4 standard errors.
    pub lyapunov: Option<LyapunovOptions>,
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
            accelerate: true,
            newton: true,
            lyapunov: Some(Self::DEFAULT_LYAPUNOV),
        }
    }
}

/// The default of [`SteadyOptions::newton`] for options saved before it existed (which were
/// settled without it).
fn default_newton() -> bool {
    false
}

impl SteadyOptions {
    /// The default measurement of motions that do not repeat ([`SteadyOptions::lyapunov`]):
    /// the steady-state search has run the transient already, so 100 drive periods align the
    /// tangent, and 5000 periods in 20 blocks give the largest exponent to a few 10⁻⁵ per
    /// unit τ at the chaotic points of the literature (ζ = 0, μs = 3, β = 9), whose exponents
    /// are 2·10⁻³ to 4·10⁻².
    pub const DEFAULT_LYAPUNOV: LyapunovOptions = LyapunovOptions {
        transient_periods: 100,
        periods: 5000,
        blocks: 20,
        significance: 4.0,
        sequential: true,
    };

    /// The measurement of motions that do not repeat, which a map of exponents needs
    /// (`phase-diagram --color lyapunov`, Python's `phase_diagram(lyapunov=True)`).
    ///
    /// # Errors
    /// [`crate::Error::InvalidOption`] naming [`OptionKey::LyapunovPeriods`] when the
    /// measurement is off (0 periods).
    pub fn lyapunov_for_map(&self) -> Result<LyapunovOptions> {
        self.lyapunov.ok_or(crate::Error::InvalidOption {
            option: OptionKey::LyapunovPeriods,
            value: 0.0,
            allowed: crate::options::Allowed::NotOff {
                why: "a map of exponents measures the motions that do not repeat",
            },
        })
    }

    /// Measure motions that do not repeat with these options, or not at all (`None`).
    ///
    /// # Errors
    /// When the options are invalid.
    pub fn with_lyapunov(mut self, lyapunov: Option<LyapunovOptions>) -> Result<Self> {
        self.lyapunov = lyapunov;
        self.validate()
    }

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

    /// Allow extrapolation of the stroboscopic map or not.
    pub fn with_accelerate(mut self, accelerate: bool) -> Self {
        self.accelerate = accelerate;
        self
    }

    /// Allow settling by Newton's method on the stroboscopic map or not
    /// ([`SteadyOptions::newton`]).
    pub fn with_newton(mut self, newton: bool) -> Self {
        self.newton = newton;
        self
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

    /// Check every field against the option table ([`crate::options`]).
    ///
    /// # Errors
    /// [`Error::InvalidOption`](crate::Error::InvalidOption) naming the first bad field.
    pub fn validate(self) -> Result<Self> {
        OptionKey::Tolerance.check(self.tolerance)?;
        OptionKey::MaxPeriods.check_count(self.max_periods)?;
        OptionKey::MaxPeriod.check_count(self.max_period)?;
        OptionKey::MinStopFraction.check(self.min_stop_fraction)?;
        if let Some(n) = self.samples_per_period {
            OptionKey::SpectrumSamples.check_count(n)?;
        }
        OptionKey::Harmonics.check_count(self.harmonics)?;
        if let Some(lyapunov) = self.lyapunov {
            OptionKey::LyapunovPeriods.check_count(lyapunov.periods)?;
            lyapunov.validate()?;
        }
        Ok(self)
    }

    /// Check every field ([`SteadyOptions::validate`]) and that the search stays within
    /// `caps` ([`Caps::check_steady`]).
    ///
    /// # Errors
    /// [`Error::InvalidOption`](crate::Error::InvalidOption) naming the first bad field.
    pub fn validate_within(self, caps: &Caps) -> Result<Self> {
        let options = self.validate()?;
        caps.check_steady(&options)?;
        Ok(options)
    }
}

/// The caps of a steady-state search live beside its options, so that `limits` sits below
/// the steady state.
impl Caps {
    /// Check a steady-state search against the caps (after its own `validate()`).
    ///
    /// # Errors
    /// [`crate::Error::InvalidOption`] with [`crate::options::Allowed::Cap`] naming the first
    /// field over its cap.
    pub fn check_steady(&self, options: &SteadyOptions) -> Result<()> {
        Self::over(
            OptionKey::MaxPeriods,
            options.max_periods as f64,
            1.0,
            self.max_periods as f64,
        )?;
        Self::over(
            OptionKey::MaxPeriod,
            options.max_period as f64,
            1.0,
            self.max_period as f64,
        )?;
        if let Some(n) = options.samples_per_period {
            Self::over(
                OptionKey::SpectrumSamples,
                n as f64,
                16.0,
                self.steady_samples as f64,
            )?;
        }
        Ok(())
    }
}
