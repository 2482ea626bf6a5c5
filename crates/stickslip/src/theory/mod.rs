//! Theory: the paper's series solution, exact periodic solutions and stick-slip boundaries.
//!
//! - [`paper`]: the paper's series solution, its eqs. (9) and (11) ([`PaperSeries`],
//!   [`UndampedSeries`], [`PaperHarmonic`]), and its approximate stick-slip boundary, eq. (13)
//!   ([`paper_boundary`]), transcribed literally into our notation (ω0 = 1, Ω → w, α → 2ζ).

pub mod paper;

pub use paper::{paper_boundary, PaperHarmonic, PaperSeries, UndampedSeries};
