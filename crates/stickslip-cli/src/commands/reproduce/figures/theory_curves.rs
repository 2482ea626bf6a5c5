//! Theory curves drawn over the simulated points: the paper's series solution (its eqs. 11
//! and 13) and the exact symmetric sliding orbit (Den Hartog's construction with damping).

use super::super::Context;
use super::common::beta_color;
use crate::plot::{Series, Style, PALETTE};
use anyhow::Result;
use stickslip::steady::SweepParameter;
use stickslip::theory::{
    paper_boundary, stick_slip_boundary, PaperHarmonic, PaperSeries, PeriodicSolution,
};
use stickslip::Params;

/// Points of a theory curve.
const POINTS: usize = 400;

/// What the gain figure's theory curves are.
pub const GAIN_NOTE: &str = "Dashed: the paper's series solution (its eq. 11); solid: the \
    exact symmetric sliding orbit, drawn where it exists (above the exact stick-slip boundary). \
    G is A1/β here, as in the paper's formula: the simulated points are the fundamental of the \
    simulated u_C over U (fig4.csv also lists the peak gain). Where the exact orbit exists the \
    simulation lands on it; the series formula is close far above the boundary and off by tens \
    of percent near it, and below it gives a gain where the oscillator in fact sticks.";

/// What the harmonic figure's theory curves are.
pub const HARMONIC_NOTE: &str = "Dashed: the paper's series solution (eq. 11); solid: the exact \
    sliding orbit where it exists. The series A3 (independent of β) is exact for a sliding \
    motion, since the friction force of a symmetric sliding motion is exactly a square wave; \
    at Ω/ω0 = 0.33 the third harmonic is near resonance (3Ω ≈ ω0) and the motion sticks for \
    most β, where neither formula applies and the simulated A3 grows with β.";

/// What the boundary curves are.
pub const BOUNDARY_NOTE: &str = "Dashed: the paper's approximate boundary (its eq. 13, which \
    with x ≈ A1 cos Ωt is w²A1 = 1); solid: the exact boundary β_c(w), the smallest β for which \
    the symmetric orbit slides without stopping. Both curves are for the PWL model; on the PWL \
    map the exact boundary follows the edge of the sliding region, while the paper's departs \
    from it away from resonance (below it at low frequency, where the exact β_c grows like \
    2/w² rather than 1/w²).";

fn grid(from: f64, to: f64) -> impl Iterator<Item = f64> {
    (0..POINTS).map(move |k| from + (to - from) * k as f64 / (POINTS - 1) as f64)
}

/// Gain curves A1/β of the paper's series solution and of the exact periodic solution.
pub fn gain_curves(ctx: &Context, betas: &[f64]) -> Result<Vec<Series>> {
    let zeta = ctx.scales.zeta();
    let mut out = Vec::new();
    for &beta in betas {
        let paper: Vec<(f64, f64)> = grid(0.2, 2.0)
            .map(|w| {
                (
                    w,
                    PaperSeries::new(zeta, w, beta).map_or(f64::NAN, |p| p.gain()),
                )
            })
            .collect();
        let exact: Vec<(f64, f64)> = grid(0.2, 2.0)
            .map(|w| {
                let g = Params::new(zeta, w, beta)
                    .ok()
                    .and_then(|p| PeriodicSolution::new(&p).ok())
                    .map_or(f64::NAN, |s| s.gain());
                (w, g)
            })
            .collect();
        out.push(Series::new(
            format!("β = {beta}, paper eq. 11"),
            paper,
            beta_color(beta),
            Style::Dashed(2),
        ));
        out.push(Series::new(
            format!("β = {beta}, exact"),
            exact,
            beta_color(beta),
            Style::Line(2),
        ));
    }
    Ok(out)
}

/// A1 and A3 (volts) of the paper's series solution and of the exact periodic solution.
pub fn harmonic_curves(
    ctx: &Context,
    parameter: SweepParameter,
    fixed: f64,
    from: f64,
    to: f64,
) -> Result<Vec<Series>> {
    let zeta = ctx.scales.zeta();
    let ut = ctx.circuit.diode.turn_on;
    let at = |x: f64| match parameter {
        SweepParameter::W => (x, fixed),
        SweepParameter::Beta => (fixed, x),
    };
    let mut curves: [Vec<(f64, f64)>; 4] = Default::default();
    for x in grid(from, to) {
        let (w, beta) = at(x);
        let paper = PaperSeries::new(zeta, w, beta).ok();
        curves[0].push((x, paper.map_or(f64::NAN, |p| p.a1 * ut)));
        // A3 of eq. (11) does not depend on β (nor need A1 to exist).
        curves[1].push((
            x,
            PaperHarmonic::new(zeta, w, 3).map_or(f64::NAN, |h| h.amplitude.abs() * ut),
        ));
        let exact = Params::new(zeta, w, beta)
            .ok()
            .and_then(|p| PeriodicSolution::new(&p).ok());
        curves[2].push((x, exact.as_ref().map_or(f64::NAN, |s| s.a1() * ut)));
        curves[3].push((
            x,
            exact
                .as_ref()
                .map_or(f64::NAN, |s| s.harmonic(3).amplitude * ut),
        ));
    }
    let [p1, p3, e1, e3] = curves;
    Ok(vec![
        Series::new("A1, paper eq. 11", p1, PALETTE[0], Style::Dashed(2)),
        Series::new("A3, paper eq. 11", p3, PALETTE[1], Style::Dashed(2)),
        Series::new("A1, exact", e1, PALETTE[0], Style::Line(2)),
        Series::new("A3, exact", e3, PALETTE[1], Style::Line(2)),
    ])
}

/// The paper's and the exact stick-slip boundaries β_c(w) (NaN where they leave the map).
pub fn boundary_curves(ctx: &Context, w_min: f64, w_max: f64) -> Result<Vec<Series>> {
    let zeta = ctx.scales.zeta();
    let inside = |b: f64| {
        if (0.0..=4.0).contains(&b) {
            b
        } else {
            f64::NAN
        }
    };
    let paper: Vec<(f64, f64)> = grid(w_min, w_max)
        .map(|w| (w, paper_boundary(zeta, w).map_or(f64::NAN, inside)))
        .collect();
    let exact: Vec<(f64, f64)> = grid(w_min, w_max)
        .map(|w| {
            (
                w,
                stick_slip_boundary(zeta, w, 1.0).map_or(f64::NAN, |b| inside(b.beta_c)),
            )
        })
        .collect();
    Ok(vec![
        Series::new("paper eq. 13", paper, PALETTE[6], Style::Dashed(2)),
        Series::new("exact β_c", exact, PALETTE[3], Style::Line(2)),
    ])
}
