//! One run of an experiment from its initial state, sampled on an even grid of times: what
//! `stickslip simulate` writes and the Python package's `simulate` returns.

use super::Experiment;
use crate::error::Result;
use crate::scan::Monitor;
use crate::solver::{Event, Phase};
use serde::{Deserialize, Serialize};

/// A sampled run: the samples column by column (each column has one value per sample), and
/// every event on the way.
///
/// Samples are taken at τ_k = k·(periods·T)/n for k = 0 … n, where T = 2π/w is the drive
/// period and n = ⌈periods × samples_per_period⌉, so there are n + 1 of them.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Trajectory {
    /// Dimensionless times τ = ω0·t of the samples.
    pub tau: Vec<f64>,
    /// Position y at each sample.
    pub y: Vec<f64>,
    /// Velocity y' at each sample.
    pub v: Vec<f64>,
    /// The drive β cos(wτ + φ) at each sample (units of y).
    pub drive: Vec<f64>,
    /// Phase of the motion at each sample.
    pub phase: Vec<Phase>,
    /// Every event (turn, stick, slip) from τ = 0 to the last sample, in order.
    pub events: Vec<Event>,
}

impl Trajectory {
    /// Most samples a run may hold (about 2 GB in memory).
    pub const MAX_SAMPLES: f64 = 5e7;

    /// Number of samples.
    pub fn len(&self) -> usize {
        self.tau.len()
    }

    /// Whether there are no samples (never, for a trajectory from [`Experiment::simulate`]).
    pub fn is_empty(&self) -> bool {
        self.tau.is_empty()
    }
}

impl Experiment {
    /// Run the experiment from its initial state for `periods` drive periods and sample the
    /// motion `samples_per_period` times per drive period (both ends included; see
    /// [`Trajectory`]). `monitor` is told after every drive period sampled (done and total
    /// periods, rounded up) and can stop the run. This is [`Experiment::trajectory`] kept
    /// whole.
    ///
    /// ```
    /// use stickslip::experiment::Experiment;
    /// let run = Experiment::dimensionless(0.05, 0.7, 1.2)
    ///     .unwrap()
    ///     .simulate(3.0, 100, &())
    ///     .unwrap();
    /// assert_eq!(run.len(), 301);
    /// assert_eq!(run.tau[0], 0.0);
    /// ```
    ///
    /// # Errors
    /// [`Error::InvalidOption`](crate::Error::InvalidOption) when `periods` is not finite and > 0 or `samples_per_period`
    /// is out of its range, [`Error::OptionProduct`](crate::Error::OptionProduct) when the run would hold more than
    /// [`Trajectory::MAX_SAMPLES`] samples ([`crate::options::SimulateOptions`]); a missing
    /// drive ([`Experiment::params`]); [`Error::HorizonTooLong`](crate::Error::HorizonTooLong) for a run longer than the
    /// solvers resolve ([`crate::limits::check_horizon`]), before any work;
    /// [`Error::Cancelled`](crate::Error::Cancelled); whatever the solver reports.
    pub fn simulate(
        &self,
        periods: f64,
        samples_per_period: usize,
        monitor: &dyn Monitor,
    ) -> Result<Trajectory> {
        crate::options::SimulateOptions {
            periods,
            samples_per_period,
        }
        .validate()?;
        // The one trajectory path: the run streamed and kept whole.
        let report = self
            .trajectory(periods, samples_per_period)?
            .monitor(monitor)
            .collect_report()?;
        Ok(Trajectory {
            tau: report.tau,
            y: report.y,
            v: report.v,
            drive: report.drive,
            phase: report.phase,
            events: report
                .events
                .into_iter()
                .map(|e| Event {
                    tau: e.tau,
                    y: e.y,
                    kind: e.kind,
                })
                .collect(),
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::error::Error;
    use crate::solver::{grid, sample_at};

    #[test]
    fn the_same_samples_as_one_pass_over_the_grid() {
        let e = Experiment::paper()
            .with_w(0.7)
            .unwrap()
            .with_beta(1.2)
            .unwrap();
        let run = e.simulate(7.5, 33, &()).unwrap();
        let params = e.params().unwrap();
        let times = grid(
            0.0,
            7.5 * params.drive_period(),
            (7.5f64 * 33.0).ceil() as usize,
        );
        let mut solver = e.solver().unwrap();
        let mut events = Vec::new();
        let samples = sample_at(solver.as_mut(), &times, |ev| events.push(*ev)).unwrap();
        assert_eq!(run.len(), samples.len());
        for (k, s) in samples.iter().enumerate() {
            assert_eq!(
                (run.tau[k], run.y[k], run.v[k], run.phase[k]),
                (s.tau, s.y, s.v, s.phase)
            );
            assert_eq!(run.drive[k], params.drive(s.tau));
        }
        assert_eq!(run.events, events);
        assert!(run.events.iter().any(|e| e.kind == crate::EventKind::Stick));
    }

    #[test]
    fn bad_requests_and_cancellation() {
        let e = Experiment::dimensionless(0.1, 0.9, 2.0).unwrap();
        for (periods, samples) in [(0.0, 10), (f64::NAN, 10), (1.0, 0), (1e7, 100)] {
            assert!(matches!(
                e.simulate(periods, samples, &()),
                Err(Error::InvalidOption { .. } | Error::OptionProduct { .. })
            ));
        }
        let stop_after_two = |done: usize, _: usize| done < 2;
        assert_eq!(
            e.simulate(10.0, 8, &stop_after_two),
            Err(Error::Cancelled { done: 2, total: 11 })
        );
    }
}
