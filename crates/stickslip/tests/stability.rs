//! Tests of the stability analysis: the tangent dynamics against finite differences of the
//! exact flow, periodic orbits by Newton's method against long simulations, and Lyapunov
//! exponents against the two-trajectory estimate and the Floquet multipliers.

use std::f64::consts::TAU;
use stickslip::solver::run_until;
use stickslip::stability::{
    classify_nonperiodic, find_periodic_orbit, lyapunov_exponents, periodic_orbit_from_steady,
    saltation, sliding_transition, strobe_map, stuck_transition, two_trajectory_exponent,
    LyapunovOptions, Matrix2, NewtonOptions, NonperiodicVerdict, PeriodicOrbit, SecondExponent,
    Stability, StabilityError, TangentSolver,
};
use stickslip::steady::{exact_solver, steady_state_from, SteadyOptions};
use stickslip::{Error, Event, EventKind, ExactSolver, Params, Phase, Solver, State};

/// Uniform pseudo-random numbers from a fixed seed (xorshift64), the same on every run.
struct Rng(u64);

impl Rng {
    fn next(&mut self) -> f64 {
        self.0 ^= self.0 << 13;
        self.0 ^= self.0 >> 7;
        self.0 ^= self.0 << 17;
        (self.0 >> 11) as f64 / (1u64 << 53) as f64
    }

    fn range(&mut self, lo: f64, hi: f64) -> f64 {
        lo + (hi - lo) * self.next()
    }
}

/// Damping regimes of the random cases: (name, ζ, w) with ζ = 0, underdamped, critical,
/// overdamped, and the secular case ζ = 0, w = 1.
fn regime(rng: &mut Rng, case: usize) -> (&'static str, f64, f64) {
    let w = rng.range(0.2, 2.5);
    match case % 5 {
        0 => ("undamped", 0.0, w),
        1 => ("underdamped", rng.range(0.01, 0.9), w),
        2 => ("critical", 1.0, w),
        3 => ("overdamped", rng.range(1.05, 3.0), w),
        _ => ("secular", 0.0, 1.0),
    }
}

/// The exact flow over `t` from `x` at τ = 0: the final state and the events.
fn flow(params: &Params, x: State, t: f64) -> (State, Vec<Event>) {
    let mut solver = ExactSolver::new(*params, x);
    let mut events = Vec::new();
    run_until(&mut solver, t, |e| events.push(*e)).expect("solver runs");
    (solver.state(), events)
}

fn kinds(events: &[Event]) -> Vec<EventKind> {
    events.iter().map(|e| e.kind).collect()
}

/// Central differences of the flow over `t` at `x`, step `h`, in the columns `columns`
/// (0: δy, 1: δy'); `None` when a perturbed run has other events than the nominal one (the
/// difference would straddle a change of the event sequence).
fn central_differences(
    params: &Params,
    x: State,
    t: f64,
    h: f64,
    columns: &[usize],
) -> Option<[[f64; 2]; 2]> {
    let nominal = kinds(&flow(params, x, t).1);
    let mut out = [[f64::NAN; 2]; 2];
    for &c in columns {
        let shift = |sign: f64| {
            let mut p = x;
            if c == 0 {
                p.y += sign * h;
            } else {
                p.v += sign * h;
            }
            p
        };
        let (plus, plus_events) = flow(params, shift(1.0), t);
        let (minus, minus_events) = flow(params, shift(-1.0), t);
        if kinds(&plus_events) != nominal || kinds(&minus_events) != nominal {
            return None;
        }
        out[0][c] = (plus.y - minus.y) / (2.0 * h);
        out[1][c] = (plus.v - minus.v) / (2.0 * h);
    }
    Some(out)
}

/// Largest difference of two matrices in the given columns.
fn difference(a: &[[f64; 2]; 2], b: &[[f64; 2]; 2], columns: &[usize]) -> f64 {
    let mut d = 0.0f64;
    for &c in columns {
        for r in 0..2 {
            d = d.max((a[r][c] - b[r][c]).abs());
        }
    }
    d
}

/// Parameters with the drive phase moved on by w·t, so that a run from τ = 0 continues one
/// that stood at τ = t.
fn shifted(params: &Params, t: f64) -> Params {
    params
        .with_phi((params.phi + params.w * t).rem_euclid(TAU))
        .expect("finite phase")
}

/// The drive F and its rate F' at τ.
fn drive_and_rate(params: &Params, tau: f64) -> (f64, f64) {
    let (s, c) = (params.w * tau + params.phi).sin_cos();
    (params.beta * c, -params.beta * params.w * s)
}

// ---------------------------------------------------------------------------------------------
// Segment and saltation matrices against finite differences of the exact flow

