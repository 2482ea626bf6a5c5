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
//! Jacobian is exact wherever every record's model is a periodic orbit. The record's channels
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

mod covariance;
mod identify;
mod jacobian;
mod json;
pub(crate) mod linalg;
mod lm;
mod options;
mod parameter;
mod profile;
mod report;
mod starts;
mod table;
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
pub use warning::{FitWarning, NotConverged};

use crate::experiment::{DiodeModel, Experiment};
use crate::measure::Measurement;
use crate::params::{Params, State};
use crate::physical::System;
use crate::shockley::{DiodePair, ShockleyOptions};
use crate::solver::sample_at;
use crate::stability::{periodic_orbit_sensitivity, OrbitSample};
use crate::steady::SolverFactory;
use crate::steady::{MotionClass, SteadyOptions};
use rayon::prelude::*;
use std::f64::consts::{PI, TAU};

use covariance::*;
use options::Watch;

/// Everything a fit keeps fixed: the experiment's circuit or mechanical oscillator and
/// options and the free list.
struct Setup {
    experiment: Experiment,
    system: System,
    free: Vec<FitParameter>,
    scale: Vec<f64>,
    /// Whether each free value is fitted in its logarithm (I_s, which spans decades and whose
    /// valley with n is straight in ln I_s): value = scale·e^(x − 1); else value = scale·x.
    log: Vec<bool>,
    steady: SteadyOptions,
    step: f64,
}

/// The strobe tolerance of a smooth law's steady state in a fit: 10⁻⁶, the stiff solver's
/// default tolerance, above the fit's own solver tolerance ([`jacobian::SMOOTH_RTOL`]), so
/// that the strobe map's jitter does not hide the cycle.
const SMOOTH_STEADY_TOLERANCE: f64 = 1e-6;

/// Whether `p` is fitted in its logarithm ([`Setup`]): the saturation current I_s.
fn fitted_in_log(p: FitParameter) -> bool {
    p == FitParameter::DiodeIs
}

impl Setup {
    fn new(experiment: &Experiment, free: &[FitParameter]) -> Result<Self, FitError> {
        let system = *experiment.system().ok_or(FitError::NeedsCircuit)?;
        if free.is_empty() {
            return Err(FitError::FreeParameters(
                "no free parameter: name at least one",
            ));
        }
        for (i, p) in free.iter().enumerate() {
            if free[..i].contains(p) {
                return Err(FitError::FreeParameters("a free parameter is named twice"));
            }
        }
        let scale = free
            .iter()
            .map(|p| p.get(experiment).map(|v| if v != 0.0 { v } else { 1.0 }))
            .collect::<Result<Vec<_>, _>>()?;
        let model = experiment.diode_model();
        // A smooth law's solver at the fit's tolerance (the shooting Jacobian's differences
        // need it), unless the caller's is tighter.
        let experiment = &if model == DiodeModel::Shockley {
            let o = *experiment.shockley_options();
            let tight = o.rtol.min(jacobian::SMOOTH_RTOL);
            experiment
                .clone()
                .with_shockley_options(ShockleyOptions {
                    rtol: tight,
                    atol: o.atol.min(jacobian::SMOOTH_RTOL),
                    ..o
                })
                .map_err(|error| FitError::Model {
                    file: "(the fit's solver)".into(),
                    error,
                })?
        } else {
            experiment.clone()
        };
        let steady = SteadyOptions {
            tolerance: if model == DiodeModel::Pwl {
                1e-12
            } else {
                SMOOTH_STEADY_TOLERANCE
            },
            spectrum: false,
            lyapunov: None,
            ..experiment.steady_options()
        };
        Ok(Self {
            experiment: experiment.clone(),
            system,
            free: free.to_vec(),
            scale,
            log: free.iter().map(|&p| fitted_in_log(p)).collect(),
            steady,
            step: if model == DiodeModel::Pwl { 1e-6 } else { 1e-4 },
        })
    }

