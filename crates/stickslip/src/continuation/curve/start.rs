//! Where a curve starts: the first special point of the followed kind on the branch of the
//! orbit the motion settles on, continued in P; that point corrected onto the extended
//! system at the model's value of Q.

use super::border::{candidates, nearest, Candidate};
use super::system::{Plane, System};
use super::trace::follow_curve_within_of;
use super::{Border, BorderKind, Curve, Follow};
use crate::continuation::corrector::counts;
use crate::continuation::{
    continue_orbit_of, settled_orbit, Branch, BranchEnd, ContinuationOptions, Obstacle,
};
use crate::error::{Error, Result};
use crate::experiment::Experiment;
use crate::options::{Allowed, OptionKey};
use crate::params::{Parameter, Params, State};
use crate::scan::Monitor;
use crate::stability::{Dynamics, ExactDynamics, NewtonOptions, PeriodicOrbit};
use serde::{Deserialize, Serialize};
use std::sync::Arc;

/// The start point of a curve: an orbit at the followed special point, at the model's value
/// of Q. Found by [`find_start`].
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct CurveStart {
    /// What the curve follows.
    pub follow: Follow,
    /// For a grazing: the event that appears and the side the orbits are taken on.
    pub border: Option<Border>,
    /// The parameter the curve is followed over (Q).
    pub over: Parameter,
    /// The parameter that follows it (P).
    pub vary: Parameter,
    /// The parameters at the start point.
    pub params: Params,
    /// Period p of the orbit in drive periods.
    pub period: usize,
    /// The orbit at the start point.
    pub orbit: PeriodicOrbit,
    /// Time of the followed event from the strobe (grazing; NaN otherwise).
    pub tau: f64,
    /// The branch of one parameter (P) on which the special point was found.
    pub branch: Branch,
}

/// Why no curve starts: no special point of the followed kind on the branch searched, or
/// none that the extended system takes.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct NoStart {
    /// What was looked for.
    pub follow: Follow,
    /// The parameter continued in the search (P).
    pub vary: Parameter,
    /// Where the search started.
    pub from: f64,
    /// Where it was heading.
    pub to: f64,
    /// The range of P the branch covered.
    pub reached: (f64, f64),
    /// How the branch ended.
    pub end: BranchEnd,
    /// A special point of the kind that was found but could not be corrected onto the
    /// extended system (its value of P), if any.
    pub not_corrected: Option<f64>,
}

impl std::fmt::Display for NoStart {
    /// One line: "no fold on the branch continued in beta from 1.45 towards 1.25 (it covers
    /// beta from 1.3 to 1.45 and ends: ...)".
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let name = self.vary.label();
        match self.not_corrected {
            Some(value) => write!(
                f,
                "the {} at {name} = {value} on the branch continued in {name} from {} towards \
                 {} could not be corrected onto its defining system",
                self.follow.words(),
                self.from,
                self.to
            ),
            None => write!(
                f,
                "no {} on the branch of the orbit settled on, continued in {name} from {} \
                 towards {} (it covers {name} from {} to {} and ends: {})",
                self.follow.words(),
                self.from,
                self.to,
                self.reached.0,
                self.reached.1,
                self.end
            ),
        }
    }
}

/// Whether a curve of the kind `follow` can be followed on the model `dynamics` with the
/// friction law `law`:
/// the exact Coulomb model has no Neimark–Sacker point (det M < 1 on every orbit that
/// reverses or sticks; docs/bifurcation.md); a smooth friction law's grazings are not
/// followed (their conditions are events of the exact solver).
///
/// # Errors
/// [`crate::Unsupported::NoNeimarkSacker`] for [`Follow::NeimarkSacker`] with the exact
/// model; [`crate::Unsupported::GrazingCurveNeedsCoulomb`] for [`Follow::Grazing`] with a
/// smooth law.
fn possible(
    dynamics: &dyn Dynamics,
    law: crate::friction::FrictionLawKind,
    follow: Follow,
) -> Result<()> {
    match follow {
        Follow::NeimarkSacker if dynamics.is_exact() => {
            Err(Error::Unsupported(crate::Unsupported::NoNeimarkSacker))
        }
        Follow::Grazing if !dynamics.is_exact() => Err(Error::Unsupported(
            crate::Unsupported::GrazingCurveNeedsCoulomb { law: law.label() },
        )),
        _ => Ok(()),
    }
}

