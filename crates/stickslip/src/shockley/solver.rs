//! The stiff solver of the Shockley model behind the common [`Solver`] trait.

use super::diode::DiodeLaw;
use super::model::ShockleyModel;
use super::options::ShockleyOptions;
use super::stops::{Classifier, Mark};
use crate::cancel::Cancel;
use crate::error::{Error, Result};
use crate::params::{Params, State};
use crate::solver::{Event, Phase, Sample, Solver, Stats};
use crate::stiff::{Columns, Radau5, Sensitivity, Settings, Step, Track};
use std::collections::VecDeque;

/// Radau IIA (order 5) solver of y'' + 2ζ_R y' + y + D(y') = β cos(w τ + φ), with turns and
/// stops detected on the dense output by the threshold rule of [`crate::shockley`].
///
/// Each call of [`Solver::advance`] covers at most one integration step, and stops early at
/// `t_end` or at an event; [`Solver::dense`] is the step's collocation polynomial.
///
/// ```
/// use stickslip::shockley::{ShockleyOptions, ShockleySolver};
/// use stickslip::{solver::run_until, Circuit, Solver, State, EventKind};
/// // The paper's circuit at w = 0.95, β = 2.14: it slides, turning twice per period.
/// let circuit = Circuit::paper_shockley();
/// let params = circuit.params(0.95, 2.14, 0.0).unwrap();
/// let model = circuit.shockley_model(&params).unwrap().unwrap();
/// let mut solver =
///     ShockleySolver::new(model, State::default(), ShockleyOptions::default()).unwrap();
/// let period = model.params.drive_period();
/// run_until(&mut solver, 50.0 * period, |_| {}).unwrap();
/// let mut kinds = Vec::new();
/// run_until(&mut solver, 60.0 * period, |e| kinds.push(e.kind)).unwrap();
/// assert_eq!(kinds.len(), 20);
/// assert!(kinds.iter().all(|k| *k == EventKind::Turn));
/// ```
#[derive(Debug, Clone)]
pub struct ShockleySolver {
    model: ShockleyModel,
    options: ShockleyOptions,
    radau: Radau5<DiodeLaw>,
    classifier: Classifier,
    /// Integrated steps not yet passed by the reported time, contiguous, in time order.
    steps: VecDeque<Step>,
    /// Reported time, state and phase.
    now: f64,
    state: State,
    phase: Phase,
    /// The step of the last advance, its interval and the phase over it (for dense output).
    last: Option<Step>,
    interval: (f64, f64),
    interval_phase: Phase,
    events: u64,
    /// Checked (and charged one step) at every advance.
    cancel: Cancel,
    /// The forward sensitivities, when asked for ([`ShockleySolver::with_sensitivities`]): at
    /// the start of the front step of `steps`.
    track: Option<Box<Track>>,
}

impl Drop for ShockleySolver {
    /// Adds the work counters to the token's ([`Cancel::work`]).
    fn drop(&mut self) {
        if !self.cancel.is_never() {
            self.cancel.add_work(Solver::stats(self));
        }
    }
}

impl ShockleySolver {
    /// A solver starting at τ = 0 from `initial`.
    ///
    /// The phase at τ = 0 is decided by the stop rule (from rest the solver integrates ahead
    /// over the minimum stop duration to decide whether the start is a stop), so construction
    /// can fail like integration.
    ///
    /// # Errors
    /// [`Error::InvalidParameter`] for invalid options or model; [`Error::StepSizeTooSmall`] when
    /// the integration fails while deciding the initial phase.
    pub fn new(model: ShockleyModel, initial: State, options: ShockleyOptions) -> Result<Self> {
        Self::with_cancel(model, initial, options, Cancel::never())
    }

