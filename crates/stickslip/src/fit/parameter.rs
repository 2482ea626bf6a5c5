//! The parameters a fit may free: keys of the experiment's table whose row says so
//! ([`crate::experiment::FitRole`]). Their names, symbols and units, the systems and diode
//! laws they belong to, the default free set and the order of the fit's lists all come from
//! the key table; what is written here is their physics: how a fit reads and sets each.

use super::FitError;
use crate::experiment::{DiodeModel, Experiment, FitRole, Key};
use crate::friction::FrictionLaw;
use crate::physical::{Circuit, Diode, Mechanics, Scales, System, SystemKind};
use serde::{Deserialize, Deserializer, Serialize, Serializer};

/// A value of the circuit or of the mechanical oscillator that a fit may free: a key of the
/// experiment's table with a [`FitRole`] ([`Key::fit_role`]), named as its command-line flag
/// (a circuit's `resistance`, `ut`, `rd`, `diode-is`, `diode-n`, `diode-rs`, `inductance`,
/// `capacitance`; a mechanical oscillator's `damping` (γ), `friction` (F0), `mass` (m),
/// `stiffness` (k) and, with the Stribeck friction law, `stribeck-speed` and
/// `viscous-friction`; either's `mu-s`). Its unit and symbol are its key's.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub struct FitParameter(Key);

/// `N` fit parameters of `keys` (those of the key table a fit may free, in the fit's order)
/// that belong to `system` (all with `None`).
const fn select<const N: usize>(system: Option<SystemKind>) -> [FitParameter; N] {
    let mut out = [FitParameter(Key::Zeta); N];
    let mut n = 0;
    let mut i = 0;
    while i < Key::FIT.len() {
        if belongs(Key::FIT[i], system) {
            out[n] = FitParameter(Key::FIT[i]);
            n += 1;
        }
        i += 1;
    }
    out
}

/// How many fit parameters belong to `system` (all with `None`).
const fn count(system: Option<SystemKind>) -> usize {
    let mut n = 0;
    let mut i = 0;
    while i < Key::FIT.len() {
        if belongs(Key::FIT[i], system) {
            n += 1;
        }
        i += 1;
    }
    n
}

/// Whether the fit parameter `key` belongs to `system` (any with `None`).
const fn belongs(key: Key, system: Option<SystemKind>) -> bool {
    let Some(system) = system else {
        return true;
    };
    let systems = key.fit_systems();
    let mut i = 0;
    while i < systems.len() {
        if systems[i] as u8 == system as u8 {
            return true;
        }
        i += 1;
    }
    false
}

/// The fit parameters by the names they had before they were keys of the experiment's table
/// (`FitParameter::Ut` is [`Key::TurnOn`]'s): shorthands, no table of their own.
#[allow(non_upper_case_globals)]
impl FitParameter {
    /// Series resistance R (Ω), [`Key::Resistance`].
    pub const Resistance: FitParameter = FitParameter(Key::Resistance);
    /// PWL turn-on voltage U_t (V), [`Key::TurnOn`].
    pub const Ut: FitParameter = FitParameter(Key::TurnOn);
    /// PWL forward resistance R_D (Ω), [`Key::DiodeResistance`].
    pub const Rd: FitParameter = FitParameter(Key::DiodeResistance);
    /// Shockley saturation current I_s of one diode (A), [`Key::SaturationCurrent`].
    pub const DiodeIs: FitParameter = FitParameter(Key::SaturationCurrent);
    /// Shockley emission coefficient n, [`Key::Emission`].
    pub const DiodeN: FitParameter = FitParameter(Key::Emission);
    /// Shockley series resistance R_s of one diode (Ω), [`Key::SeriesResistance`].
    pub const DiodeRs: FitParameter = FitParameter(Key::SeriesResistance);
    /// Inductance L (H), [`Key::Inductance`].
    pub const Inductance: FitParameter = FitParameter(Key::Inductance);
    /// Capacitance C (F), [`Key::Capacitance`].
    pub const Capacitance: FitParameter = FitParameter(Key::Capacitance);
    /// Static-to-kinetic friction ratio μs (PWL circuits and mechanics), [`Key::MuS`].
    pub const MuS: FitParameter = FitParameter(Key::MuS);
    /// Viscous damping γ of a mechanical oscillator (N·s/m), [`Key::Damping`].
    pub const Damping: FitParameter = FitParameter(Key::Damping);
    /// Kinetic friction force F0 of a mechanical oscillator (N), [`Key::Friction`].
    pub const Friction: FitParameter = FitParameter(Key::Friction);
    /// Mass m of a mechanical oscillator (kg), [`Key::Mass`].
    pub const Mass: FitParameter = FitParameter(Key::Mass);
    /// Spring constant k of a mechanical oscillator (N/m), [`Key::Stiffness`].
    pub const Stiffness: FitParameter = FitParameter(Key::Stiffness);
    /// Stribeck speed of a mechanical oscillator's Stribeck law (m/s),
    /// [`Key::StribeckSpeed`].
    pub const StribeckSpeed: FitParameter = FitParameter(Key::StribeckSpeed);
    /// Viscous friction η·F0/v of a mechanical oscillator's Stribeck law (N·s/m),
    /// [`Key::ViscousFriction`].
    pub const ViscousFriction: FitParameter = FitParameter(Key::ViscousFriction);
}

