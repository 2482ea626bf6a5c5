//! A basin map where two attractors coexist: an asymmetric orbit with one stop per period and
//! its mirror image, at ζ = 0, μs = 3, w = 0.6, β = 3.269.

use super::super::report::{sig, Report, Section};
use super::super::{Context, Later};
use anyhow::Result;
use serde_json::json;
use stickslip::basins::Basins;
use stickslip::report::BasinsTable;
use stickslip::scan::ParameterRange;
use stickslip::solver::run_until;
use stickslip::{ExactSolver, Experiment, Solver, State};

/// The basin map, its parameters and the seconds it took, computed alongside the other figures
/// from the start of `reproduce` ([`Later`]; the method of recurrences runs on one thread);
/// [`basins_mirror`] takes it.
pub struct BasinMap {
    map: stickslip::basins::BasinMap,
    params: stickslip::Params,
    seconds: f64,
}

impl BasinMap {
    /// Start computing the map (coarser with `quick`).
    pub fn start(quick: bool) -> Later<Self> {
        Later::start(move || {
            let range = ParameterRange::new("y0", -8.0, 8.0, side(quick))?;
            let experiment = Experiment::dimensionless(0.0, 0.6, 3.269)?.with_mu_s(3.0)?;
            let basins = Basins::new(&experiment, &range, &range)?;
            let started = std::time::Instant::now();
            let map = basins.run(&|_: usize, _: usize| !crate::output::interrupted())?;
            Ok(Self {
                map,
                params: *basins.params(),
                seconds: started.elapsed().as_secs_f64(),
            })
        })
    }
}

/// Cells a side of the map.
fn side(quick: bool) -> usize {
    if quick {
        50
    } else {
        120
    }
}

/// The basins of the mirror pair over initial states from −8 to 8.
pub fn basins_mirror(report: &mut Report, ctx: &Context) -> Result<()> {
    let n = side(ctx.quick);
    let BasinMap {
        map,
        params,
        seconds,
    } = ctx.basins.take()?;
    // The time goes to standard error: the report itself is the same on every run.
    eprintln!(
        "reproduce: {n} × {n} basin map in {seconds:.1} s (alongside the chapters before it)"
    );
    crate::output::check_interrupt()?;
    let title = "basins of attraction at ζ = 0, μs = 3, w = 0.6, β = 3.269 (drive phase 0)";
    report.figure(
        "beyond-basins",
        &crate::plot::Figure::single(crate::diagrams::basin_panel(&map, title), (900, 650)),
    )?;
    // The CSV of `stickslip basins --out`: the library's table of a basin map.
    report.table("beyond-basins.csv", &BasinsTable { map: &map })?;

    // The two orbits are mirror images: half a period on, one is minus the other.
    let mirror_gap = match map.attractors.as_slice() {
        [a, b, ..] => {
            let mut solver = ExactSolver::new(params, a.state);
            run_until(&mut solver, 0.5 * params.drive_period(), |_| {})?;
            let half: State = solver.state();
            (half.y + b.state.y).abs().max((half.v + b.state.v).abs())
        }
        _ => f64::NAN,
    };
    let attractors: Vec<serde_json::Value> = map
        .attractors
        .iter()
        .map(|a| {
            json!({
                "id": a.id, "kind": a.kind.label(), "period": a.period,
                "fraction": a.fraction, "y": a.state.y, "v": a.state.v,
                "multipliers": a.multipliers.map(|m| [m[0].re, m[1].re]),
            })
        })
        .collect();
    report.summary.insert(
        "beyond_basins".into(),
        json!({
            "zeta": 0.0, "mu_s": 3.0, "w": 0.6, "beta": 3.269,
            "grid": n, "y0_range": [-8.0, 8.0], "v0_range": [-8.0, 8.0],
            "attractors": attractors, "undecided": map.undecided,
            "mirror_gap": mirror_gap,
        }),
    );
    let describe = |i: usize| {
        map.attractors.get(i).map_or("—".to_string(), |a| {
            format!(
                "(y, y') = ({}, {}), {} % of the grid",
                sig(a.state.y, 5),
                sig(a.state.v, 5),
                sig(100.0 * a.fraction, 3)
            )
        })
    };
    let multiplier = map
        .attractors
        .first()
        .and_then(|a| a.multipliers)
        .map_or("—".to_string(), |m| sig(m[0].re, 5));
    let caption = format!(
        "Which motion the oscillator settles on from each initial state (y0, y0') at drive \
         phase 0, on a {n} × {n} grid, at ζ = 0, μs = 3, w = 0.6, β = 3.269. {} attractors \
         coexist, both periodic orbits of period 1 with one stop per drive period: #0 with its \
         strobe point (dot) at {}, #1 at {}. They are mirror images under the symmetry of the \
         equation, (y, y', τ) → (−y, −y', τ + T/2): half a period after #0's strobe the state is \
         minus #1's to {:.1e}, and both have the Floquet multiplier {multiplier} (one stop per \
         period cannot be symmetric, so the orbit comes in a pair). Their basins wind round \
         each other in arms. Each cell runs to its steady state (the strobe map extrapolated \
         where it converges linearly), its orbit refined by Newton's method and matched by \
         its fixed point; {} cells undecided. <code>stickslip basins \
         --zeta 0 --mu-s 3 --w 0.6 --beta 3.269 --y0-min -8 --y0-max 8 --v0-min -8 --v0-max 8 \
         --steps {n} --plot basins.png --json</code>.",
        map.attractors.len(),
        describe(0),
        describe(1),
        mirror_gap,
        map.undecided,
    );
    report.sections.push(Section {
        id: "beyond-basins".into(),
        title: "Basins of two coexisting orbits (ζ = 0, μs = 3, w = 0.6, β = 3.269)".into(),
        caption,
        figures: vec!["beyond-basins".into()],
        data: vec!["beyond-basins.csv".into()],
        ..Default::default()
    });
    Ok(())
}
