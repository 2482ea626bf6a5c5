//! Periodic orbits by Newton's method on the p-fold strobe map, with their monodromy matrix
//! and Floquet multipliers.
//!
//! A periodic orbit of period p (in drive periods) is a fixed point x* = P^p(x*) of the p-fold
//! strobe map ([`strobe_map`](super::strobe_map)); Newton's method solves P^p(x) − x = 0 with the exact Jacobian
//! M(x) = ∂P^p/∂x of [`super::tangent`]:
//!
//! ```text
//! (M(x_n) − I) δ_n = −(P^p(x_n) − x_n),      x_{n+1} = x_n + λ_n δ_n,
//! ```
//!
//! with λ_n = 1 unless the residual grows, when the step is halved (at most
//! [`NewtonOptions::max_halvings`] times). Near the orbit every step is a full one and the
//! convergence is quadratic while the iterates follow the orbit's sequence of events; the map
//! is piecewise smooth, and a change of that sequence between iterates only costs an extra
//! step. Since M is computed and not approximated, unstable orbits are found as easily as
//! stable ones.
//!
//! **Orbits that stick.** A stop erases the velocity perturbation (the stick saltation
//! diag(1, 0)), so the monodromy matrix of an orbit that stops has rank one, M = u ℓᵀ: the map
//! is locally one-dimensional, one Floquet multiplier is exactly 0 and the other is
//! μ = ℓᵀu = tr M. The Newton matrix M − I has eigenvalues −1 and μ − 1, so it stays regular
//! (unless μ = 1) and the plain step is used: it solves in the remaining direction by itself
//! (the component along the erased direction of the residual is removed in one step). Two
//! cases need more:
//!
//! - *The strobe falls inside a stop* (the state is (y, 0) and the net force within ±μs, at
//!   the start and at the image). There the map is differentiable in y only: a velocity
//!   perturbation is erased, and for μs > 1 one along a net force beyond the kinetic friction
//!   would not be stopped at all (see [`super::segment`]). Newton then solves the scalar
//!   equation P^p_y(y, 0) = y, keeping y' = 0: δy = −r_y/(M₁₁ − 1).
//! - *M − I numerically singular* (a multiplier at 1: a fold, or a continuum of fixed points
//!   such as rest). Then the step is the minimum-norm least-squares solution
//!   (pseudo-inverse), which moves only where the residual can be reduced;
//!   [`StabilityError::SingularJacobian`] only when M − I vanishes or is not finite.
//!
//! - *The iterates run onto y' = 0 inside the band 1 < |F − y| ≤ μs* (μs > 1 only), moving
//!   along the net force. The map jumps there: a state with y' = 0 stays stuck, one with y' a
//!   hair along the force slides away. Newton's iterates can converge (linearly, by halved
//!   steps) to such a point, which is no orbit: the motion that returns there would stop.
//!   This ends in [`StabilityError::OnDiscontinuity`], also when the steps run out while the
//!   iterates creep onto the jump (y' no larger than the residual).
//!
//! The iteration stops when max(|Δy|, |Δy'|) ≤ tolerance·max(1, |y|, |y'|)·max(1, max|M_ij|):
//! the map is evaluated to rounding, which the Jacobian amplifies by up to max|M_ij| for an
//! unstable orbit.

use super::error::StabilityError;
use super::matrix::{Matrix2, Multiplier};
use super::strobe::{strobe_map_on, StrobeImage};
use crate::error::{Error, Result};
use crate::exact::ExactSolver;
pub use crate::options::NewtonOptions;
use crate::params::{Params, State};
use crate::solver::{Event, EventKind, Hints};
use serde::{Deserialize, Serialize};

/// Stability of a periodic orbit from its largest Floquet multiplier modulus |μ|.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum Stability {
    /// |μ| < 1 − band: perturbations decay.
    Stable,
    /// |μ| > 1 + band: a perturbation grows by |μ| per orbit period.
    Unstable,
    /// |μ| within the band around 1 (a bifurcation, or a continuum of orbits such as rest).
    Neutral,
}

impl Stability {
    /// The label of the JSON and the CSV columns: `stable`, `unstable` or `neutral`.
    pub fn label(self) -> &'static str {
        match self {
            Stability::Stable => "stable",
            Stability::Unstable => "unstable",
            Stability::Neutral => "neutral",
        }
    }
}

