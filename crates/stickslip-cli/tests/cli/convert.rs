//! Tests of `stickslip convert`.
