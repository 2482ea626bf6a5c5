//! Harmonics of a periodic signal sampled over whole drive periods.
//!
//! With N samples per drive period over p whole periods (M = pN samples, N a power of two),
//! the real FFT `X_m = Σ_j y_j e^{−2πi jm/M}` has bin m at frequency m/p times the drive
//! frequency. Because the record spans whole periods of the motion no window is needed and
//! nothing leaks between bins; the only error is aliasing, which decays like 1/N³ for the
//! motion of this model (y'' jumps at every event, so the Fourier coefficients of y fall off
//! like 1/k³).
//!
//! Conventions: with ψ = wτ + φ the drive phase,
//!
//! ```text
//! y(τ) = A_0 + Σ_k A_k cos(k ψ + θ_k),
//! ```
//!
//! so A_k ≥ 0 is the amplitude of the k-th drive harmonic (bin kp) and θ_k ∈ (−π, π] its phase
//! relative to k times the drive phase. For the fundamental the lag behind the drive is −θ_1.
//! Bins that are not multiples of p are subharmonic content (only a motion whose period is
//! several drive periods has them).

use crate::error::{Error, Result};
use realfft::num_complex::Complex;
use realfft::RealFftPlanner;
use serde::{Deserialize, Serialize};
use std::f64::consts::PI;

/// One drive harmonic: amplitude and phase.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Harmonic {
    /// Order k ≥ 1 (multiple of the drive frequency).
    pub order: usize,
    /// Amplitude A_k ≥ 0, in the units of the signal.
    pub amplitude: f64,
    /// Phase θ_k in (−π, π] relative to k·ψ (see the module documentation).
    pub phase: f64,
}

/// Spectrum of a signal sampled over whole drive periods.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Spectrum {
    /// Samples per drive period N.
    pub samples_per_period: usize,
    /// Number of drive periods p covered by the samples.
    pub periods: usize,
    /// Mean value A_0.
    pub mean: f64,
    /// Drive harmonics k = 1, 2, … (even ones included; they vanish for a symmetric motion).
    pub harmonics: Vec<Harmonic>,
    /// Root-sum-square of the amplitudes of all bins that are not drive harmonics
    /// (`√Σ A_m²` over m not a multiple of p): zero unless the motion repeats only after
    /// several drive periods.
    pub subharmonic: f64,
    /// Mean square of the samples, (1/M) Σ y_j².
    pub mean_square: f64,
    /// The same from the spectrum, (|X_0|² + 2 Σ_{0<m<M/2} |X_m|² + |X_{M/2}|²)/M²; equal to
    /// [`Spectrum::mean_square`] up to rounding (Parseval).
    pub spectral_mean_square: f64,
}

/// Wrap an angle to (−π, π].
pub(crate) fn wrap(angle: f64) -> f64 {
    let a = angle.rem_euclid(2.0 * PI);
    if a > PI {
        a - 2.0 * PI
    } else {
        a
    }
}

impl Spectrum {
    /// Spectrum of `samples` taken at τ_j = τ_s + j·T/N, j = 0 … pN − 1, where the drive phase
    /// at τ_s is `phase_at_start` (mod 2π) and `periods` = p. Reports `harmonics` drive
    /// harmonics (fewer if N/2 is smaller).
    ///
    /// # Errors
    /// [`Error::InvalidParameter`] when `periods` is 0, the number of samples is not a
    /// multiple of `periods`, or the samples per period are not a power of two ≥ 4.
    pub fn from_samples(
        samples: &[f64],
        periods: usize,
        harmonics: usize,
        phase_at_start: f64,
    ) -> Result<Self> {
        if periods == 0 || !samples.len().is_multiple_of(periods) {
            return Err(Error::InvalidParameter {
                name: "periods",
                value: periods as f64,
                allowed: "must be >= 1 and divide the number of samples",
            });
        }
        let per_period = samples.len() / periods;
        if per_period < 4 || !per_period.is_power_of_two() {
            return Err(Error::InvalidParameter {
                name: "samples_per_period",
                value: per_period as f64,
                allowed: "must be a power of two >= 4",
            });
        }
        let m = samples.len();
        let mut planner = RealFftPlanner::<f64>::new();
        let fft = planner.plan_fft_forward(m);
        let mut input = samples.to_vec();
        let mut output = fft.make_output_vec();
        fft.process(&mut input, &mut output)
            .expect("buffer lengths come from the plan");
        let scale = 1.0 / m as f64;
        let power = |x: &Complex<f64>| (x.norm() * scale).powi(2);
        let half = m / 2;
        let mut spectral = power(&output[0]) + power(&output[half]);
        for x in &output[1..half] {
            spectral += 2.0 * power(x);
        }
        let mean_square = samples.iter().map(|y| y * y).sum::<f64>() * scale;

        let mut subharmonic = 0.0;
        for (bin, x) in output.iter().enumerate().take(half).skip(1) {
            if bin % periods != 0 {
                subharmonic += (2.0 * x.norm() * scale).powi(2);
            }
        }
        let top = harmonics.min(per_period / 2 - 1);
        let harmonics = (1..=top)
            .map(|k| {
                let x = output[k * periods];
                Harmonic {
                    order: k,
                    amplitude: 2.0 * x.norm() * scale,
                    phase: wrap(x.arg() - k as f64 * phase_at_start),
                }
            })
            .collect();
        Ok(Self {
            samples_per_period: per_period,
            periods,
            mean: output[0].re * scale,
            harmonics,
            subharmonic: subharmonic.sqrt(),
            mean_square,
            spectral_mean_square: spectral,
        })
    }

