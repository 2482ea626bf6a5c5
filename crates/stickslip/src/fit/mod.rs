//! Fitting the circuit (or the mechanical oscillator) to measurements: least squares of the model's steady state against
//! scope records ([`fit_records`]) or a table of measured amplitudes ([`fit_table`]), one
//! record at a time ([`fit_per_record`]), and the PWL law against the Shockley law on the
//! same data ([`compare_models`]).
//!
//! **The model of a record.** For each record the drive is taken as measured: a sine
//! U cos(2πf·s + φ_d) + c_d fitted to the drive channel (started from its sine fit,
//! [`crate::measure::SineFit`], and fitted again together with everything else, so that its
//! uncertainty is part of the error bars). The circuit, with the free parameters at their
//! current values, is driven at (f, U) with phase φ = φ_d + ψ; its steady state is found from
//! rest ([`Experiment::steady_with`]) and the cycle is run from its strobe on, sampled at
//! τ = ω0·s for the record's times s since its first sample; the model of u_C is U_t·y + c.
//! Nuisance parameters per record: the drive's U, f, φ_d and c_d, the DC offset c of the u_C
//! channel and a time shift δ = ψ/(2πf) between the channels (a trigger delay). The residuals
//! are model − measurement at every sample that is not clipped, of both channels, each
//! divided by its channel's noise: first the noise estimated from the data
//! ([`crate::measure::Measurement::noise`]), then, in a second pass from the first pass's
//! solution, the channel's RMS residual (records taken at different scope settings have
//! different noise, and an unweighted fit would give wrong error bars).
//!
//! **The fit.** Levenberg–Marquardt, written here (Marquardt's scaling by diag(JᵀJ); a
//! rejected step when the values leave a parameter's range). The `levenberg-marquardt` crate
//! (a port of MINPACK's lmder) was considered: it brings nalgebra, wants its own problem
//! trait and matrix types, has no notion of a step outside the model's domain, and does not
//! report (JᵀJ)⁻¹ for the error bars; the problems here are small and dense (a few to a few
//! tens of unknowns), which 150 lines over a Cholesky solver handle. It runs over the free
//! parameters (scaled by their starting values) and the nuisance
//! parameters. The Jacobian: the drive's columns on the drive samples and the offsets'
//! columns exactly. The response's columns, with PWL diodes wherever every record's model is
//! a periodic orbit, from the exact tangent dynamics with respect to the parameters
//! ([`crate::stability::periodic_orbit_sensitivity`]: the closed-form slides, the saltations,
//! the releases' moving times and dx*/dp = (I − M)⁻¹ ∂P/∂p), carried through the circuit's
//! scales (ζ = (R + R_D)/2·√(C/L), ω0 = 1/√(LC), w = 2πf/ω0, β = U/U_t, τ = ω0·s,
//! u_C = U_t·y), from the steady states the residuals were computed with. With Shockley
//! diodes, wherever every record's model is a periodic orbit, from the stiff solver's forward
//! sensitivities on its own steps along that orbit (`jacobian.rs`: the derivatives of the
//! computed samples, at a tolerance of their own, carried to R, L, C, ln I_s, n and R_s by
//! the chain rule). Otherwise (a model that does not repeat, a tangential release, a
//! multiplier 1) by forward differences (step 10⁻⁶ with PWL diodes, whose exact solver gives
//! the steady state to 10⁻¹²; 10⁻⁴ with Shockley diodes, whose stiff solver is accurate to its
//! tolerance; relative to a free parameter's value, but never smaller than that fraction of
//! its starting value, so that a value fitted near zero, such as a diode's R_s, keeps a step
//! above the solver's error), a record's own nuisance columns from that record only. The
//! report says which served at the solution ([`Jacobian`]).
//!
//! **What is reported** ([`FitReport`]): each free parameter's value, standard error from
//! s²(JᵀJ)⁻¹ with s² the weighted SSR/(N − P) (N residuals, P fitted values with the nuisance
//! ones), 95 % interval value ± t(0.975, N − P)·stderr where that linear interval holds, else
//! from the profile of χ² (each value says which: [`Interval`]), the correlation of the free
//! parameters, the warnings ([`FitWarning`]: a combination that the data do not identify, a
//! correlation beyond ±0.99, a value at its bound, clipped samples, a fit that did not
//! converge); the RMS residual of u_C per record and overall; χ²/dof = Σ r²/σ² over N − P
//! with σ each channel's noise estimated from the data alone (near 1 when the model explains
//! the data to the noise; the estimate from second differences needs the noise to exceed
//! the waveform's curvature between samples, true of 8-bit records, not of records with
//! almost no noise); the iterations of both passes and whether the fit converged (the step
//! and gradient criteria held and no restart from elsewhere found a lower χ²; both measure
//! χ² in units of the residuals' variance, never taken below the channels' precision, their
//! noise floor without noise: a record made by the model is fitted down to the rounding of
//! its digits and of the model, which no step describes, and is a minimum to that precision);
//! AIC = Σ_g N_g ln(SSR_g/N_g) + 2P and BIC (P ln N instead of 2P) over the channels g, for
//! comparing models.
//!
//! **Mechanics.** A mechanical oscillator (mass, spring, viscous and dry friction) is fitted
//! in the same way to records of its drive force F (N) and displacement r (m), with the
//! free parameters `damping` (γ), `friction` (F0), `mass` (m), `stiffness` (k) and `mu-s`
//! ([`FitParameter::MECHANICS`]); its scales take the circuit's place (ζ = γ/(2√(km)),
//! ω0 = √(k/m), β = F/F0, r = (F0/k)·y), and its Coulomb law is the PWL law, so that its
//! Jacobian is exact wherever every record's model is a periodic orbit. On a moving belt, or
//! with the Stribeck law (whose `stribeck-speed` and `viscous-friction` a fit may free beside
//! `mu-s`), the belt speed and the law's values are held in their physical units while m, k
//! and F0 move their dimensionless images, and the Jacobian is by central differences of the
//! whole model (`central.rs`, [`Jacobian::CentralDifferences`]). The record's channels
//! must say their units (`N` and `m`: a plain CSV's header `time_s,F (N),r (m)`), a circuit's
//! parameter on a mechanical oscillator (or the other way round) is refused naming the
//! parameters allowed, and so is a table of amplitudes (read in volts). The report's fields
//! named in volts then hold newtons (the drive) and metres (the response):
//! [`FitReport::units`].
//!
//! **Tables** ([`fit_table`]): the residual of a row is the steady amplitude (half the
//! peak-to-peak of u_C) minus the measured one. Rows with a `direction` are computed along
//! their sweep (rows of one leg and one drive amplitude sorted by frequency, up or down, each
//! settling from the motion of the row before, as the measurement was made), the others from
//! rest. There is no nuisance parameter and no noise estimate independent of the fit:
//! χ²/dof is not reported.

