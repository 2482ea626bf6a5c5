//! Tests of curves of special points in two parameters: the grazing curve of the sliding orbit
//! at μs = 1 against the exact stick-slip boundary β_c(w) of `theory`, and fold, grazing and
//! period-doubling curves against the special points that the one-parameter continuation
//! locates at fixed values of the curve's own parameter; the strobe map's exact parameter
//! derivatives against difference quotients.

use stickslip::continuation::{
    continue_orbit, curve, curve_within, settled_orbit, BorderKind, Codim2Kind,
    ContinuationOptions, Curve, CurveEnd, CurveReport, CurveSpec, Follow, SpecialKind,
    SpecialPoint,
};
use stickslip::stability::{find_periodic_orbit, NewtonOptions};
use stickslip::theory::stick_slip_boundary;
use stickslip::{Experiment, Parameter, State};

const PAPER_ZETA: f64 = 0.046816;

fn experiment(zeta: f64, mu_s: f64, w: f64, beta: f64, start: State) -> Experiment {
    Experiment::dimensionless(zeta, w, beta)
        .and_then(|e| e.with_mu_s(mu_s))
        .and_then(|e| e.with_initial(start))
        .expect("valid experiment")
}

fn traced(experiment: &Experiment, spec: &CurveSpec) -> Curve {
    curve(experiment, spec, &ContinuationOptions::default(), &())
        .expect("no error")
        .unwrap_or_else(|no| panic!("no start: {no}"))
}

/// `base` with `parameter` (w or β) at `value`.
fn with(base: &Experiment, parameter: Parameter, value: f64) -> Experiment {
    match parameter {
        Parameter::W => base.clone().with_w(value),
        Parameter::Beta => base.clone().with_beta(value),
        other => panic!("{other:?} is not varied here"),
    }
    .unwrap()
}

/// `count` points of the curve spread evenly over its indices (ends excluded).
fn spread(curve: &Curve, count: usize) -> Vec<usize> {
    let n = curve.points.len();
    assert!(n > 2 * count, "{n} points");
    (1..=count).map(|k| k * (n - 1) / (count + 1)).collect()
}

/// The special point of `kind` that the one-parameter continuation in `vary` locates at the
/// curve point's value of `over`, from the orbit the motion settles on at (`over`, `vary` =
/// `start_vary`), continued towards `vary_to`; `None` when it finds none.
fn located(
    base: &Experiment,
    over: Parameter,
    at: f64,
    vary: Parameter,
    start_vary: f64,
    vary_to: f64,
    kind: SpecialKind,
) -> Option<f64> {
    located_where(base, over, at, vary, start_vary, vary_to, kind, &|_| true)
}

/// [`located`], the first special point of `kind` that also satisfies `which`.
#[allow(clippy::too_many_arguments)]
fn located_where(
    base: &Experiment,
    over: Parameter,
    at: f64,
    vary: Parameter,
    start_vary: f64,
    vary_to: f64,
    kind: SpecialKind,
    which: &dyn Fn(&SpecialPoint) -> bool,
) -> Option<f64> {
    let e = with(&with(base, over, at), vary, start_vary);
    let (params, orbit) = settled_orbit(&e).unwrap();
    let branch = continue_orbit(
        &params,
        vary,
        &orbit,
        vary_to,
        &ContinuationOptions::default(),
        &(),
    )
    .unwrap();
    branch
        .special
        .iter()
        .find(|s| s.kind == kind && s.located && which(s))
        .map(|s| s.value)
}

