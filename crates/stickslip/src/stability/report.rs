//! Periodic orbits and Lyapunov exponents as flat records of numbers: what `stickslip orbit
//! --json` and `stickslip lyapunov --json` print, and what the Python package's
//! `orbit(...).to_dict()` and `lyapunov(...).to_dict()` return.

use super::dynamics::{Dynamics, ExactDynamics};
use super::lyapunov::{LyapunovOptions, SecondExponent};
use super::matrix::Multiplier;
use super::nonperiodic::{strobe_period_of, NonperiodicClassification, NonperiodicVerdict};
use super::periodic_orbit::{PeriodicOrbit, Stability, Stop};
use crate::error::Result;
use crate::params::Params;
use crate::solver::run_until;
use serde::Serialize;

/// An exponent in JSON: a number, or the string `"-inf"` (JSON has no infinity).
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
#[serde(untagged)]
pub enum ExponentValue {
    /// A finite exponent.
    Finite(f64),
    /// −∞, written `"-inf"`.
    Text(&'static str),
}

impl From<f64> for ExponentValue {
    fn from(x: f64) -> Self {
        if x == f64::NEG_INFINITY {
            ExponentValue::Text("-inf")
        } else {
            ExponentValue::Finite(x)
        }
    }
}

/// An event of an orbit: time from the orbit's strobe, position, and kind (`turn`, `stick` or
/// `slip`, as in the command-line tool's event CSV).
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct EventRecord {
    /// Dimensionless time from the strobe.
    pub tau: f64,
    /// Position y.
    pub y: f64,
    /// `turn`, `stick` or `slip`.
    pub kind: &'static str,
}

/// The numbers of a [`PeriodicOrbit`] (dimensionless; see its fields).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct OrbitReport {
    /// Period p in drive periods, as asked for.
    pub period: usize,
    /// The least period of the orbit in drive periods, a divisor of p: a fixed point of the
    /// p-fold strobe map may repeat sooner (asked for p = 3, Newton's method may land on an
    /// orbit of period 1). The multipliers are those of p drive periods.
    pub least_period: usize,
    /// The drive period T = 2π/w (dimensionless time).
    pub drive_period: f64,
    /// Position y at the orbit's strobe (τ = 0 mod pT, drive phase φ).
    pub y: f64,
    /// Velocity y' at the strobe.
    pub v: f64,
    /// Whether the orbit is stuck at its strobe.
    pub stuck_at_strobe: bool,
    /// The Floquet multipliers (eigenvalues of the monodromy matrix), the larger modulus
    /// first, each as `{"re", "im"}`.
    pub multipliers: [Multiplier; 2],
    /// Their moduli |μ|.
    pub moduli: [f64; 2],
    /// Whether every perturbation decays (|μ₁| < 1 − 10⁻⁹).
    pub stable: bool,
    /// `stable`, `unstable` or `neutral` (|μ₁| within 10⁻⁹ of 1).
    pub stability: Stability,
    /// The largest Lyapunov exponent λ₁ of the orbit per unit τ, ln|μ₁|/(pT) (`"-inf"` when
    /// both multipliers vanish).
    pub lambda1: ExponentValue,
    /// The same per drive period, ln|μ₁|/p.
    pub lambda1_per_period: ExponentValue,
    /// The monodromy matrix ∂P^p/∂(y, y') as rows [[a, b], [c, d]].
    pub monodromy: [[f64; 2]; 2],
    /// Newton steps taken.
    pub iterations: usize,
    /// The residual max(|Δy|, |Δy'|) of P^p(x) − x at the guess and after every step.
    pub residuals: Vec<f64>,
    /// Stops longer than 10⁻⁸ drive periods per drive period.
    pub stops_per_period: f64,
    /// The events over one orbit period.
    pub events: Vec<EventRecord>,
    /// The stops over one orbit period (zero-duration stops included, with duration 0).
    pub stops: Vec<Stop>,
    /// Drive frequency w.
    pub w: f64,
    /// Drive amplitude β.
    pub beta: f64,
    /// Damping ratio ζ.
    pub zeta: f64,
    /// Static-to-kinetic friction ratio μs.
    pub mu_s: f64,
    /// Drive phase φ (radians).
    pub phi: f64,
}

impl OrbitReport {
    /// The report of `orbit`, an orbit of the exact model with `params`.
    ///
    /// # Errors
    /// Whatever the solver reports while it looks for the least period.
    pub fn new(orbit: &PeriodicOrbit, params: &Params) -> Result<Self> {
        Self::of(orbit, params, &ExactDynamics)
    }

