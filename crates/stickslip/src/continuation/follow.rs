//! Following a branch: [`continue_orbit`] one way, [`continue_both_ways`], and the orbit a
//! motion settles on, where `stickslip continue` starts.

use super::corrector::{self, counts, norm, Problem, Solution};
use super::grazing::end_at;
use super::step::{aim_at, angle, natural_step};
use super::{detect, Branch, BranchEnd, BranchPoint, ContinuationOptions};
use crate::error::{Error, Result};
use crate::experiment::Experiment;
use crate::params::{Parameter, Params, State};
use crate::scan::Monitor;
use crate::stability::{Dynamics, ExactDynamics, NewtonOptions, PeriodicOrbit};
use crate::steady::periodic_orbit_from_steady_of;
use std::ops::ControlFlow;

/// The p strobe points of an orbit and its extremes in y (on a belt, also those inside its
/// slides).
fn strobes_and_extremes(
    dynamics: &dyn Dynamics,
    params: &Params,
    orbit: &PeriodicOrbit,
) -> Result<(Vec<State>, f64, f64)> {
    let mut solver = dynamics.solver(params, orbit.state)?;
    let mut strobes = vec![orbit.state];
    for k in 1..orbit.period {
        crate::solver::run_until(solver.as_mut(), k as f64 * orbit.drive_period, |_| {})?;
        strobes.push(solver.state());
    }
    let ys = orbit
        .events
        .iter()
        .map(|e| e.y)
        .chain(strobes.iter().map(|s| s.y));
    let (mut lo, mut hi) = ys.fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), y| {
        (lo.min(y), hi.max(y))
    });
    if params.vb != 0.0 {
        // On a belt the events are the slip's zeros (y' = vb): y has its extremes inside the
        // slides as well, where y' = 0, found in the dense output over the orbit's period.
        let mut scan = dynamics.solver(params, orbit.state)?;
        let end = orbit.period as f64 * orbit.drive_period;
        while scan.time() < end {
            scan.advance(end)?;
            crate::steady::extremes::velocity_zeros(scan.as_ref(), 0.2, |s, _| {
                lo = lo.min(s.y);
                hi = hi.max(s.y);
            });
        }
    }
    Ok((strobes, lo, hi))
}

fn branch_point(problem: &Problem, s: &Solution, arclength: f64) -> Result<BranchPoint> {
    let params = problem.params(s.u[2])?;
    let (strobes, y_min, y_max) = strobes_and_extremes(problem.dynamics, &params, &s.orbit)?;
    let (turns, stops) = counts(&s.orbit);
    Ok(BranchPoint {
        value: s.u[2],
        arclength,
        orbit: s.orbit.clone(),
        strobes,
        y_min,
        y_max,
        turns,
        stops,
    })
}

/// Continue the branch of `start` (a periodic orbit at `params`, found by
/// [`crate::stability::find_periodic_orbit`]) in `parameter` from its value in `params`
/// towards `to`, within the range between the two (see the module documentation); `monitor`
/// sees the number of points against
/// [`ContinuationOptions::max_points`](super::ContinuationOptions::max_points) and can stop the
/// work.
///
/// # Errors
/// [`Error::InvalidParameter`] for invalid options, `to` equal to the start value or out of
/// the parameter's range, or a start orbit at rest; [`Error::Cancelled`];
/// [`crate::stability::StabilityError::SingularJacobian`] when the branch has no tangent at
/// the start; whatever the solver reports.
pub fn continue_orbit(
    params: &Params,
    parameter: Parameter,
    start: &PeriodicOrbit,
    to: f64,
    options: &ContinuationOptions,
    monitor: &dyn Monitor,
) -> Result<Branch> {
    continue_orbit_of(
        &ExactDynamics,
        params,
        parameter,
        start,
        to,
        options,
        monitor,
    )
}

