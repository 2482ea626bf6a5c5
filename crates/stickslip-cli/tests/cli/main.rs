//! Integration tests of the `stickslip` binary, compiled as one test binary; one module per
//! subcommand.

mod common;

mod convert;
mod dynamics;
mod lab;
mod netlist;
mod phase_diagram;
mod reproduce;
mod simulate;
mod steady;
mod sweep;
mod theory;
