//! Steady motions on a grid of two parameters, computed in parallel (rayon), each point from
//! the experiment's initial state (rest, as in the paper's Fig. 7).

use super::axis::Axis;
use super::monitor::Monitor;
use crate::error::{Error, Result};
use crate::experiment::Experiment;
use crate::params::Params;
use crate::stability::{Dynamics, Estimate, LyapunovOptions};
use crate::steady::{
    check_horizon, settle_from, settle_with_exponent, MotionClass, SolverFactory, SteadyOptions,
};

use serde::{Deserialize, Serialize};
use std::ops::Range;
use std::sync::Arc;

/// One point of a grid.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct GridPoint {
    /// The parameters of the point.
    pub params: Params,
    /// Motion class.
    pub class: MotionClass,
    /// Period in drive periods (`None`: none found within the cap).
    pub period: Option<usize>,
    /// Stops of non-zero duration per drive period.
    pub stops_per_period: f64,
    /// Gain (y_max − y_min)/(2β).
    pub gain: f64,
    /// Whether the cycle is symmetric.
    pub symmetric: bool,
    /// Drive periods run before the cycle was recognised.
    pub periods_to_settle: usize,
    /// The largest Lyapunov exponent of the motion, when the grid was asked for it
    /// ([`Grid::lyapunov`]; `None` otherwise, or where the flow has no derivative).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub lyapunov: Option<Estimate>,
}

/// A finished grid: its two axes and its points, first-axis-major: `points[i·n + j]` holds
/// (first_i, second_j) with n = second.len().
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct GridMap {
    /// The first axis (rows).
    pub first: Axis,
    /// The second axis (columns).
    pub second: Axis,
    /// The points.
    pub points: Vec<GridPoint>,
}

impl GridMap {
    /// The point at (first_i, second_j).
    ///
    /// # Panics
    /// When i or j is out of range.
    pub fn at(&self, i: usize, j: usize) -> &GridPoint {
        assert!(
            i < self.first.len() && j < self.second.len(),
            "index out of the grid"
        );
        &self.points[i * self.second.len() + j]
    }
}

impl std::fmt::Debug for Grid {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Grid")
            .field("experiment", &self.experiment)
            .field("first", &self.first)
            .field("second", &self.second)
            .field("options", &self.options)
            .field("threads", &self.threads)
            .field("lyapunov", &self.lyapunov)
            .finish_non_exhaustive()
    }
}

/// A grid of two distinct parameters of an experiment (see the module documentation).
///
/// Defaults: the experiment's steady-state options ([`Experiment::steady_options`], without
/// the spectrum, which a grid never computes); rayon's global thread pool.
#[derive(Clone)]
pub struct Grid {
    experiment: Experiment,
    factory: Arc<dyn SolverFactory + Send>,
    first: Axis,
    second: Axis,
    options: SteadyOptions,
    threads: Option<usize>,
    lyapunov: Option<LyapunovOptions>,
    /// The experiment's stability tools, which measure the exponents ([`Grid::lyapunov`]).
    dynamics: Arc<dyn Dynamics>,
}

impl Grid {
    /// A grid of `first` × `second` over `experiment`, which needs no value of either
    /// parameter.
    ///
    /// # Errors
    /// [`Error::InvalidParameter`] when both axes vary the same parameter or the grid holds
    /// more than [`crate::limits::MAX_GRID_POINTS`] points; a value out of
    /// range for the model; a drive value missing that the grid does not set;
    /// [`Error::HorizonTooLong`] when the steady-state cap reaches beyond the time range the
    /// solvers resolve at some w of the grid.
    pub fn new(experiment: &Experiment, first: Axis, second: Axis) -> Result<Self> {
        if first.parameter() == second.parameter() {
            return Err(Error::InvalidParameter {
                name: first.parameter().label(),
                value: f64::NAN,
                allowed: "a grid needs two different parameters",
            });
        }
        let points = first.len().saturating_mul(second.len());
        if points > crate::limits::MAX_GRID_POINTS {
            return Err(Error::InvalidParameter {
                name: "points",
                value: points as f64,
                allowed: "a grid holds at most 1e8 points (e.g. 10000 × 10000; docs/limits.md)",
            });
        }
        let (p, q) = (first.parameter(), second.parameter());
        for &a in first.values() {
            experiment.params_with(&[(p, a), (q, second.values()[0])])?;
        }
        for &b in second.values() {
            experiment.params_with(&[(p, first.values()[0]), (q, b)])?;
        }
        let grid = Self {
            // (Validated here, once: the points take them as they are.)
            options: experiment.steady_options().validate()?.with_spectrum(false),
            factory: Arc::new(experiment.factory()),
            experiment: experiment.clone(),
            first,
            second,
            threads: None,
            lyapunov: None,
            dynamics: Arc::from(experiment.dynamics()?),
        };
        grid.check_horizons()?;
        Ok(grid)
    }

