//! A forced belt (Popp and Stelter's setting): the (w, β) map of motion classes of a Coulomb
//! belt under a harmonic force.

use super::super::report::{sig, Report, Section};
use super::super::Context;
use crate::plot::{class_color, Cell, Figure, Legend, Panel};
use anyhow::Result;
use serde_json::json;
use stickslip::friction::FrictionLaw;
use stickslip::report::MapReport;
use stickslip::scan::{Axis, Grid, ParameterRange};
use stickslip::steady::MotionClass;
use stickslip::{Experiment, Parameter};

/// The belt: ζ, μs, vb.
const BELT: (f64, f64, f64) = (0.05, 1.5, 0.3);
/// The map's ranges.
const W: (f64, f64) = (0.2, 2.0);
const BETA: (f64, f64) = (0.2, 3.0);

/// The map and its section.
pub fn forced_map(report: &mut Report, ctx: &Context) -> Result<()> {
    let n = if ctx.quick { 12 } else { 32 };
    let (zeta, mu_s, vb) = BELT;
    let experiment = Experiment::dimensionless(zeta, 1.0, 1.0)?
        .with_mu_s(mu_s)?
        .with_law(FrictionLaw::Coulomb)?
        .with_vb(vb)?;
    let w = ParameterRange::new("w", W.0, W.1, n)?;
    let beta = ParameterRange::new("beta", BETA.0, BETA.1, n)?;
    let started = std::time::Instant::now();
    let points = Grid::new(
        &experiment,
        Axis::range(Parameter::W, &w)?,
        Axis::range(Parameter::Beta, &beta)?,
    )?
    .run(&|_: usize, _: usize| !crate::output::interrupted())?
    .points;
    eprintln!(
        "reproduce: forced belt's {n} × {n} map in {:.1} s",
        started.elapsed().as_secs_f64()
    );
    let (dw, db) = (0.5 * w.spacing(), 0.5 * beta.spacing());
    let mut present: Vec<MotionClass> = points.iter().map(|p| p.class).collect();
    present.sort_by_key(|c| c.label());
    present.dedup();
    report.figure(
        "belt-forced-map",
        &Figure {
            panels: vec![Panel {
                title: format!(
                    "motion classes of a forced belt, ζ = {zeta}, μs = {mu_s}, vb = {vb}"
                ),
                x_label: "w = Ω/ω0".into(),
                y_label: "β".into(),
                cells: points
                    .iter()
                    .map(|p| Cell {
                        x: (p.params.w - dw, p.params.w + dw),
                        y: (p.params.beta - db, p.params.beta + db),
                        color: class_color(p.class),
                    })
                    .collect(),
                cell_legend: present
                    .iter()
                    .map(|c| (c.label().to_string(), class_color(*c)))
                    .collect(),
                x_range: Some((W.0 - dw, W.1 + dw)),
                y_range: Some((BETA.0 - db, BETA.1 + db)),
                legend: Some(Legend::UpperRight),
                ..Default::default()
            }],
            columns: 1,
            panel_size: (900, 640),
        },
    )?;
    report.table("belt-forced-map.csv", &MapReport::new(&points, false))?;

    let count = |c: MotionClass| points.iter().filter(|p| p.class == c).count();
    let counts: Vec<String> = present
        .iter()
        .map(|c| format!("{} {}", count(*c), c.label()))
        .collect();
    let mut periods: Vec<usize> = points.iter().filter_map(|p| p.period).collect();
    periods.sort_unstable();
    periods.dedup();
    let periods = periods
        .iter()
        .map(|p| p.to_string())
        .collect::<Vec<_>>()
        .join(", ");
    let sliding: Vec<f64> = points
        .iter()
        .filter(|p| p.class == MotionClass::Sliding)
        .map(|p| p.params.beta)
        .collect();
    let lowest = sliding.iter().copied().fold(f64::INFINITY, f64::min);
    report.summary.insert(
        "belt_forced_map".into(),
        json!({
            "zeta": zeta, "mu_s": mu_s, "vb": vb, "grid": [n, n],
            "classes": present.iter().map(|c| json!({"class": c.label(), "points": count(*c)})).collect::<Vec<_>>(),
        }),
    );
    report.sections.push(Section {
        id: "belt-forced-map".into(),
        title: "A forced belt: the (w, β) map of motion classes".into(),
        caption: format!(
            "A Coulomb belt at vb = {vb} (ζ = {zeta}, μs = {mu_s}) driven by β cos(w τ), the \
             setting of Popp and Stelter (1990): each of the {n} × {n} points from rest to its \
             steady state by the exact solver (<code>stickslip phase-diagram --vb {vb}</code>). \
             The belt makes every motion asymmetric: the drive now competes with a steady \
             pull. Classes: {}; the periods found (in drive periods) are {periods}. {}",
            counts.join(", "),
            if sliding.is_empty() {
                "The block stops at every point.".to_string()
            } else {
                format!(
                    "The block never stops (sliding) at {} of the points, none of them below \
                     β = {}.",
                    sliding.len(),
                    sig(lowest, 3)
                )
            },
        ),
        figures: vec!["belt-forced-map".into()],
        data: vec!["belt-forced-map.csv".into()],
        tables: vec![],
    });
    Ok(())
}