/// Within a slide the flow is affine in the state, so central differences are exact but for
/// rounding: about 1e-16·|x|/h. Each step size h must agree to 1e-13·(1 + |x|)/h, and the
/// tangent solver with the closed form to 1e-14·(1 + |Φ|). Liouville: det Φ = e^{−2ζΔτ}.
#[test]
fn sliding_transition_matches_finite_differences_in_every_regime() {
    let mut rng = Rng(0x5eed_0001_2345_6789);
    let mut checked = [0usize; 5];
    for case in 0..500 {
        let (name, zeta, w) = regime(&mut rng, case);
        let params = Params::new(zeta, w, rng.range(0.0, 6.0))
            .and_then(|p| p.with_phi(rng.range(0.0, TAU)))
            .and_then(|p| p.with_mu_s(rng.range(1.0, 2.5)))
            .unwrap();
        let sign = if rng.next() < 0.5 { 1.0 } else { -1.0 };
        let x = State {
            y: rng.range(-5.0, 5.0),
            v: sign * rng.range(0.3, 3.0),
        };
        // Half way to the first event at most: no perturbation by h ≤ 1e-4 reaches it.
        let horizon = 2.0 * params.drive_period();
        let first = flow(&params, x, horizon)
            .1
            .first()
            .map_or(horizon, |e| e.tau);
        let dtau = rng.range(0.05, 0.5) * first;
        let mut tangent = TangentSolver::new(params, x);
        tangent.run_until(dtau, |_| {}).unwrap();
        let phi = sliding_transition(zeta, dtau);
        let j = tangent.jacobian();
        assert!(
            difference(&j.0, &phi.0, &[0, 1]) <= 1e-14 * (1.0 + phi.max_abs()),
            "{name} case {case}: tangent {j:?} closed form {phi:?}"
        );
        let liouville = (-2.0 * zeta * dtau).exp();
        assert!(
            (phi.det() - liouville).abs() <= 1e-13 * (1.0 + liouville),
            "{name} case {case}: det {} against e^(-2 zeta dtau) = {liouville}",
            phi.det()
        );
        let log_det = tangent.log_det().expect("no stop");
        assert!((log_det + 2.0 * zeta * dtau).abs() <= 1e-15 * (1.0 + dtau));
        let size = 1.0 + flow(&params, x, dtau).0.y.abs().max(x.v.abs());
        for h in [1e-4, 1e-5, 1e-6] {
            let fd = central_differences(&params, x, dtau, h, &[0, 1])
                .unwrap_or_else(|| panic!("{name} case {case}: an event within the slide"));
            let error = difference(&fd, &phi.0, &[0, 1]);
            assert!(
                error <= 1e-13 * size / h,
                "{name} case {case} h {h:e}: FD {fd:?} closed form {phi:?} ({error:e})"
            );
        }
        checked[case % 5] += 1;
    }
    assert_eq!(checked, [100; 5]);
}

/// One event of each kind in a short window [τ_e − a, τ_e + b] around it: the tangent solver's
/// Jacobian against Φ(b)·S·Φ(a) built from the public saltation matrices, and against central
/// differences of the flow over the window.
///
/// Across an event the flow is smooth but curved (its second derivative grows like 1/|a⁻| at
/// a stop and like (μs − 1)/(sF')² at a release), so the finite differences carry an error
/// O(h²) besides the rounding O(10⁻¹⁶/h): the best of h = 1e-4, 1e-5, 1e-6 must agree to
/// 1e-6·(1 + max|J|), and h = 1e-5 to 1e-4·(1 + max|J|). After a stop only perturbations of
/// y exist in a stuck start (a velocity perturbation of a stuck oscillator is not
/// differentiable for μs > 1, see `stability::segment`), so a window starting stuck checks the
/// δy column.
#[test]
fn saltation_matrices_match_finite_differences_at_turns_stops_and_releases() {
    let mut rng = Rng(0x5eed_0002_3456_789a);
    // Per kind (turn, stick, slip): per regime, windows checked.
    let mut checked = [[0usize; 5]; 3];
    for case in 0..1000 {
        let (name, zeta, w) = regime(&mut rng, case);
        let mu_s = if rng.next() < 0.4 {
            1.0
        } else {
            rng.range(1.0, 3.0)
        };
        let params = Params::new(zeta, w, rng.range(0.5, 8.0))
            .and_then(|p| p.with_phi(rng.range(0.0, TAU)))
            .and_then(|p| p.with_mu_s(mu_s))
            .unwrap();
        let initial = State {
            y: rng.range(-5.0, 5.0),
            v: rng.range(-3.0, 3.0),
        };
        let events = flow(&params, initial, 8.0 * params.drive_period()).1;
        let mut seen = [false; 3];
        for i in 1..events.len().saturating_sub(1) {
            let (before, e, after) = (events[i - 1], events[i], events[i + 1]);
            let kind = match e.kind {
                EventKind::Turn => 0,
                EventKind::Stick => 1,
                EventKind::Slip => 2,
            };
            if seen[kind] || !(before.tau < e.tau && e.tau < after.tau) {
                continue;
            }
            let a = 0.4 * (e.tau - before.tau);
            let b = 0.4 * (after.tau - e.tau).min(5.0);
            let mut solver = ExactSolver::new(params, initial);
            run_until(&mut solver, e.tau - a, |_| {}).unwrap();
            let x = solver.state();
            let start_phase = solver.phase();
            let local = shifted(&params, e.tau - a);
            let window = a + b;
            let mut tangent = TangentSolver::new(local, x);
            let mut inside = Vec::new();
            tangent.run_until(window, |ev| inside.push(*ev)).unwrap();
            if inside.len() != 1 || inside[0].kind != e.kind {
                // (The restarted run decided differently within rounding: not this window.)
                continue;
            }
            let ev = inside[0];
            let (ta, tb) = (ev.tau, window - ev.tau);
            let (force, rate) = drive_and_rate(&local, ev.tau);
            let net = force - ev.y;
            let expected = match e.kind {
                EventKind::Turn => {
                    let s = start_phase.sign();
                    sliding_transition(zeta, tb)
                        * saltation::turn(net, s)
                        * sliding_transition(zeta, ta)
                }
                EventKind::Stick => {
                    stuck_transition() * saltation::stick() * sliding_transition(zeta, ta)
                }
                EventKind::Slip => {
                    let s = tangent.phase().sign();
                    sliding_transition(zeta, tb)
                        * saltation::release(s, rate, mu_s)
                        * stuck_transition()
                }
            };
            let j = tangent.jacobian();
            let scale = 1.0 + j.max_abs();
            assert!(
                difference(&j.0, &expected.0, &[0, 1]) <= 1e-9 * scale,
                "{name} case {case} {:?} {params:?}: tangent {j:?}, formula {expected:?}",
                e.kind
            );
            let columns: &[usize] = if start_phase == Phase::Stick {
                &[0]
            } else {
                &[0, 1]
            };
            let errors: Vec<f64> = [1e-4, 1e-5, 1e-6]
                .iter()
                .map(|&h| {
                    central_differences(&local, x, window, h, columns)
                        .map_or(f64::INFINITY, |fd| difference(&fd, &j.0, columns))
                })
                .collect();
            let best = errors.iter().copied().fold(f64::INFINITY, f64::min);
            assert!(
                best <= 1e-6 * scale && errors[1] <= 1e-4 * scale,
                "{name} case {case} {:?} at {ev:?} {params:?}: FD errors {errors:?}, J {j:?}",
                e.kind
            );
            seen[kind] = true;
            checked[kind][case % 5] += 1;
        }
    }
    for (kind, per_regime) in ["turn", "stick", "slip"].iter().zip(checked) {
        assert!(
            per_regime.iter().all(|&n| n >= 25),
            "{kind}: windows checked per regime {per_regime:?}"
        );
    }
}

