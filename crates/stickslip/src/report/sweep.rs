//! The report of a sweep: one row per step, in the order the steps were computed.

use super::{cell, optional, Table};
use crate::experiment::Experiment;
use crate::params::Parameter;
use crate::scan::{SweepDirection, SweepLeg, SweepPoint};
use crate::steady::MotionClass;
use serde::Serialize;

/// One step of a sweep.
///
/// The JSON fields are the CSV's columns (`w`, `beta`, `direction`, `gain`, `gain1`, `A1`,
/// `A3`, `class`, `stops_per_period`; the swept value as `value`) and what the CSV leaves
/// out (`zeta`, `mu_s`, `peak`, `period`, `phase_lag`, `f_Hz`), then what a self-excited
/// belt's sweep writes ([`SweepRow::SELF_EXCITED_COLUMNS`]: `amplitude`, `y_max`, `y_min`,
/// `cycle_period_tau`, `cycle_period_s`, `stick_fraction`; null where a step has none).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct SweepRow {
    /// The swept parameter's value.
    pub value: f64,
    /// Drive frequency w = Ω/ω0 of the step.
    pub w: f64,
    /// Drive amplitude β of the step.
    pub beta: f64,
    /// Damping ratio ζ of the step.
    pub zeta: f64,
    /// Static-to-kinetic friction ratio μs of the step.
    pub mu_s: f64,
    /// The leg of the step: `up` or `down`.
    pub direction: SweepLeg,
    /// Gain G = (y_max − y_min)/(2β).
    pub gain: f64,
    /// Gain of the fundamental G1 = A1/β (`None`: not measured; the CSV writes `NaN`).
    pub gain1: Option<f64>,
    /// Peak |y| of the steady motion (`None` for a step restored from a file that did not
    /// keep it).
    pub peak: Option<f64>,
    /// Amplitude of the fundamental of y (`None`: not measured; the CSV writes `NaN`).
    #[serde(rename = "A1")]
    pub a1: Option<f64>,
    /// Amplitude of the third harmonic of y (`None`: not measured; the CSV writes `NaN`).
    #[serde(rename = "A3")]
    pub a3: Option<f64>,
    /// Motion class.
    pub class: MotionClass,
    /// Stops of non-zero duration per drive period.
    pub stops_per_period: f64,
    /// Period in drive periods (`None`: none found within the cap).
    pub period: Option<usize>,
    /// Phase lag of the fundamental of y behind the drive, radians (`None`: no fundamental,
    /// or not kept).
    pub phase_lag: Option<f64>,
    /// Drive frequency in Hz, for a physical description.
    #[serde(rename = "f_Hz")]
    pub f_hz: Option<f64>,
    /// Amplitude (y_max − y_min)/2 of the steady motion (`None` for a step restored from a
    /// file that did not keep it).
    pub amplitude: Option<f64>,
    /// Largest y of the steady motion (`None`: not kept).
    pub y_max: Option<f64>,
    /// Smallest y of the steady motion (`None`: not kept).
    pub y_min: Option<f64>,
    /// The period of a self-excited cycle in τ = ω0·t (`None`: a forced step, steady
    /// sliding, or no cycle found).
    pub cycle_period_tau: Option<f64>,
    /// The same period in seconds, for a physical description.
    pub cycle_period_s: Option<f64>,
    /// The fraction of a self-excited cycle stuck to the belt (`None`: a forced step; 0 for
    /// steady sliding).
    pub stick_fraction: Option<f64>,
}

impl SweepRow {
    /// The row of a computed step; `experiment` gives the drive frequency in Hz when it is
    /// physical.
    pub fn new(point: &SweepPoint, experiment: &Experiment) -> Self {
        let s = &point.steady;
        Self {
            value: point.value,
            w: point.params.w,
            beta: point.params.beta,
            zeta: point.params.zeta,
            mu_s: point.params.mu_s,
            direction: point.leg,
            gain: s.gain,
            gain1: s.gain1(),
            peak: Some(s.peak),
            a1: s.harmonic(1),
            a3: s.harmonic(3),
            class: s.class,
            stops_per_period: s.stops_per_period,
            period: s.period,
            phase_lag: s.phase_lag(),
            f_hz: experiment
                .scales()
                .map(|sc| sc.drive_omega(point.params.w) / std::f64::consts::TAU),
            amplitude: Some(s.amplitude()),
            y_max: Some(s.y_max),
            y_min: Some(s.y_min),
            cycle_period_tau: s.self_excited.and_then(|c| c.period),
            cycle_period_s: None,
            stick_fraction: s.self_excited.map(|c| c.stick_fraction),
        }
        .with_seconds(experiment)
    }

