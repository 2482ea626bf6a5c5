//! Tests of `stickslip phase-diagram`.
