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

use super::linalg::{cholesky, cholesky_solve};

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
    /// The bounds (lo, hi) of each of the `n` coordinates, which the minimisation does not
    /// cross: a step that would is cut back to the bound and the others solved again (an
    /// active set). Default: none.
    fn bounds(&self, n: usize) -> Vec<(f64, f64)> {
        vec![(f64::NEG_INFINITY, f64::INFINITY); n]
    }
    /// Told after every iteration (`iteration` from 1, the sum of squares reached); an error
    /// stops the minimisation with it.
    fn iteration(&mut self, _iteration: usize, _sum_squares: f64) -> Result<(), Self::Error> {
        Ok(())
    }
    /// The residuals' precision: the mean square that a residual cannot be resolved below
    /// (the rounding of the data and the model's accuracy, in the residuals' units). Residuals
    /// at this floor are rounding, which no step of the model's parameters describes; the
    /// gradient criterion measures the predicted decrease in units of the larger of s² and
    /// this ([`Settings::gradient`]). Default: 0 (exact data and model).
    fn floor(&self) -> f64 {
        0.0
    }
}

/// Stopping rules.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Settings {
    pub max_iterations: usize,
    /// The step criterion: the sum of squares falls by less than this fraction in a step,
    /// or every step component is below this times (1 + |x|).
    pub tolerance: f64,
    /// The gradient criterion: the decrease of the sum of squares that a full Gauss–Newton
    /// step predicts, gᵀ(JᵀJ)⁻¹g with g = Jᵀr, in units of the residuals' variance
    /// s² = |r|²/(N − P), is at most this (the point is within √gradient standard errors of
    /// the linearised minimum, whatever the scale of the problem). The variance is never
    /// taken below the residuals' precision ([`Problem::floor`]): residuals at that floor
    /// are rounding, whose projection on the Jacobian's columns predicts a decrease of about
    /// P times their variance that no step can realise; a point within √gradient of the
    /// standard errors that the data's precision allows is a minimum to that precision.
    pub gradient: f64,
}

/// The gradient criterion's default: the solution within 0.03 standard errors of the
/// linearised minimum.
pub(crate) const GRADIENT: f64 = 1e-3;

/// The solution.
pub(crate) struct Solution {
    pub x: Vec<f64>,
    pub residuals: Vec<f64>,
    pub sum_squares: f64,
    pub iterations: usize,
    /// Both criteria hold: the step criterion (on the last step) and the gradient criterion
    /// (at the solution).
    pub converged: bool,
    /// JᵀJ at the solution (row-major).
    pub normal: Vec<f64>,
    /// The Jacobian at the solution, column by column.
    pub columns: Vec<Vec<f64>>,
    /// The decrease of the sum of squares a Gauss–Newton step predicts at the solution, in
    /// units of s² or of the residuals' precision if larger ([`Settings::gradient`]), the
    /// coordinates held at a bound left out;
    /// infinite when JᵀJ is singular.
    pub decrement: f64,
    /// Which coordinates ended at a bound that the minimum presses against.
    pub at_bound: Vec<bool>,
}

/// The Gauss–Newton decrement gᵀ(JᵀJ)⁻¹g/s² (see [`Settings::gradient`]) of the normal
/// matrix `a` (n×n) and gradient `g` with `ssr` over `residuals` residuals, s² never below
/// the residuals' precision `floor` ([`Problem::floor`]); JᵀJ that is singular to rounding
/// is regularised by 10⁻¹² of its diagonal, so that a direction the data do not see (and
/// the gradient cannot move along) does not count.
pub(crate) fn decrement(a: &[f64], g: &[f64], ssr: f64, residuals: usize, floor: f64) -> f64 {
    let n = g.len();
    let s2 = (ssr / residuals.saturating_sub(n).max(1) as f64).max(floor);
    if !(s2 > 0.0) {
        return 0.0;
    }
    let mut m = a.to_vec();
    for i in 0..n {
        m[i * n + i] += 1e-12 * a[i * n + i].abs().max(f64::MIN_POSITIVE);
    }
    match cholesky(&m, n) {
        Some(l) => {
            let step = cholesky_solve(&l, n, g);
            step.iter().zip(g).map(|(d, g)| d * g).sum::<f64>() / s2
        }
        None => f64::INFINITY,
    }
}

