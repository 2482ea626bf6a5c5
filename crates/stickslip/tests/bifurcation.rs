//! Tests of bifurcation diagrams, basins of attraction and continuation, on cases built from
//! the model's own bifurcations: period-p windows and chaos at ζ = 0, μs = 3, β = 9; a period
//! doubling and a pair of mirror-image orbits at ζ = 0, μs = 3, β = 3.269; a fold, a grazing
//! and coexisting rest and motion with the paper's ζ, μs = 1.5, w = 0.9.

use stickslip::attractor::{record_strobes, AttractorKind, RecordOptions};
use stickslip::basins::{BasinMethod, BasinOptions, BasinReport, Basins};
use stickslip::bifurcation::{Bifurcation, BifurcationOptions};
use stickslip::continuation::{
    continue_both_ways, continue_orbit, settled_orbit, Branch, BranchEnd, BranchReport,
    ContinuationOptions, Obstacle, SpecialKind,
};
use stickslip::scan::{Axis, ParameterRange, SweepDirection, SweepLeg};
use stickslip::solver::run_until;
use stickslip::stability::{
    find_periodic_orbit, lyapunov_exponents, strobe_map, LyapunovOptions, NewtonOptions,
    PeriodicOrbit, Stability,
};
use stickslip::{EventKind, ExactSolver, Experiment, Parameter, Params, Solver, State};

const PAPER_ZETA: f64 = 0.046816;

fn params(zeta: f64, mu_s: f64, w: f64, beta: f64) -> Params {
    Params::new(zeta, w, beta)
        .and_then(|p| p.with_mu_s(mu_s))
        .expect("valid parameters")
}

fn experiment(zeta: f64, mu_s: f64, w: f64, beta: f64) -> Experiment {
    Experiment::dimensionless(zeta, w, beta)
        .and_then(|e| e.with_mu_s(mu_s))
        .expect("valid experiment")
}

fn distance(a: State, b: State) -> f64 {
    (a.y - b.y).abs().max((a.v - b.v).abs())
}

/// The distinct points of `strobes`, two points being one when closer than `tolerance`.
fn distinct(strobes: &[State], tolerance: f64) -> Vec<State> {
    let mut out: Vec<State> = Vec::new();
    for &s in strobes {
        if !out.iter().any(|&d| distance(d, s) <= tolerance) {
            out.push(s);
        }
    }
    out
}

/// The strobe points x, P(x), …, P^{p−1}(x) of an orbit, by the exact solver.
fn orbit_strobes(params: &Params, orbit: &PeriodicOrbit) -> Vec<State> {
    let mut solver = ExactSolver::new(*params, orbit.state);
    let mut out = vec![orbit.state];
    for k in 1..orbit.period {
        run_until(&mut solver, k as f64 * params.drive_period(), |_| {}).unwrap();
        out.push(solver.state());
    }
    out
}

// ---------------------------------------------------------------- bifurcation diagrams

#[test]
fn a_period_p_orbit_gives_exactly_p_strobe_points() {
    // (ζ, μs, w, β) and the period the motion settles on from rest.
    for (zeta, mu_s, w, beta, p) in [
        (0.0, 3.0, 0.25, 9.0, 1),
        (0.02, 3.0, 0.3534, 9.731, 2),
        (0.0, 3.0, 0.42, 9.0, 3),
    ] {
        let e = experiment(zeta, mu_s, w, beta);
        let steps = Bifurcation::new(&e, Axis::new(Parameter::W, vec![w]).unwrap())
            .unwrap()
            .direction(SweepDirection::Up)
            .options(BifurcationOptions {
                record: RecordOptions {
                    points: 200,
                    ..RecordOptions::default()
                },
                ..BifurcationOptions::default()
            })
            .unwrap()
            .run(&())
            .unwrap();
        let record = &steps[0].record;
        assert_eq!(record.strobes.len(), 200);
        assert_eq!(
            (record.kind, record.period),
            (AttractorKind::Periodic, Some(p))
        );
        // Repeating to the record's tolerance, 1e-8 relative: the orbit computed at growing
        // times differs by the rounding of the time, amplified by the releases.
        let scale = record
            .strobes
            .iter()
            .fold(1f64, |s, x| s.max(x.y.abs()).max(x.v.abs()));
        let points = distinct(&record.strobes, 1e-8 * scale);
        assert_eq!(points.len(), p, "w = {w}: {} distinct points", points.len());
        // The points are the orbit Newton's method finds, every one of them.
        let pr = params(zeta, mu_s, w, beta);
        let orbit =
            find_periodic_orbit(&pr, record.strobes[0], p, &NewtonOptions::default()).unwrap();
        assert_eq!(orbit.stability, Stability::Stable);
        for s in orbit_strobes(&pr, &orbit) {
            let nearest = points
                .iter()
                .map(|&q| distance(q, s))
                .fold(f64::MAX, f64::min);
            assert!(
                nearest < 1e-8,
                "w = {w}: a strobe point is {nearest:e} off the orbit"
            );
        }
        // On a periodic orbit the exponent is that of its largest multiplier.
        let expected = orbit.exponent();
        assert!(
            (record.exponent - expected).abs() < 0.05 * expected.abs() + 1e-3,
            "w = {w}: exponent {} against ln|mu|/pT = {expected}",
            record.exponent
        );
    }
}

