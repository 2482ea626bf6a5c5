//! Every documented limit (`docs/limits.md`, `stickslip::limits`): just inside, the value is
//! accepted and the solver runs; just outside, it is refused with one line naming the value
//! and its range.

use stickslip::experiment::{ExperimentSpec, Key, Preset};
use stickslip::limits::{self, TAU_MAX};
use stickslip::scan::{Axis, Grid};
use stickslip::solver::{run_until, stream, Record};
use stickslip::stability::{lyapunov_exponents, LyapunovOptions};
use stickslip::steady::SteadyOptions;
use stickslip::{Error, ExactSolver, Experiment, Parameter, Params, Solver, State};

/// Just inside and just outside a lower bound > 0.
fn above(bound: f64) -> (f64, f64) {
    (bound * (1.0 + 1e-9), bound * (1.0 - 1e-9))
}

/// Just inside and just outside an upper bound (of |x| for a negative bound).
fn around(bound: f64) -> (f64, f64) {
    let step = if bound == 0.0 {
        1e-300
    } else {
        bound.abs() * 1e-9
    };
    if bound > 0.0 {
        (bound - step, bound + step)
    } else {
        (bound + step, bound - step)
    }
}

/// The message of a refusal: one line with the name, the value and the range.
fn assert_refused<T: std::fmt::Debug>(result: Result<T, Error>, name: &str, range: &str) {
    let err = result.expect_err("refused");
    let text = err.to_string();
    assert_eq!(text.lines().count(), 1, "{text}");
    assert!(text.contains(name), "{name} not in: {text}");
    assert!(text.contains(range), "{range} not in: {text}");
    assert!(text.contains("docs/limits.md"), "{text}");
}

/// Run the exact solver for 20 drive periods (τ ≤ 2000 at most) and check the motion stays
/// finite.
fn runs(params: Params, initial: State) {
    let mut solver = ExactSolver::new(params, initial);
    let end = (20.0 * params.drive_period()).min(2000.0);
    let mut events = 0u64;
    run_until(&mut solver, end, |e| {
        events += 1;
        assert!(e.tau.is_finite() && e.y.is_finite(), "{e:?}");
    })
    .unwrap_or_else(|e| panic!("{params:?} from {initial:?}: {e}"));
    let s = solver.state();
    assert!(s.y.is_finite() && s.v.is_finite(), "{params:?}: {s:?}");
}

fn params(zeta: f64, w: f64, beta: f64) -> Result<Params, Error> {
    Params::new(zeta, w, beta)
}

#[test]
fn zeta_from_0_to_1e4() {
    let (inside, outside) = around(limits::ZETA_MAX);
    runs(
        params(inside, 0.9, 50.0).unwrap(),
        State { y: 1e3, v: -1e3 },
    );
    runs(params(0.0, 0.9, 1.6).unwrap(), State::default());
    assert_refused(
        params(outside, 0.9, 1.6),
        "zeta = 10000.00001",
        "from 0 to 1e4",
    );
    assert_refused(params(-1e-300, 0.9, 1.6), "zeta", "from 0 to 1e4");
    assert_refused(Key::Zeta.check(outside), "zeta", "from 0 to 1e4");
}

#[test]
fn w_from_1e_5_to_1e5() {
    let (inside, outside) = above(limits::W_MIN);
    runs(params(0.05, inside, 3.0).unwrap(), State { y: 0.5, v: 0.0 });
    assert_refused(params(0.05, outside, 1.6), "w = ", "from 1e-5 to 1e5");
    assert_refused(params(0.05, 1e-300, 1.6), "w = ", "from 1e-5 to 1e5");
    let (inside, outside) = around(limits::W_MAX);
    runs(params(0.05, inside, 1e9).unwrap(), State::default());
    assert_refused(params(0.05, outside, 1.6), "w = ", "from 1e-5 to 1e5");
    assert_refused(Key::W.check(outside), "w", "from 1e-5 to 1e5");
}

#[test]
fn beta_from_0_to_1e9() {
    let (inside, outside) = around(limits::BETA_MAX);
    runs(params(0.0468, 1.0, inside).unwrap(), State::default());
    runs(params(0.0, 1.0, inside).unwrap(), State::default());
    assert_refused(params(0.0468, 1.0, outside), "beta = ", "from 0 to 1e9");
    assert_refused(params(0.0468, 1.0, 1e300), "beta = ", "from 0 to 1e9");
    assert_refused(Key::Beta.check(outside), "beta", "from 0 to 1e9");
}

#[test]
fn mu_s_from_1_to_1e9() {
    let (inside, outside) = around(limits::MU_S_MAX);
    let p = params(0.0468, 0.7, limits::BETA_MAX).unwrap();
    runs(p.with_mu_s(inside).unwrap(), State::default());
    assert_refused(p.with_mu_s(outside), "mu_s = ", "from 1 to 1e9");
    assert_refused(p.with_mu_s(0.999), "mu_s = ", "from 1 to 1e9");
    assert_refused(Key::MuS.check(outside), "mu_s", "from 1 to 1e9");
}

