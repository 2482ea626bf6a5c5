//! Tests of `stickslip reproduce`.