    /// As [`ShockleySolver::new`], stopping with the token's error once `cancel` is
    /// cancelled, past its deadline or over its budget (one step charged per integration
    /// step).
    ///
    /// # Errors
    /// As [`ShockleySolver::new`]; the token's error.
    pub fn with_cancel(
        model: ShockleyModel,
        initial: State,
        options: ShockleyOptions,
        cancel: Cancel,
    ) -> Result<Self> {
        let options = options.validate()?;
        let model = ShockleyModel::new(model.params, model.law)?;
        let initial = State::new(initial.y, initial.v)?;
        let settings = Settings {
            rtol: options.rtol,
            atol: options.atol,
            max_step: options.max_step,
            initial_step: 1e-4,
        };
        let radau = Radau5::new(
            model.params,
            model.law,
            0.0,
            [initial.y, initial.v],
            settings,
        );
        let min_stop = options.min_stop_fraction * model.params.drive_period();
        let classifier = Classifier::new(initial.v, options.stop_threshold, min_stop);
        let mut solver = Self {
            model,
            options,
            radau,
            classifier,
            steps: VecDeque::new(),
            now: 0.0,
            state: initial,
            phase: Phase::Stick,
            last: None,
            interval: (0.0, 0.0),
            interval_phase: Phase::Stick,
            events: 0,
            cancel,
            track: None,
        };
        let phase = loop {
            if let Some(phase) = solver.classifier.initial_phase() {
                break phase;
            }
            solver.integrate_one()?;
        };
        solver.phase = phase;
        solver.interval_phase = phase;
        Ok(solver)
    }

    /// The model being solved.
    pub fn model(&self) -> &ShockleyModel {
        &self.model
    }

    /// The options in use.
    pub fn options(&self) -> &ShockleyOptions {
        &self.options
    }

    /// Newton iterations so far (each solves the three coupled stages at once).
    pub fn newton_iterations(&self) -> u64 {
        self.radau.counters.newton
    }

    /// As [`ShockleySolver::with_cancel`], carrying the forward sensitivities of the computed
    /// solution along ([`crate::stiff::sensitivity`]): ∂x(τ)/∂(y0, v0), and with
    /// [`Columns::Parameters`] also ∂x(τ)/∂(ζ_R, β, w, φ, a, ε, r) (a, ε, r: the
    /// [`super::DiodeLaw`]'s scale, knee and resistance), from [I | 0] at τ = 0. The solution
    /// itself is the one [`ShockleySolver::with_cancel`] computes, to the bit.
    ///
    /// # Errors
    /// As [`ShockleySolver::with_cancel`].
    pub fn with_sensitivities(
        model: ShockleyModel,
        initial: State,
        options: ShockleyOptions,
        cancel: Cancel,
        columns: Columns,
    ) -> Result<Self> {
        let mut solver = Self::with_cancel(model, initial, options, cancel)?;
        solver.track = Some(Box::new(Track::new(columns.count::<DiodeLaw>())));
        Ok(solver)
    }

    /// The sensitivity ∂x(τ)/∂(y0, v0, p) at the current time τ, when the solver carries
    /// them ([`ShockleySolver::with_sensitivities`]); `None` without. After
    /// [`ShockleySolver::renormalize_sensitivity`], relative to the renormalised tangent.
    ///
    /// # Errors
    /// [`Error::StepSizeTooSmall`] at a step whose Newton matrix is singular at its converged
    /// stages (which its own convergence rules out in practice).
    pub fn sensitivity(&self) -> Option<Result<Sensitivity>> {
        let log_scale = self.track.as_ref()?.log_scale();
        Some(self.tracked()?.map(|(mut s, _)| {
            if log_scale != 0.0 {
                s.scale(log_scale.exp());
            }
            s
        }))
    }

    /// ln|det ∂x(τ)/∂x(0)| and its sign at the current time, when the solver carries
    /// sensitivities: the phase-area contraction of the computed flow, kept as a logarithm
    /// (see [`crate::stiff::Track`]; renormalisations do not change it).
    ///
    /// # Errors
    /// As [`ShockleySolver::sensitivity`].
    pub fn log_det(&self) -> Option<Result<(f64, f64)>> {
        Some(self.tracked()?.map(|(_, d)| d))
    }

    /// Divide the carried state Jacobian J = ∂x(τ)/∂x(0) by its Frobenius norm at the current
    /// time and return the logarithm of that norm (the growth of a tangent since the last
    /// renormalisation, for Lyapunov exponents); `None` without sensitivities.
    ///
    /// # Errors
    /// As [`ShockleySolver::sensitivity`].
    pub fn renormalize_sensitivity(&mut self) -> Option<Result<f64>> {
        let now = match self.tracked()? {
            Ok((s, _)) => s,
            Err(e) => return Some(Err(e)),
        };
        let norm = now
            .state()
            .iter()
            .flatten()
            .map(|x| x * x)
            .sum::<f64>()
            .sqrt();
        let track = self.track.as_mut()?;
        Some(Ok(track.renormalize(norm)))
    }

