//! 2×2 real matrices acting on perturbations (δy, δy') of the state, and their eigenvalues.

use serde::{Deserialize, Serialize};
use std::ops::Mul;

/// A real 2×2 matrix acting on perturbations (δy, δy') of the state (rows and columns in
/// that order): a state-transition, saltation, Jacobian or monodromy matrix. Dimensionless
/// (y and y' share the unit of the kinetic friction force, τ is dimensionless).
///
/// `Matrix2([[a, b], [c, d]])` maps (δy, δy') to (a δy + b δy', c δy + d δy').
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Matrix2(pub [[f64; 2]; 2]);

impl Matrix2 {
    /// The identity.
    pub const IDENTITY: Matrix2 = Matrix2([[1.0, 0.0], [0.0, 1.0]]);

    /// The diagonal matrix diag(a, d).
    pub const fn diagonal(a: f64, d: f64) -> Self {
        Matrix2([[a, 0.0], [0.0, d]])
    }

    /// The matrix applied to the perturbation `[δy, δy']`.
    pub fn apply(&self, x: [f64; 2]) -> [f64; 2] {
        let m = &self.0;
        [
            m[0][0] * x[0] + m[0][1] * x[1],
            m[1][0] * x[0] + m[1][1] * x[1],
        ]
    }

    /// The determinant.
    pub fn det(&self) -> f64 {
        let m = &self.0;
        m[0][0] * m[1][1] - m[0][1] * m[1][0]
    }

    /// The trace.
    pub fn trace(&self) -> f64 {
        self.0[0][0] + self.0[1][1]
    }

    /// The Frobenius norm √(Σ m_ij²).
    pub fn norm(&self) -> f64 {
        let m = &self.0;
        (m[0][0] * m[0][0] + m[0][1] * m[0][1] + m[1][0] * m[1][0] + m[1][1] * m[1][1]).sqrt()
    }

    /// The largest |m_ij|.
    pub fn max_abs(&self) -> f64 {
        self.0
            .iter()
            .flatten()
            .fold(0.0f64, |acc, x| acc.max(x.abs()))
    }

    /// Whether every entry is finite.
    pub fn is_finite(&self) -> bool {
        self.0.iter().flatten().all(|x| x.is_finite())
    }

    /// Every entry times `factor`.
    pub fn scaled(&self, factor: f64) -> Self {
        let m = &self.0;
        Matrix2([
            [m[0][0] * factor, m[0][1] * factor],
            [m[1][0] * factor, m[1][1] * factor],
        ])
    }

    /// The matrix minus the identity.
    pub fn minus_identity(&self) -> Self {
        let m = &self.0;
        Matrix2([[m[0][0] - 1.0, m[0][1]], [m[1][0], m[1][1] - 1.0]])
    }

    /// The eigenvalues, the one of larger modulus first (a complex pair when the discriminant
    /// is negative). For the monodromy matrix of a periodic orbit these are its Floquet
    /// multipliers.
    ///
    /// The discriminant is formed as ((a − d)/2)² + bc, which does not cancel when the
    /// eigenvalues are far apart, and the smaller real eigenvalue is det/λ₁.
    pub fn eigenvalues(&self) -> [Multiplier; 2] {
        let [[a, b], [c, d]] = self.0;
        let half_trace = 0.5 * (a + d);
        let half_gap = 0.5 * (a - d);
        let disc = half_gap * half_gap + b * c;
        if disc >= 0.0 {
            let root = disc.sqrt();
            let big = if half_trace >= 0.0 {
                half_trace + root
            } else {
                half_trace - root
            };
            let small = if big != 0.0 { self.det() / big } else { 0.0 };
            let (first, second) = if big.abs() >= small.abs() {
                (big, small)
            } else {
                (small, big)
            };
            [Multiplier::real(first), Multiplier::real(second)]
        } else {
            let im = (-disc).sqrt();
            [
                Multiplier { re: half_trace, im },
                Multiplier {
                    re: half_trace,
                    im: -im,
                },
            ]
        }
    }

    /// A solution of `self · x = rhs`: the exact one when the matrix is well conditioned
    /// (|det| > `1e-14`·(largest entry)²), else the minimum-norm least-squares one, from the
    /// pseudo-inverse. `None` when the matrix is zero or not finite.
    pub fn solve(&self, rhs: [f64; 2]) -> Option<[f64; 2]> {
        let [[a, b], [c, d]] = self.0;
        let scale = self.max_abs();
        if !(scale > 0.0) || !self.is_finite() {
            return None;
        }
        let det = self.det();
        if det.abs() > 1e-14 * scale * scale {
            return Some([
                (d * rhs[0] - b * rhs[1]) / det,
                (a * rhs[1] - c * rhs[0]) / det,
            ]);
        }
        // Numerically rank one, A ≈ σ u vᵀ: the pseudo-inverse is Aᵀ/‖A‖²_F.
        let frobenius2 = a * a + b * b + c * c + d * d;
        Some([
            (a * rhs[0] + c * rhs[1]) / frobenius2,
            (b * rhs[0] + d * rhs[1]) / frobenius2,
        ])
    }
}

