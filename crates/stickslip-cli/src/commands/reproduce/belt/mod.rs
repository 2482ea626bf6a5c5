//! The chapter "Friction-induced vibration": the block on a moving belt (issue 36), the
//! model of the friction-induced-vibration literature. One module and one function per
//! section; [`JOBS`] lists them in the report's order, the chapter's heading first.

mod approximation;
mod closed_form;
mod forced_map;
mod sweep;

pub use approximation::APPROXIMATION_COLUMNS;
pub use closed_form::CLOSED_FORM_COLUMNS;
pub use sweep::BELT_SWEEP_COLUMNS;

use super::report::Report;
use super::{Context, Job};
use anyhow::Result;
use stickslip::friction::FrictionLaw;
use stickslip::{Experiment, State};

/// The chapter's jobs, in the report's order: (progress label, function).
pub const JOBS: &[Job] = &[
    ("Friction-induced vibration", chapter),
    ("belt: amplitude against vb", sweep::belt_sweep),
    ("belt: the closed form", closed_form::closed_form),
    ("belt: Thomsen & Fidlin", approximation::approximation),
    ("belt: a forced belt's map", forced_map::forced_map),
];

/// The chapter's heading and introduction.
fn chapter(report: &mut Report, _ctx: &Context) -> Result<()> {
    report.chapter(
        "belt",
        "Friction-induced vibration",
        "The oscillator on a belt that moves at the speed vb (in units of the kinetic \
         friction's displacement per unit τ): friction acts on the slip s = y' − vb, \
         y'' + 2ζ y' + y + sgn(s) μ(|s|) = β cos(w τ + φ) while slipping, y' = vb while stuck \
         and the net force stays within μs. Without a drive (β = 0) the motion is \
         self-excited: a friction law that falls with the slip speed, or static friction \
         above kinetic, feeds it. The laws are Coulomb's (μ = 1, static μs), Stribeck's \
         (μ = 1 + (μs − 1) exp(−(s/vs)^δ) + η s) and the cubic μ = μs − k1 s + k3 s³ \
         (<code>--friction-law</code>, docs/limits.md). Coulomb's belt is solved exactly; the \
         others slide on the smooth-law integrator with every stop and release located to \
         10⁻¹². Steady sliding, the equilibrium y' = 0, y = sgn(vb) μ(|vb|), is stable where \
         2ζ + μ'(|vb|) > 0 (<code>stickslip::theory::SteadySliding</code>).",
    );
    Ok(())
}

/// An undriven belt: damping `zeta`, static level `mu_s`, `law`, belt speed `vb`, from `start`.
fn belt(zeta: f64, mu_s: f64, law: FrictionLaw, vb: f64, start: State) -> Result<Experiment> {
    Ok(Experiment::dimensionless(zeta, 1.0, 0.0)?
        .with_mu_s(mu_s)?
        .with_law(law)?
        .with_vb(vb)?
        .with_initial(start)?)
}
