//! Tests of the Shockley solver against known answers: a slow brute-force integrator, a
//! tight-tolerance run of itself, the exact PWL solver in the limit of a sharp diode, and the
//! stop rule.

use super::*;
use crate::solver::{grid, run_until, sample_at};
use crate::{Circuit, Event, EventKind, ExactSolver, Params, Phase, Solver, State};

fn paper(w: f64, beta: f64) -> ShockleyModel {
    let c = Circuit::paper_shockley();
    c.shockley_model(&c.params(w, beta, 0.0).unwrap())
        .unwrap()
        .unwrap()
}

fn tight() -> ShockleyOptions {
    ShockleyOptions::default()
        .with_rtol(1e-11)
        .unwrap()
        .with_atol(1e-11)
        .unwrap()
}

/// Classical RK4 with a fixed step, far below the explicit stability limit 2.8/(a/ε): the
/// slow, simple oracle.
fn rk4(model: &ShockleyModel, mut x: [f64; 2], t_end: f64, h: f64) -> [f64; 2] {
    let f = |t: f64, x: [f64; 2]| model.rhs(t, x[0], x[1]);
    let n = (t_end / h).round() as usize;
    let h = t_end / n as f64;
    for k in 0..n {
        let t = k as f64 * h;
        let k1 = f(t, x);
        let k2 = f(
            t + h / 2.0,
            [x[0] + h / 2.0 * k1[0], x[1] + h / 2.0 * k1[1]],
        );
        let k3 = f(
            t + h / 2.0,
            [x[0] + h / 2.0 * k2[0], x[1] + h / 2.0 * k2[1]],
        );
        let k4 = f(t + h, [x[0] + h * k3[0], x[1] + h * k3[1]]);
        for i in 0..2 {
            x[i] += h / 6.0 * (k1[i] + 2.0 * k2[i] + 2.0 * k3[i] + k4[i]);
        }
    }
    x
}

#[test]
fn agrees_with_a_brute_force_integrator() {
    // Sliding, and periodic stick, over three drive periods from rest.
    for (w, beta) in [(0.95, 2.14), (0.6, 1.2)] {
        let model = paper(w, beta);
        let t_end = 3.0 * model.params.drive_period();
        let oracle = rk4(&model, [0.0, 0.0], t_end, 2e-5);
        let mut solver = ShockleySolver::new(model, State::default(), tight()).unwrap();
        run_until(&mut solver, t_end, |_| {}).unwrap();
        let s = solver.state();
        assert!(
            (s.y - oracle[0]).abs() < 1e-7 && (s.v - oracle[1]).abs() < 1e-7,
            "w = {w}, β = {beta}: {s:?} vs {oracle:?}"
        );
    }
}

/// The largest difference of y over the last drive period, relative to the peak of `reference`.
fn last_period_difference(a: &[f64], reference: &[f64]) -> f64 {
    let peak = reference.iter().fold(0.0f64, |m, y| m.max(y.abs()));
    a.iter()
        .zip(reference)
        .fold(0.0f64, |m, (x, r)| m.max((x - r).abs()))
        / peak
}

fn last_period(model: ShockleyModel, options: ShockleyOptions, periods: f64) -> Vec<f64> {
    let t = model.params.drive_period();
    let times = grid((periods - 1.0) * t, periods * t, 500);
    let mut solver = ShockleySolver::new(model, State::default(), options).unwrap();
    sample_at(&mut solver, &times, |_| {})
        .unwrap()
        .iter()
        .map(|s| s.y)
        .collect()
}

#[test]
fn default_accuracy_against_a_tight_tolerance_run() {
    for (w, beta) in [(0.95, 2.14), (0.29, 1.07)] {
        let reference = last_period(paper(w, beta), tight(), 40.0);
        let default = last_period(paper(w, beta), ShockleyOptions::default(), 40.0);
        let d = last_period_difference(&default, &reference);
        assert!(d < 2e-6, "w = {w}, β = {beta}: {d:e}");
    }
}

