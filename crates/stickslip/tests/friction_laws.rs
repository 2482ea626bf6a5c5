//! The Stribeck and cubic friction laws on a belt ([`FrictionSolver`]: slips on the smooth
//! integrator, stops exact) against an independent integrator, to 1e-8: damped belts without
//! a drive (self-excited stick-slip: y_max, y_min and the period) and forced belts; steady
//! sliding recognised where 2ζ + μ'(vb) > 0 and a stick-slip cycle where it is negative.
//!
//! The independent integrator is the test kit's ([`stickslip_testkit::oracle::Oracle`]):
//! another method with another tolerance, the classical fourth-order Runge–Kutta method at a
//! fixed step h = 5e-4 on the slips, with the laws written out there again, the stops as
//! y = y_s + vb t checked on the same grid, and every event placed by bisection on a partial
//! Runge–Kutta step from the last grid point.

use stickslip::friction_solver::FrictionSolver;
use stickslip::steady::{MotionClass, SlidingStability, SteadyOptions};
use stickslip::{steady, EventKind, Params, Solver, State};
use stickslip_testkit::oracle::{Oracle, OracleLaw as TestLaw};

/// The oracle's step on the slips.
const H: f64 = 5e-4;

/// A self-excited cycle's period and extremes from the oracle: the interval between its
/// last two stops, and the extremes between them.
fn oracle_cycle(p: Params, law: TestLaw, initial: State, sticks: usize) -> (f64, f64, f64) {
    Oracle::new(p, law, H, initial.y, initial.v).cycle(sticks)
}

fn params(zeta: f64, mu_s: f64, vb: f64, w: f64, beta: f64, law: TestLaw) -> Params {
    Params::new(zeta, w, beta)
        .and_then(|p| p.with_mu_s(mu_s))
        .and_then(|p| p.with_vb(vb))
        .and_then(|p| p.with_law(law.library()))
        .unwrap()
}

const STRIBECK: TestLaw = TestLaw::Stribeck {
    vs: 0.5,
    delta: 2.0,
    eta: 0.05,
};
const STRIBECK_LINEAR: TestLaw = TestLaw::Stribeck {
    vs: 0.3,
    delta: 1.0,
    eta: 0.0,
};
const CUBIC: TestLaw = TestLaw::Cubic { k1: 1.0, k3: 0.4 };

/// The solver's trajectory against the oracle's, sample by sample, and their events.
fn compare_trajectories(p: Params, law: TestLaw, initial: State, end: f64) {
    let mut solver = FrictionSolver::new(p, initial).unwrap();
    let mut oracle = Oracle::new(p, law, H, initial.y, initial.v);
    let mut events = Vec::new();
    for k in 1..=(end / 0.5) as usize {
        let tau = 0.5 * k as f64;
        stickslip::solver::run_until(&mut solver, tau, |e| events.push(*e)).unwrap();
        oracle.run_to(tau);
        let s = solver.state();
        let d = (s.y - oracle.y).abs().max((s.v - oracle.v).abs());
        assert!(
            d <= 1e-8,
            "{p:?} at τ = {tau}: solver ({}, {}), oracle ({}, {})",
            s.y,
            s.v,
            oracle.y,
            oracle.v
        );
    }
    assert_eq!(events.len(), oracle.events.len(), "{p:?}");
    for (e, o) in events.iter().zip(&oracle.events) {
        assert_eq!(e.kind, o.2, "{p:?}");
        assert!(
            (e.tau - o.0).abs() <= 1e-8 && (e.y - o.1).abs() <= 1e-8,
            "{e:?} {o:?}"
        );
    }
    assert!(events.iter().any(|e| e.kind == EventKind::Stick), "{p:?}");
}

#[test]
fn damped_and_forced_belts_with_smooth_laws_follow_an_independent_integrator() {
    for law in [STRIBECK, STRIBECK_LINEAR, CUBIC] {
        compare_trajectories(
            params(0.05, 1.5, 0.3, 1.0, 0.0, law),
            law,
            State::default(),
            40.0,
        );
        compare_trajectories(
            params(0.1, 1.3, 0.4, 0.8, 1.0, law),
            law,
            State::default(),
            40.0,
        );
        compare_trajectories(
            params(0.05, 1.6, -0.2, 1.7, 2.5, law),
            law,
            State { y: 1.0, v: 0.0 },
            40.0,
        );
    }
}

/// Every event of the solver is located to 1e-12: at a stop or a reversal the slip is zero
/// and the friction force is continuous (μ(0) = μs); at a release the net force is ±μs.
#[test]
fn events_are_located_to_1e_12() {
    for law in [STRIBECK, CUBIC] {
        let p = params(0.05, 1.6, 0.3, 1.3, 1.5, law);
        let mut solver = FrictionSolver::new(p, State::default()).unwrap();
        let mut count = 0;
        while solver.time() < 60.0 {
            let Some(event) = solver.advance(60.0).unwrap() else {
                continue;
            };
            count += 1;
            let s = solver.state();
            assert_eq!(s.v, p.vb);
            if event.kind == EventKind::Slip {
                let f = p.drive(event.tau) - event.y - 2.0 * p.zeta * p.vb;
                assert!((f.abs() - p.mu_s).abs() <= 1e-12, "{event:?}: {f}");
            } else {
                // The slip just before the event is at zero within 1e-12 (the step's end).
                let (a, b) = solver.interval();
                assert_eq!(b, event.tau);
                if b > a {
                    let before = solver.dense(b);
                    assert!((before.v - p.vb).abs() <= 1e-12, "{event:?} {before:?}");
                }
            }
        }
        assert!(count > 10, "{count}");
    }
}

