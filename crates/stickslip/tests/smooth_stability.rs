//! The stability tools of the Shockley model against independent checks: its forward
//! sensitivities (the derivatives of the computed solution, [`stickslip::stiff::sensitivity`])
//! and its Floquet multipliers against Richardson-extrapolated central differences of runs at
//! a tight tolerance, its phase-area contraction against Liouville's formula, and its largest
//! Lyapunov exponent against the orbit's multiplier.

use stickslip::shockley::{DiodeLaw, ShockleyModel, ShockleyOptions, ShockleySolver};
use stickslip::solver::{grid, run_until, sample_at};
use stickslip::stability::{
    LyapunovOptions, Matrix2, Multiplier, NewtonOptions, PeriodicOrbit, ShockleyDynamics, Stability,
};
use stickslip::stiff::Columns;
use stickslip::{Cancel, Circuit, Params, Solver, State};
use stickslip_testkit::differences::{richardson, state_jacobian};

/// The paper's circuit with 1N4148 diodes: (w, β) from a drive in Hz and V, and the law.
fn paper_drive(hertz: f64, volts: f64) -> (Params, DiodeLaw) {
    let circuit = Circuit::paper_shockley();
    let scales = circuit.scales();
    let params = scales
        .params(volts, hertz * std::f64::consts::TAU, 0.0)
        .unwrap();
    let model = circuit.shockley_model(&params).unwrap().unwrap();
    (model.params, model.law)
}

fn options(tolerance: f64) -> ShockleyOptions {
    ShockleyOptions::default()
        .with_rtol(tolerance)
        .unwrap()
        .with_atol(tolerance)
        .unwrap()
}

#[test]
fn carrying_sensitivities_changes_nothing_of_the_solution() {
    let (params, law) = paper_drive(9.97e3, 1.498);
    let model = ShockleyModel::new(params, law).unwrap();
    let start = State { y: 0.3, v: -0.2 };
    let times = grid(0.0, 6.0 * params.drive_period(), 700);
    let mut plain = ShockleySolver::new(model, start, ShockleyOptions::default()).unwrap();
    let mut carried = ShockleySolver::with_sensitivities(
        model,
        start,
        ShockleyOptions::default(),
        Cancel::never(),
        Columns::Parameters,
    )
    .unwrap();
    let a = sample_at(&mut plain, &times, |_| {}).unwrap();
    let b = sample_at(&mut carried, &times, |_| {}).unwrap();
    for (a, b) in a.iter().zip(&b) {
        assert_eq!(
            (a.y.to_bits(), a.v.to_bits()),
            (b.y.to_bits(), b.v.to_bits())
        );
    }
    assert_eq!(plain.stats(), carried.stats());
}

