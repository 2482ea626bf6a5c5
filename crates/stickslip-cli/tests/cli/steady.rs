//! Tests of `stickslip steady`.
