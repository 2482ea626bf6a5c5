//! The verdict on a motion that does not repeat ([`NonperiodicVerdict`]). A leaf: it imports
//! nothing of the crate, so [`super::StabilityError`] (and so [`crate::error`]) can carry it.

use serde::{Deserialize, Serialize};

/// What the largest Lyapunov exponent λ₁ says about a motion that does not repeat, with σ its
/// standard error and k = [`LyapunovOptions::significance`](super::LyapunovOptions::significance).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum NonperiodicVerdict {
    /// λ₁ > kσ and the measurement converged: nearby motions separate exponentially.
    Chaotic,
    /// |λ₁| ≤ kσ and the measurement converged: neither growth nor decay (quasi-periodic
    /// motion on a torus; also rest, which is periodic).
    QuasiPeriodic,
    /// λ₁ < −kσ and the measurement converged: the motion contracts onto an attractor that
    /// is periodic, either not yet reached or of a longer period than was looked for.
    Contracting,
    /// A self-excited motion (β = 0 on a belt: autonomous) with |λ₁| ≤ kσ and λ₂ < −kσ
    /// (or −∞, from stops): a limit cycle, λ₁ = 0 along it, perturbations across it decay.
    LimitCycle,
    /// A self-excited motion with λ₁ < −kσ: both exponents negative, the motion settles on
    /// an equilibrium (steady sliding on the belt).
    Equilibrium,
    /// The two halves of the measurement disagree (a transient, or chaos that ends): no
    /// verdict at this length.
    Undecided,
}

impl NonperiodicVerdict {
    /// The one rule by which every tool judges a motion that does not repeat from its largest
    /// exponent λ₁ ± σ (`lambda`, `sigma`, per unit τ) with k = `significance` standard errors:
    /// [`NonperiodicVerdict::Undecided`] unless the measurement `converged` (its halves agree,
    /// its error is finite), then chaotic where λ₁ > kσ, contracting where λ₁ < −kσ,
    /// quasi-periodic between. `steady` (through
    /// [`NonperiodicClassification`](super::NonperiodicClassification)), the Lyapunov maps,
    /// `bifurcation` and `basins` (through
    /// [`crate::attractor::record_strobes_of`]) all take their verdicts from it, so that one
    /// motion measured alike gets one verdict from each.
    pub fn of(lambda: f64, sigma: f64, converged: bool, significance: f64) -> Self {
        let k = significance;
        if !converged {
            NonperiodicVerdict::Undecided
        } else if lambda > k * sigma {
            NonperiodicVerdict::Chaotic
        } else if lambda < -k * sigma {
            NonperiodicVerdict::Contracting
        } else {
            NonperiodicVerdict::QuasiPeriodic
        }
    }
}