/// A stop of the motion within an orbit.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Stop {
    /// When it starts, dimensionless time from the orbit's strobe, in [0, pT).
    pub start: f64,
    /// How long it lasts (dimensionless time; 0 for a zero-duration stop, pT for an orbit at
    /// rest). A stop that runs over the end of the orbit continues at its start and is one
    /// stop.
    pub duration: f64,
}

/// A periodic orbit found by [`find_periodic_orbit`].
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct PeriodicOrbit {
    /// Period p in drive periods (as asked for; a fixed point of P^p may have a shorter one).
    pub period: usize,
    /// The drive period T = 2π/w (dimensionless time).
    pub drive_period: f64,
    /// The state at the orbit's strobe (τ = 0 mod pT, drive phase φ).
    pub state: State,
    /// Whether the orbit is stuck at its strobe (then the map is solved in y alone).
    pub stuck_at_strobe: bool,
    /// The events over one orbit period, times from the strobe (0 < τ ≤ pT).
    pub events: Vec<Event>,
    /// The stops over one orbit period (zero-duration stops included, with duration 0).
    pub stops: Vec<Stop>,
    /// The monodromy matrix M = ∂P^p/∂(y, y') at the orbit.
    pub monodromy: Matrix2,
    /// The Floquet multipliers (eigenvalues of M), the larger modulus first; a complex pair
    /// is possible. One is 0 when the orbit stops.
    pub multipliers: [Multiplier; 2],
    /// Verdict from the larger multiplier modulus.
    pub stability: Stability,
    /// Newton steps taken.
    pub iterations: usize,
    /// The residual max(|Δy|, |Δy'|) of P^p(x) − x at the guess and after every step.
    pub residuals: Vec<f64>,
}

impl PeriodicOrbit {
    /// The orbit of period `period` (drive periods of `params`) through `state`, from the
    /// image of the `period`-fold strobe map there (its events, stops and Jacobian: the
    /// monodromy matrix), with its multipliers and verdict and Newton's `iterations` and
    /// `residuals` (either law's Newton method builds its orbit so).
    pub(crate) fn from_image(
        params: &Params,
        period: usize,
        state: State,
        image: StrobeImage,
        (multipliers, stability): ([Multiplier; 2], Stability),
        iterations: usize,
        residuals: Vec<f64>,
    ) -> Self {
        let drive_period = params.drive_period();
        let end = period as f64 * drive_period;
        PeriodicOrbit {
            period,
            drive_period,
            state,
            stuck_at_strobe: image.stuck_at_start,
            stops: stops(&image.events, image.stuck_at_start, end),
            events: image.events,
            monodromy: image.jacobian,
            multipliers,
            stability,
            iterations,
            residuals,
        }
    }

    /// Whether the orbit is rest: no events, stuck (or still) at its strobe. An orbit without
    /// events that slides throughout against a belt (its slip never changes sign) is no rest.
    pub fn is_rest(&self) -> bool {
        self.events.is_empty() && (self.stuck_at_strobe || self.state.v == 0.0)
    }

    /// The largest Lyapunov exponent of the orbit per unit τ, ln|μ_max|/(pT) (−∞ when both
    /// multipliers vanish).
    pub fn exponent(&self) -> f64 {
        let modulus = self.multipliers[0].modulus();
        if modulus == 0.0 {
            f64::NEG_INFINITY
        } else {
            modulus.ln() / (self.period as f64 * self.drive_period)
        }
    }
}

/// Largest |component| of a difference of states.
fn residual(image: &StrobeImage, x: State) -> (f64, [f64; 2]) {
    let r = [image.state.y - x.y, image.state.v - x.v];
    (r[0].abs().max(r[1].abs()), r)
}

/// Whether x is at the tolerance (see the module documentation).
fn converged(norm: f64, x: State, jacobian: &Matrix2, tolerance: f64) -> bool {
    let scale = 1f64.max(x.y.abs()).max(x.v.abs());
    norm <= tolerance * scale * jacobian.max_abs().max(1.0)
}

