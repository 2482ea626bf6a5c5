//! Fig. 7: stick-slip phase diagrams over the paper's range.

use super::super::report::{Report, Section};
use super::super::Context;
use super::common::{num, paper_params};
use crate::plot::{Cell, Figure, Legend, Panel};
use anyhow::Result;
use plotters::style::RGBColor;
use serde_json::json;
use stickslip::steady::{
    exact_solver, phase_diagram, MotionClass, ParameterRange, PhaseDiagramPoint,
};
use stickslip::{State, SteadyOptions};

/// Colour of each motion class in the maps.
pub fn class_color(class: MotionClass) -> RGBColor {
    match class {
        MotionClass::Sliding => RGBColor(235, 235, 235),
        MotionClass::PeriodicStick => RGBColor(0, 114, 178),
        MotionClass::NonperiodicStick => RGBColor(213, 94, 0),
        MotionClass::Static => RGBColor(0, 158, 115),
    }
}

/// Cells and legend of a map.
fn map_panel(
    title: &str,
    points: &[PhaseDiagramPoint],
    w: &ParameterRange,
    beta: &ParameterRange,
) -> Panel {
    let (dw, db) = (0.5 * w.spacing(), 0.5 * beta.spacing());
    let cells = points
        .iter()
        .map(|p| Cell {
            x: (p.w - dw, p.w + dw),
            y: (p.beta - db, p.beta + db),
            color: class_color(p.class),
        })
        .collect();
    let mut present: Vec<MotionClass> = points.iter().map(|p| p.class).collect();
    present.sort_by_key(|c| c.label());
    present.dedup();
    Panel {
        title: title.into(),
        x_label: "Ω/ω0".into(),
        y_label: "β = U/U_t".into(),
        cells,
        cell_legend: present
            .into_iter()
            .map(|c| (c.label().to_string(), class_color(c)))
            .collect(),
        x_range: Some((w.from() - dw, w.to() + dw)),
        y_range: Some((beta.from() - db, beta.to() + db)),
        legend: Some(Legend::UpperRight),
        ..Default::default()
    }
}

/// Fig. 7 (a): the PWL model's map from rest.
pub fn fig7(report: &mut Report, ctx: &Context) -> Result<()> {
    let n = if ctx.quick { 60 } else { 200 };
    let w = ParameterRange::new("w", 0.1, 2.5, n)?;
    let beta = ParameterRange::new("beta", 0.5, 4.0, n)?;
    let base = paper_params(ctx, 1.0, 1.0)?;
    let started = std::time::Instant::now();
    let points = phase_diagram(
        &exact_solver,
        base,
        State::default(),
        &w,
        &beta,
        &SteadyOptions::default(),
        &|| !crate::output::interrupted(),
    )?;
    let seconds = started.elapsed().as_secs_f64();
    let mut panel = map_panel("(a) PWL diodes (exact solver)", &points, &w, &beta);
    panel
        .series
        .extend(super::theory_curves::boundary_curves(ctx, 0.1, 2.5)?);
    report.figure(
        "fig7",
        &Figure {
            panels: vec![panel],
            columns: 1,
            panel_size: (760, 600),
        },
    )?;
    let rows: Vec<Vec<String>> = points
        .iter()
        .map(|p| {
            vec![
                num(p.w),
                num(p.beta),
                p.class.label().into(),
                p.period.map(|x| x.to_string()).unwrap_or_default(),
                num(p.stops_per_period),
                num(p.gain),
            ]
        })
        .collect();
    report.csv(
        "fig7a.csv",
        &["w", "beta", "class", "period", "stops_per_cycle", "gain"],
        &rows,
    )?;
    let count = |c: MotionClass| points.iter().filter(|p| p.class == c).count();
    report.summary.insert(
        "fig7a".into(),
        json!({
            "grid": [n, n],
            "seconds": seconds,
            "sliding": count(MotionClass::Sliding),
            "periodic_stick": count(MotionClass::PeriodicStick),
            "nonperiodic_stick": count(MotionClass::NonperiodicStick),
            "static": count(MotionClass::Static),
        }),
    );
    report.sections.push(Section {
        id: "fig7".into(),
        title: "Fig. 7 — stick-slip phase diagrams".into(),
        caption: format!(
            "Motion class of the steady state reached from rest on a {n} × {n} grid over the \
             paper's range (Ω/ω0 from 0.1 to 2.5, β from 0.5 to 4), (a) with PWL diodes by the \
             exact solver ({} sliding, {} periodic stick, {} non-periodic stick, {} static; \
             {seconds:.1} s). {}",
            count(MotionClass::Sliding),
            count(MotionClass::PeriodicStick),
            count(MotionClass::NonperiodicStick),
            count(MotionClass::Static),
            super::theory_curves::BOUNDARY_NOTE
        ),
        figures: vec!["fig7".into()],
        data: vec!["fig7a.csv".into()],
        tables: vec![],
    });
    Ok(())
}