/// ∂P/∂(y0, v0, ζ, β, w, φ, a, ε, r) of the strobe map over one drive period, against
/// Richardson differences, each at rtol = atol = 1e-12.
#[test]
fn strobe_map_sensitivities_match_richardson_differences() {
    let tight = options(1e-12);
    for (hertz, volts, start) in [
        (9.97e3, 1.498, State { y: 0.4, v: 2.5 }),
        (6.3e3, 0.84, State { y: -0.5, v: 0.4 }),
        (3.0e3, 1.5, State { y: 0.2, v: 0.3 }),
    ] {
        let (params, law) = paper_drive(hertz, volts);
        let dynamics = ShockleyDynamics::new(law, tight).unwrap();
        let image = dynamics
            .strobe_image(&params, start, 1, Columns::Parameters)
            .unwrap();
        let map = |params: Params, law: DiodeLaw, x: State| {
            let s = ShockleyDynamics::new(law, tight)
                .unwrap()
                .strobe_map(&params, x, 1)
                .unwrap()
                .state;
            [s.y, s.v]
        };
        let with_phi = |phi: f64| params.with_phi(phi).unwrap();
        let checks: Vec<(&str, f64, [f64; 2])> = vec![
            (
                "y0",
                1e-3,
                richardson(|y| map(params, law, State { y, ..start }), start.y, 1e-3),
            ),
            (
                "v0",
                1e-3,
                richardson(|v| map(params, law, State { v, ..start }), start.v, 1e-3),
            ),
            (
                "zeta",
                1e-4,
                richardson(
                    |z| map(Params { zeta: z, ..params }, law, start),
                    params.zeta,
                    1e-4,
                ),
            ),
            (
                "beta",
                1e-3,
                richardson(
                    |b| map(Params { beta: b, ..params }, law, start),
                    params.beta,
                    1e-3,
                ),
            ),
            (
                "w",
                1e-4,
                richardson(|w| map(Params { w, ..params }, law, start), params.w, 1e-4),
            ),
            (
                "phi",
                1e-3,
                richardson(|phi| map(with_phi(phi), law, start), 0.0, 1e-3),
            ),
            (
                "a",
                1e-5,
                richardson(
                    |a| map(params, DiodeLaw { scale: a, ..law }, start),
                    law.scale,
                    1e-5,
                ),
            ),
            (
                "epsilon",
                1e-8,
                richardson(
                    |e| map(params, DiodeLaw { knee: e, ..law }, start),
                    law.knee,
                    1e-8,
                ),
            ),
            (
                "r",
                1e-5,
                richardson(
                    |r| {
                        map(
                            params,
                            DiodeLaw {
                                resistance: r,
                                ..law
                            },
                            start,
                        )
                    },
                    law.resistance,
                    1e-5,
                ),
            ),
        ];
        // The strobe at τ = T = 2π/w moves with w: dP/dw = ∂x(T)/∂w + ẋ(T)·dT/dw.
        let moving = -std::f64::consts::TAU / (params.w * params.w);
        for (c, (name, _, fd)) in checks.iter().enumerate() {
            let mut exact = image.sensitivity.column(c);
            if *name == "w" {
                exact[0] += image.field[0] * moving;
                exact[1] += image.field[1] * moving;
            }
            for k in 0..2 {
                let scale = fd[k].abs().max(exact[k].abs()).max(1e-3);
                eprintln!(
                    "{hertz} Hz {volts} V: d{}/d{name}: sensitivity {:+.12e}, differences {:+.12e}",
                    ["y", "v"][k],
                    exact[k],
                    fd[k]
                );
                assert!(
                    (exact[k] - fd[k]).abs() <= 1e-6 * scale,
                    "{hertz} Hz {volts} V: d{}/d{name}: {} vs {}",
                    ["y", "v"][k],
                    exact[k],
                    fd[k]
                );
            }
        }
    }
}

/// The periodic orbit of period 1 of the paper's circuit driven at `hertz`, `volts`, found
/// by Newton's method at rtol = atol = `tolerance` from the state after 200 drive periods.
fn orbit_at(hertz: f64, volts: f64, tolerance: f64) -> (Params, ShockleyDynamics, PeriodicOrbit) {
    let (params, law) = paper_drive(hertz, volts);
    let dynamics = ShockleyDynamics::new(law, options(tolerance)).unwrap();
    let mut solver = ShockleySolver::new(
        dynamics.model(&params).unwrap(),
        State::default(),
        options(tolerance),
    )
    .unwrap();
    run_until(&mut solver, 200.0 * params.drive_period(), |_| {}).unwrap();
    let orbit = dynamics
        .find_periodic_orbit(&params, solver.state(), 1, &NewtonOptions::default())
        .unwrap();
    (params, dynamics, orbit)
}

