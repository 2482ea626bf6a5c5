//! The cost of the report's Fig. 7 (b) Shockley map (paper's circuit, 1N4148 pair, w 0.1–2.5,
//! β 0.5–4, search capped at 500 periods, motions that do not repeat measured) with and
//! without Newton settling, on one thread, for instruction counts under callgrind (which the
//! load of a shared machine does not change):
//!
//! ```text
//! cargo build --release -p stickslip --example shockley_map_cost
//! valgrind --tool=callgrind --callgrind-out-file=/dev/null \
//!     target/release/examples/shockley_map_cost N newton|plain
//! ```
//!
//! It prints the map's class counts and the periods run, for the two runs to be compared.
use stickslip::scan::{Axis, Grid, ParameterRange};
use stickslip::{DiodePair, Experiment, Parameter};

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let usage = "usage: shockley_map_cost N newton|plain";
    let n: usize = args.get(1).and_then(|a| a.parse().ok()).expect(usage);
    let newton = match args.get(2).map(String::as_str) {
        Some("newton") => true,
        Some("plain") => false,
        _ => panic!("{usage}"),
    };
    let shockley = Experiment::paper()
        .with_shockley(DiodePair::one_n4148())
        .expect("valid");
    let options = shockley
        .steady_options()
        .with_max_periods(500)
        .expect("valid")
        .with_newton(newton);
    let grid = Grid::new(
        &shockley,
        Axis::range(
            Parameter::W,
            &ParameterRange::new("w", 0.1, 2.5, n).expect("valid"),
        )
        .expect("valid"),
        Axis::range(
            Parameter::Beta,
            &ParameterRange::new("beta", 0.5, 4.0, n).expect("valid"),
        )
        .expect("valid"),
    )
    .expect("valid")
    .options(options)
    .expect("valid")
    .threads(1)
    .expect("valid");
    let map = grid.run(&()).expect("runs");
    let mut classes = std::collections::BTreeMap::new();
    for p in &map.points {
        *classes.entry(p.class.label()).or_insert(0usize) += 1;
    }
    let periods: usize = map.points.iter().map(|p| p.periods_to_settle).sum();
    println!("{n}x{n} newton={newton}: {classes:?}, periods run {periods}");
}
