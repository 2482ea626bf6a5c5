//! Branches of periodic orbits by pseudo-arclength continuation, with the event sequence
//! re-detected at every step.
//!
//! A periodic orbit of period p (drive periods) is a zero of
//!
//! ```text
//! F(x, λ) = P^p(x; λ) − x,       x = (y, y') at the strobe, λ one of ζ, w, β, μs, vb,
//! ```
//!
//! with P^p the p-fold strobe map of the exact solver ([`crate::stability::strobe_map`]). Its
//! zeros form curves in (y, y', λ), the branches. Continuation follows a branch by steps of
//! arclength Δs: from a point u_k with unit tangent t_k (the null vector of the 2×3 Jacobian
//! `[M − I | ∂P^p/∂λ]`, oriented along the branch), the predictor u_k + Δs·t_k is corrected by
//! Newton's method onto the branch within the hyperplane t_k·(u − u_k) = Δs. Along the
//! hyperplane the corrector's matrix `[[M − I, ∂P^p/∂λ], [t_kᵀ]]` stays regular at a fold,
//! where M − I alone is singular, so the branch goes round folds and on along their unstable
//! side. M is the exact monodromy matrix ([`crate::stability`]); ∂P^p/∂λ is a central
//! difference (step [`ContinuationOptions::derivative_step`] relative), which only slows the
//! corrector's convergence, not the accuracy of the points (the residual is exact); for the
//! belt speed vb it is exact ([`crate::stability::strobe_map_parameter_derivative`]). Where
//! the strobe falls inside a stop the state is stuck to the belt, y' = vb, and stays so along
//! the branch (moving with λ when λ is vb): the corrector solves for (y, λ) alone. Every
//! accepted point is confirmed as an orbit by [`crate::stability::find_periodic_orbit`] to
//! its tolerance, which also gives its events, stops and Floquet multipliers.
//!
//! **No fixed event sequence.** Every evaluation of P^p runs the exact solver, which finds the
//! events of that orbit by itself: when a turning point becomes a stop (or a stop shrinks to
//! nothing) the next step simply has another sequence of events, and the branch goes on. Tools that
//! continue hybrid systems with a prescribed sequence of modes (COCO's hybrid toolbox, PWSDDE-cont)
//! stop there and need the sequence re-entered by hand. The map is continuous across such a change
//! but its Jacobian jumps (a different saltation matrix), so the branch has a kink there and the
//! multipliers jump: a border collision, which may change the stability at once.
//!
//! **Special points** between two accepted points, each located by bisection along the
//! arclength to within [`ContinuationOptions::locate_tolerance`] (which bounds the error of
//! its parameter value, since |t_λ| ≤ 1):
//!
//! - [`SpecialKind::Grazing`]: the event counts of the orbit (turning points, stops) change;
//!   the parameter value, the counts and the multipliers on either side are reported. Grazing
//!   points are located first; they split the interval into smooth pieces, on which:
//! - [`SpecialKind::Fold`]: a real multiplier passes +1 (det(M − I) changes sign) and the
//!   branch turns back in λ (a saddle-node: the stable and the unstable orbit meet);
//!   [`SpecialKind::BranchPoint`] when it passes +1 without turning (another branch crosses,
//!   for example where the symmetry of a symmetric orbit breaks);
//! - [`SpecialKind::PeriodDoubling`]: a real multiplier passes −1 (det(M + I) changes sign): a
//!   branch of period 2p is born;
//! - [`SpecialKind::NeimarkSacker`]: a complex pair passes the unit circle (det M − 1 changes
//!   sign). With Coulomb's law it cannot happen on orbits that stop (det M = 0) nor, since
//!   turns contract phase area, on sliding orbits with ζ ≥ 0; a falling Stribeck law's
//!   sliding orbit on a belt has one (`tests/friction_continuation.rs`).
//!
//! A change of stability shows as [`Side::stability`] before and after each special point.
//!
//! **A stop mid-swing.** Where a slide's lowest speed reaches zero with the net force within
//! μs > 1, the motion stops there for a finite time: the strobe map jumps, and the steps stall
//! against the jump. The last orbit's slides are then searched for that minimum
//! ([`Obstacle::Grazing`]) and the branch ends as [`BranchEnd::Grazing`], with the orbit of the
//! same period and the new stop found just past it, if any: that one lies a finite jump away on
//! a branch of its own, so it is named, not joined.
//!
//! ```
//! use stickslip::continuation::{continue_orbit, ContinuationOptions, SpecialKind};
//! use stickslip::stability::{find_periodic_orbit, NewtonOptions};
//! use stickslip::{Parameter, Params, State};
//! // The paper's ζ with μs = 1.5 at w = 0.9: the sliding orbit at β = 1.45 turns into one with
//! // two stops per period as β falls below about 1.4133.
//! let params = Params::new(0.046816, 0.9, 1.45).unwrap().with_mu_s(1.5).unwrap();
//! let orbit = find_periodic_orbit(&params, State { y: 0.25, v: 2.1 }, 1, &NewtonOptions::default()).unwrap();
//! let branch = continue_orbit(&params, Parameter::Beta, &orbit, 1.40, &ContinuationOptions::default(), &()).unwrap();
//! let grazing = branch.special.iter().find(|s| s.kind == SpecialKind::Grazing).unwrap();
//! assert_eq!((grazing.before.stops, grazing.after.stops), (0, 2));
//! assert!((grazing.value - 1.4133).abs() < 1e-3);
//! ```

mod branch;
mod corrector;
mod curve;
mod detect;
mod follow;
mod grazing;
mod obstacle;
mod options;
mod report;
mod special;
mod step;

pub use branch::{Branch, BranchEnd, BranchPoint};
pub use curve::{
    check_spec, curve, curve_within, find_start, find_start_of, follow_curve, follow_curve_of,
    follow_curve_within, follow_curve_within_of, Border, BorderKind, Codim2Kind, Codim2Point,
    Codim2Report, Curve, CurveEnd, CurvePoint, CurveReport, CurveSide, CurveSideReport, CurveSpec,
    CurveStart, CurveStartReport, Follow, NoStart, StabilityChange,
};
pub use follow::{
    continue_both_ways, continue_both_ways_of, continue_orbit, continue_orbit_of, settled_orbit,
};
pub use obstacle::{obstacle_of, Obstacle, SlideMinimum};
pub use options::{check_ends, check_parameter, ContinuationOptions};
pub use report::{BranchReport, SideReport, SpecialReport};
pub use special::{Side, SpecialKind, SpecialPoint};
