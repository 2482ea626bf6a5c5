//! Scope records of circuits that stickslip never saw, made by ngspice: a series RLC circuit
//! (L = 10 mH, C = 47 nF, R = 120 Ω) with two anti-parallel diodes of three kinds (a
//! 1N914-like silicon diode, a BAT54-like Schottky diode, a red LED), driven at several
//! frequencies and amplitudes and exported in the five scope formats the readers know.
//!
//! ngspice runs once, in `crates/stickslip/tests/ngspice_traces.rs` (`STICKSLIP_BLESS=1`
//! writes the traces; without it the test makes them again and compares): its u_C, free of
//! noise, at every sample time of every record, is committed under `data/ngspice/` (one value
//! a line, 8 significant digits). Everything else is made here from those traces, for any
//! seed: the drive (an exact sine), an 8-bit converter over 10 divisions at the smallest
//! 1-2-5 volts per division that holds the channel within 4 divisions, one code of Gaussian
//! noise, a DC offset of the u_C channel, and the scope's CSV. So a test draws hundreds of
//! noisy records of the same ngspice truth without ngspice.

use crate::{keysight, plain, rigol, siglent, tektronix, Rng, Synthetic};
use std::f64::consts::{PI, TAU};
use stickslip::physical::Circuit;
use stickslip::DiodePair;

/// The circuit's inductance (H).
pub const INDUCTANCE: f64 = 10e-3;
/// The circuit's capacitance (F).
pub const CAPACITANCE: f64 = 47e-9;
/// The circuit's resistance (Ω), without the diodes.
pub const RESISTANCE: f64 = 120.0;
/// The temperature of the simulation and of the diode cards (°C).
pub const TEMPERATURE: f64 = 27.0;
/// Drive periods simulated from rest before a record's trigger.
pub const SETTLE_PERIODS: f64 = 60.0;
/// The 8-bit converter's codes per division (256 codes over 10 divisions).
pub const CODES_PER_DIV: f64 = 25.6;

/// The export format of a record.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Scope {
    /// A Rigol CSV ([`rigol`]).
    Rigol,
    /// A Keysight InfiniiVision CSV ([`keysight`]).
    Keysight,
    /// A Tektronix pair of files, one per channel ([`tektronix`]), given as `a.csv+b.csv`.
    Tektronix,
    /// A Siglent CSV ([`siglent`]).
    Siglent,
    /// A plain CSV with a header row ([`plain`]).
    Plain,
}

/// One record of a bench: the drive, the scope's sampling and the u_C channel's offset.
#[derive(Debug, Clone, Copy)]
pub struct RecordSpec {
    /// The record's name (the file name without `.csv`; a Tektronix pair adds `-ch1`, `-ch2`).
    pub name: &'static str,
    /// The export format.
    pub scope: Scope,
    /// The drive's frequency (Hz).
    pub freq_hz: f64,
    /// The drive's amplitude (V, peak).
    pub drive_v: f64,
    /// Samples per channel.
    pub samples: usize,
    /// The sampling interval (s).
    pub interval_s: f64,
    /// The DC offset of the u_C channel (V).
    pub offset_v: f64,
}

impl RecordSpec {
    /// The scope's time axis: 0 at the trigger (the drive's rising zero crossing), in the
    /// middle of the record (s).
    pub fn axis(&self) -> Vec<f64> {
        (0..self.samples)
            .map(|k| (k as f64 - 0.5 * self.samples as f64) * self.interval_s)
            .collect()
    }

    /// Time of the trigger since the start of the simulation (s).
    pub fn trigger_s(&self) -> f64 {
        SETTLE_PERIODS / self.freq_hz + 0.5 * self.samples as f64 * self.interval_s
    }

    /// The drive's phase φ at t = 0 of the simulation, so that U cos(Ω t + φ) rises through
    /// zero at the trigger (Ω t + φ = −π/2 there).
    pub fn phase(&self) -> f64 {
        (-0.5 * PI - TAU * self.freq_hz * self.trigger_s()).rem_euclid(TAU)
    }

    /// The drive channel at the scope's times (V): the generator's exact sine.
    pub fn drive(&self) -> Vec<f64> {
        let (omega, phi, trigger) = (TAU * self.freq_hz, self.phase(), self.trigger_s());
        self.axis()
            .iter()
            .map(|&t| self.drive_v * (omega * (t + trigger) + phi).cos())
            .collect()
    }
}

/// A diode pair on the bench, and the records taken with it.
#[derive(Debug, Clone, Copy)]
pub struct Bench {
    /// Its name (the directory of its traces under `data/ngspice/`).
    pub name: &'static str,
    /// The diode card's saturation current (A).
    pub is: f64,
    /// The card's emission coefficient.
    pub n: f64,
    /// The card's series resistance (Ω).
    pub rs: f64,
    /// The records.
    pub records: &'static [RecordSpec],
}

