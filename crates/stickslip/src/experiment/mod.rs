//! Experiments: what every front end (the command-line tool, the Python package, the lab
//! server) describes and runs.
//!
//! An [`Experiment`] is a system (a dimensionless model, a circuit whose diodes are PWL or
//! Shockley, or a mechanical oscillator), a drive, the friction ratio μs and an initial state.
//! It converts to the dimensionless [`Params`], builds the right solver (the exact solver for
//! PWL diodes and Coulomb friction, the stiff solver for Shockley diodes), chooses the
//! steady-state options that fit that solver, and converts results back to physical units.
//!
//! Experiments are described value by value in an [`ExperimentSpec`] (from a TOML file, flags
//! or keyword arguments, stacked in layers) and built by [`ExperimentSpec::build`], or made
//! directly:
//!
//! ```
//! use stickslip::experiment::Experiment;
//! use stickslip::steady::MotionClass;
//! // The paper's circuit at its Fig. 3 point Ω/ω0 = 0.95, β = 2.14.
//! let experiment = Experiment::paper().with_w(0.95).unwrap().with_beta(2.14).unwrap();
//! let steady = experiment.steady().unwrap();
//! assert_eq!(steady.class, MotionClass::Sliding);
//! // The same drive in volts and hertz.
//! let scales = experiment.scales().unwrap();
//! assert!((scales.drive_amplitude(2.14) - 1.498).abs() < 1e-12);
//! ```

mod choices;
mod display;
pub(crate) mod errors;
mod factory;
mod file;
mod key;
pub mod keys;
mod law;
mod spec;
mod stability;
mod text;
mod trajectory;
mod units;

pub use choices::{DiodeModel, Origin, Preset};
pub use errors::{ConfigError, SpecError};
use factory::law_of;
pub use factory::ExperimentFactory;
pub use key::{FitRole, KeyDefault, KeyForm, KeyGroup, KeyInfo, KeyRange, Section};
pub use keys::Key;
pub use law::Law;
pub use spec::ExperimentSpec;
pub use trajectory::Trajectory;
pub use units::{Conversion, PhysicalUnits};

use crate::cancel::Cancel;
use crate::error::{Error, Result};
use crate::friction::{check_vb, FrictionLaw};
use crate::params::{Parameter, Params, State};
use crate::physical::{Circuit, Diode, Mechanics, Scales, System, SystemKind};
use crate::scan::ParameterRange;
use crate::shockley::{DiodePair, ShockleyOptions};
use crate::solver::Solver;
use crate::stability::Dynamics;
use crate::steady::{steady_state_from, SolverFactory, SteadyOptions, SteadyState};
use crate::theory::curves::{SweepTheory, TheoryCurve};
use serde::{Deserialize, Serialize};

/// One experiment, validated. See the module documentation.
///
/// The drive frequency and amplitude may be absent (an experiment that a sweep or a grid
/// completes); everything that needs them says so ([`Experiment::params`]).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct Experiment {
    system: Option<System>,
    zeta: f64,
    w: Option<f64>,
    beta: Option<f64>,
    phi: f64,
    mu_s: f64,
    initial: State,
    origin: Origin,
    shockley: ShockleyOptions,
    /// The belt speed vb (mechanical or dimensionless systems; 0: no belt).
    #[serde(default, skip_serializing_if = "is_zero")]
    vb: f64,
    /// The friction law.
    #[serde(default, skip_serializing_if = "FrictionLaw::is_coulomb")]
    law: FrictionLaw,
    /// The token every solver of the experiment checks (not part of what the experiment is:
    /// not saved, not compared).
    #[serde(skip)]
    cancel: CancelSlot,
}

/// Whether a value is zero (serde skips a belt at rest).
fn is_zero(x: &f64) -> bool {
    *x == 0.0
}

/// An experiment's [`Cancel`] token: equal to any other (the token says how long to work,
/// not what to compute).
#[derive(Debug, Clone, Default)]
struct CancelSlot(Cancel);

impl PartialEq for CancelSlot {
    fn eq(&self, _: &Self) -> bool {
        true
    }
}

impl Experiment {
    fn with_system(system: Option<System>, zeta: f64, origin: Origin) -> Self {
        Self {
            system,
            zeta,
            w: None,
            beta: None,
            phi: 0.0,
            mu_s: 1.0,
            initial: State::default(),
            origin,
            shockley: ShockleyOptions::default(),
            vb: 0.0,
            law: FrictionLaw::Coulomb,
            cancel: CancelSlot::default(),
        }
    }

