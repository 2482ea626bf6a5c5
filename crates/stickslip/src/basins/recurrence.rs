//! Basins by recurrence, after `AttractorsViaRecurrences` of Attractors.jl (Datseris &
//! Wagemakers, "Effortless estimation of basins of attraction", Chaos 32, 023104, 2022),
//! adapted to the exact strobe map of the oscillator.
//!
//! A grid of cells covers the strobe map's state space (y, y'): [`BasinOptions::resolution`]
//! cells across the extent of the map along each axis (and at least 4 per spacing of the
//! map's grid), unbounded (cells are kept in a hash map, so the grid grows wherever a
//! trajectory goes). Each cell carries a label:
//! unvisited, visited by the trajectory in progress, part of attractor k, or in the basin of
//! attractor k. The initial conditions are taken in a fixed order (rows of y0, then y0'), and
//! each one iterates the strobe map P from its initial state:
//!
//! - landing [`BasinOptions::attractor_hits`] times in a row on cells of attractor k, or
//!   [`BasinOptions::basin_hits`] times in a row on cells of the basin of k, it takes k, and
//!   the cells it visited become basin of k;
//! - landing [`BasinOptions::found_revisits`] times in a row on cells it visited itself, it
//!   has found a new attractor: the motion from there is classified once, exactly as the
//!   exhaustive method classifies a cell (steady state with Newton's method on a period,
//!   rest, or the exponent), then the attractor's cells are labelled by running on until
//!   [`BasinOptions::found_revisits`] steps in a row land on cells already labelled;
//! - a motion at rest (stuck through a whole drive period on a base at rest, vb = 0) is
//!   rest, at its own position, without further work;
//! - after [`BasinOptions::max_steps`] drive periods without a verdict it is undecided.
//!
//! Every initial condition sees the labels that the ones before it left, in the same order
//! for any number of threads, so the map is the same for any number of threads. What one row
//! adds to the labels is its *memory*; [`Recurrence::replay`] restores it, so that a map
//! resumed from saved rows equals the uninterrupted one.

use super::{BasinOptions, Basins, Cell};
use crate::attractor::{distance, scale_of, AttractorKind};
use crate::checkpoint::{UnitReader, UnitWriter};
use crate::error::{Error, Result};
use crate::params::State;
use crate::scan::Monitor;
use crate::solver::Phase;
use std::collections::HashMap;
use std::ops::ControlFlow;

fn attractor_label(k: usize) -> u32 {
    2 + 2 * k as u32
}

fn basin_label(k: usize) -> u32 {
    3 + 2 * k as u32
}

/// The attractor of a label (of an attractor or of its basin).
fn label_attractor(label: u32) -> usize {
    (label as usize - 2) / 2
}

/// The state of a map by recurrence: the labelled cells and the attractors found so far.
/// Build it with [`Basins::recurrence`]; compute rows in order with [`Recurrence::run_row`]
/// or restore saved ones with [`Recurrence::replay`].
#[derive(Debug, Clone)]
pub struct Recurrence<'a> {
    basins: &'a Basins,
    /// Cell size along y and y'.
    size: (f64, f64),
    labels: HashMap<(i64, i64), u32>,
    /// The classification of each attractor found, by its number in the labels.
    found: Vec<Cell>,
    next_row: usize,
    /// Labels set in the row in progress, in order (the row's memory).
    log: Vec<((i64, i64), u32)>,
}

/// One row of a map by recurrence: its cells, and what it added to the labels (the bytes
/// [`Recurrence::replay`] takes back).
#[derive(Debug, Clone, PartialEq)]
pub struct RecurrenceRow {
    /// The cells of the row, as [`Basins::run_rows`] would give them.
    pub cells: Vec<Cell>,
    /// The attractors found and the cells labelled by the row, encoded.
    pub memory: Vec<u8>,
}

/// Where an initial condition ended.
enum Outcome {
    Label(usize),
    Rest(State),
    Unsettled,
}

impl<'a> Recurrence<'a> {
    pub(super) fn new(basins: &'a Basins) -> Self {
        let resolution = basins.options.resolution;
        let size = |v: &[f64]| {
            let span = v.last().copied().unwrap_or(0.0) - v.first().copied().unwrap_or(0.0);
            let cells = resolution.max(4 * v.len().saturating_sub(1)) as f64;
            if v.len() > 1 && span > 0.0 {
                span / cells
            } else {
                // One value along the axis: the extent of the other axis or 1.
                f64::NAN
            }
        };
        let (sy, sv) = (size(&basins.y0), size(&basins.v0));
        let fallback = if sy.is_finite() {
            sy
        } else if sv.is_finite() {
            sv
        } else {
            1.0 / resolution as f64
        };
        Self {
            basins,
            size: (
                if sy.is_finite() { sy } else { fallback },
                if sv.is_finite() { sv } else { fallback },
            ),
            labels: HashMap::new(),
            found: Vec::new(),
            next_row: 0,
            log: Vec::new(),
        }
    }

