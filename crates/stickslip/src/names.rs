//! The names a user types for the library's enums (`pwl`, `up`, `mu-s`, `periodic-stick`,
//! ...): each enum reads them with [`std::str::FromStr`], writes them with
//! [`std::fmt::Display`] and lists them in its `ALL`, so that no front end keeps a table of
//! its own.
//!
//! ```
//! use stickslip::scan::SweepDirection;
//! assert_eq!("both".parse::<SweepDirection>().unwrap(), SweepDirection::Both);
//! assert_eq!(SweepDirection::Up.to_string(), "up");
//! let err = "sideways".parse::<SweepDirection>().unwrap_err();
//! assert_eq!(err.to_string(), "invalid sweep direction 'sideways': one of up, down, both");
//! ```

use crate::attractor::AttractorKind;
use crate::basins::BasinMethod;
use crate::continuation::Follow;
use crate::experiment::{DiodeModel, Key, Preset};
use crate::friction::FrictionLawKind;
use crate::params::Parameter;
use crate::physical::SystemKind;
use crate::scan::{MapColor, SweepDirection, SweepLeg};
use crate::steady::MotionClass;
use crate::theory::curves::{CurveKind, Theory};

/// A name that is not one of an enum's ([`std::str::FromStr`] of the library's enums).
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
#[error("invalid {what} '{text}': one of {}", allowed.join(", "))]
pub struct NameError {
    /// What the name names (`diode law`, `sweep direction`, ...).
    pub what: &'static str,
    /// The text given (control characters escaped, at most 40 characters).
    pub text: String,
    /// The names allowed.
    pub allowed: Vec<&'static str>,
}

impl NameError {
    fn new(what: &'static str, text: &str, allowed: impl Iterator<Item = &'static str>) -> Self {
        Self {
            what,
            text: crate::units::shown(text),
            allowed: allowed.collect(),
        }
    }
}

/// `FromStr` from `label()` and `ALL`, and `Display` by `label()` where `display` is given.
/// With `retired`, the type's `RETIRED` names (a label of before and the value it reads as)
/// read too; the error lists the current names only.
macro_rules! names {
    ($type:ty, $what:literal) => {
        names!(@parse $type, $what, &[]);
    };
    (@parse $type:ty, $what:literal, $retired:expr) => {
        impl std::str::FromStr for $type {
            type Err = NameError;
            fn from_str(text: &str) -> Result<Self, NameError> {
                let retired: &[(&str, $type)] = $retired;
                <$type>::ALL
                    .into_iter()
                    .find(|v| v.label() == text)
                    .or_else(|| retired.iter().find(|(old, _)| *old == text).map(|&(_, v)| v))
                    .ok_or_else(|| {
                        NameError::new($what, text, <$type>::ALL.iter().map(|v| v.label()))
                    })
            }
        }
    };
    ($type:ty, $what:literal, display, retired) => {
        names!(@parse $type, $what, &<$type>::RETIRED);
        names!(@display $type);
    };
    ($type:ty, $what:literal, display) => {
        names!($type, $what);
        names!(@display $type);
    };
    (@display $type:ty) => {
        impl std::fmt::Display for $type {
            fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
                f.write_str(self.label())
            }
        }
    };
}

names!(DiodeModel, "diode law", display);
names!(Preset, "preset", display);
names!(SystemKind, "system", display);
names!(SweepDirection, "sweep direction", display);
names!(SweepLeg, "sweep leg", display);
names!(MotionClass, "motion class", display, retired);
names!(Theory, "theory", display);
names!(CurveKind, "curve", display, retired);
names!(MapColor, "map colour", display, retired);
names!(AttractorKind, "attractor kind", display, retired);
names!(BasinMethod, "basin method", display);
names!(FrictionLawKind, "friction law", display);
names!(Follow, "followed special point");

impl SweepDirection {
    /// Every direction.
    pub const ALL: [SweepDirection; 3] = [
        SweepDirection::Up,
        SweepDirection::Down,
        SweepDirection::Both,
    ];
}

impl SweepLeg {
    /// Both legs.
    pub const ALL: [SweepLeg; 2] = [SweepLeg::Up, SweepLeg::Down];
}

impl Parameter {
    /// The parameter's spelling on the command line and in the lab's query (`--over mu-s`):
    /// its key's flag ([`Key::flag`]).
    pub fn flag(self) -> &'static str {
        self.key().flag()
    }

    /// The key of an experiment that holds the parameter.
    pub fn key(self) -> Key {
        match self {
            Parameter::Zeta => Key::Zeta,
            Parameter::W => Key::W,
            Parameter::Beta => Key::Beta,
            Parameter::MuS => Key::MuS,
            Parameter::Vb => Key::Vb,
            Parameter::Vs => Key::Vs,
            Parameter::Delta => Key::Delta,
            Parameter::Eta => Key::Eta,
            Parameter::K1 => Key::K1,
            Parameter::K3 => Key::K3,
        }
    }

    /// The keys that give a value of the parameter: w also as f or Ω, β also as U (a sweep
    /// over the parameter refuses them).
    pub fn keys(self) -> &'static [Key] {
        match self {
            Parameter::W => &[Key::W, Key::Frequency, Key::Omega],
            Parameter::Beta => &[Key::Beta, Key::Amplitude],
            Parameter::Zeta => &[Key::Zeta],
            Parameter::MuS => &[Key::MuS],
            Parameter::Vb => &[Key::Vb, Key::BeltSpeed],
            Parameter::Vs => &[Key::Vs, Key::StribeckSpeed],
            Parameter::Delta => &[Key::Delta],
            Parameter::Eta => &[Key::Eta, Key::ViscousFriction],
            Parameter::K1 => &[Key::K1, Key::CubicK1],
            Parameter::K3 => &[Key::K3, Key::CubicK3],
        }
    }
}