/// The particular solution (y_p, y_p') at τ of a slide in direction `sign` (not the secular
/// case): y_p = −s + P cos(wτ + φ) + Q sin(wτ + φ).
fn particular(params: &Params, sign: f64, tau: f64) -> (f64, f64) {
    let (zeta, w, beta) = (params.zeta, params.w, params.beta);
    let detune = 1.0 - w * w;
    let den = detune * detune + 4.0 * zeta * zeta * w * w;
    let (p, q) = (beta * detune / den, 2.0 * beta * zeta * w / den);
    let (s, c) = (w * tau + params.phi).sin_cos();
    (-sign + p * c + q * s, w * (q * c - p * s))
}

/// Zero-duration stops, built in closed form: a slide in direction s⁻ that reaches y' = 0 at
/// τ_e = a exactly where s⁺(F − y) = μs (s⁺ = −s⁻) with the net force moving outward, found by
/// running the slide's closed form backwards from the event.
///
/// The flow then has two one-sided derivatives: along a direction d of perturbation either
/// the perturbed motion stops briefly (then D = Φ(b)·S_zero·Φ(a)·d with
/// S_zero = `saltation::zero_duration_stop`) or it turns (D = Φ(b)·S_turn·Φ(a)·d with
/// S_turn = `saltation::turn(s⁺μs, s⁻)`). Second-order one-sided differences along 12
/// directions (h = 1e-6: error O(h²) plus rounding 1e-16·|x|/h) must match the side the
/// perturbed run took, to 1e-6·(1 + max|J|); for μs > 1 both sides must occur, and at μs = 1
/// the two matrices must coincide (the flow is differentiable there). The tangent solver's
/// own Jacobian matches the side the solver took for the unperturbed run.
#[test]
fn zero_duration_stops_have_one_sided_derivatives_and_are_smooth_at_mu_s_one() {
    let mut rng = Rng(0x5eed_0003_4567_89ab);
    let (mut kinked, mut smooth) = (0, 0);
    for case in 0..240 {
        let (name, zeta, w) = regime(&mut rng, case % 4);
        let mu_s = if case % 3 == 0 {
            1.0
        } else {
            rng.range(1.2, 3.0)
        };
        let beta = rng.range(mu_s + 1.0, 8.0);
        let s_after = if rng.next() < 0.5 { 1.0 } else { -1.0 };
        let s_before = -s_after;
        // s⁺F' > 0: the net force moves outward through the static limit.
        let theta = -s_after * rng.range(0.3, std::f64::consts::PI - 0.3);
        let a = rng.range(0.3, 1.2);
        let params = Params::new(zeta, w, beta)
            .and_then(|p| p.with_phi((theta - w * a).rem_euclid(TAU)))
            .and_then(|p| p.with_mu_s(mu_s))
            .unwrap();
        let y_event = beta * theta.cos() - s_after * mu_s;
        let (yp_e, vp_e) = particular(&params, s_before, a);
        let (yp_0, vp_0) = particular(&params, s_before, 0.0);
        let phi = sliding_transition(zeta, a).0;
        let det = phi[0][0] * phi[1][1] - phi[0][1] * phi[1][0];
        let (u, v) = (y_event - yp_e, -vp_e);
        let x0 = State {
            y: yp_0 + (phi[1][1] * u - phi[0][1] * v) / det,
            v: vp_0 + (phi[0][0] * v - phi[1][0] * u) / det,
        };
        let events = flow(&params, x0, a + 3.0).1;
        let Some(first) = events.first() else {
            continue;
        };
        if (first.tau - a).abs() > 1e-9 || x0.v * s_before <= 0.0 {
            // The backward slide met another velocity zero on the way: not this case.
            continue;
        }
        let next = events
            .iter()
            .find(|e| e.tau > a + 1e-9)
            .map_or(a + 3.0, |e| e.tau);
        let b = (0.4 * (next - a)).min(0.5);
        let end = a + b;
        let (_, rate) = drive_and_rate(&params, a);
        let before = sliding_transition(zeta, a);
        let after = sliding_transition(zeta, b);
        let stop_side = after * saltation::zero_duration_stop(s_after, rate, mu_s) * before;
        let turn_side = after * saltation::turn(s_after * mu_s, s_before) * before;
        let scale = 1.0 + stop_side.max_abs().max(turn_side.max_abs());
        if mu_s == 1.0 {
            assert!(
                difference(&stop_side.0, &turn_side.0, &[0, 1]) <= 1e-14 * scale,
                "{name} case {case}: the two sides differ at mu_s = 1"
            );
        }
        // The solver's own decision for the unperturbed motion.
        let mut tangent = TangentSolver::new(params, x0);
        let mut nominal = Vec::new();
        tangent.run_until(end, |e| nominal.push(e.kind)).unwrap();
        let expected = match nominal[..] {
            [EventKind::Stick, EventKind::Slip] => stop_side,
            [EventKind::Turn] => turn_side,
            _ => panic!("{name} case {case}: events {nominal:?} at a zero-duration stop"),
        };
        let j = tangent.jacobian();
        assert!(
            difference(&j.0, &expected.0, &[0, 1]) <= 1e-8 * scale,
            "{name} case {case} {nominal:?}: tangent {j:?}, expected {expected:?}"
        );
        let (base, _) = flow(&params, x0, end);
        let mut sides = [0usize; 2];
        for k in 0..12 {
            let angle = (k as f64 + 0.5) * TAU / 12.0;
            let d = [angle.cos(), angle.sin()];
            let h = 1e-6;
            let run = |t: f64| {
                flow(
                    &params,
                    State {
                        y: x0.y + t * d[0],
                        v: x0.v + t * d[1],
                    },
                    end,
                )
            };
            let ((one, e1), (two, e2)) = (run(h), run(2.0 * h));
            let stops = |e: &[Event]| e.iter().any(|e| e.kind == EventKind::Stick);
            if stops(&e1) != stops(&e2) {
                // The ray runs along the boundary between the sides: no one-sided limit here.
                continue;
            }
            let side = usize::from(stops(&e1));
            sides[side] += 1;
            let jacobian = if side == 1 { stop_side } else { turn_side };
            let predicted = jacobian.apply(d);
            let fd = [
                (4.0 * one.y - 3.0 * base.y - two.y) / (2.0 * h),
                (4.0 * one.v - 3.0 * base.v - two.v) / (2.0 * h),
            ];
            let error = (fd[0] - predicted[0])
                .abs()
                .max((fd[1] - predicted[1]).abs());
            assert!(
                error <= 1e-6 * scale,
                "{name} case {case} mu_s {mu_s} direction {k} ({}): FD {fd:?}, predicted \
                 {predicted:?}",
                if side == 1 { "stop" } else { "turn" }
            );
        }
        if mu_s > 1.0 {
            assert!(
                sides[0] > 0 && sides[1] > 0,
                "{name} case {case}: one side only {sides:?}"
            );
            kinked += 1;
        } else {
            smooth += 1;
        }
    }
    assert!(
        kinked >= 60 && smooth >= 30,
        "cases: {kinked} kinked, {smooth} at mu_s = 1"
    );
}

