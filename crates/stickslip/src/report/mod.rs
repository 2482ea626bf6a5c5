//! What each computation reports, in one shape for every front end.
//!
//! Each computation has one report type here (or a re-export of the one next to the
//! computation): its serde shape is the JSON of `stickslip … --json`, of the lab's answers and
//! of the Python package's `to_dict()`, and where the command-line tool writes CSV the same
//! type is a [`Table`] whose [`Table::columns`] and [`Table::row`] give the CSV's header and
//! rows, cell for cell. A column name and the JSON field that holds the same quantity are
//! spelled the same.
//!
//! | computation | report | CSV columns |
//! |---|---|---|
//! | trajectory (`simulate`) | [`TrajectoryReport`], streamed by [`TrajectoryRun`] | `tau,y,v,drive,phase` (+ `t_s,uc_V,i_A,u_V` or `t_s,r_m,rdot_m_s,F_N`); events `tau,y,kind` |
//! | steady state | [`SteadyReport`]; its trace [`SteadyTrace`] | `tau,drive,y,v` |
//! | sweep | [`SweepReport`] | (`zeta`/`mu_s`,) `w,beta,direction,gain,gain1,A1,A3,class,stops_per_period` |
//! | map (`phase-diagram`) | [`MapReport`] | `w,beta,class,period,stops_per_period,gain` (+ `lambda1,lambda1_error`) |
//! | theory curves | [`TheoryReport`], [`TheoryTable`] | `w,gain1_paper,gain1_exact` or `w,beta_c_paper,beta_c_exact` |
//! | orbits (one row each) | [`OrbitReport`], [`OrbitTable`] | `w,beta,period,least_period,y,v,stuck_at_strobe,mu1_re,mu1_im,mu2_re,mu2_im,largest_multiplier,smallest_multiplier,stability,lambda1,stops_per_period,iterations` |
//! | Lyapunov exponent | [`LyapunovReport`] | |
//! | bifurcation diagram | [`BifurcationReport`] | `<parameter>,y,v,direction,lambda1,class,period` |
//! | basins | [`BasinReport`], [`BasinsTable`] | `y0,v0,attractor,class,period` |
//! | branch (`continue`) | [`BranchReport`], [`BranchTable`] | `<parameter>,y,v,amplitude,period,stops_per_period,turns,mu1_re,mu1_im,mu2_re,mu2_im,stable,arclength` |
//! | curve (`curve`) | [`CurveReport`], [`CurveTable`] | `<over>,<vary>,y,v,period,stops_per_period,turns,mu1_re,mu1_im,mu2_re,mu2_im,largest_multiplier,stability,arclength,special` |
//!
//! Numbers are written as Rust's `Display` writes an `f64` (the shortest text that reads
//! back to the same number: `0.1`, `1e-7`, `NaN`, `inf`); a missing value is an empty cell
//! ([`cell`], [`optional`]). A front end that hands out columns (arrays, JSON) takes them
//! from the table as [`Columns`]: the CSV's names and numbers, typed.

mod bifurcation;
mod branch;
mod columns;
mod curve;
mod map;
mod orbit;
mod steady;
mod sweep;
mod trajectory;

pub use crate::basins::{AttractorReport, BasinReport};

/// The report of a basin map (the name beside the other reports'; the type is
/// [`BasinReport`]).
pub type BasinsReport = BasinReport;
pub use crate::continuation::CurveReport;
pub use crate::continuation::{BranchReport, SideReport, SpecialReport};
pub use crate::stability::{LyapunovReport, OrbitReport};
pub use crate::steady::SteadyReport;
pub use crate::theory::TheoryReport;
pub use bifurcation::{BifurcationReport, BifurcationRow};
pub use branch::{BasinsTable, BranchTable};
pub use columns::{Column, Columns};
pub use curve::CurveTable;
pub use map::{AxisCells, MapReport, MapRow};
pub use orbit::OrbitTable;
pub use steady::{SteadyTrace, TheoryRow, TheoryTable};
pub use sweep::{SweepReport, SweepRow};
pub use trajectory::{
    EventRow, TrajectoryColumns, TrajectoryRecord, TrajectoryReport, TrajectoryRun,
    TrajectorySample,
};

use std::fmt::Write as _;

/// A report written as CSV: a header of column names and rows of cells.
pub trait Table {
    /// The column names, in order.
    fn columns(&self) -> Vec<String>;

    /// Number of rows.
    fn len(&self) -> usize;

    /// Whether there are no rows.
    fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// Row `i` (`0 ≤ i < len()`), one cell per column.
    ///
    /// # Panics
    /// When `i` is out of range.
    fn row(&self, i: usize) -> Vec<String>;

    /// The header line, without its newline.
    fn header(&self) -> String {
        self.columns().join(",")
    }

    /// Append row `i` as a CSV line, with its newline, to `out`.
    fn write_row(&self, i: usize, out: &mut String) {
        out.push_str(&self.row(i).join(","));
        out.push('\n');
    }

    /// The whole table as CSV text: header and rows, each line ending in a newline.
    fn csv(&self) -> String {
        let mut out = self.header();
        out.push('\n');
        for i in 0..self.len() {
            self.write_row(i, &mut out);
        }
        out
    }
}

/// A number as it is written in a CSV cell: Rust's `Display` of an `f64`.
pub fn cell(x: f64) -> String {
    x.to_string()
}

/// An optional number as a CSV cell: empty when absent.
pub fn optional<T: std::fmt::Display>(x: Option<T>) -> String {
    x.map(|x| x.to_string()).unwrap_or_default()
}

/// Append cells separated by commas to `out` (no newline).
pub(crate) fn push_cells<T: std::fmt::Display>(out: &mut String, cells: &[T]) {
    for (k, c) in cells.iter().enumerate() {
        if k > 0 {
            out.push(',');
        }
        let _ = write!(out, "{c}");
    }
}

/// Serialise an event kind by its CSV label (`turn`, `stick`, `slip`).
pub(crate) fn event_kind<S: serde::Serializer>(
    kind: &crate::EventKind,
    s: S,
) -> Result<S::Ok, S::Error> {
    s.serialize_str(kind.label())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn cells_are_display_and_empty_when_absent() {
        assert_eq!(cell(0.1), "0.1");
        assert_eq!(cell(1e-7), "0.0000001");
        assert_eq!(cell(f64::NAN), "NaN");
        assert_eq!(optional::<usize>(None), "");
        assert_eq!(optional(Some(3usize)), "3");
        let mut s = String::new();
        push_cells(&mut s, &[1.5, 2.0]);
        assert_eq!(s, "1.5,2");
    }
}
