//! Theory curves drawn over the simulated points: the paper's series solution and the exact
//! periodic solution.

use super::super::Context;
use crate::plot::Series;
use anyhow::Result;
use stickslip::steady::SweepParameter;

/// What the gain figure's theory curves are.
pub const GAIN_NOTE: &str = "";
/// What the harmonic figure's theory curves are.
pub const HARMONIC_NOTE: &str = "";

/// Gain curves of the paper's series solution and of the exact periodic solution.
pub fn gain_curves(_ctx: &Context, _betas: &[f64]) -> Result<Vec<Series>> {
    Ok(Vec::new())
}

/// A1 and A3 curves of the paper's series solution and of the exact periodic solution.
pub fn harmonic_curves(
    _ctx: &Context,
    _parameter: SweepParameter,
    _fixed: f64,
    _from: f64,
    _to: f64,
) -> Result<Vec<Series>> {
    Ok(Vec::new())
}

/// What the boundary curves are.
pub const BOUNDARY_NOTE: &str = "";

/// The paper's and the exact stick-slip boundaries β_c(w).
pub fn boundary_curves(_ctx: &Context, _w_min: f64, _w_max: f64) -> Result<Vec<Series>> {
    Ok(Vec::new())
}