    /// The dimensionless model at (ζ, w, β), with φ = 0, μs = 1, from rest.
    ///
    /// # Errors
    /// [`Error::InvalidParameter`] when ζ < 0, w ≤ 0, β < 0 or a value is not finite.
    pub fn dimensionless(zeta: f64, w: f64, beta: f64) -> Result<Self> {
        let p = Params::new(zeta, w, beta)?;
        let mut e = Self::with_system(None, p.zeta, Origin::Parameters);
        e.w = Some(p.w);
        e.beta = Some(p.beta);
        Ok(e)
    }

    /// The paper's circuit with PWL diodes ([`Circuit::paper`]), no drive yet, from rest.
    pub fn paper() -> Self {
        Self::circuit(Circuit::paper())
            .expect("the paper's circuit is valid")
            .with_origin(Origin::Preset(Preset::Paper))
    }

    /// A circuit, no drive yet, from rest.
    ///
    /// # Errors
    /// When the circuit is invalid.
    pub fn circuit(circuit: Circuit) -> Result<Self> {
        let c = circuit.validate()?;
        let zeta = spec::image(
            (Key::Resistance, c.resistance, c.scales().zeta()),
            Key::Zeta,
        )?;
        Ok(Self::with_system(
            Some(System::Circuit(c)),
            zeta,
            Origin::Parts,
        ))
    }

    /// A mechanical oscillator, no drive yet, from rest.
    ///
    /// # Errors
    /// When the oscillator is invalid.
    pub fn mechanics(mechanics: Mechanics) -> Result<Self> {
        let m = mechanics.validate()?;
        let zeta = spec::image((Key::Damping, m.damping, m.scales().zeta()), Key::Zeta)?;
        Ok(Self::with_system(
            Some(System::Mechanics(m)),
            zeta,
            Origin::Parts,
        ))
    }

    /// The experiment described by the text of a TOML file ([`ExperimentSpec::from_toml`]).
    ///
    /// # Errors
    /// As [`ExperimentSpec::from_toml`] and [`ExperimentSpec::build`].
    pub fn from_toml(text: &str, file: &str) -> Result<Self> {
        ExperimentSpec::from_toml(text, file)?.build()
    }

    /// The same experiment, said to come from `origin` (for its description).
    pub fn with_origin(mut self, origin: Origin) -> Self {
        self.origin = origin;
        self
    }

    /// Set the drive frequency w = Ω/ω0.
    ///
    /// # Errors
    /// When w is not finite and > 0.
    pub fn with_w(mut self, w: f64) -> Result<Self> {
        self.w = Some(Key::W.check(w)?);
        Ok(self)
    }

    /// Set the drive amplitude β (U/U_t or F/F0).
    ///
    /// # Errors
    /// When β is not finite and ≥ 0.
    pub fn with_beta(mut self, beta: f64) -> Result<Self> {
        self.beta = Some(Key::Beta.check(beta)?);
        Ok(self)
    }

    /// Set the drive phase φ in radians.
    ///
    /// # Errors
    /// When φ is not finite.
    pub fn with_phi(mut self, phi: f64) -> Result<Self> {
        self.phi = Key::Phi.check(phi)?;
        Ok(self)
    }

    /// Set the static-to-kinetic friction ratio μs (not used by the Shockley diode law).
    ///
    /// # Errors
    /// When μs is not finite and ≥ 1.
    pub fn with_mu_s(mut self, mu_s: f64) -> Result<Self> {
        self.mu_s = Key::MuS.check(mu_s)?;
        Ok(self)
    }

    /// Put the block on a belt moving at the dimensionless speed vb (0: no belt). A circuit
    /// has no belt.
    ///
    /// # Errors
    /// [`SpecError::NoBelt`] for a circuit; when vb is not finite or |vb| > 1e6.
    pub fn with_vb(mut self, vb: f64) -> Result<Self> {
        if matches!(self.system, Some(System::Circuit(_))) {
            return Err(SpecError::NoBelt { key: Key::Vb }.into());
        }
        self.vb = check_vb(vb)?;
        Ok(self)
    }

