//! Branches of periodic orbits by pseudo-arclength continuation, with the event sequence
//! re-detected at every step.
//!
//! A periodic orbit of period p (drive periods) is a zero of
//!
//! ```text
//! F(x, λ) = P^p(x; λ) − x,       x = (y, y') at the strobe, λ one of ζ, w, β, μs,
//! ```
//!
//! with P^p the p-fold strobe map of the exact solver ([`crate::stability::strobe_map`]). Its
//! zeros form curves in (y, y', λ), the branches. Continuation follows a branch by steps of
//! arclength Δs: from a point u_k with unit tangent t_k (the null vector of the 2×3 Jacobian
//! `[M − I | ∂P^p/∂λ]`, oriented along the branch), the predictor u_k + Δs·t_k is corrected by
//! Newton's method onto the branch within the hyperplane t_k·(u − u_k) = Δs. Along the
//! hyperplane the corrector's matrix `[[M − I, ∂P^p/∂λ], [t_kᵀ]]` stays regular at a fold,
//! where M − I alone is singular, so the branch goes round folds and on along their unstable
//! side. M is the exact monodromy matrix ([`crate::stability`]); ∂P^p/∂λ is a central
//! difference (step [`ContinuationOptions::derivative_step`] relative), which only slows the
//! corrector's convergence, not the accuracy of the points (the residual is exact). Every
//! accepted point is confirmed as an orbit by [`crate::stability::find_periodic_orbit`] to
//! its tolerance, which also gives its events, stops and Floquet multipliers.
//!
//! **No fixed event sequence.** Every evaluation of P^p runs the exact solver, which finds the
//! events of that orbit by itself: when a turning point becomes a stop (or a stop shrinks to
//! nothing, or a slide's velocity minimum touches zero) the next step simply has another
//! sequence of events, and the branch goes on. Tools that continue hybrid systems with a
//! prescribed sequence of modes (COCO's hybrid toolbox, PWSDDE-cont) stop there and need the
//! sequence re-entered by hand. The map is continuous across such a change but its Jacobian
//! jumps (a different saltation matrix), so the branch has a kink there and the multipliers
//! jump: a border collision, which may change the stability at once.
//!
//! **Special points** between two accepted points, each located by bisection along the
//! arclength to within [`ContinuationOptions::locate_tolerance`] (which bounds the error of
//! its parameter value, since |t_λ| ≤ 1):
//!
//! - [`SpecialKind::Grazing`]: the event counts of the orbit (turning points, stops) change;
//!   the parameter value, the counts and the multipliers on either side are reported. Grazing
//!   points are located first; they split the interval into smooth pieces, on which:
//! - [`SpecialKind::Fold`]: a real multiplier passes +1 (det(M − I) changes sign) and the
//!   branch turns back in λ (a saddle-node: the stable and the unstable orbit meet);
//!   [`SpecialKind::BranchPoint`] when it passes +1 without turning (another branch crosses,
//!   for example where the symmetry of a symmetric orbit breaks);
//! - [`SpecialKind::PeriodDoubling`]: a real multiplier passes −1 (det(M + I) changes sign): a
//!   branch of period 2p is born;
//! - [`SpecialKind::NeimarkSacker`]: a complex pair passes the unit circle (det M − 1 changes
//!   sign). It cannot happen on orbits that stop (det M = 0) nor, since turns contract phase
//!   area, on sliding orbits with ζ ≥ 0; it is tested for completeness.
//!
//! A change of stability shows as [`Side::stability`] before and after each special point.
//!
//! ```
//! use stickslip::continuation::{continue_orbit, ContinuationOptions, SpecialKind};
//! use stickslip::stability::{find_periodic_orbit, NewtonOptions};
//! use stickslip::{Parameter, Params, State};
//! // The paper's ζ with μs = 1.5 at w = 0.9: the sliding orbit at β = 1.45 turns into one with
//! // two stops per period as β falls below about 1.4133.
//! let params = Params::new(0.046816, 0.9, 1.45).unwrap().with_mu_s(1.5).unwrap();
//! let orbit = find_periodic_orbit(&params, State { y: 0.25, v: 2.1 }, 1, &NewtonOptions::default()).unwrap();
//! let branch = continue_orbit(&params, Parameter::Beta, &orbit, 1.40, &ContinuationOptions::default(), &()).unwrap();
//! let grazing = branch.special.iter().find(|s| s.kind == SpecialKind::Grazing).unwrap();
//! assert_eq!((grazing.before.stops, grazing.after.stops), (0, 2));
//! assert!((grazing.value - 1.4133).abs() < 1e-3);
//! ```

mod corrector;
mod detect;

