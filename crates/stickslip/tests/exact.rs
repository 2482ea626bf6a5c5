//! Tests of the exact solver against closed forms, an independent brute-force integrator and
//! conservation laws.

mod common;

use common::gauss_legendre;
use proptest::prelude::*;
use proptest::test_runner::{Config, RngAlgorithm, TestRng, TestRunner};
use std::f64::consts::PI;
use stickslip::solver::{run_until, sample_at};
use stickslip::{Event, EventKind, ExactSolver, Params, Phase, Solver, State};

/// A deterministic proptest runner: `cases` cases from a fixed seed.
fn runner(cases: u32) -> TestRunner {
    let config = Config {
        cases,
        failure_persistence: None,
        ..Config::default()
    };
    TestRunner::new_with_rng(config, TestRng::from_seed(RngAlgorithm::ChaCha, &[7; 32]))
}

fn events(params: Params, initial: State, t_end: f64) -> Vec<Event> {
    let mut solver = ExactSolver::new(params, initial);
    let mut out = Vec::new();
    run_until(&mut solver, t_end, |e| out.push(*e)).expect("solver runs");
    out
}

// ---------------------------------------------------------------------------------------------
// Closed forms

#[test]
fn free_coulomb_decay_falls_by_two_each_half_period_and_stops_for_good() {
    for &(y0, mu_s) in &[
        (9.3, 1.0),
        (7.5, 1.0),
        (-12.25, 1.0),
        (9.3, 1.5),
        (4.2, 3.0),
    ] {
        let params = Params::new(0.0, 1.0, 0.0).unwrap().with_mu_s(mu_s).unwrap();
        let ev = events(params, State { y: y0, v: 0.0 }, 200.0);
        // Expected: |y| falls by exactly 2 per half period π until the first |y| ≤ μs.
        let mut y = y0;
        let mut k = 0;
        loop {
            k += 1;
            y = -(y - 2.0 * y.signum());
            let e = ev
                .get(k - 1)
                .unwrap_or_else(|| panic!("y0 {y0}: missing event {k}"));
            assert!(
                (e.tau - k as f64 * PI).abs() < 1e-13 * e.tau,
                "y0 {y0} event {k}: {e:?}"
            );
            assert!((e.y - y).abs() < 1e-12, "y0 {y0} event {k}: {} vs {y}", e.y);
            if y.abs() <= mu_s {
                assert_eq!(e.kind, EventKind::Stick, "y0 {y0}");
                break;
            }
            assert_eq!(e.kind, EventKind::Turn, "y0 {y0}");
        }
        assert_eq!(ev.len(), k, "y0 {y0}: the motion stops for good");
    }
}

#[test]
fn free_viscous_decay_matches_closed_form_turning_points() {
    for &zeta in &[0.02, 0.1, 0.5, 0.9] {
        let params = Params::new(zeta, 1.0, 0.0).unwrap();
        let ev = events(params, State { y: 40.0, v: 0.0 }, 400.0);
        let wd = (1.0 - zeta * zeta).sqrt();
        let decay = (-zeta * PI / wd).exp();
        let mut y = 40.0f64;
        for (k, e) in ev.iter().enumerate() {
            let s = -y.signum(); // direction of motion from this turning point
            y = -s - (y + s) * decay;
            assert!(
                (e.tau - (k + 1) as f64 * PI / wd).abs() < 1e-12 * e.tau,
                "zeta {zeta} event {k}: {e:?}"
            );
            assert!(
                (e.y - y).abs() < 1e-11 * 40.0,
                "zeta {zeta} event {k}: {} vs {y}",
                e.y
            );
            if e.kind == EventKind::Stick {
                assert!(y.abs() <= 1.0);
                assert_eq!(k + 1, ev.len());
            }
        }
        assert_eq!(ev.last().unwrap().kind, EventKind::Stick);
    }
}

#[test]
fn overdamped_and_critical_free_motion_creeps_to_the_friction_edge_without_events() {
    for &zeta in &[1.0, 1.0 + 1e-9, 2.0, 25.0] {
        let params = Params::new(zeta, 1.0, 0.0).unwrap();
        let mut solver = ExactSolver::new(params, State { y: 5.0, v: 0.0 });
        let mut n = 0;
        let t_end = 20.0 * zeta.max(1.0);
        run_until(&mut solver, t_end, |_| n += 1).unwrap();
        assert_eq!(n, 0, "zeta {zeta}: no velocity zero in finite time");
        let s = solver.state();
        // y → 1 from above: y − 1 = 4 (r1 e^{r2 t} − r2 e^{r1 t})/(r1 − r2) > 0.
        assert!(s.y > 1.0 && s.y < 1.01, "zeta {zeta}: y = {}", s.y);
        assert!(s.v < 0.0, "zeta {zeta}");
    }
}