    /// The experiment at scaled values `x` (value = x·scale), or `None` outside the
    /// parameters' ranges.
    fn at(&self, x: &[f64]) -> Option<Experiment> {
        let mut system = self.system;
        let mut mu_s = self.experiment.mu_s();
        for (k, (p, &x)) in self.free.iter().zip(x).enumerate() {
            let v = self.value(k, x);
            if !v.is_finite() {
                return None;
            }
            match (*p, &mut system) {
                (FitParameter::MuS, _) => mu_s = v,
                (p, System::Circuit(c)) => p.set(c, v),
                (p, System::Mechanics(m)) => p.set_mechanics(m, v),
            }
        }
        let e = match system {
            System::Circuit(c) => Experiment::circuit(c).ok()?,
            System::Mechanics(m) => Experiment::mechanics(m).ok()?,
        };
        let e = e
            .with_shockley_options(*self.experiment.shockley_options())
            .ok()?;
        // The rebuilt experiment keeps the caller's cancellation token.
        e.with_mu_s(mu_s)
            .ok()
            .map(|e| e.with_cancel(self.experiment.cancel().clone()))
    }

    /// `Err(FitError::Stopped)` once the caller's token stops the fit (Ctrl-C, a deadline):
    /// checked before each evaluation, since a stopped model only looks like a failed step.
    fn check_stop(&self) -> Result<(), FitError> {
        match self.experiment.cancel().stopped() {
            Some(stop) => Err(FitError::Stopped(stop.error())),
            None => Ok(()),
        }
    }

    /// The value of free parameter `k` at the scaled coordinate `x`.
    fn value(&self, k: usize, x: f64) -> f64 {
        if self.log[k] {
            self.scale[k] * (x - 1.0).exp()
        } else {
            self.scale[k] * x
        }
    }

    /// d value / dx of free parameter `k` at `x` (the chain rule from the coordinate).
    fn slope(&self, k: usize, x: f64) -> f64 {
        if self.log[k] {
            self.value(k, x)
        } else {
            self.scale[k]
        }
    }

    /// The bounds of free parameter `k`'s coordinate that a value may reach: R, R_D, R_s and
    /// γ down to 0, μs down to 1 (the others are positive and refused at 0, which the
    /// minimisation treats as a failed step; I_s is fitted in its logarithm).
    fn bounds(&self, k: usize) -> (f64, f64) {
        let lowest = match self.free[k] {
            FitParameter::Resistance
            | FitParameter::Rd
            | FitParameter::DiodeRs
            | FitParameter::Damping => Some(0.0),
            FitParameter::MuS => Some(1.0),
            _ => None,
        };
        match lowest {
            Some(v) if !self.log[k] => (self.coordinate(k, v), f64::INFINITY),
            _ => (f64::NEG_INFINITY, f64::INFINITY),
        }
    }

    /// The coordinate of free parameter `k` at `value` (the inverse of [`Setup::value`]).
    fn coordinate(&self, k: usize, value: f64) -> f64 {
        if self.log[k] {
            1.0 + (value / self.scale[k]).ln()
        } else {
            value / self.scale[k]
        }
    }

    fn values(&self, x: &[f64]) -> Vec<f64> {
        x.iter()
            .enumerate()
            .map(|(k, &x)| self.value(k, x))
            .collect()
    }
}

/// The model of one record: u_C at the used times, and the motion's class, w and β; the
/// dimensionless parameters, the steady state's strobe state and period (what the exact
/// Jacobian starts from).
struct Evaluated {
    model: Vec<f64>,
    class: MotionClass,
    w: f64,
    beta: f64,
    params: Params,
    strobe: State,
    period: Option<usize>,
}

fn wrap(phase: f64) -> f64 {
    let p = phase.rem_euclid(TAU);
    if p > PI {
        p - TAU
    } else {
        p
    }
}

/// The steady u_C of `experiment` driven at `frequency` (Hz), `amplitude` (V) and `phase`
/// (radians, at s = 0), at the times `time` (s), without an offset; the steady state sought
/// from `start` (a strobe state of a model nearby) or, without one, from the experiment's
/// initial state (rest).
fn evaluate(
    experiment: &Experiment,
    frequency: f64,
    amplitude: f64,
    phase: f64,
    time: &[f64],
    options: &SteadyOptions,
    start: Option<State>,
) -> Result<Evaluated, crate::Error> {
    let mut e = experiment
        .clone()
        .with_frequency(frequency)?
        .with_amplitude(amplitude)?
        .with_phi(wrap(phase))?;
    if let Some(start) = start {
        e = e.with_initial(start)?;
    }
    let steady = e.steady_with(options)?;
    let scales = e.scales().expect("a circuit has scales");
    let params = e.params()?;
    let mut solver = e.factory().make(params, steady.final_state())?;
    let taus: Vec<f64> = time.iter().map(|&s| s * scales.omega0).collect();
    let samples = sample_at(solver.as_mut(), &taus, |_| {})?;
    Ok(Evaluated {
        model: samples.iter().map(|s| s.y * scales.position).collect(),
        class: steady.class,
        w: params.w,
        beta: params.beta,
        params,
        strobe: steady.final_state(),
        period: steady.period,
    })
}

