//! Continuation of periodic orbits of the smooth friction laws (Stribeck, cubic) on a forced
//! belt (`continue`, [`FrictionDynamics`]'s strobe map with its parameter derivatives): the
//! branch passes through the steady states that `steady` settles on independently at its
//! points (the strobe to 1e-6, the same stops), and a falling Stribeck law's sliding orbit
//! loses stability through a Neimark–Sacker point (a complex pair through the unit circle,
//! which the Coulomb belt never shows), located where the orbits on either side have |μ| < 1
//! and > 1.

use stickslip::continuation::{
    continue_orbit_of, settled_orbit, Branch, BranchEnd, ContinuationOptions, SpecialKind,
};
use stickslip::friction::FrictionLaw;
use stickslip::scan::{Axis, ParameterRange, Sweep, SweepDirection, SweepLeg, SweepPoint};
use stickslip::solver::run_until;
use stickslip::stability::{FrictionDynamics, NewtonOptions, Stability};
use stickslip::{Experiment, Parameter, Solver, State};

use stickslip_testkit::belts::{belt, CUBIC, STRIBECK};

/// The branch from the orbit `experiment` settles on, over `parameter` to `to`.
fn branch(experiment: &Experiment, parameter: Parameter, to: f64, max_step: f64) -> Branch {
    let (params, orbit) = settled_orbit(experiment).unwrap();
    let options = ContinuationOptions::default().with_max_step(max_step);
    continue_orbit_of(
        &FrictionDynamics::new(),
        &params,
        parameter,
        &orbit,
        to,
        &options,
        &(),
    )
    .unwrap()
}

/// Every stable point of the branch (at most `count`, spread along it) against `steady` at
/// its parameter value: the strobe to 1e-6 and the same stops. Returns how many matched.
fn check_against_steady(experiment: &Experiment, branch: &Branch, parameter: Parameter) -> usize {
    let stable: Vec<_> = branch
        .points
        .iter()
        .filter(|p| p.orbit.multipliers[0].modulus() < 0.99)
        .collect();
    let stride = (stable.len() / 10).max(1);
    let mut matched = 0;
    for p in stable.iter().step_by(stride) {
        let e = experiment
            .clone()
            .with_parameter(parameter, p.value)
            .unwrap();
        let steady = e.steady().unwrap();
        assert_eq!(
            steady.period,
            Some(1),
            "{} = {}",
            parameter.label(),
            p.value
        );
        let s = steady.strobes[0];
        let x = p.orbit.state;
        println!(
            "{} = {:.6}: branch ({:.9}, {:.9}), steady ({:.9}, {:.9}), stops {} / {}, |mu| {:.4}",
            parameter.label(),
            p.value,
            x.y,
            x.v,
            s.y,
            s.v,
            p.stops,
            steady.stops_per_period,
            p.orbit.multipliers[0].modulus()
        );
        assert!(
            (x.y - s.y).abs() <= 1e-6 && (x.v - s.v).abs() <= 1e-6,
            "{} = {}: branch {x:?}, steady {s:?}",
            parameter.label(),
            p.value
        );
        assert_eq!(p.stops as f64, steady.stops_per_period);
        matched += 1;
    }
    matched
}

#[test]
fn branches_over_w_and_beta_pass_through_the_steady_states() {
    let cases = [
        (STRIBECK, (0.05, 1.0, 2.0, 1.5, 0.5), Parameter::W, 1.4),
        (CUBIC, (0.05, 1.0, 2.0, 1.5, 0.5), Parameter::Beta, 3.0),
    ];
    for (law, case, parameter, to) in cases {
        let e = belt(law, case);
        let b = branch(&e, parameter, to, 0.02);
        println!("{law:?}: {} points, end {:?}", b.points.len(), b.end);
        for s in &b.special {
            println!(
                "  {:?} at {} ({:?} -> {:?})",
                s.kind, s.value, s.before.multipliers, s.after.multipliers
            );
        }
        let matched = check_against_steady(&e, &b, parameter);
        assert!(matched >= 8, "{law:?}: {matched} points matched");
    }
}

