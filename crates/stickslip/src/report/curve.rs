//! The CSV of a curve of special points in two parameters (its JSON summary is
//! [`crate::report::CurveReport`]).

use super::{cell, Table};
use crate::continuation::Curve;

/// A curve as CSV, one row per point:
/// `<over>,<vary>,y,v,period,stops_per_period,turns,mu1_re,mu1_im,mu2_re,mu2_im,largest_multiplier,stability,arclength,special`.
///
/// The first two columns are named after the parameters (`w`, `beta`, `zeta`, `mu_s`): the
/// one the curve is followed over (Q), then the one that follows it (P). `stability` is the
/// orbit's apart from the followed multiplier ([`crate::continuation::CurvePoint::stability`]);
/// `special` names the codimension-two points (`cusp`, `fold-grazing`, ...) that lie between
/// the row and the next (several joined by `;`), and `start` on the start point's row.
#[derive(Debug, Clone, Copy)]
pub struct CurveTable<'a> {
    /// The curve.
    pub curve: &'a Curve,
}

impl CurveTable<'_> {
    /// The columns after the two parameters' own (named after the parameters).
    pub const COLUMNS: [&'static str; 13] = [
        "y",
        "v",
        "period",
        "stops_per_period",
        "turns",
        "mu1_re",
        "mu1_im",
        "mu2_re",
        "mu2_im",
        "largest_multiplier",
        "stability",
        "arclength",
        "special",
    ];
}

impl Table for CurveTable<'_> {
    fn columns(&self) -> Vec<String> {
        [self.curve.over.label(), self.curve.vary.label()]
            .into_iter()
            .chain(Self::COLUMNS)
            .map(String::from)
            .collect()
    }

    fn len(&self) -> usize {
        self.curve.points.len()
    }

    fn row(&self, i: usize) -> Vec<String> {
        let c = self.curve;
        let p = &c.points[i];
        let m = &p.orbit.multipliers;
        let special: Vec<&str> = (i == c.start)
            .then_some("start")
            .into_iter()
            .chain(
                c.codim2
                    .iter()
                    .filter(|x| x.after_point == i)
                    .map(|x| x.kind.label()),
            )
            .collect();
        let stability = p.stability.label();
        vec![
            cell(p.over),
            cell(p.vary),
            cell(p.orbit.state.y),
            cell(p.orbit.state.v),
            p.orbit.period.to_string(),
            cell(p.stops_per_period()),
            p.turns.to_string(),
            cell(m[0].re),
            cell(m[0].im),
            cell(m[1].re),
            cell(m[1].im),
            cell(p.largest_multiplier()),
            stability.to_string(),
            cell(p.arclength),
            special.join(";"),
        ]
    }
}
