//! The Shockley diode-pair model.
//!
//! The PWL law U_t sgn(i) + R_D i of the paper is replaced by the physical law of two
//! anti-parallel diodes ([`DiodePair`]) in the series circuit ([`ShockleyCircuit`]); in the
//! dimensionless variables of the crate the model is [`ShockleyModel`] with the law
//! [`DiodeLaw`].

pub mod circuit;
pub mod diode;
pub mod options;

pub use circuit::{ShockleyCircuit, ShockleyModel};
pub use diode::{DiodeLaw, DiodePair};
pub use options::ShockleyOptions;
