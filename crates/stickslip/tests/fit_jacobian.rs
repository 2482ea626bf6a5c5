//! The exact parameter sensitivities of periodic orbits (the fit's Jacobians) against central
//! finite differences of orbits found afresh by Newton's method at shifted parameters.

use stickslip::stability::{find_periodic_orbit, periodic_orbit_sensitivity, NewtonOptions};
use stickslip::steady::{steady_state_from, SteadyOptions};
use stickslip::{ExactSolver, MotionClass, Params, State};
use stickslip_testkit::{driven, keysight, quantise, sample_steady, truth, Rng, Synthetic};

/// The periodic orbit the motion from rest settles on, polished by Newton's method:
/// (fixed point, period, class).
fn orbit(params: &Params) -> (State, usize, MotionClass) {
    let factory = stickslip::experiment::Experiment::paper().factory();
    let steady = steady_state_from(
        &factory,
        params,
        State::default(),
        &SteadyOptions::default().with_spectrum(false),
    )
    .unwrap();
    let period = steady.period.expect("a periodic motion");
    let polished = find_periodic_orbit(
        params,
        steady.final_state(),
        period,
        &NewtonOptions::default(),
    )
    .unwrap();
    (polished.state, period, steady.class)
}

/// y at `taus` on the orbit of `params` near `guess`.
fn samples(params: &Params, guess: State, period: usize, taus: &[f64]) -> Vec<f64> {
    let options = NewtonOptions {
        tolerance: 1e-14,
        ..NewtonOptions::default()
    };
    let fixed = find_periodic_orbit(params, guess, period, &options)
        .unwrap()
        .state;
    let mut solver = ExactSolver::new(*params, fixed);
    stickslip::solver::sample_at(&mut solver, taus, |_| {})
        .unwrap()
        .iter()
        .map(|s| s.y)
        .collect()
}

fn shifted(params: &Params, p: usize, value: f64) -> Params {
    let mut q = *params;
    match p {
        0 => q.zeta = value,
        1 => q.beta = value,
        2 => q.w = value,
        3 => q.phi = value,
        _ => q.mu_s = value,
    }
    q.validate().unwrap()
}

/// Every column of the exact sensitivities against Richardson-extrapolated central
/// differences, within `tolerance` of the column's largest entry.
fn check(params: Params, expect: MotionClass, expect_period: usize, columns: &[usize]) {
    let (fixed, period, class) = orbit(&params);
    assert_eq!((class, period), (expect, expect_period), "{params:?}");
    let span = (period + 1) as f64 * params.drive_period();
    let taus: Vec<f64> = (0..240).map(|k| span * k as f64 / 239.0).collect();
    let exact = periodic_orbit_sensitivity(&params, fixed, period, &taus).unwrap();
    let values = [params.zeta, params.beta, params.w, params.phi, params.mu_s];
    for &p in columns {
        let h = 1e-4 * values[p].abs().max(0.1);
        let central = |h: f64| -> Vec<f64> {
            let up = samples(&shifted(&params, p, values[p] + h), fixed, period, &taus);
            let down = samples(&shifted(&params, p, values[p] - h), fixed, period, &taus);
            up.iter()
                .zip(&down)
                .map(|(a, b)| (a - b) / (2.0 * h))
                .collect()
        };
        let (coarse, fine) = (central(h), central(h / 2.0));
        let richardson: Vec<f64> = fine
            .iter()
            .zip(&coarse)
            .map(|(f, c)| (4.0 * f - c) / 3.0)
            .collect();
        let size = richardson.iter().fold(0.0f64, |a, v| a.max(v.abs()));
        assert!(size > 0.0, "column {p} is zero");
        let mut worst = 0.0f64;
        for (s, fd) in exact.iter().zip(&richardson) {
            worst = worst.max((s.dy[p] - fd).abs() / size);
        }
        eprintln!("{params:?} column {p}: {worst:e} of {size:e}");
        assert!(
            worst < 1e-6,
            "{params:?} column {p}: worst deviation {worst:e} of the largest entry {size:e}"
        );
    }
}

/// The paper's circuit: ζ = 71 Ω/2·√(C/L).
fn paper_zeta() -> f64 {
    35.5 * (0.02e-6f64 / 11.5e-3).sqrt()
}

#[test]
fn a_sliding_orbit_matches_finite_differences() {
    let params = Params::new(paper_zeta(), 1.43, 3.0)
        .unwrap()
        .with_phi(0.7)
        .unwrap();
    check(params, MotionClass::Sliding, 1, &[0, 1, 2, 3]);
}

