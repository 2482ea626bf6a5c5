//! Fig. 7: stick-slip phase diagrams over the paper's range, PWL and Shockley diodes.

use super::super::beyond::paper_exponent_map;
use super::super::report::{sig, Report, Section};
use super::super::{Context, Later};
use super::fig7_curves::{check_edges, stop_curves, MapGrid};
use crate::plot::{class_color, Cell, Figure, Legend, Panel, Series, Style};
use anyhow::Result;
use plotters::style::RGBColor;
use serde_json::{json, Value};
use stickslip::report::{CurveTable, MapReport};
use stickslip::scan::{Axis, Grid, GridPoint, ParameterRange};
use stickslip::stability::SEARCH_BEFORE_MEASURING;
use stickslip::steady::MotionClass;
use stickslip::{DiodePair, Experiment, Parameter};

/// Drive periods the steady-state search of the Shockley map runs at most (5000 by default).
/// Every point of the map whose strobe repeats does so within 72 periods; at a few sliding
/// points (4 of the 64 × 64) the stiff solver's strobe wanders within about its rtol without
/// repeating to it, and the search ran the whole cap there, a quarter of the map's time. The
/// class of those points is the same after 500 periods as after 5000 (sliding, no period),
/// and their gain, measured over the last period, agrees far within that rtol (10⁻⁶): to
/// 3·10⁻¹¹ relative on the 64 × 64 map, 2.3·10⁻⁸ at 2 points of the quick report's 24 × 24.
/// Since Newton settles Shockley points too, those 2 points of the 24 × 24 settle on the
/// period-1 orbit their strobes wander around (gain within 1.7·10⁻⁶ of the wandering one).
const SHOCKLEY_MAX_PERIODS: usize = 500;

/// The grazing curves' legend entry.
const GRAZING_LABEL: &str = "grazing curves";

/// A map from rest over the paper's range, with its grid.
struct Map {
    points: Vec<GridPoint>,
    w: ParameterRange,
    beta: ParameterRange,
}

impl Map {
    /// The map of `experiment` from rest on an n × n grid, with the experiment's own
    /// steady-state options, the search capped at `max_periods` drive periods.
    fn compute(experiment: &Experiment, n: usize, max_periods: usize) -> Result<Self> {
        let w = ParameterRange::new("w", 0.1, 2.5, n)?;
        let beta = ParameterRange::new("beta", 0.5, 4.0, n)?;
        let started = std::time::Instant::now();
        let mut grid = Grid::new(
            experiment,
            Axis::range(Parameter::W, &w)?,
            Axis::range(Parameter::Beta, &beta)?,
        )?;
        grid = grid.options(experiment.steady_options().with_max_periods(max_periods)?)?;
        let points = grid
            .run(&|_: usize, _: usize| !crate::output::interrupted())?
            .points;
        // The time goes to standard error: the report itself is the same on every run.
        eprintln!(
            "reproduce: {} × {} map in {:.1} s",
            w.steps(),
            beta.steps(),
            started.elapsed().as_secs_f64()
        );
        Ok(Self { points, w, beta })
    }

    /// The PWL map of the paper's experiment from rest (200 × 200, 60 × 60 with --quick),
    /// taken from the paper's map of exponents ([`paper_exponent_map`], which the chapter
    /// "Beyond the paper" shows) wherever that map's strobe search repeated within its first
    /// [`SEARCH_BEFORE_MEASURING`] periods: the search is causal, so the full search of the
    /// plain map finds the same cycle at the same strobe, and the point (class, period, stops,
    /// gain) is the same, bit for bit. Elsewhere the plain map's search runs afresh.
    fn paper(ctx: &Context) -> Result<Self> {
        let exponents = paper_exponent_map(ctx)?;
        let started = std::time::Instant::now();
        let n = if ctx.quick { 60 } else { 200 };
        let w = ParameterRange::new("w", 0.1, 2.5, n)?;
        let beta = ParameterRange::new("beta", 0.5, 4.0, n)?;
        let grid = Grid::new(
            &ctx.paper,
            Axis::range(Parameter::W, &w)?,
            Axis::range(Parameter::Beta, &beta)?,
        )?;
        let mut again = 0;
        let points = exponents
            .iter()
            .enumerate()
            .map(|(k, p)| {
                if p.period.is_some() && p.periods_to_settle < SEARCH_BEFORE_MEASURING {
                    Ok(GridPoint {
                        lyapunov: None,
                        ..*p
                    })
                } else {
                    again += 1;
                    grid.point(k / n, k % n)
                }
            })
            .collect::<stickslip::Result<Vec<GridPoint>>>()?;
        eprintln!(
            "reproduce: {n} × {n} map from the exponents' map ({again} points searched again) \
             in {:.1} s",
            started.elapsed().as_secs_f64()
        );
        Ok(Self { points, w, beta })
    }