/// How a free parameter enters the dimensionless model, for the chain rule of the exact
/// Jacobian.
#[derive(Debug, Clone, Copy)]
enum Link {
    /// Through ζ, ω0 and the position scale (∂ζ/∂p, ∂ω0/∂p, ∂position/∂p).
    Scales {
        zeta: f64,
        omega0: f64,
        position: f64,
    },
    /// As the force scale that divides the drive (U_t, F0), β = drive/force; with the position
    /// scale proportional to it.
    Force,
    /// As μs.
    MuS,
}

/// The chain rule from a system's parameters to (ζ, β, w, φ, μs) and the position scale.
struct Chain {
    system: System,
    zeta: f64,
    omega0: f64,
}

impl Chain {
    fn new(system: &System, zeta: f64, omega0: f64) -> Self {
        Self {
            system: *system,
            zeta,
            omega0,
        }
    }

    /// How `p` enters, or `None` where the exact Jacobian does not serve.
    fn of(&self, p: FitParameter) -> Option<Link> {
        let (zeta, omega0) = (self.zeta, self.omega0);
        let scales = |zeta, omega0, position| {
            Some(Link::Scales {
                zeta,
                omega0,
                position,
            })
        };
        match (self.system, p) {
            (_, FitParameter::MuS) => Some(Link::MuS),
            // Circuit: ζ = (R + R_D)/2·√(C/L), ω0 = 1/√(LC), position U_t.
            (System::Circuit(c), FitParameter::Resistance | FitParameter::Rd) => {
                scales(0.5 * (c.capacitance / c.inductance).sqrt(), 0.0, 0.0)
            }
            (System::Circuit(_), FitParameter::Ut) => Some(Link::Force),
            (System::Circuit(c), FitParameter::Inductance) => scales(
                -zeta / (2.0 * c.inductance),
                -omega0 / (2.0 * c.inductance),
                0.0,
            ),
            (System::Circuit(c), FitParameter::Capacitance) => scales(
                zeta / (2.0 * c.capacitance),
                -omega0 / (2.0 * c.capacitance),
                0.0,
            ),
            // Mechanics: ζ = γ/(2√(km)), ω0 = √(k/m), position F0/k.
            (System::Mechanics(m), FitParameter::Damping) => {
                scales(0.5 / (m.stiffness * m.mass).sqrt(), 0.0, 0.0)
            }
            (System::Mechanics(_), FitParameter::Friction) => Some(Link::Force),
            (System::Mechanics(m), FitParameter::Mass) => {
                scales(-zeta / (2.0 * m.mass), -omega0 / (2.0 * m.mass), 0.0)
            }
            (System::Mechanics(m), FitParameter::Stiffness) => scales(
                -zeta / (2.0 * m.stiffness),
                omega0 / (2.0 * m.stiffness),
                -m.friction / (m.stiffness * m.stiffness),
            ),
            _ => None,
        }
    }
}

/// Per record, where its values sit in x.
#[derive(Debug, Clone, Copy)]
struct Slots {
    /// u_C offset (V), when fitted.
    offset: Option<usize>,
    /// Extra drive phase of the response ψ = 2πfδ (radians), when fitted.
    shift: Option<usize>,
    /// Drive amplitude / its sine-fit value, drive frequency / its sine-fit value, drive
    /// phase (radians), drive offset (V).
    drive: usize,
}

/// The least-squares problem of records: for each record the drive samples (against the
/// drive's sine) and the response samples (against the model), each divided by its channel's
/// noise.
struct Records<'a> {
    setup: &'a Setup,
    data: &'a [Measurement],
    slots: Vec<Slots>,
    /// Used times, drive and response samples of each record.
    time: Vec<Vec<f64>>,
    drive: Vec<Vec<f64>>,
    response: Vec<Vec<f64>>,
    /// 1/σ of the drive and response channels of each record.
    weights: Vec<(f64, f64)>,
    /// The values of the last evaluation of the residuals and each record's orbit there
    /// (Levenberg–Marquardt asks for the Jacobian where it last accepted a step).
    orbits: Option<(Vec<f64>, Vec<Orbit>)>,
    /// Whether to try the exact Jacobian ([`FitOptions::exact_jacobian`]).
    exact: bool,
    /// How the last Jacobian was computed.
    jacobian: Jacobian,
    /// Who is told of each iteration.
    watch: Watch<'a>,
    /// A coordinate held at a value (a profile likelihood's), which the minimisation's
    /// bounds then pin.
    pinned: Option<(usize, f64)>,
}

