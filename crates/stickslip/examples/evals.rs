//! Work per event of the exact solver at a few points: closed-form evaluations, search steps
//! and fallbacks to the careful search per event, and the time per event.
//!
//! `cargo run --release -p stickslip --example evals -- [PERIODS [W BETA]]` (3000 periods at
//! six points by default; one point when W and BETA are given).
use stickslip::solver::run_until;
use stickslip::{Circuit, ExactSolver, Params, Solver, State};

fn main() {
    let zeta = Circuit::paper().scales().zeta();
    let periods: f64 = std::env::args()
        .nth(1)
        .and_then(|a| a.parse().ok())
        .unwrap_or(3000.0);
    let one: Vec<f64> = std::env::args()
        .skip(2)
        .filter_map(|a| a.parse().ok())
        .collect();
    let points = match one[..] {
        [w, beta] => vec![(w, beta)],
        _ => vec![
            (0.9, 1.6),
            (0.6, 1.2),
            (0.7, 1.2),
            (0.29, 2.14),
            (1.43, 2.14),
            (0.95, 14.3),
        ],
    };
    for (w, beta) in points {
        let p = Params::new(zeta, w, beta).unwrap();
        let mut s = ExactSolver::new(p, State::default());
        let t0 = std::time::Instant::now();
        run_until(&mut s, periods * p.drive_period(), |_| {}).unwrap();
        let dt = t0.elapsed().as_secs_f64();
        let st = s.stats();
        let per = |x: u64| x as f64 / st.events as f64;
        println!(
            "w {w:5} beta {beta:5}: events {:7} evals/event {:5.2} steps/event {:5.2} fallbacks/event {:5.3}  {:.0} ns/event",
            st.events,
            per(st.evaluations),
            per(st.steps),
            per(st.rejected),
            dt * 1e9 / st.events as f64
        );
    }
}
