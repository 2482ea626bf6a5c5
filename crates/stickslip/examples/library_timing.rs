//! The library side of the Python benchmarks (`bench/python`): one timed run, as JSON on
//! standard output, for the Python package's same call to be compared with.
//!
//! ```text
//! cargo run --release -p stickslip --example library_timing -- map N
//!     Grid::run of the paper's N × N map (w 0.1–2.5, β 0.5–4, each point from rest) on
//!     rayon's global pool: what stickslip.phase_diagram(Experiment.paper(), w=..., beta=...)
//!     runs.
//! cargo run --release -p stickslip --example library_timing -- simulate PERIODS SAMPLES REPEATS
//!     Experiment::simulate of the dimensionless model (the paper's ζ, w = 0.7, β = 1.2),
//!     REPEATS times in one process: what stickslip.simulate(Experiment(w=0.7, beta=1.2),
//!     PERIODS, SAMPLES) runs.
//! ```
use std::time::Instant;
use stickslip::scan::{Axis, Grid, ParameterRange};
use stickslip::{Circuit, Experiment, MotionClass, Parameter};

fn arg<T: std::str::FromStr>(k: usize) -> T {
    std::env::args()
        .nth(k)
        .and_then(|a| a.parse().ok())
        .unwrap_or_else(|| panic!("argument {k} missing or invalid; see the file's documentation"))
}

/// CPU time of this process so far (user + system, all threads) in seconds, from
/// /proc/self/stat (Linux; clock ticks of 10 ms), or NaN where it cannot be read.
fn cpu_seconds() -> f64 {
    let ticks = std::fs::read_to_string("/proc/self/stat")
        .ok()
        .and_then(|s| {
            // The fields after the command name (which may hold spaces) in parentheses.
            let rest = &s[s.rfind(')')? + 2..];
            let fields: Vec<&str> = rest.split_whitespace().collect();
            Some(fields.get(11)?.parse::<f64>().ok()? + fields.get(12)?.parse::<f64>().ok()?)
        });
    ticks.map_or(f64::NAN, |t| t / 100.0)
}

fn main() {
    let what: String = arg(1);
    match what.as_str() {
        "map" => {
            let n: usize = arg(2);
            let w = ParameterRange::new("w", 0.1, 2.5, n).expect("valid");
            let beta = ParameterRange::new("beta", 0.5, 4.0, n).expect("valid");
            let grid = Grid::new(
                &Experiment::paper(),
                Axis::range(Parameter::W, &w).expect("valid"),
                Axis::range(Parameter::Beta, &beta).expect("valid"),
            )
            .expect("valid");
            let (started, cpu) = (Instant::now(), cpu_seconds());
            let map = grid.run(&()).expect("runs");
            let seconds = started.elapsed().as_secs_f64();
            let cpu = cpu_seconds() - cpu;
            let counts: Vec<String> = MotionClass::ALL
                .iter()
                .map(|&c| {
                    let k = map.points.iter().filter(|p| p.class == c).count();
                    format!("\"{}\": {k}", c.label())
                })
                .collect();
            println!(
                "{{\"seconds\": {seconds}, \"cpu_seconds\": {cpu}, \"points\": {}, \"threads\": {}, \"counts\": {{{}}}}}",
                map.points.len(),
                rayon::current_num_threads(),
                counts.join(", ")
            );
        }
        "simulate" => {
            let periods: f64 = arg(2);
            let samples: usize = arg(3);
            let zeta = Circuit::paper().scales().zeta();
            let repeats: usize = arg(4);
            let e = Experiment::dimensionless(zeta, 0.7, 1.2).expect("valid");
            // Repeated in one process, each run on a thread of its own, as the Python package
            // runs it (the allocator's per-thread arenas then behave the same on both sides).
            let mut seconds = Vec::new();
            let mut samples_events = (0, 0);
            for _ in 0..repeats {
                let started = Instant::now();
                let run = std::thread::scope(|s| {
                    s.spawn(|| e.simulate(periods, samples, &()).expect("runs"))
                        .join()
                        .expect("no panic")
                });
                seconds.push(started.elapsed().as_secs_f64());
                samples_events = (run.len(), run.events.len());
            }
            println!(
                "{{\"seconds\": {seconds:?}, \"samples\": {}, \"events\": {}}}",
                samples_events.0, samples_events.1
            );
        }
        other => panic!("unknown workload {other}: map or simulate"),
    }
}