/// [`continue_orbit`] on the model `dynamics` (`start` an orbit of it). With a smooth law
/// (the Shockley model) the branch has no seams: the changes of its threshold stops are
/// no grazing points and are not reported, and it ends where the steps fail or stall
/// without an [`super::Obstacle`] (those are switches of the PWL law); its residuals are
/// taken to the accuracy to which the stiff solver's map repeats
/// ([`Dynamics::repeat_tolerance`]), and ∂P/∂λ comes from its sensitivities. With a smooth
/// friction law ([`crate::stability::FrictionDynamics`]) the stops are switches again: the
/// changes of the event counts are grazing points, and an end is named by the obstacle search
/// on the law's own solver ([`super::obstacle_of`]); its grazings keep the map continuous (the
/// law starts from μs), so none ends the branch as [`BranchEnd::Grazing`].
///
/// # Errors
/// As [`continue_orbit`]; [`crate::Unsupported::MuSNeedsPwl`] for μs with a smooth law,
/// which does not use it.
pub fn continue_orbit_of(
    dynamics: &dyn Dynamics,
    params: &Params,
    parameter: Parameter,
    start: &PeriodicOrbit,
    to: f64,
    options: &ContinuationOptions,
    monitor: &dyn Monitor,
) -> Result<Branch> {
    if !dynamics.sticks() && parameter == Parameter::MuS {
        return Err(Error::Unsupported(crate::Unsupported::MuSNeedsPwl));
    }
    let options = options.validate()?;
    let params = params.validate()?;
    let from = parameter.get(&params);
    parameter.set(params, to)?;
    if to == from {
        return Err(Error::InvalidParameter {
            name: "to",
            value: to,
            allowed: "must differ from the start value",
        });
    }
    if start.is_rest() {
        return Err(Error::InvalidParameter {
            name: "start",
            value: start.state.y,
            allowed: "the start orbit is rest (no events): rest positions form a continuum, \
                      not a branch",
        });
    }
    let (lo, hi) = (from.min(to), from.max(to));
    let span = hi - lo;
    let problem = Problem {
        base: params,
        parameter,
        period: start.period,
        options,
        dynamics,
    };
    let direction = (to - from).signum();
    let Some(mut current) = problem.start(start.clone(), from, direction)? else {
        return Err(crate::stability::StabilityError::SingularJacobian {
            y: start.state.y,
            v: start.state.v,
            determinant: start.monodromy.minus_identity().det(),
        }
        .into());
    };
    let first = current.u;
    let mut points = vec![branch_point(&problem, &current, 0.0)?];
    let mut special = Vec::new();
    let mut ds = options.initial_step;
    let mut arclength = 0.0;
    let mut crawling = 0usize;
    let mut previous: Option<Solution> = None;
    let end = loop {
        if points.len() >= options.max_points {
            break BranchEnd::MaxPoints;
        }
        if monitor.step(points.len(), options.max_points) == ControlFlow::Break(()) {
            return Err(Error::Cancelled {
                done: points.len(),
                total: options.max_points,
            });
        }
        let t_lambda = current.tangent[2].abs();
        let cap = if t_lambda > 0.0 {
            options
                .max_step
                .min(options.max_parameter_step * span / t_lambda)
        } else {
            options.max_step
        };
        ds = ds.min(cap).max(options.min_step);
        let trial = problem.correct(&current, ds)?;
        let accepted = trial.filter(|s| {
            // Newton's method within the hyperplane can land on a far piece of the solution
            // set (another branch): a step is at most 4·Δs long, as a natural step.
            let d = [
                s.u[0] - current.u[0],
                s.u[1] - current.u[1],
                s.u[2] - current.u[2],
            ];
            if problem.on_belt() && norm(&d) > 4.0 * ds {
                return false;
            }
            // (A stop's edge crossing the strobe keeps the counts but turns the tangent.)
            let smooth = problem.pieces(&s.orbit) == problem.pieces(&current.orbit)
                && (!problem.on_belt() || s.orbit.stuck_at_strobe == current.orbit.stuck_at_strobe);
            !smooth
                || angle(&s.tangent, &current.tangent) <= options.max_angle
                || ds <= options.crawl_step()
        });
        let (mut next, mut natural) = match accepted {
            Some(next) => (next, false),
            None => match natural_step(&problem, &current, ds, &options)? {
                Some(next) => (next, true),
                None => {
                    if ds <= options.min_step {
                        break end_at(
                            &problem,
                            previous.as_ref(),
                            &current,
                            direction,
                            (lo, hi),
                            false,
                        )?;
                    }
                    ds = (0.5 * ds).max(options.min_step);
                    continue;
                }
            },
        };
        // Past an end of the range: aim the step at the end by the secant.
        let mut sigma = ds;
        let mut boundary = None;
        if next.u[2] < lo || next.u[2] > hi {
            let bound = if next.u[2] > hi { hi } else { lo };
            match aim_at(&problem, &current, &next, ds, natural, bound, (lo, hi))? {
                Some((s, candidate)) => {
                    sigma = s;
                    // End exactly at the bound: a last Newton correction in the state alone.
                    let direction = candidate.u[2] - current.u[2];
                    next = problem
                        .natural(bound, candidate.orbit.state, direction)?
                        .filter(|n| problem.pieces(&n.orbit) == problem.pieces(&candidate.orbit))
                        .unwrap_or(candidate);
                    if corrector::dot(&next.tangent, &current.tangent) < 0.0 && !natural {
                        next.tangent.iter_mut().for_each(|c| *c = -*c);
                    }
                    boundary = Some(bound);
                }
                None => break BranchEnd::Boundary { value: bound },
            }
        }
        let found = if natural {
            let (a, b) = (current.clone(), next.clone());
            let direction = next.u[2] - current.u[2];
            detect::between(
                &problem,
                &|t| {
                    let guess = State {
                        y: a.u[0] + t * (b.u[0] - a.u[0]),
                        v: a.u[1] + t * (b.u[1] - a.u[1]),
                    };
                    problem.natural(a.u[2] + t * (b.u[2] - a.u[2]), guess, direction)
                },
                &current,
                &next,
                points.len() - 1,
            )?
        } else {
            detect::between(
                &problem,
                &|t| problem.correct(&current, t * sigma),
                &current,
                &next,
                points.len() - 1,
            )?
        };
        special.extend(found);
        if natural {
            sigma = norm(&[
                next.u[0] - current.u[0],
                next.u[1] - current.u[1],
                next.u[2] - current.u[2],
            ]);
            natural = false;
        }
        let _ = natural;
        arclength += sigma;
        points.push(branch_point(&problem, &next, arclength)?);
        if next.orbit.is_rest() {
            break BranchEnd::Rest { value: next.u[2] };
        }
        if let Some(value) = boundary {
            break BranchEnd::Boundary { value };
        }
        let back = [
            next.u[0] - first[0],
            next.u[1] - first[1],
            next.u[2] - first[2],
        ];
        if points.len() > 10 && norm(&back) < sigma {
            break BranchEnd::Closed;
        }
        crawling = if sigma <= options.crawl_step() {
            crawling + 1
        } else {
            0
        };
        if crawling >= 25 {
            break end_at(&problem, Some(&current), &next, direction, (lo, hi), true)?;
        }
        previous = Some(current);
        current = next;
        ds = (1.5 * ds).min(options.max_step);
    };
    Ok(Branch {
        params,
        parameter,
        period: start.period,
        points,
        special,
        begin: BranchEnd::Start,
        end,
    })
}