/// Where the exact Jacobian of a record starts: the dimensionless parameters of its model,
/// the steady state's strobe state and its period.
#[derive(Debug, Clone, Copy)]
struct Orbit {
    params: Params,
    strobe: State,
    period: Option<usize>,
}

/// A record's drive as the values x hold it.
#[derive(Debug, Clone, Copy)]
struct Drive {
    amplitude: f64,
    frequency: f64,
    phase: f64,
    offset: f64,
}

impl Records<'_> {
    fn drive(&self, x: &[f64], j: usize) -> Drive {
        let k = self.slots[j].drive;
        let sine = &self.data[j].drive;
        Drive {
            amplitude: x[k] * sine.amplitude,
            frequency: x[k + 1] * sine.frequency,
            phase: x[k + 2],
            offset: x[k + 3],
        }
    }

    fn offset_and_shift(&self, x: &[f64], j: usize) -> (f64, f64) {
        (
            self.slots[j].offset.map_or(0.0, |i| x[i]),
            self.slots[j].shift.map_or(0.0, |i| x[i]),
        )
    }

    /// The response model of record j (without the offset).
    fn response_model(
        &self,
        experiment: &Experiment,
        x: &[f64],
        j: usize,
    ) -> Result<Evaluated, crate::Error> {
        let d = self.drive(x, j);
        let (_, shift) = self.offset_and_shift(x, j);
        evaluate(
            experiment,
            d.frequency,
            d.amplitude,
            d.phase + shift,
            &self.time[j],
            &self.setup.steady,
            self.warm_start(j),
        )
    }

    /// Where the steady state of record j is sought: with Shockley diodes from the strobe
    /// state of the record's last model (a few periods instead of a transient from rest, and
    /// the same attractor as the model before); with PWL diodes from rest, whose exact solver
    /// settles by Newton's method anyway.
    fn warm_start(&self, j: usize) -> Option<State> {
        if self.setup.experiment.diode_model() != DiodeModel::Shockley {
            return None;
        }
        self.orbits.as_ref().map(|(_, orbits)| orbits[j].strobe)
    }

    /// Weighted residuals of record j: its drive samples, then its response samples; and the
    /// orbit of its model.
    fn record_residuals(
        &self,
        experiment: &Experiment,
        x: &[f64],
        j: usize,
    ) -> Option<(Vec<f64>, Orbit)> {
        let e = self.response_model(experiment, x, j).ok()?;
        let d = self.drive(x, j);
        let (offset, _) = self.offset_and_shift(x, j);
        let (wd, wr) = self.weights[j];
        let mut out = Vec::with_capacity(2 * self.time[j].len());
        for (s, v) in self.time[j].iter().zip(&self.drive[j]) {
            let model = d.offset + d.amplitude * (TAU * d.frequency * s + d.phase).cos();
            out.push(wd * (model - v));
        }
        for (m, v) in e.model.iter().zip(&self.response[j]) {
            out.push(wr * (m + offset - v));
        }
        let orbit = Orbit {
            params: e.params,
            strobe: e.strobe,
            period: e.period,
        };
        Some((out, orbit))
    }

    /// Every record's residuals and orbit at x.
    fn evaluate_all(&self, x: &[f64]) -> Option<Vec<(Vec<f64>, Orbit)>> {
        let experiment = self.setup.at(&x[..self.setup.free.len()])?;
        (0..self.data.len())
            .into_par_iter()
            .map(|j| self.record_residuals(&experiment, x, j))
            .collect()
    }

    fn all(&self, x: &[f64]) -> Option<Vec<Vec<f64>>> {
        self.evaluate_all(x)
            .map(|records| records.into_iter().map(|(r, _)| r).collect())
    }

    /// The drive channels' columns, exact (the sine's derivatives), and the offsets' columns.
    fn fill_drive_columns(&self, x: &[f64], columns: &mut [Vec<f64>]) {
        for (j, &(start, len)) in self.spans().iter().enumerate() {
            let half = len / 2;
            let (wd, wr) = self.weights[j];
            let slots = self.slots[j];
            let d = self.drive(x, j);
            let sine = &self.data[j].drive;
            for (t, s) in self.time[j].iter().enumerate() {
                let (sn, cs) = (TAU * d.frequency * s + d.phase).sin_cos();
                columns[slots.drive][start + t] = wd * cs * sine.amplitude;
                columns[slots.drive + 1][start + t] =
                    -wd * d.amplitude * sn * TAU * s * sine.frequency;
                columns[slots.drive + 2][start + t] = -wd * d.amplitude * sn;
                columns[slots.drive + 3][start + t] = wd;
            }
            if let Some(i) = slots.offset {
                columns[i][start + half..start + len].fill(wr);
            }
        }
    }

    /// The Jacobian from the exact tangent dynamics with respect to the parameters
    /// ([`crate::stability::periodic_orbit_sensitivity`]), or `None` where it cannot serve:
    /// Shockley diodes, a record whose model has no period (chaos), a tangential release, a
    /// multiplier 1.
    fn exact_jacobian(&self, x: &[f64]) -> Option<Vec<Vec<f64>>> {
        if !self.exact || self.setup.experiment.diode_model() != DiodeModel::Pwl {
            return None;
        }
        let free = self.setup.free.len();
        let orbits = match &self.orbits {
            Some((at, orbits)) if at.as_slice() == x => orbits.clone(),
            _ => self.evaluate_all(x)?.into_iter().map(|(_, o)| o).collect(),
        };
        let experiment = self.setup.at(&x[..free])?;
        let system = *experiment.system()?;
        let scales = system.scales();
        let (omega0, zeta, position, force) =
            (scales.omega0, scales.zeta(), scales.position, scales.force);
        let chain = Chain::new(&system, zeta, omega0);
        let links: Vec<Link> = self
            .setup
            .free
            .iter()
            .map(|&p| chain.of(p))
            .collect::<Option<_>>()?;
        let sensitivities: Vec<Vec<OrbitSample>> = (0..self.data.len())
            .into_par_iter()
            .map(|j| {
                let orbit = orbits[j];
                let taus: Vec<f64> = self.time[j].iter().map(|&s| s * omega0).collect();
                periodic_orbit_sensitivity(&orbit.params, orbit.strobe, orbit.period?, &taus).ok()
            })
            .collect::<Option<_>>()?;
        let n_res = 2 * self.time.iter().map(Vec::len).sum::<usize>();
        let mut columns = vec![vec![0.0; n_res]; x.len()];
        self.fill_drive_columns(x, &mut columns);
        for (j, &(start, len)) in self.spans().iter().enumerate() {
            let half = len / 2;
            let wr = self.weights[j].1;
            let slots = self.slots[j];
            let params = orbits[j].params;
            let sine = &self.data[j].drive;
            for (i, (sample, &seconds)) in sensitivities[j].iter().zip(&self.time[j]).enumerate() {
                let [dz, db, dw, dphi, dmu] = sample.dy;
                let row = start + half + i;
                // dy/dω0 at a fixed time in seconds: w = Ω/ω0 and τ = ω0·s.
                let along = |zeta_p: f64, omega_p: f64| {
                    dz * zeta_p + (sample.v * seconds - dw * params.w / omega0) * omega_p
                };
                for (k, link) in links.iter().enumerate() {
                    let du = match *link {
                        // u = position·y with y(ζ(p), β(p), w(p), τ(p)) and position(p).
                        Link::Scales {
                            zeta: zeta_p,
                            omega0: omega_p,
                            position: position_p,
                        } => position * along(zeta_p, omega_p) + position_p * sample.y,
                        // u_C = U_t·y(β = U/U_t); r = (F0/k)·y(β = F/F0).
                        Link::Force => (sample.y - params.beta * db) * position / force,
                        Link::MuS => position * dmu,
                    };
                    columns[k][row] = wr * du * self.setup.slope(k, x[k]);
                }
                columns[slots.drive][row] = wr * position * db * sine.amplitude / force;
                columns[slots.drive + 1][row] = wr * position * dw * TAU * sine.frequency / omega0;
                columns[slots.drive + 2][row] = wr * position * dphi;
                if let Some(k) = slots.shift {
                    columns[k][row] = wr * position * dphi;
                }
            }
        }
        Some(columns)
    }

    /// Where each record's residuals start, and how many it has.
    fn spans(&self) -> Vec<(usize, usize)> {
        let mut start = 0;
        self.time
            .iter()
            .map(|t| {
                let span = (start, 2 * t.len());
                start += 2 * t.len();
                span
            })
            .collect()
    }
}

