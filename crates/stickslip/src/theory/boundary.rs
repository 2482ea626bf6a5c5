//! The exact stick-slip boundary β_c(w, ζ, μs): the smallest drive amplitude for which the
//! symmetric non-sticking periodic solution ([`super::PeriodicSolution`]) exists.
//!
//! Below β_min = √D·|r|/w (see [`super::periodic`]) there is no candidate at all; above it the
//! candidate is valid once the net force at its turning points exceeds μs and its velocity
//! keeps its sign over each half period. Neither condition is monotone in an obvious way, so
//! the search does not assume it: it finds an amplitude that is valid (doubling from the
//! larger of 2β_min and the paper's estimate), scans 32 evenly spaced amplitudes between β_min
//! and there for the first valid one, then bisects between it and the invalid one before it
//! to a relative width of 4ε. Each test of validity is exact (closed form plus the exact
//! solver's velocity-zero search). A valid island narrower than the scan's spacing below the
//! first valid scan point would be missed; none has been seen for 0.05 ≤ w ≤ 10 (a check of
//! 3000 amplitudes below β_c and 400 up to 20·β_c, at 120 frequencies for each of
//! ζ = 0, 0.0468, 0.2 and 1, found the validity changing exactly once).

use super::paper::paper_boundary;
use super::periodic::{Matching, Obstruction, PeriodicSolution};
use crate::error::{check, Error, NoSolutionReason, Quantity, Result};
use crate::params::Params;
use serde::{Deserialize, Serialize};

/// Number of evenly spaced amplitudes scanned between β_min and a valid amplitude.
const SCAN_POINTS: usize = 32;
/// Largest amplitude tried before giving up.
const BETA_LIMIT: f64 = 1e12;

/// The exact stick-slip boundary at one (ζ, w, μs).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct StickSlipBoundary {
    /// Damping ratio ζ.
    pub zeta: f64,
    /// Drive frequency w.
    pub w: f64,
    /// Static-to-kinetic friction ratio μs.
    pub mu_s: f64,
    /// β_c: the symmetric non-sticking periodic solution exists at β_c (to a relative 4ε)
    /// and not just below.
    pub beta_c: f64,
    /// What goes wrong just below β_c: a stop at the turning points or mid-swing.
    pub below: Obstruction,
    /// `Some(n)` near ζ = 0, w = 1/(2n), where the symmetric solution is (at the point
    /// itself) one of a continuum of periodic motions, most of them asymmetric, and nearby
    /// attracts only weakly (see [`PeriodicSolution::continuum`]).
    pub continuum: Option<u32>,
}

/// The exact stick-slip boundary β_c(w, ζ, μs).
///
/// # Errors
/// - [`Error::InvalidParameter`] for ζ < 0, w ≤ 0, μs < 1 or non-finite values.
/// - [`Error::NoSolution`] at ζ = 0, w = 1/k for odd k (no periodic solution for any β), and
///   if no β up to 1e12 gives a valid solution.
/// - Numerical failures of the exact solver ([`Error::EventSearch`]).
pub fn stick_slip_boundary(zeta: f64, w: f64, mu_s: f64) -> Result<StickSlipBoundary> {
    check("zeta", zeta, zeta >= 0.0, "must be finite and >= 0")?;
    check("w", w, w > 0.0, "must be finite and > 0")?;
    check("mu_s", mu_s, mu_s >= 1.0, "must be finite and >= 1")?;
    let matching = Matching::new(zeta, w).map_err(|why| Error::NoSolution {
        what: Quantity::ExactBoundary,
        reason: NoSolutionReason::Obstruction(why),
    })?;
    let attempt = |beta: f64| -> Result<std::result::Result<PeriodicSolution, Obstruction>> {
        let params = Params {
            zeta,
            w,
            beta,
            phi: 0.0,
            mu_s,
            vb: 0.0,
            law: crate::friction::FrictionLaw::Coulomb,
        };
        PeriodicSolution::from_matching(&params, &matching)
    };
    let beta_min = matching.beta_min();
    let mut hi = (2.0 * beta_min)
        .max(paper_boundary(zeta, w).unwrap_or(1.0))
        .max(1.0);
    while attempt(hi)?.is_err() {
        hi *= 2.0;
        if hi > BETA_LIMIT {
            return Err(Error::NoSolution {
                what: Quantity::ExactBoundary,
                reason: NoSolutionReason::NoBetaBelow { limit: BETA_LIMIT },
            });
        }
    }
    let mut lo = beta_min;
    for j in 1..SCAN_POINTS {
        let beta = beta_min + (hi - beta_min) * (j as f64 / SCAN_POINTS as f64);
        if attempt(beta)?.is_ok() {
            hi = beta;
            break;
        }
        lo = beta;
    }
    let mut below = match attempt(lo)? {
        Err(why) => why,
        Ok(_) => unreachable!("lo is invalid by construction"),
    };
    for _ in 0..200 {
        if hi - lo <= 4.0 * f64::EPSILON * hi {
            break;
        }
        let mid = 0.5 * (lo + hi);
        match attempt(mid)? {
            Ok(_) => hi = mid,
            Err(why) => {
                lo = mid;
                below = why;
            }
        }
    }
    Ok(StickSlipBoundary {
        zeta,
        w,
        mu_s,
        beta_c: hi,
        below,
        continuum: matching.continuum(),
    })
}
