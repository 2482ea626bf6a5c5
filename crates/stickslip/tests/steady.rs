//! Steady states, spectra, motion classes, sweeps and phase diagrams.

use stickslip::scan::{Axis, Grid, ParameterRange, Sweep, SweepDirection, SweepLeg};
use stickslip::solver::{run_until, sample_at, EventKind};
use stickslip::steady::{
    exact_solver, steady_state, steady_state_from, MotionClass, SteadyOptions, SteadyState,
};
use stickslip::theory::{stick_slip_boundary, PeriodicSolution};
use stickslip::{Circuit, Error, ExactSolver, Experiment, Parameter, Params, Solver, State};

fn zeta() -> f64 {
    Circuit::paper().scales().zeta()
}

fn paper(w: f64, beta: f64) -> Params {
    Params::new(zeta(), w, beta).unwrap()
}

fn steady_with(params: Params, options: &SteadyOptions) -> SteadyState {
    let mut solver = ExactSolver::new(params, State::default());
    steady_state(&mut solver, options).unwrap()
}

fn steady(w: f64, beta: f64) -> SteadyState {
    steady_with(paper(w, beta), &SteadyOptions::default())
}

#[test]
fn sliding_at_the_papers_fig6a_point() {
    let s = steady(0.9, 1.6);
    assert_eq!(s.class, MotionClass::Sliding);
    assert_eq!(s.period, Some(1));
    assert_eq!(s.stops, 0);
    assert!(s.symmetric);
    // Two turning points per period, nothing else.
    assert_eq!(s.events.len(), 2);
    assert!(s.events.iter().all(|e| e.kind == EventKind::Turn));
    // The extremes are the turning points, mirror images of each other.
    assert!((s.y_max + s.y_min).abs() < 1e-9, "{} {}", s.y_max, s.y_min);
    assert!((s.gain - s.y_max / 1.6).abs() < 1e-9);
}

#[test]
fn periodic_stick_at_the_papers_fig6b_point() {
    let s = steady(0.6, 1.2);
    assert_eq!(s.class, MotionClass::PeriodicStick);
    assert_eq!(s.period, Some(1));
    assert_eq!(s.stops, 2);
    assert_eq!(s.stops_per_period, 2.0);
    assert!(s.symmetric);
    assert!(s.longest_stop > 0.01 * paper(0.6, 1.2).drive_period());
}

/// The paper shows w = 0.7, β = 1.2 as non-periodic (its Fig. 6c, from LSODA); solved exactly
/// the motion settles on a symmetric cycle with two stops per period.
#[test]
fn papers_fig6c_point_is_periodic_when_solved_exactly() {
    let s = steady(0.7, 1.2);
    assert_eq!(s.class, MotionClass::PeriodicStick);
    assert_eq!(s.period, Some(1));
    assert_eq!(s.stops_per_period, 2.0);
    assert!(s.symmetric);
}

#[test]
fn static_from_rest_is_found_at_once() {
    // β ≤ μs = 1 from rest: the drive can never overcome static friction.
    for (w, beta) in [(0.7, 1.0), (0.1, 0.5), (2.4, 0.99), (1.0, 0.0)] {
        let s = steady(w, beta);
        assert_eq!(s.class, MotionClass::Static, "w {w} beta {beta}");
        assert_eq!(s.period, Some(1));
        assert!(s.periods_to_settle <= 2, "{}", s.periods_to_settle);
        assert_eq!(s.stops, 0);
        assert!(s.events.is_empty());
        assert_eq!(s.peak, 0.0);
        assert_eq!(s.gain, 0.0);
        assert_eq!(s.phase_lag(), None);
    }
}

