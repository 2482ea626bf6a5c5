//! Is a motion whose strobe map does not repeat chaotic? The verdict from the largest
//! Lyapunov exponent and its error.

pub use super::verdict::NonperiodicVerdict;

use super::dynamics::{Dynamics, ExactDynamics};
use super::lyapunov::{lyapunov_exponents, LyapunovExponents, LyapunovOptions, SecondExponent};
use crate::error::Result;
use crate::params::{Params, State};
use crate::solver::run_until;
use serde::{Deserialize, Serialize};

/// The verdict on a motion and the exponents behind it.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct NonperiodicClassification {
    /// The verdict.
    pub verdict: NonperiodicVerdict,
    /// The Lyapunov exponents it rests on.
    pub exponents: LyapunovExponents,
}

/// Classify the motion from `state` at τ = 0 (a strobe; for example the final state of a
/// steady-state run that found no period) by its largest Lyapunov exponent (see
/// [`NonperiodicVerdict`] and [`super::lyapunov`]).
///
/// ```
/// use stickslip::stability::{classify_nonperiodic, LyapunovOptions, NonperiodicVerdict};
/// use stickslip::{Params, State};
/// let params = Params::new(0.0468, 0.7, 1.2).unwrap();
/// let options = LyapunovOptions { transient_periods: 100, periods: 400, ..Default::default() };
/// let c = classify_nonperiodic(&params, State::default(), &options).unwrap();
/// assert_eq!(c.verdict, NonperiodicVerdict::Contracting);
/// ```
///
/// # Errors
/// As [`lyapunov_exponents`].
pub fn classify_nonperiodic(
    params: &Params,
    state: State,
    options: &LyapunovOptions,
) -> Result<NonperiodicClassification> {
    let exponents = lyapunov_exponents(params, state, options)?;
    Ok(NonperiodicClassification::new(
        exponents,
        options.significance,
    ))
}

impl NonperiodicClassification {
    /// The verdict on measured `exponents`, with `significance` = k standard errors (see
    /// [`NonperiodicVerdict`]).
    pub fn new(exponents: LyapunovExponents, significance: f64) -> Self {
        let verdict = NonperiodicVerdict::of(
            exponents.largest.per_tau,
            exponents.largest.error_per_tau,
            exponents.converged,
            significance,
        );
        Self { verdict, exponents }
    }

    /// The verdict for an autonomous motion (a self-excited belt, β = 0), with `significance`
    /// = k standard errors: a flow's λ₁ along a cycle is 0, so |λ₁| ≤ kσ with λ₂ < −kσ (or
    /// −∞) is a limit cycle ([`NonperiodicVerdict::LimitCycle`]), not a torus; λ₁ < −kσ is
    /// an equilibrium ([`NonperiodicVerdict::Equilibrium`]). Other verdicts stay.
    pub fn autonomous(mut self, significance: f64) -> Self {
        let k = significance;
        let second_negative = match self.exponents.second {
            SecondExponent::MinusInfinity { .. } => true,
            SecondExponent::Finite(s) => s.per_tau < -k * s.error_per_tau,
        };
        self.verdict = match self.verdict {
            NonperiodicVerdict::QuasiPeriodic if second_negative => NonperiodicVerdict::LimitCycle,
            NonperiodicVerdict::Contracting => NonperiodicVerdict::Equilibrium,
            verdict => verdict,
        };
        self
    }
}

impl NonperiodicVerdict {
    /// The label used in JSON: `chaotic`, `quasi-periodic`, `contracting`, `limit-cycle`,
    /// `equilibrium`, `undecided`.
    pub fn label(self) -> &'static str {
        match self {
            NonperiodicVerdict::Chaotic => "chaotic",
            NonperiodicVerdict::QuasiPeriodic => "quasi-periodic",
            NonperiodicVerdict::Contracting => "contracting",
            NonperiodicVerdict::LimitCycle => "limit-cycle",
            NonperiodicVerdict::Equilibrium => "equilibrium",
            NonperiodicVerdict::Undecided => "undecided",
        }
    }
}

/// Longest period (drive periods) [`strobe_period`] looks for.
pub const MAX_STROBE_PERIOD: usize = 16;

/// Relative distance within which [`strobe_period`] takes the strobe to have come back: far
/// above the rounding of a motion that has reached its periodic orbit, far below the distance
/// between distinct strobe states of one orbit.
pub const STROBE_PERIOD_TOLERANCE: f64 = 1e-9;

/// The least p ≤ [`MAX_STROBE_PERIOD`] after which the strobe state `state` (at τ = 0) comes
/// back, max(|Δy|, |Δy'|) ≤ [`STROBE_PERIOD_TOLERANCE`]·max(1, |y|, |y'|): whether a
/// measured motion has reached a periodic orbit (or rest, p = 1). `None` when it does not
/// come back so soon.
///
/// ```
/// use stickslip::stability::strobe_period;
/// use stickslip::{Params, State};
/// // At rest (β below μs) the strobe comes back after one period.
/// let rest = Params::new(0.0, 0.5, 0.5).unwrap();
/// assert_eq!(strobe_period(&rest, State::default()).unwrap(), Some(1));
/// ```
///
/// # Errors
/// Invalid parameters or state; whatever the solver reports.
pub fn strobe_period(params: &Params, state: State) -> Result<Option<usize>> {
    strobe_period_of(&ExactDynamics, params, state)
}

/// [`strobe_period`] for the model `dynamics`, within its
/// [`Dynamics::repeat_tolerance`] of [`STROBE_PERIOD_TOLERANCE`].
///
/// # Errors
/// As [`strobe_period`].
pub fn strobe_period_of(
    dynamics: &dyn Dynamics,
    params: &Params,
    state: State,
) -> Result<Option<usize>> {
    let params = params.validate()?;
    let state = State::new(state.y, state.v)?;
    let scale = 1f64.max(state.y.abs()).max(state.v.abs());
    let tolerance = dynamics.repeat_tolerance(STROBE_PERIOD_TOLERANCE);
    let mut solver = dynamics.solver(&params, state)?;
    for p in 1..=MAX_STROBE_PERIOD {
        run_until(solver.as_mut(), p as f64 * params.drive_period(), |_| {})?;
        let x = solver.state();
        if (x.y - state.y).abs().max((x.v - state.v).abs()) <= tolerance * scale {
            return Ok(Some(p));
        }
    }
    Ok(None)
}
