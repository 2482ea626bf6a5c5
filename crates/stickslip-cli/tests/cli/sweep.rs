//! Tests of `stickslip sweep`.