// ---------------------------------------------------------------------------------------------
// Periodic orbits

/// Steady-state options for settling on orbits: no spectrum.
fn settling() -> SteadyOptions {
    SteadyOptions::default().with_spectrum(false)
}

/// The monodromy matrix of random periodic orbits (found by simulation, refined by Newton)
/// against central differences of the p-fold strobe map, in every regime and with μs from 1
/// to 3. The strobe map is smooth near an orbit that follows one sequence of events, so the
/// differences carry O(h²) and rounding O(10⁻¹⁶/h): the best of h = 1e-5, 1e-6, 1e-7 must
/// agree to 1e-6·(1 + max|M|) and h = 1e-6 to 1e-4·(1 + max|M|). Orbits stuck at their strobe
/// are checked in the δy column (see `stability::periodic_orbit`); orbits with a
/// zero-duration stop are left out (the map has a kink there, tested above). Also Liouville
/// with saltations: an orbit that never stops has det M = e^{−2ζpT}·Π_turns(a⁺/a⁻), each turn
/// with a⁺/a⁻ = (|F − y| − 1)/(|F − y| + 1), to 1e-10 relative.
#[test]
fn monodromy_matches_finite_differences_of_the_strobe_map() {
    let mut rng = Rng(0x5eed_0004_5678_9abc);
    let (mut sliding, mut sticking, mut stuck_strobe) = (0, 0, 0);
    for case in 0..160 {
        let (name, zeta, w) = regime(&mut rng, case % 4);
        let mu_s = if case % 2 == 0 {
            1.0
        } else {
            rng.range(1.0, 3.0)
        };
        let params = Params::new(zeta, w, rng.range(0.5, 8.0))
            .and_then(|p| p.with_phi(rng.range(0.0, TAU)))
            .and_then(|p| p.with_mu_s(mu_s))
            .unwrap();
        let initial = State {
            y: rng.range(-3.0, 3.0),
            v: rng.range(-2.0, 2.0),
        };
        let steady = steady_state_from(&exact_solver, &params, initial, &settling()).unwrap();
        if steady.period.is_none() || steady.longest_stop.is_infinite() {
            continue;
        }
        let orbit = periodic_orbit_from_steady(&params, &steady, &NewtonOptions::default())
            .unwrap_or_else(|e| panic!("{name} case {case} {params:?}: {e}"));
        if orbit.stops.iter().any(|s| s.duration == 0.0) {
            continue;
        }
        let m = orbit.monodromy;
        let p = orbit.period;
        let horizon = p as f64 * params.drive_period();
        let columns: &[usize] = if orbit.stuck_at_strobe { &[0] } else { &[0, 1] };
        let scale = 1.0 + m.max_abs();
        let errors: Vec<f64> = [1e-5, 1e-6, 1e-7]
            .iter()
            .map(|&h| {
                central_differences(&params, orbit.state, horizon, h, columns)
                    .map_or(f64::INFINITY, |fd| difference(&fd, &m.0, columns))
            })
            .collect();
        let best = errors.iter().copied().fold(f64::INFINITY, f64::min);
        assert!(
            best <= 1e-6 * scale && errors[1] <= 1e-4 * scale,
            "{name} case {case} {params:?} p {p}: FD errors {errors:?}, M {m:?}, events {:?}",
            orbit.events
        );
        if orbit.stops.is_empty() {
            let mut det = (-2.0 * zeta * horizon).exp();
            for e in &orbit.events {
                let net = (drive_and_rate(&params, e.tau).0 - e.y).abs();
                det *= (net - 1.0) / (net + 1.0);
            }
            assert!(
                (m.det() - det).abs() <= 1e-10 * det,
                "{name} case {case}: det M {} against {det}",
                m.det()
            );
            sliding += 1;
        } else {
            let image = strobe_map(&params, orbit.state, p).unwrap();
            assert!(
                image.log_det.is_none()
                    && orbit.multipliers[1].modulus() <= 1e-14 * m.max_abs()
                    && m.det().abs() <= 1e-14 * m.max_abs() * m.max_abs(),
                "{name} case {case}: a stop makes M singular, {m:?}"
            );
            sticking += 1;
            stuck_strobe += usize::from(orbit.stuck_at_strobe);
        }
    }
    assert!(
        sliding >= 20 && sticking >= 20 && stuck_strobe >= 3,
        "orbits: {sliding} sliding, {sticking} sticking ({stuck_strobe} stuck at the strobe)"
    );
}

