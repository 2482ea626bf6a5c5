//! The end of a stop on a moving belt.
//!
//! Stuck to a belt at speed vb ≠ 0 from y_s, the block moves with it, y = y_s + vb·t, and
//! static friction holds the net force
//!
//! ```text
//! h(t) = β cos(θ + w t) − c − vb t,      c = y_s + 2ζ vb,
//! ```
//!
//! while |h| ≤ μs. The stop ends at the first t ≥ 0 where h reaches +μs rising (the block
//! then slips forward of the belt, s > 0) or −μs falling (s < 0). Without a drive that is
//! t = (μs − c)/vb (for vb > 0). With one, h' = −βw sin(θ + wt) − vb vanishes where
//! sin(θ + wt) = −vb/(βw): in closed form, so h is cut into monotone pieces whose ends are
//! known, and a crossing is bracketed in its piece and solved there to rounding (Newton's
//! method kept inside the bracket). When βw ≤ |vb|, h is monotone. The maxima of h fall by
//! vb·T from one drive period T = 2π/w to the next (and so do the minima): so h reaches +μs
//! in the first increasing piece or never, and the first minimum below −μs is found in one
//! step however many periods the stop lasts. A belt moving backwards (vb < 0) is the mirror
//! image (h → −h, θ → θ + π).

use std::f64::consts::{PI, TAU};

/// The end of a stop on a belt: local time and the direction of the slip that follows
/// (+1: forward of the belt, −1: behind it). See the module documentation.
///
/// - `theta`: the drive phase at the start of the stop, in [0, 2π);
/// - `c`: y_s + 2ζ vb; `vb` ≠ 0;
/// - `allow_now`: a net force already at or beyond ±μs ends the stop at once (otherwise the
///   stop lasts until h next crosses ±μs outward).
pub(crate) fn stop_end(
    beta: f64,
    w: f64,
    theta: f64,
    mu_s: f64,
    c: f64,
    vb: f64,
    allow_now: bool,
) -> (f64, f64) {
    debug_assert!(vb != 0.0);
    if vb < 0.0 {
        // h(t) = −[β cos(θ + π + wt) − (−c) − |vb| t].
        let mirrored = (theta + PI).rem_euclid(TAU);
        let (t, sign) = stop_end(beta, w, mirrored, mu_s, -c, -vb, allow_now);
        return (t, -sign);
    }
    let h = |t: f64| beta * (theta + w * t).cos() - c - vb * t;
    let rate = |t: f64| -beta * w * (theta + w * t).sin() - vb;
    let h0 = h(0.0);
    if allow_now {
        if h0 >= mu_s {
            return (0.0, 1.0);
        }
        if h0 <= -mu_s {
            return (0.0, -1.0);
        }
    }
    if beta == 0.0 {
        // −c − vb t = −μs.
        return (((mu_s - c) / vb).max(0.0), -1.0);
    }
    let swing = beta * w;
    if swing <= vb {
        // h falls monotonically: one crossing of −μs, before h's upper bound β − c − vb t
        // falls below −μs.
        let end = ((beta - c + mu_s) / vb).max(0.0);
        return (crossing(&h, &rate, 0.0, end, -mu_s), -1.0);
    }
    let period = TAU / w;
    // Phases of the maxima (cos > 0) and minima (cos < 0) of h.
    let r = (vb / swing).asin();
    let psi_max = TAU - r;
    let psi_min = PI + r;
    let first = |psi: f64| (psi - theta).rem_euclid(TAU) / w;
    let (t_max, t_min) = (first(psi_max), first(psi_min));
    // The pieces up to the first maximum and the first minimum after it: the rising crossing
    // can only come in the first rising piece.
    let mut pieces: Vec<(f64, f64, bool)> = Vec::with_capacity(3);
    if t_max < t_min {
        pieces.push((0.0, t_max, true));
        pieces.push((t_max, t_min, false));
    } else {
        pieces.push((0.0, t_min, false));
        pieces.push((t_min, t_max, true));
        pieces.push((t_max, t_min + period, false));
    }
    for &(a, b, rising) in &pieces {
        let (ha, hb) = (h(a), h(b));
        if rising && ha < mu_s && hb >= mu_s {
            return (crossing(&h, &rate, a, b, mu_s), 1.0);
        }
        if !rising && ha > -mu_s && hb <= -mu_s {
            return (crossing(&h, &rate, a, b, -mu_s), -1.0);
        }
    }
    // The minima go on falling by vb·T a period: the first at or below −μs, after the last
    // piece looked at (whose minimum is above −μs).
    let (a_last, b_last, _) = pieces[pieces.len() - 1];
    let last_min = h(b_last);
    let periods = ((last_min + mu_s) / (vb * period)).ceil().max(1.0);
    let b = b_last + periods * period;
    // (Rounding of the count: step on while the minimum is still above −μs.)
    let mut b = b;
    while h(b) > -mu_s {
        b += period;
    }
    let a = b - (b_last - a_last);
    (crossing(&h, &rate, a, b, -mu_s), -1.0)
}