#[test]
fn sliding_motion_turns_twice_per_period_at_zeros_of_the_current() {
    let model = paper(0.95, 2.14);
    let t = model.params.drive_period();
    let mut solver = ShockleySolver::new(model, State::default(), tight()).unwrap();
    run_until(&mut solver, 40.0 * t, |_| {}).unwrap();
    let mut events = Vec::new();
    while solver.time() < 50.0 * t {
        let before = solver.phase();
        if let Some(e) = solver.advance(50.0 * t).unwrap() {
            assert_eq!(e.kind, EventKind::Turn);
            assert_eq!(e.tau, solver.time());
            // The current is zero at the turn, and the phase flips.
            assert!(solver.state().v.abs() < 1e-9, "{:?}", solver.state());
            assert_eq!(
                solver.phase(),
                if before == Phase::SlipPositive {
                    Phase::SlipNegative
                } else {
                    Phase::SlipPositive
                }
            );
            events.push(e);
        }
    }
    assert_eq!(events.len(), 20);
    // Periodic: turns half a period apart, at opposite positions.
    for pair in events.windows(2) {
        assert!((pair[1].tau - pair[0].tau - t / 2.0).abs() < 1e-6 * t);
        assert!((pair[1].y + pair[0].y).abs() < 1e-6);
    }
}

/// Events over `periods` after `settle` periods, with the dense output checked against the
/// phase on every interval.
fn events_checked(
    model: ShockleyModel,
    options: ShockleyOptions,
    settle: f64,
    periods: f64,
) -> Vec<Event> {
    let t = model.params.drive_period();
    let threshold = options.stop_threshold;
    let mut solver = ShockleySolver::new(model, State::default(), options).unwrap();
    run_until(&mut solver, settle * t, |_| {}).unwrap();
    let mut events = Vec::new();
    let end = (settle + periods) * t;
    while solver.time() < end {
        let event = solver.advance(end).unwrap();
        let (from, to) = solver.interval();
        for tau in grid(from, to, 8) {
            let s = solver.dense(tau);
            match s.phase {
                Phase::Stick => assert!(s.v.abs() <= threshold * (1.0 + 1e-6), "{s:?}"),
                Phase::SlipPositive => assert!(s.v >= -threshold, "{s:?}"),
                Phase::SlipNegative => assert!(s.v <= threshold, "{s:?}"),
            }
        }
        events.extend(event);
    }
    events
}

#[test]
fn stops_begin_and_end_where_the_current_crosses_the_threshold() {
    let model = paper(0.29, 1.07);
    let options = ShockleyOptions::default();
    let t = model.params.drive_period();
    let events = events_checked(model, options, 30.0, 4.0);
    assert_eq!(events.len(), 16, "{events:?}");
    for pair in events.chunks(2) {
        assert_eq!(pair[0].kind, EventKind::Stick);
        assert_eq!(pair[1].kind, EventKind::Slip);
        // Longer than the minimum stop; the capacitor creeps by less than 1e-3 meanwhile.
        assert!(pair[1].tau - pair[0].tau > 0.01 * t);
        assert!((pair[1].y - pair[0].y).abs() < 1e-3);
    }
    // The current is at the threshold at both ends of every stop.
    let mut solver = ShockleySolver::new(model, State::default(), options).unwrap();
    run_until(&mut solver, 30.0 * t, |_| {}).unwrap();
    while solver.time() < 32.0 * t {
        if solver.advance(32.0 * t).unwrap().is_some() {
            let v = solver.state().v.abs();
            assert!((v - 1e-3).abs() < 1e-9, "{v}");
        }
    }
}

#[test]
fn the_minimum_stop_duration_decides_between_stop_and_turn() {
    let model = paper(0.29, 1.07);
    // Every dip is a stop when any duration counts...
    let every = ShockleyOptions::default()
        .with_min_stop_fraction(0.0)
        .unwrap();
    let events = events_checked(model, every, 30.0, 2.0);
    assert!(events.iter().all(|e| e.kind != EventKind::Turn));
    // ... and none is when a stop must last a whole period: the stops become turns.
    let never = ShockleyOptions::default()
        .with_min_stop_fraction(1.0)
        .unwrap();
    let events = events_checked(model, never, 30.0, 2.0);
    assert_eq!(events.len(), 4, "{events:?}");
    assert!(events.iter().all(|e| e.kind == EventKind::Turn));
    // At the sliding point the turns stay turns whatever the minimum duration.
    let events = events_checked(paper(0.95, 2.14), every, 30.0, 2.0);
    assert!(events.iter().all(|e| e.kind != EventKind::Turn));
    let events = events_checked(paper(0.95, 2.14), ShockleyOptions::default(), 30.0, 2.0);
    assert_eq!(events.len(), 4);
}

