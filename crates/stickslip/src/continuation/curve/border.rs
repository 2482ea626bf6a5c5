//! The conditions of a grazing, evaluated on the motion from a strobe state: each event that
//! can appear or disappear has a function h that changes sign where it does (see
//! [`BorderKind`]).
//!
//! - [`BorderKind::TurnAtLimit`] at every velocity zero (a turning point or the start of a
//!   stop) at τ_e: h = |F(τ_e) − y(τ_e) − 2ζ·vb| − μs, positive at a turning point, at most 0
//!   at a stop.
//! - [`BorderKind::SlideTouchesRest`] at every minimum of the speed inside a slide (y'' = 0,
//!   found on 32 samples and refined by Newton's method on y'' with its closed-form
//!   derivative): h = s·(y'(τ_m) − vb), the lowest slip, s the slide's direction. Past a stop
//!   the slide is continued in closed form as if it went on (its slip overshoots and comes
//!   back): h < 0 there, and h = 0 where the slide reaches the stop tangentially (y'' = 0 on
//!   arrival; on a belt the continuation's [`Obstacle::TangentialStick`]).
//! - [`BorderKind::ReleaseTangential`] at every extremum τ* of the net force of a stop, inside
//!   it, or in the slide right after its release (before its next event), as if the block were
//!   still stuck: h = |F(τ*) − y_s(τ*) − 2ζ·vb| − μs, at most 0 inside (no release there),
//!   positive after a release. On a base at rest y_s is the stop's position and τ* an extremum
//!   of the drive (F'(τ*) = 0); on a belt the stuck block moves with it, y_s(τ) = y_s +
//!   vb·(τ − τ_s), and τ* is where the drive's rate matches the belt's, F'(τ*) = vb (none when
//!   βw ≤ |vb|: the net force of a stop is monotone, its release never tangential).
//!
//! Each h is a function of the strobe state and the parameters through the motion up to its
//! event, exact to rounding (the exact solver's events and dense output). Without a belt every
//! term in vb is an exact 0, and each h is computed as on a base at rest, bit for bit.
//!
//! [`Obstacle::TangentialStick`]: crate::continuation::Obstacle::TangentialStick

use super::BorderKind;
use crate::error::Result;
use crate::exact::ExactSolver;
use crate::params::{Params, State};
use crate::solver::{EventKind, Phase, Solver};
use std::f64::consts::PI;

/// One condition on one motion.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Candidate {
    pub kind: BorderKind,
    /// See [`super::Border::variant`].
    pub variant: bool,
    /// Its time from the strobe.
    pub tau: f64,
    /// h.
    pub value: f64,
    /// For the start of a stop ([`BorderKind::TurnAtLimit`] of the stop's variant): how long
    /// the stop lasts (to the end of the motion when it is not released); 0 otherwise.
    pub extent: f64,
}

/// Samples of a slide's speed for its minima.
const SAMPLES: usize = 32;

/// Every condition on the motion from `state` at `params` over `period` drive periods.
pub(crate) fn candidates(params: &Params, state: State, period: usize) -> Result<Vec<Candidate>> {
    Ok(candidates_of(params, state, period, None, None)?.0)
}

/// Whether some time of [lo, hi] lies within `reach` of `tau` cyclically over `span` (a little
/// more, never less: what lies outside cannot be [`nearest`] to `tau`).
fn reaches(lo: f64, hi: f64, (tau, reach): (f64, f64), span: f64) -> bool {
    let reach = reach * (1.0 + 1e-6) + 1e-9 * span;
    (-2..=2).any(|k| {
        let centre = tau + f64::from(k) * span;
        lo <= centre + reach && hi >= centre - reach
    })
}

