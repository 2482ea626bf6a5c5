//! The largest Lyapunov exponent against the drive frequency at ζ = 0, μs = 3, β = 9, with
//! the motion classes: the literature's chaotic windows.

use super::super::report::{sig, Report, Section};
use super::super::Context;
use super::{frequency, literature, marker_color};
use crate::plot::{Figure, Legend, Panel, Series, Style};
use anyhow::Result;
use plotters::style::RGBColor;
use serde_json::json;
use stickslip::report::MapReport;
use stickslip::scan::{Axis, Grid, GridPoint, ParameterRange};
use stickslip::stability::SEARCH_BEFORE_MEASURING;
use stickslip::steady::MotionClass;
use stickslip::{Parameter, SteadyOptions};

/// The lower end of the close-up panel (per unit τ).
const ZOOM_BELOW: f64 = -0.03;

/// λ1 against w from 0.2 to 0.55 at β = 9, every point from rest.
pub fn chaos_sweep(report: &mut Report, ctx: &Context) -> Result<()> {
    let steps = if ctx.quick { 36 } else { 141 };
    let w = ParameterRange::new("w", 0.2, 0.55, steps)?;
    let options = SteadyOptions::default().with_spectrum(false);
    let measure = options.lyapunov.expect("measured by default");
    let (align, cap) = (measure.transient_periods, measure.periods);
    let longest = options.max_periods;
    let started = std::time::Instant::now();
    let points = Grid::new(
        &literature()?,
        Axis::range(Parameter::W, &w)?,
        Axis::new(Parameter::Beta, vec![9.0])?,
    )?
    .options(options)?
    .lyapunov(measure)?
    .run(&|_: usize, _: usize| !crate::output::interrupted())?
    .points;
    // The time goes to standard error: the report itself is the same on every run.
    eprintln!(
        "reproduce: chaos sweep of {steps} frequencies in {:.1} s",
        started.elapsed().as_secs_f64()
    );
    let lambda = |p: &GridPoint| p.lyapunov.map_or(f64::NAN, |l| l.per_tau);
    let error = |p: &GridPoint| p.lyapunov.map_or(f64::NAN, |l| l.error_per_tau);

    let mut series = vec![Series::new(
        "",
        vec![(0.2, 0.0), (0.55, 0.0)],
        RGBColor(150, 150, 150),
        Style::Dashed(1),
    )];
    // ±4σ bars on the measured points (the chaos criterion), one polyline broken by NaN.
    let k = measure.significance;
    let mut bars = Vec::new();
    for p in points.iter().filter(|p| error(p) > 0.0) {
        let (x, y, e) = (p.params.w, lambda(p), k * error(p));
        bars.extend([(x, y - e), (x, y + e), (f64::NAN, f64::NAN)]);
    }
    series.push(Series::new("", bars, RGBColor(0, 0, 0), Style::Line(2)));
    for class in MotionClass::ALL {
        let at: Vec<(f64, f64)> = points
            .iter()
            .filter(|p| p.class == class)
            .map(|p| (p.params.w, lambda(p)))
            .collect();
        if !at.is_empty() {
            let label = match class {
                MotionClass::Chaotic => "chaotic (λ1 > 4σ, measured)".to_string(),
                MotionClass::Undecided => "nonperiodic-stick (measured)".to_string(),
                c => format!("{} (ln|μ1|/pT, exact)", c.label()),
            };
            series.push(Series::new(
                label,
                at,
                marker_color(class),
                Style::Markers(4),
            ));
        }
    }
    let full = Panel {
        title: "(a) largest Lyapunov exponent from rest, ζ = 0, μs = 3, β = 9".into(),
        x_label: "w = Ω/ω0".into(),
        y_label: "λ1 per unit τ".into(),
        series: series.clone(),
        legend: Some(Legend::Best),
        x_range: Some((0.2 - 0.005, 0.55 + 0.005)),
        ..Default::default()
    };
    // The chaotic exponents are small beside the contraction of some orbits: a closer look
    // around 0, with the same points (those below the window are not drawn there).
    let top = points.iter().map(lambda).fold(0.0f64, f64::max);
    let zoom = Panel {
        title: format!(
            "(b) the same, λ1 from {ZOOM_BELOW} to {}",
            sig(1.15 * top, 2)
        ),
        series: series
            .into_iter()
            .map(|mut s| {
                s.label.clear();
                // (A point outside the window would be drawn on its edge: leave it out.)
                for p in &mut s.points {
                    if !(p.1 >= ZOOM_BELOW) {
                        *p = (f64::NAN, f64::NAN);
                    }
                }
                s
            })
            .collect(),
        y_range: Some((ZOOM_BELOW, 1.15 * top)),
        legend: None,
        ..full.clone()
    };
    report.figure(
        "chaos-sweep",
        &Figure {
            panels: vec![full, zoom],
            columns: 1,
            panel_size: (1000, 480),
        },
    )?;

    // A map of one β: the CSV of `stickslip phase-diagram --lyapunov --out`.
    report.table("chaos-sweep.csv", &MapReport::new(&points, true))?;

    let chaotic: Vec<&GridPoint> = points
        .iter()
        .filter(|p| p.class == MotionClass::Chaotic)
        .collect();
    let windows = windows(&points);
    let top = points
        .iter()
        .max_by(|a, b| lambda(a).total_cmp(&lambda(b)))
        .expect("points");
    let zoomed_out = points.iter().filter(|p| lambda(p) < ZOOM_BELOW).count();
    let unsettled: Vec<&GridPoint> = points
        .iter()
        .filter(|p| p.period.is_none() && p.class != MotionClass::Chaotic)
        .collect();
    let unsettled = match unsettled.as_slice() {
        [] => String::new(),
        [p] => format!(
            " One, at w = {}, does not repeat within the cap and is not chaotic either (λ1 = \
             {} ± {}: it contracts onto a periodic motion not yet reached).",
            frequency(p.params.w),
            sig(lambda(p), 3),
            sig(error(p), 2)
        ),
        many => format!(
            " {} do not repeat within the cap and are not chaotic either (λ1 within or below \
             its error: contracting onto a periodic motion not yet reached, or undecided).",
            many.len()
        ),
    };
    let (lo, hi) = chaotic.iter().fold((f64::INFINITY, 0.0f64), |(lo, hi), p| {
        (lo.min(lambda(p)), hi.max(lambda(p)))
    });
    let mut periods: Vec<usize> = points.iter().filter_map(|p| p.period).collect();
    periods.sort_unstable();
    periods.dedup();
    let unmeasured_chaos = points
        .iter()
        .filter(|p| p.class == MotionClass::Chaotic && !(lambda(p) > k * error(p)))
        .count();
    anyhow::ensure!(
        unmeasured_chaos == 0,
        "a chaotic point without a significant exponent"
    );
    report.summary.insert(
        "beyond_chaos_sweep".into(),
        json!({
            "zeta": 0.0, "mu_s": 3.0, "beta": 9.0,
            "w": [w.from(), w.to()], "steps": steps,
            "chaotic": chaotic.len(),
            "windows": windows,
            "lambda_chaotic": [lo, hi],
            "largest": {"w": top.params.w, "lambda1": lambda(top), "lambda1_error": error(top)},
            "periods": periods,
        }),
    );
    let list = windows
        .iter()
        .map(|(a, b)| {
            if a == b {
                frequency(*a)
            } else {
                format!("{}–{}", frequency(*a), frequency(*b))
            }
        })
        .collect::<Vec<_>>()
        .join(", ");
    let periods = periods
        .iter()
        .map(|p| p.to_string())
        .collect::<Vec<_>>()
        .join(", ");
    report.sections.push(Section {
        id: "chaos-sweep".into(),
        title: "Chaos at ζ = 0, μs = 3, β = 9: the largest Lyapunov exponent against w".into(),
        caption: format!(
            "The oscillator of the literature on chaos with dry friction (Licskó and Csernák \
             2014): no viscous damping, static friction three times the kinetic, β = 9. Each \
             of {steps} frequencies from w = 0.2 to 0.55 is run from rest to its steady state \
             (as <code>stickslip steady</code>: a period up to 16 within {longest} drive \
             periods). \
             Where the motion repeats, λ1 = ln|μ1|/(pT) from the Floquet multiplier μ1 of its \
             orbit, refined by Newton's method: exact, no error bar. Where it has not repeated \
             after {SEARCH_BEFORE_MEASURING} periods, λ1 is measured from there by the exact \
             tangent dynamics ({align} periods to align the tangent, then at most {cap} periods \
             in 20 blocks, stopping at the first look where λ1 is beyond 4 standard errors and \
             the halves of the blocks agree; a motion still undecided is followed for up to \
             {longest} periods from rest); the bars are ±4 standard errors, the chaos criterion \
             (mostly smaller than the markers). The motion is chaotic at {} of the {steps} \
             frequencies (w = {list}), with λ1 from {} to {} per unit τ, and repeats at the \
             others (periods {periods}), \
             where λ1 is negative, down to {} at w = {}.{unsettled} (b) shows λ1 above \
             {ZOOM_BELOW}, where the chaotic exponents lie ({zoomed_out} points fall below \
             it).",
            chaotic.len(),
            sig(lo, 3),
            sig(hi, 3),
            sig(
                points
                    .iter()
                    .map(lambda)
                    .filter(|x| x.is_finite())
                    .fold(f64::INFINITY, f64::min),
                3
            ),
            frequency(
                points
                    .iter()
                    .filter(|p| lambda(p).is_finite())
                    .min_by(|a, b| lambda(a).total_cmp(&lambda(b)))
                    .map_or(f64::NAN, |p| p.params.w)
            ),
        ),
        figures: vec!["chaos-sweep".into()],
        data: vec!["chaos-sweep.csv".into()],
        tables: vec![],
    });
    Ok(())
}

/// The runs of consecutive chaotic points, as (first w, last w).
fn windows(points: &[GridPoint]) -> Vec<(f64, f64)> {
    let mut out: Vec<(f64, f64)> = Vec::new();
    let mut open = false;
    for p in points {
        if p.class == MotionClass::Chaotic {
            match (open, out.last_mut()) {
                (true, Some(last)) => last.1 = p.params.w,
                _ => out.push((p.params.w, p.params.w)),
            }
            open = true;
        } else {
            open = false;
        }
    }
    out
}
