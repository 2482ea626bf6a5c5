//! (JᵀJ)⁻¹ at a solution, the error bars and correlations it gives, and the criteria that
//! compare fits.

use super::*;

/// (JᵀJ)⁻¹ at a solution, with the free values the records do not see left out (their rows
/// and columns NaN).
#[derive(Debug, Clone)]
pub(super) struct Covariance {
    /// (JᵀJ)⁻¹, row-major over every fitted value; NaN throughout when JᵀJ is singular
    /// beyond the unseen values.
    pub(super) inverse: Vec<f64>,
    /// Which free values the records do not see (a column of the Jacobian that is zero to
    /// 10⁻¹⁰ of the largest).
    pub(super) unseen: Vec<bool>,
    pub(super) n: usize,
    pub(super) free: usize,
}

impl Covariance {
    pub(super) fn of(solution: &lm::Solution, free: usize) -> Self {
        let n = solution.x.len();
        let a = &solution.normal;
        let largest = (0..n).map(|i| a[i * n + i]).fold(0.0f64, f64::max);
        let unseen: Vec<bool> = (0..free)
            .map(|k| !(a[k * n + k] > 1e-20 * largest))
            .collect();
        let mut m = a.clone();
        for k in (0..free).filter(|&k| unseen[k]) {
            for j in 0..n {
                m[k * n + j] = 0.0;
                m[j * n + k] = 0.0;
            }
            m[k * n + k] = 1.0;
        }
        let mut inverse = match linalg::cholesky(&m, n) {
            Some(l) => linalg::cholesky_inverse(&l, n),
            None => vec![f64::NAN; n * n],
        };
        for k in (0..free).filter(|&k| unseen[k]) {
            for j in 0..n {
                inverse[k * n + j] = f64::NAN;
                inverse[j * n + k] = f64::NAN;
            }
        }
        Self {
            inverse,
            unseen,
            n,
            free,
        }
    }

    /// The standard error of coordinate k with the residuals' variance `s2`.
    pub(super) fn sigma(&self, k: usize, s2: f64) -> f64 {
        (s2 * self.inverse[k * self.n + k]).abs().sqrt()
    }

    /// Where a restart begins: three standard errors from `x` along the direction the free
    /// values are least determined in (the covariance's largest eigenvector of their block,
    /// each value scaled by its standard error), the others moved as the linear model says
    /// they follow; `None` without a covariance.
    pub(super) fn restart(&self, x: &[f64], bounds: &[(f64, f64)]) -> Option<Vec<f64>> {
        let (n, free) = (self.n, self.free);
        let seen: Vec<usize> = (0..free).filter(|&k| !self.unseen[k]).collect();
        let m = seen.len();
        if m == 0 {
            return None;
        }
        // The correlation block of the seen free values, and its largest eigenvector.
        let sd: Vec<f64> = seen
            .iter()
            .map(|&k| self.inverse[k * n + k].sqrt())
            .collect();
        let mut block = vec![0.0; m * m];
        for (a, &i) in seen.iter().enumerate() {
            for (b, &k) in seen.iter().enumerate() {
                block[a * m + b] = self.inverse[i * n + k] / (sd[a] * sd[b]);
            }
        }
        if block.iter().any(|v| !v.is_finite()) {
            return None;
        }
        let (values, vectors) = linalg::symmetric_eigen(&block, m);
        let (lambda, u) = (values[m - 1], &vectors[m - 1]);
        if !(lambda > 0.0) {
            return None;
        }
        // The free block's displacement d = 3·√λ·(σ-scaled u); every value follows by
        // Σ_{·f} Σ_ff⁻¹ d, which for an eigenvector is Σ_{·f} (σ⁻¹ u)·3/√λ.
        let weights: Vec<f64> = u
            .iter()
            .zip(&sd)
            .map(|(u, s)| 3.0 * u / (s * lambda.sqrt()))
            .collect();
        let point = (0..n)
            .map(|j| {
                let shift: f64 = seen
                    .iter()
                    .zip(&weights)
                    .map(|(&k, w)| self.inverse[j * n + k] * w)
                    .sum();
                if shift.is_finite() {
                    (x[j] + shift).clamp(bounds[j].0, bounds[j].1)
                } else {
                    x[j]
                }
            })
            .collect();
        Some(point)
    }
}

