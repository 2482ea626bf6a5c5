//! The exact event-driven solver for the piecewise-linear (Coulomb friction / PWL diode) model.
//!
//! Between switching events the equation of motion is linear, so each sliding segment and each
//! stuck segment is advanced in closed form (the private module `linear`); only the event times are found
//! numerically.
//!
//! **No missed velocity zeros.** On a sliding segment with direction s, let g(t) = s·y'(t) ≥ 0.
//! From a point a with known g, g', g'' and bounds M₂ ≥ |g''|, M₃ ≥ |g'''| on [a, a + H]
//! (computed from the closed form: every term's amplitude times its frequency to the power of
//! the derivative), Taylor's theorem gives
//!
//! ```text
//! g(a + h) ≥ g + g'h − M₂h²/2      and      g(a + h) ≥ g + g'h + g''h²/2 − M₃h³/6,
//! ```
//!
//! so g has no zero before the first positive root of either right-hand side. Second, while
//! |g''(a)| > M₃·h the curvature keeps its sign on [a, a + h]: where g is convex it lies above
//! its tangent (no zero before the Newton point), and where it is concave it is at least
//! min(g(a), g(a + h)), so a positive value at a + h proves the stretch free of zeros and a
//! sign change brackets exactly one zero, which a safeguarded Newton iteration then locates to
//! rounding. Every step is thus derived from the segment's own frequencies, amplitudes and
//! curvature (not from a fixed dt) and can never pass a zero, however tangential.
//!
//! **Stick exit** is solved in closed form: while stuck at y_s the net force
//! β cos(wτ + φ) − y_s is a shifted cosine, and its first outward crossing of ±μs is an arccos.

use crate::error::{Error, Result};
use crate::linear::{Damping, LinearSegment};
use crate::params::{Params, State};
use crate::solver::{Event, EventKind, Phase, Sample, Solver, Stats};
use std::f64::consts::TAU;

/// Largest number of search steps on one segment before the search reports failure.
const MAX_SEARCH_STEPS: u64 = 1_000_000;

/// Motion during one segment. (Kept unboxed: a new segment starts at every event, and a heap
/// allocation there would cost more than the copy.)
#[derive(Debug, Clone, Copy)]
#[allow(clippy::large_enum_variant)]
enum Segment {
    /// Sliding in direction `sign` (±1).
    Slide { sign: f64, linear: LinearSegment },
    /// Stuck at y = `y`; leaves at local time `exit` (infinite if never) in direction
    /// `exit_sign`.
    Stick { y: f64, exit: f64, exit_sign: f64 },
}

/// The exact solver. See the module documentation for the method.
///
/// ```
/// use stickslip::{ExactSolver, Params, Solver, State, EventKind};
/// // Free Coulomb decay from y = 7.5: turning points −5.5, 3.5, −1.5, then a stop at −0.5.
/// let params = Params::new(0.0, 1.0, 0.0).unwrap();
/// let mut solver = ExactSolver::new(params, State { y: 7.5, v: 0.0 });
/// let mut turns = Vec::new();
/// while let Some(event) = solver.advance(100.0).unwrap() {
///     turns.push((event.kind, event.y));
/// }
/// assert_eq!(turns.len(), 4);
/// assert!((turns[0].1 + 5.5).abs() < 1e-12 && turns[3].0 == EventKind::Stick);
/// assert!((turns[3].1 + 0.5).abs() < 1e-12);
/// ```
#[derive(Debug, Clone)]
pub struct ExactSolver {
    params: Params,
    damping: Damping,
    /// Absolute start time of the current segment.
    tau0: f64,
    /// Drive phase w τ0 + φ (mod 2π) at the segment start, carried from segment to segment so
    /// that the force checks at events and the stick exits all see one and the same phase.
    theta0: f64,
    /// Consecutive events at one and the same instant (zero-length segments), to break loops
    /// that rounding could otherwise cause at a tangential stick boundary.
    repeats: u32,
    segment: Segment,
    /// Current absolute time.
    time: f64,
    /// Local time up to which the current sliding segment is known to have no velocity zero.
    searched: f64,
    /// The segment, its start, and the interval covered by the last advance (for dense output).
    last: (Segment, f64, f64, f64),
    stats: Stats,
}

