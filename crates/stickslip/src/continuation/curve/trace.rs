//! Following a curve from its start point: pseudo-arclength steps on the extended system,
//! codimension-two points located between neighbouring points, and why the curve ends.

use super::system::{distance, dot, norm, Node, Plane, System, U};
use super::{
    Codim2Kind, Codim2Point, Curve, CurveEnd, CurvePoint, CurveSide, CurveStart, Follow,
    StabilityChange,
};
use crate::continuation::obstacle;
use crate::continuation::ContinuationOptions;
use crate::continuation::Obstacle;
use crate::error::{Error, Result};
use crate::scan::Monitor;
use crate::stability::{Dynamics, ExactDynamics, PeriodicOrbit, Stability};
use std::ops::ControlFlow;
use std::sync::Arc;

/// What the orbit at `params` is closest to ([`obstacle::obstacle`]): switches of the exact
/// model's law; a smooth law has none ([`Obstacle::None`]), as on its branches.
fn obstacle(
    system: &System,
    params: &crate::params::Params,
    orbit: &PeriodicOrbit,
) -> Result<Obstacle> {
    if system.dynamics.is_exact() {
        obstacle::obstacle(params, orbit)
    } else {
        Ok(Obstacle::None)
    }
}

/// The angle between two unit vectors.
fn angle(a: &U, b: &U) -> f64 {
    dot(a, b).clamp(-1.0, 1.0).acos()
}

/// What the orbit does apart from the followed special point (see [`CurvePoint::stability`]).
pub(crate) fn stability(follow: Follow, orbit: &PeriodicOrbit) -> Stability {
    let m = orbit.multipliers;
    let other = match follow {
        Follow::Fold => {
            if (m[0].re - 1.0).hypot(m[0].im) >= (m[1].re - 1.0).hypot(m[1].im) {
                m[0]
            } else {
                m[1]
            }
        }
        Follow::PeriodDoubling => {
            if (m[0].re + 1.0).hypot(m[0].im) >= (m[1].re + 1.0).hypot(m[1].im) {
                m[0]
            } else {
                m[1]
            }
        }
        Follow::NeimarkSacker => return Stability::Neutral,
        Follow::Grazing => m[0],
    };
    if other.modulus() < 1.0 {
        Stability::Stable
    } else {
        Stability::Unstable
    }
}

/// The point of `node`, its orbit seen at the model's strobe.
fn point(system: &System, node: &Node, arclength: f64) -> Result<CurvePoint> {
    let orbit = match system.model_orbit(node) {
        Ok(orbit) => orbit,
        Err(Error::Stability(_)) => node.orbit.clone(),
        Err(e) => return Err(e),
    };
    Ok(CurvePoint {
        over: node.u[2],
        vary: node.u[3],
        arclength,
        turns: node.counts.0,
        stops: node.counts.1,
        stability: stability(system.follow, &node.orbit),
        orbit,
    })
}

/// `node` in a chart whose section lies in the middle of its longest slide (see
/// [`System::section`]), `system` changed to that chart; `None` (and `system` unchanged) when
/// the node cannot be corrected there.
fn rechart(system: &mut System, node: &Node) -> Result<Option<Node>> {
    let params = system.params(&node.u)?;
    let (next, x, tau) = system.recharted(&params, &node.orbit, node.tau)?;
    let u = [x.y, x.v, node.u[2], node.u[3]];
    let t = node.tangent;
    let index = if t[2].abs() >= t[3].abs() { 2 } else { 3 };
    let along = [0.0, 0.0, t[2], t[3]];
    match next.correct(
        &u,
        tau,
        &Plane::Fixed {
            index,
            value: u[index],
        },
        &along,
    )? {
        Some(n) => {
            *system = next;
            Ok(Some(n))
        }
        None => Ok(None),
    }
}