#[test]
fn a_range_of_the_varied_parameter_ends_the_curve_where_it_is_left() {
    // The exact stick-slip boundary β_c(w) dips near resonance: kept below a β between its
    // value at the start (w = 1.2) and at the ends of w's range, the curve ends on both sides
    // where β reaches that value, inside w's range, every point still on β_c.
    let e = experiment(PAPER_ZETA, 1.0, 1.2, 3.0, State { y: 0.0, v: 0.0 });
    let spec = CurveSpec {
        follow: Follow::Grazing,
        vary: Parameter::Beta,
        vary_to: 0.5,
        over: Parameter::W,
        from: 0.6,
        to: 2.0,
    };
    let whole = traced(&e, &spec);
    let at_start = whole.points[whole.start].vary;
    let ends = whole.points[0].vary.min(whole.points.last().unwrap().vary);
    assert!(
        at_start < ends,
        "β {at_start} at the start, {ends} at the ends"
    );
    let top = 0.5 * (at_start + ends);
    let c = curve_within(
        &e,
        &spec,
        Some((top, 0.0)),
        &ContinuationOptions::default(),
        &(),
    )
    .expect("no error")
    .unwrap_or_else(|no| panic!("no start: {no}"));
    assert_eq!(c.begin, CurveEnd::Boundary { value: top });
    assert_eq!(c.end, CurveEnd::Boundary { value: top });
    let (first, last) = (&c.points[0], c.points.last().unwrap());
    assert!((first.vary - top).abs() <= 1e-12 * top, "{}", first.vary);
    assert!((last.vary - top).abs() <= 1e-12 * top, "{}", last.vary);
    assert!(0.6 < first.over && last.over < 2.0);
    assert!(c.points.len() >= 10 && c.points.len() < whole.points.len());
    for p in &c.points {
        assert!(p.vary <= top * (1.0 + 1e-12), "β = {} above {top}", p.vary);
        let exact = stick_slip_boundary(PAPER_ZETA, p.over, 1.0).unwrap().beta_c;
        assert!(
            (p.vary - exact).abs() < 1e-8,
            "w = {}: β = {}",
            p.over,
            p.vary
        );
    }
    // A range of β that does not hold the start's β is refused.
    let outside = curve_within(
        &e,
        &spec,
        Some((top + 1.0, top + 2.0)),
        &ContinuationOptions::default(),
        &(),
    );
    assert!(outside.is_err());
}

#[test]
fn the_grazing_curve_at_mu_s_1_is_the_exact_stick_slip_boundary() {
    // The sliding orbit of the paper's circuit at w = 1.2, β = 3: a stop appears at its
    // turning points where β falls to β_c(w), the closed form of `theory`.
    let e = experiment(PAPER_ZETA, 1.0, 1.2, 3.0, State { y: 0.0, v: 0.0 });
    let spec = CurveSpec {
        follow: Follow::Grazing,
        vary: Parameter::Beta,
        vary_to: 0.5,
        over: Parameter::W,
        from: 0.6,
        to: 2.0,
    };
    let c = traced(&e, &spec);
    assert_eq!(c.border.map(|b| b.kind), Some(BorderKind::TurnAtLimit));
    assert_eq!(c.begin, CurveEnd::Boundary { value: 0.6 });
    assert_eq!(c.end, CurveEnd::Boundary { value: 2.0 });
    assert_eq!(c.points.first().unwrap().over, 0.6);
    assert_eq!(c.points.last().unwrap().over, 2.0);
    assert!(c.points.len() >= 40, "{} points", c.points.len());
    let mut worst: f64 = 0.0;
    for p in &c.points {
        let exact = stick_slip_boundary(PAPER_ZETA, p.over, 1.0).unwrap().beta_c;
        let error = (p.vary - exact).abs();
        worst = worst.max(error);
        assert!(
            error < 1e-8,
            "w = {}: β = {} against β_c = {exact} ({error:e})",
            p.over,
            p.vary
        );
        // Every point is the sliding orbit: two turning points, no stop.
        assert_eq!((p.turns, p.stops), (2, 0), "w = {}", p.over);
    }
    // The points go along w in order, and the curve's minimum lies inside (β_c dips near
    // resonance).
    assert!(c.points.windows(2).all(|p| p[1].over > p[0].over));
    let min = c
        .points
        .iter()
        .map(|p| p.vary)
        .fold(f64::INFINITY, f64::min);
    assert!(min < c.points[0].vary && min < c.points.last().unwrap().vary);
    eprintln!(
        "largest |β − β_c| over {} points: {worst:e}",
        c.points.len()
    );
}

/// The curve of `follow` at the paper's ζ, μs = 1.5, followed in β over w from 0.8 to 1,
/// from the sliding orbit at w = 0.9, β = 1.45.
fn mu_s_15_curve(follow: Follow) -> (Experiment, Curve) {
    let e = experiment(PAPER_ZETA, 1.5, 0.9, 1.45, State { y: 0.25, v: 2.1 });
    let spec = CurveSpec {
        follow,
        vary: Parameter::Beta,
        vary_to: 1.2,
        over: Parameter::W,
        from: 0.8,
        to: 1.0,
    };
    let c = traced(&e, &spec);
    (e, c)
}

