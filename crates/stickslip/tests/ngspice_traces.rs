//! The generator of the ngspice traces that the fit's coverage and comparison tests draw
//! their noisy records from (`stickslip_testkit::ngspice`: the circuit L = 10 mH, C = 47 nF,
//! R = 120 Ω with 1N914-like, BAT54-like and red-LED diode pairs; the drives and the scope's
//! sampling of each record).
//!
//! For each record ngspice simulates the circuit from rest for 60 drive periods and the
//! record's length, on the netlist of `stickslip::shockley::netlist`, with tight settings
//! (reltol = 10⁻⁷, abstol = 10⁻¹⁵ A, vntol = 10⁻¹⁰ V, time step at most 1/5000 of the drive
//! period), and its u_C is interpolated linearly at the scope's sample times (the error of
//! the interpolation is below 10⁻⁶ of the amplitude). `STICKSLIP_BLESS=1` writes the traces
//! under `crates/stickslip-testkit/data/ngspice/` (`examples/fit/make-ngspice-traces`);
//! without it the test makes them again and requires every value within 10⁻⁵ of the
//! record's peak of the committed one (another ngspice version or platform moves the last
//! digits; one 8-bit quantisation step is 4·10⁻³ of the peak or more).
//!
//! Without ngspice on the PATH the test says on standard error that it is skipped and why;
//! with `STICKSLIP_REQUIRE_NGSPICE=1` (set by `scripts/test`) it fails instead.

use std::path::PathBuf;
use stickslip::shockley::{netlist, NetlistOptions};
use stickslip::State;
use stickslip_testkit::ngspice::{Bench, BAT54, D1N914, LED};

mod support;
use support::{interpolate, ngspice_available, run_ngspice, work_dir};

/// ngspice's noise-free u_C (V) of record `i` of `bench` at the scope's sample times.
fn make_trace(bench: &Bench, i: usize) -> Vec<f64> {
    let spec = &bench.records[i];
    let circuit = bench.circuit();
    let scales = circuit.scales();
    let w = std::f64::consts::TAU * spec.freq_hz / scales.omega0;
    let beta = spec.drive_v / circuit.diode.reference_voltage();
    let params = circuit.params(w, beta, spec.phase()).unwrap();
    let record_periods = spec.samples as f64 * spec.interval_s * spec.freq_hz;
    let options = NetlistOptions {
        periods: stickslip_testkit::ngspice::SETTLE_PERIODS + record_periods + 0.1,
        points_per_period: 2000,
        max_step_fraction: 2e-4,
        reltol: Some(1e-7),
        abstol: Some(1e-15),
        vntol: Some(1e-10),
        wrdata: Some("out.txt".into()),
    };
    let text = netlist(&circuit, &params, State::default(), &options).unwrap();
    let points = run_ngspice(
        &work_dir(&format!("ngspice-traces-{}-{}", bench.name, spec.name)),
        &text,
    );
    let trigger = spec.trigger_s();
    let end = trigger + 0.5 * spec.samples as f64 * spec.interval_s;
    let reached = points.last().map_or(0.0, |p| p.0);
    assert!(
        reached >= end,
        "{} {}: ngspice stopped at {reached} s, before the record's end at {end} s",
        bench.name,
        spec.name
    );
    spec.axis()
        .iter()
        .map(|&t| interpolate(&points, t + trigger))
        .collect()
}

fn testkit_dir() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../stickslip-testkit")
}

#[test]
fn the_ngspice_traces_are_made_again() {
    let test = "the_ngspice_traces_are_made_again";
    if !ngspice_available(test) {
        return;
    }
    let bless = std::env::var("STICKSLIP_BLESS").is_ok_and(|v| v != "0");
    let mut stale = Vec::new();
    for bench in [D1N914, BAT54, LED] {
        for (i, spec) in bench.records.iter().enumerate() {
            let made = make_trace(&bench, i);
            let peak = made.iter().fold(0.0f64, |m, v| m.max(v.abs()));
            eprintln!(
                "{} {}: {} samples, u_C peak {peak:.4} V",
                bench.name, spec.name, spec.samples
            );
            let path = testkit_dir().join(bench.trace_path(spec));
            if bless {
                let mut text = format!(
                    "# u_C (V) of {} {} by ngspice: {} Hz, {} V, {} samples every {} s \
                     (crates/stickslip/tests/ngspice_traces.rs)\n",
                    bench.name,
                    spec.name,
                    spec.freq_hz,
                    spec.drive_v,
                    spec.samples,
                    spec.interval_s
                );
                for v in &made {
                    text += &format!("{v:.7e}\n");
                }
                std::fs::create_dir_all(path.parent().unwrap()).unwrap();
                std::fs::write(&path, text).unwrap();
                continue;
            }
            let committed = bench.trace(i);
            let largest = made
                .iter()
                .zip(&committed)
                .fold(0.0f64, |m, (a, b)| m.max((a - b).abs()));
            if largest > 1e-5 * peak {
                stale.push(format!(
                    "{} {}: up to {largest:.3e} V from the committed trace (peak {peak:.3} V)",
                    bench.name, spec.name
                ));
            }
        }
    }
    assert!(
        stale.is_empty(),
        "the committed traces are not what ngspice makes (examples/fit/make-ngspice-traces \
         writes them if the change is meant):\n{}",
        stale.join("\n")
    );
}