/// Where a fold, period-doubling or Neimark–Sacker curve that cannot go on at `node` (at
/// `params`, the point after `index`) meets the grazing condition nearest zero there: both
/// conditions solved at once from `node` ([`System::meet`]), or `node` itself where it lies
/// within 10⁻⁶ (relative to max(1, |u|)) of the border by the condition's value and gradient
/// (where the meeting's equations are degenerate: at a symmetric orbit grazing at both turning
/// points, a stop of no length is a second border at once); that distance is then the point's
/// width, and it counts as located when within the locating tolerance.
fn meeting_at(
    system: &System,
    node: &Node,
    params: &crate::params::Params,
    index: usize,
) -> Result<Option<Codim2Point>> {
    if system.follow == Follow::Grazing {
        return Ok(None);
    }
    let Some((border, tau, value)) = system.border_at(node)? else {
        return Ok(None);
    };
    let scale = 1f64.max(params.beta).max(params.mu_s);
    let (met, width) = match system
        .meet(border, &node.u, tau)?
        .filter(|n| near(&n.u, &node.u))
    {
        Some(n) => {
            let width = system.options.tolerance * norm(&n.u).max(1.0);
            (n, width)
        }
        None if value.abs() <= 1e-9 * scale => (node.clone(), 0.0),
        None => match system.border_distance(border, node, tau)? {
            Some(d) if d <= 1e-6 * norm(&node.u).max(1.0) => (node.clone(), d),
            _ => return Ok(None),
        },
    };
    let here = Sample {
        t: 0.0,
        node: node.clone(),
    };
    let at = Sample { t: 0.0, node: met };
    let kind = Codim2Kind::meets_grazing(system.follow);
    let mut c = codim2(system, kind, &here, &at, true, index)?;
    c.over = at.node.u[2];
    c.vary = at.node.u[3];
    c.state = crate::params::State {
        y: at.node.u[0],
        v: at.node.u[1],
    };
    c.width = width.max(system.options.tolerance * norm(&at.node.u).max(1.0));
    c.located = c.width <= system.options.locate_tolerance * norm(&at.node.u).max(1.0);
    Ok(Some(c))
}

/// Whether a meeting solved from `from` is the one there: within 10⁻⁴ of it (relative to
/// max(1, |u|)).
fn near(meeting: &U, from: &U) -> bool {
    distance(meeting, from) <= 1e-4 * norm(from).max(1.0)
}

/// Events closer to the strobe than this fraction of the orbit's period make the curve change
/// charts.
const MARGIN: f64 = 0.02;

/// A test function of codimension two: changes sign where the point is crossed.
type Test = Box<dyn Fn(&Node) -> f64>;