#[test]
fn large_drive_approaches_the_linear_rlc_response() {
    for &(zeta, w) in &[(0.05, 0.8), (0.0468, 1.0), (0.2, 1.7), (1.5, 0.5)] {
        let beta = 1e5;
        let params = Params::new(zeta, w, beta).unwrap();
        let mut solver = ExactSolver::new(params, State::default());
        let period = params.drive_period();
        let settle = (60.0 / zeta / period).ceil() * period;
        run_until(&mut solver, settle, |_| {}).unwrap();
        let times: Vec<f64> = (0..=4000)
            .map(|k| settle + period * k as f64 / 4000.0)
            .collect();
        let samples = sample_at(&mut solver, &times, |_| {}).unwrap();
        let (lo, hi) = samples.iter().fold((f64::MAX, f64::MIN), |(lo, hi), s| {
            (lo.min(s.y), hi.max(s.y))
        });
        let gain = (hi - lo) / (2.0 * beta);
        let linear = 1.0 / ((1.0 - w * w).powi(2) + (2.0 * zeta * w).powi(2)).sqrt();
        // Friction shifts the amplitude by O(1/β) relative.
        assert!(
            ((gain - linear) / linear).abs() < 1e-3,
            "zeta {zeta} w {w}: gain {gain} vs linear {linear}"
        );
    }
}

// ---------------------------------------------------------------------------------------------
// No missed events

/// Random parameters over every regime the solver must handle.
fn any_case() -> impl Strategy<Value = (Params, State)> {
    (
        prop_oneof![Just(0.0), 0.0..0.3f64, 0.3..3.0f64, Just(1.0)],
        prop_oneof![0.05..0.6f64, 0.6..1.6f64, 1.6..6.0f64, Just(1.0)],
        prop_oneof![0.0..2.0f64, 2.0..12.0f64],
        0.0..(2.0 * PI),
        prop_oneof![Just(1.0), 1.0..2.0f64],
        -6.0..6.0f64,
        prop_oneof![Just(0.0), -4.0..4.0f64],
    )
        .prop_map(|(zeta, w, beta, phi, mu_s, y0, v0)| {
            let params = Params::new(zeta, w, beta)
                .unwrap()
                .with_phi(phi)
                .unwrap()
                .with_mu_s(mu_s)
                .unwrap();
            (params, State { y: y0, v: v0 })
        })
}

/// Checks every interval the solver advances through: the velocity keeps the sign of the
/// slide on a fine grid (no velocity zero skipped), a stop holds (|force| ≤ μs), and every
/// event obeys the switching rules.
fn check_trajectory(params: Params, initial: State, t_end: f64) -> Result<usize, TestCaseError> {
    let mut solver = ExactSolver::new(params, initial);
    let mut count = 0;
    while solver.time() < t_end {
        let event = solver
            .advance(t_end)
            .map_err(|e| TestCaseError::fail(e.to_string()))?;
        let (from, to) = solver.interval();
        let phase = solver.dense(0.5 * (from + to)).phase;
        let n = ((to - from) * 400.0).clamp(64.0, 40_000.0) as usize;
        let mut scale = 1.0f64;
        for k in 0..=n {
            let tau = from + (to - from) * k as f64 / n as f64;
            let s = solver.dense(tau);
            scale = scale.max(s.y.abs()).max(s.v.abs()).max(params.beta);
            match phase {
                Phase::Stick => {
                    let force = params.drive(tau) - s.y;
                    prop_assert!(
                        force.abs() <= params.mu_s + 1e-9 * scale,
                        "stop does not hold at {tau}: force {force} ({params:?})"
                    );
                }
                _ => {
                    let g = phase.sign() * s.v;
                    prop_assert!(
                        g >= -1e-9 * scale,
                        "missed velocity zero at {tau} in [{from}, {to}]: v = {} ({params:?}, {initial:?})",
                        s.v
                    );
                }
            }
        }
        if let Some(e) = event {
            count += 1;
            let force = params.drive(e.tau) - e.y;
            match e.kind {
                EventKind::Stick => prop_assert!(force.abs() <= params.mu_s + 1e-9 * scale),
                EventKind::Turn => prop_assert!(force.abs() >= params.mu_s - 1e-9 * scale),
                EventKind::Slip => prop_assert!((force.abs() - params.mu_s).abs() <= 1e-9 * scale),
            }
            if e.kind != EventKind::Slip {
                // The velocity at the event, from the closed form of the segment that ends
                // there, is zero to rounding: the event time is located to ~1e-13.
                let v = solver.dense(e.tau).v;
                prop_assert!(v.abs() <= 1e-11 * scale, "velocity {v} at event {e:?}");
            }
        }
    }
    Ok(count)
}