/// Continue the branch of `start` both ways over the range from `lo` to `hi` (which holds
/// the start value): the points in order of the branch from the end reached going down in
/// λ to the end reached going up, arclength from the first.
///
/// # Errors
/// As [`continue_orbit`]; [`Error::InvalidParameter`] when the range does
/// not hold the start value or is empty.
pub fn continue_both_ways(
    params: &Params,
    parameter: Parameter,
    start: &PeriodicOrbit,
    range: (f64, f64),
    options: &ContinuationOptions,
    monitor: &dyn Monitor,
) -> Result<Branch> {
    continue_both_ways_of(
        &ExactDynamics,
        params,
        parameter,
        start,
        range,
        options,
        monitor,
    )
}

/// [`continue_both_ways`] on the model `dynamics` (see [`continue_orbit_of`]).
///
/// # Errors
/// As [`continue_both_ways`] and [`continue_orbit_of`].
pub fn continue_both_ways_of(
    dynamics: &dyn Dynamics,
    params: &Params,
    parameter: Parameter,
    start: &PeriodicOrbit,
    (lo, hi): (f64, f64),
    options: &ContinuationOptions,
    monitor: &dyn Monitor,
) -> Result<Branch> {
    let from = parameter.get(params);
    if !(lo <= from && from <= hi && lo < hi) {
        return Err(Error::InvalidParameter {
            name: parameter.label(),
            value: from,
            allowed: "the start value must lie in the range, and the range must not be empty",
        });
    }
    let down = if from > lo {
        Some(continue_orbit_of(
            dynamics, params, parameter, start, lo, options, monitor,
        )?)
    } else {
        None
    };
    let up = if from < hi {
        Some(continue_orbit_of(
            dynamics, params, parameter, start, hi, options, monitor,
        )?)
    } else {
        None
    };
    Ok(join(down, up, *params, parameter, start.period))
}

