//! Bifurcation diagrams: the strobe points of the motion against a parameter, with the
//! largest Lyapunov exponent and what the motion settled on at every value.
//!
//! One of ζ, w, β or μs is stepped up, down or both ways ([`SweepDirection`]), as in
//! [`crate::scan::Sweep`]: each step starts from the state where the step before ended (a
//! strobe, where the drive phase is φ again), so the diagram follows a branch for as long as
//! it exists, and the up and the down legs show different branches where motions coexist
//! (hysteresis). At every value the exact solver runs a transient and then records N strobe
//! points (y, y') at τ = kT with the largest Lyapunov exponent along them and a verdict
//! ([`crate::attractor`]): a period-p orbit gives exactly p points, chaos a cloud of N points
//! and a positive exponent.
//!
//! **The exponent** of a motion whose strobe points do not repeat is then measured as `steady`
//! and the maps measure it ([`SteadyOptions::DEFAULT_LYAPUNOV`]): from the record's last
//! point, 100 periods to align the tangent, then lengths that double up to 5000 periods, stopped
//! as soon as the verdict is decided at [`RecordOptions::significance`] standard errors (see
//! [`crate::stability::lyapunov`]). Its exponent and standard error replace the record's own
//! (measured over the N recorded periods only), and its verdict the record's: chaotic, or
//! quasi-periodic (within its error of zero), or unsettled (contracting onto something not
//! reached, or undecided). Periodic orbits and rest keep the record's exponent.
//!
//! The first step (from the experiment's initial state) runs
//! [`BifurcationOptions::first_transient_periods`], every later one
//! [`RecordOptions::transient_periods`]. The result is deterministic: step i depends only on
//! the options, its value and the state step i − 1 ended in, so a diagram can be computed in
//! pieces ([`Bifurcation::run_from`]) and resumed from any finished step.
//!
//! ```
//! use stickslip::bifurcation::{Bifurcation, BifurcationOptions};
//! use stickslip::scan::{Axis, SweepDirection};
//! use stickslip::{Experiment, Parameter};
//! // ζ = 0, μs = 3, β = 9: periodic at w = 0.25 and 0.42 (period 3), chaotic at w = 0.33.
//! let experiment = Experiment::dimensionless(0.0, 0.3, 9.0).unwrap().with_mu_s(3.0).unwrap();
//! let diagram = Bifurcation::new(&experiment, Axis::new(Parameter::W, vec![0.25, 0.33, 0.42]).unwrap())
//!     .unwrap()
//!     .direction(SweepDirection::Up)
//!     .run(&())
//!     .unwrap();
//! let periods: Vec<Option<usize>> = diagram.iter().map(|s| s.record.period).collect();
//! assert_eq!(periods, [Some(1), None, Some(3)]);
//! assert!(diagram[1].record.exponent > 0.0);
//! ```

use crate::attractor::{
    distance, record_strobes_of, scale_of, AttractorKind, RecordOptions, StrobeRecord,
};
use crate::continuation::{continue_both_ways_of, Branch, ContinuationOptions};
use crate::error::{Error, Result};
use crate::experiment::Experiment;
use crate::params::{Params, State};
use crate::scan::{Axis, Monitor, SweepDirection, SweepLeg};
use crate::stability::{
    Dynamics, LyapunovOptions, NewtonOptions, NonperiodicClassification, NonperiodicVerdict,
    StabilityError,
};
use crate::steady::SteadyOptions;
use rayon::prelude::*;
use serde::{Deserialize, Serialize};
use std::ops::ControlFlow;
use std::sync::atomic::{AtomicBool, AtomicUsize, Ordering};
use std::sync::Arc;

