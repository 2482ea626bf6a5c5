//! Curves of special points in two parameters for the smooth friction laws (Stribeck, cubic)
//! on a forced belt (`curve` on [`FrictionDynamics`]): each point of a fold or
//! Neimark–Sacker curve against the special point that the one-parameter continuation
//! (`continue`) locates on its own at the point's value of the curve's other parameter, and
//! the multiplier condition (+1, or a complex pair on the unit circle) of the orbit that
//! Newton's method finds there.

use stickslip::continuation::{
    continue_orbit_of, curve, settled_orbit, ContinuationOptions, Curve, CurveSpec, Follow,
    SpecialKind,
};
use stickslip::friction::FrictionLaw;
use stickslip::stability::{FrictionDynamics, NewtonOptions};
use stickslip::{Experiment, Parameter, State};

const STRIBECK: FrictionLaw = FrictionLaw::Stribeck {
    vs: 0.3,
    delta: 2.0,
    eta: 0.05,
};

/// A forced belt: (ζ, w, β, μs, vb) and the law.
fn belt(law: FrictionLaw, (zeta, w, beta, mu_s, vb): (f64, f64, f64, f64, f64)) -> Experiment {
    Experiment::dimensionless(zeta, w, beta)
        .and_then(|e| e.with_mu_s(mu_s))
        .and_then(|e| e.with_vb(vb))
        .and_then(|e| e.with_law(law))
        .unwrap()
}

fn traced(experiment: &Experiment, spec: &CurveSpec) -> Curve {
    let c = curve(experiment, spec, &ContinuationOptions::default(), &())
        .expect("no error")
        .unwrap_or_else(|no| panic!("no start: {no}"));
    println!(
        "{} points, begin {:?}, end {:?}, codim2 {:?}",
        c.points.len(),
        c.begin,
        c.end,
        c.codim2
            .iter()
            .map(|p| (p.kind, p.over, p.vary))
            .collect::<Vec<_>>()
    );
    for p in &c.points {
        println!(
            "  {} = {:.9}, {} = {:.9}: ({:.9}, {:.9}) stops {} turns {} mu {:?}",
            c.over.label(),
            p.over,
            c.vary.label(),
            p.vary,
            p.orbit.state.y,
            p.orbit.state.v,
            p.stops,
            p.turns,
            p.orbit.multipliers
        );
    }
    c
}

/// The special point of `kind` that `continue` locates in `vary` on the branch of the orbit
/// the motion of `base` (with `over` at `at`, `vary` at `start`) settles on, continued towards
/// `to`: its value, or `None` when it locates none.
fn continued(
    base: &Experiment,
    (over, at): (Parameter, f64),
    (vary, start, to): (Parameter, f64, f64),
    kind: SpecialKind,
    initial: &dyn Fn(f64) -> Option<State>,
) -> Option<f64> {
    let mut e = base
        .clone()
        .with_parameter(over, at)
        .and_then(|e| e.with_parameter(vary, start))
        .unwrap();
    if let Some(state) = initial(start) {
        e = e.with_initial(state).unwrap();
    }
    let (params, orbit) = settled_orbit(&e).unwrap();
    let options = ContinuationOptions::default().with_max_step(0.02);
    let branch = continue_orbit_of(
        &FrictionDynamics::new(),
        &params,
        vary,
        &orbit,
        to,
        &options,
        &(),
    )
    .unwrap();
    branch
        .special
        .iter()
        .find(|s| s.kind == kind && s.located)
        .map(|s| s.value)
}

/// `count` points of the curve spread evenly over its indices (ends included).
fn spread(curve: &Curve, count: usize) -> Vec<usize> {
    let n = curve.points.len();
    assert!(n > 2 * count, "{n} points");
    (0..count).map(|k| k * (n - 1) / (count - 1)).collect()
}

/// The orbit Newton's method finds at the curve point `index` (from its strobe state), on
/// the model of `base` at the point's parameters: its multipliers.
fn multipliers_at(
    base: &Experiment,
    c: &Curve,
    index: usize,
) -> [stickslip::stability::Multiplier; 2] {
    let p = &c.points[index];
    let params = c
        .vary
        .set(c.over.set(base.params().unwrap(), p.over).unwrap(), p.vary)
        .unwrap();
    let orbit = FrictionDynamics::new()
        .find_periodic_orbit(&params, p.orbit.state, c.period, &NewtonOptions::default())
        .unwrap();
    orbit.multipliers
}