#[test]
fn self_excited_stribeck_and_cubic_cycles_follow_an_independent_integrator() {
    for (zeta, mu_s, vb, law) in [
        (0.05, 1.5, 0.3, STRIBECK),
        (0.02, 1.4, 0.2, STRIBECK_LINEAR),
        (0.05, 1.5, 0.3, CUBIC),
        (0.03, 1.3, -0.4, CUBIC),
    ] {
        let p = params(zeta, mu_s, vb, 1.0, 0.0, law);
        let s = steady::steady_state(
            &mut FrictionSolver::new(p, State::default()).unwrap(),
            &SteadyOptions::default(),
        )
        .unwrap();
        assert_eq!(s.class, MotionClass::StickSlipCycle, "{p:?}");
        let (period, y_max, y_min) = oracle_cycle(p, law, State::default(), 4);
        let cycle = s.self_excited.unwrap();
        assert!(
            (cycle.period.unwrap() - period).abs() <= 1e-8,
            "{p:?}: {cycle:?} {period}"
        );
        assert!(
            (s.y_max - y_max).abs() <= 1e-8,
            "{p:?}: {} {y_max}",
            s.y_max
        );
        assert!(
            (s.y_min - y_min).abs() <= 1e-8,
            "{p:?}: {} {y_min}",
            s.y_min
        );
    }
}

/// Steady sliding of a smooth law: y = sgn(vb)·μ(|vb|), stable where 2ζ + μ'(|vb|) > 0.
/// Stable: the block released on it (and from rest at a fast belt) settles there. Unstable
/// (the law falls faster than the damping): from a hair off the equilibrium the block grows
/// into a stick-slip cycle.
#[test]
fn steady_sliding_is_an_equilibrium_where_stable_and_stick_slip_where_not() {
    // Stribeck, δ = 1: μ'(vb) = η − (μs − 1)/vs·exp(−vb/vs).
    let law = TestLaw::Stribeck {
        vs: 0.3,
        delta: 1.0,
        eta: 0.0,
    };
    let slope = |mu_s: f64, vb: f64| -(mu_s - 1.0) / 0.3 * (-vb / 0.3f64).exp();
    // Stable: ζ = 0.1, μs = 1.3, vb = 1.5 (2ζ + μ' = 0.2 − 0.0067 > 0).
    let (zeta, mu_s, vb) = (0.1, 1.3, 1.5);
    assert!(2.0 * zeta + slope(mu_s, vb) > 0.0);
    let p = params(zeta, mu_s, vb, 1.0, 0.0, law);
    let y_e = law.mu(mu_s, vb);
    for initial in [
        State::default(),
        State {
            y: y_e + 0.05,
            v: 0.0,
        },
    ] {
        let s = steady::steady_state(
            &mut FrictionSolver::new(p, initial).unwrap(),
            &SteadyOptions::default(),
        )
        .unwrap();
        assert_eq!(s.class, MotionClass::SteadySliding, "{initial:?}");
        let cycle = s.self_excited.unwrap();
        assert_eq!(cycle.sliding_stability, SlidingStability::Stable);
        assert!((cycle.equilibrium - y_e).abs() < 1e-12);
        assert!((s.y_max - y_e).abs() < 1e-6 && (s.y_min - y_e).abs() < 1e-6);
    }
    // Unstable: ζ = 0.02, μs = 1.5, vb = 0.1 (2ζ + μ' = 0.04 − 1.19 < 0).
    let (zeta, mu_s, vb) = (0.02, 1.5, 0.1);
    assert!(2.0 * zeta + slope(mu_s, vb) < 0.0);
    let p = params(zeta, mu_s, vb, 1.0, 0.0, law);
    let y_e = law.mu(mu_s, vb);
    let s = steady::steady_state(
        &mut FrictionSolver::new(
            p,
            State {
                y: y_e + 1e-6,
                v: 0.0,
            },
        )
        .unwrap(),
        &SteadyOptions::default(),
    )
    .unwrap();
    assert_eq!(s.class, MotionClass::StickSlipCycle);
    let cycle = s.self_excited.unwrap();
    assert_eq!(cycle.sliding_stability, SlidingStability::Unstable);
    assert!(cycle.stick_fraction > 0.0);
}

