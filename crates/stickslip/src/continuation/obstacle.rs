//! What the last orbit of a branch that cannot go on is closest to: a turning point at the
//! static limit, a tangential release, a slide grazing rest, or a stop reached tangentially.
//!
//! The orbit is run on its model's own solver ([`Dynamics::solver`], its dense output) with
//! the model's forces: Coulomb's law ([`crate::ExactSolver`]) slides against the kinetic level
//! 1 and holds up to μs; a smooth law (Stribeck, cubic: [`crate::stability::FrictionDynamics`])
//! slides against μ(|s|), s = y' − vb, and holds up to μs = μ(0). With Coulomb's law and
//! μs > 1 a stop that appears mid-swing has a finite length at once and the strobe map jumps.
//! A smooth law's friction at zero slip is its static limit, so there the net force at a
//! slide's lowest speed tends to ±μs, the stop that appears starts with zero length, and the
//! map stays continuous while its derivative jumps (a border collision, which `continue`
//! passes as a [`super::SpecialKind::Grazing`] point); its obstacles say so
//! ([`SlideMinimum::continuous`]).

use crate::error::Result;
use crate::params::Params;
use crate::solver::{EventKind, Phase, Sample};
use crate::stability::{Dynamics, ExactDynamics, PeriodicOrbit};
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
        /// Whether the strobe map stays continuous there (a smooth law, which starts from
        /// μs: past it the slide misses the belt's speed, or the slip before the stop
        /// shrinks to nothing, without a jump; only the map's derivative jumps). False, and
        /// left out of JSON, for Coulomb's law.
        #[serde(default, skip_serializing_if = "is_false")]
        continuous: bool,
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
    /// Whether the strobe map stays continuous where the slide reaches the belt's speed: a
    /// smooth law, whose friction at zero slip is the static limit μs, so the stop that
    /// appears begins with zero length and only the map's derivative jumps; `net_force` is
    /// then F − y − 2ζ·vb, which tends to μs there. False, and left out of JSON, for
    /// Coulomb's law (the stop has a finite length at once: the map jumps).
    #[serde(default, skip_serializing_if = "is_false")]
    pub continuous: bool,
}