/// The orbit at `value` of `vary` near `state`, by Newton's method.
fn orbit_at(
    dynamics: &dyn Dynamics,
    params: &Params,
    vary: Parameter,
    value: f64,
    state: State,
    period: usize,
    options: &ContinuationOptions,
) -> Result<Option<PeriodicOrbit>> {
    let params = vary.set(*params, value)?;
    match dynamics.find_periodic_orbit(
        &params,
        state,
        period,
        &NewtonOptions {
            tolerance: dynamics.map_tolerance(options.tolerance),
            ..NewtonOptions::default()
        },
    ) {
        Ok(o) => Ok(Some(o)),
        Err(Error::Stability(_)) => Ok(None),
        Err(e) => Err(e),
    }
}

/// The followed conditions of a grazing located between the orbits `sides` (each with its
/// value of P, the one the branch came from first): the condition that changes between the
/// two (the same event of the other variant, or none, across), nearest zero, as it is on each
/// side where it is there: the side the branch came from first.
fn grazing_borders(
    params: &Params,
    vary: Parameter,
    sides: &[(f64, PeriodicOrbit)],
) -> Result<Vec<(Border, usize, Candidate)>> {
    let mut lists = Vec::new();
    for (value, orbit) in sides {
        let p = vary.set(*params, *value)?;
        let span = orbit.period as f64 * p.drive_period();
        lists.push((candidates(&p, orbit.state, orbit.period)?, span));
    }
    let Some((list, span)) = lists.first() else {
        return Ok(Vec::new());
    };
    // The events that change across (of the first side's).
    let changes = |c: &Candidate| match lists.get(1) {
        Some((other, _)) => nearest(other, c.kind, None, c.tau, *span)
            .is_none_or(|o| o.variant != c.variant || o.value * c.value < 0.0),
        None => true,
    };
    let by_value = |a: &&Candidate, b: &&Candidate| a.value.abs().total_cmp(&b.value.abs());
    let Some(best) = list
        .iter()
        .filter(|c| changes(c))
        .min_by(by_value)
        .or_else(|| list.iter().min_by(by_value))
    else {
        return Ok(Vec::new());
    };
    let mut out = Vec::new();
    for (i, (list, span)) in lists.iter().enumerate() {
        if let Some(c) = nearest(list, best.kind, None, best.tau, *span) {
            let sign = if c.value > 0.0 {
                1.0
            } else if c.value < 0.0 {
                -1.0
            } else if c.variant == (c.kind != BorderKind::SlideTouchesRest) {
                1.0
            } else {
                -1.0
            };
            out.push((
                Border {
                    kind: c.kind,
                    variant: c.variant,
                    sign,
                    continuous: true,
                },
                i,
                c,
            ));
        }
    }
    Ok(out)
}

/// The grazing condition at the end of a branch that stops against a jump of the strobe map
/// (a stop of finite length appearing at a turning point or mid-swing, or a release becoming
/// tangential): the condition of that obstacle on the last orbit.
fn end_border(branch: &Branch) -> Result<Option<(Border, f64, PeriodicOrbit, Candidate)>> {
    let obstacle = match &branch.end {
        BranchEnd::Grazing { slide, .. } => Obstacle::Grazing(*slide),
        BranchEnd::Stalled { obstacle, .. } | BranchEnd::Failed { obstacle, .. } => *obstacle,
        _ => return Ok(None),
    };
    let (kind, variant, tau, sign) = match obstacle {
        Obstacle::TurnAtStaticLimit { tau, .. } => (BorderKind::TurnAtLimit, true, tau, 1.0),
        Obstacle::Grazing(slide) => (BorderKind::SlideTouchesRest, false, slide.tau, 1.0),
        Obstacle::TangentialRelease { tau, .. } => (BorderKind::ReleaseTangential, false, tau, 1.0),
        // On a belt, the stop side of a slide touching rest: the slide continued past the
        // stop as if it went on, whose lowest slip (below zero) rises to zero there.
        Obstacle::TangentialStick { tau, .. } => (BorderKind::SlideTouchesRest, true, tau, -1.0),
        Obstacle::None => return Ok(None),
    };
    let Some(last) = branch.points.last() else {
        return Ok(None);
    };
    let params = branch.parameter.set(branch.params, last.value)?;
    let list = candidates(&params, last.orbit.state, last.orbit.period)?;
    let span = last.orbit.period as f64 * params.drive_period();
    Ok(nearest(&list, kind, Some(variant), tau, span).map(|c| {
        (
            Border {
                kind,
                variant,
                sign,
                continuous: false,
            },
            last.value,
            last.orbit.clone(),
            c,
        )
    }))
}

