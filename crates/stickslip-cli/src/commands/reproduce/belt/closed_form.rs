//! The undamped Coulomb belt's stick-slip cycle in closed form against the exact solver's.

use super::super::report::{Report, Section};
use super::super::Context;
use super::belt;
use anyhow::{anyhow, Result};
use serde_json::json;
use stickslip::experiment::Key;
use stickslip::friction::FrictionLaw;
use stickslip::theory::CoulombBeltCycle;
use stickslip::{Parameter, State};

/// The columns of belt-closed-form.csv after μs and vb.
pub const CLOSED_FORM_COLUMNS: [&str; 4] = ["quantity", "closed_form", "exact", "difference"];

/// The (μs, vb) of the table.
const POINTS: [(f64, f64); 6] = [
    (1.5, 0.5),
    (2.0, 0.1),
    (1.2, 1.3),
    (3.0, 2.0),
    (1.05, 0.02),
    (1.5, -0.7),
];

/// The table of differences.
pub fn closed_form(report: &mut Report, _ctx: &Context) -> Result<()> {
    let mut rows = Vec::new();
    let mut worst = 0.0f64;
    for (mu_s, vb) in POINTS {
        let c = CoulombBeltCycle::new(mu_s, vb)?;
        // From a stop on the belt: every stop ends at the release point of the cycle.
        let s = belt(0.0, mu_s, FrictionLaw::Coulomb, vb, State { y: 0.0, v: vb })?.steady()?;
        let cycle = s
            .self_excited
            .ok_or_else(|| anyhow!("μs = {mu_s}, vb = {vb}: not a self-excited answer"))?;
        let period = cycle
            .period
            .ok_or_else(|| anyhow!("μs = {mu_s}, vb = {vb}: no cycle found"))?;
        for (quantity, closed, exact) in [
            ("y_max", c.y_max, s.y_max),
            ("y_min", c.y_min, s.y_min),
            ("cycle_period_tau", c.period, period),
            ("stick_fraction", c.stick_fraction, cycle.stick_fraction),
        ] {
            worst = worst.max((exact - closed).abs());
            rows.push((mu_s, vb, quantity, closed, exact));
        }
    }
    let mut header = vec![Key::MuS.name(), Parameter::Vb.label()];
    header.extend(CLOSED_FORM_COLUMNS);
    let csv: Vec<Vec<String>> = rows
        .iter()
        .map(|&(mu_s, vb, q, closed, exact)| {
            vec![
                mu_s.to_string(),
                vb.to_string(),
                q.to_string(),
                closed.to_string(),
                exact.to_string(),
                (exact - closed).to_string(),
            ]
        })
        .collect();
    report.csv("belt-closed-form.csv", &header, &csv)?;
    let shown: Vec<Vec<String>> = rows
        .iter()
        .map(|&(mu_s, vb, q, closed, exact)| {
            vec![
                mu_s.to_string(),
                vb.to_string(),
                q.to_string(),
                format!("{closed:.15}"),
                format!("{exact:.15}"),
                format!("{:.1e}", exact - closed),
            ]
        })
        .collect();
    report.summary.insert(
        "belt_closed_form".into(),
        json!({ "points": POINTS.len(), "largest_difference": worst }),
    );
    report.sections.push(Section {
        id: "belt-closed-form".into(),
        title: "The undamped Coulomb belt: closed form against the exact solver".into(),
        caption: format!(
            "Without damping the Coulomb belt's stick-slip cycle is a circle about y = 1 \
             joined to a stop: slipping behind the belt, y'' + y = 1 with (y − 1)² + y'² = \
             (μs − 1)² + vb², from the release at y = μs to the stop at y = 2 − μs, then carried \
             back at the belt's speed (<code>stickslip::theory::CoulombBeltCycle</code>): y_max \
             = 1 + R, y_min = 1 − R, T = π + 2 atan2(vb, μs − 1) + 2(μs − 1)/vb. The exact \
             solver's steady state from a stop on the belt (<code>stickslip steady --vb</code>, \
             the cycle's period found, not given) at {} pairs (μs, vb): the largest difference \
             of the {} quantities below is {worst:.1e} (the test <code>tests/belt.rs</code> holds it to \
             10⁻¹²). A belt moving backwards gives the mirror image.",
            POINTS.len(),
            rows.len(),
        ),
        figures: vec![],
        data: vec!["belt-closed-form.csv".into()],
        tables: vec![(
            [
                "μs",
                "vb",
                "quantity",
                "closed form",
                "exact solver",
                "difference",
            ]
            .iter()
            .map(|x| x.to_string())
            .collect(),
            shown,
        )],
    });
    Ok(())
}
