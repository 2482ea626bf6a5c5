//! The accuracy table: at the key points of each figure, the paper's series value, the exact
//! value and the simulated value, with relative errors.

use super::super::report::{sig, Report, Section};
use super::super::Context;
use super::common::{num, paper_at, steady_pwl};
use anyhow::Result;
use serde_json::json;
use stickslip::steady::MotionClass;
use stickslip::theory::{
    paper_boundary, stick_slip_boundary, PaperHarmonic, PaperSeries, PeriodicSolution,
};
use stickslip::SteadyOptions;

/// The columns of accuracy.csv, the report's own (the page's table spells them for reading).
pub const ACCURACY_COLUMNS: [&str; 7] = [
    "figure",
    "quantity",
    "paper",
    "exact",
    "simulated",
    "paper_rel_error",
    "exact_rel_error",
];

struct Row {
    figure: &'static str,
    quantity: String,
    paper: Option<f64>,
    exact: Option<f64>,
    simulated: f64,
}

fn relative(x: Option<f64>, reference: f64) -> Option<f64> {
    x.map(|x| (x - reference) / reference)
}

/// The smallest β at which the steady motion from rest slides, by bisection on simulations.
fn simulated_boundary(ctx: &Context, w: f64, mut lo: f64, mut hi: f64) -> Result<f64> {
    let options = SteadyOptions::default().with_spectrum(false);
    let slides = |beta: f64| -> Result<bool> {
        Ok(paper_at(ctx, w, beta)?.steady_with(&options)?.class == MotionClass::Sliding)
    };
    if slides(lo)? || !slides(hi)? {
        anyhow::bail!("the simulated boundary at w = {w} is not bracketed by [{lo}, {hi}]");
    }
    while hi - lo > 1e-7 * hi {
        let mid = 0.5 * (lo + hi);
        if slides(mid)? {
            hi = mid;
        } else {
            lo = mid;
        }
    }
    Ok(hi)
}