use crate::error::{Error, Result};
use crate::exact::ExactSolver;
use crate::experiment::{DiodeModel, Experiment};
use crate::options::{Allowed, OptionKey};
use crate::params::{Parameter, Params, State};
use crate::scan::Monitor;
use crate::solver::Solver;
use crate::stability::{Multiplier, NewtonOptions, PeriodicOrbit, Stability};
use crate::steady::periodic_orbit_from_steady;
use corrector::{counts, norm, Problem, Solution};
use serde::{Deserialize, Serialize};
use std::ops::ControlFlow;

/// Options of [`continue_orbit`]. Arclengths are measured in (y, y', λ), all dimensionless.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct ContinuationOptions {
    /// First step of arclength. Default 1e-3.
    pub initial_step: f64,
    /// Smallest step before the continuation gives up. Default 1e-9.
    pub min_step: f64,
    /// Largest step of arclength. Default 0.1.
    pub max_step: f64,
    /// Largest step of the parameter, as a fraction of the range being continued over.
    /// Default 0.02 (at least 50 points over the range).
    pub max_parameter_step: f64,
    /// Largest angle (radians) between the tangents of two neighbouring points on a smooth
    /// piece of the branch; a step that turns more is halved. Default 0.2.
    pub max_angle: f64,
    /// Most points of a branch. Default 5000.
    pub max_points: usize,
    /// Relative tolerance of the residual of P^p(x) − x, as [`NewtonOptions::tolerance`].
    /// Default 1e-12.
    pub tolerance: f64,
    /// Most Newton steps of the corrector. Default 12.
    pub corrector_iterations: usize,
    /// Width in arclength to which special points are located. Default 1e-9.
    pub locate_tolerance: f64,
    /// Step of the difference quotient ∂P^p/∂λ, relative to max(|λ|, 0.1). Default 1e-6.
    pub derivative_step: f64,
}

impl Default for ContinuationOptions {
    fn default() -> Self {
        Self {
            initial_step: 1e-3,
            min_step: 1e-9,
            max_step: 0.1,
            max_parameter_step: 0.02,
            max_angle: 0.2,
            max_points: 5000,
            tolerance: 1e-12,
            corrector_iterations: 12,
            locate_tolerance: 1e-9,
            derivative_step: 1e-6,
        }
    }
}

impl ContinuationOptions {
    /// These options with the largest step of arclength `step`; the first step is lowered to
    /// fit.
    pub fn with_max_step(mut self, step: f64) -> Self {
        self.max_step = step;
        self.initial_step = self.initial_step.min(step);
        self
    }

    /// The step below which the continuation is crawling: 1e3 × `min_step`, or the geometric
    /// mean of `min_step` and `max_step` when that is smaller. A step this small is taken
    /// whatever the angle between tangents, and 25 of them in a row end the branch as
    /// [`BranchEnd::Stalled`]. It lies below `max_step` whenever `max_step > min_step`, so a
    /// small `max_step` is a resolution the steps keep, not a stall.
    pub fn crawl_step(&self) -> f64 {
        (1e3 * self.min_step).min((self.min_step * self.max_step).sqrt())
    }

    /// Check every field.
    ///
    /// # Errors
    /// [`Error::InvalidParameter`] naming the first bad field.
    pub fn validate(self) -> Result<Self> {
        let bad = |name, value: f64, allowed| {
            Err(Error::InvalidParameter {
                name,
                value,
                allowed,
            })
        };
        let positive = |x: f64| x > 0.0 && x.is_finite();
        if !positive(self.min_step) {
            return bad("min_step", self.min_step, "must be finite and > 0");
        }
        if !(positive(self.max_step) && self.max_step >= self.min_step) {
            return Err(Error::InvalidOption {
                option: OptionKey::MaxStep,
                value: self.max_step,
                allowed: Allowed::Text("must be finite and >= min_step"),
            });
        }
        OptionKey::MaxStep.check(self.max_step)?;
        if !(self.initial_step >= self.min_step && self.initial_step <= self.max_step) {
            return bad(
                "initial_step",
                self.initial_step,
                "must lie between min_step and max_step",
            );
        }
        if !(positive(self.max_parameter_step) && self.max_parameter_step <= 1.0) {
            return bad(
                "max_parameter_step",
                self.max_parameter_step,
                "must be > 0 and <= 1",
            );
        }
        if !(positive(self.max_angle) && self.max_angle < std::f64::consts::FRAC_PI_2) {
            return bad("max_angle", self.max_angle, "must be > 0 and < pi/2");
        }
        OptionKey::MaxPoints.check_count(self.max_points)?;
        if !(self.tolerance > 0.0 && self.tolerance < 1e-3) {
            return bad("tolerance", self.tolerance, "must be > 0 and < 1e-3");
        }
        if self.corrector_iterations == 0 {
            return bad("corrector_iterations", 0.0, "must be at least 1");
        }
        if !positive(self.locate_tolerance) {
            return bad(
                "locate_tolerance",
                self.locate_tolerance,
                "must be finite and > 0",
            );
        }
        if !(self.derivative_step > 1e-12 && self.derivative_step < 1e-2) {
            return bad(
                "derivative_step",
                self.derivative_step,
                "must be > 1e-12 and < 1e-2",
            );
        }
        Ok(self)
    }
}

