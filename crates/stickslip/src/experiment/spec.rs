//! An experiment as described: every value optional, in layers (a preset, a file, flags or
//! keyword arguments), turned into an [`Experiment`] by [`ExperimentSpec::build`].

use super::errors::SpecError;
use super::key::{Key, KeyGroup};
use super::{DiodeModel, Experiment, Origin, Preset};
use crate::error::{Error, Result, Unsupported};
use crate::friction::{FrictionLaw, FrictionLawKind};
use crate::physical::{Circuit, Diode, Mechanics, PwlDiode, ShockleyDiode, System};
use crate::shockley::{DiodePair, ShockleyOptions};
use serde::{Deserialize, Serialize};
use std::collections::BTreeMap;

impl SpecError {
    /// The key the error is about (for a value given twice, the second), for a front end to
    /// point at.
    pub fn key(&self) -> Option<Key> {
        match *self {
            SpecError::Missing { key, .. }
            | SpecError::MissingDrive { key }
            | SpecError::NeedsPhysical { key }
            | SpecError::NoBelt { key }
            | SpecError::OtherLaw { key, .. }
            | SpecError::MissingLawParameter { key, .. } => Some(key),
            SpecError::Twice { second, .. } => Some(second),
            SpecError::ZetaWithPhysical => Some(Key::Zeta),
            SpecError::CircuitAndMechanics { mechanical } => Some(mechanical),
        }
    }

    /// The message, one line, with each key named by `name` (e.g. a command-line flag).
    pub fn render(&self, name: &dyn Fn(Key) -> String) -> String {
        match *self {
            SpecError::Missing { key, circuit: true } => format!(
                "a circuit description needs {} (or use the {} paper)",
                name(key),
                name(Key::Preset)
            ),
            SpecError::Missing {
                key,
                circuit: false,
            } => format!("a mechanical description needs {}", name(key)),
            SpecError::MissingDrive { key: Key::Beta } => format!(
                "missing drive amplitude: give {} (U/U_t), or {} with a physical description",
                name(Key::Beta),
                name(Key::Amplitude)
            ),
            SpecError::MissingDrive { .. } => format!(
                "missing drive frequency: give {} (Ω/ω0), or {}/{} with a physical description",
                name(Key::W),
                name(Key::Frequency),
                name(Key::Omega),
            ),
            SpecError::Twice {
                first,
                second,
                what,
            } => format!("give the {what} once: {} or {}", name(first), name(second)),
            SpecError::ZetaWithPhysical => format!(
                "{} conflicts with a physical description (ζ follows from its parts); change {} \
                 instead",
                name(Key::Zeta),
                name(Key::Resistance)
            ),
            SpecError::CircuitAndMechanics { mechanical } => format!(
                "the mechanical values ({}, {}, {}, {}) cannot be combined with a circuit \
                 description (got {})",
                name(Key::Mass),
                name(Key::Stiffness),
                name(Key::Damping),
                name(Key::Friction),
                name(mechanical)
            ),
            SpecError::NeedsPhysical { key } => format!(
                "{} is a physical value: also describe the system (the {} paper, a circuit or \
                 a mechanical oscillator)",
                name(key),
                name(Key::Preset)
            ),
            SpecError::NoBelt { key } => format!(
                "{} belongs to a block on a moving belt: a circuit has no belt and no friction \
                 law (use the mechanical twin or the dimensionless model)",
                name(key)
            ),
            SpecError::OtherLaw { key, law } => format!(
                "{} is a parameter of the {law} friction law: also give {} {law}",
                name(key),
                name(Key::FrictionLaw)
            ),
            SpecError::MissingLawParameter { key, law } => {
                format!("the {law} friction law needs {}", name(key))
            }
        }
    }
}

/// The quantities that several keys give (the drive frequency as w, f or Ω, ...): a layer
/// that sets one of them replaces the whole group of the layers below, and one layer may set
/// only one of each.
fn quantities() -> Vec<(&'static str, Vec<Key>)> {
    Key::ALL
        .into_iter()
        .filter(|k| k.image_key().is_none())
        .filter_map(Key::quantity)
        .collect()
}

