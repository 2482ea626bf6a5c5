//! Basins of attraction: which attractor the motion settles on from each initial state of a
//! grid, and the attractors identified and numbered.
//!
//! Two methods ([`BasinOptions::method`]) find the attractor of each cell:
//!
//! - **recurrence** (the default, [`BasinMethod::Recurrence`]): each initial state follows
//!   the strobe map on a finer grid of the state space until it lands on cells already
//!   labelled with an attractor or its basin, or comes back to its own cells often enough to
//!   declare a new attractor, which is then classified once, as below (see [`Recurrence`]);
//! - **exhaustive** ([`BasinMethod::Exhaustive`]): every cell is run to its steady state and
//!   classified on its own, as follows; the reference the recurrence method is tested
//!   against.
//!
//! The exhaustive method starts the exact solver at each cell (y0, y0') of the grid at τ = 0
//! (drive phase φ of the experiment), the recurrence method at a point of each new attractor,
//! and runs it to its steady state ([`crate::steady::steady_state_from`], at most
//! [`BasinOptions::max_periods`] drive periods, extrapolating the strobe map where it
//! converges linearly). Then:
//!
//! - a motion that repeats after p periods is a **periodic** orbit; its fixed point of P^p is
//!   refined by Newton's method ([`crate::stability::find_periodic_orbit`]), so every cell of
//!   its basin carries the exact orbit (to 1e-12), and cells are matched by period and by
//!   their fixed point lying within [`BasinOptions::match_tolerance`] of one of the p strobe
//!   points of an orbit found before (a period-p orbit is one attractor whichever of its strobe
//!   points a cell lands on);
//! - a motion that repeats without a single event is **rest** (static): the rest positions
//!   form a continuum, and all of them together are one attractor, kind
//!   [`AttractorKind::Static`];
//! - a motion without a period gets its largest Lyapunov exponent measured over
//!   [`BasinOptions::lyapunov_periods`] more periods ([`crate::attractor::record_strobes`]):
//!   **chaotic** when it is positive beyond [`BasinOptions::significance`] standard errors,
//!   **quasi-periodic** when it is within them of 0, and undecided (no attractor) when it is
//!   negative (a periodic orbit not reached within the cap) or a late period shows. Chaotic
//!   and quasi-periodic cells of one attractor are told apart from those of another by their
//!   strobe sets: a cell belongs to an attractor found before when at least 90 % of its
//!   [`BasinOptions::sample_points`] strobe points lie within 10 % of that attractor's extent
//!   of the attractor's strobe points.
//!
//! Exhaustive cells are computed in parallel, each on its own; recurrence cells one after the
//! other in the order of the cells. Attractors are identified afterwards in the order of the
//! cells, so the map and the numbering are the same for any number of threads and for a map
//! computed in blocks of rows ([`Basins::run_rows`], [`Recurrence::run_row`],
//! [`Basins::identify`]). Mirror images under the symmetry (y, y', τ) → (−y, −y', τ + T/2)
//! of the equation are paired ([`Attractor::mirror`]).
//!
//! ```
//! use stickslip::basins::Basins;
//! use stickslip::attractor::AttractorKind;
//! use stickslip::scan::ParameterRange;
//! use stickslip::Experiment;
//! // The paper's ζ with μs = 1.5 at (w, β) = (0.9, 1.4): rest and a stick-slip orbit coexist.
//! let experiment = Experiment::dimensionless(0.046816, 0.9, 1.4).unwrap().with_mu_s(1.5).unwrap();
//! let y0 = ParameterRange::new("y0", -3.0, 3.0, 5).unwrap();
//! let v0 = ParameterRange::new("v0", -3.0, 3.0, 5).unwrap();
//! let map = Basins::new(&experiment, &y0, &v0).unwrap().run(&()).unwrap();
//! let kinds: Vec<AttractorKind> = map.attractors.iter().map(|a| a.kind).collect();
//! assert!(kinds.contains(&AttractorKind::Static) && kinds.contains(&AttractorKind::Periodic));
//! ```

use crate::attractor::{
    distance, record_strobes_of, scale_of, strobe_sets_overlap as overlaps, AttractorKind,
    RecordOptions,
};
use crate::checkpoint::{UnitReader, UnitWriter};
use crate::error::{invalid, Error, Result};
use crate::experiment::Experiment;
use crate::options::OptionKey;
use crate::params::{Params, State};
use crate::scan::{Monitor, ParameterRange};
use crate::solver::run_until;
use crate::stability::{Dynamics, Multiplier, NewtonOptions};
use crate::steady::{exact_solver, steady_state_from, SteadyOptions};
use serde::{Deserialize, Serialize};
use std::ops::Range;
use std::sync::Arc;

