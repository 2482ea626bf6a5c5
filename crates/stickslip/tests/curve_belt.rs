//! Curves of special points on a forced Coulomb belt (vb > 0), in two parameters of which one
//! is the belt's speed: a fold and a period-doubling curve followed in vb over w and over β, a
//! grazing curve (a turning point at the static limit, whose net force carries the belt's
//! viscous term 2ζ·vb) followed in β over vb, and the belt's own border, a stop reached
//! tangentially (the slide only touches the belt's speed), followed in vb over β. Points of
//! each curve are checked against the special point (or the end) that the one-parameter
//! continuation finds independently at the curve's value of its other parameter, and against
//! the defining condition itself: a multiplier at +1 or −1, the event's margin at zero.

use stickslip::continuation::{
    continue_orbit, curve, settled_orbit, BorderKind, Branch, BranchEnd, ContinuationOptions,
    Curve, CurveEnd, CurvePoint, CurveSpec, Follow, Obstacle, SpecialKind,
};
use stickslip::solver::EventKind;
use stickslip::stability::{find_periodic_orbit, NewtonOptions};
use stickslip::{Experiment, Parameter, Params, State};

/// A forced Coulomb belt at drive phase φ, from rest.
fn belt(zeta: f64, w: f64, beta: f64, mu_s: f64, phi: f64, vb: f64) -> Experiment {
    Experiment::dimensionless(zeta, w, beta)
        .and_then(|e| e.with_phi(phi))
        .and_then(|e| e.with_mu_s(mu_s))
        .and_then(|e| e.with_vb(vb))
        .unwrap()
}

fn traced(experiment: &Experiment, spec: &CurveSpec) -> Curve {
    curve(experiment, spec, &ContinuationOptions::default(), &())
        .expect("no error")
        .unwrap_or_else(|no| panic!("no start: {no}"))
}

/// `count` points of the curve spread evenly over its indices (ends excluded).
fn spread(curve: &Curve, count: usize) -> Vec<usize> {
    let n = curve.points.len();
    assert!(n > 2 * count, "{n} points");
    (1..=count).map(|k| k * (n - 1) / (count + 1)).collect()
}

/// `base` with `parameter` at `value`.
fn with(base: &Experiment, parameter: Parameter, value: f64) -> Experiment {
    match parameter {
        Parameter::W => base.clone().with_w(value),
        Parameter::Beta => base.clone().with_beta(value),
        Parameter::Vb => base.clone().with_vb(value),
        other => panic!("{other:?} is not varied here"),
    }
    .unwrap()
}

/// The branch of one parameter, continued in `vary` from `start_vary` towards `vary_to` from
/// the orbit the motion settles on with `over` at `at`: independent of the curve.
fn branch_at(
    base: &Experiment,
    (over, at): (Parameter, f64),
    (vary, start_vary, vary_to): (Parameter, f64, f64),
) -> Branch {
    let e = with(&with(base, over, at), vary, start_vary);
    let (params, orbit) = settled_orbit(&e).unwrap();
    continue_orbit(
        &params,
        vary,
        &orbit,
        vary_to,
        &ContinuationOptions::default(),
        &(),
    )
    .unwrap()
}

/// The first located special point of `kind` on the branch.
fn first_special(branch: &Branch, kind: SpecialKind) -> Option<f64> {
    branch
        .special
        .iter()
        .find(|s| s.kind == kind && s.located)
        .map(|s| s.value)
}

/// The strobe state of `p`'s orbit as a start for Newton's method at belt speed `vb`: a
/// strobe inside a stop moves with the belt (y' = vb).
fn start_at(p: &CurvePoint, vb: f64) -> State {
    let s = p.orbit.state;
    if p.orbit.stuck_at_strobe {
        State { y: s.y, v: vb }
    } else {
        s
    }
}

/// The model's parameters at a curve point.
fn params_at(c: &Curve, p: &CurvePoint) -> Params {
    c.vary
        .set(c.over.set(c.params, p.over).unwrap(), p.vary)
        .unwrap()
}

/// The net force β cos(wτ + φ) − y − 2ζ·vb on a block at the belt's speed at (τ, y), written
/// out here apart from the library's.
fn net_force(p: &Params, tau: f64, y: f64) -> f64 {
    p.beta * (p.w * tau + p.phi).cos() - y - 2.0 * p.zeta * p.vb
}

