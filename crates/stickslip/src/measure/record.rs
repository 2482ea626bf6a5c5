//! A waveform record: sample times and channels, with what the readers measure of them.

use super::error::MeasureError;
use serde::{Deserialize, Serialize};

/// The export format a record was read from (detected from its header, see
/// [`crate::measure`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
#[non_exhaustive]
pub enum ScopeFormat {
    /// Rigol: `X,CH1,CH2,Start,Increment,` then `Sequence,Volt,Volt,<start>,<increment>`, then
    /// `index,v1,v2,` rows (time = start + index·increment).
    Rigol,
    /// Tektronix: one file per channel; `Record Length`, `Sample Interval`, `Trigger Point` …
    /// in the first two columns, time and value in the fourth and fifth.
    Tektronix,
    /// Keysight (Agilent) InfiniiVision: `x-axis,1,2` then `second,Volt,Volt`, then
    /// `time,v1,v2` rows.
    Keysight,
    /// Siglent: `Record Length,Analog:N` and further `key,value` lines, then `Second,Volt`
    /// (or `Second,Value`), then `time,value` rows.
    Siglent,
    /// Several single-channel records on the same time axis, merged
    /// ([`Record::merge`]), e.g. a Tektronix file per channel.
    Merged,
    /// A CSV file with a header row whose time column is named `t`, `time`, `time_s`,
    /// `time (s)`, `second` or `seconds` (or in ms, µs or ns: `time (µs)`, `t_ms`); every other
    /// column is a channel in volts.
    Plain,
}

impl ScopeFormat {
    /// The format's name: `rigol`, `tektronix`, `keysight`, `siglent`, `merged` or `plain`.
    pub fn label(self) -> &'static str {
        match self {
            ScopeFormat::Rigol => "rigol",
            ScopeFormat::Tektronix => "tektronix",
            ScopeFormat::Keysight => "keysight",
            ScopeFormat::Siglent => "siglent",
            ScopeFormat::Merged => "merged",
            ScopeFormat::Plain => "plain",
        }
    }
}

/// One channel of a record.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Channel {
    /// The channel's name in the file (`CH1`, `1`, `u_C` …).
    pub name: String,
    /// The unit of its values as the file says it (`V` when it says nothing).
    pub unit: String,
    /// The values, one per sample time.
    pub values: Vec<f64>,
    /// The scope's vertical resolution: the smallest step between two distinct values (in
    /// the channel's unit); `None` with fewer than two distinct values.
    pub resolution: Option<f64>,
    /// Whether each sample is clipped (part of a flat run at the channel's largest or
    /// smallest value, see [`crate::measure`]); clipped samples are left out of every fit.
    pub clipped: Vec<bool>,
}

impl Channel {
    /// A channel with its resolution and clipping measured.
    pub(crate) fn new(name: String, unit: String, values: Vec<f64>) -> Self {
        let resolution = resolution(&values);
        let clipped = clipped(&values, resolution);
        Self {
            name,
            unit,
            values,
            resolution,
            clipped,
        }
    }

    /// The number of clipped samples.
    pub fn clipped_count(&self) -> usize {
        self.clipped.iter().filter(|&&c| c).count()
    }

    /// Half the peak-to-peak of the samples that are not clipped (the unit of the channel).
    pub fn half_peak_to_peak(&self) -> f64 {
        let (lo, hi) = self
            .values
            .iter()
            .zip(&self.clipped)
            .filter(|(_, &c)| !c)
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), (&v, _)| {
                (lo.min(v), hi.max(v))
            });
        if lo <= hi {
            0.5 * (hi - lo)
        } else {
            0.0
        }
    }
}

/// A waveform record read from a scope export: times in seconds, channels in volts.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Record {
    /// The file's name, as the caller gave it.
    pub file: String,
    /// The format it was read from.
    pub format: ScopeFormat,
    /// Sample times in seconds, strictly increasing.
    pub time: Vec<f64>,
    /// The channels, in the file's order.
    pub channels: Vec<Channel>,
    /// The mean sample interval (s).
    pub sample_interval: f64,
    /// The header's `key, value` lines as the file gives them (scope model, scales …).
    pub metadata: Vec<(String, String)>,
}

/// Fewest samples a record may have.
pub const MIN_SAMPLES: usize = 16;

