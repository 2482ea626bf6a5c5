//! Motion classes on a (w, β) grid, computed in parallel (rayon), each point from the same
//! initial state (rest, as in the paper's Fig. 7).

use super::classify::MotionClass;
use super::cycle::{steady_state_from, SteadyOptions};
use super::range::ParameterRange;
use super::SolverFactory;
use crate::error::{Error, Result};
use crate::params::{Params, State};
use rayon::prelude::*;
use serde::{Deserialize, Serialize};
use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering};

/// One point of a phase diagram.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct PhaseDiagramPoint {
    /// Drive frequency w.
    pub w: f64,
    /// Drive amplitude β.
    pub beta: f64,
    /// Motion class.
    pub class: MotionClass,
    /// Period in drive periods (`None`: none found within the cap).
    pub period: Option<usize>,
    /// Stops of non-zero duration per drive period.
    pub stops_per_period: f64,
    /// Gain (y_max − y_min)/(2β).
    pub gain: f64,
    /// Whether the cycle is symmetric.
    pub symmetric: bool,
    /// Drive periods run before the cycle was recognised.
    pub periods_to_settle: usize,
}

/// Classify every point of the grid `w` × `beta` (the other parameters from `base`), each
/// started from `initial` at τ = 0, in parallel on rayon's thread pool.
///
/// Points come out w-major: index `i·beta.steps() + j` holds `(w_i, β_j)`. The spectrum is
/// never computed here, whatever `options` says. `on_point` is called (from any thread) after
/// every finished point; returning `false` stops the computation with [`Error::Cancelled`].
///
/// # Errors
/// [`Error::InvalidParameter`] for a grid value out of range or invalid options;
/// [`Error::Cancelled`]; the first solver failure.
pub fn phase_diagram<F: SolverFactory + ?Sized>(
    factory: &F,
    base: Params,
    initial: State,
    w: &ParameterRange,
    beta: &ParameterRange,
    options: &SteadyOptions,
    on_point: &(dyn Fn() -> bool + Sync),
) -> Result<Vec<PhaseDiagramPoint>> {
    let options = options.validate()?.with_spectrum(false);
    let (nw, nb) = (w.steps(), beta.steps());
    let total = nw * nb;
    let params_at = |i: usize| -> Result<Params> {
        let mut p = base;
        p.w = w.value(i / nb);
        p.beta = beta.value(i % nb);
        p.validate()
    };
    // Reject a bad grid before any work: the corners bound every value.
    for i in [0, nb - 1, total - nb, total - 1] {
        params_at(i)?;
    }
    let stop = AtomicBool::new(false);
    let done = AtomicUsize::new(0);
    (0..total)
        .into_par_iter()
        .map(|i| {
            if stop.load(Ordering::Relaxed) {
                return Err(Error::Cancelled {
                    done: done.load(Ordering::Relaxed),
                    total,
                });
            }
            let params = params_at(i)?;
            let s = steady_state_from(factory, &params, initial, &options)?;
            let finished = done.fetch_add(1, Ordering::Relaxed) + 1;
            if !on_point() {
                stop.store(true, Ordering::Relaxed);
                return Err(Error::Cancelled {
                    done: finished,
                    total,
                });
            }
            Ok(PhaseDiagramPoint {
                w: params.w,
                beta: params.beta,
                class: s.class,
                period: s.period,
                stops_per_period: s.stops_per_period,
                gain: s.gain,
                symmetric: s.symmetric,
                periods_to_settle: s.periods_to_settle,
            })
        })
        .collect()
}