/// A point of a branch: a periodic orbit and where it sits on the branch.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct BranchPoint {
    /// The continued parameter's value.
    pub value: f64,
    /// Arclength from the first point of the branch, in (y, y', λ).
    pub arclength: f64,
    /// The orbit: strobe state (the fixed point of P^p), events, stops, monodromy matrix,
    /// Floquet multipliers, stability.
    pub orbit: PeriodicOrbit,
    /// The p strobe points of the orbit: x, P(x), …, P^{p−1}(x).
    pub strobes: Vec<State>,
    /// Smallest y over the orbit.
    pub y_min: f64,
    /// Largest y over the orbit.
    pub y_max: f64,
    /// Turning points per orbit period.
    pub turns: usize,
    /// Stops (stick events, zero-duration stops included) per orbit period.
    pub stops: usize,
}

impl BranchPoint {
    /// Half the peak-to-peak excursion, (y_max − y_min)/2.
    pub fn amplitude(&self) -> f64 {
        0.5 * (self.y_max - self.y_min)
    }

    /// Stops per drive period.
    pub fn stops_per_period(&self) -> f64 {
        self.stops as f64 / self.orbit.period as f64
    }

    /// Whether the orbit is stable: its larger Floquet multiplier has modulus below 1.
    pub fn stable(&self) -> bool {
        self.orbit.multipliers[0].modulus() < 1.0
    }
}

/// What a special point is (see the module documentation).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum SpecialKind {
    /// A real multiplier through +1, the branch turning back in the parameter.
    Fold,
    /// A real multiplier through +1 without a turn: another branch crosses.
    BranchPoint,
    /// A real multiplier through −1.
    PeriodDoubling,
    /// A complex pair of multipliers through the unit circle.
    NeimarkSacker,
    /// The event counts of the orbit change (a stop or a turning point appears or
    /// disappears).
    Grazing,
}

impl SpecialKind {
    /// The label used in CSV and JSON: `fold`, `branch-point`, `period-doubling`,
    /// `neimark-sacker`, `grazing`.
    pub fn label(self) -> &'static str {
        match self {
            SpecialKind::Fold => "fold",
            SpecialKind::BranchPoint => "branch-point",
            SpecialKind::PeriodDoubling => "period-doubling",
            SpecialKind::NeimarkSacker => "neimark-sacker",
            SpecialKind::Grazing => "grazing",
        }
    }
}

/// The orbit on one side of a special point (one end of the final bracket).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Side {
    /// The parameter's value.
    pub value: f64,
    /// The strobe state.
    pub state: State,
    /// The Floquet multipliers.
    pub multipliers: [Multiplier; 2],
    /// The stability from the largest multiplier modulus strictly (no neutral band: the
    /// ends of a bracket lie within its width of a multiplier at ±1).
    pub stability: Stability,
    /// Turning points per orbit period.
    pub turns: usize,
    /// Stops per orbit period.
    pub stops: usize,
}

/// A special point of a branch, located between two orbits of the branch at most
/// [`SpecialPoint::width`] apart in arclength.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct SpecialPoint {
    /// What happens there.
    pub kind: SpecialKind,
    /// The parameter's value (the middle of the bracket).
    pub value: f64,
    /// The strobe state (the middle of the bracket).
    pub state: State,
    /// Width of the final bracket in arclength: it bounds the error of `value` and of
    /// `state`.
    pub width: f64,
    /// Whether the bracket reached [`ContinuationOptions::locate_tolerance`] (false when the
    /// corrector failed inside it; `width` then says how well it is located).
    pub located: bool,
    /// Index of the branch point just before it.
    pub after_point: usize,
    /// The orbit at the end of the bracket before it (along the branch).
    pub before: Side,
    /// The orbit at the end of the bracket after it.
    pub after: Side,
}