/// The residuals' variance s² that scales the error bars and the profiles: the sum of squares
/// over the degrees of freedom, never below the data's precision `floor`
/// ([`lm::Problem::floor`]). Rounding to a converter's codes or to printed digits is an error
/// of every sample (of variance q²/12 for a step q) that no parameter explains: a fit of
/// records without noise, down to that rounding, has error bars of the rounding's size, not
/// of the few residuals that happen to fall below it.
pub(super) fn variance(sum_squares: f64, dof: usize, floor: f64) -> f64 {
    (sum_squares / dof.max(1) as f64).max(floor)
}

/// Standard errors, intervals and correlation of the free values from the solution (the
/// weighted residuals' variance `s2` ([`variance`]) scales (JᵀJ)⁻¹), the intervals' ends
/// `found` in the coordinates with how they were found.
pub(super) fn uncertainties(
    setup: &Setup,
    solution: &lm::Solution,
    covariance: &Covariance,
    found: &[([f64; 2], Interval)],
    s2: f64,
) -> (Vec<FittedParameter>, Vec<Vec<f64>>) {
    let free = setup.free.len();
    let n = covariance.n;
    let values = setup.values(&solution.x[..free]);
    let parameters = (0..free)
        .map(|i| {
            let sigma = covariance.sigma(i, s2);
            // The value's standard error by the chain rule; the interval in the coordinate
            // (for a logarithm: never below zero).
            let slope = setup.slope(i, solution.x[i]);
            let (ends, interval) = found[i];
            FittedParameter {
                parameter: setup.free[i],
                value: values[i],
                stderr: slope * sigma,
                ci95: ends.map(|e| setup.value(i, e)),
                initial: setup.scale[i],
                interval: if sigma.is_finite() {
                    interval
                } else {
                    Interval::None
                },
            }
        })
        .collect::<Vec<_>>();
    let cov = |i: usize, k: usize| covariance.inverse[i * n + k];
    let correlation = (0..free)
        .map(|i| {
            (0..free)
                .map(|k| cov(i, k) / (cov(i, i) * cov(k, k)).sqrt())
                .collect()
        })
        .collect();
    (parameters, correlation)
}

/// AIC and BIC of Gaussian residuals with a variance of their own per group (channel):
/// −2 ln L = Σ N_g ln(SSR_g/N_g) up to a constant.
pub(super) fn criteria(groups: &[(f64, usize)], p: usize) -> (f64, f64) {
    let n: usize = groups.iter().map(|g| g.1).sum();
    let base: f64 = groups
        .iter()
        .map(|&(ssr, count)| {
            let c = count.max(1) as f64;
            c * (ssr / c).max(f64::MIN_POSITIVE).ln()
        })
        .sum();
    (
        base + 2.0 * p as f64,
        base + p as f64 * (n.max(1) as f64).ln(),
    )
}

/// The RMS of `values`.
pub(super) fn rms(values: &[f64]) -> f64 {
    (values.iter().map(|v| v * v).sum::<f64>() / values.len().max(1) as f64).sqrt()
}

#[cfg(test)]
mod tests {
    use super::variance;

    /// χ²/dof where it is above the data's precision; the precision where the residuals fall
    /// below it (a record without noise fitted to its rounding).
    #[test]
    fn the_variance_is_never_below_the_precision() {
        assert_eq!(variance(200.0, 100, 0.08), 2.0);
        assert_eq!(variance(1e-6, 100, 1.0 / 12.0), 1.0 / 12.0);
        // No degree of freedom: the sum itself.
        assert_eq!(variance(3.0, 0, 0.0), 3.0);
    }
}
