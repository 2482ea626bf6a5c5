//! Fitting the friction law of an undriven belt: a block on a moving belt with no drive force
//! (β = 0), whose self-excited stick-slip cycle is recorded as a displacement r (m) alone.
//! The records are made by an independent integrator (the test kit's Runge–Kutta oracle,
//! [`stickslip_testkit::oracle`], not the library's solvers), from rest, settled, then
//! quantised to 8 bits with a step of noise; the fit starts from other values with the belt
//! speed, m, k and F0 given, and aligns the model's cycle to each record by a section time
//! fitted with the rest. It recovers μs, the Stribeck speed and the viscous friction of a
//! Stribeck belt, and μs and γ of a Coulomb belt, within their 95 % intervals (the Coulomb
//! belt's over several noise draws); F0 and μs together are named as seen only through
//! (μs − 1)·F0; records the fit cannot take are refused in one line.

use stickslip::experiment::{Experiment, Key};
use stickslip::fit::{
    fit_undriven, FitError, FitOptions, FitParameter, FitReport, FitWarning, Interval, Jacobian,
    UndrivenRecord,
};
use stickslip::friction::FrictionLaw;
use stickslip::measure::read_scope;
use stickslip::physical::Mechanics;
use stickslip::steady::MotionClass;
use stickslip_testkit::oracle::{Oracle, OracleLaw};
use stickslip_testkit::{quantise, Rng};

/// m = 0.5 kg, k = 200 N/m (ω0 = 20 rad/s), F0 = 0.3 N: a displacement scale F0/k of 1.5 mm
/// and a velocity scale F0/k·ω0 of 0.03 m/s.
const MASS: f64 = 0.5;
const STIFFNESS: f64 = 200.0;
const F0: f64 = 0.3;
const OMEGA0: f64 = 20.0;
const VELOCITY: f64 = F0 / STIFFNESS * OMEGA0;

/// A belt in physical units: damping γ (N·s/m), belt speed (m/s), μs, Stribeck speed (m/s),
/// viscous friction (N·s/m); `None` for the law: Coulomb's.
#[derive(Debug, Clone, Copy)]
struct Belt {
    gamma: f64,
    belt_speed: f64,
    mu_s: f64,
    stribeck: Option<(f64, f64)>,
}

/// ζ = 0.04, vb = 0.3, μs = 1.5, vs = 0.5, δ = 2, η = 0.05 in the dimensionless units:
/// steady sliding is unstable (2ζ + μ'(vb) ≈ −0.71), the block sticks and slips.
const STRIBECK: Belt = Belt {
    gamma: 0.8,
    belt_speed: 0.3 * VELOCITY,
    mu_s: 1.5,
    stribeck: Some((0.5 * VELOCITY, 0.05 * F0 / VELOCITY)),
};

/// The Coulomb belt: ζ = 0.04, vb = 0.3, μs = 1.5.
const COULOMB: Belt = Belt {
    gamma: 0.8,
    belt_speed: 0.3 * VELOCITY,
    mu_s: 1.5,
    stribeck: None,
};

fn experiment(belt: Belt) -> Experiment {
    let m = Mechanics::new(MASS, STIFFNESS, belt.gamma, F0).unwrap();
    let s = m.scales();
    let image = |key: Key, v: f64| key.image(v, &s).unwrap();
    let e = Experiment::mechanics(m)
        .unwrap()
        .with_mu_s(belt.mu_s)
        .unwrap()
        .with_vb(image(Key::BeltSpeed, belt.belt_speed))
        .unwrap();
    match belt.stribeck {
        Some((vs, eta)) => e
            .with_law(FrictionLaw::Stribeck {
                vs: image(Key::StribeckSpeed, vs),
                delta: 2.0,
                eta: image(Key::ViscousFriction, eta),
            })
            .unwrap(),
        None => e,
    }
}

fn oracle_law(e: &Experiment) -> OracleLaw {
    match e.friction_law() {
        FrictionLaw::Coulomb => OracleLaw::Coulomb,
        FrictionLaw::Stribeck { vs, delta, eta } => OracleLaw::Stribeck { vs, delta, eta },
        FrictionLaw::Cubic { k1, k3 } => OracleLaw::Cubic { k1, k3 },
    }
}

