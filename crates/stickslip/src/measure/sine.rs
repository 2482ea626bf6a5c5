//! The drive's sine fit over whole periods.

use super::error::MeasureError;
use crate::fit::linalg::solve_spd;
use serde::{Deserialize, Serialize};
use std::f64::consts::TAU;

/// A sine fitted to a channel: `offset + amplitude·cos(2π·frequency·s + phase)` with s the
/// time since the record's first sample (s).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct SineFit {
    /// Frequency (Hz).
    pub frequency: f64,
    /// Amplitude (peak, in the channel's unit, V).
    pub amplitude: f64,
    /// Phase at the record's first sample (radians, in (−π, π]).
    pub phase: f64,
    /// DC offset (V).
    pub offset: f64,
    /// Whole drive periods in the record: the fit used the samples of these periods from the
    /// first sample on.
    pub periods: usize,
    /// RMS of the residual of the samples used (V).
    pub rms_residual: f64,
}

impl SineFit {
    /// The fitted sine at time `s` since the first sample.
    pub fn value(&self, s: f64) -> f64 {
        self.offset + self.amplitude * (TAU * self.frequency * s + self.phase).cos()
    }
}

/// Times of the crossings of `level` in one direction, with a hysteresis band of ±`band`
/// so that noise near the level does not count as crossings; each time interpolated
/// linearly at the last crossing of the level before leaving the band.
fn crossings(s: &[f64], x: &[f64], used: &[bool], level: f64, band: f64, up: bool) -> Vec<f64> {
    let sign = if up { 1.0 } else { -1.0 };
    let mut out = Vec::new();
    let mut armed = false;
    let mut last_cross: Option<f64> = None;
    let mut previous: Option<usize> = None;
    for i in 0..x.len() {
        if !used[i] {
            continue;
        }
        let v = sign * (x[i] - level);
        if let Some(p) = previous {
            let u = sign * (x[p] - level);
            if u < 0.0 && v >= 0.0 {
                last_cross = Some(s[p] + (s[i] - s[p]) * (-u) / (v - u));
            }
        }
        if v < -band {
            armed = true;
            last_cross = None;
        } else if v > band && armed {
            if let Some(t) = last_cross {
                out.push(t);
            }
            armed = false;
        }
        previous = Some(i);
    }
    out
}

/// Fit `offset + a cos(Ω s) + b sin(Ω s)` (linear) at fixed Ω to the used samples with
/// s < `end`; returns (a, b, offset).
fn linear(s: &[f64], x: &[f64], used: &[bool], omega: f64, end: f64) -> Option<[f64; 3]> {
    let mut m = [0.0; 9];
    let mut r = [0.0; 3];
    for i in 0..x.len() {
        if !used[i] || s[i] > end {
            continue;
        }
        let basis = [(omega * s[i]).cos(), (omega * s[i]).sin(), 1.0];
        for j in 0..3 {
            r[j] += basis[j] * x[i];
            for k in 0..3 {
                m[j * 3 + k] += basis[j] * basis[k];
            }
        }
    }
    let v = solve_spd(&m, 3, &r)?;
    Some([v[0], v[1], v[2]])
}

/// The phase (radians) of the fundamental of `x` at the frequency of `drive`, over the
/// drive's whole periods (a linear fit of offset, cos and sin): `None` without samples.
pub(crate) fn phase_at(s: &[f64], x: &[f64], used: &[bool], drive: &SineFit) -> Option<f64> {
    let end = drive.periods as f64 / drive.frequency * (1.0 + 1e-9);
    let [a, b, _] = linear(s, x, used, TAU * drive.frequency, end)?;
    (a.hypot(b) > 0.0).then(|| (-b).atan2(a))
}

