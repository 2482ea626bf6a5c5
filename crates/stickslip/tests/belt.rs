//! The block on a moving belt with Coulomb's law: the exact solver against the closed form of
//! the undamped cycle (to 1e-12), and against an independent integrator (to 1e-8) for damped
//! and driven belts; steady sliding and its stability.
//!
//! The independent integrator ([`Oracle`]) is another method with another tolerance: the
//! classical fourth-order Runge–Kutta method at a fixed step h = 1e-3 on the slides (global
//! error about h⁴ ≈ 1e-12 per unit time), the stops as y = y_s + vb t checked on the same
//! grid, and every event placed by bisection on a partial Runge–Kutta step from the last
//! grid point (a one-step method: a step of θh from there is a solution of the same order).

use stickslip::steady::{MotionClass, SlidingStability, SteadyOptions};
use stickslip::theory::CoulombBeltCycle;
use stickslip::{steady, EventKind, ExactSolver, Params, Solver, State};

fn belt(zeta: f64, mu_s: f64, vb: f64) -> Params {
    Params::new(zeta, 1.0, 0.0)
        .and_then(|p| p.with_mu_s(mu_s))
        .and_then(|p| p.with_vb(vb))
        .unwrap()
}

fn forced(zeta: f64, mu_s: f64, vb: f64, w: f64, beta: f64) -> Params {
    Params::new(zeta, w, beta)
        .and_then(|p| p.with_mu_s(mu_s))
        .and_then(|p| p.with_vb(vb))
        .unwrap()
}

/// What the oracle is doing.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Mode {
    /// Slipping with slip sign ±1.
    Slip(f64),
    /// Stuck since τ_s at y_s.
    Stick { tau: f64, y: f64 },
}

/// The independent integrator (see the module documentation).
struct Oracle {
    p: Params,
    h: f64,
    tau: f64,
    y: f64,
    v: f64,
    mode: Mode,
    /// (τ, y, kind) of every event.
    events: Vec<(f64, f64, EventKind)>,
    /// (τ, y) of every zero of y' (an extreme of y) inside a slide.
    extremes: Vec<(f64, f64)>,
}

impl Oracle {
    fn new(p: Params, y: f64, v: f64) -> Self {
        let mut o = Self {
            p,
            h: 1e-3,
            tau: 0.0,
            y,
            v,
            mode: Mode::Slip(1.0),
            events: Vec::new(),
            extremes: Vec::new(),
        };
        o.mode = if v != p.vb {
            Mode::Slip((v - p.vb).signum())
        } else {
            let f = o.force(0.0, y);
            if f.abs() <= p.mu_s {
                Mode::Stick { tau: 0.0, y }
            } else {
                Mode::Slip(f.signum())
            }
        };
        o
    }

    fn drive(&self, tau: f64) -> f64 {
        self.p.beta * (self.p.w * tau + self.p.phi).cos()
    }

    /// The net force static friction must hold while stuck.
    fn force(&self, tau: f64, y: f64) -> f64 {
        self.drive(tau) - y - 2.0 * self.p.zeta * self.p.vb
    }

    fn accel(&self, tau: f64, y: f64, v: f64, sign: f64) -> f64 {
        self.drive(tau) - y - 2.0 * self.p.zeta * v - sign
    }

    /// One RK4 step of size `h` from (τ, y, v) sliding with `sign`.
    fn rk4(&self, tau: f64, y: f64, v: f64, sign: f64, h: f64) -> (f64, f64) {
        let f = |t: f64, y: f64, v: f64| (v, self.accel(t, y, v, sign));
        let k1 = f(tau, y, v);
        let k2 = f(tau + 0.5 * h, y + 0.5 * h * k1.0, v + 0.5 * h * k1.1);
        let k3 = f(tau + 0.5 * h, y + 0.5 * h * k2.0, v + 0.5 * h * k2.1);
        let k4 = f(tau + h, y + h * k3.0, v + h * k3.1);
        (
            y + h / 6.0 * (k1.0 + 2.0 * k2.0 + 2.0 * k3.0 + k4.0),
            v + h / 6.0 * (k1.1 + 2.0 * k2.1 + 2.0 * k3.1 + k4.1),
        )
    }

    /// Bisection for the first θ in (0, 1] where `past` holds along a partial step.
    fn bisect(&self, past: impl Fn(f64) -> bool) -> f64 {
        let (mut lo, mut hi) = (0.0, 1.0);
        for _ in 0..60 {
            let mid = 0.5 * (lo + hi);
            if past(mid) {
                hi = mid;
            } else {
                lo = mid;
            }
        }
        hi
    }