    /// The row that [`Recurrence::run_row`] computes next.
    pub fn next_row(&self) -> usize {
        self.next_row
    }

    /// Attractors found so far (each counted once, before the final identification).
    pub fn found(&self) -> usize {
        self.found.len()
    }

    fn key(&self, x: State) -> Option<(i64, i64)> {
        let i = (x.y / self.size.0).floor();
        let j = (x.v / self.size.1).floor();
        // Beyond 2^52 cells a position no longer has a cell of its own: the motion escaped.
        let limit = 4.5e15;
        (i.abs() < limit && j.abs() < limit).then_some((i as i64, j as i64))
    }

    fn set(&mut self, key: (i64, i64), label: u32) {
        self.labels.insert(key, label);
        self.log.push((key, label));
    }

    /// Compute the next row (all columns); `monitor` sees each finished cell, counted from
    /// `done_before`, of the whole grid.
    ///
    /// # Errors
    /// [`Error::InvalidParameter`] when every row is done; [`Error::Cancelled`]; the first
    /// solver failure.
    pub fn run_row(&mut self, done_before: usize, monitor: &dyn Monitor) -> Result<RecurrenceRow> {
        let (rows, columns) = self.basins.shape();
        let row = self.next_row;
        if row >= rows {
            return Err(Error::InvalidParameter {
                name: "rows",
                value: row as f64,
                allowed: "every row of the grid is done",
            });
        }
        let found_before = self.found.len();
        self.log.clear();
        let mut cells = Vec::with_capacity(columns);
        for j in 0..columns {
            let start = State::new(self.basins.y0[row], self.basins.v0[j])?;
            cells.push(self.settle(start)?);
            let done = done_before + j + 1;
            if monitor.step(done, rows * columns) == ControlFlow::Break(()) {
                return Err(Error::Cancelled {
                    done,
                    total: rows * columns,
                });
            }
        }
        self.next_row += 1;
        let mut unit = UnitWriter::new();
        unit.u64((self.found.len() - found_before) as u64);
        for cell in &self.found[found_before..] {
            cell.encode(&mut unit);
        }
        unit.u64(self.log.len() as u64);
        for &((i, j), label) in &self.log {
            unit.u64(i as u64).u64(j as u64).u64(u64::from(label));
        }
        Ok(RecurrenceRow {
            cells,
            memory: unit.finish(),
        })
    }

    /// Restore the next row from its saved memory instead of computing it.
    ///
    /// # Errors
    /// [`Error::InvalidParameter`] when the memory is malformed or every row is done.
    pub fn replay(&mut self, memory: &[u8]) -> Result<()> {
        let bad = || Error::InvalidParameter {
            name: "memory",
            value: memory.len() as f64,
            allowed: "must be the memory of a row of this map",
        };
        if self.next_row >= self.basins.shape().0 {
            return Err(bad());
        }
        let mut r = UnitReader::new(memory);
        let n = r.u64().ok_or_else(bad)?;
        if n > 1 << 20 {
            return Err(bad());
        }
        for _ in 0..n {
            let cell = Cell::decode(&mut r).ok_or_else(bad)?;
            self.found.push(cell);
        }
        let n = r.u64().ok_or_else(bad)?;
        for _ in 0..n {
            let i = r.u64().ok_or_else(bad)? as i64;
            let j = r.u64().ok_or_else(bad)? as i64;
            let label = u32::try_from(r.u64().ok_or_else(bad)?).map_err(|_| bad())?;
            if label < 2 || label_attractor(label) >= self.found.len() {
                return Err(bad());
            }
            self.labels.insert((i, j), label);
        }
        if !r.is_empty() {
            return Err(bad());
        }
        self.next_row += 1;
        Ok(())
    }

    /// The cell of the initial state `start`.
    fn settle(&mut self, start: State) -> Result<Cell> {
        let mut visited = Vec::new();
        let (outcome, periods) = self.follow(start, &mut visited)?;
        if let Outcome::Label(k) = outcome {
            for key in visited {
                if !self.labels.contains_key(&key) {
                    self.set(key, basin_label(k));
                }
            }
        }
        Ok(match outcome {
            Outcome::Label(k) => Cell {
                periods,
                ..self.found[k].clone()
            },
            Outcome::Rest(at) => Cell {
                kind: AttractorKind::Static,
                period: Some(1),
                strobes: vec![at],
                exponent: 0.0,
                periods,
            },
            Outcome::Unsettled => Cell {
                kind: AttractorKind::Undecided,
                period: None,
                strobes: Vec::new(),
                exponent: f64::NAN,
                periods,
            },
        })
    }

