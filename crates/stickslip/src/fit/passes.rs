//! The loop every fit of records shares (driven records, [`super::fit_records`], and an
//! undriven belt's, [`super::fit_undriven`]): two passes of Levenberg–Marquardt (the second
//! weighting each channel by its RMS residual of the first), a restart from elsewhere and the
//! intervals' checks and profiles ([`run`]); then the report's values, error bars,
//! correlation and warnings from where it ended ([`Passed::summarise`]).

use super::*;

/// A least-squares problem of records that [`run`] fits: its coordinate can be held (a
/// profile's), its weights set again from a first pass, and its monitor told how far the
/// fit has gone.
pub(super) trait Passes: profile::Pin {
    /// Weight each channel by its RMS residual at `first` (the second pass's weights).
    fn reweight(&mut self, first: &lm::Solution);
    /// `iterations` more were done before the next minimisation (the monitor's count).
    fn advance(&mut self, iterations: usize);
}

/// How far [`run`] goes.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub(super) enum Reach {
    /// Two passes at the fit's settings, a restart, the intervals' checks and profiles.
    Full,
    /// Two quick passes, nothing more (a fit that only gives another fit its start).
    Quick,
}

/// A 95 % interval's ends in a value's coordinate, and how they were found.
type Ends = ([f64; 2], Interval);

/// Where [`run`] ended: the solution, the iterations of every minimisation that moved it,
/// by how much a lower minimum lay below the one before it (`None` when none did, or the
/// last search found none), the intervals with the covariance they were checked against
/// (`None`: the linear ones of the solution), the degrees of freedom and t(0.975, dof).
pub(super) struct Passed {
    pub(super) solution: lm::Solution,
    pub(super) iterations: usize,
    lower_by: Option<f64>,
    intervals: Option<(Vec<Ends>, Covariance)>,
    pub(super) dof: usize,
    t: f64,
}

/// The report's values of [`Passed::summarise`]: every parameter named (the held ones at
/// their starting values), their correlation (NaN beside a held one), the warnings and
/// whether the fit converged.
pub(super) struct Summary {
    pub(super) parameters: Vec<FittedParameter>,
    pub(super) correlation: Vec<Vec<f64>>,
    pub(super) warnings: Vec<FitWarning>,
    pub(super) converged: bool,
}

/// Fit `problem` from `x` (its first `n_free` coordinates the free parameters): the first
/// pass, the second with [`Passes::reweight`]'s weights, and (with [`Reach::Full`]) a
/// restart from elsewhere and the intervals' checks (linear where the model is linear
/// enough, else the profile's; see `profile`): a point lower than the minimum is a minimum
/// elsewhere, from which the fit goes on (three times at most). `failed` is the error of a
/// model with no value at the start.
///
/// # Errors
/// The problem's own (a stop), or `failed()`.
pub(super) fn run<P: Passes>(
    problem: &mut P,
    x: Vec<f64>,
    n_free: usize,
    settings: lm::Settings,
    reach: Reach,
    failed: impl Fn() -> FitError,
) -> Result<Passed, FitError> {
    let quick = lm::Settings {
        max_iterations: QUICK_ITERATIONS.min(settings.max_iterations),
        tolerance: 1e-6,
        ..settings
    };
    let passes = match reach {
        Reach::Full => settings,
        Reach::Quick => quick,
    };
    let first = lm::minimise(problem, x, passes)?.ok_or_else(&failed)?;
    // Second pass: each channel weighted by its RMS residual of the first.
    problem.reweight(&first);
    problem.advance(first.iterations);
    let mut solution = lm::minimise(problem, first.x.clone(), passes)?.ok_or_else(&failed)?;
    let mut iterations = first.iterations + solution.iterations;
    let n_values = solution.x.len();
    let dof = solution.residuals.len().saturating_sub(n_values).max(1);
    let t = t_quantile_975(dof);
    let mut lower_by = None;
    let mut intervals = None;
    if reach == Reach::Full {
        for _ in 0..3 {
            problem.advance(solution.iterations);
            // Lower by more than the residuals' precision can account for.
            let s2 = (solution.sum_squares / dof as f64).max(lm::Problem::floor(problem));
            let covariance = Covariance::of(&solution, n_free);
            let mut lower = None;
            if let Some(point) =
                covariance.restart(&solution.x, &lm::Problem::bounds(problem, n_values))
            {
                if let Some(restart) = lm::minimise(problem, point, quick)? {
                    if restart.sum_squares < solution.sum_squares - RESTART_LOWER * s2 {
                        lower = Some(restart);
                    }
                }
            }
            if lower.is_none() {
                match profile::intervals(problem, &solution, &covariance.inverse, n_free, t, quick)?
                {
                    profile::Outcome::Intervals(found) => {
                        lower_by = None;
                        intervals = Some((found, covariance));
                        break;
                    }
                    profile::Outcome::Lower(point) => {
                        lower = lm::minimise(problem, point, settings)?
                            .filter(|s| s.sum_squares < solution.sum_squares);
                    }
                }
            }
            match lower {
                Some(better) => {
                    lower_by = Some((solution.sum_squares - better.sum_squares) / s2);
                    iterations += better.iterations;
                    solution = better;
                }
                None => {
                    intervals = None;
                    break;
                }
            }
        }
    }
    Ok(Passed {
        solution,
        iterations,
        lower_by,
        intervals,
        dof,
        t,
    })
}

