//! Fitting the friction law of a mechanical oscillator on a moving belt: records of the drive
//! force F (N) and the displacement r (m) made by an independent integrator (the test kit's
//! Runge–Kutta oracle, [`stickslip_testkit::oracle`], not the library's friction solver), of a
//! forced Stribeck belt with known μs, Stribeck speed and viscous friction, quantised to 8
//! bits with noise; fitted from other starting values with the belt speed, m, k, γ and F0
//! given. The fit recovers μs, the Stribeck speed and the viscous friction within their 95 %
//! intervals; a record whose slip never comes near zero does not show the Stribeck speed, and
//! the fit says so instead of giving it an error bar; a Coulomb belt's kinetic level and μs;
//! a law's parameter on an oscillator without that law is refused.

use std::f64::consts::TAU;
use stickslip::experiment::{Experiment, Key};
use stickslip::fit::{
    fit_records, FitError, FitOptions, FitParameter, FitReport, Interval, Jacobian,
};
use stickslip::friction::FrictionLaw;
use stickslip::measure::{read_scope, Measurement};
use stickslip::physical::Mechanics;
use stickslip::steady::MotionClass;
use stickslip_testkit::oracle::{Oracle, OracleLaw};
use stickslip_testkit::{quantise, timed, Rng, Synthetic};

/// m = 0.5 kg, k = 200 N/m (ω0 = 20 rad/s), γ = 0.8 N·s/m (ζ = 0.04), F0 = 0.3 N: a
/// displacement scale F0/k of 1.5 mm and a velocity scale F0/k·ω0 of 0.03 m/s.
const MASS: f64 = 0.5;
const STIFFNESS: f64 = 200.0;
const GAMMA: f64 = 0.8;
const F0: f64 = 0.3;
/// The velocity scale (m/s).
const VELOCITY: f64 = F0 / STIFFNESS * 20.0;

/// The belt's truth, in physical units: belt speed (m/s), μs, Stribeck speed (m/s),
/// exponent, viscous friction (N·s/m).
#[derive(Debug, Clone, Copy)]
struct Belt {
    belt_speed: f64,
    mu_s: f64,
    stribeck_speed: f64,
    delta: f64,
    viscous: f64,
}

/// vb = 0.3, vs = 0.5, δ = 2, η = 0.05 in the dimensionless units; μs = 1.5.
const TRUTH: Belt = Belt {
    belt_speed: 0.3 * VELOCITY,
    mu_s: 1.5,
    stribeck_speed: 0.5 * VELOCITY,
    delta: 2.0,
    viscous: 0.05 * F0 / VELOCITY,
};

fn mechanics(friction: f64) -> Mechanics {
    Mechanics::new(MASS, STIFFNESS, GAMMA, friction).unwrap()
}

/// The oscillator on `belt` with the Stribeck law, from the physical values through the key
/// table's images.
fn stribeck(belt: Belt) -> Experiment {
    let m = mechanics(F0);
    let s = m.scales();
    let image = |key: Key, v: f64| key.image(v, &s).unwrap();
    Experiment::mechanics(m)
        .unwrap()
        .with_mu_s(belt.mu_s)
        .unwrap()
        .with_vb(image(Key::BeltSpeed, belt.belt_speed))
        .unwrap()
        .with_law(FrictionLaw::Stribeck {
            vs: image(Key::StribeckSpeed, belt.stribeck_speed),
            delta: belt.delta,
            eta: image(Key::ViscousFriction, belt.viscous),
        })
        .unwrap()
}