/// One branch from a branch run downwards (reversed) and one run upwards from the same start.
fn join(
    down: Option<Branch>,
    up: Option<Branch>,
    params: Params,
    parameter: Parameter,
    period: usize,
) -> Branch {
    let mut points = Vec::new();
    let mut special = Vec::new();
    let mut begin = BranchEnd::Start;
    let mut end = BranchEnd::Start;
    if let Some(d) = down {
        let n = d.points.len();
        let total = d.points.last().map_or(0.0, |p| p.arclength);
        points.extend(d.points.into_iter().rev().map(|mut p| {
            p.arclength = total - p.arclength;
            p
        }));
        // Along the reversed run a special point after point i lies after point n − 2 − i,
        // with its sides swapped.
        special.extend(d.special.into_iter().rev().map(|mut s| {
            s.after_point = n - 2 - s.after_point;
            std::mem::swap(&mut s.before, &mut s.after);
            s
        }));
        begin = d.end;
    }
    if let Some(u) = up {
        let offset = points.len().saturating_sub(1);
        let base = points.last().map_or(0.0, |p| p.arclength);
        let skip = usize::from(!points.is_empty());
        points.extend(u.points.into_iter().skip(skip).map(|mut p| {
            p.arclength += base;
            p
        }));
        special.extend(u.special.into_iter().map(|mut s| {
            s.after_point += offset;
            s
        }));
        end = u.end;
    }
    Branch {
        params,
        parameter,
        period,
        points,
        special,
        begin,
        end,
    }
}

/// The periodic orbit the motion of `experiment` settles on from its initial state (its
/// steady state, refined by Newton's method): where `stickslip continue` starts.
///
/// # Errors
/// [`crate::stability::StabilityError::NoPeriod`] when the motion finds no period;
/// whatever the solver and Newton's method report.
pub fn settled_orbit(experiment: &Experiment) -> Result<(Params, PeriodicOrbit)> {
    let dynamics = experiment.dynamics()?;
    let options = experiment.steady_options().with_spectrum(false);
    let steady = experiment.steady_with(&options)?;
    let params = steady.params;
    let orbit = periodic_orbit_from_steady_of(
        dynamics.as_ref(),
        &params,
        &steady,
        &NewtonOptions::default(),
    )?;
    Ok((params, orbit))
}