/// The test functions of a curve of `follow`, between `current` and the next point.
fn tests(system: &System, current: &Node) -> Vec<(Codim2Kind, Test)> {
    let follow = system.follow;
    let det = |n: &Node| n.orbit.monodromy.det();
    let trace = |n: &Node| n.orbit.monodromy.trace();
    match follow {
        Follow::Fold => {
            let reference = [current.tangent[2], current.tangent[3]];
            vec![
                (
                    Codim2Kind::Cusp,
                    Box::new(move |n: &Node| {
                        n.tangent[2] * reference[0] + n.tangent[3] * reference[1]
                    }),
                ),
                (Codim2Kind::Resonance11, Box::new(move |n| det(n) - 1.0)),
                (Codim2Kind::FoldFlip, Box::new(move |n| det(n) + 1.0)),
            ]
        }
        Follow::PeriodDoubling => vec![
            (Codim2Kind::Resonance12, Box::new(move |n| det(n) - 1.0)),
            (Codim2Kind::FoldFlip, Box::new(move |n| det(n) + 1.0)),
        ],
        Follow::NeimarkSacker => vec![
            (Codim2Kind::Resonance11, Box::new(move |n| trace(n) - 2.0)),
            (Codim2Kind::Resonance12, Box::new(move |n| trace(n) + 2.0)),
        ],
        Follow::Grazing => {
            let mut tests: Vec<(Codim2Kind, Test)> = vec![
                (
                    Codim2Kind::FoldGrazing,
                    Box::new(|n: &Node| n.orbit.monodromy.minus_identity().det()),
                ),
                (
                    Codim2Kind::PeriodDoublingGrazing,
                    Box::new(|n: &Node| {
                        let a = n.orbit.monodromy.0;
                        (a[0][0] + 1.0) * (a[1][1] + 1.0) - a[0][1] * a[1][0]
                    }),
                ),
                (
                    Codim2Kind::NeimarkSackerGrazing,
                    Box::new(|n: &Node| {
                        if n.orbit.multipliers[0].im != 0.0 {
                            n.orbit.monodromy.det() - 1.0
                        } else {
                            f64::NAN
                        }
                    }),
                ),
            ];
            // Across a border the orbits join continuously at: a fold or period doubling of
            // the orbit there meets the grazing too.
            if system.border.is_some_and(|b| b.continuous) {
                let across = |system: System, f: fn(&crate::stability::Matrix2) -> f64| {
                    Box::new(move |n: &Node| {
                        let m = n.across.get_or_init(|| system.across(n).ok().flatten());
                        m.as_ref().map_or(f64::NAN, f)
                    }) as Test
                };
                tests.push((
                    Codim2Kind::FoldGrazing,
                    across(system.clone(), |m| m.minus_identity().det()),
                ));
                tests.push((
                    Codim2Kind::PeriodDoublingGrazing,
                    across(system.clone(), |m| {
                        let a = m.0;
                        (a[0][0] + 1.0) * (a[1][1] + 1.0) - a[0][1] * a[1][0]
                    }),
                ));
            }
            tests
        }
    }
}

/// A converged point at the fraction `t` of a step.
#[derive(Clone)]
struct Sample {
    t: f64,
    node: Node,
}

/// The step from `current` of length `ds`: its points by the fraction of the way.
struct Step<'a> {
    system: &'a System,
    current: &'a Node,
    ds: f64,
}

impl Step<'_> {
    fn at(&self, t: f64) -> Result<Option<Node>> {
        let c = self.current;
        self.system.correct(
            &c.u,
            c.tau,
            &Plane::Arc {
                from: c.u,
                tangent: c.tangent,
                sigma: t * self.ds,
            },
            &c.tangent,
        )
    }

    /// The point of the step (from `current` to `next`) whose grazing condition nearest
    /// zero ([`System::border_at`]) is smallest: a golden-section search over the fraction
    /// of the way, until the bracket is at most the locating tolerance wide in u (or 60
    /// rounds); the condition falls to zero at a grazing the step passes through and rises
    /// again on the far side.
    fn closest_to_border(&self, current: &Node, next: &Node) -> Result<Node> {
        let value = |n: &Node| -> Result<f64> {
            Ok(self
                .system
                .border_at(n)?
                .map_or(f64::INFINITY, |(_, _, v)| v.abs()))
        };
        let mut best = (value(current)?, current.clone());
        let v = value(next)?;
        if v < best.0 {
            best = (v, next.clone());
        }
        let golden = 0.5 * (5f64.sqrt() - 1.0);
        let (mut a, mut b) = (0.0, 1.0);
        let at = |t: f64, best: &mut (f64, Node)| -> Result<f64> {
            let Some(n) = self.at(t)? else {
                return Ok(f64::INFINITY);
            };
            let v = value(&n)?;
            if v < best.0 {
                *best = (v, n);
            }
            Ok(v)
        };
        let mut c = b - golden * (b - a);
        let mut d = a + golden * (b - a);
        let (mut fc, mut fd) = (at(c, &mut best)?, at(d, &mut best)?);
        let tolerance = self.system.options.locate_tolerance;
        for _ in 0..60 {
            if (b - a) * self.ds <= tolerance {
                break;
            }
            if fc < fd {
                b = d;
                d = c;
                fd = fc;
                c = b - golden * (b - a);
                fc = at(c, &mut best)?;
            } else {
                a = c;
                c = d;
                fc = fd;
                d = a + golden * (b - a);
                fd = at(d, &mut best)?;
            }
        }
        Ok(best.1)
    }

    /// Bisection until the bracket is at most the locating tolerance wide: `lo` satisfies
    /// `same`, `hi` does not; whether it reached the tolerance.
    fn bisect(
        &self,
        mut lo: Sample,
        mut hi: Sample,
        same: &dyn Fn(&Node) -> bool,
    ) -> Result<(Sample, Sample, bool)> {
        let tolerance = self.system.options.locate_tolerance;
        for _ in 0..200 {
            if distance(&lo.node.u, &hi.node.u) <= tolerance {
                return Ok((lo, hi, true));
            }
            let mid = 0.5 * (lo.t + hi.t);
            if mid <= lo.t || mid >= hi.t {
                return Ok((lo, hi, true));
            }
            let Some(node) = self.at(mid)? else {
                return Ok((lo, hi, false));
            };
            if same(&node) {
                lo = Sample { t: mid, node };
            } else {
                hi = Sample { t: mid, node };
            }
        }
        Ok((lo, hi, false))
    }
}