/// A diagram measures the exponent of a motion that does not repeat as `steady` and the maps
/// do: sequentially from the record's last point (the default measurement of the steady
/// state), its error kept; and the result agrees, within the errors, with a fixed run ten
/// times as long from the same point.
#[test]
fn a_diagram_measures_a_chaotic_exponent_sequentially_with_its_error() {
    let experiment = experiment(0.0, 3.0, 0.3, 9.0);
    let diagram = Bifurcation::new(
        &experiment,
        Axis::new(Parameter::W, vec![0.25, 0.33]).unwrap(),
    )
    .unwrap()
    .direction(SweepDirection::Up)
    .run(&())
    .unwrap();
    let (periodic, chaotic) = (&diagram[0], &diagram[1]);
    assert_eq!(
        (periodic.record.kind, periodic.record.period),
        (AttractorKind::Periodic, Some(1))
    );
    assert!(periodic.record.exponent < 0.0);

    assert_eq!(chaotic.record.kind, AttractorKind::Chaotic);
    let sequential = lyapunov_exponents(
        &chaotic.params,
        chaotic.record.final_state(),
        &stickslip::steady::SteadyOptions::DEFAULT_LYAPUNOV,
    )
    .unwrap();
    assert!(sequential.converged);
    assert!(sequential.periods < sequential.cap, "stopped when it knew");
    assert_eq!(chaotic.record.exponent, sequential.largest.per_tau);
    assert_eq!(
        chaotic.record.exponent_error,
        sequential.largest.error_per_tau
    );
    assert!(chaotic.record.exponent > 4.0 * chaotic.record.exponent_error);
    let fixed = LyapunovOptions {
        transient_periods: 100,
        periods: 10 * sequential.periods,
        blocks: 20,
        significance: 4.0,
        sequential: false,
    };
    let long = lyapunov_exponents(&chaotic.params, chaotic.record.final_state(), &fixed).unwrap();
    let gap = (chaotic.record.exponent - long.largest.per_tau).abs();
    let allowed =
        4.0 * (chaotic.record.exponent_error.powi(2) + long.largest.error_per_tau.powi(2)).sqrt();
    assert!(
        gap <= allowed,
        "exponent {} ± {} against {} ± {} over {} periods",
        chaotic.record.exponent,
        chaotic.record.exponent_error,
        long.largest.per_tau,
        long.largest.error_per_tau,
        long.periods
    );
}

#[test]
fn a_chaotic_window_gives_a_cloud_of_points_and_a_positive_exponent() {
    let pr = params(0.0, 3.0, 0.33, 9.0);
    let options = RecordOptions {
        transient_periods: 1000,
        points: 2000,
        ..RecordOptions::default()
    };
    let record = record_strobes(&pr, State::default(), &options).unwrap();
    assert_eq!(record.kind, AttractorKind::Chaotic);
    assert_eq!(record.period, None);
    // No two of 2000 points coincide.
    assert_eq!(distinct(&record.strobes, 1e-9).len(), 2000);
    assert!(record.exponent > 4.0 * record.exponent_error);
    // The same exponent as the long measurement of the stability module, within their errors.
    let long = lyapunov_exponents(&pr, State::default(), &LyapunovOptions::default()).unwrap();
    let gap = (record.exponent - long.largest.per_tau).abs();
    let allowed = 4.0 * (record.exponent_error.powi(2) + long.largest.error_per_tau.powi(2)).sqrt();
    assert!(
        gap <= allowed,
        "exponent {} ± {} against {} ± {}",
        record.exponent,
        record.exponent_error,
        long.largest.per_tau,
        long.largest.error_per_tau
    );
}

#[test]
fn the_two_legs_follow_coexisting_branches() {
    // μs = 1.5: from rest the oscillator cannot start below β = 1.5, while a motion already
    // going on keeps going down to the fold near β = 1.304.
    let e = experiment(PAPER_ZETA, 1.5, 0.9, 1.0);
    let range = ParameterRange::new("beta", 1.25, 1.6, 36).unwrap();
    let steps = Bifurcation::new(&e, Axis::range(Parameter::Beta, &range).unwrap())
        .unwrap()
        .run(&())
        .unwrap();
    assert_eq!(steps.len(), 72);
    let at = |leg: SweepLeg, beta: f64| {
        steps
            .iter()
            .find(|s| s.leg == leg && (s.value - beta).abs() < 1e-12)
            .unwrap()
    };
    assert_eq!(at(SweepLeg::Up, 1.4).record.kind, AttractorKind::Static);
    let down = &at(SweepLeg::Down, 1.4).record;
    assert_eq!((down.kind, down.period), (AttractorKind::Periodic, Some(1)));
    assert_eq!(at(SweepLeg::Down, 1.25).record.kind, AttractorKind::Static);
    assert_eq!(at(SweepLeg::Up, 1.55).record.kind, AttractorKind::Periodic);
}

