//! The zero problem of continuation, F(x, λ) = P^p(x; λ) − x, its derivatives, and the
//! pseudo-arclength corrector.

use super::ContinuationOptions;
use crate::error::Result;
use crate::params::{Parameter, Params, State};
use crate::solver::EventKind;
use crate::stability::{Dynamics, NewtonOptions, PeriodicOrbit, StrobeImage};

/// A point u = (y, y', λ) of the continuation space.
pub(crate) type Point = [f64; 3];

pub(crate) fn dot(a: &Point, b: &Point) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

pub(crate) fn norm(a: &Point) -> f64 {
    dot(a, a).sqrt()
}

fn cross(a: &Point, b: &Point) -> Point {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

/// Solve the 3×3 system `a x = b` by Gaussian elimination with partial pivoting; `None` when
/// it is singular or not finite.
fn solve3(mut a: [[f64; 3]; 3], mut b: [f64; 3]) -> Option<[f64; 3]> {
    for col in 0..3 {
        let pivot = (col..3).max_by(|&i, &j| a[i][col].abs().total_cmp(&a[j][col].abs()))?;
        if !(a[pivot][col].abs() > 0.0) || !a[pivot][col].is_finite() {
            return None;
        }
        a.swap(col, pivot);
        b.swap(col, pivot);
        for row in col + 1..3 {
            let f = a[row][col] / a[col][col];
            if f != 0.0 {
                for k in col..3 {
                    a[row][k] -= f * a[col][k];
                }
                b[row] -= f * b[col];
            }
        }
    }
    let mut x = [0.0; 3];
    for row in (0..3).rev() {
        let mut s = b[row];
        for k in row + 1..3 {
            s -= a[row][k] * x[k];
        }
        x[row] = s / a[row][row];
    }
    x.iter().all(|v| v.is_finite()).then_some(x)
}

/// Solve the 2×2 system `a x = b`; `None` when singular.
fn solve2(a: [[f64; 2]; 2], b: [f64; 2]) -> Option<[f64; 2]> {
    let det = a[0][0] * a[1][1] - a[0][1] * a[1][0];
    let x = [
        (a[1][1] * b[0] - a[0][1] * b[1]) / det,
        (a[0][0] * b[1] - a[1][0] * b[0]) / det,
    ];
    (det != 0.0 && x.iter().all(|v| v.is_finite())).then_some(x)
}

/// The event counts of one orbit period: turning points and stops (stick events, zero-duration
/// stops included).
pub(crate) fn counts(orbit: &PeriodicOrbit) -> (usize, usize) {
    let turns = orbit
        .events
        .iter()
        .filter(|e| e.kind == EventKind::Turn)
        .count();
    let sticks = orbit
        .events
        .iter()
        .filter(|e| e.kind == EventKind::Stick)
        .count();
    (turns, sticks)
}

/// The continuation problem: the fixed points of the p-fold strobe map as `parameter` varies.
pub(crate) struct Problem<'a> {
    pub base: Params,
    pub parameter: Parameter,
    pub period: usize,
    pub options: ContinuationOptions,
    /// The model whose strobe map it is.
    pub dynamics: &'a dyn Dynamics,
}

/// A converged point of the branch.
#[derive(Debug, Clone)]
pub(crate) struct Solution {
    pub u: Point,
    pub orbit: PeriodicOrbit,
    /// ∂P^p/∂λ at the point.
    pub dp: [f64; 2],
    /// The unit tangent of the branch, oriented along the continuation.
    pub tangent: Point,
}

