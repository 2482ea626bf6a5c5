//! Work per event of the exact solver at a few points (evaluations and search steps per event).
use stickslip::solver::run_until;
use stickslip::{Circuit, ExactSolver, Params, Solver, State};

fn main() {
    let zeta = Circuit::paper().scales().zeta();
    for (w, beta) in [
        (0.9, 1.6),
        (0.6, 1.2),
        (0.7, 1.2),
        (0.29, 2.14),
        (1.43, 2.14),
        (0.95, 14.3),
    ] {
        let p = Params::new(zeta, w, beta).unwrap();
        let mut s = ExactSolver::new(p, State::default());
        let t0 = std::time::Instant::now();
        run_until(&mut s, 3000.0 * p.drive_period(), |_| {}).unwrap();
        let dt = t0.elapsed().as_secs_f64();
        let st = s.stats();
        println!(
            "w {w:5} beta {beta:5}: events {:7} evals/event {:6.2} steps/event {:6.2}  {:.0} ns/event",
            st.events,
            st.evaluations as f64 / st.events as f64,
            st.steps as f64 / st.events as f64,
            dt * 1e9 / st.events as f64
        );
    }
}
