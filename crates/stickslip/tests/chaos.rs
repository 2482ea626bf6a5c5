//! Classes that mean something: motions that do not repeat are measured by their largest
//! Lyapunov exponent (`chaotic` when it is positive beyond its error), grids map the exponent,
//! and an experiment finds its periodic orbits and exponents.

use stickslip::scan::{Axis, Grid};
use stickslip::stability::{
    find_periodic_orbit, lyapunov_exponents, lyapunov_exponents_monitored, steady_exponent,
    ExponentValue, LyapunovOptions, LyapunovReport, NewtonOptions, NonperiodicVerdict, OrbitReport,
    SecondExponent, Stability, StabilityError,
};
use stickslip::steady::{
    exact_solver, steady_state, steady_state_from, MotionClass, SteadyOptions, SteadyReport,
};
use stickslip::{
    Circuit, DiodePair, Error, ExactSolver, Experiment, Parameter, Params, Solver, State,
};
use stickslip_testkit::paper_shockley;

/// ζ = 0, μs = 3, β = 9: chaotic from rest for w in 0.29–0.37 and 0.46–0.48, periodic
/// elsewhere in 0.2–0.55 (the literature's setting).
fn literature(w: f64) -> Params {
    Params::new(0.0, w, 9.0).unwrap().with_mu_s(3.0).unwrap()
}

fn settle(params: Params, options: &SteadyOptions) -> stickslip::SteadyState {
    steady_state_from(&exact_solver, &params, State::default(), options).unwrap()
}

fn no_spectrum() -> SteadyOptions {
    SteadyOptions::default().with_spectrum(false)
}

#[test]
fn a_motion_that_does_not_repeat_is_chaotic_when_its_exponent_is_positive() {
    for w in [0.30, 0.33, 0.47] {
        let s = settle(literature(w), &no_spectrum());
        assert_eq!(s.period, None, "w {w}");
        assert_eq!(s.class, MotionClass::Chaotic, "w {w}");
        let c = s.lyapunov.as_ref().expect("measured");
        assert_eq!(c.verdict, NonperiodicVerdict::Chaotic);
        let l = c.exponents.largest;
        assert!(c.exponents.converged);
        assert!(
            l.per_tau > 4.0 * l.error_per_tau && l.per_tau > 1e-3,
            "w {w}: {l:?}"
        );
        assert_eq!(c.exponents.cap, SteadyOptions::DEFAULT_LYAPUNOV.periods);
        // Sequential: decided at one of its looks, before the cap.
        assert!(c.exponents.periods < c.exponents.cap);
        assert!(SteadyOptions::DEFAULT_LYAPUNOV
            .looks()
            .contains(&c.exponents.periods));
        // Measured from the final state of the record, with the default options: the same
        // numbers as a direct measurement.
        let direct =
            lyapunov_exponents(&s.params, s.final_state(), &SteadyOptions::DEFAULT_LYAPUNOV)
                .unwrap();
        assert_eq!(direct, c.exponents);
        // The report carries the exponent's keys.
        let json = serde_json::to_value(SteadyReport::from(&s)).unwrap();
        assert_eq!(json["class"], "chaotic");
        assert_eq!(json["verdict"], "chaotic");
        assert_eq!(json["lambda1"].as_f64(), Some(l.per_tau));
        assert_eq!(json["lambda1_error"].as_f64(), Some(l.error_per_tau));
        assert_eq!(json["lambda1_per_period"].as_f64(), Some(l.per_period));
        assert_eq!(json["lambda1_periods"], c.exponents.periods);
        assert_eq!(json["lambda1_converged"], true);
    }
}

