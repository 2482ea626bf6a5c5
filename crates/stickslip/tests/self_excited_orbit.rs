//! The orbit and the Lyapunov exponents of a self-excited belt (β = 0, vb ≠ 0): the period is
//! the cycle's own (the undamped Coulomb belt's against its closed form), the multipliers 1
//! (autonomous) and exactly 0 (every stop ends in the same state), steady sliding with the
//! eigenvalues of its linearisation; `lyapunov` names a limit cycle or an equilibrium, never
//! a torus; a pure-slip cycle's multiplier against Richardson differences of its return map,
//! and a stick-slip cycle's return map flat by the same differences.

use stickslip::experiment::Experiment;
use stickslip::friction::FrictionLaw;
use stickslip::stability::{LyapunovOptions, NonperiodicVerdict, SecondExponent, Stability};
use stickslip::steady::{MotionClass, SlidingStability};
use stickslip::theory::{CoulombBeltCycle, SteadySliding};
use stickslip::{Error, Params, State};

fn belt(zeta: f64, mu_s: f64, vb: f64) -> Experiment {
    Experiment::dimensionless(zeta, 1.0, 0.0)
        .unwrap()
        .with_mu_s(mu_s)
        .unwrap()
        .with_vb(vb)
        .unwrap()
}

#[test]
fn the_undamped_coulomb_belts_orbit_is_its_closed_form_cycle() {
    for (mu_s, vb) in [(1.5, 0.5), (2.0, -0.3)] {
        let e = belt(0.0, mu_s, vb);
        let orbit = e.self_excited_orbit(&e.steady_options()).unwrap();
        let exact = CoulombBeltCycle::new(mu_s, vb).unwrap();
        assert_eq!(orbit.class, MotionClass::StickSlipCycle);
        let period = orbit.cycle_period_tau.unwrap();
        assert!(
            (period - exact.period).abs() < 1e-12,
            "{period} against {}",
            exact.period
        );
        assert!((orbit.y_max - exact.y_max).abs() < 1e-12);
        assert!((orbit.y_min - exact.y_min).abs() < 1e-12);
        assert!((orbit.stick_fraction - exact.stick_fraction).abs() < 1e-12);
        // A dimensionless model has no seconds.
        assert_eq!(orbit.cycle_period_s, None);
        // Every stop ends where the spring reaches the static limit (ζ = 0: y = ±μs).
        assert_eq!(orbit.release_y, Some(vb.signum() * mu_s));
        assert!((orbit.release_y.unwrap() - exact.release_y).abs() < 1e-12);
        let [trivial, other] = orbit.multipliers.unwrap();
        assert_eq!(
            [trivial.re, trivial.im, other.re, other.im],
            [1.0, 0.0, 0.0, 0.0]
        );
        assert_eq!(orbit.stability, Some(Stability::Stable));
        assert!(orbit.summary.starts_with("self-excited cycle, period "));
    }
}

#[test]
fn steady_sliding_is_the_equilibrium_with_its_eigenvalues() {
    let e = belt(0.05, 1.5, 2.0);
    let orbit = e.self_excited_orbit(&e.steady_options()).unwrap();
    assert_eq!(orbit.class, MotionClass::SteadySliding);
    assert_eq!((orbit.cycle_period_tau, orbit.multipliers), (None, None));
    let sliding = SteadySliding::new(&e.params().unwrap()).unwrap();
    assert_eq!(orbit.sliding, sliding);
    assert_eq!(orbit.sliding_stability, SlidingStability::Stable);
    assert_eq!(orbit.stability, Some(Stability::Stable));
    // λ² + dλ + 1 = 0 at both eigenvalues.
    for l in orbit.sliding_eigenvalues {
        let (re, im) = (l.re * l.re - l.im * l.im, 2.0 * l.re * l.im);
        let residual = (re + sliding.damping * l.re + 1.0).hypot(im + sliding.damping * l.im);
        assert!(residual < 1e-14, "{l:?}: {residual}");
        assert_eq!(l.re, sliding.growth_rate);
    }
}

#[test]
fn a_driven_experiment_has_no_self_excited_orbit() {
    let e = Experiment::dimensionless(0.05, 0.5, 1.0)
        .unwrap()
        .with_vb(0.3)
        .unwrap();
    let err = e.self_excited_orbit(&e.steady_options()).unwrap_err();
    assert!(
        matches!(err, Error::InvalidParameter { name: "beta", .. }),
        "{err}"
    );
}

#[test]
fn lyapunov_names_a_limit_cycle_and_steady_sliding_not_a_torus() {
    let options = LyapunovOptions {
        transient_periods: 200,
        periods: 2000,
        ..Default::default()
    };
    // A damped stick-slip cycle: λ1 = 0 within its error, λ2 = −∞ (stops).
    let c = belt(0.05, 1.5, 0.3).lyapunov(&options, &()).unwrap();
    let l = c.exponents.largest;
    assert!(
        l.per_tau.abs() <= options.significance * l.error_per_tau,
        "{l:?}"
    );
    assert!(matches!(
        c.exponents.second,
        SecondExponent::MinusInfinity { .. }
    ));
    assert_eq!(c.verdict, NonperiodicVerdict::LimitCycle);
    // Steady sliding: both exponents the linearisation's rate −d/2.
    let e = belt(0.05, 1.5, 2.0);
    let c = e.lyapunov(&options, &()).unwrap();
    assert_eq!(c.verdict, NonperiodicVerdict::Equilibrium);
    let rate = SteadySliding::new(&e.params().unwrap())
        .unwrap()
        .growth_rate;
    let SecondExponent::Finite(second) = c.exponents.second else {
        panic!("{c:?}")
    };
    for x in [c.exponents.largest, second] {
        assert!(
            x.per_tau < 0.0 && (x.per_tau - rate).abs() < 1e-4,
            "{x:?} against {rate}"
        );
    }
}