impl ExactSolver {
    /// A solver starting at τ = 0 from `initial`. With y'(0) = 0 the oscillator starts stuck
    /// when the net force |β cos φ − y0| is at most μs.
    pub fn new(params: Params, initial: State) -> Self {
        let damping = Damping::new(params.zeta);
        let mut solver = Self {
            params,
            damping,
            tau0: 0.0,
            theta0: params.phi.rem_euclid(TAU),
            repeats: 0,
            segment: Segment::Stick {
                y: initial.y,
                exit: f64::INFINITY,
                exit_sign: 0.0,
            },
            time: 0.0,
            searched: 0.0,
            last: (
                Segment::Stick {
                    y: initial.y,
                    exit: f64::INFINITY,
                    exit_sign: 0.0,
                },
                0.0,
                0.0,
                0.0,
            ),
            stats: Stats::default(),
        };
        let theta = solver.theta0;
        if initial.v != 0.0 {
            solver.start_slide(0.0, theta, initial.y, initial.v, initial.v.signum());
        } else {
            let force = params.beta * theta.cos() - initial.y;
            if force.abs() <= params.mu_s {
                solver.start_stick(0.0, theta, initial.y);
            } else {
                solver.start_slide(0.0, theta, initial.y, 0.0, force.signum());
            }
        }
        solver.last = (solver.segment, solver.tau0, 0.0, 0.0);
        solver
    }

    /// The parameters of the model.
    pub fn params(&self) -> &Params {
        &self.params
    }

    /// Drive phase at local time t of the current segment, reduced to [0, 2π).
    fn phase_at(&self, t: f64) -> f64 {
        (self.theta0 + self.params.w * t).rem_euclid(TAU)
    }

    fn start_slide(&mut self, tau0: f64, theta: f64, y: f64, v: f64, sign: f64) {
        let p = &self.params;
        let linear = LinearSegment::new(self.damping, p.w, p.beta, theta, sign, y, v);
        self.tau0 = tau0;
        self.theta0 = theta;
        self.time = tau0;
        self.searched = 0.0;
        self.segment = Segment::Slide { sign, linear };
    }

    fn start_stick(&mut self, tau0: f64, theta: f64, y: f64) {
        let (exit, exit_sign) = self.stick_exit(theta, y, self.repeats < 4);
        self.tau0 = tau0;
        self.theta0 = theta;
        self.time = tau0;
        self.segment = Segment::Stick { y, exit, exit_sign };
    }

    /// Local time and direction at which a stop at y, starting at drive phase θ, ends: the
    /// first outward crossing of β cos(ψ) − y = ±μs. With `allow_now`, a crossing a rounding
    /// error behind θ means "now" (a stop of zero duration).
    fn stick_exit(&self, theta: f64, y: f64, allow_now: bool) -> (f64, f64) {
        let p = &self.params;
        if p.beta == 0.0 {
            return (f64::INFINITY, 0.0);
        }
        let ahead = |psi: f64| {
            let d = (psi - theta).rem_euclid(TAU);
            if allow_now && d > TAU - 1e-12 {
                0.0
            } else {
                d
            }
        };
        let up = (y + p.mu_s) / p.beta; // cos ψ rising through this: force reaches +μs
        let down = (y - p.mu_s) / p.beta; // cos ψ falling through this: force reaches −μs
        let mut best = (f64::INFINITY, 0.0);
        if up <= -1.0 {
            return (0.0, 1.0);
        }
        if down >= 1.0 {
            return (0.0, -1.0);
        }
        if up < 1.0 {
            let d = ahead(TAU - up.acos());
            best = (d, 1.0);
        }
        if down > -1.0 {
            let d = ahead(down.acos());
            if d < best.0 {
                best = (d, -1.0);
            }
        }
        (best.0 / p.w, best.1)
    }

