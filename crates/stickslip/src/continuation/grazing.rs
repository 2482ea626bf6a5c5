//! Past the end of a branch's smooth pieces: where a slide grazes rest with the net force
//! within the static limit (μs > 1), a stop of finite length appears mid-swing and the strobe
//! map jumps. The branch ends there, named as a grazing. An orbit of the same period with the
//! new stop just past it is found when there is one and reported beside it, but not continued:
//! the stop it gains has a finite length at once, so that orbit lies a finite distance away
//! (the jump), on a branch of its own that does not end at the grazing (it exists on both
//! sides of it, as at w = 0.2004 for ζ = 0, μs = 3, β = 9), and joining the two would draw one
//! branch through a jump.
//!
//! A smooth friction law (Stribeck, cubic) starts from its static level, μ(0) = μs: there
//! the stop that appears begins with zero length and the map stays continuous, so such a
//! grazing ends no branch; where a branch of such a law does stop, it ends as stalled or
//! failed with the obstacle its last orbit is closest to, found on the law's own solver.

use super::corrector::{counts, Problem, Solution};
use super::detect::side;
use super::obstacle::{obstacle_of, slide_minimum};
use super::{BranchEnd, Obstacle};
use crate::error::Result;
use crate::solver::EventKind;
use crate::stability::strobe_map;

/// Why the branch ends at `last` (its last point, `previous` the one before it), continued
/// with λ moving with the sign of `direction` within `range`; `stalled` says whether the steps
/// stalled (else they failed).
pub(super) fn end_at(
    problem: &Problem,
    previous: Option<&Solution>,
    last: &Solution,
    direction: f64,
    (lo, hi): (f64, f64),
    stalled: bool,
) -> Result<BranchEnd> {
    let lambda = last.u[2];
    let params = problem.params(lambda)?;
    let multiplier = last.orbit.multipliers[0].modulus();
    // On the model's own solver with its own forces (a smooth diode law has no switches).
    let obstacle = obstacle_of(problem.dynamics, &params, &last.orbit)?;
    // A smooth friction law's grazing is no jump (the stop appears with zero length): the
    // branch ends where the steps did, naming it.
    let slide = match obstacle {
        Obstacle::Grazing(slide) if !slide.continuous => slide,
        _ => {
            return Ok(if stalled {
                BranchEnd::Stalled {
                    value: lambda,
                    multiplier,
                    obstacle,
                }
            } else {
                BranchEnd::Failed {
                    value: lambda,
                    obstacle,
                }
            })
        }
    };
    // The speed at the minimum falls linearly in λ towards the grazing: its secant through the
    // last two points says where it reaches zero (the last point when that is not ahead).
    let mut value = lambda;
    if let Some(p) = previous {
        let prev = slide_minimum(problem.dynamics, &problem.params(p.u[2])?, &p.orbit)?;
        if let Some(prev) = prev {
            let dl = lambda - p.u[2];
            let dv = prev.velocity - slide.velocity;
            if dl != 0.0 && dv > 0.0 {
                let step = dl * slide.velocity / dv;
                if step * direction >= 0.0 && step.abs() <= 10.0 * dl.abs() {
                    value = lambda + step;
                }
            }
        }
    }
    // An orbit of the new events: Newton's method at λ just past the grazing, from the last
    // orbit's strobe state and from its image there (which has the new stop); taken when its
    // event counts differ and it stops near where the slide grazed.
    let scale = value.abs().max(0.1);
    let period = problem.period as f64 * last.orbit.drive_period;
    for offset in [1e-9, 1e-7, 1e-5, 1e-3] {
        let beyond = value + direction * offset * scale;
        if !(lo..=hi).contains(&beyond) {
            continue;
        }
        let Ok(at) = problem.params(beyond) else {
            continue;
        };
        let mut guesses = vec![last.orbit.state];
        if let Ok(image) = strobe_map(&at, last.orbit.state, problem.period) {
            guesses.push(image.state);
        }
        for guess in guesses {
            let Some(next) = problem.natural(beyond, guess, direction)? else {
                continue;
            };
            let stops_there =
                next.orbit.events.iter().any(|e| {
                    e.kind == EventKind::Stick && (e.tau - slide.tau).abs() <= 0.05 * period
                });
            if counts(&next.orbit) != counts(&last.orbit) && stops_there {
                return Ok(BranchEnd::Grazing {
                    value,
                    last: lambda,
                    multiplier,
                    slide,
                    beyond: Some(side(&next)),
                });
            }
        }
    }
    Ok(BranchEnd::Grazing {
        value,
        last: lambda,
        multiplier,
        slide,
        beyond: None,
    })
}
