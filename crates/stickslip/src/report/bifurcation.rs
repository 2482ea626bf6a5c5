//! The report of a bifurcation diagram: one row per strobe point.

use super::{cell, optional, Table};
use crate::attractor::AttractorKind;
use crate::bifurcation::BifurcationStep;
use crate::params::Parameter;
use crate::scan::SweepLeg;
use serde::Serialize;

/// One strobe point of a bifurcation diagram, with the verdict of its step.
///
/// The JSON fields are the CSV's columns (`y`, `v`, `direction`, `lambda1`, `class`,
/// `period`; the stepped value, the CSV's first column named after the parameter, as
/// `value`).
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct BifurcationRow {
    /// The stepped parameter's value.
    pub value: f64,
    /// Position y of the strobe point.
    pub y: f64,
    /// Velocity y' of the strobe point.
    pub v: f64,
    /// The leg of the step: `up` or `down`.
    pub direction: SweepLeg,
    /// The largest Lyapunov exponent λ1 of the step, per unit τ.
    pub lambda1: f64,
    /// What the step settled on (`undecided`: not decided by its record).
    pub class: AttractorKind,
    /// Period in drive periods when the points repeat (an empty cell otherwise).
    pub period: Option<usize>,
}

/// A bifurcation diagram: the stepped parameter and every strobe point of every step, in
/// the order the steps were computed.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct BifurcationReport {
    /// The stepped parameter (`w`, `beta`, `zeta` or `mu_s`).
    pub parameter: Parameter,
    /// The strobe points.
    pub points: Vec<BifurcationRow>,
}

impl BifurcationReport {
    /// The report of computed steps.
    pub fn new(parameter: Parameter, steps: &[BifurcationStep]) -> Self {
        let points = steps
            .iter()
            .flat_map(|s| {
                let r = &s.record;
                r.strobes.iter().map(move |x| BifurcationRow {
                    value: s.value,
                    y: x.y,
                    v: x.v,
                    direction: s.leg,
                    lambda1: r.exponent,
                    class: r.kind,
                    period: r.period,
                })
            })
            .collect();
        Self { parameter, points }
    }
}

impl BifurcationRow {
    /// The JSON fields of a row, in order: the CSV's columns, the stepped value as `value`.
    pub const FIELDS: [&'static str; 7] =
        ["value", "y", "v", "direction", "lambda1", "class", "period"];

    /// The columns of a bifurcation diagram's CSV after the stepped parameter's own (named
    /// after the parameter).
    pub const COLUMNS: [&'static str; 6] = ["y", "v", "direction", "lambda1", "class", "period"];
}

impl Table for BifurcationReport {
    /// `<parameter>,y,v,direction,lambda1,class,period` ([`BifurcationRow::COLUMNS`]).
    fn columns(&self) -> Vec<String> {
        std::iter::once(self.parameter.label())
            .chain(BifurcationRow::COLUMNS)
            .map(String::from)
            .collect()
    }

    fn len(&self) -> usize {
        self.points.len()
    }

    fn row(&self, i: usize) -> Vec<String> {
        let p = &self.points[i];
        vec![
            cell(p.value),
            cell(p.y),
            cell(p.v),
            p.direction.label().to_string(),
            cell(p.lambda1),
            p.class.label().to_string(),
            optional(p.period),
        ]
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::bifurcation::Bifurcation;
    use crate::scan::Axis;
    use crate::Experiment;

    #[test]
    fn one_row_per_strobe_point_as_the_cli_wrote_it() {
        let e = Experiment::dimensionless(0.05, 0.7, 1.2).unwrap();
        let diagram =
            Bifurcation::new(&e, Axis::new(Parameter::Beta, vec![1.2, 2.0]).unwrap()).unwrap();
        let steps = diagram.run(&()).unwrap();
        let report = BifurcationReport::new(Parameter::Beta, &steps);
        assert_eq!(report.header(), "beta,y,v,direction,lambda1,class,period");
        let mut expected = Vec::new();
        for s in &steps {
            let r = &s.record;
            let period = r.period.map(|p| p.to_string()).unwrap_or_default();
            for x in &r.strobes {
                expected.push(format!(
                    "{},{},{},{},{},{},{}",
                    s.value,
                    x.y,
                    x.v,
                    s.leg.label(),
                    r.exponent,
                    r.kind.label(),
                    period
                ));
            }
        }
        assert_eq!(report.len(), expected.len());
        for (i, line) in expected.iter().enumerate() {
            assert_eq!(&report.row(i).join(","), line);
        }
        let json = serde_json::to_value(&report).unwrap();
        assert_eq!(json["parameter"], "beta");
        assert_eq!(json["points"][0]["class"], steps[0].record.kind.label());
        let mut keys: Vec<&str> = json["points"][0]
            .as_object()
            .unwrap()
            .keys()
            .map(String::as_str)
            .collect();
        let mut fields = BifurcationRow::FIELDS.to_vec();
        keys.sort_unstable();
        fields.sort_unstable();
        assert_eq!(keys, fields);
        assert_eq!(BifurcationRow::FIELDS[1..], BifurcationRow::COLUMNS);
    }
}
