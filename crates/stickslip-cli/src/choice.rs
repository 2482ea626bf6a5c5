//! The library's enums as values of flags (`--model shockley`, `--over mu-s`, `--direction
//! both`): the names, their order and their help are the library's ([`std::str::FromStr`],
//! `ALL`, `label`), so the tool keeps no table of names of its own.

use clap::builder::{PossibleValue, PossibleValuesParser, TypedValueParser};
use std::marker::PhantomData;
use std::str::FromStr;
use stickslip::basins::BasinMethod;
use stickslip::continuation::Follow;
use stickslip::experiment::{DiodeModel, Preset};
use stickslip::scan::{MapColor, SweepDirection};
use stickslip::theory::curves::CurveKind;
use stickslip::Parameter;

/// A library enum a flag names by one of its values (`--model shockley`), listed with its
/// one-line help where the library gives one.
pub trait Choice: FromStr + Copy + Send + Sync + 'static {
    /// Every value, in the order the help lists them.
    fn all() -> &'static [Self];
    /// The name the user types.
    fn name(self) -> &'static str;
    /// One line about the value, if the library has one.
    fn about(self) -> Option<&'static str> {
        None
    }
    /// Names retired, with the value each still reads as (the library's `RETIRED`): accepted,
    /// not listed, and a note on standard error says the name now.
    fn retired() -> &'static [(&'static str, Self)] {
        &[]
    }
}

/// The parser of a flag that takes a value of `T` by name: the names are the library's, the
/// help lists them; a retired name still works, with a note.
pub fn choice<T: Choice>() -> ChoiceParser<T> {
    ChoiceParser(PhantomData)
}

/// The value parser [`choice`] returns.
#[derive(Debug, Clone, Copy)]
pub struct ChoiceParser<T>(PhantomData<T>);

impl<T: Choice> ChoiceParser<T> {
    fn values() -> Vec<PossibleValue> {
        let current = T::all().iter().map(|&v| {
            let value = PossibleValue::new(v.name());
            match v.about() {
                Some(about) => value.help(about),
                None => value,
            }
        });
        let retired = T::retired()
            .iter()
            .map(|(old, _)| PossibleValue::new(*old).hide(true));
        current.chain(retired).collect()
    }
}

impl<T: Choice> TypedValueParser for ChoiceParser<T> {
    type Value = T;

    fn parse_ref(
        &self,
        cmd: &clap::Command,
        arg: Option<&clap::Arg>,
        value: &std::ffi::OsStr,
    ) -> Result<T, clap::Error> {
        let name = PossibleValuesParser::new(Self::values()).parse_ref(cmd, arg, value)?;
        if let Some((old, now)) = T::retired().iter().find(|(old, _)| *old == name) {
            let flag = arg
                .and_then(|a| a.get_long())
                .map(|long| format!("--{long} "))
                .unwrap_or_default();
            eprintln!(
                "note: {flag}{old} is now called {flag}{} (the old name still works)",
                now.name()
            );
        }
        Ok(T::from_str(&name)
            .ok()
            .expect("a name the library listed reads back"))
    }

    fn possible_values(&self) -> Option<Box<dyn Iterator<Item = PossibleValue> + '_>> {
        Some(Box::new(Self::values().into_iter()))
    }
}

/// `impl Choice` by the enum's `ALL`, the method that names a value and, where the library
/// has one, the method that describes it (and with `retired`, the enum's `RETIRED`).
macro_rules! choice_of {
    ($type:ty, $name:ident) => {
        impl Choice for $type {
            fn all() -> &'static [Self] {
                &<$type>::ALL
            }
            fn name(self) -> &'static str {
                self.$name()
            }
        }
    };
    ($type:ty, $name:ident, $about:ident) => {
        choice_of!(@with $type, $name, $about, &[]);
    };
    ($type:ty, $name:ident, $about:ident, retired) => {
        choice_of!(@with $type, $name, $about, &<$type>::RETIRED);
    };
    (@with $type:ty, $name:ident, $about:ident, $retired:expr) => {
        impl Choice for $type {
            fn all() -> &'static [Self] {
                &<$type>::ALL
            }
            fn name(self) -> &'static str {
                self.$name()
            }
            fn about(self) -> Option<&'static str> {
                Some(self.$about())
            }
            fn retired() -> &'static [(&'static str, Self)] {
                $retired
            }
        }
    };
}

choice_of!(DiodeModel, label, description);
choice_of!(Preset, label, description);
choice_of!(Parameter, flag, long_name);
choice_of!(SweepDirection, label);
choice_of!(BasinMethod, label);
choice_of!(MapColor, label, description, retired);
choice_of!(CurveKind, label, description, retired);
choice_of!(stickslip::friction::FrictionLawKind, label, description);
choice_of!(Follow, label, words);

#[cfg(test)]
mod tests {
    use super::*;

    fn reads_back<T: Choice + PartialEq + std::fmt::Debug>() {
        for &value in T::all() {
            assert_eq!(T::from_str(value.name()).ok(), Some(value));
        }
    }

    /// Every name a flag lists is read back by the library's `FromStr` (the parser relies on
    /// it).
    #[test]
    fn every_name_listed_reads_back() {
        reads_back::<DiodeModel>();
        reads_back::<Preset>();
        reads_back::<Parameter>();
        reads_back::<SweepDirection>();
        reads_back::<BasinMethod>();
        reads_back::<MapColor>();
        reads_back::<CurveKind>();
        reads_back::<stickslip::friction::FrictionLawKind>();
        for (old, now) in MapColor::RETIRED {
            assert_eq!(MapColor::from_str(old).ok(), Some(now));
        }
        for (old, now) in CurveKind::RETIRED {
            assert_eq!(CurveKind::from_str(old).ok(), Some(now));
        }
    }
}
