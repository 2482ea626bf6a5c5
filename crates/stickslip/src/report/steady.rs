//! The CSV of a steady state's trace and of the theory's curves over w.

use super::{cell, optional, Table};
use crate::steady::SteadyState;
use serde::Serialize;

/// The trace of a steady state (one cycle) as CSV: `tau,drive,y,v`.
#[derive(Debug, Clone, Copy)]
pub struct SteadyTrace<'a> {
    /// The steady state.
    pub steady: &'a SteadyState,
}

impl Table for SteadyTrace<'_> {
    fn columns(&self) -> Vec<String> {
        ["tau", "drive", "y", "v"].map(String::from).to_vec()
    }

    fn len(&self) -> usize {
        self.steady.trace.len()
    }

    fn row(&self, i: usize) -> Vec<String> {
        let s = &self.steady.trace[i];
        vec![
            cell(s.tau),
            cell(self.steady.params.drive(s.tau)),
            cell(s.y),
            cell(s.v),
        ]
    }
}

/// One value of w of a [`TheoryTable`]: the paper's and the exact value of the quantity
/// (`None`: no value there, an empty cell).
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct TheoryRow {
    /// Drive frequency w.
    pub w: f64,
    /// The paper's value.
    pub paper: Option<f64>,
    /// The exact value.
    pub exact: Option<f64>,
}

/// The theory's curves over w as CSV: `w,gain1_paper,gain1_exact` or
/// `w,beta_c_paper,beta_c_exact`.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct TheoryTable {
    /// The quantity's name in the column names: `gain1` or `beta_c`.
    pub quantity: &'static str,
    /// The rows.
    pub rows: Vec<TheoryRow>,
}

impl Table for TheoryTable {
    fn columns(&self) -> Vec<String> {
        vec![
            "w".into(),
            format!("{}_paper", self.quantity),
            format!("{}_exact", self.quantity),
        ]
    }

    fn len(&self) -> usize {
        self.rows.len()
    }

    fn row(&self, i: usize) -> Vec<String> {
        let r = &self.rows[i];
        vec![cell(r.w), optional(r.paper), optional(r.exact)]
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn theory_columns_and_empty_cells() {
        let t = TheoryTable {
            quantity: "beta_c",
            rows: vec![
                TheoryRow {
                    w: 0.5,
                    paper: Some(1.25),
                    exact: None,
                },
                TheoryRow {
                    w: 1.0,
                    paper: None,
                    exact: Some(0.1),
                },
            ],
        };
        assert_eq!(t.csv(), "w,beta_c_paper,beta_c_exact\n0.5,1.25,\n1,,0.1\n");
    }

    #[test]
    fn steady_trace_is_tau_drive_y_v() {
        let e = crate::Experiment::dimensionless(0.05, 0.7, 1.2).unwrap();
        let steady = e.steady().unwrap();
        let table = SteadyTrace { steady: &steady };
        assert_eq!(table.header(), "tau,drive,y,v");
        assert_eq!(table.len(), steady.trace.len());
        let s = &steady.trace[3];
        assert_eq!(
            table.row(3).join(","),
            format!("{},{},{},{}", s.tau, steady.params.drive(s.tau), s.y, s.v)
        );
    }
}
