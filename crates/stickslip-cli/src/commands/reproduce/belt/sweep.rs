//! The classic picture: the amplitude of the self-excited motion against the belt speed,
//! swept up and down (hysteresis), for Coulomb's law and Stribeck's.

use super::super::report::{sig, Report, Section};
use super::super::Context;
use super::belt;
use crate::plot::{Figure, Legend, Panel, Quantity};
use anyhow::Result;
use serde_json::json;
use stickslip::experiment::Key;
use stickslip::friction::FrictionLaw;
use stickslip::scan::{Axis, ParameterRange, Sweep, SweepLeg, SweepPoint};
use stickslip::steady::MotionClass;
use stickslip::theory::SteadySliding;
use stickslip::{Parameter, State};

/// The columns of belt-sweep.csv after the law's name and the belt speed.
pub const BELT_SWEEP_COLUMNS: [&str; 7] = [
    "direction",
    "class",
    "amplitude",
    "y_max",
    "y_min",
    "cycle_period_tau",
    "stick_fraction",
];

/// Viscous damping of both sweeps.
const ZETA: f64 = 0.02;
/// Static friction level of both sweeps.
const MU_S: f64 = 1.5;
/// The Stribeck law of panel (b).
const STRIBECK: FrictionLaw = FrictionLaw::Stribeck {
    vs: 0.5,
    delta: 2.0,
    eta: 0.05,
};
/// The swept belt speeds.
const VB: (f64, f64) = (0.05, 3.0);

/// Amplitude (y_max − y_min)/2 of a step.
fn amplitude(p: &SweepPoint) -> f64 {
    0.5 * (p.steady.y_max - p.steady.y_min)
}

/// One law swept both ways from rest.
fn run(law: FrictionLaw, steps: usize) -> Result<Vec<SweepPoint>> {
    let vb = ParameterRange::new("vb", VB.0, VB.1, steps)?;
    let experiment = belt(ZETA, MU_S, law, VB.0, State::default())?;
    Ok(Sweep::new(&experiment, Axis::range(Parameter::Vb, &vb)?)?
        .run(&|_: usize, _: usize| !crate::output::interrupted())?)
}

/// The speeds of a sweep's leg where the class changes: (from, to, vb before, vb after).
fn jumps(points: &[SweepPoint], leg: SweepLeg) -> Vec<(MotionClass, MotionClass, f64, f64)> {
    let leg: Vec<&SweepPoint> = points.iter().filter(|p| p.leg == leg).collect();
    leg.windows(2)
        .filter(|w| w[0].steady.class != w[1].steady.class)
        .map(|w| (w[0].steady.class, w[1].steady.class, w[0].value, w[1].value))
        .collect()
}

fn describe(points: &[SweepPoint], leg: SweepLeg) -> String {
    let list = jumps(points, leg);
    if list.is_empty() {
        let class = points
            .iter()
            .find(|p| p.leg == leg)
            .map_or("—", |p| p.steady.class.label());
        return format!("stays {class}");
    }
    list.iter()
        .map(|(a, b, x, y)| {
            format!(
                "goes from {} to {} between vb = {} and {}",
                a.label(),
                b.label(),
                sig(*x, 3),
                sig(*y, 3)
            )
        })
        .collect::<Vec<_>>()
        .join(", then ")
}

