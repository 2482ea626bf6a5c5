//! The largest Lyapunov exponent and the motion classes on a (w, β) map at ζ = 0, μs = 3.

use super::super::report::{sig, Report, Section};
use super::super::{Context, Later};
use super::{frequency, literature};
use crate::plot::{class_color, Cell, ColorBar, Figure, Legend, Panel, Quantity, Series, Style};
use anyhow::Result;
use plotters::style::RGBColor;
use serde_json::json;
use stickslip::continuation::{curve, ContinuationOptions, Curve, CurveSpec, Follow};
use stickslip::report::{CurveTable, MapReport};
use stickslip::scan::{Axis, Grid, GridPoint, ParameterRange};
use stickslip::stability::{LyapunovOptions, SEARCH_BEFORE_MEASURING};
use stickslip::steady::MotionClass;
use stickslip::theory::curves::{abscissae, theory_curve, theory_value, Theory, TheoryQuantity};
use stickslip::{Parameter, SteadyOptions};

/// Drive periods of the steady-state search, and the most measured, at every point of the
/// map. 1600 = 20 blocks of 80 periods: the sequential measurement looks after 200, 400, 800
/// and 1600 periods (2000 looked after 240, 500, 1000, 2000). The test
/// `the_reports_exponent_map_keeps_every_verdict_of_the_long_run`
/// (crates/stickslip/tests/lyapunov_sequential.rs) checks these options and [`TRANSIENT`]
/// against the long run.
const PERIODS: usize = 1600;

/// Drive periods that align the tangent before a motion is measured. The measurement starts
/// where the strobe search left the motion, 300 periods from rest, so only the tangent needs
/// aligning with the most unstable direction; every chaotic motion of this map sticks, and a
/// stop leaves the Jacobian of rank one, aligned at once.
const TRANSIENT: usize = 20;

/// Points per axis of the map: the largest square with which `reproduce` takes no more CPU
/// than it did with 41 × 45 points before (e55716f; BENCHMARKS.md, "The report's exponent
/// map, 104 × 104"), with a margin of about 2 %.
const SIZE: usize = 104;
/// Points per axis of the quick report's map.
const QUICK_SIZE: usize = 22;

/// The exact boundary's legend entry: above it the sliding orbit exists, which rest need not
/// reach (the caption counts the points above it that stick from rest).
const BOUNDARY_LABEL: &str = "exact β_c: the sliding orbit exists above";

/// The curves drawn over the map, each from the orbit the motion settles on from rest at
/// (w, β), continued in w towards the third value up to its first special point of the kind,
/// then followed over β (3 to 14, both ways from β): the grazing at the map's left edge of
/// chaos (a slide of the period-1 orbit with three stops touches rest, and a stop appears
/// mid-swing), the fold of the period-1 orbit with one stop on the right, and the period
/// doubling of the period-3 orbit at the band's lower tip. (The grazing of the period-3 orbit
/// inside the band, from w = 0.48, β = 10 towards w = 0.3, is left out: it winds back and forth
/// in w and took 1.5 s of CPU for 170 points, a sixth of the whole report.) Starts found with `stickslip curve --zeta 0 --mu-s 3 --w W --beta B
/// --follow KIND --vary w --vary-to V --over beta --from 3 --to 14`.
const CURVES: [(Follow, f64, f64, f64); 3] = [
    (Follow::Grazing, 0.28, 8.0, 0.45),
    (Follow::Fold, 0.5, 12.0, 0.6),
    (Follow::PeriodDoubling, 0.44, 4.5, 0.6),
];

/// Most points of each curve each way: a few hundred in all, fast beside the map.
const CURVE_POINTS: usize = 150;

/// The followed kinds drawn, each with its legend entry, colour and CSV.
const KINDS: [(Follow, &str, RGBColor, &str); 3] = [
    (
        Follow::Grazing,
        "grazing curve",
        RGBColor(0, 150, 0),
        "chaos-map-grazing.csv",
    ),
    (
        Follow::Fold,
        "fold curve",
        RGBColor(230, 130, 0),
        "chaos-map-fold.csv",
    ),
    (
        Follow::PeriodDoubling,
        "period-doubling curve",
        RGBColor(150, 0, 200),
        "chaos-map-period-doubling.csv",
    ),
];

