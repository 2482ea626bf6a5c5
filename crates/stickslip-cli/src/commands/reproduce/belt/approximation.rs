//! The cubic law's cycles to first order (after Thomsen & Fidlin 2003) against the exact
//! cycle over the belt speeds where steady sliding is unstable.

use super::super::report::{sig, Report, Section};
use super::super::Context;
use super::belt;
use crate::plot::{Figure, Legend, Panel, Series, Style};
use anyhow::Result;
use plotters::style::RGBColor;
use serde_json::json;
use stickslip::experiment::Key;
use stickslip::friction::FrictionLaw;
use stickslip::steady::MotionClass;
use stickslip::theory::{CubicBeltApproximation, CubicBeltMotion};
use stickslip::{Parameter, State};

/// The columns of belt-approximation.csv after ζ, k1, k3 and vb.
pub const APPROXIMATION_COLUMNS: [&str; 5] = [
    "approximation_motion",
    "class",
    "amplitude",
    "amplitude_approximation",
    "relative_error",
];

/// The laws compared (ζ, k1, k3), μs = 1, each in its colour: ε = k1 doubling.
const LAWS: [(f64, f64, f64, RGBColor); 3] = [
    (0.0, 0.05, 0.02, RGBColor(0, 158, 115)),
    (0.01, 0.1, 0.05, RGBColor(0, 114, 178)),
    (0.02, 0.2, 0.1, RGBColor(213, 94, 0)),
];

/// One exact cycle and the approximation's.
struct Row {
    law: (f64, f64, f64),
    vb: f64,
    approximation: CubicBeltApproximation,
    class: MotionClass,
    amplitude: f64,
}

impl Row {
    fn error(&self) -> f64 {
        (self.approximation.amplitude - self.amplitude) / self.amplitude
    }
}