/// Why a branch ends.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case", tag = "reason")]
pub enum BranchEnd {
    /// The orbit the continuation started from (the start of a one-way branch).
    Start,
    /// The parameter reached an end of the range.
    Boundary {
        /// The end of the range.
        value: f64,
    },
    /// [`ContinuationOptions::max_points`] points.
    MaxPoints,
    /// The branch came back to its first point: a closed curve (an isola).
    Closed,
    /// The orbit came to rest (no events: a continuum of rest positions, not a branch).
    Rest {
        /// The parameter's value.
        value: f64,
    },
    /// The steps stayed at or below [`ContinuationOptions::crawl_step`] for 25 points: the
    /// branch approaches a point it cannot pass.
    Stalled {
        /// The parameter's value of the last point.
        value: f64,
        /// The largest multiplier modulus there.
        multiplier: f64,
        /// What the last orbit is closest to.
        obstacle: Obstacle,
    },
    /// No step, however small, could be corrected onto the branch.
    Failed {
        /// The parameter's value of the last point.
        value: f64,
        /// What the last orbit is closest to.
        obstacle: Obstacle,
    },
}

/// Where the strobe map of an orbit is about to jump or lose its derivative: the event of the
/// last orbit of a branch closest to such a switch, when one is close (relative margin below
/// 1e-2).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case", tag = "kind")]
pub enum Obstacle {
    /// A turning point whose net force |F − y| is within `margin` (relative to μs) of the
    /// static limit: beyond it the motion would stop there. For μs > 1 with the force falling
    /// back the stop would last long, so the strobe map jumps and the orbit ends.
    TurnAtStaticLimit {
        /// Time of the turning point from the strobe.
        tau: f64,
        /// (|F − y| − μs)/μs at the turning point.
        margin: f64,
    },
    /// A release (μs > 1) where the drive's force hardly changes any more, |F'|/(βw) =
    /// `rate`: at a tangential release the flow is not differentiable and a multiplier grows
    /// without bound; beyond it the force no longer reaches the static limit.
    TangentialRelease {
        /// Time of the release from the strobe.
        tau: f64,
        /// |F'(τ)|/(βw) at the release.
        rate: f64,
    },
    /// No event of the orbit is close to a switch.
    None,
}

/// The [`Obstacle`] of `orbit` at `params`.
fn obstacle(params: &Params, orbit: &PeriodicOrbit) -> Obstacle {
    let mut best = (1e-2, Obstacle::None);
    for e in &orbit.events {
        let phase = params.w * e.tau + params.phi;
        match e.kind {
            crate::solver::EventKind::Turn => {
                let margin = ((params.drive(e.tau) - e.y).abs() - params.mu_s) / params.mu_s;
                if margin.abs() < best.0 {
                    best = (
                        margin.abs(),
                        Obstacle::TurnAtStaticLimit { tau: e.tau, margin },
                    );
                }
            }
            crate::solver::EventKind::Slip if params.mu_s > 1.0 => {
                let rate = phase.sin().abs();
                if rate < best.0 {
                    best = (rate, Obstacle::TangentialRelease { tau: e.tau, rate });
                }
            }
            _ => {}
        }
    }
    best.1
}

/// A branch of periodic orbits (see the module documentation).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Branch {
    /// The parameters of the start orbit (the continued one varies along the branch).
    pub params: Params,
    /// The continued parameter.
    pub parameter: Parameter,
    /// Period p of the orbits in drive periods.
    pub period: usize,
    /// The points in order along the branch.
    pub points: Vec<BranchPoint>,
    /// The special points in order along the branch.
    pub special: Vec<SpecialPoint>,
    /// How the branch ends before its first point.
    pub begin: BranchEnd,
    /// How the branch ends after its last point.
    pub end: BranchEnd,
}

impl std::fmt::Display for Obstacle {
    /// "; a turning point is 1.2e-3 (relative) from the static friction limit, …", or
    /// nothing when no event is close to a switch.
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Obstacle::TurnAtStaticLimit { margin, .. } => write!(
                f,
                "; a turning point is {margin:.1e} (relative) from the static friction limit, \
                 where it would become a stop"
            ),
            Obstacle::TangentialRelease { rate, .. } => write!(
                f,
                "; a release happens where the drive's force hardly changes \
                 (|F'|/βw = {rate:.1e}): it is becoming tangential"
            ),
            Obstacle::None => Ok(()),
        }
    }
}

impl std::fmt::Display for BranchEnd {
    /// Why the branch ends, in words (one line).
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            BranchEnd::Start => f.write_str("the start orbit"),
            BranchEnd::Boundary { value } => write!(f, "the end of the range at {value}"),
            BranchEnd::MaxPoints => f.write_str("the most points allowed (max points)"),
            BranchEnd::Closed => f.write_str("back at its first point (a closed branch)"),
            BranchEnd::Rest { value } => write!(f, "the orbit comes to rest at {value}"),
            BranchEnd::Stalled {
                value,
                multiplier,
                obstacle,
            } => write!(
                f,
                "no progress near {value:.8} (largest multiplier modulus {multiplier:.3e}){obstacle}"
            ),
            BranchEnd::Failed { value, obstacle } => write!(
                f,
                "no orbit could be corrected past {value:.8}: the strobe map breaks there{obstacle}"
            ),
        }
    }
}