/// The self-excited cycle's period of `e` in τ (the library's, only to size the record).
fn period(e: &Experiment) -> f64 {
    let s = e.clone().with_beta(0.0).unwrap().steady().unwrap();
    s.self_excited.unwrap().period.expect("a cycle")
}

/// A plain CSV (`time_s,r (m)`) of the oracle's undriven motion of `truth` from rest: 80
/// natural periods to settle, then `n` samples over `cycles` cycles, quantised to 8 bits of
/// a screen 1.25 times its peak-to-peak with one step of Gaussian noise, and an offset of
/// +0.4 mm (a sensor's zero).
fn record(truth: &Experiment, cycles: f64, n: usize, rng: &mut Rng) -> String {
    let e = truth.clone().with_beta(0.0).unwrap();
    let p = e.params().unwrap();
    let scales = e.scales().unwrap();
    let settle = 80.0 * std::f64::consts::TAU;
    let dtau = cycles * period(&e) / n as f64;
    let taus: Vec<f64> = (0..n).map(|k| settle + k as f64 * dtau).collect();
    let mut oracle = Oracle::new(p, oracle_law(&e), 5e-4, 0.0, 0.0);
    let r: Vec<f64> = oracle
        .sample(&taus)
        .iter()
        .map(|y| y * scales.position + 4e-4)
        .collect();
    let r = quantise(&r, 256.0, 1.0, rng);
    let mut text = "time_s,r (m)\n".to_string();
    for (k, r) in r.iter().enumerate() {
        text += &format!("{:.9e},{r:.6e}\n", k as f64 * dtau / scales.omega0);
    }
    text
}

fn read(text: &str, name: &str) -> UndrivenRecord {
    let r = read_scope(text, name).unwrap();
    assert!(UndrivenRecord::is_undriven(&r));
    UndrivenRecord::new(&r, None).unwrap()
}

fn show(report: &FitReport) {
    for p in &report.parameters {
        eprintln!(
            "{} = {} ± {} ({:?}, {:?})",
            p.parameter, p.value, p.stderr, p.ci95, p.interval
        );
    }
    for r in &report.records {
        eprintln!(
            "{}: {:?} {} Hz, section at {} s, offset {}, rms {} (noise {})",
            r.file, r.class, r.freq_hz, r.time_shift_s, r.offset_v, r.rms_residual_v, r.noise_v
        );
    }
    eprintln!(
        "chi2/dof {:?}, iterations {}, converged {}, jacobian {:?}, warnings {:?}",
        report.chi2_dof, report.iterations, report.converged, report.jacobian, report.warnings
    );
}

/// Whether each (parameter, truth) is inside its 95 % interval, and the first that is not.
fn covers(report: &FitReport, truths: &[(FitParameter, f64)]) -> Result<(), String> {
    for &(p, truth) in truths {
        let v = report.value(p).unwrap();
        if !(v.ci95[0] <= truth && truth <= v.ci95[1]) {
            return Err(format!(
                "{p} = {} ± {}: {:?} does not cover {truth}",
                v.value, v.stderr, v.ci95
            ));
        }
    }
    Ok(())
}