    /// First velocity zero of the current sliding segment in local times (searched, limit]:
    /// `Some((t, y(t)))`, or None. Advances `self.searched`.
    fn find_velocity_zero(
        &mut self,
        sign: f64,
        linear: &LinearSegment,
        limit: f64,
    ) -> Result<Option<(f64, f64)>> {
        let mut a = self.searched;
        let mut e = linear.eval(a);
        self.stats.evaluations += 1;
        let mut steps = 0u64;
        loop {
            if steps > MAX_SEARCH_STEPS {
                return Err(Error::EventSearch {
                    tau: self.tau0 + a,
                    reason: "velocity-zero search did not converge",
                });
            }
            let g = sign * e.d[1];
            let mut g1 = sign * e.d[2];
            let g2 = sign * e.d[3];
            if a == 0.0 && g == 0.0 {
                // A slide that starts from rest has an acceleration ≥ 0 along its direction
                // (the force has crossed ±μs outward, or exceeds it after a turn); a negative
                // value here is rounding.
                g1 = g1.max(0.0);
            }
            if a > 0.0 && ((g <= e.velocity_noise && g1 < 0.0) || g < -e.velocity_noise) {
                // Converged onto a zero from the left (or crossed it within rounding noise).
                self.searched = a;
                let newton = if g1 < 0.0 {
                    (g / -g1).clamp(0.0, 1e-6)
                } else {
                    0.0
                };
                return Ok(Some((a + newton, e.d[0])));
            }
            let span = 2.0;
            let (m2, m3) = linear.derivative_bounds(a, span, &e);
            let g = g.max(0.0);
            // Taylor steps: rigorous lower bounds of the first zero.
            let mut h = quadratic_safe_step(g, g1, m2);
            if g1 >= 0.0 && g2 > 0.0 {
                // (Where g2 ≤ 0 the curvature step below does better.)
                h = h.max(cubic_safe_step(g, g1, g2, m3));
            }
            // Curvature-certified length: g'' keeps the sign of g2 on [a, a + hc].
            let hc = if m3 > 0.0 {
                (g2.abs() / m3).min(span)
            } else {
                span
            };
            if g2 > 0.0 {
                // Convex: g lies above its tangent, which stays positive up to the Newton
                // point (everywhere when g1 ≥ 0).
                let reach = if g1 < 0.0 { hc.min(g / -g1) } else { hc };
                h = h.max(reach);
            } else if g2 < 0.0 {
                // Concave: on [a, b] g is at least min(g(a), g(b)); aim just past the Newton
                // point, where the zero is expected.
                let target = if g1 < 0.0 {
                    // Root of the local quadratic model g + g1 h + g2 h²/2 (g2 < 0), a little
                    // beyond it so that the zero is bracketed.
                    let model = 2.0 * g / (-g1 + (g1 * g1 - 2.0 * g2 * g).sqrt());
                    hc.min(1.02 * model + 1e-9 * a.max(1.0))
                } else {
                    hc
                };
                // (Only when the target is past a in floating point: a step below one ulp
                // would evaluate the same point for ever.)
                if target > h && (a + target).min(limit) > a {
                    let b = (a + target).min(limit);
                    let eb = linear.eval(b);
                    self.stats.evaluations += 1;
                    steps += 1;
                    self.stats.steps += 1;
                    if sign * eb.d[1] > 0.0 {
                        if b >= limit {
                            self.searched = limit;
                            return Ok(None);
                        }
                        a = b;
                        e = eb;
                        continue;
                    }
                    // Exactly one zero in (a, b]: g is concave there.
                    return Ok(Some(self.polish_zero(sign, linear, a, b, eb)));
                }
            }
            h = h.min(span);
            if !(h > 0.0) || a + h == a {
                // Stalled on a double zero (g and g' both at rounding level): that is the event.
                if a > 0.0 {
                    self.searched = a;
                    return Ok(Some((a, e.d[0])));
                }
                h = 1e-12;
            }
            steps += 1;
            self.stats.steps += 1;
            if a + h >= limit {
                self.searched = limit;
                return Ok(None);
            }
            a += h;
            e = linear.eval(a);
            self.stats.evaluations += 1;
        }
    }

