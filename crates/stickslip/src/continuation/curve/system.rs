//! The extended system of a curve, its derivatives and the corrector.
//!
//! The unknowns are u = (y, y', Q, P); the equations P^p(x; Q, P) − x = 0 and g(u) = 0, the
//! followed condition, with one more equation that places the point (a hyperplane across the
//! curve's tangent, or a fixed value of one unknown).

use super::border::{candidates, candidates_of, earliest, nearest, Candidate};
use super::{Border, BorderKind, Follow};
use crate::continuation::corrector::counts;
use crate::continuation::ContinuationOptions;
use crate::error::{Error, Result};
use crate::params::{Parameter, Params, State};
use crate::stability::{
    strobe_map_parameter_derivative, strobe_map_parameter_derivatives, Dynamics, NewtonOptions,
    PeriodicOrbit, StrobeImage,
};
use std::sync::Arc;

/// A point (y, y', Q, P).
pub(crate) type U = [f64; 4];

pub(crate) fn dot(a: &U, b: &U) -> f64 {
    a.iter().zip(b).map(|(x, y)| x * y).sum()
}

pub(crate) fn norm(a: &U) -> f64 {
    dot(a, a).sqrt()
}

pub(crate) fn distance(a: &U, b: &U) -> f64 {
    a.iter()
        .zip(b)
        .map(|(x, y)| (x - y) * (x - y))
        .sum::<f64>()
        .sqrt()
}

/// Solve the 4×4 system `a x = b` by Gaussian elimination with partial pivoting; `None` when
/// it is singular or not finite.
pub(crate) fn solve4(mut a: [[f64; 4]; 4], mut b: [f64; 4]) -> Option<[f64; 4]> {
    for col in 0..4 {
        let pivot = (col..4).max_by(|&i, &j| a[i][col].abs().total_cmp(&a[j][col].abs()))?;
        if !(a[pivot][col].abs() > 0.0 && a[pivot][col].is_finite()) {
            return None;
        }
        a.swap(col, pivot);
        b.swap(col, pivot);
        for row in col + 1..4 {
            let f = a[row][col] / a[col][col];
            if f != 0.0 {
                for k in col..4 {
                    a[row][k] -= f * a[col][k];
                }
                b[row] -= f * b[col];
            }
        }
    }
    let mut x = [0.0; 4];
    for row in (0..4).rev() {
        let mut s = b[row];
        for k in row + 1..4 {
            s -= a[row][k] * x[k];
        }
        x[row] = s / a[row][row];
    }
    x.iter().all(|v| v.is_finite()).then_some(x)
}

/// The column of [`strobe_map_parameter_derivatives`] for `parameter` (one of the paper's
/// four), or 5 for the belt speed vb (its own derivative,
/// [`crate::stability::strobe_map_parameter_derivative`]); a friction law's parameters are
/// refused.
///
/// # Errors
/// [`Error::InvalidParameter`] naming a parameter of a friction law.
pub(crate) fn column(parameter: Parameter) -> Result<usize> {
    match parameter {
        Parameter::Zeta => Ok(0),
        Parameter::Beta => Ok(1),
        Parameter::W => Ok(2),
        Parameter::MuS => Ok(4),
        Parameter::Vb => Ok(5),
        other => Err(Error::InvalidParameter {
            name: other.label(),
            value: f64::NAN,
            allowed: "is no parameter a curve follows yet: take w, beta, zeta, mu_s or vb",
        }),
    }
}

/// `Ok` when a curve of `dynamics` at `params` can be followed in or over `parameter`: with
/// the exact model one of the paper's four or vb ([`column()`]); with a smooth friction law any
/// parameter of the model at `params` (ζ, w, β, μs, the belt's speed vb, the law's own), whose
/// derivatives the model's sensitivities give ([`Dynamics::parameter_derivative`]).
///
/// # Errors
/// As [`column()`] for the exact model; [`Error::InvalidParameter`] for a parameter of another
/// friction law.
pub(crate) fn check_parameter(
    dynamics: &dyn Dynamics,
    params: &Params,
    parameter: Parameter,
) -> Result<()> {
    if dynamics.is_exact() {
        column(parameter).map(drop)
    } else {
        parameter.set(*params, parameter.get(params)).map(drop)
    }
}

/// Where the corrector places its point besides the curve's equations.
#[derive(Debug, Clone, Copy)]
pub(crate) enum Plane {
    /// The hyperplane through `from + sigma·tangent` orthogonal to `tangent`.
    Arc { from: U, tangent: U, sigma: f64 },
    /// The unknown `index` fixed at `value`.
    Fixed { index: usize, value: f64 },
}

impl Plane {
    /// The residual of the plane's equation at u and its gradient.
    fn residual(&self, u: &U) -> (f64, U) {
        match *self {
            Plane::Arc {
                from,
                tangent,
                sigma,
            } => {
                let d = [
                    u[0] - from[0] - sigma * tangent[0],
                    u[1] - from[1] - sigma * tangent[1],
                    u[2] - from[2] - sigma * tangent[2],
                    u[3] - from[3] - sigma * tangent[3],
                ];
                (dot(&tangent, &d), tangent)
            }
            Plane::Fixed { index, value } => {
                let mut row = [0.0; 4];
                row[index] = 1.0;
                (u[index] - value, row)
            }
        }
    }