mod recurrence;
pub use recurrence::{Recurrence, RecurrenceRow};

/// How a [`Basins`] map finds the attractor of each cell.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum BasinMethod {
    /// By recurrence on a finer grid of the strobe map's state space: a cell stops as soon
    /// as its motion reaches a cell labelled with an attractor or its basin, and each
    /// attractor is classified once ([`Recurrence`]). The default.
    #[default]
    Recurrence,
    /// Every cell run to its steady state and classified on its own (the reference the
    /// recurrence method is checked against).
    Exhaustive,
}

impl BasinMethod {
    /// Both methods.
    pub const ALL: [BasinMethod; 2] = [BasinMethod::Recurrence, BasinMethod::Exhaustive];

    /// `recurrence` or `exhaustive`.
    pub fn label(self) -> &'static str {
        match self {
            BasinMethod::Recurrence => "recurrence",
            BasinMethod::Exhaustive => "exhaustive",
        }
    }

    /// The method with this label.
    pub fn from_label(label: &str) -> Option<Self> {
        label.parse().ok()
    }
}

/// Options of a [`Basins`] map.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct BasinOptions {
    /// Drive periods run at most to find a period. Default 1000.
    pub max_periods: usize,
    /// Longest period looked for, in drive periods (1 to 64). Default 16.
    pub max_period: usize,
    /// Relative tolerance of the repetition of the strobe map. Default 1e-10.
    pub tolerance: f64,
    /// Drive periods over which the exponent of a motion without a period is measured.
    /// Default 1000.
    pub lyapunov_periods: usize,
    /// Standard errors that make an exponent significant. Default 4.
    pub significance: f64,
    /// Relative distance within which two fixed points are one orbit. Default 1e-6.
    pub match_tolerance: f64,
    /// Strobe points kept of a motion without a period, for telling its attractor. Default
    /// 64.
    pub sample_points: usize,
    /// How the attractor of each cell is found. Default [`BasinMethod::Recurrence`].
    pub method: BasinMethod,
    /// Recurrence: cells of the state-space grid across the extent of the map along each
    /// axis (16 to 1e6); at least 4 per spacing of the map's grid are used. Default 1024.
    pub resolution: usize,
    /// Recurrence: drive periods in a row that land on cells the motion visited before,
    /// which declare a new attractor (and, once found, that end the labelling of its
    /// cells). Default 100.
    pub found_revisits: usize,
    /// Recurrence: drive periods in a row landing on cells of one attractor that assign a
    /// cell to it. Default 2.
    pub attractor_hits: usize,
    /// Recurrence: drive periods in a row landing on cells of one attractor's basin that
    /// assign a cell to it. Default 10.
    pub basin_hits: usize,
    /// Recurrence: drive periods run at most from one initial state before it is
    /// undecided. Default 100000.
    pub max_steps: usize,
}

impl Default for BasinOptions {
    fn default() -> Self {
        Self {
            max_periods: 1000,
            max_period: 16,
            tolerance: 1e-10,
            lyapunov_periods: 1000,
            significance: 4.0,
            match_tolerance: 1e-6,
            sample_points: 64,
            method: BasinMethod::Recurrence,
            resolution: 1024,
            found_revisits: 100,
            attractor_hits: 2,
            basin_hits: 10,
            max_steps: 100_000,
        }
    }
}

impl BasinOptions {
    /// These options with the exponent measured over `periods` drive periods, keeping at most
    /// that many sample points ([`BasinOptions::sample_points`] is lowered to fit).
    pub fn with_lyapunov_periods(mut self, periods: usize) -> Self {
        self.lyapunov_periods = periods;
        self.sample_points = self.sample_points.min(periods);
        self
    }