mod central;
mod covariance;
mod identify;
mod jacobian;
mod json;
pub(crate) mod linalg;
mod lm;
mod options;
mod parameter;
mod passes;
mod profile;
mod records;
mod report;
mod setup;
mod starts;
mod table;
mod undriven;
mod warning;

pub use json::{
    ComparisonJson, FitReportJson, ParameterJson, RecordJson, RowJson, UnitsJson, WarningJson,
};
pub use options::{FitError, FitMonitor, FitOptions, FitProgress, RECORD_PASSES};
pub use parameter::FitParameter;
pub use report::{
    t_quantile_975, FitReport, FittedParameter, Interval, Jacobian, ModelComparison, RecordFit,
    RowFit,
};
pub use table::{fit_table, fit_table_monitored};
pub use undriven::{
    check_undriven, fit_undriven, fit_undriven_monitored, UndrivenRecord, UndrivenStart,
};
pub use warning::{FitWarning, NotConverged};

use crate::experiment::{DiodeModel, Experiment};
use crate::measure::Measurement;
use crate::physical::System;
use crate::shockley::DiodePair;
use std::f64::consts::TAU;

use covariance::*;
use options::Watch;
use records::*;
use setup::*;

/// The units a record's drive and response must carry for `system`: a mechanical
/// oscillator's force in N and displacement in m (a plain CSV names them in its header,
/// `F (N)`, `r (m)`); a circuit's channels in anything but those.
fn check_units(system: &System, m: &Measurement) -> Result<(), FitError> {
    let (drive, response) = (m.drive_unit.as_str(), m.response_unit.as_str());
    let message = match system {
        System::Mechanics(_) if drive != "N" || response != "m" => format!(
            "a mechanical oscillator is fitted to a drive force in N and a displacement in m \
             (name the columns with their units, e.g. `F (N)` and `r (m)`); the record gives \
             the drive {} in {drive} and the response {} in {response}",
            m.drive_channel, m.response_channel
        ),
        System::Circuit(_) if drive == "N" || response == "m" => format!(
            "a circuit is fitted to voltages; the record gives the drive {} in {drive} and the \
             response {} in {response} (a mechanical record: give the mechanical oscillator's \
             parts)",
            m.drive_channel, m.response_channel
        ),
        _ => return Ok(()),
    };
    Err(FitError::Units {
        file: m.file.clone(),
        message,
    })
}

