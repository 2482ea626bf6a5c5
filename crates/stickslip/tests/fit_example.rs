//! The records of the worked example (docs/fit.md, examples/python/paper.ipynb), made with
//! ngspice and committed under `examples/fit/data/` so that the docs and the notebook work
//! without it. This test makes them again and requires the committed files byte for byte;
//! `examples/fit/make-records` (this test with `STICKSLIP_BLESS=1`) writes them.
//!
//! The circuit: the paper's L = 11.5 mH, C = 20 nF and R = 68 Ω with two anti-parallel
//! diodes of the D1N4148 card of PSpice's diode library (`IS=2.682n N=1.836 RS=.5664`; its
//! high-injection, recombination, capacitance and transit-time terms are left out: the
//! Shockley law and `stickslip netlist` carry IS, N and RS), at 27 °C, on the netlist of
//! `stickslip::shockley::netlist`. A student's bench: a generator of 1.5 V peak at 3, 10 and
//! 15 kHz, each run 60 drive periods from rest before the scope triggers on the drive's
//! rising zero crossing (t = 0, mid-record). The scope: 1200 samples per channel at a
//! sampling interval of 1, 0.2 and 0.2 µs, 8 bits over 10 divisions of a 1-2-5 volts per
//! division setting, one quantisation step of Gaussian noise (seeded), and a DC offset of the
//! u_C channel; exported as Rigol (3 and 15 kHz) and Keysight InfiniiVision (10 kHz) CSV.
//!
//! Without ngspice on the PATH the test says on standard error that it is skipped and why;
//! with `STICKSLIP_REQUIRE_NGSPICE=1` (set by `scripts/test`) it fails instead. Another
//! ngspice version may move a sample across a quantisation step: the failure says how many
//! samples differ and by how much (the committed files were made with ngspice-39).

use std::f64::consts::{PI, TAU};
use std::path::PathBuf;
use stickslip::measure::{read_scope, Measurement};
use stickslip::shockley::{netlist, DiodePair, NetlistOptions};
use stickslip::{Circuit, State};

mod support;
use stickslip_testkit::Rng;
use support::{interpolate, ngspice_available, run_ngspice, work_dir};

/// The D1N4148 card's IS, N and RS at 27 °C.
fn d1n4148() -> DiodePair {
    DiodePair::new(2.682e-9, 1.836, 0.5664, 27.0).unwrap()
}

/// The scope's export format.
#[derive(Clone, Copy)]
enum Format {
    Rigol,
    Keysight,
}

/// One record: the drive (Hz, V peak), the scope's sampling interval (s), volts per division
/// of the drive and u_C channels, and the u_C channel's DC offset (V).
struct Spec {
    file: &'static str,
    format: Format,
    freq_hz: f64,
    drive_v: f64,
    interval_s: f64,
    drive_v_per_div: f64,
    response_v_per_div: f64,
    offset_v: f64,
}

const SPECS: [Spec; 3] = [
    Spec {
        file: "rigol-3kHz.csv",
        format: Format::Rigol,
        freq_hz: 3000.0,
        drive_v: 1.5,
        interval_s: 1e-6,
        drive_v_per_div: 0.5,
        response_v_per_div: 0.5,
        offset_v: 0.025,
    },
    Spec {
        file: "keysight-10kHz.csv",
        format: Format::Keysight,
        freq_hz: 10000.0,
        drive_v: 1.5,
        interval_s: 0.2e-6,
        drive_v_per_div: 0.5,
        response_v_per_div: 2.0,
        offset_v: -0.015,
    },
    Spec {
        file: "rigol-15kHz.csv",
        format: Format::Rigol,
        freq_hz: 15000.0,
        drive_v: 1.5,
        interval_s: 0.2e-6,
        drive_v_per_div: 0.5,
        response_v_per_div: 0.5,
        offset_v: 0.010,
    },
];

/// Samples per channel.
const SAMPLES: usize = 1200;
/// Drive periods from rest before the trigger's record starts.
const SETTLE_PERIODS: f64 = 60.0;
/// The scope's 8-bit converter spans 10 divisions: codes −128 … 127.
const CODES_PER_DIV: f64 = 25.6;

/// `x` as a C `printf("%.*e")` prints it (`-1.523438e+00`), as scopes write their CSV.
fn sci(x: f64, digits: usize) -> String {
    let s = format!("{x:.digits$e}");
    let (mantissa, exponent) = s.split_once('e').unwrap();
    let e: i32 = exponent.parse().unwrap();
    let sign = if e < 0 { '-' } else { '+' };
    format!("{mantissa}e{sign}{:02}", e.abs())
}

/// The 8-bit codes of `values` at `v_per_div`, with one code of Gaussian noise; panics if a
/// value is off the converter's range (the scope would clip it: a wrong setting).
fn codes(values: &[f64], v_per_div: f64, rng: &mut Rng) -> Vec<f64> {
    let q = v_per_div / CODES_PER_DIV;
    values
        .iter()
        .map(|&x| {
            let code = (x / q + rng.gauss()).round();
            assert!(
                (-128.0..=127.0).contains(&code),
                "{x} V is off the screen at {v_per_div} V/div"
            );
            code * q
        })
        .collect()
}

