//! The ranges of the dimensionless parameters, initial states and run lengths in which the
//! solvers keep their accuracy, and their checks.
//!
//! Every bound follows from one requirement: the rounding of double precision (ε = 2⁻⁵²
//! ≈ 2.2·10⁻¹⁶) must stay below about 10⁻⁶ of what it decides, so that the friction force, the
//! natural period and the drive phase keep their meaning. `docs/limits.md` of the repository
//! derives each bound; in short:
//!
//! | value | range | what breaks outside |
//! |---|---|---|
//! | β, μs, \|y0\|, \|v0\| | β ≤ 10⁹, 1 ≤ μs ≤ 10⁹, \|y0\|, \|v0\| ≤ 10⁹ | the friction force (1) falls below the rounding ε·X of forces and positions of size X: at 10⁹ it is resolved to 2·10⁻⁷ |
//! | ζ | 0 ≤ ζ ≤ 10⁴ | overdamped: the slow mode's velocity (≈ 1/2ζ of the position) is a difference of terms 2ζ times larger; its relative rounding grows like ε·4ζ², 10⁻⁷ at 10⁴ |
//! | w | 10⁻⁵ ≤ w ≤ 10⁵ | below: a drive period holds up to 4/w events, and 5000 periods (the steady-state cap) reach τ = 2³²; above: the careful search resolves every drive period of a slide |
//! | \|φ\| | ≤ 10⁶ | the drive phase wτ + φ is rounded to ε·\|φ\| |
//! | run length | τ ≤ 2³² and w·τ ≤ 2³² | time and drive phase are rounded to ulp(2³²) = 2⁻²⁰ ≈ 10⁻⁶ |
//!
//! Sizes are capped too, so that a mistyped size is refused before any work instead of
//! filling the memory: [`MAX_GRID_POINTS`] points of a map, [`MAX_BASIN_STEPS`] initial states
//! along each axis of a basin map.
//!
//! [`crate::Params`], [`crate::State`] (through [`check_state`]), [`crate::experiment::Key::check`]
//! and the experiment builders enforce the ranges; [`check_horizon`] and [`check_time`] the run
//! length.

use crate::error::{Error, Result};
use crate::options::{Allowed, OptionKey, OrbitOptions, SimulateOptions};
use serde::Serialize;

/// Largest damping ratio ζ.
pub const ZETA_MAX: f64 = 1e4;
/// Smallest drive frequency w = Ω/ω0.
pub const W_MIN: f64 = 1e-5;
/// Largest drive frequency w = Ω/ω0.
pub const W_MAX: f64 = 1e5;
/// Largest drive amplitude β.
pub const BETA_MAX: f64 = 1e9;
/// Largest static-to-kinetic friction ratio μs.
pub const MU_S_MAX: f64 = 1e9;
/// Largest |φ| (radians).
pub const PHI_MAX: f64 = 1e6;
/// Largest |y0| and |v0| of an initial state.
pub const STATE_MAX: f64 = 1e9;
/// Most points of a grid of two parameters ([`crate::scan::Grid`]): 10⁸, a 10⁴ × 10⁴ map
/// (about a day of one core per millisecond a point, and gigabytes of results: a cluster's
/// job). The command-line tool allows 4·10⁶ (2000 × 2000).
pub const MAX_GRID_POINTS: usize = 100_000_000;
/// Most points of a map whose every point is kept in memory (for a plot or a checkpoint):
/// 4·10⁶ (2000 × 2000, about 520 MB); a map streamed to its file is limited by its axes
/// alone ([`MAX_GRID_POINTS`]).
pub const MAX_KEPT_GRID_POINTS: usize = 4_000_000;
/// Most initial states along each axis of a basin map ([`crate::basins::Basins`]): a
/// 2000 × 2000 map, each cell run to its steady state.
pub const MAX_BASIN_STEPS: usize = 2000;
/// Largest time τ, and largest drive phase w·τ, of a run: 2³², where the rounding of a time
/// or a phase is 2⁻²⁰ ≈ 9.5·10⁻⁷.
pub const TAU_MAX: f64 = 4_294_967_296.0;