#[test]
fn a_diagram_resumed_from_any_step_is_the_same() {
    let e = experiment(0.0, 3.0, 0.3, 9.0);
    let range = ParameterRange::new("w", 0.3, 0.4, 12).unwrap();
    let diagram = Bifurcation::new(&e, Axis::range(Parameter::W, &range).unwrap())
        .unwrap()
        .options(BifurcationOptions {
            record: RecordOptions {
                points: 30,
                transient_periods: 50,
                ..RecordOptions::default()
            },
            first_transient_periods: 300,
        })
        .unwrap();
    let mut seen = Vec::new();
    let whole = diagram
        .run_from(0, e.initial(), &(), &mut |i, _| seen.push(i))
        .unwrap();
    assert_eq!(seen, (0..24).collect::<Vec<_>>());
    for start in [1, 11, 12, 23] {
        let state = whole[start - 1].record.final_state();
        let rest = diagram.run_from(start, state, &(), &mut |_, _| {}).unwrap();
        assert_eq!(rest, whole[start..], "resumed at {start}");
    }
    // Cancelled by its monitor after 5 steps.
    let stop = |done: usize, _: usize| done < 5;
    assert!(matches!(
        diagram.run(&stop),
        Err(stickslip::Error::Cancelled { done: 5, total: 24 })
    ));
}

// ---------------------------------------------------------------- basins of attraction

/// ζ = 0, μs = 3, β = 3.269, w = 0.6: an orbit with one stop per period and its mirror image
/// under (y, y', τ) → (−y, −y', τ + T/2).
fn mirror_pair() -> Basins {
    let e = experiment(0.0, 3.0, 0.6, 3.269);
    let r = ParameterRange::new("y0", -8.0, 8.0, 24).unwrap();
    Basins::new(&e, &r, &r).unwrap()
}

#[test]
fn basin_attractors_are_the_orbits_newton_finds() {
    let basins = mirror_pair();
    let map = basins.run(&()).unwrap();
    assert_eq!(map.undecided, 0);
    assert_eq!(map.attractors.len(), 2);
    let pr = *basins.params();
    let [a, b] = [&map.attractors[0], &map.attractors[1]];
    for x in [a, b] {
        assert_eq!((x.kind, x.period), (AttractorKind::Periodic, Some(1)));
        // A fixed point: Newton's method takes no step from it.
        let orbit = find_periodic_orbit(&pr, x.state, 1, &NewtonOptions::default()).unwrap();
        assert_eq!(orbit.iterations, 0);
        assert_eq!(orbit.stability, Stability::Stable);
        assert!(x.fraction > 0.2);
    }
    assert!((a.fraction + b.fraction - 1.0).abs() < 1e-12);
    // Mirror images: half a period after the strobe, one orbit is minus the other.
    let mut solver = ExactSolver::new(pr, a.state);
    run_until(&mut solver, 0.5 * pr.drive_period(), |_| {}).unwrap();
    let half = solver.state();
    assert!(
        distance(
            State {
                y: -half.y,
                v: -half.v
            },
            b.state
        ) < 1e-9
    );
    // Every cell: a plain long simulation from its initial state ends on its attractor.
    for i in (0..24).step_by(5) {
        for j in (0..24).step_by(3) {
            let mut solver = ExactSolver::new(
                pr,
                State {
                    y: map.y0[i],
                    v: map.v0[j],
                },
            );
            run_until(&mut solver, 3000.0 * pr.drive_period(), |_| {}).unwrap();
            let end = solver.state();
            let own = map.at(i, j).unwrap();
            assert!(
                distance(end, own.state) < 1e-6,
                "cell ({i}, {j}) ends at {end:?}"
            );
        }
    }
}

#[test]
fn basins_are_the_same_for_any_threads_and_blocks() {
    // The exhaustive method, whose cells are computed on their own in blocks of rows (the
    // recurrence method: tests/basins.rs).
    let basins = mirror_pair()
        .options(BasinOptions {
            method: BasinMethod::Exhaustive,
            ..BasinOptions::default()
        })
        .unwrap();
    let one = basins.clone().threads(1).unwrap().run(&()).unwrap();
    let two = basins.clone().threads(2).unwrap().run(&()).unwrap();
    assert_eq!(one, two);
    let mut cells = basins.run_rows(0..7, &()).unwrap();
    cells.extend(basins.run_rows(7..24, &()).unwrap());
    assert_eq!(basins.identify(&cells).unwrap(), one);
}

#[test]
fn rest_and_motion_coexist_below_the_static_limit() {
    let e = experiment(PAPER_ZETA, 1.5, 0.9, 1.4);
    let r = ParameterRange::new("y0", -3.0, 3.0, 16).unwrap();
    let map = Basins::new(&e, &r, &r).unwrap().run(&()).unwrap();
    let rest = map
        .attractors
        .iter()
        .find(|a| a.kind == AttractorKind::Static)
        .expect("some cells come to rest");
    // At rest for ever needs |y| ≤ μs − β.
    let (lo, hi) = rest.rest_range.unwrap();
    assert!(
        lo >= -0.1 - 1e-12 && hi <= 0.1 + 1e-12,
        "rest from {lo} to {hi}"
    );
    let moving = map
        .attractors
        .iter()
        .find(|a| a.kind == AttractorKind::Periodic)
        .expect("some cells keep moving");
    let orbit = find_periodic_orbit(
        &params(PAPER_ZETA, 1.5, 0.9, 1.4),
        moving.state,
        1,
        &NewtonOptions::default(),
    )
    .unwrap();
    assert_eq!(orbit.stops.len(), 2);
    assert_eq!(map.attractors.len(), 2);
}

