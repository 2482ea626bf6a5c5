//! The undamped Coulomb belt (ζ = 0, β = 0, Coulomb's law) from rest, against the motion
//! worked out by hand, to 1e-12.
//!
//! From rest (y, y') = (0, 0) on a belt at vb > 0 the block slips behind the belt, so kinetic
//! friction pushes it forward with force 1: y'' + y = 1, the circle of radius 1 about y = 1,
//! y = 1 − cos τ, y' = sin τ, whose speed never exceeds 1. So:
//!
//! - **vb > 1**: it never reaches the belt's speed and slides on that circle for ever: a
//!   pure-slip cycle of period 2π, y from 0 to 2, no stop. Steady sliding, y = 1, is a centre
//!   (2ζ + μ' = 0): neutral, and every circle about it of radius up to vb is such a cycle.
//! - **vb = 1**: the circle reaches y' = 1 at its top, y = 1, tangentially (y'' = 1 − y = 0).
//!   There the net force −y = −1 sits on the static limit: with μs = 1 the "stop" ends at
//!   once (the spring's force passes μs as soon as the block moves on with the belt) and the
//!   block goes on along the same circle: a pure-slip cycle of period 2π, y from 0 to 2, that
//!   touches the belt's speed once a period. It is the stick-slip cycle of the closed form
//!   (`theory::CoulombBeltCycle`) at μs = 1, whose stop has shrunk to an instant.
//! - **vb < 1, μs = 1**: the circle reaches y' = vb transversally at y = 1 − √(1 − vb²),
//!   sticks (|y| < 1), is carried to the release at y = μs = 1 and slips from (1, vb) on the
//!   circle of radius vb about 1, which touches the belt's speed again at its top: from the
//!   first stop on, a pure-slip cycle of period 2π, y from 1 − vb to 1 + vb.
//! - **vb = 0.5, μs = 1.5** (the control, a genuine stick-slip cycle): the closed form,
//!   R = √((μs − 1)² + vb²) = √0.5, T = π + 2 atan2(vb, μs − 1) + 2(μs − 1)/vb = 3π/2 + 2,
//!   y = 1 ± R, stick fraction 2/T.
//!
//! A belt moving backwards is the mirror image y → −y. The stick events at a tangency are
//! placed by rounding alone (within √ε of it, a few 10⁻⁸): the cycle's period, extremes and
//! stick fraction must not depend on them.

use std::f64::consts::{PI, TAU};
use stickslip::experiment::Experiment;
use stickslip::solver::run_until;
use stickslip::steady::{exact_solver, steady_state_from, MotionClass, SlidingStability};
use stickslip::steady::{SteadyOptions, SteadyState};
use stickslip::theory::CoulombBeltCycle;
use stickslip::{ExactSolver, Params, Solver, State};

/// The motion from rest worked out by hand (see the module documentation): class, period,
/// y_max, y_min, stick fraction.
fn by_hand(mu_s: f64, vb: f64) -> (MotionClass, f64, f64, f64, f64) {
    let (sign, speed) = (vb.signum(), vb.abs());
    let mirror = |(class, period, high, low, fraction): (MotionClass, f64, f64, f64, f64)| {
        if sign > 0.0 {
            (class, period, high, low, fraction)
        } else {
            (class, period, -low, -high, fraction)
        }
    };
    if speed > 1.0 || (speed == 1.0 && mu_s == 1.0) {
        // The circle of radius 1 about 1 through the start.
        return mirror((MotionClass::PureSlipCycle, TAU, 2.0, 0.0, 0.0));
    }
    if mu_s == 1.0 {
        // After the first stop, the circle of radius vb about 1.
        return mirror((
            MotionClass::PureSlipCycle,
            TAU,
            1.0 + speed,
            1.0 - speed,
            0.0,
        ));
    }
    let excess = mu_s - 1.0;
    let radius = (excess * excess + speed * speed).sqrt();
    let period = PI + 2.0 * speed.atan2(excess) + 2.0 * excess / speed;
    mirror((
        MotionClass::StickSlipCycle,
        period,
        1.0 + radius,
        1.0 - radius,
        2.0 * excess / (speed * period),
    ))
}

fn belt(mu_s: f64, vb: f64) -> Params {
    Params::new(0.0, 1.0, 0.0)
        .and_then(|p| p.with_mu_s(mu_s))
        .and_then(|p| p.with_vb(vb))
        .unwrap()
}

fn check(steady: &SteadyState, mu_s: f64, vb: f64, how: &str) {
    let (class, period, y_max, y_min, fraction) = by_hand(mu_s, vb);
    let cycle = steady.self_excited.unwrap();
    let found = cycle.period.unwrap();
    let what = format!("μs = {mu_s}, vb = {vb} ({how})");
    assert_eq!(steady.class, class, "{what}");
    assert!(
        (found - period).abs() <= 1e-12 * period,
        "{what}: period {found} against {period}"
    );
    assert!(
        (steady.y_max - y_max).abs() <= 1e-12,
        "{what}: y_max {} against {y_max}",
        steady.y_max
    );
    assert!(
        (steady.y_min - y_min).abs() <= 1e-12,
        "{what}: y_min {} against {y_min}",
        steady.y_min
    );
    assert!(
        (cycle.stick_fraction - fraction).abs() <= 1e-12,
        "{what}: stick fraction {} against {fraction}",
        cycle.stick_fraction
    );
    // (A positive zero: no time stuck at all without stops.)
    assert!(cycle.stick_fraction.is_sign_positive(), "{what}");
    let stops = usize::from(class == MotionClass::StickSlipCycle);
    assert_eq!(steady.stops, stops, "{what}");
    assert_eq!(cycle.sliding_stability, SlidingStability::Neutral, "{what}");
    assert_eq!(cycle.sliding_damping, 0.0, "{what}");
}