    /// Set the friction law (checked with this experiment's μs). A circuit has none but the
    /// diodes'.
    ///
    /// # Errors
    /// [`SpecError::NoBelt`] for a circuit and a law other than Coulomb's; an invalid law
    /// ([`FrictionLaw::validate`]).
    pub fn with_law(mut self, law: FrictionLaw) -> Result<Self> {
        if !law.is_coulomb() && matches!(self.system, Some(System::Circuit(_))) {
            return Err(SpecError::NoBelt {
                key: Key::FrictionLaw,
            }
            .into());
        }
        self.law = law.validate(self.mu_s)?;
        Ok(self)
    }

    /// The belt speed vb (0: no belt).
    pub fn vb(&self) -> f64 {
        self.vb
    }

    /// The friction law.
    pub fn friction_law(&self) -> FrictionLaw {
        self.law
    }

    /// Whether the experiment is self-excited: a belt moves and no drive is given (or its
    /// amplitude is 0); its period is then the motion's own, found by the steady-state search
    /// ([`crate::steady::self_excited`]).
    pub fn is_self_excited(&self) -> bool {
        self.vb != 0.0 && self.beta.unwrap_or(0.0) == 0.0
    }

    /// Set ζ of a dimensionless experiment.
    ///
    /// # Errors
    /// [`SpecError::ZetaWithPhysical`] for a physical system (its parts decide ζ); when ζ is
    /// not finite and ≥ 0.
    pub fn with_zeta(mut self, zeta: f64) -> Result<Self> {
        if self.system.is_some() {
            return Err(SpecError::ZetaWithPhysical.into());
        }
        self.zeta = Key::Zeta.check(zeta)?;
        Ok(self)
    }

    /// Set the dimensionless initial state (y0, v0) at τ = 0.
    ///
    /// # Errors
    /// When a value is not finite or outside ±1e9 ([`crate::limits::check_state`]).
    pub fn with_initial(mut self, initial: State) -> Result<Self> {
        self.initial = crate::limits::check_state(initial.y, initial.v)?;
        Ok(self)
    }

    /// Set the drive frequency f in Hz (physical systems).
    ///
    /// # Errors
    /// [`SpecError::NeedsPhysical`] without a physical system; when f is not finite and > 0.
    pub fn with_frequency(self, hertz: f64) -> Result<Self> {
        let w = self.image_of(Key::Frequency, hertz)?;
        self.with_w(w)
    }

    /// Set the drive angular frequency Ω in rad/s (physical systems).
    ///
    /// # Errors
    /// [`SpecError::NeedsPhysical`] without a physical system; when Ω is not finite and > 0.
    pub fn with_omega(self, omega: f64) -> Result<Self> {
        let w = self.image_of(Key::Omega, omega)?;
        self.with_w(w)
    }

    /// Set the drive amplitude U in volts (circuit) or F in newtons (mechanics).
    ///
    /// # Errors
    /// [`SpecError::NeedsPhysical`] without a physical system; when the amplitude is not
    /// finite and ≥ 0.
    pub fn with_amplitude(self, amplitude: f64) -> Result<Self> {
        let beta = self.image_of(Key::Amplitude, amplitude)?;
        self.with_beta(beta)
    }

    /// Use Shockley diodes in the circuit (U_t kept as the reference voltage, R_D dropped).
    ///
    /// # Errors
    /// [`crate::Error::Unsupported`] without a circuit; when the pair is invalid.
    pub fn with_shockley(mut self, pair: DiodePair) -> Result<Self> {
        let Some(System::Circuit(c)) = self.system else {
            return Err(Error::Unsupported(crate::Unsupported::ShockleyNeedsCircuit));
        };
        let c = c.with_shockley(pair).validate()?;
        self.zeta = spec::image(
            (Key::Resistance, c.resistance, c.scales().zeta()),
            Key::Zeta,
        )?;
        self.system = Some(System::Circuit(c));
        Ok(self)
    }

    /// Set the accuracy of the stiff solver used with Shockley diodes.
    ///
    /// # Errors
    /// When the options are invalid.
    pub fn with_shockley_options(mut self, options: ShockleyOptions) -> Result<Self> {
        self.shockley = options.validate()?;
        Ok(self)
    }

    /// The dimensionless value that `value` of the physical key `key` gives with this
    /// system's scales ([`Key::image`]), checked against the range of the value it gives.
    fn image_of(&self, key: Key, value: f64) -> Result<f64> {
        let value = key.check(value)?;
        let scales = self.physical_scales(key)?;
        let (Some(target), Some(image)) = (key.image_key(), key.image(value, &scales)) else {
            return Ok(value);
        };
        spec::image((key, value, image), target)
    }