/// ∫(2ζ + D'(y'(τ)))dτ over p drive periods from `state`: ln of the phase-area contraction of
/// the flow (Liouville's formula), by adaptive Simpson on the dense output of a run at
/// rtol = atol = 1e-12, each stretch split where y' changes sign (where D' peaks at a/ε over a
/// time of the order of ε/|y''|).
fn liouville(params: &Params, law: &DiodeLaw, state: State, periods: usize) -> f64 {
    let model = ShockleyModel::new(*params, *law).unwrap();
    let mut solver = ShockleySolver::new(model, state, options(1e-12)).unwrap();
    let integrand = |v: f64| 2.0 * params.zeta + law.slope(v);
    let end = periods as f64 * params.drive_period();
    let mut total = 0.0;
    while solver.time() < end {
        solver.advance(end).unwrap();
        let (a, b) = solver.interval();
        let v = |t: f64| solver.dense(t).v;
        // Split at a sign change of y' (bisection to rounding).
        let mut cuts = vec![a];
        if v(a) * v(b) < 0.0 {
            let (mut lo, mut hi) = (a, b);
            while hi - lo > 1e-15 * b.abs().max(1.0) {
                let mid = 0.5 * (lo + hi);
                if v(lo) * v(mid) <= 0.0 {
                    hi = mid;
                } else {
                    lo = mid;
                }
            }
            cuts.push(0.5 * (lo + hi));
        }
        cuts.push(b);
        for w in cuts.windows(2) {
            total += simpson(&|t| integrand(v(t)), w[0], w[1], 1e-13, 60);
        }
    }
    total
}

/// Adaptive Simpson quadrature of `f` on [a, b] to absolute tolerance `tol`.
fn simpson(f: &dyn Fn(f64) -> f64, a: f64, b: f64, tol: f64, depth: usize) -> f64 {
    fn rule(fa: f64, fm: f64, fb: f64, a: f64, b: f64) -> f64 {
        (b - a) / 6.0 * (fa + 4.0 * fm + fb)
    }
    fn go(
        f: &dyn Fn(f64) -> f64,
        a: f64,
        b: f64,
        fa: f64,
        fm: f64,
        fb: f64,
        whole: f64,
        tol: f64,
        depth: usize,
    ) -> f64 {
        let m = 0.5 * (a + b);
        let (lm, rm) = (0.5 * (a + m), 0.5 * (m + b));
        let (flm, frm) = (f(lm), f(rm));
        let left = rule(fa, flm, fm, a, m);
        let right = rule(fm, frm, fb, m, b);
        if depth == 0 || (left + right - whole).abs() <= 15.0 * tol {
            return left + right + (left + right - whole) / 15.0;
        }
        go(f, a, m, fa, flm, fm, left, tol / 2.0, depth - 1)
            + go(f, m, b, fm, frm, fb, right, tol / 2.0, depth - 1)
    }
    if b <= a {
        return 0.0;
    }
    let (fa, fm, fb) = (f(a), f(0.5 * (a + b)), f(b));
    go(f, a, b, fa, fm, fb, rule(fa, fm, fb, a, b), tol, depth)
}

/// The Jacobian of the strobe map at `x` by Richardson differences (step `h`) of runs at
/// rtol = atol = 1e-12.
fn difference_monodromy(params: &Params, law: &DiodeLaw, x: State, h: f64) -> Matrix2 {
    let dynamics = ShockleyDynamics::new(*law, options(1e-12)).unwrap();
    let map = |x: State| {
        let s = dynamics.strobe_map(params, x, 1).unwrap().state;
        [s.y, s.v]
    };
    Matrix2(state_jacobian(map, x, h))
}