impl FitParameter {
    /// Every parameter, in the fit's order ([`FitRole::order`]).
    pub const ALL: [FitParameter; count(None)] = select(None);

    /// The parameters of a circuit, in the fit's order.
    pub const CIRCUIT: [FitParameter; count(Some(SystemKind::Circuit))] =
        select(Some(SystemKind::Circuit));

    /// The parameters of a mechanical oscillator, in the fit's order.
    pub const MECHANICS: [FitParameter; count(Some(SystemKind::Mechanics))] =
        select(Some(SystemKind::Mechanics));

    /// The fit parameter of `key`, if a fit may free it ([`Key::fit_role`]).
    pub fn new(key: Key) -> Option<FitParameter> {
        key.fit_role().map(|_| FitParameter(key))
    }

    /// Its key in the experiment's table.
    pub fn key(self) -> Key {
        self.0
    }

    fn role(self) -> FitRole {
        self.0
            .fit_role()
            .expect("a fit parameter is a key with a fit role")
    }

    /// The name: its key's flag, without the dashes (`diode-is`).
    pub fn label(self) -> &'static str {
        self.0.flag()
    }

    /// Its symbol in formulas, its key's (`U_t`, `μ_s`, `γ`).
    pub fn symbol(self) -> &'static str {
        self.0.symbol()
    }

    /// Whether the parameter belongs to a mechanical oscillator (`mu-s` belongs to both).
    pub fn is_mechanical(self) -> bool {
        self.role().systems.contains(&SystemKind::Mechanics)
    }

    /// Whether the parameter belongs to a circuit (`mu-s` belongs to both).
    pub fn is_circuit(self) -> bool {
        self.role().systems.contains(&SystemKind::Circuit)
    }

    /// The names of `list`, comma-separated.
    pub(crate) fn names(list: &[FitParameter]) -> String {
        list.iter()
            .map(|p| p.label())
            .collect::<Vec<_>>()
            .join(", ")
    }

    /// The names of `list` as `--free` takes them: `resistance,ut`.
    pub fn list(list: &[FitParameter]) -> String {
        list.iter().map(|p| p.label()).collect::<Vec<_>>().join(",")
    }

    /// The SI unit of the value, its key's (`ohm`, `N s/m`; empty for a pure number).
    pub fn unit(self) -> &'static str {
        self.0.unit().unwrap_or("")
    }

    /// Whether the parameter belongs to the diode law `model` (`ut`, `rd`, `mu-s` and the
    /// mechanical ones, whose Coulomb law is the PWL law: PWL; `diode-*`: Shockley; the
    /// others: both).
    pub fn applies_to(self, model: DiodeModel) -> bool {
        self.role().law.is_none_or(|law| law == model)
    }

    /// The parameters a fit of `system` with the diode law `law` may free, in the fit's
    /// order (none for the dimensionless model).
    pub fn of(system: SystemKind, law: DiodeModel) -> Vec<FitParameter> {
        FitParameter::ALL
            .into_iter()
            .filter(|p| p.role().applies(system, law))
            .collect()
    }

    /// The parameters a fit of `system` with the diode law `law` frees when told nothing,
    /// in the fit's order: a PWL circuit's R and U_t, a Shockley circuit's R, I_s and n (U_t
    /// is then only the unit of y and β), a mechanical oscillator's γ and F0 (the key
    /// table's [`FitRole::default`]).
    pub fn defaults(system: SystemKind, law: DiodeModel) -> Vec<FitParameter> {
        FitParameter::of(system, law)
            .into_iter()
            .filter(|p| p.role().default)
            .collect()
    }

    /// The default free set of `experiment`'s system and diode law
    /// ([`FitParameter::defaults`]).
    ///
    /// # Errors
    /// [`FitError::NeedsCircuit`] for the dimensionless model.
    pub fn defaults_of(experiment: &Experiment) -> Result<Vec<FitParameter>, FitError> {
        match experiment.system_kind() {
            SystemKind::Dimensionless => Err(FitError::NeedsCircuit),
            system => Ok(FitParameter::defaults(system, experiment.diode_model())),
        }
    }

    /// The parameter's value in `experiment` (a circuit or a mechanical oscillator).
    ///
    /// # Errors
    /// [`FitError::NeedsCircuit`] without a physical system; [`FitError::WrongSystem`] for a
    /// circuit's parameter on a mechanical oscillator or the other way round;
    /// [`FitError::WrongLaw`] for a parameter of the other diode law.
    pub fn get(self, experiment: &Experiment) -> Result<f64, FitError> {
        match experiment.system().ok_or(FitError::NeedsCircuit)? {
            System::Mechanics(m) => {
                if !self.is_mechanical() {
                    return Err(FitError::WrongSystem {
                        parameter: self,
                        mechanics: true,
                    });
                }
                Ok(match self {
                    FitParameter::Damping => m.damping,
                    FitParameter::Friction => m.friction,
                    FitParameter::Mass => m.mass,
                    FitParameter::Stiffness => m.stiffness,
                    FitParameter::StribeckSpeed | FitParameter::ViscousFriction => {
                        let law = experiment.friction_law();
                        let FrictionLaw::Stribeck { vs, eta, .. } = law else {
                            return Err(FitError::WrongFrictionLaw {
                                parameter: self,
                                law: law.kind(),
                            });
                        };
                        let dimensionless = if self == FitParameter::StribeckSpeed {
                            vs
                        } else {
                            eta
                        };
                        physical(self.0, dimensionless, &m.scales())
                    }
                    _ => experiment.mu_s(),
                })
            }
            System::Circuit(c) => {
                if !self.is_circuit() {
                    return Err(FitError::WrongSystem {
                        parameter: self,
                        mechanics: false,
                    });
                }
                self.check_law(experiment.diode_model())?;
                Ok(match (self, c.diode) {
                    (FitParameter::Resistance, _) => c.resistance,
                    (FitParameter::Inductance, _) => c.inductance,
                    (FitParameter::Capacitance, _) => c.capacitance,
                    (FitParameter::MuS, _) => experiment.mu_s(),
                    (FitParameter::Ut, Diode::Pwl(d)) => d.turn_on,
                    (FitParameter::Rd, Diode::Pwl(d)) => d.resistance,
                    (FitParameter::DiodeIs, Diode::Shockley(d)) => d.pair.saturation_current,
                    (FitParameter::DiodeN, Diode::Shockley(d)) => d.pair.emission,
                    (FitParameter::DiodeRs, Diode::Shockley(d)) => d.pair.series_resistance,
                    _ => unreachable!("the law was checked"),
                })
            }
        }
    }

    fn check_law(self, model: DiodeModel) -> Result<(), FitError> {
        if self.applies_to(model) {
            Ok(())
        } else {
            Err(FitError::WrongLaw {
                parameter: self,
                model,
            })
        }
    }

    /// `circuit` with this parameter set to `value` (μs is not a part of the circuit and is
    /// left to the caller).
    pub(crate) fn set(self, circuit: &mut Circuit, value: f64) {
        match (self, &mut circuit.diode) {
            (FitParameter::Resistance, _) => circuit.resistance = value,
            (FitParameter::Inductance, _) => circuit.inductance = value,
            (FitParameter::Capacitance, _) => circuit.capacitance = value,
            (FitParameter::Ut, Diode::Pwl(d)) => d.turn_on = value,
            (FitParameter::Rd, Diode::Pwl(d)) => d.resistance = value,
            (FitParameter::DiodeIs, Diode::Shockley(d)) => d.pair.saturation_current = value,
            (FitParameter::DiodeN, Diode::Shockley(d)) => d.pair.emission = value,
            (FitParameter::DiodeRs, Diode::Shockley(d)) => d.pair.series_resistance = value,
            _ => {}
        }
    }

    /// `mechanics` with this parameter set to `value` (μs is left to the caller).
    pub(crate) fn set_mechanics(self, mechanics: &mut Mechanics, value: f64) {
        match self {
            FitParameter::Damping => mechanics.damping = value,
            FitParameter::Friction => mechanics.friction = value,
            FitParameter::Mass => mechanics.mass = value,
            FitParameter::Stiffness => mechanics.stiffness = value,
            _ => {}
        }
    }
}