/// Settled steady states, stable by construction, at the paper's points and with μs > 1,
/// periods 1, 3 and 13.
fn settled_points() -> Vec<(Params, usize)> {
    let paper = 0.046816;
    [
        (paper, 0.7, 1.2, 1.0, 1),
        (paper, 0.6, 1.2, 1.0, 1),
        (paper, 0.9, 1.6, 1.0, 1),
        (paper, 0.29, 2.14, 1.0, 1),
        (paper, 1.43, 2.14, 1.0, 1),
        (0.05, 0.9, 3.0, 1.5, 1),
        (0.02, 0.5, 6.0, 2.0, 1),
        (0.0, 0.39, 9.0, 3.0, 3),
        (0.0, 0.38, 9.0, 3.0, 13),
    ]
    .iter()
    .map(|&(zeta, w, beta, mu_s, p)| {
        (
            Params::new(zeta, w, beta)
                .and_then(|q| q.with_mu_s(mu_s))
                .unwrap(),
            p,
        )
    })
    .collect()
}

/// Newton's method from a settled steady state lands on the orbit the simulation settled on
/// (within 1e-8·scale: the simulation's tolerance is 1e-10 relative, amplified by 1/(1 − |μ|)
/// at most 5 here) in at most 6 steps, and from a guess 1e-2 away it converges quadratically:
/// every step from a residual r_n ≤ 1e-2 to one above 1e-14·scale (ten times the rounding of
/// the map) has r_{n+1} ≤ 10·r_n² (residuals in units of the kinetic friction force; linear
/// convergence at any rate q fails this once r_n < q/10), and there is such a step at every
/// point.
#[test]
fn newton_finds_the_orbit_a_long_simulation_settles_on_quadratically() {
    for (params, period) in settled_points() {
        let steady =
            steady_state_from(&exact_solver, &params, State::default(), &settling()).unwrap();
        assert_eq!(steady.period, Some(period), "{params:?}");
        let orbit =
            periodic_orbit_from_steady(&params, &steady, &NewtonOptions::default()).unwrap();
        let settled = steady.strobes[0];
        let scale = 1f64.max(settled.y.abs()).max(settled.v.abs());
        let distance = (orbit.state.y - settled.y)
            .abs()
            .max((orbit.state.v - settled.v).abs());
        assert!(
            orbit.iterations <= 6 && distance <= 1e-8 * scale,
            "{params:?}: {} iterations, {distance:e} from the settled strobe",
            orbit.iterations
        );
        assert_eq!(orbit.stability, Stability::Stable, "{params:?}");
        assert_eq!(orbit.residuals.len(), orbit.iterations + 1);
        let guess = State {
            y: orbit.state.y + 1e-2,
            v: if orbit.stuck_at_strobe {
                0.0
            } else {
                orbit.state.v - 1e-2
            },
        };
        let again = find_periodic_orbit(&params, guess, period, &NewtonOptions::default())
            .unwrap_or_else(|e| panic!("{params:?} from {guess:?}: {e}"));
        assert!(
            (again.state.y - orbit.state.y).abs() <= 1e-9 * scale
                && (again.state.v - orbit.state.v).abs() <= 1e-9 * scale,
            "{params:?}: {:?} against {:?}",
            again.state,
            orbit.state
        );
        let r = &again.residuals;
        let steps: Vec<f64> = r
            .windows(2)
            .filter(|t| t[0] <= 1e-2 && t[1] > 1e-14 * scale)
            .map(|t| t[1] / (t[0] * t[0]))
            .collect();
        assert!(
            !steps.is_empty() && steps.iter().all(|&k| k <= 10.0),
            "{params:?}: residuals {r:?}, r[n+1]/r[n]^2 {steps:?}"
        );
    }
}

/// Components of the eigenvector of `m` for the real eigenvalue `mu`, of unit max norm.
fn eigenvector(m: &Matrix2, mu: f64) -> [f64; 2] {
    let [[a, b], [c, d]] = m.0;
    let e = if b.abs() + (mu - a).abs() >= c.abs() + (mu - d).abs() {
        [b, mu - a]
    } else {
        [mu - d, c]
    };
    let n = e[0].abs().max(e[1].abs());
    [e[0] / n, e[1] / n]
}

/// Unstable orbits, found by Newton's method from a coarse grid of guesses in a chaotic window
/// (ζ = 0, μs = 3) and with damping and μs = 2 where a stable orbit coexists: at least one
/// unstable orbit at each point. A perturbation of 1e-7 along the unstable eigenvector grows
/// under the strobe map by |μ| per orbit period: every step with the perturbation below 1e-4
/// multiplies it by |μ| to 1e-3 relative (the nonlinear part is of the order of the
/// perturbation, and Newton's residual, ~1e-11, puts the orbit 1e-4 of the first perturbation
/// away at most), and it keeps the eigenvector's direction to 1e-3.
#[test]
fn unstable_orbits_are_found_and_perturbations_grow_at_their_multiplier() {
    let points = [
        (0.0, 0.33, 9.0, 3.0),
        (0.0, 0.47, 9.0, 3.0),
        (0.02, 0.5, 6.0, 2.0),
    ];
    for (zeta, w, beta, mu_s) in points {
        let params = Params::new(zeta, w, beta)
            .and_then(|p| p.with_mu_s(mu_s))
            .unwrap();
        let mut unstable: Vec<PeriodicOrbit> = Vec::new();
        for period in 1..=2 {
            for i in 0..13 {
                for j in 0..7 {
                    let guess = State {
                        y: -12.0 + 2.0 * i as f64,
                        v: -6.0 + 2.0 * j as f64,
                    };
                    let Ok(orbit) =
                        find_periodic_orbit(&params, guess, period, &NewtonOptions::default())
                    else {
                        continue;
                    };
                    let known = unstable.iter().any(|o| {
                        o.period == period
                            && (o.state.y - orbit.state.y).abs() < 1e-6
                            && (o.state.v - orbit.state.v).abs() < 1e-6
                    });
                    if orbit.stability == Stability::Unstable && !known {
                        unstable.push(orbit);
                    }
                }
            }
        }
        assert!(!unstable.is_empty(), "{params:?}: no unstable orbit found");
        for orbit in &unstable {
            let mu = orbit.multipliers[0];
            assert!(mu.is_real() && mu.re.abs() > 1.0, "{params:?}: {mu:?}");
            let e = eigenvector(&orbit.monodromy, mu.re);
            let epsilon = 1e-7;
            let x0 = orbit.state;
            let mut x = State {
                y: x0.y + epsilon * e[0],
                v: x0.v + epsilon * e[1],
            };
            let mut size = epsilon;
            let mut steps = 0;
            while size < 1e-4 {
                x = strobe_map(&params, x, orbit.period).unwrap().state;
                let delta = [x.y - x0.y, x.v - x0.v];
                let new_size = delta[0].abs().max(delta[1].abs());
                assert!(
                    (new_size / size - mu.re.abs()).abs() <= 1e-3 * mu.re.abs(),
                    "{params:?} p {} at {x0:?}: grew by {} against |mu| = {}",
                    orbit.period,
                    new_size / size,
                    mu.re.abs()
                );
                let off = |sign: f64| {
                    (delta[0] / new_size - sign * e[0])
                        .abs()
                        .max((delta[1] / new_size - sign * e[1]).abs())
                };
                assert!(
                    off(1.0).min(off(-1.0)) <= 1e-3,
                    "{params:?}: direction {delta:?} against {e:?}"
                );
                size = new_size;
                steps += 1;
            }
            assert!(steps >= 3, "{params:?}: {steps} steps");
        }
    }
}