/// What a branch reports besides its points: exactly what `stickslip continue --json` prints
/// and what the Python package's `continuation` returns as its summary. Build it with
/// `BranchReport::from(&branch)`.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct BranchReport {
    /// The continued parameter (`w`, `beta`, `zeta` or `mu_s`).
    pub parameter: &'static str,
    /// Period of the orbits in drive periods.
    pub period: usize,
    /// Number of points of the branch.
    pub points: usize,
    /// How the branch ends before its first point.
    pub begin: BranchEnd,
    /// How it ends after its last point.
    pub end: BranchEnd,
    /// `end` in words.
    pub end_text: String,
    /// The special points in order along the branch.
    pub special: Vec<SpecialReport>,
}

/// A special point in a [`BranchReport`].
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct SpecialReport {
    /// `fold`, `branch-point`, `period-doubling`, `neimark-sacker` or `grazing`.
    pub kind: SpecialKind,
    /// The parameter's value.
    pub value: f64,
    /// The strobe point (y, y').
    pub y: f64,
    /// See `y`.
    pub v: f64,
    /// Width of the final bracket in arclength (bounds the error of `value`).
    pub width: f64,
    /// Whether the bracket reached the locating tolerance.
    pub located: bool,
    /// The orbit at the end of the bracket before it.
    pub before: SideReport,
    /// The orbit at the end of the bracket after it.
    pub after: SideReport,
}

/// One side of a special point in a [`BranchReport`].
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct SideReport {
    /// The parameter's value.
    pub value: f64,
    /// The strobe point (y, y').
    pub y: f64,
    /// See `y`.
    pub v: f64,
    /// Stops per orbit period.
    pub stops: usize,
    /// Turning points per orbit period.
    pub turns: usize,
    /// Floquet multipliers as [re, im] pairs, the larger first.
    pub multipliers: [[f64; 2]; 2],
    /// Whether the larger multiplier has modulus below 1.
    pub stable: bool,
}

impl From<&Side> for SideReport {
    fn from(s: &Side) -> Self {
        let m = &s.multipliers;
        Self {
            value: s.value,
            y: s.state.y,
            v: s.state.v,
            stops: s.stops,
            turns: s.turns,
            multipliers: [[m[0].re, m[0].im], [m[1].re, m[1].im]],
            stable: m[0].modulus() < 1.0,
        }
    }
}

impl From<&Branch> for BranchReport {
    fn from(branch: &Branch) -> Self {
        Self {
            parameter: branch.parameter.label(),
            period: branch.period,
            points: branch.points.len(),
            begin: branch.begin.clone(),
            end: branch.end.clone(),
            end_text: branch.end.to_string(),
            special: branch
                .special
                .iter()
                .map(|s| SpecialReport {
                    kind: s.kind,
                    value: s.value,
                    y: s.state.y,
                    v: s.state.v,
                    width: s.width,
                    located: s.located,
                    before: SideReport::from(&s.before),
                    after: SideReport::from(&s.after),
                })
                .collect(),
        }
    }
}

/// The p strobe points of an orbit and its extremes in y.
fn strobes_and_extremes(params: &Params, orbit: &PeriodicOrbit) -> Result<(Vec<State>, f64, f64)> {
    let mut solver = ExactSolver::new(*params, orbit.state);
    let mut strobes = vec![orbit.state];
    for k in 1..orbit.period {
        crate::solver::run_until(&mut solver, k as f64 * orbit.drive_period, |_| {})?;
        strobes.push(solver.state());
    }
    let ys = orbit
        .events
        .iter()
        .map(|e| e.y)
        .chain(strobes.iter().map(|s| s.y));
    let (lo, hi) = ys.fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), y| {
        (lo.min(y), hi.max(y))
    });
    Ok((strobes, lo, hi))
}

fn branch_point(problem: &Problem, s: &Solution, arclength: f64) -> Result<BranchPoint> {
    let params = problem.params(s.u[2])?;
    let (strobes, y_min, y_max) = strobes_and_extremes(&params, &s.orbit)?;
    let (turns, stops) = counts(&s.orbit);
    Ok(BranchPoint {
        value: s.u[2],
        arclength,
        orbit: s.orbit.clone(),
        strobes,
        y_min,
        y_max,
        turns,
        stops,
    })
}

/// The angle between two unit vectors.
fn angle(a: &[f64; 3], b: &[f64; 3]) -> f64 {
    corrector::dot(a, b).clamp(-1.0, 1.0).acos()
}