#[test]
fn no_velocity_zero_is_skipped_on_random_parameters() {
    let total = std::cell::Cell::new(0usize);
    runner(3000)
        .run(&any_case(), |(params, initial)| {
            let t_end = (3.0 * params.drive_period()).min(60.0);
            total.set(total.get() + check_trajectory(params, initial, t_end)?);
            Ok(())
        })
        .unwrap();
    let total = total.get();
    assert!(total > 10_000, "the cases exercise many events: {total}");
}

// ---------------------------------------------------------------------------------------------
// An independent oracle: a slow fixed-step RK4 integrator with its own event location.

#[derive(Clone, Copy)]
enum BruteMode {
    Slide(f64),
    Stick,
}

/// Events of the motion from a fine-step RK4 integration with bisection on sign changes; it
/// shares no code with the exact solver.
fn brute_force(p: Params, init: State, t_end: f64, dt: f64) -> Vec<Event> {
    let accel = |t: f64, y: f64, v: f64, s: f64| p.drive(t) - 2.0 * p.zeta * v - y - s;
    let rk4 = |t: f64, y: f64, v: f64, s: f64, h: f64| {
        let (k1y, k1v) = (v, accel(t, y, v, s));
        let (k2y, k2v) = (
            v + 0.5 * h * k1v,
            accel(t + 0.5 * h, y + 0.5 * h * k1y, v + 0.5 * h * k1v, s),
        );
        let (k3y, k3v) = (
            v + 0.5 * h * k2v,
            accel(t + 0.5 * h, y + 0.5 * h * k2y, v + 0.5 * h * k2v, s),
        );
        let (k4y, k4v) = (v + h * k3v, accel(t + h, y + h * k3y, v + h * k3v, s));
        (
            y + h / 6.0 * (k1y + 2.0 * k2y + 2.0 * k3y + k4y),
            v + h / 6.0 * (k1v + 2.0 * k2v + 2.0 * k3v + k4v),
        )
    };
    let force = |t: f64, y: f64| p.drive(t) - y;
    let mut out = Vec::new();
    let (mut t, mut y, mut v) = (0.0, init.y, init.v);
    let mut mode = if v != 0.0 {
        BruteMode::Slide(v.signum())
    } else if force(0.0, y).abs() <= p.mu_s {
        BruteMode::Stick
    } else {
        BruteMode::Slide(force(0.0, y).signum())
    };
    while t < t_end {
        match mode {
            BruteMode::Slide(s) => {
                let (y1, v1) = rk4(t, y, v, s, dt);
                if s * v1 > 0.0 {
                    (t, y, v) = (t + dt, y1, v1);
                    continue;
                }
                // Bisection on the step length for the velocity zero.
                let (mut lo, mut hi) = (0.0, dt);
                for _ in 0..60 {
                    let mid = 0.5 * (lo + hi);
                    if s * rk4(t, y, v, s, mid).1 > 0.0 {
                        lo = mid;
                    } else {
                        hi = mid;
                    }
                }
                let (ye, _) = rk4(t, y, v, s, hi);
                (t, y, v) = (t + hi, ye, 0.0);
                let f = force(t, y);
                if f.abs() <= p.mu_s {
                    mode = BruteMode::Stick;
                    out.push(Event {
                        tau: t,
                        y,
                        kind: EventKind::Stick,
                    });
                } else {
                    mode = BruteMode::Slide(f.signum());
                    out.push(Event {
                        tau: t,
                        y,
                        kind: EventKind::Turn,
                    });
                }
            }
            BruteMode::Stick => {
                if force(t + dt, y).abs() <= p.mu_s {
                    t += dt;
                    continue;
                }
                let (mut lo, mut hi) = (0.0, dt);
                for _ in 0..60 {
                    let mid = 0.5 * (lo + hi);
                    if force(t + mid, y).abs() <= p.mu_s {
                        lo = mid;
                    } else {
                        hi = mid;
                    }
                }
                t += hi;
                mode = BruteMode::Slide(force(t, y).signum());
                out.push(Event {
                    tau: t,
                    y,
                    kind: EventKind::Slip,
                });
            }
        }
    }
    out.retain(|e| e.tau <= t_end);
    out
}