#[test]
fn multi_stop_motion_at_low_frequency() {
    let s = steady(0.15, 2.0);
    assert_eq!(s.class, MotionClass::PeriodicStick);
    assert_eq!(s.period, Some(1));
    assert_eq!(s.stops_per_period, 4.0);
    assert!(s.symmetric);
    // Every stop is followed by a slip inside the cycle or across its end.
    let sticks = s
        .events
        .iter()
        .filter(|e| e.kind == EventKind::Stick)
        .count();
    let slips = s
        .events
        .iter()
        .filter(|e| e.kind == EventKind::Slip)
        .count();
    assert_eq!(sticks, 4);
    assert_eq!(slips, 4);
}

#[test]
fn a_cap_too_short_for_convergence_gives_nonperiodic_stick() {
    // At w = 0.7, β = 1.2 the cycle needs about 50 periods to be recognised.
    let options = SteadyOptions::default().with_max_periods(5).unwrap();
    let s = steady_with(paper(0.7, 1.2), &options);
    assert_eq!(s.class, MotionClass::Undecided);
    assert_eq!(s.period, None);
    assert_eq!(s.periods_to_settle, 5);
    assert_eq!(s.recorded_periods, 16);
    assert!(!s.symmetric);
    // A sliding motion stopped as early stays sliding, without a period.
    let s = steady_with(paper(0.9, 1.6), &options);
    assert_eq!(s.class, MotionClass::Sliding);
    assert_eq!(s.period, None);
}

#[test]
fn coexisting_static_and_moving_states_with_static_friction_above_kinetic() {
    // μs = 1.5: between β ≈ 1.35 and μs the oscillator stays at rest when it starts at rest
    // (sweep up) but keeps moving when it was already moving (sweep down).
    let base = Experiment::dimensionless(zeta(), 0.9, 0.5)
        .unwrap()
        .with_mu_s(1.5)
        .unwrap();
    let range = ParameterRange::new("beta", 1.0, 2.0, 21).unwrap();
    let options = SteadyOptions::default().with_spectrum(false);
    let points = Sweep::new(&base, Axis::range(Parameter::Beta, &range).unwrap())
        .unwrap()
        .direction(SweepDirection::Both)
        .options(options)
        .unwrap()
        .run(&())
        .unwrap();
    assert_eq!(points.len(), 42);
    let at = |leg: SweepLeg, beta: f64| {
        points
            .iter()
            .find(|p| p.leg == leg && (p.params.beta - beta).abs() < 1e-12)
            .unwrap()
    };
    let up = at(SweepLeg::Up, 1.4);
    let down = at(SweepLeg::Down, 1.4);
    assert_eq!(up.steady.class, MotionClass::Static);
    assert_ne!(down.steady.class, MotionClass::Static);
    assert!(down.steady.gain > 1.0, "{}", down.steady.gain);
    // Above μs both legs move, and agree.
    let (up, down) = (at(SweepLeg::Up, 1.8), at(SweepLeg::Down, 1.8));
    assert_eq!(up.steady.class, down.steady.class);
    assert!((up.steady.gain - down.steady.gain).abs() < 1e-8);
    // The down leg starts where the up leg ended.
    assert_eq!(points[21].params.beta, 2.0);
    assert_eq!(points[21].leg, SweepLeg::Down);
}

#[test]
fn sweep_steps_continue_from_the_previous_final_state() {
    let base = Experiment::dimensionless(zeta(), 1.0, 2.0).unwrap();
    let options = SteadyOptions::default().with_spectrum(false);
    let points = Sweep::new(&base, Axis::new(Parameter::W, vec![0.8, 0.9]).unwrap())
        .unwrap()
        .direction(SweepDirection::Up)
        .options(options)
        .unwrap()
        .run(&())
        .unwrap();
    let first_end = points[0].steady.final_state();
    let again = steady_state_from(&exact_solver, &paper(0.9, 2.0), first_end, &options).unwrap();
    assert_eq!(again, points[1].steady);
}

