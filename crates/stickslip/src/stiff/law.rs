//! The seam between a smooth law and the stiff integrator: [`SmoothLaw`].

use crate::error::Result;

/// Most parameters of its own a [`SmoothLaw`] may have (the columns of the sensitivities are
/// kept on the stack).
pub const MAX_LAW_PARAMETERS: usize = 6;

/// A smooth law D(v) of the velocity v = y' in
///
/// ```text
/// y'' + 2ζ y' + y + D(y') = β cos(w τ + φ)      (dimensionless, τ = ω0·t),
/// ```
///
/// what the stiff integrator ([`super::Radau5`]) asks of it: its value and slope in the state
/// (D and D' at v, the only nonlinearity of the equation, and the Newton matrix of the stage
/// equations), and its derivatives by its own parameters θ (the right-hand sides of the
/// forward sensitivities, [`super::sensitivity`]).
///
/// The state stays two-dimensional (y, y'); a law that depends on a moving reference, such as
/// a friction law μ(|s|) of the slip s = y' − v_b against a belt, is a law of v all the same
/// (with its knee at v = v_b). A law that jumps (Coulomb's sgn(s) at s = 0) is smooth on each
/// side: each slip direction is a law of its own, valid while the slip keeps its sign, and the
/// solver that switches between them handles the stops exactly; within one slip phase the
/// integrator sees a smooth law.
///
/// The Shockley diode pair ([`crate::shockley::DiodeLaw`]) is the first law: D(v) =
/// a·asinh(v/ε) + r·v, with its own parameters (a, ε, r).
///
/// **Steep laws.** Where D' is much larger than the rest of the stage equations (a diode
/// near zero current: slope a/ε ≈ 7.5·10³, and 10²⁰ near the PWL limit), Newton's method in
/// the velocity stalls: a step that is right for D' overshoots where the slope falls off. A
/// law may then offer a second chart, a coordinate u(v) in which it is nearly linear (the
/// junction voltage of a diode), by [`SmoothLaw::steep_slope`] and [`SmoothLaw::steep_step`];
/// the integrator solves for u on the stages where du/dv exceeds the stage's own diagonal.
/// A law without one (the default) is solved in v alone.
pub trait SmoothLaw: Copy + std::fmt::Debug + Send + Sync + 'static {
    /// The names of the law's own parameters θ (dimensionless), in the order of
    /// [`SmoothLaw::parameter_derivatives`]; at most [`MAX_LAW_PARAMETERS`].
    const PARAMETERS: &'static [&'static str];

    /// The same law, checked (for a law built by struct literal or deserialised).
    ///
    /// # Errors
    /// [`crate::Error::InvalidParameter`] naming the first invalid parameter.
    fn validate(&self) -> Result<Self>;

    /// D(v) and D'(v) = dD/dv, together (the integrator's inner loop).
    fn value_and_slope(&self, v: f64) -> (f64, f64);

    /// ∂D/∂θ_k at v for the law's own parameters, in the order of
    /// [`SmoothLaw::PARAMETERS`], written to `out` (of that length).
    fn parameter_derivatives(&self, v: f64, out: &mut [f64]);

    /// Where the law is steepest and its linearisation in v sees least of it (a diode's zero
    /// current): a Newton step in v that would cross it stops on it, where the steep chart
    /// takes over; and a step rejected across it is retried up to the crossing that its own
    /// polynomial predicts. `None` (the default): no such point.
    fn knee(&self) -> Option<f64> {
        None
    }

    /// The slope du/dv of the steep chart u at v, given the law's `slope` D'(v) there, when
    /// the law has one (see the trait's documentation). Default: `None`.
    fn steep_slope(&self, v: f64, slope: f64) -> Option<f64> {
        let _ = (v, slope);
        None
    }

    /// The velocity after a Newton step `delta` in the steep chart from `v` (where D(v) =
    /// `value`), limited as the law needs where the step leaves the range in which the chart
    /// dominates the stage, whose own diagonal is `diagonal`. Called only where
    /// [`SmoothLaw::steep_slope`] is given; the default is the linear step.
    fn steep_step(&self, v: f64, value: f64, delta: f64, diagonal: f64) -> f64 {
        let _ = (value, diagonal);
        match self.steep_slope(v, self.value_and_slope(v).1) {
            Some(slope) => v + delta / slope,
            None => v + delta,
        }
    }
}
