//! Fig. 1: (a) friction force against velocity; (b) I-V curve of the anti-parallel diode pair.

use super::super::report::{Report, Section};
use super::super::Context;
use crate::plot::{Figure, Legend, Panel, Series, Style, PALETTE};
use anyhow::Result;
use stickslip::shockley::DiodePair;

/// The columns of fig1a.csv, the report's own (the friction law, no library result).
pub const FRICTION_COLUMNS: &[&str] = &["velocity", "friction"];

/// The columns of fig1b.csv, the report's own (the diode pairs' I-V curves).
pub const DIODE_COLUMNS: [&str; 3] = ["model", "U_V", "I_A"];

/// Fig. 1 (a) the Coulomb friction law with its static band; (b) the diode pair's I-V curve.
pub fn fig1(report: &mut Report, ctx: &Context) -> Result<()> {
    // (a) f(v) = −F0 sgn(v) − γ v for v ≠ 0 and any value in [−F0, F0] at v = 0 (in units of F0,
    // velocity in units of F0/(m ω0), with the paper's ζ).
    let zeta = ctx.scales.zeta();
    let mut friction = Vec::new();
    for k in 0..=100 {
        let v = -2.0 + 2.0 * k as f64 / 100.0;
        friction.push((v, 1.0 - 2.0 * zeta * v));
    }
    friction.push((0.0, -1.0));
    for k in 0..=100 {
        let v = 2.0 * k as f64 / 100.0;
        friction.push((v, -1.0 - 2.0 * zeta * v));
    }
    let friction_panel = Panel {
        title: "(a) friction force".into(),
        x_label: "velocity ṙ·k/(F0 ω0)".into(),
        y_label: "friction f/F0".into(),
        series: vec![Series::new(
            "−sgn(ṙ) − 2ζ ṙ, any value in [−1, 1] at ṙ = 0",
            friction.clone(),
            PALETTE[0],
            Style::Line(2),
        )],
        legend: Some(Legend::UpperRight),
        y_range: Some((-1.6, 1.6)),
        ..Default::default()
    };

    // (b) PWL pair: I = 0 for |U| < U_t, (|U| − U_t)/R_D beyond, with the sign of U.
    let d = ctx.diode;
    let pwl: Vec<(f64, f64)> = (0..=400)
        .map(|k| {
            // Up to 50 mA either way, inside the axes.
            let u_max = d.turn_on + 0.05 * d.resistance;
            let u = u_max * (-1.0 + 2.0 * k as f64 / 400.0);
            let i = if u.abs() <= d.turn_on {
                0.0
            } else {
                u.signum() * (u.abs() - d.turn_on) / d.resistance
            };
            (u, 1e3 * i)
        })
        .collect();
    // Shockley pair: U(I) = n V_T asinh(I/2I_s) + R_s I, plotted parametrically in I.
    let pair = DiodePair::one_n4148();
    let shockley: Vec<(f64, f64)> = (0..=400)
        .map(|k| {
            let i = 0.05 * (-1.0 + 2.0 * k as f64 / 400.0);
            (pair.voltage(i), 1e3 * i)
        })
        .collect();
    let diode_panel = Panel {
        title: "(b) anti-parallel diode pair".into(),
        x_label: "voltage U (V)".into(),
        y_label: "current I (mA)".into(),
        series: vec![
            Series::new(
                format!("PWL: U_t = {} V, R_D = {} Ω", d.turn_on, d.resistance),
                pwl.clone(),
                PALETTE[0],
                Style::Line(2),
            ),
            Series::new(
                "Shockley 1N4148 pair, 27 °C",
                shockley.clone(),
                PALETTE[1],
                Style::Line(2),
            ),
        ],
        legend: Some(Legend::UpperLeft),
        y_range: Some((-60.0, 60.0)),
        ..Default::default()
    };
    let figure = Figure {
        panels: vec![friction_panel, diode_panel],
        columns: 2,
        panel_size: (560, 420),
    };
    report.figure("fig1", &figure)?;
    let rows: Vec<Vec<String>> = friction
        .iter()
        .map(|(v, f)| vec![format!("{v}"), format!("{f}")])
        .collect();
    report.csv("fig1a.csv", FRICTION_COLUMNS, &rows)?;
    let rows: Vec<Vec<String>> = pwl
        .iter()
        .map(|(u, i)| vec!["pwl".into(), format!("{u}"), format!("{}", i / 1e3)])
        .chain(
            shockley
                .iter()
                .map(|(u, i)| vec!["shockley".into(), format!("{u}"), format!("{}", i / 1e3)]),
        )
        .collect();
    report.csv("fig1b.csv", &DIODE_COLUMNS, &rows)?;
    report.sections.push(Section {
        id: "fig1".into(),
        title: "Fig. 1 — friction law and diode I-V curve".into(),
        caption: "(a) The friction force against velocity: kinetic friction of magnitude F0 \
                  opposing the motion plus the viscous term (here 2ζ = 0.0936 of the paper's \
                  circuit); at zero velocity static friction takes any value up to F0. (b) The \
                  current through the anti-parallel pair against its voltage in the PWL model \
                  (an ideal diode, U_t and R_D in series in each direction), the circuit's image \
                  of (a), and the Shockley law of two 1N4148 diodes, U = n V_T asinh(I/2I_s) + \
                  R_s I with I_s = 4.352 nA, n = 1.906, R_s = 0.6458 Ω at 27 °C: it conducts \
                  well below 0.7 V, with no sharp knee."
            .into(),
        figures: vec!["fig1".into()],
        data: vec!["fig1a.csv".into(), "fig1b.csv".into()],
        tables: vec![],
    });
    Ok(())
}