/// Measure the largest exponent of a motion whose strobe points do not repeat as `steady` and
/// the maps do (see the module documentation): from the record's last point, sequentially
/// ([`SteadyOptions::DEFAULT_LYAPUNOV`], at `significance` standard errors), and take its
/// exponent, error and verdict in place of the record's own (N periods only). The state the
/// next step starts from is the record's last point either way.
fn measure(
    dynamics: &dyn Dynamics,
    params: &Params,
    record: &mut StrobeRecord,
    significance: f64,
) -> Result<()> {
    if record.period.is_some() || record.kind == AttractorKind::Static {
        return Ok(());
    }
    let options = LyapunovOptions {
        significance,
        ..SteadyOptions::DEFAULT_LYAPUNOV
    };
    let exponents = match dynamics.lyapunov_exponents(params, record.final_state(), &options, &()) {
        Ok(exponents) => exponents,
        // A tangential release: the record's own exponent stays.
        Err(Error::Stability(StabilityError::NonFiniteJacobian { .. })) => return Ok(()),
        Err(e) => return Err(e),
    };
    let c = NonperiodicClassification::new(exponents, significance);
    record.exponent = c.exponents.largest.per_tau;
    record.exponent_error = c.exponents.largest.error_per_tau;
    record.kind = match c.verdict {
        NonperiodicVerdict::Chaotic => AttractorKind::Chaotic,
        NonperiodicVerdict::QuasiPeriodic => AttractorKind::QuasiPeriodic,
        NonperiodicVerdict::Contracting
        | NonperiodicVerdict::LimitCycle
        | NonperiodicVerdict::Equilibrium
        | NonperiodicVerdict::Undecided => AttractorKind::Undecided,
    };
    Ok(())
}

/// Options of a [`Bifurcation`] diagram.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct BifurcationOptions {
    /// The record at every value: transient (default 200 drive periods), strobe points
    /// (default 100), period detection and the significance of the exponent.
    pub record: RecordOptions,
    /// Drive periods of transient at the first value, from the experiment's initial state.
    /// Default 2000.
    pub first_transient_periods: usize,
}

impl Default for BifurcationOptions {
    fn default() -> Self {
        Self {
            record: RecordOptions::default(),
            first_transient_periods: 2000,
        }
    }
}

impl BifurcationOptions {
    /// Check every field.
    ///
    /// # Errors
    /// [`Error::InvalidOption`] or [`Error::InvalidParameter`] naming the first bad field
    /// ([`RecordOptions::validate`]).
    pub fn validate(self) -> Result<Self> {
        self.record.validate()?;
        crate::options::OptionKey::FirstTransient.check_count(self.first_transient_periods)?;
        Ok(self)
    }
}

/// One value of a bifurcation diagram.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct BifurcationStep {
    /// Parameters of this step.
    pub params: Params,
    /// The stepped parameter's value.
    pub value: f64,
    /// The leg the step belongs to.
    pub leg: SweepLeg,
    /// The strobe points, the exponent and the verdict.
    pub record: StrobeRecord,
}

/// A bifurcation diagram of one parameter of an experiment (see the module documentation).
///
/// Defaults: [`SweepDirection::Both`], [`BifurcationOptions::default`].
#[derive(Debug, Clone)]
pub struct Bifurcation {
    experiment: Experiment,
    /// The model of the experiment's law.
    dynamics: Arc<dyn Dynamics>,
    axis: Axis,
    direction: SweepDirection,
    options: BifurcationOptions,
}

impl Bifurcation {
    /// A diagram over `axis` of `experiment`, starting from its initial state. The experiment
    /// needs no value of the stepped parameter.
    ///
    /// With Shockley diodes the strobe points and the exponents are those of the stiff
    /// solver (its tangent dynamics, [`crate::stability::ShockleyDynamics`]), and points
    /// repeat within its [`Dynamics::repeat_tolerance`].
    ///
    /// # Errors
    /// A value out of range; a drive value missing that is not stepped.
    pub fn new(experiment: &Experiment, axis: Axis) -> Result<Self> {
        for &v in axis.values() {
            experiment.params_with(&[(axis.parameter(), v)])?;
        }
        Ok(Self {
            dynamics: Arc::from(experiment.dynamics()?),
            experiment: experiment.clone(),
            axis,
            direction: SweepDirection::Both,
            options: BifurcationOptions::default(),
        })
    }

