//! Maps of a self-excited belt over (vb, μs) beside the paper's map of (w, β), in the same
//! run, every map on one thread of its own (`Grid::threads(1)`: CPU per point, not the
//! shared machine's free cores), every point from rest:
//!
//! - `paper`: the paper's circuit, w 0.1–2.5, β 0.5–4 (the paper's Fig. 7 window), 200 × 200;
//! - `coulomb_belt`: the paper's ζ, no drive (β = 0), Coulomb's law, vb 0.05–2, μs 1–3,
//!   200 × 200 (the exact solver);
//! - `stribeck_belt`: the same window with the Stribeck law vs = 0.5, δ = 2, η = 0.05 on a
//!   coarser 50 × 50 grid (its slips on the explicit integrator, a few hundred µs a point:
//!   200 × 200 would take 15–20 s per sample); its time per point is the one that counts.
//!
//! Criterion's throughput is points per second, so the ratios of the targets (a
//! 200 × 200 Coulomb belt map ≤ 2× the paper's, a Stribeck one ≤ 20×) are ratios of the
//! time per point.
//!
//! `cargo bench -p stickslip --bench belt_map`

use criterion::{criterion_group, criterion_main, BenchmarkId, Criterion, Throughput};
use std::time::Duration;
use stickslip::friction::FrictionLaw;
use stickslip::scan::{Axis, Grid, ParameterRange};
use stickslip::{Circuit, Experiment, MotionClass, Parameter};

/// The grid of `first` × `second` over `experiment`, `n` × `n` points, one thread.
fn grid(
    experiment: &Experiment,
    (first, lo1, hi1): (Parameter, f64, f64),
    (second, lo2, hi2): (Parameter, f64, f64),
    n: usize,
) -> Grid {
    let a = ParameterRange::new(first.label(), lo1, hi1, n).expect("valid");
    let b = ParameterRange::new(second.label(), lo2, hi2, n).expect("valid");
    Grid::new(
        experiment,
        Axis::range(first, &a).expect("valid"),
        Axis::range(second, &b).expect("valid"),
    )
    .expect("valid")
    .threads(1)
    .expect("valid")
}

/// The self-excited belt with the paper's ζ and `law`.
fn belt(law: FrictionLaw) -> Experiment {
    Experiment::dimensionless(Circuit::paper().scales().zeta(), 1.0, 0.0)
        .and_then(|e| e.with_law(law))
        .expect("valid")
}

fn bench(c: &mut Criterion) {
    let vb = (Parameter::Vb, 0.05, 2.0);
    let mu_s = (Parameter::MuS, 1.0, 3.0);
    let maps = [
        (
            "paper",
            grid(
                &Experiment::paper(),
                (Parameter::W, 0.1, 2.5),
                (Parameter::Beta, 0.5, 4.0),
                200,
            ),
            200,
        ),
        (
            "coulomb_belt",
            grid(&belt(FrictionLaw::Coulomb), vb, mu_s, 200),
            200,
        ),
        (
            "stribeck_belt",
            grid(
                &belt(FrictionLaw::Stribeck {
                    vs: 0.5,
                    delta: 2.0,
                    eta: 0.05,
                }),
                vb,
                mu_s,
                50,
            ),
            50,
        ),
    ];
    // What the maps hold: the belts' maps are of self-excited classes (the search ran the
    // self-excited steady state, not the stroboscopic one).
    for (name, grid, _) in &maps[1..] {
        let points = grid.run(&()).expect("runs");
        assert!(
            points.points.iter().all(|p| matches!(
                p.class,
                MotionClass::StickSlipCycle
                    | MotionClass::PureSlipCycle
                    | MotionClass::SteadySliding
            )),
            "{name}: a class that is not self-excited"
        );
    }
    let mut group = c.benchmark_group("belt_map");
    group.sample_size(10);
    group.warm_up_time(Duration::from_secs(1));
    group.measurement_time(Duration::from_secs(10));
    for (name, grid, n) in &maps {
        group.throughput(Throughput::Elements((n * n) as u64));
        group.bench_with_input(BenchmarkId::new(*name, format!("{n}x{n}")), grid, |b, g| {
            b.iter(|| g.run(&()).expect("runs"))
        });
    }
    group.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
