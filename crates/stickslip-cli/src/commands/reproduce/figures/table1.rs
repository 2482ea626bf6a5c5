//! Table 1: the correspondence table, with the numbers of the experiment.

use super::super::report::{sig, Report, Section};
use super::super::Context;
use anyhow::Result;
use serde_json::json;

/// The columns of table1.csv (and of the page's second table), the report's own.
pub const TABLE1_COLUMNS: [&str; 4] = ["quantity", "stickslip", "unit", "paper"];

/// Table 1 with α, ω0, ζ, Q and f0 of the paper's circuit.
pub fn table1(report: &mut Report, ctx: &Context) -> Result<()> {
    let s = ctx.scales;
    let c = ctx.circuit;
    let rows = vec![
        vec![
            "ω0 = 1/√(LC)".into(),
            sig(s.omega0, 6),
            "rad/s".into(),
            "65938.0".into(),
        ],
        vec!["f0 = ω0/2π".into(), sig(s.f0(), 7), "Hz".into(), "—".into()],
        vec![
            "α = (R + R_D)/L".into(),
            sig(s.alpha, 5),
            "1/s".into(),
            "6173.9".into(),
        ],
        vec![
            "ζ = α/(2ω0)".into(),
            sig(s.zeta(), 6),
            "".into(),
            "—".into(),
        ],
        vec![
            "Q = ω0/α".into(),
            sig(s.quality_factor(), 5),
            "".into(),
            "—".into(),
        ],
        vec![
            "√(L/C)".into(),
            sig(c.impedance(), 5),
            "Ω".into(),
            "—".into(),
        ],
        vec![
            "U_t (β = U/U_t)".into(),
            sig(ctx.diode.turn_on, 2),
            "V".into(),
            "0.7".into(),
        ],
    ];
    let header = TABLE1_COLUMNS;
    report.csv("table1.csv", &header, &rows)?;
    let correspondence = vec![
        vec![
            "x (y = ω0²x)".into(),
            "r/(F0/m)".into(),
            "q/(U_t/L)".into(),
            "y = u_C/U_t".into(),
        ],
        vec!["ω0²".into(), "k/m".into(), "1/(LC)".into(), "1".into()],
        vec!["α".into(), "γ/m".into(), "(R+R_D)/L".into(), "2ζ".into()],
        vec!["β".into(), "F/F0".into(), "U/U_t".into(), "β".into()],
        vec![
            "G".into(),
            "ω0²r0/(F/m)".into(),
            "U_C0/U".into(),
            "(y_max − y_min)/(2β)".into(),
        ],
    ];
    report.sections.push(Section {
        id: "table1".into(),
        title: "Table 1 — correspondence and the numbers of the experiment".into(),
        caption: format!(
            "The paper's Eq. (6) variables against the mechanical model (Eq. 3) and the circuit \
             (Eq. 5), with our dimensionless form (time τ = ω0·t). For the experiment L = 11.5 mH, \
             C = 0.02 µF and R + R_D = 71 Ω give α = {:.1} s⁻¹ and ω0 = {:.1} rad/s, the \
             paper's printed values; ζ = {:.6} and Q = {:.3} follow.",
            s.alpha,
            s.omega0,
            s.zeta(),
            s.quality_factor()
        ),
        figures: vec![],
        data: vec!["table1.csv".into()],
        tables: vec![
            (
                ["paper (Eq. 6)", "mechanics", "circuit", "stickslip"]
                    .iter()
                    .map(|x| x.to_string())
                    .collect(),
                correspondence,
            ),
            (header.iter().map(|x| x.to_string()).collect(), rows),
        ],
    });
    report.summary.insert(
        "table1".into(),
        json!({
            "alpha": s.alpha,
            "omega0": s.omega0,
            "zeta": s.zeta(),
            "Q": s.quality_factor(),
            "f0": s.f0(),
        }),
    );
    Ok(())
}
