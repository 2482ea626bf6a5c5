//! Fitting the friction law of an undriven belt: a block on a moving belt with no drive force
//! (β = 0), whose self-excited stick-slip cycle is recorded as a displacement r (m) alone.
//! The records are made by an independent integrator (the test kit's Runge–Kutta oracle,
//! [`stickslip_testkit::oracle`], not the library's solvers), from rest, settled, then
//! quantised to 8 bits with a step of noise; the fit starts from other values with the belt
//! speed, m, k and F0 given, and aligns the model's cycle to each record by a section time
//! fitted with the rest. It recovers μs, the Stribeck speed and the viscous friction of a
//! Stribeck belt, and μs and γ of a Coulomb belt, within their 95 % intervals (the Coulomb
//! belt's over several noise draws); F0 and μs together are named as seen only through
//! (μs − 1)·F0; records the fit cannot take are refused in one line. A record from rest (the
//! belt started under the block at rest, at a known position) shows F0 apart from μs: a
//! Coulomb belt's F0, μs and γ over eight noise draws, with error bars checked against the
//! draws' scatter, and a Stribeck belt's levels and law. Two records at two belt speeds fix
//! the Stribeck law far better than one; a cubic belt's pure-slip cycle gives γ and k.

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
    experiment_with(belt, STIFFNESS, F0)
}

/// [`experiment`] with the stiffness k (N/m) and the kinetic level F0 (N) given.
fn experiment_with(belt: Belt, stiffness: f64, f0: f64) -> Experiment {
    let m = Mechanics::new(MASS, stiffness, belt.gamma, f0).unwrap();
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
    let dtau = cycles * period(&e) / n as f64;
    oracle_record(&e, (0.0, 0.0), 80.0 * std::f64::consts::TAU, dtau, n, rng)
}