#[test]
fn the_fold_curve_at_mu_s_1_5_passes_through_the_located_folds() {
    let (e, c) = mu_s_15_curve(Follow::Fold);
    assert_eq!(c.begin, CurveEnd::Boundary { value: 0.8 });
    assert_eq!(c.end, CurveEnd::Boundary { value: 1.0 });
    // The fold of the orbit with two stops: one multiplier at +1.
    for p in &c.points {
        assert_eq!((p.turns, p.stops), (0, 2));
        let m = p.orbit.multipliers;
        let one = if (m[0].re - 1.0).abs() < (m[1].re - 1.0).abs() {
            m[0]
        } else {
            m[1]
        };
        assert!((one.re - 1.0).abs() < 1e-6 && one.im == 0.0, "{m:?}");
    }
    for i in spread(&c, 6) {
        let p = &c.points[i];
        // From the sliding orbit above the grazing and the fold, down in β.
        let fold = located(
            &e,
            Parameter::W,
            p.over,
            Parameter::Beta,
            1.7,
            1.1,
            SpecialKind::Fold,
        )
        .unwrap_or_else(|| panic!("no fold located at w = {}", p.over));
        assert!(
            (fold - p.vary).abs() < 1e-7,
            "w = {}: curve β = {} against the branch's fold at {fold}",
            p.over,
            p.vary
        );
    }
}

#[test]
fn the_grazing_curve_at_mu_s_1_5_passes_through_the_located_grazings() {
    let (e, c) = mu_s_15_curve(Follow::Grazing);
    assert_eq!(c.border.map(|b| b.kind), Some(BorderKind::TurnAtLimit));
    assert_eq!(c.begin, CurveEnd::Boundary { value: 0.8 });
    assert_eq!(c.end, CurveEnd::Boundary { value: 1.0 });
    for i in spread(&c, 6) {
        let p = &c.points[i];
        assert_eq!((p.turns, p.stops), (2, 0));
        let grazing = located(
            &e,
            Parameter::W,
            p.over,
            Parameter::Beta,
            1.7,
            1.1,
            SpecialKind::Grazing,
        )
        .unwrap_or_else(|| panic!("no grazing located at w = {}", p.over));
        assert!(
            (grazing - p.vary).abs() < 1e-7,
            "w = {}: curve β = {} against the branch's grazing at {grazing}",
            p.over,
            p.vary
        );
        // And a direct check: just above the curve the orbit slides, just below it sticks.
        for (db, stops) in [(1e-6, 0), (-1e-6, 2)] {
            let at = Parameter::Beta
                .set(Parameter::W.set(c.params, p.over).unwrap(), p.vary + db)
                .unwrap();
            let o = find_periodic_orbit(&at, p.orbit.state, 1, &NewtonOptions::default()).unwrap();
            assert_eq!(o.stops.len(), stops, "w = {}, β = {}", p.over, p.vary + db);
        }
    }
}

#[test]
fn the_period_doubling_curve_at_mu_s_3_passes_through_the_located_doublings() {
    // The period-1 orbit with one stop at ζ = 0, μs = 3, w = 0.6, β = 3.269 doubles its period
    // as w rises; followed in w over β.
    let e = experiment(0.0, 3.0, 0.6, 3.269, State { y: 4.9, v: 0.0 });
    let spec = CurveSpec {
        follow: Follow::PeriodDoubling,
        vary: Parameter::W,
        vary_to: 0.7,
        over: Parameter::Beta,
        from: 3.1,
        to: 3.4,
    };
    let c = traced(&e, &spec);
    assert_eq!(c.begin, CurveEnd::Boundary { value: 3.1 });
    assert_eq!(c.end, CurveEnd::Boundary { value: 3.4 });
    for p in &c.points {
        assert!((p.orbit.multipliers[0].re + 1.0).abs() < 1e-6);
    }
    for i in spread(&c, 6) {
        let p = &c.points[i];
        let pd = located(
            &e,
            Parameter::Beta,
            p.over,
            Parameter::W,
            0.6,
            0.7,
            SpecialKind::PeriodDoubling,
        )
        .unwrap_or_else(|| panic!("no period doubling located at β = {}", p.over));
        assert!(
            (pd - p.vary).abs() < 1e-7,
            "β = {}: curve w = {} against the branch's period doubling at {pd}",
            p.over,
            p.vary
        );
    }
}

#[test]
fn the_report_holds_the_curve() {
    let (_, c) = mu_s_15_curve(Follow::Fold);
    let report = CurveReport::from(&c);
    assert_eq!(report.points, c.points.len());
    assert_eq!(report.over, "w");
    assert_eq!(report.vary, "beta");
    assert_eq!(report.start.over, 0.9);
    assert_eq!(report.start.vary, c.points[c.start].vary);
    let json = serde_json::to_value(&report).unwrap();
    assert_eq!(json["follow"], "fold");
    assert_eq!(json["end"]["reason"], "boundary");
}