    /// The report of `orbit`, an orbit of the model `dynamics` with `params`.
    ///
    /// # Errors
    /// Whatever the solver reports while it looks for the least period.
    pub fn of(orbit: &PeriodicOrbit, params: &Params, dynamics: &dyn Dynamics) -> Result<Self> {
        let least_period = least_period(orbit, params, dynamics)?;
        let exponent = orbit.exponent();
        let shortest = 1e-8 * orbit.drive_period;
        let stops = orbit.stops.iter().filter(|s| s.duration > shortest).count();
        Ok(Self {
            period: orbit.period,
            least_period,
            drive_period: orbit.drive_period,
            y: orbit.state.y,
            v: orbit.state.v,
            stuck_at_strobe: orbit.stuck_at_strobe,
            multipliers: orbit.multipliers,
            moduli: orbit.multipliers.map(|m| m.modulus()),
            stable: orbit.stability == Stability::Stable,
            stability: orbit.stability,
            lambda1: exponent.into(),
            lambda1_per_period: (exponent * orbit.drive_period).into(),
            monodromy: orbit.monodromy.0,
            iterations: orbit.iterations,
            residuals: orbit.residuals.clone(),
            stops_per_period: stops as f64 / orbit.period as f64,
            events: orbit
                .events
                .iter()
                .map(|e| EventRecord {
                    tau: e.tau,
                    y: e.y,
                    kind: e.kind.label(),
                })
                .collect(),
            stops: orbit.stops.clone(),
            w: params.w,
            beta: params.beta,
            zeta: params.zeta,
            mu_s: params.mu_s,
            phi: params.phi,
        })
    }
}

/// The least d dividing the orbit's period p after which the orbit's strobe state comes back
/// (to 10⁻⁸ relative, or the model's [`Dynamics::repeat_tolerance`] of it: far below the
/// distance between distinct strobe states of one orbit, far above the rounding of a
/// converged orbit, which an unstable orbit amplifies by its multiplier over d < p periods).
fn least_period(orbit: &PeriodicOrbit, params: &Params, dynamics: &dyn Dynamics) -> Result<usize> {
    let p = orbit.period;
    let x = orbit.state;
    let scale = 1f64.max(x.y.abs()).max(x.v.abs());
    let tolerance = dynamics.repeat_tolerance(1e-8);
    for d in (1..p).filter(|d| p.is_multiple_of(*d)) {
        let mut solver = dynamics.solver(params, x)?;
        run_until(solver.as_mut(), d as f64 * orbit.drive_period, |_| {})?;
        let y = solver.state();
        if (y.y - x.y).abs().max((y.v - x.v).abs()) <= tolerance * scale {
            return Ok(d);
        }
    }
    Ok(p)
}

/// The numbers of a Lyapunov measurement and its verdict (dimensionless: rates per unit τ
/// or per drive period).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct LyapunovReport {
    /// The largest exponent λ₁ per unit τ (JSON `lambda1`, the name of λ₁ in every report).
    pub lambda1: f64,
    /// Its standard error per unit τ (from the block means).
    pub lambda1_error: f64,
    /// λ₁ per drive period, λ₁T.
    pub lambda1_per_period: f64,
    /// Its standard error per drive period.
    pub lambda1_error_per_period: f64,
    /// What the motion is: `periodic` when it is not chaotic and its strobe at the end of
    /// the measurement repeats with a period of at most 16 drive periods (`period`; rest has
    /// period 1); else what λ₁ says: `chaotic` (λ₁ > kσ), `quasi-periodic` (|λ₁| ≤ kσ),
    /// `contracting` (λ₁ < −kσ: settling onto a periodic attractor not reached by the end of
    /// the measurement, or of a longer period) or `undecided` (the halves of the measurement
    /// disagree), with σ the error and k the significance. A self-excited motion (β = 0 on a
    /// belt) is `limit-cycle` (|λ₁| ≤ kσ, λ₂ < −kσ) or `equilibrium` (λ₁ < −kσ: steady
    /// sliding), never `periodic` in drive periods.
    pub class: &'static str,
    /// The verdict of the exponent alone (`chaotic`, `quasi-periodic`, `contracting`,
    /// `limit-cycle`, `equilibrium`, `undecided`), also when `class` is `periodic`.
    pub verdict: &'static str,
    /// The period of the motion reached, in drive periods ([`super::strobe_period`]); `None` when
    /// the strobe does not repeat (or the motion is chaotic).
    pub period: Option<usize>,
    /// Whether the two halves of the measurement agree.
    pub converged: bool,
    /// The second exponent λ₂ per unit τ; `None` (JSON null) when λ₂ = −∞, with
    /// `lambda2_reason` saying why (JSON has no infinity).
    pub lambda2: Option<f64>,
    /// Its standard error per unit τ (`None` when λ₂ = −∞).
    pub lambda2_error: Option<f64>,
    /// λ₂ per drive period (`None` when λ₂ = −∞).
    pub lambda2_per_period: Option<f64>,
    /// Why λ₂ = −∞ (`None` when it is finite).
    pub lambda2_reason: Option<String>,
    /// Stops longer than 10⁻⁸ drive periods per drive period while measured.
    pub stops_per_period: f64,
    /// Drive periods run before measuring.
    pub transient_periods: usize,
    /// Drive periods measured (fewer than `cap_periods` when the verdict was decided early).
    pub periods: usize,
    /// Drive periods the measurement could run at most ([`LyapunovOptions::periods`] rounded
    /// down to a multiple of the blocks).
    pub cap_periods: usize,
    /// Whether the measurement stops as soon as its verdict is decided
    /// ([`LyapunovOptions::sequential`]).
    pub sequential: bool,
    /// Blocks of the measurement.
    pub blocks: usize,
    /// Standard errors that make a difference significant (k).
    pub significance: f64,
    /// The block means of λ₁ per unit τ, in time order.
    pub block_means: Vec<f64>,
    /// The drive period T = 2π/w (dimensionless time).
    pub drive_period: f64,
    /// Position y at the end of the measurement (a strobe).
    pub final_y: f64,
    /// Velocity y' at the end of the measurement.
    pub final_v: f64,
    /// Drive frequency w.
    pub w: f64,
    /// Drive amplitude β.
    pub beta: f64,
    /// Damping ratio ζ.
    pub zeta: f64,
    /// Static-to-kinetic friction ratio μs.
    pub mu_s: f64,
    /// Drive phase φ (radians).
    pub phi: f64,
}