    fn count(&self, class: MotionClass) -> usize {
        self.points.iter().filter(|p| p.class == class).count()
    }

    fn sliding_fraction(&self) -> f64 {
        self.count(MotionClass::Sliding) as f64 / self.points.len() as f64
    }

    fn panel(&self, title: &str) -> Panel {
        let (dw, db) = (0.5 * self.w.spacing(), 0.5 * self.beta.spacing());
        let cells = self
            .points
            .iter()
            .map(|p| Cell {
                x: (p.params.w - dw, p.params.w + dw),
                y: (p.params.beta - db, p.params.beta + db),
                color: class_color(p.class),
            })
            .collect();
        let mut present: Vec<MotionClass> = self.points.iter().map(|p| p.class).collect();
        present.sort_by_key(|c| c.label());
        present.dedup();
        Panel {
            title: title.into(),
            x_label: "Ω/ω0".into(),
            y_label: "β = U/U_t".into(),
            cells,
            cell_legend: present
                .into_iter()
                .map(|c| (c.label().to_string(), class_color(c)))
                .collect(),
            x_range: Some((self.w.from() - dw, self.w.to() + dw)),
            y_range: Some((self.beta.from() - db, self.beta.to() + db)),
            legend: Some(Legend::UpperRight),
            ..Default::default()
        }
    }

    fn summary(&self) -> Value {
        json!({
            "grid": [self.w.steps(), self.beta.steps()],
            "sliding": self.count(MotionClass::Sliding),
            "periodic_stick": self.count(MotionClass::PeriodicStick),
            "undecided": self.count(MotionClass::Undecided),
            "static": self.count(MotionClass::Static),
            "sliding_fraction": self.sliding_fraction(),
        })
    }

    fn describe(&self) -> String {
        format!(
            "{n} × {n} grid: {} sliding, {} periodic stick, {} undecided, {} static",
            self.count(MotionClass::Sliding),
            self.count(MotionClass::PeriodicStick),
            self.count(MotionClass::Undecided),
            self.count(MotionClass::Static),
            n = self.w.steps(),
        )
    }
}

/// The map of fig. 7 (b), the Shockley model's, computed alongside the other figures from the
/// start of `reproduce` ([`Later`]); [`fig7`] takes it.
pub struct ShockleyMap(Map);

impl ShockleyMap {
    /// Start computing the map of `paper` with Shockley diodes (coarser with `quick`).
    pub fn start(paper: Experiment, quick: bool) -> Later<Self> {
        Later::start(move || {
            // The stiff solver's strobe map repeats only to its rtol (1e-6): the experiment's
            // own steady-state options say so, with the search capped at SHOCKLEY_MAX_PERIODS.
            Ok(Self(Map::compute(
                &paper.with_shockley(DiodePair::one_n4148())?,
                if quick { 24 } else { 64 },
                SHOCKLEY_MAX_PERIODS,
            )?))
        })
    }
}

