//! Exponents that stop when they know: the sequential measurement of the largest Lyapunov
//! exponent gives the verdict of the fixed-length measurement it replaces wherever that one is
//! beyond 4 standard errors, and stops early where the verdict is clear.

use stickslip::scan::{Axis, Grid, GridPoint};
use stickslip::stability::{
    lyapunov_exponents, steady_exponent, Estimate, LyapunovOptions, NonperiodicClassification,
    NonperiodicVerdict, SEARCH_BEFORE_MEASURING,
};
use stickslip::steady::{exact_solver, steady_state_from, MotionClass, SteadyOptions};
use stickslip::{Experiment, Parameter, Params, State};

/// The verdict an exponent gives at `k` standard errors: +1 chaotic, −1 contracting, 0
/// neither.
fn sign(e: &Estimate, k: f64) -> i32 {
    if e.per_tau > k * e.error_per_tau {
        1
    } else if e.per_tau < -k * e.error_per_tau {
        -1
    } else {
        0
    }
}

fn fixed(options: LyapunovOptions) -> LyapunovOptions {
    LyapunovOptions {
        sequential: false,
        ..options
    }
}

#[test]
fn looks_nearly_double_up_to_the_cap() {
    let o = LyapunovOptions::default();
    assert_eq!(o.looks(), vec![620, 1240, 2500, 5000, 10000, 20000]);
    assert_eq!(fixed(o).looks(), vec![20000]);
    // Blocks shorter than 10 periods at the cap: only the cap.
    let short = LyapunovOptions { periods: 100, ..o };
    assert_eq!(short.looks(), vec![100]);
    let steady = SteadyOptions::DEFAULT_LYAPUNOV;
    assert_eq!(steady.looks(), vec![300, 620, 1240, 2500, 5000]);
}

/// From the same state, the sequential measurement's verdict is the fixed one's, and its
/// numbers are those of a fixed measurement of the length it stopped at.
#[test]
fn the_sequential_verdict_is_the_fixed_verdict_and_stops_early() {
    let cases = [
        // (ζ, μs, w, β): chaos, a period-3 stick-slip orbit, a sliding orbit, rest.
        (0.0, 3.0, 0.33, 9.0, NonperiodicVerdict::Chaotic),
        (0.0, 3.0, 0.47, 9.0, NonperiodicVerdict::Chaotic),
        (0.0, 3.0, 0.40, 9.0, NonperiodicVerdict::Contracting),
        (0.0468, 1.0, 0.9, 1.6, NonperiodicVerdict::Contracting),
        (0.0, 3.0, 0.5, 2.0, NonperiodicVerdict::QuasiPeriodic),
    ];
    let options = LyapunovOptions {
        transient_periods: 200,
        periods: 5000,
        ..Default::default()
    };
    for (zeta, mu_s, w, beta, verdict) in cases {
        let params = Params::new(zeta, w, beta).unwrap().with_mu_s(mu_s).unwrap();
        let seq = lyapunov_exponents(&params, State::default(), &options).unwrap();
        let full = lyapunov_exponents(&params, State::default(), &fixed(options)).unwrap();
        let k = options.significance;
        let a = NonperiodicClassification::new(seq.clone(), k);
        let b = NonperiodicClassification::new(full.clone(), k);
        assert_eq!((a.verdict, b.verdict), (verdict, verdict), "{params:?}");
        assert_eq!((seq.cap, full.cap, full.periods), (5000, 5000, 5000));
        assert!(
            seq.periods < seq.cap,
            "{params:?}: a clear verdict stops early ({} periods)",
            seq.periods
        );
        assert!(options.looks().contains(&seq.periods));
        // The sequential estimate is the fixed estimate of that length.
        let short = lyapunov_exponents(
            &params,
            State::default(),
            &fixed(LyapunovOptions {
                periods: seq.periods,
                ..options
            }),
        )
        .unwrap();
        assert_eq!(short.largest, seq.largest, "{params:?}");
        assert_eq!(short.block_means, seq.block_means, "{params:?}");
        assert_eq!(short.stops, seq.stops, "{params:?}");
    }
}