/// For `skip_serializing_if`: Coulomb's obstacles keep their JSON as it was.
fn is_false(b: &bool) -> bool {
    !*b
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
        if self.continuous {
            return format!(
                "the slide after the {event} at τ = {:.6} comes to |y' − vb| = {:.1e} at \
                 τ = {:.6}, where the net force |F − y − 2ζvb| = {:.4}",
                self.after_tau, self.velocity, self.tau, self.net_force
            );
        }
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
/// output (to about 1e-10 of the slide's length). With a smooth law of `dynamics`
/// ([`Dynamics::is_exact`] false), as [`smooth_slide_minimum`].
pub(crate) fn slide_minimum(
    dynamics: &dyn Dynamics,
    params: &Params,
    orbit: &PeriodicOrbit,
) -> Result<Option<SlideMinimum>> {
    if !dynamics.is_exact() {
        return smooth_slide_minimum(dynamics, params, orbit);
    }
    const SAMPLES: usize = 32;
    let end = orbit.period as f64 * orbit.drive_period;
    // (One advance of the exact solver covers a whole slide.)
    let mut solver = ExactDynamics.solver(params, orbit.state)?;
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
    Ok(slide_at(params, orbit, (tau, velocity, y), fastest, false))
}

/// The slide minimum of `orbit` at `tau`, where the slip |y' − vb| is `velocity` and the
/// position `y`, with the orbit's largest slip `fastest` and the map's continuity there;
/// `None` when no event of the orbit precedes it.
fn slide_at(
    params: &Params,
    orbit: &PeriodicOrbit,
    (tau, velocity, y): (f64, f64, f64),
    fastest: f64,
    continuous: bool,
) -> Option<SlideMinimum> {
    after_event(orbit, tau).map(|(after, after_tau)| SlideMinimum {
        tau,
        speed: velocity / fastest.max(f64::MIN_POSITIVE),
        velocity,
        net_force: params.net_force(tau, y).abs(),
        after,
        after_tau,
        continuous,
    })
}

/// The event of `orbit` before τ, cyclically over the orbit's period: its kind and time
/// (negative when it lies in the previous period).
fn after_event(orbit: &PeriodicOrbit, tau: f64) -> Option<(EventKind, f64)> {
    let end = orbit.period as f64 * orbit.drive_period;
    orbit
        .events
        .iter()
        .rev()
        .find(|e| e.tau < tau)
        .map(|e| (e.kind, e.tau))
        .or_else(|| orbit.events.last().map(|e| (e.kind, e.tau - end)))
}

/// d|s|/dτ = σ·y'' at `x` on a slip of direction `sign` = σ (s = y' − vb of that sign) under
/// the smooth law of `params`: y'' = F − y − 2ζ y' − σ μ(|s|).
fn slip_rate(params: &Params, x: &Sample, sign: f64) -> f64 {
    let s = (x.v - params.vb).abs();
    let friction = sign * params.law.value(params.mu_s, s);
    sign * (params.drive(x.tau) - x.y - 2.0 * params.zeta * x.v - friction)
}

/// The slide minimum of a smooth law's orbit: the model's solver run over the orbit's
/// period, each slip step sampled at 32 points; where d|s|/dτ = σ y'' (with the law's
/// μ(|s|)) turns from negative to non-negative between two samples, |s| = |y' − vb| has a
/// minimum, located by bisection of σ y'' on the step's dense output (60 halvings: to
/// rounding). A slide spans many steps of the stiff integrator, and such a sign change
/// always lies between two samples of one step. The net force reported is F − y − 2ζ·vb.
fn smooth_slide_minimum(
    dynamics: &dyn Dynamics,
    params: &Params,
    orbit: &PeriodicOrbit,
) -> Result<Option<SlideMinimum>> {
    Ok(smooth_run(dynamics, params, orbit)?.0)
}

/// An event of a smooth law's orbit with the slip direction before it (0 after a stop).
struct SmoothEvent {
    event: crate::solver::Event,
    sign_before: f64,
}

/// The orbit run once on the model's solver: its slide minimum closest to rest and its
/// events with the slip direction before each.
fn smooth_run(
    dynamics: &dyn Dynamics,
    params: &Params,
    orbit: &PeriodicOrbit,
) -> Result<(Option<SlideMinimum>, Vec<SmoothEvent>)> {
    const SAMPLES: usize = 32;
    let end = orbit.period as f64 * orbit.drive_period;
    let mut solver = dynamics.solver(params, orbit.state)?;
    let mut events = Vec::new();
    let mut fastest = 0f64;
    let mut best: Option<(f64, f64, f64)> = None;
    while solver.time() < end {
        let before = solver.phase();
        if let Some(event) = solver.advance(end)? {
            events.push(SmoothEvent {
                event,
                sign_before: before.sign(),
            });
        }
        let (a, b) = solver.interval();
        if !(b > a) || before == Phase::Stick {
            continue;
        }
        let sign = before.sign();
        let h = (b - a) / SAMPLES as f64;
        let samples: Vec<Sample> = (0..=SAMPLES)
            .map(|k| solver.dense(if k == SAMPLES { b } else { a + k as f64 * h }))
            .collect();
        fastest = samples
            .iter()
            .fold(fastest, |m, x| m.max((x.v - params.vb).abs()));
        for pair in samples.windows(2) {
            if !(slip_rate(params, &pair[0], sign) < 0.0
                && slip_rate(params, &pair[1], sign) >= 0.0)
            {
                continue;
            }
            let (mut lo, mut hi) = (pair[0].tau, pair[1].tau);
            for _ in 0..60 {
                let mid = 0.5 * (lo + hi);
                if mid <= lo || mid >= hi {
                    break;
                }
                if slip_rate(params, &solver.dense(mid), sign) < 0.0 {
                    lo = mid;
                } else {
                    hi = mid;
                }
            }
            let x = solver.dense(0.5 * (lo + hi));
            let slip = (x.v - params.vb).abs();
            // (A slip that starts at the belt's speed with y'' = 0, as after a release, is
            // no minimum inside the slide: |s| did not come down to it.)
            let before = (pair[0].v - params.vb).abs();
            if slip < before && best.is_none_or(|(_, v, _)| slip < v) {
                best = Some((x.tau, slip, x.y));
            }
        }
    }
    let slide = best.and_then(|minimum| slide_at(params, orbit, minimum, fastest, true));
    Ok((slide, events))
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
            Obstacle::Grazing(slide) if slide.continuous => write!(
                f,
                "; a slide nearly touches the belt's speed: {}; past it a stop appears there, \
                 of zero length at first (the law's friction at zero slip is its static limit), \
                 so the strobe map stays continuous and its derivative jumps",
                slide.describe()
            ),
            Obstacle::Grazing(slide) => write!(
                f,
                "; a grazing: {}, within the static limit, so a stop of finite length \
                 appears mid-swing and the strobe map jumps",
                slide.describe()
            ),
            Obstacle::TangentialStick {
                tau,
                acceleration,
                continuous: true,
            } => write!(
                f,
                "; the stop at τ = {tau:.6} begins where the slide reaches the belt's speed \
                 almost tangentially (|y''|/μs = {acceleration:.1e} on arrival): past it the \
                 slide misses the belt's speed there, or the slip before the stop vanishes, \
                 without a jump (the strobe map stays continuous and its derivative jumps)"
            ),
            Obstacle::TangentialStick {
                tau, acceleration, ..
            } => write!(
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
        if let Some(slide) = slide_minimum(&ExactDynamics, params, orbit)? {
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
                            continuous: false,
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

/// The [`Obstacle`] of `orbit` at `params` for the model `dynamics`. The exact model's is
/// Coulomb's search on the exact solver; a model that does not stick (a smooth diode law) has
/// none; a smooth friction law's ([`crate::stability::FrictionDynamics`]) is found as the
/// exact model's, on its own solver and with its own forces (see the module documentation):
///
/// - a slide minimum of |s| = |y' − vb| within 10⁻² of the orbit's largest |s|
///   ([`Obstacle::Grazing`]; at such a minimum σ y'' = 0 puts the net force
///   F − y − 2ζvb at σ μ(|s|) + 2ζ s, next to the static limit, so no condition on it);
/// - a turning point whose net force is within 10⁻² (relative) of ±μs, or a stop that begins
///   within 10⁻² of the limit opposite to its slip, σ f = −μs (past it the slip reverses
///   there instead: [`Obstacle::TurnAtStaticLimit`]);
/// - a stop whose arrival acceleration σ y'' = σ f − μs is within 10⁻² μs of zero
///   ([`Obstacle::TangentialStick`]: the slide touches the belt's speed; the stop side of a
///   grazing);
/// - a release where the net force's rate |F' − vb| is within 10⁻² of βw + |vb|
///   ([`Obstacle::TangentialRelease`]);
///
/// the closest of them, measured relatively, when one is below 10⁻². The grazing and the
/// tangential stick are marked [`SlideMinimum::continuous`]: for these laws the strobe map
/// does not jump there.
///
/// # Errors
/// What the model's solver reports.
pub fn obstacle_of(
    dynamics: &dyn Dynamics,
    params: &Params,
    orbit: &PeriodicOrbit,
) -> Result<Obstacle> {
    if dynamics.is_exact() {
        return obstacle(params, orbit);
    }
    if !dynamics.sticks() {
        return Ok(Obstacle::None);
    }
    let (slide, events) = smooth_run(dynamics, params, orbit)?;
    let mu_s = params.mu_s;
    let mut best = (1e-2, Obstacle::None);
    if let Some(slide) = slide {
        if slide.speed < best.0 {
            best = (slide.speed, Obstacle::Grazing(slide));
        }
    }
    for SmoothEvent {
        event: e,
        sign_before,
    } in &events
    {
        let net = params.net_force(e.tau, e.y);
        match e.kind {
            EventKind::Turn => {
                let margin = (net.abs() - mu_s) / mu_s;
                if margin.abs() < best.0 {
                    best = (
                        margin.abs(),
                        Obstacle::TurnAtStaticLimit { tau: e.tau, margin },
                    );
                }
            }
            EventKind::Stick => {
                // The limit on the side the slip came from, σ f = μs, is where the slide only
                // touches the belt's speed (a tangential arrival); the opposite one,
                // σ f = −μs, where it would reverse instead.
                let along = sign_before * net;
                let acceleration = (along - mu_s).abs() / mu_s;
                if acceleration < best.0 {
                    best = (
                        acceleration,
                        Obstacle::TangentialStick {
                            tau: e.tau,
                            acceleration,
                            continuous: true,
                        },
                    );
                }
                let margin = (-along - mu_s) / mu_s;
                if along < 0.0 && margin.abs() < best.0 {
                    best = (
                        margin.abs(),
                        Obstacle::TurnAtStaticLimit { tau: e.tau, margin },
                    );
                }
            }
            EventKind::Slip => {
                let phase = params.w * e.tau + params.phi;
                let rate = (params.beta * params.w * phase.sin() + params.vb).abs()
                    / (params.beta * params.w + params.vb.abs());
                if rate < best.0 {
                    best = (rate, Obstacle::TangentialRelease { tau: e.tau, rate });
                }
            }
        }
    }
    Ok(best.1)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::options::NewtonOptions;
    use crate::params::State;
    use crate::solver::Solver;
    use crate::ExactSolver;

    /// On a Coulomb belt a slide's lowest slip is measured from the belt's speed and the net
    /// force there carries the belt's viscous load, |F − y − 2ζ·vb| (the force a stop would
    /// begin with): checked against the exact solver's own state at the minimum, on forced
    /// belts whose period-1 orbits have a slide with a minimum of |y' − vb| inside it.
    #[test]
    fn a_coulomb_belts_slide_minimum_carries_the_belts_load() {
        let mut checked = 0;
        let (mut orbits, mut tried) = (0, 0);
        for (w, beta) in [0.3, 0.5, 0.8, 1.2]
            .into_iter()
            .flat_map(|w| [0.8, 1.5, 2.5, 4.0].map(|beta| (w, beta)))
        {
            tried += 1;
            let params = Params::new(0.1, w, beta)
                .and_then(|p| p.with_mu_s(1.5))
                .and_then(|p| p.with_vb(0.3))
                .unwrap();
            let mut solver = ExactSolver::new(params, State::new(0.0, 0.3).unwrap());
            crate::solver::run_until(
                &mut solver,
                200.0 * 2.0 * std::f64::consts::PI / params.w,
                |_| {},
            )
            .unwrap();
            let guess = solver.state();
            let Ok(orbit) =
                crate::stability::find_periodic_orbit(&params, guess, 1, &NewtonOptions::default())
            else {
                continue;
            };
            orbits += 1;
            let Some(min) = slide_minimum(&ExactDynamics, &params, &orbit).unwrap() else {
                continue;
            };
            let mut exact = ExactSolver::new(params, orbit.state);
            crate::solver::run_until(&mut exact, min.tau, |_| {}).unwrap();
            let at = exact.state();
            let net = params.beta * (params.w * min.tau + params.phi).cos()
                - at.y
                - 2.0 * params.zeta * params.vb;
            assert!(
                (min.velocity - (at.v - params.vb).abs()).abs() < 1e-9,
                "w = {w}, β = {beta}: {min:?}"
            );
            assert!(
                (min.net_force - net.abs()).abs() < 1e-9,
                "w = {w}, β = {beta}: {min:?} against {net}"
            );
            checked += 1;
        }
        assert!(
            checked >= 2,
            "{checked} of {orbits} orbits ({tried} belts) had a slide minimum"
        );
    }
}
