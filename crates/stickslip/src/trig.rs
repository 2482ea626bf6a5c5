//! sin and cos together, for the exact solver's hot loop.
//!
//! The closed form of a segment needs sin and cos of two phases at every evaluation. The
//! system library's `sin_cos` handles every argument to the last ulp and pays for it on each
//! call; the phases here are moderate (|x| well below 10⁵), so [`sin_cos`] reduces the argument
//! by π/2 in three parts (Cody and Waite: each product n·Pᵢ is exact for |n| < 2²⁰) and
//! evaluates the minimax kernels of fdlibm (k_sin.c and k_cos.c, errors below 1 ulp on
//! [−π/4, π/4]). Larger or non-finite arguments go to the system library. The test compares it
//! with the system library on a million arguments: they differ by at most 2⁻⁵² absolutely.

use std::f64::consts::FRAC_2_PI;

/// π/2 in three parts: the first two have 33 significant bits, so n·P1 and n·P2 are exact
/// for |n| < 2²⁰.
const P1: f64 = 1.570_796_326_734_125_6;
const P2: f64 = 6.077_100_506_303_966e-11;
const P3: f64 = 2.022_266_248_795_950_6e-21;

/// Beyond this the reduction above is no longer exact enough: use the system library.
const LIMIT: f64 = 1e5;

const S1: f64 = -1.666_666_666_666_663_2e-1;
const S2: f64 = 8.333_333_333_322_49e-3;
const S3: f64 = -1.984_126_982_985_795e-4;
const S4: f64 = 2.755_731_370_707_007e-6;
const S5: f64 = -2.505_076_025_340_686_3e-8;
const S6: f64 = 1.589_690_995_211_55e-10;

const C1: f64 = 4.166_666_666_666_66e-2;
const C2: f64 = -1.388_888_888_887_411e-3;
const C3: f64 = 2.480_158_728_947_673e-5;
const C4: f64 = -2.755_731_435_139_066_3e-7;
const C5: f64 = 2.087_572_321_298_175e-9;
const C6: f64 = -1.135_964_755_778_819_5e-11;

/// sin r for |r| ≤ π/4.
#[inline]
fn kernel_sin(r: f64) -> f64 {
    let z = r * r;
    let v = z * r;
    let p = S2 + z * (S3 + z * (S4 + z * (S5 + z * S6)));
    r + v * (S1 + z * p)
}

/// cos r for |r| ≤ π/4.
#[inline]
fn kernel_cos(r: f64) -> f64 {
    let z = r * r;
    let p = z * (C1 + z * (C2 + z * (C3 + z * (C4 + z * (C5 + z * C6)))));
    let hz = 0.5 * z;
    let w = 1.0 - hz;
    w + (((1.0 - w) - hz) + z * p)
}

/// (sin x, cos x).
#[inline]
pub(crate) fn sin_cos(x: f64) -> (f64, f64) {
    if !(x.abs() < LIMIT) {
        return x.sin_cos();
    }
    // Round to the nearest integer by adding and removing 1.5·2⁵²: exact for |x·2/π| < 2⁵¹,
    // and cheaper than `round` on targets without a rounding instruction.
    const TO_INT: f64 = 1.5 / f64::EPSILON;
    let big = x * FRAC_2_PI + TO_INT;
    let n = big - TO_INT;
    let r = ((x - n * P1) - n * P2) - n * P3;
    let (s, c) = (kernel_sin(r), kernel_cos(r));
    // The quadrant n mod 4 is in the last two bits of `big` (its unit in the last place is 1
    // and 1.5·2⁵² leaves them alone): (s, c), (c, −s), (−s, −c), (−c, s) for quadrants 0 to
    // 3, by a swap and two sign flips instead of a four-way branch.
    let quadrant = big.to_bits();
    let (s, c) = if quadrant & 1 == 0 { (s, c) } else { (c, s) };
    let flip_sin = (quadrant & 2) << 62;
    let flip_cos = (quadrant.wrapping_add(1) & 2) << 62;
    (
        f64::from_bits(s.to_bits() ^ flip_sin),
        f64::from_bits(c.to_bits() ^ flip_cos),
    )
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::test_rng::TestRng;

    fn check(x: f64) {
        let (s, c) = sin_cos(x);
        let (rs, rc) = x.sin_cos();
        assert!(
            (s - rs).abs() <= f64::EPSILON && (c - rc).abs() <= f64::EPSILON,
            "x = {x:e}: ({s:e}, {c:e}) against ({rs:e}, {rc:e})"
        );
    }

    /// The quadrant's swap and sign flips give the same bits as the four-way choice
    /// `match n & 3 { 0 => (s, c), 1 => (c, −s), 2 => (−s, −c), _ => (−c, s) }` on the
    /// integer n, for every quadrant and sign of the argument and at signed zeros.
    #[test]
    fn the_quadrant_from_the_rounding_constant_is_the_integer_quadrant() {
        let reference = |x: f64| {
            let n = (x * FRAC_2_PI + 1.5 / f64::EPSILON) - 1.5 / f64::EPSILON;
            let r = ((x - n * P1) - n * P2) - n * P3;
            let (s, c) = (kernel_sin(r), kernel_cos(r));
            match (n as i64) & 3 {
                0 => (s, c),
                1 => (c, -s),
                2 => (-s, -c),
                _ => (-c, s),
            }
        };
        let mut rng = TestRng::new(0x0bad_5eed_1234_5678);
        let mut quadrants = [0u32; 4];
        for i in 0..400_000 {
            let scale = [1.0, 10.0, 1e3, 9.9e4][i % 4];
            let x = rng.range(-scale, scale);
            let x = if i % 7 == 0 {
                (x / 1.57).round() * std::f64::consts::FRAC_PI_2
            } else {
                x
            };
            let (s, c) = sin_cos(x);
            let (rs, rc) = reference(x);
            assert!(
                s.to_bits() == rs.to_bits() && c.to_bits() == rc.to_bits(),
                "x = {x:e}: ({s:e}, {c:e}) against ({rs:e}, {rc:e})"
            );
            let n = (x * FRAC_2_PI).round() as i64;
            quadrants[(n & 3) as usize] += 1;
        }
        assert!(quadrants.iter().all(|&q| q > 50_000), "{quadrants:?}");
        for x in [0.0, -0.0, 1e-300, -1e-300] {
            let ((s, c), (rs, rc)) = (sin_cos(x), reference(x));
            assert!(
                s.to_bits() == rs.to_bits() && c.to_bits() == rc.to_bits(),
                "{x:e}"
            );
        }
    }

    #[test]
    fn agrees_with_the_system_library() {
        let mut rng = TestRng::new(0x9e37_79b9_7f4a_7c15);
        for i in 0..1_000_000 {
            let scale = [1.0, 10.0, 1e3, 1e5, 1e6][i % 5];
            check(rng.range(-scale, scale));
        }
        // Near multiples of π/2, where the reduction cancels most.
        for k in -20_000i32..20_000 {
            let x = f64::from(k) * std::f64::consts::FRAC_PI_2;
            for x in [x, x.next_up(), x.next_down(), x + 1e-9, x - 1e-12] {
                check(x);
            }
        }
        for x in [0.0, -0.0, 1e-300, LIMIT, -LIMIT, LIMIT.next_down(), 1e300] {
            check(x);
        }
        assert!(sin_cos(f64::NAN).0.is_nan() && sin_cos(f64::INFINITY).1.is_nan());
    }
}