/// What [`ZETA_MAX`] allows, in words.
pub(crate) const ZETA_ALLOWED: &str = "must be finite and from 0 to 1e4 (docs/limits.md)";
/// What [`W_MIN`] and [`W_MAX`] allow, in words.
pub(crate) const W_ALLOWED: &str = "must be finite and from 1e-5 to 1e5 (docs/limits.md)";
/// What [`BETA_MAX`] allows, in words.
pub(crate) const BETA_ALLOWED: &str = "must be finite and from 0 to 1e9 (docs/limits.md)";
/// What [`MU_S_MAX`] allows, in words.
pub(crate) const MU_S_ALLOWED: &str = "must be finite and from 1 to 1e9 (docs/limits.md)";
/// What [`PHI_MAX`] allows, in words.
pub(crate) const PHI_ALLOWED: &str = "must be finite and from -1e6 to 1e6 (docs/limits.md)";
/// What [`STATE_MAX`] allows, in words.
pub(crate) const STATE_ALLOWED: &str = "must be finite and from -1e9 to 1e9 (docs/limits.md)";

/// Whether ζ is in its range.
pub(crate) fn zeta_ok(zeta: f64) -> bool {
    (0.0..=ZETA_MAX).contains(&zeta)
}

/// Whether w is in its range.
pub(crate) fn w_ok(w: f64) -> bool {
    (W_MIN..=W_MAX).contains(&w)
}

/// Whether β is in its range.
pub(crate) fn beta_ok(beta: f64) -> bool {
    (0.0..=BETA_MAX).contains(&beta)
}

/// Whether μs is in its range.
pub(crate) fn mu_s_ok(mu_s: f64) -> bool {
    (1.0..=MU_S_MAX).contains(&mu_s)
}

/// Whether φ is in its range.
pub(crate) fn phi_ok(phi: f64) -> bool {
    phi.abs() <= PHI_MAX
}

/// Whether a component of an initial state is in its range.
pub(crate) fn state_ok(x: f64) -> bool {
    x.abs() <= STATE_MAX
}

// The checks that take a `Params` or give a `State` live beside them (`crate::params`), so
// that this module sits below the parameters; their old paths stay.
pub use crate::params::{check_horizon, check_state, check_time, max_periods};

/// Caps on the sizes of a request: how much work one request may ask for. The library's
/// own ranges ([`Caps::library`], what the command line and Python allow) and a stricter
/// profile for a server shared by several users ([`Caps::shared_server`], the lab's), which
/// a server serves to its page (the field names are the JSON's).
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Caps {
    /// The profile's name (`library` or `shared-server`); not serialised.
    #[serde(skip)]
    pub profile: &'static str,
    /// Most samples per drive period of a steady cycle's trace or spectrum.
    pub steady_samples: usize,
    /// Longest period looked for by a steady state (drive periods).
    pub max_period: usize,
    /// Most drive periods run to reach a steady state.
    pub max_periods: usize,
    /// Most drive periods of a run from the initial state.
    pub simulate_periods: f64,
    /// Most samples per drive period of a run.
    pub simulate_samples: usize,
    /// Most samples of a run in all.
    pub simulate_total: usize,
    /// Most values of a sweep (each leg).
    pub sweep_steps: usize,
    /// Most values on one side of a map.
    pub map_side: usize,
    /// Most points of a map.
    pub map_points: usize,
    /// Most bytes of a measurement (a scope record's CSV text) sent to a server; the
    /// library itself reads text of any length.
    pub upload_bytes: usize,
}

impl Caps {
    /// The library's ranges ([`crate::options::OptionKey::table`]): what the command line
    /// and Python allow.
    pub const fn library() -> Self {
        Self {
            profile: "library",
            steady_samples: 1 << 20,
            max_period: 64,
            max_periods: 100_000_000,
            simulate_periods: 5e7,
            simulate_samples: 50_000_000,
            simulate_total: 50_000_000,
            sweep_steps: 100_000,
            map_side: 100_000,
            map_points: MAX_GRID_POINTS,
            upload_bytes: usize::MAX,
        }
    }