    /// The single velocity zero in (a, b], where s·v(a) > 0 ≥ s·v(b): Newton's method kept
    /// inside the shrinking bracket (bisection when a step leaves it).
    fn polish_zero(
        &mut self,
        sign: f64,
        linear: &LinearSegment,
        mut a: f64,
        mut b: f64,
        eb: crate::linear::Derivatives,
    ) -> (f64, f64) {
        let mut t = b;
        let mut e = eb;
        for _ in 0..100 {
            let g = sign * e.d[1];
            if g > 0.0 {
                a = t;
            } else {
                b = t;
            }
            let g1 = sign * e.d[2];
            let newton = if g1 != 0.0 { t - g / g1 } else { f64::NAN };
            // Newton converges quadratically: after a step below 1e-10 the next iterate is
            // exact to rounding, and y moves by v·Δt.
            if (newton - t).abs() <= 1e-10 * t.abs().max(1.0) || g == 0.0 {
                let next = if g == 0.0 { t } else { newton.clamp(a, b) };
                self.searched = a;
                return (next, e.d[0] + e.d[1] * (next - t));
            }
            let next = if newton > a && newton < b {
                newton
            } else {
                0.5 * (a + b)
            };
            t = next;
            e = linear.eval(t);
            self.stats.evaluations += 1;
        }
        self.searched = a;
        (t, e.d[0])
    }

    /// Track consecutive zero-length segments.
    fn count_repeat(&mut self, local_time: f64) {
        if local_time == 0.0 {
            self.repeats += 1;
        } else {
            self.repeats = 0;
        }
    }

    fn segment_sample(segment: &Segment, tau0: f64, tau: f64) -> Sample {
        match segment {
            Segment::Slide { sign, linear } => {
                let (y, v) = linear.state(tau - tau0);
                Sample {
                    tau,
                    y,
                    v,
                    phase: if *sign > 0.0 {
                        Phase::SlipPositive
                    } else {
                        Phase::SlipNegative
                    },
                }
            }
            Segment::Stick { y, .. } => Sample {
                tau,
                y: *y,
                v: 0.0,
                phase: Phase::Stick,
            },
        }
    }

    /// Close the current segment at absolute time `tau_end` and return the state there.
    fn close(&mut self, from: f64, tau_end: f64) -> Sample {
        self.last = (self.segment, self.tau0, from, tau_end);
        self.time = tau_end;
        Self::segment_sample(&self.segment, self.tau0, tau_end)
    }
}

/// First positive root of g + g1·h − m2·h²/2 (with g ≥ 0): a lower bound of the first zero.
#[inline]
fn quadratic_safe_step(g: f64, g1: f64, m2: f64) -> f64 {
    if m2 <= 0.0 {
        return if g1 < 0.0 { g / -g1 } else { f64::INFINITY };
    }
    let root = (g1 * g1 + 2.0 * m2 * g).sqrt();
    if g1 < 0.0 {
        2.0 * g / (root - g1)
    } else {
        (g1 + root) / m2
    }
}

