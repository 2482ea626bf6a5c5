//! Theory beside the belt's numbers: steady sliding's stability against the class `steady`
//! finds from beside the equilibrium, and the first-order approximation of the cubic law's
//! cycles (after Thomsen & Fidlin 2003) against the exact cycle over a range of belt speeds.

use stickslip::friction::FrictionLaw;
use stickslip::steady::MotionClass;
use stickslip::theory::{CubicBeltApproximation, CubicBeltMotion, SteadySliding};
use stickslip::{Experiment, State};

fn belt(zeta: f64, mu_s: f64, vb: f64, law: FrictionLaw) -> Experiment {
    Experiment::dimensionless(zeta, 1.0, 0.0)
        .and_then(|e| e.with_mu_s(mu_s))
        .and_then(|e| e.with_vb(vb))
        .and_then(|e| e.with_law(law))
        .unwrap()
}

/// From a small displacement off steady sliding, `steady` settles on steady sliding exactly
/// where the linearisation is stable, and on a cycle where it is unstable.
#[test]
fn steady_sliding_is_stable_where_the_theory_says() {
    let stribeck = FrictionLaw::Stribeck {
        vs: 0.5,
        delta: 2.0,
        eta: 0.0,
    };
    let cubic = FrictionLaw::Cubic { k1: 0.3, k3: 0.2 };
    let mut seen = [0usize; 2];
    for (law, zeta, mu_s) in [(stribeck, 0.05, 1.5), (cubic, 0.05, 1.2)] {
        for vb in [0.1, 0.25, 0.4, 0.6, 0.9, 1.2, 1.6, -0.4, -1.6] {
            let e = belt(zeta, mu_s, vb, law);
            let theory = SteadySliding::new(&e.params().unwrap()).unwrap();
            // Away from the boundary d = 0, where the class would be the slow drift's.
            if theory.damping.abs() < 0.02 {
                continue;
            }
            let start = State {
                y: theory.equilibrium + 1e-3,
                v: 0.0,
            };
            let s = e.with_initial(start).unwrap().steady().unwrap();
            let cycle = s.self_excited.expect("a self-excited answer");
            assert!(
                (cycle.equilibrium - theory.equilibrium).abs() < 1e-15
                    && (cycle.sliding_damping - theory.damping).abs() < 1e-15
            );
            if theory.is_stable() {
                assert_eq!(s.class, MotionClass::SteadySliding, "{law:?} vb = {vb}");
                assert!((s.y_max - theory.equilibrium).abs() < 1e-6);
                seen[0] += 1;
            } else {
                assert!(
                    matches!(
                        s.class,
                        MotionClass::StickSlipCycle | MotionClass::PureSlipCycle
                    ),
                    "{law:?} vb = {vb}: {:?}",
                    s.class
                );
                assert!(s.y_max - s.y_min > 1e-2, "{law:?} vb = {vb}");
                seen[1] += 1;
            }
        }
    }
    assert!(seen[0] >= 3 && seen[1] >= 3, "{seen:?}");
    assert!(
        SteadySliding::new(&belt(0.1, 1.5, 0.0, FrictionLaw::Coulomb).params().unwrap()).is_err()
    );
}

/// The linearisation's growth rate against the solver: the distance of successive maxima of
/// y from the equilibrium shrinks by exp(growth_rate · 2π/frequency) per oscillation.
#[test]
fn steady_sliding_decays_at_the_linear_rate() {
    let law = FrictionLaw::Stribeck {
        vs: 0.5,
        delta: 2.0,
        eta: 0.1,
    };
    let e = belt(0.05, 1.5, 1.5, law);
    let theory = SteadySliding::new(&e.params().unwrap()).unwrap();
    assert!(theory.is_stable() && theory.frequency > 0.0);
    let start = State {
        y: theory.equilibrium + 1e-4,
        v: 0.0,
    };
    let mut solver = e.with_initial(start).unwrap().solver().unwrap();
    // Maxima of y where y' falls through 0, placed by the parabola through three samples.
    let (h, mut maxima) = (1e-3, Vec::new());
    let mut prev = (0.0, solver.state());
    let mut before = prev;
    for k in 1..=(30.0 / h) as usize {
        let tau = k as f64 * h;
        stickslip::solver::run_until(solver.as_mut(), tau, |_| {}).unwrap();
        let now = (tau, solver.state());
        if prev.1.v > 0.0 && now.1.v <= 0.0 {
            let (y0, y1, y2) = (before.1.y, prev.1.y, now.1.y);
            let peak = y1 - (y2 - y0).powi(2) / (8.0 * (y2 - 2.0 * y1 + y0));
            maxima.push(peak - theory.equilibrium);
        }
        before = prev;
        prev = now;
    }
    let expected = (theory.growth_rate * std::f64::consts::TAU / theory.frequency).exp();
    assert!(maxima.len() >= 3, "{maxima:?}");
    for pair in maxima.windows(2) {
        let ratio = pair[1] / pair[0];
        // Amplitudes of 1e-4: the law's curvature changes the rate by about that much.
        assert!(
            (ratio - expected).abs() < 1e-3,
            "{ratio} against {expected}"
        );
    }
}