/// The Floquet multipliers of the Shockley orbit (variational equations on the solver's steps,
/// rtol 1e-12) against the eigenvalues of the strobe map's Jacobian by Richardson differences,
/// to 1e-6, at three drives of the paper's circuit; det M against Liouville's formula.
///
/// At 3 kHz and 1.5 V the orbit stops twice a period (|y'| below the threshold for a third of
/// it), where D' ≈ a/ε ≈ 7.5·10³: the flow contracts phase area by e^{−∫(2ζ + D')dτ}, whose
/// exponent the test computes (about 8.6·10³), so μ2 = det M/μ1 is far below any floating-point
/// number. What is meaningful of μ2 there is that it lies below the resolution of the map:
/// the differences see a second eigenvalue within their noise (1e-6) of 0, and the computed
/// map's own (the product of the steps' damping, which depends on the steps) is below
/// 1e-12·|μ1|; μ1 is compared to 1e-6 as at the other drives.
#[test]
fn floquet_multipliers_match_differences_of_the_strobe_map() {
    for (hertz, volts, sticks) in [
        (9.97e3, 1.498, false),
        (14.0e3, 2.5, false),
        (3.0e3, 1.5, true),
    ] {
        let (params, dynamics, orbit) = orbit_at(hertz, volts, 1e-12);
        let law = *dynamics.law();
        let fd = difference_monodromy(&params, &law, orbit.state, 1e-4);
        let expected = fd.eigenvalues();
        let [mu1, mu2] = orbit.multipliers;
        let contraction = liouville(&params, &law, orbit.state, 1);
        let image = dynamics.strobe_map(&params, orbit.state, 1).unwrap();
        let log_det = image.log_det.unwrap();
        eprintln!(
            "{hertz} Hz {volts} V: orbit {:?} stops {}; multipliers {mu1:?} {mu2:?}; differences \
             {:?}; ln det M {log_det} (steps), {} (Liouville)",
            orbit.state,
            orbit.stops.len(),
            expected,
            -contraction
        );
        let close = |a: Multiplier, b: Multiplier| (a.re - b.re).hypot(a.im - b.im) <= 1e-6;
        assert!(
            close(mu1, expected[0]),
            "{hertz} Hz: μ1 {mu1:?} vs {:?}",
            expected[0]
        );
        if sticks {
            assert!(!orbit.stops.is_empty(), "{hertz} Hz: {:?}", orbit.stops);
            assert!(expected[1].modulus() <= 1e-6, "{:?}", expected[1]);
            assert!(mu2.modulus() <= 1e-12 * mu1.modulus(), "{mu2:?}");
            assert!(
                contraction > 1e3 && log_det < -28.0,
                "{contraction} {log_det}"
            );
        } else {
            assert!(orbit.stops.is_empty(), "{hertz} Hz: {:?}", orbit.stops);
            assert!(
                close(mu2, expected[1]),
                "{hertz} Hz: μ2 {mu2:?} vs {:?}",
                expected[1]
            );
            assert!(
                (log_det + contraction).abs() <= 1e-6 * contraction,
                "{hertz} Hz: ln det M {log_det} vs {}",
                -contraction
            );
        }
        // λ1 = ln|μ1|/T against the Lyapunov measurement of the tangent dynamics, from the
        // orbit's strobe (the transient aligns J with the first eigenvector).
        let measured = dynamics
            .lyapunov_exponents(
                &params,
                orbit.state,
                &LyapunovOptions {
                    transient_periods: 50,
                    periods: 200,
                    blocks: 20,
                    ..LyapunovOptions::default()
                },
                &(),
            )
            .unwrap();
        eprintln!(
            "{hertz} Hz {volts} V: λ1 = {} (orbit), {} ± {} (measured), λ2 {:?}",
            orbit.exponent(),
            measured.largest.per_tau,
            measured.largest.error_per_tau,
            measured.second
        );
        let lambda = orbit.exponent();
        if mu1.is_real() {
            // A real dominant multiplier: the renormalised tangent grows by |μ1| a period.
            assert!(
                (measured.largest.per_tau - lambda).abs() <= 1e-6 * lambda.abs(),
                "{hertz} Hz: {} vs {lambda}",
                measured.largest.per_tau
            );
        } else {
            // A complex pair turns the tangent: its growth beats from period to period about
            // the mean ln|μ|/T, which the measurement gives within its error, and the two
            // exponents sum to ln|det M|/T exactly (both are ln|μ|/T).
            let sum = measured.largest.per_tau + measured.second.per_tau();
            assert!(
                (measured.largest.per_tau - lambda).abs() <= 4.0 * measured.largest.error_per_tau,
                "{hertz} Hz: {} ± {} vs {lambda}",
                measured.largest.per_tau,
                measured.largest.error_per_tau
            );
            assert!(
                (sum - 2.0 * lambda).abs() <= 1e-6 * lambda.abs(),
                "{sum} vs {lambda}"
            );
        }
        assert_eq!(orbit.stability, Stability::Stable);
    }
}

