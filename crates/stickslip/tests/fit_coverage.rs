//! Do the fit's 95 % intervals hold the truth 95 % of the time? Coverage over 100 noise draws
//! of the same truth, for each law:
//!
//! - **Shockley**: the five records of the 1N914-like bench (`stickslip_testkit::ngspice`:
//!   L = 10 mH, C = 47 nF, R = 120 Ω, two diodes of IS = 2.52 nA, N = 1.752, RS = 0.568 Ω,
//!   driven from 2 to 11 kHz; 1200 to 2800 samples; Rigol, Keysight, a Tektronix pair,
//!   Siglent and a plain CSV), made by ngspice once (the committed traces) and drawn with
//!   100 seeds of 8-bit quantisation and one code of Gaussian noise, each fitted with I_s, n
//!   and R_s free (R, L and C as built). Every draw starts where the fit of the noise-free
//!   traces (rounded to the converter's codes, fitted from the 1N4148's values) ends: the
//!   minimum the noise moves about, so that the draws do not each search the I_s–n valley
//!   again (the search itself is tested in `fit_shockley` and the CLI's `--compare` tests);
//! - **PWL**: three records of the exact solver's circuit at R = 80 Ω, U_t = 0.6 V
//!   (stick-slip and sliding, 1200 samples each), 100 seeds of noise, R and U_t free from the
//!   paper's values.
//!
//! Each interval must hold the truth in 90 to 99 of the 100 draws (the binomial 95 % range of
//! a 95 % interval over 100 draws is 90 … 99), and every fit must converge. The draws run in
//! parallel, each from its own seed (the counts do not depend on the threads); `--
//! --nocapture` prints each draw's distances from the truth in standard errors and the
//! counts. Cost: about 100 CPU seconds for both tests together (each Shockley fit of five
//! records under a second on one core).

use rayon::prelude::*;
use stickslip::experiment::Experiment;
use stickslip::fit::{fit_records, FitOptions, FitParameter, FitReport};
use stickslip::measure::{read_scope, Measurement};
use stickslip::DiodePair;
use stickslip_testkit::ngspice::D1N914;
use stickslip_testkit::{keysight, synthesise, Rng, TRUE_R, TRUE_UT};

const DRAWS: u64 = 100;

/// Per free parameter, the draws whose interval holds the truth; the draws that converged.
fn coverage(
    name: &str,
    truth: &[f64],
    fit: impl Fn(u64) -> FitReport + Sync,
) -> (Vec<usize>, usize) {
    let reports: Vec<FitReport> = (0..DRAWS).into_par_iter().map(&fit).collect();
    let mut held = vec![0; truth.len()];
    let mut converged = 0;
    for (seed, r) in reports.iter().enumerate() {
        let z: Vec<String> = r
            .parameters
            .iter()
            .zip(truth)
            .map(|(p, t)| format!("{:+.2}", (p.value - t) / p.stderr))
            .collect();
        eprintln!(
            "{name} draw {seed}: z = {}, chi2/dof {:.3}, {} iterations{}",
            z.join(" "),
            r.chi2_dof.unwrap_or(f64::NAN),
            r.iterations,
            if r.converged { "" } else { ", NOT converged" }
        );
        for ((p, t), count) in r.parameters.iter().zip(truth).zip(&mut held) {
            if p.ci95[0] <= *t && *t <= p.ci95[1] {
                *count += 1;
            }
        }
        converged += usize::from(r.converged);
    }
    eprintln!(
        "{name}: the intervals hold the truth in {held:?} of {DRAWS} draws; {converged} converged"
    );
    (held, converged)
}

fn check(name: &str, free: &[FitParameter], held: &[usize], converged: usize) {
    for (p, &count) in free.iter().zip(held) {
        assert!(
            (90..=99).contains(&count),
            "{name}: the 95 % interval of {p} holds the truth in {count} of {DRAWS} draws"
        );
    }
    assert_eq!(
        converged as u64, DRAWS,
        "{name}: fits that did not converge"
    );
}

#[test]
fn shockley_intervals_hold_their_coverage_on_ngspice_records() {
    let bench = D1N914;
    let free = [
        FitParameter::DiodeIs,
        FitParameter::DiodeN,
        FitParameter::DiodeRs,
    ];
    let from = Experiment::circuit(bench.circuit())
        .unwrap()
        .with_shockley(DiodePair::one_n4148())
        .unwrap();
    let noise_free: Vec<Measurement> = bench
        .measurements_with_noise(0, 0.0)
        .into_iter()
        .map(|(_, m)| m)
        .collect();
    let pilot = fit_records(&from, &noise_free, &free, &FitOptions::default()).unwrap();
    eprintln!(
        "shockley: the noise-free traces fit to {:?} (chi2/dof {:.3}, converged {})",
        pilot.parameters.iter().map(|p| p.value).collect::<Vec<_>>(),
        pilot.chi2_dof.unwrap_or(f64::NAN),
        pilot.converged
    );
    // Noise-free records fitted down to their rounding converge (the data's precision is
    // the floor of the convergence criteria, see docs/fit.md).
    assert!(pilot.converged, "{:?}", pilot.warnings);
    let start = pilot.experiment;
    let (held, converged) = coverage("shockley", &[bench.is, bench.n, bench.rs], |seed| {
        let data: Vec<Measurement> = bench
            .measurements(0x5eed_0000 + seed)
            .into_iter()
            .map(|(_, m)| m)
            .collect();
        fit_records(&start, &data, &free, &FitOptions::default()).unwrap()
    });
    check("shockley", &free, &held, converged);
}

#[test]
fn pwl_intervals_hold_their_coverage() {
    let free = [FitParameter::Resistance, FitParameter::Ut];
    let start = Experiment::paper();
    let (held, converged) = coverage("pwl", &[TRUE_R, TRUE_UT], |seed| {
        let mut rng = Rng(0x9e37_79b9 + seed);
        let data: Vec<Measurement> = [(0.29, 2.6, 0.4), (0.95, 2.14, -1.1), (1.43, 3.0, 2.5)]
            .iter()
            .map(|&(w, beta, phi)| {
                let s = synthesise(w, beta, phi, 0.02, 1.0, &mut rng);
                let r = read_scope(&keysight(&s), "k.csv").unwrap();
                Measurement::new(&r, None, None).unwrap()
            })
            .collect();
        fit_records(&start, &data, &free, &FitOptions::default()).unwrap()
    });
    check("pwl", &free, &held, converged);
}