#[test]
fn parseval_holds_on_the_sampled_cycle() {
    for (w, beta) in [(0.9, 1.6), (0.6, 1.2), (0.15, 2.0), (1.7, 3.0)] {
        let s = steady(w, beta);
        let sp = s.spectrum.as_ref().unwrap();
        let rel = (sp.mean_square - sp.spectral_mean_square).abs() / sp.mean_square;
        assert!(rel < 1e-12, "w {w} beta {beta}: {rel:e}");
        // The mean square also equals the sum over the samples computed here.
        let direct: f64 = s.trace.iter().map(|x| x.y * x.y).sum::<f64>() / s.trace.len() as f64;
        assert!((direct - sp.mean_square).abs() < 1e-13 * direct);
        // The reported harmonics hold almost all the power (the rest is the tail k > 16).
        let reported = sp.mean.powi(2)
            + sp.harmonics
                .iter()
                .map(|h| h.amplitude.powi(2) / 2.0)
                .sum::<f64>();
        assert!(reported <= sp.mean_square * (1.0 + 1e-12));
        assert!(
            reported >= sp.mean_square * (1.0 - 1e-4),
            "w {w} beta {beta}"
        );
    }
}

#[test]
fn harmonics_are_converged_in_the_samples_per_period() {
    // The automatic N against four times as many samples: harmonics up to 9 agree to 1e-10
    // of the amplitude of y, so aliasing is far below the 1e-8 required.
    for (w, beta) in [(0.9, 1.6), (0.6, 1.2), (0.15, 2.0), (2.2, 3.5)] {
        let auto = steady(w, beta);
        let n = auto.spectrum.as_ref().unwrap().samples_per_period;
        let options = SteadyOptions::default()
            .with_samples_per_period(Some(4 * n))
            .unwrap();
        let fine = steady_with(paper(w, beta), &options);
        for k in 1..=9 {
            let (a, b) = (auto.harmonic(k).unwrap(), fine.harmonic(k).unwrap());
            assert!(
                (a - b).abs() <= 1e-10 * auto.peak,
                "w {w} beta {beta} k {k}: {a:e} vs {b:e} (N = {n})"
            );
        }
    }
}

#[test]
fn symmetric_motions_have_no_even_harmonics() {
    for (w, beta) in [(0.9, 1.6), (0.6, 1.2), (0.15, 2.0)] {
        let s = steady(w, beta);
        assert!(s.symmetric);
        let sp = s.spectrum.as_ref().unwrap();
        assert!(sp.mean.abs() < 1e-9 * s.peak);
        for h in sp.harmonics.iter().filter(|h| h.order % 2 == 0) {
            assert!(
                h.amplitude < 1e-9 * s.peak,
                "k {}: {:e}",
                h.order,
                h.amplitude
            );
        }
        assert_eq!(sp.subharmonic, 0.0);
    }
}

#[test]
fn fundamental_phase_matches_a_direct_projection() {
    // A_1 cos(ψ + θ_1) against the projection of y onto cos ψ and sin ψ by the trapezoidal
    // rule on an independent grid (exact for trigonometric polynomials, spectrally accurate).
    let params = paper(1.3, 2.5).with_phi(0.4).unwrap();
    let s = steady_with(params, &SteadyOptions::default());
    let period = params.drive_period();
    let mut solver = ExactSolver::new(params, State::default());
    run_until(&mut solver, s.start, |_| {}).unwrap();
    let n = 3000;
    let times: Vec<f64> = (0..n)
        .map(|j| s.start + period * j as f64 / n as f64)
        .collect();
    let samples = sample_at(&mut solver, &times, |_| {}).unwrap();
    let (mut c, mut d) = (0.0, 0.0);
    for x in &samples {
        let psi = params.w * x.tau + params.phi;
        c += x.y * psi.cos();
        d += x.y * psi.sin();
    }
    let (c, d) = (2.0 * c / n as f64, 2.0 * d / n as f64);
    let h = s.spectrum.as_ref().unwrap().harmonics[0];
    assert!(
        (h.amplitude - c.hypot(d)).abs() < 1e-7,
        "{} {}",
        h.amplitude,
        c.hypot(d)
    );
    // y ≈ c cos ψ + d sin ψ = A cos(ψ + θ) with θ = atan2(−d, c).
    assert!((h.phase - (-d).atan2(c)).abs() < 1e-7);
    let lag = s.phase_lag().unwrap();
    assert!(lag > 0.0 && lag < std::f64::consts::PI);
}

