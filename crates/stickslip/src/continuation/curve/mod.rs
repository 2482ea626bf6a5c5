//! Curves of special points in two parameters: folds, period doublings, Neimark–Sacker points
//! and grazings of periodic orbits, followed in (Q, P) by pseudo-arclength continuation of an
//! extended system.
//!
//! **The extended system.** A special point of a periodic orbit of period p is a zero of
//!
//! ```text
//! F(u) = P^p(x; Q, P) − x = 0,     g(u) = 0,        u = (y, y', Q, P),
//! ```
//!
//! three equations in four unknowns: a curve. g is the defining condition of the special
//! point:
//!
//! - fold: det(M − I) = 0, a real multiplier at +1 (M the monodromy matrix, exact: the
//!   product of the segments' and the saltation matrices of [`crate::stability`]);
//! - period doubling: det(M + I) = 0;
//! - Neimark–Sacker: det M − 1 = 0 with a complex pair, both multipliers on the unit circle
//!   (the Coulomb model has none: det M < 1 on every orbit, docs/bifurcation.md, so
//!   [`curve`] and [`find_start`] refuse it with [`crate::Unsupported::NoNeimarkSacker`]);
//! - grazing: the condition of the event that appears ([`BorderKind`]): the net force
//!   |F − y| at a velocity zero equal to μs (a turning point becomes a stop), a slide's lowest
//!   speed zero (it touches rest mid-swing), or the net force at an extremum of the drive near
//!   a stop equal to μs (a release becomes tangential).
//!
//! For the maps of this model, whose strobe map is a 2-dimensional map with exact derivatives,
//! this is the minimal form of the systems that the continuation packages for smooth systems
//! solve with a bordered or fully extended boundary-value problem (MatCont's limit-point and
//! period-doubling curves of cycles; Govaerts, Kuznetsov and Dhooge, *Numerical continuation of
//! bifurcations of limit cycles in MATLAB*, SIAM J. Sci. Comput. 27 (2005)). The test functions
//! det(M ∓ I) and det M − 1 are COCO's `hspo` toolbox's (Dankowicz and Schilder, *Recipes for
//! Continuation*, SIAM 2013, ch. 17: the monitor functions Π(λ − 1), Π(λ + 1), Π(λᵢλⱼ − 1) of
//! the hybrid periodic orbit's monodromy matrix, a product of transfer matrices each premultiplied
//! by its saltation matrix), held at zero here instead of monitored. The grazing condition
//! follows COCO's grazing curves of hybrid periodic orbits (ch. 15, the impact oscillator: the
//! velocity at the start of a trajectory segment made a continuation parameter and held at 0
//! while the forcing's amplitude and frequency vary) and SlideCont's defining systems for
//! sliding bifurcations of cycles (Dercole and Kuznetsov, *SlideCont: an AUTO97 driver for
//! bifurcation analysis of Filippov systems*, ACM TOMS 31 (2005) 95–119; Kuznetsov, Rinaldi and
//! Gragnani, *One-parameter bifurcations in planar Filippov systems*, IJBC 13 (2003)
//! 2157–2188: the cycle together with the tangency of the vector field to the discontinuity
//! boundary at a point of the cycle, H(x) = 0 and H_x(x)·f(x) = 0). Unlike both, the event
//! sequence is not prescribed: the exact solver finds the events of every orbit afresh, and the
//! curve knows its followed event by its kind and its time from the strobe.
//!
//! **Derivatives.** M and the parameter derivatives ∂P^p/∂(Q, P) are exact
//! ([`crate::stability::strobe_map_parameter_derivatives`]: the tangent dynamics extended to
//! the parameters, the strobe's time moving with w). The gradient of g is a central difference
//! of the exact g (step [`ContinuationOptions::derivative_step`] relative to max(|u_i|, 0.1)),
//! which, like the difference quotient of a branch, only slows the corrector's convergence:
//! every point satisfies F = 0 and g = 0 to the tolerance with the exact residuals. Where the
//! strobe falls inside a stop the map is differentiable in y only, and the velocity's column is
//! left out (y' = 0 there).
//!
//! **The smooth friction laws.** The system is written against [`crate::stability::Dynamics`],
//! as the branches of [`super::continue_orbit_of`] are: with the Stribeck or cubic law on a
//! belt ([`crate::stability::FrictionDynamics`]) M is the stiff solver's tangent dynamics,
//! ∂P^p/∂(Q, P) come from its sensitivities ([`crate::stability::Dynamics::parameter_derivative`]),
//! and the residuals are taken to its map's accuracy
//! ([`crate::stability::Dynamics::map_tolerance`]); Q and P may be any of its parameters (vb and
//! the law's own too). Folds, period doublings and Neimark–Sacker points are followed
//! ([`find_start_of`], [`follow_curve_of`]); grazings are not (their conditions are events of
//! the exact solver: [`crate::Unsupported::GrazingCurveNeedsCoulomb`]), and such a curve ends
//! where its event counts change, located by bisection.
//!
//! **Pseudo-arclength.** From a point u_k with unit tangent t_k (the null vector of the 3×4
//! Jacobian, oriented along the curve), the predictor u_k + Δs·t_k is corrected by Newton's
//! method in the hyperplane t_k·(u − u_k) = Δs, steps halved where the residual does not
//! fall. Steps grow by 1.5 and are capped by [`ContinuationOptions::max_step`], by
//! [`ContinuationOptions::max_parameter_step`] of Q's range, and by the angle between
//! neighbouring tangents ([`ContinuationOptions::max_angle`]).
//!
//! **Grazing orbits on one side.** At a grazing the map is continuous with a jump of its
//! Jacobian (a border collision), or itself jumps (a stop of finite length appears at once,
//! μs > 1). The orbits of a grazing curve are taken on the side where the event has not
//! happened (a turning point, not yet a stop; a slide still moving; a stop not yet split), a
//! hair inside it: g = σ·h − δ with δ = 40 × the tolerance (relative to max(1, β, μs); 10⁻⁹ for
//! a slide touching rest, where the exact solver's search tells a touch from a near miss), so
//! that the event sequence, the multipliers and the stability along the curve are those of
//! that side. The parameters of a grazing point are off by δ/|∂h/∂P|, about 10⁻¹⁰.
//!
//! **Along the curve** ([`Curve`]):
//!
//! - every point's orbit with its event counts and multipliers, and its stability apart from
//!   the followed multiplier ([`CurvePoint::stability`]); where it changes
//!   ([`Curve::stability_changes`]);
//! - codimension-two points ([`Codim2Kind`]), each located by bisection along the arclength
//!   to [`ContinuationOptions::locate_tolerance`]: on a fold curve a cusp (its tangent's
//!   (Q, P) part reverses), a 1:1 resonance (det M = 1: the other multiplier at +1) and a
//!   fold-flip point (det M = −1); on a period-doubling curve a 1:2 resonance (det M = 1) and
//!   a fold-flip point; on a Neimark–Sacker curve the 1:1 and 1:2 resonances (tr M = ±2);
//!   on a grazing curve a fold, a period doubling or a Neimark–Sacker point of the grazing
//!   orbit (det(M ∓ I) or det M − 1 changing sign): where a fold curve meets it. Where the
//!   event counts of a fold, period-doubling or Neimark–Sacker curve change, the curve meets a
//!   grazing: that point is located and the curve ends there ([`CurveEnd::Codim2`]), its
//!   special point going on, if at all, as a border collision of another event sequence.
//!   The same where such a curve reverses sharply in (Q, P) with the same event counts on both
//!   sides: it has passed through a grazing onto the mirror image of its orbit (a stop shrunk
//!   to nothing at one turning point, appearing at the other), whose curve in the parameters is
//!   the same; the meeting is located from the step's point nearest the border;
//! - why it ends ([`CurveEnd`]): the end of Q's range, another event sequence, a
//!   codimension-two point, the model's range of a parameter, or no progress, with what the
//!   last orbit is closest to.
//!
//! **The start** ([`find_start`], [`curve`]): the orbit the motion settles on at the model's
//! point is continued in P towards a value ([`continue_orbit`](super::continue_orbit)) until
//! its first special point of the followed kind (for a grazing also the end of the branch
//! against a jump of the strobe map); that point is corrected onto the extended system at the
//! model's value of Q and followed over Q from there towards `to`, and towards `from` too when
//! the model's value lies strictly between them.
//!
//! ```
//! use stickslip::continuation::{curve, ContinuationOptions, CurveSpec, Follow};
//! use stickslip::theory::stick_slip_boundary;
//! use stickslip::{Experiment, Parameter};
//! // The sliding orbit of the paper's circuit (μs = 1) at w = 1.2: where a stop appears at
//! // its turning points as β falls is the exact stick-slip boundary β_c(w).
//! let experiment = Experiment::paper().with_w(1.2).unwrap().with_beta(3.0).unwrap();
//! let spec = CurveSpec {
//!     follow: Follow::Grazing,
//!     vary: Parameter::Beta,
//!     vary_to: 0.5,
//!     over: Parameter::W,
//!     from: 1.2,
//!     to: 1.3,
//! };
//! let grazing = curve(&experiment, &spec, &ContinuationOptions::default(), &())
//!     .unwrap()
//!     .unwrap();
//! let zeta = grazing.params.zeta;
//! for p in &grazing.points {
//!     let exact = stick_slip_boundary(zeta, p.over, 1.0).unwrap().beta_c;
//!     assert!((p.vary - exact).abs() < 1e-8);
//! }
//! ```
//!
//! [`ContinuationOptions::derivative_step`]: crate::continuation::ContinuationOptions::derivative_step
//! [`ContinuationOptions::max_step`]: crate::continuation::ContinuationOptions::max_step
//! [`ContinuationOptions::max_parameter_step`]: crate::continuation::ContinuationOptions::max_parameter_step
//! [`ContinuationOptions::max_angle`]: crate::continuation::ContinuationOptions::max_angle
//! [`ContinuationOptions::locate_tolerance`]: crate::continuation::ContinuationOptions::locate_tolerance

mod border;
mod kinds;
mod report;
mod start;
mod system;
mod trace;
mod types;

pub use kinds::{BorderKind, Codim2Kind, Follow};
pub use report::{Codim2Report, CurveReport, CurveSideReport, CurveStartReport};
pub use start::{
    check_spec, curve, curve_within, find_start, find_start_of, CurveSpec, CurveStart, NoStart,
};
pub use trace::{follow_curve, follow_curve_of, follow_curve_within, follow_curve_within_of};
pub use types::{Border, Codim2Point, Curve, CurveEnd, CurvePoint, CurveSide, StabilityChange};