#[test]
fn no_special_point_of_the_kind_is_said() {
    // The sliding orbit at μs = 1.5 has no period doubling between β = 1.45 and 1.44.
    let e = experiment(PAPER_ZETA, 1.5, 0.9, 1.45, State { y: 0.25, v: 2.1 });
    let spec = CurveSpec {
        follow: Follow::PeriodDoubling,
        vary: Parameter::Beta,
        vary_to: 1.44,
        over: Parameter::W,
        from: 0.8,
        to: 1.0,
    };
    let no = curve(&e, &spec, &ContinuationOptions::default(), &())
        .unwrap()
        .unwrap_err();
    let text = no.to_string();
    assert!(
        text.contains("period doubling") && text.contains("1.44"),
        "{text}"
    );
    // A model's value of Q outside the range is refused with its name.
    let spec = CurveSpec {
        from: 1.0,
        to: 1.2,
        ..spec
    };
    assert!(matches!(
        curve(&e, &spec, &ContinuationOptions::default(), &()),
        Err(stickslip::Error::InvalidParameter { name: "w", .. })
    ));
}

#[test]
fn the_strobe_maps_parameter_derivatives_are_its_difference_quotients() {
    use stickslip::stability::{strobe_map, strobe_map_parameter_derivatives};
    // States off any orbit, μs = 1 and 1.5, over one and two drive periods.
    for (mu_s, w, beta, state, periods) in [
        (1.0, 0.9, 1.6, State { y: 0.3, v: 1.0 }, 1),
        (1.5, 0.9, 1.35, State { y: 0.25, v: 2.1 }, 1),
        (1.5, 0.7, 1.2, State { y: -0.4, v: 0.5 }, 2),
    ] {
        let p = stickslip::Params::new(PAPER_ZETA, w, beta)
            .and_then(|p| p.with_mu_s(mu_s))
            .unwrap();
        let d = strobe_map_parameter_derivatives(&p, state, periods).unwrap();
        // Columns 1 (β) and 2 (w) of (zeta, beta, w, phi, mu_s).
        for (column, parameter) in [(1, Parameter::Beta), (2, Parameter::W)] {
            let h = 1e-6;
            let at = |x: f64| {
                let q = parameter.set(p, parameter.get(&p) + x).unwrap();
                strobe_map(&q, state, periods).unwrap().state
            };
            let (a, b) = (at(h), at(-h));
            let fd = [(a.y - b.y) / (2.0 * h), (a.v - b.v) / (2.0 * h)];
            for r in 0..2 {
                assert!(
                    (d[r][column] - fd[r]).abs() <= 1e-5 * (1.0 + fd[r].abs()),
                    "mu_s {mu_s}, w {w}, beta {beta}, {parameter:?}, row {r}: {} against {}",
                    d[r][column],
                    fd[r]
                );
            }
        }
    }
}

/// The curve of `follow` at ζ = 0, μs = 3, followed in w over β from `from` to `to`, from the
/// orbit the motion settles on at (w, β) from `start`, continued in w towards 0.7.
fn mu_s_3_curve(
    follow: Follow,
    (w, beta): (f64, f64),
    start: State,
    (from, to): (f64, f64),
) -> (Experiment, Curve) {
    let e = experiment(0.0, 3.0, w, beta, start);
    let spec = CurveSpec {
        follow,
        vary: Parameter::W,
        vary_to: 0.7,
        over: Parameter::Beta,
        from,
        to,
    };
    let c = traced(&e, &spec);
    (e, c)
}

#[test]
fn the_grazing_curve_at_mu_s_3_passes_through_the_located_grazings() {
    // The period-1 orbit with one stop at w = 0.6 loses its stop as w rises: the sliding orbit
    // (two turning points) grazes the static limit along this curve.
    let (e, c) = mu_s_3_curve(
        Follow::Grazing,
        (0.6, 3.269),
        State { y: 4.9, v: 0.0 },
        (3.1, 4.4),
    );
    assert_eq!(c.border.map(|b| b.kind), Some(BorderKind::TurnAtLimit));
    assert_eq!(c.begin, CurveEnd::Boundary { value: 3.1 });
    assert_eq!(c.end, CurveEnd::Boundary { value: 4.4 });
    for p in &c.points {
        assert_eq!((p.turns, p.stops), (2, 0), "β = {}", p.over);
    }
    for i in spread(&c, 6) {
        let p = &c.points[i];
        // On its way from the stop orbit the branch passes through orbits with two stops and
        // back before the stop disappears: the grazing into the sliding orbit is the curve's.
        let grazing = located_where(
            &e,
            Parameter::Beta,
            p.over,
            Parameter::W,
            0.6,
            0.75,
            SpecialKind::Grazing,
            &|s| (s.after.turns, s.after.stops) == (2, 0),
        )
        .unwrap_or_else(|| panic!("no grazing located at β = {}", p.over));
        assert!(
            (grazing - p.vary).abs() < 1e-7,
            "β = {}: curve w = {} against the branch's grazing at {grazing}",
            p.over,
            p.vary
        );
    }
}