/// A floor under a channel's noise σ: a noise-free record must not get an infinite weight
/// (a twelfth of the resolution's variance, 10⁻⁹ of the channel's scale).
fn noise_floor(sigma: f64, values: &[f64], q: Option<f64>) -> f64 {
    let scale = values.iter().fold(0.0f64, |a, v| a.max(v.abs()));
    let quantum = q.unwrap_or(0.0) / 12f64.sqrt();
    sigma.max(quantum).max(1e-9 * scale).max(f64::MIN_POSITIVE)
}

/// Fit the free parameters of `experiment` (a circuit, PWL or Shockley) to every record of
/// `data` at once. The experiment's values are the starting point; its drive is not used
/// (each record has its own).
///
/// Each record's drive enters as measured: its amplitude, frequency, phase and offset are
/// fitted together with everything else to the drive channel's samples (starting from the
/// sine fit), so that their uncertainty is part of the error bars. Every channel's residuals
/// are divided by its noise: first as estimated from the data
/// ([`Measurement::noise`]), then, in a second pass from the first pass's solution, as the
/// RMS residual of that channel.
///
/// # Errors
/// No record; a free parameter named twice, of the other diode law, or none; not a circuit;
/// fewer samples than values; a model that cannot be computed at the starting values.
pub fn fit_records(
    experiment: &Experiment,
    data: &[Measurement],
    free: &[FitParameter],
    options: &FitOptions,
) -> Result<FitReport, FitError> {
    fit_records_monitored(experiment, data, free, options, &())
}

/// [`fit_records`], telling `monitor` of every iteration (of both passes: at most
/// [`RECORD_PASSES`]·[`FitOptions::max_iterations`]: two passes, a restart and the
/// intervals' profiles), which can stop the fit.
///
/// # Errors
/// As [`fit_records`]; [`FitError::Stopped`] when the monitor stops the fit.
pub fn fit_records_monitored(
    experiment: &Experiment,
    data: &[Measurement],
    free: &[FitParameter],
    options: &FitOptions,
    monitor: &dyn FitMonitor,
) -> Result<FitReport, FitError> {
    let watch = Watch {
        monitor,
        before: 0,
        total: RECORD_PASSES * options.max_iterations,
    };
    records_watched(experiment, data, free, options, watch)
}

fn records_watched(
    experiment: &Experiment,
    data: &[Measurement],
    free: &[FitParameter],
    options: &FitOptions,
    watch: Watch<'_>,
) -> Result<FitReport, FitError> {
    records_with(experiment, data, free, options, watch, Depth::Full(None))
}

/// How far a fit of records goes.
#[derive(Debug, Clone, Copy)]
enum Depth {
    /// Everything: a smooth law's starts in its valley (through this knee, or the knee of a
    /// PWL fit made first), a restart, the intervals' checks and profiles.
    Full(Option<starts::Knee>),
    /// The two passes from the caller's start, nothing more (the PWL fit that gives a
    /// smooth law's knee).
    Quick,
}

/// The PWL law's knee for the Shockley fit of `experiment` (see [`starts`]): the PWL
/// equivalent of its pair at the records' working current, U_t and R_D fitted (quickly).
fn pwl_knee(
    experiment: &Experiment,
    data: &[Measurement],
    options: &FitOptions,
    watch: Watch<'_>,
) -> Option<starts::Knee> {
    let c = *experiment.circuit_ref()?;
    let crate::physical::Diode::Shockley(d) = c.diode else {
        return None;
    };
    let i = starts::working_current(c.capacitance, data)?;
    let (turn_on, resistance) = starts::pwl_equivalent(&d.pair, i);
    let pwl = Experiment::circuit(crate::physical::Circuit {
        diode: crate::physical::Diode::Pwl(crate::physical::PwlDiode {
            turn_on,
            resistance,
        }),
        ..c
    })
    .ok()?
    .with_cancel(experiment.cancel().clone());
    let free = [FitParameter::Ut, FitParameter::Rd];
    let report = records_with(&pwl, data, &free, options, watch, Depth::Quick).ok()?;
    starts::knee_of_pwl(report.experiment.system()?, c.resistance, i)
}

