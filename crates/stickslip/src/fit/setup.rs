//! What a fit keeps fixed: the experiment, its system, the free parameters and their scales
//! (I_s in its logarithm), and how a vector of the optimizer's unknowns becomes an experiment.

use crate::experiment::{DiodeModel, Experiment, Key};
use crate::friction::FrictionLaw;
use crate::physical::{Scales, System};
use crate::shockley::ShockleyOptions;
use crate::steady::SteadyOptions;

use super::*;

/// Everything a fit keeps fixed: the experiment's circuit or mechanical oscillator and
/// options and the free list.
pub(super) struct Setup {
    pub(super) experiment: Experiment,
    pub(super) system: System,
    pub(super) free: Vec<FitParameter>,
    pub(super) scale: Vec<f64>,
    /// Whether each free value is fitted in its logarithm (I_s, which spans decades and whose
    /// valley with n is straight in ln I_s): value = scale·e^(x − 1); else value = scale·x.
    pub(super) log: Vec<bool>,
    pub(super) steady: SteadyOptions,
    pub(super) step: f64,
    /// A mechanical oscillator's belt and friction law in physical units, which the fit
    /// holds (or frees) while m, k and F0 move their dimensionless images; `None` for a
    /// circuit and for an oscillator without a belt and with Coulomb's law.
    pub(super) friction: Option<Friction>,
}

/// A mechanical oscillator's belt speed (m/s) and friction law with its parameters in
/// physical units (the Stribeck speed in m/s, the viscous friction and the cubic law's K1 in
/// N·s/m, K3 in N·s³/m³; δ and μs are numbers): what stays fixed when the fit moves m, k or
/// F0, whose scales make the dimensionless vb, vs, η, k1 and k3 ([`Key::image`]).
#[derive(Debug, Clone, Copy)]
pub(super) struct Friction {
    belt_speed: f64,
    law: FrictionLaw,
}

impl Friction {
    /// The belt and law of `experiment` in physical units, or `None` (see [`Setup::friction`]).
    fn of(experiment: &Experiment) -> Option<Self> {
        let Some(System::Mechanics(m)) = experiment.system() else {
            return None;
        };
        let law = experiment.friction_law();
        if experiment.vb() == 0.0 && law.is_coulomb() {
            return None;
        }
        let s = m.scales();
        let p = |key, v| super::parameter::physical(key, v, &s);
        Some(Self {
            belt_speed: p(Key::BeltSpeed, experiment.vb()),
            law: match law {
                FrictionLaw::Coulomb => law,
                FrictionLaw::Stribeck { vs, delta, eta } => FrictionLaw::Stribeck {
                    vs: p(Key::StribeckSpeed, vs),
                    delta,
                    eta: p(Key::ViscousFriction, eta),
                },
                FrictionLaw::Cubic { k1, k3 } => FrictionLaw::Cubic {
                    k1: p(Key::CubicK1, k1),
                    k3: p(Key::CubicK3, k3),
                },
            },
        })
    }

    /// With the free value `p` set to `value` (the Stribeck speed, the viscous friction).
    fn set(&mut self, p: FitParameter, value: f64) {
        if let FrictionLaw::Stribeck { vs, eta, .. } = &mut self.law {
            match p {
                FitParameter::StribeckSpeed => *vs = value,
                FitParameter::ViscousFriction => *eta = value,
                _ => {}
            }
        }
    }

    /// The dimensionless belt speed and law at `scales`.
    fn images(&self, scales: &Scales) -> (f64, FrictionLaw) {
        let d = |key, v| super::parameter::dimensionless(key, v, scales);
        let law = match self.law {
            FrictionLaw::Coulomb => self.law,
            FrictionLaw::Stribeck { vs, delta, eta } => FrictionLaw::Stribeck {
                vs: d(Key::StribeckSpeed, vs),
                delta,
                eta: d(Key::ViscousFriction, eta),
            },
            FrictionLaw::Cubic { k1, k3 } => FrictionLaw::Cubic {
                k1: d(Key::CubicK1, k1),
                k3: d(Key::CubicK3, k3),
            },
        };
        (d(Key::BeltSpeed, self.belt_speed), law)
    }
}

/// The strobe tolerance of a smooth law's steady state in a fit: 10⁻⁶, the stiff solver's
/// default tolerance, above the fit's own solver tolerance ([`jacobian::SMOOTH_RTOL`]), so
/// that the strobe map's jitter does not hide the cycle.
pub(super) const SMOOTH_STEADY_TOLERANCE: f64 = 1e-6;

/// Whether `p` is fitted in its logarithm ([`Setup`]): the saturation current I_s.
pub(super) fn fitted_in_log(p: FitParameter) -> bool {
    p == FitParameter::DiodeIs
}