fn no_value(file: &str, value: f64) -> FitError {
    FitError::Model {
        file: file.to_string(),
        error: crate::Error::InvalidParameter {
            name: "fit parameter",
            value,
            allowed: "the model has no value on either side of this value",
        },
    }
}

impl lm::Problem for Records<'_> {
    type Error = FitError;

    fn residuals(&mut self, x: &[f64]) -> Result<Option<Vec<f64>>, FitError> {
        self.setup.check_stop()?;
        let Some(records) = self.evaluate_all(x) else {
            return Ok(None);
        };
        let (residuals, orbits): (Vec<Vec<f64>>, Vec<Orbit>) = records.into_iter().unzip();
        self.orbits = Some((x.to_vec(), orbits));
        Ok(Some(residuals.concat()))
    }

    fn jacobian(&mut self, x: &[f64], r: &[f64]) -> Result<Vec<Vec<f64>>, FitError> {
        self.setup.check_stop()?;
        let (columns, kind) = self.jacobian_source(x, r)?;
        self.jacobian = kind;
        Ok(columns)
    }

    fn iteration(&mut self, iteration: usize, sum_squares: f64) -> Result<(), FitError> {
        self.watch.tell(iteration, sum_squares)
    }

    /// Each channel's precision ([`noise_floor`] of no noise: its quantisation, 10⁻⁹ of its
    /// scale, above the rounding of its printed digits and the PWL model's 10⁻¹²) in units
    /// of its weight, squared and averaged over the residuals.
    fn floor(&self) -> f64 {
        let mut sum = 0.0;
        let mut count = 0;
        for (j, m) in self.data.iter().enumerate() {
            let (wd, wr) = self.weights[j];
            let fd = wd * noise_floor(0.0, &self.drive[j], None);
            let fr = wr * noise_floor(0.0, &self.response[j], m.resolution);
            let samples = self.time[j].len();
            sum += samples as f64 * (fd * fd + fr * fr);
            count += 2 * samples;
        }
        sum / count.max(1) as f64
    }

    fn bounds(&self, n: usize) -> Vec<(f64, f64)> {
        let mut bounds = vec![(f64::NEG_INFINITY, f64::INFINITY); n];
        for (k, bound) in bounds.iter_mut().enumerate().take(self.setup.free.len()) {
            *bound = self.setup.bounds(k);
        }
        if let Some((k, v)) = self.pinned {
            bounds[k] = (v, v);
        }
        bounds
    }
}

