//! The Coulomb model has no Neimark–Sacker point (docs/bifurcation.md, "No Neimark–Sacker
//! point in the Coulomb model"): det M of the exact monodromy matrix is the product of the
//! slides' e^(−2ζΔτ) and the reversals' saltation determinants (|F| − 1)/(|F| + 1), below 1,
//! and 0 with a stop; `curve` refuses to follow a Neimark–Sacker point, naming why.

use stickslip::continuation::{curve, settled_orbit, ContinuationOptions, CurveSpec, Follow};
use stickslip::{Error, EventKind, Experiment, Parameter, State, Unsupported};

fn experiment(zeta: f64, mu_s: f64, w: f64, beta: f64) -> Experiment {
    Experiment::dimensionless(zeta, w, beta)
        .and_then(|e| e.with_mu_s(mu_s))
        .and_then(|e| e.with_initial(State { y: 0.0, v: 0.0 }))
        .expect("valid experiment")
}

/// det M from the proof: e^(−2ζ p T) times (|F| − 1)/(|F| + 1) at every turning point, F the
/// net force β cos(wτ + φ) − y there (a base at rest).
fn det_from_events(zeta: f64, mu_s: f64, w: f64, beta: f64) -> (f64, f64, usize) {
    let (params, orbit) = settled_orbit(&experiment(zeta, mu_s, w, beta)).expect("an orbit");
    assert!(
        orbit.stops.is_empty(),
        "{zeta} {mu_s} {w} {beta}: a sliding orbit"
    );
    let span = orbit.period as f64 * orbit.drive_period;
    let mut det = (-2.0 * zeta * span).exp();
    let mut turns = 0;
    for e in &orbit.events {
        assert_eq!(e.kind, EventKind::Turn);
        let force = params.beta * (params.w * e.tau + params.phi).cos() - e.y;
        assert!(
            force.abs() > params.mu_s,
            "a reversal needs |F| > μs: {force}"
        );
        det *= (force.abs() - 1.0) / (force.abs() + 1.0);
        turns += 1;
    }
    (orbit.monodromy.det(), det, turns)
}

#[test]
fn det_m_is_the_slides_and_reversals_product() {
    // Sliding orbits of period 1 (two turning points each) at ζ = 0, 0.05, 0.2 and μs = 1,
    // 1.5, 3, some with a complex pair (μ = 0.39 ± 0.21i at ζ = 0.05, μs = 1.5, w = 0.9,
    // β = 2); ζ = 0 near resonance, where det M comes nearest 1.
    let mut complex = 0;
    for (zeta, mu_s, w, beta) in [
        (0.0, 1.0, 0.9, 3.0),
        (0.0, 1.0, 1.1, 6.0),
        (0.05, 1.5, 0.9, 2.0),
        (0.046816, 1.0, 1.2, 3.0),
        (0.2, 3.0, 1.5, 8.0),
    ] {
        let (exact, product, turns) = det_from_events(zeta, mu_s, w, beta);
        assert!(turns >= 2, "{turns} turning points");
        assert!(
            (exact - product).abs() <= 1e-9 * product.abs().max(1e-3),
            "ζ = {zeta}, μs = {mu_s}, w = {w}, β = {beta}: det M = {exact}, product {product}"
        );
        assert!(exact > 0.0 && exact < 1.0, "det M = {exact}");
        let (_, orbit) = settled_orbit(&experiment(zeta, mu_s, w, beta)).unwrap();
        let m = orbit.multipliers;
        if m[0].im != 0.0 {
            complex += 1;
            // A complex pair has |μ|² = det M < 1: inside the unit circle.
            let modulus = m[0].re.hypot(m[0].im);
            assert!(
                (modulus * modulus - exact).abs() < 1e-9,
                "{modulus}² vs {exact}"
            );
        }
    }
    assert!(complex >= 1, "no orbit with a complex pair was checked");
}

#[test]
fn a_stop_makes_det_m_zero() {
    // Past the grazing at β = 1.4248 (ζ = 0.05, μs = 1.5, w = 0.9) the orbit stops twice.
    let (_, orbit) = settled_orbit(&experiment(0.05, 1.5, 0.9, 1.4)).expect("an orbit");
    assert!(!orbit.stops.is_empty(), "the orbit sticks");
    let det = orbit.monodromy.det();
    let norm = orbit
        .monodromy
        .0
        .iter()
        .flatten()
        .map(|x| x * x)
        .sum::<f64>();
    assert!(det.abs() <= 1e-12 * norm.max(1.0), "det M = {det}");
}

#[test]
fn a_neimark_sacker_curve_is_refused_with_the_reason() {
    let spec = CurveSpec {
        follow: Follow::NeimarkSacker,
        vary: Parameter::Beta,
        vary_to: 1.0,
        over: Parameter::W,
        from: 0.8,
        to: 1.0,
    };
    let e = experiment(0.05, 1.5, 0.9, 2.0);
    let err = curve(&e, &spec, &ContinuationOptions::default(), &()).unwrap_err();
    assert!(
        matches!(err, Error::Unsupported(Unsupported::NoNeimarkSacker)),
        "{err:?}"
    );
    let text = err.to_string();
    assert!(!text.contains('\n'), "one line: {text}");
    assert!(
        text.contains("det M") && text.contains("docs/bifurcation.md"),
        "{text}"
    );
}