    fn physical_scales(&self, key: Key) -> Result<Scales> {
        self.scales()
            .ok_or(Error::Spec(SpecError::NeedsPhysical { key }))
    }

    /// The physical system, if one was described (`None`: dimensionless).
    pub fn system(&self) -> Option<&System> {
        self.system.as_ref()
    }

    /// What the experiment describes: the dimensionless model, a circuit or a mechanical
    /// oscillator (its [`SystemKind::label`] is the name every front end shows).
    pub fn system_kind(&self) -> SystemKind {
        SystemKind::of(self.system.as_ref())
    }

    /// The circuit, if the system is one.
    pub fn circuit_ref(&self) -> Option<&Circuit> {
        match &self.system {
            Some(System::Circuit(c)) => Some(c),
            _ => None,
        }
    }

    /// Where the description came from.
    pub fn origin(&self) -> &Origin {
        &self.origin
    }

    /// The damping ratio ζ of the dimensionless model (ζ_R, the circuit resistance only,
    /// with Shockley diodes).
    pub fn zeta(&self) -> f64 {
        self.zeta
    }

    /// The drive frequency w = Ω/ω0, if given.
    pub fn w(&self) -> Option<f64> {
        self.w
    }

    /// The drive amplitude β, if given.
    pub fn beta(&self) -> Option<f64> {
        self.beta
    }

    /// The drive phase φ (radians).
    pub fn phi(&self) -> f64 {
        self.phi
    }

    /// The static-to-kinetic friction ratio μs.
    pub fn mu_s(&self) -> f64 {
        self.mu_s
    }

    /// The dimensionless initial state at τ = 0.
    pub fn initial(&self) -> State {
        self.initial
    }

    /// The diode law, and so the solver.
    pub fn diode_model(&self) -> DiodeModel {
        match &self.system {
            Some(System::Circuit(Circuit {
                diode: Diode::Shockley(_),
                ..
            })) => DiodeModel::Shockley,
            _ => DiodeModel::Pwl,
        }
    }

    /// The accuracy settings of the stiff solver (used with Shockley diodes).
    pub fn shockley_options(&self) -> &ShockleyOptions {
        &self.shockley
    }

    /// The law of the dissipative element, in dimensionless form ([`Law`]): it decides the
    /// solver ([`Experiment::factory`]) and the stability tools ([`Experiment::dynamics`]).
    ///
    /// # Errors
    /// When a Shockley pair's law cannot be formed (invalid parts; a validated experiment
    /// has none).
    pub fn law(&self) -> Result<Law> {
        law_of(
            self.circuit_ref()
                .filter(|_| self.diode_model() == DiodeModel::Shockley),
        )
    }

    /// The stability tools of this experiment's model ([`Dynamics`]: the exact PWL model's,
    /// the Shockley model's with the experiment's stiff-solver options, or a Stribeck or
    /// cubic friction law's, [`crate::stability::FrictionDynamics`]), checking the
    /// experiment's cancel token.
    ///
    /// # Errors
    /// As [`Experiment::law`].
    pub fn dynamics(&self) -> Result<Box<dyn Dynamics>> {
        let law = self.law()?;
        if matches!(law, Law::Pwl) && !self.friction_law().is_coulomb() {
            return Ok(Box::new(
                crate::stability::FrictionDynamics::new().with_cancel(self.cancel.0.clone()),
            ));
        }
        law.dynamics(self.shockley, self.cancel.0.clone())
    }

    /// `Ok` for a tool that takes Coulomb's friction law alone (`curve`).
    ///
    /// # Errors
    /// [`crate::Unsupported::SmoothFrictionLaw`] for a Stribeck or cubic law.
    pub fn check_coulomb_tool(&self) -> Result<()> {
        if self.friction_law().is_coulomb() {
            Ok(())
        } else {
            Err(Error::Unsupported(crate::Unsupported::SmoothFrictionLaw))
        }
    }

    /// The scales to physical units, for a physical system.
    pub fn scales(&self) -> Option<Scales> {
        self.system.map(|s| s.scales())
    }

    /// Physical units of samples, for a physical system.
    pub fn units(&self) -> Option<PhysicalUnits> {
        self.system.map(|s| PhysicalUnits {
            circuit: matches!(s, System::Circuit(_)),
            scales: s.scales(),
        })
    }

