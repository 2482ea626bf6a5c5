//! The periodic orbit of a self-excited motion (a belt without a drive, β = 0): the cycle
//! `steady` settles on ([`super::self_excited`]), with its own period (not a drive period)
//! and its Floquet multipliers, or steady sliding with the eigenvalues of its linearisation.
//!
//! **Multipliers.** The motion is autonomous, so one multiplier of a cycle is 1 (a shift
//! along the cycle stays a shift). The other is exactly 0 for a stick-slip cycle, for every
//! law: every stop ends at the same state, y = sgn(vb)·μs − 2ζ vb with y' = vb (where the
//! spring and damper's force reaches the static limit), so sticking collapses every
//! perturbation across the cycle onto that point.
//!
//! **A pure-slip cycle's multiplier.** The block never sticks, so the flow is differentiable
//! along the cycle and its nontrivial multiplier μ2 is the derivative of the Poincaré return
//! map on any section the cycle crosses transversally; on the turning point of y's maximum
//! (y' = 0, where the slip s = −vb ≠ 0) it is P'(y_max) for P(y) = the next maximum of y from
//! (y, 0). It is computed from the solver's tangent dynamics ([`Dynamics::tangent`]: the
//! friction solver's step derivatives and the saltation matrices of its reversals for a
//! smooth law, the exact segments for Coulomb's) over one period T from (y_max, 0): the
//! monodromy matrix M = ∂x(T)/∂x(0) has the eigenvalue 1 along the flow, f(x0) = (0, y'')
//! (so M = [[m11, 0], [m21, 1]] on the cycle), and its determinant is the other,
//! μ2 = det M = m11 = P'(y_max). The tangent carries ln|det M| itself (a product of its steps'
//! and events' determinants), which keeps a small μ2 to its relative accuracy. The test
//! `self_excited_orbit.rs` checks μ2 against Richardson differences of P (steps 10⁻⁵ and
//! half), and a stick-slip cycle's P' = 0 by the same differences.

use super::classify::MotionClass;
use super::self_excited::{CycleSection, SlidingStability};
use super::state::SteadyState;
use crate::error::Result;
use crate::params::{Params, State};
use crate::stability::{Dynamics, Multiplier, Stability, StabilityError};
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
    /// The Floquet multipliers of the cycle, the trivial one (1) first: [1, 0] for a
    /// stick-slip cycle, [1, μ2] for a pure-slip cycle (μ2 from the tangent dynamics, see the
    /// module documentation); `None` for steady sliding, and for a pure-slip cycle from
    /// [`SelfExcitedOrbit::from_steady`] alone (without [`SelfExcitedOrbit::with_tangent`]).
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

    /// A pure-slip cycle's nontrivial multiplier μ2 from the tangent dynamics of `dynamics`
    /// (the model's, [`crate::experiment::Experiment::dynamics`]) with the parameters
    /// `params` of the steady state (see the module documentation), and its stability
    /// (stable for μ2 < 1); any other orbit is returned as it is.
    ///
    /// A pure-slip cycle that touches the belt's speed (a stop of no duration, as the
    /// undamped Coulomb belt's with μs = 1: `crate::theory::belt`) has no multiplier: the
    /// return map has no derivative there; it is returned without one, its summary saying
    /// so.
    ///
    /// # Errors
    /// What the solver reports.
    pub fn with_tangent(mut self, dynamics: &dyn Dynamics, params: &Params) -> Result<Self> {
        let (MotionClass::PureSlipCycle, Some(period)) = (self.class, self.cycle_period_tau) else {
            return Ok(self);
        };
        let mu2 = match pure_slip_multiplier(dynamics, params, self.y_max, period) {
            // The cycle touches the belt's speed (a stop of no duration, which the class does
            // not count): perturbations outwards stick there and inwards do not, so the
            // return map has no derivative on the cycle (at ζ = 0, μs = 1: slope 0 outside,
            // 1 inside), and there is no multiplier to report.
            Err(crate::Error::Stability(StabilityError::NoPeriod { .. })) => {
                self.summary
                    .push_str(", touching the belt's speed: its return map has no derivative");
                return Ok(self);
            }
            other => other?,
        };
        self.multipliers = Some([Multiplier::real(1.0), Multiplier::real(mu2)]);
        self.stability = Some(if mu2 < 1.0 {
            Stability::Stable
        } else if mu2 > 1.0 {
            Stability::Unstable
        } else {
            Stability::Neutral
        });
        Ok(self)
    }
}

/// The nontrivial multiplier μ2 = det M of a pure-slip cycle of period `period` (in τ) whose
/// largest y is `y_max` (a turning point, y' = 0): ln|det M| of the tangent dynamics of
/// `dynamics` over one period from (y_max, 0) (see the module documentation).
///
/// # Errors
/// [`StabilityError::NoPeriod`] when the motion sticks on the way (M is then singular and the
/// cycle not a pure-slip one); what the solver reports.
pub fn pure_slip_multiplier(
    dynamics: &dyn Dynamics,
    params: &Params,
    y_max: f64,
    period: f64,
) -> Result<f64> {
    let mut tangent = dynamics.tangent(params, State { y: y_max, v: 0.0 })?;
    tangent.run_until(period, &mut |_| {})?;
    match tangent.log_det() {
        Some(log_det) if tangent.stops() == 0 => Ok(log_det.exp()),
        _ => Err(StabilityError::NoPeriod {
            periods_run: 1,
            exponent: None,
            verdict: None,
        }
        .into()),
    }
}
