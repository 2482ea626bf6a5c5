//! `GET /api/map`: motion classes on a (w, β) grid, with the stick-slip boundaries.

use super::answer::*;
use super::caps::CAPS;
use super::request::*;
use crate::limit::Budget;
use crate::query::{ApiError, Query};
use serde::Serialize;
use std::sync::Arc;
use stickslip::experiment::Experiment;
use stickslip::report::MapReport;
use stickslip::scan::{Axis, Grid, ParameterRange};
use stickslip::steady::SteadyOptions;
use stickslip::theory::curves::{abscissae, theory_curve, Theory, TheoryQuantity};
use stickslip::{Error, OptionKey, Parameter};

/// The options of a map's sides, in the order of the query keys' documentation.
const MAP_OPTIONS: [OptionKey; 6] = [
    OptionKey::MapWMin,
    OptionKey::MapWMax,
    OptionKey::MapWSteps,
    OptionKey::MapBetaMin,
    OptionKey::MapBetaMax,
    OptionKey::MapBetaSteps,
];

/// `GET /api/map`.
#[derive(Debug)]
pub struct MapRequest {
    experiment: Experiment,
    w: ParameterRange,
    beta: ParameterRange,
    options: SteadyOptions,
}

/// The answer of `/api/map`: motion classes on a (w, β) grid, each point from the initial
/// state, as `stickslip phase-diagram` computes them: the library's map report.
#[derive(Debug, Serialize)]
pub struct MapAnswer {
    /// The experiment.
    #[serde(flatten)]
    pub about: About,
    /// The frequencies w (rows of the grid).
    pub w: Vec<f64>,
    /// The amplitudes β (columns of the grid).
    pub beta: Vec<f64>,
    /// The library's map report (`lyapunov`, `points`), the shape of every front end's map:
    /// point (w_i, β_j) at i·(number of β) + j, with the columns of `stickslip
    /// phase-diagram`'s CSV as its fields.
    #[serde(flatten)]
    pub report: MapReport,
    /// The stick-slip boundaries over w inside the β range (null elsewhere).
    pub boundary: Boundary,
}

/// Stick-slip boundaries β_c over w.
#[derive(Debug, Serialize)]
pub struct Boundary {
    /// Frequencies.
    pub w: Vec<f64>,
    /// The paper's eq. (13).
    pub paper: Vec<f64>,
    /// The exact β_c(w, ζ, μs).
    pub exact: Vec<f64>,
    /// `PWL theory: ` with Shockley diodes, else empty.
    pub prefix: &'static str,
}

impl MapRequest {
    /// Keys: the model keys (without w or β), `w-min`, `w-max`, `w-steps` (default 0.1 to
    /// 2.5 in 60), `beta-min`, `beta-max`, `beta-steps` (default 0.5 to 4 in 50), at most
    /// 1000 on a side and 40000 points; `tolerance`, `max-periods`, `max-period`.
    ///
    /// # Errors
    /// A 400 naming the key at fault.
    pub fn parse(raw: Option<&str>) -> Result<Self, ApiError> {
        let mut q = Query::parse(raw)?;
        reject_swept(&q, Parameter::W, "a map")?;
        reject_swept(&q, Parameter::Beta, "a map")?;
        let experiment = q.experiment()?;
        let w = side(
            &mut q,
            [OptionKey::MapWMin, OptionKey::MapWMax],
            OptionKey::MapWSteps,
            60,
            &|n| CAPS.check_map(n, 1),
        )?;
        let beta = side(
            &mut q,
            [OptionKey::MapBetaMin, OptionKey::MapBetaMax],
            OptionKey::MapBetaSteps,
            50,
            &|n| CAPS.check_map(1, n),
        )?;
        CAPS.check_map(w.steps(), beta.steps())
            .map_err(|e| option_error(&e))?;
        let options = steady_options(&mut q, &experiment)?;
        q.finish(&known(&[&MAP_OPTIONS[..], &STEADY_OPTIONS].concat(), &[]))?;
        Grid::new(
            &experiment,
            grid_axis(&w, Parameter::W)?,
            grid_axis(&beta, Parameter::Beta)?,
        )
        .map_err(|e| ApiError::library(&e))?;
        Ok(Self {
            experiment,
            w,
            beta,
            options,
        })
    }

    /// Classify every point, as `stickslip phase-diagram` does.
    ///
    /// # Errors
    /// The time limit; the library's errors.
    pub fn run(self, budget: &Arc<Budget>) -> Result<MapAnswer, ApiError> {
        let e = &budget.limit_experiment(&self.experiment);
        let library = |err: Error| ApiError::library(&err);
        let grid = Grid::new(
            e,
            Axis::range(Parameter::W, &self.w).map_err(library)?,
            Axis::range(Parameter::Beta, &self.beta).map_err(library)?,
        )
        .map_err(library)?
        .options(self.options)
        .map_err(library)?;
        let (rows, cols) = grid.shape();
        let total = rows * cols;
        budget.start(total);
        // Block by block (a grid computed so equals the grid computed at once), so that the
        // map gives its turn to other clients between blocks of about one slice: the blocks'
        // points run on the parallel pool, whose threads must never wait for a turn.
        let keep_going = budget.keep_going();
        let mut points = Vec::with_capacity(total);
        let mut size = 2 * rayon::current_num_threads();
        while points.len() < total {
            let next = points.len();
            let (row, col) = (next / cols, next % cols);
            let (block_rows, block_cols) = if col == 0 && size >= cols {
                (row..(row + size / cols).min(rows), 0..cols)
            } else {
                (row..row + 1, col..(col + size).min(cols))
            };
            let n = block_rows.len() * block_cols.len();
            let started = std::time::Instant::now();
            points.extend(
                grid.run_block(block_rows, block_cols, &|done, _| {
                    keep_going(next + done, total)
                })
                .map_err(|err| failed(err, budget, "map"))?,
            );
            let per_point = started.elapsed().as_secs_f64() / n as f64;
            size =
                ((crate::fair::SLICE.as_secs_f64() / per_point.max(1e-9)) as usize).clamp(1, total);
            budget.share();
        }
        let map = stickslip::scan::GridMap {
            first: grid_axis(&self.w, Parameter::W)?,
            second: grid_axis(&self.beta, Parameter::Beta)?,
            points,
        };
        // The boundaries of the PWL theory, where they lie inside the β range.
        let ws = abscissae(self.w.from(), self.w.to(), self.w.steps());
        let base = e
            .params_with(&[
                (Parameter::W, self.w.from()),
                (Parameter::Beta, self.beta.from()),
            ])
            .map_err(library)?;
        let boundary = |theory| {
            theory_curve(theory, TheoryQuantity::Boundary, &base, Parameter::W, &ws)
                .within(self.beta.from(), self.beta.to())
                .y
        };
        Ok(MapAnswer {
            about: About::new(e),
            w: map.first.values().to_vec(),
            beta: map.second.values().to_vec(),
            report: MapReport::new(&map.points, false),
            boundary: Boundary {
                paper: boundary(Theory::Paper),
                exact: boundary(Theory::Exact),
                w: ws,
                prefix: pwl_prefix(e),
            },
        })
    }
}