    /// The scale of the plane's residual.
    fn scale(&self) -> f64 {
        match *self {
            Plane::Arc { sigma, .. } => 1.0 + sigma.abs(),
            Plane::Fixed { value, .. } => 1.0 + value.abs(),
        }
    }

    /// The point where the corrector starts.
    pub(crate) fn prediction(&self, current: &U) -> U {
        match *self {
            Plane::Arc {
                from,
                tangent,
                sigma,
            } => [
                from[0] + sigma * tangent[0],
                from[1] + sigma * tangent[1],
                from[2] + sigma * tangent[2],
                from[3] + sigma * tangent[3],
            ],
            Plane::Fixed { index, value } => {
                let mut u = *current;
                u[index] = value;
                u
            }
        }
    }
}

/// A converged point of the curve.
#[derive(Debug, Clone)]
pub(crate) struct Node {
    pub u: U,
    /// Time of the followed event from the strobe (grazing curves; NaN otherwise).
    pub tau: f64,
    pub orbit: PeriodicOrbit,
    /// The unit tangent, oriented along the curve.
    pub tangent: U,
    /// (turns, stops) per orbit period.
    pub counts: (usize, usize),
    /// The 3×4 Jacobian of the extended system at u (the one the tangent is the null vector
    /// of), when the node was corrected by this system: [`System::across`] starts from it.
    pub rows: Option<[[f64; 4]; 3]>,
    /// The monodromy matrix just across the border ([`System::across`]), once asked for: the
    /// codimension-two tests of a step read it at both its ends.
    pub across: std::sync::OnceLock<Option<crate::stability::Matrix2>>,
}

/// The map and the condition at one u.
struct Evaluation {
    image: StrobeImage,
    g: f64,
    tau: f64,
}

/// The curve's problem.
#[derive(Debug, Clone)]
pub(crate) struct System {
    pub base: Params,
    pub over: Parameter,
    pub vary: Parameter,
    pub period: usize,
    pub follow: Follow,
    pub border: Option<Border>,
    pub options: ContinuationOptions,
    /// The drive phase of the chart's section from the model's strobe, in [0, 2πp): the
    /// unknowns (y, y') are the state at drive phase φ + `phase` (see [`System::section`]).
    pub phase: f64,
    /// The model: its strobe map with the monodromy matrix, Newton's method for its orbits,
    /// its solver and parameter derivatives (the exact model's exact ones, or a smooth
    /// friction law's from the stiff solver's sensitivities).
    pub dynamics: Arc<dyn Dynamics>,
}

/// Whether an error of the map or of the parameters means "no point here" rather than a
/// failure to report.
fn absent(e: &Error) -> bool {
    matches!(
        e,
        Error::Stability(_) | Error::InvalidParameter { .. } | Error::EventSearch { .. }
    )
}

impl System {
    /// The residual tolerance of the extended system: the options' for the exact model, at
    /// least the relative accuracy of a stiff solver's map ([`Dynamics::map_tolerance`]).
    pub(crate) fn tolerance(&self) -> f64 {
        self.dynamics.map_tolerance(self.options.tolerance)
    }

    /// The Newton options that confirm a corrected point as an orbit without a step.
    fn confirming(&self) -> NewtonOptions {
        NewtonOptions {
            tolerance: self.tolerance(),
            max_iterations: 2,
            ..NewtonOptions::default()
        }
    }

    /// Whether `orbit` is rest, not an orbit to follow: no events (the exact model's
    /// criterion, kept to the bit), or for a smooth law no events and stuck at its strobe
    /// (an orbit that slides throughout against a belt has no events and is no rest).
    fn rest(&self, orbit: &PeriodicOrbit) -> bool {
        if self.dynamics.is_exact() {
            orbit.events.is_empty()
        } else {
            orbit.is_rest()
        }
    }

    /// `params` (of any chart) with this chart's drive phase.
    fn params_with(&self, params: &Params) -> Result<Params> {
        params.with_phi(self.base.phi + self.phase)
    }

    /// The model's parameters at u (its drive phase φ at τ = 0).
    pub(crate) fn model_params(&self, u: &U) -> Result<Params> {
        self.vary.set(self.over.set(self.base, u[2])?, u[3])
    }

    /// The parameters of the chart at u: the model's, with the drive phase of the section.
    pub(crate) fn params(&self, u: &U) -> Result<Params> {
        let p = self.model_params(u)?;
        if self.phase == 0.0 {
            Ok(p)
        } else {
            p.with_phi(self.base.phi + self.phase)
        }
    }

    /// The time from the strobe of `orbit` (at `params`) to the middle of its longest slide:
    /// the section of a chart in which no event comes near the strobe. Where an event passes
    /// the strobe the strobe map changes its formula (an event moves from the end of the
    /// period to its start, and with it a saltation matrix from one side of the monodromy
    /// matrix to the other; a stop reaching the strobe makes the map differentiable in y
    /// only, and for μs > 1 discontinuous in y'): the orbit and its multipliers do not change,
    /// their representation does. A chart whose section lies inside a slide follows the
    /// orbit smoothly until an event comes near it, and the curve then changes charts.
    pub(crate) fn section(params: &Params, orbit: &PeriodicOrbit) -> f64 {
        let span = orbit.period as f64 * params.drive_period();
        // Slides as (start, length), in order over [0, span).
        let mut slides: Vec<(f64, f64)> = Vec::new();
        let mut sliding = !orbit.stuck_at_strobe;
        let mut since = 0.0;
        for e in &orbit.events {
            let now = e.tau.min(span);
            if sliding && now > since {
                slides.push((since, now - since));
            }
            sliding = e.kind != crate::solver::EventKind::Stick;
            since = now;
        }
        if sliding && span > since {
            slides.push((since, span - since));
        }
        // A slide over the strobe is one slide.
        if slides.len() > 1 && !orbit.stuck_at_strobe {
            let last = slides[slides.len() - 1];
            if last.0 + last.1 >= span && slides[0].0 == 0.0 {
                let first = slides.remove(0);
                let n = slides.len();
                slides[n - 1].1 += first.1;
            }
        }
        slides
            .iter()
            .max_by(|a, b| a.1.total_cmp(&b.1))
            .map_or(0.0, |&(start, length)| {
                (start + 0.5 * length).rem_euclid(span)
            })
    }

