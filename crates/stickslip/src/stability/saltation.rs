//! Saltation matrices: how a perturbation (δy, δy') jumps at an event.
//!
//! At an event at τ_e the motion meets a surface h(x, τ) = 0 and the vector field switches
//! from f⁻ to f⁺. A perturbed motion meets the surface at τ_e + δτ_e with
//! δτ_e = −∇h·δx / (∇h·f⁻ + ∂h/∂τ), and past both instants the two differ by
//! δx + (f⁻ − f⁺)δτ_e, so
//!
//! ```text
//! S = I + (f⁺ − f⁻) ∇hᵀ / (∇h·f⁻ + ∂h/∂τ)          (everything at the event).
//! ```
//!
//! With x = (y, y'), F(τ) = β cos(wτ + φ), a slide in direction s has f_s = (y', F − y − 2ζy'
//! − s), a stop has f₀ = (0, 0). At a velocity zero y' = 0, so the acceleration of a slide in
//! direction s there is a_s = F − y − s.
//!
//! - **Turn** (h = y', direction s⁻ → s⁺ = −s⁻): ∇h = (0, 1), ∇h·f⁻ = a⁻ = F − y − s⁻,
//!   f⁺ − f⁻ = (0, a⁺ − a⁻):
//!   ```text
//!   S_turn = diag(1, a⁺/a⁻) = diag(1, (|F − y| − 1)/(|F − y| + 1)).
//!   ```
//!   A turn happens only where s⁻(F − y) < −μs, so |a⁻| > μs + 1 ≥ 2 and the ratio lies in
//!   [(μs − 1)/(μs + 1), 1): a turn never amplifies a perturbation and never divides by a
//!   small number.
//! - **Stick** (h = y', f⁺ = f₀): S = I − (0, a⁻)ᵀ(0, 1)/a⁻, that is
//!   ```text
//!   S_stick = diag(1, 0),
//!   ```
//!   rank one: the velocity perturbation is erased. It does not depend on a⁻ and is applied
//!   without dividing by it, so it holds at a grazing stop as well.
//! - **Release** (stick → slip in direction s: h = s(F(τ) − y) − μs, the friction limit that
//!   moves with the drive): ∇h = (−s, 0), f⁻ = f₀ so ∇h·f⁻ = 0, ∂h/∂τ = sF'(τ_r) > 0 at an
//!   outward crossing, f⁺ = (0, a⁺) with a⁺ = s(μs − 1):
//!   ```text
//!   S_release = [[1, 0], [−(μs − 1)/(s F'(τ_r)), 1]],     F'(τ) = −βw sin(wτ + φ).
//!   ```
//!   A displacement δy along s delays the release by δy/(sF'), while the unperturbed motion
//!   already accelerates at a⁺: the shear. For μs > 1 it grows without bound as the release
//!   becomes tangential (sF' → 0, the drive's extremum just reaching the limit), where the
//!   map is not differentiable; [`release`] then returns non-finite entries.
//!
//!   **μs = 1 is degenerate**: a⁺ = 0, the vector field is continuous at the release (the
//!   stop is the attracting sliding mode of the Filippov system, and the slide leaves y' = 0
//!   tangentially, y' ≈ sF'(τ − τ_r)²/2). The shift of the release time has no first-order
//!   effect, S_release = I, also where F'(τ_r) = 0 and the formula reads 0/0. [`release`]
//!   returns the identity at μs = 1 without forming that quotient.
//! - **Zero-duration stop** (the velocity vanishes exactly where s⁺(F − y) = μs with the force
//!   moving outward, and the motion leaves at once in direction s⁺): the product
//!   ```text
//!   S_zero = S_release·S_stick = [[1, 0], [−(μs − 1)/(s⁺F'), 0]].
//!   ```
//!   This is the derivative on the side where a perturbed motion stops briefly. On the other
//!   side a perturbed motion turns without stopping, with |F − y| = μs:
//!   S_turn = diag(1, (μs − 1)/(μs + 1)). For μs > 1 the two differ and the flow has a kink
//!   there (it is continuous, and piecewise smooth); the tangent propagation uses the side the
//!   solver took. At μs = 1 both are diag(1, 0): the flow is differentiable across
//!   zero-duration stops.

use super::matrix::Matrix2;

/// Saltation matrix of a turn: the velocity reverses from direction `sign_before` (±1) with
/// net force `net_force` = β cos(wτ_e + φ) − y (dimensionless, |net_force| > μs at a turn):
/// diag(1, a⁺/a⁻) with a∓ = net_force ∓ s∓ (see the module documentation).
pub fn turn(net_force: f64, sign_before: f64) -> Matrix2 {
    let before = net_force - sign_before;
    let after = net_force + sign_before;
    Matrix2::diagonal(1.0, after / before)
}

/// Saltation matrix of a stop (slip → stick): diag(1, 0), the velocity perturbation erased.
pub fn stick() -> Matrix2 {
    Matrix2::diagonal(1.0, 0.0)
}

/// Saltation matrix of a release (stick → slip) in direction `sign_after` (±1), where the
/// drive changes at the rate `drive_rate` = F'(τ_r) = −βw sin(wτ_r + φ) (dimensionless), with
/// static-to-kinetic friction ratio `mu_s` ≥ 1: [[1, 0], [−(μs − 1)/(s F'), 1]], and exactly
/// the identity at μs = 1 (see the module documentation).
///
/// The entry is infinite (or of the wrong sign) when s·F' ≤ 0, a tangential release.
pub fn release(sign_after: f64, drive_rate: f64, mu_s: f64) -> Matrix2 {
    if mu_s == 1.0 {
        return Matrix2::IDENTITY;
    }
    Matrix2([[1.0, 0.0], [-(mu_s - 1.0) / (sign_after * drive_rate), 1.0]])
}

/// Saltation matrix of a zero-duration stop (stop and release in direction `sign_after` at one
/// instant): `release(..) · stick()`, the derivative on the side where perturbed motions stop
/// briefly (see the module documentation).
pub fn zero_duration_stop(sign_after: f64, drive_rate: f64, mu_s: f64) -> Matrix2 {
    release(sign_after, drive_rate, mu_s) * stick()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn turn_contracts_the_velocity_and_release_is_the_identity_at_mu_s_one() {
        // Turning from + with net force −3: a⁻ = −4, a⁺ = −2.
        assert_eq!(turn(-3.0, 1.0), Matrix2::diagonal(1.0, 0.5));
        assert_eq!(turn(3.0, -1.0), Matrix2::diagonal(1.0, 0.5));
        assert_eq!(release(1.0, 0.0, 1.0), Matrix2::IDENTITY);
        assert_eq!(release(-1.0, -2.0, 2.0).0[1][0], -0.5);
        let zero = zero_duration_stop(1.0, 0.5, 1.5);
        assert_eq!(zero, Matrix2([[1.0, 0.0], [-1.0, 0.0]]));
        // At μs = 1 the two sides of a zero-duration stop agree.
        assert_eq!(zero_duration_stop(1.0, 0.5, 1.0), turn(1.0, -1.0));
    }
}
