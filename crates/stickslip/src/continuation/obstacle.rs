//! What the last orbit of a branch that cannot go on is closest to: a turning point at the
//! static limit, a tangential release, a slide grazing rest, or a stop reached tangentially.

use crate::error::Result;
use crate::exact::ExactSolver;
use crate::params::Params;
use crate::solver::{EventKind, Phase, Solver};
use crate::stability::PeriodicOrbit;
use serde::{Deserialize, Serialize};

/// Where the strobe map of an orbit is about to jump or lose its derivative: the event of the
/// last orbit of a branch closest to such a switch, when one is close (relative margin below
/// 1e-2).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case", tag = "kind")]
pub enum Obstacle {
    /// A turning point whose net force |F − y| is within `margin` (relative to μs) of the
    /// static limit: beyond it the motion would stop there. For μs > 1 with the force falling
    /// back the stop would last long, so the strobe map jumps and the orbit ends. Or, on a
    /// belt, with `margin` < 0, the start of a stop that close to the limit: beyond it the
    /// slip would reverse there instead, and the stop that followed vanishes.
    TurnAtStaticLimit {
        /// Time of the turning point (or the stop's start) from the strobe.
        tau: f64,
        /// (|F − y − 2ζ·vb| − μs)/μs there.
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
    /// A slide whose speed comes within `speed` (relative to the orbit's largest speed) of
    /// rest at a minimum inside the slide, with the net force there inside the static limit:
    /// at the grazing the motion stops mid-swing for a finite time, so for μs > 1 the strobe
    /// map jumps (the orbit gains a stop of finite length at once).
    Grazing(SlideMinimum),
    /// On a belt, a stop that begins where the slide reaches the belt's speed almost
    /// tangentially: the relative acceleration on arrival, |y''| = |F − y − 2ζ·vb ∓ 1|,
    /// is `acceleration` (relative to μs). At the tangency the slide only touches the belt's
    /// speed; past it the slide misses it and goes on, so for μs > 1 the stop that followed
    /// vanishes at once and the strobe map jumps (the other side of [`Obstacle::Grazing`]).
    TangentialStick {
        /// Time of the stop's start from the strobe.
        tau: f64,
        /// The relative acceleration on arrival over μs.
        acceleration: f64,
    },
    /// No event of the orbit is close to a switch.
    None,
}

/// The lowest speed inside a slide of an orbit (a minimum of |y'| between two events, where
/// y'' = 0), and which event the slide follows.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct SlideMinimum {
    /// Time of the minimum from the strobe.
    pub tau: f64,
    /// |y'| at the minimum over the largest |y'| of the orbit.
    pub speed: f64,
    /// |y'| at the minimum (dimensionless).
    pub velocity: f64,
    /// The net force |F − y| at the minimum: a stop begins there when it is at most μs.
    pub net_force: f64,
    /// The event the slide follows (within the orbit's period, counted cyclically).
    pub after: EventKind,
    /// Time of that event from the strobe (negative when it happens in the previous period,
    /// before the strobe).
    pub after_tau: f64,
}

impl SlideMinimum {
    /// "the slide after the release at τ = 2.215000 comes to |y'| = 1.1e-5 at τ =
    /// 4.400000, where the net force |F − y| = 1.0000".
    pub fn describe(&self) -> String {
        let event = match self.after {
            EventKind::Turn => "turning point",
            EventKind::Stick => "stop",
            EventKind::Slip => "release",
        };
        format!(
            "the slide after the {event} at τ = {:.6} comes to |y'| = {:.1e} at τ = {:.6}, \
             where the net force |F − y| = {:.4}",
            self.after_tau, self.velocity, self.tau, self.net_force
        )
    }
}

/// The slide minimum of `orbit` at `params` closest to rest (relative to the orbit's largest
/// speed), or `None` when no slide has a minimum of |y'| away from its ends. The minima are
/// found on 32 samples of each slide and refined by golden sections on the exact dense
/// output (to about 1e-10 of the slide's length).
pub(crate) fn slide_minimum(
    params: &Params,
    orbit: &PeriodicOrbit,
) -> Result<Option<SlideMinimum>> {
    const SAMPLES: usize = 32;
    let end = orbit.period as f64 * orbit.drive_period;
    let mut solver = ExactSolver::new(*params, orbit.state);
    let mut fastest = 0f64;
    let mut best: Option<(f64, f64, f64)> = None;
    while solver.time() < end {
        solver.advance(end)?;
        let (a, b) = solver.interval();
        if !(b > a) || solver.dense(0.5 * (a + b)).phase == Phase::Stick {
            continue;
        }
        let h = (b - a) / SAMPLES as f64;
        let speeds: Vec<f64> = (0..=SAMPLES)
            .map(|k| (solver.dense(a + k as f64 * h).v - params.vb).abs())
            .collect();
        fastest = speeds.iter().fold(fastest, |m, &s| m.max(s));
        let Some(k) = (1..SAMPLES)
            .filter(|&k| speeds[k] <= speeds[k - 1] && speeds[k] <= speeds[k + 1])
            .min_by(|&i, &j| speeds[i].total_cmp(&speeds[j]))
        else {
            continue;
        };
        // Golden sections on the bracket around the sampled minimum.
        let g = 0.5 * (5f64.sqrt() - 1.0);
        let speed = |t: f64| (solver.dense(t).v - params.vb).abs();
        let (mut lo, mut hi) = (a + (k - 1) as f64 * h, a + (k + 1) as f64 * h);
        let (mut c, mut d) = (hi - g * (hi - lo), lo + g * (hi - lo));
        let (mut fc, mut fd) = (speed(c), speed(d));
        for _ in 0..60 {
            if fc < fd {
                hi = d;
                (d, fd) = (c, fc);
                c = hi - g * (hi - lo);
                fc = speed(c);
            } else {
                lo = c;
                (c, fc) = (d, fd);
                d = lo + g * (hi - lo);
                fd = speed(d);
            }
        }
        let tau = 0.5 * (lo + hi);
        let s = solver.dense(tau);
        let slip = (s.v - params.vb).abs();
        if best.is_none_or(|(_, v, _)| slip < v) {
            best = Some((tau, slip, s.y));
        }
    }
    let Some((tau, velocity, y)) = best else {
        return Ok(None);
    };
    // The event before the minimum, cyclically over the orbit's period.
    let previous = orbit
        .events
        .iter()
        .rev()
        .find(|e| e.tau < tau)
        .map(|e| (e.kind, e.tau))
        .or_else(|| orbit.events.last().map(|e| (e.kind, e.tau - end)));
    let Some((after, after_tau)) = previous else {
        return Ok(None);
    };
    Ok(Some(SlideMinimum {
        tau,
        speed: velocity / fastest.max(f64::MIN_POSITIVE),
        velocity,
        net_force: (params.drive(tau) - y).abs(),
        after,
        after_tau,
    }))
}