    /// How close the nearest event of a node's orbit comes to its strobe, relative to the
    /// orbit's period (0 when the strobe falls inside a stop).
    pub(crate) fn margin(node: &Node) -> f64 {
        let o = &node.orbit;
        if o.stuck_at_strobe {
            return 0.0;
        }
        let span = o.period as f64 * o.drive_period;
        o.events
            .iter()
            .map(|e| e.tau.min(span - e.tau).max(0.0) / span)
            .fold(1.0, f64::min)
    }

    /// The state at the section `s` drive-period time after the strobe of the motion from `x`
    /// at `params`.
    pub(crate) fn advance(&self, params: &Params, x: State, s: f64) -> Result<State> {
        if self.dynamics.is_exact() {
            let mut solver = crate::exact::ExactSolver::new(*params, x);
            crate::solver::run_until(&mut solver, s, |_| {})?;
            return Ok(crate::solver::Solver::state(&solver));
        }
        let mut solver = self.dynamics.solver(params, x)?;
        crate::solver::run_until(solver.as_mut(), s, |_| {})?;
        Ok(solver.state())
    }

    /// This system in the chart whose section lies in the middle of the longest slide of
    /// `orbit` (at `params`, this system's chart's parameters), with the state there and the
    /// followed event's time `tau` counted from there.
    pub(crate) fn recharted(
        &self,
        params: &Params,
        orbit: &PeriodicOrbit,
        tau: f64,
    ) -> Result<(System, State, f64)> {
        let s = Self::section(params, orbit);
        let span = orbit.period as f64 * params.drive_period();
        let x = self.advance(params, orbit.state, s)?;
        let mut next = self.clone();
        let turns = std::f64::consts::TAU * self.period as f64;
        next.phase = (self.phase + params.w * s).rem_euclid(turns);
        let mut tau = (tau - s).rem_euclid(span);
        // The followed event: of partners at the same border, the first in this chart.
        if let Some(border) = self.border {
            let chart = next.params_with(params)?;
            let (list, _) = candidates_of(&chart, x, self.period, Some(border.kind), None)?;
            let within = 1e-6 * 1f64.max(params.beta).max(params.mu_s);
            if let Some(c) = earliest(&list, border.kind, border.variant, tau, span, within) {
                tau = c.tau;
            }
        }
        Ok((next, x, tau))
    }

    /// The orbit of `node` as seen at the model's strobe (drive phase φ): its state there,
    /// events, stops and monodromy matrix (the multipliers are those of any section).
    pub(crate) fn model_orbit(&self, node: &Node) -> Result<PeriodicOrbit> {
        if self.phase == 0.0 {
            return Ok(node.orbit.clone());
        }
        let params = self.params(&node.u)?;
        let back = (std::f64::consts::TAU * self.period as f64 - self.phase) / params.w;
        let x = self.advance(&params, node.orbit.state, back)?;
        let model = self.model_params(&node.u)?;
        self.dynamics.find_periodic_orbit(
            &model,
            x,
            self.period,
            &NewtonOptions {
                tolerance: self.tolerance(),
                ..NewtonOptions::default()
            },
        )
    }

    /// The scale of the condition's value (its tolerance is `tolerance` times it).
    fn g_scale(&self, image: &StrobeImage, params: &Params) -> f64 {
        match self.follow {
            Follow::Grazing => 1f64.max(params.beta).max(params.mu_s),
            _ => {
                let m = image.jacobian.max_abs().max(1.0);
                m * m
            }
        }
    }

    /// How far inside the followed side a grazing orbit is placed: σ·h = 4 × its tolerance
    /// (slides touching rest: 1e-9 relative, where the solver's search tells a touch from a
    /// near miss).
    fn offset(&self, params: &Params) -> f64 {
        let scale = 1f64.max(params.beta).max(params.mu_s);
        match self.border {
            Some(b) if b.kind == BorderKind::SlideTouchesRest => 1e-9 * scale,
            Some(_) => 40.0 * self.options.tolerance * scale,
            None => 0.0,
        }
    }