/// Check the dimensionless value `image` that the value `value` of `key` gives against the
/// range of `target` ([`Key::check`]); out of range, the error names the key the user gave
/// ([`Error::ImageOutOfRange`] when that is a physical value).
pub(super) fn image((key, value, image): (Key, f64, f64), target: Key) -> Result<f64> {
    match target.check(image) {
        Err(Error::InvalidParameter { allowed, .. }) if key != target => {
            Err(Error::ImageOutOfRange {
                key,
                value,
                image: target.name(),
                image_value: image,
                allowed,
            })
        }
        other => other,
    }
}

/// The values that give the dimensionless `target` in `system`, each with the power it
/// enters with: ζ = (R + R_D)/2·√(C/L) or γ/(2√(km)); w = 2πf·√(LC) or Ω·√(m/k);
/// β = U/U_t or F/F0; y0 = u_C(0)/U_t or r(0)·k/F0; v0 = i(0)·√(L/C)/U_t or
/// ṙ(0)·√(km)/F0. The drive and initial values themselves enter with power 1.
fn factors(target: Key, system: &System) -> &'static [(Key, f64)] {
    use Key::*;
    match (target, system) {
        (Zeta, System::Circuit(_)) => &[
            (Resistance, 1.0),
            (DiodeResistance, 1.0),
            (Capacitance, 0.5),
            (Inductance, -0.5),
        ],
        (Zeta, System::Mechanics(_)) => &[(Damping, 1.0), (Stiffness, -0.5), (Mass, -0.5)],
        (W, System::Circuit(_)) => &[
            (Frequency, 1.0),
            (Omega, 1.0),
            (Inductance, 0.5),
            (Capacitance, 0.5),
        ],
        (W, System::Mechanics(_)) => &[
            (Frequency, 1.0),
            (Omega, 1.0),
            (Mass, 0.5),
            (Stiffness, -0.5),
        ],
        (Beta, System::Circuit(_)) => &[(Amplitude, 1.0), (TurnOn, -1.0)],
        (Beta, System::Mechanics(_)) => &[(Amplitude, 1.0), (Friction, -1.0)],
        (Y0, System::Circuit(_)) => &[(Uc0, 1.0), (TurnOn, -1.0)],
        (Y0, System::Mechanics(_)) => &[(Uc0, 1.0), (Stiffness, 1.0), (Friction, -1.0)],
        (V0, System::Circuit(_)) => &[
            (I0, 1.0),
            (TurnOn, -1.0),
            (Inductance, 0.5),
            (Capacitance, -0.5),
        ],
        (V0, System::Mechanics(_)) => &[(I0, 1.0), (Friction, -1.0), (Stiffness, 0.5), (Mass, 0.5)],
        _ => &[],
    }
}

/// The value of `key` in the reference description of a system of `system`'s kind (the
/// paper's circuit, or the example mechanical oscillator, [`Mechanics::example`]): its part,
/// or for a drive or initial value the one whose dimensionless image is 1.
fn reference(key: Key, system: &System) -> Option<f64> {
    let reference = match system {
        System::Circuit(_) => System::Circuit(Circuit::paper()),
        System::Mechanics(_) => System::Mechanics(Mechanics::example()),
    };
    if let Some(unit) = key.image(1.0, &reference.scales()) {
        return Some(1.0 / unit);
    }
    match (key, reference) {
        (Key::Inductance, System::Circuit(c)) => Some(c.inductance),
        (Key::Capacitance, System::Circuit(c)) => Some(c.capacitance),
        (Key::Resistance, System::Circuit(c)) => Some(c.resistance),
        (Key::TurnOn, System::Circuit(c)) => Some(c.diode.reference_voltage()),
        (Key::DiodeResistance, System::Circuit(c)) => Some(c.diode.linear_resistance()),
        (Key::Mass, System::Mechanics(m)) => Some(m.mass),
        (Key::Stiffness, System::Mechanics(m)) => Some(m.stiffness),
        (Key::Damping, System::Mechanics(m)) => Some(m.damping),
        (Key::Friction, System::Mechanics(m)) => Some(m.friction),
        _ => None,
    }
}