/// The multiplier of `p`'s orbit nearest `target` (+1 or −1).
fn multiplier_near(p: &CurvePoint, target: f64) -> (f64, f64) {
    let m = p.orbit.multipliers;
    let near = if (m[0].re - target).abs() <= (m[1].re - target).abs() {
        m[0]
    } else {
        m[1]
    };
    (near.re, near.im)
}

/// The undamped belt ζ = 0, β = 1, μs = 1.5 at φ = 3: at w = 0.5 its period-1 orbit with one
/// stop folds back at vb ≈ 0.44739 (`tests/belt_continuation.rs`). The fold, followed in vb
/// over w and over β, passes through the fold that the continuation in vb locates at each
/// value of w (β), to 1e-7; a multiplier sits at +1 at every point.
#[test]
fn a_fold_curve_in_vb_passes_through_the_folds_continued_in_vb() {
    let base = belt(0.0, 0.5, 1.0, 1.5, 3.0, 0.3);
    let mut worst: f64 = 0.0;
    for (over, from, to) in [(Parameter::W, 0.47, 0.53), (Parameter::Beta, 0.97, 1.03)] {
        let spec = CurveSpec {
            follow: Follow::Fold,
            vary: Parameter::Vb,
            vary_to: 1.5,
            over,
            from,
            to,
        };
        let c = traced(&base, &spec);
        assert_eq!(c.begin, CurveEnd::Boundary { value: from });
        assert_eq!(c.end, CurveEnd::Boundary { value: to });
        assert!(c.points.len() >= 20, "{} points", c.points.len());
        for p in &c.points {
            assert_eq!((p.turns, p.stops), (0, 1), "{over:?} = {}", p.over);
            let (re, im) = multiplier_near(p, 1.0);
            assert!(
                (re - 1.0).abs() < 1e-6 && im == 0.0,
                "{:?}",
                p.orbit.multipliers
            );
        }
        // vb rises with w and with β along the fold.
        assert!(c.points.windows(2).all(|q| q[1].vary > q[0].vary));
        for i in spread(&c, 5) {
            let p = &c.points[i];
            let branch = branch_at(&base, (over, p.over), (Parameter::Vb, 0.3, 1.5));
            let fold = first_special(&branch, SpecialKind::Fold)
                .unwrap_or_else(|| panic!("no fold at {over:?} = {}", p.over));
            let error = (fold - p.vary).abs();
            worst = worst.max(error);
            assert!(
                error < 1e-7,
                "{over:?} = {}: curve vb = {} against the branch's fold at {fold}",
                p.over,
                p.vary
            );
        }
    }
    eprintln!("fold: largest |vb − vb_fold| {worst:e}");
}

/// The damped belt ζ = 0.05, w = 0.5, μs = 1.5 at φ = 0: at β = 1 its period-1 orbit doubles
/// its period as vb falls through ≈ 0.09801 (`tests/belt_continuation.rs`). Followed in vb
/// over β, the curve passes through the doubling that the continuation in vb locates at each
/// β, to 1e-7; a multiplier sits at −1 at every point, and Newton's orbits a hair either
/// side of the curve have it inside and outside the unit circle.
#[test]
fn a_period_doubling_curve_in_vb_passes_through_the_doublings_continued_in_vb() {
    let base = belt(0.05, 0.5, 1.0, 1.5, 0.0, 0.2);
    let spec = CurveSpec {
        follow: Follow::PeriodDoubling,
        vary: Parameter::Vb,
        vary_to: 0.06,
        over: Parameter::Beta,
        from: 0.9,
        to: 1.1,
    };
    let c = traced(&base, &spec);
    assert_eq!(c.begin, CurveEnd::Boundary { value: 0.9 });
    assert_eq!(c.end, CurveEnd::Boundary { value: 1.1 });
    for p in &c.points {
        assert_eq!((p.turns, p.stops), (0, 1), "β = {}", p.over);
        let (re, im) = multiplier_near(p, -1.0);
        assert!(
            (re + 1.0).abs() < 1e-6 && im == 0.0,
            "{:?}",
            p.orbit.multipliers
        );
    }
    let mut worst: f64 = 0.0;
    for i in spread(&c, 5) {
        let p = &c.points[i];
        let branch = branch_at(&base, (Parameter::Beta, p.over), (Parameter::Vb, 0.2, 0.06));
        let pd = first_special(&branch, SpecialKind::PeriodDoubling)
            .unwrap_or_else(|| panic!("no period doubling at β = {}", p.over));
        let error = (pd - p.vary).abs();
        worst = worst.max(error);
        assert!(
            error < 1e-7,
            "β = {}: curve vb = {} against the branch's doubling at {pd}",
            p.over,
            p.vary
        );
        // Above the curve in vb the multiplier lies inside the unit circle, below outside.
        for (dv, inside) in [(1e-5, true), (-1e-5, false)] {
            let at = Parameter::Vb.set(params_at(&c, p), p.vary + dv).unwrap();
            let o =
                find_periodic_orbit(&at, start_at(p, at.vb), 1, &NewtonOptions::default()).unwrap();
            let re = o.multipliers[0].re;
            assert_eq!(
                re > -1.0,
                inside,
                "β = {}, vb = {}: {re}",
                p.over,
                p.vary + dv
            );
        }
    }
    eprintln!("period doubling: largest |vb − vb_pd| {worst:e}");
}