#[test]
fn peak_and_gain_come_from_the_exact_extremes() {
    let s = steady(0.6, 1.2);
    let sampled_max = s.trace.iter().map(|x| x.y).fold(f64::MIN, f64::max);
    let sampled_min = s.trace.iter().map(|x| x.y).fold(f64::MAX, f64::min);
    assert!(s.y_max >= sampled_max && s.y_min <= sampled_min);
    assert!(s.y_max - sampled_max < 1e-6);
    // The extremes are the stops' positions.
    let stop_max = s
        .events
        .iter()
        .filter(|e| e.kind == EventKind::Stick)
        .map(|e| e.y)
        .fold(f64::MIN, f64::max);
    assert_eq!(s.y_max, stop_max);
    assert!((s.gain - (s.y_max - s.y_min) / 2.4).abs() < 1e-15);
}

#[test]
fn velocity_harmonics_follow_from_those_of_y() {
    let params = paper(0.9, 1.6);
    let s = steady_with(params, &SteadyOptions::default());
    let sp = s.spectrum.as_ref().unwrap();
    let v: Vec<f64> = s.trace.iter().map(|x| x.v).collect();
    let direct = stickslip::steady::Spectrum::from_samples(&v, 1, 5, params.phi).unwrap();
    for (a, b) in sp.derivative(params.w).iter().zip(&direct.harmonics) {
        // y' has kinks at the turns, so its own FFT aliases like 1/N²; the derived one is exact.
        assert!((a.amplitude - b.amplitude).abs() < 1e-6, "{a:?} {b:?}");
        if a.amplitude > 1e-3 {
            assert!((a.phase - b.phase).abs() < 1e-5, "{a:?} {b:?}");
        }
    }
}

/// Regression: at w = 0.6, β = 1.2 the exact solver used to alternate Slip and Stick at one
/// instant for ever after ~1570 periods (rounding of the drive phase at large τ made the
/// acceleration at the start of a slide −1e-12).
#[test]
fn slip_stick_loop_at_one_instant_regression() {
    for (w, beta) in [(0.6, 1.2), (0.7, 1.2)] {
        let params = paper(w, beta);
        let mut solver = ExactSolver::new(params, State::default());
        let mut events = 0u64;
        run_until(&mut solver, 2000.0 * params.drive_period(), |_| events += 1).unwrap();
        assert!(events <= 4 * 2000 + 10, "w {w}: {events} events");
    }
}

#[test]
fn steady_state_runs_from_a_solver_that_started_earlier() {
    let params = paper(0.9, 1.6);
    let mut solver = ExactSolver::new(params, State::default());
    run_until(&mut solver, 3.3 * params.drive_period(), |_| {}).unwrap();
    let s = steady_state(&mut solver, &SteadyOptions::default()).unwrap();
    let fresh = steady(0.9, 1.6);
    assert_eq!(s.class, MotionClass::Sliding);
    assert!((s.start / params.drive_period()).fract().abs() < 1e-9);
    assert!((s.gain - fresh.gain).abs() < 1e-9);
    assert!(solver.time() > s.start);
}