/// The curves of [`CURVES`] at ζ = 0, μs = 3.
fn curves() -> Result<Vec<Curve>> {
    let options = ContinuationOptions {
        max_points: CURVE_POINTS,
        ..ContinuationOptions::default()
    };
    CURVES
        .iter()
        .map(|&(follow, w, beta, vary_to)| {
            let experiment = literature()?.with_w(w)?.with_beta(beta)?;
            let spec = CurveSpec {
                follow,
                vary: Parameter::W,
                vary_to,
                over: Parameter::Beta,
                from: 3.0,
                to: 14.0,
            };
            let monitor = |_: usize, _: usize| !crate::output::interrupted();
            curve(&experiment, &spec, &options, &monitor)?
                .map_err(|no| anyhow::anyhow!("the chaos map's {} curve: {no}", follow.label()))
        })
        .collect()
}

/// The map's grid: its axes (w, β) and the measurement of its exponents.
fn axes(quick: bool) -> Result<(ParameterRange, ParameterRange, LyapunovOptions)> {
    let n = if quick { QUICK_SIZE } else { SIZE };
    let measure = LyapunovOptions {
        periods: PERIODS,
        transient_periods: TRANSIENT,
        ..SteadyOptions::DEFAULT_LYAPUNOV
    };
    Ok((
        ParameterRange::new("w", 0.2, 0.6, n)?,
        ParameterRange::new("beta", 3.0, 14.0, n)?,
        measure,
    ))
}

/// The points of the map and how long they took (seconds), computed alongside the other
/// figures from the start of `reproduce` ([`Later`]); [`chaos_map`] takes them.
pub struct ChaosMap {
    points: Vec<GridPoint>,
    curves: Vec<Curve>,
    seconds: f64,
}

impl ChaosMap {
    /// Start computing the map (coarser with `quick`).
    pub fn start(quick: bool) -> Later<Self> {
        Later::start(move || compute(quick))
    }
}

/// Every point of the map, from rest.
fn compute(quick: bool) -> Result<ChaosMap> {
    let (w, beta, measure) = axes(quick)?;
    let options = SteadyOptions::default()
        .with_spectrum(false)
        .with_max_periods(PERIODS)?
        .with_lyapunov(Some(measure))?;
    let started = std::time::Instant::now();
    let curves = curves()?;
    let points = Grid::new(
        &literature()?,
        Axis::range(Parameter::W, &w)?,
        Axis::range(Parameter::Beta, &beta)?,
    )?
    .options(options)?
    .lyapunov(measure)?
    .run(&|_: usize, _: usize| !crate::output::interrupted())?
    .points;
    Ok(ChaosMap {
        points,
        curves,
        seconds: started.elapsed().as_secs_f64(),
    })
}