fn cubic_exact(zeta: f64, mu_s: f64, k1: f64, k3: f64, vb: f64) -> (MotionClass, f64, f64) {
    let e = belt(zeta, mu_s, vb, FrictionLaw::Cubic { k1, k3 })
        .with_initial(State { y: 0.0, v: vb })
        .unwrap();
    let s = e.steady().unwrap();
    let period = s.self_excited.and_then(|c| c.period).unwrap_or(f64::NAN);
    (s.class, 0.5 * (s.y_max - s.y_min), period)
}

/// The approximation against the exact cycle at twelve belt speeds from vb_H/13 to
/// 12 vb_H/13 (vb_H where steady sliding turns stable), for three sizes ε = k1 of the law's
/// fall (k3 = k1/2 or less, ζ ≤ k1/10, μs = 1): the motion (stick-slip or pure slip) agrees at
/// every speed, and the amplitude's largest relative error is, as measured (release build,
/// `cargo test -p stickslip --release --test belt_theory -- --nocapture`), 3.01e-3 at
/// ε = 0.05, 7.52e-3 at ε = 0.1 and 2.81e-2 at ε = 0.2: it grows about as ε^1.5, the order
/// the first-order analysis leaves (its stop lasts √(2πb)). The bounds are those numbers
/// rounded up in their third digit. The period is 2π to this order only: the exact one is
/// longer by up to 1.7 % at ε = 0.1 (the stop's length is of order √ε and the slide's lost
/// arc cancels it only to that order).
#[test]
fn thomsen_fidlin_against_the_exact_cycle() {
    for (zeta, k1, k3, bound) in [
        (0.0, 0.05, 0.02, 3.02e-3),
        (0.01, 0.1, 0.05, 7.53e-3),
        (0.02, 0.2, 0.1, 2.82e-2),
    ] {
        let top = CubicBeltApproximation::new(zeta, 1.0, k1, k3, 0.1)
            .unwrap()
            .vb_hopf
            .unwrap();
        assert!((top - ((k1 - 2.0 * zeta) / (3.0 * k3)).sqrt()).abs() < 1e-15);
        let mut worst = 0.0f64;
        for i in 1..=12 {
            let vb = top * i as f64 / 13.0;
            let a = CubicBeltApproximation::new(zeta, 1.0, k1, k3, vb).unwrap();
            let (class, amplitude, period) = cubic_exact(zeta, 1.0, k1, k3, vb);
            let expected = match a.motion {
                CubicBeltMotion::StickSlip => MotionClass::StickSlipCycle,
                CubicBeltMotion::PureSlip => MotionClass::PureSlipCycle,
                CubicBeltMotion::SteadySliding => MotionClass::SteadySliding,
            };
            assert_eq!(class, expected, "ε = {k1}, vb = {vb}");
            let error = ((a.amplitude - amplitude) / amplitude).abs();
            worst = worst.max(error);
            assert!(
                error <= bound,
                "ε = {k1}, vb = {vb}: {} against {amplitude} ({error:.3e})",
                a.amplitude
            );
            assert!((period / a.period.unwrap() - 1.0).abs() < 0.06);
            // The mirror belt has the mirror cycle.
            let mirror = CubicBeltApproximation::new(zeta, 1.0, k1, k3, -vb).unwrap();
            assert_eq!(mirror.amplitude, a.amplitude);
        }
        // The bound is the measurement, not a loose fence.
        assert!(worst > 0.9 * bound, "ε = {k1}: worst {worst:.3e}");
    }
    // Steady sliding past the Hopf speed; refused input names the key.
    let fast = CubicBeltApproximation::new(0.01, 1.0, 0.1, 0.05, 1.0).unwrap();
    assert_eq!(fast.motion, CubicBeltMotion::SteadySliding);
    assert_eq!((fast.amplitude, fast.period), (0.0, None));
    assert!(CubicBeltApproximation::new(0.01, 1.0, 0.1, 0.05, 0.0).is_err());
    assert!(CubicBeltApproximation::new(0.0, 1.0, 5.0, 0.01, 0.3).is_err());
}
