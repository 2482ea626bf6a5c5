//! Records for the tests of stickslip, made by the library's exact solver: a seeded random
//! source, the circuit the fit tests measure, its steady state sampled like an oscilloscope,
//! quantised to a screen's steps with noise, and written in the CSV formats the readers take
//! (Rigol, Keysight, Tektronix, Siglent, a plain CSV), with a table of amplitudes.
//!
//! A dev-dependency of the library, the CLI and the lab; no I/O.

use std::f64::consts::TAU;
use stickslip::experiment::Experiment;
use stickslip::physical::{Circuit, Diode, PwlDiode, Scales};
use stickslip::solver::sample_at;
use stickslip::steady::SolverFactory;
use stickslip::DiodePair;

pub mod allowances;
pub mod belts;
pub mod differences;
pub mod ngspice;
pub mod oracle;

/// xorshift64 from a fixed seed, with Gaussian numbers by Box–Muller.
pub struct Rng(pub u64);

impl Rng {
    /// The next state of the sequence.
    pub fn next_u64(&mut self) -> u64 {
        self.0 ^= self.0 << 13;
        self.0 ^= self.0 >> 7;
        self.0 ^= self.0 << 17;
        self.0
    }

    /// Uniform in (0, 1).
    pub fn uniform(&mut self) -> f64 {
        ((self.next_u64() >> 11) as f64 + 0.5) / (1u64 << 53) as f64
    }

    /// Uniform in [-1/2, 1/2).
    pub fn centred(&mut self) -> f64 {
        (self.next_u64() >> 11) as f64 / (1u64 << 53) as f64 - 0.5
    }

    /// Standard normal.
    pub fn gauss(&mut self) -> f64 {
        let (u, v) = (self.uniform(), self.uniform());
        (-2.0 * u.ln()).sqrt() * (TAU * v).cos()
    }
}

/// The resistance (Ω) of the circuit the recovery tests synthesise their records with.
pub const TRUE_R: f64 = 80.0;
/// The diodes' turn-on voltage (V) of that circuit.
pub const TRUE_UT: f64 = 0.6;

/// The paper's L and C with resistance `r` (Ω) and PWL diodes of turn-on `ut` (V), R_D = 3 Ω.
pub fn circuit(r: f64, ut: f64) -> Experiment {
    Experiment::circuit(Circuit {
        resistance: r,
        diode: Diode::Pwl(PwlDiode {
            turn_on: ut,
            resistance: 3.0,
        }),
        ..Circuit::paper()
    })
    .unwrap()
}

/// The circuit of [`TRUE_R`] and [`TRUE_UT`].
pub fn truth() -> Experiment {
    circuit(TRUE_R, TRUE_UT)
}

/// The paper's circuit with two 1N4148 diodes (Shockley's law) at w = 0.95, β = 2.14.
pub fn paper_shockley() -> Experiment {
    Experiment::paper()
        .with_shockley(DiodePair::one_n4148())
        .unwrap()
        .with_w(0.95)
        .unwrap()
        .with_beta(2.14)
        .unwrap()
}

/// `e` driven at (w, β, φ).
pub fn driven(e: Experiment, w: f64, beta: f64, phi: f64) -> Experiment {
    e.with_w(w)
        .and_then(|e| e.with_beta(beta))
        .and_then(|e| e.with_phi(phi))
        .unwrap()
}

/// A steady state sampled: the drive (V or N) and the response (u_C in V, or the
/// displacement in m) at the instants `taus` (dimensionless time from the first sample).
pub struct Samples {
    /// The sampling instants, τ = ω0 t.
    pub taus: Vec<f64>,
    /// β·scale·cos(w τ + φ): the drive in physical units.
    pub drive: Vec<f64>,
    /// y·scale: the response in physical units.
    pub response: Vec<f64>,
    /// The experiment's scales.
    pub scales: Scales,
}