impl Records<'_> {
    /// The Jacobian by finite differences (see the module documentation).
    fn finite_difference_jacobian(&self, x: &[f64], r: &[f64]) -> Result<Vec<Vec<f64>>, FitError> {
        let n = x.len();
        let spans = self.spans();
        let mut columns = vec![vec![0.0; r.len()]; n];
        let h = self.setup.step;
        for (k, column) in columns.iter_mut().enumerate().take(self.setup.free.len()) {
            let mut xp = x.to_vec();
            let mut dx = h * x[k].abs().max(1.0);
            xp[k] += dx;
            let mut rp = self.all(&xp);
            if rp.is_none() {
                // At the edge of the range: the backward difference.
                xp[k] = x[k] - dx;
                dx = -dx;
                rp = self.all(&xp);
            }
            let rp = rp.ok_or_else(|| no_value(&self.data[0].file, x[k] * self.setup.scale[k]))?;
            for (i, v) in rp.concat().iter().enumerate() {
                column[i] = (v - r[i]) / dx;
            }
        }
        let experiment = self
            .setup
            .at(&x[..self.setup.free.len()])
            .ok_or_else(|| no_value(&self.data[0].file, f64::NAN))?;
        // Per record, the response's derivatives by the drive amplitude, frequency and phase
        // (the time shift's column is the phase's: the response sees φ + ψ).
        let steps = [h, h, h];
        let derivatives: Vec<Option<[Vec<f64>; 3]>> = (0..self.data.len())
            .into_par_iter()
            .map(|j| {
                let k = self.slots[j].drive;
                let (start, len) = spans[j];
                let half = len / 2;
                let base = &r[start + half..start + len];
                let mut out: [Vec<f64>; 3] = Default::default();
                for (q, step) in steps.iter().enumerate() {
                    let mut xp = x.to_vec();
                    xp[k + q] += step;
                    let (rp, _) = self.record_residuals(&experiment, &xp, j)?;
                    out[q] = rp[half..]
                        .iter()
                        .zip(base)
                        .map(|(a, b)| (a - b) / step)
                        .collect();
                }
                Some(out)
            })
            .collect();
        self.fill_drive_columns(x, &mut columns);
        for j in 0..self.data.len() {
            let (start, len) = spans[j];
            let half = len / 2;
            let slots = self.slots[j];
            let dr = derivatives[j]
                .as_ref()
                .ok_or_else(|| no_value(&self.data[j].file, self.drive(x, j).frequency))?;
            for q in 0..3 {
                columns[slots.drive + q][start + half..start + len].copy_from_slice(&dr[q]);
            }
            if let Some(i) = slots.shift {
                columns[i][start + half..start + len].copy_from_slice(&dr[2]);
            }
        }
        Ok(columns)
    }
}