// ---------------------------------------------------------------------------------------------
// Lyapunov exponents

/// The options of the Lyapunov tests: 1000 periods of transient, 20 000 measured in 20 blocks,
/// all of them (the fixed measurement; the sequential one is tested in lyapunov_sequential.rs).
fn measuring() -> LyapunovOptions {
    LyapunovOptions {
        sequential: false,
        ..LyapunovOptions::default()
    }
}

/// Chaotic points (ζ = 0, μs = 3, β = 9, in the two windows of the w sweep) and stable orbits:
/// the tangent estimate and the two-trajectory estimate (separation d₀ = 1e-8, its own solver
/// runs restarted every period) agree within 4 combined standard errors plus twice the
/// two-trajectory estimate's bias, which its block error does not see. The bias is O(d₀) (the
/// curvature of the map) and is estimated as the change of the estimate from d₀ to 2d₀. At
/// the chaotic points the exponent is positive beyond 4 standard errors; all estimates
/// converged.
#[test]
fn tangent_exponent_agrees_with_the_two_trajectory_estimate() {
    let chaotic = [
        (0.0, 0.30, 9.0, 3.0),
        (0.0, 0.33, 9.0, 3.0),
        (0.0, 0.47, 9.0, 3.0),
    ];
    let periodic = [
        (0.046816, 0.7, 1.2, 1.0),
        (0.046816, 0.9, 1.6, 1.0),
        (0.046816, 1.43, 2.14, 1.0),
        (0.02, 0.5, 6.0, 2.0),
    ];
    for (is_chaotic, points) in [(true, &chaotic[..]), (false, &periodic[..])] {
        for &(zeta, w, beta, mu_s) in points {
            let params = Params::new(zeta, w, beta)
                .and_then(|p| p.with_mu_s(mu_s))
                .unwrap();
            let tangent = lyapunov_exponents(&params, State::default(), &measuring()).unwrap();
            let two =
                two_trajectory_exponent(&params, State::default(), &measuring(), 1e-8).unwrap();
            let wider =
                two_trajectory_exponent(&params, State::default(), &measuring(), 2e-8).unwrap();
            let bias = (wider.largest.per_tau - two.largest.per_tau).abs();
            let (t, b) = (tangent.largest, two.largest);
            let combined = t.error_per_tau.hypot(b.error_per_tau);
            assert!(
                (t.per_tau - b.per_tau).abs() <= 4.0 * combined + 2.0 * bias,
                "{params:?}: tangent {t:?}, two trajectories {b:?}, bias {bias:e}"
            );
            assert!(tangent.converged && two.converged, "{params:?}");
            assert_eq!(
                t.per_tau > 4.0 * t.error_per_tau,
                is_chaotic,
                "{params:?}: {t:?}"
            );
            assert!((t.per_period - t.per_tau * params.drive_period()).abs() <= 1e-15);
        }
    }
}

/// Every periodic orbit's largest exponent, measured along the orbit from its strobe, is
/// ln|μ_max|/(pT) from Newton's monodromy matrix: within 4 standard errors plus 1e-9·|λ| (the
/// monodromy matrix and the long run round differently), and negative. The second exponent is
/// finite for sliding orbits, with λ₁ + λ₂ = ln|det M|/(pT) to 1e-9 (Liouville with the turns'
/// saltations), and −∞ for orbits that stop.
#[test]
fn every_periodic_orbit_has_the_exponent_of_its_largest_multiplier() {
    let options = LyapunovOptions {
        transient_periods: 200,
        periods: 4000,
        ..LyapunovOptions::default()
    };
    for (params, _) in settled_points() {
        let steady =
            steady_state_from(&exact_solver, &params, State::default(), &settling()).unwrap();
        let orbit =
            periodic_orbit_from_steady(&params, &steady, &NewtonOptions::default()).unwrap();
        let lyap = lyapunov_exponents(&params, orbit.state, &options).unwrap();
        let expected = orbit.exponent();
        let l = lyap.largest;
        assert!(
            expected < 0.0
                && (l.per_tau - expected).abs() <= 4.0 * l.error_per_tau + 1e-9 * expected.abs(),
            "{params:?}: Lyapunov {l:?}, ln|mu|/pT = {expected}"
        );
        match lyap.second {
            SecondExponent::Finite(second) => {
                assert!(orbit.stops.is_empty(), "{params:?}");
                let horizon = orbit.period as f64 * params.drive_period();
                let contraction = orbit.monodromy.det().ln() / horizon;
                assert!(
                    (l.per_tau + second.per_tau - contraction).abs() <= 1e-9 * contraction.abs(),
                    "{params:?}: {l:?} + {second:?} against ln det M / pT = {contraction}"
                );
            }
            SecondExponent::MinusInfinity { stops } => {
                assert!(stops > 0 && !orbit.stops.is_empty(), "{params:?}");
                assert_eq!(lyap.second.per_tau(), f64::NEG_INFINITY);
            }
        }
    }
}

