//! Support for the measurement tests, the fit benchmark and the worked example's records: a
//! seeded random source, scope records synthesised by the exact solver (8-bit quantisation,
//! noise, a channel offset), their CSV exports in the formats the readers take, a table of
//! amplitudes, and ngspice run as an external program.
//!
//! Included with `mod support;` by the tests and with `#[path]` by `benches/fit.rs`; not
//! every user takes every item.
#![allow(dead_code)]

use std::f64::consts::TAU;
use std::io::Write;
use std::path::{Path, PathBuf};
use std::process::Command;
use stickslip::experiment::Experiment;
use stickslip::physical::{Circuit, Diode, PwlDiode};
use stickslip::solver::sample_at;
use stickslip::steady::SolverFactory;

/// xorshift64 from a fixed seed, with Gaussian numbers by Box–Muller.
pub struct Rng(pub u64);

impl Rng {
    /// Uniform in (0, 1).
    pub fn uniform(&mut self) -> f64 {
        self.0 ^= self.0 << 13;
        self.0 ^= self.0 >> 7;
        self.0 ^= self.0 << 17;
        ((self.0 >> 11) as f64 + 0.5) / (1u64 << 53) as f64
    }

    /// Standard normal.
    pub fn gauss(&mut self) -> f64 {
        let (u, v) = (self.uniform(), self.uniform());
        (-2.0 * u.ln()).sqrt() * (TAU * v).cos()
    }
}

/// The circuit values the recovery tests and the benchmark synthesise with.
pub const TRUE_R: f64 = 80.0;
pub const TRUE_UT: f64 = 0.6;

/// The paper's L and C with R = 80 Ω and a PWL diode of U_t = 0.6 V, R_D = 3 Ω.
pub fn truth() -> Experiment {
    Experiment::circuit(Circuit {
        resistance: TRUE_R,
        diode: Diode::Pwl(PwlDiode {
            turn_on: TRUE_UT,
            resistance: 3.0,
        }),
        ..Circuit::paper()
    })
    .unwrap()
}

/// Each value plus `noise` quantisation steps of Gaussian noise, rounded to a step, the step
/// being 1.25 times the values' peak-to-peak over `levels` (a scope set to fill its screen).
pub fn quantise(values: &[f64], levels: f64, noise: f64, rng: &mut Rng) -> Vec<f64> {
    let (lo, hi) = values
        .iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), &x| {
            (a.min(x), b.max(x))
        });
    let q = 1.25 * (hi - lo) / levels;
    values
        .iter()
        .map(|&x| ((x + noise * q * rng.gauss()) / q).round() * q)
        .collect()
}

/// A two-channel record: times (s), drive (V), u_C (V); the time axis starts at `start` and
/// steps by `increment` (s).
pub struct Synthetic {
    pub time: Vec<f64>,
    pub drive: Vec<f64>,
    pub response: Vec<f64>,
    pub start: f64,
    pub increment: f64,
}

impl Synthetic {
    /// A record of `drive` and `response` sampled every `increment` from `start`.
    pub fn new(drive: Vec<f64>, response: Vec<f64>, start: f64, increment: f64) -> Self {
        assert_eq!(drive.len(), response.len());
        Synthetic {
            time: (0..drive.len())
                .map(|k| start + k as f64 * increment)
                .collect(),
            drive,
            response,
            start,
            increment,
        }
    }
}

/// The steady state of [`truth`] at (w, β, φ), 1200 samples over 3.4 drive periods, quantised
/// to 8 bits with `noise` steps of noise and a u_C offset of `offset` V; the time axis is
/// centred on the trigger.
pub fn synthesise(
    w: f64,
    beta: f64,
    phi: f64,
    offset: f64,
    noise: f64,
    rng: &mut Rng,
) -> Synthetic {
    let e = truth()
        .with_w(w)
        .unwrap()
        .with_beta(beta)
        .unwrap()
        .with_phi(phi)
        .unwrap();
    let steady = e.steady().unwrap();
    let scales = e.scales().unwrap();
    let params = e.params().unwrap();
    let mut solver = e.factory().make(params, steady.final_state()).unwrap();
    let n = 1200;
    let period = TAU / (w * scales.omega0);
    let increment = 3.4 * period / n as f64;
    let start = -0.5 * n as f64 * increment;
    let taus: Vec<f64> = (0..n)
        .map(|k| k as f64 * increment * scales.omega0)
        .collect();
    let samples = sample_at(solver.as_mut(), &taus, |_| {}).unwrap();
    let drive: Vec<f64> = taus
        .iter()
        .map(|&tau| beta * scales.force * (w * tau + phi).cos())
        .collect();
    let response: Vec<f64> = samples
        .iter()
        .map(|s| s.y * scales.position + offset)
        .collect();
    let drive = quantise(&drive, 256.0, noise, rng);
    let response = quantise(&response, 256.0, noise, rng);
    Synthetic::new(drive, response, start, increment)
}

/// A Rigol export: a header with the start time and the increment, then index rows.
pub fn rigol(s: &Synthetic) -> String {
    let mut t = format!(
        "X,CH1,CH2,Start,Increment,\nSequence,Volt,Volt,{:.6e},{:.6e}\n",
        s.start, s.increment
    );
    for k in 0..s.time.len() {
        t += &format!("{k},{:.6e},{:.6e},\n", s.drive[k], s.response[k]);
    }
    t
}

/// A Keysight InfiniiVision export: a time column.
pub fn keysight(s: &Synthetic) -> String {
    let mut t = "x-axis,1,2\nsecond,Volt,Volt\n".to_string();
    for k in 0..s.time.len() {
        t += &format!(
            "{:.9e},{:.6e},{:.6e}\n",
            s.time[k], s.drive[k], s.response[k]
        );
    }
    t
}