#[test]
fn an_undriven_stribeck_belt_fit_recovers_mu_s_the_stribeck_speed_and_the_viscous_friction() {
    let truth = experiment(STRIBECK);
    let data = [read(&record(&truth, 3.4, 2400, &mut Rng(311)), "free.csv")];
    let (vs, eta) = STRIBECK.stribeck.unwrap();
    let start = experiment(Belt {
        mu_s: 1.4,
        stribeck: Some((0.8 * vs, 0.6 * eta)),
        ..STRIBECK
    });
    let free = [
        FitParameter::MuS,
        FitParameter::StribeckSpeed,
        FitParameter::ViscousFriction,
    ];
    let report = fit_undriven(&start, &data, &free, &FitOptions::default()).unwrap();
    show(&report);
    assert!(report.converged, "{report:?}");
    assert_eq!(report.jacobian, Jacobian::CentralDifferences);
    assert_eq!(report.records[0].class, MotionClass::StickSlipCycle);
    covers(
        &report,
        &[
            (FitParameter::MuS, STRIBECK.mu_s),
            (FitParameter::StribeckSpeed, vs),
            (FitParameter::ViscousFriction, eta),
        ],
    )
    .unwrap();
    // μs and the Stribeck speed to a few per cent. One stick-slip cycle shows the viscous
    // slope mostly through its combination with μs (both raise the friction of the fast
    // part of the slip): the two are correlated beyond 0.99 and named so, and η's interval
    // (the profile's, cut at η = 0) is wide but holds the truth.
    for p in [FitParameter::MuS, FitParameter::StribeckSpeed] {
        let v = report.value(p).unwrap();
        assert!(v.stderr < 0.05 * v.value, "{p}: {v:?}");
    }
    for p in free {
        let v = report.value(p).unwrap();
        assert!(
            matches!(v.interval, Interval::Linear | Interval::Profile),
            "{v:?}"
        );
    }
    assert!(
        report.warnings.iter().any(|w| w.kind() == "correlated"
            && w.parameters() == [FitParameter::MuS, FitParameter::ViscousFriction]),
        "{:?}",
        report.warnings
    );
    let chi2 = report.chi2_dof.unwrap();
    assert!((0.7..1.5).contains(&chi2), "chi2/dof = {chi2}");
    // The sensor's zero: the offset moves with μs (the block leaves the belt at
    // k·r = μs·F0 − γ·vb), within three of μs's standard errors times F0/k. And the cycle's
    // frequency against the truth's (the library's).
    let r = &report.records[0];
    let mu = report.value(FitParameter::MuS).unwrap();
    assert!(
        (r.offset_v - 4e-4).abs() < 3.0 * mu.stderr * F0 / STIFFNESS,
        "{}",
        r.offset_v
    );
    let f = OMEGA0 / period(&truth); // Hz: one cycle of T/ω0 seconds
    assert!(
        (r.freq_hz / f - 1.0).abs() < 3e-3,
        "{} against {f}",
        r.freq_hz
    );
}

/// The Coulomb belt's μs and γ over several noise draws: each fit converges with its
/// residual at the noise, and the 95 % intervals cover the truth in all but at most one of
/// eight draws (binomially, 95 % intervals miss two or more of eight 6 % of the time).
#[test]
fn an_undriven_coulomb_belt_fit_recovers_mu_s_and_the_damping_over_noise_draws() {
    let truth = experiment(COULOMB);
    let start = experiment(Belt {
        gamma: 0.6,
        mu_s: 1.35,
        ..COULOMB
    });
    let free = [FitParameter::MuS, FitParameter::Damping];
    let mut missed = Vec::new();
    for seed in 0..8 {
        let data = [read(
            &record(&truth, 3.4, 1600, &mut Rng(1000 + seed)),
            "coulomb.csv",
        )];
        let report = fit_undriven(&start, &data, &free, &FitOptions::default()).unwrap();
        show(&report);
        assert!(report.converged, "{report:?}");
        assert_eq!(report.records[0].class, MotionClass::StickSlipCycle);
        let chi2 = report.chi2_dof.unwrap();
        assert!((0.7..1.5).contains(&chi2), "seed {seed}: chi2/dof = {chi2}");
        if let Err(e) = covers(
            &report,
            &[
                (FitParameter::MuS, COULOMB.mu_s),
                (FitParameter::Damping, COULOMB.gamma),
            ],
        ) {
            missed.push((seed, e));
        }
    }
    assert!(missed.len() <= 1, "{missed:?}");
}

/// With the offset of r free, the kinetic level F0 only shifts r: F0 and μs are seen as
/// (μs − 1)·F0, the fit holds the one named last and says so; the law's parameter of another
/// law is refused.
#[test]
fn the_kinetic_level_and_mu_s_are_seen_only_together() {
    let truth = experiment(COULOMB);
    let data = [read(&record(&truth, 2.5, 1200, &mut Rng(9)), "c.csv")];
    let start = experiment(Belt {
        mu_s: 1.35,
        ..COULOMB
    });
    let report = fit_undriven(
        &start,
        &data,
        &[FitParameter::Friction, FitParameter::MuS],
        &FitOptions::default(),
    )
    .unwrap();
    show(&report);
    let held: Vec<&FitWarning> = report
        .warnings
        .iter()
        .filter(|w| w.kind() == "not-identified")
        .collect();
    assert_eq!(held.len(), 1, "{:?}", report.warnings);
    assert_eq!(
        held[0].parameters(),
        [FitParameter::Friction, FitParameter::MuS]
    );
    let mu = report.value(FitParameter::MuS).unwrap();
    assert_eq!(mu.interval, Interval::Held);
    // F0 fitted with μs held at 1.35: (μs − 1)·F0 is what the record fixes.
    let f0 = report.value(FitParameter::Friction).unwrap();
    let seen = 0.35 * f0.value;
    assert!((seen / (0.5 * F0) - 1.0).abs() < 0.02, "{f0:?}");
    let e = fit_undriven(
        &start,
        &data,
        &[FitParameter::StribeckSpeed],
        &FitOptions::default(),
    )
    .unwrap_err();
    assert!(matches!(e, FitError::WrongFrictionLaw { .. }), "{e:?}");
}