/// The start of a curve of `follow` over `over` on the exact Coulomb model: the orbit `orbit`
/// at `params` continued in `vary` towards `vary_to` ([`continue_orbit`]) until its first special point of the
/// followed kind (for a grazing, also the end of the branch at a jump of the strobe map:
/// a turning point reaching the static limit, a slide touching rest, a release becoming
/// tangential), corrected onto the extended system at the value of `over` in `params`.
///
/// # Errors
/// [`Error::InvalidOption`] naming [`OptionKey::TwoParameterVary`] when `over` and `vary`
/// are the same parameter (as [`check_spec`]); [`crate::Unsupported::NoNeimarkSacker`] for a Neimark–Sacker point, which the model cannot
/// have; as [`continue_orbit`]; `Ok(Err(NoStart))` when the branch has no such point.
///
/// [`continue_orbit`]: crate::continuation::continue_orbit
pub fn find_start(
    params: &Params,
    orbit: &PeriodicOrbit,
    follow: Follow,
    (vary, vary_to): (Parameter, f64),
    over: Parameter,
    options: &ContinuationOptions,
    monitor: &dyn Monitor,
) -> Result<std::result::Result<CurveStart, NoStart>> {
    find_start_of(
        Arc::new(ExactDynamics),
        params,
        orbit,
        follow,
        (vary, vary_to),
        over,
        options,
        monitor,
    )
}