    /// The condition g at the state `x` and `params` with the image there, and the time of
    /// the followed event; `None` when the followed event is not there.
    fn condition(
        &self,
        params: &Params,
        x: State,
        image: &StrobeImage,
        tau: f64,
        strict: bool,
    ) -> Result<Option<(f64, f64)>> {
        let m = image.jacobian;
        Ok(Some(match (self.follow, self.border) {
            (Follow::Fold, _) => (m.minus_identity().det(), f64::NAN),
            (Follow::PeriodDoubling, _) => {
                let a = m.0;
                (
                    (a[0][0] + 1.0) * (a[1][1] + 1.0) - a[0][1] * a[1][0],
                    f64::NAN,
                )
            }
            (Follow::NeimarkSacker, _) => (m.det() - 1.0, f64::NAN),
            (Follow::Grazing, Some(_)) => {
                // (Loosely, the followed event alone is read: the conditions near it.)
                let near = (!strict).then_some(tau);
                let list = match self.followed_candidates(params, x, near) {
                    Ok((list, _)) => list,
                    Err(e) if absent(&e) => return Ok(None),
                    Err(e) => return Err(e),
                };
                match self.grazing_condition(params, &list, tau, strict) {
                    Some(g) => g,
                    None => return Ok(None),
                }
            }
            (Follow::Grazing, None) => return Ok(None),
        }))
    }

    /// The conditions of the followed border's kind on the motion from `x` at `params`, with
    /// its (turns, stops); with `near` = τ, complete only where [`nearest`] looks for the
    /// followed event near τ (a twentieth of the period either way).
    fn followed_candidates(
        &self,
        params: &Params,
        x: State,
        near: Option<f64>,
    ) -> Result<(Vec<Candidate>, (usize, usize))> {
        let span = self.period as f64 * params.drive_period();
        let near = near.map(|tau| (tau, 0.05 * span));
        candidates_of(params, x, self.period, self.border.map(|b| b.kind), near)
    }

    /// The grazing condition g = σ·h − δ of the followed event nearest `tau` among `list`
    /// (the motion's conditions at `params`) and its time; `None` when the followed event is
    /// not there (`strict`: not of its own variant, or with a partner across its border).
    fn grazing_condition(
        &self,
        params: &Params,
        list: &[Candidate],
        tau: f64,
        strict: bool,
    ) -> Option<(f64, f64)> {
        let border = self.border?;
        let span = self.period as f64 * params.drive_period();
        // Strictly, the followed event as it is on the followed side, with no partner
        // of it (the other turning point of a symmetric orbit, at the same border)
        // across; loosely, the same function across the border too (a stop's start
        // for a turning point, a drive's extremum after a release for one inside a
        // stop), where the corrector's differences and moves read it.
        let c = nearest(list, border.kind, None, tau, span)?;
        if strict && c.variant != border.variant {
            return None;
        }
        let within = 1e-6 * 1f64.max(params.beta).max(params.mu_s);
        // (A stop of some length is an event of its own, not a turning point across.)
        if strict
            && list.iter().any(|o| {
                o.kind == border.kind
                    && o.variant != border.variant
                    && (o.tau - c.tau).abs() > 1e-9 * span
                    && o.value.abs() <= within
                    && o.extent <= 1e-6 * span
            })
        {
            return None;
        }
        Some((border.sign * c.value - self.offset(params), c.tau))
    }

    fn evaluate(&self, u: &U, tau: f64) -> Result<Option<Evaluation>> {
        self.evaluate_on(u, tau, false)
    }

    /// [`System::evaluate`], the followed event of its own variant when `strict`.
    fn evaluate_on(&self, u: &U, tau: f64, strict: bool) -> Result<Option<Evaluation>> {
        let params = match self.params(u) {
            Ok(p) => p,
            Err(e) if absent(&e) => return Ok(None),
            Err(e) => return Err(e),
        };
        let Ok(x) = State::new(u[0], u[1]) else {
            return Ok(None);
        };
        let image = match self.dynamics.strobe_map(&params, x, self.period) {
            Ok(image) => image,
            Err(e) if absent(&e) => return Ok(None),
            Err(e) => return Err(e),
        };
        Ok(self
            .condition(&params, x, &image, tau, strict)?
            .map(|(g, tau)| Evaluation { image, g, tau }))
    }

    /// g alone at u.
    /// g at u, when the motion there has the event counts `here`.
    fn g_at(&self, u: &U, tau: f64, here: (usize, usize)) -> Result<Option<f64>> {
        if self.follow == Follow::Grazing && self.border.is_some() {
            // The condition needs the motion's events alone, not the strobe map's Jacobian:
            // one run of the solver (the events and counts are those of the strobe map's run).
            let params = match self.params(u) {
                Ok(p) => p,
                Err(e) if absent(&e) => return Ok(None),
                Err(e) => return Err(e),
            };
            let Ok(x) = State::new(u[0], u[1]) else {
                return Ok(None);
            };
            let (list, counts) = match self.followed_candidates(&params, x, Some(tau)) {
                Ok(found) => found,
                Err(e) if absent(&e) => return Ok(None),
                Err(e) => return Err(e),
            };
            return Ok((counts == here)
                .then(|| self.grazing_condition(&params, &list, tau, false))
                .flatten()
                .map(|(g, _)| g));
        }
        Ok(self
            .evaluate(u, tau)?
            .filter(|e| sequence(&e.image) == here)
            .map(|e| e.g))
    }

