//! Integration tests of the `stickslip` binary, compiled as one test binary; one module per
//! subcommand.

mod common;

mod belt;
mod belt_continue;
mod belt_tools;
mod checkpoint;
mod convert;
mod curve;
mod curve_belt;
mod determinism;
mod dynamics;
mod fit;
mod fit_belt;
mod friction_continue;
mod front_end_keys;
mod fuzz_props;
mod keys;
mod lab;
mod limits;
mod lyapunov;
mod netlist;
mod options_help;
mod orbit;
mod phase_diagram;
mod reproduce;
mod simulate;
mod steady;
mod streaming;
mod sweep;
mod theory;
mod worked_example;