    /// Step up, down or both ways.
    pub fn direction(mut self, direction: SweepDirection) -> Self {
        self.direction = direction;
        self
    }

    /// Use these options.
    ///
    /// # Errors
    /// When the options are invalid.
    pub fn options(mut self, options: BifurcationOptions) -> Result<Self> {
        self.options = options.validate()?;
        Ok(self)
    }

    /// The options used.
    pub fn bifurcation_options(&self) -> &BifurcationOptions {
        &self.options
    }

    /// The stepped axis.
    pub fn axis(&self) -> &Axis {
        &self.axis
    }

    /// The steps in order: value and leg (as [`crate::scan::Sweep::plan`]).
    pub fn plan(&self) -> Vec<(f64, SweepLeg)> {
        (0..self.len()).map(|i| self.planned(i)).collect()
    }

    /// Number of steps of the plan.
    pub fn len(&self) -> usize {
        match self.direction {
            SweepDirection::Both => 2 * self.axis.len(),
            _ => self.axis.len(),
        }
    }

    /// Whether the plan has no steps (never: an axis has at least one value).
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// Value and leg of step `index`.
    fn planned(&self, index: usize) -> (f64, SweepLeg) {
        let values = self.axis.values();
        let n = values.len();
        match self.direction {
            SweepDirection::Up => (values[index], SweepLeg::Up),
            SweepDirection::Down => (values[n - 1 - index], SweepLeg::Down),
            SweepDirection::Both if index < n => (values[index], SweepLeg::Up),
            SweepDirection::Both => (values[2 * n - 1 - index], SweepLeg::Down),
        }
    }

    /// The parameters of step `index` of the plan.
    ///
    /// # Errors
    /// A value out of range.
    ///
    /// # Panics
    /// When `index` is beyond the plan.
    pub fn params(&self, index: usize) -> Result<Params> {
        assert!(index < self.len(), "step beyond the plan");
        let (value, _) = self.planned(index);
        self.experiment
            .params_with(&[(self.axis.parameter(), value)])
    }

    /// Step `index` of the plan alone, from `state` (the state the step before ended in, or
    /// the experiment's initial state for step 0).
    ///
    /// # Errors
    /// Whatever the solver reports.
    ///
    /// # Panics
    /// When `index` is beyond the plan.
    pub fn step(&self, index: usize, state: State) -> Result<BifurcationStep> {
        let params = self.params(index)?;
        let (value, leg) = self.planned(index);
        let mut record = self.options.record;
        if index == 0 {
            record.transient_periods = self.options.first_transient_periods;
        }
        let dynamics = self.dynamics.as_ref();
        let mut record = record_strobes_of(dynamics, &params, state, &record)?;
        measure(
            dynamics,
            &params,
            &mut record,
            self.options.record.significance,
        )?;
        Ok(BifurcationStep {
            params,
            value,
            leg,
            record,
        })
    }

    /// Compute the whole diagram; `monitor` sees every finished step and can stop the work.
    ///
    /// # Errors
    /// [`Error::Cancelled`]; whatever the solver reports.
    pub fn run(&self, monitor: &dyn Monitor) -> Result<Vec<BifurcationStep>> {
        self.run_from(0, self.experiment.initial(), monitor, &mut |_, _| {})
    }

