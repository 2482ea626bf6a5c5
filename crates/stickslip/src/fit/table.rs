//! The problem of a table of measured amplitudes ([`fit_table`]): each row's steady
//! amplitude against the measured one, rows with a direction computed along their sweep.

use super::*;
use crate::experiment::Experiment;
use crate::measure::{AmplitudeTable, Direction};
use crate::params::State;
use crate::physical::System;
use crate::steady::MotionClass;
use rayon::prelude::*;

/// The problem of a table.
pub(super) struct Table<'a> {
    pub(super) setup: &'a Setup,
    pub(super) table: &'a AmplitudeTable,
    /// Rows in computing order: legs (each a list of row indices, each row settling from the
    /// previous one) and single rows from rest.
    pub(super) legs: Vec<Vec<usize>>,
    /// Who is told of each iteration.
    pub(super) watch: Watch<'a>,
}

impl Table<'_> {
    /// (amplitude in V, class) of every row, or None outside the model's domain.
    pub(super) fn amplitudes(&self, x: &[f64]) -> Option<Vec<(f64, MotionClass)>> {
        let experiment = self.setup.at(x)?;
        let legs: Vec<Option<Vec<(usize, f64, MotionClass)>>> = self
            .legs
            .par_iter()
            .map(|leg| {
                let mut state = State::default();
                let mut out = Vec::with_capacity(leg.len());
                for &i in leg {
                    let row = &self.table.rows[i];
                    let e = experiment
                        .clone()
                        .with_frequency(row.frequency)
                        .and_then(|e| e.with_amplitude(row.drive))
                        .and_then(|e| e.with_initial(state))
                        .ok()?;
                    let steady = e.steady_with(&self.setup.steady).ok()?;
                    state = steady.final_state();
                    let scale = e.scales()?.position;
                    out.push((i, steady.amplitude() * scale, steady.class));
                }
                Some(out)
            })
            .collect();
        let mut rows = vec![(0.0, MotionClass::Static); self.table.rows.len()];
        for leg in legs {
            for (i, a, c) in leg? {
                rows[i] = (a, c);
            }
        }
        Some(rows)
    }
}

impl lm::Problem for Table<'_> {
    type Error = FitError;

    fn residuals(&mut self, x: &[f64]) -> Result<Option<Vec<f64>>, FitError> {
        self.setup.check_stop()?;
        Ok(self.amplitudes(x).map(|a| {
            a.iter()
                .zip(&self.table.rows)
                .map(|((m, _), row)| m - row.response)
                .collect()
        }))
    }

    fn jacobian(&mut self, x: &[f64], r: &[f64]) -> Result<Vec<Vec<f64>>, FitError> {
        self.setup.check_stop()?;
        let h = self.setup.step;
        (0..x.len())
            .map(|k| {
                let mut xp = x.to_vec();
                let mut dx = h * x[k].abs().max(1.0);
                xp[k] += dx;
                let rp = match self.residuals(&xp)? {
                    Some(rp) => Some(rp),
                    None => {
                        xp[k] = x[k] - dx;
                        dx = -dx;
                        self.residuals(&xp)?
                    }
                };
                let rp = rp.ok_or_else(|| FitError::Model {
                    file: self.table.file.clone(),
                    error: crate::Error::InvalidParameter {
                        name: "fit parameter",
                        value: x[k] * self.setup.scale[k],
                        allowed: "the model has no value on either side",
                    },
                })?;
                Ok(rp.iter().zip(r).map(|(a, b)| (a - b) / dx).collect())
            })
            .collect()
    }

    fn iteration(&mut self, iteration: usize, sum_squares: f64) -> Result<(), FitError> {
        self.watch.tell(iteration, sum_squares)
    }

    /// The table's precision (V²): 10⁻⁹ of its largest amplitude, as a record's channel
    /// without noise or a known resolution ([`noise_floor`]); the digits a table prints are
    /// not kept, and the model's amplitudes are no finer.
    fn floor(&self) -> f64 {
        let responses: Vec<f64> = self.table.rows.iter().map(|r| r.response).collect();
        noise_floor(0.0, &responses, None).powi(2)
    }
}

/// Fit the free parameters of `experiment` to a table of measured amplitudes (see the module
/// documentation).
///
/// # Errors
/// As [`fit_records`].
pub fn fit_table(
    experiment: &Experiment,
    table: &AmplitudeTable,
    free: &[FitParameter],
    options: &FitOptions,
) -> Result<FitReport, FitError> {
    fit_table_monitored(experiment, table, free, options, &())
}

