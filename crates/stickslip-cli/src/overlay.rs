//! Theory curves drawn over simulated sweeps and phase diagrams: the paper's series solution
//! and boundary (eqs. (11), (13)) and the exact symmetric sliding orbit and boundary.
//!
//! The theory is that of the piecewise-linear model; over a Shockley simulation the curves are
//! labelled as such. Where a curve does not exist (no solution, or outside the plotted range)
//! its points are NaN, which breaks the line.

use stickslip::theory::{paper_boundary, stick_slip_boundary, PaperSeries, PeriodicSolution};
use stickslip::Params;

/// Fewest points of a theory curve; a sweep or grid with more values uses one per value.
const MIN_POINTS: usize = 200;

/// The abscissae of a theory curve over [from, to]: evenly spaced, at least [`MIN_POINTS`]
/// (or `steps`, if more); a single point when the range is one value.
pub fn abscissae(from: f64, to: f64, steps: usize) -> Vec<f64> {
    if to <= from {
        return vec![from];
    }
    let n = steps.max(MIN_POINTS);
    (0..n)
        .map(|i| {
            if i + 1 == n {
                to
            } else {
                from + (to - from) * i as f64 / (n - 1) as f64
            }
        })
        .collect()
}

/// A theory curve: its points (NaN where it does not exist) and how many exist.
#[derive(Debug, Clone, Default)]
pub struct Curve {
    /// (x, y) with y NaN where the curve does not exist.
    pub points: Vec<(f64, f64)>,
    /// Number of points with a finite y.
    pub present: usize,
}

impl Curve {
    fn from_values(xs: &[f64], value: impl Fn(f64) -> Option<f64>) -> Self {
        let points: Vec<(f64, f64)> = xs
            .iter()
            .map(|&x| (x, value(x).filter(|y| y.is_finite()).unwrap_or(f64::NAN)))
            .collect();
        let present = points.iter().filter(|p| p.1.is_finite()).count();
        Self { points, present }
    }
}

/// Gain curves of the theory at parameters `params` with one of w or β replaced by each
/// abscissa (`set` does the replacing): the paper's A1/β (eq. (11)) and the exact sliding
/// orbit's peak/β, which is what the simulated gain (max y − min y)/(2β) measures on a
/// sliding orbit (its A1/β differs from it by the superharmonics' contribution).
pub fn gain_curves(
    params: &Params,
    xs: &[f64],
    set: impl Fn(Params, f64) -> Params,
) -> (Curve, Curve) {
    let paper = Curve::from_values(xs, |x| {
        let p = set(*params, x);
        PaperSeries::new(p.zeta, p.w, p.beta).ok().map(|s| s.gain())
    });
    let exact = Curve::from_values(xs, |x| {
        let p = set(*params, x);
        (p.beta > 0.0)
            .then(|| PeriodicSolution::new(&p).ok().map(|s| s.peak / p.beta))
            .flatten()
    });
    (paper, exact)
}

/// Boundary curves over the frequencies `ws` at damping ζ and static friction μs: the
/// paper's β_c (eq. (13), which assumes μs = 1) and the exact β_c, each kept only inside
/// `[beta_lo, beta_hi]`.
pub fn boundary_curves(
    zeta: f64,
    mu_s: f64,
    ws: &[f64],
    (beta_lo, beta_hi): (f64, f64),
) -> (Curve, Curve) {
    let inside = |b: f64| (beta_lo..=beta_hi).contains(&b).then_some(b);
    let paper = Curve::from_values(ws, |w| paper_boundary(zeta, w).ok().and_then(inside));
    let exact = Curve::from_values(ws, |w| {
        stick_slip_boundary(zeta, w, mu_s)
            .ok()
            .and_then(|b| inside(b.beta_c))
    });
    (paper, exact)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn abscissae_cover_the_range_ends_included() {
        let xs = abscissae(0.5, 2.0, 3);
        assert_eq!(xs.len(), MIN_POINTS);
        assert_eq!((xs[0], xs[MIN_POINTS - 1]), (0.5, 2.0));
        assert!(xs.windows(2).all(|p| p[1] > p[0]));
        assert_eq!(abscissae(0.5, 2.0, 500).len(), 500);
        assert_eq!(abscissae(1.0, 1.0, 1), vec![1.0]);
    }

    #[test]
    fn gain_curves_exist_above_the_boundary_only() {
        let params = Params::new(0.0468, 0.9, 1.6).unwrap();
        let (paper, exact) = gain_curves(&params, &[0.9, 0.2], |p, w| Params { w, ..p });
        // At w = 0.9, β = 1.6 the orbit slides; at w = 0.2 it cannot (β_c is far above 1.6).
        let orbit = PeriodicSolution::new(&params).unwrap();
        assert_eq!(exact.points[0].1, orbit.peak / 1.6);
        // The peak is not the fundamental: the two gains differ.
        assert!((exact.points[0].1 - orbit.gain()).abs() > 1e-3 * orbit.gain());
        assert!(exact.points[1].1.is_nan());
        assert_eq!(exact.present, 1);
        assert!(paper.points[0].1 > 0.0);
    }

    #[test]
    fn boundary_curves_are_cut_to_the_beta_range() {
        let ws = [0.3, 0.9, 1.5];
        let (paper, exact) = boundary_curves(0.0468, 1.0, &ws, (0.5, 4.0));
        let all = boundary_curves(0.0468, 1.0, &ws, (0.0, f64::INFINITY));
        assert_eq!(all.1.present, 3);
        for (cut, full) in [(&paper, &all.0), (&exact, &all.1)] {
            for (c, f) in cut.points.iter().zip(&full.points) {
                if (0.5..=4.0).contains(&f.1) {
                    assert_eq!(c.1, f.1);
                } else {
                    assert!(c.1.is_nan());
                }
            }
        }
        // At w = 0.3 the exact β_c lies above 4 (many stops per period below it).
        assert!(all.1.points[0].1 > 4.0 && exact.points[0].1.is_nan());
        assert!(exact.present >= 1);
    }
}
