//! Sweeps and grids of steady states over the dimensionless parameters ζ, w, β and μs.
//!
//! - [`Sweep`]: one parameter stepped up, down or both ways, each step starting from the state
//!   where the step before ended, as when turning a knob of the experiment: hysteresis and
//!   coexisting motions show up as different branches.
//! - [`Grid`]: any two parameters on a grid, every point from the experiment's initial state
//!   (rest, as in the paper's Fig. 7), computed in parallel.
//!
//! Both take an [`Experiment`](crate::experiment::Experiment) whose swept parameters need no
//! value, an [`Axis`] per parameter (any values, or an evenly spaced [`ParameterRange`]), and
//! report progress to a [`Monitor`], which can also cancel. Results do not depend on the
//! number of threads: every grid point is computed on its own, the same way, whichever thread
//! runs it.
//!
//! ```
//! use stickslip::experiment::Experiment;
//! use stickslip::scan::{Axis, Grid, ParameterRange, Sweep, SweepDirection};
//! use stickslip::Parameter;
//! let paper = Experiment::paper();
//! let sweep = Sweep::new(
//!     &paper.clone().with_beta(3.61).unwrap(),
//!     Axis::range(Parameter::W, &ParameterRange::new("w", 0.5, 1.5, 5).unwrap()).unwrap(),
//! )
//! .unwrap()
//! .direction(SweepDirection::Both)
//! .run(&())
//! .unwrap();
//! assert_eq!(sweep.len(), 10);
//! let map = Grid::new(
//!     &paper,
//!     Axis::new(Parameter::W, vec![0.6, 0.9]).unwrap(),
//!     Axis::new(Parameter::Beta, vec![1.0, 1.6]).unwrap(),
//! )
//! .unwrap()
//! .run(&())
//! .unwrap();
//! assert_eq!(map.points.len(), 4);
//! ```

mod axis;
mod color;
mod grid;
mod monitor;
mod range;
mod sweep;

pub use axis::Axis;
pub use color::MapColor;
pub use grid::{Grid, GridMap, GridPoint};
pub(crate) use monitor::run_parallel;
pub use monitor::Monitor;
pub use range::{grid_value, ParameterRange};
pub use sweep::{Sweep, SweepDirection, SweepLeg, SweepPoint};