#[test]
fn events_agree_with_an_independent_brute_force_integrator() {
    let compared = std::cell::Cell::new(0usize);
    let mismatches = std::cell::RefCell::new(Vec::new());
    runner(1500)
        .run(&any_case(), |(params, initial)| {
            let t_end = (2.0 * params.drive_period()).min(25.0);
            let exact = events(params, initial, t_end);
            let brute = brute_force(params, initial, t_end, 2e-3);
            // Compare the events both saw well inside the horizon.
            let inside = |e: &&Event| e.tau < t_end - 1e-3;
            let a: Vec<_> = exact.iter().filter(inside).collect();
            let b: Vec<_> = brute.iter().filter(inside).collect();
            let same = a.len() == b.len()
                && a.iter().zip(&b).all(|(x, y)| {
                    x.kind == y.kind && (x.tau - y.tau).abs() < 1e-6 && (x.y - y.y).abs() < 1e-6
                });
            if !same {
                mismatches
                    .borrow_mut()
                    .push((params, initial, a.len(), b.len()));
            }
            compared.set(compared.get() + a.len());
            Ok(())
        })
        .unwrap();
    let (compared, mismatches) = (compared.get(), mismatches.into_inner());
    assert!(compared > 3000, "events compared: {compared}");
    assert!(
        mismatches.is_empty(),
        "{} mismatches, first: {:?}",
        mismatches.len(),
        mismatches.first()
    );
}

// ---------------------------------------------------------------------------------------------
// Conservation

#[test]
fn gauss_legendre_integrates_polynomials_exactly() {
    let gl = gauss_legendre(16);
    let integral: f64 = gl.iter().map(|(x, w)| w * x.powi(30)).sum();
    assert!((integral - 2.0 / 31.0).abs() < 1e-14);
    assert!((gl.iter().map(|(_, w)| w).sum::<f64>() - 2.0).abs() < 1e-14);
}

#[test]
fn energy_balance_over_a_thousand_periods() {
    let gl = gauss_legendre(16);
    for &(zeta, w, beta, mu_s) in &[
        (0.0468, 0.9, 1.6, 1.0),
        (0.0468, 0.6, 1.2, 1.0),
        (0.0468, 0.29, 2.14, 1.0),
        (0.2, 1.43, 5.0, 1.3),
        (0.0, 0.7, 3.0, 1.0),
        (1.7, 0.4, 6.0, 1.0),
    ] {
        let params = Params::new(zeta, w, beta).unwrap().with_mu_s(mu_s).unwrap();
        let initial = State { y: 0.3, v: -0.2 };
        let mut solver = ExactSolver::new(params, initial);
        let t_end = 1000.0 * params.drive_period();
        let (mut work, mut viscous, mut friction) = (0.0, 0.0, 0.0);
        let mut scale = 0.0f64;
        while solver.time() < t_end {
            solver.advance(t_end).unwrap();
            let (from, to) = solver.interval();
            let pieces = ((to - from) / 0.25).ceil().max(1.0) as usize;
            for k in 0..pieces {
                let a = from + (to - from) * k as f64 / pieces as f64;
                let b = from + (to - from) * (k + 1) as f64 / pieces as f64;
                for &(x, wt) in &gl {
                    let tau = 0.5 * (a + b) + 0.5 * (b - a) * x;
                    let s = solver.dense(tau);
                    let h = 0.5 * (b - a) * wt;
                    work += h * params.drive(tau) * s.v;
                    viscous += h * 2.0 * zeta * s.v * s.v;
                    friction += h * s.v.abs();
                    scale = scale.max((h * params.drive(tau) * s.v).abs());
                }
            }
        }
        let change = solver.state().energy() - initial.energy();
        let residual = work - viscous - friction - change;
        let size = work.abs().max(friction).max(viscous);
        assert!(
            residual.abs() <= 1e-9 * size,
            "({zeta}, {w}, {beta}): work {work}, viscous {viscous}, friction {friction}, \
             change {change}, residual {residual}"
        );
    }
}