#[test]
fn a_chaotic_basin_is_one_attractor() {
    let e = experiment(0.0, 3.0, 0.33, 9.0);
    let r = ParameterRange::new("y0", -4.0, 4.0, 3).unwrap();
    let map = Basins::new(&e, &r, &r)
        .unwrap()
        .options(BasinOptions {
            max_periods: 300,
            lyapunov_periods: 2000,
            ..BasinOptions::default()
        })
        .unwrap()
        .run(&())
        .unwrap();
    assert_eq!(map.attractors.len(), 1, "{:?}", map.attractors);
    let a = &map.attractors[0];
    assert_eq!((a.kind, a.cells), (AttractorKind::Chaotic, 9));
    assert!(a.exponent > 0.0);
}

// ---------------------------------------------------------------- continuation

/// The period-1 orbit at ζ = 0, μs = 3, β = 3.269, w = 0.6 (one stop per period).
fn doubling_start() -> (Params, PeriodicOrbit) {
    let pr = params(0.0, 3.0, 0.6, 3.269);
    let orbit =
        find_periodic_orbit(&pr, State { y: 4.9, v: 0.0 }, 1, &NewtonOptions::default()).unwrap();
    (pr, orbit)
}

/// The sliding orbit with the paper's ζ, μs = 1.5, w = 0.9 at β = 1.45.
fn fold_start() -> (Params, PeriodicOrbit) {
    let pr = params(PAPER_ZETA, 1.5, 0.9, 1.45);
    let orbit =
        find_periodic_orbit(&pr, State { y: 0.25, v: 2.1 }, 1, &NewtonOptions::default()).unwrap();
    (pr, orbit)
}

fn special(branch: &Branch, kind: SpecialKind) -> &stickslip::continuation::SpecialPoint {
    branch
        .special
        .iter()
        .find(|s| s.kind == kind)
        .unwrap_or_else(|| panic!("no {kind:?} on the branch: {:?}", branch.special))
}

#[test]
fn continuation_reproduces_the_branch_newton_finds_point_by_point() {
    let (pr, orbit) = doubling_start();
    let branch = continue_orbit(
        &pr,
        Parameter::W,
        &orbit,
        0.7,
        &ContinuationOptions::default(),
        &(),
    )
    .unwrap();
    assert_eq!(branch.end, BranchEnd::Boundary { value: 0.7 });
    assert_eq!(branch.points.last().unwrap().value, 0.7);
    assert!(branch.points.len() > 50);
    // Natural-parameter continuation: Newton's method at each of the branch's parameter
    // values in turn, from the orbit at the value before.
    let mut guess = orbit.state;
    for point in &branch.points {
        let at = Parameter::W.set(pr, point.value).unwrap();
        let newton = find_periodic_orbit(&at, guess, 1, &NewtonOptions::default()).unwrap();
        guess = newton.state;
        let scale = 1f64.max(newton.state.y.abs());
        assert!(
            distance(newton.state, point.orbit.state) <= 1e-9 * scale,
            "w = {}: {:?} against {:?}",
            point.value,
            newton.state,
            point.orbit.state
        );
        assert!((newton.multipliers[0].re - point.orbit.multipliers[0].re).abs() < 1e-7);
        assert_eq!(newton.events.len(), point.orbit.events.len());
    }
    // Every special point lies between the two points it is said to lie between.
    for s in &branch.special {
        let (a, b) = (
            &branch.points[s.after_point],
            &branch.points[s.after_point + 1],
        );
        assert!(a.value.min(b.value) <= s.value && s.value <= a.value.max(b.value));
    }
}

/// Solve F(y, y', λ) = P(x; λ) − x = 0 together with g(x, λ) = 0, g = det(M ∓ I), by
/// Newton's method with a difference Jacobian: an independent location of a fold (sign −1:
/// det(M − I)) or a period doubling (sign +1: det(M + I)).
fn augmented(base: Params, parameter: Parameter, start: [f64; 3], sign: f64) -> [f64; 3] {
    let residual = |u: [f64; 3]| -> [f64; 3] {
        let p = parameter.set(base, u[2]).unwrap();
        let image = strobe_map(&p, State { y: u[0], v: u[1] }, 1).unwrap();
        let m = image.jacobian.0;
        let g = (m[0][0] + sign) * (m[1][1] + sign) - m[0][1] * m[1][0];
        [image.state.y - u[0], image.state.v - u[1], g]
    };
    let mut u = start;
    for _ in 0..40 {
        let r = residual(u);
        if r.iter().all(|x| x.abs() < 1e-13) {
            return u;
        }
        let mut j = [[0.0; 3]; 3];
        for k in 0..3 {
            let h = 1e-7 * u[k].abs().max(1.0);
            let (mut a, mut b) = (u, u);
            a[k] += h;
            b[k] -= h;
            let (ra, rb) = (residual(a), residual(b));
            for i in 0..3 {
                j[i][k] = (ra[i] - rb[i]) / (2.0 * h);
            }
        }
        // Cramer's rule.
        let det3 = |m: [[f64; 3]; 3]| {
            m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1])
                - m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0])
                + m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0])
        };
        let d = det3(j);
        let mut step = [0.0; 3];
        for k in 0..3 {
            let mut jk = j;
            for i in 0..3 {
                jk[i][k] = -r[i];
            }
            step[k] = det3(jk) / d;
        }
        for k in 0..3 {
            u[k] += step[k];
        }
    }
    panic!("the augmented system did not converge from {start:?}");
}