    /// Compute the steps from `start` on, step `start` from `state` (the final state of step
    /// `start − 1`, [`StrobeRecord::final_state`], or the experiment's initial state when
    /// `start` is 0), handing every finished step to `on_step` with its index (to save it) and
    /// then to `monitor` (counting over the whole plan), which can stop the work. The steps
    /// equal those of an uninterrupted [`Bifurcation::run`].
    ///
    /// # Errors
    /// [`Error::InvalidParameter`] when `start` is beyond the plan; [`Error::Cancelled`];
    /// whatever the solver reports.
    pub fn run_from(
        &self,
        start: usize,
        state: State,
        monitor: &dyn Monitor,
        on_step: &mut dyn FnMut(usize, &BifurcationStep),
    ) -> Result<Vec<BifurcationStep>> {
        let total = self.len();
        if start > total {
            return Err(Error::InvalidParameter {
                name: "start",
                value: start as f64,
                allowed: "must not exceed the number of steps",
            });
        }
        let mut state = State::new(state.y, state.v)?;
        let mut out = Vec::with_capacity(total - start);
        for index in start..total {
            let step = self.step(index, state)?;
            state = step.record.final_state();
            on_step(index, &step);
            out.push(step);
            if monitor.step(index + 1, total) == ControlFlow::Break(()) {
                return Err(Error::Cancelled {
                    done: index + 1,
                    total,
                });
            }
        }
        Ok(out)
    }
}

impl Bifurcation {
    /// The branches of the periodic orbits that `steps` (this diagram's, from
    /// [`Bifurcation::run`]) settled on, continued both ways over the diagram's range
    /// ([`crate::continuation::continue_both_ways`]): stable and unstable, through folds and
    /// changes of the event
    /// sequence, for drawing on top of the strobe points.
    ///
    /// Every run of consecutive steps on one leg with a periodic orbit of one period (and the
    /// same stops) gives a seed, its middle step, refined by Newton's method; the seeds are
    /// continued in parallel, and a branch is dropped when its seed lies on an earlier branch
    /// (so each branch is drawn once). Periodic steps that lie on no branch then seed a
    /// further round (at most four rounds). `monitor` sees the seeds finished (its total is
    /// 0: the number of seeds is not known in advance) and can stop the work. The result does
    /// not depend on the number of threads.
    ///
    /// # Errors
    /// [`Error::Cancelled`]; invalid options; whatever the solver reports.
    pub fn branches(
        &self,
        steps: &[BifurcationStep],
        options: &ContinuationOptions,
        monitor: &dyn Monitor,
    ) -> Result<Vec<Branch>> {
        let options = options.validate()?;
        let (lo, hi) = self
            .axis
            .values()
            .iter()
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), &v| {
                (a.min(v), b.max(v))
            });
        if !(lo < hi) {
            return Ok(Vec::new());
        }
        let mut branches: Vec<Branch> = Vec::new();
        let mut tried: Vec<usize> = Vec::new();
        let done = AtomicUsize::new(0);
        let stop = AtomicBool::new(false);
        // Rounds: seeds from the runs of steps not yet on a branch, until every periodic step
        // lies on one (or was a seed itself).
        for _ in 0..4 {
            let covered = |step: &BifurcationStep| {
                branches.iter().any(|b| {
                    Some(b.period) == step.record.period
                        && passes_through(b, step.value, step.record.strobes[0])
                })
            };
            let open: Vec<usize> = (0..steps.len())
                .filter(|&i| {
                    steps[i].record.kind == AttractorKind::Periodic
                        && !tried.contains(&i)
                        && !covered(&steps[i])
                })
                .collect();
            let seeds = seeds(steps, &open);
            if seeds.is_empty() {
                break;
            }
            tried.extend(&seeds);
            let computed =
                self.continue_seeds(steps, &seeds, (lo, hi), &options, monitor, &done, &stop)?;
            for (branch, seed_value, seed) in computed.into_iter().flatten() {
                let duplicate = branches
                    .iter()
                    .any(|b| b.period == branch.period && passes_through(b, seed_value, seed));
                if !duplicate && branch.points.len() > 1 {
                    branches.push(branch);
                }
            }
        }
        Ok(branches)
    }

    /// The branches through the seeds (indices into `steps`), in parallel, in their order.
    #[allow(clippy::type_complexity)]
    fn continue_seeds(
        &self,
        steps: &[BifurcationStep],
        seeds: &[usize],
        range: (f64, f64),
        options: &ContinuationOptions,
        monitor: &dyn Monitor,
        done: &AtomicUsize,
        stop: &AtomicBool,
    ) -> Result<Vec<Option<(Branch, f64, State)>>> {
        let parameter = self.axis.parameter();
        seeds
            .par_iter()
            .map(|&i| -> Result<Option<(Branch, f64, State)>> {
                if stop.load(Ordering::Relaxed) {
                    return Err(Error::Cancelled {
                        done: done.load(Ordering::Relaxed),
                        total: 0,
                    });
                }
                let step = &steps[i];
                let period = step.record.period.expect("a periodic step has a period");
                let dynamics = self.dynamics.as_ref();
                let outcome = match dynamics.find_periodic_orbit(
                    &step.params,
                    step.record.strobes[0],
                    period,
                    &NewtonOptions::default(),
                ) {
                    Ok(orbit) if !orbit.events.is_empty() => {
                        match continue_both_ways_of(
                            dynamics,
                            &step.params,
                            parameter,
                            &orbit,
                            range,
                            options,
                            &(),
                        ) {
                            Ok(branch) => Some((branch, step.value, orbit.state)),
                            Err(Error::Stability(_)) => None,
                            Err(e) => return Err(e),
                        }
                    }
                    Ok(_) | Err(Error::Stability(_)) => None,
                    Err(e) => return Err(e),
                };
                let finished = done.fetch_add(1, Ordering::Relaxed) + 1;
                if monitor.step(finished, 0) == ControlFlow::Break(()) {
                    stop.store(true, Ordering::Relaxed);
                    return Err(Error::Cancelled {
                        done: finished,
                        total: 0,
                    });
                }
                Ok(outcome)
            })
            .collect()
    }
}

