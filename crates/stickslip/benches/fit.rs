//! Fits of measurements on one core (a one-thread pool).
//!
//! `records`: the joint fit of three 1200-sample records (w = 0.29, 0.95, 1.43, synthesised
//! by the exact solver at R = 80 Ω, U_t = 0.6 V, 8-bit quantisation and one step of noise)
//! with R and U_t free, from the paper's values; the target is at most 1 s.
//! `records_3x1200_two_free_finite_differences`: the same fit with the Jacobian by finite
//! differences throughout (`FitOptions::exact_jacobian = false`, the fit before the exact
//! Jacobians), to compare in one run.
//! `table`: the fit of a table of 45 amplitudes (15 frequencies at three drive levels) with R
//! and U_t free; the target is at most 0.5 s.
//! `shockley_records_5_three_free`: the Shockley fit of the five records of the 1N914-like
//! ngspice bench (`stickslip_testkit::ngspice::D1N914`: 1200 to 2800 samples each, 10 300
//! in all, drawn with the seed 1) with I_s, n and R_s free from the 1N4148's values (R, L, C
//! as built), everything `stickslip fit` does: the PWL fit for the valley's start, both
//! passes, the restart and the profile intervals; the target is at most 2 s (issue 34).

use criterion::{criterion_group, criterion_main, Criterion};
use std::hint::black_box;
use stickslip::experiment::Experiment;
use stickslip::fit::{fit_records, fit_table, FitOptions, FitParameter};
use stickslip::measure::{read_amplitudes, read_scope, Measurement};

use stickslip_testkit::{amplitude_table, keysight, synthesise, Rng};

const FREE: [FitParameter; 2] = [FitParameter::Resistance, FitParameter::Ut];

fn bench_fit(c: &mut Criterion) {
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(1)
        .build()
        .expect("a pool");
    let mut rng = Rng(2026);
    let data: Vec<Measurement> = [(0.29, 2.6, 0.4), (0.95, 2.14, -1.1), (1.43, 3.0, 2.5)]
        .iter()
        .map(|&(w, beta, phi)| {
            let s = synthesise(w, beta, phi, 0.0, 1.0, &mut rng);
            let r = read_scope(&keysight(&s), "k.csv").expect("reads");
            Measurement::new(&r, None, None).expect("a record")
        })
        .collect();
    let amplitudes = read_amplitudes(&amplitude_table(&mut rng, false), "gain.csv").expect("reads");
    let start = Experiment::paper();
    let options = FitOptions::default();
    let report = pool.install(|| fit_records(&start, &data, &FREE, &options).expect("fits"));
    eprintln!(
        "records: {} iterations, R = {:.3} ohm, U_t = {:.5} V, {} Jacobian",
        report.iterations,
        report.parameters[0].value,
        report.parameters[1].value,
        report.jacobian.label()
    );
    let report = pool.install(|| fit_table(&start, &amplitudes, &FREE, &options).expect("fits"));
    eprintln!(
        "table: {} iterations, R = {:.3} ohm, U_t = {:.5} V",
        report.iterations, report.parameters[0].value, report.parameters[1].value
    );
    let mut group = c.benchmark_group("fit");
    group.sample_size(10);
    group.bench_function("records_3x1200_two_free", |b| {
        b.iter(|| {
            pool.install(|| {
                fit_records(&start, black_box(&data), &FREE, &options)
                    .expect("fits")
                    .iterations
            })
        })
    });
    let fd = FitOptions {
        exact_jacobian: false,
        ..options
    };
    group.bench_function("records_3x1200_two_free_finite_differences", |b| {
        b.iter(|| {
            pool.install(|| {
                fit_records(&start, black_box(&data), &FREE, &fd)
                    .expect("fits")
                    .iterations
            })
        })
    });
    group.bench_function("table_45_two_free", |b| {
        b.iter(|| {
            pool.install(|| {
                fit_table(&start, black_box(&amplitudes), &FREE, &options)
                    .expect("fits")
                    .iterations
            })
        })
    });
    let bench = stickslip_testkit::ngspice::D1N914;
    let records: Vec<Measurement> = bench.measurements(1).into_iter().map(|(_, m)| m).collect();
    let from = Experiment::circuit(bench.circuit())
        .expect("a circuit")
        .with_shockley(stickslip::DiodePair::one_n4148())
        .expect("Shockley diodes");
    let shockley = [
        FitParameter::DiodeIs,
        FitParameter::DiodeN,
        FitParameter::DiodeRs,
    ];
    let report = pool.install(|| fit_records(&from, &records, &shockley, &options).expect("fits"));
    eprintln!(
        "shockley: {} iterations, converged {}, {} Jacobian, chi2/dof {:.3}",
        report.iterations,
        report.converged,
        report.jacobian.label(),
        report.chi2_dof.unwrap_or(f64::NAN)
    );
    group.bench_function("shockley_records_5_three_free", |b| {
        b.iter(|| {
            pool.install(|| {
                fit_records(&from, black_box(&records), &shockley, &options)
                    .expect("fits")
                    .iterations
            })
        })
    });
    group.finish();
}

criterion_group!(benches, bench_fit);
criterion_main!(benches);
