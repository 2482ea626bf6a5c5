//! The report of a map (`stickslip phase-diagram`, the lab's map): one row per point of the
//! grid of (w, β).

use super::{cell, optional, Table};
use crate::params::Parameter;
use crate::scan::GridPoint;
use crate::steady::MotionClass;
use serde::Serialize;
use std::fmt::Write as _;

/// One point of a map.
///
/// The JSON fields are the CSV's columns ([`MapRow::columns`]): `w`, `beta`, `class`,
/// `period`, `stops_per_period`, `gain`, and with exponents `lambda1`, `lambda1_error`.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct MapRow {
    /// Drive frequency w = Ω/ω0.
    pub w: f64,
    /// Drive amplitude β.
    pub beta: f64,
    /// Motion class.
    pub class: MotionClass,
    /// Period in drive periods (`None`: none found within the cap; an empty cell).
    pub period: Option<usize>,
    /// Stops of non-zero duration per drive period.
    pub stops_per_period: f64,
    /// Gain G = (y_max − y_min)/(2β).
    pub gain: f64,
    /// Largest Lyapunov exponent λ1 per unit τ, when the map measured exponents (`None`
    /// where the flow has no derivative: an empty cell).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub lambda1: Option<f64>,
    /// Its standard error per unit τ.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub lambda1_error: Option<f64>,
}

impl From<&GridPoint> for MapRow {
    fn from(p: &GridPoint) -> Self {
        Self {
            w: p.params.w,
            beta: p.params.beta,
            class: p.class,
            period: p.period,
            stops_per_period: p.stops_per_period,
            gain: p.gain,
            lambda1: p.lyapunov.map(|l| l.per_tau),
            lambda1_error: p.lyapunov.map(|l| l.error_per_tau),
        }
    }
}

impl MapRow {
    /// The columns of a map without exponents.
    pub const COLUMNS: [&'static str; 6] =
        ["w", "beta", "class", "period", "stops_per_period", "gain"];
    /// The columns of the exponent, after [`MapRow::COLUMNS`] in a map that measured it.
    pub const EXPONENT_COLUMNS: [&'static str; 2] = ["lambda1", "lambda1_error"];

    /// The columns of a map; `lyapunov`: with the exponent's two.
    pub fn columns(lyapunov: bool) -> Vec<&'static str> {
        let mut columns = Self::COLUMNS.to_vec();
        if lyapunov {
            columns.extend(Self::EXPONENT_COLUMNS);
        }
        columns
    }

    /// The row's cells; `lyapunov`: with the exponent's two (empty where it is absent).
    pub fn cells(&self, lyapunov: bool) -> Vec<String> {
        let mut row = vec![
            cell(self.w),
            cell(self.beta),
            self.class.label().to_string(),
            optional(self.period),
            cell(self.stops_per_period),
            cell(self.gain),
        ];
        if lyapunov {
            row.push(optional(self.lambda1));
            row.push(optional(self.lambda1_error));
        }
        row
    }

    /// The columns of a map over two keys `first` × `second` (any two [`Parameter`]s: the
    /// belt speed and μs, say): the keys' names ([`Parameter::label`]), then the columns of
    /// [`MapRow::columns`] after w and β. For (w, β) they are [`MapRow::columns`].
    pub fn columns_over(first: Parameter, second: Parameter, lyapunov: bool) -> Vec<&'static str> {
        let mut columns = vec![first.label(), second.label()];
        columns.extend(Self::columns(lyapunov).into_iter().skip(2));
        columns
    }

    /// The row as a CSV line of a map over two keys ([`MapRow::columns_over`]), with its
    /// newline, appended to `out`: the values `at` of the two keys at the point, then the
    /// cells of [`MapRow::cells`] after w and β.
    pub fn write_row_over(&self, at: (f64, f64), lyapunov: bool, out: &mut String) {
        let cells = self.cells(lyapunov);
        let _ = write!(out, "{},{}", at.0, at.1);
        for c in &cells[2..] {
            out.push(',');
            out.push_str(c);
        }
        out.push('\n');
    }

    /// Append the row as a CSV line, with its newline, to `out`.
    pub fn write_row(&self, lyapunov: bool, out: &mut String) {
        self.write_row_with(lyapunov, &mut AxisCells::default(), out);
    }