/// The value to blame for the dimensionless `target`, whose value `image` is out of its
/// range: of the values the user gave (`given`) that enter it ([`factors`]), the one that
/// moves it furthest the wrong way (too large or too small) from the reference description
/// ([`reference()`]), measured as |power·ln(value/reference)|; `fallback` (the key the image
/// was computed from) when none moves it that way. So C = 1e308 is blamed for ζ, not R,
/// and C = 1e-308 for w, not the drive frequency; a drive frequency far from f0 is blamed
/// for w.
fn culprit(
    target: Key,
    image: f64,
    system: &System,
    fallback: (Key, f64),
    given: &dyn Fn(Key) -> Option<(Key, f64)>,
) -> (Key, f64) {
    let too_large = image.is_nan() || image.abs() > target.range().max.abs().min(f64::MAX);
    let mut best: Option<(f64, (Key, f64))> = None;
    for &(key, power) in factors(target, system) {
        let (Some((key, value)), Some(reference)) = (given(key), reference(key, system)) else {
            continue;
        };
        if value == 0.0 || reference == 0.0 {
            continue;
        }
        let pull = power * (value.abs() / reference.abs()).ln();
        let pull = if too_large { pull } else { -pull };
        if pull > 0.0 && best.is_none_or(|(b, _)| pull > b) {
            best = Some((pull, (key, value)));
        }
    }
    best.map_or(fallback, |(_, blamed)| blamed)
}

/// An experiment description in which every value is optional.
///
/// Values are checked one by one as they are set ([`Key::check`]); the description as a
/// whole is checked by [`ExperimentSpec::build`]. Descriptions stack: [`ExperimentSpec::overlay`]
/// puts one over another (a file over a preset, flags over a file), where the upper layer
/// wins value by value, and a layer that gives a quantity in any form (the drive frequency as
/// w, f or Ω, say) replaces that quantity of the layers below.
///
/// ```
/// use stickslip::experiment::{ExperimentSpec, Key, Preset};
/// let mut spec = ExperimentSpec::new();
/// spec.set_preset(Preset::Paper);
/// spec.set(Key::Frequency, 9.97e3).unwrap();
/// spec.set(Key::Amplitude, 1.498).unwrap();
/// let experiment = spec.build().unwrap();
/// let p = experiment.params().unwrap();
/// assert!((p.beta - 2.14).abs() < 1e-12);
/// ```
#[derive(Debug, Clone, Default, PartialEq, Serialize, Deserialize)]
pub struct ExperimentSpec {
    values: BTreeMap<Key, f64>,
    preset: Option<Preset>,
    diode: Option<DiodeModel>,
    /// The friction law (of a block on a belt).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    law: Option<FrictionLawKind>,
    /// Where the values came from (a file name), for descriptions and messages.
    source: Option<String>,
}

impl ExperimentSpec {
    /// An empty description.
    pub fn new() -> Self {
        Self::default()
    }

    /// Set `key` to `value` (in the key's unit, [`Key::description`]).
    ///
    /// # Errors
    /// [`Error::InvalidParameter`] when the value is outside the key's range ([`Key::check`]);
    /// for [`Key::Diode`] and [`Key::Preset`], which are not numbers (use
    /// [`ExperimentSpec::set_diode`] and [`ExperimentSpec::set_preset`]).
    pub fn set(&mut self, key: Key, value: f64) -> Result<&mut Self> {
        self.values.insert(key, key.check(value)?);
        Ok(self)
    }

    /// This description with `key` set to `value` ([`ExperimentSpec::set`]).
    ///
    /// # Errors
    /// As [`ExperimentSpec::set`].
    pub fn with(mut self, key: Key, value: f64) -> Result<Self> {
        self.set(key, value)?;
        Ok(self)
    }

    /// Remove `key`.
    pub fn unset(&mut self, key: Key) -> &mut Self {
        self.values.remove(&key);
        match key {
            Key::Preset => self.preset = None,
            Key::Diode => self.diode = None,
            Key::FrictionLaw => self.law = None,
            _ => {}
        }
        self
    }

    /// Remove the quantity that `key` gives, in every form: [`Key::W`] removes the drive
    /// frequency given as w, f or Ω, say (see the type's documentation).
    pub fn unset_quantity(&mut self, key: Key) -> &mut Self {
        match key.quantity() {
            Some((_, keys)) => {
                for k in keys {
                    self.unset(k);
                }
            }
            None => {
                self.unset(key);
            }
        }
        self
    }

    /// The value of `key`, if set.
    pub fn get(&self, key: Key) -> Option<f64> {
        self.values.get(&key).copied()
    }