impl Setup {
    pub(super) fn new(experiment: &Experiment, free: &[FitParameter]) -> Result<Self, FitError> {
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
            friction: Friction::of(experiment),
        })
    }

    /// The experiment at scaled values `x` (value = x·scale), or `None` outside the
    /// parameters' ranges.
    pub(super) fn at(&self, x: &[f64]) -> Option<Experiment> {
        let mut system = self.system;
        let mut mu_s = self.experiment.mu_s();
        let mut friction = self.friction;
        for (k, (p, &x)) in self.free.iter().zip(x).enumerate() {
            let v = self.value(k, x);
            if !v.is_finite() {
                return None;
            }
            match (*p, &mut system) {
                (FitParameter::MuS, _) => mu_s = v,
                (p, System::Circuit(c)) => p.set(c, v),
                (p, System::Mechanics(m)) => {
                    p.set_mechanics(m, v);
                    if let Some(f) = friction.as_mut() {
                        f.set(p, v);
                    }
                }
            }
        }
        let e = match system {
            System::Circuit(c) => Experiment::circuit(c).ok()?,
            System::Mechanics(m) => Experiment::mechanics(m).ok()?,
        };
        let e = e
            .with_shockley_options(*self.experiment.shockley_options())
            .ok()?;
        let mut e = e.with_mu_s(mu_s).ok()?;
        // The belt and the law at this oscillator's scales.
        if let (Some(f), System::Mechanics(m)) = (friction, system) {
            let (vb, law) = f.images(&m.scales());
            e = e.with_vb(vb).ok()?.with_law(law).ok()?;
        }
        // The rebuilt experiment keeps the caller's cancellation token.
        Some(e.with_cancel(self.experiment.cancel().clone()))
    }

    /// `Err(FitError::Stopped)` once the caller's token stops the fit (Ctrl-C, a deadline):
    /// checked before each evaluation, since a stopped model only looks like a failed step.
    pub(super) fn check_stop(&self) -> Result<(), FitError> {
        match self.experiment.cancel().stopped() {
            Some(stop) => Err(FitError::Stopped(stop.error())),
            None => Ok(()),
        }
    }

    /// The value of free parameter `k` at the scaled coordinate `x`.
    pub(super) fn value(&self, k: usize, x: f64) -> f64 {
        if self.log[k] {
            self.scale[k] * (x - 1.0).exp()
        } else {
            self.scale[k] * x
        }
    }

    /// d value / dx of free parameter `k` at `x` (the chain rule from the coordinate).
    pub(super) fn slope(&self, k: usize, x: f64) -> f64 {
        if self.log[k] {
            self.value(k, x)
        } else {
            self.scale[k]
        }
    }

    /// The bounds of free parameter `k`'s coordinate that a value may reach: R, R_D, R_s, γ
    /// and the viscous friction down to 0, μs down to 1 (the others are positive and refused at 0, which the
    /// minimisation treats as a failed step; I_s is fitted in its logarithm).
    pub(super) fn bounds(&self, k: usize) -> (f64, f64) {
        let lowest = match self.free[k] {
            FitParameter::Resistance
            | FitParameter::Rd
            | FitParameter::DiodeRs
            | FitParameter::Damping
            | FitParameter::ViscousFriction => Some(0.0),
            FitParameter::MuS => Some(1.0),
            _ => None,
        };
        match lowest {
            Some(v) if !self.log[k] => (self.coordinate(k, v), f64::INFINITY),
            _ => (f64::NEG_INFINITY, f64::INFINITY),
        }
    }

    /// The bounds of all `n` coordinates of a fit (the free parameters' first, then the
    /// nuisance values', unbounded), coordinate k held at v where `pinned` is (k, v) (a
    /// profile's).
    pub(super) fn all_bounds(&self, n: usize, pinned: Option<(usize, f64)>) -> Vec<(f64, f64)> {
        let mut bounds = vec![(f64::NEG_INFINITY, f64::INFINITY); n];
        for (k, bound) in bounds.iter_mut().enumerate().take(self.free.len()) {
            *bound = self.bounds(k);
        }
        if let Some((k, v)) = pinned {
            bounds[k] = (v, v);
        }
        bounds
    }

    /// The coordinate of free parameter `k` at `value` (the inverse of [`Setup::value`]).
    pub(super) fn coordinate(&self, k: usize, value: f64) -> f64 {
        if self.log[k] {
            1.0 + (value / self.scale[k]).ln()
        } else {
            value / self.scale[k]
        }
    }

    pub(super) fn values(&self, x: &[f64]) -> Vec<f64> {
        x.iter()
            .enumerate()
            .map(|(k, &x)| self.value(k, x))
            .collect()
    }
}