#[test]
fn phase_diagram_matches_single_runs_and_is_deterministic() {
    let base = Experiment::dimensionless(zeta(), 1.0, 1.0).unwrap();
    let w = ParameterRange::new("w", 0.3, 1.5, 4).unwrap();
    let beta = ParameterRange::new("beta", 0.8, 2.6, 3).unwrap();
    let options = SteadyOptions::default();
    let grid = Grid::new(
        &base,
        Axis::range(Parameter::W, &w).unwrap(),
        Axis::range(Parameter::Beta, &beta).unwrap(),
    )
    .unwrap()
    .options(options)
    .unwrap();
    let points = grid.run(&()).unwrap().points;
    assert_eq!(points.len(), 12);
    assert_eq!(points, grid.run(&()).unwrap().points);
    // Block by block equals all at once.
    let mut blocks = grid.run_block(0..2, 0..3, &()).unwrap();
    blocks.extend(grid.run_block(2..4, 0..3, &()).unwrap());
    assert_eq!(blocks, points);
    for (i, p) in points.iter().enumerate() {
        assert_eq!(p.params.w, w.value(i / 3));
        assert_eq!(p.params.beta, beta.value(i % 3));
        let params = paper(p.params.w, p.params.beta);
        // The same computation as the map's (which skips the spectrum), point by point.
        let s = steady_state_from(
            &exact_solver,
            &params,
            State::default(),
            &options.with_spectrum(false),
        )
        .unwrap();
        assert_eq!(p.class, s.class);
        assert_eq!(p.period, s.period);
        assert_eq!(p.gain, s.gain);
        // Without extrapolation: the same motion, found later.
        let plain = steady_with(params, &options.with_accelerate(false));
        assert_eq!(p.class, plain.class);
        assert_eq!(p.period, plain.period);
        assert_eq!(p.stops_per_period, plain.stops_per_period);
        assert!((p.gain - plain.gain).abs() < 1e-8 * plain.gain.max(1.0));
        assert!(p.periods_to_settle <= plain.periods_to_settle);
    }
    let classes: Vec<_> = points.iter().map(|p| p.class).collect();
    assert!(classes.contains(&MotionClass::Static));
    assert!(classes.contains(&MotionClass::Sliding));
    assert!(classes.contains(&MotionClass::PeriodicStick));
}

#[test]
fn phase_diagram_can_be_cancelled() {
    let base = Experiment::dimensionless(zeta(), 1.0, 1.0).unwrap();
    let w = ParameterRange::new("w", 0.3, 1.5, 10).unwrap();
    let beta = ParameterRange::new("beta", 1.2, 2.6, 10).unwrap();
    let result = Grid::new(
        &base,
        Axis::range(Parameter::W, &w).unwrap(),
        Axis::range(Parameter::Beta, &beta).unwrap(),
    )
    .unwrap()
    .run(&|_: usize, _: usize| false);
    assert!(matches!(result, Err(Error::Cancelled { total: 100, .. })));
    let sweep = Sweep::new(&base, Axis::range(Parameter::W, &w).unwrap())
        .unwrap()
        .run(&|done: usize, _: usize| done < 3);
    assert_eq!(sweep, Err(Error::Cancelled { done: 3, total: 20 }));
}

#[test]
fn bad_ranges_and_options_are_rejected_with_the_value() {
    let name = |r: Result<ParameterRange, Error>| match r {
        Err(Error::InvalidParameter { name, .. }) => name,
        other => panic!("expected an error, got {other:?}"),
    };
    assert_eq!(name(ParameterRange::new("w", 2.0, 1.0, 5)), "w");
    assert_eq!(name(ParameterRange::new("w", 0.5, 1.0, 0)), "steps");
    assert_eq!(name(ParameterRange::new("w", 0.5, 1.0, 1)), "steps");
    assert_eq!(name(ParameterRange::new("beta", f64::NAN, 1.0, 5)), "beta");
    assert_eq!(
        name(ParameterRange::new("beta", 0.5, f64::INFINITY, 5)),
        "beta"
    );
    let single = ParameterRange::new("w", 0.7, 0.7, 1).unwrap();
    assert_eq!(single.values(), vec![0.7]);
    let r = ParameterRange::new("w", 0.1, 2.5, 400).unwrap();
    assert_eq!(r.value(399), 2.5);
    assert_eq!(r.values().len(), 400);

    let o = SteadyOptions::default();
    assert!(o.with_tolerance(0.0).is_err());
    assert!(o.with_tolerance(f64::NAN).is_err());
    assert!(o.with_max_periods(0).is_err());
    assert!(o.with_max_period(0).is_err());
    assert!(o.with_samples_per_period(Some(1000)).is_err());
    assert!(o.with_harmonics(0).is_err());
    assert!(o.with_min_stop_fraction(-1.0).is_err());

    // A swept value outside the model's range is refused before any work.
    let r = ParameterRange::new("w", -1.0, 1.0, 3).unwrap();
    assert!(matches!(
        Axis::range(Parameter::W, &r),
        Err(Error::InvalidParameter { name: "w", .. })
    ));
    assert!(matches!(
        Axis::new(Parameter::MuS, vec![1.0, 0.5]),
        Err(Error::InvalidParameter { name: "mu_s", .. })
    ));
    // A grid of one parameter against itself is refused.
    let w = Axis::new(Parameter::W, vec![0.5]).unwrap();
    assert!(Grid::new(&Experiment::paper(), w.clone(), w.clone()).is_err());
    // A missing drive value that the sweep does not set is named.
    assert!(matches!(
        Sweep::new(&Experiment::paper(), w),
        Err(Error::Spec(_))
    ));
}