#[test]
fn a_weak_drive_keeps_it_stopped_from_the_start() {
    // β = 0.3 never overcomes the diodes: the start is a stop (the initial phase, no event),
    // and it stays one.
    let model = paper(0.5, 0.3);
    let mut solver =
        ShockleySolver::new(model, State::default(), ShockleyOptions::default()).unwrap();
    assert_eq!(solver.phase(), Phase::Stick);
    let mut events = Vec::new();
    run_until(&mut solver, 10.0 * model.params.drive_period(), |e| {
        events.push(*e)
    })
    .unwrap();
    assert!(events.is_empty(), "{events:?}");
    assert_eq!(solver.phase(), Phase::Stick);
}

#[test]
fn free_decay_turns_then_stops() {
    // No drive, from y = 7.5: the amplitude decays through turns until the diodes hold it.
    let model = paper(1.0, 0.0);
    let mut solver =
        ShockleySolver::new(model, State { y: 7.5, v: 0.0 }, ShockleyOptions::default()).unwrap();
    let mut events = Vec::new();
    run_until(&mut solver, 100.0, |e| events.push(*e)).unwrap();
    let last = events.last().unwrap();
    assert_eq!(last.kind, EventKind::Stick);
    assert!(events[..events.len() - 1]
        .iter()
        .all(|e| e.kind == EventKind::Turn));
    // Turning points alternate in sign and shrink. After the last one the restoring force
    // is below the diode voltage at the stop threshold, and the capacitor creeps (a smooth
    // diode leaks) until the current falls below the threshold: the stop.
    let turns = &events[..events.len() - 1];
    for pair in turns.windows(2) {
        assert!(
            pair[1].y.abs() < pair[0].y.abs() && pair[1].y * pair[0].y < 0.0,
            "{events:?}"
        );
    }
    let final_turn = turns.last().unwrap();
    assert!(last.y * final_turn.y > 0.0 && last.y.abs() <= final_turn.y.abs());
    assert!(last.y.abs() < 1.0);
}

#[test]
fn honours_the_solver_contract() {
    let model = paper(0.6, 1.2);
    let mut solver =
        ShockleySolver::new(model, State::default(), ShockleyOptions::default()).unwrap();
    let t = model.params.drive_period();
    run_until(&mut solver, 20.0 * t, |_| {}).unwrap();
    let now = solver.time();
    assert_eq!(solver.advance(now).unwrap(), None);
    assert_eq!(solver.interval(), (now, now));
    assert!(matches!(
        solver.advance(now - 1.0),
        Err(crate::Error::TimeBeforeCurrent { .. })
    ));
    let mut previous = now;
    while solver.time() < 22.0 * t {
        let event = solver.advance(22.0 * t).unwrap();
        let (from, to) = solver.interval();
        assert_eq!(from, previous);
        assert_eq!(to, solver.time());
        let end = solver.dense(to);
        assert_eq!((end.y, end.v), (solver.state().y, solver.state().v));
        if let Some(e) = event {
            assert_eq!((e.tau, e.y), (to, end.y));
        }
        previous = to;
    }
    // Sampling on a grid gives the same values as a run to each time, and is deterministic.
    let times = grid(20.0 * t, 21.0 * t, 37);
    let mut a = ShockleySolver::new(model, State::default(), ShockleyOptions::default()).unwrap();
    let sa = sample_at(&mut a, &times, |_| {}).unwrap();
    let mut b = ShockleySolver::new(model, State::default(), ShockleyOptions::default()).unwrap();
    let sb = sample_at(&mut b, &times, |_| {}).unwrap();
    assert_eq!(sa, sb);
    let mut c = ShockleySolver::new(model, State::default(), ShockleyOptions::default()).unwrap();
    run_until(&mut c, times[5], |_| {}).unwrap();
    assert!((c.state().y - sa[5].y).abs() < 1e-12);
}