/// The samples of a periodic orbit and their derivatives by (ζ, β, w, φ) and the law's (a, ε,
/// r) against Richardson differences of the whole computation (Newton's method on the
/// orbit at the changed parameter, then the samples), at rtol = atol = 1e-12.
#[test]
fn orbit_sample_sensitivities_match_richardson_differences() {
    for (hertz, volts) in [(9.97e3, 1.498), (3.0e3, 1.5)] {
        let (params, dynamics, orbit) = orbit_at(hertz, volts, 1e-12);
        let law = *dynamics.law();
        let taus = grid(0.0, 1.5 * params.drive_period(), 31);
        let samples = dynamics
            .orbit_sensitivity(&params, orbit.state, 1, &taus)
            .unwrap();
        // The samples are those of a plain solver from the fixed point.
        let mut plain = ShockleySolver::new(
            dynamics.model(&params).unwrap(),
            orbit.state,
            options(1e-12),
        )
        .unwrap();
        let plain = sample_at(&mut plain, &taus, |_| {}).unwrap();
        for (a, b) in samples.iter().zip(&plain) {
            assert_eq!(a.y.to_bits(), b.y.to_bits());
        }
        let ys = |params: Params, law: DiodeLaw| -> Vec<f64> {
            let d = ShockleyDynamics::new(law, options(1e-12)).unwrap();
            let o = d
                .find_periodic_orbit(&params, orbit.state, 1, &NewtonOptions::default())
                .unwrap();
            let mut s =
                ShockleySolver::new(d.model(&params).unwrap(), o.state, options(1e-12)).unwrap();
            sample_at(&mut s, &taus, |_| {})
                .unwrap()
                .iter()
                .map(|s| s.y)
                .collect()
        };
        type Change = Box<dyn Fn(f64) -> (Params, DiodeLaw)>;
        let (p, l) = (params, law);
        let cases: Vec<(&str, f64, f64, Change)> = vec![
            (
                "zeta",
                p.zeta,
                1e-4,
                Box::new(move |z| (Params { zeta: z, ..p }, l)),
            ),
            (
                "beta",
                p.beta,
                1e-3,
                Box::new(move |b| (Params { beta: b, ..p }, l)),
            ),
            ("w", p.w, 1e-4, Box::new(move |w| (Params { w, ..p }, l))),
            (
                "phi",
                0.0,
                1e-3,
                Box::new(move |phi| (p.with_phi(phi).unwrap(), l)),
            ),
            (
                "a",
                l.scale,
                1e-5,
                Box::new(move |a| (p, DiodeLaw { scale: a, ..l })),
            ),
            (
                "epsilon",
                l.knee,
                1e-8,
                Box::new(move |e| (p, DiodeLaw { knee: e, ..l })),
            ),
            (
                "r",
                l.resistance,
                1e-5,
                Box::new(move |r| (p, DiodeLaw { resistance: r, ..l })),
            ),
        ];
        for (k, (name, at, h, change)) in cases.iter().enumerate() {
            let d = |h: f64| -> Vec<f64> {
                let (pp, lp) = change(at + h);
                let (pm, lm) = change(at - h);
                ys(pp, lp)
                    .iter()
                    .zip(ys(pm, lm))
                    .map(|(a, b)| (a - b) / (2.0 * h))
                    .collect()
            };
            let (coarse, fine) = (d(*h), d(h / 2.0));
            let fd: Vec<f64> = fine
                .iter()
                .zip(&coarse)
                .map(|(f, c)| (4.0 * f - c) / 3.0)
                .collect();
            let exact: Vec<f64> = samples
                .iter()
                .map(|s| if k < 4 { s.dy[k] } else { s.dlaw[k - 4] })
                .collect();
            let scale = fd.iter().fold(0.0f64, |m, x| m.max(x.abs()));
            let worst = exact
                .iter()
                .zip(&fd)
                .fold(0.0f64, |m, (a, b)| m.max((a - b).abs()));
            eprintln!("{hertz} Hz {volts} V: dy/d{name}: largest {scale:.6e}, worst difference {worst:.3e}");
            assert!(
                worst <= 1e-6 * scale,
                "{hertz} Hz: dy/d{name}: {worst} of {scale}"
            );
        }
        assert!(samples.iter().all(|s| s.dy[4] == 0.0));
    }
}