    /// The theory's gain curves over the range of a sweep of `parameter` from this
    /// experiment ([`SweepTheory`]): the paper's eq. (11) and the exact sliding orbit's
    /// peak gain.
    ///
    /// # Errors
    /// [`SpecError::MissingDrive`] when w or β is missing and not swept; a value out of range.
    pub fn sweep_theory(
        &self,
        parameter: Parameter,
        range: &ParameterRange,
    ) -> Result<SweepTheory> {
        let base = self.params_with(&[(parameter, range.from())])?;
        Ok(SweepTheory::new(
            &base,
            parameter,
            (range.from(), range.to(), range.steps()),
            self.diode_model() == DiodeModel::Shockley,
        ))
    }

    /// The exact sliding orbit's A1/β over the range of a sweep of `parameter` from this
    /// experiment ([`SweepTheory::exact_a1`]).
    ///
    /// # Errors
    /// As [`Experiment::sweep_theory`].
    pub fn sweep_theory_a1(
        &self,
        parameter: Parameter,
        range: &ParameterRange,
    ) -> Result<TheoryCurve> {
        let base = self.params_with(&[(parameter, range.from())])?;
        Ok(SweepTheory::exact_a1(
            &base,
            parameter,
            (range.from(), range.to(), range.steps()),
        ))
    }

    /// The dimensionless parameters.
    ///
    /// # Errors
    /// [`SpecError::MissingDrive`] when the drive frequency or amplitude is missing.
    pub fn params(&self) -> Result<Params> {
        self.params_with(&[])
    }

    /// The dimensionless parameters with some of ζ, w, β, μs set to other values (a sweep's
    /// or a grid's); a value set here may be missing from the experiment.
    ///
    /// # Errors
    /// [`SpecError::MissingDrive`] when w or β is missing and not set here; a value out of
    /// range.
    pub fn params_with(&self, values: &[(Parameter, f64)]) -> Result<Params> {
        let given = |p: Parameter| values.iter().rev().find(|(q, _)| *q == p).map(|v| v.1);
        let vb = given(Parameter::Vb).unwrap_or(self.vb);
        // A belt without a drive: β = 0, and w (which then sets no period of the motion, only
        // the unit of time that runs count in) 1.
        let undriven = vb != 0.0 && self.beta.is_none() && given(Parameter::Beta).is_none();
        let beta = given(Parameter::Beta)
            .or(self.beta)
            .or(undriven.then_some(0.0))
            .ok_or(Error::Spec(SpecError::MissingDrive { key: Key::Beta }))?;
        let w = given(Parameter::W)
            .or(self.w)
            .or((vb != 0.0 && beta == 0.0).then_some(1.0))
            .ok_or(Error::Spec(SpecError::MissingDrive { key: Key::W }))?;
        let zeta = given(Parameter::Zeta).unwrap_or(self.zeta);
        let mu_s = given(Parameter::MuS).unwrap_or(self.mu_s);
        let mut params = Params::new(zeta, w, beta)?
            .with_phi(self.phi)?
            .with_mu_s(mu_s)?;
        if vb == 0.0 && self.law.is_coulomb() && values.iter().all(|(p, _)| !p.is_friction()) {
            return Ok(params);
        }
        params = params.with_vb(vb)?;
        params.law = self.law;
        for &(p, value) in values {
            if p.is_friction() && p != Parameter::Vb {
                params = p.set(params, value)?;
            }
        }
        params.validate()
    }

    /// The same experiment with one of its parameters changed (ζ too, even for a physical
    /// system: the parameters are dimensionless).
    ///
    /// # Errors
    /// A value out of range; a parameter of a law the experiment does not follow; a belt or
    /// a law with a circuit.
    pub fn with_parameter(mut self, parameter: Parameter, value: f64) -> Result<Self> {
        let key = parameter.key();
        let value = key.check(value)?;
        match parameter {
            Parameter::Zeta => self.zeta = value,
            Parameter::W => self.w = Some(value),
            Parameter::Beta => self.beta = Some(value),
            Parameter::MuS => self.mu_s = value,
            Parameter::Vb => return self.with_vb(value),
            _ => {
                let base = Params::new(0.0, 1.0, 0.0)?
                    .with_mu_s(self.mu_s)?
                    .with_law(self.law)?;
                let law = parameter.set(base, value)?.law;
                return self.with_law(law);
            }
        }
        Ok(self)
    }

