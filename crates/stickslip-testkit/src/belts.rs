//! The belts that the tests of the smooth friction laws (Stribeck, cubic) share: the laws
//! and the experiments built from them.

use stickslip::experiment::Experiment;
use stickslip::friction::FrictionLaw;
use stickslip::physical::Circuit;

/// A Stribeck law that falls from μs to 1 over vs = 0.3 (δ = 2) and rises again with
/// η = 0.05.
pub const STRIBECK: FrictionLaw = FrictionLaw::Stribeck {
    vs: 0.3,
    delta: 2.0,
    eta: 0.05,
};

/// The cubic law μ(s) = μs − k1·s + k3·s³ with k1 = k3 = 0.5.
pub const CUBIC: FrictionLaw = FrictionLaw::Cubic { k1: 0.5, k3: 0.5 };

/// A forced belt: (ζ, w, β, μs, vb) with `law`.
///
/// # Panics
/// For values the library refuses.
pub fn belt(law: FrictionLaw, (zeta, w, beta, mu_s, vb): (f64, f64, f64, f64, f64)) -> Experiment {
    Experiment::dimensionless(zeta, w, beta)
        .and_then(|e| e.with_mu_s(mu_s))
        .and_then(|e| e.with_vb(vb))
        .and_then(|e| e.with_law(law))
        .expect("a valid belt")
}

/// The Stribeck law of the belt benchmark (vs = 0.5, δ = 2, η = 0.05) at the paper's ζ,
/// w = 1 and without a drive: the base of the maps over vb and μs that the tests draw.
///
/// # Panics
/// Never for these values (the library accepts them).
pub fn benchmark_stribeck_belt() -> Experiment {
    Experiment::dimensionless(Circuit::paper().scales().zeta(), 1.0, 0.0)
        .and_then(|e| {
            e.with_law(FrictionLaw::Stribeck {
                vs: 0.5,
                delta: 2.0,
                eta: 0.05,
            })
        })
        .expect("a valid belt")
}