#[test]
fn a_fold_is_located_to_the_stated_tolerance() {
    let (pr, orbit) = fold_start();
    let options = ContinuationOptions::default();
    let branch = continue_orbit(&pr, Parameter::Beta, &orbit, 1.2, &options, &()).unwrap();
    let fold = special(&branch, SpecialKind::Fold);
    assert!(fold.located && fold.width <= options.locate_tolerance);
    // The stable orbit meets an unstable one.
    assert_eq!(
        (fold.before.stability, fold.after.stability),
        (Stability::Stable, Stability::Unstable)
    );
    // Independently: the fold as a zero of (P(x) − x, det(M − I)), from a guess 1e-2 away.
    let exact = augmented(
        pr,
        Parameter::Beta,
        [fold.state.y + 0.01, fold.state.v - 0.01, fold.value + 0.003],
        -1.0,
    );
    // The bracket bounds the error in arclength: 1e-9 (at a fold λ varies quadratically).
    assert!(
        (fold.value - exact[2]).abs() < 1e-9,
        "{} against {}",
        fold.value,
        exact[2]
    );
    assert!(
        distance(
            fold.state,
            State {
                y: exact[0],
                v: exact[1]
            }
        ) < 1e-8
    );
    // The branch turns back: points on both sides of the fold lie above it in β.
    let i = fold.after_point;
    assert!(branch.points[i].value > fold.value && branch.points[i + 1].value > fold.value);
}

#[test]
fn a_period_doubling_is_located_to_the_stated_tolerance() {
    let (pr, orbit) = doubling_start();
    let options = ContinuationOptions::default();
    let branch = continue_orbit(&pr, Parameter::W, &orbit, 0.7, &options, &()).unwrap();
    let pd = special(&branch, SpecialKind::PeriodDoubling);
    assert!(pd.located && pd.width <= options.locate_tolerance);
    assert_eq!(
        (pd.before.stability, pd.after.stability),
        (Stability::Stable, Stability::Unstable)
    );
    let exact = augmented(
        pr,
        Parameter::W,
        [pd.state.y + 0.01, pd.state.v + 0.01, pd.value - 0.002],
        1.0,
    );
    assert!(
        (pd.value - exact[2]).abs() < 1e-9,
        "{} against {}",
        pd.value,
        exact[2]
    );
    // Natural-parameter Newton 1e-8 on either side: the multiplier straddles −1.
    for (dw, below) in [(-1e-8, false), (1e-8, true)] {
        let at = Parameter::W.set(pr, pd.value + dw).unwrap();
        let o = find_periodic_orbit(&at, pd.state, 1, &NewtonOptions::default()).unwrap();
        assert_eq!(o.multipliers[0].re < -1.0, below, "w = {}", pd.value + dw);
    }
}

/// Stick events per drive period of a plain simulation from `state` over 40 periods.
fn simulated_stops(pr: &Params, state: State) -> f64 {
    let mut solver = ExactSolver::new(*pr, state);
    let mut sticks = 0;
    run_until(&mut solver, 40.0 * pr.drive_period(), |e| {
        sticks += usize::from(e.kind == EventKind::Stick)
    })
    .unwrap();
    sticks as f64 / 40.0
}

#[test]
fn a_grazing_point_is_where_simulation_changes_its_stops() {
    let (pr, orbit) = fold_start();
    let branch = continue_orbit(
        &pr,
        Parameter::Beta,
        &orbit,
        1.2,
        &ContinuationOptions::default(),
        &(),
    )
    .unwrap();
    let g = special(&branch, SpecialKind::Grazing);
    assert!(g.located);
    assert_eq!((g.before.turns, g.before.stops), (2, 0));
    assert_eq!((g.after.turns, g.after.stops), (0, 2));
    // A direct simulation 1e-6 on either side, from the orbit there: sliding above, two stops
    // per period below, where each stop is still short.
    for (db, stops) in [(1e-6, 0.0), (-1e-6, 2.0)] {
        let at = Parameter::Beta.set(pr, g.value + db).unwrap();
        let o = find_periodic_orbit(&at, g.state, 1, &NewtonOptions::default()).unwrap();
        assert_eq!(
            simulated_stops(&at, o.state),
            stops,
            "beta = {}",
            g.value + db
        );
        assert!(o.stops.iter().all(|s| s.duration < 1e-2));
    }
    // And from rest just below: the simulation settles on the motion with stops.
    let below = Parameter::Beta.set(pr, g.value - 1e-3).unwrap();
    let o = find_periodic_orbit(&below, g.state, 1, &NewtonOptions::default()).unwrap();
    assert_eq!(o.stops.len(), 2);
}

#[test]
fn branches_end_where_the_strobe_map_breaks() {
    let (pr, orbit) = fold_start();
    let branch = continue_orbit(
        &pr,
        Parameter::Beta,
        &orbit,
        1.2,
        &ContinuationOptions::default(),
        &(),
    )
    .unwrap();
    // Past the fold the unstable orbit's release moves onto the maximum of the drive.
    match branch.end {
        BranchEnd::Stalled {
            multiplier,
            obstacle: Obstacle::TangentialRelease { rate, .. },
            ..
        } => assert!(multiplier > 100.0 && rate < 1e-2),
        ref other => panic!("end {other:?}"),
    }
    // μs = 3, w falling from 0.6: a turn becomes a stop (a kink of the branch).
    let (pr, orbit) = doubling_start();
    let down = continue_orbit(
        &pr,
        Parameter::W,
        &orbit,
        0.5,
        &ContinuationOptions::default(),
        &(),
    )
    .unwrap();
    assert_eq!(down.end, BranchEnd::Boundary { value: 0.5 });
    let g = special(&down, SpecialKind::Grazing);
    assert_eq!(
        (g.before.turns, g.before.stops, g.after.turns, g.after.stops),
        (1, 1, 0, 2)
    );
    assert!((g.value - 0.51765).abs() < 1e-4);
}

