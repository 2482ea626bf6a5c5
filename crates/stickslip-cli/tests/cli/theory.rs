//! Tests of `stickslip theory`.
