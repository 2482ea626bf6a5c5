//! A fit's options, its errors, and how it reports progress and watches for a stop.

use super::*;
use crate::experiment::DiodeModel;
use crate::measure::MeasureError;
use crate::scan::Monitor;
use serde::{Deserialize, Serialize};
use std::ops::ControlFlow;
use thiserror::Error;

/// What can go wrong in a fit.
#[derive(Debug, Clone, PartialEq, Error)]
#[non_exhaustive]
pub enum FitError {
    /// A measurement that cannot be used.
    #[error(transparent)]
    Measure(#[from] MeasureError),
    /// A name that is no fit parameter.
    #[error(
        "unknown fit parameter \"{0}\" (the parameters are {circuit} for a circuit; \
         {mechanics} for a mechanical oscillator)",
        circuit = FitParameter::names(&FitParameter::CIRCUIT),
        mechanics = FitParameter::names(&FitParameter::MECHANICS)
    )]
    UnknownParameter(String),
    /// The experiment is neither a circuit nor a mechanical oscillator.
    #[error(
        "fitting needs a circuit or a mechanical oscillator (give its parts or a preset), not \
         dimensionless parameters alone"
    )]
    NeedsCircuit,
    /// A circuit's parameter on a mechanical oscillator, or the other way round.
    #[error(
        "{parameter} is not a parameter of {} (its parameters are {})",
        if *mechanics { "a mechanical oscillator" } else { "a circuit" },
        FitParameter::names(if *mechanics { &FitParameter::MECHANICS } else { &FitParameter::CIRCUIT })
    )]
    WrongSystem {
        /// The parameter.
        parameter: FitParameter,
        /// Whether the experiment is a mechanical oscillator (else a circuit).
        mechanics: bool,
    },
    /// A record whose channels' units do not fit the experiment (a mechanical oscillator
    /// needs the force in N and the displacement in m).
    #[error("{file}: {message}")]
    Units {
        /// The record.
        file: String,
        /// What is wrong and what is allowed.
        message: String,
    },
    /// A table of amplitudes (read in volts) given for a mechanical oscillator.
    #[error(
        "a table of amplitudes is read in volts (U_V, response_V): a mechanical oscillator is \
         fitted to records (a force in N and a displacement in m)"
    )]
    TableNeedsCircuit,
    /// A parameter of the other diode law.
    #[error("{parameter} is not a parameter of the {} diode law", model.label())]
    WrongLaw {
        /// The parameter.
        parameter: FitParameter,
        /// The law of the experiment.
        model: DiodeModel,
    },
    /// A parameter of a friction law (the Stribeck speed, the viscous friction) that the
    /// mechanical oscillator's law does not have.
    #[error(
        "{parameter} is a parameter of the stribeck friction law, and this oscillator's law is \
         {} (a coulomb belt's friction is fitted by friction and mu-s)",
        law.label()
    )]
    WrongFrictionLaw {
        /// The parameter.
        parameter: FitParameter,
        /// The oscillator's friction law.
        law: crate::friction::FrictionLawKind,
    },
    /// No free parameter, or one given twice.
    #[error("{0}")]
    FreeParameters(&'static str),
    /// An undriven record (or its oscillator) that cannot be fitted: what is missing.
    #[error("{0}")]
    Undriven(String),
    /// No record or row to fit.
    #[error("nothing to fit: no record or row was given")]
    NoData,
    /// Fewer residuals than fitted values.
    #[error("{residuals} samples cannot fit {values} values")]
    TooFewSamples {
        /// Residuals.
        residuals: usize,
        /// Fitted values (free and nuisance).
        values: usize,
    },
    /// The experiment's cancellation token stopped the fit ([`Experiment::with_cancel`]).
    #[error(transparent)]
    Stopped(crate::Error),
    /// The model cannot be computed at the starting values.
    #[error("{file}: the model cannot be computed at the starting values: {error}")]
    Model {
        /// The record or table.
        file: String,
        /// What the library reported.
        error: crate::Error,
    },
}

/// How a fit runs. The defaults are listed field by field.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(default)]
pub struct FitOptions {
    /// Most Levenberg–Marquardt iterations. Default 50.
    pub max_iterations: usize,
    /// Converged when a step lowers the sum of squares by less than this fraction, or moves
    /// every (scaled) value by less than this. Default 1e-9.
    pub tolerance: f64,
    /// Fit a time shift between the channels of each record. Default true.
    pub time_shift: bool,
    /// Fit a DC offset of each record's u_C channel. Default true.
    pub offset: bool,
    /// Jacobians of records from the exact tangent dynamics wherever they serve ([`Jacobian`]);
    /// false: finite differences always (to compare). Default true.
    pub exact_jacobian: bool,
}

impl Default for FitOptions {
    fn default() -> Self {
        Self {
            max_iterations: 50,
            tolerance: 1e-9,
            time_shift: true,
            offset: true,
            exact_jacobian: true,
        }
    }
}

/// A fit's progress, told to a [`FitMonitor`] after every Levenberg–Marquardt iteration.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FitProgress {
    /// Iterations done, over every pass and (per record) every record so far.
    pub iteration: usize,
    /// The most iterations the fit may take (the passes' and records' maxima together); the
    /// fit usually converges well before.
    pub total: usize,
    /// The sum of squares of the weighted residuals reached (records: dimensionless, each
    /// residual in units of its channel's noise; a table: V²).
    pub sum_squares: f64,
}

/// Watches a fit: told after every iteration, and able to stop it (the fit then returns
/// [`FitError::Stopped`] with [`crate::Error::Cancelled`]). Every scan monitor
/// ([`crate::scan::Monitor`], such as `()` or a closure `Fn(done, total) -> bool`) is one and
/// sees (iterations done, most iterations).
pub trait FitMonitor: Sync {
    /// `progress` was reached; [`ControlFlow::Break`] stops the fit.
    fn iteration(&self, progress: &FitProgress) -> ControlFlow<()>;
}

impl<M: Monitor + ?Sized> FitMonitor for M {
    fn iteration(&self, progress: &FitProgress) -> ControlFlow<()> {
        self.step(progress.iteration, progress.total)
    }
}

/// Where a problem's iterations stand in the whole fit, and who watches.
#[derive(Clone, Copy)]
pub(super) struct Watch<'a> {
    pub(super) monitor: &'a dyn FitMonitor,
    /// Iterations done before this minimisation.
    pub(super) before: usize,
    pub(super) total: usize,
}

/// The most iterations a fit of records is told of, in units of
/// [`FitOptions::max_iterations`]: two passes, a restart and the minimisations of the
/// intervals' profiles (the count stops there; the fit is usually done far sooner).
pub const RECORD_PASSES: usize = 4;

impl Watch<'_> {
    pub(super) fn tell(&self, iteration: usize, sum_squares: f64) -> Result<(), FitError> {
        let progress = FitProgress {
            iteration: (self.before + iteration).min(self.total),
            total: self.total,
            sum_squares,
        };
        match self.monitor.iteration(&progress) {
            ControlFlow::Continue(()) => Ok(()),
            ControlFlow::Break(()) => Err(FitError::Stopped(crate::Error::Cancelled {
                done: progress.iteration,
                total: progress.total,
            })),
        }
    }
}