/// The conditions of `only`'s kind (every kind when `None`) on the motion from `state` at
/// `params` over `period` drive periods, each computed as [`candidates`] computes it, with the
/// motion's (turns, stops) over the period. A kind left out costs nothing: the minima of the
/// slides' speeds (a search on every slide) are sought only for
/// [`BorderKind::SlideTouchesRest`], and with `near` = (τ, r) only on the slides that come
/// within r of τ (cyclically over the period): the others' cannot be [`nearest`] to τ within
/// r, and the list is complete within r of τ alone.
pub(crate) fn candidates_of(
    params: &Params,
    state: State,
    period: usize,
    only: Option<BorderKind>,
    near: Option<(f64, f64)>,
) -> Result<(Vec<Candidate>, (usize, usize))> {
    let wanted = |kind: BorderKind| only.is_none_or(|k| k == kind);
    let mut counts = (0usize, 0usize);
    let end = period as f64 * params.drive_period();
    let within = |lo: f64, hi: f64| near.is_none_or(|n| reaches(lo, hi, n, end));
    let mut solver = ExactSolver::new(*params, state);
    let mut out = Vec::new();
    // The position and time of the stop just released, until the slide after it has an event.
    let mut released: Option<(f64, f64)> = None;
    // The direction of the last slide.
    let mut last_sign = 0.0;
    // The candidate of the stop under way.
    let mut stop_start: Option<usize> = None;
    while solver.time() < end {
        let event = solver.advance(end)?;
        let (a, b) = solver.interval();
        if b > a {
            let middle = solver.dense(0.5 * (a + b));
            match middle.phase {
                Phase::Stick if wanted(BorderKind::ReleaseTangential) => {
                    // (On a belt the stuck block moves with it.)
                    let mid = 0.5 * (a + b);
                    let stuck = |tau: f64| stuck_position(params, middle.y, mid, tau);
                    for tau in extrema(params, a, b) {
                        out.push(Candidate {
                            kind: BorderKind::ReleaseTangential,
                            variant: true,
                            tau,
                            value: params.net_force(tau, stuck(tau)).abs() - params.mu_s,
                            extent: 0.0,
                        });
                    }
                }
                Phase::Stick => {}
                phase => {
                    let sign = phase.sign();
                    last_sign = sign;
                    if let Some((y_s, tau_s)) = released.take() {
                        let extrema = extrema(params, a, b);
                        for tau in extrema.filter(|_| wanted(BorderKind::ReleaseTangential)) {
                            let stuck = stuck_position(params, y_s, tau_s, tau);
                            out.push(Candidate {
                                kind: BorderKind::ReleaseTangential,
                                variant: false,
                                tau,
                                value: params.net_force(tau, stuck).abs() - params.mu_s,
                                extent: 0.0,
                            });
                        }
                    }
                    if wanted(BorderKind::SlideTouchesRest) && within(a, b) {
                        minima(params, &solver, a, b, sign, &mut out);
                    }
                }
            }
        }
        match event {
            Some(e) if matches!(e.kind, EventKind::Turn | EventKind::Stick) => {
                if e.kind == EventKind::Turn {
                    counts.0 += 1;
                } else {
                    counts.1 += 1;
                }
                released = None;
                // (A virtual minimum lies within half a drive period after the stop.)
                if e.kind == EventKind::Stick
                    && last_sign != 0.0
                    && wanted(BorderKind::SlideTouchesRest)
                    && within(e.tau, e.tau + 0.5 * params.drive_period())
                {
                    if let Some(c) = virtual_minimum(params, e.tau, e.y, last_sign) {
                        out.push(c);
                    }
                }
                if !wanted(BorderKind::TurnAtLimit) {
                    continue;
                }
                if e.kind == EventKind::Stick {
                    stop_start = Some(out.len());
                }
                out.push(Candidate {
                    kind: BorderKind::TurnAtLimit,
                    variant: e.kind == EventKind::Turn,
                    tau: e.tau,
                    value: params.net_force(e.tau, e.y).abs() - params.mu_s,
                    extent: if e.kind == EventKind::Stick {
                        end - e.tau
                    } else {
                        0.0
                    },
                });
            }
            Some(e) if e.kind == EventKind::Slip => {
                released = Some((e.y, e.tau));
                if let Some(k) = stop_start.take() {
                    out[k].extent = e.tau - out[k].tau;
                }
            }
            _ => {}
        }
    }
    Ok((out, counts))
}

/// Where a block stuck since τ_s at y_s is at τ: it moves with the belt, y_s + vb·(τ − τ_s)
/// (y_s itself, bit for bit, without one).
fn stuck_position(params: &Params, y_s: f64, tau_s: f64, tau: f64) -> f64 {
    if params.vb == 0.0 {
        y_s
    } else {
        y_s + params.vb * (tau - tau_s)
    }
}

/// The extrema in [a, b] of the net force on a stuck block, F(τ) − vb·τ up to a constant:
/// without a belt those of the drive, w·τ + φ ≡ 0 (mod π); on one, where F'(τ) = vb,
/// sin(wτ + φ) = −vb/(βw) (none when βw ≤ |vb|), in order.
fn extrema(params: &Params, a: f64, b: f64) -> impl Iterator<Item = f64> {
    let (w, phi) = (params.w, params.phi);
    // The phases θ₀ + kπ·(step) of the extrema: 0 + kπ without a belt; on one the two roots
    // −asin(r) and π + asin(r) of sin θ = −r in each turn.
    let roots: Vec<f64> = if params.vb == 0.0 {
        let first = ((w * a + phi) / PI).ceil() as i64;
        let last = ((w * b + phi) / PI).floor() as i64;
        (first..=last).map(|k| (k as f64 * PI - phi) / w).collect()
    } else {
        let r = params.vb / (params.beta * w);
        if !(r.abs() < 1.0) {
            Vec::new()
        } else {
            let s = r.asin();
            let tau = std::f64::consts::TAU;
            let mut out = Vec::new();
            for base in [-s, PI + s] {
                let first = ((w * a + phi - base) / tau).floor() as i64;
                let last = ((w * b + phi - base) / tau).ceil() as i64;
                out.extend((first..=last).map(|k| (base + k as f64 * tau - phi) / w));
            }
            out.sort_by(f64::total_cmp);
            out
        }
    };
    roots.into_iter().filter(move |&t| t >= a && t <= b)
}

