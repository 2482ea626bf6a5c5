//! One run of an experiment from its initial state, streamed: the samples and events that
//! `stickslip simulate` writes, the lab's simulation shows and the Python package's
//! `simulate` returns.

use super::{event_kind, push_cells, Table};
use crate::error::{Error, Result};
use crate::experiment::{Experiment, PhysicalUnits};
use crate::scan::Monitor;
use crate::solver::{Cursor, Event, Phase, Record, Solver};
use serde::ser::SerializeMap;
use serde::{Serialize, Serializer};
use std::ops::ControlFlow;

/// The columns of a trajectory: `tau,y,v,drive,phase`, and with a physical description the
/// same sample in physical units, `t_s,uc_V,i_A,u_V` (circuit) or `t_s,r_m,rdot_m_s,F_N`
/// (mechanical oscillator).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TrajectoryColumns {
    /// The physical units of the last four columns, if any.
    pub units: Option<PhysicalUnits>,
}

impl TrajectoryColumns {
    /// The dimensionless columns, always present.
    pub const DIMENSIONLESS: [&'static str; 5] = ["tau", "y", "v", "drive", "phase"];

    /// The column names, in order.
    pub fn names(&self) -> Vec<&'static str> {
        let mut names = Self::DIMENSIONLESS.to_vec();
        if let Some(u) = &self.units {
            names.extend(u.columns());
        }
        names
    }

    /// The header line, without its newline.
    pub fn header(&self) -> String {
        self.names().join(",")
    }
}

/// One sample of a trajectory: the dimensionless state, the drive, the phase, and with a
/// physical description the same in physical units.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TrajectorySample {
    /// Dimensionless time τ = ω0·t.
    pub tau: f64,
    /// Position y.
    pub y: f64,
    /// Velocity y'.
    pub v: f64,
    /// The drive β cos(wτ + φ) (units of y), as the solver applies it.
    pub drive: f64,
    /// Phase of the motion.
    pub phase: Phase,
    /// Time (s), position (V or m), velocity (A or m/s), drive (V or N).
    pub physical: Option<[f64; 4]>,
}

impl TrajectorySample {
    /// Append the sample as a CSV line (the columns of [`TrajectoryColumns`]), with its
    /// newline, to `out`.
    pub fn write_row(&self, out: &mut String) {
        push_cells(out, &[self.tau, self.y, self.v, self.drive]);
        out.push(',');
        out.push_str(self.phase.label());
        if let Some(p) = &self.physical {
            out.push(',');
            push_cells(out, p);
        }
        out.push('\n');
    }

    /// The sample's cells, one per column of [`TrajectoryColumns`].
    pub fn row(&self) -> Vec<String> {
        let mut row = vec![
            self.tau.to_string(),
            self.y.to_string(),
            self.v.to_string(),
            self.drive.to_string(),
            self.phase.label().to_string(),
        ];
        if let Some(p) = &self.physical {
            row.extend(p.iter().map(f64::to_string));
        }
        row
    }
}

/// An event of a trajectory as the event log writes it: `tau,y,kind`.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct EventRow {
    /// Dimensionless time τ of the event.
    pub tau: f64,
    /// Position y at the event.
    pub y: f64,
    /// `turn`, `stick` or `slip`.
    #[serde(serialize_with = "event_kind")]
    pub kind: crate::EventKind,
}

impl EventRow {
    /// The columns of the event log.
    pub const COLUMNS: [&'static str; 3] = ["tau", "y", "kind"];

    /// Append the event as a CSV line, with its newline, to `out`.
    pub fn write_row(&self, out: &mut String) {
        push_cells(out, &[self.tau, self.y]);
        out.push(',');
        out.push_str(self.kind.label());
        out.push('\n');
    }
}

impl From<Event> for EventRow {
    fn from(e: Event) -> Self {
        Self {
            tau: e.tau,
            y: e.y,
            kind: e.kind,
        }
    }
}

/// One item of a [`TrajectoryRun`]: a sample or an event, in time order.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum TrajectoryRecord {
    /// A sample at one of the grid's times.
    Sample(TrajectorySample),
    /// An event, handed out before the samples that follow it.
    Event(EventRow),
}