fn codim2(
    system: &System,
    kind: Codim2Kind,
    lo: &Sample,
    hi: &Sample,
    located: bool,
    index: usize,
) -> Result<Codim2Point> {
    let (a, b) = (&lo.node.u, &hi.node.u);
    Ok(Codim2Point {
        kind,
        over: 0.5 * (a[2] + b[2]),
        vary: 0.5 * (a[3] + b[3]),
        state: crate::params::State {
            y: 0.5 * (a[0] + b[0]),
            v: 0.5 * (a[1] + b[1]),
        },
        width: distance(a, b),
        located,
        after_point: index,
        before: CurveSide::of(&point(system, &lo.node, 0.0)?),
        after: CurveSide::of(&point(system, &hi.node, 0.0)?),
    })
}

/// [`codim2`], the point refined where it is the meeting of a fold, period doubling or
/// Neimark–Sacker curve with a grazing: both conditions solved at once ([`System::meet`])
/// from the bracket's end before it.
fn refined(
    system: &System,
    kind: Codim2Kind,
    lo: &Sample,
    hi: &Sample,
    located: bool,
    index: usize,
) -> Result<Codim2Point> {
    let mut c = codim2(system, kind, lo, hi, located, index)?;
    let meeting = match (system.follow, kind) {
        (Follow::Grazing, _) => {
            let follow = match kind {
                Codim2Kind::FoldGrazing => Follow::Fold,
                Codim2Kind::PeriodDoublingGrazing => Follow::PeriodDoubling,
                Codim2Kind::NeimarkSackerGrazing => Follow::NeimarkSacker,
                _ => return Ok(c),
            };
            let Some(border) = system.border else {
                return Ok(c);
            };
            let smooth = System {
                follow,
                border: None,
                ..system.clone()
            };
            smooth.meet(border, &lo.node.u, lo.node.tau)?
        }
        (follow, kind) if kind == Codim2Kind::meets_grazing(follow) => {
            match system.border_at(&lo.node)? {
                Some((border, tau, _)) => system.meet(border, &lo.node.u, tau)?,
                None => None,
            }
        }
        _ => None,
    };
    // Newton's method on the meeting's four equations can converge to another meeting far
    // along the curves (another fold–grazing point): only one next to the bracket is this one.
    if let Some(n) = meeting.filter(|n| near(&n.u, &lo.node.u)) {
        c.over = n.u[2];
        c.vary = n.u[3];
        c.state = crate::params::State {
            y: n.u[0],
            v: n.u[1],
        };
        c.width = system.options.tolerance * norm(&n.u).max(1.0);
        c.located = true;
    }
    Ok(c)
}

/// A curve followed one way from `start` (its tangent pointing the way), with Q within
/// `range` and P within `vary_range` when given.
struct OneWay {
    points: Vec<CurvePoint>,
    codim2: Vec<Codim2Point>,
    end: CurveEnd,
}