/// A parameter by its label (`mu_s`, [`Parameter::label`]) or its flag (`mu-s`,
/// [`Parameter::flag`]).
impl std::str::FromStr for Parameter {
    type Err = NameError;
    fn from_str(text: &str) -> Result<Self, NameError> {
        Parameter::ALL
            .into_iter()
            .find(|p| p.label() == text || p.flag() == text)
            .ok_or_else(|| {
                NameError::new("parameter", text, Parameter::ALL.iter().map(|p| p.flag()))
            })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::fmt::Display;
    use std::str::FromStr;

    /// Every name reads back as its value, and a wrong name lists them all.
    fn round_trip<T>(all: &[T])
    where
        T: FromStr<Err = NameError> + Display + PartialEq + std::fmt::Debug + Copy,
    {
        for &v in all {
            assert_eq!(v.to_string().parse::<T>().unwrap(), v);
        }
        let err = "nonsense\n".parse::<T>().unwrap_err();
        assert_eq!(err.allowed.len(), all.len());
        assert!(!err.to_string().contains('\n'), "{err}");
        assert!(
            err.to_string().contains(all[0].to_string().as_str()),
            "{err}"
        );
    }

    #[test]
    fn every_enum_reads_what_it_writes() {
        round_trip(&DiodeModel::ALL);
        round_trip(&Preset::ALL);
        round_trip(&SweepDirection::ALL);
        round_trip(&SweepLeg::ALL);
        round_trip(&MotionClass::ALL);
        round_trip(&AttractorKind::ALL);
        round_trip(&BasinMethod::ALL);
        round_trip(&Theory::ALL);
        round_trip(&CurveKind::ALL);
        round_trip(&MapColor::ALL);
        round_trip(&Parameter::ALL);
        round_trip(&FrictionLawKind::ALL);
    }

    #[test]
    fn retired_names_read_as_the_current_ones() {
        let pairs: [(&str, String); 4] = [
            ("nonperiodic-stick", MotionClass::Undecided.to_string()),
            ("unsettled", AttractorKind::Undecided.to_string()),
            ("lyapunov", MapColor::Lambda1.to_string()),
            ("gain", CurveKind::Gain1.to_string()),
        ];
        assert_eq!(
            "nonperiodic-stick".parse::<MotionClass>().unwrap(),
            MotionClass::Undecided
        );
        assert_eq!(
            "unsettled".parse::<AttractorKind>().unwrap(),
            AttractorKind::Undecided
        );
        assert_eq!("lyapunov".parse::<MapColor>().unwrap(), MapColor::Lambda1);
        assert_eq!("gain".parse::<CurveKind>().unwrap(), CurveKind::Gain1);
        for (old, new) in pairs {
            assert_ne!(old, new);
        }
        // A wrong name lists the current names only.
        let err = "x".parse::<MotionClass>().unwrap_err().to_string();
        assert!(
            err.contains("undecided") && !err.contains("nonperiodic"),
            "{err}"
        );
    }

    #[test]
    fn parameters_take_their_flag_and_their_label() {
        assert_eq!("mu-s".parse::<Parameter>().unwrap(), Parameter::MuS);
        assert_eq!("mu_s".parse::<Parameter>().unwrap(), Parameter::MuS);
        assert_eq!(
            "f".parse::<Parameter>().unwrap_err().to_string(),
            "invalid parameter 'f': one of zeta, w, beta, mu-s, vb, vs, delta, eta, k1, k3"
        );
        for p in Parameter::ALL {
            assert_eq!(p.keys()[0], p.key());
            assert!(p
                .keys()
                .iter()
                .all(|k| k.image_key().unwrap_or(*k) == p.key()));
        }
    }

    #[test]
    fn labels_serialise_as_they_display() {
        for d in DiodeModel::ALL {
            assert_eq!(serde_json::to_string(&d).unwrap(), format!("\"{d}\""));
        }
        for c in MotionClass::ALL {
            assert_eq!(serde_json::to_string(&c).unwrap(), format!("\"{c}\""));
        }
        for d in SweepDirection::ALL {
            assert_eq!(serde_json::to_string(&d).unwrap(), format!("\"{d}\""));
        }
    }
}