/// A plain CSV (`time_s,F (N),r (m)`) of the oracle's motion of `truth` driven at (w, β, φ):
/// 60 drive periods from rest to settle, then 2400 samples over 3.4 drive periods, each
/// channel quantised to 8 bits of a screen 1.25 times its peak-to-peak with one step of
/// Gaussian noise.
fn record(
    truth: &Experiment,
    law: OracleLaw,
    w: f64,
    beta: f64,
    phi: f64,
    rng: &mut Rng,
) -> String {
    let e = truth
        .clone()
        .with_w(w)
        .and_then(|e| e.with_beta(beta))
        .and_then(|e| e.with_phi(phi))
        .unwrap();
    let p = e.params().unwrap();
    let scales = e.scales().unwrap();
    let period = TAU / w;
    let settle = 60.0 * period;
    let n = 2400;
    let dtau = 3.4 * period / n as f64;
    let taus: Vec<f64> = (0..n).map(|k| settle + k as f64 * dtau).collect();
    let mut oracle = Oracle::new(p, law, 5e-4, 0.0, 0.0);
    let y = oracle.sample(&taus);
    let force: Vec<f64> = taus
        .iter()
        .map(|&tau| beta * scales.force * (w * tau + phi).cos())
        .collect();
    let displacement: Vec<f64> = y.iter().map(|y| y * scales.position).collect();
    let force = quantise(&force, 256.0, 1.0, rng);
    let displacement = quantise(&displacement, 256.0, 1.0, rng);
    timed(
        &Synthetic::new(force, displacement, 0.0, dtau / scales.omega0),
        "time_s,F (N),r (m)\n",
    )
}

fn oracle_law(e: &Experiment) -> OracleLaw {
    match e.friction_law() {
        FrictionLaw::Coulomb => OracleLaw::Coulomb,
        FrictionLaw::Stribeck { vs, delta, eta } => OracleLaw::Stribeck { vs, delta, eta },
        FrictionLaw::Cubic { k1, k3 } => OracleLaw::Cubic { k1, k3 },
    }
}

fn records(truth: &Experiment, drives: &[(f64, f64, f64)], rng: &mut Rng) -> Vec<Measurement> {
    let law = oracle_law(truth);
    drives
        .iter()
        .enumerate()
        .map(|(i, &(w, beta, phi))| {
            let text = record(truth, law, w, beta, phi, rng);
            let r = read_scope(&text, &format!("belt{i}.csv")).unwrap();
            Measurement::new(&r, None, None).unwrap()
        })
        .collect()
}

fn show(report: &FitReport) {
    for p in &report.parameters {
        eprintln!(
            "{} = {} ± {} ({:?}, {:?})",
            p.parameter, p.value, p.stderr, p.ci95, p.interval
        );
    }
    for r in &report.records {
        eprintln!("{}: {:?} rms {}", r.file, r.class, r.rms_residual_v);
    }
    eprintln!(
        "chi2/dof {:?}, iterations {}, converged {}, jacobian {:?}, warnings {:?}",
        report.chi2_dof, report.iterations, report.converged, report.jacobian, report.warnings
    );
}

const FREE: [FitParameter; 3] = [
    FitParameter::MuS,
    FitParameter::StribeckSpeed,
    FitParameter::ViscousFriction,
];

/// Two drives of the Stribeck belt: a slow one with stick-slip (slips from rest through
/// the Stribeck fall) and a faster, stronger one whose slips reach several Stribeck speeds
/// (where the viscous term shows).
const DRIVES: [(f64, f64, f64); 2] = [(0.5, 1.2, 0.4), (1.3, 3.0, -1.1)];

#[test]
fn a_stribeck_belt_fit_recovers_mu_s_the_stribeck_speed_and_the_viscous_friction() {
    let truth = stribeck(TRUTH);
    let data = records(&truth, &DRIVES, &mut Rng(2031));
    let start = stribeck(Belt {
        mu_s: 1.3,
        stribeck_speed: 0.7 * TRUTH.stribeck_speed,
        viscous: 0.5 * TRUTH.viscous,
        ..TRUTH
    });
    let report = fit_records(&start, &data, &FREE, &FitOptions::default()).unwrap();
    show(&report);
    assert!(report.converged, "{report:?}");
    assert_eq!(report.jacobian, Jacobian::CentralDifferences);
    for (p, truth) in [
        (FitParameter::MuS, TRUTH.mu_s),
        (FitParameter::StribeckSpeed, TRUTH.stribeck_speed),
        (FitParameter::ViscousFriction, TRUTH.viscous),
    ] {
        let v = report.value(p).unwrap();
        assert!(
            v.ci95[0] <= truth && truth <= v.ci95[1],
            "{p} = {} ± {}: {:?} does not cover {truth}",
            v.value,
            v.stderr,
            v.ci95
        );
        // An error bar that says something: well under the value.
        assert!(v.stderr < 0.2 * v.value, "{p}: {v:?}");
    }
    let chi2 = report.chi2_dof.unwrap();
    assert!((0.7..1.5).contains(&chi2), "chi2/dof = {chi2}");
}