    /// This experiment with `cancel` as the token that every solver it builds checks
    /// ([`crate::cancel`]): every computation on it stops within a solver step once the token
    /// is cancelled, past its deadline or over its budget.
    pub fn with_cancel(mut self, cancel: Cancel) -> Self {
        self.cancel = CancelSlot(cancel);
        self
    }

    /// The token every solver of this experiment checks ([`Cancel::never`] unless given).
    pub fn cancel(&self) -> &Cancel {
        &self.cancel.0
    }

    /// The factory of this experiment's solver (exact, or stiff for Shockley diodes), for
    /// any parameters and initial state.
    pub fn factory(&self) -> ExperimentFactory {
        ExperimentFactory {
            cancel: self.cancel.0.clone(),
            circuit: self
                .circuit_ref()
                .copied()
                .filter(|_| self.diode_model() == DiodeModel::Shockley),
            options: self.shockley,
        }
    }

    /// A solver of this experiment from its initial state at τ = 0.
    ///
    /// # Errors
    /// A missing drive ([`Experiment::params`]).
    pub fn solver(&self) -> Result<Box<dyn Solver + Send>> {
        self.factory().make(self.params()?, self.initial)
    }

    /// The steady-state options that fit this experiment's solver: the defaults of
    /// [`SteadyOptions`], with the repetition tolerance of the stroboscopic map at the stiff
    /// solver's own accuracy (its rtol, 1e-6 by default) with Shockley diodes, since its
    /// strobes repeat only that well.
    pub fn steady_options(&self) -> SteadyOptions {
        match self.diode_model() {
            DiodeModel::Pwl => SteadyOptions::default(),
            DiodeModel::Shockley => SteadyOptions {
                tolerance: self.shockley.rtol,
                ..SteadyOptions::default()
            },
        }
    }

    /// The steady state reached from the initial state, with [`Experiment::steady_options`].
    ///
    /// # Errors
    /// A missing drive; whatever the solver reports.
    pub fn steady(&self) -> Result<SteadyState> {
        self.steady_with(&self.steady_options())
    }

    /// The steady state reached from the initial state, with `options`.
    ///
    /// # Errors
    /// A missing drive; invalid options; whatever the solver reports.
    pub fn steady_with(&self, options: &SteadyOptions) -> Result<SteadyState> {
        steady_state_from(&self.factory(), &self.params()?, self.initial, options)
    }

