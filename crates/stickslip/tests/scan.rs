//! Sweeps and grids as library builders: results that do not depend on the number of
//! threads, experiments read from a file.

use stickslip::experiment::Experiment;
use stickslip::scan::{Axis, Grid, ParameterRange, Sweep, SweepDirection};
use stickslip::steady::MotionClass;
use stickslip::{DiodePair, Parameter};

fn paper() -> Experiment {
    let text = std::fs::read_to_string(concat!(env!("CARGO_MANIFEST_DIR"), "/examples/paper.toml"))
        .unwrap();
    Experiment::from_toml(&text, "paper.toml").unwrap()
}

#[test]
fn the_example_file_is_the_papers_circuit() {
    assert_eq!(
        paper().with_origin(stickslip::experiment::Origin::Preset(
            stickslip::experiment::Preset::Paper
        )),
        Experiment::paper()
    );
}

/// A map and a sweep with 1, 2 and 8 threads: bit for bit the same.
#[test]
fn maps_and_sweeps_do_not_depend_on_the_number_of_threads() {
    let grid = Grid::new(
        &paper(),
        Axis::range(
            Parameter::W,
            &ParameterRange::new("w", 0.3, 1.7, 12).unwrap(),
        )
        .unwrap(),
        Axis::range(
            Parameter::Beta,
            &ParameterRange::new("beta", 0.8, 3.0, 10).unwrap(),
        )
        .unwrap(),
    )
    .unwrap();
    let maps: Vec<_> = [1, 2, 8]
        .into_iter()
        .map(|n| grid.clone().threads(n).unwrap().run(&()).unwrap())
        .collect();
    let classes: Vec<MotionClass> = maps[0].points.iter().map(|p| p.class).collect();
    assert!(classes.contains(&MotionClass::Sliding));
    assert!(classes.contains(&MotionClass::PeriodicStick));
    assert_eq!(maps[0], maps[1]);
    assert_eq!(maps[0], maps[2]);

    let sweep = Sweep::new(
        &paper().with_beta(3.61).unwrap(),
        Axis::range(
            Parameter::W,
            &ParameterRange::new("w", 0.6, 1.4, 9).unwrap(),
        )
        .unwrap(),
    )
    .unwrap()
    .direction(SweepDirection::Both);
    let runs: Vec<_> = [1, 2, 8]
        .into_iter()
        .map(|n| {
            rayon::ThreadPoolBuilder::new()
                .num_threads(n)
                .build()
                .unwrap()
                .install(|| sweep.run(&()).unwrap())
        })
        .collect();
    assert_eq!(runs[0].len(), 18);
    assert_eq!(runs[0], runs[1]);
    assert_eq!(runs[0], runs[2]);
}

/// Any two of ζ, w, β, μs: a (μs, ζ) grid at a fixed drive.
#[test]
fn grids_over_any_two_parameters() {
    let e = Experiment::dimensionless(0.05, 0.9, 1.45).unwrap();
    let map = Grid::new(
        &e,
        Axis::new(Parameter::MuS, vec![1.0, 1.5]).unwrap(),
        Axis::new(Parameter::Zeta, vec![0.02, 0.05]).unwrap(),
    )
    .unwrap()
    .run(&())
    .unwrap();
    assert_eq!(map.points.len(), 4);
    assert_eq!(map.at(1, 0).params.mu_s, 1.5);
    assert_eq!(map.at(1, 0).params.zeta, 0.02);
    // From rest, β = 1.45 below μs = 1.5 cannot start the motion: static.
    assert_eq!(map.at(1, 1).class, MotionClass::Static);
    assert_ne!(map.at(0, 1).class, MotionClass::Static);
}

/// The Shockley model runs through the same builders with its own tolerance.
#[test]
fn shockley_maps_use_the_stiff_solver_and_its_tolerance() {
    let e = Experiment::paper()
        .with_shockley(DiodePair::one_n4148())
        .unwrap();
    let grid = Grid::new(
        &e,
        Axis::new(Parameter::W, vec![0.95]).unwrap(),
        Axis::new(Parameter::Beta, vec![2.14]).unwrap(),
    )
    .unwrap();
    assert_eq!(grid.steady_options().tolerance, 1e-6);
    let map = grid.run(&()).unwrap();
    assert_eq!(map.points[0].class, MotionClass::Sliding);
    assert_eq!(map.points[0].params.zeta, e.zeta());
}

