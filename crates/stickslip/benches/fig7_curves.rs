//! Fig. 7 (a)'s boundaries between numbers of stops per period, drawn from grazing curves
//! (the report's `reproduce`) against the grid edges they replace: the paper's 200 × 200 PWL
//! map (w 0.1–2.5, β 0.5–4, from rest), measured in the same run (issue 37's target: the
//! curves no slower than the map).
//!
//! - `curves_5`: the five grazing curves that `reproduce` traces on the paper's map, from the
//!   starts it finds there (the paper's circuit at w = 0.1 and the β below, continued in w
//!   towards the next column's w = 0.1120603… up to its first grazing, followed over β from
//!   0.5 to 4), each kept within the map's range of w (0.1–2.5), traced at once on the
//!   threads there are (as `reproduce` traces them), taken in order;
//! - `map_200`: the paper's 200 × 200 map.
//!
//! The number of curves and points is printed once; a start that finds no grazing stops the
//! bench.

use criterion::{criterion_group, criterion_main, Criterion};
use rayon::prelude::*;
use std::hint::black_box;
use stickslip::continuation::{curve_within, ContinuationOptions, CurveSpec, Follow};
use stickslip::scan::{Axis, Grid, ParameterRange};
use stickslip::{Experiment, Parameter};

/// β of the five starts (the cells at w = 0.1 whose neighbour along w has another number of
/// stops per period, and that no curve traced before crosses).
const STARTS: [f64; 5] = [
    1.221105527638191,
    1.7839195979899496,
    1.871859296482412,
    2.5226130653266328,
    3.92964824120603,
];

/// The second column's w of the 200 × 200 map.
const NEXT_W: f64 = 0.112_060_301_507_537_7;

/// The points of the five curves.
fn curves(paper: &Experiment) -> usize {
    let options = ContinuationOptions {
        max_points: 400,
        ..ContinuationOptions::default()
    };
    let spec = CurveSpec {
        follow: Follow::Grazing,
        vary: Parameter::W,
        vary_to: NEXT_W,
        over: Parameter::Beta,
        from: 0.5,
        to: 4.0,
    };
    let points: Vec<usize> = STARTS
        .par_iter()
        .map(|&beta| {
            let start = paper.clone().with_w(0.1).and_then(|e| e.with_beta(beta));
            curve_within(&start.unwrap(), &spec, Some((0.1, 2.5)), &options, &())
                .expect("no error")
                .expect("a grazing")
                .points
                .len()
        })
        .collect();
    points.iter().sum()
}

/// The cells of the paper's map.
fn map(paper: &Experiment) -> usize {
    let w = ParameterRange::new("w", 0.1, 2.5, 200).unwrap();
    let beta = ParameterRange::new("beta", 0.5, 4.0, 200).unwrap();
    let grid = Grid::new(
        paper,
        Axis::range(Parameter::W, &w).unwrap(),
        Axis::range(Parameter::Beta, &beta).unwrap(),
    )
    .unwrap();
    grid.run(&|_: usize, _: usize| true).unwrap().points.len()
}

fn bench_fig7(c: &mut Criterion) {
    let paper = Experiment::paper();
    eprintln!("fig7a: 5 curves, {} points", curves(&paper));
    let mut group = c.benchmark_group("fig7a");
    group.sample_size(10);
    group.bench_function("curves_5", |b| b.iter(|| black_box(curves(&paper))));
    group.bench_function("map_200", |b| b.iter(|| black_box(map(&paper))));
    group.finish();
}

criterion_group!(benches, bench_fig7);
criterion_main!(benches);