/// Fig. 7 (a) the PWL model's map from rest, (b) the Shockley model's.
pub fn fig7(report: &mut Report, ctx: &Context) -> Result<()> {
    let pwl = Map::paper(ctx)?;
    let ShockleyMap(shockley) = ctx.shockley_map.take()?;

    // The edges between numbers of stops per period, traced as grazing curves from the PWL
    // map's own changes of region.
    let grid = MapGrid {
        points: &pwl.points,
        w: &pwl.w,
        beta: &pwl.beta,
    };
    let started = std::time::Instant::now();
    let traced = stop_curves(&ctx.paper, &grid)?;
    eprintln!(
        "reproduce: Fig. 7's {} grazing curves ({} starts tried) in {:.1} s",
        traced.curves.len(),
        traced.tried,
        started.elapsed().as_secs_f64()
    );
    let boundaries = super::theory_curves::boundary_curves(ctx, 0.1, 2.5)?;
    let exact = boundaries
        .iter()
        .find(|s| s.label == super::theory_curves::EXACT_LABEL)
        .map(|s| s.points.clone())
        .unwrap_or_default();
    let check = check_edges(&grid, &traced.curves, &exact);
    // One line for all the curves (a non-finite point between two curves breaks it), cut
    // where it leaves the map's range of w.
    let (w_lo, w_hi) = (
        pwl.w.from() - 0.5 * pwl.w.spacing(),
        pwl.w.to() + 0.5 * pwl.w.spacing(),
    );
    let mut line = Vec::new();
    for c in &traced.curves {
        if !line.is_empty() {
            line.push((f64::NAN, f64::NAN));
        }
        line.extend(c.points.iter().map(|p| {
            if (w_lo..=w_hi).contains(&p.vary) {
                (p.vary, p.over)
            } else {
                (f64::NAN, f64::NAN)
            }
        }));
    }
    let grazing =
        |label: &str| Series::new(label, line.clone(), RGBColor(0, 150, 0), Style::Line(2));

    let mut a = pwl.panel("(a) PWL diodes (exact solver)");
    a.series.extend(boundaries);
    if !traced.curves.is_empty() {
        a.series.push(grazing(GRAZING_LABEL));
    }
    let mut b = shockley.panel("(b) Shockley diodes (stiff solver)");
    // The curves are the PWL model's in both panels (the Shockley law has no closed-form
    // boundary): (b)'s legend says so.
    b.series.extend(
        super::theory_curves::boundary_curves(ctx, 0.1, 2.5)?
            .into_iter()
            .map(|mut s| {
                s.label = format!("PWL {}", s.label);
                s
            }),
    );
    if !traced.curves.is_empty() {
        b.series.push(grazing(&format!("PWL {GRAZING_LABEL}")));
    }
    report.figure(
        "fig7",
        &Figure {
            panels: vec![a, b],
            columns: 2,
            panel_size: (640, 540),
        },
    )?;
    // The CSV of `stickslip phase-diagram --out`: the library's table of a map.
    report.table("fig7a.csv", &MapReport::new(&pwl.points, false))?;
    report.table("fig7b.csv", &MapReport::new(&shockley.points, false))?;
    // The grazing curves one after another (each begins where its arclength is 0).
    let tables: Vec<CurveTable> = traced
        .curves
        .iter()
        .map(|curve| CurveTable { curve })
        .collect();
    report.tables(
        "fig7-grazing.csv",
        &[],
        tables.iter().map(|t| (Vec::new(), t)),
    )?;
    report.summary.insert("fig7a".into(), pwl.summary());
    report.summary.insert(
        "fig7a_curves".into(),
        json!({
            "curves": traced.curves.len(),
            "points": traced.curves.iter().map(|c| c.points.len()).sum::<usize>(),
            "starts_tried": traced.tried,
            "starts_without_grazing": traced.no_start,
            "stop_edges": check.stop_edges,
            "stop_edges_crossed": check.stop_edges_crossed,
            "pairs_crossed_odd": check.crossed,
            "pairs_crossed_odd_changing": check.crossed_changing,
            "pairs_crossed_even": check.crossed_even,
            "pairs_crossed_even_same": check.crossed_even_same,
            "sliding_edges": check.sliding_edges,
            "sliding_edges_crossed_by_beta_c": check.sliding_edges_crossed,
        }),
    );
    let mut stops: Vec<f64> = pwl
        .points
        .iter()
        .filter(|p| p.class == MotionClass::PeriodicStick)
        .map(|p| p.stops_per_period)
        .collect();
    stops.sort_by(f64::total_cmp);
    stops.dedup();
    let show = |s: &f64| {
        if s.fract() == 0.0 {
            format!("{s:.0}")
        } else {
            sig(*s, 3)
        }
    };
    let stop_counts = match stops.split_last() {
        Some((last, rest)) if !rest.is_empty() => format!(
            "{} or {}",
            rest.iter().map(show).collect::<Vec<_>>().join(", "),
            show(last)
        ),
        _ => stops.iter().map(show).collect::<String>(),
    };
    let curve_list = traced
        .curves
        .iter()
        .map(|c| {
            let range = |f: &dyn Fn(&stickslip::continuation::CurvePoint) -> f64| {
                c.points
                    .iter()
                    .map(f)
                    .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), x| {
                        (lo.min(x), hi.max(x))
                    })
            };
            let (b0, b1) = range(&|p| p.over);
            let (w0, w1) = range(&|p| p.vary);
            let start = &c.points[c.start];
            format!(
                "{} (the period-{} orbit with {} stops per period on its side; β from {} to \
                 {}, w from {} to {})",
                c.border.map_or("a grazing", |b| b.kind.words()),
                c.period,
                show(&start.stops_per_period()),
                sig(b0, 3),
                sig(b1, 3),
                sig(w0, 3),
                sig(w1, 3),
            )
        })
        .collect::<Vec<_>>()
        .join("; ");
    let percent = |part: usize, whole: usize| {
        if whole == 0 {
            "—".to_string()
        } else {
            format!("{:.0} %", 100.0 * part as f64 / whole as f64)
        }
    };
    let curves_note = format!(
        "The green lines are grazing curves traced exactly in (β, w) by `continuation::curve` \
         (stickslip curve --follow grazing --vary w --over beta), each started from a pair of \
         neighbouring cells of (a) along w whose numbers of stops per period differ and that \
         no curve traced before crosses (the orbit of the first cell continued in w towards \
         the second's up to its first grazing, then followed over β from 0.5 to 4): {} \
         curves from {} starts ({} of them met no grazing: the two cells' motions are \
         different attractors reached from rest): {}. Across each an event of the orbit \
         appears or disappears, and with it the number of stops per period changes. They lie on the map's edges: of the {} pairs of \
         neighbouring cells of (a) whose numbers of stops per period differ, {} ({}) have \
         the curves between their centres (crossing the segment that joins them an odd \
         number of times); of the {} pairs with the curves between them, {} ({}) change \
         region, and of the {} pairs that the curves cross twice (a region thinner than a \
         cell between them), {} do not; the exact β_c lies between {} of the {} pairs of \
         a sliding and a stick-slip cell ({}). \
         The edge between periodic stick and static is no bifurcation but the class's \
         threshold (an amplitude at most β/100): no curve is drawn there. The map's colours \
         give the class only: the stops per period of each cell ({} in the periodic \
         stick-slip cells of (a)) are in fig7a.csv's column stops_per_period, and the CSV \
         fig7-grazing.csv holds the curves, one after another.",
        traced.curves.len(),
        traced.tried,
        traced.no_start,
        if curve_list.is_empty() {
            "none".to_string()
        } else {
            curve_list
        },
        check.stop_edges,
        check.stop_edges_crossed,
        percent(check.stop_edges_crossed, check.stop_edges),
        check.crossed,
        check.crossed_changing,
        percent(check.crossed_changing, check.crossed),
        check.crossed_even,
        check.crossed_even_same,
        check.sliding_edges_crossed,
        check.sliding_edges,
        percent(check.sliding_edges_crossed, check.sliding_edges),
        stop_counts,
    );
    report.summary.insert("fig7b".into(), shockley.summary());
    report.sections.push(Section {
        id: "fig7".into(),
        title: "Fig. 7 — stick-slip phase diagrams".into(),
        caption: format!(
            "Class of the steady motion reached from rest over the paper's range (Ω/ω0 from \
             0.1 to 2.5, β from 0.5 to 4): (a) PWL diodes, exact solver ({}); (b) two Shockley \
             1N4148 diodes, stiff solver, β keeping its meaning U/0.7 V ({}). Sliding covers \
             {:.0} % of the Shockley map against {:.0} % of the PWL map: as the paper says, \
             the sliding region is broader with the smooth diode law, which conducts below \
             0.7 V. With Shockley diodes a stop is |i| below 1e-3·U_t/√(L/C) for more than \
             1 % of the drive period; the sliding share of (b) depends on that threshold, \
             since the current of a smooth diode law never stays exactly zero: a larger \
             threshold finds more stops and less sliding. The curves of (b) are the PWL \
             model's, as in (a), for comparison: the Shockley law has no closed-form boundary. \
             {} {curves_note}",
            pwl.describe(),
            shockley.describe(),
            100.0 * shockley.sliding_fraction(),
            100.0 * pwl.sliding_fraction(),
            super::theory_curves::BOUNDARY_NOTE
        ),
        figures: vec!["fig7".into()],
        data: vec![
            "fig7a.csv".into(),
            "fig7b.csv".into(),
            "fig7-grazing.csv".into(),
        ],
        tables: vec![],
    });
    Ok(())
}
