//! Bifurcation diagrams, basin maps and maps of the largest Lyapunov exponent of the smooth
//! friction laws (Stribeck, cubic) on a forced belt, each against tools it does not use:
//! a diagram's periods and strobe points against `steady` at each value and its exponent
//! against the measured one and ln|μ1|/T of Newton's orbit; a basin map's cells against
//! `steady` from each cell's start and its fixed points against Newton's orbit; an exponent
//! map's values against `lyapunov` at each point; two coexisting attractors of a Stribeck
//! belt told apart; the same maps for 1 and 4 threads.

use stickslip::attractor::{strobe_sets_overlap, AttractorKind, RecordOptions};
use stickslip::basins::{BasinMap, BasinMethod, BasinOptions, Basins};
use stickslip::bifurcation::{Bifurcation, BifurcationOptions};
use stickslip::continuation::ContinuationOptions;
use stickslip::friction::FrictionLaw;
use stickslip::scan::{Axis, Grid, ParameterRange, SweepDirection};
use stickslip::stability::{LyapunovOptions, NewtonOptions, NonperiodicVerdict, PeriodicOrbit};
use stickslip::steady::{MotionClass, SteadyOptions, SteadyState};
use stickslip::{Experiment, Parameter, State};
use stickslip_testkit::belts::{belt, CUBIC, STRIBECK};

fn distance(a: State, b: State) -> f64 {
    (a.y - b.y).abs().max((a.v - b.v).abs())
}

fn scale(x: State) -> f64 {
    1f64.max(x.y.abs()).max(x.v.abs())
}

/// Whether every point of `a` lies within `tolerance`·scale of a point of `b`.
fn covered(a: &[State], b: &[State], tolerance: f64) -> bool {
    a.iter()
        .all(|x| b.iter().any(|y| distance(*x, *y) <= tolerance * scale(*x)))
}

/// The steady state from `experiment`'s initial state (its own solver factory).
fn steady(experiment: &Experiment) -> SteadyState {
    experiment
        .steady_with(&SteadyOptions::default().with_spectrum(false))
        .expect("steady")
}

/// Newton's orbit of period `period` from the strobe point `at`.
fn orbit(experiment: &Experiment, at: State, period: usize) -> PeriodicOrbit {
    experiment
        .clone()
        .with_initial(at)
        .unwrap()
        .periodic_orbit(
            Some(period),
            0,
            &SteadyOptions::default(),
            &NewtonOptions::default(),
            &(),
        )
        .expect("orbit")
}

/// The exponent measured by `lyapunov` from the experiment's initial state (fixed length).
fn measured(experiment: &Experiment) -> (f64, f64) {
    let options = LyapunovOptions {
        transient_periods: 200,
        periods: 400,
        blocks: 20,
        significance: 4.0,
        sequential: false,
    };
    let c = experiment.lyapunov(&options, &()).expect("lyapunov");
    (
        c.exponents.largest.per_tau,
        c.exponents.largest.error_per_tau,
    )
}

#[test]
fn a_bifurcation_diagram_has_steadys_orbits_and_their_exponents() {
    for law in [STRIBECK, CUBIC] {
        let experiment = belt(law, (0.05, 1.0, 2.0, 1.5, 0.5));
        let values = vec![0.9, 1.0, 1.1];
        let diagram = Bifurcation::new(&experiment, Axis::new(Parameter::W, values).unwrap())
            .unwrap()
            .direction(SweepDirection::Up)
            .options(BifurcationOptions {
                record: RecordOptions {
                    transient_periods: 100,
                    points: 40,
                    ..RecordOptions::default()
                },
                first_transient_periods: 300,
            })
            .unwrap()
            .run(&())
            .unwrap();
        for step in &diagram {
            let at = experiment.clone().with_w(step.value).unwrap();
            let s = steady(&at);
            let record = &step.record;
            assert_eq!(
                record.kind,
                AttractorKind::Periodic,
                "{law:?} {}",
                step.value
            );
            let p = s.period.expect("steady repeats");
            assert_eq!(record.period, Some(p), "{law:?} w = {}", step.value);
            // The same p strobe points: the orbit's, whichever phase each run recorded first.
            let points = &s.strobes[..p];
            assert!(
                covered(&record.strobes, points, 1e-8) && covered(points, &record.strobes, 1e-8),
                "{law:?} w = {}: {:?} against {points:?}",
                step.value,
                &record.strobes[..p]
            );
            // Its exponent, over the 40 recorded periods, against Newton's orbit (exact to
            // the map's accuracy) and the measurement by `lyapunov` from rest.
            let o = orbit(&at, record.strobes[0], p);
            let exact = o.exponent();
            let (lambda, error) = measured(&at);
            let slack = 4.0 * record.exponent_error.max(error) + 1e-8 * exact.abs();
            assert!(
                (record.exponent - exact).abs() <= slack,
                "{law:?} w = {}: λ1 {} ± {} against ln|μ1|/T {exact}",
                step.value,
                record.exponent,
                record.exponent_error
            );
            assert!(
                (lambda - exact).abs() <= 4.0 * error + 1e-8 * exact.abs(),
                "{law:?} w = {}: lyapunov {lambda} ± {error} against ln|μ1|/T {exact}",
                step.value
            );
        }
    }
}