const CASES: [(f64, f64); 10] = [
    (1.0, 1.0),
    (1.0, 2.0),
    (1.5, 0.5),
    (1.0, 0.5),
    (1.0, 0.3),
    (1.0, 0.9),
    (1.0, -1.0),
    (1.0, -0.4),
    (1.5, 2.0),
    (1.5, 1.0),
];

/// The steady state from rest, as `stickslip steady` finds it (the exact solver's factory,
/// Newton's method on) and on one solver without a factory.
#[test]
fn the_undamped_coulomb_belt_from_rest_is_the_motion_worked_out_by_hand() {
    for (mu_s, vb) in CASES {
        let p = belt(mu_s, vb);
        let options = SteadyOptions::default();
        let s = steady_state_from(&exact_solver, &p, State::default(), &options).unwrap();
        check(&s, mu_s, vb, "factory");
        let mut solver = ExactSolver::new(p, State::default());
        let s = stickslip::steady::steady_state(&mut solver, &options).unwrap();
        check(&s, mu_s, vb, "one solver");
    }
}

/// At μs = 1 every belt speed up to 1 gives a cycle that touches the belt's speed once a
/// period, its stick events placed by rounding: across 160 speeds of both signs the search
/// never takes such a touch for a stop, and finds the period 2π to 1e-12.
#[test]
fn touching_cycles_are_found_at_every_belt_speed() {
    for k in 1..=80 {
        for vb in [k as f64 / 80.0, -(k as f64) / 80.0] {
            let p = belt(1.0, vb);
            let s = steady_state_from(&exact_solver, &p, State::default(), &Default::default())
                .unwrap();
            check(&s, 1.0, vb, "sweep");
        }
    }
}

/// The closed form of the cycle (`CoulombBeltCycle`) agrees with the hand's where the motion
/// from rest reaches the belt's speed; at μs = 1 it is the circle of radius vb with a stop of
/// no duration.
#[test]
fn the_closed_form_cycle_is_the_one_reached_from_rest() {
    for (mu_s, vb) in CASES.into_iter().filter(|(_, vb)| vb.abs() <= 1.0) {
        let (_, period, y_max, y_min, fraction) = by_hand(mu_s, vb);
        let c = CoulombBeltCycle::new(mu_s, vb).unwrap();
        assert!(
            (c.period - period).abs() <= 1e-12 * period,
            "({mu_s}, {vb})"
        );
        assert!((c.y_max - y_max).abs() <= 1e-12, "({mu_s}, {vb})");
        assert!((c.y_min - y_min).abs() <= 1e-12, "({mu_s}, {vb})");
        assert!(
            (c.stick_fraction - fraction).abs() <= 1e-12,
            "({mu_s}, {vb})"
        );
    }
}

/// The trajectory (`simulate`) from rest at vb = 1 and 2: y = 1 − cos τ, y' = sin τ for ten
/// natural periods, touching the belt's speed at vb = 1 without leaving the circle.
#[test]
fn the_trajectory_from_rest_is_the_circle_through_it() {
    for vb in [1.0, 2.0] {
        let mut solver = ExactSolver::new(belt(1.0, vb), State::default());
        let mut worst = 0.0f64;
        for k in 1..=400 {
            let tau = 0.05 * PI * k as f64;
            run_until(&mut solver, tau, |_| {}).unwrap();
            let s = solver.state();
            let (sin, cos) = tau.sin_cos();
            worst = worst.max((s.y - (1.0 - cos)).abs()).max((s.v - sin).abs());
        }
        assert!(worst <= 1e-12, "vb = {vb}: off the circle by {worst:e}");
    }
}

/// `orbit` of these belts: at vb = 2 the neutral circle, multipliers 1 and 1; at vb = 1 the
/// circle that touches the belt's speed, whose return map has no derivative (slope 0
/// outside, where motions stick and are released onto it, and 1 inside): no multipliers,
/// said in its summary.
#[test]
fn the_orbit_of_the_neutral_circle_and_of_the_touching_one() {
    for vb in [1.0, 2.0] {
        let e = Experiment::dimensionless(0.0, 1.0, 0.0)
            .and_then(|e| e.with_vb(vb))
            .unwrap();
        let orbit = e.self_excited_orbit(&e.steady_options()).unwrap();
        assert_eq!(orbit.class, MotionClass::PureSlipCycle, "vb = {vb}");
        let period = orbit.cycle_period_tau.unwrap();
        assert!((period - TAU).abs() <= 1e-12 * TAU, "vb = {vb}: {period}");
        assert!((orbit.y_max - 2.0).abs() <= 1e-12 && orbit.y_min.abs() <= 1e-12);
        if vb == 2.0 {
            let [trivial, other] = orbit.multipliers.unwrap();
            assert_eq!((trivial.re, trivial.im), (1.0, 0.0));
            assert!(
                (other.re - 1.0).abs() <= 1e-12 && other.im == 0.0,
                "{other:?}"
            );
        } else {
            assert_eq!(orbit.multipliers, None);
            assert_eq!(orbit.stability, None);
            assert!(
                orbit.summary.contains("touching the belt's speed"),
                "{}",
                orbit.summary
            );
        }
    }
}