const fn spec(
    name: &'static str,
    scope: Scope,
    freq_hz: f64,
    drive_v: f64,
    samples: usize,
    interval_s: f64,
    offset_v: f64,
) -> RecordSpec {
    RecordSpec {
        name,
        scope,
        freq_hz,
        drive_v,
        samples,
        interval_s,
        offset_v,
    }
}

/// A 1N914-like silicon diode (the PSpice card's IS = 2.52 nA, N = 1.752, RS = 0.568 Ω; its
/// capacitance, recombination and breakdown terms left out), five records in the five
/// formats, 1200 to 2800 samples: stick-slip at 2 kHz, sliding from 5 to 11 kHz (f0 = 7.34 kHz).
pub const D1N914: Bench = Bench {
    name: "1n914",
    is: 2.52e-9,
    n: 1.752,
    rs: 0.568,
    records: &[
        spec("rigol-2kHz", Scope::Rigol, 2000.0, 2.0, 1200, 1e-6, 0.025),
        spec(
            "keysight-5kHz",
            Scope::Keysight,
            5000.0,
            1.5,
            2000,
            0.4e-6,
            -0.015,
        ),
        spec(
            "tek-7kHz",
            Scope::Tektronix,
            7000.0,
            1.0,
            2500,
            0.2e-6,
            0.01,
        ),
        spec(
            "siglent-8kHz",
            Scope::Siglent,
            8000.0,
            2.5,
            1400,
            0.25e-6,
            0.03,
        ),
        spec(
            "plain-11kHz",
            Scope::Plain,
            11000.0,
            3.0,
            2800,
            0.1e-6,
            -0.02,
        ),
    ],
};

/// A BAT54-like Schottky diode (IS = 100 nA, N = 1.1, RS = 2.5 Ω: about 0.26 V at 1 mA; not
/// a vendor's card), three records.
pub const BAT54: Bench = Bench {
    name: "bat54",
    is: 1e-7,
    n: 1.1,
    rs: 2.5,
    records: &[
        spec("rigol-3kHz", Scope::Rigol, 3000.0, 0.8, 1200, 1e-6, 0.01),
        spec(
            "keysight-7kHz",
            Scope::Keysight,
            7000.0,
            0.6,
            1400,
            0.4e-6,
            -0.01,
        ),
        spec(
            "plain-10kHz",
            Scope::Plain,
            10000.0,
            1.2,
            1200,
            0.25e-6,
            0.005,
        ),
    ],
};

/// A red LED (IS = 93.5 pA, N = 3.5, RS = 2.8 Ω: 1.47 V at 1 mA, 1.70 V at 10 mA, with the
/// large emission coefficient of LED cards; not a vendor's card), three records. (A card of
/// I_s = 10⁻¹⁷ A and n = 2 stops ngspice: with the diodes blocking, the node between the coil
/// and the diodes hangs on GMIN and the time step falls below 10⁻¹⁹ s.)
pub const LED: Bench = Bench {
    name: "led-red",
    is: 9.35e-11,
    n: 3.5,
    rs: 2.8,
    records: &[
        spec("rigol-3kHz", Scope::Rigol, 3000.0, 4.0, 1200, 1e-6, 0.05),
        spec(
            "keysight-7kHz",
            Scope::Keysight,
            7000.0,
            3.0,
            1400,
            0.4e-6,
            -0.04,
        ),
        spec(
            "siglent-10kHz",
            Scope::Siglent,
            10000.0,
            5.0,
            1200,
            0.25e-6,
            0.02,
        ),
    ],
};

impl Bench {
    /// The diode pair of the card.
    pub fn pair(&self) -> DiodePair {
        DiodePair::new(self.is, self.n, self.rs, TEMPERATURE).expect("a valid card")
    }

    /// The circuit with these diodes (Shockley's law).
    pub fn circuit(&self) -> Circuit {
        Circuit {
            inductance: INDUCTANCE,
            capacitance: CAPACITANCE,
            resistance: RESISTANCE,
            ..Circuit::paper()
        }
        .with_shockley(self.pair())
    }

    /// Where the traces of record `spec` are committed, relative to the testkit's directory.
    pub fn trace_path(&self, spec: &RecordSpec) -> String {
        format!("data/ngspice/{}/{}.txt", self.name, spec.name)
    }

    /// The committed noise-free u_C of record `i` (V), one value per sample.
    ///
    /// # Panics
    /// When the file is missing or malformed (`ngspice_traces` with `STICKSLIP_BLESS=1`
    /// writes it).
    pub fn trace(&self, i: usize) -> Vec<f64> {
        let spec = &self.records[i];
        let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join(self.trace_path(spec));
        let text = std::fs::read_to_string(&path)
            .unwrap_or_else(|e| panic!("{}: {e} (ngspice_traces writes it)", path.display()));
        let values: Vec<f64> = text
            .lines()
            .filter(|l| !l.starts_with('#') && !l.trim().is_empty())
            .map(|l| l.trim().parse().expect("a number"))
            .collect();
        assert_eq!(values.len(), spec.samples, "{}", path.display());
        values
    }