#[test]
fn phi_within_1e6() {
    let (inside, outside) = around(limits::PHI_MAX);
    let p = params(0.0468, 0.7, 1.2).unwrap();
    runs(p.with_phi(inside).unwrap(), State::default());
    runs(p.with_phi(-inside).unwrap(), State::default());
    assert_refused(p.with_phi(outside), "phi = ", "from -1e6 to 1e6");
    assert_refused(p.with_phi(-outside), "phi = ", "from -1e6 to 1e6");
    assert_refused(Key::Phi.check(outside), "phi", "from -1e6 to 1e6");
}

#[test]
fn initial_state_within_1e9() {
    let (inside, outside) = around(limits::STATE_MAX);
    let p = params(0.0468, 0.9, 1.6).unwrap();
    for (y, v) in [(inside, 0.0), (-inside, inside), (0.0, -inside)] {
        let state = limits::check_state(y, v).unwrap();
        runs(p, state);
    }
    assert_refused(
        limits::check_state(outside, 0.0),
        "y0 = ",
        "from -1e9 to 1e9",
    );
    assert_refused(
        limits::check_state(0.0, -outside),
        "v0 = ",
        "from -1e9 to 1e9",
    );
    assert_refused(Key::Y0.check(1e300), "y0", "from -1e9 to 1e9");
    assert_refused(Key::V0.check(-outside), "v0", "from -1e9 to 1e9");
    let e = Experiment::dimensionless(0.05, 0.9, 1.6).unwrap();
    assert_refused(
        e.clone().with_initial(State { y: outside, v: 0.0 }),
        "y0",
        "from -1e9 to 1e9",
    );
    assert!(e.with_initial(State { y: inside, v: 0.0 }).is_ok());
}

/// The paper's circuit: ω0 = 65938 rad/s, U_t = 0.7 V, √(L/C) = 758.3 Ω.
fn paper(pairs: &[(Key, f64)]) -> Result<Experiment, Error> {
    let mut spec = ExperimentSpec::new();
    spec.set_preset(Preset::Paper);
    for &(k, v) in pairs {
        spec.set(k, v)?;
    }
    spec.build()
}

#[test]
fn physical_values_are_checked_through_their_images() {
    let omega0 = Experiment::paper().scales().unwrap().omega0;
    let f_max = limits::W_MAX * omega0 / std::f64::consts::TAU;
    let (inside, outside) = around(f_max);
    assert!(paper(&[(Key::Frequency, inside), (Key::Beta, 1.0)]).is_ok());
    let err = paper(&[(Key::Frequency, outside), (Key::Beta, 1.0)]).unwrap_err();
    assert!(
        matches!(
            err,
            Error::ImageOutOfRange {
                key: Key::Frequency,
                ..
            }
        ),
        "{err:?}"
    );
    assert_refused(Err::<(), _>(err), "invalid f = ", "it gives w = 100000.000");
    let (inside, outside) = above(limits::W_MIN * omega0);
    paper(&[(Key::Omega, inside), (Key::Beta, 1.0)]).unwrap();
    assert_refused(
        paper(&[(Key::Omega, outside), (Key::Beta, 1.0)]),
        "invalid omega = ",
        "from 1e-5 to 1e5",
    );
    let (inside, outside) = around(limits::BETA_MAX * 0.7);
    assert!(paper(&[(Key::Amplitude, inside), (Key::W, 1.0)]).is_ok());
    assert_refused(
        paper(&[(Key::Amplitude, outside), (Key::W, 1.0)]),
        "invalid U = ",
        "from 0 to 1e9",
    );
    let (inside, outside) = around(limits::STATE_MAX * 0.7);
    assert!(paper(&[(Key::Uc0, inside)]).is_ok());
    assert_refused(paper(&[(Key::Uc0, -outside)]), "invalid uc0 = ", "gives y0");
    let impedance = (11.5e-3f64 / 0.02e-6).sqrt();
    let (inside, outside) = around(limits::STATE_MAX * 0.7 / impedance);
    assert!(paper(&[(Key::I0, inside)]).is_ok());
    assert_refused(paper(&[(Key::I0, outside)]), "invalid i0 = ", "gives v0");
    // ζ = (R + R_D)/2·√(C/L): R is its knob.
    let r_max = 2.0 * limits::ZETA_MAX * impedance - 3.0;
    let (inside, outside) = around(r_max);
    assert!(paper(&[(Key::Resistance, inside)]).is_ok());
    assert_refused(
        paper(&[(Key::Resistance, outside)]),
        "invalid R = ",
        "gives zeta",
    );
    // A mechanical oscillator: ζ = γ/(2√(km)).
    let mech = |gamma: f64| {
        let mut spec = ExperimentSpec::new();
        for (k, v) in [
            (Key::Mass, 1.0),
            (Key::Stiffness, 1.0),
            (Key::Damping, gamma),
            (Key::Friction, 1.0),
        ] {
            spec.set(k, v).unwrap();
        }
        spec.build()
    };
    let (inside, outside) = around(2.0 * limits::ZETA_MAX);
    assert!(mech(inside).is_ok());
    assert_refused(mech(outside), "invalid gamma = ", "gives zeta");
    // L and C whose product or ratio leaves the range of doubles.
    let mut spec = ExperimentSpec::new();
    for (k, v) in [
        (Key::Inductance, 1e-200),
        (Key::Capacitance, 1e-200),
        (Key::Resistance, 1.0),
        (Key::TurnOn, 0.7),
        (Key::DiodeResistance, 0.0),
    ] {
        spec.set(k, v).unwrap();
    }
    let text = spec.build().unwrap_err().to_string();
    assert!(
        text.contains("invalid L = ") && text.contains("ω0"),
        "{text}"
    );
}