fn one_way(
    system: &System,
    start: Node,
    (lo, hi): (f64, f64),
    vary_range: Option<(f64, f64)>,
    monitor: &dyn Monitor,
) -> Result<OneWay> {
    let mut system = system.clone();
    let options = system.options;
    let follow = system.follow;
    let span = hi - lo;
    let reference = start.counts;
    let first = start.u;
    let mut current = start;
    let mut points = vec![point(&system, &current, 0.0)?];
    let mut found = Vec::new();
    let mut ds = options.initial_step;
    let mut arclength = 0.0;
    let mut crawling = 0usize;
    let end = loop {
        if points.len() >= options.max_points {
            break CurveEnd::MaxPoints;
        }
        if monitor.step(points.len(), options.max_points) == ControlFlow::Break(()) {
            return Err(Error::Cancelled {
                done: points.len(),
                total: options.max_points,
            });
        }
        let t_over = current.tangent[2].abs();
        let cap = if t_over > 0.0 {
            options
                .max_step
                .min(options.max_parameter_step * span / t_over)
        } else {
            options.max_step
        };
        ds = ds.min(cap).max(options.min_step);
        let step = Step {
            system: &system,
            current: &current,
            ds,
        };
        let trial = step.at(1.0)?.filter(|n| {
            n.counts != current.counts
                || angle(&n.tangent, &current.tangent) <= options.max_angle
                || ds <= options.crawl_step()
        });
        let Some(mut next) = trial else {
            if ds <= options.min_step {
                let (over, vary) = (current.u[2], current.u[3]);
                let ahead: U = std::array::from_fn(|i| current.u[i] + ds * current.tangent[i]);
                if system.params(&ahead).is_err() {
                    break CurveEnd::ParameterLimit { over, vary };
                }
                let params = system.params(&current.u)?;
                let obstacle = obstacle(&system, &params, &current.orbit)?;
                // Against a jump of the strobe map: a fold, period doubling or Neimark–Sacker
                // curve meeting the grazing where it is.
                if obstacle != Obstacle::None {
                    if let Some(c) = meeting_at(&system, &current, &params, points.len() - 1)? {
                        let end = CurveEnd::Codim2 {
                            kind: c.kind,
                            over: c.over,
                            vary: c.vary,
                        };
                        found.push(c);
                        break end;
                    }
                }
                break CurveEnd::Failed {
                    over,
                    vary,
                    obstacle,
                };
            }
            ds = (0.5 * ds).max(options.min_step);
            continue;
        };
        let index = points.len() - 1;
        // Another sequence of events: the followed point's smooth piece ends there.
        if next.counts != reference {
            let (l, r, located) = step.bisect(
                Sample {
                    t: 0.0,
                    node: current.clone(),
                },
                Sample { t: 1.0, node: next },
                &|n| n.counts == reference,
            )?;
            let kind = Codim2Kind::meets_grazing(follow);
            if l.t > 0.0 {
                arclength += l.t * ds;
                points.push(point(&system, &l.node, arclength)?);
            }
            let c = refined(&system, kind, &l, &r, located, points.len() - 1)?;
            let end = match follow {
                Follow::Grazing => CurveEnd::EventSequence {
                    over: c.over,
                    vary: c.vary,
                    before: (c.before.turns, c.before.stops),
                    after: (c.after.turns, c.after.stops),
                },
                _ => CurveEnd::Codim2 {
                    kind,
                    over: c.over,
                    vary: c.vary,
                },
            };
            found.push(c);
            break end;
        }
        // A sharp reversal in the parameter plane, taken only because the steps crawl, with
        // the same event counts on both sides: on a fold, period-doubling or Neimark–Sacker
        // curve, the step has passed through a grazing onto the mirror image of the orbit
        // (whose stop has shrunk to nothing at one turning point and appears at the other),
        // which has the same curve in the parameters, traced back. The curve meets the
        // grazing there: located from the point of the step nearest the border, and the curve
        // ends.
        let ahead =
            |n: &Node| n.tangent[2] * current.tangent[2] + n.tangent[3] * current.tangent[3] > 0.0;
        if follow != Follow::Grazing
            && system.dynamics.is_exact()
            && angle(&next.tangent, &current.tangent) > options.max_angle
            && !ahead(&next)
        {
            let nearest = step.closest_to_border(&current, &next)?;
            let params = system.params(&nearest.u)?;
            if let Some(c) = meeting_at(&system, &nearest, &params, index)? {
                let end = CurveEnd::Codim2 {
                    kind: c.kind,
                    over: c.over,
                    vary: c.vary,
                };
                found.push(c);
                break end;
            }
        }
        // Past an end of Q's range, or of P's when it has one: the point at the end itself
        // (of the range the step leaves first).
        let mut boundary = None;
        let mut sigma = ds;
        let mut exit: Option<(usize, f64, f64)> = None;
        for (index, range) in [(2, Some((lo, hi))), (3, vary_range)] {
            let Some((l, h)) = range else { continue };
            let x = next.u[index];
            if x < l || x > h {
                let bound = if x > h { h } else { l };
                let s = (bound - current.u[index]) / (x - current.u[index]);
                if exit.is_none_or(|e| s < e.2) {
                    exit = Some((index, bound, s));
                }
            }
        }
        if let Some((index, bound, s)) = exit {
            let guess: U = std::array::from_fn(|i| current.u[i] + s * (next.u[i] - current.u[i]));
            match system.correct(
                &guess,
                current.tau,
                &Plane::Fixed {
                    index,
                    value: bound,
                },
                &current.tangent,
            )? {
                Some(n) if n.counts == reference => {
                    sigma = distance(&n.u, &current.u);
                    next = n;
                    boundary = Some(bound);
                }
                _ => break CurveEnd::Boundary { value: bound },
            }
        }
        // Codimension-two points on the way.
        let mut on_the_way = Vec::new();
        for (kind, test) in tests(&system, &current) {
            let (a, b) = (test(&current), test(&next));
            if !(a.is_finite() && b.is_finite()) || (a > 0.0) == (b > 0.0) {
                continue;
            }
            let sign = a > 0.0;
            let step = Step {
                system: &system,
                current: &current,
                ds: sigma,
            };
            let (l, r, located) = step.bisect(
                Sample {
                    t: 0.0,
                    node: current.clone(),
                },
                Sample {
                    t: 1.0,
                    node: next.clone(),
                },
                &|n| (test(n) > 0.0) == sign,
            )?;
            // A cusp is where the tangent's (Q, P) part vanishes; a reversal of it across a
            // sharp turn of the curve in the parameter plane (where the steps crawl) is none.
            if kind == Codim2Kind::Cusp
                && [&l, &r]
                    .iter()
                    .any(|s| s.node.tangent[2].hypot(s.node.tangent[3]) > 0.05)
            {
                continue;
            }
            on_the_way.push((l.t, refined(&system, kind, &l, &r, located, index)?));
        }
        on_the_way.sort_by(|a, b| a.0.total_cmp(&b.0));
        found.extend(on_the_way.into_iter().map(|(_, c)| c));
        arclength += sigma;
        points.push(point(&system, &next, arclength)?);
        if let Some(value) = boundary {
            break CurveEnd::Boundary { value };
        }
        if points.len() > 10 && distance(&next.u, &first) < sigma {
            break CurveEnd::Closed;
        }
        crawling = if sigma <= options.crawl_step() {
            crawling + 1
        } else {
            0
        };
        if crawling >= 25 {
            let params = system.params(&next.u)?;
            if let Some(c) = meeting_at(&system, &next, &params, points.len() - 1)? {
                let end = CurveEnd::Codim2 {
                    kind: c.kind,
                    over: c.over,
                    vary: c.vary,
                };
                found.push(c);
                break end;
            }
            break CurveEnd::Stalled {
                over: next.u[2],
                vary: next.u[3],
                multiplier: next.orbit.multipliers[0].modulus(),
                obstacle: obstacle(&system, &params, &next.orbit)?,
            };
        }
        if System::margin(&next) < MARGIN {
            if let Some(n) = rechart(&mut system, &next)? {
                next = n;
            }
        }
        current = next;
        ds = (1.5 * ds).min(options.max_step);
    };
    Ok(OneWay {
        points,
        codim2: found,
        end,
    })
}