/// The benchmark map (ζ = 0, μs = 3, w 0.2–0.6, β 3–14, 30 × 30): every cell of
/// the exponent map (sequential, chaotic motions reported after a shortened search) has the
/// verdict of the long run it replaces (the full strobe search, then a fixed measurement of
/// 5000 periods) wherever the long run's exponent is beyond 4 standard errors; classes and
/// periods are those of the long run, except where the map decided a motion contracting before
/// it reached its orbit (the long run then finds the orbit, contracting too), and where the
/// chaos the map measured ends within the long run (see [`compare_with_long_run`]).
#[test]
fn the_exponent_map_keeps_every_verdict_of_the_long_run() {
    let steady = SteadyOptions::default().with_spectrum(false);
    let tally = compare_with_long_run(steady, SteadyOptions::DEFAULT_LYAPUNOV);
    assert!(tally.compared > 850, "{tally:?}");
    assert!(tally.chaotic > 100, "{tally:?}");
    assert_eq!(
        tally.early, tally.chaotic,
        "every chaotic cell decided before the cap"
    );
    assert_eq!(tally.undecided, 0, "{tally:?}");
    // The cells whose motion reaches a periodic orbit between the shortened search and the
    // full one are few, and so are those whose chaos ends within the long run.
    assert!(tally.settled_later <= 30, "{tally:?}");
    assert!(tally.chaos_that_ends <= 3, "{tally:?}");
}

/// The same with the options of the report's chaos map (`stickslip reproduce`, chapter
/// "Beyond the paper"): the search and the measurement capped at 1600 periods, 20 periods to
/// align the tangent. No verdict contradicts the long run's; a few cells that the long run
/// decides stay undecided at the shorter cap (a motion still settling, or close to neutral).
#[test]
fn the_reports_exponent_map_keeps_every_verdict_of_the_long_run() {
    let steady = SteadyOptions::default()
        .with_spectrum(false)
        .with_max_periods(1600)
        .unwrap();
    let measure = LyapunovOptions {
        periods: 1600,
        transient_periods: 20,
        ..SteadyOptions::DEFAULT_LYAPUNOV
    };
    let tally = compare_with_long_run(steady, measure);
    println!("{tally:?}");
    assert!(tally.compared > 850, "{tally:?}");
    assert!(tally.chaotic > 100, "{tally:?}");
    // Nearly every chaotic cell decided before the cap.
    assert!(tally.early + 3 >= tally.chaotic, "{tally:?}");
    assert!(tally.undecided <= 3, "{tally:?}");
    assert!(tally.settled_later <= 20, "{tally:?}");
    assert!(tally.chaos_that_ends <= 3, "{tally:?}");
}

/// Where the strobe search of an exponent map repeats within its first
/// [`SEARCH_BEFORE_MEASURING`] periods, the point is the plain map's, bit for bit (the search is
/// causal: the full search finds the same cycle at the same strobe). `stickslip reproduce`
/// takes the map of fig. 7 (a) from the paper's exponent map there.
#[test]
fn a_point_that_repeats_early_is_the_plain_maps_point() {
    let n = 40;
    let axis = |p, lo: f64, hi: f64| {
        let values = (0..n)
            .map(|i| lo + (hi - lo) * i as f64 / (n - 1) as f64)
            .collect();
        Axis::new(p, values).unwrap()
    };
    let literature = Experiment::dimensionless(0.0, 0.3, 9.0)
        .unwrap()
        .with_mu_s(3.0)
        .unwrap();
    let maps = [
        (Experiment::paper(), (0.1, 2.5), (0.5, 4.0)),
        (literature, (0.2, 0.6), (3.0, 14.0)),
    ];
    for (experiment, (w0, w1), (b0, b1)) in maps {
        let grid = || {
            Grid::new(
                &experiment,
                axis(Parameter::W, w0, w1),
                axis(Parameter::Beta, b0, b1),
            )
            .unwrap()
            .options(SteadyOptions::default().with_spectrum(false))
            .unwrap()
        };
        let plain = grid().run(&()).unwrap();
        let exponents = grid()
            .lyapunov(SteadyOptions::DEFAULT_LYAPUNOV)
            .unwrap()
            .run(&())
            .unwrap();
        let mut same = 0;
        for (p, e) in plain.points.iter().zip(&exponents.points) {
            if e.period.is_some() && e.periods_to_settle < SEARCH_BEFORE_MEASURING {
                let e = GridPoint {
                    lyapunov: None,
                    ..*e
                };
                assert_eq!(&e, p);
                same += 1;
            }
        }
        assert!(same > n * n / 2, "{same} points compared");
    }
}

/// Cells of the map compared with the long run, and what the comparison found.
#[derive(Debug, Default)]
struct Tally {
    /// Cells whose long-run exponent is beyond 4 standard errors.
    compared: usize,
    /// Of those, cells the map leaves undecided (within 4 of its standard errors).
    undecided: usize,
    /// Cells the map calls chaotic.
    chaotic: usize,
    /// Chaotic cells decided before the measurement's cap.
    early: usize,
    /// Cells non-periodic and contracting on the map, periodic in the long run.
    settled_later: usize,
    /// Cells chaotic on the map whose long run is not called chaotic although its exponent
    /// is positive beyond 4 standard errors: the two halves of the long measurement disagree,
    /// chaos that ends within it (a transient longer than the map's measurement).
    chaos_that_ends: usize,
}