/// The normal matrix JᵀJ (row-major) and the gradient Jᵀr of Jacobian `columns` at residuals
/// `r`. A record's own values (its drive, offset, time shift) have columns that vanish outside
/// the record's residuals: each product runs over the rows where both columns can be nonzero
/// (the same sums as over every row, whose other terms are exact zeros).
fn normal(columns: &[Vec<f64>], r: &[f64]) -> (Vec<f64>, Vec<f64>) {
    let n = columns.len();
    let support: Vec<(usize, usize)> = columns
        .iter()
        .map(|c| match c.iter().position(|v| *v != 0.0) {
            Some(first) => (
                first,
                c.iter().rposition(|v| *v != 0.0).map_or(first, |l| l + 1),
            ),
            None => (0, 0),
        })
        .collect();
    let dot = |a: &[f64], b: &[f64], (lo, hi): (usize, usize)| -> f64 {
        if lo >= hi {
            return 0.0;
        }
        a[lo..hi].iter().zip(&b[lo..hi]).map(|(a, b)| a * b).sum()
    };
    let mut a = vec![0.0; n * n];
    let mut g = vec![0.0; n];
    for i in 0..n {
        g[i] = dot(&columns[i], r, support[i]);
        for k in 0..=i {
            let span = (
                support[i].0.max(support[k].0),
                support[i].1.min(support[k].1),
            );
            let v = dot(&columns[i], &columns[k], span);
            a[i * n + k] = v;
            a[k * n + i] = v;
        }
    }
    (a, g)
}

fn sum_squares(r: &[f64]) -> f64 {
    r.iter().map(|v| v * v).sum()
}

/// The coordinates at a bound that the descent direction −g would push past it: held there
/// (the minimum over the box lies on that face).
fn active(x: &[f64], g: &[f64], bounds: &[(f64, f64)]) -> Vec<bool> {
    x.iter()
        .zip(g)
        .zip(bounds)
        .map(|((&x, &g), &(lo, hi))| (x <= lo && g > 0.0) || (x >= hi && g < 0.0))
        .collect()
}

/// The normal matrix and gradient without the held coordinates (their rows and columns
/// replaced by the identity and zero), so that the decrement and the step see the others
/// alone.
pub(crate) fn without(a: &[f64], g: &[f64], held: &[bool]) -> (Vec<f64>, Vec<f64>) {
    let n = g.len();
    let mut a = a.to_vec();
    let mut g = g.to_vec();
    for i in (0..n).filter(|&i| held[i]) {
        for k in 0..n {
            a[i * n + k] = 0.0;
            a[k * n + i] = 0.0;
        }
        a[i * n + i] = 1.0;
        g[i] = 0.0;
    }
    (a, g)
}

/// The damped step −(A + λD)⁻¹g with the coordinates that it would carry past a bound held
/// at that bound (the others solved again with them moved there), or `None` when the damped
/// matrix is not positive definite.
fn bounded_step(
    m: &[f64],
    g: &[f64],
    x: &[f64],
    bounds: &[(f64, f64)],
    held: &[bool],
) -> Option<Vec<f64>> {
    let n = g.len();
    let mut fixed: Vec<Option<f64>> = held.iter().map(|&h| h.then_some(0.0)).collect();
    for _ in 0..=n {
        // Solve for the coordinates not fixed, the fixed ones moved by their own amount.
        let free: Vec<usize> = (0..n).filter(|&i| fixed[i].is_none()).collect();
        let k = free.len();
        let mut mf = vec![0.0; k * k];
        let mut rhs = vec![0.0; k];
        for (a, &i) in free.iter().enumerate() {
            rhs[a] = -g[i]
                - (0..n)
                    .filter_map(|j| fixed[j].map(|d| m[i * n + j] * d))
                    .sum::<f64>();
            for (b, &j) in free.iter().enumerate() {
                mf[a * k + b] = m[i * n + j];
            }
        }
        let solved = if k == 0 {
            Vec::new()
        } else {
            cholesky_solve(&cholesky(&mf, k)?, k, &rhs)
        };
        let mut step: Vec<f64> = fixed.iter().map(|d| d.unwrap_or(0.0)).collect();
        for (a, &i) in free.iter().enumerate() {
            step[i] = solved[a];
        }
        let past: Vec<usize> = free
            .iter()
            .copied()
            .filter(|&i| x[i] + step[i] < bounds[i].0 || x[i] + step[i] > bounds[i].1)
            .collect();
        if past.is_empty() {
            return Some(step);
        }
        for i in past {
            let to = (x[i] + step[i]).clamp(bounds[i].0, bounds[i].1);
            fixed[i] = Some(to - x[i]);
        }
    }
    None
}