/// A belt fast enough (vb = 3, ten Stribeck speeds) that the block, driven below resonance,
/// never stops and its slip never comes below 2: the Stribeck fall, (μs − 1)·exp(−(s/vs)²),
/// is below 10⁻⁷ on every sample, and the record cannot see the Stribeck speed (nor μs, which
/// enters only through that fall without a stop). The fit names them instead of giving
/// them error bars, and still fits the viscous friction.
#[test]
fn a_record_that_never_slips_slowly_does_not_show_the_stribeck_speed() {
    let fast = Belt {
        belt_speed: 3.0 * VELOCITY,
        ..TRUTH
    };
    let truth = stribeck(fast);
    let data = records(&truth, &[(0.6, 1.0, 0.3)], &mut Rng(77));
    let start = stribeck(Belt {
        mu_s: 1.3,
        stribeck_speed: 0.7 * TRUTH.stribeck_speed,
        viscous: 0.5 * TRUTH.viscous,
        ..fast
    });
    let report = fit_records(&start, &data, &FREE, &FitOptions::default()).unwrap();
    show(&report);
    assert!(report.converged, "{report:?}");
    assert_eq!(report.records[0].class, MotionClass::Sliding);
    let named: Vec<FitParameter> = report
        .warnings
        .iter()
        .filter(|w| w.kind() == "unseen")
        .flat_map(|w| w.parameters())
        .collect();
    assert_eq!(
        named,
        [FitParameter::MuS, FitParameter::StribeckSpeed],
        "{:?}",
        report.warnings
    );
    for p in [FitParameter::MuS, FitParameter::StribeckSpeed] {
        let v = report.value(p).unwrap();
        assert!(
            v.stderr.is_nan() && v.ci95.iter().all(|c| c.is_nan()),
            "{v:?}"
        );
        assert_eq!(v.interval, Interval::None);
    }
    let json = serde_json::to_value(report.to_json()).unwrap();
    assert!(
        json["parameters"]["stribeck-speed"]["stderr"].is_null(),
        "{json}"
    );
    let eta = report.value(FitParameter::ViscousFriction).unwrap();
    assert!(
        eta.ci95[0] <= TRUTH.viscous && TRUTH.viscous <= eta.ci95[1],
        "{eta:?}"
    );
}

/// The oscillator with Coulomb's law on a belt moving at `belt_speed` (m/s), kinetic
/// friction `friction` (N) and μs.
fn coulomb(friction: f64, mu_s: f64, belt_speed: f64) -> Experiment {
    let m = mechanics(friction);
    let vb = Key::BeltSpeed.image(belt_speed, &m.scales()).unwrap();
    Experiment::mechanics(m)
        .unwrap()
        .with_mu_s(mu_s)
        .unwrap()
        .with_vb(vb)
        .unwrap()
}