    /// ∂g/∂u_i at u by differences of g on motions with the event counts of u's: central
    /// where both sides have them, one-sided of second order where one side has (g's formula
    /// changes across a border, and det(M ∓ I) jumps with M where μs > 1), the step shrunk
    /// eightfold up to three times where neither has.
    fn difference(
        &self,
        u: &U,
        at: &Evaluation,
        here: (usize, usize),
        i: usize,
    ) -> Result<Option<f64>> {
        let mut h = self.options.derivative_step * u[i].abs().max(0.1);
        let at_offset = |k: f64| -> U {
            let mut v = *u;
            v[i] += k;
            v
        };
        for _ in 0..4 {
            let plus = self.g_at(&at_offset(h), at.tau, here)?;
            let minus = self.g_at(&at_offset(-h), at.tau, here)?;
            match (plus, minus) {
                (Some(p), Some(q)) => return Ok(Some((p - q) / (2.0 * h))),
                (Some(p), None) => {
                    return Ok(Some(
                        match self.g_at(&at_offset(2.0 * h), at.tau, here)? {
                            Some(p2) => (-3.0 * at.g + 4.0 * p - p2) / (2.0 * h),
                            None => (p - at.g) / h,
                        },
                    ))
                }
                (None, Some(q)) => {
                    return Ok(Some(
                        match self.g_at(&at_offset(-2.0 * h), at.tau, here)? {
                            Some(q2) => (3.0 * at.g - 4.0 * q + q2) / (2.0 * h),
                            None => (at.g - q) / h,
                        },
                    ))
                }
                (None, None) => h /= 8.0,
            }
        }
        // Borders on both sides within the smallest step (the two turning points of a
        // symmetric orbit at theirs, one each way): g across, as it goes on there.
        let h = self.options.derivative_step * u[i].abs().max(0.1);
        let g = |v: U| -> Result<Option<f64>> { Ok(self.evaluate(&v, at.tau)?.map(|e| e.g)) };
        Ok(match (g(at_offset(h))?, g(at_offset(-h))?) {
            (Some(p), Some(q)) => Some((p - q) / (2.0 * h)),
            (Some(p), None) => Some((p - at.g) / h),
            (None, Some(q)) => Some((at.g - q) / h),
            (None, None) => None,
        })
    }

    /// ∂P^p/∂(Q, P) at u, rows (y, y'): the exact model's exact columns
    /// ([`strobe_map_parameter_derivatives`]); a smooth law's from its sensitivities
    /// ([`Dynamics::parameter_derivative`]), or central differences of its map where it has
    /// none. `None` where the map cannot be had.
    fn parameter_columns(&self, u: &U) -> Result<Option<[[f64; 2]; 2]>> {
        let params = self.params(u)?;
        let x = State { y: u[0], v: u[1] };
        if self.dynamics.is_exact() {
            let derivatives = || -> Result<[[f64; 6]; 2]> {
                let dp = strobe_map_parameter_derivatives(&params, x, self.period)?;
                // ∂P^p/∂vb, when the curve moves the belt's speed.
                let vb = if [self.over, self.vary].contains(&Parameter::Vb) {
                    strobe_map_parameter_derivative(&params, x, self.period, Parameter::Vb)?
                } else {
                    [0.0; 2]
                };
                Ok([0, 1].map(|i| std::array::from_fn(|k| if k == 5 { vb[i] } else { dp[i][k] })))
            };
            let dp = match derivatives() {
                Ok(dp) => dp,
                Err(e) if absent(&e) => return Ok(None),
                Err(e) => return Err(e),
            };
            let (a, b) = (column(self.over)?, column(self.vary)?);
            return Ok(Some([[dp[0][a], dp[0][b]], [dp[1][a], dp[1][b]]]));
        }
        let mut columns = [[0.0; 2]; 2];
        for (k, (index, parameter)) in [(2, self.over), (3, self.vary)].into_iter().enumerate() {
            let d = match self
                .dynamics
                .parameter_derivative(&params, x, self.period, parameter)
            {
                Some(d) => d,
                None => {
                    let h = self.options.derivative_step * u[index].abs().max(0.1);
                    let at = |k: f64| -> Result<State> {
                        let mut v = *u;
                        v[index] += k;
                        Ok(self
                            .dynamics
                            .strobe_map(&self.params(&v)?, x, self.period)?
                            .state)
                    };
                    at(h).and_then(|p| {
                        let q = at(-h)?;
                        Ok([(p.y - q.y) / (2.0 * h), (p.v - q.v) / (2.0 * h)])
                    })
                }
            };
            match d {
                Ok(d) => {
                    columns[0][k] = d[0];
                    columns[1][k] = d[1];
                }
                Err(e) if absent(&e) => return Ok(None),
                Err(e) => return Err(e),
            }
        }
        Ok(Some(columns))
    }

    /// The 3×4 Jacobian of (P^p − x, g) at u: [M − I | ∂P^p/∂Q, ∂P^p/∂P] exactly (a smooth
    /// law's from its sensitivities, see [`System::parameter_columns`]), and the gradient of
    /// g by central differences of g (one-sided where one side has no value; the velocity's
    /// column left out where the strobe falls inside a stop).
    fn jacobian(&self, u: &U, at: &Evaluation) -> Result<Option<[[f64; 4]; 3]>> {
        let Some(dp) = self.parameter_columns(u)? else {
            return Ok(None);
        };
        let m = at.image.jacobian.0;
        let mut rows = [
            [m[0][0] - 1.0, m[0][1], dp[0][0], dp[0][1]],
            [m[1][0], m[1][1] - 1.0, dp[1][0], dp[1][1]],
            [0.0; 4],
        ];
        let stuck = at.image.stuck_at_start && at.image.stuck_at_end;
        let here = sequence(&at.image);
        for i in 0..4 {
            if i == 1 && stuck {
                continue;
            }
            let Some(d) = self.difference(u, at, here, i)? else {
                return Ok(None);
            };
            rows[2][i] = d;
        }
        Ok(Some(rows))
    }