    /// Whether `key` is set.
    pub fn has(&self, key: Key) -> bool {
        match key {
            Key::Preset => self.preset.is_some(),
            Key::Diode => self.diode.is_some(),
            Key::FrictionLaw => self.law.is_some(),
            _ => self.values.contains_key(&key),
        }
    }

    /// Start from a built-in physical description.
    pub fn set_preset(&mut self, preset: Preset) -> &mut Self {
        self.preset = Some(preset);
        self
    }

    /// Choose the diode law (a circuit is needed for [`DiodeModel::Shockley`]).
    pub fn set_diode(&mut self, diode: DiodeModel) -> &mut Self {
        self.diode = Some(diode);
        self
    }

    /// Choose the friction law (of a block on a belt: not with a circuit).
    pub fn set_law(&mut self, law: FrictionLawKind) -> &mut Self {
        self.law = Some(law);
        self
    }

    /// The friction law, if chosen.
    pub fn law(&self) -> Option<FrictionLawKind> {
        self.law
    }

    /// Name where the values came from (a file name), for descriptions.
    pub fn set_source(&mut self, source: impl Into<String>) -> &mut Self {
        self.source = Some(source.into());
        self
    }

    /// The preset, if any.
    pub fn preset(&self) -> Option<Preset> {
        self.preset
    }

    /// The diode law, if chosen.
    pub fn diode(&self) -> Option<DiodeModel> {
        self.diode
    }

    /// This description with `top` over it: each value of `top` wins, and a quantity that
    /// `top` gives in any form (see the type's documentation) replaces the same quantity
    /// below.
    pub fn overlay(&self, top: &ExperimentSpec) -> ExperimentSpec {
        let mut out = self.clone();
        for (_, keys) in quantities() {
            if keys.iter().any(|k| top.values.contains_key(k)) {
                for k in &keys {
                    out.values.remove(k);
                }
            }
        }
        for (&k, &v) in &top.values {
            out.values.insert(k, v);
        }
        out.preset = top.preset.or(self.preset);
        out.diode = top.diode.or(self.diode);
        out.law = top.law.or(self.law);
        out.source = top.source.clone().or_else(|| self.source.clone());
        out
    }

