//! Tests of `stickslip netlist`.
