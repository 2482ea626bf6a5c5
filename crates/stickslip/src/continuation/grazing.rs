//! Past the end of a branch's smooth pieces: where a slide grazes rest with the net force
//! within the static limit, a stop of finite length appears mid-swing and the strobe map
//! jumps. The branch is named there as a grazing and goes on when an orbit with the new
//! events (a stop where the slide grazed) lies just past it.

use super::corrector::{counts, Problem, Solution};
use super::detect::side;
use super::obstacle::{obstacle, slide_minimum};
use super::{BranchEnd, Obstacle, SpecialKind, SpecialPoint};
use crate::error::Result;
use crate::solver::EventKind;
use crate::stability::strobe_map;

/// What lies past the last point of a branch that can go no further by steps.
pub(super) enum Past {
    /// An orbit with the new events just past a grazing, and the grazing between the two.
    Across {
        next: Box<Solution>,
        special: Box<SpecialPoint>,
    },
    /// The branch ends here.
    End(BranchEnd),
}

/// What lies past `last` (the last point of the branch, `previous` the one before it, `index`
/// its position in the branch), continued with λ moving with the sign of `direction` within
/// `range`; `stalled` says whether the steps stalled (else they failed).
pub(super) fn past(
    problem: &Problem,
    previous: Option<&Solution>,
    last: &Solution,
    direction: f64,
    (lo, hi): (f64, f64),
    index: usize,
    stalled: bool,
) -> Result<Past> {
    let lambda = last.u[2];
    let params = problem.params(lambda)?;
    let multiplier = last.orbit.multipliers[0].modulus();
    let obstacle = obstacle(&params, &last.orbit)?;
    let Obstacle::Grazing(slide) = obstacle else {
        return Ok(Past::End(if stalled {
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
        }));
    };
    // The speed at the minimum falls linearly in λ towards the grazing: its secant through the
    // last two points says where it reaches zero (the last point when that is not ahead).
    let mut value = lambda;
    if let Some(p) = previous {
        let prev = slide_minimum(&problem.params(p.u[2])?, &p.orbit)?;
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
    // orbit's strobe state and from its image there (which has the new stop); accepted when
    // its event counts differ and it stops near where the slide grazed.
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
                let (a, b) = (&last.u, &next.u);
                let width =
                    ((a[0] - b[0]).powi(2) + (a[1] - b[1]).powi(2) + (a[2] - b[2]).powi(2)).sqrt();
                let special = SpecialPoint {
                    kind: SpecialKind::Grazing,
                    value,
                    state: last.orbit.state,
                    width,
                    located: width <= problem.options.locate_tolerance,
                    after_point: index,
                    before: side(last),
                    after: side(&next),
                };
                return Ok(Past::Across {
                    next: Box::new(next),
                    special: Box::new(special),
                });
            }
        }
    }
    Ok(Past::End(BranchEnd::Grazing {
        value,
        last: lambda,
        multiplier,
        slide,
    }))
}
