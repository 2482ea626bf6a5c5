//! Where a branch of a smooth friction law (Stribeck, cubic) meets a switch of the law: a
//! slide that comes down to the belt's speed mid-swing (a stop appears or vanishes there), and
//! a turning point whose net force reaches the static limit (it becomes a stop). Both laws
//! start from the static level, μ(0) = μs, so the stop appears with zero length and the strobe
//! map stays continuous: `continue` passes the point as a grazing special point (the event
//! counts change, the branch goes on), and the obstacle search on the model's own solver
//! (`obstacle_of`) names it on the orbits beside it.
//!
//! The independent check: the orbits on the near side (Newton's method at two values of the
//! parameter) run on the friction solver's explicit integrator (Dormand–Prince 8(5,3), not the
//! Radau IIA steps the branch and the obstacle search use), from which the quantity that
//! vanishes at the border (the slide's lowest |y' − vb|, or the turning point's |f| − μs) is
//! measured on its dense output and extrapolated linearly to zero. Both are smooth in the
//! parameter with a nonzero slope there, so the secant through points 1e-4 and 2e-4 away
//! misses the zero by about |q''|·(1e-4)²/|q'| (some 1e-8 for slopes and curvatures of
//! order 1), and the special point is located to 7.5e-10 of arclength: they must agree to
//! 1e-6.

use stickslip::cancel::Cancel;
use stickslip::continuation::{
    continue_orbit_of, obstacle_of, settled_orbit, Branch, BranchEnd, ContinuationOptions,
    Obstacle, SpecialKind, SpecialPoint,
};
use stickslip::friction::FrictionLaw;
use stickslip::friction_solver::{FrictionSolver, SlipIntegrator};
use stickslip::stability::{FrictionDynamics, NewtonOptions, PeriodicOrbit};
use stickslip::{EventKind, Experiment, Parameter, Params, Phase, Solver, State};

const STRIBECK: FrictionLaw = FrictionLaw::Stribeck {
    vs: 0.3,
    delta: 2.0,
    eta: 0.05,
};
const CUBIC: FrictionLaw = FrictionLaw::Cubic { k1: 0.5, k3: 0.5 };

/// A forced belt: (ζ, w, β, μs, vb) and the law.
fn belt(law: FrictionLaw, (zeta, w, beta, mu_s, vb): (f64, f64, f64, f64, f64)) -> Experiment {
    Experiment::dimensionless(zeta, w, beta)
        .and_then(|e| e.with_mu_s(mu_s))
        .and_then(|e| e.with_vb(vb))
        .and_then(|e| e.with_law(law))
        .unwrap()
}

/// The branch from the orbit `experiment` settles on, over `parameter` to `to`.
fn branch(experiment: &Experiment, parameter: Parameter, to: f64) -> (Params, Branch) {
    let (params, orbit) = settled_orbit(experiment).unwrap();
    let options = ContinuationOptions::default().with_max_step(0.05);
    let branch = continue_orbit_of(
        &FrictionDynamics::new(),
        &params,
        parameter,
        &orbit,
        to,
        &options,
        &(),
    )
    .unwrap();
    (params, branch)
}

/// The grazing special point of `branch` whose (turns, stops) go from `before` to `after`.
fn grazing(branch: &Branch, before: (usize, usize), after: (usize, usize)) -> SpecialPoint {
    for s in &branch.special {
        println!(
            "  {:?} at {:.10} (±{:.1e}): ({}, {}) -> ({}, {})",
            s.kind, s.value, s.width, s.before.turns, s.before.stops, s.after.turns, s.after.stops
        );
    }
    branch
        .special
        .iter()
        .find(|s| {
            s.kind == SpecialKind::Grazing
                && (s.before.turns, s.before.stops) == before
                && (s.after.turns, s.after.stops) == after
        })
        .unwrap_or_else(|| panic!("no grazing {before:?} -> {after:?}: {:?}", branch.special))
        .clone()
}

/// Newton's orbit at `value` of `parameter` from `guess`.
fn orbit_at(
    params: &Params,
    parameter: Parameter,
    value: f64,
    guess: State,
) -> (Params, PeriodicOrbit) {
    let p = parameter.set(*params, value).unwrap();
    let orbit = FrictionDynamics::new()
        .find_periodic_orbit(&p, guess, 1, &NewtonOptions::default())
        .unwrap();
    (p, orbit)
}