#[test]
fn deterministic_and_dense_output_matches_stepping() {
    let params = Params::new(0.0468, 0.7, 1.2).unwrap();
    let a = events(params, State::default(), 500.0);
    let b = events(params, State::default(), 500.0);
    assert_eq!(a, b);
    // Dense samples equal the state reached by advancing to the same time.
    let times: Vec<f64> = (0..50).map(|k| 10.0 * k as f64 + 0.37).collect();
    let mut solver = ExactSolver::new(params, State::default());
    let samples = sample_at(&mut solver, &times, |_| {}).unwrap();
    for (tau, s) in times.iter().zip(&samples) {
        let mut other = ExactSolver::new(params, State::default());
        run_until(&mut other, *tau, |_| {}).unwrap();
        let st = other.state();
        assert!(
            (st.y - s.y).abs() < 1e-12 && (st.v - s.v).abs() < 1e-12,
            "at {tau}"
        );
    }
}

#[test]
fn secular_resonance_without_damping_runs() {
    // ζ = 0, w = 1: the particular solution grows like τ; with β > 4/π the amplitude grows
    // without bound at the rate (β − 4/π)/2 per unit time (energy balance of the
    // fundamental), so after many periods peak/τ approaches that rate.
    let beta = 3.0;
    let params = Params::new(0.0, 1.0, beta).unwrap();
    let mut solver = ExactSolver::new(params, State::default());
    let t_end = 400.0 * 2.0 * PI;
    let mut last_turn = 0.0f64;
    run_until(&mut solver, t_end, |e| last_turn = e.y.abs()).unwrap();
    let rate = last_turn / t_end;
    let expected = (beta - 4.0 / PI) / 2.0;
    assert!(
        (rate - expected).abs() / expected < 0.01,
        "rate {rate} vs {expected}"
    );
}

// ---------------------------------------------------------------------------------------------
// Near-tangential double zeros

/// For ζ = 0 and a slide upwards, the initial state whose velocity grazes zero at t* (v = a = 0
/// there, a local minimum), with its velocity as a function of time: y = −1 + P cos(wt + φ) +
/// A cos t + B sin t with P = β/(1 − w²).
fn grazing_start(w: f64, beta: f64, phi: f64, t_star: f64) -> Option<(State, impl Fn(f64) -> f64)> {
    let p = beta / (1.0 - w * w);
    let (sd, cd) = (w * t_star + phi).sin_cos();
    let (st, ct) = t_star.sin_cos();
    // v(t*) = −Pw sd − A st + B ct = 0 and a(t*) = −Pw² cd − A ct − B st = 0.
    let a = -p * w * sd * st - p * w * w * cd * ct;
    let b = p * w * sd * ct - p * w * w * cd * st;
    let y0 = -1.0 + p * phi.cos() + a;
    let v0 = -p * w * phi.sin() + b;
    let velocity = move |t: f64| -p * w * (w * t + phi).sin() - a * t.sin() + b * t.cos();
    let jerk = p * w * (w * w - 1.0) * sd;
    // A true minimum at t*, positive velocity before it, and cos t* > 0 so that lowering v0
    // (which shifts v by −δ cos t) opens a pair of zeros there.
    let positive_before = (1..1000).all(|k| velocity(t_star * k as f64 / 1000.0) > 0.0);
    (v0 > 0.0 && jerk > 0.0 && ct > 0.05 && positive_before)
        .then_some((State { y: y0, v: v0 }, velocity))
}

/// First zero of `f` in [from, to] by a scan of step `h` and bisection, if any.
fn first_zero(f: impl Fn(f64) -> f64, from: f64, to: f64, h: f64) -> Option<f64> {
    let mut a = from;
    while a < to {
        let b = (a + h).min(to);
        if f(b) <= 0.0 {
            let (mut lo, mut hi) = (a, b);
            for _ in 0..80 {
                let mid = 0.5 * (lo + hi);
                if f(mid) > 0.0 {
                    lo = mid;
                } else {
                    hi = mid;
                }
            }
            return Some(hi);
        }
        a = b;
    }
    None
}