/// Each of `count` points of `c` against `continue`'s special point of `kind` at its value of
/// Q (continued in P from `start` towards `to`): within `within`. Returns the largest
/// difference.
fn check_against_continue(
    base: &Experiment,
    c: &Curve,
    count: usize,
    (start, to): (f64, f64),
    kind: SpecialKind,
    initial: &dyn Fn(f64) -> Option<State>,
    within: f64,
) -> f64 {
    let mut largest: f64 = 0.0;
    for i in spread(c, count) {
        let p = &c.points[i];
        let found = continued(base, (c.over, p.over), (c.vary, start, to), kind, initial)
            .unwrap_or_else(|| panic!("no {kind:?} at {} = {}", c.over.label(), p.over));
        let d = (found - p.vary).abs();
        println!(
            "{} = {:.9}: curve {} = {:.10}, continue {:.10}, difference {d:.2e}",
            c.over.label(),
            p.over,
            c.vary.label(),
            p.vary,
            found
        );
        assert!(
            d <= within,
            "{} = {}: curve {}, continue {found}",
            c.over.label(),
            p.over,
            p.vary
        );
        largest = largest.max(d);
    }
    largest
}

#[test]
fn a_stribeck_fold_curve_over_beta_passes_through_continues_folds() {
    let e = belt(STRIBECK, (0.05, 0.7, 1.45, 1.5, 0.05));
    let spec = CurveSpec {
        follow: Follow::Fold,
        vary: Parameter::W,
        vary_to: 1.2,
        over: Parameter::Beta,
        from: 1.40,
        to: 1.50,
    };
    let c = traced(&e, &spec);
    assert!(c.points.len() > 3);
    // (The fold of `friction_continuation.rs` at β = 1.45.)
    let start = c.points[c.start].vary;
    assert!((start - 0.90137).abs() < 1e-5, "{start}");
    for i in spread(&c, 5) {
        let mu = multipliers_at(&e, &c, i);
        let off = mu
            .iter()
            .map(|m| (m.re - 1.0).hypot(m.im))
            .fold(f64::INFINITY, f64::min);
        println!("{:?}: {off:.2e}", mu);
        assert!(off <= 1e-8, "{mu:?}");
    }
    let largest = check_against_continue(&e, &c, 4, (0.7, 1.2), SpecialKind::Fold, &|_| None, 1e-8);
    println!("largest difference {largest:.2e}");
}

/// A falling Stribeck law (η = 0) on a belt, weakly forced: the sliding orbit's
/// Neimark–Sacker point in vb (`friction_continuation.rs`) followed over w.
#[test]
fn a_stribeck_neimark_sacker_curve_over_w() {
    let law = FrictionLaw::Stribeck {
        vs: 0.3,
        delta: 2.0,
        eta: 0.0,
    };
    let rest = |vb: f64| {
        Some(State {
            y: law.sliding_equilibrium(1.5, vb),
            v: 0.0,
        })
    };
    let e = belt(law, (0.05, 0.7, 0.1, 1.5, 0.9));
    let e = e.with_initial(rest(0.9).unwrap()).unwrap();
    let spec = CurveSpec {
        follow: Follow::NeimarkSacker,
        vary: Parameter::Vb,
        vary_to: 0.4,
        over: Parameter::W,
        from: 0.6,
        to: 0.8,
    };
    let c = traced(&e, &spec);
    let start = c.points[c.start].vary;
    assert!((start - 0.6604728).abs() < 1e-6, "{start}");
    for i in spread(&c, 5) {
        let mu = multipliers_at(&e, &c, i);
        println!("{mu:?}");
        assert!(
            mu[0].im != 0.0 && (mu[0].modulus() - 1.0).abs() <= 1e-8,
            "{mu:?}"
        );
    }
    let largest = check_against_continue(
        &e,
        &c,
        4,
        (0.9, 0.4),
        SpecialKind::NeimarkSacker,
        &rest,
        1e-8,
    );
    println!("largest difference {largest:.2e}");
}

/// The cubic law μ(s) = μs − k1·s + k3·s³ falls up to s = √(k1/(3k3)): a belt in that range,
/// weakly forced, has a Neimark–Sacker point of its sliding orbit in vb.
#[test]
fn a_cubic_neimark_sacker_curve_over_w() {
    let law = FrictionLaw::Cubic { k1: 0.5, k3: 0.5 };
    let rest = |vb: f64| {
        Some(State {
            y: law.sliding_equilibrium(1.5, vb),
            v: 0.0,
        })
    };
    let e = belt(law, (0.05, 0.7, 0.1, 1.5, 0.8));
    let e = e.with_initial(rest(0.8).unwrap()).unwrap();
    let spec = CurveSpec {
        follow: Follow::NeimarkSacker,
        vary: Parameter::Vb,
        vary_to: 0.3,
        over: Parameter::W,
        from: 0.6,
        to: 0.8,
    };
    let c = traced(&e, &spec);
    for i in spread(&c, 5) {
        let mu = multipliers_at(&e, &c, i);
        println!("{mu:?}");
        assert!(
            mu[0].im != 0.0 && (mu[0].modulus() - 1.0).abs() <= 1e-8,
            "{mu:?}"
        );
    }
    let largest = check_against_continue(
        &e,
        &c,
        4,
        (0.8, 0.3),
        SpecialKind::NeimarkSacker,
        &rest,
        1e-8,
    );
    println!("largest difference {largest:.2e}");
}