/// The seeds among the steps `open` (increasing indices into `steps`): the middle step of
/// every run of consecutive steps on one leg with the same period and the same stops while
/// recording (a change of either is another orbit, or a point where the branch changes its
/// events, which the continuation crosses anyway).
fn seeds(steps: &[BifurcationStep], open: &[usize]) -> Vec<usize> {
    let mut out = Vec::new();
    let mut run: Vec<usize> = Vec::new();
    for &i in open {
        let continues = run.last().is_some_and(|&last| {
            let (a, b) = (&steps[last], &steps[i]);
            last + 1 == i
                && a.leg == b.leg
                && a.record.period == b.record.period
                && a.record.stops == b.record.stops
        });
        if !continues && !run.is_empty() {
            out.push(run[run.len() / 2]);
            run.clear();
        }
        run.push(i);
    }
    if !run.is_empty() {
        out.push(run[run.len() / 2]);
    }
    out
}

/// Whether `branch` passes within 1e-6 (relative) of the strobe point `state` at the
/// parameter's `value`, between two of its points.
fn passes_through(branch: &Branch, value: f64, state: crate::params::State) -> bool {
    let tolerance = 1e-6 * scale_of(&[state]);
    branch.points.windows(2).any(|pair| {
        let (a, b) = (&pair[0], &pair[1]);
        let (lo, hi) = (a.value.min(b.value), a.value.max(b.value));
        if !(lo <= value && value <= hi) {
            return false;
        }
        let t = if b.value != a.value {
            (value - a.value) / (b.value - a.value)
        } else {
            0.0
        };
        a.strobes.iter().zip(&b.strobes).any(|(p, q)| {
            let between = crate::params::State {
                y: p.y + t * (q.y - p.y),
                v: p.v + t * (q.v - p.v),
            };
            distance(between, state) <= tolerance.max(0.1 * distance(*p, *q))
        })
    })
}