/// A run of an experiment from its initial state, computed as it is asked for: an iterator of
/// samples and events whose memory stays flat however long the run (build it with
/// [`Experiment::trajectory`]). Collect it into a [`TrajectoryReport`] with
/// [`TrajectoryRun::collect_report`].
///
/// Samples are taken at τ_k = k·(periods·T)/n for k = 0 … n, T = 2π/w the drive period and
/// n = ⌈periods × samples_per_period⌉: bit for bit the samples of
/// [`crate::solver::sample_at`] on [`crate::solver::grid`]`(0, periods·T, n)`. A monitor
/// ([`TrajectoryRun::monitor`]) is told after every `samples_per_period` samples and after
/// the last (done and total, the total being ⌈(n + 1)/samples_per_period⌉) and can stop the
/// run: the run then hands out [`Error::Cancelled`] and ends. After an error the run ends.
pub struct TrajectoryRun<'m> {
    solver: Box<dyn Solver>,
    cursor: Cursor,
    columns: TrajectoryColumns,
    periods: f64,
    samples_per_period: usize,
    samples: usize,
    monitor: Option<&'m dyn Monitor>,
    ended: bool,
}

impl std::fmt::Debug for TrajectoryRun<'_> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("TrajectoryRun")
            .field("periods", &self.periods)
            .field("samples_per_period", &self.samples_per_period)
            .field("samples", &self.samples)
            .field("done", &self.cursor.samples_done())
            .finish()
    }
}

impl Experiment {
    /// Stream a run from the initial state for `periods` drive periods, sampled
    /// `samples_per_period` times per drive period (see [`TrajectoryRun`]).
    ///
    /// ```
    /// use stickslip::experiment::Experiment;
    /// use stickslip::report::{Table, TrajectoryRecord};
    /// let e = Experiment::dimensionless(0.05, 0.7, 1.2).unwrap();
    /// let run = e.trajectory(3.0, 100).unwrap();
    /// assert_eq!(run.samples(), 301);
    /// let report = run.collect_report().unwrap();
    /// assert_eq!(report.header(), "tau,y,v,drive,phase");
    /// assert_eq!(report.len(), 301);
    /// ```
    ///
    /// # Errors
    /// [`Error::InvalidParameter`] when `periods` is not finite and > 0, `samples_per_period`
    /// is 0, or the run would hold more than [`crate::experiment::Trajectory::MAX_SAMPLES`]
    /// samples; a missing drive ([`Experiment::params`]); [`Error::HorizonTooLong`] for a
    /// run longer than the solvers resolve ([`crate::limits::check_horizon`]).
    pub fn trajectory(
        &self,
        periods: f64,
        samples_per_period: usize,
    ) -> Result<TrajectoryRun<'static>> {
        if !(periods.is_finite() && periods > 0.0) {
            return Err(Error::InvalidParameter {
                name: "periods",
                value: periods,
                allowed: "must be finite and > 0",
            });
        }
        if samples_per_period == 0 {
            return Err(Error::InvalidParameter {
                name: "samples_per_period",
                value: 0.0,
                allowed: "must be at least 1",
            });
        }
        let count = (periods * samples_per_period as f64).ceil();
        if count > crate::experiment::Trajectory::MAX_SAMPLES {
            return Err(Error::InvalidParameter {
                name: "samples",
                value: count,
                allowed: "periods × samples_per_period must be at most 5e7",
            });
        }
        let params = self.params()?;
        crate::limits::check_horizon(&params, periods)?;
        let solver = self.solver()?;
        let cursor = Cursor::new(
            solver.as_ref(),
            0.0,
            periods * params.drive_period(),
            count as usize,
        )?;
        Ok(TrajectoryRun {
            solver,
            cursor,
            columns: TrajectoryColumns {
                units: self.units(),
            },
            periods,
            samples_per_period,
            samples: count as usize + 1,
            monitor: None,
            ended: false,
        })
    }
}

