//! One file per subcommand: each has its `Args` (flags as typed) and `run`.

use clap::Subcommand;

pub mod basins;
pub mod bifurcation;
pub mod continuation;
pub mod convert;
pub mod curve;
pub mod fit;
pub mod lab;
pub mod lyapunov;
pub mod netlist;
pub mod orbit;
pub mod phase_diagram;
pub mod reproduce;
pub mod simulate;
pub mod steady;
pub mod sweep;
pub mod theory;

/// The subcommands. A variant without a doc comment takes its help from its `Args` struct,
/// which carries the command's examples.
#[derive(Debug, Subcommand)]
pub enum Command {
    Simulate(simulate::Args),
    Convert(convert::Args),
    /// The paper's series solution, the exact periodic solution, and stick-slip boundaries.
    Theory(theory::Args),
    /// Run to the steady state and report its class, period, spectrum and gain.
    Steady(steady::Args),
    /// Sweep w or β up and/or down, each step starting where the last ended (hysteresis).
    Sweep(sweep::Args),
    /// Classify the motion on a (w, β) grid: sliding, periodic or non-periodic stick, static, chaotic.
    PhaseDiagram(phase_diagram::Args),
    /// A periodic orbit by Newton's method, with its Floquet multipliers and stability.
    Orbit(orbit::Args),
    /// The Lyapunov exponents of a motion, from the exact tangent dynamics: chaos or not.
    Lyapunov(lyapunov::Args),
    /// Write the circuit as a SPICE netlist (Shockley diodes) for ngspice or any SPICE.
    Netlist(netlist::Args),
    /// Regenerate every figure and table of the paper with an HTML report.
    Reproduce(reproduce::Args),
    Lab(lab::Args),
    /// Bifurcation diagram: strobe points and the Lyapunov exponent against a parameter.
    Bifurcation(bifurcation::Args),
    /// Basins of attraction: the attractor reached from each initial state of a grid.
    Basins(basins::Args),
    /// Continue a branch of periodic orbits through folds and changes of the event sequence.
    Continue(continuation::Args),
    /// Follow a fold, period doubling, Neimark–Sacker point or grazing in two parameters.
    Curve(curve::Args),
    Fit(fit::Args),
}

/// Run one subcommand.
pub fn run(command: Command) -> anyhow::Result<()> {
    match command {
        Command::Simulate(a) => simulate::run(a),
        Command::Convert(a) => convert::run(a),
        Command::Theory(a) => theory::run(a),
        Command::Steady(a) => steady::run(a),
        Command::Sweep(a) => sweep::run(a),
        Command::PhaseDiagram(a) => phase_diagram::run(a),
        Command::Orbit(a) => orbit::run(a),
        Command::Lyapunov(a) => lyapunov::run(a),
        Command::Netlist(a) => netlist::run(a),
        Command::Reproduce(a) => reproduce::run(a),
        Command::Lab(a) => lab::run(a),
        Command::Bifurcation(a) => bifurcation::run(a),
        Command::Basins(a) => basins::run(a),
        Command::Continue(a) => continuation::run(a),
        Command::Curve(a) => curve::run(a),
        Command::Fit(a) => fit::run(a),
    }
}
