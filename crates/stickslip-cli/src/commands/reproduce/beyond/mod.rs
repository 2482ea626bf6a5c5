//! The chapter "Beyond the paper": what the exact solver and its stability analysis
//! (`stickslip::stability`) find in the same oscillator that the paper could not. One
//! module and one function per figure; [`JOBS`] lists them in the report's order, the
//! chapter's heading first. A new figure is a module here and a line in [`JOBS`].

mod basins_mirror;
mod bifurcation_w;
mod branch_fold;
mod chaos_map;
mod chaos_sweep;
mod floquet_laws;
mod paper_exponents;

pub use basins_mirror::BasinMap;
pub use bifurcation_w::{Diagram as BifurcationDiagram, SPECIAL_COLUMNS};
pub use chaos_map::ChaosMap;
pub use paper_exponents::paper_exponent_map;

use super::report::Report;
use super::{Context, Job};
use crate::plot::class_color;
use anyhow::Result;
use plotters::style::RGBColor;
use stickslip::steady::MotionClass;
use stickslip::Experiment;

use basins_mirror::basins_mirror;
use bifurcation_w::bifurcation_w;
use branch_fold::branch_fold;
use chaos_map::chaos_map;
use chaos_sweep::chaos_sweep;
use floquet_laws::floquet_laws;
use paper_exponents::paper_exponents;

/// The chapter's jobs, in the report's order: (progress label, function).
pub const JOBS: &[Job] = &[
    ("Beyond the paper", chapter),
    ("chaos: λ1 against w", chaos_sweep),
    ("chaos: (w, β) map", chaos_map),
    ("the paper's non-periodic class", paper_exponents),
    ("bifurcation diagram in w", bifurcation_w),
    ("basins of attraction", basins_mirror),
    ("a branch and its stability", branch_fold),
    ("Floquet multipliers, PWL and Shockley", floquet_laws),
];

/// The chapter's heading and introduction.
fn chapter(report: &mut Report, _ctx: &Context) -> Result<()> {
    report.chapter(
        "beyond",
        "Beyond the paper",
        "The paper's model, solved exactly and differentiated exactly: every segment of the \
         motion has a closed form, and so has its 2×2 Jacobian (the segment matrices and the \
         saltation matrices of turns, stops and releases; <code>stickslip::stability</code>, \
         docs/stability.md). This gives periodic orbits by Newton's method with their Floquet \
         multipliers (<code>stickslip orbit</code>) and Lyapunov exponents with a statistical \
         error (<code>stickslip lyapunov</code>), and so a motion class that means something: \
         a motion that does not repeat is <i>chaotic</i> when its largest exponent λ1 is \
         positive beyond 4 standard errors. Exponents are per unit τ = ω0·t. The strobe \
         points, basins and branches of the last three figures come from <code>stickslip \
         bifurcation</code>, <code>stickslip basins</code> and <code>stickslip continue</code> \
         (docs/bifurcation.md): the continuation re-detects the events of every orbit, so a \
         branch goes on by itself where a stop appears or disappears.",
    );
    Ok(())
}

/// The setting of the literature on chaos in this oscillator (Licskó and Csernák 2014): no
/// viscous damping, static friction three times the kinetic.
fn literature() -> Result<Experiment> {
    Ok(Experiment::dimensionless(0.0, 0.3, 9.0)?.with_mu_s(3.0)?)
}

/// The colour of a class for markers: as in the maps, but sliding darker (the maps' light
/// grey does not show as a marker on white).
fn marker_color(class: MotionClass) -> RGBColor {
    match class {
        MotionClass::Sliding => RGBColor(110, 110, 110),
        c => class_color(c),
    }
}

/// A drive frequency of a grid for a caption: 4 decimals at most, no trailing zeros.
fn frequency(w: f64) -> String {
    let text = format!("{w:.4}");
    text.trim_end_matches('0').trim_end_matches('.').to_string()
}