    /// Merit of an evaluation: the largest residual, each relative to its tolerance's scale.
    ///
    /// With `scales` given (those of the corrector's first point), the residuals are measured
    /// on that one scale, so that two points on either side of a jump of the Jacobian compare.
    fn merit(
        &self,
        u: &U,
        e: &Evaluation,
        plane: &Plane,
        scales: Option<(f64, f64)>,
    ) -> Result<f64> {
        let r = [e.image.state.y - u[0], e.image.state.v - u[1]];
        let (scale_f, scale_g) = match scales {
            Some(s) => s,
            None => self.scales(u, e)?,
        };
        let f = r[0].abs().max(r[1].abs()) / scale_f;
        let g = e.g.abs() / scale_g;
        let p = plane.residual(u).0.abs() / plane.scale();
        Ok(f.max(g).max(p))
    }

    /// The scales of the residuals of (P^p − x, g) at u: those of Newton's method for orbits
    /// (max(1, |y|, |y'|)·max(1, max|M_ij|)), and of the condition.
    fn scales(&self, u: &U, e: &Evaluation) -> Result<(f64, f64)> {
        let params = self.params(u)?;
        Ok((
            1f64.max(u[0].abs()).max(u[1].abs()) * e.image.jacobian.max_abs().max(1.0),
            self.g_scale(&e.image, &params),
        ))
    }

    /// The point of the curve on `plane`, by Newton's method from the plane's prediction (or
    /// `guess` for a fixed plane) with the followed event near `tau`, its tangent oriented
    /// along `along`; `None` when Newton's method does not converge or the point is not on
    /// the followed side.
    ///
    /// A grazing curve's iterates stay on the followed side: a prediction or a step that lands
    /// across (the followed event of the other variant, or a partner of it across its border)
    /// is moved back along the gradient of g onto the curve's offset (g = 0, σ·h = δ), where
    /// the map is that of the followed side.
    pub(crate) fn correct(
        &self,
        guess: &U,
        tau: f64,
        plane: &Plane,
        along: &U,
    ) -> Result<Option<Node>> {
        // Where the map is continuous across the border the iterates may cross it on the way;
        // where they land on another orbit across it (a partner's border, a jump), the
        // iterates are kept on the followed side.
        match self.correct_on(guess, tau, plane, along, false)? {
            Some(node) => Ok(Some(node)),
            None if self.border.is_some() => self.correct_on(guess, tau, plane, along, true),
            None => Ok(None),
        }
    }

    /// [`System::correct`], with the iterates kept on the followed side when `strict`.
    fn correct_on(
        &self,
        guess: &U,
        tau: f64,
        plane: &Plane,
        along: &U,
        strict: bool,
    ) -> Result<Option<Node>> {
        let tolerance = self.tolerance();
        let Some((mut u, mut at)) = self.on_side(plane.prediction(guess), tau, None, strict)?
        else {
            return Ok(None);
        };
        let mut tau = at.tau;
        let mut converged = false;
        for _ in 0..self.options.corrector_iterations.max(1) + 1 {
            let merit = self.merit(&u, &at, plane, None)?;
            if merit <= tolerance {
                converged = true;
                break;
            }
            let fixed = Some(self.scales(&u, &at)?);
            let progress = self.merit(&u, &at, plane, fixed)?;
            let Some(rows) = self.jacobian(&u, &at)? else {
                return Ok(None);
            };
            let (pr, prow) = plane.residual(&u);
            let a = [rows[0], rows[1], rows[2], prow];
            let b = [
                -(at.image.state.y - u[0]),
                -(at.image.state.v - u[1]),
                -at.g,
                -pr,
            ];
            let Some(du) = solve4(a, b) else {
                return Ok(None);
            };
            let mut fraction = 1.0;
            let mut next = None;
            for _ in 0..12 {
                let trial = std::array::from_fn(|i| u[i] + fraction * du[i]);
                if let Some((trial, e)) = self.on_side(trial, at.tau, Some(&rows[2]), strict)? {
                    if self.merit(&trial, &e, plane, fixed)? < progress {
                        next = Some((trial, e));
                        break;
                    }
                }
                fraction *= 0.5;
            }
            let Some((trial, e)) = next else {
                return Ok(None);
            };
            u = trial;
            tau = e.tau;
            at = e;
        }
        if !converged {
            return Ok(None);
        }
        if !strict && self.border.is_some() && self.evaluate_on(&u, tau, true)?.is_none() {
            return Ok(None);
        }
        let params = self.params(&u)?;
        let orbit = match self.dynamics.find_periodic_orbit(
            &params,
            State { y: u[0], v: u[1] },
            self.period,
            &self.confirming(),
        ) {
            Ok(orbit) => orbit,
            Err(e) if absent(&e) => return Ok(None),
            Err(e) => return Err(e),
        };
        if orbit.iterations > 0 || self.rest(&orbit) {
            return Ok(None);
        }
        let Some((tangent, rows)) = self.tangent(&u, &at, along)? else {
            return Ok(None);
        };
        Ok(Some(Node {
            u,
            tau,
            counts: counts(&orbit),
            orbit,
            tangent,
            rows: Some(rows),
            across: std::sync::OnceLock::new(),
        }))
    }