    /// Check the description as a whole and build the experiment. The drive frequency and
    /// amplitude may be missing (a sweep or a grid sets them); [`Experiment::params`] asks
    /// for them.
    ///
    /// # Errors
    /// - [`Error::Spec`]: a missing part of a physical description, a quantity given twice,
    ///   ζ with a physical description, a circuit with mechanical values, a physical value
    ///   (U, f, Ω, u_C(0), i(0)) without a physical description;
    /// - [`Error::Unsupported`]: Shockley diodes without a circuit;
    /// - [`Error::InvalidParameter`]: a value out of range after conversion (w from f, say).
    pub fn build(&self) -> Result<Experiment> {
        let has = |k: Key| self.values.contains_key(&k);
        let circuit =
            self.preset.is_some() || Key::ALL.into_iter().any(|k| k.is_circuit_part() && has(k));
        let mechanical = Key::ALL
            .into_iter()
            .find(|&k| k.is_mechanics_part() && has(k));
        if let (true, Some(key)) = (circuit, mechanical) {
            return Err(SpecError::CircuitAndMechanics { mechanical: key }.into());
        }
        let model = self.diode.unwrap_or_default();
        let system = if mechanical.is_some() {
            let need = |key: Key| {
                self.get(key).ok_or(Error::Spec(SpecError::Missing {
                    key,
                    circuit: false,
                }))
            };
            Some(System::Mechanics(Mechanics::new(
                need(Key::Mass)?,
                need(Key::Stiffness)?,
                need(Key::Damping)?,
                need(Key::Friction)?,
            )?))
        } else if circuit {
            Some(System::Circuit(self.circuit(model)?))
        } else {
            None
        };
        if model == DiodeModel::Shockley && !matches!(system, Some(System::Circuit(_))) {
            return Err(Error::Unsupported(Unsupported::ShockleyNeedsCircuit));
        }
        if matches!(system, Some(System::Circuit(_))) {
            let law = self.law.filter(|l| *l != FrictionLawKind::Coulomb);
            let given = Key::ALL
                .into_iter()
                .find(|&k| k.group() == KeyGroup::Friction && has(k))
                .or(law.map(|_| Key::FrictionLaw));
            if let Some(key) = given {
                return Err(SpecError::NoBelt { key }.into());
            }
        }
        if system.is_none() {
            if let Some(key) = Key::ALL
                .into_iter()
                .find(|&k| k.image_key().is_some() && has(k))
            {
                return Err(SpecError::NeedsPhysical { key }.into());
            }
        }
        for (what, keys) in quantities() {
            let given: Vec<Key> = keys.iter().copied().filter(|&k| has(k)).collect();
            if given.len() > 1 {
                return Err(SpecError::Twice {
                    first: given[0],
                    second: given[1],
                    what,
                }
                .into());
            }
        }
        let scales = system.map(|s| s.scales());
        let zeta = match (scales, self.get(Key::Zeta)) {
            (Some(_), Some(_)) => return Err(SpecError::ZetaWithPhysical.into()),
            (Some(s), None) => s.zeta(),
            (None, Some(z)) => z,
            (None, None) => Circuit::paper().scales().zeta(),
        };
        // Each dimensionless value as given, or from the first physical value that gives it
        // (converted with the scales; without scales they were rejected above).
        let value = |target: Key| {
            Key::ALL
                .into_iter()
                .filter(|&k| k == target || k.image_key() == Some(target))
                .find_map(|key| {
                    let x = self.get(key)?;
                    let image = scales.and_then(|s| key.image(x, &s)).unwrap_or(x);
                    Some((key, x, image))
                })
        };
        let w = value(Key::W);
        let beta = value(Key::Beta);
        let y0 = value(Key::Y0);
        let v0 = value(Key::V0);
        let origin = match (system, self.preset, &self.source) {
            (None, _, _) => Origin::Parameters,
            (Some(_), Some(p), _) => Origin::Preset(p),
            (Some(_), None, Some(file)) => Origin::File(file.clone()),
            (Some(_), None, None) => Origin::Parts,
        };
        // A dimensionless value out of range is blamed on the value the user gave that
        // put it there ([`culprit`]).
        let checked = |(key, value, image_value): (Key, f64, f64), target: Key| {
            image((key, value, image_value), target).map_err(|err| match (err, system) {
                (Error::ImageOutOfRange { allowed, .. }, Some(system)) => {
                    let given = |k: Key| self.get(k).map(|v| (k, v));
                    let (key, value) = culprit(target, image_value, &system, (key, value), &given);
                    Error::ImageOutOfRange {
                        key,
                        value,
                        image: target.name(),
                        image_value,
                        allowed,
                    }
                }
                (err, _) => err,
            })
        };
        let y0 = y0.map_or(Ok(0.0), |v| checked(v, Key::Y0))?;
        let v0 = v0.map_or(Ok(0.0), |v| checked(v, Key::V0))?;
        let zeta_from = match system {
            Some(System::Circuit(c)) => (Key::Resistance, c.resistance),
            Some(System::Mechanics(m)) => (Key::Damping, m.damping),
            None => (Key::Zeta, zeta),
        };
        let mut experiment = Experiment {
            system,
            zeta: checked((zeta_from.0, zeta_from.1, zeta), Key::Zeta)?,
            w: None,
            beta: None,
            phi: self.get(Key::Phi).unwrap_or(0.0),
            mu_s: self.get(Key::MuS).unwrap_or(1.0),
            initial: crate::limits::check_state(y0, v0)?,
            origin,
            shockley: ShockleyOptions::default(),
            vb: 0.0,
            law: FrictionLaw::Coulomb,
            cancel: Default::default(),
        };
        if let Some(w) = w {
            experiment.w = Some(checked(w, Key::W)?);
        }
        if let Some(beta) = beta {
            experiment.beta = Some(checked(beta, Key::Beta)?);
        }
        if let Some(vb) = value(Key::Vb) {
            experiment.vb = crate::friction::check_vb(image(vb, Key::Vb)?)?;
        }
        experiment.law = self.friction_law(&value, experiment.mu_s)?;
        Ok(experiment)
    }