/// [`find_start`] on the model `dynamics` (`orbit` an orbit of it): the branch is continued
/// on it ([`continue_orbit_of`]) and its special point corrected onto the extended system of
/// its strobe map. A smooth friction law ([`crate::stability::FrictionDynamics`]) takes
/// folds, period doublings and Neimark–Sacker points, over and in any of its parameters
/// (the belt's speed vb and the law's own too); the exact model the paper's four and vb.
///
/// # Errors
/// As [`find_start`]; [`crate::Unsupported::GrazingCurveNeedsCoulomb`] for a grazing with a
/// smooth law.
#[allow(clippy::too_many_arguments)]
pub fn find_start_of(
    dynamics: Arc<dyn Dynamics>,
    params: &Params,
    orbit: &PeriodicOrbit,
    follow: Follow,
    (vary, vary_to): (Parameter, f64),
    over: Parameter,
    options: &ContinuationOptions,
    monitor: &dyn Monitor,
) -> Result<std::result::Result<CurveStart, NoStart>> {
    if over == vary {
        return Err(Error::InvalidOption {
            option: OptionKey::TwoParameterVary,
            value: f64::NAN,
            allowed: Allowed::Differs {
                other: OptionKey::TwoParameterOver,
            },
        });
    }
    super::system::check_parameter(dynamics.as_ref(), params, over)?;
    super::system::check_parameter(dynamics.as_ref(), params, vary)?;
    possible(dynamics.as_ref(), params.law.kind(), follow)?;
    let options = options.validate()?;
    let branch = continue_orbit_of(
        dynamics.as_ref(),
        params,
        vary,
        orbit,
        vary_to,
        &options,
        monitor,
    )?;
    let from = vary.get(params);
    let values = branch.points.iter().map(|p| p.value);
    let reached = values.fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), v| {
        (a.min(v), b.max(v))
    });
    let no_start = |not_corrected| NoStart {
        follow,
        vary,
        from,
        to: vary_to,
        reached,
        end: branch.end.clone(),
        not_corrected,
    };
    let period = branch.period;
    let special = branch
        .special
        .iter()
        .find(|s| s.kind == follow.special_kind());
    // The points to correct, in order of preference: P's value, the state, the followed
    // event's time, the condition.
    let tries: Vec<(f64, State, f64, Option<Border>)> = match (follow, special) {
        (Follow::Grazing, Some(s)) => {
            let mut sides = Vec::new();
            for side in [&s.before, &s.after] {
                if let Some(o) = orbit_at(
                    dynamics.as_ref(),
                    params,
                    vary,
                    side.value,
                    side.state,
                    period,
                    &options,
                )? {
                    sides.push((side.value, o));
                }
            }
            grazing_borders(params, vary, &sides)?
                .into_iter()
                .map(|(border, i, c)| (sides[i].0, sides[i].1.state, c.tau, Some(border)))
                .collect()
        }
        (Follow::Grazing, None) => match end_border(&branch)? {
            Some((border, value, orbit, c)) => vec![(value, orbit.state, c.tau, Some(border))],
            None => return Ok(Err(no_start(None))),
        },
        (_, Some(s)) => vec![(s.value, s.state, f64::NAN, None)],
        (_, None) => return Ok(Err(no_start(None))),
    };
    let not_corrected = tries.first().map(|t| t.0);
    let mut found = None;
    for (value, state, tau, border) in tries {
        let base = vary.set(branch.params, value)?;
        let model = System {
            base,
            over,
            vary,
            period,
            follow,
            border,
            options,
            phase: 0.0,
            dynamics: dynamics.clone(),
        };
        let a0 = over.get(&base);
        // In a chart whose section lies in the middle of a slide (see `System::section`).
        let Some(orbit) = orbit_at(
            dynamics.as_ref(),
            &base,
            vary,
            value,
            state,
            period,
            &options,
        )?
        else {
            continue;
        };
        let (system, x, tau) = model.recharted(&base, &orbit, tau)?;
        let u = [x.y, x.v, a0, value];
        let node = system.correct(
            &u,
            tau,
            &Plane::Fixed {
                index: 2,
                value: a0,
            },
            &[0.0, 0.0, 1.0, 0.0],
        )?;
        // The orbit of the special point itself, not another one nearby.
        if let Some(node) = node.filter(|n| n.counts == counts(&orbit)) {
            found = Some((system, node, border));
            break;
        }
    }
    let Some((system, node, border)) = found else {
        return Ok(Err(no_start(not_corrected)));
    };
    // Back at the model's strobe.
    let params = system.model_params(&node.u)?;
    let span = period as f64 * params.drive_period();
    let forward = system.phase / params.w;
    let orbit = system.model_orbit(&node)?;
    Ok(Ok(CurveStart {
        follow,
        border,
        over,
        vary,
        params,
        period,
        orbit,
        tau: (node.tau + forward).rem_euclid(span),
        branch,
    }))
}

/// What a curve is asked for: the followed kind, the search for its start in P, and Q's
/// range.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct CurveSpec {
    /// What to follow.
    pub follow: Follow,
    /// The parameter continued to find the start (P), which then follows the curve.
    pub vary: Parameter,
    /// The value of P the search heads for.
    pub vary_to: f64,
    /// The parameter the curve is followed over (Q).
    pub over: Parameter,
    /// One end of Q's range (the start value, when the model has no value of Q).
    pub from: f64,
    /// The end of Q's range the curve heads for.
    pub to: f64,
}

/// Check `spec` before any work: the ends of Q's range finite and apart, P's target finite,
/// and P and Q two parameters.
///
/// # Errors
/// [`Error::InvalidOption`] naming [`OptionKey::TwoParameterFrom`],
/// [`OptionKey::TwoParameterTo`] or [`OptionKey::TwoParameterVaryTo`], or
/// [`OptionKey::TwoParameterVary`] when P is Q ([`Allowed::Differs`] from
/// [`OptionKey::TwoParameterOver`]: each front end names the two its own way, `invalid
/// --vary: must differ from --over` on the command line).
pub fn check_spec(spec: &CurveSpec) -> Result<()> {
    OptionKey::TwoParameterFrom.check(spec.from)?;
    OptionKey::TwoParameterTo.check(spec.to)?;
    OptionKey::TwoParameterVaryTo.check(spec.vary_to)?;
    if spec.to == spec.from {
        return Err(Error::InvalidOption {
            option: OptionKey::TwoParameterTo,
            value: spec.to,
            allowed: Allowed::Differs {
                other: OptionKey::TwoParameterFrom,
            },
        });
    }
    if spec.vary == spec.over {
        return Err(Error::InvalidOption {
            option: OptionKey::TwoParameterVary,
            value: f64::NAN,
            allowed: Allowed::Differs {
                other: OptionKey::TwoParameterOver,
            },
        });
    }
    Ok(())
}