    /// Check every field.
    ///
    /// # Errors
    /// [`Error::InvalidOption`] naming the first bad field of the option table
    /// ([`crate::options`]), [`Error::InvalidParameter`] naming any other.
    pub fn validate(self) -> Result<Self> {
        OptionKey::BasinMaxPeriods.check_count(self.max_periods)?;
        OptionKey::BasinMaxPeriod.check_count(self.max_period)?;
        self.steady_options()?;
        OptionKey::BasinLyapunovPeriods.check_count(self.lyapunov_periods)?;
        if !(self.significance > 0.0 && self.significance.is_finite()) {
            return invalid("significance", self.significance, "must be finite and > 0");
        }
        if !(self.match_tolerance > 0.0 && self.match_tolerance < 1e-2) {
            return invalid(
                "match_tolerance",
                self.match_tolerance,
                "must be > 0 and < 1e-2",
            );
        }
        if !(1..=self.lyapunov_periods).contains(&self.sample_points) {
            return invalid(
                "sample_points",
                self.sample_points as f64,
                "must be from 1 to lyapunov_periods",
            );
        }
        OptionKey::Resolution.check_count(self.resolution)?;
        for (name, value) in [
            ("found_revisits", self.found_revisits),
            ("attractor_hits", self.attractor_hits),
            ("basin_hits", self.basin_hits),
        ] {
            if !(1..=1_000_000).contains(&value) {
                return invalid(name, value as f64, "must be from 1 to 1e6");
            }
        }
        if !(1..=100_000_000).contains(&self.max_steps) {
            return invalid("max_steps", self.max_steps as f64, "must be from 1 to 1e8");
        }
        Ok(self)
    }

    fn steady_options(&self) -> Result<SteadyOptions> {
        SteadyOptions::default()
            .with_spectrum(false)
            .with_tolerance(self.tolerance)?
            .with_max_periods(self.max_periods)?
            .with_max_period(self.max_period)
    }
}

/// What one cell of the grid settled on, before the attractors are identified.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Cell {
    /// The verdict.
    pub kind: AttractorKind,
    /// The period in drive periods (periodic and static cells).
    pub period: Option<usize>,
    /// Periodic: the p strobe points of the orbit, from its fixed point refined by Newton's
    /// method; static: the rest state; otherwise up to [`BasinOptions::sample_points`]
    /// strobe points of the motion.
    pub strobes: Vec<State>,
    /// The largest Lyapunov exponent per unit τ: ln|μ|/(pT) of the orbit for a periodic cell
    /// (−∞ when both multipliers vanish), measured for a motion without a period, 0 at rest.
    pub exponent: f64,
    /// Drive periods simulated for this cell.
    pub periods: usize,
}

impl Cell {
    /// Append the cell to a checkpoint unit (the one encoding of a cell, which the method of
    /// recurrences keeps in its memory and `stickslip basins --checkpoint` in its rows): the
    /// index of its kind in [`AttractorKind::ALL`], its period (0: none), its exponent, the
    /// periods simulated and its strobe points (their count, then y and y' of each).
    pub fn encode(&self, unit: &mut UnitWriter) {
        let kind = AttractorKind::ALL
            .iter()
            .position(|&k| k == self.kind)
            .expect("a kind of ALL");
        unit.u8(kind as u8)
            .u64(self.period.map_or(0, |p| p as u64))
            .f64(self.exponent)
            .u64(self.periods as u64)
            .u64(self.strobes.len() as u64);
        for x in &self.strobes {
            unit.f64(x.y).f64(x.v);
        }
    }

    /// The cell that [`Cell::encode`] wrote at the reader's position; `None` when the bytes
    /// are not one (a damaged checkpoint).
    pub fn decode(r: &mut UnitReader<'_>) -> Option<Cell> {
        let kind = *AttractorKind::ALL.get(r.u8()? as usize)?;
        let period = r.u64()?;
        let exponent = r.f64()?;
        let periods = usize::try_from(r.u64()?).ok()?;
        let n = r.u64()?;
        if n > 1 << 20 {
            return None;
        }
        let mut strobes = Vec::with_capacity(n as usize);
        for _ in 0..n {
            let y = r.f64()?;
            let v = r.f64()?;
            strobes.push(State { y, v });
        }
        Some(Cell {
            kind,
            period: (period > 0).then_some(period as usize),
            strobes,
            exponent,
            periods,
        })
    }
}

/// An attractor of a basin map.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Attractor {
    /// Its number, from 0, in the order of the first cell that reached it.
    pub id: usize,
    /// What it is.
    pub kind: AttractorKind,
    /// Period in drive periods (periodic only).
    pub period: Option<usize>,
    /// Cells that reached it.
    pub cells: usize,
    /// Their fraction of the grid.
    pub fraction: f64,
    /// A representative state at a strobe: the fixed point of a periodic orbit (refined by
    /// Newton's method), the first rest state found, or a strobe point of the motion.
    pub state: State,
    /// Its strobe points: the p points of a periodic orbit, or up to 1024 points of the
    /// strobe set of a chaotic or quasi-periodic attractor; the rest state for rest.
    pub strobes: Vec<State>,
    /// Largest Lyapunov exponent per unit τ (of the orbit, of the first cell's motion, or 0).
    pub exponent: f64,
    /// Floquet multipliers of a periodic orbit.
    pub multipliers: Option<[Multiplier; 2]>,
    /// The smallest and the largest rest position of the cells at rest (static only).
    pub rest_range: Option<(f64, f64)>,
    /// The first cell (row, column) that reached it.
    pub first_cell: (usize, usize),
    /// The attractor that is its mirror image under the symmetry (y, y', τ) → (−y, −y',
    /// τ + T/2) of the equation: its own id when it is symmetric, `None` when its image is
    /// not among the attractors of the map.
    pub mirror: Option<usize>,
}