/// The stability tools of an experiment with Shockley diodes: continuation (no grazing, no
/// μs), a bifurcation diagram and a basin map, each consistent with the orbit found by
/// Newton's method at the same drive.
#[test]
fn the_experiments_tools_take_shockley_diodes() {
    use stickslip::attractor::AttractorKind;
    use stickslip::basins::Basins;
    use stickslip::bifurcation::{Bifurcation, BifurcationOptions};
    use stickslip::continuation::{continue_orbit_of, settled_orbit, ContinuationOptions};
    use stickslip::scan::{Axis, ParameterRange, SweepDirection};
    use stickslip::{DiodePair, Experiment, Parameter};

    let e = Experiment::paper()
        .with_shockley(DiodePair::one_n4148())
        .unwrap()
        .with_beta(3.61)
        .unwrap()
        .with_w(1.1)
        .unwrap();
    let dynamics = e.dynamics().unwrap();
    assert!(!dynamics.is_exact());
    // A branch in w: every point a fixed point of the map to its accuracy, its multipliers
    // the eigenvalues of the map's Jacobian there; no grazing reported.
    let (params, orbit) = settled_orbit(&e).unwrap();
    let branch = continue_orbit_of(
        dynamics.as_ref(),
        &params,
        Parameter::W,
        &orbit,
        0.9,
        &ContinuationOptions::default(),
        &(),
    )
    .unwrap();
    assert!(branch.points.len() > 5, "{}", branch.points.len());
    assert!(branch
        .special
        .iter()
        .all(|s| s.kind != stickslip::continuation::SpecialKind::Grazing));
    for p in branch.points.iter().step_by(7) {
        let at = Parameter::W.set(params, p.value).unwrap();
        let image = dynamics.strobe_map(&at, p.orbit.state, 1).unwrap();
        let residual = (image.state.y - p.orbit.state.y)
            .abs()
            .max((image.state.v - p.orbit.state.v).abs());
        let scale = 1f64.max(p.orbit.state.y.abs()).max(p.orbit.state.v.abs())
            * image.jacobian.max_abs().max(1.0);
        assert!(
            residual <= 1e-6 * scale,
            "{residual} at w = {}: {:?} {:?} {:?}",
            p.value,
            p.orbit.state,
            image.state,
            p.orbit.residuals
        );
        let mu = ShockleyDynamics::multipliers(&image)[0];
        assert!((mu.modulus() - p.orbit.multipliers[0].modulus()).abs() < 1e-6);
    }
    // A bifurcation diagram: periodic at every value, the exponent that of the orbit.
    let values = vec![0.9, 1.0, 1.1];
    let diagram = Bifurcation::new(&e, Axis::new(Parameter::W, values).unwrap())
        .unwrap()
        .direction(SweepDirection::Up)
        .options(BifurcationOptions {
            first_transient_periods: 300,
            record: stickslip::attractor::RecordOptions {
                transient_periods: 100,
                points: 40,
                ..Default::default()
            },
        })
        .unwrap()
        .run(&())
        .unwrap();
    for step in &diagram {
        assert_eq!(
            (step.record.kind, step.record.period),
            (AttractorKind::Periodic, Some(1))
        );
        let at = e.clone().with_w(step.value).unwrap();
        let orbit = at
            .periodic_orbit(
                None,
                0,
                &at.steady_options(),
                &NewtonOptions::default(),
                &(),
            )
            .unwrap();
        // Over the 100 recorded periods the tangent of a focus (a complex pair) beats about
        // its mean: the record's exponent lies within its error of the orbit's.
        assert!(
            (step.record.exponent - orbit.exponent()).abs()
                <= 4.0 * step.record.exponent_error + 1e-6 * orbit.exponent().abs(),
            "{} ± {} vs {}",
            step.record.exponent,
            step.record.exponent_error,
            orbit.exponent()
        );
    }
    // A basin map: one attractor, the periodic orbit, with its multipliers.
    let range = ParameterRange::new("y0", -2.0, 2.0, 3).unwrap();
    let map = Basins::new(&e, &range, &range).unwrap().run(&()).unwrap();
    assert_eq!(map.attractors.len(), 1);
    let a = &map.attractors[0];
    assert_eq!(
        (a.kind, a.period, a.cells),
        (AttractorKind::Periodic, Some(1), 9)
    );
    let orbit = e
        .periodic_orbit(None, 0, &e.steady_options(), &NewtonOptions::default(), &())
        .unwrap();
    let mu = a.multipliers.unwrap()[0];
    assert!(
        (mu.modulus() - orbit.multipliers[0].modulus()).abs() < 1e-6,
        "{mu:?} at {:?} vs {:?} at {:?}",
        a.state,
        orbit.multipliers,
        orbit.state
    );
}