/// A step in the parameter alone (Newton's method at λ + Δλ from the current state), taken
/// where the pseudo-arclength step fails: past a kink of the branch at a grazing point, whose
/// two sides can meet at so sharp an angle that no hyperplane across the tangent before it
/// meets the branch after it. Accepted when it lands within 4·Δs and either crosses a change
/// of the event counts or turns the tangent by at most the largest angle.
fn natural_step(
    problem: &Problem,
    current: &Solution,
    ds: f64,
    options: &ContinuationOptions,
) -> Result<Option<Solution>> {
    let t = current.tangent;
    if t[2] == 0.0 {
        return Ok(None);
    }
    let dl = ds * t[2];
    let Some(next) = problem.natural(current.u[2] + dl, current.orbit.state, dl.signum())? else {
        return Ok(None);
    };
    let d = [
        next.u[0] - current.u[0],
        next.u[1] - current.u[1],
        next.u[2] - current.u[2],
    ];
    let kink = counts(&next.orbit) != counts(&current.orbit);
    let mut next = next;
    if !kink && corrector::dot(&next.tangent, &t) < 0.0 {
        next.tangent.iter_mut().for_each(|c| *c = -*c);
    }
    // Forward along the branch: within 60° of the tangent on a smooth piece, λ moving on
    // across a kink.
    let forward = if kink {
        d[2] * t[2] > 0.0
    } else {
        corrector::dot(&d, &t) > 0.5 * norm(&d)
    };
    let ok =
        forward && norm(&d) <= 4.0 * ds && (kink || angle(&next.tangent, &t) <= options.max_angle);
    Ok(ok.then_some(next))
}

/// The point of the branch at the end `bound` of the range, between `current` (inside) and
/// `next` (outside, at arclength `ds` or by a natural step), by the secant; with its
/// arclength from `current`. `None` when it cannot be found.
fn aim_at(
    problem: &Problem,
    current: &Solution,
    next: &Solution,
    ds: f64,
    natural: bool,
    bound: f64,
    (lo, hi): (f64, f64),
) -> Result<Option<(f64, Solution)>> {
    let (mut s_in, mut l_in) = (0.0, current.u[2]);
    let (mut s_out, mut l_out) = (1.0, next.u[2]);
    let mut inside = None;
    for _ in 0..30 {
        let s = s_in + (bound - l_in) * (s_out - s_in) / (l_out - l_in);
        if !(s > s_in && s < s_out) {
            break;
        }
        let candidate = if natural {
            let guess = State {
                y: current.u[0] + s * (next.u[0] - current.u[0]),
                v: current.u[1] + s * (next.u[1] - current.u[1]),
            };
            problem.natural(
                current.u[2] + s * (next.u[2] - current.u[2]),
                guess,
                next.u[2] - current.u[2],
            )?
        } else {
            problem.correct(current, s * ds)?
        };
        let Some(candidate) = candidate else {
            break;
        };
        let l = candidate.u[2];
        let outside = l < lo || l > hi;
        let arclength = if natural {
            norm(&[
                candidate.u[0] - current.u[0],
                candidate.u[1] - current.u[1],
                candidate.u[2] - current.u[2],
            ])
        } else {
            s * ds
        };
        if !outside && (l - bound).abs() <= 1e-12 * bound.abs().max(1.0) {
            return Ok(Some((arclength, candidate)));
        }
        if outside {
            (s_out, l_out) = (s, l);
        } else {
            (s_in, l_in) = (s, l);
            inside = Some((arclength, candidate));
        }
    }
    Ok(inside)
}

/// Check the ends of a branch before any work: both finite and `to` another value than
/// `from` (the ranges of the parameter are the experiment's to check).
///
/// # Errors
/// [`Error::InvalidOption`] naming [`OptionKey::ContinuationFrom`] or
/// [`OptionKey::ContinuationTo`] (`invalid --to 1.2: must differ from --from`).
pub fn check_ends(from: f64, to: f64) -> Result<()> {
    OptionKey::ContinuationFrom.check(from)?;
    OptionKey::ContinuationTo.check(to)?;
    if to == from {
        return Err(Error::InvalidOption {
            option: OptionKey::ContinuationTo,
            value: to,
            allowed: Allowed::Differs {
                other: OptionKey::ContinuationFrom,
            },
        });
    }
    Ok(())
}