/// The amplitude against vb, Coulomb (a) and Stribeck (b), both directions.
pub fn belt_sweep(report: &mut Report, ctx: &Context) -> Result<()> {
    let steps = if ctx.quick { 16 } else { 60 };
    let started = std::time::Instant::now();
    let coulomb = run(FrictionLaw::Coulomb, steps)?;
    let stribeck = run(STRIBECK, steps)?;
    eprintln!(
        "reproduce: belt sweeps of 2 × 2 × {steps} steps in {:.1} s",
        started.elapsed().as_secs_f64()
    );
    let panel = |title: &str, points: &[SweepPoint]| {
        let leg = |l: SweepLeg| -> Vec<(f64, f64)> {
            points
                .iter()
                .filter(|p| p.leg == l)
                .map(|p| (p.value, amplitude(p)))
                .collect()
        };
        Panel {
            title: title.into(),
            x_label: "belt speed vb".into(),
            y_label: "amplitude (y_max − y_min)/2".into(),
            // Down first, under the up sweep's dots.
            series: vec![
                Quantity::SweepDown.series("down", leg(SweepLeg::Down)),
                Quantity::SweepUp.series("up", leg(SweepLeg::Up)),
            ],
            legend: Some(Legend::Best),
            x_range: Some((0.0, VB.1 + 0.05)),
            ..Default::default()
        }
    };
    report.figure(
        "belt-sweep",
        &Figure {
            panels: vec![
                panel(&format!("(a) Coulomb, ζ = {ZETA}, μs = {MU_S}"), &coulomb),
                panel(
                    &format!("(b) Stribeck, ζ = {ZETA}, μs = {MU_S}, vs = 0.5, δ = 2, η = 0.05"),
                    &stribeck,
                ),
            ],
            columns: 2,
            panel_size: (760, 520),
        },
    )?;

    let mut header = vec![Key::FrictionLaw.name(), Parameter::Vb.label()];
    header.extend(BELT_SWEEP_COLUMNS);
    let mut rows = Vec::new();
    for (law, points) in [(FrictionLaw::Coulomb, &coulomb), (STRIBECK, &stribeck)] {
        for p in points {
            let cycle = p.steady.self_excited;
            rows.push(vec![
                law.kind().label().to_string(),
                p.value.to_string(),
                p.leg.label().to_string(),
                p.steady.class.label().to_string(),
                amplitude(p).to_string(),
                p.steady.y_max.to_string(),
                p.steady.y_min.to_string(),
                stickslip::report::optional(cycle.and_then(|c| c.period)),
                cycle.map_or(String::new(), |c| c.stick_fraction.to_string()),
            ]);
        }
    }
    report.csv("belt-sweep.csv", &header, &rows)?;

    // Where steady sliding of the Stribeck belt is unstable, on the swept speeds.
    let unstable: Vec<f64> = stribeck
        .iter()
        .filter(|p| p.leg == SweepLeg::Up)
        .filter(|p| SteadySliding::new(&p.params).is_ok_and(|s| s.is_unstable()))
        .map(|p| p.value)
        .collect();
    let unstable_text = match (unstable.first(), unstable.last()) {
        (Some(a), Some(b)) => format!(
            "steady sliding is unstable (2ζ + μ'(vb) &lt; 0) at the swept speeds from vb = {} to {}",
            sig(*a, 3),
            sig(*b, 3)
        ),
        _ => "steady sliding is stable at every swept speed".into(),
    };
    let largest = |points: &[SweepPoint]| points.iter().map(amplitude).fold(0.0, f64::max);
    let differ = |points: &[SweepPoint]| {
        let up: Vec<&SweepPoint> = points.iter().filter(|p| p.leg == SweepLeg::Up).collect();
        points
            .iter()
            .filter(|p| p.leg == SweepLeg::Down)
            .filter(|d| {
                up.iter()
                    .any(|u| u.value == d.value && u.steady.class != d.steady.class)
            })
            .count()
    };
    report.summary.insert(
        "belt_sweep".into(),
        json!({
            "zeta": ZETA, "mu_s": MU_S, "vb": [VB.0, VB.1], "steps": steps,
            "coulomb_hysteresis_steps": differ(&coulomb),
            "stribeck_hysteresis_steps": differ(&stribeck),
            "stribeck_unstable_vb": [unstable.first(), unstable.last()],
        }),
    );
    report.sections.push(Section {
        id: "belt-sweep".into(),
        title: "Amplitude against belt speed, both ways".into(),
        caption: format!(
            "The undriven belt (β = 0) swept over {steps} belt speeds from vb = {} to {}, up \
             from rest and down again, each step starting where the last one ended (the \
             library's <code>Sweep</code> over vb; <code>stickslip sweep --over vb</code>). \
             (a) Coulomb's law: the up sweep {}; the down sweep {}. Steady sliding is stable \
             at every speed (μ' = 0, ζ > 0){}: the two legs differ at {} speeds. The largest \
             amplitude is {}. (b) Stribeck's law: {}. The up sweep {}; the down sweep {}; the \
             legs differ at {} speeds. The largest amplitude is {}. Where the legs differ, a \
             stick-slip cycle and stable steady sliding coexist: each leg keeps the motion it \
             came with.",
            sig(VB.0, 3),
            sig(VB.1, 3),
            describe(&coulomb, SweepLeg::Up),
            describe(&coulomb, SweepLeg::Down),
            if jumps(&coulomb, SweepLeg::Down).is_empty() {
                ", so once the block slides it stays sliding as the belt slows"
            } else {
                ""
            },
            differ(&coulomb),
            sig(largest(&coulomb), 4),
            unstable_text,
            describe(&stribeck, SweepLeg::Up),
            describe(&stribeck, SweepLeg::Down),
            differ(&stribeck),
            sig(largest(&stribeck), 4),
        ),
        figures: vec!["belt-sweep".into()],
        data: vec!["belt-sweep.csv".into()],
        tables: vec![],
    });
    Ok(())
}