/// The benchmark map (ζ = 0, μs = 3, w 0.2–0.6, β 3–14, 30 × 30) with `steady` and
/// `measure` against the long run (the full strobe search over 5000 periods, then a fixed
/// measurement of 5000 periods): a cell's verdict never contradicts the long run's where that
/// one is beyond 4 standard errors; classes and periods are those of the long run, except
/// where the map decided a motion contracting before it reached its orbit (the long run then
/// finds the orbit, contracting too), and where the map calls chaotic a motion whose long run
/// has an exponent positive beyond 4 standard errors too but is not called chaotic: the two
/// halves of its measurement disagree, chaos that ends within it. (At w = 0.3517, β = 12.10
/// the long run's exponent is 0.01639 ± 0.00005 and its class non-periodic; which cells
/// these are depends on the chaotic trajectories' last bits.)
fn compare_with_long_run(steady: SteadyOptions, measure: LyapunovOptions) -> Tally {
    let n = 30;
    let axis = |p, lo: f64, hi: f64| {
        let values = (0..n)
            .map(|i| lo + (hi - lo) * i as f64 / (n - 1) as f64)
            .collect();
        Axis::new(p, values).unwrap()
    };
    let experiment = Experiment::dimensionless(0.0, 0.3, 9.0)
        .unwrap()
        .with_mu_s(3.0)
        .unwrap();
    let map = Grid::new(
        &experiment,
        axis(Parameter::W, 0.2, 0.6),
        axis(Parameter::Beta, 3.0, 14.0),
    )
    .unwrap()
    .options(steady.with_lyapunov(Some(measure)).unwrap())
    .unwrap()
    .lyapunov(measure)
    .unwrap()
    .run(&())
    .unwrap();
    let long_measure = fixed(SteadyOptions::DEFAULT_LYAPUNOV);
    let long_options = SteadyOptions::default()
        .with_spectrum(false)
        .with_lyapunov(Some(long_measure))
        .unwrap();
    let mut tally = Tally::default();
    for point in &map.points {
        let long = steady_state_from(
            &exact_solver,
            &point.params,
            State::default(),
            &long_options,
        )
        .unwrap();
        let long_exponent = steady_exponent(&long, &long_measure).unwrap();
        let new_sign = point.lyapunov.map(|l| sign(&l, 4.0));
        let chaos_that_ends = point.class == MotionClass::Chaotic
            && long.period.is_none()
            && long_exponent.is_some_and(|old| sign(&old, 4.0) == 1);
        if chaos_that_ends && long.class != MotionClass::Chaotic {
            // The same verdict by the exponent; the long run's class stays non-periodic
            // because its measurement is undecided (its halves disagree).
            tally.chaos_that_ends += 1;
        } else if (point.class, point.period) != (long.class, long.period) && new_sign != Some(0) {
            // Decided contracting after the shortened search, before the motion reached its
            // orbit: non-periodic there, and contracting in the long run too.
            let new = point.lyapunov.expect("a measured exponent");
            assert!(point.period.is_none() && sign(&new, 4.0) == -1, "{point:?}");
            let old = long_exponent.expect("the long run's exponent");
            assert!(old.per_tau < -4.0 * old.error_per_tau, "{point:?}: {old:?}");
            tally.settled_later += 1;
        }
        let (Some(new), Some(old)) = (point.lyapunov, long_exponent) else {
            assert_eq!(point.lyapunov.is_some(), long_exponent.is_some());
            continue;
        };
        if old.per_tau.abs() > 4.0 * old.error_per_tau {
            tally.compared += 1;
            if sign(&new, 4.0) == 0 {
                tally.undecided += 1;
            } else {
                assert_eq!(
                    sign(&new, 4.0),
                    sign(&old, 4.0),
                    "{:?}: {new:?} against the long run's {old:?}",
                    point.params
                );
            }
        }
        if sign(&new, 4.0) == 1 {
            tally.chaotic += 1;
            let measured = point_measurement(&point.params, &steady, &measure);
            tally.early += usize::from(measured < measure.periods);
        }
    }
    tally
}

/// Drive periods the map's measurement of a chaotic cell ran (the shortened search, then the
/// sequential measurement).
fn point_measurement(params: &Params, steady: &SteadyOptions, measure: &LyapunovOptions) -> usize {
    let short = SteadyOptions {
        max_periods: stickslip::stability::SEARCH_BEFORE_MEASURING,
        lyapunov: None,
        ..*steady
    };
    let s = steady_state_from(&exact_solver, params, State::default(), &short).unwrap();
    lyapunov_exponents(params, s.final_state(), measure)
        .unwrap()
        .periods
}
