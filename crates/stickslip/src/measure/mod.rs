//! Measurements: oscilloscope exports and tables of measured amplitudes, read from text the
//! caller hands over (the library opens no files).
//!
//! **Scope exports** ([`read_scope`]) are detected from their header ([`detect`]):
//!
//! | format | header | checked against |
//! |---|---|---|
//! | Rigol | `X,CH1,CH2,Start,Increment,` then `Sequence,Volt,Volt,<start>,<increment>`, then `index,v1,v2,` | the layout of the DS1000Z series' CSV export as other readers of it parse it |
//! | Tektronix | `Record Length,<n>,,<t>,<v>` and further `key,value,,t,v` rows (`Sample Interval`, `Trigger Point`, `Source`, `Vertical Units` …): one file per channel, merged by [`Record::merge`] | TDS1000/TDS2000-series CSV (five columns) |
//! | Keysight InfiniiVision | `x-axis,1,2` then `second,Volt,Volt` | the InfiniiVision 2000/3000 X-series user's guides (CSV file structure) |
//! | Siglent | `Record Length,Analog:<n>`, `Sample Rate`, `Vertical Scale,CH1: …` …, then `Second,Volt` (or `Second,Value`) | an SDS1104X-E export as shown by a published converter of such files |
//! | plain | a row of column names, one of them `t`, `time`, `time_s`, `time (s)`, `second` or `seconds` (or `time (ms)`, `t (µs)`, `t_ns`); the others are channels (a unit in brackets, `CH1(V)`, is read) | — |
//!
//! No published description of a UNI-T CSV export (the paper's scope) was found: a UNI-T
//! file is read when its header names a time column as the plain format asks (a time column
//! may carry its unit: `time (ms)`, `t (µs)`, `t_ns`). Values such as `-0.00e+00` and
//! trailing commas are normal; every value must be a finite number and the time must
//! increase, or the error names the line.
//!
//! **Files from any desk**: fields separated by commas, semicolons or tabs (the first of `;`,
//! tab, `,` on the first line, or a spreadsheet's `sep=;` line), quoted or not; a decimal
//! comma (`-3,5e-03`) is read in a file that writes no number with a decimal point, and
//! thousands separators (`"1,500.25"`) in one that writes no decimal comma. What cannot be
//! read unambiguously is refused with its cause: a file with both decimal points and decimal
//! commas, a number that reads either way (`1,500`) with no other number telling which, a
//! row with more fields than its header (decimal commas between fields separated by commas),
//! an empty file. The front ends decode a file's bytes with
//! [`decode`]: UTF-8, UTF-16 with its byte-order mark, or Windows-1252 (a spreadsheet's `µs`
//! in a header); a binary file is refused as such.
//!
//! **What a record says of itself** ([`Record`], [`Channel`]): the mean sample interval; per
//! channel the vertical resolution (the smallest step between two distinct values) and the
//! clipped samples (runs of equal values at the channel's extreme longer than a smooth peak
//! stays within one resolution step: three times N·√(2q/A)/π samples for N samples per
//! period, q the resolution and A half the range; at least four; entered or left steeply, as
//! a flat stop of u_C is not).
//!
//! **A record for fitting** ([`Measurement`]): the drive and response channels picked by
//! name (default: the first channel is the drive, the second u_C); the drive's sine fitted
//! over its whole periods ([`fit_sine`]: frequency, amplitude, phase, offset, periods); the
//! response's samples that are not clipped; the noise of the response estimated from its
//! second differences.
//!
//! **Amplitude tables** ([`read_amplitudes`]): columns `freq_Hz`, `U_V`, `response_V`,
//! optionally `direction` (`up`/`down`), `A1_V`, `A3_V` ([`AMPLITUDE_COLUMNS`]); an unknown
//! column is refused.

mod error;
mod record;
mod scope;
mod sine;
mod table;
mod text;

pub use error::MeasureError;
pub use record::{Channel, Record, ScopeFormat, MIN_SAMPLES};
pub use scope::{detect, read_scope};
pub use sine::{fit_sine, SineFit};
pub use table::{read_amplitudes, AmplitudeRow, AmplitudeTable, Direction, AMPLITUDE_COLUMNS};
pub use text::decode;

use serde::{Deserialize, Serialize};

/// Smallest fraction of a channel's samples that must be left after clipping.
pub const MIN_UNCLIPPED_FRACTION: f64 = 0.1;

