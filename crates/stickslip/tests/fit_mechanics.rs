//! Fitting a mechanical oscillator (mass, spring, viscous and dry friction): records of the
//! drive force F (N) and the displacement r (m) synthesised by the exact solver at known
//! γ and F0 (two drive frequencies, 8-bit quantisation, noise, an offset of r), fitted from
//! other starting values; the 95 % intervals' coverage over 100 noise draws; and the
//! refusals (a circuit's parameter on a mechanical oscillator and the other way round, a
//! record in volts, a table).

use std::f64::consts::TAU;
use stickslip::experiment::Experiment;
use stickslip::fit::{fit_records, fit_table, FitOptions, FitParameter, FitReport, Jacobian};
use stickslip::measure::{read_amplitudes, read_scope, Measurement};
use stickslip::physical::Mechanics;
use stickslip::steady::MotionClass;
use stickslip_testkit::{driven, quantise, sample_steady, timed, Rng, Synthetic};

/// m = 0.5 kg, k = 200 N/m (ω0 = 20 rad/s, f0 = 3.18 Hz), γ = 2 N·s/m (ζ = 0.1), F0 = 0.3 N
/// (a displacement scale F0/k of 1.5 mm).
const MASS: f64 = 0.5;
const STIFFNESS: f64 = 200.0;
const TRUE_GAMMA: f64 = 2.0;
const TRUE_F0: f64 = 0.3;

fn truth() -> Experiment {
    Experiment::mechanics(Mechanics::new(MASS, STIFFNESS, TRUE_GAMMA, TRUE_F0).unwrap()).unwrap()
}

/// The starting point of the fits: the known m and k, γ and F0 off by 25 % and 33 %.
fn start() -> Experiment {
    Experiment::mechanics(Mechanics::new(MASS, STIFFNESS, 1.5, 0.4).unwrap()).unwrap()
}

/// A plain CSV (`time_s,F (N),r (m)`) of the steady motion at (w, β, φ): 2400 samples over
/// 3.4 drive periods, each channel quantised to 8 bits of a screen 1.25 times its
/// peak-to-peak with one step of Gaussian noise, and an offset of r by `offset` m.
fn record(w: f64, beta: f64, phi: f64, offset: f64, rng: &mut Rng) -> String {
    let e = driven(truth(), w, beta, phi);
    let n = 2400;
    let increment = 3.4 * TAU / (w * e.scales().unwrap().omega0) / n as f64;
    let s = sample_steady(&e, n, increment);
    let displacement: Vec<f64> = s.response.iter().map(|r| r + offset).collect();
    let force = quantise(&s.drive, 256.0, 1.0, rng);
    let displacement = quantise(&displacement, 256.0, 1.0, rng);
    timed(
        &Synthetic::new(force, displacement, 0.0, increment),
        "time_s,F (N),r (m)\n",
    )
}

/// Two drive frequencies: well below resonance with stick-slip, and near it sliding (where
/// the amplitude is set by the damping).
const DRIVES: [(f64, f64, f64, f64); 2] = [(0.45, 2.6, 0.4, 2e-4), (0.95, 2.0, -1.1, -1e-4)];

fn records(rng: &mut Rng) -> Vec<Measurement> {
    DRIVES
        .iter()
        .enumerate()
        .map(|(i, &(w, beta, phi, offset))| {
            let text = record(w, beta, phi, offset, rng);
            let r = read_scope(&text, &format!("mech{i}.csv")).unwrap();
            Measurement::new(&r, None, None).unwrap()
        })
        .collect()
}

const FREE: [FitParameter; 2] = [FitParameter::Damping, FitParameter::Friction];

fn fit(data: &[Measurement]) -> FitReport {
    fit_records(&start(), data, &FREE, &FitOptions::default()).unwrap()
}

#[test]
fn a_mechanical_fit_recovers_gamma_and_f0() {
    let mut rng = Rng(2027);
    let data = records(&mut rng);
    assert_eq!(
        (data[0].drive_unit.as_str(), data[0].response_unit.as_str()),
        ("N", "m")
    );
    let report = fit(&data);
    assert!(report.converged, "{report:?}");
    assert_eq!(report.jacobian, Jacobian::Exact);
    let classes: Vec<MotionClass> = report.records.iter().map(|r| r.class).collect();
    assert!(classes.contains(&MotionClass::PeriodicStick), "{classes:?}");
    assert!(classes.contains(&MotionClass::Sliding), "{classes:?}");
    for (p, truth) in [
        (FitParameter::Damping, TRUE_GAMMA),
        (FitParameter::Friction, TRUE_F0),
    ] {
        let v = report.value(p).unwrap();
        assert!(
            (v.value / truth - 1.0).abs() < 0.01,
            "{p} = {} ± {}",
            v.value,
            v.stderr
        );
        assert!(
            v.ci95[0] <= truth && truth <= v.ci95[1],
            "{p}: {:?} does not cover {truth}",
            v.ci95
        );
    }
    let chi2 = report.chi2_dof.unwrap();
    assert!((0.7..1.5).contains(&chi2), "chi2/dof = {chi2}");
    // The offsets of r, in metres; the drive in newtons; β = F/F0 at the fitted F0.
    assert!(
        (report.records[0].offset_v - 2e-4).abs() < 2e-5,
        "{report:?}"
    );
    assert!(
        (report.records[1].offset_v + 1e-4).abs() < 2e-5,
        "{report:?}"
    );
    let f0 = report.value(FitParameter::Friction).unwrap().value;
    for (rec, &(w, beta, _, _)) in report.records.iter().zip(&DRIVES) {
        assert!(
            (rec.amplitude_v / (beta * TRUE_F0) - 1.0).abs() < 2e-3,
            "{rec:?}"
        );
        assert!((rec.beta - rec.amplitude_v / f0).abs() < 1e-9 * rec.beta);
        assert!((rec.w / w - 1.0).abs() < 2e-3, "{rec:?}");
    }
    assert_eq!(report.units(), ("N", "m"));
    let json = serde_json::to_value(report.to_json()).unwrap();
    assert_eq!(json["units"]["drive"], "N");
    assert_eq!(json["units"]["response"], "m");
    assert!(json["parameters"]["damping"]["value"].is_number());
    assert!(json["parameters"]["friction"]["ci95"][1].is_number());
    // Finite differences reach the same minimum (the chain rule through the mechanical
    // scales is checked column by column in the library's unit test).
    let options = FitOptions {
        exact_jacobian: false,
        ..FitOptions::default()
    };
    let fd = fit_records(&start(), &data, &FREE, &options).unwrap();
    assert_eq!(fd.jacobian, Jacobian::FiniteDifferences);
    for (a, b) in report.parameters.iter().zip(&fd.parameters) {
        assert!(
            (a.value - b.value).abs() < 0.05 * a.stderr,
            "{}: {} (exact) against {} (finite differences) ± {}",
            a.parameter,
            a.value,
            b.value,
            a.stderr
        );
        assert!((a.stderr / b.stderr - 1.0).abs() < 0.01, "{a:?} {b:?}");
    }
    // The fitted experiment holds the fitted values and the known ones.
    match report.experiment.system() {
        Some(stickslip::physical::System::Mechanics(m)) => {
            assert_eq!((m.mass, m.stiffness), (MASS, STIFFNESS));
            assert_eq!(m.friction, f0);
        }
        other => panic!("{other:?}"),
    }
}

