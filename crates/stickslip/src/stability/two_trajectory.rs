//! The largest Lyapunov exponent from two nearby trajectories (Benettin's method), without
//! tangents: an independent check of [`super::lyapunov_exponents`].
//!
//! A reference state x_k and a companion x_k + d₀u_k (|u_k| = 1, Euclidean norm in (y, y'))
//! are each mapped over one drive period by the exact solver (the strobe map P); the
//! separation d_k = |P(x_k + d₀u_k) − P(x_k)| gives g_k = ln(d_k/d₀), and the companion is set
//! back to the distance d₀ along the new separation, u_{k+1} = (P(x_k + d₀u_k) − P(x_k))/d_k.
//! The last 50 periods of the transient (all of it when shorter) align u with the most
//! unstable direction unrecorded; then λ₁ = Σg_k/(NT), with the block error and convergence
//! check of [`super::lyapunov`]. The finite separation biases each g_k by a relative O(d₀) (the
//! curvature of the map), which the block error does not include.

use super::error::StabilityError;
use super::lyapunov::{halves_agree, mean_and_error, Estimate, LyapunovOptions};
use crate::error::{Error, Result};
use crate::exact::ExactSolver;
use crate::params::{Params, State};
use crate::solver::{run_until, Solver};
use serde::{Deserialize, Serialize};

/// The two-trajectory estimate of the largest Lyapunov exponent.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct TwoTrajectoryEstimate {
    /// The largest exponent with its block error.
    pub largest: Estimate,
    /// Whether the two halves of the measurement agree (as in [`super::lyapunov`]).
    pub converged: bool,
    /// The block means, per unit τ, in time order.
    pub block_means: Vec<f64>,
}

/// Drive periods at the end of the transient that align the separation (fewer when the
/// transient is shorter).
const ALIGN: usize = 50;

/// A reference state and its companion's direction.
struct Pair {
    x: State,
    u: [f64; 2],
    separation: f64,
    /// Periods done, alignment included (for the error report).
    done: usize,
}

impl Pair {
    /// Map both over one drive period, renormalise, and return ln(d/d₀).
    fn step(&mut self, params: &Params) -> Result<f64> {
        let companion = State {
            y: self.x.y + self.separation * self.u[0],
            v: self.x.v + self.separation * self.u[1],
        };
        let next = strobe_step(params, self.x)?;
        let next_companion = strobe_step(params, companion)?;
        let delta = [next_companion.y - next.y, next_companion.v - next.v];
        let distance = delta[0].hypot(delta[1]);
        self.done += 1;
        if !(distance > 0.0) {
            return Err(StabilityError::SeparationLost { period: self.done }.into());
        }
        self.u = [delta[0] / distance, delta[1] / distance];
        self.x = next;
        Ok((distance / self.separation).ln())
    }
}

/// One drive period of the exact flow from `state` at a strobe.
fn strobe_step(params: &Params, state: State) -> Result<State> {
    let mut solver = ExactSolver::new(*params, state);
    run_until(&mut solver, params.drive_period(), |_| {})?;
    Ok(solver.state())
}

/// The largest Lyapunov exponent of the motion from `initial` (at τ = 0, a strobe) from two
/// trajectories `separation` apart (dimensionless, in (y, y'); for example 1e-9), renormalised
/// once per drive period (see the module documentation). The transient, the periods and the
/// blocks are those of `options`.
///
/// # Errors
/// [`Error::InvalidParameter`] for invalid parameters, state, options or separation;
/// [`StabilityError::SeparationLost`] when the two trajectories coincide; whatever the solver
/// reports.
pub fn two_trajectory_exponent(
    params: &Params,
    initial: State,
    options: &LyapunovOptions,
    separation: f64,
) -> Result<TwoTrajectoryEstimate> {
    let options = options.validate()?;
    let params = params.validate()?;
    crate::exact::check_coulomb(&params)?;
    if !(separation > 0.0 && separation.is_finite()) {
        return Err(Error::InvalidParameter {
            name: "separation",
            value: separation,
            allowed: "must be finite and > 0",
        });
    }
    let period = params.drive_period();
    // The last `align` periods of the transient turn the separation into the most unstable
    // direction, unrecorded.
    let align = options.transient_periods.min(ALIGN);
    let mut solver = ExactSolver::new(params, State::new(initial.y, initial.v)?);
    run_until(
        &mut solver,
        (options.transient_periods - align) as f64 * period,
        |_| {},
    )?;
    let mut pair = Pair {
        x: solver.state(),
        u: [std::f64::consts::FRAC_1_SQRT_2; 2],
        separation,
        done: 0,
    };
    for _ in 0..align {
        pair.step(&params)?;
    }
    let per_block = options.periods / options.blocks;
    let length = per_block as f64 * period;
    let mut block_means = Vec::with_capacity(options.blocks);
    for _ in 0..options.blocks {
        let mut growth = 0.0;
        for _ in 0..per_block {
            growth += pair.step(&params)?;
        }
        block_means.push(growth / length);
    }
    let (mean, error) = mean_and_error(&block_means);
    Ok(TwoTrajectoryEstimate {
        largest: Estimate {
            per_tau: mean,
            error_per_tau: error,
            per_period: mean * period,
            error_per_period: error * period,
        },
        converged: halves_agree(&block_means, options.significance),
        block_means,
    })
}