/// The physical value (m/s, N·s/m, …) of the key `key` whose dimensionless image is
/// `dimensionless` with `scales` ([`Key::image`]; the key itself for a key without an image).
pub(super) fn physical(key: Key, dimensionless: f64, scales: &Scales) -> f64 {
    key.image(1.0, scales)
        .map_or(dimensionless, |unit| dimensionless / unit)
}

/// The dimensionless image of the physical value `value` of `key` with `scales`.
pub(super) fn dimensionless(key: Key, value: f64, scales: &Scales) -> f64 {
    key.image(value, scales).unwrap_or(value)
}

impl std::fmt::Display for FitParameter {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.label())
    }
}

/// In the fit's order ([`FitRole::order`]).
impl Ord for FitParameter {
    fn cmp(&self, other: &Self) -> std::cmp::Ordering {
        self.role().order.cmp(&other.role().order)
    }
}

impl PartialOrd for FitParameter {
    fn partial_cmp(&self, other: &Self) -> Option<std::cmp::Ordering> {
        Some(self.cmp(other))
    }
}

impl std::str::FromStr for FitParameter {
    type Err = FitError;

    /// A parameter by its key's flag ([`FitParameter::label`]: `resistance`, `diode-is`)
    /// or its key's name (`R`, `U_t`, `gamma`, `F0`), in any case, `_` and `-` alike
    /// (`mu_s`, `diode_is`, `f0`).
    fn from_str(s: &str) -> Result<Self, FitError> {
        let fold = |t: &str| t.trim().replace('_', "-").to_ascii_lowercase();
        let wanted = fold(s);
        FitParameter::ALL
            .into_iter()
            .find(|p| fold(p.label()) == wanted || fold(p.0.name()) == wanted)
            .ok_or_else(|| FitError::UnknownParameter(s.trim().chars().take(40).collect()))
    }
}

