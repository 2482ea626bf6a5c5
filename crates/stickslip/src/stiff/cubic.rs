//! Cubics on [0, 1], as the dense output of a step gives them: their value, their range and
//! where they cross a level, with no crossing missed.
//!
//! The dense output of a Radau IIA step is a cubic in θ = (τ − τ0)/h per component
//! ([`super::Step::cubic`]); the stop rule of the Shockley solver and the integrator's own
//! retry at a reversal read it with these.

/// p(θ) for a cubic given by its coefficients of 1, θ, θ², θ³.
#[inline]
pub fn horner(p: &[f64; 4], theta: f64) -> f64 {
    p[0] + theta * (p[1] + theta * (p[2] + theta * p[3]))
}

/// The critical points of the cubic `p` inside (0, 1), in increasing order, followed by
/// their count.
fn critical_points(p: &[f64; 4]) -> ([f64; 2], usize) {
    // Roots of 3 p3 θ² + 2 p2 θ + p1.
    let (a, b, c) = (3.0 * p[3], 2.0 * p[2], p[1]);
    let mut roots = [f64::NAN; 2];
    if a != 0.0 {
        let disc = b * b - 4.0 * a * c;
        if disc >= 0.0 {
            let q = -0.5 * (b + b.signum() * disc.sqrt());
            roots = if q != 0.0 { [q / a, c / q] } else { [0.0, 0.0] };
        }
    } else if b != 0.0 {
        roots[0] = -c / b;
    }
    let mut out = [0.0; 2];
    let mut count = 0;
    for r in roots {
        if r > 0.0 && r < 1.0 {
            out[count] = r;
            count += 1;
        }
    }
    if count == 2 && out[0] > out[1] {
        out.swap(0, 1);
    }
    (out, count)
}

/// Smallest and largest value of the cubic `p` on [0, 1].
pub fn range(p: &[f64; 4]) -> (f64, f64) {
    let (a, b) = (p[0], horner(p, 1.0));
    let (mut low, mut high) = (a.min(b), a.max(b));
    let (points, count) = critical_points(p);
    for &theta in &points[..count] {
        let x = horner(p, theta);
        low = low.min(x);
        high = high.max(x);
    }
    (low, high)
}

/// Hand `found` every θ ∈ (0, 1) where the cubic `p` crosses `level` (changes from ≤ level
/// to > level or back). The cubic is split at its critical points into monotone pieces, so no
/// crossing is missed, and each crossing is located to rounding level in θ.
pub fn crossings(p: &[f64; 4], level: f64, mut found: impl FnMut(f64)) {
    let above = |theta: f64| horner(p, theta) > level;
    let (points, count) = critical_points(p);
    let mut knots = [0.0; 4];
    knots[1..=count].copy_from_slice(&points[..count]);
    knots[count + 1] = 1.0;
    for k in 0..=count {
        let (mut lo, mut hi) = (knots[k], knots[k + 1]);
        let side = above(lo);
        if above(hi) == side {
            continue;
        }
        // Invariant: above(lo) == side != above(hi). Regula falsi with the Illinois
        // modification (superlinear, never leaves the bracket) down to 1e-9 in θ, then one
        // Newton step from the middle of the bracket, which squares that error.
        let (mut f_lo, mut f_hi) = (horner(p, lo) - level, horner(p, hi) - level);
        let mut kept = 0i8;
        let mut x = 0.5 * (lo + hi);
        for _ in 0..200 {
            if hi - lo <= 1e-9 {
                let mid = 0.5 * (lo + hi);
                let slope = p[1] + mid * (2.0 * p[2] + mid * 3.0 * p[3]);
                let newton = mid - (horner(p, mid) - level) / slope;
                x = if newton >= lo && newton <= hi {
                    newton
                } else {
                    mid
                };
                break;
            }
            x = (lo * f_hi - hi * f_lo) / (f_hi - f_lo);
            if !(x > lo && x < hi) {
                x = 0.5 * (lo + hi);
                if !(x > lo && x < hi) {
                    // lo and hi are adjacent doubles.
                    break;
                }
            }
            let f = horner(p, x) - level;
            if f == 0.0 {
                break;
            }
            if (f > 0.0) == side {
                lo = x;
                f_lo = f;
                // The same end kept twice: halve the other end's weight (Illinois).
                if kept == 1 {
                    f_hi *= 0.5;
                }
                kept = 1;
            } else {
                hi = x;
                f_hi = f;
                if kept == -1 {
                    f_lo *= 0.5;
                }
                kept = -1;
            }
        }
        if x < 1.0 {
            found(x);
        }
    }
}