/// The map of λ1 and of the classes over w 0.2–0.6, β 3–14, from rest.
pub fn chaos_map(report: &mut Report, ctx: &Context) -> Result<()> {
    let (w, beta, measure) = axes(ctx.quick)?;
    let (nw, nb) = (w.steps(), beta.steps());
    let looks = measure
        .looks()
        .iter()
        .map(|l| l.to_string())
        .collect::<Vec<_>>();
    let looks = match looks.split_last() {
        Some((last, rest)) if !rest.is_empty() => format!("{} or {last}", rest.join(", ")),
        _ => looks.join(""),
    };
    let ChaosMap {
        points,
        curves,
        seconds,
    } = ctx.chaos_map.take()?;
    // The time goes to standard error: the report itself is the same on every run.
    eprintln!(
        "reproduce: chaos map {nw} × {nb} in {seconds:.1} s (alongside the chapters before it)"
    );
    let lambda = |p: &GridPoint| p.lyapunov.map_or(f64::NAN, |l| l.per_tau);
    let error = |p: &GridPoint| p.lyapunov.map_or(f64::NAN, |l| l.error_per_tau);

    let values: Vec<f64> = points.iter().map(lambda).collect();
    let bar = ColorBar::for_values("λ1 per unit τ", &values);
    let (dw, db) = (0.5 * w.spacing(), 0.5 * beta.spacing());
    let cells = |color: &dyn Fn(&GridPoint) -> RGBColor| -> Vec<Cell> {
        points
            .iter()
            .map(|p| Cell {
                x: (p.params.w - dw, p.params.w + dw),
                y: (p.params.beta - db, p.params.beta + db),
                color: color(p),
            })
            .collect()
    };
    // The exact stick-slip boundary at μs = 3: above it the symmetric sliding orbit exists.
    let base = literature()?.params()?;
    let boundary = theory_curve(
        Theory::Exact,
        TheoryQuantity::Boundary,
        &base,
        Parameter::W,
        &abscissae(w.from() - dw, w.to() + dw, 300),
    )
    .within(beta.from() - db, beta.to() + db)
    .points();
    let boundary = || Quantity::ExactTheory.series(BOUNDARY_LABEL, boundary.clone());
    // The curves, one series per kind (a non-finite point between two curves breaks the line).
    let kind_series = |label: bool| -> Vec<Series> {
        KINDS
            .iter()
            .filter_map(|&(follow, name, color, _)| {
                let mut points = Vec::new();
                for c in curves.iter().filter(|c| c.follow == follow) {
                    if !points.is_empty() {
                        points.push((f64::NAN, f64::NAN));
                    }
                    // Outside the map's w the line breaks (not drawn along its edge).
                    let inside = |x: f64| (w.from() - dw..=w.to() + dw).contains(&x);
                    points.extend(c.points.iter().map(|p| {
                        if inside(p.vary) {
                            (p.vary, p.over)
                        } else {
                            (f64::NAN, f64::NAN)
                        }
                    }));
                }
                (!points.is_empty()).then(|| {
                    Series::new(if label { name } else { "" }, points, color, Style::Line(2))
                })
            })
            .collect()
    };
    let frame = |title: &str| Panel {
        title: title.into(),
        x_label: "w = Ω/ω0".into(),
        y_label: "β".into(),
        x_range: Some((w.from() - dw, w.to() + dw)),
        y_range: Some((beta.from() - db, beta.to() + db)),
        // (The upper left is uniformly periodic: nothing to hide there.)
        legend: Some(Legend::UpperLeft),
        series: [vec![boundary()], kind_series(true)].concat(),
        ..Default::default()
    };
    // The boundary's legend entry is in (a), with the classes: (b), beside its colour bar,
    // keeps its whole width for the map.
    let mut line = boundary();
    line.label.clear();
    let exponents = Panel {
        cells: cells(&|p| bar.color(lambda(p))),
        color_bar: Some(bar.clone()),
        series: [vec![line], kind_series(false)].concat(),
        legend: None,
        ..frame("(b) largest Lyapunov exponent λ1, ζ = 0, μs = 3")
    };
    let mut present: Vec<MotionClass> = MotionClass::ALL
        .into_iter()
        .filter(|&c| points.iter().any(|p| p.class == c))
        .collect();
    present.sort_by_key(|&c| MotionClass::ALL.iter().position(|&k| k == c));
    let classes = Panel {
        cells: cells(&|p| class_color(p.class)),
        cell_legend: present
            .iter()
            .map(|&c| (c.label().to_string(), class_color(c)))
            .collect(),
        legend: Some(Legend::LowerRight),
        ..frame("(a) motion classes from rest, ζ = 0, μs = 3")
    };
    report.figure(
        "chaos-map",
        &Figure {
            // The colour bar of (b) at the right edge of the figure.
            panels: vec![classes, exponents],
            columns: 2,
            panel_size: (760, 600),
        },
    )?;
    // The CSV of `stickslip phase-diagram --lyapunov --out`: the library's table of a map.
    report.table("chaos-map.csv", &MapReport::new(&points, true))?;
    // The curves of each kind in one CSV: the library's table of a curve, one after another
    // (each begins where its arclength is 0).
    for &(follow, _, _, file) in &KINDS {
        let tables: Vec<CurveTable> = curves
            .iter()
            .filter(|c| c.follow == follow)
            .map(|curve| CurveTable { curve })
            .collect();
        report.tables(file, &[], tables.iter().map(|t| (Vec::new(), t)))?;
    }
    let count = |c: MotionClass| points.iter().filter(|p| p.class == c).count();
    let top = points
        .iter()
        .max_by(|a, b| lambda(a).total_cmp(&lambda(b)))
        .expect("points");
    let positive_periodic = points
        .iter()
        .filter(|p| p.period.is_some() && lambda(p) > 0.0)
        .count();
    let chaotic: Vec<&GridPoint> = points
        .iter()
        .filter(|p| p.class == MotionClass::Chaotic)
        .collect();
    let sticking = chaotic.iter().filter(|p| p.stops_per_period > 0.0).count();
    // What (b) shows white: λ1 = 0 (rest) and slow contraction, within 5 % of the bar's
    // negative end.
    let faint = 0.05 * -bar.range.0;
    let at_rest = points.iter().filter(|p| lambda(p) == 0.0).count();
    let slow = points
        .iter()
        .filter(|p| p.period.is_some() && lambda(p) < 0.0 && lambda(p) > -faint)
        .count();
    // Below the exact boundary: no symmetric sliding orbit at that β (NaN: none at any β).
    let below = chaotic
        .iter()
        .filter(|p| {
            let beta_c = theory_value(Theory::Exact, TheoryQuantity::Boundary, &p.params)
                .unwrap_or(f64::NAN);
            !(p.params.beta >= beta_c)
        })
        .count();
    // Above the exact boundary the sliding orbit exists; rest need not lead to it.
    let above: Vec<&GridPoint> = points
        .iter()
        .filter(|p| {
            theory_value(Theory::Exact, TheoryQuantity::Boundary, &p.params)
                .is_some_and(|beta_c| p.params.beta >= beta_c)
        })
        .collect();
    let above_sticking = above
        .iter()
        .filter(|p| p.class != MotionClass::Sliding)
        .count();
    report.summary.insert(
        "beyond_chaos_map".into(),
        json!({
            "zeta": 0.0, "mu_s": 3.0,
            "w": [w.from(), w.to()], "beta": [beta.from(), beta.to()],
            "grid": [nw, nb],
            "max_periods": PERIODS, "lyapunov_periods": PERIODS,
            "lyapunov_transient": TRANSIENT,
            "sliding": count(MotionClass::Sliding),
            "periodic_stick": count(MotionClass::PeriodicStick),
            "undecided": count(MotionClass::Undecided),
            "static": count(MotionClass::Static),
            "chaotic": count(MotionClass::Chaotic),
            "periodic_with_positive_exponent": positive_periodic,
            "chaotic_with_stops": sticking,
            "chaotic_below_exact_boundary": below,
            "above_exact_boundary": above.len(),
            "above_exact_boundary_not_sliding": above_sticking,
            "largest": {"w": top.params.w, "beta": top.params.beta,
                        "lambda1": lambda(top), "lambda1_error": error(top)},
        }),
    );
    let curve_list = curves
        .iter()
        .map(|c| {
            let (lo, hi) = c
                .points
                .iter()
                .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), p| {
                    (a.min(p.over), b.max(p.over))
                });
            let (wlo, whi) = c
                .points
                .iter()
                .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), p| {
                    (a.min(p.vary), b.max(p.vary))
                });
            format!(
                "the {} of the period-{} orbit for β from {} to {} (w from {} to {}, {} points)",
                c.follow.label(),
                c.period,
                sig(lo, 3),
                sig(hi, 3),
                sig(wlo, 3),
                sig(whi, 3),
                c.points.len()
            )
        })
        .collect::<Vec<_>>()
        .join("; ");
    report.sections.push(Section {
        id: "chaos-map".into(),
        title: "Chaos at ζ = 0, μs = 3: the (w, β) map of the largest Lyapunov exponent".into(),
        caption: format!(
            "(a) The motion class and (b) the largest Lyapunov exponent λ1 at every point of a \
             {nw} × {nb} grid (w from 0.2 to 0.6, β from 3 to 14), each from rest. Every point \
             is followed until its strobe repeats (a period up to 16); where it repeats, λ1 is \
             the exact ln|μ1|/(pT) of its orbit's largest Floquet multiplier. A motion that has \
             not repeated after {SEARCH_BEFORE_MEASURING} drive periods is measured from there \
             by its exact tangent dynamics ({TRANSIENT} periods to align the tangent, then \
             at most {PERIODS} periods in 20 blocks, stopping at the first look, after {looks} \
             periods, where λ1 is beyond 4 standard errors and the halves of the blocks agree): \
             chaotic when λ1 > 0, contracting onto a periodic motion not reached yet when \
             λ1 &lt; 0; a motion still undecided is followed for up to {PERIODS} periods from rest \
             and measured again there. Red: chaos (λ1 > 0); blue: contraction onto a periodic motion \
             (the bar's lower end is the 2nd percentile of the negative values, lower ones take \
             its colour); white or nearly: λ1 within {} of 0, that is {at_rest} points with \
             λ1 = 0 (at rest: β ≤ μs never moves from rest) and {slow} periodic motions that \
             contract slowly (λ1 &lt; 0 by less than 5 % of the bar's lower end). {} of the {} \
             points are chaotic, {} do not repeat without being chaotic (they contract onto a \
             periodic motion not reached, or are undecided), and {}. The largest exponent, {} \
             ± {} per unit τ, is at (w, β) = ({}, {}). {} of the {} chaotic motions stick, and \
             {} lie below the exact stick-slip boundary (black). Above that boundary the \
             symmetric sliding orbit exists, which is not to say that rest leads to it: {} of \
             the {} points above it do not slide from rest (another motion coexists there and \
             attracts rest). Over both panels, curves traced exactly in (β, w) by \
             `continuation::curve` (stickslip curve): {curve_list}. The green grazing curve on \
             the left is the left edge of the chaotic band between the β its curve covers: there \
             a slide of the period-1 orbit with three stops touches rest, a stop appears \
             mid-swing and the strobe map jumps with no orbit of that period past it, so rest \
             leads to chaos on its right; the fold (orange) ends the period-1 orbit with one \
             stop, right of which rest reaches the sliding orbit; the period doubling (violet) \
             is a special point of the period-3 orbit at the band's lower tip. Each curve ends where its event \
             sequence changes, where no orbit can be corrected past (the map jumps) or at \
             {CURVE_POINTS} points each way; the CSVs chaos-map-grazing.csv, chaos-map-fold.csv \
             and chaos-map-period-doubling.csv hold them, one after another.{}",
            sig(faint, 2),
            count(MotionClass::Chaotic),
            points.len(),
            count(MotionClass::Undecided),
            if positive_periodic == 0 {
                "every periodic orbit found has λ1 &lt; 0 (it attracts: it was reached from rest)"
                    .to_string()
            } else {
                format!("{positive_periodic} periodic orbits have λ1 > 0")
            },
            sig(lambda(top), 3),
            sig(error(top), 2),
            frequency(top.params.w),
            sig(top.params.beta, 3),
            sticking,
            chaotic.len(),
            below,
            above_sticking,
            above.len(),
            if ctx.quick {
                format!(" (--quick: a coarser grid than the full report's {SIZE} × {SIZE}.)")
            } else {
                String::new()
            }
        ),
        figures: vec!["chaos-map".into()],
        data: [&["chaos-map.csv"][..], &KINDS.map(|k| k.3)]
            .concat()
            .iter()
            .map(|f| f.to_string())
            .collect(),
        tables: vec![],
    });
    Ok(())
}
