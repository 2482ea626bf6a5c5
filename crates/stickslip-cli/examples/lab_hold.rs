//! `stickslip lab` for the browser tests, with the one test hook that `stickslip lab` has no
//! way to turn on: a request to PATH whose query contains QUERY waits, before it is computed,
//! until the next request to PATH arrives (or its client goes away). A test can then drop a
//! request that is certainly still in flight, however loaded the machine is.
//!
//! ```text
//! target/release/examples/lab_hold PATH QUERY [--time-limit SECONDS]
//! target/release/examples/lab_hold /api/sweep 'to=2&steps=40'
//! ```
//!
//! It listens on a free loopback port and prints its address as `stickslip lab` does; it
//! stops when killed (SIGINT).

use std::process::ExitCode;

fn main() -> ExitCode {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let (Some(path), Some(query)) = (args.first(), args.get(1)) else {
        eprintln!("usage: lab_hold PATH QUERY [--time-limit SECONDS]");
        return ExitCode::from(2);
    };
    let mut config = stickslip_lab::Config {
        port: 0,
        ..stickslip_lab::Config::default()
    };
    if let Some(i) = args.iter().position(|a| a == "--time-limit") {
        match args.get(i + 1).and_then(|v| v.parse().ok()) {
            Some(seconds) => config.time_limit = seconds,
            None => {
                eprintln!("lab_hold: --time-limit takes seconds");
                return ExitCode::from(2);
            }
        }
    }
    let hold = stickslip_lab::router::Hold::new(path.as_str(), query.as_str());
    match stickslip_lab::run_holding(config, hold, || false) {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("lab_hold: {e:#}");
            ExitCode::FAILURE
        }
    }
}
