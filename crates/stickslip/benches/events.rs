//! Events per second of the exact solver on the paper's motions (criterion reports the
//! throughput in elements = events per second), without a cancellation token and with the
//! tokens a front end gives it (a deadline; a deadline and a hook, as the lab's).

use criterion::{criterion_group, criterion_main, BenchmarkId, Criterion, Throughput};
use std::sync::Arc;
use std::time::{Duration, Instant};
use stickslip::cancel::Cancel;
use stickslip::solver::run_until;
use stickslip::{Circuit, ExactSolver, Params, State};

/// Count events over `periods` drive periods from rest.
fn events_over(params: Params, periods: f64) -> u64 {
    events_checking(params, periods, Cancel::never())
}

/// Count events over `periods` drive periods from rest, the solver checking `cancel`.
fn events_checking(params: Params, periods: f64, cancel: Cancel) -> u64 {
    let mut solver = ExactSolver::new(params, State::default()).with_cancel(cancel);
    let mut n = 0u64;
    run_until(&mut solver, periods * params.drive_period(), |_| n += 1).expect("solver runs");
    n
}

fn bench_events(c: &mut Criterion) {
    let zeta = Circuit::paper().scales().zeta();
    let mut group = c.benchmark_group("exact_solver_events");
    for (name, w, beta) in [
        ("sliding_w0.9_b1.6", 0.9, 1.6),
        ("periodic_stick_w0.6_b1.2", 0.6, 1.2),
        ("stick_w0.7_b1.2", 0.7, 1.2),
        ("low_freq_w0.29_b2.14", 0.29, 2.14),
    ] {
        let params = Params::new(zeta, w, beta).expect("valid");
        let periods = 300.0;
        let events = events_over(params, periods);
        group.throughput(Throughput::Elements(events));
        group.bench_with_input(BenchmarkId::from_parameter(name), &params, |b, &p| {
            b.iter(|| events_over(p, periods))
        });
    }
    group.finish();

    // The cost of the checks: the low-frequency motion (the most events per period) with a
    // token that has a deadline (read every few hundred events), and with a hook too (called
    // as often; here it does nothing, as the lab's does while nobody waits).
    let params = Params::new(zeta, 0.29, 2.14).expect("valid");
    let periods = 300.0;
    let mut group = c.benchmark_group("exact_solver_events_checking");
    group.throughput(Throughput::Elements(events_over(params, periods)));
    let far = || Instant::now() + Duration::from_secs(3600);
    group.bench_function("never", |b| {
        b.iter(|| events_checking(params, periods, Cancel::never()))
    });
    group.bench_function("deadline", |b| {
        b.iter(|| events_checking(params, periods, Cancel::new().with_deadline(far())))
    });
    group.bench_function("deadline_and_hook", |b| {
        let hook: stickslip::cancel::Hook = Arc::new(|| {});
        b.iter(|| {
            events_checking(
                params,
                periods,
                Cancel::new().with_deadline(far()).with_hook(hook.clone()),
            )
        })
    });
    group.finish();
}

criterion_group!(benches, bench_events);
criterion_main!(benches);
