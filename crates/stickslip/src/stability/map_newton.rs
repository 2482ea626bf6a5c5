//! Newton's method on a strobe map computed to a finite accuracy: the maps of the stiff
//! integrator, the Shockley model's ([`super::ShockleyDynamics::find_periodic_orbit`]) and the
//! smooth friction laws' ([`super::FrictionDynamics::find_periodic_orbit`]), which differ only
//! in their map and its accuracy.
//!
//! Steps (M − I)δ = −(P^p(x) − x), halved while the residual grows, until
//! max(|Δy|, |Δy'|) ≤ tolerance·max(1, |y|, |y'|)·max(1, max|M_ij|). Such a map is the
//! solver's: smooth in the state where the solver's decisions (its step sizes, rejections and
//! Newton iterations) do not change, with jumps of the order of its accuracy where they do.
//! Where a full step no longer reduces a residual within the map's relative accuracy (times
//! the same scale), the iterate is at the map's own accuracy and is taken as the orbit, as it
//! is when the steps run out there.

use super::error::StabilityError;
use super::matrix::Multiplier;
use super::periodic_orbit::{NewtonOptions, PeriodicOrbit, Stability};
use super::smooth::ShockleyDynamics;
use super::strobe::StrobeImage;
use crate::error::{Error, Result};
use crate::params::{Params, State};

/// The Floquet multipliers of an image at a fixed point: where the motion stuck on the way
/// (no ln|det J|), M = A·diag(1, 0)·B has rank one, so they are tr M and exactly 0 (rounding
/// would leave ~1e-16); otherwise the eigenvalues with det M from its logarithm
/// ([`ShockleyDynamics::multipliers`]).
fn multipliers(image: &StrobeImage) -> [Multiplier; 2] {
    if image.log_det.is_none() {
        [
            Multiplier::real(image.jacobian.trace()),
            Multiplier::real(0.0),
        ]
    } else {
        ShockleyDynamics::multipliers(image)
    }
}

/// The periodic orbit of period `period` near `guess` by Newton's method on `map` (the
/// `period`-fold strobe map of `params`, validated before it is called) whose relative
/// accuracy is `accuracy` (see the module documentation), with the image of the guess (the
/// map's first evaluation).
///
/// With `loose` = (tolerance, modulus) the iteration also stops at the looser residual
/// tolerance·max(1, |y|, |y'|)·max(1, max|M_ij|) where the largest multiplier's modulus is at
/// most `modulus`, and then takes one more Newton step from the last iterate without
/// evaluating the map there (a step that stalled is not taken): the orbit's state is that
/// step's end, its monodromy, events and multipliers those of the last image (the settling
/// of a steady state, [`ShockleyDynamics`]' `settling_orbit`).
///
/// # Errors
/// [`Error::InvalidParameter`] for invalid parameters, guess, options or p = 0;
/// [`StabilityError::NoConvergence`], [`StabilityError::SingularJacobian`]; what `map`
/// reports.
pub(crate) fn find_orbit<F>(
    map: F,
    params: &Params,
    guess: State,
    period: usize,
    options: &NewtonOptions,
    accuracy: f64,
    loose: Option<(f64, f64)>,
) -> Result<(PeriodicOrbit, StrobeImage)>
where
    F: Fn(&Params, State) -> Result<StrobeImage>,
{
    let options = options.validate()?;
    let params = params.validate()?;
    if period == 0 {
        return Err(Error::InvalidParameter {
            name: "period",
            value: 0.0,
            allowed: "must be at least 1",
        });
    }
    let mut x = State::new(guess.y, guess.v)?;
    let mut image = map(&params, x)?;
    let first = image.clone();
    let residual = |image: &StrobeImage, x: State| {
        let r = [image.state.y - x.y, image.state.v - x.v];
        (r[0].abs().max(r[1].abs()), r)
    };
    let limit = |x: State, image: &StrobeImage| {
        options.tolerance * 1f64.max(x.y.abs()).max(x.v.abs()) * image.jacobian.max_abs().max(1.0)
    };
    // The map's own accuracy: its jumps where the solver's decisions change.
    let at_accuracy = |norm: f64, x: State, image: &StrobeImage| {
        norm <= accuracy / options.tolerance * limit(x, image)
    };
    // Where the settling's iteration may stop.
    let finished = |norm: f64, x: State, image: &StrobeImage| {
        loose.is_some_and(|(tolerance, modulus)| {
            norm <= tolerance / options.tolerance * limit(x, image)
                && multipliers(image)[0].modulus() <= modulus
        })
    };
    let (mut norm, mut r) = residual(&image, x);
    let mut residuals = vec![norm];
    let mut iterations = 0;
    let mut stalled = false;
    while norm > limit(x, &image) && !finished(norm, x, &image) {
        if iterations == options.max_iterations {
            if at_accuracy(norm, x, &image) {
                stalled = true;
                break;
            }
            return Err(StabilityError::NoConvergence {
                iterations,
                residual: norm,
                tolerance: limit(x, &image),
            }
            .into());
        }
        let m = image.jacobian.minus_identity();
        let step = m
            .solve([-r[0], -r[1]])
            .ok_or(StabilityError::SingularJacobian {
                y: x.y,
                v: x.v,
                determinant: m.det(),
            })?;
        let mut fraction = 1.0;
        let mut halvings = 0;
        loop {
            let trial = State::new(x.y + fraction * step[0], x.v + fraction * step[1])?;
            let trial_image = map(&params, trial)?;
            let (trial_norm, trial_r) = residual(&trial_image, trial);
            if trial_norm >= norm && halvings == 0 && at_accuracy(norm, x, &image) {
                // A full step that does not help within the map's accuracy: its jumps.
                stalled = true;
                break;
            }
            if trial_norm < norm || halvings == options.max_halvings {
                (x, image, norm, r) = (trial, trial_image, trial_norm, trial_r);
                break;
            }
            fraction *= 0.5;
            halvings += 1;
        }
        if stalled {
            break;
        }
        iterations += 1;
        residuals.push(norm);
    }
    let multipliers = multipliers(&image);
    let modulus = multipliers[0].modulus();
    if loose.is_some() && !stalled {
        // The finishing step, from the last image (a step that stalled is not taken).
        if let Some(step) = image.jacobian.minus_identity().solve([-r[0], -r[1]]) {
            if let Ok(next) = State::new(x.y + step[0], x.v + step[1]) {
                x = next;
            }
        }
    }
    let stability = if (1.0 - modulus).abs() <= options.neutral_band {
        Stability::Neutral
    } else if modulus < 1.0 {
        Stability::Stable
    } else {
        Stability::Unstable
    };
    let orbit = PeriodicOrbit::from_image(
        &params,
        period,
        x,
        image,
        (multipliers, stability),
        iterations,
        residuals,
    );
    Ok((orbit, first))
}
