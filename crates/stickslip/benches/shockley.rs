//! The Shockley solver against ngspice, side by side in one run: 300 drive periods of the
//! paper's circuit at w = 0.95, β = 2.14 from rest, at matched accuracy.
//!
//! Accuracy is the largest deviation of u_C over the 300th period from a reference (our
//! solver at rtol = atol = 1e-11, which ngspice approaches to 1e-6 as its own settings
//! tighten), relative to the peak; the bench prints it for every configuration before timing
//! them. Each ngspice sample is one `ngspice -b` process on the netlist of
//! `stickslip::shockley::netlist` without output (start-up included, 10 ms or less here);
//! `ngspice` must be on the PATH, otherwise only our solver is timed.
//!
//! `cargo bench -p stickslip --bench shockley`

use criterion::{criterion_group, criterion_main, BenchmarkId, Criterion};
use std::path::{Path, PathBuf};
use std::process::Command;
use std::time::Duration;
use stickslip::shockley::{
    netlist, NetlistOptions, ShockleyModel, ShockleyOptions, ShockleySolver,
};
use stickslip::solver::{grid, run_until, sample_at};
use stickslip::{Circuit, Solver, State};

const PERIODS: f64 = 300.0;

fn model() -> ShockleyModel {
    let circuit = Circuit::paper_shockley();
    circuit
        .shockley_model(&circuit.params(0.95, 2.14, 0.0).expect("valid"))
        .expect("valid")
        .expect("Shockley diodes")
}

/// Our configurations: rtol = atol, and the largest step in τ.
const OURS: [(f64, f64); 2] = [(5e-3, 0.5), (3e-4, 0.25)];

fn options((rtol, max_step): (f64, f64)) -> ShockleyOptions {
    ShockleyOptions::default()
        .with_rtol(rtol)
        .and_then(|o| o.with_atol(rtol))
        .and_then(|o| o.with_max_step(max_step))
        .expect("valid")
}

fn name((rtol, max_step): (f64, f64)) -> String {
    format!("rtol_{rtol:e}_max_step_{max_step}")
}

/// u_C in volts at the dimensionless times `times` (sorted, within the last period).
fn ours(config: (f64, f64), times: &[f64]) -> Vec<f64> {
    let mut solver = ShockleySolver::new(model(), State::default(), options(config)).expect("ok");
    let u_t = Circuit::paper_shockley().diode.reference_voltage();
    sample_at(&mut solver, times, |_| {})
        .expect("solver runs")
        .iter()
        .map(|s| s.y * u_t)
        .collect()
}

/// The time of the whole run: 300 periods from rest.
fn run_ours(config: (f64, f64)) -> f64 {
    let m = model();
    let mut solver = ShockleySolver::new(m, State::default(), options(config)).expect("ok");
    run_until(&mut solver, PERIODS * m.params.drive_period(), |_| {}).expect("solver runs");
    solver.state().y
}

/// An ngspice configuration: a name, reltol (None: SPICE's 1e-3), and the largest step as a
/// fraction of the period.
struct Spice {
    name: &'static str,
    reltol: Option<f64>,
    max_step_fraction: f64,
}

const SPICE: [Spice; 3] = [
    Spice {
        name: "ngspice_default_tol_tmax_T/50",
        reltol: None,
        max_step_fraction: 1.0 / 50.0,
    },
    Spice {
        name: "ngspice_default_tol_tmax_T/200",
        reltol: None,
        max_step_fraction: 1.0 / 200.0,
    },
    Spice {
        name: "ngspice_reltol_1e-4_tmax_T/200",
        reltol: Some(1e-4),
        max_step_fraction: 1.0 / 200.0,
    },
];