    /// The profile of a server shared by several users (the lab's caps): every request
    /// answers within seconds.
    pub const fn shared_server() -> Self {
        Self {
            profile: "shared-server",
            steady_samples: 4096,
            max_period: 16,
            max_periods: 5000,
            simulate_periods: 2000.0,
            simulate_samples: 10_000,
            simulate_total: 200_000,
            sweep_steps: 400,
            map_side: 1000,
            map_points: 40_000,
            upload_bytes: 2 * 1024 * 1024,
        }
    }

    /// `value` of `option` from `min` to `max` (the error says so): the cap's own range, so
    /// that a value below the table's range (0 steps, say) is told the cap too, not the
    /// library's larger range.
    pub(crate) fn over(option: OptionKey, value: f64, min: f64, max: f64) -> Result<()> {
        if (min..=max).contains(&value) {
            Ok(())
        } else {
            Err(Error::InvalidOption {
                option,
                value,
                allowed: Allowed::Cap { min, max },
            })
        }
    }

    /// Check the samples per drive period of a steady cycle's trace: within the cap, then a
    /// power of two from the table ([`OptionKey::TraceSamples`]).
    ///
    /// # Errors
    /// [`Error::InvalidOption`] naming [`OptionKey::TraceSamples`].
    pub fn check_trace_samples(&self, samples: usize) -> Result<usize> {
        Self::over(
            OptionKey::TraceSamples,
            samples as f64,
            16.0,
            self.steady_samples as f64,
        )?;
        OptionKey::TraceSamples.check_count(samples)
    }

    /// Check a periodic orbit's search (`orbit`) against the caps: the drive periods run to
    /// its steady state or its transient at most [`Caps::max_periods`], the period looked for
    /// at most [`Caps::max_period`].
    ///
    /// # Errors
    /// [`Error::InvalidOption`] with [`Allowed::Cap`] naming the first field over its cap.
    pub fn check_orbit(&self, options: &OrbitOptions) -> Result<()> {
        let periods = self.max_periods as f64;
        Self::over(
            OptionKey::OrbitTransient,
            options.transient as f64,
            0.0,
            periods,
        )?;
        Self::over(
            OptionKey::OrbitMaxPeriods,
            options.max_periods as f64,
            1.0,
            periods,
        )?;
        Self::over(
            OptionKey::OrbitMaxPeriod,
            options.max_period as f64,
            1.0,
            self.max_period as f64,
        )?;
        if let Some(p) = options.period {
            Self::over(
                OptionKey::OrbitPeriod,
                p as f64,
                1.0,
                self.max_period as f64,
            )?;
        }
        Ok(())
    }

    /// Check a run from the initial state against the caps.
    ///
    /// # Errors
    /// [`Error::InvalidOption`] with [`Allowed::Cap`] naming the first field over its cap;
    /// [`Error::OptionProduct`] for too many samples in all.
    pub fn check_simulate(&self, options: &SimulateOptions) -> Result<()> {
        Self::over(
            OptionKey::SimulatePeriods,
            options.periods,
            0.0,
            self.simulate_periods,
        )?;
        Self::over(
            OptionKey::SimulateSamples,
            options.samples_per_period as f64,
            1.0,
            self.simulate_samples as f64,
        )?;
        let total = (options.periods * options.samples_per_period as f64).ceil();
        if total > self.simulate_total as f64 {
            return Err(Error::OptionProduct {
                what: "samples",
                first: OptionKey::SimulatePeriods,
                second: OptionKey::SimulateSamples,
                product: total,
                max: if self.profile == "library" {
                    "5e7"
                } else {
                    "200000"
                },
            });
        }
        Ok(())
    }

    /// Check the values of a sweep (each leg) against the caps.
    ///
    /// # Errors
    /// [`Error::InvalidOption`] naming [`OptionKey::SweepSteps`].
    pub fn check_sweep(&self, steps: usize) -> Result<()> {
        Self::over(
            OptionKey::SweepSteps,
            steps as f64,
            1.0,
            self.sweep_steps as f64,
        )
    }

