//! The paper's "non-periodic motion with sticking", tested by Lyapunov exponents over the
//! paper's own map (μs = 1), against the chaos found with μs > 1.

use super::super::report::{sig, Report, Section};
use super::super::Context;
use super::frequency;
use crate::plot::{Cell, ColorBar, Figure, Legend, Panel};
use anyhow::Result;
use serde_json::json;
use stickslip::report::MapReport;
use stickslip::scan::{Axis, Grid, GridPoint, ParameterRange};
use stickslip::steady::MotionClass;
use stickslip::{Parameter, SteadyOptions};

/// The axes of the paper's map: w from 0.1 to 2.5 and β from 0.5 to 4, 200 values each (60
/// with --quick).
fn paper_axes(ctx: &Context) -> Result<(ParameterRange, ParameterRange)> {
    let n = if ctx.quick { 60 } else { 200 };
    Ok((
        ParameterRange::new("w", 0.1, 2.5, n)?,
        ParameterRange::new("beta", 0.5, 4.0, n)?,
    ))
}

/// The paper's map (its circuit, PWL diodes, μs = 1, every point from rest, the default
/// steady-state options) with the largest Lyapunov exponent of every point, computed on the
/// first call and kept in `ctx`.
///
/// # Errors
/// As [`Grid::run`].
pub fn paper_exponent_map(ctx: &Context) -> Result<&[GridPoint]> {
    if let Some(points) = ctx.paper_exponents.get() {
        return Ok(points);
    }
    let (w, beta) = paper_axes(ctx)?;
    let options = SteadyOptions::default().with_spectrum(false);
    let measure = options.lyapunov.expect("measured by default");
    let started = std::time::Instant::now();
    let points = Grid::new(
        &ctx.paper,
        Axis::range(Parameter::W, &w)?,
        Axis::range(Parameter::Beta, &beta)?,
    )?
    .options(options)?
    .lyapunov(measure)?
    .run(&|_: usize, _: usize| !crate::output::interrupted())?
    .points;
    // The time goes to standard error: the report itself is the same on every run.
    eprintln!(
        "reproduce: exponents of the paper's map {} × {} in {:.1} s",
        w.steps(),
        beta.steps(),
        started.elapsed().as_secs_f64()
    );
    Ok(ctx.paper_exponents.get_or_init(|| points))
}