impl Passed {
    /// The report's values of a fit of `free` (the parameters named, in their order) from
    /// `experiment`'s starting values, of which `setup.free` were fitted (`held`: the
    /// warnings of those held), `clipped` each record's (file, samples clipped, samples).
    pub(super) fn summarise<P: lm::Problem>(
        &self,
        problem: &P,
        (experiment, setup): (&Experiment, &Setup),
        (free, held): (&[FitParameter], &[FitWarning]),
        options: &FitOptions,
        clipped: impl IntoIterator<Item = (String, usize, usize)>,
    ) -> Summary {
        let floor = problem.floor();
        let max_iterations = options.max_iterations;
        let solution = &self.solution;
        let n_free = setup.free.len();
        let t = self.t;
        let covariance = match self.intervals.as_ref() {
            Some((_, c)) => c.clone(),
            None => Covariance::of(solution, n_free),
        };
        let s2 = variance(solution.sum_squares, self.dof, floor);
        let found: Vec<Ends> = match self.intervals.as_ref() {
            Some((found, _)) => found.clone(),
            None => (0..n_free)
                .map(|k| {
                    let sigma = covariance.sigma(k, s2);
                    (
                        [solution.x[k] - t * sigma, solution.x[k] + t * sigma],
                        if sigma.is_finite() {
                            Interval::Linear
                        } else {
                            Interval::None
                        },
                    )
                })
                .collect(),
        };
        let (fitted_parameters, correlation) =
            uncertainties(setup, solution, &covariance, &found, s2);
        // Every parameter named, in the order named: the held ones at their starting values.
        let parameters: Vec<FittedParameter> = free
            .iter()
            .map(
                |&p| match fitted_parameters.iter().find(|f| f.parameter == p) {
                    Some(f) => *f,
                    None => {
                        let start = p.get(experiment).unwrap_or(f64::NAN);
                        FittedParameter {
                            parameter: p,
                            value: start,
                            stderr: f64::NAN,
                            ci95: [f64::NAN; 2],
                            initial: start,
                            interval: Interval::Held,
                        }
                    }
                },
            )
            .collect();
        // The correlation over every parameter named (NaN beside a held one).
        let index = |p: FitParameter| setup.free.iter().position(|&q| q == p);
        let named_correlation: Vec<Vec<f64>> = free
            .iter()
            .map(|&a| {
                free.iter()
                    .map(|&b| match (index(a), index(b)) {
                        (Some(i), Some(k)) => correlation[i][k],
                        _ => f64::NAN,
                    })
                    .collect()
            })
            .collect();
        let mut warnings = held.to_vec();
        let converged = solution.converged && self.lower_by.is_none();
        if !converged {
            let why = match self.lower_by {
                Some(lower_by) => warning::NotConverged::Restart { lower_by },
                None if solution.iterations >= max_iterations => {
                    warning::NotConverged::Iterations {
                        limit: max_iterations,
                    }
                }
                None => warning::NotConverged::Stalled {
                    predicted: solution.decrement,
                },
            };
            warnings.insert(0, FitWarning::NotConverged { why });
        }
        for (k, &p) in setup.free.iter().enumerate() {
            if covariance.unseen[k] {
                warnings.push(FitWarning::Unseen { parameter: p });
            }
            if solution.at_bound[k] {
                warnings.push(FitWarning::AtBound {
                    parameter: p,
                    bound: setup.value(k, solution.x[k]),
                });
            }
        }
        warnings.extend(identify::correlations(&setup.free, &correlation));
        warnings.extend(
            clipped
                .into_iter()
                .filter(|c| c.1 > 0)
                .map(|(file, samples, of)| FitWarning::Clipped { file, samples, of }),
        );
        Summary {
            parameters,
            correlation: named_correlation,
            warnings,
            converged,
        }
    }
}