/// The multipliers of the computed strobe map against the flow's (Richardson differences of
/// the map at rtol 1e-12) as the map's tolerance tightens: the Jacobian converges more slowly
/// than the map (see `ShockleyDynamics::MAP_TOLERANCE`, the tolerance the tools use).
#[test]
fn multipliers_converge_with_the_tolerance() {
    let (params, law) = paper_drive(9.97e3, 1.498);
    let (_, _, reference) = orbit_at(9.97e3, 1.498, 1e-12);
    let expected = difference_monodromy(&params, &law, reference.state, 1e-4).eigenvalues()[0];
    let mut errors = Vec::new();
    for tolerance in [1e-6, 1e-9, ShockleyDynamics::MAP_TOLERANCE] {
        let dynamics = ShockleyDynamics::new(law, options(tolerance))
            .unwrap()
            .with_map_options(options(tolerance))
            .unwrap();
        let orbit = dynamics
            .find_periodic_orbit(&params, reference.state, 1, &NewtonOptions::default())
            .unwrap();
        let mu = orbit.multipliers[0];
        let error = (mu.re - expected.re).hypot(mu.im - expected.im);
        eprintln!("rtol {tolerance:e}: μ1 {mu:?}, {error:.2e} from the flow's");
        errors.push(error);
    }
    assert!(
        errors[0] > 1e-3 && errors[1] < 1e-4 && errors[2] < 1e-5,
        "{errors:?}"
    );
    assert!(errors[0] > errors[1] && errors[1] > errors[2], "{errors:?}");
}