/// The oracle's undriven motion of `e` from (y, y') = `start` at τ = 0, sampled `n` times
/// every `dtau` from τ = `settle` on (the record's time 0 there), as [`record`] says.
fn oracle_record(
    e: &Experiment,
    start: (f64, f64),
    settle: f64,
    dtau: f64,
    n: usize,
    rng: &mut Rng,
) -> String {
    let p = e.params().unwrap();
    let scales = e.scales().unwrap();
    let taus: Vec<f64> = (0..n).map(|k| settle + k as f64 * dtau).collect();
    let mut oracle = Oracle::new(p, oracle_law(e), 5e-4, start.0, start.1);
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

/// The Stribeck belt's law as the fits free it: (parameter, truth).
fn stribeck_law() -> [(FitParameter, f64); 3] {
    let (vs, eta) = STRIBECK.stribeck.unwrap();
    [
        (FitParameter::MuS, STRIBECK.mu_s),
        (FitParameter::StribeckSpeed, vs),
        (FitParameter::ViscousFriction, eta),
    ]
}

/// The Stribeck belt's fits' start, F0 (N) given: μs = 1.4, vs and η at 0.8 and 0.6 of theirs.
fn stribeck_start(f0: f64) -> Experiment {
    let (vs, eta) = STRIBECK.stribeck.unwrap();
    experiment_with(
        Belt {
            mu_s: 1.4,
            stribeck: Some((0.8 * vs, 0.6 * eta)),
            ..STRIBECK
        },
        STIFFNESS,
        f0,
    )
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
    let start = stribeck_start(F0);
    let free = stribeck_law().map(|(p, _)| p);
    let report = fit_undriven(&start, &data, &free, &FitOptions::default()).unwrap();
    show(&report);
    assert!(report.converged, "{report:?}");
    assert_eq!(report.jacobian, Jacobian::CentralDifferences);
    assert_eq!(report.records[0].class, MotionClass::StickSlipCycle);
    covers(&report, &stribeck_law()).unwrap();
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

/// The records of the worked examples in docs/fit.md (`examples/fit/undriven/`): that of the
/// Stribeck belt's recovery test above (`stribeck.csv`, seed 311), the same belt at twice the
/// speed (`fast.csv`, seed 312, of the two-speed test) and the Coulomb belt from rest 0.3 mm
/// behind the spring's rest length (`rest.csv`, the first draw of the test from rest),
/// committed so that the page's commands run as written. This test makes them again and
/// requires the committed files byte for byte; with `STICKSLIP_BLESS=1` it writes them.
#[test]
fn the_committed_undriven_records_are_what_the_oracle_makes() {
    let dir =
        std::path::PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../examples/fit/undriven");
    let fast = experiment(Belt {
        belt_speed: 2.0 * STRIBECK.belt_speed,
        ..STRIBECK
    });
    let coulomb = experiment(COULOMB);
    let files = [
        (
            "stribeck.csv",
            record(&experiment(STRIBECK), 3.4, 2400, &mut Rng(311)),
        ),
        ("fast.csv", record(&fast, 3.4, 2400, &mut Rng(312))),
        (
            "rest.csv",
            from_rest(
                &coulomb,
                START,
                3.5 * period(&coulomb),
                1600,
                &mut Rng(2000),
            ),
        ),
    ];
    for (name, text) in files {
        let path = dir.join(name);
        if std::env::var("STICKSLIP_BLESS").is_ok_and(|v| v != "0") {
            std::fs::create_dir_all(&dir).unwrap();
            std::fs::write(&path, &text).unwrap();
        }
        assert!(
            std::fs::read_to_string(&path).ok().as_deref() == Some(text.as_str()),
            "examples/fit/undriven/{name} differs from what this test makes; \
             STICKSLIP_BLESS=1 cargo test --release -p stickslip --test fit_belt_free -- \
             committed writes it"
        );
    }
}

/// A record from rest (`time_s,r (m)`, as [`record`] makes them): the block at rest on the
/// ground `position` (m) from the spring's rest length when the belt starts, at the record's
/// first sample; `n` samples over `span` in τ.
fn from_rest(truth: &Experiment, position: f64, span: f64, n: usize, rng: &mut Rng) -> String {
    let e = truth.clone().with_beta(0.0).unwrap();
    let y0 = position / e.scales().unwrap().position;
    oracle_record(&e, (y0, 0.0), 0.0, span / n as f64, n, rng)
}

fn read_from_rest(text: &str, name: &str, position: f64) -> UndrivenRecord {
    read(text, name).from_rest(position).unwrap()
}

/// The start of the block 0.3 mm behind the spring's rest length.
const START: f64 = -3e-4;

/// A Coulomb belt started under the block at rest, over eight noise draws, with F0, μs and γ
/// free: the transient shows what a settled cycle cannot, the kinetic level F0 apart from μs
/// (the stick from the known start to the release fixes μs·F0 − γ·vb, the slips about the
/// kinetic level fix F0). Each fit converges with its residual at the noise; the 95 %
/// intervals cover the truth in all but at most one draw of eight; and the error bars are
/// honest: each parameter's RMS standard error is within a factor 1.5 of the scatter of its
/// values over the draws.
#[test]
fn a_coulomb_belt_from_rest_shows_the_kinetic_level_apart_from_mu_s() {
    let truth = experiment(COULOMB);
    let start = experiment_with(
        Belt {
            gamma: 0.6,
            mu_s: 1.35,
            ..COULOMB
        },
        STIFFNESS,
        0.27,
    );
    let free = [
        FitParameter::Friction,
        FitParameter::MuS,
        FitParameter::Damping,
    ];
    let truths = [
        (FitParameter::Friction, F0),
        (FitParameter::MuS, COULOMB.mu_s),
        (FitParameter::Damping, COULOMB.gamma),
    ];
    let span = 3.5 * period(&truth);
    let mut missed = Vec::new();
    let mut values = vec![Vec::new(); free.len()];
    let mut stderrs = vec![Vec::new(); free.len()];
    for seed in 0..8 {
        let text = from_rest(&truth, START, span, 1600, &mut Rng(2000 + seed));
        let data = [read_from_rest(&text, "rest.csv", START)];
        let report = fit_undriven(&start, &data, &free, &FitOptions::default()).unwrap();
        show(&report);
        assert!(report.converged, "seed {seed}: {:?}", report.warnings);
        // No level held: the start position separates them.
        assert!(
            report.warnings.iter().all(|w| w.kind() != "not-identified"),
            "{:?}",
            report.warnings
        );
        let chi2 = report.chi2_dof.unwrap();
        assert!((0.7..1.5).contains(&chi2), "seed {seed}: chi2/dof = {chi2}");
        // The offset: the sensor's zero (+0.4 mm), within three standard errors of F0's
        // share of it (r is read from the spring's rest length plus the offset).
        let r = &report.records[0];
        assert_eq!(r.time_shift_s, 0.0);
        assert!((r.offset_v - 4e-4).abs() < 2e-5, "{}", r.offset_v);
        if let Err(e) = covers(&report, &truths) {
            missed.push((seed, e));
        }
        for (k, &p) in free.iter().enumerate() {
            let v = report.value(p).unwrap();
            values[k].push(v.value);
            stderrs[k].push(v.stderr);
        }
    }
    assert!(missed.len() <= 1, "{missed:?}");
    for (k, p) in free.iter().enumerate() {
        let n = values[k].len() as f64;
        let mean = values[k].iter().sum::<f64>() / n;
        let scatter =
            (values[k].iter().map(|v| (v - mean).powi(2)).sum::<f64>() / (n - 1.0)).sqrt();
        let stderr = (stderrs[k].iter().map(|s| s * s).sum::<f64>() / n).sqrt();
        eprintln!("{p}: mean {mean}, scatter {scatter}, RMS stderr {stderr}");
        assert!(
            (1.0 / 1.5..1.5).contains(&(stderr / scatter)),
            "{p}: RMS standard error {stderr:e} against a scatter of {scatter:e}"
        );
    }
    // F0 and μs each to better than a per cent: what no settled cycle shows apart.
    for k in 0..2 {
        let stderr = stderrs[k].iter().fold(0.0f64, |a, &s| a.max(s));
        assert!(stderr < 0.01 * truths[k].1, "{}: {stderr:e}", free[k]);
    }
}

/// A Stribeck belt from rest with F0, μs, the Stribeck speed and the viscous friction free:
/// the fit converges with its residual at the noise and every interval covers the truth.
/// One record from rest shows the two levels and the viscous slope mostly together (each
/// pair correlated beyond 0.999, named in warnings): F0 and μs to about 4 %, not the 0.2 %
/// of the Coulomb belt's, whose law has no slope to trade against them.
#[test]
fn a_stribeck_belt_from_rest_recovers_the_levels_and_the_law() {
    let truth = experiment(STRIBECK);
    let start = stribeck_start(0.27);
    let free = [
        FitParameter::Friction,
        FitParameter::MuS,
        FitParameter::StribeckSpeed,
        FitParameter::ViscousFriction,
    ];
    let text = from_rest(&truth, 0.0, 3.5 * period(&truth), 2400, &mut Rng(77));
    let data = [read_from_rest(&text, "rest.csv", 0.0)];
    let report = fit_undriven(&start, &data, &free, &FitOptions::default()).unwrap();
    show(&report);
    assert!(report.converged, "{:?}", report.warnings);
    covers(&report, &[(FitParameter::Friction, F0)]).unwrap();
    covers(&report, &stribeck_law()).unwrap();
    for p in [FitParameter::Friction, FitParameter::MuS] {
        let v = report.value(p).unwrap();
        assert!(v.stderr < 0.05 * v.value, "{p}: {v:?}");
    }
    let v = report.value(FitParameter::StribeckSpeed).unwrap();
    assert!(v.stderr < 0.01 * v.value, "{v:?}");
    assert!(
        report.warnings.iter().any(|w| w.kind() == "correlated"
            && w.parameters() == [FitParameter::Friction, FitParameter::MuS]),
        "{:?}",
        report.warnings
    );
    let chi2 = report.chi2_dof.unwrap();
    assert!((0.7..1.5).contains(&chi2), "chi2/dof = {chi2}");
    // The motion it settles on, at the fitted values: the stick-slip cycle.
    assert_eq!(report.records[0].class, MotionClass::StickSlipCycle);
}

/// One Stribeck belt's settled cycles at two belt speeds (9 and 18 mm/s: vb = 0.3 and 0.6),
/// fitted together, each record with its own belt speed: the joint fit covers the truth, and
/// the viscous friction, which one cycle shows only together with μs, is fixed far better
/// than by the slower record alone: its standard error falls by more than the √2 that twice
/// the samples alone would give.
#[test]
fn two_belt_speeds_fix_the_stribeck_law_better_than_one() {
    let truth = experiment(STRIBECK);
    let fast_speed = 2.0 * STRIBECK.belt_speed;
    let fast = experiment(Belt {
        belt_speed: fast_speed,
        ..STRIBECK
    });
    let start = stribeck_start(F0);
    let free = stribeck_law().map(|(p, _)| p);
    let slow = read(&record(&truth, 3.4, 2400, &mut Rng(311)), "slow.csv");
    let quick = read(&record(&fast, 3.4, 2400, &mut Rng(312)), "fast.csv")
        .on_belt(fast_speed)
        .unwrap();
    let alone = fit_undriven(
        &start,
        std::slice::from_ref(&slow),
        &free,
        &FitOptions::default(),
    )
    .unwrap();
    show(&alone);
    let joint = fit_undriven(&start, &[slow, quick], &free, &FitOptions::default()).unwrap();
    show(&joint);
    assert!(joint.converged, "{:?}", joint.warnings);
    covers(&joint, &stribeck_law()).unwrap();
    let chi2 = joint.chi2_dof.unwrap();
    assert!((0.7..1.5).contains(&chi2), "chi2/dof = {chi2}");
    // Each record's own cycle: the faster belt's is another.
    assert_eq!(joint.records.len(), 2);
    assert!(
        (joint.records[0].freq_hz - joint.records[1].freq_hz).abs() > 1e-3,
        "{} and {} Hz",
        joint.records[0].freq_hz,
        joint.records[1].freq_hz
    );
    for p in free {
        let (a, j) = (alone.value(p).unwrap(), joint.value(p).unwrap());
        eprintln!("{p}: alone ± {:e}, joint ± {:e}", a.stderr, j.stderr);
        assert!(j.stderr < a.stderr, "{p}: {j:?} against {a:?}");
    }
    let (a, j) = (
        alone.value(FitParameter::ViscousFriction).unwrap(),
        joint.value(FitParameter::ViscousFriction).unwrap(),
    );
    assert!(j.stderr < a.stderr / 2f64.sqrt(), "{j:?} against {a:?}");
}

/// A cubic belt whose self-excited cycle never sticks (ζ = 0.05, μs = 1.5, k1 = 0.5,
/// k3 = 0.3 at vb = 0.6: a pure-slip cycle, the block always slower than the belt), with γ and
/// k free: the fit aligns the cycle by its turning point and recovers both.
#[test]
fn an_undriven_pure_slip_cycle_fit_recovers_the_damping_and_the_stiffness() {
    // The law in physical units (K1 in N·s/m, K3 in N·s³/m³) from the truth's scales: the
    // fit holds them while k moves the scales.
    let scales = experiment(COULOMB).scales().unwrap();
    let k1 = 0.5 / Key::CubicK1.image(1.0, &scales).unwrap();
    let k3 = 0.3 / Key::CubicK3.image(1.0, &scales).unwrap();
    let cubic = |gamma: f64, stiffness: f64| {
        let belt = Belt {
            gamma,
            belt_speed: 0.6 * VELOCITY,
            mu_s: 1.5,
            stribeck: None,
        };
        let e = experiment_with(belt, stiffness, F0);
        let s = e.scales().unwrap();
        e.with_law(FrictionLaw::Cubic {
            k1: Key::CubicK1.image(k1, &s).unwrap(),
            k3: Key::CubicK3.image(k3, &s).unwrap(),
        })
        .unwrap()
    };
    let truth = cubic(1.0, STIFFNESS);
    let s = truth.clone().with_beta(0.0).unwrap().steady().unwrap();
    assert_eq!(s.class, MotionClass::PureSlipCycle);
    let data = [read(&record(&truth, 3.4, 1600, &mut Rng(41)), "slip.csv")];
    let start = cubic(1.15, 190.0);
    let free = [FitParameter::Damping, FitParameter::Stiffness];
    let report = fit_undriven(&start, &data, &free, &FitOptions::default()).unwrap();
    show(&report);
    assert!(report.converged, "{:?}", report.warnings);
    assert_eq!(report.records[0].class, MotionClass::PureSlipCycle);
    covers(
        &report,
        &[
            (FitParameter::Damping, 1.0),
            (FitParameter::Stiffness, STIFFNESS),
        ],
    )
    .unwrap();
    let chi2 = report.chi2_dof.unwrap();
    assert!((0.7..1.5).contains(&chi2), "chi2/dof = {chi2}");
}