    /// Advance one grid step (or to the event inside it).
    fn step(&mut self) {
        let h = self.h;
        let vb = self.p.vb;
        match self.mode {
            Mode::Slip(sign) => {
                let (y1, v1) = self.rk4(self.tau, self.y, self.v, sign, h);
                if self.v * v1 < 0.0 || (v1 == 0.0 && self.v != 0.0) {
                    let (t0, y0, v0) = (self.tau, self.y, self.v);
                    let theta = self.bisect(|th| {
                        let v = self.rk4(t0, y0, v0, sign, th * h).1;
                        v * v0 <= 0.0
                    });
                    let (y, _) = self.rk4(t0, y0, v0, sign, theta * h);
                    self.extremes.push((t0 + theta * h, y));
                }
                if sign * (v1 - vb) <= 0.0 {
                    let (t0, y0, v0) = (self.tau, self.y, self.v);
                    let theta = self.bisect(|th| {
                        let v = self.rk4(t0, y0, v0, sign, th * h).1;
                        sign * (v - vb) <= 0.0
                    });
                    let (y, _) = self.rk4(t0, y0, v0, sign, theta * h);
                    self.tau = t0 + theta * h;
                    self.y = y;
                    self.v = vb;
                    let f = self.force(self.tau, y);
                    if f.abs() <= self.p.mu_s {
                        self.mode = Mode::Stick { tau: self.tau, y };
                        self.events.push((self.tau, y, EventKind::Stick));
                    } else if f.signum() != sign {
                        self.mode = Mode::Slip(f.signum());
                        self.events.push((self.tau, y, EventKind::Turn));
                    }
                    return;
                }
                self.tau += h;
                self.y = y1;
                self.v = v1;
            }
            Mode::Stick { tau: ts, y: ys } => {
                let at = |t: f64| ys + vb * (t - ts);
                let t1 = self.tau + h;
                let f1 = self.force(t1, at(t1));
                if f1.abs() > self.p.mu_s {
                    let t0 = self.tau;
                    let theta = self
                        .bisect(|th| self.force(t0 + th * h, at(t0 + th * h)).abs() > self.p.mu_s);
                    self.tau = t0 + theta * h;
                    self.y = at(self.tau);
                    self.v = vb;
                    self.mode = Mode::Slip(f1.signum());
                    self.events.push((self.tau, self.y, EventKind::Slip));
                    return;
                }
                self.tau = t1;
                self.y = at(t1);
                self.v = vb;
            }
        }
    }

    /// Run to τ = `end` (the last step shortened to land on it).
    fn run_to(&mut self, end: f64) {
        while self.tau < end - 1e-12 {
            let full = self.h;
            if self.tau + full > end {
                self.h = end - self.tau;
                self.step();
                self.h = full;
            } else {
                self.step();
            }
        }
    }
}

#[test]
fn the_undamped_coulomb_belt_is_its_closed_form() {
    for (mu_s, vb) in [(1.5, 0.5), (2.0, 0.1), (1.2, 1.3), (3.0, 2.0), (1.5, -0.7)] {
        let p = belt(0.0, mu_s, vb);
        // From a stop on the belt: every stop ends at the release point of the cycle.
        let mut solver = ExactSolver::new(p, State { y: 0.0, v: vb });
        let s = steady::steady_state(&mut solver, &SteadyOptions::default()).unwrap();
        let c = CoulombBeltCycle::new(mu_s, vb).unwrap();
        let cycle = s.self_excited.unwrap();
        assert_eq!(s.class, MotionClass::StickSlipCycle, "({mu_s}, {vb})");
        let period = cycle.period.unwrap();
        assert!(
            (period - c.period).abs() <= 1e-12 * c.period,
            "({mu_s}, {vb}): period {period} against {}",
            c.period
        );
        assert!(
            (s.y_max - c.y_max).abs() <= 1e-12,
            "{} {}",
            s.y_max,
            c.y_max
        );
        assert!(
            (s.y_min - c.y_min).abs() <= 1e-12,
            "{} {}",
            s.y_min,
            c.y_min
        );
        assert!((cycle.stick_fraction - c.stick_fraction).abs() <= 1e-12);
        assert_eq!(cycle.sliding_stability, SlidingStability::Neutral);
        // The record's events: the stop that opens it, the release at μs.
        let release = s.events.iter().find(|e| e.kind == EventKind::Slip).unwrap();
        assert!((release.y - c.release_y).abs() <= 1e-12);
        assert!((s.events[0].y - c.stick_y).abs() <= 1e-12);
    }
}