#[test]
fn runs_end_before_time_or_phase_lose_their_resolution() {
    // At w ≤ 1 the time bounds the run, above 1 the drive phase.
    for w in [1e-5, 0.01, 1.0, 50.0] {
        let p = params(0.05, w, 1.6).unwrap();
        let max = limits::max_periods(&p);
        assert!((max - TAU_MAX / std::f64::consts::TAU * w.min(1.0)).abs() <= 1e-9 * max);
        let (inside, outside) = around(max);
        assert!(limits::check_horizon(&p, inside).is_ok());
        let text = limits::check_horizon(&p, outside).unwrap_err().to_string();
        assert!(
            text.contains("too long") && text.contains("docs/limits.md"),
            "{text}"
        );
        // A stream to just past the end is refused before any work; to the end it runs.
        let mut solver = ExactSolver::new(p, State::default());
        let end = max * p.drive_period();
        assert!(stream(&mut solver, 0.0, end * (1.0 + 1e-9), 4).is_err());
        assert!(solver.time() == 0.0);
        assert!(stream(&mut solver, 0.0, end * (1.0 - 1e-9), 4).is_ok());
    }
    // The steady-state cap: 5000 periods fit at the lowest w; a cap past the range is
    // refused before any work.
    let slow = Experiment::dimensionless(0.05, limits::W_MIN, 1.6).unwrap();
    let options = SteadyOptions::default().with_max_periods(10_000).unwrap();
    let err = slow.steady_with(&options).unwrap_err();
    assert!(matches!(err, Error::HorizonTooLong { .. }), "{err:?}");
    // A sampled run past the range is refused before any work (the Python package's
    // `simulate` and the command line's both go through `Experiment::simulate`'s check).
    let slow = Experiment::dimensionless(0.05, limits::W_MIN, 1.2).unwrap();
    let max = limits::max_periods(&slow.params().unwrap());
    let err = slow.simulate(7000.0, 1, &()).unwrap_err();
    match err {
        Error::HorizonTooLong { max_periods, .. } => assert_eq!(max_periods, max),
        other => panic!("{other:?}"),
    }
    let stopped = slow.simulate(max.floor(), 1, &stop_at_once).unwrap_err();
    assert!(matches!(stopped, Error::Cancelled { .. }), "{stopped:?}");
}

/// A monitor that stops the run at its first report.
fn stop_at_once(_done: usize, _total: usize) -> bool {
    false
}

/// Sizes past the caps are refused before any work: a map of more than 4e6 points, a basin
/// map of more than 2000 initial states along an axis; the caps themselves are accepted.
#[test]
fn sizes_are_capped_before_any_work() {
    let e = Experiment::dimensionless(0.05, 0.7, 1.2).unwrap();
    let axis = |p: Parameter, n: usize, from: f64| {
        Axis::new(p, (0..n).map(|k| from + k as f64 * 1e-6).collect()).unwrap()
    };
    let at_cap = Grid::new(
        &e,
        axis(Parameter::W, 10_000, 0.5),
        axis(Parameter::Beta, 10_000, 1.0),
    );
    assert!(at_cap.is_ok());
    let err = Grid::new(
        &e,
        axis(Parameter::W, 10_001, 0.5),
        axis(Parameter::Beta, 10_000, 1.0),
    )
    .unwrap_err();
    assert_refused::<()>(Err(err), "points", "at most 1e8 points");
    let range = |n| stickslip::scan::ParameterRange::new("y0", -1.0, 1.0, n).unwrap();
    assert!(stickslip::basins::Basins::new(&e, &range(2000), &range(2)).is_ok());
    for (y, v) in [(2001, 2), (2, 2001), (1_000_000, 1_000_000)] {
        let err = stickslip::basins::Basins::new(&e, &range(y), &range(v)).unwrap_err();
        assert_refused::<()>(Err(err), "steps", "from 1 to 2000 along each axis");
    }
}