/// A finished basin map: the grid, the attractor of every cell, and the attractors.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct BasinMap {
    /// The parameters of the model (φ is the drive phase of the initial states).
    pub params: Params,
    /// Initial positions y0 (rows).
    pub y0: Vec<f64>,
    /// Initial velocities y0' (columns).
    pub v0: Vec<f64>,
    /// The attractor of each cell (an index into `attractors`), `None` when undecided;
    /// row-major: `cells[i·n + j]` is (y0_i, v0_j), n = `v0.len()`.
    pub cells: Vec<Option<usize>>,
    /// The attractors, numbered in the order of their first cell.
    pub attractors: Vec<Attractor>,
    /// Cells without an attractor.
    pub undecided: usize,
}

impl BasinMap {
    /// The attractor of the cell (y0_i, v0_j).
    ///
    /// # Panics
    /// When i or j is out of range.
    pub fn at(&self, i: usize, j: usize) -> Option<&Attractor> {
        assert!(
            i < self.y0.len() && j < self.v0.len(),
            "cell out of the grid"
        );
        self.cells[i * self.v0.len() + j].map(|k| &self.attractors[k])
    }
}

/// A basin map of an experiment over a grid of initial states (see the module
/// documentation).
#[derive(Debug, Clone)]
pub struct Basins {
    params: Params,
    /// The model of the experiment's law.
    dynamics: Arc<dyn Dynamics>,
    y0: Vec<f64>,
    v0: Vec<f64>,
    options: BasinOptions,
    threads: Option<usize>,
}

impl Basins {
    /// The map of `experiment` (its parameters, drive phase φ included) over the initial
    /// positions `y0` and velocities `v0`.
    ///
    /// With Shockley diodes every cell is run on the stiff solver, and strobe states repeat,
    /// and fixed points match, within the solver's accuracy
    /// ([`Dynamics::repeat_tolerance`] of [`BasinOptions::tolerance`] and
    /// [`BasinOptions::match_tolerance`]).
    ///
    /// # Errors
    /// A missing drive value; [`Error::InvalidParameter`] for more than
    /// [`crate::limits::MAX_BASIN_STEPS`] values along an axis.
    pub fn new(experiment: &Experiment, y0: &ParameterRange, v0: &ParameterRange) -> Result<Self> {
        for range in [y0, v0] {
            if range.steps() > crate::limits::MAX_BASIN_STEPS {
                return Err(Error::InvalidParameter {
                    name: "steps",
                    value: range.steps() as f64,
                    allowed: "must be from 1 to 2000 along each axis (docs/limits.md)",
                });
            }
        }
        Ok(Self {
            params: experiment.params()?,
            dynamics: Arc::from(experiment.dynamics()?),
            y0: y0.values(),
            v0: v0.values(),
            options: BasinOptions::default(),
            threads: None,
        })
    }

    /// Use these options.
    ///
    /// # Errors
    /// When the options are invalid.
    pub fn options(mut self, options: BasinOptions) -> Result<Self> {
        self.options = options.validate()?;
        Ok(self)
    }

    /// Compute on a pool of `threads` threads of its own instead of rayon's global pool
    /// (the map is the same for any number).
    ///
    /// # Errors
    /// [`crate::Error::InvalidOption`] naming [`crate::options::OptionKey::Threads`] outside
    /// its row's range (1 to 1024).
    pub fn threads(mut self, threads: usize) -> Result<Self> {
        crate::options::OptionKey::Threads.check_count(threads)?;
        self.threads = Some(threads);
        Ok(self)
    }

    /// The parameters of the model.
    pub fn params(&self) -> &Params {
        &self.params
    }

    /// The options used.
    pub fn basin_options(&self) -> &BasinOptions {
        &self.options
    }

    /// The model of the experiment's law.
    pub(crate) fn dynamics(&self) -> &dyn Dynamics {
        self.dynamics.as_ref()
    }

