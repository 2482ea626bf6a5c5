//! The two records of the mechanical fit in docs/fit.md (`examples/fit/mechanics/slow.csv`
//! and `near.csv`), committed so that the page's command and Python snippet run as written
//! (the docs' test runs them). This test makes them again and requires the committed files
//! byte for byte; with `STICKSLIP_BLESS=1` it writes them.
//!
//! A mass of 0.5 kg on a spring of 200 N/m (ω0 = 20 rad/s, f0 = 3.18 Hz) with viscous
//! damping γ = 2 N·s/m (ζ = 0.1) and dry friction F0 = 0.3 N, driven at w = 0.45 with
//! β = 2.6 (stick-slip: `slow.csv`) and at w = 0.95 with β = 2.0 (sliding: `near.csv`); the
//! steady motion by the exact solver, 2400 samples over 3.4 drive periods, each channel
//! quantised to 8 bits of a screen 1.25 times its peak-to-peak with one step of Gaussian
//! noise (seeded), and an offset of r (+0.2 mm, −0.1 mm): the records of
//! `tests/fit_mechanics.rs`, as a plain CSV `time_s,F (N),r (m)`.

use std::f64::consts::TAU;
use std::path::PathBuf;
use stickslip::experiment::Experiment;
use stickslip::measure::{read_scope, Measurement};
use stickslip::physical::Mechanics;
use stickslip_testkit::{driven, quantise, sample_steady, timed, Rng, Synthetic};

fn truth() -> Experiment {
    Experiment::mechanics(Mechanics::new(0.5, 200.0, 2.0, 0.3).unwrap()).unwrap()
}

/// The record of the steady motion at (w, β, φ) with an offset of r (m).
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

#[test]
fn the_committed_mechanical_records_are_what_the_exact_solver_makes() {
    let dir = PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../examples/fit/mechanics");
    let bless = std::env::var("STICKSLIP_BLESS").is_ok_and(|v| v != "0");
    let mut rng = Rng(2027);
    let mut stale = Vec::new();
    for (file, w, beta, phi, offset) in [
        ("slow.csv", 0.45, 2.6, 0.4, 2e-4),
        ("near.csv", 0.95, 2.0, -1.1, -1e-4),
    ] {
        let text = record(w, beta, phi, offset, &mut rng);
        let m = Measurement::new(&read_scope(&text, file).unwrap(), None, None).unwrap();
        assert_eq!(
            (m.drive_unit.as_str(), m.response_unit.as_str()),
            ("N", "m")
        );
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
        "examples/fit/mechanics: {stale:?} differ from what this test makes; \
         STICKSLIP_BLESS=1 cargo test --release -p stickslip --test fit_mechanics_records \
         writes them"
    );
}