/// A map of exponents with Shockley diodes (`phase-diagram --color lambda1 --model
/// shockley`): every point's λ1 is that of its periodic orbit (`orbit`), the same for one
/// thread and two; at one point the measured exponent (`lyapunov`) agrees within its error.
#[test]
fn a_shockley_map_of_exponents_is_its_orbits_exponents() {
    use stickslip::scan::{Axis, Grid};
    use stickslip::steady::MotionClass;
    use stickslip::{DiodePair, Experiment, Parameter};

    let e = Experiment::paper()
        .with_shockley(DiodePair::one_n4148())
        .unwrap();
    let grid = |threads: usize| {
        Grid::new(
            &e,
            Axis::new(Parameter::W, vec![0.9, 1.1]).unwrap(),
            Axis::new(Parameter::Beta, vec![2.0, 3.61]).unwrap(),
        )
        .unwrap()
        .lyapunov(stickslip::SteadyOptions::DEFAULT_LYAPUNOV)
        .unwrap()
        .threads(threads)
        .unwrap()
        .run(&())
        .unwrap()
    };
    let (one, two) = (grid(1), grid(2));
    assert_eq!(one.points, two.points);
    for p in &one.points {
        assert_eq!(
            (p.class, p.period),
            (MotionClass::Sliding, Some(1)),
            "{p:?}"
        );
        let at = e
            .clone()
            .with_w(p.params.w)
            .unwrap()
            .with_beta(p.params.beta)
            .unwrap();
        let orbit = at
            .periodic_orbit(
                None,
                0,
                &at.steady_options(),
                &NewtonOptions::default(),
                &(),
            )
            .unwrap();
        let lambda = p.lyapunov.expect("an exponent at every point");
        assert!(
            lambda.per_tau < 0.0 && lambda.error_per_tau == 0.0,
            "{lambda:?}"
        );
        assert!(
            (lambda.per_tau - orbit.exponent()).abs() <= 1e-9 * orbit.exponent().abs(),
            "{} vs the orbit's {} at {:?}",
            lambda.per_tau,
            orbit.exponent(),
            p.params
        );
        assert!(
            (lambda.per_period - lambda.per_tau * p.params.drive_period()).abs()
                <= 1e-12 * lambda.per_period.abs()
        );
    }
    // The measurement of the tangent dynamics over 2000 periods, against the map's exact one.
    let p = &one.points[3];
    let at = e
        .clone()
        .with_w(p.params.w)
        .unwrap()
        .with_beta(p.params.beta)
        .unwrap();
    let options = LyapunovOptions {
        transient_periods: 300,
        periods: 2000,
        ..Default::default()
    };
    let measured = at.lyapunov(&options, &()).unwrap().exponents.largest;
    let exact = p.lyapunov.unwrap().per_tau;
    assert!(
        (measured.per_tau - exact).abs() <= 4.0 * measured.error_per_tau + 1e-3 * exact.abs(),
        "measured {measured:?} vs the map's {exact}"
    );
}

/// A Shockley motion that has not repeated within the search's cap is measured, as the PWL
/// model's are (`steady`'s λ1): here a transient cut short, contracting onto the orbit whose
/// exponent it measures.
#[test]
fn a_shockley_motion_that_does_not_repeat_is_measured() {
    use stickslip::stability::NonperiodicVerdict;
    use stickslip::{DiodePair, Experiment};

    let e = Experiment::paper()
        .with_shockley(DiodePair::one_n4148())
        .unwrap()
        .with_w(1.1)
        .unwrap()
        .with_beta(3.61)
        .unwrap();
    let short = e.steady_options().with_max_periods(2).unwrap();
    let steady = e.steady_with(&short).unwrap();
    assert_eq!(steady.period, None);
    let c = steady.lyapunov.expect("the motion is measured");
    let orbit = e
        .periodic_orbit(None, 0, &e.steady_options(), &NewtonOptions::default(), &())
        .unwrap();
    assert_eq!(c.verdict, NonperiodicVerdict::Contracting, "{c:?}");
    let l = c.exponents.largest;
    assert!(
        (l.per_tau - orbit.exponent()).abs()
            <= 4.0 * l.error_per_tau + 1e-3 * orbit.exponent().abs(),
        "{l:?} vs the orbit's {}",
        orbit.exponent()
    );
    // Without the measurement, nothing is measured.
    let off = short.with_lyapunov(None).unwrap();
    assert!(e.steady_with(&off).unwrap().lyapunov.is_none());
}