/// The start node, in a chart whose section lies in the middle of the start orbit's longest
/// slide, with its tangent pointing towards larger Q when `direction` > 0.
fn oriented(system: &System, start: &CurveStart, direction: f64) -> Result<(System, Node)> {
    let (system, x, tau) = system.recharted(&start.params, &start.orbit, start.tau)?;
    let u = [
        x.y,
        x.v,
        system.over.get(&start.params),
        system.vary.get(&start.params),
    ];
    let node = system
        .correct(
            &u,
            tau,
            &Plane::Fixed {
                index: 2,
                value: u[2],
            },
            &[0.0, 0.0, direction, 0.0],
        )?
        .ok_or_else(|| -> Error {
            crate::stability::StabilityError::SingularJacobian {
                y: u[0],
                v: u[1],
                determinant: 0.0,
            }
            .into()
        })?;
    Ok((system, node))
}

/// Follow the curve of `start` (see [`super::find_start`]) over Q from its start value towards
/// `to`, within the range between `from` and `to`; when the start value lies strictly inside
/// that range, the curve is followed from it towards `from` too, and the two ways are joined
/// into one curve from `from`'s side to `to`'s. `monitor` sees the points of each way against
/// [`ContinuationOptions::max_points`] and can stop the work.
///
/// # Errors
/// [`Error::InvalidParameter`] for invalid options, `from` equal to `to`, or a start value of
/// Q outside the range; [`Error::Cancelled`];
/// [`crate::stability::StabilityError::SingularJacobian`] when the extended system has no
/// tangent at the start; whatever the solver reports.
pub fn follow_curve(
    start: &CurveStart,
    (from, to): (f64, f64),
    options: &ContinuationOptions,
    monitor: &dyn Monitor,
) -> Result<Curve> {
    follow_curve_within(start, (from, to), None, options, monitor)
}