impl std::fmt::Display for Obstacle {
    /// "; a turning point is 1.2e-3 (relative) from the static friction limit, …", or
    /// nothing when no event is close to a switch.
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Obstacle::TurnAtStaticLimit { margin, .. } if *margin < 0.0 => write!(
                f,
                "; a stop begins {:.1e} (relative) inside the static friction limit, where \
                 it would become a turning point",
                -margin
            ),
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
            Obstacle::Grazing(slide) => write!(
                f,
                "; a grazing: {}, within the static limit, so a stop of finite length \
                 appears mid-swing and the strobe map jumps",
                slide.describe()
            ),
            Obstacle::TangentialStick { tau, acceleration } => write!(
                f,
                "; the stop at τ = {tau:.6} begins where the slide reaches the belt's speed \
                 almost tangentially (|y''|/μs = {acceleration:.1e} on arrival): past it the \
                 slide misses the stop and the strobe map jumps"
            ),
            Obstacle::None => Ok(()),
        }
    }
}

/// The [`Obstacle`] of `orbit` at `params`: the closest of a turning point at the
/// static limit (on a belt also a stop beginning there), a tangential release, a slide grazing
/// rest with the net force within the static limit and, on a belt, a stop reached tangentially
/// (the last three for μs > 1), each measured relatively, when one is below 1e-2.
pub(super) fn obstacle(params: &Params, orbit: &PeriodicOrbit) -> Result<Obstacle> {
    let mut best = (1e-2, Obstacle::None);
    if params.mu_s > 1.0 {
        if let Some(slide) = slide_minimum(params, orbit)? {
            if slide.speed < best.0 && slide.net_force < params.mu_s {
                best = (slide.speed, Obstacle::Grazing(slide));
            }
        }
    }
    for e in &orbit.events {
        let phase = params.w * e.tau + params.phi;
        match e.kind {
            crate::solver::EventKind::Turn => {
                let margin = (params.net_force(e.tau, e.y).abs() - params.mu_s) / params.mu_s;
                if margin.abs() < best.0 {
                    best = (
                        margin.abs(),
                        Obstacle::TurnAtStaticLimit { tau: e.tau, margin },
                    );
                }
            }
            // (On a belt: on a base at rest the ends of the paper's branches are kept.)
            crate::solver::EventKind::Stick if params.vb != 0.0 => {
                // A stop that begins at the static limit: beyond it the motion would turn
                // there (a margin below zero).
                let net = params.net_force(e.tau, e.y);
                let margin = (net.abs() - params.mu_s) / params.mu_s;
                if margin.abs() < best.0 {
                    best = (
                        margin.abs(),
                        Obstacle::TurnAtStaticLimit { tau: e.tau, margin },
                    );
                }
                // Arriving at the belt's speed from either side, y'' = net − sgn(s): the
                // smaller of |net ∓ 1| (|net| ≤ μs at a stick).
                let acceleration = (net - 1.0).abs().min((net + 1.0).abs()) / params.mu_s;
                if params.mu_s > 1.0 && acceleration < best.0 {
                    best = (
                        acceleration,
                        Obstacle::TangentialStick {
                            tau: e.tau,
                            acceleration,
                        },
                    );
                }
            }
            crate::solver::EventKind::Slip if params.mu_s > 1.0 => {
                // The net force's rate at the release relative to its largest, the drive's
                // βw (and the belt's vb that loads the spring).
                let rate = if params.vb == 0.0 {
                    phase.sin().abs()
                } else {
                    (params.beta * params.w * phase.sin() + params.vb).abs()
                        / (params.beta * params.w + params.vb.abs())
                };
                if rate < best.0 {
                    best = (rate, Obstacle::TangentialRelease { tau: e.tau, rate });
                }
            }
            _ => {}
        }
    }
    Ok(best.1)
}