#[test]
fn the_issues_slow_point_settles_on_its_period_1_orbit() {
    // (ζ, μs, w, β) = (0, 2.5, 0.4227, 3.627) contracts onto a period-1 orbit with multiplier
    // 0.99911: the plain iteration reaches it after 13 806 periods, so within 5000 it does not
    // repeat; Newton's method finds the orbit, and the trajectory's steps pass the checks of
    // its basin, well within the cap.
    let params = Params::new(0.0, 0.4227, 3.627)
        .unwrap()
        .with_mu_s(2.5)
        .unwrap();
    let s = settle(params, &no_spectrum());
    assert_eq!(s.period, Some(1));
    assert_eq!(s.class, MotionClass::PeriodicStick);
    assert!(s.periods_to_settle < 5000, "{}", s.periods_to_settle);
    assert!(s.lyapunov.is_none());
    // The plain iteration, run long enough at a tighter tolerance, records the same cycle.
    let long = no_spectrum()
        .with_newton(false)
        .with_tolerance(1e-12)
        .unwrap()
        .with_max_periods(40_000)
        .unwrap();
    let plain = settle(params, &long);
    assert_eq!((plain.period, plain.class), (s.period, s.class));
    assert!(plain.periods_to_settle > 5000);
    assert!(
        (plain.gain - s.gain).abs() <= 1e-8 * s.gain,
        "{} against {}",
        plain.gain,
        s.gain
    );
    // Without Newton, within the default cap: no period, and not chaotic either.
    let s = settle(params, &no_spectrum().with_newton(false));
    assert_eq!(s.period, None);
    assert_eq!(s.class, MotionClass::Undecided);
    let c = s.lyapunov.as_ref().expect("measured");
    assert_ne!(c.verdict, NonperiodicVerdict::Chaotic);
    assert!(
        c.exponents.largest.per_tau < 0.0,
        "{:?}",
        c.exponents.largest
    );
    let json = serde_json::to_value(SteadyReport::from(&s)).unwrap();
    assert_eq!(json["class"], "undecided");
    assert_eq!(json["verdict"], c.verdict.label());
    assert!(json["lambda1"].as_f64().unwrap() < 0.0);
}

#[test]
fn motions_that_repeat_are_not_measured_and_unchanged() {
    for (params, class) in [
        (literature(0.25), MotionClass::PeriodicStick),
        (literature(0.40), MotionClass::PeriodicStick),
        (
            Params::new(0.046816, 0.9, 1.6).unwrap(),
            MotionClass::Sliding,
        ),
        (
            Params::new(0.046816, 0.7, 1.0).unwrap(),
            MotionClass::Static,
        ),
    ] {
        let measured = settle(params, &SteadyOptions::default());
        let plain = settle(
            params,
            &SteadyOptions::default().with_lyapunov(None).unwrap(),
        );
        assert_eq!(measured.class, class);
        assert!(measured.lyapunov.is_none());
        assert_eq!(measured, plain, "the option changes nothing for {params:?}");
        let json = serde_json::to_value(SteadyReport::from(&measured)).unwrap();
        for key in ["lambda1", "lambda1_error", "verdict", "lambda1_periods"] {
            assert!(json.get(key).is_none(), "{key} in {json}");
        }
    }
}

#[test]
fn without_the_option_or_a_tangent_dynamics_nothing_is_measured() {
    let params = literature(0.33);
    let off = settle(params, &no_spectrum().with_lyapunov(None).unwrap());
    assert_eq!(
        (off.class, off.lyapunov.is_none()),
        (MotionClass::Undecided, true)
    );
    // A solver that does not say it follows the exact model is not measured.
    struct Hidden(ExactSolver);
    impl Solver for Hidden {
        fn params(&self) -> &Params {
            self.0.params()
        }
        fn time(&self) -> f64 {
            self.0.time()
        }
        fn state(&self) -> State {
            self.0.state()
        }
        fn phase(&self) -> stickslip::Phase {
            self.0.phase()
        }
        fn drive(&self, tau: f64) -> f64 {
            self.0.drive(tau)
        }
        fn advance(&mut self, t_end: f64) -> stickslip::Result<Option<stickslip::Event>> {
            self.0.advance(t_end)
        }
        fn interval(&self) -> (f64, f64) {
            self.0.interval()
        }
        fn dense(&self, tau: f64) -> stickslip::Sample {
            self.0.dense(tau)
        }
        fn stats(&self) -> stickslip::Stats {
            self.0.stats()
        }
        fn is_exact(&self) -> bool {
            false
        }
    }
    let options = no_spectrum().with_max_periods(300).unwrap();
    let mut hidden = Hidden(ExactSolver::new(params, State::default()));
    let s = steady_state(&mut hidden, &options).unwrap();
    assert_eq!(
        (s.class, s.lyapunov.is_none()),
        (MotionClass::Undecided, true)
    );
    // The exact solver itself, through the same function, is measured.
    let mut exact = ExactSolver::new(params, State::default());
    let s = steady_state(&mut exact, &options).unwrap();
    assert_eq!(s.class, MotionClass::Chaotic);
    // Shockley diodes: the stiff solver is not the exact model, but its factory has the
    // smooth law's tangent dynamics (tests/smooth_stability.rs compares their exponent).
    let shockley = paper_shockley();
    let s = shockley
        .steady_with(
            &shockley
                .steady_options()
                .with_spectrum(false)
                .with_max_periods(3)
                .unwrap(),
        )
        .unwrap();
    assert_eq!((s.period, s.lyapunov.is_some()), (None, true));
}