/// The verdicts: chaos in the window at w = 0.33 (ζ = 0, μs = 3, β = 9); contraction at the
/// paper's Fig. 6 point (0.7, 1.2) and at (ζ, μs, w, β) = (0, 2.5, 0.4227, 3.627), whose strobe
/// map does not repeat within 5000 periods but which contracts slowly onto a stable period-1
/// orbit (its exponent equals that orbit's ln|μ|/T; a measurement still in the approach is
/// undecided); rest (β < μs from rest) has exponent 0
/// exactly, the verdict for neither growth nor decay; and a measurement that begins in a
/// transient disagrees between its halves (undecided).
#[test]
fn classify_nonperiodic_tells_chaos_from_contraction() {
    let verdict = |zeta: f64, w: f64, beta: f64, mu_s: f64, options: &LyapunovOptions| {
        let params = Params::new(zeta, w, beta)
            .and_then(|p| p.with_mu_s(mu_s))
            .unwrap();
        classify_nonperiodic(&params, State::default(), options).unwrap()
    };
    let c = verdict(0.0, 0.33, 9.0, 3.0, &measuring());
    assert_eq!(
        c.verdict,
        NonperiodicVerdict::Chaotic,
        "{:?}",
        c.exponents.largest
    );
    let c = verdict(0.046816, 0.7, 1.2, 1.0, &measuring());
    assert_eq!(c.verdict, NonperiodicVerdict::Contracting);

    let slow = Params::new(0.0, 0.4227, 3.627)
        .and_then(|p| p.with_mu_s(2.5))
        .unwrap();
    // Its multiplier is 0.9991 per period: 1000 periods of transient leave the measurement
    // in the approach (undecided); 20 000 do not.
    let c = classify_nonperiodic(&slow, State::default(), &measuring()).unwrap();
    assert_eq!(c.verdict, NonperiodicVerdict::Undecided);
    let long = LyapunovOptions {
        transient_periods: 20_000,
        ..measuring()
    };
    let c = classify_nonperiodic(&slow, State::default(), &long).unwrap();
    assert_eq!(c.verdict, NonperiodicVerdict::Contracting);
    let steady = steady_state_from(
        &exact_solver,
        &slow,
        State::default(),
        &settling().with_max_periods(40_000).unwrap(),
    )
    .unwrap();
    assert_eq!(steady.period, Some(1));
    let orbit = periodic_orbit_from_steady(&slow, &steady, &NewtonOptions::default()).unwrap();
    let l = c.exponents.largest;
    assert!(
        (l.per_tau - orbit.exponent()).abs() <= 4.0 * l.error_per_tau + 1e-9 * l.per_tau.abs(),
        "{l:?} against ln|mu|/T = {}",
        orbit.exponent()
    );

    let rest = verdict(0.05, 0.8, 0.5, 1.0, &measuring());
    assert_eq!(rest.exponents.largest.per_tau, 0.0);
    assert_eq!(rest.verdict, NonperiodicVerdict::QuasiPeriodic);

    let early = LyapunovOptions {
        transient_periods: 0,
        periods: 200,
        ..LyapunovOptions::default()
    };
    let c = verdict(0.046816, 0.7, 1.2, 1.0, &early);
    assert_eq!(
        c.verdict,
        NonperiodicVerdict::Undecided,
        "{:?}",
        c.exponents
    );
}

/// Typed errors: Newton's method that cannot converge in its iterations, a tangential
/// release, iterates that run onto the jump of the strobe map, a steady state without a
/// period, and invalid arguments.
#[test]
fn failures_are_typed() {
    let params = Params::new(0.0, 0.33, 9.0)
        .and_then(|p| p.with_mu_s(3.0))
        .unwrap();
    let one_step = NewtonOptions {
        max_iterations: 1,
        ..NewtonOptions::default()
    };
    match find_periodic_orbit(&params, State { y: -10.0, v: -5.0 }, 1, &one_step) {
        Err(Error::Stability(StabilityError::NoConvergence { iterations: 1, .. })) => {}
        other => panic!("{other:?}"),
    }
    // At rest where the net force is exactly −μs with the drive at its maximum: the release
    // is tangential.
    let tangential = Params::new(0.02, 0.5, 6.0)
        .and_then(|p| p.with_mu_s(2.0))
        .unwrap();
    match strobe_map(&tangential, State { y: 8.0, v: 0.0 }, 1) {
        Err(Error::Stability(StabilityError::NonFiniteJacobian { tau })) => assert_eq!(tau, 0.0),
        other => panic!("{other:?}"),
    }
    assert!(matches!(
        strobe_map(&params, State::default(), 0),
        Err(Error::InvalidParameter {
            name: "periods",
            ..
        })
    ));
    // From this guess the period-2 iterates run onto y' = 0 at a net force of about 2.15,
    // between the kinetic and the static limit (μs = 3), where the map jumps: with y' = 0
    // exactly the oscillator stays stuck and lands far from the limit point.
    match find_periodic_orbit(
        &params,
        State { y: -8.0, v: 1.0 },
        2,
        &NewtonOptions::default(),
    ) {
        Err(Error::Stability(StabilityError::OnDiscontinuity { y, v, net_force })) => {
            // The iterates creep onto y' = 0 by halved steps; they are reported on the jump
            // once y' is no larger than the residual (about 1e-10 after the 30 steps).
            assert!(
                v.abs() < 1e-9 && net_force > 1.0 && net_force < 3.0,
                "{y} {v}"
            );
            let stuck = strobe_map(&params, State { y, v: 0.0 }, 2).unwrap();
            assert!(stuck.stuck_at_start && (stuck.state.y - y).abs() > 1.0);
        }
        other => panic!("{other:?}"),
    }
    // A chaotic motion has no period to refine.
    let chaotic = steady_state_from(&exact_solver, &params, State::default(), &settling()).unwrap();
    match periodic_orbit_from_steady(&params, &chaotic, &NewtonOptions::default()) {
        Err(Error::Stability(StabilityError::NoPeriod { periods_run, .. })) => {
            assert_eq!(periods_run, SteadyOptions::default().max_periods)
        }
        other => panic!("{other:?}"),
    }
    let loose = NewtonOptions {
        tolerance: 1.0,
        ..NewtonOptions::default()
    };
    assert!(matches!(
        find_periodic_orbit(&params, State::default(), 1, &loose),
        Err(Error::InvalidOption {
            option: stickslip::OptionKey::NewtonTolerance,
            ..
        })
    ));
}