/// The orbit's period on the explicit integrator from its strobe state: for each slip step,
/// 64 samples of σ y'' (y'' = F − y − 2ζ y' − σ μ(|y' − vb|)); the lowest |y' − vb| where it
/// turns from negative to positive (by bisection on the dense output), and the net force
/// f = F − y − 2ζ vb at every turning point.
fn explicit_run(params: &Params, orbit: &PeriodicOrbit) -> (Option<f64>, Vec<f64>) {
    let mut solver = FrictionSolver::with_integrator(
        *params,
        orbit.state,
        SlipIntegrator::Explicit,
        Cancel::never(),
    )
    .unwrap();
    let end = params.drive_period();
    let accel = |x: &stickslip::Sample, sign: f64| {
        let s = (x.v - params.vb).abs();
        sign * (params.drive(x.tau)
            - x.y
            - 2.0 * params.zeta * x.v
            - sign * params.law.value(params.mu_s, s))
    };
    let mut lowest: Option<f64> = None;
    let mut turns = Vec::new();
    while solver.time() < end {
        let phase = solver.phase();
        if let Some(e) = solver.advance(end).unwrap() {
            if e.kind == EventKind::Turn {
                turns.push(params.net_force(e.tau, e.y));
            }
        }
        let (a, b) = solver.interval();
        if phase == Phase::Stick || !(b > a) {
            continue;
        }
        let sign = phase.sign();
        let n = 64;
        for k in 0..n {
            let (t0, t1) = (
                a + (b - a) * k as f64 / n as f64,
                a + (b - a) * (k + 1) as f64 / n as f64,
            );
            if !(accel(&solver.dense(t0), sign) < 0.0 && accel(&solver.dense(t1), sign) >= 0.0) {
                continue;
            }
            let (mut lo, mut hi) = (t0, t1);
            for _ in 0..80 {
                let mid = 0.5 * (lo + hi);
                if accel(&solver.dense(mid), sign) < 0.0 {
                    lo = mid;
                } else {
                    hi = mid;
                }
            }
            let s = (solver.dense(0.5 * (lo + hi)).v - params.vb).abs();
            lowest = Some(lowest.map_or(s, |l: f64| l.min(s)));
        }
    }
    (lowest, turns)
}

/// Where `quantity` (of the explicit run of Newton's orbit) reaches zero, by the secant
/// through the orbits 1e-4 and 2e-4 from `at` on the side `side` (±1), from `guess`.
fn extrapolated_zero(
    params: &Params,
    parameter: Parameter,
    at: f64,
    side: f64,
    guess: State,
    quantity: &dyn Fn(&Params, &PeriodicOrbit) -> f64,
) -> f64 {
    let scale = at.abs().max(0.1);
    let (l1, l2) = (at + side * 1e-4 * scale, at + side * 2e-4 * scale);
    let (p1, o1) = orbit_at(params, parameter, l1, guess);
    let (p2, o2) = orbit_at(params, parameter, l2, o1.state);
    let (q1, q2) = (quantity(&p1, &o1), quantity(&p2, &o2));
    println!(
        "  {} = {l1:.8}: {q1:.6e}; {l2:.8}: {q2:.6e}",
        parameter.label()
    );
    l1 - q1 * (l2 - l1) / (q2 - q1)
}

