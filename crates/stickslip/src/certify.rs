//! Certificates for the velocity-zero search of the exact solver, from Taylor data alone.
//!
//! On a sliding segment with direction s the solver looks for the first zero of g = s·y' ≥ 0.
//! These functions take the Taylor data of g at a point (a [`Jet`]) and bounds on higher
//! derivatives of g over an interval, and prove statements about g without evaluating it
//! anywhere else:
//!
//! - [`reach`]: g has no zero in (a, a + h] (a lower bound g ≥ P(h) that stays positive);
//! - [`locate`]: the first zero lies within a tiny bracket around the root of the local
//!   cubic model, where g is strictly decreasing.
//!
//! Every bound allows for the rounding noise of g itself.

/// Taylor data of g = s·y' at one point: g, g', g'', g''' and the size of the rounding error
/// of g.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Jet {
    /// g, g', g'', g'''.
    pub g: [f64; 4],
    /// Bound on the absolute rounding error of g.
    pub noise: f64,
}

impl Jet {
    /// The jet of t ↦ g(a − t), for bounds that reach backwards from a.
    pub(crate) fn reflected(self) -> Self {
        let [g, g1, g2, g3] = self.g;
        Self {
            g: [g, -g1, g2, -g3],
            noise: self.noise,
        }
    }

    /// The certain part of g: g less its rounding noise.
    fn floor(&self) -> f64 {
        self.g[0] - self.noise
    }
}

/// First positive root of g + g1·h − m2·h²/2 (with g ≥ 0): a lower bound of the first zero of
/// any function with these values and |second derivative| ≤ m2.
#[inline]
pub(crate) fn quadratic_safe_step(g: f64, g1: f64, m2: f64) -> f64 {
    if m2 <= 0.0 {
        return if g1 < 0.0 { g / -g1 } else { f64::INFINITY };
    }
    let root = (g1 * g1 + 2.0 * m2 * g).sqrt();
    if g1 < 0.0 {
        2.0 * g / (root - g1)
    } else {
        (g1 + root) / m2
    }
}

/// A lower bound (within 1e-4 relative) of the positive root of
/// L(h) = g + g1·h + g2·h²/2 − m3·h³/6 for g, g1 ≥ 0.
/// L rises (or is flat) and then falls, so it has exactly one positive root; Newton's method
/// from a point past the root where L is concave and decreasing converges monotonically from
/// the right.
#[inline]
pub(crate) fn cubic_safe_step(g: f64, g1: f64, g2: f64, m3: f64) -> f64 {
    if m3 <= 0.0 {
        return 0.0;
    }
    let l = |h: f64| g + h * (g1 + h * (0.5 * g2 - m3 * h / 6.0));
    let dl = |h: f64| g1 + h * (g2 - 0.5 * m3 * h);
    // Start right of the peak of L (root of L'), of the inflection g2/m3, and of the root.
    let peak = (g2 + (g2 * g2 + 2.0 * m3 * g1).sqrt()) / m3;
    let mut h = peak.max(g2 / m3).max(1e-300);
    while l(h) > 0.0 {
        h *= 2.0;
        if !h.is_finite() {
            return 0.0;
        }
    }
    // Newton from the right stays right of the root and converges quadratically, so once a
    // correction is below 1e-4 of h the root lies within one correction of h: step back two.
    for _ in 0..60 {
        let slope = dl(h);
        let value = l(h);
        if value >= 0.0 {
            return h;
        }
        if slope >= 0.0 {
            return 0.0;
        }
        let next = h - value / slope;
        let step = h - next;
        h = next;
        if step <= 1e-4 * h {
            return (h - 2.0 * step).max(0.0);
        }
    }
    0.0
}