#[test]
fn both_ways_joins_two_runs() {
    let (pr, orbit) = doubling_start();
    let options = ContinuationOptions::default();
    let both = continue_both_ways(&pr, Parameter::W, &orbit, (0.5, 0.7), &options, &()).unwrap();
    let up = continue_orbit(&pr, Parameter::W, &orbit, 0.7, &options, &()).unwrap();
    let down = continue_orbit(&pr, Parameter::W, &orbit, 0.5, &options, &()).unwrap();
    assert_eq!(both.points.len(), up.points.len() + down.points.len() - 1);
    assert_eq!(both.points.first().unwrap().value, 0.5);
    assert_eq!(both.points.last().unwrap().value, 0.7);
    assert_eq!(both.special.len(), up.special.len() + down.special.len());
    assert!(both
        .points
        .windows(2)
        .all(|p| p[1].arclength > p[0].arclength));
    for s in &both.special {
        let (a, b) = (&both.points[s.after_point], &both.points[s.after_point + 1]);
        assert!(a.value.min(b.value) <= s.value && s.value <= a.value.max(b.value));
        assert!(s.before.value.min(s.after.value) >= a.value.min(b.value));
    }
    // In the joined branch the sides of the grazing found going down are in increasing w.
    let g = special(&both, SpecialKind::Grazing);
    assert!(g.before.value < g.after.value);
    assert_eq!((g.before.stops, g.after.stops), (2, 1));
}

#[test]
fn a_diagram_draws_stable_and_unstable_branches() {
    let e = experiment(0.0, 3.0, 0.6, 3.269);
    let range = ParameterRange::new("w", 0.6, 0.66, 13).unwrap();
    let diagram = Bifurcation::new(&e, Axis::range(Parameter::W, &range).unwrap())
        .unwrap()
        .direction(SweepDirection::Up)
        .options(BifurcationOptions {
            first_transient_periods: 3000,
            ..BifurcationOptions::default()
        })
        .unwrap();
    let steps = diagram.run(&()).unwrap();
    let branches = diagram
        .branches(&steps, &ContinuationOptions::default(), &())
        .unwrap();
    let through = branches
        .iter()
        .find(|b| {
            b.special
                .iter()
                .any(|s| s.kind == SpecialKind::PeriodDoubling)
        })
        .expect("a branch through the period doubling");
    assert!(through
        .points
        .iter()
        .any(|p| p.orbit.stability == Stability::Stable));
    assert!(through
        .points
        .iter()
        .any(|p| p.orbit.stability == Stability::Unstable));
    // Each branch once.
    let doubling: Vec<_> = branches
        .iter()
        .filter(|b| {
            b.special
                .iter()
                .any(|s| s.kind == SpecialKind::PeriodDoubling)
        })
        .collect();
    assert_eq!(doubling.len(), 1);
}

#[test]
fn bad_input_is_refused_with_its_name() {
    let (pr, orbit) = doubling_start();
    let bad = ContinuationOptions {
        max_step: 0.0,
        ..ContinuationOptions::default()
    };
    assert!(matches!(
        continue_orbit(&pr, Parameter::W, &orbit, 0.7, &bad, &()),
        Err(stickslip::Error::InvalidOption {
            option: stickslip::OptionKey::MaxStep,
            ..
        })
    ));
    assert!(matches!(
        continue_orbit(
            &pr,
            Parameter::W,
            &orbit,
            0.6,
            &ContinuationOptions::default(),
            &()
        ),
        Err(stickslip::Error::InvalidParameter { name: "to", .. })
    ));
    assert!(matches!(
        continue_orbit(
            &pr,
            Parameter::MuS,
            &orbit,
            0.5,
            &ContinuationOptions::default(),
            &()
        ),
        Err(stickslip::Error::InvalidParameter { name: "mu_s", .. })
    ));
    let shockley = Experiment::paper()
        .with_w(0.9)
        .unwrap()
        .with_beta(2.0)
        .unwrap();
    let shockley = shockley
        .with_shockley(stickslip::DiodePair::default())
        .unwrap();
    // Shockley diodes: accepted, but not continued in μs, which their law does not use.
    assert!(Bifurcation::new(&shockley, Axis::new(Parameter::W, vec![0.9]).unwrap()).is_ok());
    let (params, orbit) = stickslip::continuation::settled_orbit(&shockley).unwrap();
    assert!(matches!(
        stickslip::continuation::continue_orbit_of(
            shockley.dynamics().unwrap().as_ref(),
            &params,
            Parameter::MuS,
            &orbit,
            1.5,
            &ContinuationOptions::default(),
            &()
        ),
        Err(stickslip::Error::Unsupported(
            stickslip::Unsupported::MuSNeedsPwl
        ))
    ));
}