/// One channel (1: the drive, 2: u_C) of a Tektronix export.
pub fn tektronix(s: &Synthetic, channel: usize) -> String {
    let values = if channel == 1 { &s.drive } else { &s.response };
    let header = [
        ("Record Length", format!("{:.6e}", s.time.len())),
        ("Sample Interval", format!("{:.6e}", s.increment)),
        ("Trigger Point", "6.000000000000e+02".into()),
        ("", String::new()),
        ("Source", format!("CH{channel}")),
        ("Vertical Units", "V".into()),
        ("Model Number", "TDS2012B".into()),
    ];
    let mut t = String::new();
    for k in 0..s.time.len() {
        let (key, value) = header.get(k).cloned().unwrap_or(("", String::new()));
        t += &format!("{key},{value},,{:.9e},{:.6e},\r\n", s.time[k], values[k]);
    }
    t
}

/// A Siglent export.
pub fn siglent(s: &Synthetic) -> String {
    let mut t = format!(
        "Record Length,Analog:{}\nSample Rate,{:.1}\nVertical Scale,CH1: 0.5,CH2: 0.5\n\
         Second,Volt,Volt\n",
        s.time.len(),
        1.0 / s.increment
    );
    for k in 0..s.time.len() {
        t += &format!("{:.9e},{:.5},{:.5}\n", s.time[k], s.drive[k], s.response[k]);
    }
    t
}

/// A plain CSV with a header row.
pub fn plain(s: &Synthetic) -> String {
    let mut t = "time_s,u_V,uc_V\n".to_string();
    for k in 0..s.time.len() {
        t += &format!(
            "{:.9e},{:.6e},{:.6e}\n",
            s.time[k], s.drive[k], s.response[k]
        );
    }
    t
}

/// A table of 45 amplitudes of [`truth`]: 15 frequencies (w from 0.3 to 1.6) at three drive
/// levels (β = 1.6, 2.5, 4), from the exact steady state with 0.5 % Gaussian noise; with
/// `direction` a column `direction` (all `up`).
pub fn amplitude_table(rng: &mut Rng, direction: bool) -> String {
    let e = truth();
    let f0 = e.scales().unwrap().f0();
    let mut text = if direction {
        "freq_Hz,U_V,response_V,direction\n".to_string()
    } else {
        "# the paper's Fig. 4, three drive levels\nfreq_Hz,U_V,response_V\n".to_string()
    };
    for beta in [1.6, 2.5, 4.0] {
        for k in 0..15 {
            let w = 0.3 + 1.3 * k as f64 / 14.0;
            let s = e
                .clone()
                .with_w(w)
                .unwrap()
                .with_beta(beta)
                .unwrap()
                .steady()
                .unwrap();
            let a = s.amplitude() * TRUE_UT * (1.0 + 0.005 * rng.gauss());
            text += &format!("{:.4},{:.5},{:.6}", w * f0, beta * TRUE_UT, a);
            text += if direction { ",up\n" } else { "\n" };
        }
    }
    text
}

/// Whether ngspice runs. When it does not: fails if `STICKSLIP_REQUIRE_NGSPICE` is set (and
/// not `0`), else says on standard error, past the harness's capture, why the test is skipped.
pub fn ngspice_available(test: &str) -> bool {
    if let Ok(out) = Command::new("ngspice").arg("--version").output() {
        if out.status.success() {
            return true;
        }
    }
    let required = std::env::var("STICKSLIP_REQUIRE_NGSPICE").is_ok_and(|v| v != "0");
    assert!(
        !required,
        "{test}: ngspice not found on PATH, and STICKSLIP_REQUIRE_NGSPICE is set"
    );
    let _ = writeln!(
        std::io::stderr(),
        "SKIPPED {test}: ngspice not found on PATH (apt-get install ngspice to run it; \
         STICKSLIP_REQUIRE_NGSPICE=1 makes this a failure)"
    );
    false
}

/// A fresh directory `name` under the target's temporary directory.
pub fn work_dir(name: &str) -> PathBuf {
    let dir = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join(name);
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).expect("create the work directory");
    dir
}

/// Run ngspice in batch mode on `netlist` (whose `wrdata` writes `out.txt`) in `dir`, and
/// return the rows it wrote (t in s, the first saved vector).
pub fn run_ngspice(dir: &Path, netlist: &str) -> Vec<(f64, f64)> {
    std::fs::write(dir.join("circuit.cir"), netlist).unwrap();
    let out = Command::new("ngspice")
        .args(["-b", "circuit.cir"])
        .current_dir(dir)
        .output()
        .expect("ngspice runs");
    assert!(
        out.status.success(),
        "ngspice failed: {}",
        String::from_utf8_lossy(&out.stderr)
    );
    let data = std::fs::read_to_string(dir.join("out.txt")).expect("ngspice wrote its output");
    data.lines()
        .filter(|l| !l.trim().is_empty())
        .map(|l| {
            let v: Vec<f64> = l
                .split_whitespace()
                .map(|x| x.parse().expect("a number"))
                .collect();
            (v[0], v[1])
        })
        .collect()
}

/// Linear interpolation of ngspice's points at `t` (with its steps at most 1/1000 of a
/// period the error is below 10⁻⁵ of the amplitude, far under one 8-bit step).
pub fn interpolate(points: &[(f64, f64)], t: f64) -> f64 {
    let k = points
        .partition_point(|p| p.0 <= t)
        .clamp(1, points.len() - 1);
    let ((t0, y0), (t1, y1)) = (points[k - 1], points[k]);
    y0 + (y1 - y0) * (t - t0) / (t1 - t0)
}