/// The Lyapunov measurement runs one solver through its transient and its periods: a
/// measurement past the time range is refused before any work, alone, in a steady state
/// (which measures a motion that does not repeat from τ = 0 again) and in a map.
#[test]
fn lyapunov_measurements_end_before_time_loses_its_resolution() {
    let p = params(0.0, 0.33, 9.0).unwrap().with_mu_s(3.0).unwrap();
    let max = limits::max_periods(&p).floor() as usize;
    let fits = LyapunovOptions {
        transient_periods: 0,
        periods: max / 20 * 20,
        ..LyapunovOptions::default()
    };
    assert!(fits.check_horizon(&p).is_ok());
    let long = LyapunovOptions {
        transient_periods: 20,
        ..fits
    };
    assert!(long.check_horizon(&p).is_err());
    let err = lyapunov_exponents(&p, State::default(), &long).unwrap_err();
    assert!(matches!(err, Error::HorizonTooLong { .. }), "{err:?}");

    // A steady state at the lowest w: the default measurement fits, a longer one does not.
    let slow = Experiment::dimensionless(0.0, limits::W_MIN, 9.0)
        .unwrap()
        .with_mu_s(3.0)
        .unwrap();
    let slow_params = slow.params().unwrap();
    assert!(SteadyOptions::DEFAULT_LYAPUNOV
        .check_horizon(&slow_params)
        .is_ok());
    let measure = LyapunovOptions {
        periods: 10_000,
        ..SteadyOptions::DEFAULT_LYAPUNOV
    };
    let options = SteadyOptions::default()
        .with_lyapunov(Some(measure))
        .unwrap();
    let err = slow.steady_with(&options).unwrap_err();
    assert!(matches!(err, Error::HorizonTooLong { .. }), "{err:?}");
    let grid = Grid::new(
        &slow,
        Axis::new(Parameter::W, vec![limits::W_MIN, 0.3]).unwrap(),
        Axis::new(Parameter::Beta, vec![9.0]).unwrap(),
    )
    .unwrap();
    let err = grid.lyapunov(measure).unwrap_err();
    assert!(matches!(err, Error::HorizonTooLong { .. }), "{err:?}");
}

/// At the edge of β the friction is still resolved: the steady sliding motion at β = 1e9 is
/// symmetric (no even harmonics above the rounding of y, ≈ 2e-16·|y|·10³ ≈ 2e-3 in units of
/// the friction force) and its peak is that of the exact sliding orbit to 1e-12.
#[test]
fn friction_is_resolved_at_the_largest_beta() {
    let e = Experiment::dimensionless(0.0468, 0.9, 1e9).unwrap();
    let steady = e.steady().unwrap();
    let exact = stickslip::PeriodicSolution::new(&e.params().unwrap()).unwrap();
    let relative = (steady.peak - exact.peak).abs() / exact.peak;
    assert!(relative < 1e-12, "peak off by {relative:e}");
    let spectrum = steady.spectrum.as_ref().unwrap();
    let even = spectrum.amplitude(2).unwrap();
    assert!(even < 1e-2, "A2 = {even}");
    // The third harmonic comes from the friction's square wave: 4/(3π·|1 − 9w²|) at the
    // order of the friction force, resolved against y ≈ 5e9.
    let a3 = spectrum.amplitude(3).unwrap();
    let square_wave = 4.0 / (3.0 * std::f64::consts::PI * (1.0 - 9.0 * 0.81f64).abs());
    assert!(
        (a3 - square_wave).abs() < 1e-2 * square_wave,
        "A3 = {a3}, {square_wave}"
    );
}

#[test]
fn streams_are_bit_identical_to_sample_at() {
    let p = params(0.0468, 0.7, 1.2).unwrap();
    let end = 30.0 * p.drive_period();
    let mut a = ExactSolver::new(p, State::default());
    let mut events = Vec::new();
    let times = stickslip::solver::grid(0.0, end, 3000);
    let samples = stickslip::solver::sample_at(&mut a, &times, |e| events.push(*e)).unwrap();
    let mut b = ExactSolver::new(p, State::default());
    let (mut s2, mut e2) = (Vec::new(), Vec::new());
    for r in stream(&mut b, 0.0, end, 3000).unwrap() {
        match r.unwrap() {
            Record::Sample(s) => s2.push(s),
            Record::Event(e) => {
                // Every event comes before the first sample after it.
                assert!(s2.last().is_none_or(|s: &stickslip::Sample| s.tau <= e.tau));
                e2.push(e)
            }
        }
    }
    assert_eq!(samples, s2);
    assert_eq!(events, e2);
}