impl<'m> TrajectoryRun<'m> {
    /// Watch the run with `monitor` (progress in blocks of `samples_per_period` samples;
    /// stopping it ends the run with [`Error::Cancelled`]).
    pub fn monitor<'n>(self, monitor: &'n dyn Monitor) -> TrajectoryRun<'n> {
        TrajectoryRun {
            solver: self.solver,
            cursor: self.cursor,
            columns: self.columns,
            periods: self.periods,
            samples_per_period: self.samples_per_period,
            samples: self.samples,
            monitor: Some(monitor),
            ended: self.ended,
        }
    }

    /// The columns of the samples.
    pub fn columns(&self) -> TrajectoryColumns {
        self.columns
    }

    /// Number of samples the run hands out in all, n + 1.
    pub fn samples(&self) -> usize {
        self.samples
    }

    /// Drive periods of the run.
    pub fn periods(&self) -> f64 {
        self.periods
    }

    /// Samples per drive period.
    pub fn samples_per_period(&self) -> usize {
        self.samples_per_period
    }

    /// The solver (its time is that of the last record handed out).
    pub fn solver(&self) -> &dyn Solver {
        self.solver.as_ref()
    }

    /// Run to the end and keep every sample and event.
    ///
    /// # Errors
    /// [`Error::Cancelled`] when the monitor stops the run; whatever the solver reports.
    pub fn collect_report(self) -> Result<TrajectoryReport> {
        let mut report = TrajectoryReport {
            periods: self.periods,
            samples_per_period: self.samples_per_period,
            columns: self.columns,
            tau: Vec::with_capacity(self.samples),
            y: Vec::with_capacity(self.samples),
            v: Vec::with_capacity(self.samples),
            drive: Vec::with_capacity(self.samples),
            phase: Vec::with_capacity(self.samples),
            physical: self
                .columns
                .units
                .map(|_| std::array::from_fn(|_| Vec::with_capacity(self.samples))),
            events: Vec::new(),
        };
        for record in self {
            match record? {
                TrajectoryRecord::Sample(s) => report.push(&s),
                TrajectoryRecord::Event(e) => report.events.push(e),
            }
        }
        Ok(report)
    }
}

impl Iterator for TrajectoryRun<'_> {
    type Item = Result<TrajectoryRecord>;

    fn next(&mut self) -> Option<Result<TrajectoryRecord>> {
        if self.ended {
            return None;
        }
        let record = match self.cursor.next(self.solver.as_mut()) {
            None => {
                self.ended = true;
                return None;
            }
            Some(Err(e)) => {
                self.ended = true;
                return Some(Err(e));
            }
            Some(Ok(record)) => record,
        };
        match record {
            Record::Event(e) => Some(Ok(TrajectoryRecord::Event(e.into()))),
            Record::Sample(s) => {
                let drive = self.solver.drive(s.tau);
                let sample = TrajectorySample {
                    tau: s.tau,
                    y: s.y,
                    v: s.v,
                    drive,
                    phase: s.phase,
                    physical: self
                        .columns
                        .units
                        .map(|u| u.convert(s.tau, s.y, s.v, drive)),
                };
                let done = self.cursor.samples_done();
                if let Some(monitor) = self.monitor {
                    if done.is_multiple_of(self.samples_per_period) || done == self.samples {
                        let total = self.samples.div_ceil(self.samples_per_period);
                        let blocks = done.div_ceil(self.samples_per_period);
                        if monitor.step(blocks, total) == ControlFlow::Break(()) {
                            self.ended = true;
                            return Some(Err(Error::Cancelled {
                                done: blocks,
                                total,
                            }));
                        }
                    }
                }
                Some(Ok(TrajectoryRecord::Sample(sample)))
            }
        }
    }
}