/// The paper's ζ, μs = 1.5, w = 0.9 on a slow belt: the sliding orbit (two slip reversals a
/// period) gains a stop at one of its reversals as β falls (the belt breaks their symmetry:
/// on a base at rest both stick at once), where the net force there, with the
/// belt's viscous term, reaches the static limit: |β cos(wτ + φ) − y − 2ζ·vb| = μs. Followed
/// in β over vb, the curve passes through the grazing that the continuation in β locates at
/// each vb, to 1e-7; at every point the nearest reversal's margin is zero (to the curve's
/// offset onto the sliding side, 6e-11), and a hair above in β the orbit slides, below it
/// sticks.
#[test]
fn a_grazing_curve_over_vb_passes_through_the_grazings_continued_in_beta() {
    let base = belt(0.046816, 0.9, 1.45, 1.5, 0.0, 0.1)
        .with_initial(State { y: 0.25, v: 2.1 })
        .unwrap();
    let spec = CurveSpec {
        follow: Follow::Grazing,
        vary: Parameter::Beta,
        vary_to: 1.2,
        over: Parameter::Vb,
        from: 0.05,
        to: 0.2,
    };
    let c = traced(&base, &spec);
    assert_eq!(c.border.map(|b| b.kind), Some(BorderKind::TurnAtLimit));
    assert_eq!(c.begin, CurveEnd::Boundary { value: 0.05 });
    assert_eq!(c.end, CurveEnd::Boundary { value: 0.2 });
    let mut worst: f64 = 0.0;
    let mut worst_margin: f64 = 0.0;
    for p in &c.points {
        assert_eq!((p.turns, p.stops), (2, 0), "vb = {}", p.over);
        let params = params_at(&c, p);
        let margin = p
            .orbit
            .events
            .iter()
            .filter(|e| e.kind == EventKind::Turn)
            .map(|e| net_force(&params, e.tau, e.y).abs() - params.mu_s)
            .fold(f64::INFINITY, f64::min);
        worst_margin = worst_margin.max(margin.abs());
        assert!(
            (0.0..1e-9).contains(&margin),
            "vb = {}: the nearest reversal's margin {margin:e}",
            p.over
        );
    }
    for i in spread(&c, 5) {
        let p = &c.points[i];
        let branch = branch_at(&base, (Parameter::Vb, p.over), (Parameter::Beta, 1.45, 1.2));
        let grazing = first_special(&branch, SpecialKind::Grazing)
            .unwrap_or_else(|| panic!("no grazing at vb = {}", p.over));
        let error = (grazing - p.vary).abs();
        worst = worst.max(error);
        assert!(
            error < 1e-7,
            "vb = {}: curve β = {} against the branch's grazing at {grazing}",
            p.over,
            p.vary
        );
        // (The belt breaks the symmetry of the two reversals: one of them sticks first.)
        for (db, stops) in [(1e-6, 0), (-1e-6, 1)] {
            let at = Parameter::Beta.set(params_at(&c, p), p.vary + db).unwrap();
            let o = find_periodic_orbit(&at, p.orbit.state, 1, &NewtonOptions::default()).unwrap();
            assert_eq!(o.stops.len(), stops, "vb = {}, β = {}", p.over, p.vary + db);
        }
    }
    eprintln!("grazing: largest |β − β_grazing| {worst:e}, largest margin {worst_margin:e}");
}

