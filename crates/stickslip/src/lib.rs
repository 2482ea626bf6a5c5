//! # stickslip
//!
//! The forced harmonic oscillator damped by dry (Coulomb) friction, and its electrical twin,
//! a series RLC circuit damped by two anti-parallel diodes, after Xu, Fan, Wang and Jiang,
//! *Nonlinear effect of forced harmonic oscillator subject to sliding friction and simulation
//! by a simple nonlinear circuit* ("the paper").
//!
//! In dimensionless time τ = ω0·t ([`Params`]):
//!
//! ```text
//! y'' + 2ζ y' + y + sgn(y') = β cos(w τ + φ)      while sliding
//! y' = 0 and |β cos(w τ + φ) − y| ≤ μs            while stuck
//! ```
//!
//! - [`experiment`]: what front ends describe and run: an [`Experiment`] (a dimensionless
//!   model, a circuit with PWL or Shockley diodes, or a mechanical oscillator; a drive; μs; an
//!   initial state), read from a TOML file or built value by value, that converts to
//!   [`Params`], builds the right solver and its steady-state options, and converts back to
//!   physical units.
//! - [`physical`]: circuits and mechanical oscillators in SI units, and their exact
//!   conversion to [`Params`] (the paper's Table 1).
//! - [`ExactSolver`]: exact event-driven solution; every segment in closed form, only event
//!   times found numerically, with a step rule that cannot miss a velocity zero.
//! - [`Solver`]: the trait every solver implements; [`solver::run_until`] and
//!   [`solver::sample_at`] drive any of them.
//! - [`stiff`]: the stiff integrator of smooth laws (Radau IIA), generic over the law
//!   ([`stiff::SmoothLaw`]: the Shockley diode pair is the first), which runs the Shockley
//!   solver ([`ShockleySolver`]).
//! - [`steady`]: the steady state of any solver ([`steady_state`]), its spectrum and
//!   [`MotionClass`].
//! - [`scan`]: sweeps of ζ, w, β or μs with hysteresis ([`scan::Sweep`]) and grids of any two
//!   ([`scan::Grid`]), with progress and cancellation, deterministic for any number of
//!   threads.
//! - [`limits`]: the ranges of parameters, initial states and run lengths in which the
//!   solvers keep their accuracy, enforced wherever values enter the library.
//! - [`measure`]: oscilloscope exports (Rigol, Tektronix, Keysight, Siglent, plain CSV) and
//!   tables of measured amplitudes, read from text, with the drive's sine fit; [`fit`]: the
//!   circuit's parameters fitted to them by least squares, with error bars, per record, and
//!   PWL against Shockley.
//! - [`checkpoint`]: a resumable record of finished work (rows of a map, steps of a sweep),
//!   with its parameters and a checksum, for front ends that save long runs as they go.
//! - [`theory`]: the paper's series solution, the exact periodic solution, both stick-slip
//!   boundaries, and their curves.
//! - [`stability`]: the exact tangent dynamics (segment and saltation matrices), periodic
//!   orbits by Newton's method with their Floquet multipliers, Lyapunov exponents, and chaos
//!   told from quasi-periodic motion.
//! - [`attractor`]: what a motion settles on, from its strobe points and the exponent along
//!   them ([`attractor::AttractorKind`]: periodic, static, chaotic, quasi-periodic).
//! - [`bifurcation`]: bifurcation diagrams (strobe points against a parameter, state carried
//!   from value to value, up and down); [`basins`]: basins of attraction on a grid of initial
//!   states; [`continuation`]: branches of periodic orbits by pseudo-arclength continuation,
//!   through changes of the event sequence, with folds, period doublings and grazings.
//!
//! The library does no I/O and prints nothing; the `stickslip` command-line tool is the glue.

pub mod attractor;
pub mod basins;
pub mod bifurcation;
pub mod cancel;
mod certify;
pub mod checkpoint;
pub mod continuation;
pub mod error;
pub mod exact;
pub mod experiment;
pub mod fit;
pub mod friction;
pub mod friction_solver;
pub mod limits;
mod linear;
pub mod measure;
pub mod names;
pub mod options;
pub mod params;
pub mod physical;
pub mod report;
pub mod scan;
pub mod shockley;
pub mod solver;
pub mod stability;
pub mod steady;
pub mod stiff;
#[cfg(test)]
mod test_rng;
pub mod theory;
mod trig;
pub mod units;

pub use cancel::Cancel;
pub use error::{Error, NoSolutionReason, Number, Quantity, Result, Unsupported};
pub use exact::ExactSolver;
pub use experiment::{DiodeModel, Experiment, ExperimentSpec};
pub use options::{OptionKey, Spelling};
pub use params::{Parameter, Params, State};
pub use physical::{
    Circuit, Diode, Mechanics, PwlDiode, Scales, ShockleyDiode, System, SystemKind,
};
pub use shockley::{DiodePair, ShockleyOptions, ShockleySolver};
pub use solver::{Event, EventKind, Hints, Phase, Sample, Solver, Stats};
pub use steady::{steady_state, MotionClass, SteadyOptions, SteadyState};
pub use theory::{paper_boundary, stick_slip_boundary, PaperSeries, PeriodicSolution};