    /// Record `i` drawn with noise from `rng`: the files of its export (one; two for a
    /// Tektronix pair), each (name, text).
    pub fn export(&self, i: usize, rng: &mut Rng) -> Vec<(String, String)> {
        self.export_with_noise(i, rng, 1.0)
    }

    /// Record `i` as [`Bench::export`] makes it, with `noise` codes (RMS) of Gaussian noise
    /// instead of one; 0: the converter's rounding alone (and no draw from `rng`).
    pub fn export_with_noise(&self, i: usize, rng: &mut Rng, noise: f64) -> Vec<(String, String)> {
        let spec = &self.records[i];
        let drive = spec.drive();
        let response: Vec<f64> = self.trace(i).iter().map(|u| u + spec.offset_v).collect();
        let drive = noisy_codes(&drive, volts_per_div(&drive), rng, noise);
        let response = noisy_codes(&response, volts_per_div(&response), rng, noise);
        let start = -0.5 * spec.samples as f64 * spec.interval_s;
        let record = Synthetic::new(drive, response, start, spec.interval_s);
        let name = |suffix: &str| format!("{}{suffix}.csv", spec.name);
        match spec.scope {
            Scope::Rigol => vec![(name(""), rigol(&record))],
            Scope::Keysight => vec![(name(""), keysight(&record))],
            Scope::Siglent => vec![(name(""), siglent(&record))],
            Scope::Plain => vec![(name(""), plain(&record))],
            Scope::Tektronix => vec![
                (name("-ch1"), tektronix(&record, 1)),
                (name("-ch2"), tektronix(&record, 2)),
            ],
        }
    }
}

/// The smallest 1-2-5 volts per division that keeps `values` within 4 of the screen's 5
/// divisions either side of zero.
pub fn volts_per_div(values: &[f64]) -> f64 {
    let peak = values.iter().fold(0.0f64, |m, v| m.max(v.abs()));
    let mut decade = 1e-3;
    loop {
        for step in [1.0, 2.0, 5.0] {
            if peak <= 4.0 * step * decade {
                return step * decade;
            }
        }
        decade *= 10.0;
    }
}

/// The 8-bit codes of `values` at `v_per_div` with one code of Gaussian noise, in volts.
///
/// # Panics
/// When a value is off the converter's range (a wrong setting: the scope would clip it).
pub fn codes(values: &[f64], v_per_div: f64, rng: &mut Rng) -> Vec<f64> {
    noisy_codes(values, v_per_div, rng, 1.0)
}

/// [`codes`] with `noise` codes (RMS) of Gaussian noise; 0: rounding alone.
fn noisy_codes(values: &[f64], v_per_div: f64, rng: &mut Rng, noise: f64) -> Vec<f64> {
    let q = v_per_div / CODES_PER_DIV;
    values
        .iter()
        .map(|&x| {
            let dither = if noise > 0.0 {
                noise * rng.gauss()
            } else {
                0.0
            };
            let code = (x / q + dither).round();
            assert!(
                (-128.0..=127.0).contains(&code),
                "{x} V is off the screen at {v_per_div} V/div"
            );
            code * q
        })
        .collect()
}

impl Bench {
    /// Every record drawn with noise from `Rng(seed)` and read back as the program reads it
    /// (a Tektronix pair merged), prepared for fitting with the default channels: (the
    /// name as `--data` gives it, the measurement).
    pub fn measurements(&self, seed: u64) -> Vec<(String, stickslip::measure::Measurement)> {
        self.measurements_with_noise(seed, 1.0)
    }

    /// [`Bench::measurements`] with `noise` codes (RMS) of Gaussian noise instead of one; 0:
    /// the noise-free traces, rounded to the converter's codes.
    pub fn measurements_with_noise(
        &self,
        seed: u64,
        noise: f64,
    ) -> Vec<(String, stickslip::measure::Measurement)> {
        use stickslip::measure::{read_scope, Measurement, Record};
        let mut rng = Rng(seed);
        (0..self.records.len())
            .map(|i| {
                let files = self.export_with_noise(i, &mut rng, noise);
                let parts: Vec<Record> = files
                    .iter()
                    .map(|(name, text)| read_scope(text, name).expect("the export reads"))
                    .collect();
                let record = Record::merge(parts).expect("the parts merge");
                let m = Measurement::new(&record, None, None).expect("a record to fit");
                (record.file.clone(), m)
            })
            .collect()
    }
}