    fn tracked(&self) -> Option<Result<(Sensitivity, (f64, f64))>> {
        let track = self.track.as_ref()?;
        Some(match self.position() {
            (None, _) => Ok(track.base()),
            (Some(step), theta) => track
                .at(&step, &self.model.params, &self.model.law, theta)
                .ok_or(singular(&step)),
        })
    }

    /// The step the current time lies in, and where (θ), as the state was computed.
    fn position(&self) -> (Option<Step>, f64) {
        match &self.last {
            Some(step) if self.now > step.t0 => {
                let theta = if self.now == step.t1() {
                    1.0
                } else {
                    (self.now - step.t0) / step.h
                };
                (Some(*step), theta)
            }
            _ => (None, 0.0),
        }
    }

    /// Move the sensitivities past the front step, which the reported time has passed.
    fn pass(&mut self, step: &Step) -> Result<()> {
        if let Some(track) = self.track.as_mut() {
            track
                .pass(step, &self.model.params, &self.model.law)
                .ok_or(singular(step))?;
        }
        Ok(())
    }

    fn integrate_one(&mut self) -> Result<()> {
        self.cancel.charge(1)?;
        let step = self.radau.step()?;
        self.classifier.feed(&step);
        self.steps.push_back(step);
        Ok(())
    }
}

impl Solver for ShockleySolver {
    fn params(&self) -> &Params {
        &self.model.params
    }

    fn time(&self) -> f64 {
        self.now
    }

    fn state(&self) -> State {
        self.state
    }

    fn phase(&self) -> Phase {
        self.phase
    }

    fn drive(&self, tau: f64) -> f64 {
        self.model.params.drive(tau)
    }

    fn advance(&mut self, t_end: f64) -> Result<Option<Event>> {
        if t_end < self.now || t_end.is_nan() {
            return Err(Error::TimeBeforeCurrent {
                requested: t_end,
                current: self.now,
            });
        }
        let from = self.now;
        if t_end == from {
            self.interval = (from, from);
            self.interval_phase = self.phase;
            return Ok(None);
        }
        loop {
            while let Some(step) = self.steps.front().copied().filter(|s| s.t1() <= self.now) {
                self.pass(&step)?;
                self.steps.pop_front();
            }
            let Some(&step) = self.steps.front() else {
                self.integrate_one()?;
                continue;
            };
            let mut target = t_end.min(step.t1());
            let mut hit: Option<Mark> = None;
            if let Some(mark) = self.classifier.marks.front() {
                if mark.tau <= target {
                    debug_assert!(mark.tau >= from, "events are decided ahead of time");
                    target = mark.tau.max(from);
                    hit = Some(*mark);
                }
            }
            if target > self.classifier.frontier(self.radau.time()) {
                self.integrate_one()?;
                continue;
            }
            let x = step.eval(target);
            self.now = target;
            self.state = State { y: x[0], v: x[1] };
            self.last = Some(step);
            self.interval = (from, target);
            self.interval_phase = self.phase;
            let Some(mark) = hit else {
                return Ok(None);
            };
            self.classifier.marks.pop_front();
            self.phase = mark.phase_after;
            self.events += 1;
            return Ok(Some(Event {
                tau: target,
                y: x[0],
                kind: mark.kind,
            }));
        }
    }

    fn interval(&self) -> (f64, f64) {
        self.interval
    }

    fn dense(&self, tau: f64) -> Sample {
        let (y, v) = match &self.last {
            Some(step) => {
                let x = step.eval(tau);
                (x[0], x[1])
            }
            None => (self.state.y, self.state.v),
        };
        Sample {
            tau,
            y,
            v,
            phase: self.interval_phase,
        }
    }

    fn is_exact(&self) -> bool {
        false
    }

    fn stats(&self) -> Stats {
        let c = self.radau.counters;
        Stats {
            events: self.events,
            evaluations: c.rhs,
            steps: c.accepted,
            rejected: c.rejected,
        }
    }
}

/// The error of a step whose Newton matrix is singular at its converged stages.
fn singular(step: &Step) -> Error {
    Error::StepSizeTooSmall {
        tau: step.t0,
        step: step.h,
    }
}