/// The interior minima of the speed of the slide in direction `sign` over [a, b].
fn minima(
    params: &Params,
    solver: &ExactSolver,
    a: f64,
    b: f64,
    sign: f64,
    out: &mut Vec<Candidate>,
) {
    let h = (b - a) / SAMPLES as f64;
    // (The slip s·(y' − vb); without a belt s·y', bit for bit.)
    let slip = |v: f64| {
        if params.vb == 0.0 {
            sign * v
        } else {
            sign * (v - params.vb)
        }
    };
    let speeds: Vec<f64> = (0..=SAMPLES)
        .map(|k| slip(solver.dense(a + k as f64 * h).v))
        .collect();
    // y'' on the slide, and its derivative y''' = F' − y' − 2ζ y''.
    let acceleration = |t: f64| {
        let s = solver.dense(t);
        params.drive(t) - s.y - 2.0 * params.zeta * s.v - sign
    };
    let jerk = |t: f64, acc: f64| {
        let s = solver.dense(t);
        -params.beta * params.w * (params.w * t + params.phi).sin() - s.v - 2.0 * params.zeta * acc
    };
    for k in 1..SAMPLES {
        if !(speeds[k] <= speeds[k - 1] && speeds[k] <= speeds[k + 1]) {
            continue;
        }
        // The speed's derivative s·y'' goes from negative to positive in the bracket.
        let (mut lo, mut hi) = (a + (k - 1) as f64 * h, a + (k + 1) as f64 * h);
        let (f_lo, f_hi) = (sign * acceleration(lo), sign * acceleration(hi));
        if !(f_lo <= 0.0 && f_hi >= 0.0) {
            continue;
        }
        let mut t = a + k as f64 * h;
        for _ in 0..100 {
            let acc = acceleration(t);
            let f = sign * acc;
            if f == 0.0 {
                break;
            }
            if f < 0.0 {
                lo = t;
            } else {
                hi = t;
            }
            let step = acc / jerk(t, acc);
            let next = t - step;
            let next = if next > lo && next < hi && step.is_finite() {
                next
            } else {
                0.5 * (lo + hi)
            };
            if (next - t).abs() <= 4.0 * f64::EPSILON * t.abs().max(1.0) || hi - lo <= 0.0 {
                t = next;
                break;
            }
            t = next;
        }
        // A minimum the slide reaches (not one past its end, where it has stopped).
        let value = slip(solver.dense(t).v);
        if t > a && t < b && value > 0.0 {
            out.push(Candidate {
                kind: BorderKind::SlideTouchesRest,
                variant: false,
                tau: t,
                value,
                extent: 0.0,
            });
        }
    }
}

/// The candidate of `kind` (and of `variant`, when given) nearest in time to `tau`
/// (cyclically over the orbit's period `span`), if one lies within a twentieth of it.
pub(crate) fn nearest(
    candidates: &[Candidate],
    kind: BorderKind,
    variant: Option<bool>,
    tau: f64,
    span: f64,
) -> Option<Candidate> {
    let distance = |c: &Candidate| {
        let d = (c.tau - tau).rem_euclid(span);
        d.min(span - d)
    };
    candidates
        .iter()
        .filter(|c| {
            c.kind == kind
                && (kind == BorderKind::SlideTouchesRest || variant.is_none_or(|v| c.variant == v))
        })
        .filter(|c| distance(c) <= 0.05 * span)
        .min_by(|a, b| distance(a).total_cmp(&distance(b)))
        .copied()
}

/// Of the candidates of `kind` and `variant` whose value lies within `within` of the one
/// nearest `tau`, the first after the strobe: a followed event with a partner at the same
/// border (the two turning points of a symmetric orbit) is taken as the earlier one, so that
/// the motion up to it, and with it the condition, does not cross the partner's border.
pub(crate) fn earliest(
    candidates: &[Candidate],
    kind: BorderKind,
    variant: bool,
    tau: f64,
    span: f64,
    within: f64,
) -> Option<Candidate> {
    let reference = nearest(candidates, kind, Some(variant), tau, span)?;
    candidates
        .iter()
        .filter(|c| {
            c.kind == kind && c.variant == variant && (c.value - reference.value).abs() <= within
        })
        .min_by(|a, b| a.tau.total_cmp(&b.tau))
        .copied()
}