/// A Coulomb belt (the exact solver with a belt, the oracle's Coulomb law): its kinetic
/// level F0 and μs from a stick-slip record and a sliding one, the belt speed given in m/s
/// (its dimensionless image moves with F0, which the fit frees).
#[test]
fn a_coulomb_belt_fit_recovers_the_kinetic_level_and_mu_s() {
    let belt_speed = 0.3 * VELOCITY;
    let truth = coulomb(F0, 1.5, belt_speed);
    let data = records(&truth, &DRIVES, &mut Rng(4099));
    let start = coulomb(1.2 * F0, 1.3, belt_speed);
    let free = [FitParameter::Friction, FitParameter::MuS];
    let report = fit_records(&start, &data, &free, &FitOptions::default()).unwrap();
    show(&report);
    assert!(report.converged, "{report:?}");
    assert_eq!(report.jacobian, Jacobian::CentralDifferences);
    for (p, truth) in [(FitParameter::Friction, F0), (FitParameter::MuS, 1.5)] {
        let v = report.value(p).unwrap();
        assert!(
            v.ci95[0] <= truth && truth <= v.ci95[1],
            "{p} = {} ± {}: {:?} does not cover {truth}",
            v.value,
            v.stderr,
            v.ci95
        );
        assert!(v.stderr < 0.05 * v.value, "{p}: {v:?}");
    }
    // The fitted oscillator keeps the belt's speed in m/s.
    let fitted = &report.experiment;
    let scales = fitted.scales().unwrap();
    assert!((fitted.vb() * scales.velocity / belt_speed - 1.0).abs() < 1e-12);
}

/// A law's own parameter on an oscillator whose law does not have it, and on a circuit.
#[test]
fn a_stribeck_parameter_without_the_stribeck_law_is_refused() {
    let data = records(&coulomb(F0, 1.5, 0.3 * VELOCITY), &DRIVES[..1], &mut Rng(5));
    let start = coulomb(F0, 1.5, 0.3 * VELOCITY);
    for p in [FitParameter::StribeckSpeed, FitParameter::ViscousFriction] {
        let e = fit_records(
            &start,
            &data,
            &[FitParameter::MuS, p],
            &FitOptions::default(),
        )
        .unwrap_err();
        assert!(matches!(e, FitError::WrongFrictionLaw { .. }), "{e:?}");
        assert_eq!(
            e.to_string(),
            format!(
                "{p} is a parameter of the stribeck friction law, and this oscillator's law is \
                 coulomb (a coulomb belt's friction is fitted by friction and mu-s)"
            )
        );
    }
    let e = fit_records(
        &Experiment::paper(),
        &data,
        &[FitParameter::StribeckSpeed],
        &FitOptions::default(),
    )
    .unwrap_err();
    assert!(
        e.to_string()
            .starts_with("stribeck-speed is not a parameter of a circuit"),
        "{e}"
    );
}

/// The two records of the worked example in docs/fit.md (`examples/fit/belt/stick.csv` and
/// `fast.csv`): those of the Stribeck belt's recovery test above (the oracle's motion at
/// [`DRIVES`], seed 2031), committed so that the page's command runs as written (the docs'
/// test runs it and compares its output). This test makes them again and requires the
/// committed files byte for byte; with `STICKSLIP_BLESS=1` it writes them.
#[test]
fn the_committed_belt_records_are_what_the_oracle_makes() {
    let dir = std::path::PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../examples/fit/belt");
    let bless = std::env::var("STICKSLIP_BLESS").is_ok_and(|v| v != "0");
    let truth = stribeck(TRUTH);
    let law = oracle_law(&truth);
    let mut rng = Rng(2031);
    let mut stale = Vec::new();
    for (file, &(w, beta, phi)) in ["stick.csv", "fast.csv"].iter().zip(&DRIVES) {
        let text = record(&truth, law, w, beta, phi, &mut rng);
        let path = dir.join(file);
        if bless {
            std::fs::create_dir_all(&dir).unwrap();
            std::fs::write(&path, &text).unwrap();
        } else if std::fs::read_to_string(&path).ok().as_deref() != Some(text.as_str()) {
            stale.push(file);
        }
    }
    assert!(
        stale.is_empty(),
        "examples/fit/belt: {stale:?} differ from what this test makes; \
         STICKSLIP_BLESS=1 cargo test --release -p stickslip --test fit_belt -- committed \
         writes them"
    );
}