/// A map streamed a block of rows at a time: the blocks come in order, cover every row once,
/// hold the points of the map computed at once (bit for bit, for 1, 2 and 8 threads, whose
/// blocks differ in size), and the monitor counts every point of the grid once.
#[test]
fn streamed_rows_are_the_map_in_order() {
    let grid = Grid::new(
        &paper(),
        Axis::range(
            Parameter::W,
            &ParameterRange::new("w", 0.2, 2.4, 70).unwrap(),
        )
        .unwrap(),
        Axis::range(
            Parameter::Beta,
            &ParameterRange::new("beta", 0.5, 4.0, 9).unwrap(),
        )
        .unwrap(),
    )
    .unwrap();
    let whole = grid.clone().threads(1).unwrap().run(&()).unwrap();
    for threads in [1, 2, 8] {
        let grid = grid.clone().threads(threads).unwrap();
        assert_eq!(grid.stream_block_rows(), (256 * threads).div_ceil(9));
        let mut points = Vec::new();
        let mut next = 0;
        let mut blocks = 0;
        let largest = std::sync::atomic::AtomicUsize::new(0);
        grid.run_rows(
            &|done: usize, total: usize| {
                assert_eq!(total, 630);
                largest.fetch_max(done, std::sync::atomic::Ordering::Relaxed);
                true
            },
            |rows, block| {
                assert_eq!(rows.start, next, "blocks in order");
                assert_eq!(block.len(), rows.len() * 9);
                next = rows.end;
                blocks += 1;
                points.extend(block);
                Ok(())
            },
        )
        .unwrap();
        assert_eq!(next, 70);
        assert_eq!(blocks, 70usize.div_ceil(grid.stream_block_rows()));
        assert_eq!(largest.into_inner(), 630);
        assert_eq!(points, whole.points, "{threads} threads");
    }
    // An error of the consumer stops the work and is returned.
    let mut calls = 0;
    let err = grid
        .clone()
        .threads(1)
        .unwrap()
        .run_rows(&(), |_, _| {
            calls += 1;
            Err(stickslip::Error::Cancelled { done: 0, total: 0 })
        })
        .unwrap_err();
    assert!(matches!(err, stickslip::Error::Cancelled { .. }));
    assert_eq!(calls, 1);
}

/// A self-excited belt's map over (vb, μs), Coulomb's law and Stribeck's: each point's class
/// is `steady`'s at that point from rest (the same experiment with vb and μs set), and the
/// map is bit for bit the same on 1 and 2 threads (and its report's CSV names the keys).
#[test]
fn a_belt_map_of_vb_and_mu_s_has_the_steady_states_classes_on_any_threads() {
    use stickslip::friction::FrictionLaw;
    use stickslip::report::MapRow;
    let laws = [
        FrictionLaw::Coulomb,
        FrictionLaw::Stribeck {
            vs: 0.5,
            delta: 2.0,
            eta: 0.05,
        },
    ];
    for law in laws {
        let belt = Experiment::dimensionless(0.05, 1.0, 0.0)
            .and_then(|e| e.with_law(law))
            .unwrap();
        let vb = ParameterRange::new("vb", 0.1, 1.5, 3).unwrap();
        let mu_s = ParameterRange::new("mu_s", 1.0, 3.0, 3).unwrap();
        let grid = Grid::new(
            &belt,
            Axis::range(Parameter::Vb, &vb).unwrap(),
            Axis::range(Parameter::MuS, &mu_s).unwrap(),
        )
        .unwrap();
        let one = grid.clone().threads(1).unwrap().run(&()).unwrap();
        let two = grid.clone().threads(2).unwrap().run(&()).unwrap();
        assert_eq!(one, two, "{law:?}");
        let mut seen = Vec::new();
        for (i, &v) in vb.values().iter().enumerate() {
            for (j, &m) in mu_s.values().iter().enumerate() {
                let point = one.at(i, j);
                let steady = belt
                    .clone()
                    .with_mu_s(m)
                    .and_then(|e| e.with_vb(v))
                    .and_then(|e| e.steady())
                    .unwrap();
                assert_eq!(point.class, steady.class, "{law:?} at vb = {v}, μs = {m}");
                assert!(
                    matches!(
                        point.class,
                        MotionClass::StickSlipCycle
                            | MotionClass::PureSlipCycle
                            | MotionClass::SteadySliding
                    ),
                    "{law:?} at vb = {v}, μs = {m}: {:?}",
                    point.class
                );
                seen.push(point.class);
            }
        }
        // A slow belt with μs > 1 sticks; a fast one slides steadily.
        assert!(
            seen.contains(&MotionClass::StickSlipCycle),
            "{law:?}: {seen:?}"
        );
        assert!(
            seen.contains(&MotionClass::SteadySliding),
            "{law:?}: {seen:?}"
        );
    }
    assert_eq!(
        MapRow::columns_over(Parameter::Vb, Parameter::MuS, false),
        ["vb", "mu_s", "class", "period", "stops_per_period", "gain"]
    );
    assert_eq!(
        MapRow::columns_over(Parameter::W, Parameter::Beta, true),
        MapRow::columns(true)
    );
}
