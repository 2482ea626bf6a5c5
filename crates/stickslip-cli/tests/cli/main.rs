//! Integration tests of the `stickslip` binary, compiled as one test binary; one module per
//! subcommand.

mod common;

mod convert;
mod lab;
mod lyapunov;
mod netlist;
mod orbit;
mod phase_diagram;
mod reproduce;
mod simulate;
mod steady;
mod sweep;
mod theory;