    /// The distance within which two fixed points are one orbit:
    /// [`BasinOptions::match_tolerance`], at least the accuracy of the model's map.
    pub(crate) fn match_tolerance(&self) -> f64 {
        self.dynamics.repeat_tolerance(self.options.match_tolerance)
    }

    /// Rows (initial positions) and columns (initial velocities).
    pub fn shape(&self) -> (usize, usize) {
        (self.y0.len(), self.v0.len())
    }

    /// The cell (y0_i, v0_j), computed alone.
    ///
    /// # Errors
    /// Whatever the solver reports.
    ///
    /// # Panics
    /// When i or j is out of range.
    pub fn cell(&self, i: usize, j: usize) -> Result<Cell> {
        self.cell_from(State::new(self.y0[i], self.v0[j])?)
    }

    /// What the motion from `start` (at τ = 0) settles on, computed alone (the exhaustive
    /// method's verdict).
    fn cell_from(&self, start: State) -> Result<Cell> {
        let options = self.options;
        let steady = if self.dynamics.is_exact() {
            steady_state_from(
                &exact_solver,
                &self.params,
                start,
                &options.steady_options()?,
            )?
        } else {
            let dynamics = self.dynamics.as_ref();
            let factory = |p: Params, s: State| dynamics.solver(&p, s);
            let steady_options = options
                .steady_options()?
                .with_tolerance(dynamics.repeat_tolerance(options.tolerance))?;
            steady_state_from(&factory, &self.params, start, &steady_options)?
        };
        let mut periods = steady.periods_to_settle + steady.recorded_periods;
        if let Some(period) = steady.period {
            let at = steady.strobes[0];
            if steady.events.is_empty() {
                return Ok(Cell {
                    kind: AttractorKind::Static,
                    period: Some(period),
                    strobes: vec![at],
                    exponent: 0.0,
                    periods,
                });
            }
            return self.periodic_cell(at, period, periods);
        }
        let record = record_strobes_of(
            self.dynamics.as_ref(),
            &self.params,
            steady.final_state(),
            &RecordOptions {
                transient_periods: 0,
                points: options.lyapunov_periods,
                max_period: options.max_period,
                tolerance: options.tolerance.max(1e-12),
                significance: options.significance,
            },
        )?;
        periods += options.lyapunov_periods;
        match record.kind {
            AttractorKind::Periodic => {
                let period = record.period.expect("periodic");
                self.periodic_cell(record.final_state(), period, periods)
            }
            kind => Ok(Cell {
                kind,
                period: record.period,
                strobes: record
                    .strobes
                    .iter()
                    .rev()
                    .take(options.sample_points)
                    .rev()
                    .copied()
                    .collect(),
                exponent: record.exponent,
                periods,
            }),
        }
    }

    /// A periodic cell: the orbit refined by Newton's method from the strobe point `at`, with
    /// its p strobe points (the points as simulated when Newton's method fails).
    fn periodic_cell(&self, at: State, period: usize, periods: usize) -> Result<Cell> {
        let drive_period = self.params.drive_period();
        let (start, exponent) = match self.dynamics.find_periodic_orbit(
            &self.params,
            at,
            period,
            &NewtonOptions::default(),
        ) {
            Ok(orbit) => (orbit.state, orbit.exponent()),
            Err(Error::Stability(_)) => (at, f64::NAN),
            Err(e) => return Err(e),
        };
        let mut solver = self.dynamics.solver(&self.params, start)?;
        let mut strobes = vec![start];
        for k in 1..period {
            run_until(solver.as_mut(), k as f64 * drive_period, |_| {})?;
            strobes.push(solver.state());
        }
        Ok(Cell {
            kind: AttractorKind::Periodic,
            period: Some(period),
            strobes,
            exponent,
            periods,
        })
    }

    /// Compute the cells of `rows` (all columns) by the exhaustive method, each on its own,
    /// row-major; `monitor` sees every finished cell (counted within the block) and can stop
    /// the work. The cells do not depend on the number of threads nor on the blocks. (The
    /// recurrence method computes rows in order: [`Basins::recurrence`].)
    ///
    /// # Errors
    /// [`Error::InvalidParameter`] for rows outside the grid; [`Error::Cancelled`]; the first
    /// solver failure.
    pub fn run_rows(&self, rows: Range<usize>, monitor: &dyn Monitor) -> Result<Vec<Cell>> {
        let (nr, nc) = self.shape();
        if rows.start > rows.end || rows.end > nr {
            return Err(Error::InvalidParameter {
                name: "rows",
                value: rows.end as f64,
                allowed: "the rows must lie inside the grid",
            });
        }
        let total = rows.len() * nc;
        crate::scan::run_parallel(total, self.threads, monitor, |k| {
            self.cell(rows.start + k / nc, k % nc)
        })
    }