impl Mul for Matrix2 {
    type Output = Matrix2;

    /// The product `self · rhs` (apply `rhs` first).
    fn mul(self, rhs: Matrix2) -> Matrix2 {
        let (a, b) = (&self.0, &rhs.0);
        Matrix2([
            [
                a[0][0] * b[0][0] + a[0][1] * b[1][0],
                a[0][0] * b[0][1] + a[0][1] * b[1][1],
            ],
            [
                a[1][0] * b[0][0] + a[1][1] * b[1][0],
                a[1][0] * b[0][1] + a[1][1] * b[1][1],
            ],
        ])
    }
}

/// A complex eigenvalue re + i·im (a Floquet multiplier when it belongs to a monodromy
/// matrix). Dimensionless.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Multiplier {
    /// Real part.
    pub re: f64,
    /// Imaginary part (0 for a real eigenvalue).
    pub im: f64,
}

impl Multiplier {
    /// The real number x.
    pub const fn real(x: f64) -> Self {
        Self { re: x, im: 0.0 }
    }

    /// The modulus |μ|.
    pub fn modulus(&self) -> f64 {
        self.re.hypot(self.im)
    }

    /// Whether the eigenvalue is real.
    pub fn is_real(&self) -> bool {
        self.im == 0.0
    }

    /// The argument arg μ in radians, from −π to π (0 for a positive real multiplier, π for
    /// a negative one): the turn of a perturbation per orbit.
    pub fn argument(&self) -> f64 {
        self.im.atan2(self.re)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn eigenvalues_of_known_matrices() {
        // Rotation by 0.3 scaled by 2: 2e^{±0.3i}.
        let (s, c) = 0.3f64.sin_cos();
        let e = Matrix2([[2.0 * c, -2.0 * s], [2.0 * s, 2.0 * c]]).eigenvalues();
        assert!((e[0].re - 2.0 * c).abs() < 1e-15 && (e[0].im.abs() - 2.0 * s).abs() < 1e-15);
        assert_eq!(e[0].im, -e[1].im);
        // Rank one: tr and 0.
        let e = Matrix2([[3.0, 0.0], [-1.5, 0.0]]).eigenvalues();
        assert_eq!((e[0], e[1]), (Multiplier::real(3.0), Multiplier::real(0.0)));
        // Widely separated real eigenvalues keep their small one to full relative accuracy.
        let e = Matrix2([[1e8, 1.0], [0.0, 1e-8]]).eigenvalues();
        assert_eq!(e[0].re, 1e8);
        assert!((e[1].re - 1e-8).abs() < 1e-23);
        // Negative dominant eigenvalue comes first.
        let e = Matrix2::diagonal(0.5, -4.0).eigenvalues();
        assert_eq!((e[0].re, e[1].re), (-4.0, 0.5));
    }

    #[test]
    fn solve_exact_and_least_squares() {
        let m = Matrix2([[2.0, 1.0], [1.0, 3.0]]);
        let x = m.solve([3.0, 5.0]).unwrap();
        assert!((x[0] - 0.8).abs() < 1e-15 && (x[1] - 1.4).abs() < 1e-15);
        // Rank one: the minimum-norm least-squares solution of [[1, 1], [1, 1]] x = [2, 0]
        // is (0.5, 0.5).
        let x = Matrix2([[1.0, 1.0], [1.0, 1.0]]).solve([2.0, 0.0]).unwrap();
        assert!((x[0] - 0.5).abs() < 1e-15 && (x[1] - 0.5).abs() < 1e-15);
        assert!(Matrix2([[0.0; 2]; 2]).solve([1.0, 0.0]).is_none());
    }

    #[test]
    fn product_applies_the_right_factor_first() {
        let a = Matrix2([[1.0, 2.0], [3.0, 4.0]]);
        let b = Matrix2([[0.0, 1.0], [1.0, 0.0]]);
        let x = [5.0, -7.0];
        assert_eq!((a * b).apply(x), a.apply(b.apply(x)));
        assert_eq!((a * b).det(), a.det() * b.det());
    }
}
