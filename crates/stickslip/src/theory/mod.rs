//! Theory: the paper's series solution, exact periodic solutions and stick-slip boundaries.
//!
//! - [`paper`]: the paper's series solution, its eqs. (9) and (11) ([`PaperSeries`],
//!   [`UndampedSeries`], [`PaperHarmonic`]), and its approximate stick-slip boundary, eq. (13)
//!   ([`paper_boundary`]), transcribed literally into our notation (ω0 = 1, Ω → w, α → 2ζ).
//! - [`periodic`]: the exact symmetric periodic motion that never stops
//!   ([`PeriodicSolution`]): Den Hartog's solution (Phil. Mag. 1930) for ζ = 0, and its
//!   damped generalisation, with exact harmonics ([`Harmonic`]) and stability.
//! - [`boundary`]: the exact stick-slip boundary β_c(w, ζ, μs) ([`stick_slip_boundary`]).
//! - [`curves`]: either theory's gain, harmonics or boundary along one parameter, cut where
//!   they do not exist (the curves drawn over sweeps and maps).
//! - [`report`]: both theories side by side at one point ([`TheoryReport`]).
//! - [`belt`]: the block on a moving belt without a drive: the undamped Coulomb belt's
//!   stick-slip cycle in closed form ([`CoulombBeltCycle`]), the stability of steady
//!   sliding ([`SteadySliding`]), and the cubic law's cycles to first order after Thomsen &
//!   Fidlin ([`CubicBeltApproximation`]).
//!
//! ```
//! use stickslip::theory::{paper_boundary, stick_slip_boundary, PaperSeries, PeriodicSolution};
//! use stickslip::Params;
//! let params = Params::new(0.0468, 0.9, 2.0).unwrap();
//! let exact = PeriodicSolution::new(&params).unwrap();
//! let paper = PaperSeries::new(params.zeta, params.w, params.beta).unwrap();
//! // The paper's A1 is an approximation; its superharmonic amplitudes are exact.
//! assert!((paper.a1 - exact.a1()).abs() < 0.1 * exact.a1());
//! let a3 = paper.harmonic(2).unwrap().amplitude;
//! assert!((a3 - exact.harmonic(3).amplitude).abs() < 1e-12 * a3);
//! // Both boundaries lie below β = 2 at w = 0.9.
//! assert!(stick_slip_boundary(params.zeta, params.w, 1.0).unwrap().beta_c < 2.0);
//! assert!(paper_boundary(params.zeta, params.w).unwrap() < 2.0);
//! ```

pub mod belt;
pub mod boundary;
pub mod curves;
pub mod fourier;
pub(crate) mod obstruction;
pub mod paper;
pub mod periodic;
pub mod report;

pub use belt::{CoulombBeltCycle, CubicBeltApproximation, CubicBeltMotion, SteadySliding};
pub use boundary::{stick_slip_boundary, StickSlipBoundary};
pub use fourier::Harmonic;
pub use paper::{paper_boundary, PaperHarmonic, PaperSeries, UndampedSeries};
pub use periodic::{Obstruction, PeriodicSolution, CONTINUUM_DEFECT};
pub use report::{TheoryNote, TheoryReport};
