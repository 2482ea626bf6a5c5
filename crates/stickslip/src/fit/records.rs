//! The records problem: the model of each record (its steady state sampled at the record's
//! times), the residuals of every channel over all records, and their Jacobian for the
//! Levenberg–Marquardt iteration (exact from the orbit's sensitivities, or by differences).

use crate::experiment::{DiodeModel, Experiment};
use crate::measure::Measurement;
use crate::params::{Params, State};
use crate::physical::System;
use crate::solver::sample_at;
use crate::stability::{periodic_orbit_sensitivity, OrbitSample};
use crate::steady::SolverFactory;
use crate::steady::{MotionClass, SteadyOptions};
use rayon::prelude::*;
use std::f64::consts::{PI, TAU};

use super::setup::*;
use super::*;
use options::Watch;

/// The model of one record: u_C at the used times, and the motion's class, w and β; the
/// dimensionless parameters, the steady state's strobe state and period (what the exact
/// Jacobian starts from).
pub(super) struct Evaluated {
    pub(super) model: Vec<f64>,
    pub(super) class: MotionClass,
    pub(super) w: f64,
    pub(super) beta: f64,
    pub(super) params: Params,
    pub(super) strobe: State,
    pub(super) period: Option<usize>,
}

pub(super) fn wrap(phase: f64) -> f64 {
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
pub(super) fn evaluate(
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
pub(super) enum Link {
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
pub(super) struct Chain {
    pub(super) system: System,
    pub(super) zeta: f64,
    pub(super) omega0: f64,
}

impl Chain {
    pub(super) fn new(system: &System, zeta: f64, omega0: f64) -> Self {
        Self {
            system: *system,
            zeta,
            omega0,
        }
    }

    /// How `p` enters, or `None` where the exact Jacobian does not serve.
    pub(super) fn of(&self, p: FitParameter) -> Option<Link> {
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
pub(super) struct Slots {
    /// u_C offset (V), when fitted.
    pub(super) offset: Option<usize>,
    /// Extra drive phase of the response ψ = 2πfδ (radians), when fitted.
    pub(super) shift: Option<usize>,
    /// Drive amplitude / its sine-fit value, drive frequency / its sine-fit value, drive
    /// phase (radians), drive offset (V).
    pub(super) drive: usize,
}

impl Slots {
    /// Fill `row` of the Jacobian's columns of the record's drive (its amplitude and
    /// frequency, each relative to its sine-fit value, and its phase) and of the response's
    /// shift, from the derivatives `[dy/dβ, dy/dw, dy/dφ]` of the model's y at one sample;
    /// `scale` is the row's weight times the position scale (u = position·y), `force` the
    /// force scale (β = amplitude/force) and `omega0` the natural frequency (rad/s).
    #[allow(clippy::too_many_arguments)]
    pub(super) fn fill_drive(
        &self,
        columns: &mut [Vec<f64>],
        row: usize,
        scale: f64,
        [db, dw, dphi]: [f64; 3],
        sine: &crate::measure::SineFit,
        force: f64,
        omega0: f64,
    ) {
        columns[self.drive][row] = scale * db * sine.amplitude / force;
        columns[self.drive + 1][row] = scale * dw * TAU * sine.frequency / omega0;
        columns[self.drive + 2][row] = scale * dphi;
        if let Some(k) = self.shift {
            columns[k][row] = scale * dphi;
        }
    }
}

/// The least-squares problem of records: for each record the drive samples (against the
/// drive's sine) and the response samples (against the model), each divided by its channel's
/// noise.
pub(super) struct Records<'a> {
    pub(super) setup: &'a Setup,
    pub(super) data: &'a [Measurement],
    pub(super) slots: Vec<Slots>,
    /// Used times, drive and response samples of each record.
    pub(super) time: Vec<Vec<f64>>,
    pub(super) drive: Vec<Vec<f64>>,
    pub(super) response: Vec<Vec<f64>>,
    /// 1/σ of the drive and response channels of each record.
    pub(super) weights: Vec<(f64, f64)>,
    /// The values of the last evaluation of the residuals and each record's orbit there
    /// (Levenberg–Marquardt asks for the Jacobian where it last accepted a step).
    pub(super) orbits: Option<(Vec<f64>, Vec<Orbit>)>,
    /// Whether to try the exact Jacobian ([`FitOptions::exact_jacobian`]).
    pub(super) exact: bool,
    /// How the last Jacobian was computed.
    pub(super) jacobian: Jacobian,
    /// Who is told of each iteration.
    pub(super) watch: Watch<'a>,
    /// A coordinate held at a value (a profile likelihood's), which the minimisation's
    /// bounds then pin.
    pub(super) pinned: Option<(usize, f64)>,
}

/// Where the exact Jacobian of a record starts: the dimensionless parameters of its model,
/// the steady state's strobe state and its period.
#[derive(Debug, Clone, Copy)]
pub(super) struct Orbit {
    pub(super) params: Params,
    pub(super) strobe: State,
    pub(super) period: Option<usize>,
}

/// A record's drive as the values x hold it.
#[derive(Debug, Clone, Copy)]
pub(super) struct Drive {
    pub(super) amplitude: f64,
    pub(super) frequency: f64,
    pub(super) phase: f64,
    pub(super) offset: f64,
}

impl Records<'_> {
    pub(super) fn drive(&self, x: &[f64], j: usize) -> Drive {
        let k = self.slots[j].drive;
        let sine = &self.data[j].drive;
        Drive {
            amplitude: x[k] * sine.amplitude,
            frequency: x[k + 1] * sine.frequency,
            phase: x[k + 2],
            offset: x[k + 3],
        }
    }

    pub(super) fn offset_and_shift(&self, x: &[f64], j: usize) -> (f64, f64) {
        (
            self.slots[j].offset.map_or(0.0, |i| x[i]),
            self.slots[j].shift.map_or(0.0, |i| x[i]),
        )
    }

    /// The response model of record j (without the offset).
    pub(super) fn response_model(
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
    /// the same attractor as the model before), and so on a belt or with a friction law
    /// other than Coulomb's; with PWL diodes from rest, whose exact solver settles by
    /// Newton's method anyway.
    pub(super) fn warm_start(&self, j: usize) -> Option<State> {
        if self.setup.experiment.diode_model() != DiodeModel::Shockley && !self.central() {
            return None;
        }
        self.orbits.as_ref().map(|(_, orbits)| orbits[j].strobe)
    }

    /// Weighted residuals of record j: its drive samples, then its response samples; and the
    /// orbit of its model.
    pub(super) fn record_residuals(
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
    pub(super) fn evaluate_all(&self, x: &[f64]) -> Option<Vec<(Vec<f64>, Orbit)>> {
        let experiment = self.setup.at(&x[..self.setup.free.len()])?;
        (0..self.data.len())
            .into_par_iter()
            .map(|j| self.record_residuals(&experiment, x, j))
            .collect()
    }

    pub(super) fn all(&self, x: &[f64]) -> Option<Vec<Vec<f64>>> {
        self.evaluate_all(x)
            .map(|records| records.into_iter().map(|(r, _)| r).collect())
    }

    /// The drive channels' columns, exact (the sine's derivatives), and the offsets' columns.
    pub(super) fn fill_drive_columns(&self, x: &[f64], columns: &mut [Vec<f64>]) {
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
    pub(super) fn exact_jacobian(&self, x: &[f64]) -> Option<Vec<Vec<f64>>> {
        if !self.exact || self.setup.experiment.diode_model() != DiodeModel::Pwl || self.central() {
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
                slots.fill_drive(
                    &mut columns,
                    row,
                    wr * position,
                    [db, dw, dphi],
                    sine,
                    force,
                    omega0,
                );
            }
        }
        Some(columns)
    }

    /// Where each record's residuals start, and how many it has.
    pub(super) fn spans(&self) -> Vec<(usize, usize)> {
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

pub(super) fn no_value(file: &str, value: f64) -> FitError {
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
        self.setup.all_bounds(n, self.pinned)
    }
}

impl passes::Passes for Records<'_> {
    /// The drive's and the response's channel of each record by its RMS residual.
    fn reweight(&mut self, first: &lm::Solution) {
        let weights = self
            .spans()
            .iter()
            .zip(&self.weights)
            .zip(self.data.iter().zip(self.drive.iter().zip(&self.response)))
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
        self.weights = weights;
    }

    fn advance(&mut self, iterations: usize) {
        self.watch.before += iterations;
    }
}

impl Records<'_> {
    /// The Jacobian by finite differences (see the module documentation).
    pub(super) fn finite_difference_jacobian(
        &self,
        x: &[f64],
        r: &[f64],
    ) -> Result<Vec<Vec<f64>>, FitError> {
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
        self.place_drive_derivatives(x, &derivatives, &mut columns)?;
        Ok(columns)
    }

    /// The drive channels' exact columns, then each record's response derivatives by its drive
    /// amplitude, frequency and phase (`derivatives`, over the record's second half) in their
    /// columns; the time shift's column is the phase's. A record without them (`None`: its
    /// model had no value) is the error.
    pub(super) fn place_drive_derivatives(
        &self,
        x: &[f64],
        derivatives: &[Option<[Vec<f64>; 3]>],
        columns: &mut [Vec<f64>],
    ) -> Result<(), FitError> {
        self.fill_drive_columns(x, columns);
        for (j, &(start, len)) in self.spans().iter().enumerate() {
            let half = len / 2;
            let slots = self.slots[j];
            let dr = derivatives[j]
                .as_ref()
                .ok_or_else(|| no_value(&self.data[j].file, self.drive(x, j).frequency))?;
            for (q, d) in dr.iter().enumerate() {
                columns[slots.drive + q][start + half..start + len].copy_from_slice(d);
            }
            if let Some(i) = slots.shift {
                columns[i][start + half..start + len].copy_from_slice(&dr[2]);
            }
        }
        Ok(())
    }
}

/// The most iterations of a quick minimisation: the PWL fit that gives a smooth law's knee,
/// a restart (which only has to show whether it goes lower).
pub(super) const QUICK_ITERATIONS: usize = 10;

/// A restart (and an interval's search) counts as lower when its χ² lies below the
/// minimum's by more than this (in units of the residuals' variance s²).
pub(super) const RESTART_LOWER: f64 = 1e-2;

impl<'a> Records<'a> {
    /// The problem of `data` with the free parameters of `setup`, and the starting values
    /// (free values scaled to 1, then each record's nuisance values).
    pub(super) fn new(
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