#[test]
fn near_tangential_double_zeros_are_not_missed() {
    let mut cases = 0;
    for &w in &[2.5, 3.0, 3.7, 5.0] {
        for &beta in &[2.0, 6.0] {
            for k in 0..16 {
                let phi = k as f64 * PI / 8.0;
                for &t_star in &[0.6, 0.9, 1.2] {
                    let Some((start, velocity)) = grazing_start(w, beta, phi, t_star) else {
                        continue;
                    };
                    let params = Params::new(0.0, w, beta).unwrap().with_phi(phi).unwrap();
                    let scale = start.y.abs() + start.v.abs() + beta;
                    for &delta in &[1e-3, 1e-6, 1e-9, 1e-12] {
                        let d = delta * scale;
                        // Dipping below zero: the first event is at the first of the two zeros,
                        // within ~√(2δ/jerk) of t*.
                        let below = events(
                            params,
                            State {
                                y: start.y,
                                v: start.v - d,
                            },
                            t_star + 1.0,
                        );
                        let first = below.first().unwrap_or_else(|| {
                            panic!("w {w} β {beta} φ {phi} t* {t_star} δ {delta}: missed the zero pair")
                        });
                        assert!(
                            (first.tau - t_star).abs() < 50.0 * delta.sqrt() + 1e-6
                                && first.tau <= t_star + 1e-6,
                            "w {w} β {beta} φ {phi} t* {t_star} δ {delta}: event at {}",
                            first.tau
                        );
                        // Staying above zero: v + δ cos t > 0 near t*, so the first event is the
                        // first zero of the analytic velocity after the grazing point.
                        let lifted = |t: f64| velocity(t) + d * t.cos();
                        let expected = first_zero(lifted, t_star + 1e-3, t_star + 1.0, 1e-4);
                        let above = events(
                            params,
                            State {
                                y: start.y,
                                v: start.v + d,
                            },
                            t_star + 1.0,
                        );
                        match (above.first(), expected) {
                            (Some(e), Some(t)) => assert!(
                                (e.tau - t).abs() < 1e-9,
                                "w {w} β {beta} φ {phi} t* {t_star} δ {delta}: {} vs {t}",
                                e.tau
                            ),
                            (None, None) => {}
                            (got, want) => panic!(
                                "w {w} β {beta} φ {phi} t* {t_star} δ {delta}: {got:?} vs {want:?}"
                            ),
                        }
                    }
                    cases += 1;
                }
            }
        }
    }
    assert!(cases >= 20, "enough grazing configurations: {cases}");
}

// ---------------------------------------------------------------------------------------------
// Regressions

/// Runs `periods` drive periods, failing if any single advance stops making progress.
fn runs_through(params: Params, initial: State, periods: f64) -> usize {
    let mut solver = ExactSolver::new(params, initial);
    let t_end = periods * params.drive_period();
    let mut events = 0;
    let mut idle = 0;
    while solver.time() < t_end {
        let before = solver.time();
        if solver.advance(t_end).expect("advances").is_some() {
            events += 1;
        }
        idle = if solver.time() == before { idle + 1 } else { 0 };
        assert!(idle < 16, "{params:?}: stalled at tau = {before}");
    }
    events
}

#[test]
fn regression_slip_stick_loop_at_one_instant_after_many_periods() {
    // The force at a velocity zero and the stick exit used differently rounded drive phases;
    // at tau ~ 1.6e4 a stop ended "now" and the next slide stopped at once, for ever.
    for &(zeta, w, beta, periods) in &[
        (0.046816, 0.6, 1.2, 3000.0),
        (0.046816, 0.7, 1.2, 3000.0),
        (0.0, 0.5, 3.3, 1500.0),
        (0.05, 0.07, 378.3, 400.0),
    ] {
        let params = Params::new(zeta, w, beta).unwrap();
        assert!(runs_through(params, State::default(), periods) > periods as usize);
    }
}

#[test]
fn regression_search_hung_on_a_concave_step_below_one_ulp() {
    // ζ = 0 at w = 1/2 and 1/4, started on the continuum of sliding orbits there (the
    // symmetric orbit shifted by a free oscillation): the curvature-certified target fell below
    // one ulp of the search point, which was then evaluated again for ever.
    use stickslip::theory::PeriodicSolution;
    for &(w, beta) in &[(0.5, 4.5), (0.25, 24.0)] {
        let params = Params::new(0.0, w, beta).unwrap();
        let orbit = PeriodicSolution::new(&params).unwrap();
        let t0 = orbit.first_lower_turn();
        let offset = 0.02 * orbit.peak;
        let on = orbit.state_at(0.0);
        let start = State {
            y: on.y + offset * t0.cos(),
            v: on.v + offset * t0.sin(),
        };
        assert!(runs_through(params, start, 200.0) >= 399);
    }
}