/// The positive root of g1 + (g2/2)·h − (m3/6)·h² (g1 ≥ 0, m3 > 0): where the cubic lower
/// bound g + g1·h + g2·h²/2 − m3·h³/6 ≥ h·(g1 + g2·h/2 − m3·h²/6) is still positive (for
/// g ≥ 0). Exact for the cubic's root when g = 0, as at the start of every slide.
#[inline]
fn cubic_root_from_slope(g1: f64, g2: f64, m3: f64) -> f64 {
    let half = 0.5 * g2;
    let root = (half * half + (2.0 / 3.0) * m3 * g1).sqrt();
    // 3(half + root)/m3, written without cancellation when half < 0.
    if half >= 0.0 {
        3.0 * (half + root) / m3
    } else {
        2.0 * g1 / (root - half)
    }
}

/// A length h ≥ 0 such that g has no zero in (a, a + h], from the jet of g at a and bounds
/// m2 ≥ |g''|, m3 ≥ |g'''| over [a, a + cap]. The result is at most `cap` only when it stops
/// there; it may exceed `cap`, and is then only valid up to `cap`.
///
/// Two lower bounds of g(a + h) are tried: g + g'h − m2·h²/2, and (where g' ≥ 0)
/// g + g'h + g''h²/2 − m3·h³/6. Each has a single positive root, before which it is positive:
/// the first's in closed form, the second's first from below in closed form and, where that
/// is not enough, to 1e-4 by Newton's method.
pub(crate) fn reach(jet: Jet, m2: f64, m3: f64, cap: f64) -> f64 {
    let g = jet.floor();
    let [_, g1, g2, _] = jet.g;
    if g < 0.0 {
        return 0.0;
    }
    let quadratic = quadratic_safe_step(g, g1, m2);
    if quadratic >= cap || g1 < 0.0 || !(m3 > 0.0) {
        return quadratic;
    }
    let cubic = cubic_root_from_slope(g1, g2, m3);
    if cubic >= cap || g == 0.0 {
        return quadratic.max(cubic);
    }
    quadratic.max(cubic_safe_step(g, g1, g2, m3))
}

/// Whether g has no zero in (a, a + len), from its jets at both ends and bounds m2 ≥ |g''|,
/// m3 ≥ |g'''| over the interval: the lower bounds of [`reach`] from a forwards and from
/// a + len backwards meet. The cheap quadratic bounds are tried first.
pub(crate) fn covers(left: Jet, right: Jet, len: f64, m2: f64, m3: f64) -> bool {
    let right = right.reflected();
    // First the closed-form bounds from both ends (no root finding).
    let cheap = |jet: Jet| {
        let g = jet.floor();
        let [_, g1, g2, _] = jet.g;
        if g < 0.0 {
            return 0.0;
        }
        let quadratic = quadratic_safe_step(g, g1, m2);
        if g1 >= 0.0 && m3 > 0.0 {
            quadratic.max(cubic_root_from_slope(g1, g2, m3))
        } else {
            quadratic
        }
    };
    let back = cheap(right);
    let ahead = cheap(left);
    if ahead + back >= len {
        return true;
    }
    let ahead = reach(left, m2, m3, len - back);
    if ahead + back >= len {
        return true;
    }
    ahead + reach(right, m2, m3, len - ahead) >= len
}

/// A bracket of the first zero of g near a point p where g is decreasing.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Located {
    /// Offset δ from p of the root of the local cubic model: the zero's best estimate.
    pub offset: f64,
    /// The zero lies in [p + offset − half_width, p + offset + half_width].
    pub half_width: f64,
}

/// What [`locate`] concludes from the jet at p.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) enum Location {
    /// The zero is bracketed to within the rounding noise of g.
    Found(Located),
    /// g is decreasing on [from, p + offset], where the zero of the model lies, but the
    /// bracket is not yet tight: evaluate at p + offset and try again.
    Closer(f64),
    /// g is not certainly decreasing up to its zero: no conclusion.
    Unknown,
}

