//! Shared pieces of the figures: colours per β, steady states of the paper's circuit.

use super::super::Context;
use anyhow::Result;
use plotters::style::RGBColor;
use stickslip::steady::{exact_solver, steady_state_from};
use stickslip::{Params, State, SteadyOptions, SteadyState};

/// One colour per drive amplitude, the same in every figure.
pub fn beta_color(beta: f64) -> RGBColor {
    const BETAS: [f64; 10] = [1.0, 1.07, 1.2, 1.43, 1.6, 2.14, 3.61, 7.1, 14.3, 4.0];
    const COLORS: [RGBColor; 10] = [
        RGBColor(120, 120, 120),
        RGBColor(0, 114, 178),
        RGBColor(86, 180, 233),
        RGBColor(0, 158, 115),
        RGBColor(204, 121, 167),
        RGBColor(213, 94, 0),
        RGBColor(230, 159, 0),
        RGBColor(0, 0, 0),
        RGBColor(117, 112, 179),
        RGBColor(166, 118, 29),
    ];
    BETAS
        .iter()
        .position(|b| (b - beta).abs() < 1e-9)
        .map(|i| COLORS[i])
        .unwrap_or(RGBColor(80, 80, 80))
}

/// Dimensionless parameters of the paper's circuit at (w, β).
pub fn paper_params(ctx: &Context, w: f64, beta: f64) -> Result<Params> {
    Ok(Params::new(ctx.scales.zeta(), w, beta)?)
}

/// Steady state from rest with the exact solver.
pub fn steady_pwl(ctx: &Context, w: f64, beta: f64) -> Result<(Params, SteadyState)> {
    let params = paper_params(ctx, w, beta)?;
    let s = steady_state_from(
        &exact_solver,
        &params,
        State::default(),
        &SteadyOptions::default(),
    )?;
    Ok((params, s))
}

/// A number for file contents.
pub fn num(x: f64) -> String {
    format!("{x}")
}

/// Sweep `parameter` of the paper's circuit up then down (each step from the last), the other
/// parameter fixed at `fixed`, from rest.
pub fn sweep_pwl(
    ctx: &Context,
    parameter: stickslip::steady::SweepParameter,
    fixed: f64,
    from: f64,
    to: f64,
    steps: usize,
    spectrum: bool,
) -> Result<Vec<stickslip::steady::SweepPoint>> {
    use stickslip::steady::{sweep, ParameterRange, SweepDirection, SweepParameter};
    let (w, beta, name) = match parameter {
        SweepParameter::W => (from, fixed, "w"),
        SweepParameter::Beta => (fixed, from, "beta"),
    };
    let base = paper_params(ctx, w, beta)?;
    let range = ParameterRange::new(name, from, to, steps)?;
    let options = SteadyOptions::default().with_spectrum(spectrum);
    Ok(sweep(
        &exact_solver,
        base,
        State::default(),
        parameter,
        &range,
        SweepDirection::Both,
        &options,
        &mut |_, _, _| !crate::output::interrupted(),
    )?)
}
