//! The exact event-driven solver for the piecewise-linear (Coulomb friction / PWL diode) model.
//!
//! Between switching events the equation of motion is linear, so each sliding segment and each
//! stuck segment is advanced in closed form ([`crate::linear`]); only the event times are found
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
//! so g has no zero before the first positive root of either right-hand side. The search steps
//! by the larger of those two roots (capped by H), which can never pass a zero, however
//! tangential, and converges quadratically onto a simple zero from the left. The step is thus
//! derived from the segment's own frequencies and amplitudes, not from a fixed dt.
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

/// Motion during one segment.
#[derive(Debug, Clone, Copy)]
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
    segment: Segment,
    /// Current absolute time.
    time: f64,
    /// Local time up to which the current sliding segment is known to have no velocity zero.
    searched: f64,
    /// Whether the current sliding segment started from rest (y' = 0).
    from_rest: bool,
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
            segment: Segment::Stick {
                y: initial.y,
                exit: f64::INFINITY,
                exit_sign: 0.0,
            },
            time: 0.0,
            searched: 0.0,
            from_rest: false,
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
        if initial.v != 0.0 {
            solver.start_slide(0.0, initial.y, initial.v, initial.v.signum());
        } else {
            let force = params.drive(0.0) - initial.y;
            if force.abs() <= params.mu_s {
                solver.start_stick(0.0, initial.y);
            } else {
                solver.start_slide(0.0, initial.y, 0.0, force.signum());
            }
        }
        solver.last = (solver.segment, solver.tau0, 0.0, 0.0);
        solver
    }

    /// The parameters of the model.
    pub fn params(&self) -> &Params {
        &self.params
    }

    /// Drive phase w τ + φ reduced to [0, 2π).
    fn drive_phase(&self, tau: f64) -> f64 {
        (self.params.w * tau + self.params.phi).rem_euclid(TAU)
    }

    fn start_slide(&mut self, tau0: f64, y: f64, v: f64, sign: f64) {
        let p = &self.params;
        let theta = self.drive_phase(tau0);
        let linear = LinearSegment::new(self.damping, p.w, p.beta, theta, sign, y, v);
        self.tau0 = tau0;
        self.time = tau0;
        self.searched = 0.0;
        self.from_rest = v == 0.0;
        self.segment = Segment::Slide { sign, linear };
    }

    fn start_stick(&mut self, tau0: f64, y: f64) {
        let (exit, exit_sign) = self.stick_exit(tau0, y);
        self.tau0 = tau0;
        self.time = tau0;
        self.segment = Segment::Stick { y, exit, exit_sign };
    }

    /// Local time and direction at which a stop at y (starting at absolute time τ0) ends: the
    /// first outward crossing of β cos(ψ) − y = ±μs, ψ = w τ + φ.
    fn stick_exit(&self, tau0: f64, y: f64) -> (f64, f64) {
        let p = &self.params;
        let theta = self.drive_phase(tau0);
        if p.beta == 0.0 {
            return (f64::INFINITY, 0.0);
        }
        // Phase still to go from θ to ψ (mod 2π); a crossing just behind θ through rounding
        // means "now".
        let ahead = |psi: f64| {
            let d = (psi - theta).rem_euclid(TAU);
            if d > TAU - 1e-12 {
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

    /// First velocity zero of the current sliding segment in local times (searched, limit],
    /// or None. Advances `self.searched`.
    fn find_velocity_zero(
        &mut self,
        sign: f64,
        linear: &LinearSegment,
        limit: f64,
    ) -> Result<Option<f64>> {
        let mut a = self.searched;
        let mut steps = 0u64;
        loop {
            let e = linear.eval(a);
            self.stats.evaluations += 1;
            let g = sign * e.d[1];
            let mut g1 = sign * e.d[2];
            let g2 = sign * e.d[3];
            if a == 0.0 && self.from_rest {
                // A slide from rest starts only where the net force onward has reached
                // μs ≥ 1, so g' = s·(drive − y) − 1 ≥ 0 exactly. Rounding of the drive phase
                // at large τ can make it −ε; the search would then find a zero closer than
                // the resolution of τ and stop the motion again at the same instant, for ever
                // (a slip–stick loop at one τ).
                g1 = g1.max(0.0);
            }
            if a > 0.0 {
                // Converged onto a zero from the left, or crossed it (possible only through
                // rounding noise in g).
                if (g <= e.velocity_noise && g1 < 0.0) || g < -e.velocity_noise {
                    self.searched = a;
                    let newton = if g1 < 0.0 { (g / -g1).max(0.0) } else { 0.0 };
                    return Ok(Some(a + newton.min(1e-6)));
                }
            }
            let span = a.max(1.0);
            let m2 = linear.derivative_bound(3, a, span, e.envelope);
            let m3 = linear.derivative_bound(4, a, span, e.envelope);
            let g = g.max(0.0);
            let mut h = quadratic_safe_step(g, g1, m2);
            if g1 >= 0.0 {
                h = h.max(cubic_safe_step(g, g1, g2, m3));
            }
            h = h.min(span);
            if !(h > 0.0) || a + h == a {
                // Stalled on a double zero (g and g' both at rounding level): that is the event.
                if a > 0.0 {
                    self.searched = a;
                    return Ok(Some(a));
                }
                // At the very start with g = g' = 0: resume from a tiny offset.
                h = 1e-12;
            }
            steps += 1;
            self.stats.steps += 1;
            if a + h >= limit {
                self.searched = limit;
                return Ok(None);
            }
            a += h;
            if steps > MAX_SEARCH_STEPS {
                return Err(Error::EventSearch {
                    tau: self.tau0 + a,
                    reason: "velocity-zero search did not converge",
                });
            }
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

/// First positive root of L(h) = g + g1·h + g2·h²/2 − m3·h³/6 for g, g1 ≥ 0, rounded down.
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
    for _ in 0..60 {
        let slope = dl(h);
        if slope >= 0.0 {
            break;
        }
        let next = h - l(h) / slope;
        if !(next < h) {
            break;
        }
        let done = h - next <= 1e-12 * h;
        h = next;
        if done {
            break;
        }
    }
    h * (1.0 - 1e-9)
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
                self.close(from, tau);
                self.start_slide(tau, y, 0.0, exit_sign);
                self.stats.events += 1;
                Ok(Some(Event {
                    tau,
                    y,
                    kind: EventKind::Slip,
                }))
            }
            Segment::Slide { sign, linear } => {
                let Some(t) = self.find_velocity_zero(sign, &linear, limit)? else {
                    self.close(from, t_end);
                    return Ok(None);
                };
                let tau = self.tau0 + t;
                let y = self.close(from, tau).y;
                let force = self.params.drive(tau) - y;
                if force.abs() <= self.params.mu_s {
                    self.start_stick(tau, y);
                    self.stats.events += 1;
                    Ok(Some(Event {
                        tau,
                        y,
                        kind: EventKind::Stick,
                    }))
                } else if force.signum() != sign {
                    self.start_slide(tau, y, 0.0, force.signum());
                    self.stats.events += 1;
                    Ok(Some(Event {
                        tau,
                        y,
                        kind: EventKind::Turn,
                    }))
                } else {
                    // The velocity touched zero while the force still pushes onward: the motion
                    // goes on in the same direction (a tangency within rounding), no event.
                    self.start_slide(tau, y, 0.0, sign);
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