/// [`follow_curve`] on the model `dynamics` (`start` found on it by [`super::find_start_of`]):
/// with a smooth friction law ([`crate::stability::FrictionDynamics`]) the residuals are taken
/// to the accuracy of its stiff solver's map ([`Dynamics::map_tolerance`]) and ∂P^p/∂(Q, P)
/// come from its sensitivities ([`Dynamics::parameter_derivative`]).
///
/// # Errors
/// As [`follow_curve`].
pub fn follow_curve_of(
    dynamics: Arc<dyn Dynamics>,
    start: &CurveStart,
    (from, to): (f64, f64),
    options: &ContinuationOptions,
    monitor: &dyn Monitor,
) -> Result<Curve> {
    follow_curve_within_of(dynamics, start, (from, to), None, options, monitor)
}

/// [`follow_curve`] with P kept within `vary_range` (its ends in either order) when given: a
/// way that leaves it ends at the point where P equals the end it passes
/// ([`CurveEnd::Boundary`] with that end's value). The two ways are traced at once (each on
/// its own thread when there are several); the curve is the same for any number of threads.
///
/// # Errors
/// As [`follow_curve`]; [`Error::InvalidParameter`] for a range of P whose ends are not finite
/// or are equal, or that does not hold the start's value of P.
pub fn follow_curve_within(
    start: &CurveStart,
    (from, to): (f64, f64),
    vary_range: Option<(f64, f64)>,
    options: &ContinuationOptions,
    monitor: &dyn Monitor,
) -> Result<Curve> {
    follow_curve_within_of(
        Arc::new(ExactDynamics),
        start,
        (from, to),
        vary_range,
        options,
        monitor,
    )
}