/// As its name ([`FitParameter::label`]).
impl Serialize for FitParameter {
    fn serialize<S: Serializer>(&self, serializer: S) -> Result<S::Ok, S::Error> {
        serializer.serialize_str(self.label())
    }
}

impl<'de> Deserialize<'de> for FitParameter {
    fn deserialize<D: Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        let name = String::deserialize(deserializer)?;
        name.parse().map_err(serde::de::Error::custom)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn names_round_trip() {
        for p in FitParameter::ALL {
            assert_eq!(p.label().parse::<FitParameter>().unwrap(), p);
            assert_eq!(p.key().name().parse::<FitParameter>().unwrap(), p);
            assert_eq!(p.to_string(), p.label());
            assert_eq!(FitParameter::new(p.key()), Some(p));
            let json = serde_json::to_string(&p).unwrap();
            assert_eq!(json, format!("\"{}\"", p.label()));
            assert_eq!(serde_json::from_str::<FitParameter>(&json).unwrap(), p);
        }
        assert_eq!("mu_s".parse::<FitParameter>().unwrap(), FitParameter::MuS);
        assert_eq!(
            "Diode_IS".parse::<FitParameter>().unwrap(),
            FitParameter::DiodeIs
        );
        assert_eq!(FitParameter::new(Key::W), None);
        let err = "zeta".parse::<FitParameter>().unwrap_err().to_string();
        // The list the message gave when it was written by hand, from the key table now.
        assert_eq!(
            err,
            "unknown fit parameter \"zeta\" (the parameters are resistance, ut, rd, diode-is, \
             diode-n, diode-rs, inductance, capacitance, mu-s for a circuit; damping, friction, \
             mass, stiffness, mu-s, stribeck-speed, viscous-friction for a mechanical \
             oscillator)"
        );
        for (symbol, p) in [
            ("gamma", FitParameter::Damping),
            ("F0", FitParameter::Friction),
            ("m", FitParameter::Mass),
            ("k", FitParameter::Stiffness),
            ("U_t", FitParameter::Ut),
        ] {
            assert_eq!(symbol.parse::<FitParameter>().unwrap(), p);
        }
        // Every parameter belongs to a circuit or to mechanics, and only μs to both.
        for p in FitParameter::ALL {
            assert!(p.is_circuit() || p.is_mechanical(), "{p}");
            assert_eq!(p.is_circuit() && p.is_mechanical(), p == FitParameter::MuS);
        }
    }

