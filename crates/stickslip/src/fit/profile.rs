//! 95 % intervals that hold their coverage: the linear approximation where it holds, the
//! profile likelihood where it does not.
//!
//! The linear interval of a fitted value is x̂ ± t·σ (t Student's 97.5 % quantile with the
//! fit's degrees of freedom, σ from s²(JᵀJ)⁻¹), in the value's coordinate (ln I_s for I_s).
//! It is the set where the sum of squares, minimised over everything else, rises by at most
//! t²·s² **if** the model is linear in the parameters over that range. That is checked at
//! each end ([`intervals`]): the other values are moved as the linear model says they follow
//! (x_j = x̂_j + Σ_jk/Σ_kk·(x_k − x̂_k)) and then settled by two Gauss–Newton steps with
//! the solution's Jacobian (x_k held), and the rise Δ = (SSR − SSR_min)/s² there is
//! compared with t². Within 10 % the end stands. Otherwise (or where the end lies beyond the
//! value's range: R_s below 0) the end is the profile likelihood's: the value x_k where the
//! sum of squares minimised over every other value (Levenberg–Marquardt with x_k held) has
//! risen by t²·s², found by a secant search on the signed root of the rise, or the edge of
//! the range when the rise there is less. (Where the linear model holds the two agree, and
//! the profile costs a minimisation per step of the search; so it is done only where
//! needed.) The report says which served for each value ([`super::Interval`]).
//!
//! A point of either search whose sum of squares lies below the minimum's is a lower
//! minimum: it is returned, and the fit goes on from there.

use super::linalg::{cholesky, cholesky_solve};
use super::{lm, variance, FitError, Interval, Records, RESTART_LOWER};

/// The outcome of [`intervals`]: per fitted value the interval's ends in its coordinate and
/// how they were found; or a point with a lower sum of squares.
pub(super) enum Outcome {
    Intervals(Vec<([f64; 2], Interval)>),
    Lower(Vec<f64>),
}

/// A least-squares problem whose coordinate can be held at a value (a profile's): its
/// bounds then pin it.
pub(super) trait Pin: lm::Problem<Error = FitError> {
    /// Hold coordinate k at a value, or (`None`) free it again.
    fn pin(&mut self, pinned: Option<(usize, f64)>);
}

impl Pin for Records<'_> {
    fn pin(&mut self, pinned: Option<(usize, f64)>) {
        self.pinned = pinned;
    }
}

/// The relative difference from t² beyond which a linear end is replaced by the profile's.
const LINEARITY: f64 = 0.1;

/// The sum of squares at `point` with coordinate k held and the others moved by two
/// Gauss–Newton steps with the Jacobian of the solution (no new Jacobian: the check of a
/// linear end costs three evaluations of the model), and the point reached; `None` where the
/// model has no value.
fn settle<P: Pin>(
    problem: &mut P,
    solution: &lm::Solution,
    bounds: &[(f64, f64)],
    k: usize,
    point: Vec<f64>,
) -> Result<Option<(f64, Vec<f64>)>, FitError> {
    let n = point.len();
    let Some(mut r) = lm::Problem::residuals(problem, &point)? else {
        return Ok(None);
    };
    let mut best = (r.iter().map(|v| v * v).sum::<f64>(), point);
    let mut held = vec![false; n];
    held[k] = true;
    for _ in 0..2 {
        let g: Vec<f64> = solution
            .columns
            .iter()
            .map(|c| c.iter().zip(&r).map(|(a, b)| a * b).sum())
            .collect();
        let (a, g) = lm::without(&solution.normal, &g, &held);
        let Some(l) = cholesky(&a, n) else {
            break;
        };
        let step = cholesky_solve(&l, n, &g.iter().map(|v| -v).collect::<Vec<_>>());
        let next: Vec<f64> = best
            .1
            .iter()
            .zip(&step)
            .zip(bounds)
            .map(|((x, d), &(lo, hi))| (x + d).clamp(lo, hi))
            .collect();
        let Some(rn) = lm::Problem::residuals(problem, &next)? else {
            break;
        };
        let ssr: f64 = rn.iter().map(|v| v * v).sum();
        if ssr >= best.0 {
            break;
        }
        best = (ssr, next);
        r = rn;
    }
    Ok(Some(best))
}