impl Record {
    /// A record from times and channels, checked: at least [`MIN_SAMPLES`] samples, times
    /// finite and strictly increasing (the line of the first fault is `lines[i]`).
    pub(crate) fn build(
        file: &str,
        format: ScopeFormat,
        time: Vec<f64>,
        lines: &[usize],
        channels: Vec<(String, String, Vec<f64>)>,
        metadata: Vec<(String, String)>,
    ) -> Result<Self, MeasureError> {
        if channels.is_empty() {
            return Err(MeasureError::file(file, "no channel of values"));
        }
        if time.len() < MIN_SAMPLES {
            return Err(MeasureError::file(
                file,
                format!(
                    "{} samples: a record needs at least {MIN_SAMPLES}",
                    time.len()
                ),
            ));
        }
        for i in 1..time.len() {
            if !(time[i] > time[i - 1]) {
                return Err(MeasureError::at(
                    file,
                    lines.get(i).copied().unwrap_or(0),
                    format!(
                        "the time {} s does not follow the time {} s before it: the time \
                         column must increase",
                        time[i],
                        time[i - 1]
                    ),
                ));
            }
        }
        let sample_interval = (time[time.len() - 1] - time[0]) / (time.len() - 1) as f64;
        let channels = channels
            .into_iter()
            .map(|(name, unit, values)| Channel::new(name, unit, values))
            .collect();
        Ok(Self {
            file: file.to_string(),
            format,
            time,
            channels,
            sample_interval,
            metadata,
        })
    }

    /// The number of samples.
    pub fn len(&self) -> usize {
        self.time.len()
    }

    /// Whether the record has no samples (never true for a record that was read).
    pub fn is_empty(&self) -> bool {
        self.time.is_empty()
    }

    /// The duration from the first to the last sample (s).
    pub fn duration(&self) -> f64 {
        self.time[self.time.len() - 1] - self.time[0]
    }

    /// The index of a channel named `name`: its name in the file (any case), `CHn`, or its
    /// 1-based position `n`.
    ///
    /// # Errors
    /// When no channel answers to the name, naming the channels there are.
    pub fn channel_index(&self, name: &str) -> Result<usize, MeasureError> {
        let wanted = name.trim();
        if let Some(i) = self
            .channels
            .iter()
            .position(|c| c.name.eq_ignore_ascii_case(wanted))
        {
            return Ok(i);
        }
        let digits = wanted
            .strip_prefix("CH")
            .or_else(|| wanted.strip_prefix("ch"))
            .or_else(|| wanted.strip_prefix("Ch"))
            .unwrap_or(wanted);
        if let Ok(n) = digits.parse::<usize>() {
            if (1..=self.channels.len()).contains(&n) {
                return Ok(n - 1);
            }
        }
        Err(MeasureError::file(
            &self.file,
            format!(
                "no channel {} (the record has {})",
                super::error::quote(wanted),
                self.channel_names()
            ),
        ))
    }

    fn channel_names(&self) -> String {
        self.channels
            .iter()
            .map(|c| c.name.as_str())
            .collect::<Vec<_>>()
            .join(", ")
    }

    /// Single-channel (or any) records on the same time axis merged into one, channels in
    /// the order given (a Tektronix export writes a file per channel). The times must agree
    /// to 10⁻⁶ of the sample interval.
    ///
    /// # Errors
    /// When `parts` is empty, or a part has another number of samples or other times than
    /// the first (naming its file).
    pub fn merge(parts: Vec<Record>) -> Result<Record, MeasureError> {
        let mut parts = parts.into_iter();
        let Some(mut first) = parts.next() else {
            return Err(MeasureError::file("(no file)", "no record to merge"));
        };
        let mut names = vec![first.file.clone()];
        for part in parts {
            if part.time.len() != first.time.len() {
                return Err(MeasureError::file(
                    &part.file,
                    format!(
                        "{} samples, but {} has {}: records merged into one must share their \
                         times",
                        part.time.len(),
                        first.file,
                        first.time.len()
                    ),
                ));
            }
            let tolerance = 1e-6 * first.sample_interval;
            if let Some(i) =
                (0..part.time.len()).find(|&i| (part.time[i] - first.time[i]).abs() > tolerance)
            {
                return Err(MeasureError::file(
                    &part.file,
                    format!(
                        "sample {} is at {} s, but in {} at {} s: records merged into one \
                         must share their times",
                        i + 1,
                        part.time[i],
                        first.file,
                        first.time[i]
                    ),
                ));
            }
            names.push(part.file.clone());
            first.channels.extend(part.channels);
            first.metadata.extend(part.metadata);
        }
        if names.len() > 1 {
            first.file = names.join("+");
            first.format = ScopeFormat::Merged;
        }
        Ok(first)
    }
}