/// The lowest slip of the slide in direction `sign` that stops at `tau` at `y`, continued in
/// closed form past the stop as if it went on (its slip s·(y' − vb) falls below zero and
/// comes back): the condition [`BorderKind::SlideTouchesRest`] across its border. `None` when
/// it does not come back within half a drive period (the slide would turn, not touch rest).
fn virtual_minimum(params: &Params, tau: f64, y: f64, sign: f64) -> Option<Candidate> {
    let theta = (params.w * tau + params.phi).rem_euclid(std::f64::consts::TAU);
    let segment = crate::linear::LinearSegment::new(
        crate::linear::Damping::new(params.zeta),
        params.w,
        params.beta,
        theta,
        sign,
        y,
        params.vb,
    );
    let horizon = 0.5 * params.drive_period();
    let n = 64;
    let h = horizon / n as f64;
    // s·y'' from negative to positive: the speed's minimum.
    let acc = |t: f64| sign * segment.eval(t).d[2];
    let mut previous = acc(0.0);
    if !(previous < 0.0) {
        return None;
    }
    for k in 1..=n {
        let t = k as f64 * h;
        let a = acc(t);
        if a >= 0.0 {
            let (mut lo, mut hi) = (t - h, t);
            let mut m = t - h * a / (a - previous);
            for _ in 0..60 {
                let d = segment.eval(m).d;
                let f = sign * d[2];
                if f < 0.0 {
                    lo = m;
                } else {
                    hi = m;
                }
                let next = m - d[2] / d[3];
                let next = if next > lo && next < hi && next.is_finite() {
                    next
                } else {
                    0.5 * (lo + hi)
                };
                if (next - m).abs() <= 4.0 * f64::EPSILON * (tau + m).abs().max(1.0) {
                    m = next;
                    break;
                }
                m = next;
            }
            return Some(Candidate {
                kind: BorderKind::SlideTouchesRest,
                variant: true,
                tau: tau + m,
                value: if params.vb == 0.0 {
                    sign * segment.eval(m).d[1]
                } else {
                    sign * (segment.eval(m).d[1] - params.vb)
                },
                extent: 0.0,
            });
        }
        previous = a;
    }
    None
}

#[cfg(test)]
mod tests {
    use super::*;

    /// On a belt a stuck block rides along, y = y_s + vb·(τ − τ_s), so a stop's net force
    /// β cos(wτ + φ) − y − 2ζ·vb is extremal where F'(τ) = vb, not where F'(τ) = 0. Each
    /// release condition inside a stop sits at such a point, with the value |net| − μs that
    /// the solver's own motion gives there, and the net force 10⁻³ either side lies on one
    /// side of it (an extremum).
    #[test]
    fn a_stops_release_conditions_on_a_belt_sit_at_its_net_forces_extrema() {
        let params = Params::new(0.05, 0.5, 1.0)
            .and_then(|p| p.with_mu_s(3.0))
            .and_then(|p| p.with_vb(0.1))
            .unwrap();
        // Stuck at the start (|net| = 0.99 < μs) for about 30 time units, two drive periods
        // and more: the net force β cos − vb·τ swings through several extrema meanwhile.
        let state = State::new(0.0, 0.1).unwrap();
        let (list, _) =
            candidates_of(&params, state, 3, Some(BorderKind::ReleaseTangential), None).unwrap();
        let inside: Vec<&Candidate> = list.iter().filter(|c| c.variant).collect();
        assert!(inside.len() >= 3, "{list:?}");
        let net = |tau: f64| {
            let mut solver = ExactSolver::new(params, state);
            crate::solver::run_until(&mut solver, tau, |_| {}).unwrap();
            let s = solver.state();
            assert_eq!(s.v, params.vb, "stuck at τ = {tau}");
            params.beta * (params.w * tau + params.phi).cos() - s.y - 2.0 * params.zeta * params.vb
        };
        for c in inside {
            let (w, beta) = (params.w, params.beta);
            let rate = -beta * w * (w * c.tau + params.phi).sin() - params.vb;
            assert!(
                rate.abs() < 1e-12,
                "τ = {}: net force's rate {rate:e}",
                c.tau
            );
            let at = net(c.tau);
            assert!(
                (at.abs() - params.mu_s - c.value).abs() < 1e-12,
                "τ = {}: {} against |{at}| − μs",
                c.tau,
                c.value
            );
            let (before, after) = (net(c.tau - 1e-3), net(c.tau + 1e-3));
            assert!(
                (before - at) * (after - at) > 0.0,
                "τ = {}: {before}, {at}, {after}",
                c.tau
            );
        }
    }
}
