//! The samples of a self-excited cycle ([`self_excited_trace`]): the steady-state search of a
//! belt without a drive ([`super::self_excited`]) keeps the cycle's events and extremes, not
//! its samples; a front end that draws the cycle (the lab's scope, its block on the belt) runs
//! it once more from its section.

use super::state::SteadyState;
use super::SolverFactory;
use crate::error::Result;
use crate::solver::{grid, sample_at, Sample};
use std::f64::consts::TAU;

/// `samples` evenly spaced samples of the self-excited motion `steady` (a state that
/// [`super::self_excited_state`] found: β = 0, vb ≠ 0) over one cycle from its section,
/// τ = `steady.start` to `steady.start` + its period (the last sample, at the period itself,
/// left out: it repeats the first), run again from the section's state by a solver of
/// `factory`. Without a drive the motion does not depend on τ, so the run starts its solver
/// at τ = 0 and the samples' τ are shifted by `steady.start`. A motion without a cycle
/// (steady sliding, or none found) gives one natural period 2π from the state the search
/// ended at. `None` for a driven motion (its trace is [`SteadyState::trace`]).
///
/// # Errors
/// Whatever the solver reports.
pub fn self_excited_trace<F: SolverFactory + ?Sized>(
    factory: &F,
    steady: &SteadyState,
    samples: usize,
) -> Result<Option<Vec<Sample>>> {
    let Some(cycle) = steady.self_excited else {
        return Ok(None);
    };
    let samples = samples.max(2);
    let span = cycle.period.unwrap_or(TAU);
    let mut solver = factory.make(steady.params, steady.strobes[0])?;
    let mut times = grid(0.0, span, samples);
    times.pop();
    let mut trace = sample_at(solver.as_mut(), &times, |_| {})?;
    for s in &mut trace {
        s.tau += steady.start;
    }
    Ok(Some(trace))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::friction::FrictionLaw;
    use crate::params::{Params, State};
    use crate::solver::Phase;
    use crate::steady::{steady_state_from, MotionClass, SteadyOptions};
    use crate::Experiment;

    /// A Stribeck belt's stick-slip cycle: the samples start at the onset of sticking, stay
    /// on the belt (y' = vb) for the cycle's stick fraction, span the cycle's extremes, and
    /// close on themselves.
    #[test]
    fn the_samples_of_a_stick_slip_cycle_close_and_span_its_extremes() {
        let e = Experiment::dimensionless(0.05, 1.0, 0.0)
            .and_then(|e| e.with_mu_s(1.5))
            .and_then(|e| e.with_vb(0.3))
            .and_then(|e| {
                e.with_law(FrictionLaw::Stribeck {
                    vs: 0.1,
                    delta: 2.0,
                    eta: 0.0,
                })
            })
            .unwrap();
        let params: Params = e.params().unwrap();
        let options = SteadyOptions::default();
        let steady = steady_state_from(&e.factory(), &params, State::default(), &options).unwrap();
        assert_eq!(steady.class, MotionClass::StickSlipCycle);
        let cycle = steady.self_excited.unwrap();
        let n = 2000;
        let trace = self_excited_trace(&e.factory(), &steady, n)
            .unwrap()
            .unwrap();
        assert_eq!(trace.len(), n);
        let period = cycle.period.unwrap();
        assert_eq!(trace[0].tau, steady.start);
        assert!(
            (trace[n - 1].tau - (steady.start + period * (n - 1) as f64 / n as f64)).abs() < 1e-9
        );
        let stuck = trace.iter().filter(|s| s.phase == Phase::Stick).count() as f64 / n as f64;
        assert!(
            (stuck - cycle.stick_fraction).abs() < 2.0 / n as f64,
            "{stuck} vs {}",
            cycle.stick_fraction
        );
        for s in trace.iter().filter(|s| s.phase == Phase::Stick) {
            assert_eq!(s.v, 0.3, "stuck: on the belt");
        }
        let (lo, hi) = trace
            .iter()
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), s| {
                (lo.min(s.y), hi.max(s.y))
            });
        let step = period / n as f64;
        assert!(
            lo >= steady.y_min - 1e-9 && hi <= steady.y_max + 1e-9,
            "{lo} {hi}"
        );
        assert!(
            lo - steady.y_min < step && steady.y_max - hi < step,
            "{lo} {hi}"
        );
        // One step further the cycle is where it began.
        let mut solver = e.factory().make(params, steady.strobes[0]).unwrap();
        let end = sample_at(solver.as_mut(), &[period], |_| {}).unwrap()[0];
        assert!(
            (end.y - trace[0].y).abs() < 1e-6,
            "{} vs {}",
            end.y,
            trace[0].y
        );
    }

    /// A driven motion has its own trace.
    #[test]
    fn a_driven_motion_has_none() {
        let e = Experiment::paper()
            .with_w(0.95)
            .unwrap()
            .with_beta(2.14)
            .unwrap();
        let steady = e.steady().unwrap();
        assert!(self_excited_trace(&e.factory(), &steady, 64)
            .unwrap()
            .is_none());
    }
}
