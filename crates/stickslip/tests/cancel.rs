//! Cancellation, deadlines and budgets: every computation on an experiment that carries a
//! token stops with the token's error, and a token that never stops changes nothing.

use std::time::{Duration, Instant};
use stickslip::cancel::Cancel;
use stickslip::scan::{Axis, ParameterRange, Sweep};
use stickslip::stability::LyapunovOptions;
use stickslip::{Error, Experiment, Parameter, SteadyOptions};
use stickslip_testkit::paper_shockley;

fn point() -> Experiment {
    Experiment::dimensionless(0.05, 0.7, 2.0).unwrap()
}

#[test]
fn a_cancelled_token_stops_the_steady_state() {
    let token = Cancel::new();
    token.cancel();
    let e = point().with_cancel(token).steady().unwrap_err();
    assert_eq!(e, Error::Cancelled { done: 0, total: 1 });
    assert!(e.is_stop());
}

#[test]
fn a_token_that_does_not_stop_changes_nothing_and_counts_the_work() {
    let plain = point().steady().unwrap();
    let token = Cancel::new().with_deadline(Instant::now() + Duration::from_secs(3600));
    let watched = point().with_cancel(token.clone()).steady().unwrap();
    assert_eq!(plain, watched);
    // Every advance of the solver is charged: at least two events a drive period over the
    // periods run.
    assert!(
        token.spent() >= 2 * plain.periods_to_settle as u64,
        "{} steps for {} periods",
        token.spent(),
        plain.periods_to_settle
    );
    // The token is not part of what the experiment is.
    assert_eq!(point(), point().with_cancel(Cancel::new()));
}

#[test]
fn the_budget_stops_the_exact_and_the_stiff_solver() {
    // Half the steps the steady state takes (its strobes, Newton's tangent periods and the
    // record: all charged to the token).
    let counted = Cancel::new();
    point().with_cancel(counted.clone()).steady().unwrap();
    assert!(counted.spent() >= 20, "{} steps", counted.spent());
    let budget = counted.spent() / 2;
    let e = point()
        .with_cancel(Cancel::new().with_budget(budget))
        .steady()
        .unwrap_err();
    assert_eq!(e, Error::BudgetExceeded { budget });
    let shockley = paper_shockley();
    let token = Cancel::new().with_budget(200);
    let e = shockley.with_cancel(token.clone()).steady().unwrap_err();
    assert_eq!(e, Error::BudgetExceeded { budget: 200 });
    assert_eq!(token.spent(), 201);
}

#[test]
fn a_past_deadline_stops_a_sweep() {
    let token = Cancel::new().with_deadline(Instant::now());
    let experiment = Experiment::dimensionless(0.05, 1.0, 2.0)
        .unwrap()
        .with_cancel(token.clone());
    let sweep = Sweep::new(
        &experiment,
        Axis::range(
            Parameter::W,
            &ParameterRange::new("w", 0.6, 1.4, 5).unwrap(),
        )
        .unwrap(),
    )
    .unwrap();
    let e = sweep.run(&()).unwrap_err();
    assert_eq!(e, Error::DeadlineExceeded);
    // The token is a monitor too: a scan watched by it stops between its points.
    let cancelled = Cancel::new();
    cancelled.cancel();
    let e = Sweep::new(
        &Experiment::dimensionless(0.05, 1.0, 2.0).unwrap(),
        Axis::range(
            Parameter::W,
            &ParameterRange::new("w", 0.6, 1.4, 5).unwrap(),
        )
        .unwrap(),
    )
    .unwrap()
    .run(&cancelled)
    .unwrap_err();
    assert!(matches!(e, Error::Cancelled { .. }), "{e:?}");
}

#[test]
fn the_measurement_of_a_motion_that_does_not_repeat_stops_at_the_deadline() {
    // The chaotic point of the literature (ζ = 0, μs = 3, β = 9): the search runs its 5000
    // periods, then the Lyapunov measurement runs 5000 more, outside the solvers the
    // experiment builds. A deadline half-way through the measurement stops it with the
    // deadline's error. The measurement runs its whole length (not sequential, 20 000
    // periods: about four times the search), so that half of it is far beyond the jitter of
    // the timings. Timed runs on a busy machine vary: a run that beats the deadline is timed
    // again, up to five times.
    let chaotic = Experiment::dimensionless(0.0, 0.3, 9.0)
        .unwrap()
        .with_mu_s(3.0)
        .unwrap();
    let search_only = SteadyOptions {
        lyapunov: None,
        ..chaotic.steady_options()
    };
    let measured = SteadyOptions {
        lyapunov: Some(LyapunovOptions {
            periods: 20_000,
            sequential: false,
            ..SteadyOptions::DEFAULT_LYAPUNOV
        }),
        ..chaotic.steady_options()
    };
    for _ in 0..5 {
        let start = Instant::now();
        assert!(chaotic
            .steady_with(&search_only)
            .unwrap()
            .lyapunov
            .is_none());
        let search = start.elapsed();
        let start = Instant::now();
        let full = chaotic.steady_with(&measured).unwrap();
        let both = start.elapsed();
        assert!(full.lyapunov.is_some(), "{:?}", full.class);
        let deadline = Instant::now() + (search + both) / 2;
        match chaotic
            .clone()
            .with_cancel(Cancel::new().with_deadline(deadline))
            .steady_with(&measured)
        {
            Err(e) => {
                assert_eq!(e, Error::DeadlineExceeded);
                return;
            }
            Ok(again) => assert_eq!(again, full),
        }
    }
    panic!("five runs finished before their deadline");
}

#[test]
fn the_token_adds_the_work_of_the_solvers_it_watched() {
    let token = Cancel::new();
    let experiment = point().with_cancel(token.clone());
    let mut solver = experiment.solver().unwrap();
    stickslip::solver::run_until(solver.as_mut(), 200.0, |_| {}).unwrap();
    let stats = solver.stats();
    assert!(stats.events > 10 && stats.evaluations > 0, "{stats:?}");
    assert_eq!(token.work(), stickslip::Stats::default());
    drop(solver);
    assert_eq!(token.work(), stats);
    let mut again = experiment.solver().unwrap();
    stickslip::solver::run_until(again.as_mut(), 200.0, |_| {}).unwrap();
    drop(again);
    assert_eq!(token.work().events, 2 * stats.events);
}