/// The sum of squares of residuals `r`.
fn sum_of_squares(r: &[f64]) -> f64 {
    r.iter().map(|v| v * v).sum()
}

fn records_with(
    experiment: &Experiment,
    data: &[Measurement],
    free: &[FitParameter],
    options: &FitOptions,
    watch: Watch<'_>,
    depth: Depth,
) -> Result<FitReport, FitError> {
    if data.is_empty() {
        return Err(FitError::NoData);
    }
    // The free list as named (its faults refused first), then the parameters the records
    // can determine.
    Setup::new(experiment, free)?;
    let plan = identify::plan(experiment, free);
    let setup = Setup::new(experiment, &plan.fitted)?;
    let (mut problem, x) = Records::new(&setup, data, options, watch)?;
    let n_free = setup.free.len();
    let n_values = x.len();
    let settings = lm::Settings {
        max_iterations: options.max_iterations,
        tolerance: options.tolerance,
        gradient: lm::GRADIENT,
    };
    let failed = || FitError::Model {
        file: data[0].file.clone(),
        error: crate::Error::InvalidParameter {
            name: "fit",
            value: f64::NAN,
            allowed: "a model that can be computed at the starting values",
        },
    };
    // A smooth law's fit starts in the valley of I_s and n (see `starts`).
    let mut x = x;
    let valley_free = setup
        .free
        .iter()
        .any(|p| matches!(*p, FitParameter::DiodeIs | FitParameter::DiodeN));
    if let Depth::Full(knee) = depth {
        if setup.experiment.diode_model() == DiodeModel::Shockley && valley_free {
            let knee = knee.or_else(|| pwl_knee(experiment, data, options, problem.watch));
            if let Some(knee) = knee {
                let mut best = lm::Problem::residuals(&mut problem, &x)?
                    .map_or(f64::INFINITY, |r| sum_of_squares(&r));
                for candidate in starts::valley(&setup, &x, knee) {
                    if let Some(r) = lm::Problem::residuals(&mut problem, &candidate)? {
                        let ssr = sum_of_squares(&r);
                        if ssr < best {
                            best = ssr;
                            x = candidate;
                        }
                    }
                }
            }
        }
    }
    let reach = match depth {
        Depth::Full(_) => passes::Reach::Full,
        Depth::Quick => passes::Reach::Quick,
    };
    let spans = problem.spans();
    let passed = passes::run(&mut problem, x, n_free, settings, reach, failed)?;
    let summary = passed.summarise(
        &problem,
        (experiment, &setup),
        (free, &plan.warnings),
        options,
        data.iter()
            .map(|m| (m.file.clone(), m.clipped, m.time.len())),
    );
    let (solution, iterations, dof) = (&passed.solution, passed.iterations, passed.dof);
    let fitted = setup.at(&solution.x[..n_free]).ok_or_else(failed)?;
    let mut records = Vec::with_capacity(data.len());
    let mut chi2 = 0.0;
    let mut groups = Vec::new();
    let mut all_response = Vec::new();
    for (j, m) in data.iter().enumerate() {
        let (offset, shift) = problem.offset_and_shift(&solution.x, j);
        let d = problem.drive(&solution.x, j);
        let e = problem
            .response_model(&fitted, &solution.x, j)
            .map_err(|error| FitError::Model {
                file: m.file.clone(),
                error,
            })?;
        let (start, len) = spans[j];
        let half = len / 2;
        let (wd, wr) = problem.weights[j];
        let drive_residuals: Vec<f64> = solution.residuals[start..start + half]
            .iter()
            .map(|r| r / wd)
            .collect();
        let residuals: Vec<f64> = solution.residuals[start + half..start + len]
            .iter()
            .map(|r| r / wr)
            .collect();
        let ssr_d: f64 = drive_residuals.iter().map(|r| r * r).sum();
        let ssr_r: f64 = residuals.iter().map(|r| r * r).sum();
        chi2 += ssr_d / noise_floor(m.drive_noise, &problem.drive[j], None).powi(2)
            + ssr_r / noise_floor(m.noise, &problem.response[j], m.resolution).powi(2);
        groups.push((ssr_d, half));
        groups.push((ssr_r, half));
        all_response.extend_from_slice(&residuals);
        records.push(RecordFit {
            file: m.file.clone(),
            freq_hz: d.frequency,
            amplitude_v: d.amplitude,
            w: e.w,
            beta: e.beta,
            class: e.class,
            periods: m.drive.periods,
            clipped: m.clipped,
            rms_residual_v: rms(&residuals),
            offset_v: offset,
            time_shift_s: shift / (TAU * d.frequency),
            noise_v: m.noise,
            time: problem.time[j].clone(),
            model: e.model.iter().map(|v| v + offset).collect(),
            residuals,
        });
    }
    let n = solution.residuals.len();
    let noise = (data
        .iter()
        .zip(&problem.time)
        .map(|(m, t)| m.noise * m.noise * t.len() as f64)
        .sum::<f64>()
        / all_response.len() as f64)
        .sqrt();
    let (aic, bic) = criteria(&groups, n_values);
    Ok(FitReport {
        model: experiment.diode_model(),
        parameters: summary.parameters,
        correlation: summary.correlation,
        records,
        rows: vec![],
        rms_residual_v: rms(&all_response),
        noise_v: Some(noise),
        chi2_dof: Some(chi2 / dof as f64),
        dof,
        residuals: n,
        fitted_values: n_values,
        aic,
        bic,
        iterations,
        converged: summary.converged,
        jacobian: problem.jacobian,
        experiment: fitted,
        warnings: summary.warnings,
    })
}