impl LyapunovReport {
    /// The report of the measurement `c`, made with `options` on the model with `params`; the
    /// strobe at the end of the measurement is followed for up to 16 more drive periods to see
    /// whether the motion has reached a periodic orbit.
    ///
    /// # Errors
    /// Whatever the solver reports on that run.
    pub fn new(
        c: &NonperiodicClassification,
        options: &LyapunovOptions,
        params: &Params,
    ) -> Result<Self> {
        Self::of(c, options, params, &ExactDynamics)
    }

    /// [`LyapunovReport::new`] for a measurement on the model `dynamics`.
    ///
    /// # Errors
    /// Whatever the solver reports on the run that looks for the period.
    pub fn of(
        c: &NonperiodicClassification,
        options: &LyapunovOptions,
        params: &Params,
        dynamics: &dyn Dynamics,
    ) -> Result<Self> {
        let e = &c.exponents;
        let period = match c.verdict {
            // A self-excited motion has no drive period: its own is the cycle's.
            NonperiodicVerdict::Chaotic
            | NonperiodicVerdict::LimitCycle
            | NonperiodicVerdict::Equilibrium => None,
            _ => strobe_period_of(dynamics, params, e.final_state)?,
        };
        let (lambda2, error2, reason) = match e.second {
            SecondExponent::Finite(s) => (Some(s.per_tau), Some(s.error_per_tau), None),
            SecondExponent::MinusInfinity { stops } => (
                None,
                None,
                Some(format!(
                    "the motion stopped {stops} times while measured: a stop erases the \
                     velocity perturbation (det J = 0)"
                )),
            ),
        };
        Ok(Self {
            lambda1: e.largest.per_tau,
            lambda1_error: e.largest.error_per_tau,
            lambda1_per_period: e.largest.per_period,
            lambda1_error_per_period: e.largest.error_per_period,
            class: if period.is_some() {
                "periodic"
            } else {
                c.verdict.label()
            },
            verdict: c.verdict.label(),
            period,
            converged: e.converged,
            lambda2,
            lambda2_error: error2,
            lambda2_per_period: lambda2.map(|l| l * e.drive_period),
            lambda2_reason: reason,
            stops_per_period: e.stops_per_period(),
            transient_periods: options.transient_periods,
            periods: e.periods,
            cap_periods: e.cap,
            sequential: options.sequential,
            blocks: options.blocks,
            significance: options.significance,
            block_means: e.block_means.clone(),
            drive_period: e.drive_period,
            final_y: e.final_state.y,
            final_v: e.final_state.v,
            w: params.w,
            beta: params.beta,
            zeta: params.zeta,
            mu_s: params.mu_s,
            phi: params.phi,
        })
    }
}