#[test]
fn invalid_measurement_options_are_refused() {
    let bad = LyapunovOptions {
        blocks: 3,
        ..SteadyOptions::DEFAULT_LYAPUNOV
    };
    assert!(matches!(
        SteadyOptions::default().with_lyapunov(Some(bad)),
        Err(Error::InvalidOption {
            option: stickslip::OptionKey::Blocks,
            ..
        })
    ));
}

#[test]
fn stops_are_counted_while_measured() {
    let options = LyapunovOptions {
        transient_periods: 200,
        periods: 400,
        ..LyapunovOptions::default()
    };
    let zeta = Circuit::paper().scales().zeta();
    for (w, beta, per_period) in [(0.7, 1.2, 2.0), (0.9, 1.6, 0.0), (0.15, 2.0, 4.0)] {
        let params = Params::new(zeta, w, beta).unwrap();
        let l = lyapunov_exponents(&params, State::default(), &options).unwrap();
        assert_eq!(l.stops_per_period(), per_period, "w {w} beta {beta}");
    }
    // At rest for ever: no stop.
    let rest = Params::new(zeta, 0.7, 0.5).unwrap();
    let l = lyapunov_exponents(&rest, State::default(), &options).unwrap();
    assert_eq!((l.stops, l.largest.per_tau), (0, 0.0));
}

#[test]
fn the_monitor_sees_every_period_and_can_stop_the_measurement() {
    let params = literature(0.33);
    let options = LyapunovOptions {
        transient_periods: 300,
        periods: 2000,
        blocks: 20,
        significance: 4.0,
        sequential: false,
    };
    let seen = std::sync::Mutex::new(Vec::new());
    let watched = lyapunov_exponents_monitored(&params, State::default(), &options, &|d, t| {
        seen.lock().unwrap().push((d, t));
        true
    })
    .unwrap();
    assert_eq!(
        watched,
        lyapunov_exponents(&params, State::default(), &options).unwrap()
    );
    let seen = seen.into_inner().unwrap();
    assert_eq!(seen.last(), Some(&(2300, 2300)));
    assert!(seen.windows(2).all(|w| w[0].0 < w[1].0));
    let stopped =
        lyapunov_exponents_monitored(&params, State::default(), &options, &|d: usize, _| d < 500);
    assert!(matches!(
        stopped,
        Err(Error::Cancelled {
            done: 500,
            total: 2300
        })
    ));
}

#[test]
fn the_exponent_of_a_steady_state_is_its_orbits_or_its_measurement() {
    let options = LyapunovOptions {
        transient_periods: 100,
        periods: 4000,
        ..LyapunovOptions::default()
    };
    // Periodic: ln|μ₁|/(pT) of the orbit, error 0; a tangent measurement agrees.
    for w in [0.25, 0.40, 0.52] {
        let params = literature(w);
        let s = settle(params, &no_spectrum());
        let p = s.period.expect("periodic");
        let lambda = steady_exponent(&s, &options).unwrap().unwrap();
        let orbit =
            find_periodic_orbit(&params, s.strobes[0], p, &NewtonOptions::default()).unwrap();
        assert_eq!(lambda.per_tau, orbit.exponent());
        assert_eq!((lambda.error_per_tau, lambda.error_per_period), (0.0, 0.0));
        assert!((lambda.per_period - lambda.per_tau * params.drive_period()).abs() < 1e-15);
        let measured = lyapunov_exponents(&params, s.final_state(), &options).unwrap();
        let tolerance = 1e-6 * lambda.per_tau.abs() + 4.0 * measured.largest.error_per_tau;
        assert!(
            (measured.largest.per_tau - lambda.per_tau).abs() <= tolerance,
            "w {w}: {} against {}",
            measured.largest.per_tau,
            lambda.per_tau
        );
    }
    // Rest: the multiplier 1 of a continuum of rest positions, exponent 0.
    let rest = settle(Params::new(0.05, 0.7, 0.5).unwrap(), &no_spectrum());
    assert_eq!(rest.class, MotionClass::Static);
    assert_eq!(
        steady_exponent(&rest, &options).unwrap().unwrap().per_tau,
        0.0
    );
    // Not repeating: the steady state's own measurement.
    let chaotic = settle(literature(0.33), &no_spectrum());
    assert_eq!(
        steady_exponent(&chaotic, &options).unwrap(),
        Some(chaotic.lyapunov.as_ref().unwrap().exponents.largest)
    );
}

