//! A bifurcation diagram in w at ζ = 0, μs = 3, β = 9, with the branches of periodic orbits
//! continued through it.

use super::super::report::{sig, Report, Section};
use super::super::{Context, Later};
use anyhow::Result;
use serde_json::json;
use stickslip::attractor::{same_attractor, AttractorKind, RecordOptions};
use stickslip::basins::BasinOptions;
use stickslip::bifurcation::{Bifurcation, BifurcationOptions, BifurcationStep};
use stickslip::continuation::{ContinuationOptions, SpecialKind};
use stickslip::report::BifurcationReport;
use stickslip::scan::{Axis, ParameterRange, SweepDirection, SweepLeg};
use stickslip::Parameter;

/// The diagram and its branches, with the seconds each took, computed alongside the other
/// figures from the start of `reproduce` ([`Later`]); [`bifurcation_w`] takes them.
pub struct Diagram {
    steps: Vec<BifurcationStep>,
    branches: Vec<stickslip::continuation::Branch>,
    diagram_seconds: f64,
    branch_seconds: f64,
}

impl Diagram {
    /// Start computing the diagram (coarser with `quick`).
    pub fn start(quick: bool) -> Later<Self> {
        Later::start(move || compute(quick))
    }
}

/// The columns of beyond-bifurcation-special.csv, the report's own (no library table lists
/// the special points of several branches).
pub const SPECIAL_COLUMNS: [&str; 7] = ["branch", "period", "kind", "w", "y", "v", "width"];

/// The values of w (0.2 to 0.55) and the strobe points recorded at each.
fn sizes(quick: bool) -> Result<(ParameterRange, usize)> {
    let steps = if quick { 90 } else { 250 };
    let points = if quick { 40 } else { 80 };
    Ok((ParameterRange::new("w", 0.2, 0.55, steps)?, points))
}

/// The diagram over w from 0.2 to 0.55, up and down, and its branches.
fn compute(quick: bool) -> Result<Diagram> {
    let (w, points) = sizes(quick)?;
    // The setting of the chaos figures above.
    let experiment = super::literature()?;
    let diagram = Bifurcation::new(&experiment, Axis::range(Parameter::W, &w)?)?
        .direction(SweepDirection::Both)
        .options(BifurcationOptions {
            record: RecordOptions {
                points,
                ..RecordOptions::default()
            },
            ..BifurcationOptions::default()
        })?;
    let keep_going = |_: usize, _: usize| !crate::output::interrupted();
    let started = std::time::Instant::now();
    let steps = diagram.run(&keep_going)?;
    let diagram_seconds = started.elapsed().as_secs_f64();
    let started = std::time::Instant::now();
    let branches = diagram.branches(
        &steps,
        &ContinuationOptions {
            max_points: 600,
            ..ContinuationOptions::default()
        },
        &keep_going,
    )?;
    Ok(Diagram {
        steps,
        branches,
        diagram_seconds,
        branch_seconds: started.elapsed().as_secs_f64(),
    })
}