/// The belt's own border: the damped belt ζ = 0.05, w = 0.5, β = 1, μs = 1.5 at φ = 0 reaches
/// the stop that follows its long slide ever more tangentially as vb rises, until at vb ≈
/// 0.43188 the slide only touches the belt's speed; past it the stop vanishes and the strobe
/// map jumps: the continuation in vb ends there, naming the stop reached tangentially
/// (`tests/belt_continuation.rs`). Continued past the stop as if it went on, the slide's slip
/// dips below zero and comes back; its lowest value rises to zero at the border, and the
/// curve follows that (a slide touching rest, on the stop's side) in vb over β. It passes
/// through the end of the continuation in vb at each β, to 1e-7; the slide arrives at the
/// belt's speed with y'' → 0; a hair below in vb the orbit keeps its stop, a hair above it
/// is gone.
#[test]
fn a_stop_reached_tangentially_is_followed_in_vb_over_beta() {
    let base = belt(0.05, 0.5, 1.0, 1.5, 0.0, 0.3);
    let spec = CurveSpec {
        follow: Follow::Grazing,
        vary: Parameter::Vb,
        vary_to: 0.6,
        over: Parameter::Beta,
        from: 0.9,
        to: 1.1,
    };
    let c = traced(&base, &spec);
    let border = c.border.expect("a grazing curve's border");
    assert_eq!(
        (border.kind, border.variant),
        (BorderKind::SlideTouchesRest, true)
    );
    assert_eq!(c.begin, CurveEnd::Boundary { value: 0.9 });
    assert_eq!(c.end, CurveEnd::Boundary { value: 1.1 });
    let mut worst: f64 = 0.0;
    let mut worst_acceleration: f64 = 0.0;
    for p in &c.points {
        assert_eq!((p.turns, p.stops), (0, 1), "β = {}", p.over);
        // Arriving at the belt's speed from the slide, y'' = net force − sgn(slip).
        let params = params_at(&c, p);
        let stick = p
            .orbit
            .events
            .iter()
            .find(|e| e.kind == EventKind::Stick)
            .unwrap();
        let net = net_force(&params, stick.tau, stick.y);
        let acceleration = (net - 1.0).abs().min((net + 1.0).abs());
        worst_acceleration = worst_acceleration.max(acceleration);
        assert!(
            acceleration < 1e-3,
            "β = {}: y'' = {acceleration:e}",
            p.over
        );
    }
    for i in spread(&c, 5) {
        let p = &c.points[i];
        let branch = branch_at(&base, (Parameter::Beta, p.over), (Parameter::Vb, 0.3, 0.6));
        let (end, obstacle) = match branch.end {
            BranchEnd::Failed { value, obstacle }
            | BranchEnd::Stalled {
                value, obstacle, ..
            } => (value, obstacle),
            other => panic!("β = {}: {other:?}", p.over),
        };
        assert!(
            matches!(obstacle, Obstacle::TangentialStick { .. }),
            "β = {}: {obstacle:?}",
            p.over
        );
        let error = (end - p.vary).abs();
        worst = worst.max(error);
        assert!(
            error < 1e-7,
            "β = {}: curve vb = {} against the branch's end at {end}",
            p.over,
            p.vary
        );
        // A hair below the curve the orbit keeps its stop; above, Newton's method from the
        // curve's orbit finds none with a stop near it.
        let at = |dv: f64| Parameter::Vb.set(params_at(&c, p), p.vary + dv).unwrap();
        let below = find_periodic_orbit(
            &at(-1e-6),
            start_at(p, p.vary - 1e-6),
            1,
            &NewtonOptions::default(),
        )
        .unwrap();
        assert_eq!(below.stops.len(), 1, "β = {}", p.over);
        let above = find_periodic_orbit(
            &at(1e-6),
            start_at(p, p.vary + 1e-6),
            1,
            &NewtonOptions::default(),
        );
        assert!(
            above.as_ref().map_or(true, |o| o.stops.is_empty()
                || (o.state.y - p.orbit.state.y).abs() > 1e-3),
            "β = {}: {above:?}",
            p.over
        );
    }
    eprintln!(
        "tangential stick: largest |vb − branch end| {worst:e}, largest y'' on arrival \
         {worst_acceleration:e}"
    );
}
