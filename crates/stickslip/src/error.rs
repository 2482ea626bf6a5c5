//! Typed errors of the library.
//!
//! Every variant carries the values a caller needs to act on it (the offending value, the time
//! of a numerical failure, the reason a solution does not exist as an enum), and its `Display`
//! is one line.

use crate::experiment::errors::{ConfigError, SpecError};
use crate::experiment::keys::Key;
use crate::options::key::{Allowed, OptionKey, Spelling};
use crate::stability::error::StabilityError;
use crate::theory::obstruction::Obstruction;
use crate::units::NumberError;
use thiserror::Error;

/// Everything that can go wrong in the library, with the offending value in the variant.
#[derive(Debug, Clone, PartialEq, Error)]
#[non_exhaustive]
pub enum Error {
    /// A parameter is NaN, infinite or outside its allowed range.
    #[error("invalid {name} = {}: {allowed}", Number(*value))]
    InvalidParameter {
        /// Name of the parameter as the user knows it (e.g. `zeta`, `L`).
        name: &'static str,
        /// The rejected value.
        value: f64,
        /// What is allowed, in words (e.g. "must be finite and >= 0").
        allowed: &'static str,
    },
    /// An option of a computation is outside its range ([`crate::options`]).
    #[error("{}", option.message(*value, allowed, Spelling::Python))]
    InvalidOption {
        /// The option.
        option: OptionKey,
        /// The rejected value.
        value: f64,
        /// What is allowed.
        allowed: Allowed,
    },
    /// Two options whose product (the size of the result) is too large.
    #[error(
        "invalid {what} = {}: {} × {} must be at most {max}",
        Number(*product),
        first.name(),
        second.name()
    )]
    OptionProduct {
        /// What the product counts (`samples`, `rows`, `points`).
        what: &'static str,
        /// The first option.
        first: OptionKey,
        /// The second option.
        second: OptionKey,
        /// Their product.
        product: f64,
        /// The largest product allowed, in words.
        max: &'static str,
    },
    /// A requested time lies before the solver's current time.
    #[error("requested time {requested} lies before the solver's current time {current}")]
    TimeBeforeCurrent {
        /// The requested time (dimensionless τ).
        requested: f64,
        /// The solver's current time (dimensionless τ).
        current: f64,
    },
    /// An event search could not bracket or converge (a numerical failure, reported not hidden).
    #[error("event search failed at tau = {tau}: {reason}")]
    EventSearch {
        /// Time (dimensionless τ) at which the failure happened.
        tau: f64,
        /// What failed.
        reason: &'static str,
    },
    /// The exact solver's search for the velocity zero that ends a slide (a turn or a stop)
    /// used up its step budget: the motion lies outside what the solver resolves.
    #[error(
        "the search for the velocity zero (turn or stop) ending the slide in the {direction} \
         direction that started at tau = {start:.6e} gave up at tau = {tau:.6e} after {steps} \
         steps: lower beta, |y0|, |v0| or zeta, or shorten the run (docs/limits.md)"
    )]
    SlideSearch {
        /// Time (dimensionless τ) at which the slide started.
        start: f64,
        /// Time (dimensionless τ) up to which the slide was searched.
        tau: f64,
        /// Direction of the slide, `+` or `-`.
        direction: char,
        /// Search steps taken on the slide.
        steps: u64,
    },
    /// A run longer than the time range the solvers resolve ([`crate::limits::max_periods`]).
    #[error(
        "a run of {} drive periods at w = {} is too long: the time and the drive phase must \
         stay below 2^32, where their rounding is 1e-6; at most {} periods at this w \
         (docs/limits.md)",
        Number(*periods),
        Number(*w),
        Number(max_periods.floor())
    )]
    HorizonTooLong {
        /// Drive periods asked for.
        periods: f64,
        /// The drive frequency w.
        w: f64,
        /// The most drive periods allowed at this w.
        max_periods: f64,
    },
    /// A physical value whose dimensionless image lies outside the range the solvers
    /// support ([`crate::limits`]).
    #[error(
        "invalid {key} = {}: it gives {image} = {}, which {allowed}",
        Number(*value),
        Number(*image_value)
    )]
    ImageOutOfRange {
        /// The physical value (e.g. `f`, `U`, `R`).
        key: Key,
        /// The physical value.
        value: f64,
        /// The dimensionless quantity it gives (e.g. `w`, `beta`, `zeta`).
        image: &'static str,
        /// Its value.
        image_value: f64,
        /// The dimensionless quantity's range, in words.
        allowed: &'static str,
    },
    /// The stiff integrator's step size fell below what the time's rounding allows.
    #[error("integrator failed at tau = {tau}: step size underflow (h = {step:e})")]
    StepSizeTooSmall {
        /// Time (dimensionless τ) at which the step could not be taken.
        tau: f64,
        /// The step size (dimensionless) that was too small.
        step: f64,
    },
    /// A quantity requested from a theory does not exist for these parameters.
    #[error("{what} does not exist: {reason}")]
    NoSolution {
        /// What was asked for.
        what: Quantity,
        /// Why it does not exist.
        reason: NoSolutionReason,
    },
    /// A long computation (a sweep or a grid) was stopped by its caller.
    #[error("cancelled after {done} of {total} points")]
    Cancelled {
        /// Points finished when the computation stopped.
        done: usize,
        /// Points requested.
        total: usize,
    },
    /// The computation's [`crate::cancel::Cancel`] token passed its deadline.
    #[error("stopped: the deadline passed")]
    DeadlineExceeded,
    /// The computation's [`crate::cancel::Cancel`] token used up its budget of solver steps.
    #[error("stopped: the budget of {budget} solver steps is used up")]
    BudgetExceeded {
        /// The budget (solver steps).
        budget: u64,
    },
    /// An experiment description is incomplete or contradicts itself.
    #[error(transparent)]
    Spec(#[from] SpecError),
    /// An experiment file could not be read as an experiment.
    #[error(transparent)]
    Config(#[from] ConfigError),
    /// Text that is not a value of its key: not a number, or a number with a unit that is
    /// not the key's ([`crate::experiment::Key::parse`]).
    #[error("invalid {key}: {error}")]
    InvalidText {
        /// The key the text was given for.
        key: Key,
        /// What is wrong with the text.
        error: NumberError,
    },
    /// Text that is none of the names a key takes (the diode law, the preset:
    /// [`crate::experiment::Key::choices`]).
    #[error("invalid {key} '{text}': one of {}", allowed.join(", "))]
    InvalidName {
        /// The key the text was given for.
        key: Key,
        /// The text given (control characters escaped, at most 40 characters).
        text: String,
        /// The names the key takes.
        allowed: Vec<&'static str>,
    },
    /// What was asked for does not apply to this model.
    #[error("{0}")]
    Unsupported(Unsupported),
    /// A stability analysis failed (Newton's method, a non-finite Jacobian, …).
    #[error(transparent)]
    Stability(#[from] StabilityError),
}

impl Error {
    /// The option an [`Error::InvalidOption`] names (the first of an
    /// [`Error::OptionProduct`]).
    pub fn option(&self) -> Option<OptionKey> {
        match self {
            Error::InvalidOption { option, .. } => Some(*option),
            Error::OptionProduct { first, .. } => Some(*first),
            _ => None,
        }
    }

    /// Whether the computation was stopped by its caller (cancelled, past its deadline or
    /// over its budget) rather than failed.
    pub fn is_stop(&self) -> bool {
        matches!(
            self,
            Error::Cancelled { .. } | Error::DeadlineExceeded | Error::BudgetExceeded { .. }
        )
    }
}

/// A quantity that a theory may fail to provide.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
#[non_exhaustive]
pub enum Quantity {
    /// The paper's A1, eq. (11).
    PaperA1,
    /// A superharmonic of the paper's eq. (11).
    PaperHarmonic,
    /// The paper's undamped A1, eq. (9).
    PaperUndampedA1,
    /// A superharmonic of the paper's eq. (9).
    PaperUndampedHarmonic,
    /// The paper's stick-slip boundary, eq. (13).
    PaperBoundary,
    /// The exact symmetric periodic motion that never stops.
    ExactOrbit,
    /// The exact stick-slip boundary β_c.
    ExactBoundary,
}

impl std::fmt::Display for Quantity {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(match self {
            Quantity::PaperA1 => "the paper's A1 (eq. (11))",
            Quantity::PaperHarmonic => "the paper's superharmonic (eq. (11))",
            Quantity::PaperUndampedA1 => "the paper's undamped A1 (eq. (9))",
            Quantity::PaperUndampedHarmonic => "the paper's undamped superharmonic (eq. (9))",
            Quantity::PaperBoundary => "the paper's boundary (eq. (13))",
            Quantity::ExactOrbit => "the exact non-sticking periodic solution",
            Quantity::ExactBoundary => "the exact stick-slip boundary",
        })
    }
}

/// Why a theory's quantity does not exist.
#[derive(Debug, Clone, Copy, PartialEq)]
#[non_exhaustive]
pub enum NoSolutionReason {
    /// ζ = 0 and w = 1: the paper's impedance Z vanishes and eq. (11) is 0/0.
    ZeroImpedance,
    /// Eq. (11) takes the square root of π²β²Z² − 16(w² − 1)² < 0.
    NegativeRadicand {
        /// The radicand.
        radicand: f64,
        /// The drive amplitude β.
        beta: f64,
        /// The smallest β for which the radicand is not negative, 4|1 − w²|/(πZ).
        beta_min: f64,
    },
    /// Eq. (11) gives A1 < 0: β is below 4/π.
    NegativeAmplitude {
        /// The negative A1.
        a1: f64,
        /// The drive amplitude β.
        beta: f64,
    },
    /// ζ = 0 and (order)·w = 1: the friction's harmonic drives the undamped oscillator at
    /// resonance and the harmonic is infinite.
    HarmonicResonance {
        /// The odd harmonic order.
        order: u32,
    },
    /// Eq. (9) takes the square root of β² − (4/π)² < 0.
    BelowFourOverPi {
        /// The radicand β² − (4/π)².
        radicand: f64,
        /// The drive amplitude β.
        beta: f64,
    },
    /// Eq. (9) divides by 1 − w² = 0 at w = 1.
    UndampedResonance,
    /// Eq. (9) divides by zero at (order)·w = 1.
    UndampedHarmonicResonance {
        /// The odd harmonic order.
        order: u32,
    },
    /// The exact construction fails for this reason.
    Obstruction(Obstruction),
    /// No β up to `limit` gives a motion that never stops.
    NoBetaBelow {
        /// The largest β tried.
        limit: f64,
    },
}

impl std::fmt::Display for NoSolutionReason {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match *self {
            NoSolutionReason::ZeroImpedance => {
                f.write_str("Z = 0 at ζ = 0, w = 1: eq. (11) is 0/0 (the undamped resonance)")
            }
            NoSolutionReason::NegativeRadicand {
                radicand,
                beta,
                beta_min,
            } => write!(
                f,
                "eq. (11) takes the square root of π²β²Z² − 16(w² − 1)² = {radicand:.6} < 0 \
                 (β = {beta} < 4|1 − w²|/(πZ) = {beta_min:.6})"
            ),
            NoSolutionReason::NegativeAmplitude { a1, beta } => write!(
                f,
                "eq. (11) gives A1 = {a1:.6} < 0: β = {beta} is below 4/π, where the \
                 friction's square wave outweighs the drive"
            ),
            NoSolutionReason::HarmonicResonance { order } => write!(
                f,
                "A_{order} is infinite at ζ = 0, {order}w = 1: the friction's harmonic \
                 {order} drives the undamped oscillator at resonance"
            ),
            NoSolutionReason::BelowFourOverPi { radicand, beta } => write!(
                f,
                "eq. (9) takes the square root of β² − (4/π)² = {radicand:.6} < 0 \
                 (β = {beta} < 4/π)"
            ),
            NoSolutionReason::UndampedResonance => {
                f.write_str("eq. (9) divides by 1 − w² = 0 at w = 1")
            }
            NoSolutionReason::UndampedHarmonicResonance { order } => {
                write!(f, "eq. (9) divides by zero at {order}w = 1")
            }
            NoSolutionReason::Obstruction(why) => write!(f, "{why}"),
            NoSolutionReason::NoBetaBelow { limit } => {
                write!(f, "no β up to {limit:e} gives a non-sticking motion")
            }
        }
    }
}

