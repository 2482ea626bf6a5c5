//! The slips of a Stribeck or cubic belt on the explicit integrator (DOP853,
//! [`SlipIntegrator::Explicit`], which the steady-state search of a self-excited belt uses)
//! against the same solver on Radau IIA ([`SlipIntegrator::Radau`], the stability tools'),
//! and against the test kit's independent integrator ([`stickslip_testkit::oracle::Oracle`]:
//! the classical Runge–Kutta method at a fixed step 5e-4, events by bisection).
//!
//! - a 12 × 12 map of the belt bench's Stribeck belt (the paper's ζ, vs = 0.5, δ = 2,
//!   η = 0.05, vb 0.05–2, μs 1–3, from rest): every point's class and section the same on
//!   both integrators, and the period, y_max, y_min and stick fraction within 1e-9;
//! - self-excited cycles of both laws against the oracle to 1e-8;
//! - trajectories of damped and forced belts against the oracle, events to 1e-12.

use stickslip::cancel::Cancel;
use stickslip::friction_solver::{FrictionSolver, SlipIntegrator};
use stickslip::steady::{self, MotionClass, SteadyOptions};
use stickslip::{EventKind, Params, Solver, State};
use stickslip_testkit::belts::benchmark_stribeck_belt;
use stickslip_testkit::oracle::{Oracle, OracleLaw as TestLaw};

/// The oracle's step on the slips.
const H: f64 = 5e-4;

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

fn params(zeta: f64, mu_s: f64, vb: f64, w: f64, beta: f64, law: TestLaw) -> Params {
    Params::new(zeta, w, beta)
        .and_then(|p| p.with_mu_s(mu_s))
        .and_then(|p| p.with_vb(vb))
        .and_then(|p| p.with_law(law.library()))
        .unwrap()
}

fn explicit(p: Params, initial: State) -> FrictionSolver {
    FrictionSolver::with_integrator(p, initial, SlipIntegrator::Explicit, Cancel::never()).unwrap()
}

#[test]
fn a_stribeck_map_is_the_same_on_both_integrators_to_1e_9() {
    let experiment = benchmark_stribeck_belt();
    // The experiment's factory searches on the explicit integrator; this one on Radau.
    let fast = experiment.factory();
    let radau = |p: Params, s: State| -> stickslip::Result<Box<dyn Solver + Send>> {
        Ok(Box::new(FrictionSolver::new(p, s)?))
    };
    let base = experiment.params().unwrap();
    let options = experiment.steady_options();
    let mut classes = std::collections::BTreeMap::new();
    let mut worst = 0.0f64;
    for i in 0..12 {
        for j in 0..12 {
            let vb = 0.05 + 1.95 * i as f64 / 11.0;
            let mu_s = 1.0 + 2.0 * j as f64 / 11.0;
            let p = base.with_vb(vb).and_then(|p| p.with_mu_s(mu_s)).unwrap();
            let a = steady::steady_state_from(&fast, &p, State::default(), &options).unwrap();
            let b = steady::steady_state_from(&radau, &p, State::default(), &options).unwrap();
            let at = format!("vb = {vb}, μs = {mu_s}");
            assert_eq!(a.class, b.class, "{at}");
            let (ca, cb) = (a.self_excited.unwrap(), b.self_excited.unwrap());
            assert_eq!(ca.section, cb.section, "{at}");
            assert_eq!(ca.period.is_some(), cb.period.is_some(), "{at}");
            let period = match (ca.period, cb.period) {
                (Some(x), Some(y)) => (x - y).abs() / x.abs().max(1.0),
                _ => 0.0,
            };
            let d = period
                .max((a.y_max - b.y_max).abs())
                .max((a.y_min - b.y_min).abs())
                .max((ca.stick_fraction - cb.stick_fraction).abs());
            assert!(d <= 1e-9, "{at}: {a:?}\nagainst\n{b:?}");
            worst = worst.max(d);
            *classes.entry(a.class.label()).or_insert(0) += 1;
        }
    }
    // The map holds stick-slip cycles and steady sliding.
    assert!(classes.len() >= 2, "{classes:?}");
    eprintln!("classes {classes:?}, largest difference {worst:e}");
}