/// From rest at ζ = 0, inside the circle of radius |vb| about steady sliding, the block never
/// reaches the belt's speed: a pure-slip cycle of period 2π, neutral.
#[test]
fn the_undamped_coulomb_belt_from_rest_inside_the_belt_speed_slips_for_ever() {
    let p = belt(0.0, 1.2, 1.3);
    let mut solver = ExactSolver::new(p, State::default());
    let s = steady::steady_state(&mut solver, &SteadyOptions::default()).unwrap();
    assert_eq!(s.class, MotionClass::PureSlipCycle);
    let cycle = s.self_excited.unwrap();
    assert!((cycle.period.unwrap() - std::f64::consts::TAU).abs() < 1e-9);
    // The circle about y = 1 through y = 0.
    assert!((s.y_max - 2.0).abs() < 1e-12 && s.y_min.abs() < 1e-12);
}

/// The exact trajectory against the oracle's, sample by sample, and their events.
fn compare_trajectories(p: Params, initial: State, end: f64) {
    let mut exact = ExactSolver::new(p, initial);
    let mut oracle = Oracle::new(p, initial.y, initial.v);
    let mut worst = 0.0f64;
    let mut events = Vec::new();
    for k in 1..=(end / 0.5) as usize {
        let tau = 0.5 * k as f64;
        stickslip::solver::run_until(&mut exact, tau, |e| events.push(*e)).unwrap();
        oracle.run_to(tau);
        let s = exact.state();
        let d = (s.y - oracle.y).abs().max((s.v - oracle.v).abs());
        worst = worst.max(d);
        assert!(
            d <= 1e-8,
            "{p:?} at τ = {tau}: exact ({}, {}), oracle ({}, {})",
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
    assert!(!events.is_empty());
}

#[test]
fn damped_and_driven_belts_follow_an_independent_integrator() {
    // Damped belts without a drive: stick-slip.
    compare_trajectories(belt(0.05, 1.5, 0.3), State::default(), 60.0);
    compare_trajectories(belt(0.2, 2.0, -0.8), State { y: 0.5, v: 0.0 }, 60.0);
    // Driven belts: stops, slips and reversals under a drive.
    compare_trajectories(forced(0.1, 1.3, 0.4, 0.8, 1.0), State::default(), 60.0);
    compare_trajectories(forced(0.05, 1.0, 0.6, 1.7, 2.5), State::default(), 60.0);
    compare_trajectories(
        forced(0.02, 2.0, -0.2, 0.3, 3.0),
        State { y: 1.0, v: 0.0 },
        60.0,
    );
}

/// A self-excited cycle's period and extremes from the oracle: the interval between its
/// last two stops, and the extremes between them.
fn oracle_cycle(p: Params, initial: State, sticks: usize) -> (f64, f64, f64) {
    let mut o = Oracle::new(p, initial.y, initial.v);
    while o.events.iter().filter(|e| e.2 == EventKind::Stick).count() < sticks {
        o.step();
    }
    let onsets: Vec<f64> = o
        .events
        .iter()
        .filter(|e| e.2 == EventKind::Stick)
        .map(|e| e.0)
        .collect();
    let (a, b) = (onsets[sticks - 2], onsets[sticks - 1]);
    let ys = o
        .events
        .iter()
        .filter(|e| e.0 >= a && e.0 <= b)
        .map(|e| e.1)
        .chain(
            o.extremes
                .iter()
                .filter(|e| e.0 > a && e.0 < b)
                .map(|e| e.1),
        );
    let (lo, hi) = ys.fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), y| {
        (lo.min(y), hi.max(y))
    });
    (b - a, hi, lo)
}

#[test]
fn damped_self_excited_cycles_follow_an_independent_integrator() {
    for (zeta, mu_s, vb) in [(0.05, 1.5, 0.3), (0.1, 2.0, 0.5), (0.02, 1.3, -0.2)] {
        let p = belt(zeta, mu_s, vb);
        let s = steady::steady_state(
            &mut ExactSolver::new(p, State::default()),
            &SteadyOptions::default(),
        )
        .unwrap();
        assert_eq!(s.class, MotionClass::StickSlipCycle, "{p:?}");
        let (period, y_max, y_min) = oracle_cycle(p, State::default(), 4);
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
        // Coulomb's law never falls: steady sliding is stable with damping.
        assert_eq!(cycle.sliding_stability, SlidingStability::Stable);
        assert_eq!(cycle.equilibrium, vb.signum());
    }
}