/// Minimise ½|r(x)|² from `x0` within the problem's bounds ([`Problem::bounds`]).
pub(crate) fn minimise<P: Problem>(
    problem: &mut P,
    x0: Vec<f64>,
    settings: Settings,
) -> Result<Option<Solution>, P::Error> {
    let n = x0.len();
    let bounds = problem.bounds(n);
    let floor = problem.floor();
    let mut x = x0;
    let Some(mut r) = problem.residuals(&x)? else {
        return Ok(None);
    };
    let mut ssr = sum_squares(&r);
    let mut lambda = 1e-3;
    let mut iterations = 0;
    let mut converged = false;
    let mut columns = problem.jacobian(&x, &r)?;
    let gradient_holds = |columns: &[Vec<f64>], r: &[f64], ssr: f64, x: &[f64]| {
        let (a, g) = normal(columns, r);
        let (a, g) = without(&a, &g, &active(x, &g, &bounds));
        decrement(&a, &g, ssr, r.len(), floor) <= settings.gradient
    };
    while iterations < settings.max_iterations && !converged {
        iterations += 1;
        let (a, g) = normal(&columns, &r);
        let held = active(&x, &g, &bounds);
        let largest = (0..n).map(|i| a[i * n + i]).fold(0.0, f64::max);
        let mut accepted = false;
        for _ in 0..30 {
            let mut m = a.clone();
            for i in 0..n {
                m[i * n + i] += lambda * a[i * n + i].max(1e-12 * largest);
            }
            let Some(step) = bounded_step(&m, &g, &x, &bounds, &held) else {
                lambda *= 4.0;
                continue;
            };
            let trial: Vec<f64> = x
                .iter()
                .zip(&step)
                .zip(&bounds)
                .map(|((x, d), &(lo, hi))| (x + d).clamp(lo, hi))
                .collect();
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
        if accepted {
            columns = problem.jacobian(&x, &r)?;
        }
        if converged && !gradient_holds(&columns, &r, ssr, &x) {
            converged = false;
            if !accepted {
                // No step lowers the sum, yet the gradient says the minimum is elsewhere: the
                // Jacobian does not describe the residuals. Stop, not converged.
                break;
            }
            // The step criterion alone: a small step on a slope. Go on, less damped.
            lambda = (lambda / 10.0).max(1e-12);
        }
    }
    let (a, g) = normal(&columns, &r);
    let at_bound = active(&x, &g, &bounds);
    let (reduced, g) = without(&a, &g, &at_bound);
    let decrement = decrement(&reduced, &g, ssr, r.len(), floor);
    Ok(Some(Solution {
        x,
        residuals: r,
        sum_squares: ssr,
        iterations,
        converged,
        normal: a,
        columns,
        decrement,
        at_bound,
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

    /// A paraboloid whose minimum (2, −1) lies outside the box x0 ≤ 1, x1 ≥ 0.
    struct Boxed;

    impl Problem for Boxed {
        type Error = ();
        fn residuals(&mut self, x: &[f64]) -> Result<Option<Vec<f64>>, ()> {
            Ok(Some(vec![x[0] - 2.0, x[1] + 1.0, 0.3 * (x[0] + x[1])]))
        }
        fn jacobian(&mut self, _: &[f64], _: &[f64]) -> Result<Vec<Vec<f64>>, ()> {
            Ok(vec![vec![1.0, 0.0, 0.3], vec![0.0, 1.0, 0.3]])
        }
        fn bounds(&self, _: usize) -> Vec<(f64, f64)> {
            vec![(f64::NEG_INFINITY, 1.0), (0.0, f64::INFINITY)]
        }
    }

    /// A line a + b·t through data (0.5 + 2t, exactly), evaluated with a rounding error of
    /// 10⁻¹⁴ that changes with every bit of the parameters (as a model's does), the data's
    /// precision 10⁻⁹ ([`Problem::floor`] = `floor`).
    struct Rounded {
        floor: f64,
    }

    impl Rounded {
        const T: [f64; 40] = {
            let mut t = [0.0; 40];
            let mut i = 0;
            while i < 40 {
                t[i] = i as f64 / 39.0;
                i += 1;
            }
            t
        };

        /// A rounding error in [−10⁻¹⁴, 10⁻¹⁴], a hash of the parameters' bits and `i`.
        fn rounding(x: &[f64], i: usize) -> f64 {
            let mut z = x[0].to_bits() ^ x[1].to_bits().rotate_left(29) ^ (i as u64) << 48;
            z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
            z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
            z ^= z >> 31;
            1e-14 * ((z >> 11) as f64 / (1u64 << 53) as f64 * 2.0 - 1.0)
        }
    }

    impl Problem for Rounded {
        type Error = ();
        fn residuals(&mut self, x: &[f64]) -> Result<Option<Vec<f64>>, ()> {
            Ok(Some(
                Self::T
                    .iter()
                    .enumerate()
                    .map(|(i, t)| (x[0] - 0.5) + (x[1] - 2.0) * t + Self::rounding(x, i))
                    .collect(),
            ))
        }
        fn jacobian(&mut self, _: &[f64], _: &[f64]) -> Result<Vec<Vec<f64>>, ()> {
            Ok(vec![vec![1.0; 40], Self::T.to_vec()])
        }
        fn floor(&self) -> f64 {
            self.floor * self.floor
        }
    }

    const TIGHT: Settings = Settings {
        max_iterations: 100,
        tolerance: 1e-14,
        gradient: GRADIENT,
    };

    #[test]
    fn residuals_at_the_floor_are_a_minimum_to_the_datas_precision() {
        // Exact data: the fit goes down to the rounding, where the gradient of that
        // rounding predicts a decrease of about P·s² (P = 2) that no step realises.
        let blind = minimise(&mut Rounded { floor: 0.0 }, vec![3.0, -1.0], TIGHT)
            .unwrap()
            .unwrap();
        assert!(blind.sum_squares < 40.0 * 1e-28, "{}", blind.sum_squares);
        assert!(
            !blind.converged && blind.decrement > GRADIENT,
            "{}",
            blind.decrement
        );
        // Known to 10⁻⁹: that decrease is nothing the data can tell.
        let s = minimise(&mut Rounded { floor: 1e-9 }, vec![3.0, -1.0], TIGHT)
            .unwrap()
            .unwrap();
        assert!(s.converged, "{}", s.decrement);
        assert!(
            (s.x[0] - 0.5).abs() < 1e-12 && (s.x[1] - 2.0).abs() < 1e-12,
            "{:?}",
            s.x
        );
    }

    /// Data with noise of variance ~1 (a fixed pattern), and a Jacobian whose first column
    /// has the wrong sign: the fit stalls where its Jacobian cannot lead it on.
    struct Misled {
        floor: f64,
    }

    impl Problem for Misled {
        type Error = ();
        fn residuals(&mut self, x: &[f64]) -> Result<Option<Vec<f64>>, ()> {
            Ok(Some(
                Rounded::T
                    .iter()
                    .enumerate()
                    .map(|(i, t)| (x[0] - 0.5) + (x[1] - 2.0) * t + (1.7 * i as f64).sin())
                    .collect(),
            ))
        }
        fn jacobian(&mut self, _: &[f64], _: &[f64]) -> Result<Vec<Vec<f64>>, ()> {
            Ok(vec![vec![-1.0; 40], Rounded::T.to_vec()])
        }
        fn floor(&self) -> f64 {
            self.floor * self.floor
        }
    }

    #[test]
    fn a_stall_above_the_floor_is_not_converged() {
        for floor in [0.0, 1e-9] {
            let s = minimise(&mut Misled { floor }, vec![3.0, -1.0], TIGHT)
                .unwrap()
                .unwrap();
            // Stopped where no step lowers the sum, not by the iterations' limit.
            assert!(
                s.iterations < TIGHT.max_iterations,
                "{floor}: {}",
                s.iterations
            );
            assert!(!s.converged, "{floor}: {:?}", s.x);
            assert!(s.decrement > 1.0, "{floor}: {}", s.decrement);
        }
    }

    #[test]
    fn stops_on_the_faces_of_its_box() {
        let s = minimise(
            &mut Boxed,
            vec![-3.0, 2.0],
            Settings {
                max_iterations: 50,
                tolerance: 1e-12,
                gradient: GRADIENT,
            },
        )
        .unwrap()
        .unwrap();
        assert!(s.converged);
        assert_eq!(s.x, vec![1.0, 0.0]);
        assert_eq!(s.at_bound, vec![true, true]);
    }

    #[test]
    fn finds_the_rosenbrock_minimum() {
        let s = minimise(
            &mut Rosenbrock,
            vec![-1.2, 1.0],
            Settings {
                max_iterations: 200,
                tolerance: 1e-14,
                gradient: GRADIENT,
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