    /// Check the sides and the points of a map against the caps.
    ///
    /// # Errors
    /// [`Error::InvalidOption`] naming the side over its cap; [`Error::OptionProduct`] for
    /// too many points.
    pub fn check_map(&self, w_steps: usize, beta_steps: usize) -> Result<()> {
        Self::over(
            OptionKey::MapWSteps,
            w_steps as f64,
            1.0,
            self.map_side as f64,
        )?;
        Self::over(
            OptionKey::MapBetaSteps,
            beta_steps as f64,
            1.0,
            self.map_side as f64,
        )?;
        let points = w_steps as f64 * beta_steps as f64;
        if points > self.map_points as f64 {
            return Err(Error::OptionProduct {
                what: "points",
                first: OptionKey::MapWSteps,
                second: OptionKey::MapBetaSteps,
                product: points,
                max: if self.profile == "library" {
                    "1e8"
                } else {
                    "40000"
                },
            });
        }
        Ok(())
    }
}

/// Check a map whose every point is kept in memory (a plot of it, or a checkpoint) against
/// [`MAX_KEPT_GRID_POINTS`].
///
/// # Errors
/// [`Error::OptionProduct`] naming the two counts.
pub fn check_kept_map(w_steps: usize, beta_steps: usize) -> Result<()> {
    crate::options::check_product(
        "points kept in memory (with a plot or a checkpoint)",
        (OptionKey::MapWSteps, w_steps),
        (OptionKey::MapBetaSteps, beta_steps),
        MAX_KEPT_GRID_POINTS as f64,
        "4000000",
    )
    .map(|_| ())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::params::Params;
    use std::f64::consts::TAU;

    #[test]
    fn the_horizon_is_in_time_and_in_phase() {
        let slow = Params::new(0.05, 0.01, 1.0).unwrap();
        let fast = Params::new(0.05, 100.0, 1.0).unwrap();
        let max_fast = TAU_MAX / TAU;
        assert!((max_periods(&fast) - max_fast).abs() < 1e-6 * max_fast);
        assert!((max_periods(&slow) - 0.01 * max_fast).abs() < 1e-6 * max_fast);
        assert!(check_horizon(&slow, 0.99 * 0.01 * max_fast).is_ok());
        match check_horizon(&slow, 1.01 * 0.01 * max_fast) {
            Err(Error::HorizonTooLong { max_periods, .. }) => {
                assert!((max_periods - 0.01 * max_fast).abs() < 1e-6 * max_fast)
            }
            other => panic!("{other:?}"),
        }
        assert!(check_time(&slow, 0.99 * TAU_MAX).is_ok());
        assert!(check_time(&slow, 1.01 * TAU_MAX).is_err());
        assert!(check_time(&fast, 0.99 * TAU_MAX / 100.0).is_ok());
        assert!(check_time(&fast, 1.01 * TAU_MAX / 100.0).is_err());
        assert!(check_time(&fast, f64::NAN).is_err());
    }

    #[test]
    fn the_shared_server_is_within_the_library() {
        let (lib, lab) = (Caps::library(), Caps::shared_server());
        assert!(lab.max_period <= lib.max_period && lab.max_periods <= lib.max_periods);
        assert!(lab.map_points <= lib.map_points && lab.sweep_steps <= lib.sweep_steps);
        assert!(lab.upload_bytes <= lib.upload_bytes);
        let steady = crate::SteadyOptions::default();
        assert!(lab.check_steady(&steady).is_ok());
        let long = crate::SteadyOptions {
            max_period: 32,
            ..steady
        };
        assert!(lib.check_steady(&long).is_ok());
        let e = lab.check_steady(&long).unwrap_err();
        assert_eq!(
            e.to_string(),
            "invalid max_period = 32: must be from 1 to 16"
        );
        let map = lab.check_map(300, 300).unwrap_err();
        assert_eq!(
            map.to_string(),
            "invalid points = 90000: w_steps × beta_steps must be at most 40000"
        );
        assert!(lib.check_map(300, 300).is_ok());
        assert!(check_kept_map(2000, 2000).is_ok());
        assert_eq!(
            check_kept_map(2001, 2000)
                .unwrap_err()
                .render(crate::Spelling::Flag),
            "--w-steps × --beta-steps = 4002000 points kept in memory (with a plot or a \
             checkpoint): at most 4000000 allowed"
        );
    }

    #[test]
    fn the_default_steady_cap_fits_at_the_lowest_frequency() {
        let p = Params::new(0.05, W_MIN, 1.0).unwrap();
        assert!(check_horizon(&p, 5000.0).is_ok());
    }
}
