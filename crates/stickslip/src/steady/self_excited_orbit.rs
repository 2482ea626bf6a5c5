//! The periodic orbit of a self-excited motion (a belt without a drive, β = 0): the cycle
//! `steady` settles on ([`super::self_excited`]), with its own period (not a drive period)
//! and its Floquet multipliers, or steady sliding with the eigenvalues of its linearisation.
//!
//! **Multipliers.** The motion is autonomous, so one multiplier of a cycle is 1 (a shift
//! along the cycle stays a shift). The other is exactly 0 for a stick-slip cycle, for every
//! law: every stop ends at the same state, y = sgn(vb)·μs − 2ζ vb with y' = vb (where the
//! spring and damper's force reaches the static limit), so sticking collapses every
//! perturbation across the cycle onto that point. A pure-slip cycle's nontrivial multiplier
//! is not computed here ([`SelfExcitedOrbit::multipliers`] is `None`).

use super::classify::MotionClass;
use super::self_excited::{CycleSection, SlidingStability};
use super::state::SteadyState;
use crate::error::Result;
use crate::stability::{Multiplier, Stability};
use crate::theory::SteadySliding;
use serde::{Deserialize, Serialize};

/// The orbit of a self-excited motion (β = 0 on a belt). Dimensionless: times in τ = ω0·t,
/// rates per unit τ.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct SelfExcitedOrbit {
    /// What it is in a few words: `self-excited cycle, period T τ` (with the class), or
    /// `self-excited: steady sliding at y = y_e`.
    pub summary: String,
    /// A stick-slip cycle, a pure-slip cycle or steady sliding.
    pub class: MotionClass,
    /// The period of the cycle in τ (found, not given); `None` for steady sliding.
    pub cycle_period_tau: Option<f64>,
    /// The period in seconds, T/ω0, for a physical model; `None` otherwise.
    pub cycle_period_s: Option<f64>,
    /// Where the cycle was recognised; `None` for steady sliding.
    pub section: Option<CycleSection>,
    /// The position at which every stop of a stick-slip cycle ends, sgn(vb)·μs − 2ζ vb (with
    /// y' = vb); `None` without stops.
    pub release_y: Option<f64>,
    /// The Floquet multipliers of the cycle, [1, 0] for a stick-slip cycle (see the module
    /// documentation); `None` for steady sliding and for a pure-slip cycle.
    pub multipliers: Option<[Multiplier; 2]>,
    /// The cycle's orbital stability from its nontrivial multiplier (stable for a stick-slip
    /// cycle); for steady sliding, the equilibrium's.
    pub stability: Option<Stability>,
    /// Largest y over the cycle (the equilibrium for steady sliding).
    pub y_max: f64,
    /// Smallest y over the cycle.
    pub y_min: f64,
    /// The fraction of the period stuck to the belt.
    pub stick_fraction: f64,
    /// Steady sliding, y' = 0 at y_e = sgn(vb)·μ(|vb|), and its linearisation, whether or not
    /// the motion settled there.
    pub sliding: SteadySliding,
    /// The eigenvalues of steady sliding's linearisation y'' + d y' + y = 0, the larger real
    /// part first.
    pub sliding_eigenvalues: [Multiplier; 2],
    /// Whether steady sliding is stable (the sign of d).
    pub sliding_stability: SlidingStability,
}

impl SelfExcitedOrbit {
    /// The orbit of the self-excited steady state `steady` (β = 0, vb ≠ 0; from
    /// [`crate::experiment::Experiment::steady_with`] or [`super::self_excited_state`]),
    /// with `omega0` (rad/s) for the period in seconds of a physical model.
    ///
    /// # Errors
    /// [`crate::Error::InvalidParameter`] naming `beta` when `steady` is not self-excited (a driven
    /// motion, or no belt); [`crate::stability::StabilityError::NoPeriod`] when it found no
    /// cycle.
    pub fn from_steady(steady: &SteadyState, omega0: Option<f64>) -> Result<Self> {
        let params = &steady.params;
        let Some(cycle) = steady.self_excited.filter(|_| params.vb != 0.0) else {
            return crate::error::invalid(
                "beta",
                params.beta,
                "must be 0 on a moving belt (vb ≠ 0) for a self-excited cycle",
            );
        };
        let sliding = SteadySliding::new(params)?;
        let half = 0.5 * sliding.damping;
        let discriminant = half * half - 1.0;
        let sliding_eigenvalues = if discriminant < 0.0 {
            let im = (-discriminant).sqrt();
            [
                Multiplier { re: -half, im },
                Multiplier { re: -half, im: -im },
            ]
        } else {
            let root = discriminant.sqrt();
            [
                Multiplier::real(-half + root),
                Multiplier::real(-half - root),
            ]
        };
        let summary = match (steady.class, cycle.period) {
            (MotionClass::SteadySliding, _) | (_, None) => format!(
                "self-excited: steady sliding at y = {:.12} ({})",
                sliding.equilibrium,
                cycle.sliding_stability.label()
            ),
            (class, Some(t)) => {
                format!("self-excited cycle, period {t:.12} τ ({})", class.label())
            }
        };
        let settled = |multipliers, stability, release_y| Self {
            summary: summary.clone(),
            class: steady.class,
            cycle_period_tau: cycle.period,
            cycle_period_s: cycle.period.zip(omega0).map(|(t, w)| t / w),
            section: cycle.section,
            release_y,
            multipliers,
            stability,
            y_max: steady.y_max,
            y_min: steady.y_min,
            stick_fraction: cycle.stick_fraction,
            sliding,
            sliding_eigenvalues,
            sliding_stability: cycle.sliding_stability,
        };
        match steady.class {
            MotionClass::SteadySliding => Ok(settled(
                None,
                Some(match cycle.sliding_stability {
                    SlidingStability::Stable => Stability::Stable,
                    SlidingStability::Unstable => Stability::Unstable,
                    SlidingStability::Neutral => Stability::Neutral,
                }),
                None,
            )),
            _ if cycle.period.is_none() => Err(crate::stability::StabilityError::NoPeriod {
                periods_run: steady.periods_to_settle,
                exponent: None,
                verdict: None,
            }
            .into()),
            MotionClass::StickSlipCycle => Ok(settled(
                Some([Multiplier::real(1.0), Multiplier::real(0.0)]),
                Some(Stability::Stable),
                Some(params.vb.signum() * params.mu_s - 2.0 * params.zeta * params.vb),
            )),
            _ => Ok(settled(None, None, None)),
        }
    }
}