/// A falling Stribeck law (η = 0, μs = 1.5, vs = 0.3) on a belt, weakly damped (ζ = 0.05) and
/// weakly forced (β = 0.1, w = 0.7): the orbit slides throughout (s = y' − vb < 0, no event)
/// and its multipliers are a complex pair with |μ|² = det M = exp(−∫(2ζ + μ'(|s|)) dτ). As vb
/// falls towards the law's steepest fall (vs/√2) the damping 2ζ + μ'(s) turns negative on
/// average over the orbit and the pair crosses the unit circle.
#[test]
fn a_falling_stribeck_law_gives_a_neimark_sacker_point_on_a_sliding_branch() {
    let law = FrictionLaw::Stribeck {
        vs: 0.3,
        delta: 2.0,
        eta: 0.0,
    };
    // From steady sliding (y = sgn(vb) μ(|vb|), y' = 0): from rest the belt can pull the
    // block into a stick-slip cycle.
    let e = belt(law, (0.05, 0.7, 0.1, 1.5, 0.9));
    let rest = law.sliding_equilibrium(1.5, 0.9);
    let e = e.with_initial(State { y: rest, v: 0.0 }).unwrap();
    let b = branch(&e, Parameter::Vb, 0.4, 0.02);
    assert!(
        matches!(b.end, BranchEnd::Boundary { .. }),
        "{} points, end {:?}",
        b.points.len(),
        b.end
    );
    assert!(
        b.points.iter().all(|p| p.orbit.events.is_empty()),
        "slides throughout"
    );
    let specials: Vec<_> = b.special.iter().map(|s| (s.kind, s.value)).collect();
    println!("{} points; special points {specials:?}", b.points.len());
    assert_eq!(specials.len(), 1, "{specials:?}");
    let ns = &b.special[0];
    assert_eq!(ns.kind, SpecialKind::NeimarkSacker);
    assert!(
        ns.before.stability == Stability::Stable && ns.after.stability == Stability::Unstable,
        "{ns:?}"
    );
    // The orbits on either side (Newton's method from the branch's nearest point): a complex
    // pair inside the unit circle above the point, outside below it.
    let dynamics = FrictionDynamics::new();
    let (params, _) = settled_orbit(&e).unwrap();
    for (offset, inside) in [(0.005, true), (-0.005, false)] {
        let vb = ns.value + offset;
        let near = b
            .points
            .iter()
            .min_by(|a, c| (a.value - vb).abs().total_cmp(&(c.value - vb).abs()))
            .unwrap();
        let p = Parameter::Vb.set(params, vb).unwrap();
        let orbit = dynamics
            .find_periodic_orbit(&p, near.orbit.state, 1, &NewtonOptions::default())
            .unwrap();
        let mu = orbit.multipliers[0];
        println!(
            "vb = {vb}: multipliers {:?}, |mu| {}",
            orbit.multipliers,
            mu.modulus()
        );
        assert!(mu.im != 0.0 && orbit.events.is_empty(), "{orbit:?}");
        assert_eq!(mu.modulus() < 1.0, inside, "vb = {vb}: {mu:?}");
    }
    // At the point |μ|² = det M = 1: the orbit's mean damping ∫(2ζ + μ'(s)) dτ over a period
    // vanishes (Liouville), measured on the solver's motion by the trapezoidal rule (spectral
    // for a smooth periodic integrand).
    let p = Parameter::Vb.set(params, ns.value).unwrap();
    let mut solver = dynamics.plain_solver(&p, ns.before.state).unwrap();
    let n = 2000;
    let period = p.drive_period();
    let mut integral = 0.0;
    for k in 0..n {
        let tau = period * k as f64 / n as f64;
        run_until(&mut solver, tau, |_| {}).unwrap();
        // (The block moves slower than the belt throughout: s < 0.)
        let s = solver.state().v - p.vb;
        assert!(s < 0.0, "{s}");
        integral += 2.0 * p.zeta + law.value_and_slope(p.mu_s, s.abs()).1;
    }
    integral *= period / n as f64;
    println!("NS at vb = {}: ∫(2ζ + μ') dτ = {integral:.2e}", ns.value);
    assert!(integral.abs() <= 1e-6, "{integral}");
}

/// The largest change of the amplitude between neighbouring steps of a sweep leg (its
/// values in the leg's order): the interval and the change, and the median change.
fn largest_jump(leg: &[&SweepPoint]) -> ((f64, f64), f64, f64) {
    let mut changes: Vec<((f64, f64), f64)> = leg
        .windows(2)
        .map(|p| {
            let d = (p[1].steady.amplitude() - p[0].steady.amplitude()).abs();
            ((p[0].value, p[1].value), d)
        })
        .collect();
    changes.sort_by(|a, b| b.1.total_cmp(&a.1));
    let median = changes[changes.len() / 2].1;
    (changes[0].0, changes[0].1, median)
}

/// A Stribeck belt's stick-slip branch over w folds back (the stable and an unstable orbit
/// meet): the fold `continue` reports lies in the interval where a sweep up in w jumps, and
/// the sweep down passes it without a jump there (hysteresis).
#[test]
fn a_fold_of_a_stribeck_branch_is_where_the_sweep_up_jumps() {
    let (from, to) = (0.7, 1.2);
    let e = belt(STRIBECK, (0.05, from, 1.45, 1.5, 0.05));
    let b = branch(&e, Parameter::W, to, 0.05);
    let folds: Vec<f64> = b
        .special
        .iter()
        .filter(|s| s.kind == SpecialKind::Fold)
        .map(|s| s.value)
        .collect();
    println!(
        "{} points, end {:?}, folds {folds:?}",
        b.points.len(),
        b.end
    );
    assert_eq!(folds.len(), 1, "{:?}", b.special);
    let fold = folds[0];
    let range = ParameterRange::new("w", from, to, 51).unwrap();
    let steps = Sweep::new(&e, Axis::range(Parameter::W, &range).unwrap())
        .unwrap()
        .direction(SweepDirection::Both)
        .run(&())
        .unwrap();
    let up: Vec<&SweepPoint> = steps.iter().filter(|p| p.leg == SweepLeg::Up).collect();
    let mut down: Vec<&SweepPoint> = steps.iter().filter(|p| p.leg == SweepLeg::Down).collect();
    let ((a, c), jump, median) = largest_jump(&up);
    println!("up: largest jump {jump} in ({a}, {c}), median change {median}");
    assert!(
        a < fold && fold < c,
        "fold at w = {fold}, the sweep up jumps in ({a}, {c})"
    );
    assert!(jump > 20.0 * median, "{jump} against {median}");
    down.reverse();
    let below = |leg: &[&SweepPoint]| {
        leg.iter()
            .filter(|p| p.value < fold)
            .max_by(|x, y| x.value.total_cmp(&y.value))
            .map(|p| (p.value, p.steady.amplitude()))
            .unwrap()
    };
    let (w_up, a_up) = below(&up);
    let (w_down, a_down) = below(&down);
    println!("just below the fold, w = {w_up}: amplitude {a_up} up, {a_down} down ({w_down})");
    assert!(
        (a_up - a_down).abs() > 0.1 * a_up,
        "no hysteresis at w = {w_up}"
    );
}