    /// Compute the whole map; `monitor` sees every finished cell and can stop the work.
    ///
    /// # Errors
    /// [`Error::Cancelled`]; the first solver failure.
    pub fn run(&self, monitor: &dyn Monitor) -> Result<BasinMap> {
        let cells = match self.options.method {
            BasinMethod::Exhaustive => self.run_rows(0..self.y0.len(), monitor)?,
            BasinMethod::Recurrence => {
                let mut recurrence = self.recurrence();
                let mut cells = Vec::with_capacity(self.y0.len() * self.v0.len());
                while recurrence.next_row() < self.y0.len() {
                    cells.extend(recurrence.run_row(cells.len(), monitor)?.cells);
                }
                cells
            }
        };
        self.identify(&cells)
    }

    /// A map by recurrence from its first row (whatever [`BasinOptions::method`] says): the
    /// rows are computed in order, each from the labels the rows before it left.
    pub fn recurrence(&self) -> Recurrence<'_> {
        Recurrence::new(self)
    }

    /// Identify and number the attractors of `cells` (all cells of the grid, row-major, as
    /// [`Basins::run_rows`] gives them), in the order of the cells.
    ///
    /// # Errors
    /// [`Error::InvalidParameter`] when the number of cells is not that of the grid.
    pub fn identify(&self, cells: &[Cell]) -> Result<BasinMap> {
        let (nr, nc) = self.shape();
        if cells.len() != nr * nc {
            return Err(Error::InvalidParameter {
                name: "cells",
                value: cells.len() as f64,
                allowed: "must be one per cell of the grid",
            });
        }
        let mut attractors: Vec<Attractor> = Vec::new();
        let mut assigned = Vec::with_capacity(cells.len());
        let tolerance = self.match_tolerance();
        for (k, cell) in cells.iter().enumerate() {
            let found = match cell.kind {
                AttractorKind::Undecided => {
                    assigned.push(None);
                    continue;
                }
                AttractorKind::Static => attractors
                    .iter()
                    .position(|a| a.kind == AttractorKind::Static),
                AttractorKind::Periodic => {
                    let x = cell.strobes[0];
                    let limit = tolerance * scale_of(&[x]);
                    attractors.iter().position(|a| {
                        a.kind == AttractorKind::Periodic
                            && a.period == cell.period
                            && a.strobes.iter().any(|s| distance(*s, x) <= limit)
                    })
                }
                kind => attractors
                    .iter()
                    .position(|a| a.kind == kind && overlaps(&a.strobes, &cell.strobes)),
            };
            let index = match found {
                Some(index) => index,
                None => {
                    attractors.push(Attractor {
                        id: attractors.len(),
                        kind: cell.kind,
                        period: (cell.kind == AttractorKind::Periodic)
                            .then_some(cell.period)
                            .flatten(),
                        cells: 0,
                        fraction: 0.0,
                        state: cell.strobes[0],
                        strobes: Vec::new(),
                        exponent: cell.exponent,
                        multipliers: None,
                        rest_range: None,
                        first_cell: (k / nc, k % nc),
                        mirror: None,
                    });
                    attractors.len() - 1
                }
            };
            let a = &mut attractors[index];
            a.cells += 1;
            match cell.kind {
                AttractorKind::Periodic => {
                    if a.strobes.is_empty() {
                        a.strobes = cell.strobes.clone();
                    }
                }
                AttractorKind::Static => {
                    let y = cell.strobes[0].y;
                    a.rest_range = Some(match a.rest_range {
                        Some((lo, hi)) => (lo.min(y), hi.max(y)),
                        None => (y, y),
                    });
                    if a.strobes.is_empty() {
                        a.strobes = cell.strobes.clone();
                    }
                }
                _ => {
                    let room = 1024usize.saturating_sub(a.strobes.len());
                    a.strobes.extend(cell.strobes.iter().take(room));
                }
            }
            assigned.push(Some(index));
        }
        let total = cells.len() as f64;
        for a in &mut attractors {
            a.fraction = a.cells as f64 / total;
            if a.kind == AttractorKind::Periodic {
                let period = a.period.expect("periodic");
                a.multipliers = self
                    .dynamics
                    .find_periodic_orbit(&self.params, a.state, period, &NewtonOptions::default())
                    .ok()
                    .map(|o| o.multipliers);
            }
        }
        self.pair_mirrors(&mut attractors)?;
        let undecided = assigned.iter().filter(|a| a.is_none()).count();
        Ok(BasinMap {
            params: self.params,
            y0: self.y0.clone(),
            v0: self.v0.clone(),
            cells: assigned,
            attractors,
            undecided,
        })
    }
}