/// A lower bound (within 1e-4 relative) of the positive root of
/// L(h) = g + g1·h + g2·h²/2 − m3·h³/6 for g, g1 ≥ 0.
/// L rises (or is flat) and then falls, so it has exactly one positive root; Newton's method
/// from a point past the root where L is concave and decreasing converges monotonically from
/// the right.
#[inline]
fn cubic_safe_step(g: f64, g1: f64, g2: f64, m3: f64) -> f64 {
    if m3 <= 0.0 {
        return 0.0;
    }
    let l = |h: f64| g + h * (g1 + h * (0.5 * g2 - m3 * h / 6.0));
    let dl = |h: f64| g1 + h * (g2 - 0.5 * m3 * h);
    // Start right of the peak of L (root of L'), of the inflection g2/m3, and of the root.
    let peak = (g2 + (g2 * g2 + 2.0 * m3 * g1).sqrt()) / m3;
    let mut h = peak.max(g2 / m3).max(1e-300);
    while l(h) > 0.0 {
        h *= 2.0;
        if !h.is_finite() {
            return 0.0;
        }
    }
    // Newton from the right stays right of the root and converges quadratically, so once a
    // correction is below 1e-4 of h the root lies within one correction of h: step back two.
    for _ in 0..60 {
        let slope = dl(h);
        let value = l(h);
        if value >= 0.0 {
            return h;
        }
        if slope >= 0.0 {
            return 0.0;
        }
        let next = h - value / slope;
        let step = h - next;
        h = next;
        if step <= 1e-4 * h {
            return (h - 2.0 * step).max(0.0);
        }
    }
    0.0
}

impl Solver for ExactSolver {
    fn time(&self) -> f64 {
        self.time
    }

    fn state(&self) -> State {
        let s = Self::segment_sample(&self.segment, self.tau0, self.time);
        State { y: s.y, v: s.v }
    }

    fn phase(&self) -> Phase {
        match self.segment {
            Segment::Slide { sign, .. } if sign > 0.0 => Phase::SlipPositive,
            Segment::Slide { .. } => Phase::SlipNegative,
            Segment::Stick { .. } => Phase::Stick,
        }
    }

    fn drive(&self, tau: f64) -> f64 {
        self.params.drive(tau)
    }

    fn advance(&mut self, t_end: f64) -> Result<Option<Event>> {
        if t_end < self.time || t_end.is_nan() {
            return Err(Error::TimeBeforeCurrent {
                requested: t_end,
                current: self.time,
            });
        }
        let from = self.time;
        let limit = t_end - self.tau0;
        match self.segment {
            Segment::Stick { y, exit, exit_sign } => {
                if exit > limit || exit == f64::INFINITY {
                    self.close(from, t_end);
                    return Ok(None);
                }
                let tau = self.tau0 + exit;
                let theta = self.phase_at(exit);
                self.close(from, tau);
                self.count_repeat(exit);
                self.start_slide(tau, theta, y, 0.0, exit_sign);
                self.stats.events += 1;
                Ok(Some(Event {
                    tau,
                    y,
                    kind: EventKind::Slip,
                }))
            }
            Segment::Slide { sign, linear } => {
                let Some((t, y)) = self.find_velocity_zero(sign, &linear, limit)? else {
                    self.close(from, t_end);
                    return Ok(None);
                };
                let tau = self.tau0 + t;
                let theta = self.phase_at(t);
                self.last = (self.segment, self.tau0, from, tau);
                self.time = tau;
                let force = self.params.beta * theta.cos() - y;
                self.count_repeat(t);
                if force.abs() <= self.params.mu_s || (t == 0.0 && force.signum() == sign) {
                    // (At t = 0 a slide that cannot start is a stop, even when rounding puts
                    // the force a hair beyond μs.)
                    self.start_stick(tau, theta, y);
                    self.stats.events += 1;
                    Ok(Some(Event {
                        tau,
                        y,
                        kind: EventKind::Stick,
                    }))
                } else if force.signum() != sign {
                    self.start_slide(tau, theta, y, 0.0, force.signum());
                    self.stats.events += 1;
                    Ok(Some(Event {
                        tau,
                        y,
                        kind: EventKind::Turn,
                    }))
                } else {
                    // The velocity touched zero while the force still pushes onward: the motion
                    // goes on in the same direction (a tangency within rounding), no event.
                    self.start_slide(tau, theta, y, 0.0, sign);
                    self.advance(t_end)
                }
            }
        }
    }

    fn interval(&self) -> (f64, f64) {
        (self.last.2, self.last.3)
    }

    fn dense(&self, tau: f64) -> Sample {
        Self::segment_sample(&self.last.0, self.last.1, tau)
    }

    fn stats(&self) -> Stats {
        self.stats
    }
}
