//! Cost of a curve of special points in two parameters of about 500 points (issue 37's target:
//! at most 2 s of CPU), from the orbit the motion settles on, the search for the start
//! included:
//!
//! - `grazing_mu_s_1`: the grazing curve of the sliding orbit of the paper's circuit (μs = 1)
//!   in β over w from 0.6 to 2 (the exact stick-slip boundary β_c(w)), `max_step` 0.01;
//! - `fold_mu_s_1_5`: the fold curve of the orbit with two stops at μs = 1.5 in β over w from
//!   0.8 to 1, `max_step` 0.0012.
//!
//! The number of points of each is printed once and must lie between 450 and 550, or the
//! bench stops.

use criterion::{criterion_group, criterion_main, Criterion};
use std::hint::black_box;
use stickslip::continuation::{curve, ContinuationOptions, Curve, CurveSpec, Follow};
use stickslip::{Experiment, Parameter, State};

fn case(name: &str) -> (Experiment, CurveSpec, ContinuationOptions) {
    let paper = Experiment::paper();
    match name {
        "grazing_mu_s_1" => (
            paper.with_w(1.2).and_then(|e| e.with_beta(3.0)).unwrap(),
            CurveSpec {
                follow: Follow::Grazing,
                vary: Parameter::Beta,
                vary_to: 0.5,
                over: Parameter::W,
                from: 0.6,
                to: 2.0,
            },
            ContinuationOptions::default().with_max_step(0.01),
        ),
        _ => (
            paper
                .with_mu_s(1.5)
                .and_then(|e| e.with_w(0.9))
                .and_then(|e| e.with_beta(1.45))
                .and_then(|e| e.with_initial(State { y: 0.25, v: 2.1 }))
                .unwrap(),
            CurveSpec {
                follow: Follow::Fold,
                vary: Parameter::Beta,
                vary_to: 1.2,
                over: Parameter::W,
                from: 0.8,
                to: 1.0,
            },
            ContinuationOptions::default().with_max_step(0.0012),
        ),
    }
}

fn traced(e: &Experiment, spec: &CurveSpec, options: &ContinuationOptions) -> Curve {
    curve(e, spec, options, &())
        .expect("no error")
        .expect("a start")
}

fn bench_curve(c: &mut Criterion) {
    let mut group = c.benchmark_group("curve_500");
    group.sample_size(10);
    for name in ["grazing_mu_s_1", "fold_mu_s_1_5"] {
        let (e, spec, options) = case(name);
        let n = traced(&e, &spec, &options).points.len();
        eprintln!("{name}: {n} points");
        assert!(
            (450..=550).contains(&n),
            "{name}: {n} points, not about 500"
        );
        group.bench_function(name, |b| {
            b.iter(|| black_box(traced(&e, &spec, &options)).points.len())
        });
    }
    group.finish();
}

criterion_group!(benches, bench_curve);
criterion_main!(benches);