    /// [`MapRow::write_row`], the text of w and β taken from `axes` where it holds them (the
    /// same bytes: a map's rows repeat a few values of each).
    pub fn write_row_with(&self, lyapunov: bool, axes: &mut AxisCells, out: &mut String) {
        out.push_str(axes.w(self.w));
        out.push(',');
        out.push_str(axes.beta(self.beta));
        let _ = write!(out, ",{},", self.class.label());
        if let Some(period) = self.period {
            let _ = write!(out, "{period}");
        }
        let _ = write!(out, ",{},{}", self.stops_per_period, self.gain);
        if lyapunov {
            let _ = write!(
                out,
                ",{},{}",
                optional(self.lambda1),
                optional(self.lambda1_error)
            );
        }
        out.push('\n');
    }
}

/// The text of the values of a map's two axes, each formatted once: w of the last row, and
/// every β seen (the rows of a map run over the same β values).
#[derive(Debug, Clone, Default)]
pub struct AxisCells {
    w: Option<(u64, String)>,
    beta: std::collections::HashMap<u64, String>,
}

impl AxisCells {
    /// The text of w.
    fn w(&mut self, w: f64) -> &str {
        match &mut self.w {
            Some((bits, _)) if *bits == w.to_bits() => {}
            slot => *slot = Some((w.to_bits(), w.to_string())),
        }
        self.w.as_ref().map_or("", |(_, text)| text)
    }

    /// The text of β.
    fn beta(&mut self, beta: f64) -> &str {
        self.beta
            .entry(beta.to_bits())
            .or_insert_with(|| beta.to_string())
    }
}

/// A map: its points, rows of the grid one after the other (w-major, as the CSV).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct MapReport {
    /// Whether the map measured Lyapunov exponents (the CSV then has their two columns).
    pub lyapunov: bool,
    /// The points.
    pub points: Vec<MapRow>,
}

impl MapReport {
    /// The report of computed points.
    pub fn new(points: &[GridPoint], lyapunov: bool) -> Self {
        Self {
            lyapunov,
            points: points.iter().map(MapRow::from).collect(),
        }
    }
}

impl Table for MapReport {
    fn columns(&self) -> Vec<String> {
        MapRow::columns(self.lyapunov)
            .into_iter()
            .map(String::from)
            .collect()
    }

    fn len(&self) -> usize {
        self.points.len()
    }

    fn row(&self, i: usize) -> Vec<String> {
        self.points[i].cells(self.lyapunov)
    }

    fn write_row(&self, i: usize, out: &mut String) {
        self.points[i].write_row(self.lyapunov, out);
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::scan::{Axis, Grid};
    use crate::{Experiment, Parameter};

    #[test]
    fn cells_are_the_cli_line_and_write_row_agrees() {
        let e = Experiment::dimensionless(0.05, 0.7, 1.2).unwrap();
        let grid = Grid::new(
            &e,
            Axis::new(Parameter::W, vec![0.5, 0.9]).unwrap(),
            Axis::new(Parameter::Beta, vec![0.8, 2.5]).unwrap(),
        )
        .unwrap();
        let map = grid.run(&()).unwrap();
        for lyapunov in [false, true] {
            let report = MapReport::new(&map.points, lyapunov);
            let csv = report.csv();
            let mut lines = csv.lines();
            assert_eq!(
                lines.next().unwrap(),
                if lyapunov {
                    "w,beta,class,period,stops_per_period,gain,lambda1,lambda1_error"
                } else {
                    "w,beta,class,period,stops_per_period,gain"
                }
            );
            for (i, (line, p)) in lines.zip(&map.points).enumerate() {
                let mut expected = format!(
                    "{},{},{},{},{},{}",
                    p.params.w,
                    p.params.beta,
                    p.class.label(),
                    p.period.map(|x| x.to_string()).unwrap_or_default(),
                    p.stops_per_period,
                    p.gain
                );
                if lyapunov {
                    expected.push_str(",,");
                }
                assert_eq!(line, expected);
                assert_eq!(line, report.row(i).join(","));
            }
        }
        // The JSON fields are the CSV's columns.
        let mut row = MapRow::from(&map.points[0]);
        row.lambda1 = Some(-0.5);
        row.lambda1_error = Some(0.0);
        let json = serde_json::to_value(row).unwrap();
        let mut keys: Vec<&str> = json
            .as_object()
            .unwrap()
            .keys()
            .map(String::as_str)
            .collect();
        let mut columns = MapRow::columns(true);
        keys.sort_unstable();
        columns.sort_unstable();
        assert_eq!(keys, columns);
        let json = serde_json::to_value(MapReport::new(&map.points, false)).unwrap();
        let first = &json["points"][0];
        assert_eq!(first["class"], map.points[0].class.label());
        assert!(first.get("lambda1").is_none());
    }
}
