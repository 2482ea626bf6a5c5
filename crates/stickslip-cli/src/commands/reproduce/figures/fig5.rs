//! Fig. 5: the fundamental A1 and the third harmonic A3, against frequency and amplitude.

use super::super::report::{Report, Section};
use super::super::Context;
use super::common::sweep_pwl;
use super::theory_curves::{style_legend, INK};
use crate::plot::{Figure, Legend, Panel, Quantity, Series, Style};
use anyhow::Result;
use stickslip::report::SweepReport;
use stickslip::scan::{SweepDirection, SweepLeg, SweepPoint};
use stickslip::steady::MotionClass;
use stickslip::Parameter;

/// The column fig5.csv adds before the sweep's own: which parameter the row's sweep varies
/// (`w` for panel (a), `beta` for (b)).
pub const FIG5_LEADING: [&str; 1] = ["swept"];

/// Fig. 5 (a) A1, A3 against Ω/ω0 at β = 7.1; (b) against β at Ω/ω0 = 0.33.
pub fn fig5(report: &mut Report, ctx: &Context) -> Result<()> {
    let ut = ctx.diode.turn_on;
    let steps = if ctx.quick { 25 } else { 73 };
    let mut panels = Vec::new();
    let mut sweeps = Vec::new();
    // Panel (b): the values of β (up sweep) and how many of them stick.
    let (mut sticking, mut shown, mut exact_in_b) = (0, 0, false);
    for (parameter, fixed, from, to) in [
        (Parameter::W, 7.1, 0.2, 2.0),
        (Parameter::Beta, 0.33, 1.0, 15.0),
    ] {
        let points = sweep_pwl(ctx, parameter, fixed, from, to, steps, true)?;
        let x = |p: &SweepPoint| p.value;
        let mut a1 = Vec::new();
        let mut a3 = Vec::new();
        for p in points.iter().filter(|p| p.leg == SweepLeg::Up) {
            let h1 = p.steady.harmonic(1).unwrap_or(f64::NAN) * ut;
            let h3 = p.steady.harmonic(3).unwrap_or(f64::NAN) * ut;
            a1.push((x(p), h1));
            a3.push((x(p), h3));
            if parameter == Parameter::Beta {
                shown += 1;
                sticking += usize::from(p.steady.class != MotionClass::Sliding);
            }
        }
        sweeps.push((
            vec![parameter.label().to_string()],
            SweepReport::new(&ctx.paper, parameter, SweepDirection::Both, &points),
        ));
        let (c1, c3) = (Quantity::Harmonic1.color(), Quantity::Harmonic3.color());
        let mut series = vec![
            Quantity::Harmonic1.series("", a1),
            Quantity::Harmonic3.series("", a3),
        ];
        series.extend(super::theory_curves::harmonic_curves(
            ctx,
            parameter,
            fixed,
            from,
            to,
            [c1, c3],
        )?);
        // The legend: one colour per harmonic, one symbol or line per source.
        series.push(Series::new("A1", vec![], c1, Style::Bars(1.0)));
        series.push(Series::new("A3", vec![], c3, Style::Bars(1.0)));
        series.push(Series::new("simulated", vec![], INK, Style::Markers(3)));
        let legend = style_legend(&series);
        if parameter == Parameter::Beta {
            exact_in_b = legend.iter().any(|s| s.label == "exact");
        }
        series.extend(legend);
        let (title, x_label) = match parameter {
            Parameter::W => ("(a) β = 7.1".to_string(), "Ω/ω0"),
            _ => ("(b) Ω/ω0 = 0.33".to_string(), "β = U/U_t"),
        };
        panels.push(Panel {
            title,
            x_label: x_label.into(),
            y_label: "amplitude (V)".into(),
            series,
            legend: Some(Legend::Best),
            x_range: Some((from, to)),
            // Against w, A3 is two decades below A1 away from w = 1/3: a log axis shows both.
            y_log: parameter == Parameter::W,
            ..Default::default()
        });
    }
    report.figure(
        "fig5",
        &Figure {
            panels,
            columns: 2,
            panel_size: (620, 460),
        },
    )?;
    // The CSV of `stickslip sweep --out` (A1 and A3 in units of U_t), after the swept
    // parameter's name.
    report.tables(
        "fig5.csv",
        &FIG5_LEADING,
        sweeps.iter().map(|(swept, s)| (swept.clone(), s)),
    )?;
    report.sections.push(Section {
        id: "fig5".into(),
        title: "Fig. 5 — harmonic amplitudes".into(),
        caption: format!(
            "Amplitudes of the fundamental A1 and of the third harmonic A3 of u_C (volts), \
             (a) against Ω/ω0 at β = 7.1 (logarithmic axis) and (b) against β at Ω/ω0 = 0.33. Dots: simulated \
             steady states (exact solver, spectrum by FFT over whole periods, up sweep). {}",
            super::theory_curves::harmonic_note(exact_in_b, sticking, shown)
        ),
        figures: vec!["fig5".into()],
        data: vec!["fig5.csv".into()],
        tables: vec![],
    });
    Ok(())
}