#[test]
fn self_excited_cycles_on_the_explicit_integrator_follow_the_oracle() {
    for (zeta, mu_s, vb, law) in [
        (0.05, 1.5, 0.3, STRIBECK),
        (0.02, 1.4, 0.2, STRIBECK_LINEAR),
        (0.05, 1.5, 0.3, CUBIC),
        (0.03, 1.3, -0.4, CUBIC),
    ] {
        let p = params(zeta, mu_s, vb, 1.0, 0.0, law);
        let s = steady::steady_state(
            &mut explicit(p, State::default()),
            &SteadyOptions::default(),
        )
        .unwrap();
        assert_eq!(s.class, MotionClass::StickSlipCycle, "{p:?}");
        let (period, y_max, y_min) = Oracle::new(p, law, H, 0.0, 0.0).cycle(4);
        let cycle = s.self_excited.unwrap();
        let d = (cycle.period.unwrap() - period)
            .abs()
            .max((s.y_max - y_max).abs())
            .max((s.y_min - y_min).abs());
        assert!(
            d <= 1e-8,
            "{p:?}: {cycle:?} {s:?} against {period} {y_max} {y_min}"
        );
    }
}

#[test]
fn trajectories_on_the_explicit_integrator_follow_the_oracle_and_events_are_to_1e_12() {
    for (law, (zeta, mu_s, vb, w, beta), initial) in [
        (STRIBECK, (0.05, 1.6, 0.3, 1.3, 1.5), State::default()),
        (CUBIC, (0.05, 1.6, 0.3, 1.3, 1.5), State::default()),
        (
            STRIBECK,
            (0.03, 1.4, 0.5, 1.0, 0.0),
            State::new(0.5, 0.0).unwrap(),
        ),
        (
            STRIBECK_LINEAR,
            (0.02, 1.4, -0.2, 0.8, 0.7),
            State::default(),
        ),
    ] {
        let p = params(zeta, mu_s, vb, w, beta, law);
        let mut solver = explicit(p, initial);
        let mut oracle = Oracle::new(p, law, H, initial.y, initial.v);
        let mut events = Vec::new();
        for k in 1..=300 {
            let tau = 0.1 * k as f64;
            while solver.time() < tau {
                if let Some(e) = solver.advance(tau).unwrap() {
                    // Every event to 1e-12: the slip at zero, or the net force at ±μs.
                    let s = solver.state();
                    assert_eq!(s.v, p.vb);
                    if e.kind == EventKind::Slip {
                        let f = p.drive(e.tau) - e.y - 2.0 * p.zeta * p.vb;
                        assert!((f.abs() - p.mu_s).abs() <= 1e-12, "{e:?}: {f}");
                    } else {
                        let (a, b) = solver.interval();
                        if b > a {
                            let before = solver.dense(b);
                            assert!((before.v - p.vb).abs() <= 1e-12, "{e:?} {before:?}");
                        }
                    }
                    events.push(e);
                }
            }
            oracle.run_to(tau);
            let s = solver.state();
            let d = (s.y - oracle.y).abs().max((s.v - oracle.v).abs());
            assert!(
                d <= 1e-8,
                "{p:?} at τ = {tau}: {s:?}, oracle ({}, {})",
                oracle.y,
                oracle.v
            );
        }
        assert_eq!(events.len(), oracle.events.len(), "{p:?}");
        for (e, o) in events.iter().zip(&oracle.events) {
            assert_eq!(e.kind, o.2, "{p:?}");
            assert!((e.tau - o.0).abs() <= 1e-8, "{p:?}: {e:?} {o:?}");
        }
        assert!(events.len() >= 4, "{p:?}: {events:?}");
    }
}