/// Where the steady-state search decides that a Stribeck or cubic belt slides steadily
/// (sooner, by the energy argument of `steady/self_excited.rs`: a turning point nearer
/// steady sliding than vb where the law's chord stays below 2ζ), the motion from rest indeed
/// never sticks or reverses again: the friction solver run on for 300 natural periods has
/// no event after that point, the distances of its turning points from y_e never rise, and
/// its energy about steady sliding falls to a hundredth of the decided one or below.
#[test]
fn where_a_smooth_law_belt_is_decided_sliding_it_never_sticks_again() {
    let zeta = 0.0468;
    let mut sliding = 0;
    for law in [STRIBECK, STRIBECK_LINEAR, CUBIC] {
        for vb in [0.3, 0.6, 1.0, 1.5, 2.0] {
            for mu_s in [1.0, 1.05, 1.2, 1.5, 2.5] {
                let p = params(zeta, mu_s, vb, 1.0, 0.0, law);
                let s = steady::steady_state(
                    &mut FrictionSolver::new(p, State::default()).unwrap(),
                    &SteadyOptions::default(),
                )
                .unwrap();
                if s.class != MotionClass::SteadySliding {
                    continue;
                }
                sliding += 1;
                let cycle = s.self_excited.unwrap();
                let (settled, y_e) = (cycle.time_to_settle, cycle.equilibrium);
                let mut solver = FrictionSolver::new(p, State::default()).unwrap();
                stickslip::solver::run_until(&mut solver, settled, |_| {}).unwrap();
                let energy = |s: State| 0.5 * (s.v * s.v + (s.y - y_e) * (s.y - y_e));
                let decided = energy(solver.state());
                let end = settled + 300.0 * std::f64::consts::TAU;
                let mut last = solver.state();
                let mut distance = f64::INFINITY;
                for k in 1..=((end - settled) / 0.05) as usize {
                    let tau = settled + 0.05 * k as f64;
                    stickslip::solver::run_until(&mut solver, tau, |e| {
                        panic!("{law:?}, vb = {vb}, μs = {mu_s}: {e:?} after τ = {settled}")
                    })
                    .unwrap();
                    let now = solver.state();
                    if last.v > 0.0 && now.v <= 0.0 {
                        // A maximum of y between the samples: its distance from y_e, to
                        // the sampling's error (the samples are 0.05 apart).
                        let d = last.y.max(now.y) - y_e;
                        assert!(
                            d <= distance + 1e-3 * distance.min(1.0) + 1e-12,
                            "{law:?}, vb = {vb}, μs = {mu_s}: {d} after {distance}"
                        );
                        distance = d;
                    }
                    last = now;
                }
                let final_energy = energy(solver.state());
                assert!(
                    final_energy <= 1e-2 * decided,
                    "{law:?}, vb = {vb}, μs = {mu_s}: energy {final_energy} from {decided}"
                );
            }
        }
    }
    assert!(sliding >= 15, "{sliding}");
}

/// Newton's method on the turning-point map of a slow pure-slip cycle
/// (`steady/self_excited.rs`) changes no class: a 12 × 12 map of the belt bench's Stribeck
/// belt (the paper's ζ, vs = 0.5, δ = 2, η = 0.05) over vb 0.05–1.2, μs 1–1.4, where the
/// pure-slip cycles are, each point from rest with and without it: the same class and
/// section, and y_min, y_max within 1e-8; and Newton settles the pure-slip cycles sooner.
#[test]
fn newton_on_the_turning_point_map_changes_no_class_of_a_stribeck_map() {
    use stickslip_testkit::belts::benchmark_stribeck_belt;
    let experiment = benchmark_stribeck_belt();
    let factory = experiment.factory();
    let base = experiment.params().unwrap();
    let options = experiment.steady_options();
    assert!(options.newton);
    let (mut pure, mut sooner) = (0, 0);
    for i in 0..12 {
        for j in 0..12 {
            let vb = 0.05 + 1.15 * i as f64 / 11.0;
            let mu_s = 1.0 + 0.4 * j as f64 / 11.0;
            let p = base.with_vb(vb).and_then(|p| p.with_mu_s(mu_s)).unwrap();
            let run = |newton: bool| {
                steady::steady_state_from(
                    &factory,
                    &p,
                    State::default(),
                    &options.with_newton(newton),
                )
                .unwrap()
            };
            let (fast, plain) = (run(true), run(false));
            let at = format!("vb = {vb}, μs = {mu_s}");
            assert_eq!(fast.class, plain.class, "{at}");
            let (a, b) = (fast.self_excited.unwrap(), plain.self_excited.unwrap());
            assert_eq!(a.section, b.section, "{at}");
            assert!(
                (fast.y_min - plain.y_min).abs() <= 1e-8
                    && (fast.y_max - plain.y_max).abs() <= 1e-8,
                "{at}: [{}, {}] against [{}, {}]",
                fast.y_min,
                fast.y_max,
                plain.y_min,
                plain.y_max
            );
            if let (Some(pa), Some(pb)) = (a.period, b.period) {
                assert!((pa - pb).abs() <= 1e-8, "{at}: period {pa} against {pb}");
            }
            if fast.class == MotionClass::PureSlipCycle {
                pure += 1;
                sooner += usize::from(a.time_to_settle < 0.5 * b.time_to_settle);
            }
        }
    }
    assert!(
        pure >= 2 && sooner >= 2,
        "{pure} pure-slip cycles, {sooner} settled sooner"
    );
}
