//! The options of a continuation.

use crate::error::{invalid, Error, Result};
use crate::options::{Allowed, OptionKey};
use serde::{Deserialize, Serialize};

/// Options of [`continue_orbit`](super::continue_orbit). Arclengths are measured in (y, y', λ), all
/// dimensionless.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct ContinuationOptions {
    /// First step of arclength. Default 1e-3.
    pub initial_step: f64,
    /// Smallest step before the continuation gives up. Default 1e-9.
    pub min_step: f64,
    /// Largest step of arclength. Default 0.1.
    pub max_step: f64,
    /// Largest step of the parameter, as a fraction of the range being continued over.
    /// Default 0.02 (at least 50 points over the range).
    pub max_parameter_step: f64,
    /// Largest angle (radians) between the tangents of two neighbouring points on a smooth
    /// piece of the branch; a step that turns more is halved. Default 0.2.
    pub max_angle: f64,
    /// Most points of a branch. Default 5000.
    pub max_points: usize,
    /// Relative tolerance of the residual of P^p(x) − x, as
    /// [`NewtonOptions::tolerance`](crate::stability::NewtonOptions::tolerance). Default 1e-12.
    pub tolerance: f64,
    /// Most Newton steps of the corrector. Default 12.
    pub corrector_iterations: usize,
    /// Width in arclength to which special points are located. Default 1e-9.
    pub locate_tolerance: f64,
    /// Step of the difference quotient ∂P^p/∂λ, relative to max(|λ|, 0.1). Default 1e-6.
    pub derivative_step: f64,
}

impl Default for ContinuationOptions {
    fn default() -> Self {
        Self {
            initial_step: 1e-3,
            min_step: 1e-9,
            max_step: 0.1,
            max_parameter_step: 0.02,
            max_angle: 0.2,
            max_points: 5000,
            tolerance: 1e-12,
            corrector_iterations: 12,
            locate_tolerance: 1e-9,
            derivative_step: 1e-6,
        }
    }
}

impl ContinuationOptions {
    /// These options with the largest step of arclength `step`; the first step is lowered to
    /// fit.
    pub fn with_max_step(mut self, step: f64) -> Self {
        self.max_step = step;
        self.initial_step = self.initial_step.min(step);
        self
    }

    /// The step below which the continuation is crawling: 1e3 × `min_step`, or the geometric
    /// mean of `min_step` and `max_step` when that is smaller. A step this small is taken
    /// whatever the angle between tangents, and 25 of them in a row end the branch as
    /// [`BranchEnd::Stalled`](super::BranchEnd::Stalled). It lies below `max_step` whenever
    /// `max_step > min_step`, so a small `max_step` is a resolution the steps keep, not a stall.
    pub fn crawl_step(&self) -> f64 {
        (1e3 * self.min_step).min((self.min_step * self.max_step).sqrt())
    }

    /// Check every field.
    ///
    /// # Errors
    /// [`Error::InvalidParameter`] naming the first bad field.
    pub fn validate(self) -> Result<Self> {
        let positive = |x: f64| x > 0.0 && x.is_finite();
        if !positive(self.min_step) {
            return invalid("min_step", self.min_step, "must be finite and > 0");
        }
        if !(positive(self.max_step) && self.max_step >= self.min_step) {
            return Err(Error::InvalidOption {
                option: OptionKey::MaxStep,
                value: self.max_step,
                allowed: Allowed::Text("must be finite and >= min_step"),
            });
        }
        OptionKey::MaxStep.check(self.max_step)?;
        if !(self.initial_step >= self.min_step && self.initial_step <= self.max_step) {
            return invalid(
                "initial_step",
                self.initial_step,
                "must lie between min_step and max_step",
            );
        }
        if !(positive(self.max_parameter_step) && self.max_parameter_step <= 1.0) {
            return invalid(
                "max_parameter_step",
                self.max_parameter_step,
                "must be > 0 and <= 1",
            );
        }
        if !(positive(self.max_angle) && self.max_angle < std::f64::consts::FRAC_PI_2) {
            return invalid("max_angle", self.max_angle, "must be > 0 and < pi/2");
        }
        OptionKey::MaxPoints.check_count(self.max_points)?;
        if !(self.tolerance > 0.0 && self.tolerance < 1e-3) {
            return invalid("tolerance", self.tolerance, "must be > 0 and < 1e-3");
        }
        if self.corrector_iterations == 0 {
            return invalid("corrector_iterations", 0.0, "must be at least 1");
        }
        if !positive(self.locate_tolerance) {
            return invalid(
                "locate_tolerance",
                self.locate_tolerance,
                "must be finite and > 0",
            );
        }
        if !(self.derivative_step > 1e-12 && self.derivative_step < 1e-2) {
            return invalid(
                "derivative_step",
                self.derivative_step,
                "must be > 1e-12 and < 1e-2",
            );
        }
        Ok(self)
    }
}

/// Check the ends of a branch before any work: both finite and `to` another value than
/// `from` (the ranges of the parameter are the experiment's to check).
///
/// # Errors
/// [`Error::InvalidOption`] naming [`OptionKey::ContinuationFrom`] or
/// [`OptionKey::ContinuationTo`] (`invalid --to 1.2: must differ from --from`).
pub fn check_ends(from: f64, to: f64) -> Result<()> {
    OptionKey::ContinuationFrom.check(from)?;
    OptionKey::ContinuationTo.check(to)?;
    if to == from {
        return Err(Error::InvalidOption {
            option: OptionKey::ContinuationTo,
            value: to,
            allowed: Allowed::Differs {
                other: OptionKey::ContinuationFrom,
            },
        });
    }
    Ok(())
}

/// Check before any work that `experiment`'s law has the continued `parameter`: μs is a
/// parameter of the piecewise-linear law only.
///
/// # Errors
/// [`crate::Unsupported::MuSNeedsPwl`] for μs with Shockley diodes.
pub fn check_parameter(experiment: &crate::Experiment, parameter: crate::Parameter) -> Result<()> {
    if parameter == crate::Parameter::MuS
        && experiment.diode_model() != crate::experiment::DiodeModel::Pwl
    {
        return Err(Error::Unsupported(crate::Unsupported::MuSNeedsPwl));
    }
    Ok(())
}