/// Fit the free parameters to each record alone (to see how a parameter drifts with the
/// drive, as the paper observes of U_t), in the order of `data`.
///
/// # Errors
/// As [`fit_records`], for the first record that fails.
pub fn fit_per_record(
    experiment: &Experiment,
    data: &[Measurement],
    free: &[FitParameter],
    options: &FitOptions,
) -> Result<Vec<FitReport>, FitError> {
    fit_per_record_monitored(experiment, data, free, options, &())
}

/// [`fit_per_record`], telling `monitor` of every iteration (at most
/// [`RECORD_PASSES`]·[`FitOptions::max_iterations`] per record), which can stop the fits.
///
/// # Errors
/// As [`fit_per_record`]; [`FitError::Stopped`] when the monitor stops the fits.
pub fn fit_per_record_monitored(
    experiment: &Experiment,
    data: &[Measurement],
    free: &[FitParameter],
    options: &FitOptions,
    monitor: &dyn FitMonitor,
) -> Result<Vec<FitReport>, FitError> {
    if data.is_empty() {
        return Err(FitError::NoData);
    }
    let per = RECORD_PASSES * options.max_iterations;
    data.iter()
        .enumerate()
        .map(|(j, m)| {
            let watch = Watch {
                monitor,
                before: j * per,
                total: data.len() * per,
            };
            records_watched(experiment, std::slice::from_ref(m), free, options, watch)
        })
        .collect()
}

/// The same records fitted with PWL diodes (`experiment`, free `pwl_free`) and with the
/// Shockley pair `pair` in the same circuit (free `shockley_free`), compared by AIC.
///
/// # Errors
/// As [`fit_records`] for either fit; [`FitError::WrongLaw`] when `experiment` has Shockley
/// diodes.
pub fn compare_models(
    experiment: &Experiment,
    pair: DiodePair,
    data: &[Measurement],
    pwl_free: &[FitParameter],
    shockley_free: &[FitParameter],
    options: &FitOptions,
) -> Result<ModelComparison, FitError> {
    compare_models_monitored(
        experiment,
        pair,
        data,
        pwl_free,
        shockley_free,
        options,
        &(),
    )
}

