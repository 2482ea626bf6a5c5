//! Levenberg–Marquardt for small dense problems (a few to a few tens of unknowns, thousands
//! of residuals).
//!
//! Written here rather than taken from a crate: the `levenberg-marquardt` crate (the
//! well-kept Rust implementation, a port of MINPACK's lmder) brings nalgebra and wants the
//! Jacobian as a nalgebra matrix behind its own problem trait; our problems need a step
//! that fails (a parameter leaving its physical range, a model that cannot be solved there)
//! to count as a rejected step, and the covariance (JᵀJ)⁻¹ at the solution for the error
//! bars, which it does not report. The algorithm is the textbook one (Marquardt's scaling
//! by diag(JᵀJ)) in 100 lines over [`super::linalg`].

use super::linalg::{cholesky, cholesky_inverse, cholesky_solve};

/// What a least-squares problem supplies: residuals and their Jacobian at a point.
pub(crate) trait Problem {
    /// The error of a point where the model cannot be evaluated.
    type Error;
    /// The residuals at `x`; `Ok(None)` when `x` lies outside the model's domain (a
    /// rejected step).
    fn residuals(&mut self, x: &[f64]) -> Result<Option<Vec<f64>>, Self::Error>;
    /// The Jacobian at `x` with residuals `r`, column by column (`columns[j][i]` =
    /// ∂r_i/∂x_j).
    fn jacobian(&mut self, x: &[f64], r: &[f64]) -> Result<Vec<Vec<f64>>, Self::Error>;
    /// Told after every iteration (`iteration` from 1, the sum of squares reached); an error
    /// stops the minimisation with it.
    fn iteration(&mut self, _iteration: usize, _sum_squares: f64) -> Result<(), Self::Error> {
        Ok(())
    }
}

/// Stopping rules.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Settings {
    pub max_iterations: usize,
    /// Converged when the sum of squares falls by less than this fraction in a step, or
    /// every step component is below this times (1 + |x|).
    pub tolerance: f64,
}

/// The solution.
pub(crate) struct Solution {
    pub x: Vec<f64>,
    pub residuals: Vec<f64>,
    pub sum_squares: f64,
    pub iterations: usize,
    pub converged: bool,
    /// (JᵀJ)⁻¹ at the solution (row-major), `None` when JᵀJ is singular.
    pub inverse_normal: Option<Vec<f64>>,
}

fn normal(columns: &[Vec<f64>], r: &[f64]) -> (Vec<f64>, Vec<f64>) {
    let n = columns.len();
    let mut a = vec![0.0; n * n];
    let mut g = vec![0.0; n];
    for i in 0..n {
        g[i] = columns[i].iter().zip(r).map(|(j, r)| j * r).sum();
        for k in 0..=i {
            let v: f64 = columns[i].iter().zip(&columns[k]).map(|(a, b)| a * b).sum();
            a[i * n + k] = v;
            a[k * n + i] = v;
        }
    }
    (a, g)
}

fn sum_squares(r: &[f64]) -> f64 {
    r.iter().map(|v| v * v).sum()
}

/// Minimise ½|r(x)|² from `x0`.
pub(crate) fn minimise<P: Problem>(
    problem: &mut P,
    x0: Vec<f64>,
    settings: Settings,
) -> Result<Option<Solution>, P::Error> {
    let n = x0.len();
    let mut x = x0;
    let Some(mut r) = problem.residuals(&x)? else {
        return Ok(None);
    };
    let mut ssr = sum_squares(&r);
    let mut lambda = 1e-3;
    let mut iterations = 0;
    let mut converged = false;
    let mut columns = problem.jacobian(&x, &r)?;
    while iterations < settings.max_iterations && !converged {
        iterations += 1;
        let (a, g) = normal(&columns, &r);
        let largest = (0..n).map(|i| a[i * n + i]).fold(0.0, f64::max);
        let mut accepted = false;
        for _ in 0..30 {
            let mut m = a.clone();
            for i in 0..n {
                m[i * n + i] += lambda * a[i * n + i].max(1e-12 * largest);
            }
            let Some(l) = cholesky(&m, n) else {
                lambda *= 4.0;
                continue;
            };
            let step = cholesky_solve(&l, n, &g.iter().map(|v| -v).collect::<Vec<_>>());
            let trial: Vec<f64> = x.iter().zip(&step).map(|(x, d)| x + d).collect();
            let small = step
                .iter()
                .zip(&x)
                .all(|(d, x)| d.abs() <= settings.tolerance * (1.0 + x.abs()));
            match problem.residuals(&trial)? {
                Some(rt) if sum_squares(&rt) <= ssr => {
                    let new = sum_squares(&rt);
                    converged = small || ssr - new <= settings.tolerance * ssr;
                    x = trial;
                    r = rt;
                    ssr = new;
                    lambda = (lambda / 3.0).max(1e-12);
                    accepted = true;
                    break;
                }
                _ => {
                    if small {
                        // No step of the size the tolerance resolves lowers the sum: a
                        // minimum to that tolerance.
                        converged = true;
                        break;
                    }
                    lambda *= 4.0;
                }
            }
        }
        problem.iteration(iterations, ssr)?;
        if !accepted && !converged {
            break;
        }
        columns = problem.jacobian(&x, &r)?;
    }
    let (a, _) = normal(&columns, &r);
    let inverse_normal = cholesky(&a, n).map(|l| cholesky_inverse(&l, n));
    Ok(Some(Solution {
        x,
        residuals: r,
        sum_squares: ssr,
        iterations,
        converged,
        inverse_normal,
    }))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Rosenbrock as least squares: r = (10(x1 − x0²), 1 − x0), minimum at (1, 1).
    struct Rosenbrock;

    impl Problem for Rosenbrock {
        type Error = ();
        fn residuals(&mut self, x: &[f64]) -> Result<Option<Vec<f64>>, ()> {
            Ok(Some(vec![10.0 * (x[1] - x[0] * x[0]), 1.0 - x[0]]))
        }
        fn jacobian(&mut self, x: &[f64], _: &[f64]) -> Result<Vec<Vec<f64>>, ()> {
            Ok(vec![vec![-20.0 * x[0], -1.0], vec![10.0, 0.0]])
        }
    }

    #[test]
    fn finds_the_rosenbrock_minimum() {
        let s = minimise(
            &mut Rosenbrock,
            vec![-1.2, 1.0],
            Settings {
                max_iterations: 200,
                tolerance: 1e-14,
            },
        )
        .unwrap()
        .unwrap();
        assert!(s.converged);
        assert!(
            (s.x[0] - 1.0).abs() < 1e-8 && (s.x[1] - 1.0).abs() < 1e-8,
            "{:?}",
            s.x
        );
    }
}