#[test]
fn a_stick_slip_orbit_with_stops_matches_finite_differences() {
    // The paper's parameters at w = 0.29: two stops per period.
    let params = Params::new(paper_zeta(), 0.29, 2.6)
        .unwrap()
        .with_phi(0.4)
        .unwrap();
    check(params, MotionClass::PeriodicStick, 1, &[0, 1, 2, 3]);
}

#[test]
fn static_friction_above_kinetic_moves_the_releases() {
    // μs > 1: every release's time depends on β, w, φ and μs.
    let params = Params::new(paper_zeta(), 0.29, 2.6)
        .unwrap()
        .with_phi(0.4)
        .unwrap()
        .with_mu_s(1.3)
        .unwrap();
    check(params, MotionClass::PeriodicStick, 1, &[0, 1, 2, 3, 4]);
}

#[test]
fn a_period_two_stick_slip_orbit_matches_finite_differences() {
    // ζ = 0, μs = 3, w = 0.43, β = 13.5: a period-2 stick-slip cycle (see
    // tests/newton_settling.rs).
    let params = Params::new(0.0, 0.43, 13.5)
        .unwrap()
        .with_mu_s(3.0)
        .unwrap();
    check(params, MotionClass::PeriodicStick, 2, &[1, 2, 3, 4]);
}

#[test]
fn an_overdamped_orbit_matches_finite_differences() {
    let params = Params::new(1.6, 0.5, 4.0).unwrap().with_phi(-1.0).unwrap();
    let class = orbit(&params).2;
    check(params, class, 1, &[0, 1, 2, 3]);
}

/// A Keysight export of the circuit R = 80 Ω, U_t = 0.6 V at (w, β, φ): 1200 samples over
/// 3.4 periods, 8 bits over 1.25 times each channel's peak-to-peak, one step of noise, an
/// offset of 30 mV on u_C.
fn record(w: f64, beta: f64, phi: f64, rng: &mut Rng) -> stickslip::measure::Measurement {
    let e = driven(truth(), w, beta, phi);
    let n = 1200;
    let dt = 3.4 * std::f64::consts::TAU / (w * e.scales().unwrap().omega0) / n as f64;
    let s = sample_steady(&e, n, dt);
    let response: Vec<f64> = s.response.iter().map(|r| r + 0.03).collect();
    let drive = quantise(&s.drive, 256.0, 1.0, rng);
    let response = quantise(&response, 256.0, 1.0, rng);
    let text = keysight(&Synthetic::new(drive, response, 0.0, dt));
    let r = stickslip::measure::read_scope(&text, "k.csv").unwrap();
    stickslip::measure::Measurement::new(&r, None, None).unwrap()
}

#[test]
fn fits_with_exact_and_finite_difference_jacobians_agree_within_their_errors() {
    use stickslip::fit::{fit_records, FitOptions, FitParameter, Jacobian};
    let mut rng = Rng(2027);
    let data: Vec<_> = [(0.29, 2.6, 0.4), (0.95, 2.14, -1.1), (1.43, 3.0, 2.5)]
        .iter()
        .map(|&(w, beta, phi)| record(w, beta, phi, &mut rng))
        .collect();
    let free = [FitParameter::Resistance, FitParameter::Ut];
    let start = stickslip::experiment::Experiment::paper();
    let exact = fit_records(&start, &data, &free, &FitOptions::default()).unwrap();
    let fd = fit_records(
        &start,
        &data,
        &free,
        &FitOptions {
            exact_jacobian: false,
            ..FitOptions::default()
        },
    )
    .unwrap();
    assert_eq!(exact.jacobian, Jacobian::Exact);
    assert_eq!(fd.jacobian, Jacobian::FiniteDifferences);
    assert_eq!(exact.to_json().jacobian, "exact");
    assert!(exact.converged && fd.converged);
    for (e, f) in exact.parameters.iter().zip(&fd.parameters) {
        eprintln!(
            "{}: exact {} ± {}, finite differences {} ± {}",
            e.parameter, e.value, e.stderr, f.value, f.stderr
        );
        // The same minimum, to a thousandth of the error bars, which agree to 10⁻⁴.
        assert!((e.value - f.value).abs() < 1e-3 * e.stderr, "{e:?} {f:?}");
        assert!((e.stderr - f.stderr).abs() < 1e-4 * e.stderr, "{e:?} {f:?}");
    }
    // And the truth within 1 %.
    assert!((exact.parameters[0].value - 80.0).abs() < 0.8);
    assert!((exact.parameters[1].value - 0.6).abs() < 0.006);
}
