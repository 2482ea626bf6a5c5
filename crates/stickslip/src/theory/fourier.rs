//! Exact Fourier coefficients of a closed-form segment, by integration by parts.
//!
//! If y solves y'' + 2ζy' + y = f(t) on [0, L], then for any frequency Ω, integrating
//! (y'' + 2ζy' + y)·e^{−iΩt} by parts twice gives
//!
//! ```text
//! (1 − Ω² + 2iζΩ) ∫₀ᴸ y e^{−iΩt} dt = ∫₀ᴸ f e^{−iΩt} dt − [ (y' + (2ζ + iΩ) y) e^{−iΩt} ]₀ᴸ
//! ```
//!
//! so the integral of the closed form needs only its end states and the integral of the
//! forcing: no sampling, no quadrature, and one formula for every damping regime.

use rustfft::num_complex::Complex64;
use serde::{Deserialize, Serialize};

/// One harmonic of a periodic motion: the term `amplitude·cos(order·ψ + phase)` of its
/// Fourier series, where ψ is a reference phase stated by whoever returns it.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Harmonic {
    /// Order k of the harmonic (1 for the fundamental).
    pub order: u32,
    /// Amplitude A_k ≥ 0, in the units of y.
    pub amplitude: f64,
    /// Phase φ_k in radians, in (−π, π].
    pub phase: f64,
}

/// `∫₀ᴸ y e^{−iΩt} dt` for y'' + 2ζy' + y = f on [0, L], from the end states (y, y') at 0 and
/// L and `forcing` = `∫₀ᴸ f e^{−iΩt} dt`. Infinite when 1 − Ω² + 2iζΩ = 0 (ζ = 0, Ω = 1:
/// the free oscillation itself).
pub(crate) fn segment_integral(
    zeta: f64,
    omega: f64,
    length: f64,
    start: (f64, f64),
    end: (f64, f64),
    forcing: Complex64,
) -> Complex64 {
    let i = Complex64::i();
    let e_end = Complex64::from_polar(1.0, -omega * length);
    let k = 2.0 * zeta + i * omega;
    let boundary = (end.1 + k * end.0) * e_end - (start.1 + k * start.0);
    let response = Complex64::new((1.0 - omega) * (1.0 + omega), 2.0 * zeta * omega);
    (forcing - boundary) / response
}

/// Reduce an angle to (−π, π].
pub(crate) fn wrap_phase(phase: f64) -> f64 {
    use std::f64::consts::{PI, TAU};
    let r = phase.rem_euclid(TAU);
    if r > PI {
        r - TAU
    } else {
        r
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::linear::{Damping, LinearSegment};

    /// Composite Simpson on a fine grid is an independent (slow) check of the formula in
    /// every damping regime, with a drive and a constant force.
    #[test]
    fn matches_quadrature_of_the_closed_form() {
        for &zeta in &[0.0, 0.1, 1.0, 2.5] {
            for &(w, omega) in &[(0.7, 0.7), (0.7, 2.1), (1.3, 0.4)] {
                let (beta, theta, c, length) = (1.9, 0.6, 1.0, 4.3);
                let seg = LinearSegment::new(Damping::new(zeta), w, beta, theta, c, -0.4, 0.3);
                let n = 20_000;
                let h = length / n as f64;
                let f = |t: f64| {
                    let (y, _) = seg.state(t);
                    y * Complex64::from_polar(1.0, -omega * t)
                };
                let g = |t: f64| {
                    (beta * (w * t + theta).cos() - c) * Complex64::from_polar(1.0, -omega * t)
                };
                let simpson = |fun: &dyn Fn(f64) -> Complex64| {
                    let mut s = fun(0.0) + fun(length);
                    for j in 1..n {
                        s += fun(j as f64 * h) * if j % 2 == 1 { 4.0 } else { 2.0 };
                    }
                    s * h / 3.0
                };
                let quad = simpson(&f);
                let forcing = simpson(&g);
                let exact = segment_integral(
                    zeta,
                    omega,
                    length,
                    seg.state(0.0),
                    seg.state(length),
                    forcing,
                );
                assert!(
                    (exact - quad).norm() < 1e-10 * (1.0 + quad.norm()),
                    "zeta {zeta} w {w} omega {omega}: {exact} vs {quad}"
                );
            }
        }
    }

    #[test]
    fn wraps_into_half_open_interval() {
        use std::f64::consts::PI;
        assert_eq!(wrap_phase(PI), PI);
        assert!((wrap_phase(-PI) - PI).abs() < 1e-15);
        assert!((wrap_phase(3.0 * PI / 2.0) + PI / 2.0).abs() < 1e-15);
    }
}