/// `n` samples `increment` seconds apart of the steady state of `e` (whose w and β are set),
/// from the final state of its steady-state search, by the exact solver.
pub fn sample_steady(e: &Experiment, n: usize, increment: f64) -> Samples {
    let (w, beta, phi) = (e.w().unwrap(), e.beta().unwrap(), e.phi());
    let steady = e.steady().unwrap();
    let scales = e.scales().unwrap();
    let params = e.params().unwrap();
    let mut solver = e.factory().make(params, steady.final_state()).unwrap();
    let taus: Vec<f64> = (0..n)
        .map(|k| k as f64 * increment * scales.omega0)
        .collect();
    let samples = sample_at(solver.as_mut(), &taus, |_| {}).unwrap();
    let drive = taus
        .iter()
        .map(|&tau| beta * scales.force * (w * tau + phi).cos())
        .collect();
    let response = samples.iter().map(|s| s.y * scales.position).collect();
    Samples {
        taus,
        drive,
        response,
        scales,
    }
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

/// A two-channel record: times (s), drive, response; the time axis starts at `start` and
/// steps by `increment` (s).
pub struct Synthetic {
    /// The sampling times (s).
    pub time: Vec<f64>,
    /// Channel 1: the drive.
    pub drive: Vec<f64>,
    /// Channel 2: the response.
    pub response: Vec<f64>,
    /// The first time (s).
    pub start: f64,
    /// The sampling interval (s).
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
    let e = driven(truth(), w, beta, phi);
    let n = 1200;
    let period = TAU / (w * e.scales().unwrap().omega0);
    let increment = 3.4 * period / n as f64;
    let start = -0.5 * n as f64 * increment;
    let s = sample_steady(&e, n, increment);
    let response: Vec<f64> = s.response.iter().map(|&r| r + offset).collect();
    let drive = quantise(&s.drive, 256.0, noise, rng);
    let response = quantise(&response, 256.0, noise, rng);
    Synthetic::new(drive, response, start, increment)
}

/// Each channel of `drive` and `response` (of peaks `peaks`) rounded to steps of 2.5/256 of
/// its peak after up to a step of uniform noise, drawn from `rng` in turn for the drive and
/// the response of each sample.
pub fn round_to_steps(
    drive: &[f64],
    response: &[f64],
    peaks: (f64, f64),
    rng: &mut Rng,
) -> (Vec<f64>, Vec<f64>) {
    let mut q = |v: f64, peak: f64| {
        let step = 2.5 * peak / 256.0;
        ((v + 2.0 * step * rng.centred()) / step).round() * step
    };
    drive
        .iter()
        .zip(response)
        .map(|(&d, &r)| (q(d, peaks.0), q(r, peaks.1)))
        .unzip()
}

/// The formats [`stepped_record`] writes.
pub enum Format {
    /// [`rigol`].
    Rigol,
    /// [`keysight`].
    Keysight,
    /// [`timed`] with this header.
    Timed(&'static str),
}

/// A record of `n` samples over `periods` drive periods of the steady state of `e` (whose w
/// and β are set) from time 0, each channel rounded by [`round_to_steps`] (the drive's peak
/// its amplitude, the response's its largest value) with noise from `Rng(seed)`, in `format`.
pub fn stepped_record(e: &Experiment, n: usize, periods: f64, seed: u64, format: Format) -> String {
    let w = e.w().unwrap();
    let dt = periods * TAU / (w * e.scales().unwrap().omega0) / n as f64;
    let s = sample_steady(e, n, dt);
    let amplitude = e.beta().unwrap() * s.scales.force;
    let peak = s.response.iter().fold(0.0f64, |a, r| a.max(r.abs()));
    let (drive, response) =
        round_to_steps(&s.drive, &s.response, (amplitude, peak), &mut Rng(seed));
    let record = Synthetic::new(drive, response, 0.0, dt);
    match format {
        Format::Rigol => rigol(&record),
        Format::Keysight => keysight(&record),
        Format::Timed(header) => timed(&record, header),
    }
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

/// `header`, then a row of time, drive and response a sample.
pub fn timed(s: &Synthetic, header: &str) -> String {
    let mut t = header.to_string();
    for k in 0..s.time.len() {
        t += &format!(
            "{:.9e},{:.6e},{:.6e}\n",
            s.time[k], s.drive[k], s.response[k]
        );
    }
    t
}

/// A Keysight InfiniiVision export: a time column.
pub fn keysight(s: &Synthetic) -> String {
    timed(s, "x-axis,1,2\nsecond,Volt,Volt\n")
}

/// A plain CSV with a header row.
pub fn plain(s: &Synthetic) -> String {
    timed(s, "time_s,u_V,uc_V\n")
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
