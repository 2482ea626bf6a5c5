//! The steps a continuation takes where the pseudo-arclength step fails: a step in the
//! parameter alone across a kink, and the last step aimed at an end of the range.

use super::corrector::{self, norm, Problem, Solution};
use super::ContinuationOptions;
use crate::error::Result;
use crate::params::State;

/// The angle between two unit vectors.
pub(super) fn angle(a: &[f64; 3], b: &[f64; 3]) -> f64 {
    corrector::dot(a, b).clamp(-1.0, 1.0).acos()
}

/// A step in the parameter alone (Newton's method at λ + Δλ from the current state), taken
/// where the pseudo-arclength step fails: past a kink of the branch at a grazing point, whose
/// two sides can meet at so sharp an angle that no hyperplane across the tangent before it
/// meets the branch after it. Accepted when it lands within 4·Δs and either crosses a change
/// of the event counts or turns the tangent by at most the largest angle.
pub(super) fn natural_step(
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
    let kink = problem.pieces(&next.orbit) != problem.pieces(&current.orbit)
        || (problem.on_belt() && next.orbit.stuck_at_strobe != current.orbit.stuck_at_strobe);
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
pub(super) fn aim_at(
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