/// The smallest step between two distinct values, ignoring differences below 10⁻⁹ of the
/// range (the rounding of printed decimals).
fn resolution(values: &[f64]) -> Option<f64> {
    let mut sorted: Vec<f64> = values.to_vec();
    sorted.sort_by(f64::total_cmp);
    let range = sorted.last()? - sorted.first()?;
    if !(range > 0.0) {
        return None;
    }
    sorted
        .windows(2)
        .map(|w| w[1] - w[0])
        .filter(|&d| d > 1e-9 * range)
        .min_by(f64::total_cmp)
}

/// Clipped samples: runs of samples within one resolution step of the channel's largest or
/// smallest value (the rail) that hold the rail itself longer than a smooth peak stays within
/// one step, entered or left steeply.
///
/// A scope reads a signal beyond its screen as the rail's code; with noise of a step or more
/// the samples of a clipped stretch fall one step below it now and then, so a run is every
/// sample within one step q of the rail, gaps of up to two samples (a noise dip of two steps)
/// joined, and the whole run is left out. A sine of amplitude A (half the range) sampled N
/// times per period stays within one step of its peak for about N·√(2q/A)/π samples; N is
/// taken from the number of times the channel crosses its mid-range. A run counts as clipped
/// when more than three times that many of its samples (and at least four, and at least a
/// third of the run) are at the rail itself (a smooth peak with noise touches its largest
/// value only now and then), and when the signal enters or leaves it steeply: the slope over
/// the three samples outside either end above a tenth of the largest slope 2πA/N of a sine of
/// that amplitude and period (q at most a 32nd of the range). A stop of the oscillator (u_C
/// constant while the current is zero, which a noise-free record shows as a flat run) starts
/// and ends with zero slope and is kept when the samples are dense enough to show it; in a
/// record without noise and with a few samples per stop's approach it can look clipped, and
/// its samples are then left out (which costs information but does not bias a fit). Records
/// with noise of a step or more, as a scope's are, show no flat stops.
fn clipped(values: &[f64], resolution: Option<f64>) -> Vec<bool> {
    let n = values.len();
    let mut mask = vec![false; n];
    let Some(q) = resolution else {
        return mask;
    };
    let (lo, hi) = values
        .iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), &v| {
            (lo.min(v), hi.max(v))
        });
    let amplitude = 0.5 * (hi - lo);
    let mean = 0.5 * (hi + lo);
    let crossings = values
        .windows(2)
        .filter(|w| (w[0] < mean) != (w[1] < mean))
        .count()
        .max(1);
    let per_period = 2.0 * n as f64 / crossings as f64;
    // A channel with fewer than 32 levels over its range (a square wave between two rails
    // shows hardly any level in between) is judged as if it had 32.
    let q = q.min(2.0 * amplitude / 32.0);
    let smooth = per_period * (2.0 * q / amplitude).sqrt() / std::f64::consts::PI;
    let longest = (3.0 * smooth).max(4.0);
    // A clipped run starts and ends with the signal still moving (it would go on past the
    // rail); a stop of u_C starts and ends with zero slope (u_C' = i/C and the current is
    // continuous). The slope over the three samples outside each end, against a tenth of the
    // largest slope of a sine of this amplitude and period.
    let steep = 0.1 * amplitude * std::f64::consts::TAU / per_period;
    let tolerance = 1e-9 * (hi - lo);
    for (rail, near) in [
        (
            hi,
            Box::new(|v: f64| v >= hi - q - tolerance) as Box<dyn Fn(f64) -> bool>,
        ),
        (lo, Box::new(|v: f64| v <= lo + q + tolerance)),
    ] {
        let mut i = 0;
        while i < n {
            if !near(values[i]) {
                i += 1;
                continue;
            }
            // The run from i: samples near the rail, gaps of up to two samples joined.
            let mut j = i + 1;
            let mut end = i + 1;
            while j < n {
                if near(values[j]) {
                    j += 1;
                    end = j;
                } else if j + 2 < n && (near(values[j + 1]) || near(values[j + 2])) && j - end < 2 {
                    j += 1;
                } else {
                    break;
                }
            }
            let at_rail = values[i..end].iter().filter(|&&v| v == rail).count();
            if at_rail as f64 > longest && 3 * at_rail >= end - i {
                let entry = (i >= 4).then(|| (values[i - 1] - values[i - 4]).abs() / 3.0);
                let exit = (end + 3 < n).then(|| (values[end + 3] - values[end]).abs() / 3.0);
                let slope = entry.into_iter().chain(exit).fold(0.0f64, f64::max);
                if slope > steep || (entry.is_none() && exit.is_none()) {
                    mask[i..end].iter_mut().for_each(|m| *m = true);
                }
            }
            i = end.max(i + 1);
        }
    }
    mask
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn resolution_is_the_smallest_step() {
        let v = [0.0, 0.04, 0.08, 0.04, -0.04, 0.0];
        assert!((resolution(&v).unwrap() - 0.04).abs() < 1e-15);
        assert_eq!(resolution(&[1.0, 1.0]), None);
    }

    #[test]
    fn a_flat_top_is_clipped_and_a_sine_peak_is_not() {
        let q = 2.0 / 255.0;
        let quantise = |x: f64| (x / q).round() * q;
        let sine: Vec<f64> = (0..1200)
            .map(|k| quantise((std::f64::consts::TAU * 3.0 * k as f64 / 1200.0).sin()))
            .collect();
        let c = Channel::new("CH1".into(), "V".into(), sine.clone());
        assert_eq!(c.clipped_count(), 0);
        let flat: Vec<f64> = sine.iter().map(|&x| x.min(quantise(0.8))).collect();
        let c = Channel::new("CH1".into(), "V".into(), flat);
        // Three tops, each the part of a period where sin > 0.8: 2·acos(0.8)/2π of 400.
        let expected = 3.0 * 400.0 * 2.0 * 0.8f64.acos() / std::f64::consts::TAU;
        assert!((c.clipped_count() as f64 - expected).abs() < 12.0);
    }

    /// A sine 1.3 times the screen's height, with one step of Gaussian noise before the
    /// converter clips it at its rails (codes −128 … 127): every sample whose signal lies
    /// beyond a rail is found (and the few within a step of it), and the same sine with noise
    /// inside the screen has none.
    #[test]
    fn clipping_with_noise_at_the_rail_is_found() {
        let mut rng = crate::test_rng::TestRng::new(11);
        let mut gauss = || {
            let (u, v) = (rng.next().max(1e-300), rng.next());
            (-2.0 * u.ln()).sqrt() * (std::f64::consts::TAU * v).cos()
        };
        let n = 2400;
        let signal: Vec<f64> = (0..n)
            .map(|k| 1.3 * 127.0 * (std::f64::consts::TAU * 4.0 * k as f64 / n as f64).sin())
            .collect();
        let codes: Vec<f64> = signal
            .iter()
            .map(|&x| (x + gauss()).round().clamp(-128.0, 127.0))
            .collect();
        let c = Channel::new("CH2".into(), "V".into(), codes);
        let beyond: Vec<usize> = (0..n)
            .filter(|&k| signal[k] >= 127.0 || signal[k] <= -128.0)
            .collect();
        let found = beyond.iter().filter(|&&k| c.clipped[k]).count();
        assert_eq!(
            found,
            beyond.len(),
            "{found} of {} clipped samples found",
            beyond.len()
        );
        let within = (0..n)
            .filter(|&k| c.clipped[k] && signal[k].abs() < 127.0 - 3.0)
            .count();
        assert_eq!(
            within, 0,
            "samples more than three steps inside the screen called clipped"
        );
        // Inside the screen, with the same noise: nothing clipped.
        let inside: Vec<f64> = signal
            .iter()
            .map(|&x| (0.7 * x + gauss()).round())
            .collect();
        assert_eq!(
            Channel::new("CH2".into(), "V".into(), inside).clipped_count(),
            0
        );
    }
}
