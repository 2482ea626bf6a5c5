//! The `Experiment` API of docs/library.md in a program that cargo compiles (the page's snippet
//! is an excerpt of it; the docs' test checks that): the paper's circuit driven
//! dimensionlessly and physically, and with Shockley diodes.
//!
//! ```sh
//! cargo run --release -p stickslip --example experiment_api
//! ```

fn main() -> Result<(), Box<dyn std::error::Error>> {
    use stickslip::{DiodePair, Experiment};
    let sliding = Experiment::paper()
        .with_w(0.95)?
        .with_beta(2.14)?
        .steady()?;
    let physical = Experiment::paper()
        .with_frequency(9.97e3)?
        .with_amplitude(1.498)?;
    let shockley = Experiment::paper().with_shockley(DiodePair::one_n4148())?;
    println!("{}: {}", sliding.class.label(), physical);
    println!("{shockley}");
    Ok(())
}