    /// Landings in a row on cells of the attractor or basin `label` that assign a motion to
    /// it: for a periodic orbit of period p at least 2p + 1, so that a motion on another
    /// orbit whose points share some of the orbit's cells is not taken for it.
    fn hits_needed(&self, label: u32) -> usize {
        let options = &self.basins.options;
        if label % 2 == 1 {
            return options.basin_hits;
        }
        let found = &self.found[label_attractor(label)];
        match (found.kind, found.period) {
            (AttractorKind::Periodic, Some(p)) => options.attractor_hits.max(2 * p + 1),
            _ => options.attractor_hits,
        }
    }

    /// Iterate the strobe map from `start` until a verdict (see the module documentation);
    /// the unlabelled cells it visits go to `visited`. Returns the verdict and the drive
    /// periods simulated.
    fn follow(&mut self, start: State, visited: &mut Vec<(i64, i64)>) -> Result<(Outcome, usize)> {
        let options: BasinOptions = self.basins.options;
        let period = self.basins.params.drive_period();
        let mut solver = self.basins.dynamics().solver(&self.basins.params, start)?;
        let mut own = std::collections::HashSet::new();
        let mut x = start;
        let mut steps = 0usize;
        let mut revisits = 0usize;
        // (label, landings in a row) of the attractor or basin cells landed on last.
        let mut hits: (u32, usize) = (0, 0);
        loop {
            let Some(key) = self.key(x) else {
                return Ok((Outcome::Unsettled, steps));
            };
            // Revisits count the motion's own cells, whatever their label: a motion that
            // cycles through cells of several basins still finds its attractor.
            if own.insert(key) {
                revisits = 0;
            } else {
                revisits += 1;
            }
            match self.labels.get(&key).copied() {
                None => {
                    if revisits == 0 {
                        visited.push(key);
                    }
                    hits = (0, 0);
                }
                Some(label) => {
                    hits = if hits.0 == label {
                        (label, hits.1 + 1)
                    } else {
                        (label, 1)
                    };
                    if hits.1 >= self.hits_needed(label) {
                        return Ok((Outcome::Label(label_attractor(label)), steps));
                    }
                }
            }
            if revisits >= options.found_revisits {
                let k = self.found_attractor(x)?;
                return Ok((Outcome::Label(k), steps));
            }
            if steps >= options.max_steps {
                return Ok((Outcome::Unsettled, steps));
            }
            let mut events = 0usize;
            steps += 1;
            crate::solver::run_until(solver.as_mut(), steps as f64 * period, |_| events += 1)?;
            x = solver.state();
            // Stuck through a whole drive period with the same drive to come: stuck for
            // ever, on a base at rest (on a moving belt the spring stretches while the
            // block rides along, so the stop ends).
            if events == 0 && solver.phase() == Phase::Stick && self.basins.params.vb == 0.0 {
                return Ok((Outcome::Rest(x), steps));
            }
        }
    }

    /// The attractor found earlier that is the periodic orbit or rest of `cell`.
    fn known(&self, cell: &Cell) -> Option<usize> {
        let tolerance = self.basins.match_tolerance();
        self.found.iter().position(|f| {
            f.kind == cell.kind
                && match cell.kind {
                    AttractorKind::Periodic => {
                        let x = cell.strobes[0];
                        let limit = tolerance * scale_of(&[x]);
                        f.period == cell.period
                            && f.strobes.iter().any(|s| distance(*s, x) <= limit)
                    }
                    _ => false,
                }
        })
    }

    /// A new attractor reached at `x`: classify it once (or recognise an orbit found
    /// before) and label its cells.
    fn found_attractor(&mut self, x: State) -> Result<usize> {
        let cell = self.basins.cell_from(x)?;
        let start = match cell.kind {
            AttractorKind::Periodic | AttractorKind::Static => cell.strobes[0],
            _ => x,
        };
        let k = match self.known(&cell) {
            Some(k) => k,
            None => {
                self.found.push(cell);
                self.found.len() - 1
            }
        };
        let label = attractor_label(k);
        let options = self.basins.options;
        let period = self.basins.params.drive_period();
        // Label the attractor's cells (over basin labels, not over other attractors): run on
        // it until found_revisits steps in a row land on cells already labelled (at most
        // max_steps).
        let mut solver = self.basins.dynamics().solver(&self.basins.params, start)?;
        let mut x = start;
        let mut in_a_row = 0usize;
        let mut steps = 0usize;
        while in_a_row < options.found_revisits && steps < options.max_steps {
            let Some(key) = self.key(x) else { break };
            match self.labels.get(&key).copied() {
                Some(l) if l % 2 == 0 => in_a_row += 1,
                _ => {
                    self.set(key, label);
                    in_a_row = 0;
                }
            }
            steps += 1;
            crate::solver::run_until(solver.as_mut(), steps as f64 * period, |_| {})?;
            x = solver.state();
        }
        Ok(k)
    }
}
