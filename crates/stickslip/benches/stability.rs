//! Cost of the tangent dynamics against a plain exact run: 300 drive periods from rest with
//! the exact solver alone (`plain`), with its Jacobian carried along and renormalised at the
//! end as `lyapunov_exponents` does per block (`tangent`), and with the Jacobian renormalised
//! at every strobe (`strobed`, one more stop of the solver per period). The target: tangents
//! cost at most 1.5× the plain run.

use criterion::{criterion_group, criterion_main, BenchmarkId, Criterion};
use std::hint::black_box;
use stickslip::solver::run_until;
use stickslip::stability::TangentSolver;
use stickslip::{Circuit, ExactSolver, Params, Solver, State};

const PERIODS: usize = 300;

fn plain(params: Params) -> f64 {
    let mut solver = ExactSolver::new(params, State::default());
    run_until(&mut solver, PERIODS as f64 * params.drive_period(), |_| {}).expect("solver runs");
    solver.state().y
}

fn tangent(params: Params) -> f64 {
    let mut tangent = TangentSolver::new(params, State::default());
    tangent
        .run_until(PERIODS as f64 * params.drive_period(), |_| {})
        .expect("solver runs");
    tangent.renormalize()
}

fn strobed(params: Params) -> f64 {
    let mut tangent = TangentSolver::new(params, State::default());
    let period = params.drive_period();
    let mut growth = 0.0;
    for k in 1..=PERIODS {
        tangent
            .run_until(k as f64 * period, |_| {})
            .expect("solver runs");
        growth += tangent.renormalize();
    }
    growth
}

fn bench_tangent(c: &mut Criterion) {
    let zeta = Circuit::paper().scales().zeta();
    let mut group = c.benchmark_group("tangent_cost");
    for (name, params) in [
        ("sliding_w0.9_b1.6", Params::new(zeta, 0.9, 1.6)),
        ("periodic_stick_w0.6_b1.2", Params::new(zeta, 0.6, 1.2)),
        ("stick_w0.7_b1.2", Params::new(zeta, 0.7, 1.2)),
        ("low_freq_w0.29_b2.14", Params::new(zeta, 0.29, 2.14)),
        (
            "chaotic_z0_mus3_w0.33_b9",
            Params::new(0.0, 0.33, 9.0).and_then(|p| p.with_mu_s(3.0)),
        ),
    ] {
        let params = params.expect("valid");
        group.bench_with_input(BenchmarkId::new("plain", name), &params, |b, &p| {
            b.iter(|| plain(black_box(p)))
        });
        group.bench_with_input(BenchmarkId::new("tangent", name), &params, |b, &p| {
            b.iter(|| tangent(black_box(p)))
        });
        group.bench_with_input(BenchmarkId::new("strobed", name), &params, |b, &p| {
            b.iter(|| strobed(black_box(p)))
        });
    }
    group.finish();
}

criterion_group!(benches, bench_tangent);
criterion_main!(benches);