/// A whole run: its samples column by column and its events.
///
/// JSON: `{"periods", "samples_per_period", "columns": [names], "tau": [...], "y", "v",
/// "drive", "phase": ["slip+", ...], "t_s", "uc_V", "i_A", "u_V" (or the mechanical
/// columns; only with a physical description), "events": [{"tau", "y", "kind"}]}`.
#[derive(Debug, Clone, PartialEq)]
pub struct TrajectoryReport {
    /// Drive periods of the run.
    pub periods: f64,
    /// Samples per drive period.
    pub samples_per_period: usize,
    /// The columns.
    pub columns: TrajectoryColumns,
    /// Dimensionless times τ of the samples.
    pub tau: Vec<f64>,
    /// Position y at each sample.
    pub y: Vec<f64>,
    /// Velocity y' at each sample.
    pub v: Vec<f64>,
    /// The drive at each sample (units of y).
    pub drive: Vec<f64>,
    /// Phase of the motion at each sample.
    pub phase: Vec<Phase>,
    /// The physical columns (time, position, velocity, drive), with a physical description.
    pub physical: Option<[Vec<f64>; 4]>,
    /// Every event from τ = 0 to the last sample, in order.
    pub events: Vec<EventRow>,
}

impl TrajectoryReport {
    fn push(&mut self, s: &TrajectorySample) {
        self.tau.push(s.tau);
        self.y.push(s.y);
        self.v.push(s.v);
        self.drive.push(s.drive);
        self.phase.push(s.phase);
        if let (Some(columns), Some(values)) = (&mut self.physical, &s.physical) {
            for (c, x) in columns.iter_mut().zip(values) {
                c.push(*x);
            }
        }
    }

    /// Sample `i`.
    ///
    /// # Panics
    /// When `i` is out of range.
    pub fn sample(&self, i: usize) -> TrajectorySample {
        TrajectorySample {
            tau: self.tau[i],
            y: self.y[i],
            v: self.v[i],
            drive: self.drive[i],
            phase: self.phase[i],
            physical: self
                .physical
                .as_ref()
                .map(|p| std::array::from_fn(|k| p[k][i])),
        }
    }

    /// The event log as CSV: `tau,y,kind`.
    pub fn events_csv(&self) -> String {
        let mut out = EventRow::COLUMNS.join(",");
        out.push('\n');
        for e in &self.events {
            e.write_row(&mut out);
        }
        out
    }
}

impl Table for TrajectoryReport {
    fn columns(&self) -> Vec<String> {
        self.columns.names().into_iter().map(String::from).collect()
    }

    fn len(&self) -> usize {
        self.tau.len()
    }

    fn row(&self, i: usize) -> Vec<String> {
        self.sample(i).row()
    }

    fn write_row(&self, i: usize, out: &mut String) {
        self.sample(i).write_row(out);
    }
}