    /// Where this system's condition (a fold, period doubling or Neimark–Sacker point) and the
    /// grazing condition of `border` hold at once, a point of codimension two: Newton's method
    /// on (P^p − x, g, σ·h − δ) = 0, four equations in the four unknowns, from `guess` (with the
    /// border's event near `tau`), its iterates on the grazing's followed side. The node's
    /// tangent is zero. `None` when it does not converge.
    pub(crate) fn meet(&self, border: Border, guess: &U, tau: f64) -> Result<Option<Node>> {
        let smooth = System {
            border: None,
            ..self.clone()
        };
        let graze = System {
            follow: Follow::Grazing,
            border: Some(border),
            ..self.clone()
        };
        let tolerance = self.tolerance();
        let Some((mut u, mut at)) = graze.on_side(*guess, tau, None, true)? else {
            return Ok(None);
        };
        let residuals = |u: &U, e: &Evaluation| -> Result<([f64; 4], f64)> {
            let params = self.params(u)?;
            let x = State { y: u[0], v: u[1] };
            let g1 = smooth
                .condition(&params, x, &e.image, f64::NAN, false)?
                .map_or(f64::NAN, |(g, _)| g);
            let (scale_f, scale_g2) = graze.scales(u, e)?;
            let scale_g1 = smooth.g_scale(&e.image, &params);
            let r = [e.image.state.y - u[0], e.image.state.v - u[1], g1, e.g];
            let merit = (r[0].abs().max(r[1].abs()) / scale_f)
                .max(r[2].abs() / scale_g1)
                .max(r[3].abs() / scale_g2);
            Ok((r, merit))
        };
        for _ in 0..24 {
            let (r, merit) = residuals(&u, &at)?;
            if !merit.is_finite() {
                return Ok(None);
            }
            if merit <= tolerance {
                let params = self.params(&u)?;
                let orbit = match self.dynamics.find_periodic_orbit(
                    &params,
                    State { y: u[0], v: u[1] },
                    self.period,
                    &self.confirming(),
                ) {
                    Ok(orbit) => orbit,
                    Err(e) if absent(&e) => return Ok(None),
                    Err(e) => return Err(e),
                };
                if orbit.iterations > 0 {
                    return Ok(None);
                }
                return Ok(Some(Node {
                    u,
                    tau: at.tau,
                    counts: counts(&orbit),
                    orbit,
                    tangent: [0.0; 4],
                    rows: None,
                    across: std::sync::OnceLock::new(),
                }));
            }
            let Some(rows) = graze.jacobian(&u, &at)? else {
                return Ok(None);
            };
            let smooth_at = Evaluation {
                image: at.image.clone(),
                g: r[2],
                tau: f64::NAN,
            };
            let Some(smooth_rows) = smooth.jacobian(&u, &smooth_at)? else {
                return Ok(None);
            };
            let Some(du) = solve4(
                [rows[0], rows[1], smooth_rows[2], rows[2]],
                [-r[0], -r[1], -r[2], -r[3]],
            ) else {
                return Ok(None);
            };
            let mut fraction = 1.0;
            let mut next = None;
            for _ in 0..16 {
                let trial = std::array::from_fn(|i| u[i] + fraction * du[i]);
                if let Some((trial, e)) = graze.on_side(trial, at.tau, Some(&rows[2]), true)? {
                    if residuals(&trial, &e)?.1 < merit {
                        next = Some((trial, e));
                        break;
                    }
                }
                fraction *= 0.5;
            }
            let Some((trial, e)) = next else {
                return Ok(None);
            };
            u = trial;
            at = e;
        }
        Ok(None)
    }

    /// The monodromy matrix of the motion just across the border from `node` (a grazing
    /// orbit): at u moved to σ·h = −δ, where the followed event has crossed, while every
    /// partner of it at the same border (the other turning point of a symmetric orbit) stays
    /// where it is (the smallest move that does both, by the gradients of the conditions).
    /// Not a fixed point there, but within about 2δ of the orbit across, whose multipliers it
    /// gives to that order. `None` where it cannot be had.
    pub(crate) fn across(&self, node: &Node) -> Result<Option<crate::stability::Matrix2>> {
        let Some(border) = self.border else {
            return Ok(None);
        };
        let Some(at) = self.evaluate(&node.u, node.tau)? else {
            return Ok(None);
        };
        let rows = match node.rows {
            Some(rows) => rows,
            None => match self.jacobian(&node.u, &at)? {
                Some(rows) => rows,
                None => return Ok(None),
            },
        };
        let params = self.params(&node.u)?;
        let span = self.period as f64 * params.drive_period();
        let within = 1e-6 * 1f64.max(params.beta).max(params.mu_s);
        // Rows of the conditions to move, and how far.
        let mut a = vec![rows[2]];
        let mut b = vec![-2.0 * self.offset(&params) - at.g];
        let (list, _) = candidates_of(
            &params,
            node.orbit.state,
            self.period,
            Some(border.kind),
            None,
        )?;
        for c in list {
            if c.kind == border.kind
                && c.variant == border.variant
                && (c.tau - at.tau).abs() > 1e-9 * span
                && c.value.abs() <= within
            {
                let Some(partner) = self.evaluate(&node.u, c.tau)? else {
                    return Ok(None);
                };
                let Some(partner_rows) = self.jacobian(&node.u, &partner)? else {
                    return Ok(None);
                };
                a.push(partner_rows[2]);
                b.push(0.0);
            }
        }
        // The smallest move: Δ = Aᵀ (A Aᵀ)⁻¹ b (one or two rows).
        let delta: U = match (a.len(), a.as_slice()) {
            (1, [g]) => {
                let n2 = dot(g, g);
                if !(n2 > 0.0 && n2.is_finite()) {
                    return Ok(None);
                }
                std::array::from_fn(|i| g[i] * b[0] / n2)
            }
            (2, [g, p]) => {
                let (gg, gp, pp) = (dot(g, g), dot(g, p), dot(p, p));
                let det = gg * pp - gp * gp;
                if !(det.abs() > 1e-12 * gg * pp) {
                    return Ok(None);
                }
                let c0 = (pp * b[0] - gp * b[1]) / det;
                let c1 = (gg * b[1] - gp * b[0]) / det;
                std::array::from_fn(|i| c0 * g[i] + c1 * p[i])
            }
            _ => return Ok(None),
        };
        let u = std::array::from_fn(|i| node.u[i] + delta[i]);
        Ok(self.evaluate(&u, node.tau)?.map(|e| e.image.jacobian))
    }

