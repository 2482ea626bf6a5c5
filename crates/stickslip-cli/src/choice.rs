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

impl Choice for DiodeModel {
    fn all() -> &'static [Self] {
        &DiodeModel::ALL
    }
    fn name(self) -> &'static str {
        self.label()
    }
    fn about(self) -> Option<&'static str> {
        Some(self.description())
    }
}

impl Choice for Preset {
    fn all() -> &'static [Self] {
        &Preset::ALL
    }
    fn name(self) -> &'static str {
        self.label()
    }
    fn about(self) -> Option<&'static str> {
        Some(self.description())
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

impl Choice for Parameter {
    fn all() -> &'static [Self] {
        &Parameter::ALL
    }
    fn name(self) -> &'static str {
        self.flag()
    }
    fn about(self) -> Option<&'static str> {
        Some(self.long_name())
    }
}

impl Choice for SweepDirection {
    fn all() -> &'static [Self] {
        &SweepDirection::ALL
    }
    fn name(self) -> &'static str {
        self.label()
    }
}

impl Choice for BasinMethod {
    fn all() -> &'static [Self] {
        &BasinMethod::ALL
    }
    fn name(self) -> &'static str {
        self.label()
    }
}

impl Choice for MapColor {
    fn all() -> &'static [Self] {
        &MapColor::ALL
    }
    fn name(self) -> &'static str {
        self.label()
    }
    fn about(self) -> Option<&'static str> {
        Some(self.description())
    }
}

impl Choice for CurveKind {
    fn all() -> &'static [Self] {
        &CurveKind::ALL
    }
    fn name(self) -> &'static str {
        self.label()
    }
    fn about(self) -> Option<&'static str> {
        Some(self.description())
    }
}