/// The largest |f| − μs, f = F − y − 2ζ vb, during the stops of the explicit run of the orbit
/// (its largest maximum inside a stop, from 256 samples of each stop refined by golden
/// sections: f is smooth while stuck).
fn stop_force_margin(params: &Params, orbit: &PeriodicOrbit) -> f64 {
    let mut solver = FrictionSolver::with_integrator(
        *params,
        orbit.state,
        SlipIntegrator::Explicit,
        Cancel::never(),
    )
    .unwrap();
    let end = params.drive_period();
    let mut best = f64::NEG_INFINITY;
    while solver.time() < end {
        let phase = solver.phase();
        solver.advance(end).unwrap();
        let (a, b) = solver.interval();
        if phase != Phase::Stick || !(b > a) {
            continue;
        }
        let force = |t: f64| {
            let x = solver.dense(t);
            params.net_force(t, x.y).abs()
        };
        let n: usize = 256;
        let h = (b - a) / n as f64;
        // The largest interior maximum (a stop ends at the limit, |f| = μs, at its release).
        let values: Vec<f64> = (0..=n).map(|i| force(a + i as f64 * h)).collect();
        let Some(k) = (1..n)
            .filter(|&i| values[i] >= values[i - 1] && values[i] >= values[i + 1])
            .max_by(|&i, &j| values[i].total_cmp(&values[j]))
        else {
            continue;
        };
        let (mut lo, mut hi) = (a + (k - 1) as f64 * h, a + (k + 1) as f64 * h);
        let g = 0.5 * (5f64.sqrt() - 1.0);
        for _ in 0..80 {
            let (c, d) = (hi - g * (hi - lo), lo + g * (hi - lo));
            if force(c) > force(d) {
                hi = d;
            } else {
                lo = c;
            }
        }
        best = best.max(force(0.5 * (lo + hi)) - params.mu_s);
    }
    best
}

/// (a) A stop mid-swing that splits in two: on one side of the grazing point the net force
/// during a long stop comes up to the static limit and falls back (|f| − μs < 0 at its
/// largest); on the other it passes the limit for a moment, and the block slips briefly and
/// sticks again (a stop more, no turn). The point lies where the largest |f| − μs during the
/// stop, extrapolated, vanishes; on the side with the short slip the obstacle search names
/// its stop reached almost tangentially (the short slip's speed never leaves the belt's by
/// much). The branch goes on past it: the strobe states on either side agree.
#[test]
fn a_stop_that_splits_mid_swing_is_a_grazing_point_where_the_force_touches_the_limit() {
    // (law, belt, parameter, from, to, counts with one stop, with the short slip)
    let cases = [
        (
            CUBIC,
            (0.05, 1.0, 2.0, 1.5, 0.5),
            Parameter::Beta,
            2.0,
            1.9,
            (0, 1),
            (0, 2),
        ),
        (
            STRIBECK,
            (0.05, 1.0, 2.0, 1.5, 0.5),
            Parameter::Beta,
            1.42,
            1.39,
            (0, 1),
            (0, 2),
        ),
    ];
    for (law, model, parameter, from, to, whole, split) in cases {
        let e = belt(law, model).with_parameter(parameter, from).unwrap();
        let (params, b) = branch(&e, parameter, to);
        println!("{law:?} over {}: end {:?}", parameter.label(), b.end);
        assert!(matches!(b.end, BranchEnd::Boundary { .. }), "{:?}", b.end);
        // Either order along the branch.
        let point = if b
            .special
            .iter()
            .any(|s| (s.before.turns, s.before.stops) == split)
        {
            grazing(&b, split, whole)
        } else {
            grazing(&b, whole, split)
        };
        let (one, two) = if (point.before.turns, point.before.stops) == whole {
            (&point.before, &point.after)
        } else {
            (&point.after, &point.before)
        };
        // Continuous: the strobe states on either side of the bracket agree.
        let jump = (one.state.y - two.state.y).hypot(one.state.v - two.state.v);
        assert!(
            jump <= 2.0 * point.width.max(1e-9),
            "{jump} across {}",
            point.width
        );
        let side = (one.value - two.value).signum();
        let zero = extrapolated_zero(
            &params,
            parameter,
            point.value,
            side,
            one.state,
            &stop_force_margin,
        );
        println!(
            "  grazing at {:.10}, the stop's force margin extrapolated to zero at {zero:.10}",
            point.value
        );
        assert!(
            (zero - point.value).abs() <= 1e-6,
            "{zero} against {}",
            point.value
        );
        let scale = point.value.abs().max(0.1);
        let (p, o) = orbit_at(
            &params,
            parameter,
            point.value - side * 1e-4 * scale,
            two.state,
        );
        let obstacle = obstacle_of(&FrictionDynamics::new(), &p, &o).unwrap();
        println!("  past it: {obstacle:?}; {obstacle}");
        assert!(
            matches!(obstacle, Obstacle::TangentialStick { acceleration, continuous: true, .. } if acceleration < 1e-2),
            "{law:?}: {obstacle:?}"
        );
        assert!(
            obstacle.to_string().contains("stays continuous"),
            "{obstacle}"
        );
    }
}

