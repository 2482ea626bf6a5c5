//! The extremes of y inside a slide on a moving belt.
//!
//! Without a belt y has its extremes where y' = 0, that is at the events (turns and stops),
//! which the event log holds with their exact y. On a belt the events are where the slip
//! y' − vb vanishes, and y turns round inside a slide (where y' = 0) or at the ends of a stop
//! (which moves with the belt): [`velocity_zeros`] finds the zeros of y' inside the stretch a
//! solver last advanced through, from its dense output: samples a fixed spacing apart bracket
//! every sign change, and bisection places each to rounding. A pair of zeros closer than the
//! spacing (y' touching zero) can be missed; y then differs from its value there by less than
//! the largest |y'| between them times the spacing, y' itself being within that pair's
//! extremum of zero.

use crate::solver::{Phase, Sample, Solver};

/// Most samples of one stretch (a stretch longer than this many spacings is sampled more
/// coarsely).
const MOST_SAMPLES: f64 = 1e7;

/// Each zero of y' inside the stretch `solver` last advanced through ([`Solver::interval`],
/// where its dense output holds), as the sample there and whether y has a maximum (y' going
/// from positive to negative) or a minimum: every sign change between samples `spacing` apart, placed by
/// bisection to rounding. A zero at the stretch's start belongs to the stretch before it.
/// Stuck stretches (y' = vb ≠ 0, or 0 without a belt) are skipped.
pub(crate) fn velocity_zeros<S: Solver + ?Sized>(
    solver: &S,
    spacing: f64,
    mut found: impl FnMut(Sample, bool),
) {
    let (a, b) = solver.interval();
    if !(b > a) || solver.dense(0.5 * (a + b)).phase == Phase::Stick {
        return;
    }
    let n = ((b - a) / spacing).ceil().clamp(1.0, MOST_SAMPLES) as u64;
    let at = |i: u64| {
        if i == n {
            b
        } else {
            a + (b - a) * (i as f64 / n as f64)
        }
    };
    let mut previous = solver.dense(a);
    for i in 1..=n {
        let t = at(i);
        let current = solver.dense(t);
        let maximum = previous.v > 0.0 && current.v <= 0.0;
        let minimum = previous.v < 0.0 && current.v >= 0.0;
        if maximum || minimum {
            let (mut lo, mut hi) = (previous.tau, t);
            let mut past = current;
            for _ in 0..200 {
                let mid = 0.5 * (lo + hi);
                if mid <= lo || mid >= hi {
                    break;
                }
                let s = solver.dense(mid);
                let before = if maximum { s.v > 0.0 } else { s.v < 0.0 };
                if before {
                    lo = mid;
                } else {
                    hi = mid;
                    past = s;
                }
            }
            found(past, maximum);
        }
        previous = current;
    }
}
