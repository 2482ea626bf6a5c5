//! The library's enums as values of flags (`--model shockley`, `--over mu-s`, `--direction
//! both`): the names, their order and their help are the library's ([`std::str::FromStr`],
//! `ALL`, `label`), so the tool keeps no table of names of its own.

use clap::builder::{PossibleValue, PossibleValuesParser, TypedValueParser};
use std::str::FromStr;
use stickslip::basins::BasinMethod;
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
}

/// The parser of a flag that takes a value of `T` by name: the names are the library's, the
/// help lists them.
pub fn choice<T: Choice>() -> impl TypedValueParser<Value = T> {
    PossibleValuesParser::new(T::all().iter().map(|&v| {
        let value = PossibleValue::new(v.name());
        match v.about() {
            Some(about) => value.help(about),
            None => value,
        }
    }))
    .map(|name| {
        T::from_str(&name)
            .ok()
            .expect("a name the library listed reads back")
    })
}

/// `impl Choice` by the enum's `ALL`, the method that names a value and, where the library
/// has one, the method that describes it.
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
        }
    };
}

choice_of!(DiodeModel, label, description);
choice_of!(Preset, label, description);
choice_of!(Parameter, flag, long_name);
choice_of!(SweepDirection, label);
choice_of!(BasinMethod, label);
choice_of!(MapColor, label, description);
choice_of!(CurveKind, label, description);

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
    }
}