/// A diagram's branches (the plot's lines) are `continue`'s: with a Stribeck belt they pass
/// through the diagram's orbits, as Newton's method finds them at the branch's own values.
#[test]
fn a_bifurcation_diagrams_branches_pass_through_its_orbits() {
    let experiment = belt(STRIBECK, (0.05, 1.0, 2.0, 1.5, 0.3));
    let values = vec![0.9, 1.0, 1.1];
    let diagram = Bifurcation::new(&experiment, Axis::new(Parameter::W, values).unwrap())
        .unwrap()
        .direction(SweepDirection::Up)
        .options(BifurcationOptions {
            record: RecordOptions {
                transient_periods: 100,
                points: 10,
                ..RecordOptions::default()
            },
            first_transient_periods: 300,
        })
        .unwrap();
    let steps = diagram.run(&()).unwrap();
    let branches = diagram
        .branches(&steps, &ContinuationOptions::default(), &())
        .expect("the continuation follows the Stribeck law");
    assert!(!branches.is_empty());
    for step in &steps {
        assert_eq!(step.record.period, Some(1), "w = {}", step.value);
        let nearest = branches
            .iter()
            .flat_map(|b| &b.points)
            .min_by(|a, b| {
                (a.value - step.value)
                    .abs()
                    .total_cmp(&(b.value - step.value).abs())
            })
            .unwrap();
        assert!(
            (nearest.value - step.value).abs() <= 0.05,
            "w = {}: nearest branch point at {}",
            step.value,
            nearest.value
        );
        let at = experiment.clone().with_w(nearest.value).unwrap();
        let newton = orbit(&at, step.record.strobes[0], 1);
        assert!(
            distance(newton.state, nearest.orbit.state) <= 1e-8 * scale(newton.state),
            "w = {}: {:?} against {:?}",
            nearest.value,
            newton.state,
            nearest.orbit.state
        );
    }
}

/// The small map of a Stribeck belt: 4 × 4 initial states.
fn small_map(method: BasinMethod, threads: usize) -> (Experiment, BasinMap) {
    let experiment = belt(STRIBECK, (0.05, 1.0, 2.0, 1.5, 0.5));
    let r = ParameterRange::new("y0", -3.0, 3.0, 4).unwrap();
    let map = Basins::new(&experiment, &r, &r)
        .unwrap()
        .options(BasinOptions {
            method,
            ..BasinOptions::default()
        })
        .unwrap()
        .threads(threads)
        .unwrap()
        .run(&())
        .unwrap();
    (experiment, map)
}