    /// Check that every point's longest run stays within the time range the solvers resolve
    /// ([`crate::steady::check_horizon`]): on the axes' edges, which hold every value of w.
    fn check_horizons(&self) -> Result<()> {
        for i in 0..self.first.len() {
            check_horizon(&self.params(i, 0)?, &self.options, 0.0)?;
        }
        for j in 0..self.second.len() {
            check_horizon(&self.params(0, j)?, &self.options, 0.0)?;
        }
        Ok(())
    }

    /// Build solvers with `factory` instead of the experiment's own (for another solver of the
    /// same model).
    pub fn with_factory(mut self, factory: impl SolverFactory + Send + 'static) -> Self {
        self.factory = Arc::new(factory);
        self
    }

    /// Use these steady-state options (the spectrum is never computed).
    ///
    /// # Errors
    /// When the options are invalid; [`Error::HorizonTooLong`] as [`Grid::new`].
    pub fn options(mut self, options: SteadyOptions) -> Result<Self> {
        self.options = options.validate()?.with_spectrum(false);
        self.check_horizons()?;
        Ok(self)
    }

    /// Compute on a pool of `threads` threads of its own instead of rayon's global pool
    /// (results are the same for any number).
    ///
    /// # Errors
    /// [`crate::Error::InvalidOption`] naming [`crate::options::OptionKey::Threads`] outside
    /// its row's range (1 to 1024).
    pub fn threads(mut self, threads: usize) -> Result<Self> {
        crate::options::OptionKey::Threads.check_count(threads)?;
        self.threads = Some(threads);
        Ok(self)
    }

    /// Also find the largest Lyapunov exponent of every point ([`GridPoint::lyapunov`], by
    /// [`crate::stability::steady_exponent_of`] with the experiment's
    /// [`Experiment::dynamics`]): exactly, from the Floquet multipliers of the periodic orbit,
    /// where the motion repeats (a Newton step or two from the recorded cycle), and measured
    /// with `options` where it does not (unless the steady-state search measured it already,
    /// with [`SteadyOptions::lyapunov`]). A motion decided chaotic or contracting early in its
    /// search stops there ([`crate::steady::steady_state_with_exponent`]). With Shockley
    /// diodes the multipliers and the tangent dynamics are those of the stiff solver's
    /// computed solution ([`crate::stability::ShockleyDynamics`]), exact to its tolerance;
    /// with a Stribeck or cubic law those of the friction solver
    /// ([`crate::stability::FrictionDynamics`]). Points still differ only by what they compute, so the map stays the same for any
    /// number of threads.
    ///
    /// # Errors
    /// Invalid options; [`Error::HorizonTooLong`] when the measurement reaches beyond the
    /// time range the solvers resolve at some w of the grid.
    pub fn lyapunov(mut self, options: LyapunovOptions) -> Result<Self> {
        let options = options.validate()?;
        // The measurement starts again at τ = 0 from the end of the steady-state search; the
        // axes' edges hold every value of w.
        for i in 0..self.first.len() {
            options.check_horizon(&self.params(i, 0)?)?;
        }
        for j in 0..self.second.len() {
            options.check_horizon(&self.params(0, j)?)?;
        }
        self.lyapunov = Some(options);
        Ok(self)
    }

    /// The steady-state options used.
    pub fn steady_options(&self) -> &SteadyOptions {
        &self.options
    }

    /// The options of the Lyapunov exponents, when the grid was asked for them
    /// ([`Grid::lyapunov`]).
    pub fn lyapunov_options(&self) -> Option<&LyapunovOptions> {
        self.lyapunov.as_ref()
    }

    /// The first axis (rows).
    pub fn first(&self) -> &Axis {
        &self.first
    }

    /// The second axis (columns).
    pub fn second(&self) -> &Axis {
        &self.second
    }

    /// Rows and columns.
    pub fn shape(&self) -> (usize, usize) {
        (self.first.len(), self.second.len())
    }

    /// The parameters of the point (first_i, second_j), as [`Grid::point`] computes it with
    /// (for front ends that rebuild points they saved, e.g. in a
    /// [`crate::checkpoint::Checkpoint`]).
    ///
    /// # Errors
    /// A value out of range (never for a grid built by [`Grid::new`]).
    ///
    /// # Panics
    /// When i or j is out of range.
    pub fn params(&self, i: usize, j: usize) -> Result<Params> {
        self.experiment.params_with(&[
            (self.first.parameter(), self.first.values()[i]),
            (self.second.parameter(), self.second.values()[j]),
        ])
    }

    /// The experiment the grid varies.
    pub fn experiment(&self) -> &Experiment {
        &self.experiment
    }

