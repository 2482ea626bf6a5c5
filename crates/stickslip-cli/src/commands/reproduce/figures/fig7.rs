//! Fig. 7: stick-slip phase diagrams over the paper's range, PWL and Shockley diodes.

use super::super::beyond::paper_exponent_map;
use super::super::report::{Report, Section};
use super::super::{Context, Later};
use crate::plot::{class_color, Cell, Figure, Legend, Panel};
use anyhow::Result;
use serde_json::{json, Value};
use stickslip::report::MapReport;
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

    let mut a = pwl.panel("(a) PWL diodes (exact solver)");
    a.series
        .extend(super::theory_curves::boundary_curves(ctx, 0.1, 2.5)?);
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
    report.summary.insert("fig7a".into(), pwl.summary());
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
             {}",
            pwl.describe(),
            shockley.describe(),
            100.0 * shockley.sliding_fraction(),
            100.0 * pwl.sliding_fraction(),
            super::theory_curves::BOUNDARY_NOTE
        ),
        figures: vec!["fig7".into()],
        data: vec!["fig7a.csv".into(), "fig7b.csv".into()],
        tables: vec![],
    });
    Ok(())
}