/// [`fit_table`], telling `monitor` of every iteration (at most
/// [`FitOptions::max_iterations`]), which can stop the fit.
///
/// # Errors
/// As [`fit_table`]; [`FitError::Stopped`] when the monitor stops the fit.
pub fn fit_table_monitored(
    experiment: &Experiment,
    table: &AmplitudeTable,
    free: &[FitParameter],
    options: &FitOptions,
    monitor: &dyn FitMonitor,
) -> Result<FitReport, FitError> {
    if table.rows.is_empty() {
        return Err(FitError::NoData);
    }
    let setup = Setup::new(experiment, free)?;
    if matches!(setup.system, System::Mechanics(_)) {
        return Err(FitError::TableNeedsCircuit);
    }
    if table.rows.len() <= free.len() {
        return Err(FitError::TooFewSamples {
            residuals: table.rows.len(),
            values: free.len(),
        });
    }
    // Legs: rows of one direction and one drive amplitude (to 10⁻⁶), sorted along the sweep.
    let mut legs: Vec<(Direction, f64, Vec<usize>)> = Vec::new();
    let mut singles = Vec::new();
    for (i, row) in table.rows.iter().enumerate() {
        match row.direction {
            None => singles.push(vec![i]),
            Some(d) => match legs
                .iter_mut()
                .find(|(ld, u, _)| *ld == d && (u - row.drive).abs() <= 1e-6 * u.abs())
            {
                Some(leg) => leg.2.push(i),
                None => legs.push((d, row.drive, vec![i])),
            },
        }
    }
    let mut order: Vec<Vec<usize>> = legs
        .into_iter()
        .map(|(d, _, mut rows)| {
            rows.sort_by(|&a, &b| {
                let (fa, fb) = (table.rows[a].frequency, table.rows[b].frequency);
                match d {
                    Direction::Up => fa.total_cmp(&fb),
                    Direction::Down => fb.total_cmp(&fa),
                }
            });
            rows
        })
        .collect();
    order.extend(singles);
    let mut problem = Table {
        setup: &setup,
        table,
        legs: order,
        watch: Watch {
            monitor,
            before: 0,
            total: options.max_iterations,
        },
    };
    let x = vec![1.0; free.len()];
    if problem.amplitudes(&x).is_none() {
        return Err(FitError::Model {
            file: table.file.clone(),
            error: crate::Error::InvalidParameter {
                name: "fit",
                value: f64::NAN,
                allowed: "a model that can be computed at the starting values",
            },
        });
    }
    let solution = lm::minimise(
        &mut problem,
        x,
        lm::Settings {
            max_iterations: options.max_iterations,
            tolerance: options.tolerance,
            gradient: lm::GRADIENT,
        },
    )?
    .expect("the start was evaluated");
    let n_values = free.len();
    let dof = solution.residuals.len().saturating_sub(n_values).max(1);
    let covariance = Covariance::of(&solution, n_values);
    let t = t_quantile_975(dof);
    let s2 = variance(solution.sum_squares, dof, lm::Problem::floor(&problem));
    let linear: Vec<([f64; 2], Interval)> = (0..n_values)
        .map(|k| {
            let sigma = covariance.sigma(k, s2);
            (
                [solution.x[k] - t * sigma, solution.x[k] + t * sigma],
                Interval::Linear,
            )
        })
        .collect();
    let (parameters, correlation) = uncertainties(&setup, &solution, &covariance, &linear, s2);
    let fitted = setup.at(&solution.x).expect("the solution was evaluated");
    let amplitudes = problem
        .amplitudes(&solution.x)
        .expect("the solution was evaluated");
    let rows = table
        .rows
        .iter()
        .zip(&amplitudes)
        .map(|(row, &(model, class))| RowFit {
            line: row.line,
            freq_hz: row.frequency,
            drive_v: row.drive,
            direction: row.direction,
            measured_v: row.response,
            model_v: model,
            class,
        })
        .collect();
    let n = solution.residuals.len();
    let (aic, bic) = criteria(&[(solution.sum_squares, n)], n_values);
    Ok(FitReport {
        model: experiment.diode_model(),
        parameters,
        correlation,
        records: vec![],
        rows,
        rms_residual_v: (solution.sum_squares / n as f64).sqrt(),
        noise_v: None,
        chi2_dof: None,
        dof,
        residuals: n,
        fitted_values: n_values,
        aic,
        bic,
        iterations: solution.iterations,
        converged: solution.converged,
        jacobian: Jacobian::FiniteDifferences,
        experiment: fitted,
        warnings: if solution.converged {
            Vec::new()
        } else {
            vec![FitWarning::NotConverged {
                why: if solution.iterations >= options.max_iterations {
                    warning::NotConverged::Iterations {
                        limit: options.max_iterations,
                    }
                } else {
                    warning::NotConverged::Stalled {
                        predicted: solution.decrement,
                    }
                },
            }]
        },
    })
}