impl Basins {
    /// Set [`Attractor::mirror`]: the image of an attractor under (y, y', τ) → (−y, −y',
    /// τ + T/2) is an attractor of the same kind and period, whose strobe points are those
    /// of the first run on half a drive period and negated. Orbits are matched by their
    /// fixed point (within [`BasinOptions::match_tolerance`]), chaotic and quasi-periodic
    /// attractors by their strobe sets overlapping both ways, rest (|y| ≤ μs − β, a
    /// symmetric set) is its own image.
    fn pair_mirrors(&self, attractors: &mut [Attractor]) -> Result<()> {
        let half = 0.5 * self.params.drive_period();
        let tolerance = self.match_tolerance();
        let mut mirrors = Vec::with_capacity(attractors.len());
        for a in attractors.iter() {
            if a.kind == AttractorKind::Static {
                mirrors.push(Some(a.id));
                continue;
            }
            let mut images = Vec::with_capacity(a.strobes.len());
            for &s in &a.strobes {
                let mut solver = self.dynamics.solver(&self.params, s)?;
                run_until(solver.as_mut(), half, |_| {})?;
                let x = solver.state();
                images.push(State { y: -x.y, v: -x.v });
            }
            let found = attractors.iter().find(|b| {
                b.kind == a.kind
                    && b.period == a.period
                    && match a.kind {
                        AttractorKind::Periodic => {
                            let x = images[0];
                            let limit = tolerance * scale_of(&[x]);
                            b.strobes.iter().any(|s| distance(*s, x) <= limit)
                        }
                        _ => overlaps(&b.strobes, &images) && overlaps(&images, &b.strobes),
                    }
            });
            mirrors.push(found.map(|b| b.id));
        }
        for (a, m) in attractors.iter_mut().zip(mirrors) {
            a.mirror = m;
        }
        Ok(())
    }
}

/// What a basin map reports: exactly what `stickslip basins --json` prints and what the
/// Python package's `basins` returns as its summary. Build it with `BasinReport::from(&map)`.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct BasinReport {
    /// The model's parameters (φ: the drive phase at which the initial states are given).
    pub model: BasinModel,
    /// The grid of initial states.
    pub grid: BasinGrid,
    /// The attractors, numbered in the order of their first cell.
    pub attractors: Vec<AttractorReport>,
    /// Cells without an attractor.
    pub undecided: usize,
    /// Their fraction of the grid.
    pub undecided_fraction: f64,
}

/// The model's parameters in a [`BasinReport`] (dimensionless; φ in radians).
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct BasinModel {
    /// Damping ratio ζ.
    pub zeta: f64,
    /// Drive frequency w = Ω/ω0.
    pub w: f64,
    /// Drive amplitude β.
    pub beta: f64,
    /// Drive phase φ of the initial states (radians).
    pub phi: f64,
    /// Static-to-kinetic friction ratio μs.
    pub mu_s: f64,
}

/// The grid of a [`BasinReport`]: the ends of both axes and the number of values of each.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct BasinGrid {
    /// Smallest initial position.
    pub y0_min: f64,
    /// Largest initial position.
    pub y0_max: f64,
    /// Smallest initial velocity.
    pub v0_min: f64,
    /// Largest initial velocity.
    pub v0_max: f64,
    /// Initial positions (rows).
    pub steps: usize,
    /// Initial velocities (columns).
    pub v0_steps: usize,
}

/// One attractor in a [`BasinReport`]: [`Attractor`] with plain numbers.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct AttractorReport {
    /// Its number, from 0.
    pub id: usize,
    /// What it is: `periodic`, `static`, `chaotic` or `quasiperiodic` (JSON `class`, as the
    /// CSV's column).
    pub class: AttractorKind,
    /// Period in drive periods (periodic and static), else `None`.
    pub period: Option<usize>,
    /// Its fraction of the grid.
    pub fraction: f64,
    /// Cells that reached it.
    pub cells: usize,
    /// A representative state at the strobe (the fixed point of a periodic orbit).
    pub state: State,
    /// Its strobe points, at most [`AttractorReport::MAX_STROBES`].
    pub strobes: Vec<State>,
    /// Largest Lyapunov exponent λ1 per unit τ; `None` where it is not finite (−∞ when both
    /// multipliers of an orbit vanish).
    pub lambda1: Option<f64>,
    /// Floquet multipliers of a periodic orbit as [re, im] pairs, the larger first.
    pub multipliers: Option<[[f64; 2]; 2]>,
    /// [min, max] of the rest positions (static only).
    pub rest_range: Option<[f64; 2]>,
    /// The first cell [row, column] that reached it.
    pub first_cell: [usize; 2],
    /// The id of its mirror image under (y, y', τ) → (−y, −y', τ + T/2): its own id when
    /// symmetric, `None` when the image is not an attractor of the map.
    pub mirror: Option<usize>,
}

