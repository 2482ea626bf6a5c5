//! Theory curves drawn over the simulated points: the paper's series solution (its eqs. 11
//! and 13) and the exact symmetric sliding orbit (Den Hartog's construction with damping).

use super::super::Context;
use super::common::beta_color;
use crate::plot::{Quantity, Series, Style};
use anyhow::Result;
use plotters::style::RGBColor;
use stickslip::theory::curves::{abscissae, theory_curve, Theory, TheoryQuantity};
use stickslip::{Parameter, Params};

/// Points of a theory curve.
const POINTS: usize = 400;

/// What the gain figure's theory curves are.
pub const GAIN_NOTE: &str = "Dashed: the paper's series solution (its eq. 11); solid: the \
    exact symmetric sliding orbit, drawn where it exists (above the exact stick-slip boundary). \
    The gain here is G1 = A1/β, as in the paper's formula: the simulated points are the \
    fundamental of the simulated u_C over U (fig4.csv's gain1; its gain is G = (y_max − \
    y_min)/(2β), Table 1's G). Where the exact orbit exists the \
    simulation lands on it; the series formula is close far above the boundary and off by tens \
    of percent near it, and below it gives a gain where the oscillator in fact sticks.";

/// What the harmonic figure's theory curves are, given whether panel (b) draws the exact
/// orbit anywhere and at how many of its values of β the simulated motion sticks.
pub fn harmonic_note(exact_in_b: bool, sticking: usize, of: usize) -> String {
    let where_exact = if exact_in_b {
        ""
    } else {
        " (in (b) nowhere: at Ω/ω0 = 0.33 no β shown has one, and its legend lists only the \
         paper's curves)"
    };
    let sticks = match (sticking, of) {
        (0, _) => "the motion slides at every β shown".to_string(),
        (s, n) if s == n => format!("the motion sticks at every one of the {n} values of β shown"),
        (s, n) => format!("the motion sticks at {s} of the {n} values of β shown"),
    };
    format!(
        "Dashed: the paper's series solution (eq. 11); solid: the exact sliding orbit where it \
         exists{where_exact}. The series A3 (independent of β) is exact for a sliding motion, \
         since the friction force of a symmetric sliding motion is exactly a square wave; at \
         Ω/ω0 = 0.33 the third harmonic is near resonance (3Ω ≈ ω0) and {sticks}, where \
         neither formula applies and the simulated A3 grows with β."
    )
}

/// What the boundary curves are.
pub const BOUNDARY_NOTE: &str = "Dashed: the paper's approximate boundary (its eq. 13, which \
    with x ≈ A1 cos Ωt is w²A1 = 1); solid: the exact boundary β_c(w), the smallest β for which \
    the symmetric orbit slides without stopping. Both curves are for the PWL model; on the PWL \
    map the exact boundary follows the edge of the sliding region, while the paper's departs \
    from it away from resonance (below it at low frequency, where the exact β_c grows like \
    2/w² rather than 1/w²).";

/// The base parameters of the paper's circuit (μs = 1, φ = 0) at (w, β).
fn base(ctx: &Context, w: f64, beta: f64) -> Result<Params> {
    super::common::paper_params(ctx, w, beta)
}

/// The quantity each theory is drawn as: dashed for the paper's series, solid for the exact
/// orbit.
fn theory_quantity(theory: Theory) -> Quantity {
    match theory {
        Theory::Paper => Quantity::PaperTheory,
        Theory::Exact => Quantity::ExactTheory,
    }
}

/// The line style of each theory (see [`theory_quantity`]).
pub fn theory_style(theory: Theory) -> Style {
    theory_quantity(theory).style()
}

/// Legend entries that say what the line styles mean (no data of their own), one per theory
/// drawn in `curves`: a theory whose curves have no point in the figure (the exact sliding
/// orbit where it exists nowhere) has no entry.
pub fn style_legend(curves: &[Series]) -> Vec<Series> {
    [(Theory::Paper, "paper, eq. 11"), (Theory::Exact, "exact")]
        .into_iter()
        .filter(|&(theory, _)| {
            curves.iter().any(|s| {
                s.style == theory_style(theory)
                    && s.points.iter().any(|(x, y)| x.is_finite() && y.is_finite())
            })
        })
        .map(|(theory, label)| Series::new(label, vec![], INK, theory_style(theory)))
        .collect()
}

/// The colour of legend entries that stand for a style, not for data.
pub const INK: RGBColor = crate::plot::INK;

/// Gain curves A1/β of the paper's series solution and of the exact periodic solution, one
/// colour per β, without legend entries (see [`style_legend`]).
pub fn gain_curves(ctx: &Context, betas: &[f64]) -> Result<Vec<Series>> {
    let ws = abscissae(0.2, 2.0, POINTS);
    let mut out = Vec::new();
    for &beta in betas {
        for theory in [Theory::Paper, Theory::Exact] {
            let curve = theory_curve(
                theory,
                TheoryQuantity::Gain1,
                &base(ctx, 1.0, beta)?,
                Parameter::W,
                &ws,
            );
            out.push(Series::new(
                "",
                curve.points(),
                beta_color(beta),
                theory_style(theory),
            ));
        }
    }
    Ok(out)
}

/// A1 and A3 (volts) of the paper's series solution and of the exact periodic solution, in
/// the colours of the simulated A1 and A3, without legend entries.
pub fn harmonic_curves(
    ctx: &Context,
    parameter: Parameter,
    fixed: f64,
    from: f64,
    to: f64,
    colors: [RGBColor; 2],
) -> Result<Vec<Series>> {
    let ut = ctx.diode.turn_on;
    let base = match parameter {
        Parameter::W => base(ctx, from, fixed)?,
        _ => base(ctx, fixed, from)?,
    };
    let xs = abscissae(from, to, POINTS);
    let mut out = Vec::new();
    for theory in [Theory::Paper, Theory::Exact] {
        for (k, color) in [1, 3].into_iter().zip(colors) {
            let curve = theory_curve(theory, TheoryQuantity::Harmonic(k), &base, parameter, &xs);
            out.push(Series::new(
                "",
                curve.scaled(ut).points(),
                color,
                theory_style(theory),
            ));
        }
    }
    Ok(out)
}

/// The legend entry of the exact boundary of [`boundary_curves`].
pub const EXACT_LABEL: &str = "exact β_c";

/// The paper's and the exact stick-slip boundaries β_c(w) (NaN where they leave the map).
pub fn boundary_curves(ctx: &Context, w_min: f64, w_max: f64) -> Result<Vec<Series>> {
    let ws = abscissae(w_min, w_max, POINTS);
    let curve = |theory| -> Result<Vec<(f64, f64)>> {
        Ok(theory_curve(
            theory,
            TheoryQuantity::Boundary,
            &base(ctx, 1.0, 1.0)?,
            Parameter::W,
            &ws,
        )
        // Past the top of the map (β = 4) the chart's frame cuts the line: keeping the next
        // point lets the curve reach the frame instead of stopping short of it.
        .within(0.0, 8.0)
        .points())
    };
    Ok(vec![
        Quantity::PaperTheory.series("paper, eq. 13", curve(Theory::Paper)?),
        Quantity::ExactTheory.series(EXACT_LABEL, curve(Theory::Exact)?),
    ])
}