/// The periodic orbit of period `period` (in drive periods, p ≥ 1) near `guess` (the state at
/// a strobe τ = kT), by Newton's method on the p-fold strobe map with its exact Jacobian (see
/// the module documentation). Stable and unstable orbits alike.
///
/// ```
/// use stickslip::stability::{find_periodic_orbit, NewtonOptions, Stability};
/// use stickslip::{Params, State};
/// let params = Params::new(0.0468, 0.9, 1.6).unwrap();
/// let orbit = find_periodic_orbit(&params, State::default(), 1, &NewtonOptions::default()).unwrap();
/// assert_eq!(orbit.stability, Stability::Stable);
/// assert!(orbit.stops.is_empty() && orbit.events.len() == 2);
/// ```
///
/// # Errors
/// [`Error::InvalidParameter`] for invalid parameters, guess, options or p = 0;
/// [`StabilityError::NoConvergence`] when the tolerance is not reached;
/// [`StabilityError::SingularJacobian`] when no step can be formed;
/// [`StabilityError::OnDiscontinuity`] when the iterates converge onto the jump of the map;
/// [`StabilityError::NonFiniteJacobian`] at a tangential release; whatever the solver
/// reports.
pub fn find_periodic_orbit(
    params: &Params,
    guess: State,
    period: usize,
    options: &NewtonOptions,
) -> Result<PeriodicOrbit> {
    find_orbit(params, guess, period, options, None).map(|(orbit, _)| orbit)
}

/// What the steady-state search asks of [`find_periodic_orbit_finished`] beyond the options.
pub(crate) struct Finish {
    /// Hints of a solver on the same motion: the map's evaluations start from them and hand
    /// theirs on, one to the next (see [`Hints`]).
    pub hints: Option<Hints>,
    /// The image of the guess, computed already (see `strobe::image_along`): the map is not
    /// evaluated there again (the orbit's `residuals` still begin with the guess's).
    pub first: Option<StrobeImage>,
    /// A looser residual tolerance, and the largest modulus of the multipliers up to which
    /// the iteration may stop at it.
    pub loose: (f64, f64),
}

/// [`find_periodic_orbit`] to `options.tolerance` (or to `finish.loose` where the orbit
/// contracts fast enough), and then one more Newton step from the last iterate, without
/// evaluating the map there: the orbit's state is that step's end, its monodromy, events and
/// multipliers those of the last image (one step before). Near the orbit the step's error is
/// quadratic in the last residual, so a loose tolerance saves the map's last evaluations; the
/// caller must check the state it gets (the steady-state search checks it by the repetition
/// of the cycle it records from it). The hints of the last evaluation are returned with the
/// orbit.
pub(crate) fn find_periodic_orbit_finished(
    params: &Params,
    guess: State,
    period: usize,
    options: &NewtonOptions,
    finish: Finish,
) -> Result<(PeriodicOrbit, Option<Hints>)> {
    find_orbit(params, guess, period, options, Some(finish))
}