impl AttractorReport {
    /// The most strobe points a report lists per attractor.
    pub const MAX_STROBES: usize = 64;
}

impl From<&Attractor> for AttractorReport {
    fn from(a: &Attractor) -> Self {
        Self {
            id: a.id,
            class: a.kind,
            period: a.period,
            fraction: a.fraction,
            cells: a.cells,
            state: a.state,
            strobes: a.strobes.iter().take(Self::MAX_STROBES).copied().collect(),
            lambda1: Some(a.exponent).filter(|x| x.is_finite()),
            multipliers: a
                .multipliers
                .map(|m| [[m[0].re, m[0].im], [m[1].re, m[1].im]]),
            rest_range: a.rest_range.map(|(lo, hi)| [lo, hi]),
            first_cell: [a.first_cell.0, a.first_cell.1],
            mirror: a.mirror,
        }
    }
}

impl From<&BasinMap> for BasinReport {
    fn from(map: &BasinMap) -> Self {
        let end = |v: &[f64], last: bool| {
            (if last { v.last() } else { v.first() })
                .copied()
                .unwrap_or(f64::NAN)
        };
        Self {
            model: BasinModel {
                zeta: map.params.zeta,
                w: map.params.w,
                beta: map.params.beta,
                phi: map.params.phi,
                mu_s: map.params.mu_s,
            },
            grid: BasinGrid {
                y0_min: end(&map.y0, false),
                y0_max: end(&map.y0, true),
                v0_min: end(&map.v0, false),
                v0_max: end(&map.v0, true),
                steps: map.y0.len(),
                v0_steps: map.v0.len(),
            },
            attractors: map.attractors.iter().map(AttractorReport::from).collect(),
            undecided: map.undecided,
            undecided_fraction: map.undecided as f64 / map.cells.len().max(1) as f64,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_cell_reads_back_as_it_was_written() {
        let cells = [
            Cell {
                kind: AttractorKind::Periodic,
                period: Some(3),
                strobes: vec![State { y: 1.5, v: -0.25 }, State { y: -2.0, v: 1e-300 }],
                exponent: f64::NEG_INFINITY,
                periods: 417,
            },
            Cell {
                kind: AttractorKind::Undecided,
                period: None,
                strobes: vec![],
                exponent: -3.5e-4,
                periods: 100_000,
            },
        ];
        let mut unit = UnitWriter::new();
        for c in &cells {
            c.encode(&mut unit);
        }
        let bytes = unit.finish();
        // The layout of the checkpoints written before the encoding moved here, field by
        // field (kind as its index in ALL: periodic 0, undecided 4), so that they still read.
        let mut old = UnitWriter::new();
        old.u8(0).u64(3).f64(f64::NEG_INFINITY).u64(417).u64(2);
        old.f64(1.5).f64(-0.25).f64(-2.0).f64(1e-300);
        old.u8(4).u64(0).f64(-3.5e-4).u64(100_000).u64(0);
        assert_eq!(old.finish(), bytes);
        let mut r = UnitReader::new(&bytes);
        for c in &cells {
            assert_eq!(Cell::decode(&mut r).as_ref(), Some(c));
        }
        assert!(r.is_empty());
        // A damaged unit is refused, not misread.
        let mut short = UnitReader::new(&bytes[..bytes.len() - 3]);
        assert!(Cell::decode(&mut short).is_some());
        assert!(Cell::decode(&mut short).is_none());
    }

    #[test]
    fn strobe_sets_overlap_when_they_share_their_region() {
        let circle = |n: usize, r: f64, shift: f64| -> Vec<State> {
            (0..n)
                .map(|k| {
                    let a = k as f64 * 2.399;
                    State {
                        y: r * a.cos() + shift,
                        v: r * a.sin(),
                    }
                })
                .collect()
        };
        let reference = circle(200, 1.0, 0.0);
        assert!(overlaps(&reference, &circle(30, 1.0, 0.0)));
        assert!(!overlaps(&reference, &circle(30, 1.0, 5.0)));
        assert!(!overlaps(&[], &circle(3, 1.0, 0.0)));
    }
}