#[test]
fn reports_hold_what_front_ends_print() {
    // A basin map: the report lists every attractor with its share of the grid.
    let map = mirror_pair().run(&()).unwrap();
    let report = BasinReport::from(&map);
    assert_eq!(report.attractors.len(), map.attractors.len());
    let shares: f64 = report.attractors.iter().map(|a| a.fraction).sum();
    assert!((shares + report.undecided_fraction - 1.0).abs() < 1e-12);
    assert_eq!(
        (report.grid.y0_min, report.grid.y0_max, report.grid.steps),
        (-8.0, 8.0, 24)
    );
    for (a, r) in map.attractors.iter().zip(&report.attractors) {
        assert_eq!(
            (r.id, r.class, r.period, r.state),
            (a.id, a.kind, a.period, a.state)
        );
        let m = a.multipliers.unwrap();
        assert_eq!(r.multipliers.unwrap()[0], [m[0].re, m[0].im]);
        assert!(r.strobes.len() <= 64 && r.lambda1.unwrap() < 0.0);
    }
    let json = serde_json::to_value(&report).unwrap();
    assert_eq!(json["attractors"][0]["class"], "periodic");
    assert_eq!(json["model"]["mu_s"], 3.0);
    // A branch: its special points with the stability on either side, its end in words.
    let (pr, orbit) = fold_start();
    let branch = continue_orbit(
        &pr,
        Parameter::Beta,
        &orbit,
        1.2,
        &ContinuationOptions::default(),
        &(),
    )
    .unwrap();
    let report = BranchReport::from(&branch);
    assert_eq!(report.parameter, "beta");
    assert_eq!(report.points, branch.points.len());
    let kinds: Vec<SpecialKind> = report.special.iter().map(|s| s.kind).collect();
    assert_eq!(kinds, [SpecialKind::Grazing, SpecialKind::Fold]);
    let fold = &report.special[1];
    assert!(fold.before.stable && !fold.after.stable);
    assert!(report.end_text.starts_with("no progress near 1.37"));
    assert!(report.end_text.contains("becoming tangential"));
    let stable: Vec<bool> = branch.points.iter().map(|p| p.stable()).collect();
    assert!(stable[0] && !stable[stable.len() - 1]);
    assert_eq!(
        BranchEnd::Boundary { value: 0.5 }.to_string(),
        "the end of the range at 0.5"
    );
}

#[test]
fn option_helpers_keep_the_options_consistent() {
    let o = BasinOptions::default().with_lyapunov_periods(20);
    assert_eq!((o.lyapunov_periods, o.sample_points), (20, 20));
    assert!(o.validate().is_ok());
    let o = BasinOptions::default().with_lyapunov_periods(5000);
    assert_eq!(o.sample_points, BasinOptions::default().sample_points);
    let o = ContinuationOptions::default().with_max_step(1e-4);
    assert_eq!((o.max_step, o.initial_step), (1e-4, 1e-4));
    assert!(o.validate().is_ok());
    let o = ContinuationOptions::default().with_max_step(0.5);
    assert_eq!(o.initial_step, ContinuationOptions::default().initial_step);
}

/// A largest step far below the default one (1e-7 of arclength) is a choice of resolution,
/// not a sign of an obstacle: on the stable period-1 orbit of [`doubling_start`] the branch
/// goes on at that step, as it does at 1e-5, until its points run out.
#[test]
fn a_tiny_max_step_does_not_stall_on_a_stable_orbit() {
    let (pr, orbit) = doubling_start();
    assert!(orbit.multipliers[0].modulus() < 1.0);
    for max_step in [1e-5, 1e-7] {
        let options = ContinuationOptions {
            max_points: 200,
            ..ContinuationOptions::default().with_max_step(max_step)
        };
        let branch = continue_orbit(&pr, Parameter::W, &orbit, 0.7, &options, &()).unwrap();
        assert_eq!(branch.end, BranchEnd::MaxPoints, "max_step {max_step}");
        assert_eq!(branch.points.len(), 200);
        // Every step after the first few is the largest allowed: nothing cut it.
        let last = branch.points.last().unwrap();
        assert!(
            last.arclength > 150.0 * max_step && last.arclength <= 199.0 * max_step * (1.0 + 1e-9),
            "max_step {max_step}: arclength {}",
            last.arclength
        );
        assert!(last.value > 0.6);
        for point in &branch.points {
            let at = Parameter::W.set(pr, point.value).unwrap();
            let newton =
                find_periodic_orbit(&at, point.orbit.state, 1, &NewtonOptions::default()).unwrap();
            assert!(
                distance(newton.state, point.orbit.state) <= 1e-9 * newton.state.y.abs().max(1.0)
            );
        }
    }
}

