//! The phase diagram the README quotes (400 × 400 points, the paper's ζ, w 0.1–2.5,
//! β 0.5–4, each point from rest), the cost of one point against its distance from the
//! stick-slip boundary, and the Shockley map of the report's Fig. 7 (b) (64 × 64 points on
//! one thread, the search capped at 500 periods as there; criterion's throughput is points
//! per second).

use criterion::{criterion_group, criterion_main, BenchmarkId, Criterion, Throughput};
use std::time::Duration;
use stickslip::scan::{Axis, Grid, ParameterRange};
use stickslip::steady::{exact_solver, steady_state_from, SteadyOptions};
use stickslip::{Circuit, DiodePair, Experiment, MotionClass, Parameter, Params, State};

fn zeta() -> f64 {
    Circuit::paper().scales().zeta()
}

fn bench_grid(c: &mut Criterion) {
    let mut group = c.benchmark_group("phase_diagram");
    group.sample_size(10);
    group.measurement_time(Duration::from_secs(60));
    let paper = Experiment::paper();
    for n in [100usize, 400] {
        let w = ParameterRange::new("w", 0.1, 2.5, n).expect("valid");
        let beta = ParameterRange::new("beta", 0.5, 4.0, n).expect("valid");
        let grid = Grid::new(
            &paper,
            Axis::range(Parameter::W, &w).expect("valid"),
            Axis::range(Parameter::Beta, &beta).expect("valid"),
        )
        .expect("valid");
        group.bench_with_input(
            BenchmarkId::new("paper_window", format!("{n}x{n}")),
            &n,
            |b, _| b.iter(|| grid.run(&()).expect("runs")),
        );
    }
    group.finish();
}

fn class(w: f64, beta: f64) -> MotionClass {
    let params = Params::new(zeta(), w, beta).expect("valid");
    let options = SteadyOptions::default().with_spectrum(false);
    steady_state_from(&exact_solver, &params, State::default(), &options)
        .expect("runs")
        .class
}

/// β on the stick-slip boundary at w, by bisection between a sticking and a sliding β.
fn boundary(w: f64) -> f64 {
    let (mut stick, mut slide) = (1.3, 4.0);
    assert_eq!(class(w, slide), MotionClass::Sliding);
    assert_eq!(class(w, stick), MotionClass::PeriodicStick);
    for _ in 0..45 {
        let mid = 0.5 * (stick + slide);
        if class(w, mid) == MotionClass::Sliding {
            slide = mid;
        } else {
            stick = mid;
        }
    }
    0.5 * (stick + slide)
}

fn bench_near_boundary(c: &mut Criterion) {
    let mut group = c.benchmark_group("point_near_boundary");
    group.measurement_time(Duration::from_secs(2));
    group.warm_up_time(Duration::from_millis(500));
    let options = SteadyOptions::default().with_spectrum(false);
    for w in [0.6, 1.5] {
        let beta_c = boundary(w);
        for offset in [-1e-1, -1e-3, -1e-6, 1e-6, 1e-3, 1e-1, 1.0] {
            let params = Params::new(zeta(), w, beta_c + offset).expect("valid");
            let id = BenchmarkId::new(format!("w{w}"), format!("{offset:+e}"));
            group.bench_with_input(id, &params, |b, p| {
                b.iter(|| {
                    steady_state_from(&exact_solver, p, State::default(), &options).expect("runs")
                })
            });
        }
    }
    group.finish();
}

fn bench_shockley_map(c: &mut Criterion) {
    let mut group = c.benchmark_group("phase_diagram");
    group.sample_size(10);
    group.measurement_time(Duration::from_secs(30));
    let shockley = Experiment::paper()
        .with_shockley(DiodePair::one_n4148())
        .expect("valid");
    let n = 64;
    let w = ParameterRange::new("w", 0.1, 2.5, n).expect("valid");
    let beta = ParameterRange::new("beta", 0.5, 4.0, n).expect("valid");
    group.throughput(Throughput::Elements((n * n) as u64));
    // As the report computes it (motions that do not repeat measured), without the
    // measurement (`--lyapunov-periods 0`), and as the report computed it before Newton
    // settled Shockley points (`_plain`: Newton off, the baseline of issue 34).
    for (name, measured, newton) in [
        ("shockley_fig7b", true, true),
        ("shockley_fig7b_unmeasured", false, true),
        ("shockley_fig7b_plain", true, false),
    ] {
        let options = shockley
            .steady_options()
            .with_max_periods(500)
            .expect("valid")
            .with_newton(newton);
        let options = if measured {
            options
        } else {
            options.with_lyapunov(None).expect("valid")
        };
        let grid = Grid::new(
            &shockley,
            Axis::range(Parameter::W, &w).expect("valid"),
            Axis::range(Parameter::Beta, &beta).expect("valid"),
        )
        .expect("valid")
        .options(options)
        .expect("valid")
        .threads(1)
        .expect("valid");
        group.bench_function(BenchmarkId::new(name, format!("{n}x{n}")), |b| {
            b.iter(|| grid.run(&()).expect("runs"))
        });
    }
    group.finish();
}

criterion_group!(benches, bench_near_boundary, bench_grid, bench_shockley_map);
criterion_main!(benches);
