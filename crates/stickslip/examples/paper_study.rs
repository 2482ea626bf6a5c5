//! The paper's experiment read from a TOML file, its Fig. 4 sweep at β = 3.61 up and down, and
//! a 50 × 50 map of motion classes over the paper's window: the library API in a few lines.
//!
//! ```sh
//! cargo run --release -p stickslip --example paper_study [-- FILE.toml]
//! ```

use stickslip::experiment::Experiment;
use stickslip::scan::{Axis, Grid, ParameterRange, Sweep, SweepDirection, SweepLeg};
use stickslip::steady::MotionClass;
use stickslip::Parameter;

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let path = std::env::args()
        .nth(1)
        .unwrap_or_else(|| concat!(env!("CARGO_MANIFEST_DIR"), "/examples/paper.toml").into());
    let paper = Experiment::from_toml(&std::fs::read_to_string(&path)?, &path)?;
    println!("{paper}");

    // Fig. 4 at β = 3.61: w from 0.2 to 2, up then down, each step from the last one's state.
    let w = ParameterRange::new("w", 0.2, 2.0, 73)?;
    let sweep = Sweep::new(
        &paper.clone().with_beta(3.61)?,
        Axis::range(Parameter::W, &w)?,
    )?
    .direction(SweepDirection::Both)
    .run(&())?;
    for leg in [SweepLeg::Up, SweepLeg::Down] {
        let (w_peak, gain) = sweep
            .iter()
            .filter(|p| p.leg == leg)
            .map(|p| (p.value, p.steady.harmonic(1).unwrap_or(0.0) / 3.61))
            .fold((0.0, 0.0), |m, p| if p.1 > m.1 { p } else { m });
        println!(
            "sweep {}: largest gain of the fundamental G1 = A1/β = {gain:.4} at w = {w_peak:.3}",
            leg.label()
        );
    }

    // The motion class from rest on a 50 × 50 grid of the paper's Fig. 7 window.
    let map = Grid::new(
        &paper,
        Axis::range(Parameter::W, &ParameterRange::new("w", 0.1, 2.5, 50)?)?,
        Axis::range(Parameter::Beta, &ParameterRange::new("beta", 0.5, 4.0, 50)?)?,
    )?
    .run(&())?;
    for class in MotionClass::ALL {
        let n = map.points.iter().filter(|p| p.class == class).count();
        println!("{:>18}: {n} of {} points", class.label(), map.points.len());
    }
    Ok(())
}