#[test]
fn a_grid_maps_the_exponent_and_the_chaotic_class() {
    let experiment = Experiment::dimensionless(0.0, 0.3, 9.0)
        .unwrap()
        .with_mu_s(3.0)
        .unwrap();
    let w = Axis::new(Parameter::W, vec![0.25, 0.30, 0.33, 0.40, 0.47]).unwrap();
    let beta = Axis::new(Parameter::Beta, vec![9.0, 2.0]).unwrap();
    let options = LyapunovOptions {
        transient_periods: 100,
        periods: 2000,
        ..LyapunovOptions::default()
    };
    let grid = Grid::new(&experiment, w.clone(), beta.clone())
        .unwrap()
        .lyapunov(options)
        .unwrap();
    let one = grid.clone().threads(1).unwrap().run(&()).unwrap();
    let two = grid.threads(2).unwrap().run(&()).unwrap();
    assert_eq!(one, two, "the same map for any number of threads");
    for point in &one.points {
        let lambda = point.lyapunov.expect("every point has its exponent");
        let beta = point.params.beta;
        if beta == 2.0 {
            // β ≤ μs: never leaves rest.
            assert_eq!((point.class, lambda.per_tau), (MotionClass::Static, 0.0));
        } else if point.period.is_none() {
            assert_eq!(point.class, MotionClass::Chaotic, "{point:?}");
            assert!(lambda.per_tau > 4.0 * lambda.error_per_tau);
        } else {
            assert!(
                lambda.per_tau < 0.0 && lambda.error_per_tau == 0.0,
                "{point:?}"
            );
        }
    }
    let chaotic = one
        .points
        .iter()
        .filter(|p| p.class == MotionClass::Chaotic)
        .count();
    assert_eq!(chaotic, 3);
    // Without the option, the classes are the same and no exponent is computed.
    let plain = Grid::new(&experiment, w, beta).unwrap().run(&()).unwrap();
    for (a, b) in plain.points.iter().zip(&one.points) {
        assert_eq!((a.class, a.period, a.lyapunov), (b.class, b.period, None));
    }
    // With Shockley diodes the map is of the stiff solver's tangent dynamics
    // (tests/smooth_stability.rs).
}

#[test]
fn an_experiment_finds_its_orbits_and_exponents() {
    let newton = NewtonOptions::default();
    let steady = SteadyOptions::default();
    let e = Experiment::dimensionless(0.0, 0.40, 9.0)
        .unwrap()
        .with_mu_s(3.0)
        .unwrap();
    // Automatically: the period-3 orbit that the motion from rest settles on.
    let auto = e.periodic_orbit(None, 0, &steady, &newton, &()).unwrap();
    assert_eq!((auto.period, auto.stability), (3, Stability::Stable));
    assert!(auto.iterations <= 6);
    // With the period given, from the state after a transient: the same orbit, up to the
    // strobe at which it is entered.
    let given = e
        .periodic_orbit(Some(3), 3000, &steady, &newton, &())
        .unwrap();
    assert_eq!(given.period, 3);
    assert!((given.multipliers[0].modulus() - auto.multipliers[0].modulus()).abs() < 1e-9);
    // The transient is watched, and can be stopped.
    let stopped = e.periodic_orbit(Some(3), 3000, &steady, &newton, &|d: usize, _| d < 2000);
    assert!(matches!(
        stopped,
        Err(Error::Cancelled {
            done: 2000,
            total: 3000
        })
    ));
    assert!(matches!(
        e.periodic_orbit(Some(0), 0, &steady, &newton, &()),
        Err(Error::InvalidParameter { name: "period", .. })
    ));
    // Asked for period 2 in a chaotic window, Newton's method lands on the unstable period-1
    // orbit: the report says so, and the multiplier is that of two periods.
    let chaotic = e.clone().with_w(0.33).unwrap();
    let once = chaotic
        .periodic_orbit(Some(1), 2000, &steady, &newton, &())
        .unwrap();
    let twice = chaotic
        .periodic_orbit(Some(2), 2000, &steady, &newton, &())
        .unwrap();
    assert_eq!(once.stability, Stability::Unstable);
    let params = chaotic.params().unwrap();
    let r1 = OrbitReport::new(&once, &params).unwrap();
    let r2 = OrbitReport::new(&twice, &params).unwrap();
    assert_eq!((r1.least_period, r2.period, r2.least_period), (1, 2, 1));
    let square = once.multipliers[0].modulus().powi(2);
    assert!((twice.multipliers[0].modulus() - square).abs() < 1e-8 * square);
    // A chaotic motion has no period to start from.
    assert!(matches!(
        chaotic.periodic_orbit(None, 0, &steady, &newton, &()),
        Err(Error::Stability(StabilityError::NoPeriod {
            periods_run: 5000,
            verdict: Some(NonperiodicVerdict::Chaotic),
            ..
        }))
    ));
    let options = LyapunovOptions {
        transient_periods: 500,
        periods: 2000,
        ..LyapunovOptions::default()
    };
    let c = chaotic.lyapunov(&options, &()).unwrap();
    assert_eq!(c.verdict, NonperiodicVerdict::Chaotic);
    assert_eq!(
        c.exponents,
        lyapunov_exponents(&chaotic.params().unwrap(), State::default(), &options).unwrap()
    );
    // Shockley diodes: the same tools on the stiff solver's tangent dynamics.
    let shockley = Experiment::paper()
        .with_shockley(DiodePair::one_n4148())
        .unwrap()
        .with_w(0.9)
        .unwrap()
        .with_beta(2.0)
        .unwrap();
    let orbit = shockley
        .periodic_orbit(None, 0, &steady, &newton, &())
        .unwrap();
    assert_eq!((orbit.period, orbit.stability), (1, Stability::Stable));
    let c = shockley.lyapunov(&options, &()).unwrap();
    assert_eq!(c.verdict, NonperiodicVerdict::Contracting);
    assert!(
        (c.exponents.largest.per_tau - orbit.exponent()).abs()
            <= 4.0 * c.exponents.largest.error_per_tau + 1e-6 * orbit.exponent().abs(),
        "{:?} vs {}",
        c.exponents.largest,
        orbit.exponent()
    );
}