/// The bifurcation diagram in w and its branches ([`Diagram`]).
pub fn bifurcation_w(report: &mut Report, ctx: &Context) -> Result<()> {
    let Diagram {
        steps,
        branches,
        diagram_seconds,
        branch_seconds,
    } = ctx.bifurcation.take()?;
    let (w, points) = sizes(ctx.quick)?;
    let steps_n = w.steps();
    // The times go to standard error: the report itself is the same on every run.
    eprintln!(
        "reproduce: bifurcation diagram of {} values in {diagram_seconds:.1} s, its branches in \
         {branch_seconds:.1} s (alongside the chapters before it)",
        steps.len()
    );
    crate::output::check_interrupt()?;

    let title = "bifurcation diagram in w at ζ = 0, μs = 3, β = 9";
    report.stack(
        "beyond-bifurcation",
        &crate::diagrams::diagram_figure(&steps, &branches, Parameter::W, title),
    )?;
    // The CSV of `stickslip bifurcation --out`: the library's table of a diagram.
    report.table(
        "beyond-bifurcation.csv",
        &BifurcationReport::new(Parameter::W, &steps),
    )?;
    let special: Vec<&stickslip::continuation::SpecialPoint> =
        branches.iter().flat_map(|b| b.special.iter()).collect();
    let special_rows: Vec<Vec<String>> = branches
        .iter()
        .enumerate()
        .flat_map(|(i, b)| {
            b.special.iter().map(move |s| {
                vec![
                    i.to_string(),
                    b.period.to_string(),
                    s.kind.label().into(),
                    format!("{}", s.value),
                    format!("{}", s.state.y),
                    format!("{}", s.state.v),
                    format!("{}", s.width),
                ]
            })
        })
        .collect();
    report.csv(
        "beyond-bifurcation-special.csv",
        &SPECIAL_COLUMNS,
        &special_rows,
    )?;

    let up: Vec<&BifurcationStep> = steps.iter().filter(|s| s.leg == SweepLeg::Up).collect();
    let count = |kind: AttractorKind| up.iter().filter(|s| s.record.kind == kind).count();
    let chaotic = windows(&up);
    let mut periods: Vec<usize> = up.iter().filter_map(|s| s.record.period).collect();
    periods.sort_unstable();
    periods.dedup();
    let legs = compare_legs(&steps);
    let both_differ = legs.records_differ;
    let of = |kind: SpecialKind| -> Vec<f64> {
        let mut v: Vec<f64> = special
            .iter()
            .filter(|s| s.kind == kind)
            .map(|s| (s.value * 1e6).round() / 1e6)
            .collect();
        v.sort_by(f64::total_cmp);
        v.dedup();
        v
    };
    let list = |v: &[f64]| v.iter().map(|x| sig(*x, 5)).collect::<Vec<_>>().join(", ");
    let (folds, grazings, branch_points, doublings) = (
        of(SpecialKind::Fold),
        of(SpecialKind::Grazing),
        of(SpecialKind::BranchPoint),
        of(SpecialKind::PeriodDoubling),
    );
    report.summary.insert(
        "beyond_bifurcation_w".into(),
        json!({
            "zeta": 0.0, "mu_s": 3.0, "beta": 9.0,
            "w_from": w.from(), "w_to": w.to(), "steps": w.steps(),
            "points_per_value": points,
            "up_periodic": count(AttractorKind::Periodic),
            "up_chaotic": count(AttractorKind::Chaotic),
            "up_quasiperiodic": count(AttractorKind::QuasiPeriodic),
            "up_undecided": count(AttractorKind::Undecided),
            "periods": periods,
            "chaotic_windows": chaotic.iter().map(|(a, b)| [*a, *b]).collect::<Vec<_>>(),
            "values_where_up_and_down_differ": both_differ,
            "values_with_different_attractors_up_and_down": legs.different_attractors,
            "values_with_different_decided_attractors_up_and_down": legs.different_decided,
            "branches": branches.len(),
            "folds": folds, "grazings": grazings, "branch_points": branch_points,
            "period_doublings": doublings,
        }),
    );
    let windows_text = chaotic
        .iter()
        .map(|(a, b)| format!("{}–{}", sig(*a, 3), sig(*b, 3)))
        .collect::<Vec<_>>()
        .join(" and ");
    let n_branches = branches.len();
    let clauses: Vec<String> = [
        ("folds (squares, a multiplier through +1)", &folds),
        ("period doublings (a multiplier through −1)", &doublings),
        ("branch points", &branch_points),
        (
            "grazings (the stops per period change and the continuation goes on by itself)",
            &grazings,
        ),
    ]
    .iter()
    .filter(|(_, at)| !at.is_empty())
    .map(|(what, at)| format!("{what} at w = {}", list(at)))
    .collect();
    let special_text = if clauses.is_empty() {
        "No special point on these branches.".to_string()
    } else {
        let mut text = format!("Special points: {}.", clauses.join("; "));
        if grazings.is_empty() {
            text.push_str(" No stop appears or disappears along these branches.");
        }
        text
    };
    let different = legs.different_attractors;
    let undecided_text = match different - legs.different_decided {
        0 => "none of them is a motion undecided either way".to_string(),
        1 => "the other one, a motion is undecided in at least one direction (undecided \
              matches nothing)"
            .to_string(),
        n => format!(
            "the other {n}, a motion is undecided in at least one direction (undecided \
             matches nothing)"
        ),
    };
    let caption = format!(
        "The motion's strobe points (y once per drive period, at drive phase 0) against the \
         drive frequency w, at ζ = 0, μs = 3, β = 9, the setting in which the stability analysis \
         found chaos. w is stepped up (blue) and then down again (orange), {steps_n} values each \
         way, each value starting from the state where the one before ended; at each, {points} \
         strobe points after 200 periods of transient (2000 at the first), and the largest \
         Lyapunov exponent over those periods (lower panel). A period-p orbit shows as p dots, \
         chaos as a vertical smear: on the way up {} values are chaotic (λ1 > 4 standard \
         errors of its block means; the chaotic stretches span w ≈ {windows_text}), {} \
         periodic (periods {}), {} quasi-periodic (no period, λ1 within 4 standard errors of \
         0) and {} undecided (no period and no verdict: still contracting onto a motion not \
         reached, or a record too short to judge); every value's kind is in \
         beyond-bifurcation.csv. The two directions' records differ at {both_differ} of the \
         {steps_n} values, but a record is one sample of its attractor: compared as sets of \
         strobe points, the way the basin map below tells attractors apart (a periodic orbit \
         is the same recorded at another phase, a chaotic one the same sampled at other \
         times), {} of those are the same attractor both ways and {different} values hold \
         different attractors up and down. {} At {undecided_text}. The lines are {n_branches} branches of periodic orbits \
         continued from the periodic values by pseudo-arclength continuation \
         (<code>stickslip continue</code>), stable solid and unstable dashed: the unstable \
         orbits are what the simulation cannot show. {special_text} Most periodic windows end \
         where the strobe map \
         breaks: a turning point reaches the static friction limit and would become a long \
         stop. Classes here come from {points} periods only; the chaos figures above measure \
         at length. \
         <code>stickslip bifurcation --zeta 0 --mu-s 3 --beta 9 --over w --from 0.2 --to 0.55 \
         --steps {steps_n} --points {points} --plot bif.png</code>.",
        count(AttractorKind::Chaotic),
        count(AttractorKind::Periodic),
        periods
            .iter()
            .map(|p| p.to_string())
            .collect::<Vec<_>>()
            .join(", "),
        count(AttractorKind::QuasiPeriodic),
        count(AttractorKind::Undecided),
        both_differ - different,
        match legs.different_decided {
            0 => "None of them with both motions decided.".to_string(),
            1 => "One of them, with both motions decided, is a pair of coexisting motions."
                .to_string(),
            n => format!(
                "{n} of them, with both motions decided, are pairs of coexisting motions."
            ),
        },
    );
    report.sections.push(Section {
        id: "beyond-bifurcation".into(),
        title: "Bifurcation diagram in w at μs = 3 (ζ = 0, β = 9)".into(),
        caption,
        figures: vec!["beyond-bifurcation".into()],
        data: vec![
            "beyond-bifurcation.csv".into(),
            "beyond-bifurcation-special.csv".into(),
        ],
        ..Default::default()
    });
    Ok(())
}