#[test]
fn the_95_percent_intervals_cover_gamma_and_f0_in_90_of_100_draws() {
    let mut rng = Rng(0x0bad_cafe);
    let (mut gamma_in, mut f0_in) = (0, 0);
    for _ in 0..100 {
        let report = fit(&records(&mut rng));
        let gamma = report.value(FitParameter::Damping).unwrap();
        let f0 = report.value(FitParameter::Friction).unwrap();
        gamma_in += usize::from(gamma.ci95[0] <= TRUE_GAMMA && TRUE_GAMMA <= gamma.ci95[1]);
        f0_in += usize::from(f0.ci95[0] <= TRUE_F0 && TRUE_F0 <= f0.ci95[1]);
    }
    eprintln!("95 % intervals: gamma covered the truth {gamma_in}, F0 {f0_in} times of 100");
    assert!(
        gamma_in >= 90 && f0_in >= 90,
        "gamma covered {gamma_in}, F0 covered {f0_in} of 100"
    );
}

#[test]
fn parameters_of_the_other_twin_and_volts_are_refused() {
    let mut rng = Rng(7);
    let data = records(&mut rng);
    let options = FitOptions::default();
    // A circuit's parameter on a mechanical oscillator, naming what is allowed.
    let e = fit_records(&start(), &data, &[FitParameter::Resistance], &options).unwrap_err();
    assert_eq!(
        e.to_string(),
        "resistance is not a parameter of a mechanical oscillator (its parameters are damping, \
         friction, mass, stiffness, mu-s, stribeck-speed, viscous-friction)"
    );
    let e = fit_records(
        &start(),
        &data,
        &[FitParameter::Damping, FitParameter::Ut],
        &options,
    )
    .unwrap_err();
    assert!(e
        .to_string()
        .starts_with("ut is not a parameter of a mechanical"));
    // A mechanical parameter on a circuit.
    let e = fit_records(
        &Experiment::paper(),
        &data,
        &[FitParameter::Friction],
        &options,
    )
    .unwrap_err();
    assert_eq!(
        e.to_string(),
        "friction is not a parameter of a circuit (its parameters are resistance, ut, rd, \
         diode-is, diode-n, diode-rs, inductance, capacitance, mu-s)"
    );
    // A mechanical record on a circuit, a record in volts on a mechanical oscillator.
    let e = fit_records(&Experiment::paper(), &data, &[FitParameter::Ut], &options).unwrap_err();
    assert!(
        e.to_string()
            .starts_with("mech0.csv: a circuit is fitted to voltages"),
        "{e}"
    );
    let volts = record(0.45, 2.6, 0.4, 0.0, &mut rng).replace("F (N),r (m)", "u_V,uc_V");
    let volts = Measurement::new(&read_scope(&volts, "volts.csv").unwrap(), None, None).unwrap();
    let e = fit_records(&start(), &[volts], &FREE, &options).unwrap_err();
    assert_eq!(
        e.to_string(),
        "volts.csv: a mechanical oscillator is fitted to a drive force in N and a displacement \
         in m (name the columns with their units, e.g. `F (N)` and `r (m)`); the record gives \
         the drive u_V in V and the response uc_V in V"
    );
    // A table of amplitudes is read in volts.
    let table = read_amplitudes("freq_Hz,U_V,response_V\n1,1,1\n2,1,1\n3,1,1\n", "t.csv").unwrap();
    let e = fit_table(&start(), &table, &FREE, &options).unwrap_err();
    assert!(e.to_string().contains("fitted to records"), "{e}");
    // The symbols of the key table name the same parameters.
    assert_eq!(
        "gamma".parse::<FitParameter>().unwrap(),
        FitParameter::Damping
    );
    assert_eq!(
        "F0".parse::<FitParameter>().unwrap(),
        FitParameter::Friction
    );
}