/// How far the drive channel may be from a sine: the RMS of its sine fit's residual beyond
/// its noise, √(rms² − σ²), as a fraction of its amplitude. A generator's sine leaves well
/// under 1 % (its distortion and the scope's); a triangle wave leaves 8.5 %, a square wave
/// 34 %, and u_C leaves several per cent wherever the diodes shape it (stick-slip, a knee).
pub const SINE_TOLERANCE: f64 = 0.03;

/// How far the response may seem to lead the drive, as the sine of the lag: its fundamental
/// must lag the drive's by ψ with sin ψ ≥ −0.05 (a circuit that dissipates lags by 0 < ψ < π;
/// the margin allows for a skew between the channels where ψ is near 0 or π, at the ends of
/// the frequency range).
pub const LEAD_TOLERANCE: f64 = 0.05;

/// The part of a channel that its sine fit does not explain beyond the noise σ (see
/// [`SINE_TOLERANCE`]).
fn non_sine(fit: &SineFit, sigma: f64) -> f64 {
    (fit.rms_residual.powi(2) - sigma * sigma).max(0.0).sqrt()
        / fit.amplitude.max(f64::MIN_POSITIVE)
}

/// A waveform record prepared for fitting: the drive's sine fit and the response's samples.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Measurement {
    /// The record's file name.
    pub file: String,
    /// The drive channel's name.
    pub drive_channel: String,
    /// The response (u_C) channel's name.
    pub response_channel: String,
    /// The drive's sine fit.
    pub drive: SineFit,
    /// Times since the record's first sample (s).
    pub time: Vec<f64>,
    /// The drive channel (V).
    pub drive_values: Vec<f64>,
    /// The response u_C (V).
    pub response: Vec<f64>,
    /// Which response samples are used (not clipped in either channel).
    pub used: Vec<bool>,
    /// Samples left out as clipped (in either channel).
    pub clipped: usize,
    /// The response's vertical resolution (V).
    pub resolution: Option<f64>,
    /// The response's noise (V, standard deviation), estimated from the data alone: the mean
    /// square of the second differences x(i−1) − 2x(i) + x(i+1) of used samples over 6 (white
    /// noise gives 6σ²; a smooth waveform sampled many times per period adds little).
    pub noise: f64,
    /// The drive channel's noise (V), estimated in the same way.
    pub drive_noise: f64,
    /// The drive channel's unit as the file gives it (`V` when it says nothing; a mechanical
    /// record's force in `N`). The fields above named in volts are in this unit.
    #[serde(default = "volt")]
    pub drive_unit: String,
    /// The response channel's unit as the file gives it (`V`; a mechanical record's
    /// displacement in `m`).
    #[serde(default = "volt")]
    pub response_unit: String,
}

fn volt() -> String {
    "V".into()
}