fn spice_netlist(s: &Spice, wrdata: Option<&str>) -> String {
    let m = model();
    let o = NetlistOptions {
        periods: PERIODS,
        points_per_period: 200,
        max_step_fraction: s.max_step_fraction,
        reltol: s.reltol,
        abstol: None,
        vntol: None,
        wrdata: Some(wrdata.unwrap_or("unused.txt").to_string()),
    };
    let text = netlist(&Circuit::paper_shockley(), &m.params, State::default(), &o).expect("ok");
    if wrdata.is_some() {
        text
    } else {
        // Time the simulation, not the writing of its output.
        text.replace("wrdata unused.txt v(uc) i(L1)\n", "")
    }
}

fn run_ngspice(dir: &Path, file: &str) {
    let out = Command::new("ngspice")
        .args(["-b", file])
        .current_dir(dir)
        .output()
        .expect("ngspice runs");
    assert!(out.status.success(), "ngspice failed");
}

fn ngspice_available() -> bool {
    matches!(
        Command::new("ngspice").arg("--version").output(),
        Ok(o) if o.status.success()
    )
}

/// Largest deviation over the last period relative to the peak of the reference.
fn deviation(values: &[f64], reference: &[f64]) -> f64 {
    let peak = reference.iter().fold(0.0f64, |m, x| m.max(x.abs()));
    values
        .iter()
        .zip(reference)
        .fold(0.0f64, |m, (a, b)| m.max((a - b).abs()))
        / peak
}

fn bench_shockley(c: &mut Criterion) {
    let m = model();
    let period = m.params.drive_period();
    let omega0 = Circuit::paper_shockley().scales().omega0;
    let last = grid((PERIODS - 1.0) * period, PERIODS * period, 2000);
    let tight = (1e-11, 0.25);
    let reference = ours(tight, &last);
    for config in OURS {
        eprintln!(
            "accuracy stickslip_radau/{}: {:.2e} of the peak",
            name(config),
            deviation(&ours(config, &last), &reference)
        );
    }
    let spice = ngspice_available();
    let dir: PathBuf = std::env::temp_dir().join(format!("stickslip-bench-{}", std::process::id()));
    if spice {
        std::fs::create_dir_all(&dir).expect("temp dir");
        for (k, s) in SPICE.iter().enumerate() {
            std::fs::write(
                dir.join(format!("acc{k}.cir")),
                spice_netlist(s, Some("acc.txt")),
            )
            .expect("write");
            run_ngspice(&dir, &format!("acc{k}.cir"));
            let rows: Vec<(f64, f64)> = std::fs::read_to_string(dir.join("acc.txt"))
                .expect("ngspice output")
                .lines()
                .map(|l| {
                    let v: Vec<f64> = l.split_whitespace().map(|x| x.parse().unwrap()).collect();
                    (v[0] * omega0, v[1])
                })
                .filter(|r| r.0 >= (PERIODS - 1.0) * period)
                .collect();
            let times: Vec<f64> = rows.iter().map(|r| r.0).collect();
            let values: Vec<f64> = rows.iter().map(|r| r.1).collect();
            eprintln!(
                "accuracy {}: {:.2e} of the peak",
                s.name,
                deviation(&values, &ours(tight, &times))
            );
            std::fs::write(dir.join(format!("run{k}.cir")), spice_netlist(s, None)).expect("write");
        }
    } else {
        eprintln!("ngspice not found on PATH: timing stickslip only");
    }

    let mut group = c.benchmark_group("shockley_300_periods_w0.95_b2.14");
    group.sample_size(10);
    group.measurement_time(Duration::from_secs(10));
    for config in OURS {
        group.bench_with_input(
            BenchmarkId::new("stickslip_radau", name(config)),
            &config,
            |b, &c| b.iter(|| run_ours(c)),
        );
    }
    if spice {
        for (k, s) in SPICE.iter().enumerate() {
            let file = format!("run{k}.cir");
            group.bench_function(s.name, |b| b.iter(|| run_ngspice(&dir, &file)));
        }
        let _ = std::fs::remove_dir_all(&dir);
    }
    group.finish();
}

criterion_group!(benches, bench_shockley);
criterion_main!(benches);