/// The intervals of the first `free` values of `solution` (see the module documentation);
/// `t` the quantile, `settings` those of the profile's minimisations.
pub(super) fn intervals<P: Pin>(
    problem: &mut P,
    solution: &lm::Solution,
    inverse: &[f64],
    free: usize,
    t: f64,
    settings: lm::Settings,
) -> Result<Outcome, FitError> {
    let n = solution.x.len();
    let x = &solution.x;
    let dof = solution.residuals.len().saturating_sub(n);
    let s2 = variance(solution.sum_squares, dof, lm::Problem::floor(problem));
    let bounds = lm::Problem::bounds(problem, n);
    let rise = |ssr: f64| (ssr - solution.sum_squares) / s2;
    let mut out = Vec::with_capacity(free);
    for k in 0..free {
        let sigma = (s2 * inverse[k * n + k]).sqrt();
        if !sigma.is_finite() {
            // A value the records do not see, or a singular fit: no interval.
            out.push(([f64::NAN; 2], Interval::None));
            continue;
        }
        let mut ends = [f64::NAN; 2];
        let mut method = Interval::Linear;
        for (side, sign) in [-1.0, 1.0].into_iter().enumerate() {
            let wald = x[k] + sign * t * sigma;
            // The other values as the linear model moves them with x_k.
            let along = |to: f64| -> Vec<f64> {
                (0..n)
                    .map(|j| {
                        let v = x[j] + inverse[j * n + k] / inverse[k * n + k] * (to - x[k]);
                        if j == k {
                            to
                        } else if v.is_finite() {
                            v.clamp(bounds[j].0, bounds[j].1)
                        } else {
                            x[j]
                        }
                    })
                    .collect()
            };
            let inside = (bounds[k].0..=bounds[k].1).contains(&wald);
            if inside {
                let point = along(wald);
                if let Some((ssr, point)) = settle(problem, solution, &bounds, k, point)? {
                    if rise(ssr) < -RESTART_LOWER {
                        return Ok(Outcome::Lower(point));
                    }
                    if (rise(ssr) / (t * t) - 1.0).abs() <= LINEARITY {
                        ends[side] = wald;
                        continue;
                    }
                }
            }
            method = Interval::Profile;
            // The profile: the rise at x_k = p with every other value minimised.
            // The profile's minimisations start from the last one's point (x_k moved).
            let mut from = along(if inside { wald } else { x[k] });
            let mut profile = |p: f64| -> Result<Option<(f64, Vec<f64>)>, FitError> {
                problem.pin(Some((k, p)));
                from[k] = p;
                let result = lm::minimise(problem, from.clone(), settings);
                problem.pin(None);
                Ok(result?.map(|s| {
                    from.clone_from(&s.x);
                    (rise(s.sum_squares), s.x)
                }))
            };
            let edge = if sign < 0.0 { bounds[k].0 } else { bounds[k].1 };
            let mut p = if inside { wald } else { edge };
            let mut found = f64::NAN;
            // The signed root of the rise, z(p) = ±√Δ, is near linear in p: a secant search
            // for z = t from the minimum (z = 0 at x̂_k).
            let mut last = (x[k], 0.0);
            for _ in 0..6 {
                let Some((delta, at)) = profile(p)? else {
                    break;
                };
                if delta < -RESTART_LOWER {
                    return Ok(Outcome::Lower(at));
                }
                found = p;
                if p == edge && delta <= t * t {
                    break;
                }
                let root = delta.max(0.0).sqrt();
                if (root / t - 1.0).abs() <= 0.02 {
                    break;
                }
                let slope = (root - last.1) / (p - last.0);
                let next = if slope * (p - x[k]) > 0.0 {
                    p + (t - root) / slope
                } else {
                    x[k] + 2.0 * (p - x[k])
                };
                last = (p, root);
                p = if sign < 0.0 {
                    next.max(edge).min(x[k])
                } else {
                    next.min(edge).max(x[k])
                };
                found = p;
            }
            ends[side] = found;
        }
        out.push((ends, method));
    }
    Ok(Outcome::Intervals(out))
}