impl Problem<'_> {
    pub fn params(&self, lambda: f64) -> Result<Params> {
        self.parameter.set(self.base, lambda)
    }

    /// The velocity of a state stuck to the belt at the parameter value `lambda`: the belt's
    /// speed vb (0 without a belt, or with an invalid `lambda`).
    fn stuck_velocity(&self, lambda: f64) -> f64 {
        self.params(lambda).map_or(0.0, |p| p.vb)
    }

    /// d(stuck velocity)/dλ: 1 when λ is vb, else 0.
    fn stuck_moves(&self) -> f64 {
        if self.parameter == Parameter::Vb {
            1.0
        } else {
            0.0
        }
    }

    /// The residual tolerance: the options' for the exact model, at least the accuracy of a
    /// stiff solver's map for a smooth law ([`Dynamics::map_tolerance`]).
    pub fn tolerance(&self) -> f64 {
        self.dynamics.map_tolerance(self.options.tolerance)
    }

    /// The event counts that split a branch into smooth pieces (turning points, stops) for a
    /// model whose orbits stick (the exact model, the Stribeck and cubic belts: a new stop or
    /// reversal is a seam of the map); none for a smooth diode law, whose map has no seams
    /// (its stops are a threshold of the current, not a switch of the equation).
    pub fn pieces(&self, orbit: &PeriodicOrbit) -> (usize, usize) {
        if self.dynamics.sticks() {
            counts(orbit)
        } else {
            (0, 0)
        }
    }

    pub fn image(&self, u: &Point) -> Result<StrobeImage> {
        self.dynamics
            .strobe_map(&self.params(u[2])?, State { y: u[0], v: u[1] }, self.period)
    }

    /// ∂P^p/∂λ by differences: central where λ ± h are both valid values of the parameter,
    /// else one-sided of second order.
    pub fn dparam(&self, u: &Point) -> Result<[f64; 2]> {
        let lambda = u[2];
        let x = State { y: u[0], v: u[1] };
        if let Some(d) = self.dynamics.parameter_derivative(
            &self.params(lambda)?,
            x,
            self.period,
            self.parameter,
        ) {
            return d;
        }
        let h = self.options.derivative_step * lambda.abs().max(0.1);
        let at = |l: f64| -> Result<State> {
            Ok(self
                .dynamics
                .strobe_map(&self.params(l)?, x, self.period)?
                .state)
        };
        if self.params(lambda - h).is_ok() {
            let (plus, minus) = (at(lambda + h)?, at(lambda - h)?);
            Ok([
                (plus.y - minus.y) / (2.0 * h),
                (plus.v - minus.v) / (2.0 * h),
            ])
        } else {
            let (f0, f1, f2) = (at(lambda)?, at(lambda + h)?, at(lambda + 2.0 * h)?);
            Ok([
                (-3.0 * f0.y + 4.0 * f1.y - f2.y) / (2.0 * h),
                (-3.0 * f0.v + 4.0 * f1.v - f2.v) / (2.0 * h),
            ])
        }
    }

    /// The unit null vector of [M − I | ∂P/∂λ], oriented along `along` (or with t_λ of the
    /// sign of `along[2]` when `along` is the zero-free direction hint).
    pub fn tangent(orbit: &PeriodicOrbit, dp: [f64; 2], along: &Point) -> Option<Point> {
        let m = orbit.monodromy.0;
        let r1 = [m[0][0] - 1.0, m[0][1], dp[0]];
        let r2 = [m[1][0], m[1][1] - 1.0, dp[1]];
        let mut t = cross(&r1, &r2);
        let n = norm(&t);
        if !(n > 0.0 && n.is_finite()) {
            return None;
        }
        t.iter_mut().for_each(|c| *c /= n);
        if dot(&t, along) < 0.0 {
            t.iter_mut().for_each(|c| *c = -*c);
        }
        Some(t)
    }

    /// The orbit at `u` with all its data, when `u` is a fixed point to the tolerance (no
    /// Newton step is then taken).
    fn orbit_at(&self, u: &Point) -> Result<PeriodicOrbit> {
        let options = NewtonOptions {
            tolerance: self.tolerance(),
            max_iterations: 4,
            ..NewtonOptions::default()
        };
        self.dynamics.find_periodic_orbit(
            &self.params(u[2])?,
            State { y: u[0], v: u[1] },
            self.period,
            &options,
        )
    }

    /// The orbit at a converged point `u`, confirmed by Newton's method without a step;
    /// `None` when it is no orbit (for example on the jump of the map).
    fn confirm(&self, mut u: Point) -> Result<Option<(Point, PeriodicOrbit)>> {
        // Where a stop begins or ends at the strobe, Newton's method can land a rounding error
        // off y' = 0, on an orbit that sticks right after the strobe and again right before
        // the next: the orbit stuck at the strobe, with a spurious extra stop. Prefer the
        // stuck one when it is a fixed point to the tolerance. (Stuck is y' = vb on a belt.)
        let stuck = self.stuck_velocity(u[2]);
        if self.dynamics.sticks()
            && u[1] != stuck
            && (u[1] - stuck).abs() <= 1e-6 * 1f64.max(u[0].abs())
        {
            let snapped = [u[0], stuck, u[2]];
            if let Ok(orbit) = self.orbit_at(&snapped) {
                if orbit.iterations == 0 && orbit.stuck_at_strobe {
                    u = snapped;
                }
            }
        }
        match self.orbit_at(&u) {
            Ok(orbit) if orbit.iterations == 0 => Ok(Some((u, orbit))),
            Ok(_) | Err(crate::Error::Stability(_)) => Ok(None),
            Err(e) => Err(e),
        }
    }

    /// The orbit at the parameter value `lambda` by Newton's method from `guess` (a natural
    /// parameter step), with its tangent oriented so that λ moves with the sign of
    /// `direction`; `None` when Newton's method fails.
    pub fn natural(&self, lambda: f64, guess: State, direction: f64) -> Result<Option<Solution>> {
        let Ok(params) = self.params(lambda) else {
            return Ok(None);
        };
        let options = NewtonOptions {
            tolerance: self.tolerance(),
            max_iterations: self.options.corrector_iterations.min(8),
            max_halvings: 4,
            ..NewtonOptions::default()
        };
        let orbit = match self
            .dynamics
            .find_periodic_orbit(&params, guess, self.period, &options)
        {
            Ok(orbit) => orbit,
            Err(crate::Error::Stability(_)) => return Ok(None),
            Err(e) => return Err(e),
        };
        let Some((u, orbit)) = self.confirm([orbit.state.y, orbit.state.v, lambda])? else {
            return Ok(None);
        };
        self.oriented(u, orbit, direction)
    }

    /// A solution from an orbit found by Newton's method at the parameter value `lambda`,
    /// with its tangent oriented so that λ moves with the sign of `direction`.
    pub fn start(
        &self,
        orbit: PeriodicOrbit,
        lambda: f64,
        direction: f64,
    ) -> Result<Option<Solution>> {
        self.oriented([orbit.state.y, orbit.state.v, lambda], orbit, direction)
    }

    /// The solution at `u` on `orbit`, with its tangent oriented so that λ moves with the sign
    /// of `direction`; `None` without a tangent.
    fn oriented(&self, u: Point, orbit: PeriodicOrbit, direction: f64) -> Result<Option<Solution>> {
        let dp = self.dparam(&u)?;
        let Some(tangent) = Self::tangent(&orbit, dp, &[0.0, 0.0, direction]) else {
            return Ok(None);
        };
        Ok(Some(Solution {
            u,
            orbit,
            dp,
            tangent,
        }))
    }

    /// The solution on the hyperplane through `from.u + sigma·from.tangent` orthogonal to
    /// `from.tangent`, by Newton's method from that predicted point (with the parameter
    /// derivative of `from`); `None` when the corrector does not converge or lands on no
    /// orbit.
    pub fn correct(&self, from: &Solution, sigma: f64) -> Result<Option<Solution>> {
        let t = from.tangent;
        let pred = [
            from.u[0] + sigma * t[0],
            from.u[1] + sigma * t[1],
            from.u[2] + sigma * t[2],
        ];
        let mut u = pred;
        let dp = from.dp;
        let mut converged = false;
        let mut last = f64::INFINITY;
        for iteration in 0..self.options.corrector_iterations {
            if self.params(u[2]).is_err() {
                return Ok(None);
            }
            let image = match self.image(&u) {
                Ok(image) => image,
                Err(crate::Error::Stability(_)) => return Ok(None),
                Err(e) => return Err(e),
            };
            let r = [image.state.y - u[0], image.state.v - u[1]];
            let m = image.jacobian.0;
            let scale = 1f64.max(u[0].abs()).max(u[1].abs());
            let limit = self.tolerance() * scale * image.jacobian.max_abs().max(1.0);
            let on_plane = dot(&t, &[u[0] - pred[0], u[1] - pred[1], u[2] - pred[2]]);
            let norm_r = r[0].abs().max(r[1].abs());
            if norm_r <= limit && on_plane.abs() <= 1e-12 * (1.0 + sigma.abs()) {
                converged = true;
                break;
            }
            // Diverging: Newton's iterates left the orbit's neighbourhood (or the piece of
            // the map it lies on).
            if iteration >= 2 && norm_r > 10.0 * last {
                return Ok(None);
            }
            last = norm_r;
            if image.stuck_at_start && image.stuck_at_end {
                // The strobe falls inside a stop: the map is differentiable in y only; keep
                // y' at the belt's speed vb (0 without a belt; λ itself when λ is vb, then
                // dp is the derivative along the stuck states) and solve for (y, λ).
                let (stuck, moves) = (self.stuck_velocity(u[2]), self.stuck_moves());
                let Some(d) = solve2(
                    [[m[0][0] - 1.0, dp[0]], [t[0], t[2] + t[1] * moves]],
                    [-r[0], -(on_plane + t[1] * (stuck - u[1]))],
                ) else {
                    return Ok(None);
                };
                u = [u[0] + d[0], 0.0, u[2] + d[1]];
                u[1] = self.stuck_velocity(u[2]);
            } else {
                let Some(d) = solve3(
                    [
                        [m[0][0] - 1.0, m[0][1], dp[0]],
                        [m[1][0], m[1][1] - 1.0, dp[1]],
                        t,
                    ],
                    [-r[0], -r[1], -on_plane],
                ) else {
                    return Ok(None);
                };
                u = [u[0] + d[0], u[1] + d[1], u[2] + d[2]];
            }
            if !u.iter().all(|c| c.is_finite()) {
                return Ok(None);
            }
        }
        if !converged {
            return Ok(None);
        }
        let Some((u, orbit)) = self.confirm(u)? else {
            return Ok(None);
        };
        let dp = self.dparam(&u)?;
        let Some(tangent) = Self::tangent(&orbit, dp, &from.tangent) else {
            return Ok(None);
        };
        Ok(Some(Solution {
            u,
            orbit,
            dp,
            tangent,
        }))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn linear_solves() {
        let a = [[0.0, 2.0, 1.0], [1.0, 0.0, 0.0], [0.0, 1.0, 3.0]];
        let x = solve3(a, [5.0, 1.0, 10.0]).unwrap();
        for (row, b) in a.iter().zip([5.0, 1.0, 10.0]) {
            assert!((row[0] * x[0] + row[1] * x[1] + row[2] * x[2] - b).abs() < 1e-14);
        }
        assert!(solve3(
            [[1.0, 2.0, 3.0], [2.0, 4.0, 6.0], [0.0, 0.0, 1.0]],
            [1.0; 3]
        )
        .is_none());
        assert_eq!(
            solve2([[2.0, 0.0], [0.0, 4.0]], [2.0, 2.0]),
            Some([1.0, 0.5])
        );
        assert!(solve2([[1.0, 2.0], [2.0, 4.0]], [1.0, 1.0]).is_none());
        let c = cross(&[1.0, 0.0, 0.0], &[0.0, 1.0, 0.0]);
        assert_eq!(c, [0.0, 0.0, 1.0]);
    }
}