/// [`compare_models`], telling `monitor` of every iteration of both fits (at most
/// 2·[`RECORD_PASSES`]·[`FitOptions::max_iterations`]), which can stop them.
///
/// # Errors
/// As [`compare_models`]; [`FitError::Stopped`] when the monitor stops the fits.
pub fn compare_models_monitored(
    experiment: &Experiment,
    pair: DiodePair,
    data: &[Measurement],
    pwl_free: &[FitParameter],
    shockley_free: &[FitParameter],
    options: &FitOptions,
    monitor: &dyn FitMonitor,
) -> Result<ModelComparison, FitError> {
    if experiment.diode_model() != DiodeModel::Pwl {
        return Err(FitError::WrongLaw {
            parameter: FitParameter::Ut,
            model: experiment.diode_model(),
        });
    }
    let shockley_experiment =
        experiment
            .clone()
            .with_shockley(pair)
            .map_err(|error| FitError::Model {
                file: "(comparison)".into(),
                error,
            })?;
    let per = RECORD_PASSES * options.max_iterations;
    let watch = |before| Watch {
        monitor,
        before,
        total: 2 * per,
    };
    let pwl = records_watched(experiment, data, pwl_free, options, watch(0))?;
    // The Shockley fit enters its valley where the PWL fit says the diodes work.
    let knee = experiment.circuit_ref().and_then(|c| {
        let i = starts::working_current(c.capacitance, data)?;
        starts::knee_of_pwl(pwl.experiment.system()?, c.resistance, i)
    });
    let shockley = records_with(
        &shockley_experiment,
        data,
        shockley_free,
        options,
        watch(per),
        Depth::Full(knee),
    )?;
    let delta_aic = shockley.aic - pwl.aic;
    Ok(ModelComparison {
        preferred: if delta_aic < 0.0 {
            DiodeModel::Shockley
        } else {
            DiodeModel::Pwl
        },
        delta_aic,
        pwl,
        shockley,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    use crate::physical::{Circuit, Mechanics};
    use crate::solver::sample_at;
    use crate::steady::{MotionClass, SolverFactory};

    #[test]
    fn t_quantiles_match_tables() {
        // Student's t, 0.975: 2.571 (5), 2.228 (10), 2.042 (30), 1.984 (100).
        for (dof, t) in [(5, 2.5706), (10, 2.2281), (30, 2.0423), (100, 1.9840)] {
            assert!((t_quantile_975(dof) - t).abs() < 2e-3 * t, "{dof}");
        }
    }
    /// A plain-CSV record of `truth` at (w, β, φ): 600 samples over 2.5 drive periods, with
    /// a deterministic ripple of 0.3 % as noise and an offset of 20 mV on u_C.
    pub(super) fn record(truth: &Experiment, w: f64, beta: f64, phi: f64) -> Measurement {
        let e = truth
            .clone()
            .with_w(w)
            .and_then(|e| e.with_beta(beta))
            .and_then(|e| e.with_phi(phi))
            .unwrap();
        let steady = e.steady().unwrap();
        let scales = e.scales().unwrap();
        let mut solver = e
            .factory()
            .make(e.params().unwrap(), steady.final_state())
            .unwrap();
        let n = 600;
        let dt = 2.5 * TAU / (w * scales.omega0) / n as f64;
        let taus: Vec<f64> = (0..n).map(|k| k as f64 * dt * scales.omega0).collect();
        let samples = sample_at(solver.as_mut(), &taus, |_| {}).unwrap();
        let mut text = if e.circuit_ref().is_some() {
            "time_s,u_V,uc_V\n".to_string()
        } else {
            "time_s,F (N),r (m)\n".to_string()
        };
        for (k, (tau, s)) in taus.iter().zip(&samples).enumerate() {
            let ripple = 0.003 * ((k * k % 97) as f64 / 48.0 - 1.0);
            let drive = beta * scales.force * (w * tau + phi).cos() * (1.0 + ripple);
            let response = (s.y + ripple + 0.03) * scales.position;
            text += &format!("{:.12e},{drive:.12e},{response:.12e}\n", k as f64 * dt);
        }
        let r = crate::measure::read_scope(&text, "plain.csv").unwrap();
        Measurement::new(&r, None, None).unwrap()
    }

    /// The exact Jacobian of records against Richardson-extrapolated central differences of
    /// the residuals, column by column, for every PWL parameter and every nuisance value:
    /// sliding records and a stick-slip record with μs > 1 (the releases move with the
    /// parameters).
    #[test]
    fn the_exact_jacobian_of_records_matches_central_differences() {
        let truth = Experiment::circuit(Circuit {
            resistance: 80.0,
            ..Circuit::paper()
        })
        .unwrap()
        .with_mu_s(1.25)
        .unwrap();
        let data: Vec<Measurement> = [(0.29, 2.6, 0.4), (0.95, 2.14, -1.1), (1.43, 3.0, 2.5)]
            .iter()
            .map(|&(w, beta, phi)| record(&truth, w, beta, phi))
            .collect();
        let start = Experiment::paper().with_mu_s(1.2).unwrap();
        let free = [
            FitParameter::Resistance,
            FitParameter::Ut,
            FitParameter::Rd,
            FitParameter::Inductance,
            FitParameter::Capacitance,
            FitParameter::MuS,
        ];
        exact_matches_central_differences(&start, &free, &data);
    }

    /// Every column of the exact Jacobian of `data` at `start` against Richardson-extrapolated
    /// central differences; the records must include a sliding and a stick-slip one.
    fn exact_matches_central_differences(
        start: &Experiment,
        free: &[FitParameter],
        data: &[Measurement],
    ) {
        let setup = Setup::new(start, free).unwrap();
        let watch = Watch {
            monitor: &(),
            before: 0,
            total: 1,
        };
        let (mut problem, x) = Records::new(&setup, data, &FitOptions::default(), watch).unwrap();
        let r = lm::Problem::residuals(&mut problem, &x).unwrap().unwrap();
        let exact = problem.exact_jacobian(&x).expect("periodic PWL models");
        let classes: Vec<MotionClass> = (0..data.len())
            .map(|j| {
                problem
                    .response_model(&setup.at(&x[..free.len()]).unwrap(), &x, j)
                    .unwrap()
                    .class
            })
            .collect();
        assert!(classes.contains(&MotionClass::PeriodicStick), "{classes:?}");
        assert!(classes.contains(&MotionClass::Sliding), "{classes:?}");
        let central = |k: usize, h: f64| -> Vec<f64> {
            let mut up = x.clone();
            let mut down = x.clone();
            up[k] += h;
            down[k] -= h;
            let (a, b) = (problem.all(&up).unwrap(), problem.all(&down).unwrap());
            a.concat()
                .iter()
                .zip(&b.concat())
                .map(|(a, b)| (a - b) / (2.0 * h))
                .collect()
        };
        for k in 0..x.len() {
            let h = 1e-5 * x[k].abs().max(1.0);
            let (coarse, fine) = (central(k, h), central(k, h / 2.0));
            let size = fine.iter().fold(0.0f64, |a, v| a.max(v.abs()));
            let mut worst = 0.0f64;
            for i in 0..r.len() {
                let richardson = (4.0 * fine[i] - coarse[i]) / 3.0;
                worst = worst.max((exact[k][i] - richardson).abs());
            }
            assert!(
                worst <= 1e-6 * size,
                "column {k}: deviation {worst:e} against a largest entry {size:e}"
            );
        }
    }

    /// The same for a mechanical oscillator: γ, F0, m, k and μs through the mechanical scales
    /// (ζ = γ/(2√(km)), ω0 = √(k/m), β = F/F0, r = (F0/k)·y).
    #[test]
    fn the_exact_jacobian_of_mechanical_records_matches_central_differences() {
        let truth = Experiment::mechanics(Mechanics::new(0.5, 200.0, 0.8, 0.3).unwrap())
            .unwrap()
            .with_mu_s(1.25)
            .unwrap();
        let data: Vec<Measurement> = [(0.29, 2.6, 0.4), (0.95, 2.14, -1.1), (1.43, 3.0, 2.5)]
            .iter()
            .map(|&(w, beta, phi)| record(&truth, w, beta, phi))
            .collect();
        let start = Experiment::mechanics(Mechanics::new(0.55, 180.0, 0.7, 0.32).unwrap())
            .unwrap()
            .with_mu_s(1.2)
            .unwrap();
        // Every mechanical parameter but the Stribeck law's (this oscillator's law is
        // Coulomb's, without a belt: the exact Jacobian's).
        let free = [
            FitParameter::Damping,
            FitParameter::Friction,
            FitParameter::Mass,
            FitParameter::Stiffness,
            FitParameter::MuS,
        ];
        exact_matches_central_differences(&start, &free, &data);
    }
}
