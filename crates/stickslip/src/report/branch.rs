//! The CSV of a branch of periodic orbits and of a basin map (their JSON summaries are
//! [`crate::report::BranchReport`] and [`crate::report::BasinReport`]).

use super::{cell, optional, Table};
use crate::attractor::AttractorKind;
use crate::basins::BasinMap;
use crate::continuation::Branch;

/// A branch as CSV, one row per point:
/// `<parameter>,y,v,amplitude,period,stops_per_period,turns,mu1_re,mu1_im,mu2_re,mu2_im,stable,arclength`.
#[derive(Debug, Clone, Copy)]
pub struct BranchTable<'a> {
    /// The branch.
    pub branch: &'a Branch,
}

impl BranchTable<'_> {
    /// The columns after the continued parameter's own (named after the parameter).
    pub const COLUMNS: [&'static str; 12] = [
        "y",
        "v",
        "amplitude",
        "period",
        "stops_per_period",
        "turns",
        "mu1_re",
        "mu1_im",
        "mu2_re",
        "mu2_im",
        "stable",
        "arclength",
    ];
}

impl Table for BranchTable<'_> {
    fn columns(&self) -> Vec<String> {
        std::iter::once(self.branch.parameter.label())
            .chain(Self::COLUMNS)
            .map(String::from)
            .collect()
    }

    fn len(&self) -> usize {
        self.branch.points.len()
    }

    fn row(&self, i: usize) -> Vec<String> {
        let p = &self.branch.points[i];
        let m = &p.orbit.multipliers;
        vec![
            cell(p.value),
            cell(p.orbit.state.y),
            cell(p.orbit.state.v),
            cell(p.amplitude()),
            p.orbit.period.to_string(),
            cell(p.stops_per_period()),
            p.turns.to_string(),
            cell(m[0].re),
            cell(m[0].im),
            cell(m[1].re),
            cell(m[1].im),
            p.stable().to_string(),
            cell(p.arclength),
        ]
    }
}

/// A basin map as CSV, one row per cell (y0-major): `y0,v0,attractor,class,period`; a cell
/// not decided has an empty attractor and period and the class `undecided`.
#[derive(Debug, Clone, Copy)]
pub struct BasinsTable<'a> {
    /// The map.
    pub map: &'a BasinMap,
}

impl BasinsTable<'_> {
    /// The columns: `class` is what the cell's attractor is ([`AttractorKind`]'s labels, as
    /// the bifurcation diagram's `class`).
    pub const COLUMNS: [&'static str; 5] = ["y0", "v0", "attractor", "class", "period"];
}

impl Table for BasinsTable<'_> {
    fn columns(&self) -> Vec<String> {
        Self::COLUMNS.map(String::from).to_vec()
    }

    fn len(&self) -> usize {
        self.map.cells.len()
    }

    fn row(&self, k: usize) -> Vec<String> {
        let map = self.map;
        let n = map.v0.len();
        let (y, v) = (map.y0[k / n], map.v0[k % n]);
        match map.cells[k].map(|i| &map.attractors[i]) {
            Some(a) => vec![
                cell(y),
                cell(v),
                a.id.to_string(),
                a.kind.label().to_string(),
                optional(a.period),
            ],
            None => vec![
                cell(y),
                cell(v),
                String::new(),
                AttractorKind::Undecided.label().to_string(),
                String::new(),
            ],
        }
    }
}