/// The four-parameter sine fit (IEEE 1057's) of a channel over its whole periods.
///
/// `s`: times since the first sample (s), increasing; `used`: the samples to use (not
/// clipped). The frequency is first estimated from the crossings of the channel's mid-range
/// (hysteresis ±20 % of the half range), then the offset, amplitude, phase and frequency
/// are fitted by Gauss–Newton to the samples of the whole periods from the first sample.
///
/// # Errors
/// Less than one whole period between two crossings in the same direction ("shorter than
/// one drive period"), or a fit that does not converge.
pub fn fit_sine(
    file: &str,
    channel: &str,
    s: &[f64],
    x: &[f64],
    used: &[bool],
) -> Result<SineFit, MeasureError> {
    let (lo, hi) = x
        .iter()
        .zip(used)
        .filter(|(_, &u)| u)
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), (&v, _)| {
            (lo.min(v), hi.max(v))
        });
    let short = || {
        MeasureError::file(
            file,
            format!(
                "the record is shorter than one drive period: channel {channel} does not \
                 cross its mid-range twice in the same direction"
            ),
        )
    };
    if !(hi > lo) {
        return Err(short());
    }
    let mid = 0.5 * (hi + lo);
    let band = 0.2 * 0.5 * (hi - lo);
    let period = [true, false]
        .iter()
        .filter_map(|&up| {
            let c = crossings(s, x, used, mid, band, up);
            (c.len() >= 2).then(|| ((c[c.len() - 1] - c[0]) / (c.len() - 1) as f64, c.len()))
        })
        .max_by_key(|&(_, n)| n)
        .map(|(p, _)| p)
        .ok_or_else(short)?;
    let duration = s[s.len() - 1];
    let mut frequency = 1.0 / period;
    let mut periods = (duration * frequency + 1e-9).floor() as usize;
    if periods == 0 {
        return Err(short());
    }
    let fail =
        |what: &str| MeasureError::file(file, format!("the sine fit of channel {channel} {what}"));
    let mut end = periods as f64 / frequency * (1.0 + 1e-9);
    let [mut a, mut b, mut c] =
        linear(s, x, used, TAU * frequency, end).ok_or_else(|| fail("has a singular system"))?;
    // Gauss–Newton on a fixed window of samples, then the window of the whole periods at the
    // frequency found, until the window stays the same. (Within one pass the samples must not
    // change: a sample that the window's end passes as the frequency moves would make the
    // iteration jump between the fits with and without it.)
    let within = |end: f64| (0..x.len()).filter(|&i| used[i] && s[i] <= end).count();
    let mut windows: Vec<usize> = Vec::new();
    // Set when the window alternated and the shorter was taken: its fit is the last.
    let mut last = false;
    loop {
        let mut converged = false;
        for _ in 0..50 {
            let omega = TAU * frequency;
            let mut m = [0.0; 16];
            let mut r = [0.0; 4];
            for i in 0..x.len() {
                if !used[i] || s[i] > end {
                    continue;
                }
                let (sn, cs) = (omega * s[i]).sin_cos();
                let model = a * cs + b * sn + c;
                let basis = [cs, sn, 1.0, s[i] * (-a * sn + b * cs)];
                let e = x[i] - model;
                for j in 0..4 {
                    r[j] += basis[j] * e;
                    for k in 0..4 {
                        m[j * 4 + k] += basis[j] * basis[k];
                    }
                }
            }
            let d = solve_spd(&m, 4, &r).ok_or_else(|| fail("has a singular system"))?;
            a += d[0];
            b += d[1];
            c += d[2];
            let new_frequency = (omega + d[3]) / TAU;
            if !(new_frequency > 0.0) {
                return Err(fail("lost its frequency"));
            }
            let step = (new_frequency - frequency).abs() / frequency;
            frequency = new_frequency;
            if step < 1e-13 {
                converged = true;
                break;
            }
        }
        if !converged {
            return Err(fail("did not converge in 50 iterations"));
        }
        if last {
            break;
        }
        let whole = (duration * frequency + 1e-9).floor() as usize;
        if whole > 0 {
            periods = whole;
        }
        let next = periods as f64 / frequency * (1.0 + 1e-9);
        let (now, then) = (within(end), within(next));
        if now == then {
            break;
        }
        // A window that alternates (its end within the frequency's uncertainty of a sample)
        // keeps the shorter of the two (fitted once more on it, then done: the fit on the
        // shorter window may point to the longer again); a window that keeps moving is
        // refused.
        if windows.contains(&then) {
            if then < now {
                end = next;
                last = true;
                continue;
            }
            break;
        }
        if windows.len() >= 4 {
            return Err(fail("did not settle on its whole periods"));
        }
        windows.push(now);
        end = next;
    }
    let amplitude = a.hypot(b);
    let phase = (-b).atan2(a);
    let fit = SineFit {
        frequency,
        amplitude,
        phase,
        offset: c,
        periods,
        rms_residual: 0.0,
    };
    let (sum, count) = (0..x.len())
        .filter(|&i| used[i] && s[i] <= end)
        .fold((0.0, 0usize), |(sum, n), i| {
            (sum + (x[i] - fit.value(s[i])).powi(2), n + 1)
        });
    Ok(SineFit {
        rms_residual: (sum / count.max(1) as f64).sqrt(),
        ..fit
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::test_rng::TestRng;

    #[test]
    fn recovers_a_noisy_quantised_sine() {
        let mut rng = TestRng::new(7);
        let (f, a, phase, offset) = (1234.5, 1.7, 2.2, 0.05);
        let n = 1200;
        let dt = 3.3 / f / n as f64;
        let q = 4.0 / 255.0;
        let s: Vec<f64> = (0..n).map(|k| k as f64 * dt).collect();
        let x: Vec<f64> = s
            .iter()
            .map(|&t| {
                let noise = (rng.next() - 0.5) * 2.0 * q;
                ((offset + a * (TAU * f * t + phase).cos() + noise) / q).round() * q
            })
            .collect();
        let used = vec![true; n];
        let fit = fit_sine("x.csv", "CH1", &s, &x, &used).unwrap();
        assert_eq!(fit.periods, 3);
        assert!((fit.frequency / f - 1.0).abs() < 2e-4, "{fit:?}");
        assert!((fit.amplitude / a - 1.0).abs() < 2e-3, "{fit:?}");
        assert!((fit.phase - phase).abs() < 3e-3, "{fit:?}");
        assert!((fit.offset - offset).abs() < 3e-3, "{fit:?}");
    }

    #[test]
    fn less_than_a_period_is_refused() {
        let s: Vec<f64> = (0..100).map(|k| k as f64 * 1e-5).collect();
        let x: Vec<f64> = s.iter().map(|&t| (TAU * 700.0 * t).cos()).collect();
        let err = fit_sine("x.csv", "CH1", &s, &x, &[true; 100]).unwrap_err();
        assert!(
            err.to_string().contains("shorter than one drive period"),
            "{err}"
        );
    }
}