#[test]
fn rejects_invalid_options() {
    let bad = ShockleyOptions {
        rtol: 0.0,
        ..Default::default()
    };
    assert!(matches!(
        ShockleySolver::new(paper(1.0, 1.0), State::default(), bad),
        Err(crate::Error::InvalidParameter { name: "rtol", .. })
    ));
    assert!(ShockleyOptions::default().with_atol(-1.0).is_err());
    assert!(ShockleyOptions::default().with_max_step(0.0).is_err());
    assert!(ShockleyOptions::default()
        .with_stop_threshold(f64::NAN)
        .is_err());
    assert!(ShockleyOptions::default()
        .with_min_stop_fraction(1.5)
        .is_err());
}

/// The PWL limit: with a = n V_T/U_t → 0 at a fixed turn-on current (junction voltage U_t at
/// v = 1) and R_s = R_D, the Shockley trajectory approaches the exact PWL one; the difference
/// is first order in a. Returns the largest |Δy| over periods 20 to 30 relative to the peak,
/// and the events of both over the last two periods.
fn pwl_distance(w: f64, beta: f64, a: f64) -> (f64, Vec<Event>, Vec<Event>) {
    let c = Circuit::paper();
    let z = c.impedance();
    let r = c.diode.linear_resistance() / z;
    let zeta_r = c.resistance / z / 2.0;
    let pwl = Params::new(zeta_r + r / 2.0, w, beta).unwrap();
    let t = pwl.drive_period();
    let times = grid(20.0 * t, 30.0 * t, 2000);
    let late = |e: &Event, list: &mut Vec<Event>| {
        if e.tau > 28.0 * t {
            list.push(*e)
        }
    };
    let mut exact_events = Vec::new();
    let mut exact = ExactSolver::new(pwl, State::default());
    let ye = sample_at(&mut exact, &times, |e| late(e, &mut exact_events)).unwrap();
    let law = DiodeLaw::pwl_limit(a, 1.0, r).unwrap();
    let model = ShockleyModel::new(Params::new(zeta_r, w, beta).unwrap(), law).unwrap();
    let options = ShockleyOptions::default()
        .with_rtol(1e-8)
        .unwrap()
        .with_atol(1e-8)
        .unwrap();
    let mut events = Vec::new();
    let mut solver = ShockleySolver::new(model, State::default(), options).unwrap();
    let ys = sample_at(&mut solver, &times, |e| late(e, &mut events)).unwrap();
    let peak = ye.iter().fold(0.0f64, |m, s| m.max(s.y.abs()));
    let d = ys
        .iter()
        .zip(&ye)
        .fold(0.0f64, |m, (a, b)| m.max((a.y - b.y).abs()));
    (d / peak, events, exact_events)
}

#[test]
fn approaches_the_exact_pwl_solution_as_the_diode_sharpens() {
    // Sliding (w = 0.9, β = 1.6) and periodic stick (w = 0.6, β = 1.2), Fig. 5 of the paper.
    for (w, beta) in [(0.9, 1.6), (0.6, 1.2)] {
        let t = Params::new(0.0, w, beta).unwrap().drive_period();
        let runs: Vec<_> = [0.04, 0.02, 0.01, 0.005]
            .iter()
            .map(|&a| pwl_distance(w, beta, a))
            .collect();
        for (a, run) in [0.04, 0.02, 0.01, 0.005].iter().zip(&runs) {
            eprintln!(
                "PWL limit w = {w}, β = {beta}: a = {a}: max |Δy| = {:.3e} of the peak",
                run.0
            );
        }
        for k in 0..3 {
            let ratio = runs[k].0 / runs[k + 1].0;
            assert!(
                (1.7..2.3).contains(&ratio),
                "w = {w}, β = {beta}: halving a divides the distance by {ratio}"
            );
        }
        let (d, events, exact) = &runs[3];
        assert!(*d < 0.02, "w = {w}, β = {beta}: {d}");
        // The same events, at nearby times and positions.
        assert_eq!(events.len(), exact.len(), "{events:?} vs {exact:?}");
        for (s, e) in events.iter().zip(exact) {
            assert_eq!(s.kind, e.kind);
            assert!((s.tau - e.tau).abs() < 0.002 * t, "{s:?} vs {e:?}");
            assert!(
                (s.y - e.y).abs() < 0.02 * e.y.abs().max(1.0),
                "{s:?} vs {e:?}"
            );
        }
    }
}