    /// The row with [`SweepRow::cycle_period_s`] from its period in τ, for a physical
    /// `experiment` (seconds = τ/ω0).
    pub fn with_seconds(mut self, experiment: &Experiment) -> Self {
        self.cycle_period_s = experiment
            .scales()
            .zip(self.cycle_period_tau)
            .map(|(sc, tau)| tau / sc.omega0);
        self
    }

    /// Whether the step is a self-excited belt's (no drive; its period is its own).
    pub fn is_self_excited(&self) -> bool {
        self.stick_fraction.is_some()
    }
}

/// A sweep: the swept parameter, the direction asked for, and the steps.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct SweepReport {
    /// The swept parameter (`w`, `beta`, `zeta`, `mu_s` or `vb`).
    pub over: Parameter,
    /// `up`, `down` or `both`.
    #[serde(serialize_with = "direction")]
    pub direction: SweepDirection,
    /// The steps in the order they were computed.
    pub points: Vec<SweepRow>,
}

fn direction<S: serde::Serializer>(d: &SweepDirection, s: S) -> Result<S::Ok, S::Error> {
    s.serialize_str(d.label())
}

impl SweepReport {
    /// The report of computed steps.
    pub fn new(
        experiment: &Experiment,
        over: Parameter,
        direction: SweepDirection,
        points: &[SweepPoint],
    ) -> Self {
        Self {
            over,
            direction,
            points: points
                .iter()
                .map(|p| SweepRow::new(p, experiment))
                .collect(),
        }
    }

    /// Whether the CSV puts the swept value in a column of its own, first (a sweep of ζ, μs
    /// or the belt speed vb, whose value is not among the other columns, and every sweep of a
    /// self-excited belt).
    pub fn value_column(&self) -> bool {
        self.self_excited() || !matches!(self.over, Parameter::W | Parameter::Beta)
    }

    /// Whether a step is a self-excited belt's (a belt without a drive): the CSV then has
    /// the columns of the classic amplitude against belt speed
    /// ([`SweepRow::SELF_EXCITED_COLUMNS`]) instead of the gains and harmonics, which a
    /// motion without a drive does not have.
    pub fn self_excited(&self) -> bool {
        self.points.iter().any(SweepRow::is_self_excited)
    }

    /// Whether the description is physical (the CSV of a self-excited sweep then has the
    /// period in seconds too).
    fn physical(&self) -> bool {
        self.points.iter().any(|p| p.f_hz.is_some())
    }
}

impl SweepRow {
    /// The JSON fields of a row, in order: the CSV's columns and what the CSV leaves out.
    pub const FIELDS: [&'static str; 22] = [
        "value",
        "w",
        "beta",
        "zeta",
        "mu_s",
        "direction",
        "gain",
        "gain1",
        "peak",
        "A1",
        "A3",
        "class",
        "stops_per_period",
        "period",
        "phase_lag",
        "f_Hz",
        "amplitude",
        "y_max",
        "y_min",
        "cycle_period_tau",
        "cycle_period_s",
        "stick_fraction",
    ];

    /// The columns of a self-excited belt's sweep after the swept value's (the classic
    /// amplitude against belt speed); `cycle_period_s` only for a physical description.
    pub const SELF_EXCITED_COLUMNS: [&'static str; 8] = [
        "direction",
        "amplitude",
        "y_max",
        "y_min",
        "cycle_period_tau",
        "cycle_period_s",
        "stick_fraction",
        "class",
    ];

    /// The columns of a sweep's CSV after the swept value's own column (which a sweep of ζ, μs
    /// or vb has first, [`SweepReport::value_column`]).
    pub const COLUMNS: [&'static str; 9] = [
        "w",
        "beta",
        "direction",
        "gain",
        "gain1",
        "A1",
        "A3",
        "class",
        "stops_per_period",
    ];
}

impl Table for SweepReport {
    /// `w,beta,direction,gain,gain1,A1,A3,class,stops_per_period` ([`SweepRow::COLUMNS`]),
    /// after `zeta`, `mu_s` or `vb` for a sweep of that parameter; a self-excited belt's
    /// sweep: the swept parameter, then
    /// `direction,amplitude,y_max,y_min,cycle_period_tau,stick_fraction,class`
    /// ([`SweepRow::SELF_EXCITED_COLUMNS`], `cycle_period_s` after `cycle_period_tau` for a
    /// physical description).
    fn columns(&self) -> Vec<String> {
        let mut columns = Vec::new();
        if self.value_column() {
            columns.push(self.over.label().to_string());
        }
        if self.self_excited() {
            let physical = self.physical();
            columns.extend(
                SweepRow::SELF_EXCITED_COLUMNS
                    .into_iter()
                    .filter(|&c| physical || c != "cycle_period_s")
                    .map(String::from),
            );
        } else {
            columns.extend(SweepRow::COLUMNS.map(String::from));
        }
        columns
    }