/// The most iterations of a quick minimisation: the PWL fit that gives a smooth law's knee,
/// a restart (which only has to show whether it goes lower).
const QUICK_ITERATIONS: usize = 10;

/// A restart (and an interval's search) counts as lower when its χ² lies below the
/// minimum's by more than this (in units of the residuals' variance s²).
const RESTART_LOWER: f64 = 1e-2;

impl<'a> Records<'a> {
    /// The problem of `data` with the free parameters of `setup`, and the starting values
    /// (free values scaled to 1, then each record's nuisance values).
    fn new(
        setup: &'a Setup,
        data: &'a [Measurement],
        options: &FitOptions,
        watch: Watch<'a>,
    ) -> Result<(Self, Vec<f64>), FitError> {
        let free = &setup.free;
        for m in data {
            check_units(&setup.system, m)?;
        }
        let mut x: Vec<f64> = vec![1.0; free.len()];
        let pick = |values: &[f64], used: &[bool]| -> Vec<f64> {
            values
                .iter()
                .zip(used)
                .filter(|(_, &u)| u)
                .map(|(&v, _)| v)
                .collect()
        };
        let time: Vec<Vec<f64>> = data.iter().map(|m| pick(&m.time, &m.used)).collect();
        let drive: Vec<Vec<f64>> = data
            .iter()
            .map(|m| pick(&m.drive_values, &m.used))
            .collect();
        let response: Vec<Vec<f64>> = data.iter().map(|m| pick(&m.response, &m.used)).collect();
        let mut slots = Vec::with_capacity(data.len());
        for (m, values) in data.iter().zip(&response) {
            let offset = options.offset.then(|| {
                x.push(values.iter().sum::<f64>() / values.len().max(1) as f64);
                x.len() - 1
            });
            let shift = options.time_shift.then(|| {
                x.push(0.0);
                x.len() - 1
            });
            slots.push(Slots {
                offset,
                shift,
                drive: x.len(),
            });
            x.extend([1.0, 1.0, m.drive.phase, m.drive.offset]);
        }
        let n_res: usize = 2 * time.iter().map(Vec::len).sum::<usize>();
        if n_res <= x.len() {
            return Err(FitError::TooFewSamples {
                residuals: n_res,
                values: x.len(),
            });
        }
        let start = setup.at(&x[..free.len()]).ok_or(FitError::FreeParameters(
            "the starting values are outside the parameters' ranges",
        ))?;
        for (m, t) in data.iter().zip(&time) {
            evaluate(
                &start,
                m.drive.frequency,
                m.drive.amplitude,
                m.drive.phase,
                t,
                &setup.steady,
                None,
            )
            .map_err(|error| FitError::Model {
                file: m.file.clone(),
                error,
            })?;
        }
        let weights = data
            .iter()
            .zip(drive.iter().zip(&response))
            .map(|(m, (d, r))| {
                (
                    1.0 / noise_floor(m.drive_noise, d, None),
                    1.0 / noise_floor(m.noise, r, m.resolution),
                )
            })
            .collect();
        let problem = Records {
            setup,
            data,
            slots,
            time,
            drive,
            response,
            weights,
            orbits: None,
            exact: options.exact_jacobian,
            jacobian: Jacobian::FiniteDifferences,
            watch,
            pinned: None,
        };
        Ok((problem, x))
    }
}

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
    let quick = lm::Settings {
        max_iterations: QUICK_ITERATIONS.min(settings.max_iterations),
        tolerance: 1e-6,
        ..settings
    };
    let first = match depth {
        Depth::Full(_) => lm::minimise(&mut problem, x, settings)?,
        Depth::Quick => lm::minimise(&mut problem, x, quick)?,
    }
    .ok_or_else(failed)?;
    // Second pass: each channel weighted by its RMS residual of the first.
    let spans = problem.spans();
    let weights = spans
        .iter()
        .zip(&problem.weights)
        .zip(data.iter().zip(problem.drive.iter().zip(&problem.response)))
        .map(|((&(start, len), &(wd, wr)), (m, (d, r)))| {
            let half = len / 2;
            let sd = rms(&first.residuals[start..start + half]) / wd;
            let sr = rms(&first.residuals[start + half..start + len]) / wr;
            (
                1.0 / noise_floor(sd, d, None),
                1.0 / noise_floor(sr, r, m.resolution),
            )
        })
        .collect();
    problem.weights = weights;
    problem.watch.before += first.iterations;
    let mut solution = match depth {
        Depth::Full(_) => lm::minimise(&mut problem, first.x.clone(), settings)?,
        Depth::Quick => lm::minimise(&mut problem, first.x.clone(), quick)?,
    }
    .ok_or_else(failed)?;
    let mut iterations = first.iterations + solution.iterations;
    let dof = solution.residuals.len().saturating_sub(n_values).max(1);
    let t = t_quantile_975(dof);
    // A restart from elsewhere, and the intervals' checks: a point lower than the minimum
    // is a minimum elsewhere, from which the fit goes on (three times at most).
    let mut lower_by = None;
    let mut intervals = None;
    if let Depth::Full(_) = depth {
        for _ in 0..3 {
            problem.watch.before += solution.iterations;
            // Lower by more than the residuals' precision can account for.
            let s2 = (solution.sum_squares / dof as f64).max(lm::Problem::floor(&problem));
            let covariance = Covariance::of(&solution, n_free);
            let mut lower = None;
            if let Some(point) =
                covariance.restart(&solution.x, &lm::Problem::bounds(&problem, n_values))
            {
                let restart = lm::minimise(&mut problem, point, quick)?;
                if let Some(restart) = restart {
                    if restart.sum_squares < solution.sum_squares - RESTART_LOWER * s2 {
                        lower = Some(restart);
                    }
                }
            }
            if lower.is_none() {
                match profile::intervals(
                    &mut problem,
                    &solution,
                    &covariance.inverse,
                    n_free,
                    t,
                    quick,
                )? {
                    profile::Outcome::Intervals(found) => {
                        lower_by = None;
                        intervals = Some((found, covariance));
                        break;
                    }
                    profile::Outcome::Lower(point) => {
                        lower = lm::minimise(&mut problem, point, settings)?
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
    let covariance = match intervals.as_ref() {
        Some((_, c)) => c.clone(),
        None => Covariance::of(&solution, n_free),
    };
    let s2 = variance(solution.sum_squares, dof, lm::Problem::floor(&problem));
    let linear: Vec<([f64; 2], Interval)> = (0..n_free)
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
        .collect();
    let found = intervals.map_or(linear, |(found, _)| found);
    let (fitted_parameters, correlation) =
        uncertainties(&setup, &solution, &covariance, &found, s2);
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
    let mut warnings = plan.warnings.clone();
    let converged = solution.converged && lower_by.is_none();
    if !converged {
        let why = match lower_by {
            Some(lower_by) => warning::NotConverged::Restart { lower_by },
            None if solution.iterations >= options.max_iterations => {
                warning::NotConverged::Iterations {
                    limit: options.max_iterations,
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
    for m in data {
        if m.clipped > 0 {
            warnings.push(FitWarning::Clipped {
                file: m.file.clone(),
                samples: m.clipped,
                of: m.time.len(),
            });
        }
    }
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
        parameters,
        correlation: named_correlation,
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
        converged,
        jacobian: problem.jacobian,
        experiment: fitted,
        warnings,
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
        let free = FitParameter::MECHANICS;
        exact_matches_central_differences(&start, &free, &data);
    }
}