#[test]
fn a_basin_maps_cells_are_steadys_and_its_fixed_points_newtons() {
    let (experiment, map) = small_map(BasinMethod::Recurrence, 1);
    assert_eq!(map.undecided, 0);
    for (i, &y0) in map.y0.iter().enumerate() {
        for (j, &v0) in map.v0.iter().enumerate() {
            let a = map.at(i, j).expect("a cell with an attractor");
            let from = experiment
                .clone()
                .with_initial(State { y: y0, v: v0 })
                .unwrap();
            let s = steady(&from);
            assert_eq!(a.kind, AttractorKind::Periodic);
            let p = s.period.expect("steady repeats");
            assert_eq!(a.period, Some(p), "({y0}, {v0})");
            assert!(
                covered(&s.strobes[..p], &a.strobes, 1e-8),
                "({y0}, {v0}): {:?} against {:?}",
                &s.strobes[..p],
                a.strobes
            );
        }
    }
    for a in &map.attractors {
        let o = orbit(&experiment, a.state, a.period.unwrap());
        assert!(distance(o.state, a.state) <= 1e-9 * scale(a.state), "{a:?}");
        let m = a.multipliers.expect("the orbit's multipliers");
        assert!(
            (m[0].modulus() - o.multipliers[0].modulus()).abs() <= 1e-8,
            "{m:?} against {:?}",
            o.multipliers
        );
        assert!((a.exponent - o.exponent()).abs() <= 1e-8 * o.exponent().abs());
    }
    // Every cell computed on its own (the exhaustive method), on 1 and on 4 threads: the
    // same map as by recurrence.
    let (_, one) = small_map(BasinMethod::Exhaustive, 1);
    let (_, four) = small_map(BasinMethod::Exhaustive, 4);
    assert_eq!(one, four);
    assert_eq!(one.cells, map.cells);
    for (a, b) in one.attractors.iter().zip(&map.attractors) {
        assert_eq!((a.kind, a.period), (b.kind, b.period));
        assert!(covered(&a.strobes, &b.strobes, 1e-8));
    }
}

#[test]
fn an_exponent_map_has_the_exponents_lyapunov_measures() {
    for law in [STRIBECK, CUBIC] {
        let experiment = belt(law, (0.05, 1.0, 2.0, 1.5, 0.5));
        let grid = Grid::new(
            &experiment,
            Axis::new(Parameter::W, vec![0.9, 1.1]).unwrap(),
            Axis::new(Parameter::Beta, vec![1.5, 2.5]).unwrap(),
        )
        .unwrap()
        .lyapunov(LyapunovOptions::default())
        .unwrap();
        let one = grid.clone().threads(1).unwrap().run(&()).unwrap();
        let four = grid.threads(4).unwrap().run(&()).unwrap();
        assert_eq!(one, four, "{law:?}: 1 and 4 threads");
        for point in &one.points {
            let at = experiment
                .clone()
                .with_w(point.params.w)
                .and_then(|e| e.with_beta(point.params.beta))
                .unwrap();
            let lambda = point.lyapunov.expect("an exponent").per_tau;
            let (measured, error) = measured(&at);
            assert!(
                (lambda - measured).abs() <= 4.0 * error + 1e-8 * lambda.abs(),
                "{law:?} (w, β) = ({}, {}): map {lambda}, lyapunov {measured} ± {error}",
                point.params.w,
                point.params.beta
            );
        }
    }
}