    /// The friction law chosen, with its parameters (each as given, or from the physical
    /// value that gives it, `value`), checked with the static level `mu_s`.
    fn friction_law(
        &self,
        value: &dyn Fn(Key) -> Option<(Key, f64, f64)>,
        mu_s: f64,
    ) -> Result<FrictionLaw> {
        let kind = self.law.unwrap_or_default();
        // Each law's dimensionless parameters, in the table's order ([`Key::law`]).
        let of = |law: FrictionLawKind| -> Vec<Key> {
            Key::ALL
                .into_iter()
                .filter(|k| k.law() == Some(law) && k.image_key().is_none())
                .collect()
        };
        let (stribeck, cubic) = (of(FrictionLawKind::Stribeck), of(FrictionLawKind::Cubic));
        // A parameter of a law that is not the one chosen.
        for (keys, law) in [
            (&stribeck[..], FrictionLawKind::Stribeck),
            (&cubic[..], FrictionLawKind::Cubic),
        ] {
            if law == kind {
                continue;
            }
            if let Some(key) = keys.iter().find_map(|&k| value(k).map(|v| v.0)) {
                return Err(SpecError::OtherLaw {
                    key,
                    law: law.label(),
                }
                .into());
            }
        }
        let parameter = |key: Key| -> Result<(Key, f64)> {
            match value(key) {
                Some(v) => Ok((v.0, image(v, key)?)),
                None => match key.default_value() {
                    Some(crate::experiment::KeyDefault::Number(x)) => Ok((key, x)),
                    _ => Err(SpecError::MissingLawParameter {
                        key,
                        law: kind.label(),
                    }
                    .into()),
                },
            }
        };
        let (law, blamed) = match kind {
            FrictionLawKind::Coulomb => return Ok(FrictionLaw::Coulomb),
            FrictionLawKind::Stribeck => {
                let (vs, delta, eta) = (
                    parameter(Key::Vs)?,
                    parameter(Key::Delta)?,
                    parameter(Key::Eta)?,
                );
                let law = FrictionLaw::Stribeck {
                    vs: vs.1,
                    delta: delta.1,
                    eta: eta.1,
                };
                (law, [vs, delta, eta].to_vec())
            }
            FrictionLawKind::Cubic => {
                let (k1, k3) = (parameter(Key::K1)?, parameter(Key::K3)?);
                (FrictionLaw::Cubic { k1: k1.1, k3: k3.1 }, [k1, k3].to_vec())
            }
        };
        law.validate(mu_s).map_err(|error| match error {
            // The law as a whole (a cubic that goes negative): blame the key the user gave
            // for the parameter named.
            Error::InvalidParameter {
                name,
                value: image_value,
                allowed,
            } => match blamed.iter().find(|(k, _)| {
                k.image_key().unwrap_or(*k).name() == name && k.image_key().is_some()
            }) {
                Some(&(key, _)) => Error::ImageOutOfRange {
                    key,
                    value: self.get(key).unwrap_or(f64::NAN),
                    image: name,
                    image_value,
                    allowed,
                },
                None => Error::InvalidParameter {
                    name,
                    value: image_value,
                    allowed,
                },
            },
            other => other,
        })?;
        Ok(law)
    }