/// Root δ of the cubic model g + g1·δ + g2·δ²/2 + g3·δ³/6 nearest to the Newton point −g/g1,
/// by Newton's method (NaN if it does not settle).
pub(crate) fn model_root([g, g1, g2, g3]: [f64; 4]) -> f64 {
    let model = |d: f64| g + d * (g1 + d * (0.5 * g2 + d * g3 / 6.0));
    let slope = |d: f64| g1 + d * (g2 + 0.5 * d * g3);
    let mut d = -g / g1;
    for _ in 0..8 {
        let step = model(d) / slope(d);
        d -= step;
        // Newton converges quadratically: after a step below 1e-9 of d the next error is
        // far below rounding. (A tighter test would never pass: steps stall at rounding.)
        if !(step.abs() > 1e-9 * d.abs()) {
            break;
        }
    }
    if d.is_finite() {
        d
    } else {
        f64::NAN
    }
}

/// The first zero of g near p, from the jet at p, when g is known positive on (0, from]
/// (from ≤ p) and has a zero in (from, ∞) close to p.
///
/// Bounds: m3 ≥ |g'''| and m4 ≥ |g''''| everywhere on the segment. With the cubic model's
/// root δ the zero lies where g changes sign between p + δ − ε and p + δ + ε, because
/// |g(p + x) − model(x)| ≤ m4·x⁴/24 + noise; it is the first zero when g' < 0 on
/// [from, p + δ + ε], checked with g'(p + x) ≤ g' + |g''||x| + m3·x²/2.
pub(crate) fn locate(jet: Jet, p: f64, from: f64, m3: f64, m4: f64) -> Location {
    let [g, g1, g2, g3] = jet.g;
    if !(g1 < 0.0) {
        return Location::Unknown;
    }
    let offset = model_root(jet.g);
    // (A model zero where g is already proved positive: nothing to conclude.)
    if !offset.is_finite() || p + offset < from {
        return Location::Unknown;
    }
    let remainder = |x: f64| m4 * x * x * x * x / 24.0;
    let model = |x: f64| g + x * (g1 + x * (0.5 * g2 + x * g3 / 6.0));
    // The bracket's half-width: the error of the model (its remainder and the noise of g)
    // divided by the slope, doubled, plus a few ulps of the time.
    let ulps = 4.0 * f64::EPSILON * (p + offset).abs().max(1.0);
    let error = jet.noise + remainder(offset.abs() * 1.01 + ulps);
    let half_width = 2.0 * error / -g1 + ulps;
    let reach = (p - from).max(offset.abs() + half_width);
    let decreasing = g1 + g2.abs() * reach + 0.5 * m3 * reach * reach < 0.0;
    if !decreasing {
        return Location::Unknown;
    }
    let (left, right) = (offset - half_width, offset + half_width);
    let bracketed = model(left) - remainder(left.abs()) - jet.noise > 0.0
        && model(right) + remainder(right.abs()) + jet.noise < 0.0;
    // Done when the model's own error is below the rounding noise of g: another evaluation
    // could not place the zero better.
    if bracketed && remainder(offset.abs() * 1.01 + ulps) <= jet.noise.max(f64::MIN_POSITIVE) {
        Location::Found(Located { offset, half_width })
    } else {
        Location::Closer(offset)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn sine_jet(t: f64, noise: f64) -> Jet {
        Jet {
            g: [t.sin(), t.cos(), -t.sin(), -t.cos()],
            noise,
        }
    }

    #[test]
    fn reach_stays_short_of_the_zero_of_a_sine() {
        // g = sin t, bounds 1 on every derivative; its first zero after 0 is π.
        for &a in &[0.3, 1.0, 1.6, 2.5, 3.0, 3.1] {
            let h = reach(sine_jet(a, 1e-16), 1.0, 1.0, 10.0);
            assert!(a + h.min(10.0) < std::f64::consts::PI, "a {a}: reach {h}");
            assert!(h > 0.0, "a {a}: some progress");
        }
        // From 0 (g = 0, g' = 1) the cubic bound h − h³/6 gives √6.
        let h = reach(sine_jet(0.0, 0.0), 1.0, 1.0, 10.0);
        assert!((h - 6f64.sqrt()).abs() < 1e-3, "{h}");
        // Backwards from π − 0.2 the reflected jet reaches at least as far.
        let back = reach(
            sine_jet(std::f64::consts::PI - 0.2, 0.0).reflected(),
            1.0,
            1.0,
            10.0,
        );
        assert!(back > 1.5 && back < std::f64::consts::PI - 0.2, "{back}");
    }

    #[test]
    fn covers_a_sine_arch_but_not_past_its_zero() {
        let pi = std::f64::consts::PI;
        // g = sin t on (0, π − 0.1): covered from both ends.
        let end = pi - 0.1;
        assert!(covers(
            sine_jet(0.0, 0.0),
            sine_jet(end, 1e-16),
            end,
            1.0,
            1.0
        ));
        // On (0, π + 0.1) the right end is negative: never covered.
        let end = pi + 0.1;
        assert!(!covers(
            sine_jet(0.0, 0.0),
            sine_jet(end, 1e-16),
            end,
            1.0,
            1.0
        ));
        // (0.1, 2π − 0.1) contains a zero at π although g > 0 at both ends.
        let (a, b) = (0.1, 2.0 * pi - 0.1);
        let jet = |t: f64| Jet {
            g: [t.sin().abs(), t.cos(), -t.sin(), -t.cos()],
            noise: 0.0,
        };
        let right = Jet {
            g: [b.sin().abs(), -b.cos(), b.sin(), b.cos()],
            noise: 0.0,
        };
        assert!(!covers(jet(a), right, b - a, 1.0, 1.0));
    }

    #[test]
    fn the_closed_form_cubic_bound_is_the_root_when_g_is_zero() {
        for &(g1, g2, m3) in &[
            (1.0, 0.0, 1.0),
            (0.3, -0.7, 2.0),
            (0.0, 0.5, 1.5),
            (2.0, 3.0, 0.1),
        ] {
            let h = cubic_root_from_slope(g1, g2, m3);
            let cubic = h * (g1 + h * (0.5 * g2 - m3 * h / 6.0));
            assert!(
                cubic.abs() < 1e-12 * (1.0 + h * h * h * m3),
                "{g1} {g2} {m3}: {cubic}"
            );
            // Below the root the bound is positive: it is the first positive root.
            for k in 1..100 {
                let x = h * k as f64 / 100.0;
                assert!(
                    x * (g1 + x * (0.5 * g2 - m3 * x / 6.0)) > 0.0,
                    "{g1} {g2} {m3} at {x}"
                );
            }
        }
    }

    #[test]
    fn reach_is_zero_where_the_value_is_noise() {
        let jet = Jet {
            g: [1e-17, -1.0, 0.0, 0.0],
            noise: 1e-16,
        };
        assert_eq!(reach(jet, 1.0, 1.0, 1.0), 0.0);
    }

    #[test]
    fn locate_brackets_the_zero_of_a_sine_from_both_sides() {
        let pi = std::f64::consts::PI;
        for &d in &[1e-9, 1e-6, -1e-6, 1e-5, -3e-5] {
            let p = pi - d;
            let jet = sine_jet(p, 1e-16);
            match locate(jet, p, p.min(pi - 1e-3), 1.0, 1.0) {
                Location::Found(l) => {
                    let err = (p + l.offset - pi).abs();
                    assert!(err <= l.half_width, "d {d}: err {err} > {}", l.half_width);
                    assert!(l.half_width < 1e-14, "d {d}: {}", l.half_width);
                }
                other => panic!("d {d}: {other:?}"),
            }
        }
        // Far from the zero the model is not trusted to rounding: evaluate closer.
        let p = pi - 0.05;
        match locate(sine_jet(p, 1e-16), p, p, 1.0, 1.0) {
            Location::Closer(offset) => assert!((p + offset - pi).abs() < 1e-6),
            other => panic!("{other:?}"),
        }
        // Before the maximum g rises: no conclusion.
        assert_eq!(
            locate(sine_jet(1.0, 1e-16), 1.0, 1.0, 1.0, 1.0),
            Location::Unknown
        );
    }
}