/// The return map on the turning point of y's maximum: P(y) = the next maximum of y of the
/// motion from (y, 0) (a maximum: y above steady sliding), by the plain solver of `e` (no
/// tangent). The turning point is bracketed by the solver's advances, located on its dense
/// output by bisection, and y taken there from a fresh solver run to that instant (a step
/// end, to the solver's tolerance; y is stationary there, so the instant's error enters to
/// second order).
fn return_map(e: &Experiment, params: &Params, y: f64) -> f64 {
    let dynamics = e.dynamics().unwrap();
    let start = State { y, v: 0.0 };
    let mut solver = dynamics.solver(params, start).unwrap();
    // 0: leaving the maximum (y' < 0 next), 1: past the minimum (y' > 0), 2: done.
    let mut stage = 0;
    let mut turn = None;
    while turn.is_none() {
        assert!(solver.time() < 100.0, "no turning point from y = {y}");
        let target = solver.time() + 0.05;
        let before = solver.state().v;
        solver.advance(target).unwrap();
        let v = solver.state().v;
        match stage {
            0 if v < 0.0 => stage = 1,
            1 if v > 0.0 => stage = 2,
            2 if v <= 0.0 && before > 0.0 => {
                let (mut a, mut b) = solver.interval();
                for _ in 0..200 {
                    let m = 0.5 * (a + b);
                    if m <= a || m >= b {
                        break;
                    }
                    if solver.dense(m).v > 0.0 {
                        a = m;
                    } else {
                        b = m;
                    }
                }
                turn = Some(0.5 * (a + b));
            }
            _ => {}
        }
    }
    let mut fresh = dynamics.solver(params, start).unwrap();
    stickslip::solver::run_until(fresh.as_mut(), turn.unwrap(), |_| {}).unwrap();
    fresh.state().y
}

/// P'(y) by central differences with steps h and h/2, Richardson-extrapolated.
fn return_map_slope(e: &Experiment, params: &Params, y: f64, h: f64) -> f64 {
    let central =
        |h: f64| (return_map(e, params, y + h) - return_map(e, params, y - h)) / (2.0 * h);
    (4.0 * central(h / 2.0) - central(h)) / 3.0
}

fn cubic_belt(vb: f64) -> Experiment {
    belt(0.05, 1.5, vb)
        .with_law(FrictionLaw::Cubic { k1: 0.5, k3: 0.3 })
        .unwrap()
        .with_initial(State { y: 1.25, v: 0.05 })
        .unwrap()
}

#[test]
fn a_pure_slip_cycles_multiplier_is_its_return_maps_derivative() {
    for e in [cubic_belt(0.6), cubic_belt(0.65)] {
        let orbit = e.self_excited_orbit(&e.steady_options()).unwrap();
        assert_eq!(orbit.class, MotionClass::PureSlipCycle, "{}", orbit.summary);
        assert_eq!(orbit.stick_fraction, 0.0);
        let [trivial, other] = orbit.multipliers.expect("a pure-slip cycle's multipliers");
        assert_eq!((trivial.re, trivial.im, other.im), (1.0, 0.0, 0.0));
        let params = e.params().unwrap();
        // The return map's fixed point is the cycle's maximum.
        let y = orbit.y_max;
        assert!((return_map(&e, &params, y) - y).abs() < 1e-8);
        let slope = return_map_slope(&e, &params, y, 1e-5);
        assert!(
            (other.re - slope).abs() < 1e-6,
            "μ2 = {} against the return map's {slope}",
            other.re
        );
        // An attracting cycle (it was found by running onto it).
        assert!(0.0 < other.re && other.re < 1.0, "{}", other.re);
        assert_eq!(orbit.stability, Some(Stability::Stable));
    }
}

#[test]
fn a_stick_slip_cycles_return_map_is_flat() {
    let cases = [
        belt(0.05, 1.5, 0.3),
        belt(0.05, 1.5, 0.3)
            .with_law(FrictionLaw::Stribeck {
                vs: 0.5,
                delta: 2.0,
                eta: 0.0,
            })
            .unwrap(),
        cubic_belt(0.3)
            .with_initial(State { y: 0.0, v: 0.0 })
            .unwrap(),
    ];
    for e in cases {
        let orbit = e.self_excited_orbit(&e.steady_options()).unwrap();
        assert_eq!(
            orbit.class,
            MotionClass::StickSlipCycle,
            "{}",
            orbit.summary
        );
        assert_eq!(orbit.multipliers.unwrap()[1].re, 0.0);
        let params = e.params().unwrap();
        let y = orbit.y_max;
        assert!((return_map(&e, &params, y) - y).abs() < 1e-8);
        let slope = return_map_slope(&e, &params, y, 1e-5);
        assert!(slope.abs() < 1e-6, "{}: P' = {slope}", orbit.summary);
    }
}