/// [`follow_curve_within`] on the model `dynamics` (see [`follow_curve_of`]).
///
/// # Errors
/// As [`follow_curve_within`].
pub fn follow_curve_within_of(
    dynamics: Arc<dyn Dynamics>,
    start: &CurveStart,
    (from, to): (f64, f64),
    vary_range: Option<(f64, f64)>,
    options: &ContinuationOptions,
    monitor: &dyn Monitor,
) -> Result<Curve> {
    let options = options.validate()?;
    crate::continuation::check_ends(from, to)?;
    let (lo, hi) = (from.min(to), from.max(to));
    let a0 = start.over.get(&start.params);
    if !(lo <= a0 && a0 <= hi) {
        return Err(Error::InvalidParameter {
            name: start.over.label(),
            value: a0,
            allowed: "the curve's start value must lie between from and to",
        });
    }
    let vary_range = match vary_range {
        Some((a, b)) => {
            let p0 = start.vary.get(&start.params);
            let (l, h) = (a.min(b), a.max(b));
            if !(a.is_finite() && b.is_finite() && l < h) {
                return Err(Error::InvalidParameter {
                    name: start.vary.label(),
                    value: if a.is_finite() { b } else { a },
                    allowed: "the ends of the range of the varied parameter must be finite \
                              numbers that differ",
                });
            }
            if !(l <= p0 && p0 <= h) {
                return Err(Error::InvalidParameter {
                    name: start.vary.label(),
                    value: p0,
                    allowed: "the curve's start value of the varied parameter must lie within \
                              its range",
                });
            }
            Some((l, h))
        }
        None => None,
    };
    let system = System {
        base: start.params,
        over: start.over,
        vary: start.vary,
        period: start.period,
        follow: start.follow,
        border: start.border,
        options,
        phase: 0.0,
        dynamics,
    };
    let towards = (to - a0).signum();
    let way = |ahead: bool, direction: f64| -> Result<Option<OneWay>> {
        if !ahead {
            return Ok(None);
        }
        let (system, node) = oriented(&system, start, direction)?;
        Ok(Some(one_way(&system, node, (lo, hi), vary_range, monitor)?))
    };
    let (forward, backward) = rayon::join(|| way(a0 != to, towards), || way(a0 != from, -towards));
    let (forward, backward) = (forward?, backward?);
    let mut points = Vec::new();
    let mut codim2 = Vec::new();
    let mut begin = CurveEnd::Start;
    let mut end = CurveEnd::Start;
    let mut start_index = 0;
    if let Some(b) = backward {
        let n = b.points.len();
        let total = b.points.last().map_or(0.0, |p| p.arclength);
        points.extend(b.points.into_iter().rev().map(|mut p| {
            p.arclength = total - p.arclength;
            p
        }));
        codim2.extend(b.codim2.into_iter().rev().map(|mut c| {
            c.after_point = n.saturating_sub(2 + c.after_point.min(n - 1)).min(n - 1);
            std::mem::swap(&mut c.before, &mut c.after);
            c
        }));
        begin = b.end;
        start_index = n - 1;
    }
    if let Some(f) = forward {
        let offset = points.len().saturating_sub(1);
        let base = points.last().map_or(0.0, |p| p.arclength);
        let skip = usize::from(!points.is_empty());
        points.extend(f.points.into_iter().skip(skip).map(|mut p| {
            p.arclength += base;
            p
        }));
        codim2.extend(f.codim2.into_iter().map(|mut c| {
            c.after_point += offset;
            c
        }));
        end = f.end;
    }
    let stability_changes = points
        .windows(2)
        .enumerate()
        .filter(|(_, w)| w[0].stability != w[1].stability)
        .map(|(i, w)| StabilityChange {
            after_point: i,
            over: 0.5 * (w[0].over + w[1].over),
            vary: 0.5 * (w[0].vary + w[1].vary),
            from: w[0].stability,
            to: w[1].stability,
        })
        .collect();
    Ok(Curve {
        follow: start.follow,
        border: start.border,
        over: start.over,
        vary: start.vary,
        params: start.params,
        period: start.period,
        points,
        start: start_index,
        codim2,
        stability_changes,
        begin,
        end,
    })
}
