//! The p-fold strobe map and its exact Jacobian.

use super::error::StabilityError;
use super::matrix::Matrix2;
use super::tangent::Tangent;
use crate::error::{Error, Result};
use crate::exact::ExactSolver;
use crate::params::{Params, State};
use crate::solver::{Event, Hints, Phase, Solver};
use serde::{Deserialize, Serialize};

/// The image of a state under the p-fold strobe map P^p: the state p drive periods later,
/// with the Jacobian and the events on the way.
///
/// The strobe map takes the state at τ = kT (T = 2π/w, drive phase φ) to the state at
/// τ = (k + 1)T; it does not depend on k, so it is computed from τ = 0.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct StrobeImage {
    /// The state at τ = pT.
    pub state: State,
    /// The Jacobian ∂P^p/∂(y, y') at the starting state (for a periodic orbit: the monodromy
    /// matrix). When the motion starts stuck its second column is zero (see
    /// [`super::segment`]).
    pub jacobian: Matrix2,
    /// ln|det J|, `None` when the motion stops on the way (det J = 0).
    pub log_det: Option<f64>,
    /// The events in 0 < τ ≤ pT (a release at τ = 0 included), times from the start.
    pub events: Vec<Event>,
    /// Whether the motion is stuck at τ = 0.
    pub stuck_at_start: bool,
    /// Whether the motion is stuck at τ = pT.
    pub stuck_at_end: bool,
}

/// The p-fold strobe map P^p (`periods` = p ≥ 1 drive periods) from `state` at a strobe, with
/// its exact Jacobian.
///
/// ```
/// use stickslip::stability::strobe_map;
/// use stickslip::{Params, State};
/// // Free Coulomb decay from y = 7.5 stops at y = −0.5 within one drive period: the stop
/// // erases the velocity perturbation, so the Jacobian is singular and only δy survives.
/// let params = Params::new(0.0, 0.25, 0.0).unwrap();
/// let image = strobe_map(&params, State { y: 7.5, v: 0.0 }, 1).unwrap();
/// assert!(image.stuck_at_end && image.log_det.is_none());
/// assert_eq!(image.jacobian.0[1], [0.0, 0.0]);
/// assert!((image.state.y + 0.5).abs() < 1e-12);
/// ```
///
/// # Errors
/// [`Error::InvalidParameter`] for invalid parameters, state or p = 0;
/// [`StabilityError::NonFiniteJacobian`] at a tangential release; whatever the solver reports.
pub fn strobe_map(params: &Params, state: State, periods: usize) -> Result<StrobeImage> {
    strobe_map_on(&mut None, params, state, periods, None).map(|(image, _)| image)
}

/// The image under the strobe map of the state at which `solver` stands, a strobe, computed
/// on `solver` itself as it runs on to the next strobe `t_end` (handing every event, with its
/// absolute time, to `on_event`): the same image as [`strobe_map`] from that state, to the
/// rounding of the absolute times, without a run of its own.
///
/// # Errors
/// [`StabilityError::NonFiniteJacobian`] at a tangential release (the solver has run on to
/// `t_end` all the same); whatever the solver reports.
pub(crate) fn image_along(
    solver: &mut ExactSolver,
    t_end: f64,
    mut on_event: impl FnMut(&Event),
) -> Result<StrobeImage> {
    let start = solver.time();
    let stuck_at_start = solver.phase() == Phase::Stick;
    let mut tangent = Tangent::new(solver);
    // (Room for the events of most periods: one allocation.)
    let mut events = Vec::with_capacity(8);
    tangent.run_until(solver, t_end, |e| {
        on_event(e);
        events.push(Event {
            tau: e.tau - start,
            ..*e
        });
    })?;
    if let Some(tau) = tangent.grazing() {
        return Err(StabilityError::NonFiniteJacobian { tau: tau - start }.into());
    }
    Ok(StrobeImage {
        state: solver.state(),
        jacobian: tangent.jacobian(),
        log_det: tangent.log_det(),
        events,
        stuck_at_start,
        stuck_at_end: solver.phase() == Phase::Stick,
    })
}

/// [`strobe_map`] on the solver in `slot`, restarted in place at `state` (a new one when the
/// slot is empty, left there for the next evaluation), by [`image_along`]: its search starts
/// from `hints` of an earlier run on the same motion (see [`Hints`]: the image is the same to
/// rounding), or from nothing, as a new solver's (the image is then [`strobe_map`]'s to the
/// bit). Returns the hints its own run leaves.
pub(crate) fn strobe_map_on(
    slot: &mut Option<ExactSolver>,
    params: &Params,
    state: State,
    periods: usize,
    hints: Option<Hints>,
) -> Result<(StrobeImage, Option<Hints>)> {
    let params = params.validate()?;
    crate::exact::check_coulomb(&params)?;
    let state = State::new(state.y, state.v)?;
    if periods == 0 {
        return Err(Error::InvalidParameter {
            name: "periods",
            value: 0.0,
            allowed: "must be at least 1",
        });
    }
    let solver = match slot {
        Some(solver) if *solver.params() == params => {
            solver.restart_at(state, hints);
            solver
        }
        _ => {
            let mut solver = ExactSolver::new(params, state);
            if let Some(hints) = hints {
                solver.take_hints(hints);
            }
            slot.insert(solver)
        }
    };
    let image = image_along(solver, periods as f64 * params.drive_period(), |_| {})?;
    Ok((image, solver.hints()))
}