/// Invalid options and separations are rejected, naming the field.
#[test]
fn lyapunov_options_are_validated() {
    let params = Params::new(0.05, 0.9, 1.6).unwrap();
    let odd_blocks = LyapunovOptions {
        blocks: 5,
        ..LyapunovOptions::default()
    };
    assert!(matches!(
        lyapunov_exponents(&params, State::default(), &odd_blocks),
        Err(Error::InvalidOption {
            option: stickslip::OptionKey::Blocks,
            ..
        })
    ));
    let short = LyapunovOptions {
        periods: 10,
        ..LyapunovOptions::default()
    };
    let e = classify_nonperiodic(&params, State::default(), &short).unwrap_err();
    assert_eq!(e.option(), Some(stickslip::OptionKey::LyapunovMeasured));
    assert_eq!(
        e.to_string(),
        "invalid periods = 10: must be from blocks (20) to 1e9"
    );
    assert_eq!(
        e.render(stickslip::Spelling::Flag),
        "invalid --periods 10: must be from --blocks (20) to 1e9"
    );
    assert!(matches!(
        two_trajectory_exponent(&params, State::default(), &measuring(), 0.0),
        Err(Error::InvalidParameter {
            name: "separation",
            ..
        })
    ));
}

/// At ζ = 0, w = ½, β = 5, φ = π + 0.5 Newton's method converges linearly onto the edge of
/// a family of period-1 orbits and stops, at its tolerance, on an orbit with a short stop
/// whose length depends on the start. Its modulus is cos(stop) (checked here), so it goes to
/// 1 as the stop shrinks to the edge: the verdict is neutral, not stable.
#[test]
fn orbit_at_the_edge_of_the_neutral_family_at_zeta_0_w_half_is_neutral_not_stable() {
    let params = Params::new(0.0, 0.5, 5.0)
        .and_then(|p| p.with_phi(3.64159265358979))
        .unwrap();
    let mut durations = Vec::new();
    for (y, v) in [(-6.4, 1.0), (-7.0, 1.5), (-6.0, 0.5)] {
        let orbit =
            find_periodic_orbit(&params, State { y, v }, 1, &NewtonOptions::default()).unwrap();
        assert_eq!(orbit.stability, Stability::Neutral, "from ({y}, {v})");
        assert!(
            orbit.residuals.len() > 15,
            "linear convergence: {:?}",
            orbit.residuals
        );
        assert_eq!(orbit.stops.len(), 1);
        let stop = orbit.stops[0].duration;
        let modulus = orbit.multipliers[0].modulus();
        assert!(
            (modulus - stop.cos()).abs() < 1e-9,
            "{modulus} against cos({stop})"
        );
        assert!(1.0 - modulus > 1e-9, "outside the band of 1e-9: {modulus}");
        durations.push(stop);
    }
    // The start decides where the iteration stops along the flat direction.
    durations.sort_by(f64::total_cmp);
    assert!(durations[2] - durations[0] > 1e-5, "{durations:?}");
}

/// At ζ = 0, w = 1/(2n) the sliding orbit is one of a family (docs/stability.md, "A neutral
/// family"): y + A·cos(τ − τ_turn) is a periodic orbit for every small A, so the strobe map
/// has a line of fixed points and its Jacobian the eigenvalue 1, with the eigenvector
/// (cos τ_turn, sin τ_turn). The computed multiplier is 1 to rounding there, and the verdict
/// neutral; at nearby w it is not.
#[test]
fn the_sliding_orbit_at_zeta_0_w_one_over_2n_has_multiplier_one() {
    use stickslip::theory::{stick_slip_boundary, PeriodicSolution};
    for n in 1..=3u32 {
        let w = 1.0 / (2.0 * f64::from(n));
        let beta = 1.5 * stick_slip_boundary(0.0, w, 1.0).unwrap().beta_c;
        let params = Params::new(0.0, w, beta).unwrap();
        let solution = PeriodicSolution::new(&params).unwrap();
        let orbit = find_periodic_orbit(
            &params,
            solution.state_at(0.0),
            1,
            &NewtonOptions::default(),
        )
        .unwrap();
        assert!(orbit.events.iter().all(|e| e.kind == EventKind::Turn));
        let m = orbit.multipliers;
        assert!(
            (m[0].re - 1.0).abs() < 1e-12 && m[0].im == 0.0,
            "n {n}: {m:?}"
        );
        assert_eq!(orbit.stability, Stability::Neutral, "n {n}");
        // The family's direction is the eigenvector of 1.
        let t = solution.first_lower_turn();
        let e = [t.cos(), t.sin()];
        let j = orbit.monodromy.0;
        let me = [
            j[0][0] * e[0] + j[0][1] * e[1],
            j[1][0] * e[0] + j[1][1] * e[1],
        ];
        assert!(
            (me[0] - e[0]).abs() < 1e-10 && (me[1] - e[1]).abs() < 1e-10,
            "n {n}: M·e = {me:?}, e = {e:?}"
        );
        for factor in [0.98, 1.02] {
            let near = Params::new(0.0, w * factor, beta).unwrap();
            let s = PeriodicSolution::new(&near).unwrap();
            let o =
                find_periodic_orbit(&near, s.state_at(0.0), 1, &NewtonOptions::default()).unwrap();
            let m = o.multipliers;
            let distance = (m[0].re - 1.0).hypot(m[0].im);
            assert!(distance > 1e-3, "n {n}, w × {factor}: {m:?}");
            assert_ne!(
                o.stability,
                Stability::Neutral,
                "n {n}, w × {factor}: {m:?}"
            );
        }
    }
}
