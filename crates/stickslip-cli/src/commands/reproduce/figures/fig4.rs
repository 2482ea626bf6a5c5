//! Fig. 4: the gain of the fundamental G1 = A1/β against frequency at three drive amplitudes.

use super::super::report::{Report, Section};
use super::super::Context;
use super::common::{beta_color, sweep_pwl};
use super::theory_curves::{style_legend, INK};
use crate::plot::{Figure, Legend, Panel, Quantity, Series, Style};
use anyhow::Result;
use serde_json::json;
use stickslip::report::SweepReport;
use stickslip::scan::{SweepDirection, SweepLeg};
use stickslip::Parameter;

/// The paper's three drive amplitudes.
pub const BETAS: [f64; 3] = [1.43, 3.61, 14.3];

/// Fig. 4: the gain of the fundamental G1 = A1/β against Ω/ω0; simulated up and down sweeps.
pub fn fig4(report: &mut Report, ctx: &Context) -> Result<()> {
    let steps = if ctx.quick { 25 } else { 73 };
    let mut series = Vec::new();
    let (mut up_series, mut down_series) = (Vec::new(), Vec::new());
    let mut sweeps = Vec::new();
    let mut peaks = Vec::new();
    for &beta in &BETAS {
        let points = sweep_pwl(ctx, Parameter::W, beta, 0.2, 2.0, steps, true)?;
        let mut up = Vec::new();
        let mut down = Vec::new();
        for p in &points {
            // G1 = A1/β, the definition of the paper's formula and of the exact curve.
            let g = p.steady.harmonic(1).unwrap_or(f64::NAN) / beta;
            match p.leg {
                SweepLeg::Up => up.push((p.params.w, g)),
                SweepLeg::Down => down.push((p.params.w, g)),
            }
        }
        sweeps.push(SweepReport::new(
            &ctx.paper,
            Parameter::W,
            SweepDirection::Both,
            &points,
        ));
        let peak = up
            .iter()
            .chain(&down)
            .fold((0.0, 0.0), |m, &(w, g)| if g > m.1 { (w, g) } else { m });
        peaks.push(json!({"beta": beta, "w": peak.0, "gain1": peak.1}));
        // Down squares first and larger: the up dots show inside them.
        down_series.push(
            Quantity::SweepDown
                .series("", down)
                .colored(beta_color(beta)),
        );
        up_series.push(Quantity::SweepUp.series("", up).colored(beta_color(beta)));
    }
    series.extend(down_series);
    series.extend(up_series);
    // The curves over the markers: a short exact segment stays visible.
    series.extend(super::theory_curves::gain_curves(ctx, &BETAS)?);
    // The legend: one colour per β, one symbol per sweep direction, one line per theory.
    for &beta in &BETAS {
        series.push(Series::new(
            format!("β = {beta}"),
            vec![],
            beta_color(beta),
            Style::Bars(1.0),
        ));
    }
    series.push(Quantity::SweepUp.series("sweep up", vec![]).colored(INK));
    series.push(
        Quantity::SweepDown
            .series("sweep down", vec![])
            .colored(INK),
    );
    let legend = style_legend(&series);
    series.extend(legend);
    let panel = Panel {
        title: "Fig. 4: resonance of the gain of the fundamental G1 = A1/β".into(),
        x_label: "Ω/ω0".into(),
        y_label: "G1 = A1/β".into(),
        series,
        legend: Some(Legend::Best),
        x_range: Some((0.2, 2.0)),
        ..Default::default()
    };
    report.figure("fig4", &Figure::single(panel, (900, 600)))?;
    // The CSV of `stickslip sweep --out`, the three sweeps one after the other.
    report.tables("fig4.csv", &[], sweeps.iter().map(|s| (Vec::new(), s)))?;
    report.summary.insert("fig4_peaks".into(), json!(peaks));
    report.sections.push(Section {
        id: "fig4".into(),
        title: "Fig. 4 — resonance curves".into(),
        caption: format!(
            "The gain of the fundamental G1 = A1/β against Ω/ω0 at β = 1.43, 3.61 and 14.3: \
             simulated steady states of the exact solver, sweeping the frequency up (dots) and \
             then down (squares), each step starting from where the last ended. {}",
            super::theory_curves::GAIN_NOTE
        ),
        figures: vec!["fig4".into()],
        data: vec!["fig4.csv".into()],
        tables: vec![],
    });
    Ok(())
}
