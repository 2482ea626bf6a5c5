//! A self-excited Stribeck belt's steady state (issue 36: ≤ 5 ms of CPU), beside the
//! Coulomb belt's (the exact solver) in the same run: ζ = 0.05, μs = 1.5, vb = 0.3, from
//! rest; Stribeck vs = 0.5, δ = 2, η = 0.05.
//!
//! `cargo bench -p stickslip --bench friction`

use criterion::{criterion_group, criterion_main, Criterion};
use stickslip::friction::FrictionLaw;
use stickslip::friction_solver::FrictionSolver;
use stickslip::steady::{steady_state, MotionClass, SteadyOptions};
use stickslip::{ExactSolver, Params, State};

fn belt() -> Params {
    Params::new(0.05, 1.0, 0.0)
        .and_then(|p| p.with_mu_s(1.5))
        .and_then(|p| p.with_vb(0.3))
        .expect("valid")
}

fn bench(c: &mut Criterion) {
    let stribeck = belt()
        .with_law(FrictionLaw::Stribeck {
            vs: 0.5,
            delta: 2.0,
            eta: 0.05,
        })
        .expect("valid");
    let options = SteadyOptions::default();
    let check = steady_state(
        &mut FrictionSolver::new(stribeck, State::default()).expect("valid"),
        &options,
    )
    .expect("runs");
    assert_eq!(check.class, MotionClass::StickSlipCycle);
    let mut group = c.benchmark_group("belt_steady");
    group.bench_function("stribeck", |b| {
        b.iter(|| {
            let mut solver = FrictionSolver::new(stribeck, State::default()).expect("valid");
            steady_state(&mut solver, &options).expect("runs").class
        })
    });
    group.bench_function("coulomb", |b| {
        b.iter(|| {
            let mut solver = ExactSolver::new(belt(), State::default());
            steady_state(&mut solver, &options).expect("runs").class
        })
    });
    group.finish();
}

criterion_group!(benches, bench);
criterion_main!(benches);