/// How the two legs of the diagram compare, value by value.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
struct Legs {
    /// Values whose records differ: in kind, period or first strobe point.
    records_differ: usize,
    /// Values whose records are of different attractors ([`same_attractor`]).
    different_attractors: usize,
    /// Of those, the values where both records are decided (not
    /// [`AttractorKind::Undecided`]).
    different_decided: usize,
}

/// Compare the up and down records at each value: as records (the first strobe point) and
/// as attractors, sets of strobe points matched within the basin map's tolerance.
fn compare_legs(steps: &[BifurcationStep]) -> Legs {
    let tolerance = BasinOptions::default().match_tolerance;
    let mut legs = Legs {
        records_differ: 0,
        different_attractors: 0,
        different_decided: 0,
    };
    for u in steps.iter().filter(|s| s.leg == SweepLeg::Up) {
        let Some(d) = steps
            .iter()
            .find(|d| d.leg == SweepLeg::Down && d.value == u.value)
        else {
            continue;
        };
        let (a, b) = (&u.record, &d.record);
        let first = |r: &stickslip::attractor::StrobeRecord| r.strobes.first().map(|x| x.y);
        let records_differ = a.kind != b.kind
            || a.period != b.period
            || match (first(a), first(b)) {
                (Some(x), Some(y)) => (x - y).abs() > 1e-6 * (1.0 + x.abs()),
                (x, y) => x.is_some() != y.is_some(),
            };
        if !records_differ {
            continue;
        }
        legs.records_differ += 1;
        if !same_attractor(a, b, tolerance) {
            legs.different_attractors += 1;
            if a.kind != AttractorKind::Undecided && b.kind != AttractorKind::Undecided {
                legs.different_decided += 1;
            }
        }
    }
    legs
}

/// The stretches of consecutive chaotic values: (first, last).
fn windows(steps: &[&BifurcationStep]) -> Vec<(f64, f64)> {
    let mut out: Vec<(f64, f64)> = Vec::new();
    let mut open: Option<(f64, f64)> = None;
    for s in steps {
        if s.record.kind == AttractorKind::Chaotic {
            open = Some(open.map_or((s.value, s.value), |(a, _)| (a, s.value)));
        } else if let Some(w) = open.take() {
            out.push(w);
        }
    }
    out.extend(open);
    // Single chaotic values between periodic ones are noise of a short record: keep
    // stretches of at least three values.
    let spacing = steps
        .windows(2)
        .map(|p| (p[1].value - p[0].value).abs())
        .fold(f64::INFINITY, f64::min);
    out.retain(|(a, b)| b - a >= 1.5 * spacing);
    out
}