/// Regression: `continue --zeta 0 --mu-s 3 --beta 9 --over w --from 0.27 --to 0.34` stalled
/// with `obstacle: none` near w = 0.2862, where a slide's lowest speed reaches zero with the
/// net force within μs, so that a stop of finite length appears mid-swing (the strobe map
/// jumps). It is a grazing, named with its slide; past it no period-1 orbit with the new stop
/// lies near, and the motion settles on a period-5 orbit instead.
#[test]
fn a_stop_appearing_mid_swing_is_a_grazing() {
    let (pr, orbit) = settled_orbit(&experiment(0.0, 3.0, 0.27, 9.0)).unwrap();
    let branch = continue_orbit(
        &pr,
        Parameter::W,
        &orbit,
        0.34,
        &ContinuationOptions::default(),
        &(),
    )
    .unwrap();
    let BranchEnd::Grazing {
        value,
        last,
        multiplier,
        slide,
        beyond,
    } = branch.end.clone()
    else {
        panic!("end {:?}", branch.end)
    };
    assert!((value - 0.28621).abs() < 1e-4, "grazing at {value}");
    assert!(beyond.is_none(), "{beyond:?}");
    assert!(value >= last && multiplier < 1.0);
    assert!(slide.speed < 1e-4, "speed {}", slide.speed);
    assert_eq!(slide.after, EventKind::Slip);
    assert!(slide.net_force < 3.0 && (slide.net_force - 1.0).abs() < 1e-6);
    assert!(branch.end.to_string().starts_with("a grazing at 0.28621"));
    let json = serde_json::to_value(BranchReport::from(&branch)).unwrap();
    assert_eq!(json["end"]["reason"], "grazing");

    // The slide minimum against the motion sampled densely over the orbit's period.
    let point = branch.points.last().unwrap();
    let at = Parameter::W.set(pr, last).unwrap();
    let mut solver = ExactSolver::new(at, point.orbit.state);
    let times: Vec<f64> = (0..=40_000)
        .map(|k| slide.tau - 1.0 + 2.0 * k as f64 / 40_000.0)
        .collect();
    run_until(&mut solver, times[0], |_| {}).unwrap();
    let samples = stickslip::solver::sample_at(&mut solver, &times, |_| {}).unwrap();
    let lowest = samples
        .iter()
        .min_by(|a, b| a.v.abs().total_cmp(&b.v.abs()))
        .unwrap();
    assert!(
        (lowest.tau - slide.tau).abs() < 1e-3,
        "{} {}",
        lowest.tau,
        slide.tau
    );
    assert!((lowest.v.abs() - slide.velocity).abs() < 1e-7);
    assert!(
        samples.iter().all(|s| s.v * lowest.v > 0.0),
        "the slide goes on through the minimum"
    );

    // The orbit before the grazing: the steady state there is that orbit, with the same
    // period and multipliers.
    let steady = experiment(0.0, 3.0, last, 9.0).steady().unwrap();
    assert_eq!(steady.period, Some(1));
    let settled =
        find_periodic_orbit(&at, steady.strobes[0], 1, &NewtonOptions::default()).unwrap();
    assert!((settled.state.y - point.orbit.state.y).abs() < 1e-8);
    assert!((settled.state.v - point.orbit.state.v).abs() < 1e-8);
    let (a, b) = (settled.multipliers[0], point.orbit.multipliers[0]);
    assert!((a.re - b.re).abs() < 1e-6 && a.im == b.im, "{a:?} {b:?}");
    assert_eq!(point.stops, 2);

    // Past it: no period-1 orbit near (Newton's method from the last strobe state fails or
    // lands elsewhere), and the motion settles on a period-5 orbit with 12 stops, a stop of
    // finite length mid-swing among them.
    let past = Parameter::W.set(pr, 0.2863).unwrap();
    match find_periodic_orbit(&past, point.orbit.state, 1, &NewtonOptions::default()) {
        Err(_) => {}
        Ok(o) => assert!((o.state.y - point.orbit.state.y).abs() > 0.5, "{o:?}"),
    }
    let steady = experiment(0.0, 3.0, 0.2863, 9.0).steady().unwrap();
    assert_eq!(steady.period, Some(5));
    let five = find_periodic_orbit(&past, steady.strobes[0], 5, &NewtonOptions::default()).unwrap();
    assert_eq!(five.stops.len(), 12);
    assert!(five.multipliers[0].modulus() < 1.0);
    assert!(five.stops.iter().any(|s| s.duration < 0.5));
}

/// Going down in w from 0.21 (ζ = 0, μs = 3, β = 9) the orbit with 3 stops meets a stop
/// appearing mid-swing at w = 0.200404: the branch ends there as a grazing and names the orbit
/// with the new stop that Newton's method finds just past it. That orbit is not the branch's
/// continuation: it lies a jump away and exists on both sides of the grazing.
#[test]
fn past_a_grazing_mid_swing_lies_another_branch() {
    let (pr, orbit) = settled_orbit(&experiment(0.0, 3.0, 0.21, 9.0)).unwrap();
    assert_eq!(orbit.stops.len(), 3);
    let branch = continue_orbit(
        &pr,
        Parameter::W,
        &orbit,
        0.19,
        &ContinuationOptions::default(),
        &(),
    )
    .unwrap();
    let BranchEnd::Grazing {
        value,
        last,
        slide,
        beyond: Some(beyond),
        ..
    } = branch.end.clone()
    else {
        panic!("end {:?}", branch.end)
    };
    assert!((value - 0.200404).abs() < 1e-5, "grazing at {value}");
    assert!(value <= last && slide.speed < 1e-6);
    assert!(beyond.value < value && beyond.stops == 4, "{beyond:?}");
    let end = branch.points.last().unwrap();
    assert_eq!(end.stops, 3);
    let jump = (beyond.state.y - end.orbit.state.y).hypot(beyond.state.v - end.orbit.state.v);
    assert!(jump > 0.1, "a jump of {jump}");
    // The orbit past it, confirmed there, and on the branch's side of the grazing too.
    for w in [beyond.value, value + 1e-3] {
        let at = Parameter::W.set(pr, w).unwrap();
        let o = find_periodic_orbit(&at, beyond.state, 1, &NewtonOptions::default()).unwrap();
        assert_eq!(o.stops.len(), 4, "w {w}");
        assert!((o.state.y - beyond.state.y).abs() < 0.05, "w {w}: {o:?}");
    }
    assert!(branch
        .end
        .to_string()
        .contains("another orbit of this period with the new stop"));
}