/// λ1 over the paper's map (its circuit, PWL diodes, μs = 1), every point from rest, and the
/// statement about the paper's non-periodic class.
pub fn paper_exponents(report: &mut Report, ctx: &Context) -> Result<()> {
    let (w, beta) = paper_axes(ctx)?;
    let points = paper_exponent_map(ctx)?;
    let n = w.steps();
    let lambda = |p: &GridPoint| p.lyapunov.map_or(f64::NAN, |l| l.per_tau);

    let values: Vec<f64> = points.iter().map(lambda).collect();
    let bar = ColorBar::for_values("λ1 per unit τ", &values);
    let (dw, db) = (0.5 * w.spacing(), 0.5 * beta.spacing());
    let panel = Panel {
        title: "largest Lyapunov exponent over the paper's map (μs = 1, PWL diodes)".into(),
        x_label: "Ω/ω0".into(),
        y_label: "β = U/U_t".into(),
        cells: points
            .iter()
            .map(|p| Cell {
                x: (p.params.w - dw, p.params.w + dw),
                y: (p.params.beta - db, p.params.beta + db),
                color: bar.color(lambda(p)),
            })
            .collect(),
        series: super::super::figures::boundary_curves(ctx, 0.1, 2.5)?,
        x_range: Some((w.from() - dw, w.to() + dw)),
        y_range: Some((beta.from() - db, beta.to() + db)),
        legend: Some(Legend::UpperRight),
        color_bar: Some(bar),
        ..Default::default()
    };
    report.figure("paper-exponents", &Figure::single(panel, (960, 640)))?;
    // The CSV of `stickslip phase-diagram --lyapunov --out`: the library's table of a map.
    report.table("paper-exponents.csv", &MapReport::new(points, true))?;

    // Rest (never leaving it, or an amplitude below β/100) has λ1 = 0 exactly or contracts;
    // the motions that move are the ones that could be chaotic.
    let moving: Vec<&GridPoint> = points
        .iter()
        .filter(|p| p.class != MotionClass::Static)
        .collect();
    let repeating = points.iter().filter(|p| p.period.is_some()).count();
    let positive = points.iter().filter(|p| lambda(p) > 0.0).count();
    let top = moving
        .iter()
        .max_by(|a, b| lambda(a).total_cmp(&lambda(b)))
        .expect("moving points");
    report.summary.insert(
        "beyond_paper_exponents".into(),
        json!({
            "grid": [n, n],
            "repeating": repeating,
            "nonperiodic": points.len() - repeating,
            "moving": moving.len(),
            "positive": positive,
            "largest_moving": {"w": top.params.w, "beta": top.params.beta,
                               "lambda1": lambda(top)},
        }),
    );
    let chaos = report.summary.get("beyond_chaos_map").and_then(|m| {
        Some((
            m["chaotic"].as_u64()?,
            m["grid"][0].as_u64()? * m["grid"][1].as_u64()?,
            m["periodic_with_positive_exponent"].as_u64()?,
            m["undecided"].as_u64()?,
        ))
    });
    let contrast = match chaos {
        Some((chaotic, total, positive_periodic, undecided)) => format!(
            "With static friction above kinetic, motions that do not repeat exist, chaos among \
             them: at μs = 3 (ζ = 0, the map above) {chaotic} of {total} points do not repeat \
             and have λ1 positive beyond 4 standard errors{}{}.",
            if positive_periodic == 0 {
                ", while every motion there that repeats has λ1 &lt; 0"
            } else {
                ""
            },
            match undecided {
                0 => String::new(),
                n => format!(
                    "; {n} more do not repeat within the cap and have no verdict on λ1 \
                     (undecided, no class of motion)"
                ),
            }
        ),
        None => String::new(),
    };
    let verdict = if positive == 0 && repeating == points.len() {
        format!(
            "With μs = 1, as in the paper, the class is empty: every one of the {} motions \
             repeats (a period of at most 16 within 5000 drive periods) and none has a positive \
             exponent. Of the {} that move (not static), the largest λ1 is {} per unit τ, at \
             (Ω/ω0, β) = ({}, {}): every orbit attracts its neighbours.",
            points.len(),
            moving.len(),
            sig(lambda(top), 3),
            frequency(top.params.w),
            sig(top.params.beta, 3),
        )
    } else {
        format!(
            "With μs = 1, {} of the {} motions do not repeat within 5000 drive periods and {} \
             have a positive exponent; the largest λ1 among the moving ones is {} per unit τ at \
             (Ω/ω0, β) = ({}, {}).",
            points.len() - repeating,
            points.len(),
            positive,
            sig(lambda(top), 3),
            frequency(top.params.w),
            sig(top.params.beta, 3),
        )
    };
    let absent = positive == 0 && repeating == points.len();
    let conclusion = if absent {
        " So the paper's non-periodic motion with sticking is no motion of its circuit as \
         modelled (μs = 1): in our reading it comes from integrating sgn(ẋ) without stick \
         logic, which makes the velocity chatter at every stop (Fig. 6); with μs > 1 motions that do not \
         repeat exist, and the ones decided are chaos."
    } else {
        ""
    };
    let bar_top = if positive == 0 {
        ", and its upper end is as far above 0, in reds that no point takes: no exponent is \
         positive"
    } else {
        ", its upper end the largest exponent"
    };
    report.sections.push(Section {
        id: "paper-exponents".into(),
        title: "The paper's \"non-periodic motion with sticking\": absent at μs = 1, chaos at \
                μs > 1"
            .into(),
        caption: format!(
            "The paper names four motion classes, one of them non-periodic motion with \
             sticking (its Fig. 6c, at (0.7, 1.2), which the exact solver finds periodic: see \
             Fig. 6). Here is the largest Lyapunov exponent λ1 at every point of the paper's \
             map, its circuit with PWL diodes ({n} × {n} points, Ω/ω0 from 0.1 to 2.5, β from \
             0.5 to 4, each from rest): exactly ln|μ1|/(pT) from the Floquet multipliers where \
             the motion repeats, measured where it does not. {verdict} White: rest (λ1 = 0: \
             the oscillator stays wherever it stopped); the colour bar's lower end is the 2nd \
             percentile of the negative values{bar_top}. {contrast}{conclusion}",
        ),
        figures: vec!["paper-exponents".into()],
        data: vec!["paper-exponents.csv".into()],
        tables: vec![],
    });
    Ok(())
}