/// Continue the branch of `start` (a periodic orbit at `params`, found by
/// [`crate::stability::find_periodic_orbit`]) in `parameter` from its value in `params`
/// towards `to`, within the range between the two (see the module documentation); `monitor`
/// sees the number of points against [`ContinuationOptions::max_points`] and can stop the
/// work.
///
/// # Errors
/// [`Error::InvalidParameter`] for invalid options, `to` equal to the start value or out of
/// the parameter's range, or a start orbit at rest; [`Error::Cancelled`];
/// [`crate::stability::StabilityError::SingularJacobian`] when the branch has no tangent at
/// the start; whatever the solver reports.
pub fn continue_orbit(
    params: &Params,
    parameter: Parameter,
    start: &PeriodicOrbit,
    to: f64,
    options: &ContinuationOptions,
    monitor: &dyn Monitor,
) -> Result<Branch> {
    let options = options.validate()?;
    let params = params.validate()?;
    let from = parameter.get(&params);
    parameter.set(params, to)?;
    if to == from {
        return Err(Error::InvalidParameter {
            name: "to",
            value: to,
            allowed: "must differ from the start value",
        });
    }
    if start.events.is_empty() {
        return Err(Error::InvalidParameter {
            name: "start",
            value: start.state.y,
            allowed: "the start orbit is rest (no events): rest positions form a continuum, \
                      not a branch",
        });
    }
    let (lo, hi) = (from.min(to), from.max(to));
    let span = hi - lo;
    let problem = Problem {
        base: params,
        parameter,
        period: start.period,
        options,
    };
    let direction = (to - from).signum();
    let Some(mut current) = problem.start(start.clone(), from, direction)? else {
        return Err(crate::stability::StabilityError::SingularJacobian {
            y: start.state.y,
            v: start.state.v,
            determinant: start.monodromy.minus_identity().det(),
        }
        .into());
    };
    let first = current.u;
    let mut points = vec![branch_point(&problem, &current, 0.0)?];
    let mut special = Vec::new();
    let mut ds = options.initial_step;
    let mut arclength = 0.0;
    let mut crawling = 0usize;
    let end = loop {
        if points.len() >= options.max_points {
            break BranchEnd::MaxPoints;
        }
        if monitor.step(points.len(), options.max_points) == ControlFlow::Break(()) {
            return Err(Error::Cancelled {
                done: points.len(),
                total: options.max_points,
            });
        }
        let t_lambda = current.tangent[2].abs();
        let cap = if t_lambda > 0.0 {
            options
                .max_step
                .min(options.max_parameter_step * span / t_lambda)
        } else {
            options.max_step
        };
        ds = ds.min(cap).max(options.min_step);
        let trial = problem.correct(&current, ds)?;
        let accepted = trial.filter(|s| {
            let smooth = counts(&s.orbit) == counts(&current.orbit);
            !smooth
                || angle(&s.tangent, &current.tangent) <= options.max_angle
                || ds <= options.crawl_step()
        });
        let (mut next, mut natural) = match accepted {
            Some(next) => (next, false),
            None => match natural_step(&problem, &current, ds, &options)? {
                Some(next) => (next, true),
                None => {
                    if ds <= options.min_step {
                        break BranchEnd::Failed {
                            value: current.u[2],
                            obstacle: obstacle(&problem.params(current.u[2])?, &current.orbit),
                        };
                    }
                    ds = (0.5 * ds).max(options.min_step);
                    continue;
                }
            },
        };
        // Past an end of the range: aim the step at the end by the secant.
        let mut sigma = ds;
        let mut boundary = None;
        if next.u[2] < lo || next.u[2] > hi {
            let bound = if next.u[2] > hi { hi } else { lo };
            match aim_at(&problem, &current, &next, ds, natural, bound, (lo, hi))? {
                Some((s, candidate)) => {
                    sigma = s;
                    // End exactly at the bound: a last Newton correction in the state alone.
                    let direction = candidate.u[2] - current.u[2];
                    next = problem
                        .natural(bound, candidate.orbit.state, direction)?
                        .filter(|n| counts(&n.orbit) == counts(&candidate.orbit))
                        .unwrap_or(candidate);
                    if corrector::dot(&next.tangent, &current.tangent) < 0.0 && !natural {
                        next.tangent.iter_mut().for_each(|c| *c = -*c);
                    }
                    boundary = Some(bound);
                }
                None => break BranchEnd::Boundary { value: bound },
            }
        }
        let found = if natural {
            let (a, b) = (current.clone(), next.clone());
            let direction = next.u[2] - current.u[2];
            detect::between(
                &problem,
                &|t| {
                    let guess = State {
                        y: a.u[0] + t * (b.u[0] - a.u[0]),
                        v: a.u[1] + t * (b.u[1] - a.u[1]),
                    };
                    problem.natural(a.u[2] + t * (b.u[2] - a.u[2]), guess, direction)
                },
                &current,
                &next,
                points.len() - 1,
            )?
        } else {
            detect::between(
                &problem,
                &|t| problem.correct(&current, t * sigma),
                &current,
                &next,
                points.len() - 1,
            )?
        };
        special.extend(found);
        if natural {
            sigma = norm(&[
                next.u[0] - current.u[0],
                next.u[1] - current.u[1],
                next.u[2] - current.u[2],
            ]);
            natural = false;
        }
        let _ = natural;
        arclength += sigma;
        points.push(branch_point(&problem, &next, arclength)?);
        if next.orbit.events.is_empty() {
            break BranchEnd::Rest { value: next.u[2] };
        }
        if let Some(value) = boundary {
            break BranchEnd::Boundary { value };
        }
        let back = [
            next.u[0] - first[0],
            next.u[1] - first[1],
            next.u[2] - first[2],
        ];
        if points.len() > 10 && norm(&back) < sigma {
            break BranchEnd::Closed;
        }
        crawling = if sigma <= options.crawl_step() {
            crawling + 1
        } else {
            0
        };
        if crawling >= 25 {
            break BranchEnd::Stalled {
                value: next.u[2],
                multiplier: next.orbit.multipliers[0].modulus(),
                obstacle: obstacle(&problem.params(next.u[2])?, &next.orbit),
            };
        }
        current = next;
        ds = (1.5 * ds).min(options.max_step);
    };
    Ok(Branch {
        params,
        parameter,
        period: start.period,
        points,
        special,
        begin: BranchEnd::Start,
        end,
    })
}