    fn len(&self) -> usize {
        self.points.len()
    }

    fn row(&self, i: usize) -> Vec<String> {
        let p = &self.points[i];
        let mut row = Vec::with_capacity(10);
        if self.value_column() {
            row.push(cell(p.value));
        }
        if self.self_excited() {
            let number = |x: Option<f64>| cell(x.unwrap_or(f64::NAN));
            row.extend([
                p.direction.label().to_string(),
                number(p.amplitude),
                number(p.y_max),
                number(p.y_min),
                optional(p.cycle_period_tau),
            ]);
            if self.physical() {
                row.push(optional(p.cycle_period_s));
            }
            row.extend([optional(p.stick_fraction), p.class.label().to_string()]);
            return row;
        }
        row.extend([
            cell(p.w),
            cell(p.beta),
            p.direction.label().to_string(),
            cell(p.gain),
            cell(p.gain1.unwrap_or(f64::NAN)),
            cell(p.a1.unwrap_or(f64::NAN)),
            cell(p.a3.unwrap_or(f64::NAN)),
            p.class.label().to_string(),
            cell(p.stops_per_period),
        ]);
        row
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scan::{Axis, Sweep};

    #[test]
    fn rows_csv_and_json_of_a_sweep_of_mu_s() {
        let e = Experiment::dimensionless(0.05, 0.7, 2.0).unwrap();
        let axis = Axis::new(Parameter::MuS, vec![1.0, 1.5]).unwrap();
        let sweep = Sweep::new(&e, axis)
            .unwrap()
            .direction(SweepDirection::Both)
            .options(e.steady_options().with_harmonics(3).unwrap())
            .unwrap();
        let points = sweep.run(&()).unwrap();
        let report = SweepReport::new(&e, Parameter::MuS, SweepDirection::Both, &points);
        assert_eq!(
            report.header(),
            "mu_s,w,beta,direction,gain,gain1,A1,A3,class,stops_per_period"
        );
        assert_eq!(report.len(), 4);
        for (i, p) in points.iter().enumerate() {
            let s = &p.steady;
            // The CLI's line before the report type, written out.
            let line = format!(
                "{},{},{},{},{},{},{},{},{},{}",
                p.value,
                p.params.w,
                p.params.beta,
                p.leg.label(),
                s.gain,
                s.harmonic(1).unwrap_or(f64::NAN) / p.params.beta,
                s.harmonic(1).unwrap_or(f64::NAN),
                s.harmonic(3).unwrap_or(f64::NAN),
                s.class.label(),
                s.stops_per_period
            );
            assert_eq!(report.row(i).join(","), line);
        }
        let json = serde_json::to_value(&report).unwrap();
        assert_eq!(json["over"], "mu_s");
        assert_eq!(json["direction"], "both");
        let row = &json["points"][3];
        assert_eq!(row["direction"], "down");
        assert_eq!(row["mu_s"], 1.0);
        assert_eq!(row["class"], points[3].steady.class.label());
        assert_eq!(row["A1"], points[3].steady.harmonic(1).unwrap());
        assert!(row["f_Hz"].is_null());
        // The JSON fields are the row's FIELDS and hold every CSV column.
        let mut keys: Vec<&str> = row
            .as_object()
            .unwrap()
            .keys()
            .map(String::as_str)
            .collect();
        let mut fields = SweepRow::FIELDS.to_vec();
        keys.sort_unstable();
        fields.sort_unstable();
        assert_eq!(keys, fields);
        assert!(SweepRow::COLUMNS.iter().all(|c| keys.contains(c)));
        for key in [
            "value",
            "w",
            "beta",
            "zeta",
            "gain",
            "gain1",
            "peak",
            "A3",
            "stops_per_period",
            "period",
            "phase_lag",
        ] {
            assert!(row.get(key).is_some(), "{key}");
        }
    }

    #[test]
    fn a_sweep_of_w_has_no_value_column_and_a_circuit_has_f_hz() {
        let e = Experiment::paper().with_beta(1.2).unwrap();
        let axis = Axis::new(Parameter::W, vec![0.7]).unwrap();
        let sweep = Sweep::new(&e, axis).unwrap().direction(SweepDirection::Up);
        let points = sweep.run(&()).unwrap();
        let report = SweepReport::new(&e, Parameter::W, SweepDirection::Up, &points);
        assert_eq!(
            report.header(),
            "w,beta,direction,gain,gain1,A1,A3,class,stops_per_period"
        );
        let scales = e.scales().unwrap();
        let f = report.points[0].f_hz.unwrap();
        assert!((f * std::f64::consts::TAU / scales.omega0 - 0.7).abs() < 1e-12);
    }
}