/// See [`find_periodic_orbit`] and [`find_periodic_orbit_finished`].
fn find_orbit(
    params: &Params,
    guess: State,
    period: usize,
    options: &NewtonOptions,
    finish: Option<Finish>,
) -> Result<(PeriodicOrbit, Option<Hints>)> {
    let (hints, first, loose) = match finish {
        Some(f) => (f.hints, f.first, Some(f.loose)),
        None => (None, None, None),
    };
    let options = options.validate()?;
    let mut x = State::new(guess.y, guess.v)?;
    // Given hints, every evaluation of the map starts from the hints the one before left (the
    // first from the caller's): the iterates follow one motion. Without, none does (the
    // public search: its iterates are the same to the bit as they always were).
    let chain = hints.is_some();
    // One solver for every evaluation, restarted in place.
    let mut solver: Option<ExactSolver> = None;
    let (mut image, mut hints) = match first {
        Some(image) => (image, hints),
        None => strobe_map_on(&mut solver, params, x, period, hints)?,
    };
    hints = hints.filter(|_| chain);
    let (mut norm, mut r) = residual(&image, x);
    // (Room for every step: one allocation.)
    let mut residuals = Vec::with_capacity(options.max_iterations + 1);
    residuals.push(norm);
    let mut iterations = 0;
    // Iterates on the jump of the map: y' = 0 (to `within`) with the net force in the band
    // between kinetic and static friction and y' along it (see the module documentation).
    let on_jump = |x: State, image: &StrobeImage, within: f64| {
        let net_force = params.beta * params.phi.cos() - x.y - params.belt_force();
        let slip = x.v - params.vb;
        !image.stuck_at_start
            && slip * net_force >= 0.0
            && net_force.abs() > 1.0
            && net_force.abs() <= params.mu_s
            && slip.abs() <= within
    };
    let jump = |x: State| {
        Error::from(StabilityError::OnDiscontinuity {
            y: x.y,
            v: x.v,
            net_force: params.beta * params.phi.cos() - x.y - params.belt_force(),
        })
    };
    let done = |norm: f64, x: State, image: &StrobeImage| {
        converged(norm, x, &image.jacobian, options.tolerance)
            || loose.is_some_and(|(tolerance, modulus)| {
                converged(norm, x, &image.jacobian, tolerance)
                    && image.jacobian.eigenvalues()[0].modulus() <= modulus
            })
    };
    while !done(norm, x, &image) {
        if iterations == options.max_iterations {
            // Out of steps while creeping onto the jump (each step halved, y' shrinking with
            // the residual): the jump is why, not the step budget.
            if iterations > 0 && on_jump(x, &image, norm) {
                return Err(jump(x));
            }
            let scale = 1f64.max(x.y.abs()).max(x.v.abs());
            return Err(StabilityError::NoConvergence {
                iterations,
                residual: norm,
                tolerance: options.tolerance * scale * image.jacobian.max_abs().max(1.0),
            }
            .into());
        }
        let m = image.jacobian;
        let singular = |determinant: f64| StabilityError::SingularJacobian {
            y: x.y,
            v: x.v,
            determinant,
        };
        let step = if image.stuck_at_start && image.stuck_at_end {
            let slope = m.0[0][0] - 1.0;
            if !(slope != 0.0 && slope.is_finite()) {
                return Err(singular(m.minus_identity().det()).into());
            }
            [-r[0] / slope, 0.0]
        } else {
            m.minus_identity()
                .solve([-r[0], -r[1]])
                .ok_or_else(|| singular(m.minus_identity().det()))?
        };
        let mut fraction = 1.0;
        let mut halvings = 0;
        loop {
            let trial = State::new(x.y + fraction * step[0], x.v + fraction * step[1])?;
            let (trial_image, trial_hints) =
                strobe_map_on(&mut solver, params, trial, period, hints)?;
            hints = trial_hints.filter(|_| chain).or(hints);
            let (trial_norm, trial_r) = residual(&trial_image, trial);
            if trial_norm < norm || halvings == options.max_halvings {
                (x, image, norm, r) = (trial, trial_image, trial_norm, trial_r);
                break;
            }
            fraction *= 0.5;
            halvings += 1;
        }
        iterations += 1;
        residuals.push(norm);
    }
    let within =
        options.tolerance * 1f64.max(x.y.abs()).max(x.v.abs()) * image.jacobian.max_abs().max(1.0);
    if on_jump(x, &image, within) {
        return Err(jump(x));
    }
    let multipliers = image.jacobian.eigenvalues();
    let modulus = multipliers[0].modulus();
    let stability = if (1.0 - modulus).abs() <= options.neutral_band
        || tends_to_one(params, x, &image, r, period, modulus, hints, &mut solver)
    {
        Stability::Neutral
    } else if modulus < 1.0 {
        Stability::Stable
    } else {
        Stability::Unstable
    };
    if loose.is_some() {
        let m = image.jacobian;
        let step = if image.stuck_at_start && image.stuck_at_end {
            let slope = m.0[0][0] - 1.0;
            [if slope != 0.0 { -r[0] / slope } else { 0.0 }, 0.0]
        } else {
            m.minus_identity()
                .solve([-r[0], -r[1]])
                .unwrap_or([0.0, 0.0])
        };
        if let Ok(next) = State::new(x.y + step[0], x.v + step[1]) {
            x = next;
        }
    }
    let orbit = PeriodicOrbit::from_image(
        params,
        period,
        x,
        image,
        (multipliers, stability),
        iterations,
        residuals,
    );
    Ok((orbit, hints))
}

/// Beyond this distance from 1 the largest multiplier modulus is taken as Newton's method
/// leaves it. At a tangential fixed point (a double root of P(x) − x) the distance left at
/// the tolerance is of the order of the square root of the residual: below 1e-5 for the
/// default tolerance on states of order 1.
const TANGENCY_PROBE_BELOW: f64 = 1e-3;