    /// The circuit: its parts from the values, else from the preset.
    fn circuit(&self, model: DiodeModel) -> Result<Circuit> {
        let base = self.preset.map(Preset::circuit);
        let part = |key: Key, from_base: Option<f64>| {
            self.get(key)
                .or(from_base)
                .ok_or(Error::Spec(SpecError::Missing { key, circuit: true }))
        };
        let inductance = part(Key::Inductance, base.map(|b| b.inductance))?;
        let capacitance = part(Key::Capacitance, base.map(|b| b.capacitance))?;
        let resistance = part(Key::Resistance, base.map(|b| b.resistance))?;
        let base_diode = base.map(|b| b.diode);
        let turn_on = part(Key::TurnOn, base_diode.map(|d| d.reference_voltage()))?;
        let diode = match model {
            DiodeModel::Pwl => {
                let base_rd = match base_diode {
                    Some(Diode::Pwl(d)) => Some(d.resistance),
                    _ => None,
                };
                Diode::Pwl(PwlDiode::new(
                    turn_on,
                    part(Key::DiodeResistance, base_rd)?,
                )?)
            }
            DiodeModel::Shockley => {
                let d = DiodePair::one_n4148();
                let pair = DiodePair::new(
                    self.get(Key::SaturationCurrent)
                        .unwrap_or(d.saturation_current),
                    self.get(Key::Emission).unwrap_or(d.emission),
                    self.get(Key::SeriesResistance)
                        .unwrap_or(d.series_resistance),
                    self.get(Key::Temperature).unwrap_or(d.temperature),
                )?;
                Diode::Shockley(ShockleyDiode::new(pair, turn_on)?)
            }
        };
        Circuit::new(inductance, capacitance, resistance, diode)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::f64::consts::TAU;

    fn spec(pairs: &[(Key, f64)]) -> ExperimentSpec {
        let mut s = ExperimentSpec::new();
        for &(k, v) in pairs {
            s.set(k, v).unwrap();
        }
        s
    }

    #[test]
    fn dimensionless_defaults_to_the_papers_damping() {
        let e = spec(&[(Key::W, 0.9), (Key::Beta, 1.6)]).build().unwrap();
        let p = e.params().unwrap();
        assert_eq!(p.zeta, Circuit::paper().scales().zeta());
        assert_eq!((p.w, p.beta, p.phi, p.mu_s), (0.9, 1.6, 0.0, 1.0));
        assert!(e.system().is_none());
    }

    #[test]
    fn the_preset_converts_a_physical_drive_exactly_as_the_scales_do() {
        let mut s = spec(&[(Key::Frequency, 9.97e3), (Key::Amplitude, 1.498)]);
        s.set_preset(Preset::Paper);
        let p = s.build().unwrap().params().unwrap();
        let scales = Circuit::paper().scales();
        let expected = scales.params(1.498, 9.97e3 * TAU, 0.0).unwrap();
        assert_eq!(p, expected);
    }

    #[test]
    fn layers_replace_a_quantity_whatever_its_form() {
        let mut file = spec(&[(Key::W, 0.5), (Key::Beta, 2.0)]);
        file.set_preset(Preset::Paper);
        let flags = spec(&[(Key::Frequency, 1e4)]);
        let e = file.overlay(&flags).build().unwrap();
        let p = e.params().unwrap();
        assert!((p.w - 1e4 * TAU / Circuit::paper().scales().omega0).abs() < 1e-15);
        assert_eq!(p.beta, 2.0);
    }

    #[test]
    fn contradictions_and_gaps_are_typed() {
        let err = |s: ExperimentSpec| s.build().unwrap_err();
        assert_eq!(
            err(spec(&[(Key::Inductance, 1e-3)])),
            Error::Spec(SpecError::Missing {
                key: Key::Capacitance,
                circuit: true
            })
        );
        assert_eq!(
            err(spec(&[
                (Key::Mass, 1.0),
                (Key::Stiffness, 1.0),
                (Key::Damping, 0.0)
            ])),
            Error::Spec(SpecError::Missing {
                key: Key::Friction,
                circuit: false
            })
        );
        let mut both = spec(&[(Key::Mass, 1.0)]);
        both.set_preset(Preset::Paper);
        assert!(matches!(
            err(both),
            Error::Spec(SpecError::CircuitAndMechanics { .. })
        ));
        assert_eq!(
            err(spec(&[(Key::Amplitude, 1.0), (Key::W, 1.0)])),
            Error::Spec(SpecError::NeedsPhysical {
                key: Key::Amplitude
            })
        );
        let mut twice = spec(&[(Key::Frequency, 1e3), (Key::Omega, 5.0)]);
        twice.set_preset(Preset::Paper);
        assert!(matches!(err(twice), Error::Spec(SpecError::Twice { .. })));
        let mut zeta = spec(&[(Key::Zeta, 0.1)]);
        zeta.set_preset(Preset::Paper);
        assert_eq!(err(zeta), Error::Spec(SpecError::ZetaWithPhysical));
        let mut shockley = spec(&[(Key::W, 1.0)]);
        shockley.set_diode(DiodeModel::Shockley);
        assert_eq!(
            err(shockley),
            Error::Unsupported(Unsupported::ShockleyNeedsCircuit)
        );
    }

    /// Absurd values are blamed on themselves, not on another value of the description
    /// (issue 38: C = 1e308 was blamed on R, C = 1e-308 on the drive frequency; L, k or
    /// γ = 1e308 named no key the lab could mark).
    #[test]
    fn absurd_values_are_blamed_on_themselves() {
        let paper = |pairs: &[(Key, f64)]| {
            let mut s = spec(&[(Key::Frequency, 9.97e3), (Key::Amplitude, 1.498)]);
            s.set_preset(Preset::Paper);
            s.overlay(&spec(pairs)).build().unwrap_err()
        };
        let parts = |pairs: &[(Key, f64)]| {
            let mut all = vec![
                (Key::Inductance, 11.5e-3),
                (Key::Capacitance, 20e-9),
                (Key::Resistance, 68.0),
                (Key::TurnOn, 0.7),
                (Key::DiodeResistance, 3.0),
                (Key::Frequency, 9.97e3),
                (Key::Amplitude, 1.498),
            ];
            all.retain(|(k, _)| !pairs.iter().any(|(p, _)| p == k));
            all.extend_from_slice(pairs);
            spec(&all).build().unwrap_err()
        };
        let mechanics = |pairs: &[(Key, f64)]| {
            let mut all = vec![
                (Key::Mass, 0.5),
                (Key::Stiffness, 200.0),
                (Key::Damping, 0.94),
                (Key::Friction, 1.0),
                (Key::Omega, 19.0),
                (Key::Amplitude, 2.14),
            ];
            all.retain(|(k, _)| !pairs.iter().any(|(p, _)| p == k));
            all.extend_from_slice(pairs);
            spec(&all).build().unwrap_err()
        };
        for (key, value) in [
            (Key::Capacitance, 1e308),
            (Key::Capacitance, 1e-308),
            (Key::Inductance, 1e308),
            (Key::Inductance, 1e-308),
            (Key::TurnOn, 1e-300),
            (Key::Frequency, 1e-3),
            (Key::Frequency, 1e300),
            (Key::Resistance, 1e9),
            (Key::Amplitude, 1e300),
        ] {
            assert_eq!(paper(&[(key, value)]).key(), Some(key), "{key} = {value}");
            assert_eq!(parts(&[(key, value)]).key(), Some(key), "{key} = {value}");
        }
        for (key, value) in [
            (Key::Stiffness, 1e308),
            (Key::Stiffness, 1e-308),
            (Key::Damping, 1e308),
            (Key::Mass, 1e308),
            (Key::Mass, 1e-308),
            (Key::Friction, 1e-308),
            (Key::Omega, 1e-6),
        ] {
            assert_eq!(
                mechanics(&[(key, value)]).key(),
                Some(key),
                "{key} = {value}"
            );
        }
        // The message names the value and what it gives.
        let err = paper(&[(Key::Capacitance, 1e308)]).to_string();
        assert!(
            err.starts_with("invalid C = 1e308: it gives zeta = "),
            "{err}"
        );
        let err = paper(&[(Key::Capacitance, 1e-308)]).to_string();
        assert!(
            err.starts_with("invalid C = 1e-308: it gives w = "),
            "{err}"
        );
    }

    #[test]
    fn a_quantity_is_unset_in_every_form() {
        let mut s = spec(&[(Key::Frequency, 1e4), (Key::Beta, 2.0), (Key::Phi, 0.5)]);
        s.set_preset(Preset::Paper);
        s.unset_quantity(Key::W).unset_quantity(Key::Phi);
        assert!(!s.has(Key::Frequency) && !s.has(Key::Phi));
        assert_eq!(s.get(Key::Beta), Some(2.0));
        s.unset_quantity(Key::Preset);
        assert_eq!(s.preset(), None);
    }

    #[test]
    fn messages_name_keys_as_the_caller_does() {
        let e = SpecError::MissingDrive { key: Key::W };
        assert_eq!(
            e.to_string(),
            "missing drive frequency: give w (Ω/ω0), or f/omega with a physical description"
        );
        let flags = e.render(&|k| format!("--{}", k.name()));
        assert!(flags.starts_with("missing drive frequency: give --w"));
    }

    #[test]
    fn shockley_needs_no_r_d_and_keeps_u_t() {
        let mut s = spec(&[
            (Key::Inductance, 11.5e-3),
            (Key::Capacitance, 20e-9),
            (Key::Resistance, 68.0),
            (Key::TurnOn, 0.7),
            (Key::Emission, 1.5),
        ]);
        s.set_diode(DiodeModel::Shockley);
        let e = s.build().unwrap();
        let Some(System::Circuit(c)) = e.system() else {
            panic!("a circuit")
        };
        let Diode::Shockley(d) = c.diode else {
            panic!("Shockley diodes")
        };
        assert_eq!((d.pair.emission, d.reference_voltage), (1.5, 0.7));
        assert_eq!(
            d.pair.saturation_current,
            DiodePair::one_n4148().saturation_current
        );
    }
}
