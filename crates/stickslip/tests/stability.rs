//! Tests of the stability analysis: the tangent dynamics against finite differences of the
//! exact flow.

use std::f64::consts::TAU;
use stickslip::solver::run_until;
use stickslip::stability::{saltation, sliding_transition, stuck_transition, TangentSolver};
use stickslip::{Event, EventKind, ExactSolver, Params, Phase, Solver, State};

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