/// Whether the distance d = 1 − |μ₁| of the converged `x` is an artifact of where Newton's
/// method stopped rather than a property of the orbit. One more Newton step from `x` gives
/// d₁. At a simple fixed point the step is of the order of the residual and d₁ = d to that
/// order. At a fixed point where M − I is singular (a tangency of P(x) and x, the edge of a
/// family of periodic orbits: Newton's method converges there only linearly, halving its
/// distance to the root each step) d shrinks with the distance left to the root, which the
/// residual cannot resolve below its square root, and its limit is 0: a multiplier 1. Such an
/// orbit is neutral: when 0 < d₁/d < 0.9 (the modulus moves toward 1 by more than a tenth of
/// its distance in one step), its verdict is not stable or unstable.
///
/// An example: ζ = 0, w = ½, β = 5, φ = π + 0.5, μs = 1 from (−6.4, 1). Newton's method
/// reaches the edge of the family of period-1 orbits in 23 linear steps and stops on orbits
/// with a stop of 4·10⁻⁴ to 5.3·10⁻⁴ (the start decides which), |μ₁| = cos(stop) to 10⁻⁹
/// (between 1 − 1.4·10⁻⁷ and 1 − 7·10⁻⁸); d₁/d ≈ 0.47.
fn tends_to_one(
    params: &Params,
    x: State,
    image: &StrobeImage,
    r: [f64; 2],
    period: usize,
    modulus: f64,
    hints: Option<Hints>,
    solver: &mut Option<ExactSolver>,
) -> bool {
    let d = 1.0 - modulus;
    if d.abs() > TANGENCY_PROBE_BELOW {
        return false;
    }
    let m = image.jacobian;
    let step = if image.stuck_at_start && image.stuck_at_end {
        let slope = m.0[0][0] - 1.0;
        if !(slope != 0.0 && slope.is_finite()) {
            return false;
        }
        [-r[0] / slope, 0.0]
    } else {
        match m.minus_identity().solve([-r[0], -r[1]]) {
            Some(step) => step,
            None => return false,
        }
    };
    let Ok(next) = State::new(x.y + step[0], x.v + step[1]) else {
        return false;
    };
    let Ok((next_image, _)) = strobe_map_on(solver, params, next, period, hints) else {
        return false;
    };
    let ratio = (1.0 - next_image.jacobian.eigenvalues()[0].modulus()) / d;
    ratio > 0.0 && ratio < 0.9
}

/// The stops of one orbit period [0, end] from its events (a stop over the end joins the one
/// at the start).
pub(crate) fn stops(events: &[Event], stuck_at_start: bool, end: f64) -> Vec<Stop> {
    let mut out = Vec::new();
    let mut since = stuck_at_start.then_some(0.0);
    let mut head: Option<f64> = None;
    for e in events {
        match e.kind {
            EventKind::Stick => since = Some(e.tau),
            EventKind::Slip => {
                if let Some(s) = since.take() {
                    if stuck_at_start && s == 0.0 && head.is_none() && out.is_empty() {
                        head = Some(e.tau);
                    } else {
                        out.push(Stop {
                            start: s,
                            duration: e.tau - s,
                        });
                    }
                }
            }
            EventKind::Turn => {}
        }
    }
    match (head, since) {
        (Some(h), Some(s)) => out.push(Stop {
            start: s,
            duration: end - s + h,
        }),
        (Some(h), None) => out.push(Stop {
            start: 0.0,
            duration: h,
        }),
        (None, Some(s)) => out.push(Stop {
            start: s,
            duration: end - s,
        }),
        (None, None) => {}
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    fn ev(tau: f64, kind: EventKind) -> Event {
        Event { tau, y: 0.0, kind }
    }

    #[test]
    fn stops_join_over_the_end_and_keep_zero_durations() {
        let events = [
            ev(0.5, EventKind::Slip),
            ev(1.0, EventKind::Stick),
            ev(1.0, EventKind::Slip),
            ev(3.5, EventKind::Stick),
        ];
        let s = stops(&events, true, 4.0);
        assert_eq!(
            s,
            vec![
                Stop {
                    start: 1.0,
                    duration: 0.0
                },
                Stop {
                    start: 3.5,
                    duration: 1.0
                }
            ]
        );
        assert_eq!(
            stops(&[], true, 4.0),
            vec![Stop {
                start: 0.0,
                duration: 4.0
            }]
        );
        assert!(stops(&[ev(1.0, EventKind::Turn)], false, 4.0).is_empty());
    }
}
