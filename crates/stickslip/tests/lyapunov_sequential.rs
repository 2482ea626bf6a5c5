//! Exponents that stop when they know: the sequential measurement of the largest Lyapunov
//! exponent gives the verdict of the fixed-length measurement it replaces wherever that one is
//! beyond 4 standard errors, and stops early where the verdict is clear.

use stickslip::scan::{Axis, Grid};
use stickslip::stability::{
    lyapunov_exponents, steady_exponent, Estimate, LyapunovOptions, NonperiodicClassification,
    NonperiodicVerdict,
};
use stickslip::steady::{exact_solver, steady_state_from, SteadyOptions};
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
/// it reached its orbit (the long run then finds the orbit, contracting too).
#[test]
fn the_exponent_map_keeps_every_verdict_of_the_long_run() {
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
    let steady = SteadyOptions::default().with_spectrum(false);
    let measure = SteadyOptions::DEFAULT_LYAPUNOV;
    let map = Grid::new(
        &experiment,
        axis(Parameter::W, 0.2, 0.6),
        axis(Parameter::Beta, 3.0, 14.0),
    )
    .unwrap()
    .options(steady)
    .unwrap()
    .lyapunov(measure)
    .unwrap()
    .run(&())
    .unwrap();
    let long_options = steady.with_lyapunov(Some(fixed(measure))).unwrap();
    let (mut compared, mut chaotic, mut early, mut settled_later) = (0, 0, 0, 0);
    for point in &map.points {
        let long = steady_state_from(
            &exact_solver,
            &point.params,
            State::default(),
            &long_options,
        )
        .unwrap();
        let long_exponent = steady_exponent(&long, &fixed(measure)).unwrap();
        if (point.class, point.period) != (long.class, long.period) {
            // Decided contracting after the shortened search, before the motion reached its
            // orbit: non-periodic there, and contracting in the long run too.
            let new = point.lyapunov.expect("a measured exponent");
            assert!(point.period.is_none() && sign(&new, 4.0) == -1, "{point:?}");
            let old = long_exponent.expect("the long run's exponent");
            assert!(old.per_tau < -4.0 * old.error_per_tau, "{point:?}: {old:?}");
            settled_later += 1;
        }
        let (Some(new), Some(old)) = (point.lyapunov, long_exponent) else {
            assert_eq!(point.lyapunov.is_some(), long_exponent.is_some());
            continue;
        };
        if old.per_tau.abs() > 4.0 * old.error_per_tau {
            compared += 1;
            assert_eq!(
                sign(&new, 4.0),
                sign(&old, 4.0),
                "{:?}: {new:?} against the long run's {old:?}",
                point.params
            );
        }
        if sign(&new, 4.0) == 1 {
            chaotic += 1;
            let measured = point_measurement(&point.params, &steady);
            early += usize::from(measured < measure.periods);
        }
    }
    assert!(compared > 850, "{compared} cells compared");
    assert!(chaotic > 100, "{chaotic} chaotic cells");
    assert_eq!(early, chaotic, "every chaotic cell decided before the cap");
    // The cells whose motion reaches a periodic orbit between the shortened search and the
    // full one are few.
    assert!(settled_later <= 30, "{settled_later} cells settled later");
}

/// Drive periods the map's measurement of a chaotic cell ran (the shortened search, then the
/// sequential measurement).
fn point_measurement(params: &Params, steady: &SteadyOptions) -> usize {
    let short = SteadyOptions {
        max_periods: stickslip::stability::SEARCH_BEFORE_MEASURING,
        lyapunov: None,
        ..*steady
    };
    let s = steady_state_from(&exact_solver, params, State::default(), &short).unwrap();
    lyapunov_exponents(params, s.final_state(), &SteadyOptions::DEFAULT_LYAPUNOV)
        .unwrap()
        .periods
}