/// The accuracy table.
pub fn accuracy(report: &mut Report, ctx: &Context) -> Result<()> {
    let zeta = ctx.scales.zeta();
    let ut = ctx.diode.turn_on;
    let mut rows = Vec::new();
    let amplitude_points: [(&str, f64, f64); 11] = [
        ("fig3", 0.29, 2.14),
        ("fig3", 0.95, 2.14),
        ("fig3", 1.43, 2.14),
        ("fig3", 0.29, 1.07),
        ("fig5a", 0.5, 7.1),
        ("fig5a", 0.9, 7.1),
        ("fig5a", 1.0, 7.1),
        ("fig5a", 1.5, 7.1),
        ("fig5b", 0.33, 5.0),
        ("fig5b", 0.33, 15.0),
        ("fig4", 1.1, 3.61),
    ];
    for (figure, w, beta) in amplitude_points {
        let (params, s) = steady_pwl(ctx, w, beta)?;
        let exact = PeriodicSolution::new(&params).ok();
        let sim1 = s.harmonic(1).unwrap_or(f64::NAN);
        rows.push(Row {
            figure,
            quantity: format!("A1 (V) at Ω/ω0 = {w}, β = {beta} [{}]", s.class.label()),
            paper: PaperSeries::new(zeta, w, beta).ok().map(|p| p.a1 * ut),
            exact: exact.as_ref().map(|e| e.a1() * ut),
            simulated: sim1 * ut,
        });
        rows.push(Row {
            figure,
            quantity: format!("A3 (V) at Ω/ω0 = {w}, β = {beta}"),
            paper: PaperHarmonic::new(zeta, w, 3)
                .ok()
                .map(|h| h.amplitude.abs() * ut),
            exact: exact.as_ref().map(|e| e.harmonic(3).amplitude * ut),
            simulated: s.harmonic(3).unwrap_or(f64::NAN) * ut,
        });
    }
    for (w, beta) in [(0.9, 14.3), (1.0, 3.61), (0.9, 1.43)] {
        let (params, s) = steady_pwl(ctx, w, beta)?;
        rows.push(Row {
            figure: "fig4",
            quantity: format!("G1 = A1/β at Ω/ω0 = {w}, β = {beta} [{}]", s.class.label()),
            paper: PaperSeries::new(zeta, w, beta).ok().map(|p| p.gain1()),
            exact: PeriodicSolution::new(&params).ok().map(|e| e.gain1()),
            simulated: s.harmonic(1).unwrap_or(f64::NAN) / beta,
        });
    }
    for w in [0.5, 0.7, 0.9, 1.43, 2.0] {
        let exact = stick_slip_boundary(zeta, w, 1.0).ok().map(|b| b.beta_c);
        let (lo, hi) = match exact {
            Some(b) => (0.8 * b, 1.25 * b),
            None => (1.0, 10.0),
        };
        rows.push(Row {
            figure: "fig7",
            quantity: format!("β_c at Ω/ω0 = {w}"),
            paper: paper_boundary(zeta, w).ok(),
            exact,
            simulated: simulated_boundary(ctx, w, lo, hi)?,
        });
    }

    let header = [
        "figure",
        "quantity",
        "paper (series)",
        "exact",
        "simulated",
        "paper error",
        "exact error",
    ];
    let fmt_opt = |x: Option<f64>| x.map_or("—".to_string(), |v| sig(v, 6));
    let fmt_rel = |x: Option<f64>| x.map_or("—".to_string(), |v| format!("{:+.2e}", v));
    let table: Vec<Vec<String>> = rows
        .iter()
        .map(|r| {
            vec![
                r.figure.to_string(),
                r.quantity.clone(),
                fmt_opt(r.paper),
                fmt_opt(r.exact),
                sig(r.simulated, 6),
                fmt_rel(relative(r.paper, r.simulated)),
                fmt_rel(relative(r.exact, r.simulated)),
            ]
        })
        .collect();
    let csv: Vec<Vec<String>> = rows
        .iter()
        .map(|r| {
            let o = |x: Option<f64>| x.map(num).unwrap_or_default();
            vec![
                r.figure.to_string(),
                r.quantity.clone(),
                o(r.paper),
                o(r.exact),
                num(r.simulated),
                o(relative(r.paper, r.simulated)),
                o(relative(r.exact, r.simulated)),
            ]
        })
        .collect();
    report.csv("accuracy.csv", &ACCURACY_COLUMNS, &csv)?;
    let worst_exact = rows
        .iter()
        .filter_map(|r| relative(r.exact, r.simulated).map(f64::abs))
        .fold(0.0, f64::max);
    report.summary.insert(
        "accuracy".into(),
        json!({
            "max_exact_vs_simulated": worst_exact,
            "rows": rows.iter().map(|r| json!({
                "figure": r.figure, "quantity": r.quantity, "paper": r.paper,
                "exact": r.exact, "simulated": r.simulated,
            })).collect::<Vec<_>>(),
        }),
    );
    report.sections.push(Section {
        id: "accuracy".into(),
        title: "Accuracy — the paper's series, the exact solution and the simulation".into(),
        caption: format!(
            "At the key points of the figures: the paper's series value (its eqs. 11 and 13), \
             the exact value (the symmetric sliding orbit, where it exists, and the exact \
             boundary), and the value simulated by the exact solver (the steady state from \
             rest; for β_c the smallest β whose steady motion from rest slides, by bisection to \
             1e-7). Errors are relative to the simulation. Where the exact orbit exists it \
             agrees with the simulation to {worst_exact:.1e} (the β_c rows are limited by the \
             bisection). The paper's A3 is exact whenever the motion slides (its friction \
             force is then exactly a square wave); its A1 and β_c are approximations, off by \
             tens of percent near the boundary and at low frequency; below the boundary the \
             oscillator sticks and neither formula holds (—: no value)."
        ),
        figures: vec![],
        data: vec!["accuracy.csv".into()],
        tables: vec![(header.iter().map(|h| h.to_string()).collect(), table)],
    });
    Ok(())
}
