//! Cost of the tangent dynamics against a plain exact run: 300 drive periods from rest with
//! the exact solver alone (`plain`), with its Jacobian carried along and renormalised at the
//! end as `lyapunov_exponents` does per block (`tangent`), and with the Jacobian renormalised
//! at every strobe (`strobed`, one more stop of the solver per period). The target: tangents
//! cost at most 1.5× the plain run.
//!
//! `lyapunov_cost`: the whole measurement, `lyapunov_exponents` over N = 3000 drive periods
//! (no transient, 20 blocks: renormalisation, block means, stop count, the solver restarted
//! every block), against a plain exact run of the same 3000 periods. The target: at most 1.5×.
//!
//! `newton`: Newton's method from a settled guess (`periodic_orbit_from_steady`, the steady
//! state computed once outside the timing); the iterations are printed and must be at most
//! 6 (the target), or the bench stops.

use criterion::{criterion_group, criterion_main, BenchmarkId, Criterion};
use std::hint::black_box;
use stickslip::solver::run_until;
use stickslip::stability::{
    lyapunov_exponents, periodic_orbit_from_steady, LyapunovOptions, NewtonOptions, TangentSolver,
};
use stickslip::steady::{exact_solver, steady_state_from, SteadyOptions};
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

/// The workloads: the four points of the events bench (paper's ζ) and a chaotic one.
fn points() -> Vec<(&'static str, Params)> {
    let zeta = Circuit::paper().scales().zeta();
    [
        ("sliding_w0.9_b1.6", Params::new(zeta, 0.9, 1.6)),
        ("periodic_stick_w0.6_b1.2", Params::new(zeta, 0.6, 1.2)),
        ("stick_w0.7_b1.2", Params::new(zeta, 0.7, 1.2)),
        ("low_freq_w0.29_b2.14", Params::new(zeta, 0.29, 2.14)),
        (
            "chaotic_z0_mus3_w0.33_b9",
            Params::new(0.0, 0.33, 9.0).and_then(|p| p.with_mu_s(3.0)),
        ),
    ]
    .into_iter()
    .map(|(name, p)| (name, p.expect("valid")))
    .collect()
}

/// Drive periods of the `lyapunov_cost` group.
const MEASURED: usize = 3000;

fn plain_run(params: Params, periods: usize) -> f64 {
    let mut solver = ExactSolver::new(params, State::default());
    run_until(&mut solver, periods as f64 * params.drive_period(), |_| {}).expect("solver runs");
    solver.state().y
}

fn bench_lyapunov(c: &mut Criterion) {
    let mut group = c.benchmark_group("lyapunov_cost");
    let options = LyapunovOptions {
        transient_periods: 0,
        periods: MEASURED,
        blocks: 20,
        significance: 4.0,
        sequential: false,
    };
    for (name, params) in points() {
        group.bench_with_input(BenchmarkId::new("plain", name), &params, |b, &p| {
            b.iter(|| plain_run(black_box(p), MEASURED))
        });
        group.bench_with_input(BenchmarkId::new("lyapunov", name), &params, |b, &p| {
            b.iter(|| {
                lyapunov_exponents(&black_box(p), State::default(), &options)
                    .expect("measures")
                    .largest
                    .per_tau
            })
        });
    }
    group.finish();
}

fn bench_newton(c: &mut Criterion) {
    let mut group = c.benchmark_group("newton");
    let mut cases = points();
    cases.pop(); // chaotic: no period to start from
    cases.push((
        "period3_z0_mus3_w0.40_b9",
        Params::new(0.0, 0.40, 9.0)
            .and_then(|p| p.with_mu_s(3.0))
            .expect("valid"),
    ));
    let newton = NewtonOptions::default();
    for (name, params) in cases {
        let options = SteadyOptions::default().with_spectrum(false);
        let steady =
            steady_state_from(&exact_solver, &params, State::default(), &options).expect("settles");
        let orbit = periodic_orbit_from_steady(&params, &steady, &newton).expect("converges");
        eprintln!(
            "newton {name}: period {}, {} iterations from the settled guess, residuals {:?}",
            orbit.period, orbit.iterations, orbit.residuals
        );
        assert!(
            orbit.iterations <= 6,
            "{name}: {} Newton iterations from a settled guess",
            orbit.iterations
        );
        group.bench_with_input(BenchmarkId::new("from_settled", name), &steady, |b, s| {
            b.iter(|| {
                periodic_orbit_from_steady(&params, black_box(s), &newton)
                    .expect("converges")
                    .iterations
            })
        });
    }
    group.finish();
}

criterion_group!(benches, bench_tangent, bench_lyapunov, bench_newton);
criterion_main!(benches);
