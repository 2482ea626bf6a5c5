//! The cost of the belt bench's Stribeck map point by point (the paper's ζ, no drive,
//! vs = 0.5, δ = 2, η = 0.05, vb 0.05–2, μs 1–3, every point from rest): for each point its
//! class, the section its cycle was recognised at, the τ it took to settle and the wall
//! clock, with or without Newton's method on the section map; then the totals. For instruction
//! counts under callgrind (which the load of a shared machine does not change):
//!
//! ```text
//! cargo build --release -p stickslip --example belt_map_cost
//! valgrind --tool=callgrind --callgrind-out-file=/dev/null \
//!     target/release/examples/belt_map_cost N newton|plain [quiet]
//! ```
use std::time::Instant;
use stickslip::friction::FrictionLaw;
use stickslip::steady::steady_state_from;
use stickslip::{Circuit, Experiment, State};

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let usage = "usage: belt_map_cost N newton|plain [quiet]";
    let n: usize = args.get(1).and_then(|a| a.parse().ok()).expect(usage);
    let newton = match args.get(2).map(String::as_str) {
        Some("newton") => true,
        Some("plain") => false,
        _ => panic!("{usage}"),
    };
    let quiet = args.get(3).is_some_and(|a| a == "quiet");
    let law = FrictionLaw::Stribeck {
        vs: 0.5,
        delta: 2.0,
        eta: 0.05,
    };
    let experiment = Experiment::dimensionless(Circuit::paper().scales().zeta(), 1.0, 0.0)
        .and_then(|e| e.with_law(law))
        .expect("valid");
    let options = experiment.steady_options().with_newton(newton);
    let factory = experiment.factory();
    let base = experiment.params().expect("valid");
    let mut classes = std::collections::BTreeMap::new();
    let (mut settle, start) = (0.0, Instant::now());
    for i in 0..n {
        for j in 0..n {
            let vb = 0.05 + (2.0 - 0.05) * i as f64 / (n - 1) as f64;
            let mu_s = 1.0 + 2.0 * j as f64 / (n - 1) as f64;
            let params = base
                .with_vb(vb)
                .and_then(|p| p.with_mu_s(mu_s))
                .expect("valid");
            let t = Instant::now();
            let s =
                steady_state_from(&factory, &params, State::default(), &options).expect("settles");
            let cycle = s.self_excited.expect("self-excited");
            settle += cycle.time_to_settle;
            *classes.entry(s.class.label()).or_insert(0usize) += 1;
            if !quiet {
                println!(
                    "vb {vb:.4} mu_s {mu_s:.4} {:>16} {:>14} damping {:+.4} settle {:9.1} \
                     y [{:.10}, {:.10}] {:8.2} ms",
                    s.class.label(),
                    cycle.section.map_or("-", |c| c.label()),
                    cycle.sliding_damping,
                    cycle.time_to_settle,
                    s.y_min,
                    s.y_max,
                    t.elapsed().as_secs_f64() * 1e3
                );
            }
        }
    }
    println!(
        "{n}x{n} newton={newton}: {classes:?}, τ to settle {settle:.0}, {:.2} s",
        start.elapsed().as_secs_f64()
    );
}