#[test]
fn analysis_is_generic_over_the_solver_trait() {
    /// A solver that hides the exact solver's type behind the trait.
    struct Wrapped(ExactSolver);
    impl Solver for Wrapped {
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
        // It follows the exact model, so the steady-state search may settle it by Newton's
        // method as it does the exact solver.
        fn is_exact(&self) -> bool {
            self.0.is_exact()
        }
        // Its hints, and the exact solver inside for the tangent dynamics, are handed on too:
        // with them the search does on it what it does on the exact solver.
        fn hints(&self) -> Option<stickslip::Hints> {
            self.0.hints()
        }
        fn take_hints(&mut self, hints: stickslip::Hints) {
            self.0.take_hints(hints)
        }
        fn as_any_mut(&mut self) -> Option<&mut dyn std::any::Any> {
            self.0.as_any_mut()
        }
    }
    let factory = |p: Params, s: State| -> stickslip::Result<Box<dyn Solver + Send>> {
        Ok(Box::new(Wrapped(ExactSolver::new(p, s))))
    };
    let grid = Grid::new(
        &Experiment::dimensionless(zeta(), 1.0, 1.0).unwrap(),
        Axis::new(Parameter::W, vec![0.6, 0.9]).unwrap(),
        Axis::new(Parameter::Beta, vec![1.2, 1.6]).unwrap(),
    )
    .unwrap();
    let direct = grid.run(&()).unwrap();
    let wrapped = grid.with_factory(factory).run(&()).unwrap();
    assert_eq!(wrapped, direct);
}

#[test]
fn extrapolation_finds_the_same_cycle_sooner() {
    for (w, beta) in [
        (0.9, 1.6),
        (0.6, 1.2),
        (0.7, 1.2),
        (1.2, 1.5),
        (2.4, 3.9),
        (0.15, 2.0),
    ] {
        let params = paper(w, beta);
        let plain = steady_with(params, &SteadyOptions::default().with_accelerate(false));
        // Extrapolation alone (Newton's settling is compared with the plain iteration in
        // tests/newton_settling.rs).
        let fast = steady_state_from(
            &exact_solver,
            &params,
            State::default(),
            &SteadyOptions::default().with_newton(false),
        )
        .unwrap();
        assert_eq!(fast.class, plain.class, "w {w} beta {beta}");
        assert_eq!(fast.period, plain.period);
        assert_eq!(fast.stops, plain.stops);
        assert_eq!(fast.symmetric, plain.symmetric);
        assert!(fast.periods_to_settle <= plain.periods_to_settle);
        for k in 1..=9 {
            let (a, b) = (fast.harmonic(k).unwrap(), plain.harmonic(k).unwrap());
            assert!(
                (a - b).abs() < 1e-8 * plain.peak,
                "w {w} beta {beta} k {k}: {a:e} {b:e}"
            );
        }
    }
}