    /// Amplitude A_k of the k-th drive harmonic (0 for k = 0 means the mean; `None` past the
    /// computed harmonics).
    pub fn amplitude(&self, k: usize) -> Option<f64> {
        if k == 0 {
            Some(self.mean)
        } else {
            self.harmonics.get(k - 1).map(|h| h.amplitude)
        }
    }

    /// The harmonics of the derivative dy/dτ, exactly from those of y (the derivative of
    /// A cos(kψ + θ) is k·w·A cos(kψ + θ + π/2)); for the circuit that is the current, for the
    /// mechanical oscillator the velocity. `w` is the drive frequency.
    pub fn derivative(&self, w: f64) -> Vec<Harmonic> {
        self.harmonics
            .iter()
            .map(|h| Harmonic {
                order: h.order,
                amplitude: h.order as f64 * w * h.amplitude,
                phase: wrap(h.phase + 0.5 * PI),
            })
            .collect()
    }

    /// Lag of the fundamental behind the drive, −θ_1 in (−π, π] (None without a fundamental).
    pub fn phase_lag(&self) -> Option<f64> {
        self.harmonics
            .first()
            .filter(|h| h.amplitude > 0.0)
            .map(|h| wrap(-h.phase))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn recovers_a_trigonometric_polynomial() {
        // y = 0.3 + 2 cos(ψ − 0.4) + 0.5 cos(3ψ + 1.1) over 2 periods with φ = 0.7.
        let (n, p, phi) = (64usize, 2usize, 0.7);
        let samples: Vec<f64> = (0..n * p)
            .map(|j| {
                let psi = 2.0 * PI * j as f64 / n as f64 + phi;
                0.3 + 2.0 * (psi - 0.4).cos() + 0.5 * (3.0 * psi + 1.1).cos()
            })
            .collect();
        let s = Spectrum::from_samples(&samples, p, 5, phi).unwrap();
        assert!((s.mean - 0.3).abs() < 1e-14);
        assert!((s.harmonics[0].amplitude - 2.0).abs() < 1e-14);
        assert!((s.harmonics[0].phase + 0.4).abs() < 1e-14);
        assert!((s.phase_lag().unwrap() - 0.4).abs() < 1e-14);
        assert!(s.harmonics[1].amplitude < 1e-14);
        assert!((s.harmonics[2].amplitude - 0.5).abs() < 1e-14);
        assert!((s.harmonics[2].phase - 1.1).abs() < 1e-13);
        assert!(s.subharmonic < 1e-14);
        let parseval = 0.3f64.powi(2) + 2.0 + 0.125;
        assert!((s.mean_square - parseval).abs() < 1e-13);
        assert!((s.spectral_mean_square - parseval).abs() < 1e-13);
    }

    #[test]
    fn half_frequency_content_is_subharmonic() {
        let (n, p) = (32usize, 2usize);
        let samples: Vec<f64> = (0..n * p)
            .map(|j| {
                let psi = 2.0 * PI * j as f64 / n as f64;
                psi.cos() + 0.25 * (0.5 * psi).sin()
            })
            .collect();
        let s = Spectrum::from_samples(&samples, p, 3, 0.0).unwrap();
        assert!((s.subharmonic - 0.25).abs() < 1e-14);
        assert!((s.harmonics[0].amplitude - 1.0).abs() < 1e-14);
    }

    #[test]
    fn rejects_bad_lengths() {
        assert!(Spectrum::from_samples(&[0.0; 12], 1, 3, 0.0).is_err());
        assert!(Spectrum::from_samples(&[0.0; 16], 3, 3, 0.0).is_err());
        assert!(Spectrum::from_samples(&[0.0; 16], 0, 3, 0.0).is_err());
    }
}
