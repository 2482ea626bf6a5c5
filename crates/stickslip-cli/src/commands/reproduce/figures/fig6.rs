//! Fig. 6: the four types of motion.

use super::super::report::{Report, Samples, Section};
use super::super::Context;
use super::common::{beta_color, class_title, num, paper_at, steady_pwl};
use crate::plot::{Figure, Legend, Panel, Quantity};
use anyhow::Result;
use serde_json::json;
use stickslip::experiment::Key;
use stickslip::solver::{grid, sample_at};
use stickslip::EventKind;

/// The paper's four points and the class it gives each.
pub const POINTS: [(f64, f64, &str); 4] = [
    (0.9, 1.6, "sliding"),
    (0.6, 1.2, "periodic-stick"),
    (0.7, 1.2, "nonperiodic-stick"),
    (0.7, 1.0, "static"),
];

/// Fig. 6 (a)–(d): traces from rest at the paper's four points, titled with our class.
pub fn fig6(report: &mut Report, ctx: &Context) -> Result<()> {
    let ut = ctx.diode.turn_on;
    let ms = 1e3 / ctx.scales.omega0;
    let mut panels = Vec::new();
    let mut traces = Vec::new();
    let mut summary = Vec::new();
    let mut differ = Vec::new();
    for (i, &(w, beta, paper_class)) in POINTS.iter().enumerate() {
        let (params, s) = steady_pwl(ctx, w, beta)?;
        let periods = 12.0;
        let mut solver = paper_at(ctx, w, beta)?.solver()?;
        let times = grid(
            0.0,
            periods * params.drive_period(),
            (periods * 200.0) as usize,
        );
        let mut stops = Vec::new();
        let samples = sample_at(solver.as_mut(), &times, |e| {
            if e.kind == EventKind::Stick {
                stops.push((e.tau * ms, e.y * ut));
            }
        })?;
        let uc: Vec<(f64, f64)> = samples.iter().map(|p| (p.tau * ms, p.y * ut)).collect();
        let drive: Vec<(f64, f64)> = samples
            .iter()
            .map(|p| (p.tau * ms, params.drive(p.tau) * ut))
            .collect();
        let mut trace = Samples::new(ctx.paper.units());
        for p in &samples {
            trace.push(p.tau, p, params.drive(p.tau));
        }
        traces.push((vec![num(w), num(beta)], trace));
        let class = s.class.label();
        if class != paper_class {
            differ.push(format!(
                "({w}, {beta}): paper {paper_class}, exact solver {class}"
            ));
        }
        let period = s
            .period
            .map(|p| format!(", period {p}"))
            .unwrap_or_default();
        panels.push(Panel {
            title: format!(
                "({}) Ω/ω0 = {w}, β = {beta}: {}{period}, {} stops/period",
                ["a", "b", "c", "d"][i],
                class_title(s.class),
                s.stops_per_period
            ),
            x_label: "t (ms)".into(),
            y_label: "voltage (V)".into(),
            series: vec![
                Quantity::Drive.series("U", drive),
                Quantity::Response
                    .series("u_C", uc)
                    .colored(beta_color(beta)),
                Quantity::Stops.series("stops", stops),
            ],
            legend: Some(Legend::UpperRight),
            ..Default::default()
        });
        summary.push(json!({
            "w": w, "beta": beta, "class": class, "paper_class": paper_class,
            "period": s.period, "stops_per_period": s.stops_per_period,
            "periods_to_settle": s.periods_to_settle, "gain": s.gain,
        }));
    }
    report.figure(
        "fig6",
        &Figure {
            panels,
            columns: 2,
            panel_size: (620, 340),
        },
    )?;
    // The CSV of `stickslip simulate --out` at each point, after its w and β.
    report.tables(
        "fig6.csv",
        &[Key::W.name(), Key::Beta.name()],
        traces.iter().map(|(point, t)| (point.clone(), t)),
    )?;
    report.summary.insert("fig6".into(), json!(summary));
    let difference = if differ.is_empty() {
        "The exact solver finds the class the paper gives at every point.".to_string()
    } else {
        format!(
            "Where the exact solver differs from the paper: {}. The paper says only that it \
             integrated with LSODA; our reading is that it integrated ẍ + αẋ + ω0²x + sgn(ẋ) = \
             β cos Ωt with no stick logic (it mentions none), and then at every stop the \
             velocity chatters around zero instead of resting there; the chattering makes a \
             motion that sticks look irregular. The exact solver stops the oscillator when \
             the net force is within the static friction and restarts it at the exact instant \
             the force leaves it, and its stroboscopic map repeats to 1e-10: the motion is \
             periodic.",
            differ.join("; ")
        )
    };
    report.sections.push(Section {
        id: "fig6".into(),
        title: "Fig. 6 — the four types of motion".into(),
        caption: format!(
            "Capacitor voltage u_C (coloured) and drive U (grey) from rest over 12 drive periods \
             at the paper's four points (PWL diodes, exact solver); dots mark where the motion \
             stops. Titles give the class of the steady state, decided from the exact event \
             log: sliding (no stop), periodic stick (periodic, with stops), non-periodic stick \
             (no period up to 16 drive periods within 5000 periods), static (amplitude below \
             β/100, the paper's rule: a static motion need not be at rest). \
             {difference}"
        ),
        figures: vec!["fig6".into()],
        data: vec!["fig6.csv".into()],
        tables: vec![],
    });
    Ok(())
}