/// Sliding points comfortably above the exact stick-slip boundary (β ≥ 1.15·β_c, checked).
const SLIDING_POINTS: [(f64, f64, f64); 9] = [
    (0.0468, 0.9, 1.6),
    (0.0468, 0.95, 2.14),
    (0.0468, 1.43, 2.14),
    (0.0468, 0.5, 5.0),
    (0.0468, 2.0, 3.0),
    (0.1, 0.9, 2.5),
    (0.1, 1.5, 3.0),
    (0.2, 0.8, 3.0),
    (0.2, 1.2, 4.0),
];

/// Largest deviation, relative to the exact fundamental A1, of the simulated harmonics
/// 1…`top` (as complex amplitudes A_k e^{iθ_k}, so amplitude and phase both count) from the
/// exact Fourier coefficients of [`PeriodicSolution`].
fn harmonic_deviation(s: &SteadyState, exact: &PeriodicSolution, top: u32) -> (f64, u32) {
    let sp = s.spectrum.as_ref().expect("spectrum on");
    let a1 = exact.a1();
    let mut worst = (0.0, 0);
    for k in 1..=top {
        let sim = sp.harmonics[k as usize - 1];
        let ex = exact.harmonic(k);
        assert_eq!(sim.order, k as usize);
        let (sr, si) = (
            sim.amplitude * sim.phase.cos(),
            sim.amplitude * sim.phase.sin(),
        );
        let (er, ei) = (ex.amplitude * ex.phase.cos(), ex.amplitude * ex.phase.sin());
        let d = (sr - er).hypot(si - ei) / a1;
        if d > worst.0 {
            worst = (d, k);
        }
    }
    worst
}

#[test]
fn sliding_harmonics_match_the_exact_periodic_solution() {
    // Tolerance: every harmonic k = 1…11 of the simulated cycle, as a complex amplitude
    // A_k e^{iθ_k}, within 1e-8·A1 of the exact one (so |ΔA_k| ≤ 1e-8·A1 and, for the
    // fundamental, |Δθ_1| ≤ 1e-8 rad); even orders exactly zero in theory, so ≤ 1e-8·A1.
    // Measured at these points: at most 8.2e-11·A1 (ζ = 0.0468, w = 2, β = 3, k = 7).
    const TOL: f64 = 1e-8;
    for (zeta, w, beta) in SLIDING_POINTS {
        let params = Params::new(zeta, w, beta).unwrap();
        let beta_c = stick_slip_boundary(zeta, w, 1.0).unwrap().beta_c;
        assert!(beta >= 1.15 * beta_c, "{zeta} {w} {beta}: β_c = {beta_c}");
        let exact = PeriodicSolution::new(&params).unwrap();
        for k in (2..=10).step_by(2) {
            assert!(exact.harmonic(k).amplitude < 1e-12 * exact.a1());
        }
        let plain = steady_with(params, &SteadyOptions::default());
        let from = steady_state_from(
            &exact_solver,
            &params,
            State::default(),
            &SteadyOptions::default(),
        )
        .unwrap();
        for (how, s) in [("steady_state", &plain), ("steady_state_from", &from)] {
            assert_eq!(s.class, MotionClass::Sliding, "{how} {zeta} {w} {beta}");
            assert_eq!(s.period, Some(1));
            assert!(s.symmetric);
            let (d, k) = harmonic_deviation(s, &exact, 11);
            assert!(d <= TOL, "{how} ζ {zeta} w {w} β {beta}: {d:e} at k = {k}");
            // The simulated gain (max y − min y)/(2β) is the exact peak/β, not A1/β.
            assert!((s.peak - exact.peak).abs() <= 1e-9 * exact.peak);
            assert!((s.gain - exact.peak / beta).abs() <= 1e-9 * exact.peak / beta);
            assert!((s.gain - exact.gain1()).abs() > 1e-6 * s.gain);
        }
    }
}