/// Continue the branch of `start` both ways over the range from `lo` to `hi` (which holds
/// the start value): the points in order of the branch from the end reached going down in
/// λ to the end reached going up, arclength from the first.
///
/// # Errors
/// As [`continue_orbit`]; [`Error::InvalidParameter`] when the range does not hold the start
/// value or is empty.
pub fn continue_both_ways(
    params: &Params,
    parameter: Parameter,
    start: &PeriodicOrbit,
    (lo, hi): (f64, f64),
    options: &ContinuationOptions,
    monitor: &dyn Monitor,
) -> Result<Branch> {
    let from = parameter.get(params);
    if !(lo <= from && from <= hi && lo < hi) {
        return Err(Error::InvalidParameter {
            name: parameter.label(),
            value: from,
            allowed: "the start value must lie in the range, and the range must not be empty",
        });
    }
    let down = if from > lo {
        Some(continue_orbit(
            params, parameter, start, lo, options, monitor,
        )?)
    } else {
        None
    };
    let up = if from < hi {
        Some(continue_orbit(
            params, parameter, start, hi, options, monitor,
        )?)
    } else {
        None
    };
    Ok(join(down, up, *params, parameter, start.period))
}

/// One branch from a branch run downwards (reversed) and one run upwards from the same start.
fn join(
    down: Option<Branch>,
    up: Option<Branch>,
    params: Params,
    parameter: Parameter,
    period: usize,
) -> Branch {
    let mut points = Vec::new();
    let mut special = Vec::new();
    let mut begin = BranchEnd::Start;
    let mut end = BranchEnd::Start;
    if let Some(d) = down {
        let n = d.points.len();
        let total = d.points.last().map_or(0.0, |p| p.arclength);
        points.extend(d.points.into_iter().rev().map(|mut p| {
            p.arclength = total - p.arclength;
            p
        }));
        // Along the reversed run a special point after point i lies after point n − 2 − i,
        // with its sides swapped.
        special.extend(d.special.into_iter().rev().map(|mut s| {
            s.after_point = n - 2 - s.after_point;
            std::mem::swap(&mut s.before, &mut s.after);
            s
        }));
        begin = d.end;
    }
    if let Some(u) = up {
        let offset = points.len().saturating_sub(1);
        let base = points.last().map_or(0.0, |p| p.arclength);
        let skip = usize::from(!points.is_empty());
        points.extend(u.points.into_iter().skip(skip).map(|mut p| {
            p.arclength += base;
            p
        }));
        special.extend(u.special.into_iter().map(|mut s| {
            s.after_point += offset;
            s
        }));
        end = u.end;
    }
    Branch {
        params,
        parameter,
        period,
        points,
        special,
        begin,
        end,
    }
}

/// The periodic orbit the motion of `experiment` settles on from its initial state (its
/// steady state, refined by Newton's method): where `stickslip continue` starts.
///
/// # Errors
/// [`crate::Unsupported::StabilityNeedsPwl`] for Shockley diodes;
/// [`crate::stability::StabilityError::NoPeriod`] when the motion finds no period;
/// whatever the solver and Newton's method report.
pub fn settled_orbit(experiment: &Experiment) -> Result<(Params, PeriodicOrbit)> {
    if experiment.diode_model() != DiodeModel::Pwl {
        return Err(Error::Unsupported(crate::Unsupported::StabilityNeedsPwl));
    }
    let options = experiment.steady_options().with_spectrum(false);
    let steady = experiment.steady_with(&options)?;
    let params = steady.params;
    let orbit = periodic_orbit_from_steady(&params, &steady, &NewtonOptions::default())?;
    Ok((params, orbit))
}