/// A Stribeck belt where two attractors coexist (the base of the paper's map of rest beside
/// a stick-slip orbit, ζ = 0.046816, μs = 1.5, (w, β) = (0.9, 1.4), set moving at vb = 0.05:
/// rest becomes a slow chaotic creep of stops and slips beside the period-1 orbit): a basin
/// map of two colours, the orbit the one Newton's method finds from its state, the chaotic
/// attractor's exponent positive as `lyapunov` measures it, and each cell's attractor the
/// one `steady` reaches from the cell's start; the same map by recurrence and cell by cell
/// on 4 threads.
#[test]
fn a_stribeck_belts_coexisting_attractors_have_a_map_of_two_colours() {
    let experiment = belt(
        FrictionLaw::Stribeck {
            vs: 0.3,
            delta: 2.0,
            eta: 0.0,
        },
        (0.046816, 0.9, 1.4, 1.5, 0.05),
    );
    let r = ParameterRange::new("y0", -3.0, 3.0, 5).unwrap();
    let basins = Basins::new(&experiment, &r, &r).unwrap();
    let map = basins.clone().run(&()).unwrap();
    let kinds: Vec<_> = map.attractors.iter().map(|a| (a.kind, a.period)).collect();
    assert_eq!(
        kinds,
        [
            (AttractorKind::Chaotic, None),
            (AttractorKind::Periodic, Some(1))
        ]
    );
    assert_eq!(map.undecided, 0);
    for a in &map.attractors {
        assert!(a.cells >= 3, "{kinds:?}: {} cells of #{}", a.cells, a.id);
        let from = experiment.clone().with_initial(a.state).unwrap();
        if a.kind == AttractorKind::Periodic {
            let o = orbit(&experiment, a.state, 1);
            assert!(distance(o.state, a.state) <= 1e-9 * scale(a.state), "{a:?}");
        } else {
            let (lambda, error) = measured(&from);
            assert!(lambda > 4.0 * error, "λ1 {lambda} ± {error}");
        }
    }
    for (i, &y0) in map.y0.iter().enumerate() {
        for (j, &v0) in map.v0.iter().enumerate() {
            let a = map.at(i, j).unwrap();
            let s = steady(
                &experiment
                    .clone()
                    .with_initial(State { y: y0, v: v0 })
                    .unwrap(),
            );
            match a.kind {
                AttractorKind::Periodic => {
                    assert_eq!(s.period, Some(1), "({y0}, {v0})");
                    assert!(
                        covered(&s.strobes[..1], &a.strobes, 1e-8),
                        "({y0}, {v0}): steady {:?}, map {:?}",
                        s.strobes[0],
                        a.strobes
                    );
                }
                _ => {
                    // Not repeating, and chaotic by `steady`'s measurement too.
                    assert_eq!(s.period, None, "({y0}, {v0})");
                    assert_eq!(s.class, MotionClass::Chaotic, "({y0}, {v0})");
                    assert!(
                        strobe_sets_overlap(&a.strobes, &s.strobes),
                        "({y0}, {v0}): steady's strobes on the chaotic attractor"
                    );
                }
            }
        }
    }
    let exhaustive = BasinOptions {
        method: BasinMethod::Exhaustive,
        ..BasinOptions::default()
    };
    let four = basins.options(exhaustive).unwrap().threads(4).unwrap();
    assert_eq!(four.run(&()).unwrap().cells, map.cells);
}

/// One motion of a smooth law that does not repeat, classed alike by `steady` and `basins`:
/// the Stribeck belt's chaotic creep above, from rest. `steady` measures its exponents by the
/// friction law's tangent dynamics (`FrictionDynamics`, the ones `basins` and `lyapunov` use)
/// and calls it chaotic; the basin map's cell at rest (the exhaustive method's verdict on
/// that start) is chaotic too, by the same rule (`NonperiodicVerdict::of`), and so is what
/// `lyapunov` says from the state `steady` ended at.
#[test]
fn steady_and_basins_class_a_stribeck_belts_chaotic_creep_alike() {
    let experiment = belt(
        FrictionLaw::Stribeck {
            vs: 0.3,
            delta: 2.0,
            eta: 0.0,
        },
        (0.046816, 0.9, 1.4, 1.5, 0.05),
    );
    let s = steady(&experiment);
    assert_eq!(s.period, None);
    let measured = s.lyapunov.as_ref().expect("steady measured the exponents");
    assert_eq!(
        measured.verdict,
        NonperiodicVerdict::Chaotic,
        "{measured:?}"
    );
    assert_eq!(s.class, MotionClass::Chaotic);
    let largest = measured.exponents.largest;
    assert!(largest.per_tau > 4.0 * largest.error_per_tau, "{largest:?}");

    let r = ParameterRange::new("y0", -1.0, 1.0, 3).unwrap();
    let basins = Basins::new(&experiment, &r, &r).unwrap();
    let cell = basins.cell(1, 1).unwrap();
    assert_eq!(cell.kind, AttractorKind::Chaotic, "{:?}", cell.exponent);
    assert!(cell.exponent > 0.0);

    let (lambda, error) = measured_from(&experiment, s.final_state());
    assert!(lambda > 4.0 * error, "lyapunov: λ1 {lambda} ± {error}");
}

/// The exponent `lyapunov` measures from `at` (fixed length).
fn measured_from(experiment: &Experiment, at: State) -> (f64, f64) {
    measured(&experiment.clone().with_initial(at).unwrap())
}