/// A request that does not apply to the model it was made for.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
#[non_exhaustive]
pub enum Unsupported {
    /// The Shockley diode law needs a circuit (L, C, R and a reference voltage).
    ShockleyNeedsCircuit,
    /// A SPICE netlist describes a circuit with Shockley diodes.
    NetlistNeedsShockley,
    /// The theories (the paper's series, the exact orbit) are those of the piecewise-linear
    /// model.
    TheoryNeedsPwl,
    /// A tool of the exact piecewise-linear model alone
    /// ([`crate::Experiment::exact_params`]; the stability tools take Shockley diodes too).
    StabilityNeedsPwl,
    /// μs, the static friction ratio, is a parameter of the piecewise-linear law only (a
    /// continuation in it with Shockley diodes).
    MuSNeedsPwl,
    /// A tool of the exact Coulomb model alone (its exact solver, tangent dynamics and
    /// sensitivities) was asked for a Stribeck or cubic law; the commands take both
    /// (`simulate`, `steady`, `sweep`, `phase-diagram`, `orbit`, `lyapunov`, `continue`,
    /// `bifurcation`, `basins`, `curve`).
    SmoothFrictionLaw,
    /// Grazing curves follow events of the exact solver, with Coulomb's law: a Stribeck or
    /// cubic law (`law`) has curves of folds, period doublings and Neimark–Sacker points.
    GrazingCurveNeedsCoulomb {
        /// The law asked for, as users type it (`stribeck`, `cubic`).
        law: &'static str,
    },
    /// Curves of special points in two parameters are followed with the exact
    /// piecewise-linear model (its grazings are events of the exact solver).
    CurveNeedsPwl,
    /// The theories (the paper's series, the exact periodic solution) are those of Coulomb
    /// friction on a base at rest (vb = 0).
    TheoryNeedsCoulombAtRest,
    /// The Coulomb model has no Neimark–Sacker point: a complex pair of multipliers on the
    /// unit circle needs det M = 1, and det M = e^(−2ζpT) Π (|F|−1)/(|F|+1) over the slip
    /// reversals (|F| > μs ≥ 1 the net force there) is below 1 on every orbit that reverses,
    /// 0 on one that sticks (docs/bifurcation.md, "No Neimark–Sacker point").
    NoNeimarkSacker,
}