impl Measurement {
    /// Prepare `record` for fitting, with the drive and response channels named by `drive`
    /// and `response` (see [`Record::channel_index`]; defaults: the first and the second
    /// channel).
    ///
    /// # Errors
    /// A missing channel, a channel clipped (or constant) in more than 90 % of its samples, a
    /// record shorter than one drive period, a drive channel that is not a sine
    /// ([`SINE_TOLERANCE`]; when the response channel is one, the error's
    /// [`MeasureError::swap`] says which channel to take as the drive).
    pub fn new(
        record: &Record,
        drive: Option<&str>,
        response: Option<&str>,
    ) -> Result<Self, MeasureError> {
        let drive_index = match drive {
            Some(name) => record.channel_index(name)?,
            None => 0,
        };
        let response_index = match response {
            Some(name) => record.channel_index(name)?,
            None => {
                if record.channels.len() < 2 {
                    return Err(MeasureError::file(
                        &record.file,
                        format!(
                            "the record has one channel ({}): the drive channel or u_C is \
                             missing (pick them by name)",
                            record.channels[0].name
                        ),
                    ));
                }
                usize::from(drive_index == 0)
            }
        };
        if drive_index == response_index {
            return Err(MeasureError::file(
                &record.file,
                format!(
                    "the drive and u_C are the same channel {}",
                    record.channels[drive_index].name
                ),
            ));
        }
        for &c in &[drive_index, response_index] {
            let channel = &record.channels[c];
            let left = channel.values.len() - channel.clipped_count();
            if channel.resolution.is_none()
                || (left as f64) < MIN_UNCLIPPED_FRACTION * channel.values.len() as f64
            {
                return Err(MeasureError::file(
                    &record.file,
                    format!(
                        "channel {} is clipped or constant in {} of its {} samples: nothing \
                         left to fit",
                        channel.name,
                        if channel.resolution.is_none() {
                            channel.values.len()
                        } else {
                            channel.clipped_count()
                        },
                        channel.values.len()
                    ),
                ));
            }
        }
        let d = &record.channels[drive_index];
        let r = &record.channels[response_index];
        let t0 = record.time[0];
        let time: Vec<f64> = record.time.iter().map(|&t| t - t0).collect();
        let sine_of = |c: &Channel| {
            let unclipped: Vec<bool> = c.clipped.iter().map(|c| !c).collect();
            let fit = fit_sine(&record.file, &c.name, &time, &c.values, &unclipped)?;
            let excess = non_sine(&fit, noise(&c.values, &unclipped));
            Ok::<_, MeasureError>((fit, excess))
        };
        // The drive must be the generator's sine; a drive channel that is not, beside a
        // response that is, is the channels the wrong way round.
        let (sine, excess) = match sine_of(d) {
            Ok(fit) => fit,
            Err(e) => match sine_of(r) {
                Ok((_, other)) if other <= SINE_TOLERANCE => {
                    return Err(MeasureError::swapped(
                        &record.file,
                        format!(
                            "the drive channel {} is not a sine ({}), and {} is: the channels \
                             look swapped",
                            d.name, e.message, r.name
                        ),
                        &r.name,
                        &d.name,
                    ))
                }
                _ => return Err(e),
            },
        };
        if excess > SINE_TOLERANCE {
            let percent = |x: f64| format!("{:.1} %", 100.0 * x);
            return Err(match sine_of(r) {
                Ok((_, other)) if other <= SINE_TOLERANCE => MeasureError::swapped(
                    &record.file,
                    format!(
                        "the drive channel {} is not a sine (its sine fit leaves {} of its \
                         amplitude beyond the noise), and {} is ({}): the channels look swapped",
                        d.name,
                        percent(excess),
                        r.name,
                        percent(other)
                    ),
                    &r.name,
                    &d.name,
                ),
                _ => MeasureError::file(
                    &record.file,
                    format!(
                        "the drive channel {} is not a sine: its sine fit leaves {} of its \
                         amplitude beyond the noise (at most {} is a generator's sine); pick \
                         the channel of the generator's sine as the drive",
                        d.name,
                        percent(excess),
                        percent(SINE_TOLERANCE)
                    ),
                ),
            });
        }
        // Power flows from the generator into the circuit (or the oscillator): u_C's
        // fundamental lags the drive by ψ in (0, π), so that the current's in-phase part,
        // ∝ sin ψ, is positive. A response that leads the drive would give power back: the
        // channels the wrong way round.
        let unclipped: Vec<bool> = r.clipped.iter().map(|c| !c).collect();
        if let Some(phase) = sine::phase_at(&time, &r.values, &unclipped, &sine) {
            let power = (sine.phase - phase).sin();
            if power < -LEAD_TOLERANCE {
                return Err(MeasureError::swapped(
                    &record.file,
                    format!(
                        "{} leads the drive {} by {:.0}°: power would flow from the circuit \
                         into the generator, so the channels look swapped (the drive is the \
                         channel that u_C lags)",
                        r.name,
                        d.name,
                        (phase - sine.phase)
                            .rem_euclid(std::f64::consts::TAU)
                            .to_degrees()
                    ),
                    &r.name,
                    &d.name,
                ));
            }
        }
        let used: Vec<bool> = d
            .clipped
            .iter()
            .zip(&r.clipped)
            .map(|(a, b)| !a && !b)
            .collect();
        let clipped = used.iter().filter(|&&u| !u).count();
        let (response_noise, drive_noise) = (noise(&r.values, &used), noise(&d.values, &used));
        Ok(Self {
            file: record.file.clone(),
            drive_channel: d.name.clone(),
            response_channel: r.name.clone(),
            drive: sine,
            time,
            drive_values: d.values.clone(),
            response: r.values.clone(),
            used,
            clipped,
            resolution: r.resolution,
            noise: response_noise,
            drive_noise,
            drive_unit: d.unit.clone(),
            response_unit: r.unit.clone(),
        })
    }

    /// The number of samples used.
    pub fn used_count(&self) -> usize {
        self.used.iter().filter(|&&u| u).count()
    }
}

/// The noise of a channel from the second differences of its used samples (see
/// [`Measurement::noise`]).
pub(crate) fn noise(values: &[f64], used: &[bool]) -> f64 {
    let (sum, count) = (1..values.len() - 1)
        .filter(|&i| used[i - 1] && used[i] && used[i + 1])
        .fold((0.0, 0usize), |(s, n), i| {
            let d2 = values[i - 1] - 2.0 * values[i] + values[i + 1];
            (s + d2 * d2, n + 1)
        });
    (sum / (6.0 * count.max(1) as f64)).sqrt()
}
