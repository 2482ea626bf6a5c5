//! Shared pieces of the figures: colours per β, steady states of the paper's circuit.

use super::super::Context;
use anyhow::Result;
use plotters::style::RGBColor;
use stickslip::scan::{Axis, ParameterRange, Sweep, SweepDirection, SweepPoint};
use stickslip::{Experiment, Parameter, Params, SteadyOptions, SteadyState};

/// One colour per drive amplitude, the same in every figure.
pub fn beta_color(beta: f64) -> RGBColor {
    const BETAS: [f64; 10] = [1.0, 1.07, 1.2, 1.43, 1.6, 2.14, 3.61, 7.1, 14.3, 4.0];
    // β = 1 is not grey: grey is the drive's colour.
    const COLORS: [RGBColor; 10] = [
        RGBColor(0, 110, 110),
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

/// A class for titles: "static" carries the paper's rule, which allows a small motion.
pub fn class_title(class: stickslip::steady::MotionClass) -> String {
    match class {
        stickslip::steady::MotionClass::Static => "static (amplitude < β/100)".to_string(),
        other => other.label().to_string(),
    }
}

/// The range of `values` with `frac` of its span added on each side (a loop that must not
/// touch the frame).
pub fn padded(values: impl Iterator<Item = f64>, frac: f64) -> Option<(f64, f64)> {
    let (lo, hi) = values
        .filter(|v| v.is_finite())
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), v| {
            (a.min(v), b.max(v))
        });
    (lo < hi).then_some((lo - frac * (hi - lo), hi + frac * (hi - lo)))
}

/// Dimensionless parameters of the paper's circuit at (w, β).
pub fn paper_params(ctx: &Context, w: f64, beta: f64) -> Result<Params> {
    Ok(ctx
        .paper
        .params_with(&[(Parameter::W, w), (Parameter::Beta, beta)])?)
}

/// The paper's experiment driven at (w, β).
pub fn paper_at(ctx: &Context, w: f64, beta: f64) -> Result<Experiment> {
    Ok(ctx.paper.clone().with_w(w)?.with_beta(beta)?)
}

/// Steady state from rest with the exact solver.
pub fn steady_pwl(ctx: &Context, w: f64, beta: f64) -> Result<(Params, SteadyState)> {
    let s = paper_at(ctx, w, beta)?.steady()?;
    Ok((s.params, s))
}

/// A number for file contents.
pub fn num(x: f64) -> String {
    format!("{x}")
}

/// Sweep `parameter` of the paper's circuit up then down (each step from the last), the other
/// drive parameter fixed at `fixed`, from rest.
pub fn sweep_pwl(
    ctx: &Context,
    parameter: Parameter,
    fixed: f64,
    from: f64,
    to: f64,
    steps: usize,
    spectrum: bool,
) -> Result<Vec<SweepPoint>> {
    let experiment = match parameter {
        Parameter::W => ctx.paper.clone().with_beta(fixed)?,
        _ => ctx.paper.clone().with_w(fixed)?,
    };
    let range = ParameterRange::new(parameter.label(), from, to, steps)?;
    Ok(Sweep::new(&experiment, Axis::range(parameter, &range)?)?
        .direction(SweepDirection::Both)
        .options(SteadyOptions::default().with_spectrum(spectrum))?
        .run(&|_: usize, _: usize| !crate::output::interrupted())?)
}
