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

use criterion::{criterion_group, criterion_main, Criterion};
use std::f64::consts::TAU;
use std::hint::black_box;
use stickslip::experiment::Experiment;
use stickslip::fit::{fit_records, fit_table, FitOptions, FitParameter};
use stickslip::measure::{read_amplitudes, read_scope, Measurement};
use stickslip::physical::{Circuit, Diode, PwlDiode};
use stickslip::solver::sample_at;
use stickslip::steady::SolverFactory;

struct Rng(u64);

impl Rng {
    fn uniform(&mut self) -> f64 {
        self.0 ^= self.0 << 13;
        self.0 ^= self.0 >> 7;
        self.0 ^= self.0 << 17;
        ((self.0 >> 11) as f64 + 0.5) / (1u64 << 53) as f64
    }
    fn gauss(&mut self) -> f64 {
        let (u, v) = (self.uniform(), self.uniform());
        (-2.0 * u.ln()).sqrt() * (TAU * v).cos()
    }
}

fn truth() -> Experiment {
    Experiment::circuit(Circuit {
        resistance: 80.0,
        diode: Diode::Pwl(PwlDiode {
            turn_on: 0.6,
            resistance: 3.0,
        }),
        ..Circuit::paper()
    })
    .expect("valid")
}

/// A Keysight export of the record at (w, β, φ).
fn record(w: f64, beta: f64, phi: f64, rng: &mut Rng) -> String {
    let e = truth()
        .with_w(w)
        .and_then(|e| e.with_beta(beta))
        .and_then(|e| e.with_phi(phi))
        .expect("valid");
    let steady = e.steady().expect("settles");
    let scales = e.scales().expect("a circuit");
    let mut solver = e
        .factory()
        .make(e.params().expect("a drive"), steady.final_state())
        .expect("starts");
    let n = 1200;
    let dt = 3.4 * TAU / (w * scales.omega0) / n as f64;
    let taus: Vec<f64> = (0..n).map(|k| k as f64 * dt * scales.omega0).collect();
    let samples = sample_at(solver.as_mut(), &taus, |_| {}).expect("runs");
    let drive: Vec<f64> = taus
        .iter()
        .map(|&tau| beta * scales.force * (w * tau + phi).cos())
        .collect();
    let response: Vec<f64> = samples.iter().map(|s| s.y * scales.position).collect();
    let mut quantise = |v: &[f64]| -> Vec<f64> {
        let (lo, hi) = v
            .iter()
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), &x| {
                (a.min(x), b.max(x))
            });
        let q = 1.25 * (hi - lo) / 256.0;
        v.iter()
            .map(|&x| ((x + q * rng.gauss()) / q).round() * q)
            .collect()
    };
    let (drive, response) = (quantise(&drive), quantise(&response));
    let mut text = "x-axis,1,2\nsecond,Volt,Volt\n".to_string();
    for k in 0..n {
        text += &format!(
            "{:.9e},{:.6e},{:.6e}\n",
            k as f64 * dt,
            drive[k],
            response[k]
        );
    }
    text
}

fn table(rng: &mut Rng) -> String {
    let e = truth();
    let f0 = e.scales().expect("a circuit").f0();
    let mut text = "freq_Hz,U_V,response_V\n".to_string();
    for beta in [1.6, 2.5, 4.0] {
        for k in 0..15 {
            let w = 0.3 + 1.3 * k as f64 / 14.0;
            let s = e
                .clone()
                .with_w(w)
                .and_then(|e| e.with_beta(beta))
                .and_then(|e| e.steady())
                .expect("settles");
            let a = s.amplitude() * 0.6 * (1.0 + 0.005 * rng.gauss());
            text += &format!("{:.4},{:.5},{:.6}\n", w * f0, beta * 0.6, a);
        }
    }
    text
}

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
            let r = read_scope(&record(w, beta, phi, &mut rng), "k.csv").expect("reads");
            Measurement::new(&r, None, None).expect("a record")
        })
        .collect();
    let amplitudes = read_amplitudes(&table(&mut rng), "gain.csv").expect("reads");
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
    group.finish();
}

criterion_group!(benches, bench_fit);
criterion_main!(benches);