impl Serialize for TrajectoryReport {
    fn serialize<S: Serializer>(&self, s: S) -> std::result::Result<S::Ok, S::Error> {
        let mut map = s.serialize_map(None)?;
        map.serialize_entry("periods", &self.periods)?;
        map.serialize_entry("samples_per_period", &self.samples_per_period)?;
        map.serialize_entry("columns", &self.columns.names())?;
        map.serialize_entry("tau", &self.tau)?;
        map.serialize_entry("y", &self.y)?;
        map.serialize_entry("v", &self.v)?;
        map.serialize_entry("drive", &self.drive)?;
        let phase: Vec<&str> = self.phase.iter().map(|p| p.label()).collect();
        map.serialize_entry("phase", &phase)?;
        if let (Some(units), Some(values)) = (&self.columns.units, &self.physical) {
            for (name, column) in units.columns().iter().zip(values) {
                map.serialize_entry(name, column)?;
            }
        }
        map.serialize_entry("events", &self.events)?;
        map.end()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::solver::{grid, sample_at};

    fn paper() -> Experiment {
        Experiment::paper()
            .with_w(0.7)
            .unwrap()
            .with_beta(1.2)
            .unwrap()
    }

    #[test]
    fn the_samples_and_events_of_one_pass_over_the_grid() {
        let e = paper();
        let report = e.trajectory(7.5, 33).unwrap().collect_report().unwrap();
        let params = e.params().unwrap();
        let times = grid(0.0, 7.5 * params.drive_period(), 248);
        let mut solver = e.solver().unwrap();
        let mut events = Vec::new();
        let samples = sample_at(solver.as_mut(), &times, |ev| events.push(*ev)).unwrap();
        assert_eq!(report.len(), samples.len());
        for (k, s) in samples.iter().enumerate() {
            assert_eq!(
                (report.tau[k], report.y[k], report.v[k], report.phase[k]),
                (s.tau, s.y, s.v, s.phase)
            );
            assert_eq!(report.drive[k], params.drive(s.tau));
        }
        let expected: Vec<EventRow> = events.into_iter().map(EventRow::from).collect();
        assert_eq!(report.events, expected);
        assert!(report
            .events
            .iter()
            .any(|e| e.kind == crate::EventKind::Stick));
        // The same as the run kept whole by `Experiment::simulate`.
        let whole = e.simulate(7.5, 33, &()).unwrap();
        assert_eq!(whole.tau, report.tau);
        assert_eq!(whole.y, report.y);
        assert_eq!(whole.drive, report.drive);
    }

    #[test]
    fn csv_lines_are_the_cells_joined() {
        let e = Experiment::dimensionless(0.05, 0.7, 1.2).unwrap();
        let report = e.trajectory(1.0, 20).unwrap().collect_report().unwrap();
        let csv = report.csv();
        let mut lines = csv.lines();
        assert_eq!(lines.next(), Some("tau,y,v,drive,phase"));
        for (i, line) in lines.enumerate() {
            assert_eq!(line, report.row(i).join(","));
            let s = report.sample(i);
            assert_eq!(
                line,
                format!("{},{},{},{},{}", s.tau, s.y, s.v, s.drive, s.phase.label())
            );
        }
        let events = report.events_csv();
        assert!(events.starts_with("tau,y,kind\n"));
        assert_eq!(events.lines().count(), report.events.len() + 1);
    }

    #[test]
    fn a_circuit_has_its_physical_columns_in_csv_and_json() {
        let e = paper();
        let report = e.trajectory(2.0, 10).unwrap().collect_report().unwrap();
        assert_eq!(report.header(), "tau,y,v,drive,phase,t_s,uc_V,i_A,u_V");
        let units = e.units().unwrap();
        let s = report.sample(5);
        assert_eq!(s.physical, Some(units.convert(s.tau, s.y, s.v, s.drive)));
        let json = serde_json::to_value(&report).unwrap();
        assert_eq!(json["uc_V"][5], serde_json::json!(s.physical.unwrap()[1]));
        assert_eq!(json["phase"][5], serde_json::json!(s.phase.label()));
        assert_eq!(json["columns"][5], "t_s");
    }

    #[test]
    fn the_monitor_sees_blocks_and_can_stop_the_run() {
        let e = Experiment::dimensionless(0.1, 0.9, 2.0).unwrap();
        let stop_after_two = |done: usize, _: usize| done < 2;
        let result = e
            .trajectory(10.0, 8)
            .unwrap()
            .monitor(&stop_after_two)
            .collect_report();
        // The blocks of `Experiment::simulate`: 81 samples in blocks of 8.
        assert_eq!(result, Err(Error::Cancelled { done: 2, total: 11 }));
        let seen = std::sync::Mutex::new(Vec::new());
        let watch = |done: usize, total: usize| {
            seen.lock().unwrap().push((done, total));
            true
        };
        e.trajectory(10.0, 8)
            .unwrap()
            .monitor(&watch)
            .collect_report()
            .unwrap();
        let seen = seen.into_inner().unwrap();
        assert_eq!(seen.len(), 11);
        assert_eq!(seen.last(), Some(&(11, 11)));
        for (periods, samples) in [(0.0, 10), (f64::NAN, 10), (1.0, 0), (1e7, 100)] {
            assert!(matches!(
                e.trajectory(periods, samples),
                Err(Error::InvalidParameter { .. })
            ));
        }
    }
}