/// The figure and its data.
pub fn approximation(report: &mut Report, ctx: &Context) -> Result<()> {
    let speeds = if ctx.quick { 6 } else { 12 };
    let started = std::time::Instant::now();
    let mut rows = Vec::new();
    for &(zeta, k1, k3, _) in &LAWS {
        let hopf = CubicBeltApproximation::new(zeta, 1.0, k1, k3, 1.0)?
            .vb_hopf
            .ok_or_else(|| anyhow::anyhow!("no self-excitation at k1 = {k1}"))?;
        for i in 1..=speeds {
            let vb = hopf * i as f64 / (speeds + 1) as f64;
            let law = FrictionLaw::Cubic { k1, k3 };
            // From a stop on the belt (released where the net force reaches μs).
            let s = belt(zeta, 1.0, law, vb, State { y: 0.0, v: vb })?.steady()?;
            rows.push(Row {
                law: (zeta, k1, k3),
                vb,
                approximation: CubicBeltApproximation::new(zeta, 1.0, k1, k3, vb)?,
                class: s.class,
                amplitude: 0.5 * (s.y_max - s.y_min),
            });
        }
    }
    eprintln!(
        "reproduce: {} cubic belts' cycles in {:.1} s",
        rows.len(),
        started.elapsed().as_secs_f64()
    );

    let mut amplitude = Vec::new();
    let mut error = vec![Series::new(
        "",
        vec![(0.0, 0.0), (1.0, 0.0)],
        RGBColor(150, 150, 150),
        Style::Dashed(1),
    )];
    let mut top = 0.0f64;
    for &(zeta, k1, k3, color) in &LAWS {
        let mine: Vec<&Row> = rows.iter().filter(|r| r.law == (zeta, k1, k3)).collect();
        let hopf = mine[0].approximation.vb_hopf.unwrap_or(1.0);
        top = top.max(hopf);
        // The approximation on a fine grid (it costs nothing), broken where its motion
        // changes (stick-slip to pure slip: the branches meet, but not with one slope).
        let mut line = Vec::new();
        let mut last = None;
        for j in 1..=400 {
            let vb = hopf * j as f64 / 400.0;
            let a = CubicBeltApproximation::new(zeta, 1.0, k1, k3, vb)?;
            if last.is_some_and(|m| m != a.motion) {
                line.push((f64::NAN, f64::NAN));
            }
            last = Some(a.motion);
            line.push((vb, a.amplitude));
        }
        let name = format!("k1 = {k1}, k3 = {k3}, ζ = {zeta}");
        amplitude.push(Series::new("", line, color, Style::Dashed(2)));
        amplitude.push(Series::new(
            "",
            mine.iter().map(|r| (r.vb, r.amplitude)).collect(),
            color,
            Style::Markers(4),
        ));
        error.push(Series::new(
            name,
            mine.iter().map(|r| (r.vb, r.error())).collect(),
            color,
            Style::Markers(4),
        ));
        error.push(Series::new(
            "",
            mine.iter().map(|r| (r.vb, r.error())).collect(),
            color,
            Style::Line(1),
        ));
    }
    for s in &mut error[..1] {
        s.points = vec![(0.0, 0.0), (1.05 * top, 0.0)];
    }
    report.figure(
        "belt-approximation",
        &Figure {
            panels: vec![
                Panel {
                    title: "(a) amplitude of the cubic belt's cycle, μs = 1".into(),
                    x_label: "belt speed vb".into(),
                    y_label: "amplitude (y_max − y_min)/2".into(),
                    series: amplitude,
                    // The colours are named in (b)'s legend; dashed and dots in the caption.
                    legend: None,
                    x_range: Some((0.0, 1.05 * top)),
                    ..Default::default()
                },
                Panel {
                    title: "(b) relative error of the approximation's amplitude".into(),
                    x_label: "belt speed vb".into(),
                    y_label: "(approximation − exact)/exact".into(),
                    series: error,
                    legend: Some(Legend::LowerRight),
                    x_range: Some((0.0, 1.05 * top)),
                    ..Default::default()
                },
            ],
            columns: 2,
            panel_size: (760, 520),
        },
    )?;

    let mut header = vec![
        Key::Zeta.name(),
        Key::K1.name(),
        Key::K3.name(),
        Parameter::Vb.label(),
    ];
    header.extend(APPROXIMATION_COLUMNS);
    let motion = |m: CubicBeltMotion| match m {
        CubicBeltMotion::StickSlip => MotionClass::StickSlipCycle.label(),
        CubicBeltMotion::PureSlip => MotionClass::PureSlipCycle.label(),
        CubicBeltMotion::SteadySliding => MotionClass::SteadySliding.label(),
    };
    let csv: Vec<Vec<String>> = rows
        .iter()
        .map(|r| {
            vec![
                r.law.0.to_string(),
                r.law.1.to_string(),
                r.law.2.to_string(),
                r.vb.to_string(),
                motion(r.approximation.motion).to_string(),
                r.class.label().to_string(),
                r.amplitude.to_string(),
                r.approximation.amplitude.to_string(),
                r.error().to_string(),
            ]
        })
        .collect();
    report.csv("belt-approximation.csv", &header, &csv)?;

    let agree = rows
        .iter()
        .filter(|r| motion(r.approximation.motion) == r.class.label())
        .count();
    let worst: Vec<(f64, f64)> = LAWS
        .iter()
        .map(|&(zeta, k1, k3, _)| {
            let e = rows
                .iter()
                .filter(|r| r.law == (zeta, k1, k3))
                .map(|r| r.error().abs())
                .fold(0.0, f64::max);
            (k1, e)
        })
        .collect();
    let worst_text = worst
        .iter()
        .map(|(k1, e)| format!("{} at k1 = {k1}", sig(100.0 * e, 2) + " %"))
        .collect::<Vec<_>>()
        .join(", ");
    let (first, last) = (worst[0], worst[worst.len() - 1]);
    let order = (last.1 / first.1).ln() / (last.0 / first.0).ln();
    let worst_law = LAWS[LAWS.len() - 1];
    let worst_at = rows
        .iter()
        .filter(|r| r.law == (worst_law.0, worst_law.1, worst_law.2))
        .max_by(|a, b| a.error().abs().total_cmp(&b.error().abs()))
        .ok_or_else(|| anyhow::anyhow!("no cycle"))?;
    report.summary.insert(
        "belt_approximation".into(),
        json!({
            "cycles": rows.len(),
            "motion_agrees": agree,
            "largest_relative_error": worst.iter().map(|(k1, e)| json!({"k1": k1, "error": e})).collect::<Vec<_>>(),
        }),
    );
    report.sections.push(Section {
        id: "belt-approximation".into(),
        title: "Thomsen & Fidlin's approximation against the exact cycle (cubic law)".into(),
        caption: format!(
            "The cubic law μ(s) = μs − k1 s + k3 s³ of Thomsen & Fidlin (2003) at μs = 1, for \
             three sizes of its fall. Their paper's formulas could not be consulted here: the \
             approximation drawn is derived in <code>stickslip::theory::belt</code> by the \
             method their abstract names, the slip phase to first order in k1, ζ and k3 vb² \
             matched to the stop. It gives a stick-slip cycle of amplitude vb (1 + π b/2), \
             b = k1 − 2ζ − (15/4) k3 vb², where b > 0, and the averaged pure-slip cycle of \
             amplitude 2 √((k1 − 2ζ − 3 k3 vb²)/(3 k3)) above that speed, up to the speed where \
             steady sliding turns stable (the right end of each curve). Dashed: the \
             approximation; dots: the exact cycle (<code>stickslip steady</code> with the cubic \
             law, from a stop on the belt) at {speeds} speeds below that end for each law. \
             The approximation names the motion the exact cycle has (stick-slip or pure slip) \
             at {agree} of the {} speeds. Its largest relative error in the amplitude is {} \
             (b): from the smallest fall to the largest it grows as k1 to the power {}, \
             beyond the first order the analysis keeps (its stop lasts √(2π b), of order \
             √k1). For k1 = {} the largest error is at vb = {}. The test \
             <code>tests/belt_theory.rs</code> holds these errors at their measured size.",
            rows.len(),
            worst_text,
            sig(order, 2),
            worst_law.1,
            sig(worst_at.vb, 2),
        ),
        figures: vec!["belt-approximation".into()],
        data: vec!["belt-approximation.csv".into()],
        tables: vec![],
    });
    Ok(())
}