/// The t in [a, b] where the monotone h crosses `level` (h(a) on one side, h(b) on the other
/// or on it): Newton's method kept inside the shrinking bracket, bisection where a step
/// leaves it, to rounding.
fn crossing(h: &dyn Fn(f64) -> f64, rate: &dyn Fn(f64) -> f64, a: f64, b: f64, level: f64) -> f64 {
    let (mut lo, mut hi) = (a, b);
    let g = |t: f64| h(t) - level;
    let rising = g(hi) >= g(lo);
    // g(lo) on the starting side, g(hi) at or past the level.
    let past = |v: f64| if rising { v >= 0.0 } else { v <= 0.0 };
    if past(g(lo)) {
        return lo;
    }
    let mut t = hi;
    for _ in 0..200 {
        let v = g(t);
        if past(v) {
            hi = t;
        } else {
            lo = t;
        }
        if v == 0.0 || hi - lo <= 4.0 * f64::EPSILON * hi.abs().max(1e-300) {
            break;
        }
        let slope = rate(t);
        let newton = t - v / slope;
        t = if slope != 0.0 && newton > lo && newton < hi {
            newton
        } else {
            0.5 * (lo + hi)
        };
        if t == lo || t == hi {
            break;
        }
    }
    // The first instant at or past the level, to rounding.
    hi
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The first exit on a fine grid of h, by brute force.
    fn brute(beta: f64, w: f64, theta: f64, mu_s: f64, c: f64, vb: f64) -> (f64, f64) {
        let h = |t: f64| beta * (theta + w * t).cos() - c - vb * t;
        let dt = 1e-4;
        let mut t = 0.0;
        loop {
            let (a, b) = (h(t), h(t + dt));
            if a < mu_s && b >= mu_s {
                return (t, 1.0);
            }
            if a > -mu_s && b <= -mu_s {
                return (t, -1.0);
            }
            t += dt;
            assert!(t < 1e4, "no exit");
        }
    }

    #[test]
    fn the_exit_is_the_first_crossing_of_the_static_limit() {
        let mut seed = 0x9e37_79b9_7f4a_7c15u64;
        let mut next = || {
            seed ^= seed << 13;
            seed ^= seed >> 7;
            seed ^= seed << 17;
            (seed >> 11) as f64 / (1u64 << 53) as f64
        };
        for case in 0..400 {
            let beta = if case % 7 == 0 { 0.0 } else { 3.0 * next() };
            let w = 0.2 + 2.0 * next();
            let theta = TAU * next();
            let mu_s = 1.0 + next();
            let vb = (0.05 + 2.0 * next()) * if case % 2 == 0 { 1.0 } else { -1.0 };
            // A start inside the limits: c such that |h(0)| < μs.
            let h0 = (2.0 * next() - 1.0) * mu_s * 0.999;
            let c = beta * theta.cos() - h0;
            let (t, sign) = stop_end(beta, w, theta, mu_s, c, vb, true);
            let (tb, sb) = brute(beta, w, theta, mu_s, c, vb);
            assert_eq!(sign, sb, "case {case}: {t} {tb}");
            assert!(
                (t - tb).abs() <= 1e-4 + 1e-12,
                "case {case}: {t} against {tb}"
            );
            let h = beta * (theta + w * t).cos() - c - vb * t;
            assert!(
                (h - sign * mu_s).abs() <= 1e-12 * (1.0 + beta + c.abs() + (vb * t).abs()),
                "case {case}: h = {h} at the exit"
            );
        }
    }

    #[test]
    fn a_slow_belt_under_a_drive_skips_whole_periods() {
        // Each drive period the minimum falls by vb·T = 2π·1e-6: from −1 to −2 takes about
        // 1e6/(2π) periods.
        let (beta, w, mu_s, vb) = (1.0, 1.0, 2.0, 1e-6);
        let (t, sign) = stop_end(beta, w, 0.0, mu_s, 0.0, vb, true);
        assert_eq!(sign, -1.0);
        let h = |t: f64| beta * (w * t).cos() - vb * t;
        assert!((h(t) + mu_s).abs() < 1e-9, "{}", h(t));
        assert!((t - 1e6).abs() < 1e3, "{t}");
        // The minimum of the period before stays above −μs.
        let r = (vb / (beta * w)).asin();
        let k = ((t * w - PI - r) / TAU).floor() - 1.0;
        let previous = (PI + r + k * TAU) / w;
        assert!(previous < t && t - previous < 2.0 * TAU && h(previous) > -mu_s);
    }
}