/// The curve of `spec` from the orbit the motion of `experiment` settles on (its value of Q
/// must lie between `from` and `to`): [`settled_orbit`], [`find_start_of`],
/// [`super::follow_curve_of`] on the experiment's model ([`Experiment::dynamics`]: the exact
/// Coulomb model, or a Stribeck or cubic law's [`crate::stability::FrictionDynamics`]).
/// `monitor` sees the search's points, then each way's.
///
/// # Errors
/// [`Error::InvalidParameter`] for bad ends or parameters, or a motion that comes to rest;
/// [`crate::Unsupported::CurveNeedsPwl`] with Shockley diodes;
/// [`crate::Unsupported::NoNeimarkSacker`] for a Neimark–Sacker point with Coulomb's law,
/// which cannot have one, and [`crate::Unsupported::GrazingCurveNeedsCoulomb`] for a grazing
/// with a smooth law (both before any work); as [`settled_orbit`], [`find_start`] and [`super::follow_curve`];
/// `Ok(Err(NoStart))` when the branch has no special point of the kind.
pub fn curve(
    experiment: &Experiment,
    spec: &CurveSpec,
    options: &ContinuationOptions,
    monitor: &dyn Monitor,
) -> Result<std::result::Result<Curve, NoStart>> {
    curve_within(experiment, spec, None, options, monitor)
}

/// [`curve`] with P kept within `vary_range` along the curve when given (the search for the
/// start is not bounded by it): see [`super::follow_curve_within`].
///
/// # Errors
/// As [`curve`] and [`super::follow_curve_within`].
pub fn curve_within(
    experiment: &Experiment,
    spec: &CurveSpec,
    vary_range: Option<(f64, f64)>,
    options: &ContinuationOptions,
    monitor: &dyn Monitor,
) -> Result<std::result::Result<Curve, NoStart>> {
    check_spec(spec)?;
    if experiment.diode_model() != crate::experiment::DiodeModel::Pwl {
        return Err(Error::Unsupported(crate::Unsupported::CurveNeedsPwl));
    }
    let dynamics: Arc<dyn Dynamics> = Arc::from(experiment.dynamics()?);
    possible(
        dynamics.as_ref(),
        experiment.friction_law().kind(),
        spec.follow,
    )?;
    let options = options.validate()?;
    let (params, orbit) = settled_orbit(experiment)?;
    let rest = if dynamics.is_exact() {
        orbit.events.is_empty()
    } else {
        orbit.is_rest()
    };
    if rest {
        return Err(Error::InvalidParameter {
            name: "y0",
            value: experiment.initial().y,
            allowed: "the motion comes to rest from this initial state: nothing to follow; \
                      start from a moving state (y0, v0)",
        });
    }
    spec.vary.set(params, spec.vary_to)?;
    if spec.vary.get(&params) == spec.vary_to {
        return Err(Error::InvalidOption {
            option: OptionKey::TwoParameterVaryTo,
            value: spec.vary_to,
            allowed: Allowed::Table,
        });
    }
    let a0 = spec.over.get(&params);
    let (lo, hi) = (spec.from.min(spec.to), spec.from.max(spec.to));
    if !(lo <= a0 && a0 <= hi) {
        return Err(Error::InvalidParameter {
            name: spec.over.label(),
            value: a0,
            allowed: "the model's value of the parameter the curve is followed over must lie \
                      between from and to",
        });
    }
    let start = match find_start_of(
        dynamics.clone(),
        &params,
        &orbit,
        spec.follow,
        (spec.vary, spec.vary_to),
        spec.over,
        &options,
        monitor,
    )? {
        Ok(start) => start,
        Err(no) => return Ok(Err(no)),
    };
    Ok(Ok(follow_curve_within_of(
        dynamics,
        &start,
        (spec.from, spec.to),
        vary_range,
        &options,
        monitor,
    )?))
}
