//! The CSV of a list of periodic orbits (each one's JSON is [`crate::report::OrbitReport`]).

use super::{cell, Table};
use crate::stability::{ExponentValue, OrbitReport};

/// Periodic orbits as CSV, one row per orbit:
/// `w,beta,period,least_period,y,v,stuck_at_strobe,mu1_re,mu1_im,mu2_re,mu2_im,largest_multiplier,smallest_multiplier,stability,lambda1,stops_per_period,iterations`.
///
/// The columns hold the [`OrbitReport`]'s fields of the same names; `largest_multiplier` and
/// `smallest_multiplier` are its `moduli` (|μ₁| ≥ |μ₂|), `lambda1` is λ₁ = ln|μ₁|/(pT) per
/// unit τ (`-inf` when both multipliers vanish).
#[derive(Debug, Clone, Copy)]
pub struct OrbitTable<'a> {
    /// The orbits' reports, one row each.
    pub orbits: &'a [OrbitReport],
}

impl OrbitTable<'_> {
    /// The columns.
    pub const COLUMNS: [&'static str; 17] = [
        "w",
        "beta",
        "period",
        "least_period",
        "y",
        "v",
        "stuck_at_strobe",
        "mu1_re",
        "mu1_im",
        "mu2_re",
        "mu2_im",
        "largest_multiplier",
        "smallest_multiplier",
        "stability",
        "lambda1",
        "stops_per_period",
        "iterations",
    ];
}

impl Table for OrbitTable<'_> {
    fn columns(&self) -> Vec<String> {
        Self::COLUMNS.iter().map(|c| c.to_string()).collect()
    }

    fn len(&self) -> usize {
        self.orbits.len()
    }

    fn row(&self, i: usize) -> Vec<String> {
        let o = &self.orbits[i];
        let m = &o.multipliers;
        vec![
            cell(o.w),
            cell(o.beta),
            o.period.to_string(),
            o.least_period.to_string(),
            cell(o.y),
            cell(o.v),
            o.stuck_at_strobe.to_string(),
            cell(m[0].re),
            cell(m[0].im),
            cell(m[1].re),
            cell(m[1].im),
            cell(o.moduli[0]),
            cell(o.moduli[1]),
            o.stability.label().to_string(),
            match o.lambda1 {
                ExponentValue::Finite(x) => cell(x),
                ExponentValue::Text(t) => t.to_string(),
            },
            cell(o.stops_per_period),
            o.iterations.to_string(),
        ]
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::experiment::Experiment;
    use crate::stability::NewtonOptions;
    use crate::SteadyOptions;

    #[test]
    fn a_row_per_orbit_with_a_cell_per_column() {
        let e = Experiment::paper()
            .with_w(0.7)
            .unwrap()
            .with_beta(1.2)
            .unwrap();
        let orbit = e
            .periodic_orbit(
                None,
                0,
                &SteadyOptions::default(),
                &NewtonOptions::default(),
                &(),
            )
            .unwrap();
        let report = OrbitReport::new(&orbit, &e.params().unwrap()).unwrap();
        let orbits = [report.clone(), report];
        let table = OrbitTable { orbits: &orbits };
        let csv = table.csv();
        let lines: Vec<&str> = csv.lines().collect();
        assert_eq!(lines.len(), 3);
        assert_eq!(lines[0], OrbitTable::COLUMNS.join(","));
        let row = table.row(0);
        assert_eq!(row.len(), OrbitTable::COLUMNS.len());
        let at = |name: &str| &row[OrbitTable::COLUMNS.iter().position(|c| *c == name).unwrap()];
        assert_eq!(at("w"), "0.7");
        assert_eq!(at("stability"), orbit.stability.label());
        assert_eq!(
            at("largest_multiplier").parse::<f64>().unwrap(),
            orbit.multipliers[0].modulus()
        );
    }
}
