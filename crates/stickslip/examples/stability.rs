//! Stability and chaos, exactly: the numbers of the stability analysis at the points the
//! literature discusses.
//!
//! `cargo run --release -p stickslip --example stability -- [point|sweep|map]` (all three by
//! default):
//!
//! - `point`: (ζ, μs, w, β) = (0, 2.5, 0.4227, 3.627), whose strobe map does not repeat within
//!   5000 periods: its largest Lyapunov exponent, the orbit it settles on and that orbit's
//!   Floquet multipliers.
//! - `sweep`: ζ = 0, μs = 3, β = 9, 36 values of w from 0.2 to 0.55, each from rest: the motion
//!   class of the steady-state analysis, the largest exponent and the verdict.
//! - `map`: the largest exponent over a 25 × 15 grid of the paper's map (ζ = 0.046816, μs = 1,
//!   w from 0.1 to 2.5, β from 0.5 to 4), each point from rest.
use rayon::prelude::*;
use stickslip::stability::{
    classify_nonperiodic, lyapunov_exponents, periodic_orbit_from_steady, LyapunovOptions,
    NewtonOptions,
};
use stickslip::steady::{exact_solver, steady_state_from, SteadyOptions};
use stickslip::{Params, State};

fn main() {
    let what: Vec<String> = std::env::args().skip(1).collect();
    let wants = |name: &str| what.is_empty() || what.iter().any(|w| w == name);
    if wants("point") {
        point();
    }
    if wants("sweep") {
        sweep();
    }
    if wants("map") {
        map();
    }
}

fn params(zeta: f64, mu_s: f64, w: f64, beta: f64) -> Params {
    Params::new(zeta, w, beta)
        .and_then(|p| p.with_mu_s(mu_s))
        .expect("valid parameters")
}

fn point() {
    let p = params(0.0, 2.5, 0.4227, 3.627);
    println!("== (zeta, mu_s, w, beta) = (0, 2.5, 0.4227, 3.627), from rest");
    for transient in [1000, 20_000] {
        let options = LyapunovOptions {
            transient_periods: transient,
            ..LyapunovOptions::default()
        };
        let c = classify_nonperiodic(&p, State::default(), &options).expect("runs");
        let l = c.exponents.largest;
        println!(
            "largest exponent after {transient} periods of transient, over {} periods: \
             {:.6e} ± {:.1e} per unit tau, {:.6e} ± {:.1e} per drive period; converged {}; \
             verdict {:?}; second exponent {:?}",
            c.exponents.periods,
            l.per_tau,
            l.error_per_tau,
            l.per_period,
            l.error_per_period,
            c.exponents.converged,
            c.verdict,
            c.exponents.second
        );
    }
    for max_periods in [5000, 40_000] {
        let options = SteadyOptions::default()
            .with_spectrum(false)
            .with_max_periods(max_periods)
            .expect("valid");
        let steady =
            steady_state_from(&exact_solver, &p, State::default(), &options).expect("runs");
        println!(
            "steady state with at most {max_periods} periods: {:?}, period {:?}, after {} \
             periods, {} stops per period",
            steady.class, steady.period, steady.periods_to_settle, steady.stops_per_period
        );
        if steady.period.is_some() {
            let orbit = periodic_orbit_from_steady(&p, &steady, &NewtonOptions::default())
                .expect("Newton converges");
            println!(
                "its orbit by Newton ({} steps, residuals {:?}): strobe {:?}, multipliers \
                 {:?}, {:?}, ln|mu|/T = {:.6e}",
                orbit.iterations,
                orbit.residuals,
                orbit.state,
                orbit.multipliers,
                orbit.stability,
                orbit.exponent()
            );
        }
    }
}

fn sweep() {
    println!("== zeta = 0, mu_s = 3, beta = 9, from rest; exponents per unit tau");
    println!("w       class              period  exponent     error     verdict");
    let rows: Vec<String> = (0..36)
        .into_par_iter()
        .map(|i| {
            let w = 0.2 + 0.35 * i as f64 / 35.0;
            let p = params(0.0, 3.0, w, 9.0);
            let options = SteadyOptions::default().with_spectrum(false);
            let steady =
                steady_state_from(&exact_solver, &p, State::default(), &options).expect("runs");
            let c = classify_nonperiodic(&p, State::default(), &LyapunovOptions::default())
                .expect("runs");
            let l = c.exponents.largest;
            format!(
                "{w:.4}  {:<17}  {:>6}  {:+.4e}  {:.1e}  {:?}",
                steady.class.label(),
                steady.period.map_or("-".into(), |p| p.to_string()),
                l.per_tau,
                l.error_per_tau,
                c.verdict
            )
        })
        .collect();
    for row in rows {
        println!("{row}");
    }
}

fn map() {
    let (w_steps, beta_steps) = (25, 15);
    let options = LyapunovOptions {
        transient_periods: 1000,
        periods: 10_000,
        ..LyapunovOptions::default()
    };
    let points: Vec<(f64, f64)> = (0..beta_steps)
        .flat_map(|j| {
            (0..w_steps).map(move |i| {
                (
                    0.1 + 2.4 * i as f64 / (w_steps - 1) as f64,
                    0.5 + 3.5 * j as f64 / (beta_steps - 1) as f64,
                )
            })
        })
        .collect();
    let results: Vec<_> = points
        .par_iter()
        .map(|&(w, beta)| {
            let p = params(0.046816, 1.0, w, beta);
            let l = lyapunov_exponents(&p, State::default(), &options).expect("runs");
            (w, beta, l)
        })
        .collect();
    println!(
        "== paper's map (zeta = 0.046816, mu_s = 1), {w_steps} x {beta_steps} points, from \
         rest; largest exponent per drive period"
    );
    print!("beta \\ w");
    for i in 0..w_steps {
        print!(" {:>6.2}", 0.1 + 2.4 * i as f64 / (w_steps - 1) as f64);
    }
    println!();
    for j in (0..beta_steps).rev() {
        print!("{:>8.2}", results[j * w_steps].1);
        for i in 0..w_steps {
            print!(" {:>6.2}", results[j * w_steps + i].2.largest.per_period);
        }
        println!();
    }
    // From rest with β ≤ μs the oscillator never moves: J = diag(1, 0) for ever, exponent 0.
    let moving: Vec<_> = results
        .iter()
        .filter(|r| r.2.largest.per_tau != 0.0)
        .collect();
    let (w, beta, top) = moving
        .iter()
        .max_by(|a, b| a.2.largest.per_tau.total_cmp(&b.2.largest.per_tau))
        .expect("moving points");
    let positive = results
        .iter()
        .filter(|r| r.2.largest.per_tau > options.significance * r.2.largest.error_per_tau)
        .count();
    let unconverged: Vec<_> = results
        .iter()
        .filter(|r| !r.2.converged)
        .map(|r| (r.0, r.1))
        .collect();
    println!(
        "at rest (exponent exactly 0): {} points; moving: {}, largest exponent among them \
         {:+.4e} ± {:.1e} per unit tau ({:+.4} per drive period) at (w, beta) = ({w:.3}, \
         {beta:.3}); positive beyond {} errors: {positive} of {}; not converged (halves \
         disagree): {unconverged:.2?}",
        results.len() - moving.len(),
        moving.len(),
        top.largest.per_tau,
        top.largest.error_per_tau,
        top.largest.per_period,
        options.significance,
        results.len()
    );
}