#[test]
fn the_fold_curve_at_mu_s_3_passes_through_the_located_folds() {
    // A period-3 orbit with two stops in its three drive periods, settled on at w = 0.62,
    // β = 4.3, folds as w rises.
    let (e, c) = mu_s_3_curve(
        Follow::Fold,
        (0.62, 4.3),
        State { y: 0.0, v: 0.0 },
        (4.0, 4.8),
    );
    assert_eq!(c.period, 3);
    assert_eq!(c.begin, CurveEnd::Boundary { value: 4.0 });
    assert_eq!(c.end, CurveEnd::Boundary { value: 4.8 });
    for p in &c.points {
        let m = p.orbit.multipliers;
        assert!(
            m.iter().any(|m| (m.re - 1.0).abs() < 1e-6 && m.im == 0.0),
            "{m:?}"
        );
    }
    for i in spread(&c, 6) {
        let p = &c.points[i];
        let fold = located(
            &e,
            Parameter::Beta,
            p.over,
            Parameter::W,
            0.62,
            0.7,
            SpecialKind::Fold,
        )
        .unwrap_or_else(|| panic!("no fold located at β = {}", p.over));
        assert!(
            (fold - p.vary).abs() < 1e-7,
            "β = {}: curve w = {} against the branch's fold at {fold}",
            p.over,
            p.vary
        );
    }
}

#[test]
fn the_period_doubling_grazing_point_is_reached_from_both_curves() {
    // At ζ = 0, μs = 3 the grazing curve of the sliding orbit meets the period doubling of the
    // orbit with one stop across it; the period-doubling curve of that orbit, followed over β
    // from 2 to 6, ends there (it passes through the grazing onto the orbit's mirror image,
    // whose curve in (β, w) is the same, and must not trace it back).
    let (_, grazing) = mu_s_3_curve(
        Follow::Grazing,
        (0.6, 3.269),
        State { y: 4.9, v: 0.0 },
        (3.1, 4.6),
    );
    let kinds: Vec<_> = grazing.codim2.iter().map(|c| c.kind).collect();
    assert_eq!(
        kinds,
        [Codim2Kind::PeriodDoublingGrazing, Codim2Kind::FoldGrazing],
        "{:?}",
        grazing.codim2
    );
    // Each where the curve found it (not another meeting far along the curves).
    let pdg = &grazing.codim2[0];
    let fg = &grazing.codim2[1];
    assert!(pdg.located && fg.located);
    assert!((pdg.over - 3.5667484).abs() < 1e-6 && (pdg.vary - 0.6815310).abs() < 1e-6);
    assert!((fg.over - 4.4919836).abs() < 1e-6 && (fg.vary - 0.6354210).abs() < 1e-6);

    let e = experiment(0.0, 3.0, 0.6, 3.269, State { y: 4.9, v: 0.0 });
    let spec = CurveSpec {
        follow: Follow::PeriodDoubling,
        vary: Parameter::W,
        vary_to: 0.7,
        over: Parameter::Beta,
        from: 2.0,
        to: 6.0,
    };
    let pd = traced(&e, &spec);
    for p in &pd.points {
        assert!(
            (p.orbit.multipliers[0].re + 1.0).abs() < 1e-6,
            "β = {}",
            p.over
        );
        assert_eq!((p.turns, p.stops), (1, 1), "β = {}", p.over);
    }
    let CurveEnd::Codim2 { kind, over, vary } = pd.end else {
        panic!("ends {:?}", pd.end);
    };
    assert_eq!(kind, Codim2Kind::PeriodDoublingGrazing);
    let last = pd.codim2.last().unwrap();
    assert_eq!((last.kind, last.over, last.vary), (kind, over, vary));
    assert!(
        (over - pdg.over).abs() < 1e-7 && (vary - pdg.vary).abs() < 1e-7,
        "from the period-doubling curve ({over}, {vary}), from the grazing curve ({}, {})",
        pdg.over,
        pdg.vary
    );
    // The curve's last point is next to it, not back near β = 2.32.
    let end = pd.points.last().unwrap();
    assert!(
        (end.over - over).abs() < 1e-6,
        "last point at β = {}",
        end.over
    );
}