/// (b) A turning point whose net force reaches the static limit: on one side of the grazing
/// point the slip reverses there (|f| > μs at the turn), on the other it stops (a turn fewer,
/// a stop more). The point lies where |f| − μs at the turn, extrapolated, vanishes; the
/// obstacle search names the turning point at the static limit.
#[test]
fn a_turning_point_at_the_static_limit_is_a_grazing_point_where_its_margin_vanishes() {
    let cases = [
        (
            STRIBECK,
            (0.05, 1.0, 2.0, 1.5, 0.5),
            Parameter::Beta,
            2.0,
            1.5,
            (2, 0),
            (1, 1),
        ),
        (
            CUBIC,
            (0.05, 1.0, 2.0, 1.5, 0.5),
            Parameter::Beta,
            3.5,
            3.37,
            (2, 0),
            (1, 1),
        ),
    ];
    for (law, model, parameter, from, to, turning, stuck) in cases {
        let e = belt(law, model).with_parameter(parameter, from).unwrap();
        let (params, b) = branch(&e, parameter, to);
        println!("{law:?} over {}: end {:?}", parameter.label(), b.end);
        assert!(matches!(b.end, BranchEnd::Boundary { .. }), "{:?}", b.end);
        // Either order along the branch.
        let point = if b
            .special
            .iter()
            .any(|s| (s.before.turns, s.before.stops) == stuck)
        {
            grazing(&b, stuck, turning)
        } else {
            grazing(&b, turning, stuck)
        };
        let (turns, held) = if (point.before.turns, point.before.stops) == turning {
            (&point.before, &point.after)
        } else {
            (&point.after, &point.before)
        };
        let jump = (turns.state.y - held.state.y).hypot(turns.state.v - held.state.v);
        assert!(
            jump <= 2.0 * point.width.max(1e-9),
            "{jump} across {}",
            point.width
        );
        let side = (turns.value - held.value).signum();
        // The turn closest to the limit on the explicit run.
        let margin = |p: &Params, o: &PeriodicOrbit| {
            explicit_run(p, o)
                .1
                .iter()
                .map(|f| f.abs() - p.mu_s)
                .min_by(|a, b| a.abs().total_cmp(&b.abs()))
                .expect("a turning point")
        };
        let zero = extrapolated_zero(&params, parameter, point.value, side, turns.state, &margin);
        println!(
            "  grazing at {:.10}, turn margin extrapolated to zero at {zero:.10}",
            point.value
        );
        assert!(
            (zero - point.value).abs() <= 1e-6,
            "{zero} against {}",
            point.value
        );
        let scale = point.value.abs().max(0.1);
        let (p, o) = orbit_at(
            &params,
            parameter,
            point.value + side * 1e-4 * scale,
            turns.state,
        );
        let obstacle = obstacle_of(&FrictionDynamics::new(), &p, &o).unwrap();
        let explicit = margin(&p, &o) / p.mu_s;
        println!("  {obstacle:?} (explicit margin {explicit:.6e})");
        assert!(
            matches!(obstacle, Obstacle::TurnAtStaticLimit { margin, .. } if margin > 0.0 && (margin - explicit).abs() <= 1e-8),
            "{law:?}: {obstacle:?}, explicit {explicit}"
        );
        // Past it the stop begins inside the limit opposite to its slip.
        let (p, o) = orbit_at(
            &params,
            parameter,
            point.value - side * 1e-4 * scale,
            held.state,
        );
        let obstacle = obstacle_of(&FrictionDynamics::new(), &p, &o).unwrap();
        println!("  past it: {obstacle:?}");
        assert!(
            matches!(obstacle, Obstacle::TurnAtStaticLimit { margin, .. } if (-1e-2..0.0).contains(&margin)),
            "{law:?}: {obstacle:?}"
        );
    }
}