/// With damping and a belt fast enough that the block, released from rest, never catches up
/// with it, the Coulomb belt settles on steady sliding, y = 1 (and the stick-slip cycle does
/// not coexist from rest).
#[test]
fn a_fast_damped_belt_slides_steadily() {
    let p = belt(0.1, 1.5, 2.0);
    let s = steady::steady_state(
        &mut ExactSolver::new(p, State::default()),
        &SteadyOptions::default(),
    )
    .unwrap();
    assert_eq!(s.class, MotionClass::SteadySliding);
    let cycle = s.self_excited.unwrap();
    assert_eq!(cycle.period, None);
    assert_eq!((s.y_max, s.y_min), (1.0, 1.0));
    assert_eq!(cycle.sliding_stability, SlidingStability::Stable);
    assert!((cycle.sliding_damping - 0.2).abs() < 1e-15);
}

/// A forced belt's steady state (drive periods, stops per cycle) and its extremes, which lie
/// inside slides where y' = 0, against the oracle run over the same recorded periods.
#[test]
fn a_forced_belt_steady_state_follows_an_independent_integrator() {
    for p in [
        forced(0.1, 1.3, 0.4, 0.8, 1.0),
        forced(0.05, 1.0, 0.6, 1.7, 2.5),
    ] {
        let s = steady::steady_state(
            &mut ExactSolver::new(p, State::default()),
            &SteadyOptions::default(),
        )
        .unwrap();
        let period = s.period.expect("a periodic motion");
        assert!(s.self_excited.is_none() && !s.symmetric);
        let mut o = Oracle::new(p, 0.0, 0.0);
        o.run_to(s.start);
        let mut hi = f64::NEG_INFINITY;
        let mut lo = f64::INFINITY;
        let first = o.extremes.len();
        let events = o.events.len();
        o.run_to(s.start + period as f64 * p.drive_period());
        for &(_, y) in &o.extremes[first..] {
            hi = hi.max(y);
            lo = lo.min(y);
        }
        for e in &o.events[events..] {
            hi = hi.max(e.1);
            lo = lo.min(e.1);
        }
        assert!((s.y_max - hi).abs() <= 1e-8, "{p:?}: {} {hi}", s.y_max);
        assert!((s.y_min - lo).abs() <= 1e-8, "{p:?}: {} {lo}", s.y_min);
        let end = s.final_state();
        assert!((end.y - o.y).abs() <= 1e-8 && (end.v - o.v).abs() <= 1e-8);
    }
}

/// Where the steady-state search decides that a damped Coulomb belt slides steadily (at the
/// first turning point nearer y = 1 than vb, issue 36's map speed), the motion from rest
/// indeed never sticks again: the exact solver run on for 300 natural periods has no stop
/// after that point and ends at y = 1, y' = 0.
#[test]
fn where_a_damped_coulomb_belt_is_decided_sliding_it_never_sticks_again() {
    let mut sliding = 0;
    for vb in [0.3, 0.5, 0.8, 1.2, 2.0] {
        for mu_s in [1.0, 1.5, 2.5] {
            let p = belt(0.05, mu_s, vb);
            let s = steady::steady_state(
                &mut ExactSolver::new(p, State::default()),
                &SteadyOptions::default(),
            )
            .unwrap();
            if s.class != MotionClass::SteadySliding {
                continue;
            }
            sliding += 1;
            let settled = s.self_excited.unwrap().time_to_settle;
            let mut solver = ExactSolver::new(p, State::default());
            let end = 300.0 * std::f64::consts::TAU;
            while solver.time() < end {
                if let Some(e) = solver.advance(end).unwrap() {
                    assert!(
                        e.kind != EventKind::Stick || e.tau < settled,
                        "vb = {vb}, μs = {mu_s}: a stop at τ = {} after {settled}",
                        e.tau
                    );
                }
            }
            let last = solver.state();
            assert!(
                (last.y - 1.0).abs() < 1e-9 && last.v.abs() < 1e-9,
                "vb = {vb}, μs = {mu_s}: {last:?}"
            );
        }
    }
    assert!(sliding >= 5, "{sliding}");
}
