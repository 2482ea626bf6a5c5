//! A branch of periodic orbits with its stability: the paper's circuit with μs = 1.5 at
//! w = 0.9, continued in β through a grazing and a fold, with the sweeps that show the
//! hysteresis it explains.

use super::super::report::{sig, Report, Section};
use super::super::Context;
use crate::plot::{Series, Style, PALETTE};
use anyhow::Result;
use serde_json::json;
use stickslip::continuation::{
    continue_both_ways, settled_orbit, BranchEnd, ContinuationOptions, SpecialKind,
};
use stickslip::report::BranchTable;
use stickslip::scan::{Axis, ParameterRange, Sweep, SweepDirection, SweepLeg};
use stickslip::{Parameter, State};

/// The branch over β from 1.25 to 1.6 and the sweeps up and down.
pub fn branch_fold(report: &mut Report, ctx: &Context) -> Result<()> {
    let base = ctx.paper.clone().with_mu_s(1.5)?.with_w(0.9)?;
    let started = std::time::Instant::now();
    // Started from a moving state: from rest the oscillator cannot move below β = μs.
    let (params, orbit) = settled_orbit(
        &base
            .clone()
            .with_beta(1.45)?
            .with_initial(State { y: 0.25, v: 2.1 })?,
    )?;
    let branch = continue_both_ways(
        &params,
        Parameter::Beta,
        &orbit,
        (1.25, 1.6),
        &ContinuationOptions::default(),
        &|_: usize, _: usize| !crate::output::interrupted(),
    )?;
    // The time goes to standard error: the report itself is the same on every run.
    eprintln!(
        "reproduce: branch of {} points in {:.1} s",
        branch.points.len(),
        started.elapsed().as_secs_f64()
    );
    let steps = if ctx.quick { 15 } else { 36 };
    let sweep = Sweep::new(
        &base,
        Axis::range(
            Parameter::Beta,
            &ParameterRange::new("beta", 1.25, 1.6, steps)?,
        )?,
    )?
    .direction(SweepDirection::Both)
    .options(stickslip::SteadyOptions::default().with_spectrum(false))?
    .run(&|_: usize, _: usize| !crate::output::interrupted())?;
    crate::output::check_interrupt()?;

    let title = format!(
        "period-1 orbits of the paper's circuit with μs = 1.5 at w = 0.9 (ζ = {})",
        sig(params.zeta, 4)
    );
    let mut figure = crate::diagrams::branch_figure(&branch, &title);
    for (leg, color, style, label) in [
        (
            SweepLeg::Up,
            PALETTE[0],
            Style::Markers(4),
            "sweep up from rest (simulated)",
        ),
        (
            SweepLeg::Down,
            PALETTE[1],
            Style::Squares(4),
            "sweep down (simulated)",
        ),
    ] {
        let points = sweep
            .iter()
            .filter(|p| p.leg == leg)
            .map(|p| (p.value, p.steady.amplitude()))
            .collect();
        figure.panels[0]
            .0
            .series
            .push(Series::new(label, points, color, style));
    }
    // The whole range of the sweep: below the fold only rest remains.
    for (panel, _) in &mut figure.panels {
        panel.x_range = Some((1.25, 1.6));
    }
    let top = &mut figure.panels[0].0;
    if let Some((lo, hi)) = top.y_range {
        top.y_range = Some((lo.min(-0.05), hi + 0.15 * (hi - lo)));
    }
    report.stack("beyond-branch", &figure)?;
    // The CSV of `stickslip continue`: the library's table of a branch.
    report.table("beyond-branch.csv", &BranchTable { branch: &branch })?;
    let find = |kind: SpecialKind| branch.special.iter().find(|s| s.kind == kind);
    let fold = find(SpecialKind::Fold);
    let grazing = find(SpecialKind::Grazing);
    // Where the unstable side stops: at either end of the joined branch.
    let end = [&branch.begin, &branch.end]
        .into_iter()
        .find_map(|e| match e {
            BranchEnd::Stalled {
                value, multiplier, ..
            } => Some((Some(*value), Some(*multiplier))),
            BranchEnd::Failed { value, .. } => Some((Some(*value), None)),
            _ => None,
        })
        .unwrap_or((None, None));
    report.summary.insert(
        "beyond_branch".into(),
        json!({
            "zeta": params.zeta, "mu_s": 1.5, "w": 0.9,
            "points": branch.points.len(),
            "fold_beta": fold.map(|s| s.value),
            "fold_width": fold.map(|s| s.width),
            "grazing_beta": grazing.map(|s| s.value),
            "grazing_stops": grazing.map(|s| [s.before.stops, s.after.stops]),
            "end_beta": end.0, "end_multiplier": end.1,
        }),
    );
    let at = |s: Option<&stickslip::continuation::SpecialPoint>| {
        s.map_or("—".to_string(), |s| format!("{:.6}", s.value))
    };
    let caption = format!(
        "A branch of periodic orbits with its stability: the paper's circuit with static \
         friction 1.5 times the kinetic (μs = 1.5), driven at w = 0.9, continued in β by \
         pseudo-arclength continuation (<code>stickslip continue</code>) from the orbit at \
         β = 1.45. Upper panel: the amplitude, stable solid, unstable dashed; lower panel: the \
         largest Floquet multiplier. Coming down from β = 1.6 the orbit slides (two turning \
         points per period) until β = {}, a grazing: the turning points reach the static \
         friction limit and become stops, two per period, their duration growing from zero. \
         The continuation passes it without being told: the exact solver finds the new events. \
         The multiplier jumps there (other saltation matrices), from {} to {}. At β = {} the \
         stable orbit meets an unstable one in a fold (a multiplier through +1, located to \
         {:.0e} in arclength); the unstable orbit goes back up in β with a growing multiplier \
         and ends near β = {} where its release moves onto the maximum of the drive and \
         becomes tangential. The markers are simulations of the sweep: from rest, nothing \
         moves below β = μs = 1.5 (rest is stable for β &lt; μs); going down, the motion follows \
         the stable branch to the fold and then stops: the hysteresis between β ≈ {} and 1.5 \
         is the fold, and the unstable orbit is the threshold between rest and motion.",
        at(grazing),
        grazing.map_or("—".into(), |s| sig(s.before.multipliers[0].re, 4)),
        grazing.map_or("—".into(), |s| sig(s.after.multipliers[0].re, 4)),
        at(fold),
        fold.map_or(0.0, |s| s.width.max(1e-12)),
        end.0.map_or("—".to_string(), |v| sig(v, 4)),
        fold.map_or("—".to_string(), |s| sig(s.value, 4)),
    );
    report.sections.push(Section {
        id: "beyond-branch".into(),
        title: "A branch and its stability: fold and grazing (μs = 1.5, w = 0.9)".into(),
        caption,
        figures: vec!["beyond-branch".into()],
        data: vec!["beyond-branch.csv".into()],
        ..Default::default()
    });
    Ok(())
}