/// The export of record `spec`: ngspice's u_C sampled like the scope.
fn export(spec: &Spec, rng: &mut Rng) -> String {
    let circuit = Circuit::paper().with_shockley(d1n4148());
    let scales = circuit.scales();
    let omega = TAU * spec.freq_hz;
    let w = omega / scales.omega0;
    let beta = spec.drive_v / circuit.diode.reference_voltage();
    let record_s = SAMPLES as f64 * spec.interval_s;
    // The trigger: mid-record, SETTLE_PERIODS periods and half a record after the start, on
    // the drive's rising zero crossing (U cos(Ω t + φ) with Ω t + φ = −π/2 there).
    let trigger_s = SETTLE_PERIODS / spec.freq_hz + 0.5 * record_s;
    let phi = (-0.5 * PI - omega * trigger_s).rem_euclid(TAU);
    let params = circuit.params(w, beta, phi).unwrap();
    let options = NetlistOptions {
        periods: SETTLE_PERIODS + record_s * spec.freq_hz + 0.1,
        points_per_period: 400,
        max_step_fraction: 1e-3,
        reltol: Some(1e-6),
        abstol: Some(1e-15),
        vntol: Some(1e-9),
        wrdata: Some("out.txt".into()),
    };
    let text = netlist(&circuit, &params, State::default(), &options).unwrap();
    let points = run_ngspice(&work_dir(&format!("fit-example-{}", spec.file)), &text);
    // Times on the scope's axis (0 at the trigger) and in the simulation.
    let axis: Vec<f64> = (0..SAMPLES)
        .map(|k| (k as f64 - 0.5 * SAMPLES as f64) * spec.interval_s)
        .collect();
    let drive: Vec<f64> = axis
        .iter()
        .map(|&t| spec.drive_v * (omega * (t + trigger_s) + phi).cos())
        .collect();
    let response: Vec<f64> = axis
        .iter()
        .map(|&t| interpolate(&points, t + trigger_s) + spec.offset_v)
        .collect();
    let peak = response.iter().fold(0.0f64, |m, x| m.max(x.abs()));
    eprintln!(
        "{}: w = {w:.4}, β = {beta:.4}, u_C peak {peak:.3} V ({:.2} div)",
        spec.file,
        peak / spec.response_v_per_div
    );
    let drive = codes(&drive, spec.drive_v_per_div, rng);
    let response = codes(&response, spec.response_v_per_div, rng);
    match spec.format {
        Format::Rigol => {
            let mut t = format!(
                "X,CH1,CH2,Start,Increment,\nSequence,Volt,Volt,{},{}\n",
                sci(axis[0], 6),
                sci(spec.interval_s, 6)
            );
            for k in 0..SAMPLES {
                t += &format!("{k},{},{},\n", sci(drive[k], 6), sci(response[k], 6));
            }
            t
        }
        Format::Keysight => {
            let mut t = "x-axis,1,2\nsecond,Volt,Volt\n".to_string();
            for k in 0..SAMPLES {
                t += &format!(
                    "{},{},{}\n",
                    sci(axis[k], 9),
                    sci(drive[k], 6),
                    sci(response[k], 6)
                );
            }
            t
        }
    }
}

/// The committed records' directory.
fn data_dir() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../examples/fit/data")
}

/// Where `made` and `committed` differ: (differing lines, the largest difference in volts).
fn differences(made: &str, committed: &str) -> (usize, f64) {
    let mut count = made.lines().count().abs_diff(committed.lines().count());
    let mut largest = 0.0f64;
    for (a, b) in made.lines().zip(committed.lines()) {
        if a == b {
            continue;
        }
        count += 1;
        for (x, y) in a.split(',').zip(b.split(',')) {
            if let (Ok(x), Ok(y)) = (x.parse::<f64>(), y.parse::<f64>()) {
                largest = largest.max((x - y).abs());
            }
        }
    }
    (count, largest)
}

#[test]
fn the_worked_example_records_are_made_again_byte_for_byte() {
    let test = "the_worked_example_records_are_made_again_byte_for_byte";
    if !ngspice_available(test) {
        return;
    }
    let bless = std::env::var("STICKSLIP_BLESS").is_ok_and(|v| v != "0");
    let mut rng = Rng(4148);
    let mut stale = Vec::new();
    for spec in &SPECS {
        let text = export(spec, &mut rng);
        // The record reads, with the drive as set and nothing clipped.
        let record = read_scope(&text, spec.file).unwrap();
        let m = Measurement::new(&record, None, None).unwrap();
        assert!(
            (m.drive.frequency / spec.freq_hz - 1.0).abs() < 1e-3
                && (m.drive.amplitude / spec.drive_v - 1.0).abs() < 1e-2,
            "{}: {:?}",
            spec.file,
            m.drive
        );
        assert!(record.channels.iter().all(|c| c.clipped_count() == 0));
        let path = data_dir().join(spec.file);
        if bless {
            std::fs::create_dir_all(data_dir()).unwrap();
            std::fs::write(&path, &text).unwrap();
            continue;
        }
        let committed = std::fs::read_to_string(&path).unwrap_or_else(|e| {
            panic!(
                "{}: {e} (examples/fit/make-records writes it)",
                path.display()
            )
        });
        if committed != text {
            let (lines, largest) = differences(&text, &committed);
            stale.push(format!(
                "{}: {lines} lines differ, by up to {largest:.3e} V (one quantisation step is \
                 {:.3e} V on u_C)",
                spec.file,
                spec.response_v_per_div / CODES_PER_DIV
            ));
        }
    }
    assert!(
        stale.is_empty(),
        "the committed records are not what this test makes (run examples/fit/make-records \
         if the change is meant):\n{}",
        stale.join("\n")
    );
}