    /// The point at (first_i, second_j), computed alone.
    ///
    /// # Errors
    /// Whatever the solver reports.
    ///
    /// # Panics
    /// When i or j is out of range.
    pub fn point(&self, i: usize, j: usize) -> Result<GridPoint> {
        let params = self.params(i, j)?;
        let (s, lyapunov) = match &self.lyapunov {
            // (The options were validated when the grid took them.)
            Some(options) => settle_with_exponent(
                self.factory.as_ref(),
                self.dynamics.as_ref(),
                &params,
                self.experiment.initial(),
                &self.options,
                options,
            )?,
            None => (
                settle_from(
                    self.factory.as_ref(),
                    &params,
                    self.experiment.initial(),
                    &self.options,
                )?,
                None,
            ),
        };
        Ok(GridPoint {
            params,
            class: s.class,
            period: s.period,
            stops_per_period: s.stops_per_period,
            gain: s.gain,
            symmetric: s.symmetric,
            periods_to_settle: s.periods_to_settle,
            lyapunov,
        })
    }

    /// Compute the whole grid; `monitor` sees every finished point and can stop the work.
    ///
    /// # Errors
    /// [`Error::Cancelled`]; the first solver failure.
    pub fn run(&self, monitor: &dyn Monitor) -> Result<GridMap> {
        let (rows, cols) = self.shape();
        let points = self.run_block(0..rows, 0..cols, monitor)?;
        Ok(GridMap {
            first: self.first.clone(),
            second: self.second.clone(),
            points,
        })
    }

    /// Compute the whole grid a block of rows at a time, in order, handing every finished
    /// block to `rows` (its row range and its points, row-major) before the next block
    /// starts: memory stays at a few blocks whatever the grid's size, and a caller that passes
    /// the points on to another thread (to write them) overlaps that with the computation of
    /// the next block. A block holds whole rows, at least 256 points per thread
    /// ([`Grid::stream_block_rows`]); the points are those of [`Grid::run`], whatever the
    /// block size or number of threads. `monitor` sees every finished point, counted over the
    /// whole grid, and can stop the work.
    ///
    /// # Errors
    /// [`Error::Cancelled`]; the first solver failure; the first error of `rows` (the work
    /// stops there).
    pub fn run_rows(
        &self,
        monitor: &dyn Monitor,
        mut rows: impl FnMut(Range<usize>, Vec<GridPoint>) -> Result<()>,
    ) -> Result<()> {
        let (nr, nc) = self.shape();
        let total = nr * nc;
        let block = self.stream_block_rows();
        let mut first = 0;
        while first < nr {
            let last = (first + block).min(nr);
            let offset = first * nc;
            let counted = |done: usize, _: usize| monitor.step(offset + done, total);
            let points = self.run_block(first..last, 0..nc, &Offset(&counted))?;
            rows(first..last, points)?;
            first = last;
        }
        Ok(())
    }

    /// Rows per block of [`Grid::run_rows`]: enough for 256 points per thread of the pool
    /// (at least one row).
    pub fn stream_block_rows(&self) -> usize {
        let threads = self.threads.unwrap_or_else(rayon::current_num_threads);
        (256 * threads).div_ceil(self.shape().1.max(1)).max(1)
    }

    /// Compute the block `rows` × `cols` of the grid, row-major; `monitor` sees every
    /// finished point (counted within the block) and can stop the work. A grid computed
    /// block by block equals the grid computed at once.
    ///
    /// # Errors
    /// [`Error::InvalidParameter`] for a block outside the grid; [`Error::Cancelled`]; the
    /// first solver failure.
    pub fn run_block(
        &self,
        rows: Range<usize>,
        cols: Range<usize>,
        monitor: &dyn Monitor,
    ) -> Result<Vec<GridPoint>> {
        let (nr, nc) = self.shape();
        if rows.start > rows.end || rows.end > nr || cols.start > cols.end || cols.end > nc {
            return Err(Error::InvalidParameter {
                name: "block",
                value: rows.end.max(cols.end) as f64,
                allowed: "the block must lie inside the grid",
            });
        }
        let width = cols.len();
        let total = rows.len() * width;
        super::run_parallel(total, self.threads, monitor, |k| {
            self.point(rows.start + k / width, cols.start + k % width)
        })
    }
}

/// A monitor that counts points over the whole grid (see [`Grid::run_rows`]).
struct Offset<'a, F: Fn(usize, usize) -> std::ops::ControlFlow<()> + Sync>(&'a F);

impl<F: Fn(usize, usize) -> std::ops::ControlFlow<()> + Sync> Monitor for Offset<'_, F> {
    fn step(&self, done: usize, total: usize) -> std::ops::ControlFlow<()> {
        (self.0)(done, total)
    }
}