    /// The conversion of a physical description to the dimensionless model (what
    /// `stickslip convert` prints), or `None` for a dimensionless experiment.
    pub fn conversion(&self) -> Option<Conversion> {
        let s = self.scales()?;
        let drive = self.w.zip(self.beta);
        Some(Conversion {
            omega0: s.omega0,
            f0: s.f0(),
            alpha: s.alpha,
            zeta: s.zeta(),
            q: s.quality_factor(),
            w: drive.map(|d| d.0),
            beta: drive.map(|d| d.1),
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::steady::MotionClass;
    use std::f64::consts::TAU;

    #[test]
    fn paper_shockley_uses_the_stiff_solver_with_its_own_zeta() {
        let e = Experiment::paper()
            .with_shockley(DiodePair::one_n4148())
            .unwrap()
            .with_w(0.95)
            .unwrap()
            .with_beta(2.14)
            .unwrap();
        assert_eq!(e.diode_model(), DiodeModel::Shockley);
        let c = Circuit::paper();
        assert!((2.0 * e.zeta() - c.resistance / c.impedance()).abs() < 1e-15);
        assert_eq!(e.steady_options().tolerance, 1e-6);
        let solver = e.solver().unwrap();
        assert_eq!(solver.params().zeta, e.zeta());
    }

    #[test]
    fn a_missing_drive_is_named() {
        let e = Experiment::paper().with_w(0.9).unwrap();
        assert_eq!(
            e.params(),
            Err(Error::Spec(SpecError::MissingDrive { key: Key::Beta }))
        );
        let p = e.params_with(&[(Parameter::Beta, 1.6)]).unwrap();
        assert_eq!((p.w, p.beta), (0.9, 1.6));
    }

    #[test]
    fn physical_setters_agree_with_the_scales() {
        let e = Experiment::paper()
            .with_frequency(9.97e3)
            .unwrap()
            .with_amplitude(1.498)
            .unwrap();
        let expected = Circuit::paper()
            .scales()
            .params(1.498, 9.97e3 * TAU, 0.0)
            .unwrap();
        assert_eq!(e.params().unwrap(), expected);
        assert!(Experiment::dimensionless(0.1, 1.0, 1.0)
            .unwrap()
            .with_frequency(1.0)
            .is_err());
        assert!(Experiment::paper().with_zeta(0.1).is_err());
    }

    /// The setters and the description convert a physical drive the same way (one
    /// conversion, [`Key::image`]), bit for bit.
    #[test]
    fn setters_and_descriptions_convert_alike() {
        for hertz in [9.97e3, 1.0, 123.456e3, 7.77e2] {
            let set = Experiment::paper().with_frequency(hertz).unwrap().w();
            let mut spec = ExperimentSpec::new();
            spec.set_preset(Preset::Paper);
            spec.set(Key::Frequency, hertz).unwrap();
            let described = spec.build().unwrap().w();
            assert_eq!(
                set.map(f64::to_bits),
                described.map(f64::to_bits),
                "{hertz}"
            );
        }
        let mut spec = ExperimentSpec::new();
        spec.set_preset(Preset::Paper);
        spec.set(Key::Amplitude, 1.498).unwrap();
        spec.set(Key::Omega, 6.0e4).unwrap();
        let described = spec.build().unwrap();
        let set = Experiment::paper()
            .with_omega(6.0e4)
            .unwrap()
            .with_amplitude(1.498)
            .unwrap();
        assert_eq!(set, described.with_origin(Origin::Preset(Preset::Paper)));
    }

    /// The curves drawn over a sweep are the theory's curves over the sweep's range, at the
    /// sweep's first value; with Shockley diodes they are labelled as the PWL theory.
    #[test]
    fn the_sweep_theory_is_the_theory_curves_over_the_range() {
        use crate::theory::curves::{abscissae, theory_curve, Theory, TheoryQuantity};
        let bits = |c: &TheoryCurve| {
            let x: Vec<u64> = c.x.iter().map(|v| v.to_bits()).collect();
            let y: Vec<u64> = c.y.iter().map(|v| v.to_bits()).collect();
            (x, y)
        };
        let e = Experiment::paper().with_beta(2.14).unwrap();
        let range = ParameterRange::new("w", 0.5, 1.5, 11).unwrap();
        let theory = e.sweep_theory(Parameter::W, &range).unwrap();
        let base = e.params_with(&[(Parameter::W, 0.5)]).unwrap();
        let xs = abscissae(0.5, 1.5, 11);
        let curve = |t, q| theory_curve(t, q, &base, Parameter::W, &xs);
        assert_eq!(
            bits(&theory.paper),
            bits(&curve(Theory::Paper, TheoryQuantity::Gain1))
        );
        assert_eq!(
            bits(&theory.exact),
            bits(&curve(Theory::Exact, TheoryQuantity::PeakGain))
        );
        assert_eq!(
            bits(&e.sweep_theory_a1(Parameter::W, &range).unwrap()),
            bits(&curve(Theory::Exact, TheoryQuantity::Gain1))
        );
        assert!(theory.exact.present() > 0 && theory.paper.present() > 0);
        assert_eq!(theory.prefix, "");
        let shockley = e.with_shockley(DiodePair::one_n4148()).unwrap();
        let theory = shockley.sweep_theory(Parameter::W, &range).unwrap();
        assert_eq!(theory.prefix, "PWL theory: ");
    }

    #[test]
    fn steady_state_of_a_mechanical_oscillator() {
        let m = Mechanics::new(2.0, 8.0, 0.4, 0.5).unwrap();
        let e = Experiment::mechanics(m)
            .unwrap()
            .with_omega(1.8)
            .unwrap()
            .with_amplitude(1.0)
            .unwrap();
        let s = e.steady().unwrap();
        assert_eq!(s.class, MotionClass::Sliding);
        let units = e.units().unwrap();
        assert_eq!(units.columns()[1], "r_m");
        assert_eq!(units.convert(2.0, 1.0, 0.0, 0.0)[0], 1.0);
    }

    #[test]
    fn experiments_round_trip_through_serde() {
        let e = Experiment::paper().with_w(0.7).unwrap();
        let json = serde_json::to_string(&e).unwrap();
        let back: Experiment = serde_json::from_str(&json).unwrap();
        assert_eq!(back, e);
    }
}