#[test]
fn reports_write_minus_infinity_as_null_with_its_reason_and_count_real_stops() {
    let zeta = Circuit::paper().scales().zeta();
    // A stick-slip orbit: two stops per period, one multiplier exactly 0.
    let params = Params::new(zeta, 0.7, 1.2).unwrap();
    let s = settle(params, &no_spectrum());
    let orbit = find_periodic_orbit(&params, s.strobes[0], 1, &NewtonOptions::default()).unwrap();
    let r = OrbitReport::new(&orbit, &params).unwrap();
    assert_eq!((r.period, r.least_period), (1, 1));
    assert_eq!(r.stops_per_period, 2.0);
    // One multiplier vanishes (to the rounding of det M): a stop erases δy'.
    assert!(
        r.stable && r.moduli[1] < 1e-12 && r.moduli[0] < 1.0,
        "{r:?}"
    );
    assert_eq!(r.lambda1, ExponentValue::Finite(orbit.exponent()));
    let json = serde_json::to_value(&r).unwrap();
    assert_eq!(json["stability"], "stable");
    assert_eq!(json["multipliers"][0]["im"], 0.0);
    assert_eq!(json["events"].as_array().unwrap().len(), orbit.events.len());
    assert!(json["events"]
        .as_array()
        .unwrap()
        .iter()
        .all(|e| ["turn", "stick", "slip"].contains(&e["kind"].as_str().unwrap())));
    // Its Lyapunov measurement: λ₂ = −∞, written "-inf", with the reason.
    let options = LyapunovOptions {
        transient_periods: 100,
        periods: 400,
        ..LyapunovOptions::default()
    };
    let c = Experiment::paper()
        .with_w(0.7)
        .unwrap()
        .with_beta(1.2)
        .unwrap()
        .lyapunov(&options, &())
        .unwrap();
    assert!(matches!(
        c.exponents.second,
        SecondExponent::MinusInfinity { .. }
    ));
    let json = serde_json::to_value(LyapunovReport::new(&c, &options, &params).unwrap()).unwrap();
    assert_eq!(json["lambda2"], serde_json::Value::Null);
    assert_eq!(json["lambda2_error"], serde_json::Value::Null);
    assert!(json["lambda2_reason"].as_str().unwrap().contains("stopped"));
    // It has reached its period-1 orbit: periodic, and what the exponent says beside it.
    assert_eq!(json["class"], "periodic");
    assert_eq!(json["period"], 1);
    assert_eq!(json["verdict"], "contracting");
    assert_eq!(json["stops_per_period"], 2.0);
    // A sliding motion: λ₂ finite.
    let sliding = Params::new(zeta, 0.9, 1.6).unwrap();
    let c =
        stickslip::stability::classify_nonperiodic(&sliding, State::default(), &options).unwrap();
    let json = serde_json::to_value(LyapunovReport::new(&c, &options, &sliding).unwrap()).unwrap();
    assert!(json["lambda2"].as_f64().unwrap() < json["lambda1"].as_f64().unwrap());
    assert_eq!(json["lambda2_reason"], serde_json::Value::Null);
    assert_eq!(json["stops_per_period"], 0.0);
}