impl std::fmt::Display for Unsupported {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let text = match self {
            Unsupported::ShockleyNeedsCircuit => {
                "the Shockley diode model needs a circuit description (e.g. the paper preset)"
            }
            Unsupported::NetlistNeedsShockley => {
                "a SPICE netlist needs a circuit description with Shockley diodes"
            }
            Unsupported::TheoryNeedsPwl => {
                "the theory covers the piecewise-linear diode (Coulomb friction) model, not \
                 Shockley diodes"
            }
            Unsupported::StabilityNeedsPwl => {
                "this tool takes the exact piecewise-linear diode (Coulomb friction) model, \
                 not Shockley diodes (`stickslip orbit`, `lyapunov`, `continue`, \
                 `bifurcation`, `basins` and `phase-diagram --color lambda1` take either)"
            }
            Unsupported::MuSNeedsPwl => {
                "mu_s (static friction) is a parameter of the piecewise-linear law only: a \
                 Shockley diode has no static threshold; continue in w, beta or zeta"
            }
            Unsupported::SmoothFrictionLaw => {
                "this takes Coulomb's friction law alone (the exact model's solver and its \
                 derivatives): the Stribeck and cubic laws are solved by simulate, steady, \
                 sweep, phase-diagram, orbit, lyapunov, continue, bifurcation, basins and curve"
            }
            Unsupported::TheoryNeedsCoulombAtRest => {
                "the theory (the paper's series, the exact periodic solution) is that of \
                 Coulomb friction on a base at rest: it takes neither a belt speed vb nor the \
                 Stribeck or cubic law (`stickslip steady` finds a belt's steady state)"
            }
            Unsupported::NoNeimarkSacker => {
                "the Coulomb model has no Neimark–Sacker point: a complex pair on the unit \
                 circle needs det M = 1, but det M = e^(-2ζpT) × Π (|F|-1)/(|F|+1) over the \
                 slip reversals (|F| > μs ≥ 1, the net force there) is below 1 on every orbit \
                 that reverses, and 0 on one that sticks (docs/bifurcation.md)"
            }
            Unsupported::GrazingCurveNeedsCoulomb { law } => {
                return write!(
                    f,
                    "grazing curves follow the exact solver's events, with Coulomb's friction \
                     law: with the {} law a curve follows a fold, a period doubling or a \
                     Neimark–Sacker point (follow fold, period-doubling or neimark-sacker; or \
                     grazing with the coulomb law)",
                    law
                )
            }
            Unsupported::CurveNeedsPwl => {
                "curves of special points in two parameters are followed with the exact \
                 piecewise-linear diode (Coulomb friction) model, not Shockley diodes \
                 (`stickslip continue` follows a branch of either)"
            }
        };
        f.write_str(text)
    }
}

/// A number for a message: as Rust writes it (shortest text that reads back the same) from
/// 10⁻⁴ to 10¹⁵, in exponent form beyond (never 300 digits).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Number(pub f64);

impl std::fmt::Display for Number {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let x = self.0;
        if x == 0.0 || !x.is_finite() || (1e-4..1e15).contains(&x.abs()) {
            write!(f, "{x}")
        } else {
            write!(f, "{x:e}")
        }
    }
}

/// Result alias of the library.
pub type Result<T, E = Error> = std::result::Result<T, E>;

/// Check that `value` is finite; `allowed` is the message shown otherwise.
pub(crate) fn check(
    name: &'static str,
    value: f64,
    ok: bool,
    allowed: &'static str,
) -> Result<f64> {
    if value.is_finite() && ok {
        Ok(value)
    } else {
        invalid(name, value, allowed)
    }
}

/// [`Error::InvalidParameter`] as a result: `value` of `name` refused, `allowed` saying what
/// is allowed.
pub(crate) fn invalid<T>(name: &'static str, value: f64, allowed: &'static str) -> Result<T> {
    Err(Error::InvalidParameter {
        name,
        value,
        allowed,
    })
}