    /// How far `node` is from the border of `border`'s event (near `tau` from the strobe) in
    /// u = (y, y', Q, P): the condition's value over the length of its gradient (by
    /// differences, as the corrector's); `None` where the event or the gradient cannot be had.
    pub(crate) fn border_distance(
        &self,
        border: Border,
        node: &Node,
        tau: f64,
    ) -> Result<Option<f64>> {
        let graze = System {
            follow: Follow::Grazing,
            border: Some(border),
            ..self.clone()
        };
        let Some(at) = graze.evaluate(&node.u, tau)? else {
            return Ok(None);
        };
        let Some(rows) = graze.jacobian(&node.u, &at)? else {
            return Ok(None);
        };
        let params = self.params(&node.u)?;
        let value = at.g + graze.offset(&params);
        let gradient = norm(&rows[2]);
        Ok((gradient > 0.0 && gradient.is_finite()).then(|| value.abs() / gradient))
    }

    /// The grazing condition nearest zero on the motion of `node`, followed on the node's
    /// side: the event whose border a curve through `node` meets.
    ///
    /// `None` with a smooth law: the conditions are those of the exact solver's events (a
    /// curve of such a law ends at a change of its event counts, located by bisection).
    pub(crate) fn border_at(&self, node: &Node) -> Result<Option<(Border, f64, f64)>> {
        if !self.dynamics.is_exact() {
            return Ok(None);
        }
        let params = self.params(&node.u)?;
        let list = candidates(&params, node.orbit.state, self.period)?;
        Ok(list
            .iter()
            .min_by(|a, b| a.value.abs().total_cmp(&b.value.abs()))
            .map(|c| {
                (
                    Border {
                        kind: c.kind,
                        variant: c.variant,
                        sign: if c.value >= 0.0 { 1.0 } else { -1.0 },
                        continuous: false,
                    },
                    c.tau,
                    c.value,
                )
            }))
    }

    /// u (`strict`: for a grazing curve, u moved onto the followed side, at most four moves along
    /// `gradient`, the gradient of g, or one by differences at u when not given), with its
    /// evaluation there.
    fn on_side(
        &self,
        mut u: U,
        tau: f64,
        gradient: Option<&[f64; 4]>,
        strict: bool,
    ) -> Result<Option<(U, Evaluation)>> {
        if self.border.is_none() || !strict {
            return Ok(self.evaluate(&u, tau)?.map(|e| (u, e)));
        }
        let mut own = None;
        for _ in 0..4 {
            if let Some(e) = self.evaluate_on(&u, tau, true)? {
                return Ok(Some((u, e)));
            }
            // Across: g continues there as the same function (see `condition`).
            let Some(loose) = self.evaluate_on(&u, tau, false)? else {
                return Ok(None);
            };
            let grad = match gradient {
                Some(g) => *g,
                None => {
                    if own.is_none() {
                        own = self.jacobian(&u, &loose)?.map(|rows| rows[2]);
                    }
                    let Some(g) = own else {
                        return Ok(None);
                    };
                    g
                }
            };
            let norm2 = dot(&grad, &grad);
            if !(norm2 > 0.0 && norm2.is_finite()) {
                return Ok(None);
            }
            // To g = +δ_g·(a fraction of the offset) inside, where σ·h is about 1.5δ.
            let params = self.params(&u)?;
            let target = 0.5 * self.offset(&params);
            let lambda = (target - loose.g) / norm2;
            u = std::array::from_fn(|i| u[i] + lambda * grad[i]);
        }
        Ok(None)
    }

    /// The unit null vector of the 3×4 Jacobian at u, oriented along `along`, with the
    /// Jacobian.
    fn tangent(&self, u: &U, at: &Evaluation, along: &U) -> Result<Option<(U, [[f64; 4]; 3])>> {
        let Some(rows) = self.jacobian(u, at)? else {
            return Ok(None);
        };
        let n = norm(along);
        if !(n > 0.0) {
            return Ok(None);
        }
        let along = along.map(|c| c / n);
        let Some(z) = solve4([rows[0], rows[1], rows[2], along], [0.0, 0.0, 0.0, 1.0]) else {
            return Ok(None);
        };
        let n = norm(&z);
        Ok((n > 0.0 && n.is_finite()).then(|| (z.map(|c| c / n), rows)))
    }
}

/// (turns, stops) of a motion's events.
fn sequence(image: &StrobeImage) -> (usize, usize) {
    let count = |kind| image.events.iter().filter(|e| e.kind == kind).count();
    (
        count(crate::solver::EventKind::Turn),
        count(crate::solver::EventKind::Stick),
    )
}