    /// The fit's order is a place per parameter, from 0, each once; the units and symbols
    /// are the keys'.
    #[test]
    fn the_order_units_and_symbols_are_the_key_tables() {
        let keys: Vec<Key> = Key::ALL
            .into_iter()
            .filter(|k| k.fit_role().is_some())
            .collect();
        assert_eq!(keys.len(), FitParameter::ALL.len());
        for (place, p) in FitParameter::ALL.into_iter().enumerate() {
            assert_eq!(p.key().fit_role().unwrap().order as usize, place, "{p}");
            assert_eq!(Some(p.unit()).filter(|u| !u.is_empty()), p.key().unit());
            assert_eq!(p.symbol(), p.key().symbol());
        }
        assert!(FitParameter::ALL.windows(2).all(|w| w[0] < w[1]));
        assert_eq!(
            FitParameter::names(&FitParameter::MECHANICS),
            "damping, friction, mass, stiffness, mu-s, stribeck-speed, viscous-friction"
        );
        assert_eq!(FitParameter::Damping.unit(), "N s/m");
        assert_eq!(FitParameter::MuS.symbol(), "μ_s");
    }

    /// One default free set per system and law: what the command line, Python and the lab
    /// free when told nothing.
    #[test]
    fn the_default_free_sets() {
        let list = |system, law| FitParameter::list(&FitParameter::defaults(system, law));
        assert_eq!(list(SystemKind::Circuit, DiodeModel::Pwl), "resistance,ut");
        assert_eq!(
            list(SystemKind::Circuit, DiodeModel::Shockley),
            "resistance,diode-is,diode-n"
        );
        assert_eq!(
            list(SystemKind::Mechanics, DiodeModel::Pwl),
            "damping,friction"
        );
        assert_eq!(list(SystemKind::Dimensionless, DiodeModel::Pwl), "");
        for system in SystemKind::ALL {
            for law in DiodeModel::ALL {
                let of = FitParameter::of(system, law);
                for p in FitParameter::defaults(system, law) {
                    assert!(of.contains(&p) && p.applies_to(law), "{system} {law} {p}");
                }
            }
        }
        assert_eq!(
            FitParameter::names(&FitParameter::of(SystemKind::Circuit, DiodeModel::Shockley)),
            "resistance, diode-is, diode-n, diode-rs, inductance, capacitance"
        );
        let shockley = Experiment::paper()
            .with_shockley(crate::shockley::DiodePair::one_n4148())
            .unwrap();
        assert_eq!(
            FitParameter::defaults_of(&shockley).unwrap(),
            [
                FitParameter::Resistance,
                FitParameter::DiodeIs,
                FitParameter::DiodeN
            ]
        );
        let dimensionless = Experiment::dimensionless(0.1, 1.0, 2.0).unwrap();
        assert_eq!(
            FitParameter::defaults_of(&dimensionless),
            Err(FitError::NeedsCircuit)
        );
    }
}