/// What the fit does not take, each in one line naming what is missing.
#[test]
fn records_and_oscillators_an_undriven_fit_cannot_take_are_refused() {
    let truth = experiment(COULOMB);
    let text = record(&truth, 2.5, 600, &mut Rng(3));
    let data = [read(&text, "c.csv")];
    let free = [FitParameter::MuS];
    let options = FitOptions::default();
    // No belt.
    let still = Experiment::mechanics(Mechanics::new(MASS, STIFFNESS, 0.8, F0).unwrap()).unwrap();
    let e = fit_undriven(&still, &data, &free, &options).unwrap_err();
    assert!(
        e.to_string().contains("needs a moving belt (--belt-speed)"),
        "{e}"
    );
    // Starting values that slide steadily: a belt fast enough for the Stribeck fall to be
    // past (2ζ + μ'(vb) > 0).
    let fast = experiment(Belt {
        belt_speed: 3.0 * VELOCITY,
        ..STRIBECK
    });
    let e = fit_undriven(&fast, &data, &free, &options).unwrap_err();
    assert!(e.to_string().contains("slides steadily on the belt"), "{e}");
    // A record shorter than one cycle.
    let short: String = text.lines().take(100).map(|l| format!("{l}\n")).collect();
    let e = fit_undriven(&truth, &[read(&short, "short.csv")], &free, &options).unwrap_err();
    assert!(
        e.to_string().starts_with("short.csv: the record spans")
            && e.to_string().contains("less than one self-excited cycle"),
        "{e}"
    );
    assert!(!e.to_string().contains('\n'), "{e}");
    // A record with a varying force channel is a driven record; one without a channel in m.
    let driven: String = text
        .lines()
        .enumerate()
        .map(|(k, l)| {
            if k == 0 {
                "time_s,F (N),r (m)\n".to_string()
            } else {
                let (t, r) = l.split_once(',').unwrap();
                format!("{t},{:.4e},{r}\n", 0.1 * (k as f64 * 0.05).sin())
            }
        })
        .collect();
    let r = read_scope(&driven, "driven.csv").unwrap();
    assert!(!UndrivenRecord::is_undriven(&r));
    let e = UndrivenRecord::new(&r, None).unwrap_err();
    assert!(
        e.to_string().contains("channel F (N) varies") || e.to_string().contains("varies"),
        "{e}"
    );
    let volts = text.replacen("r (m)", "u (V)", 1);
    let r = read_scope(&volts, "volts.csv").unwrap();
    let e = UndrivenRecord::new(&r, None).unwrap_err();
    assert!(
        e.to_string().contains("needs a displacement channel in m"),
        "{e}"
    );
}

/// The record of the worked example in docs/fit.md (`examples/fit/undriven/stribeck.csv`):
/// that of the Stribeck belt's recovery test above (seed 311), committed so that the page's
/// command runs as written. This test makes it again and requires the committed file byte
/// for byte; with `STICKSLIP_BLESS=1` it writes it.
#[test]
fn the_committed_undriven_record_is_what_the_oracle_makes() {
    let dir =
        std::path::PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../examples/fit/undriven");
    let path = dir.join("stribeck.csv");
    let text = record(&experiment(STRIBECK), 3.4, 2400, &mut Rng(311));
    if std::env::var("STICKSLIP_BLESS").is_ok_and(|v| v != "0") {
        std::fs::create_dir_all(&dir).unwrap();
        std::fs::write(&path, &text).unwrap();
    }
    assert!(
        std::fs::read_to_string(&path).ok().as_deref() == Some(text.as_str()),
        "examples/fit/undriven/stribeck.csv differs from what this test makes; \
         STICKSLIP_BLESS=1 cargo test --release -p stickslip --test fit_belt_free -- committed \
         writes it"
    );
}
