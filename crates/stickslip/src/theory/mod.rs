//! Theory: the paper's series solution, exact periodic solutions and stick-slip boundaries.
//!
//! - [`paper`]: the paper's series solution, its eqs. (9) and (11) ([`PaperSeries`],
//!   [`UndampedSeries`], [`PaperHarmonic`]), and its approximate stick-slip boundary, eq. (13)
//!   ([`paper_boundary`]), transcribed literally into our notation (ω0 = 1, Ω → w, α → 2ζ).
//! - [`periodic`]: the exact symmetric periodic motion that never stops
//!   ([`PeriodicSolution`]): Den Hartog's solution (Phil. Mag. 1930) for ζ = 0, and its
//!   damped generalisation, with exact harmonics ([`Harmonic`]) and stability.

pub mod fourier;
pub mod paper;
pub mod periodic;

pub use fourier::Harmonic;
pub use paper::{paper_boundary, PaperHarmonic, PaperSeries, UndampedSeries};
pub use periodic::{Obstruction, PeriodicSolution, CONTINUUM_DEFECT};
