//! The theory module against values computed by hand from the paper's equations, Den Hartog's
//! closed form, independent quadrature, and simulation with the exact solver.
//!
//! Random parameters come from a fixed-seed generator, so every run checks the same cases.

// Hand values are quoted with the 17 significant digits they were computed to.
#![allow(clippy::excessive_precision)]

mod common;

use common::gauss_legendre;
use std::f64::consts::{FRAC_PI_2, PI, TAU};
use stickslip::theory::{
    paper_boundary, stick_slip_boundary, Obstruction, PaperHarmonic, PaperSeries, PeriodicSolution,
    UndampedSeries,
};
use stickslip::{Error, Event, EventKind, ExactSolver, Params, Solver, State};

// ---------------------------------------------------------------------------------------------
// Helpers: a seeded generator, Gauss–Legendre quadrature, and a simulation harness.

/// xorshift64*: a small deterministic generator for parameter grids.
struct Rng(u64);

impl Rng {
    fn next(&mut self) -> f64 {
        self.0 ^= self.0 >> 12;
        self.0 ^= self.0 << 25;
        self.0 ^= self.0 >> 27;
        (self.0.wrapping_mul(0x2545_F491_4F6C_DD1D) >> 11) as f64 / (1u64 << 53) as f64
    }

    fn uniform(&mut self, lo: f64, hi: f64) -> f64 {
        lo + (hi - lo) * self.next()
    }

    fn log_uniform(&mut self, lo: f64, hi: f64) -> f64 {
        (lo.ln() + (hi.ln() - lo.ln()) * self.next()).exp()
    }
}

/// ∫ₐᵇ f, composite 16-point Gauss–Legendre on pieces no longer than 0.25.
fn integrate(
    a: f64,
    b: f64,
    rule: &[(f64, f64)],
    f: &mut impl FnMut(f64) -> (f64, f64),
) -> (f64, f64) {
    let pieces = ((b - a) / 0.25).ceil().max(1.0) as usize;
    let h = (b - a) / pieces as f64;
    let (mut re, mut im) = (0.0, 0.0);
    for j in 0..pieces {
        let mid = a + (j as f64 + 0.5) * h;
        for &(x, wt) in rule {
            let (fr, fi) = f(mid + 0.5 * h * x);
            re += 0.5 * h * wt * fr;
            im += 0.5 * h * wt * fi;
        }
    }
    (re, im)
}

#[test]
fn gauss_legendre_integrates_polynomials_and_trigonometry() {
    let rule = gauss_legendre(16);
    for k in 0..=31 {
        let (got, _) = integrate(0.0, 1.0, &rule[..], &mut |x| (x.powi(k), 0.0));
        assert!((got - 1.0 / (k as f64 + 1.0)).abs() < 1e-14, "x^{k}");
    }
    let (got, _) = integrate(0.0, 10.0, &rule, &mut |x| ((3.0 * x).cos(), 0.0));
    assert!((got - (30.0f64).sin() / 3.0).abs() < 1e-14);
}

/// The exact solver fed period by period, refusing to spin in place.
struct Sim {
    solver: ExactSolver,
    events: Vec<Event>,
}

/// The solver stopped advancing in time: it alternated stick and slip at one instant.
#[derive(Debug)]
struct Stalled {
    tau: f64,
}

impl Sim {
    fn new(params: Params, initial: State) -> Self {
        Self {
            solver: ExactSolver::new(params, initial),
            events: Vec::new(),
        }
    }

    /// Advance to `tau`, recording events and handing each covered interval to `piece`.
    fn run_to(
        &mut self,
        tau: f64,
        mut piece: impl FnMut(&ExactSolver, f64, f64),
    ) -> Result<(), Stalled> {
        let mut idle = 0;
        while self.solver.time() < tau {
            let before = self.solver.time();
            if let Some(e) = self.solver.advance(tau).expect("the exact solver advances") {
                self.events.push(e);
            }
            let (from, to) = self.solver.interval();
            if to > from {
                piece(&self.solver, from, to);
            }
            if self.solver.time() == before {
                idle += 1;
                if idle > 100 {
                    return Err(Stalled { tau: before });
                }
            } else {
                idle = 0;
            }
        }
        Ok(())
    }

    fn sticks_after(&self, tau: f64) -> usize {
        self.events
            .iter()
            .filter(|e| e.tau > tau && e.kind == EventKind::Stick)
            .count()
    }
}

/// Peak |y| at the turning points and fundamental amplitude A1 of one simulated period
/// [τ0, τ0 + T], the latter from Gauss–Legendre quadrature of the dense output piece by
/// piece (y is smooth between events). Also the kinds of the events in that period.
fn simulated_period(sim: &mut Sim, params: &Params, tau0: f64) -> (f64, f64, Vec<EventKind>) {
    let period = params.drive_period();
    let rule = gauss_legendre(16);
    let first = sim.events.len();
    let (mut re, mut im) = (0.0, 0.0);
    sim.run_to(tau0 + period, |s, from, to| {
        let (r, i) = integrate(from, to, &rule, &mut |tau| {
            let y = s.dense(tau).y;
            let (sn, cs) = (params.w * tau).sin_cos();
            (y * cs, -y * sn)
        });
        re += r;
        im += i;
    })
    .expect("no stall on a sliding orbit");
    let events = &sim.events[first..];
    let peak = events
        .iter()
        .filter(|e| e.kind == EventKind::Turn)
        .map(|e| e.y.abs())
        .fold(0.0, f64::max);
    let a1 = 2.0 / period * re.hypot(im);
    (peak, a1, events.iter().map(|e| e.kind).collect())
}

/// Run period by period until the strobe state stops changing (to 1e-12 relative, three
/// times in a row; rounding of the drive phase wτ grows with τ) or `max_periods` pass;
/// returns the number of periods run.
fn settle(sim: &mut Sim, params: &Params, scale: f64, max_periods: usize) -> usize {
    let period = params.drive_period();
    let mut last = sim.solver.state();
    let mut quiet = 0;
    for k in 1..=max_periods {
        sim.run_to(k as f64 * period, |_, _, _| {})
            .expect("no stall while settling");
        let s = sim.solver.state();
        let change = (s.y - last.y).hypot(s.v - last.v);
        last = s;
        quiet = if change <= 1e-12 * scale {
            quiet + 1
        } else {
            0
        };
        if quiet == 3 {
            return k;
        }
    }
    max_periods
}

// ---------------------------------------------------------------------------------------------
// The paper's formulas, literally.

/// Values of eqs. (9), (11) and (13) evaluated by hand (30-digit arithmetic, mpmath), with
/// ω0 = 1, Ω = w, α = 2ζ substituted in the printed formulas:
/// Z = √((ω0² − Ω²)² + α²Ω²), A1 = (−4αΩ + √(π²β²Z² − 16(Ω² − ω0²)²))/(πZ²),
/// φ0 = arccos((ω0² − Ω²)A1/β), A_k = (4/(kπ))/√((ω0² − k²Ω²)² + α²k²Ω²),
/// φ_k = −π/2 − arctan(αkΩ/(ω0² − k²Ω²)). The first three points are the paper's Fig. 3 (2a–c)
/// drives with its circuit's ζ = α/(2ω0) = 6173.9/(2·65938.0) ≈ 0.0468.
#[test]
fn eq11_reproduces_hand_values() {
    // (ζ, w, β) → A1, φ0, A3, φ3, A5, φ5
    let cases: [((f64, f64, f64), [f64; 6]); 5] = [
        (
            (0.0468, 0.95, 2.14),
            [
                8.0643364788367642,
                1.1945658716819559,
                0.059545921259444605,
                -1.5333606829298712,
                0.01180724844559112,
                -1.5501801176793528,
            ],
        ),
        (
            (0.0468, 1.43, 2.14),
            [
                1.4864030671341421,
                2.3829457930515314,
                0.024379328281879591,
                -1.5477286143385539,
                0.0050800581154460424,
                -1.557445032786331,
            ],
        ),
        (
            (0.0468, 0.29, 2.14),
            [
                1.8364177887944098,
                0.66653341788797698,
                1.6554309715248454,
                -1.8940220901784849,
                0.22924270638846248,
                -1.448310526517731,
            ],
        ),
        (
            (0.2, 0.5, 3.0),
            [
                3.1023595179526607,
                0.68314728594249611,
                0.30609461526910841,
                -1.1232763516377267,
                0.047647707012858823,
                -1.3825748214901258,
            ],
        ),
        (
            (0.0468, 0.33, 7.1),
            [
                7.7845001225677724,
                0.21484436920174829,
                4.478031903408026,
                -2.930051271913467,
                0.147245564012134,
                -1.4813750566089937,
            ],
        ),
    ];
    for ((zeta, w, beta), want) in cases {
        let s = PaperSeries::new(zeta, w, beta).unwrap();
        let h3 = s.harmonic(2).unwrap();
        let h5 = s.harmonic(3).unwrap();
        let got = [s.a1, s.phi0, h3.amplitude, h3.phase, h5.amplitude, h5.phase];
        for (i, (g, e)) in got.iter().zip(want).enumerate() {
            assert!(
                (g - e).abs() <= 1e-13 * e.abs().max(1.0),
                "ζ {zeta} w {w} β {beta} field {i}: {g} vs {e}"
            );
        }
        assert_eq!((h3.order, h5.order), (3, 5));
        assert!((s.gain1() - s.a1 / beta).abs() == 0.0);
    }
}

/// Eq. (9) by hand: A1 = √(β² − (4/π)²)/(ω0² − Ω²), φ0 = arcsin(4/(βπ)),
/// A_{2n−1} = 4/((2n−1)π[(2n−1)²Ω² − ω0²]).
#[test]
fn eq9_reproduces_hand_values() {
    let cases = [
        (
            (0.5, 2.0),
            [
                2.0564742478210811,
                0.69010709137453995,
                0.33953054526271005,
                0.048504363608958579,
            ],
        ),
        (
            (1.43, 3.0),
            [
                -2.5996802649689809,
                0.43831370455148585,
                0.024385816076578944,
                0.0050805109271690869,
            ],
        ),
    ];
    for ((w, beta), want) in cases {
        let s = UndampedSeries::new(w, beta).unwrap();
        let got = [s.a1, s.phi0, s.harmonic(2).unwrap(), s.harmonic(3).unwrap()];
        for (g, e) in got.iter().zip(want) {
            assert!(
                (g - e).abs() <= 1e-13 * e.abs(),
                "w {w} β {beta}: {g} vs {e}"
            );
        }
    }
}

/// The harmonic balance of the paper's eq. (7), x'' + x − Σ (4/(kπ)) sin(kwτ) = β cos(wτ + φ0)
/// with x = A1 cos wτ + Σ A_k sin kwτ, needs (1 − k²w²)A_k = 4/(kπ): eq. (9) as printed has the
/// opposite sign, while |A_k| agrees with eq. (11) at ζ = 0. The fundamental balances.
#[test]
fn eq9_superharmonic_sign_disagrees_with_the_balance_of_eq7() {
    for &(w, beta) in &[(0.22, 2.0), (0.5, 3.0), (1.5, 4.0)] {
        let s = UndampedSeries::new(w, beta).unwrap();
        for n in 2..=4u32 {
            let k = f64::from(2 * n - 1);
            let printed = s.harmonic(n).unwrap();
            let residual = |a: f64| (1.0 - k * k * w * w) * a - 4.0 / (k * PI);
            assert!(residual(printed).abs() > 1e-3, "w {w} k {k}");
            assert!(residual(-printed).abs() < 1e-14, "w {w} k {k}");
            let damped = PaperHarmonic::new(0.0, w, 2 * n - 1).unwrap();
            assert!((damped.amplitude - printed.abs()).abs() < 1e-15);
        }
        // Fundamental: cos and sin parts of (1 − w²)A1 cos − (4/π) sin = β cos(wτ + φ0).
        let (sin0, cos0) = s.phi0.sin_cos();
        assert!(((1.0 - w * w) * s.a1 - beta * cos0).abs() < 1e-13 * beta);
        assert!((4.0 / PI - beta * sin0).abs() < 1e-13 * beta);
    }
}

/// Eq. (11)'s φ_k with the principal arctan equals the phase of the linear response to the
/// friction's harmonic −(4/(kπ)) sin(kwτ)·(−1) below kw = 1 and is off by π above it.
#[test]
fn eq11_phase_is_off_by_pi_above_kw_one() {
    let zeta = 0.1;
    for &(w, order) in &[(0.2, 3u32), (0.25, 3), (0.4, 3), (0.15, 5), (0.3, 5)] {
        let h = PaperHarmonic::new(zeta, w, order).unwrap();
        let k = f64::from(order);
        // Response to (4/(kπ)) sin(kwτ) = (4/(kπ)) cos(kwτ − π/2): phase −π/2 − arg(H_k).
        let balance = -FRAC_PI_2 - (2.0 * zeta * k * w).atan2(1.0 - k * k * w * w);
        assert!((h.balance_phase(zeta, w) - balance).abs() < 1e-15);
        let gap = (h.phase - balance).rem_euclid(TAU);
        if k * w < 1.0 {
            assert!(gap < 1e-12 || TAU - gap < 1e-12, "w {w} k {k}: {gap}");
        } else {
            assert!((gap - PI).abs() < 1e-12, "w {w} k {k}: {gap}");
        }
    }
}

/// Eq. (13), −A1 + 1 + β cos φ0 = 0 with eq. (11)'s A1 and φ0, holds at the closed form, and
/// a bisection on β of the literal eq. (11) lands there; hand values (mpmath bisection of eq.
/// (13)) agree.
#[test]
fn eq13_boundary_is_the_root_of_the_printed_condition() {
    for &(zeta, w, by_hand) in &[
        (0.0468, 0.9, 1.3970722471912139),
        (0.2, 2.0, 1.6531590232556182),
        (0.0, 0.5, 3.2590088889534199),
    ] {
        let beta_c = paper_boundary(zeta, w).unwrap();
        assert!(
            (beta_c - by_hand).abs() < 1e-14 * by_hand,
            "{beta_c} vs {by_hand}"
        );
        let s = PaperSeries::new(zeta, w, beta_c).unwrap();
        assert!((-s.a1 + 1.0 + beta_c * s.phi0.cos()).abs() < 1e-12);
        let (mut lo, mut hi) = (4.0 / PI, 1e4);
        for _ in 0..200 {
            let mid = 0.5 * (lo + hi);
            if w * w * PaperSeries::new(zeta, w, mid).unwrap().a1 < 1.0 {
                lo = mid;
            } else {
                hi = mid;
            }
        }
        assert!((hi - beta_c).abs() < 1e-12 * beta_c);
    }
    for &zeta in &[0.0, 0.05, 0.3] {
        for &w in &[0.05, 0.3, 0.8, 1.2, 4.0, 10.0] {
            let beta_c = paper_boundary(zeta, w).unwrap();
            let below = PaperSeries::new(zeta, w, beta_c * (1.0 - 1e-9)).unwrap();
            let above = PaperSeries::new(zeta, w, beta_c * (1.0 + 1e-9)).unwrap();
            assert!(!below.slides_by_eq13() && above.slides_by_eq13());
        }
    }
}

#[test]
fn formulas_without_a_real_solution_say_so() {
    let no = |r: Result<f64, Error>| matches!(r, Err(Error::NoSolution { .. }));
    // The paper's own low-drive experiments (β = 1.07 < 4/π, Fig. 3 (1a–c)): no positive A1.
    for &w in &[0.29, 0.95, 1.43] {
        assert!(no(PaperSeries::new(0.0468, w, 1.07).map(|s| s.a1)));
    }
    assert!(no(PaperSeries::new(0.0, 1.0, 3.0).map(|s| s.a1)));
    assert!(no(paper_boundary(0.0, 1.0)));
    assert!(no(UndampedSeries::new(0.7, 1.2).map(|s| s.a1)));
    assert!(no(UndampedSeries::new(1.0, 3.0).map(|s| s.a1)));
    assert!(no(PaperHarmonic::new(0.0, 0.2, 5).map(|h| h.amplitude)));
    assert!(matches!(
        PaperSeries::new(-0.1, 1.0, 2.0),
        Err(Error::InvalidParameter { name: "zeta", .. })
    ));
}

// ---------------------------------------------------------------------------------------------
// The exact periodic solution.

/// Den Hartog (1930), ζ = 0: Y = √((β/(1 − w²))² − U²), U = sin(π/w)/(w(1 + cos(π/w))).
#[test]
fn undamped_amplitude_is_den_hartogs() {
    for &(w, beta) in &[
        (0.7, 2.0),
        (0.85, 1.5),
        (1.3, 2.0),
        (2.0, 3.0),
        (6.0, 2.5),
        (0.4, 9.0),
    ] {
        let s = PeriodicSolution::new(&Params::new(0.0, w, beta).unwrap()).unwrap();
        let u = (PI / w).sin() / (w * (1.0 + (PI / w).cos()));
        let den_hartog = ((beta / (1.0 - w * w)).powi(2) - u * u).sqrt();
        assert!(
            (s.peak - den_hartog).abs() < 1e-12 * den_hartog,
            "w {w} β {beta}: {} vs {den_hartog}",
            s.peak
        );
    }
}

/// The orbit starts and ends its half period at rest at ∓Y, is odd under a half-period shift,
/// slides up with positive velocity (checked on a fine grid, independently of the solver), and
/// leaves its turning points with more net force than static friction holds.
#[test]
fn orbit_is_symmetric_turns_at_rest_and_slides_throughout() {
    let mut rng = Rng(0x5eed_0001);
    for _ in 0..40 {
        let zeta = rng.uniform(0.0, 0.5);
        let w = rng.log_uniform(0.1, 8.0);
        let mu_s = 1.0 + rng.uniform(0.0, 0.3) * rng.next();
        let Ok(b) = stick_slip_boundary(zeta, w, mu_s) else {
            continue;
        };
        let beta = b.beta_c * rng.uniform(1.001, 4.0);
        let params = Params::new(zeta, w, beta)
            .unwrap()
            .with_phi(rng.uniform(-3.0, 3.0))
            .unwrap()
            .with_mu_s(mu_s)
            .unwrap();
        let s = PeriodicSolution::new(&params).unwrap();
        let (t0, half) = (s.first_lower_turn(), PI / w);
        let tol = 1e-11 * s.peak.max(1.0);
        let start = s.state_at(t0);
        let end = s.state_at(t0 + half);
        assert!((start.y + s.peak).abs() < tol && start.v.abs() < tol);
        assert!((end.y - s.peak).abs() < tol && end.v.abs() < tol);
        assert!(
            ((params.w * t0 + params.phi) - s.turn_phase)
                .rem_euclid(TAU)
                .min(TAU - ((params.w * t0 + params.phi) - s.turn_phase).rem_euclid(TAU))
                < 1e-12
        );
        let force = params.drive(t0) - start.y;
        assert!((force - s.turn_force).abs() < tol && force > mu_s);
        for j in 1..2000 {
            let tau = t0 + half * j as f64 / 2000.0;
            let a = s.state_at(tau);
            let b = s.state_at(tau + half);
            assert!((a.y + b.y).abs() < tol && (a.v + b.v).abs() < tol);
            assert!(a.v > 0.0, "ζ {zeta} w {w} β {beta}: v = {} at {j}", a.v);
        }
    }
}

/// The exact harmonics (integrated in closed form) against 16-point Gauss–Legendre quadrature
/// of the orbit over one period, split at the turning points.
#[test]
fn harmonics_match_quadrature_of_the_orbit() {
    let rule = gauss_legendre(16);
    let mut rng = Rng(0x5eed_0002);
    for _ in 0..20 {
        let zeta = rng.uniform(0.0, 2.0);
        let w = rng.log_uniform(0.2, 5.0);
        let Ok(b) = stick_slip_boundary(zeta, w, 1.0) else {
            continue;
        };
        let params = Params::new(zeta, w, b.beta_c * rng.uniform(1.01, 3.0))
            .unwrap()
            .with_phi(rng.uniform(0.0, TAU))
            .unwrap();
        let s = PeriodicSolution::new(&params).unwrap();
        let (t0, half, period) = (s.first_lower_turn(), PI / w, TAU / w);
        for order in 1..=9u32 {
            let k = f64::from(order);
            let mut f = |tau: f64| {
                let y = s.state_at(tau).y;
                let psi = k * (w * tau + params.phi);
                (y * psi.cos(), -y * psi.sin())
            };
            let (r1, i1) = integrate(t0, t0 + half, &rule, &mut f);
            let (r2, i2) = integrate(t0 + half, t0 + period, &rule, &mut f);
            // y = Σ A_k cos(kψ + φ_k) ⇒ (2/T)∫ y e^{−ikψ} dτ = A_k e^{iφ_k}.
            let (re, im) = (2.0 / period * (r1 + r2), 2.0 / period * (i1 + i2));
            let h = s.harmonic(order);
            let scale = 1e-11 * s.peak.max(1.0);
            if order % 2 == 0 {
                assert!(re.hypot(im) < scale && h.amplitude == 0.0);
            } else {
                let (pr, pi) = (h.amplitude * h.phase.cos(), h.amplitude * h.phase.sin());
                assert!(
                    (re - pr).hypot(im - pi) < scale,
                    "ζ {zeta} w {w} k {order}: ({re}, {im}) vs ({pr}, {pi})"
                );
            }
        }
        assert!((s.gain1() - s.a1() / params.beta).abs() == 0.0);
        assert!((s.phase_lag() + s.harmonic(1).phase).abs() < 1e-15);
    }
}

/// The friction force of a symmetric sliding motion is exactly a square wave, so the
/// superharmonic amplitudes of eq. (11) are exact; A1 and every phase are not.
#[test]
fn eq11_superharmonic_amplitudes_are_exact() {
    for &(zeta, w, beta) in &[
        (0.0468, 0.95, 2.14),
        (0.0468, 1.43, 2.14),
        (0.2, 0.5, 6.0),
        (0.0, 0.7, 2.0),
    ] {
        let exact = PeriodicSolution::new(&Params::new(zeta, w, beta).unwrap()).unwrap();
        let paper = PaperSeries::new(zeta, w, beta).unwrap();
        for n in 2..=6u32 {
            let a = paper.harmonic(n).unwrap().amplitude;
            let e = exact.harmonic(2 * n - 1).amplitude;
            assert!(
                (a - e).abs() < 1e-13 * a,
                "ζ {zeta} w {w} n {n}: {a} vs {e}"
            );
        }
        assert!((paper.a1 - exact.a1()).abs() > 1e-6 * exact.a1());
    }
}

/// How far the paper's A1 is from the exact one: tens of percent just above the exact
/// boundary, under one percent at ten times it.
#[test]
fn paper_a1_is_poor_near_the_boundary_and_good_far_above() {
    let zeta = 0.0468;
    let mut worst: f64 = 0.0;
    for &w in &[0.7, 0.9, 0.95, 1.1, 1.43, 2.0, 5.0] {
        let b = stick_slip_boundary(zeta, w, 1.0).unwrap();
        let err = |f: f64| {
            let p = Params::new(zeta, w, b.beta_c * f).unwrap();
            let exact = PeriodicSolution::new(&p).unwrap().a1();
            (PaperSeries::new(zeta, w, p.beta).unwrap().a1 - exact).abs() / exact
        };
        worst = worst.max(err(1.0001));
        assert!(err(10.0) < 0.01, "w {w}: {}", err(10.0));
    }
    assert!(
        worst > 0.3,
        "worst relative error near the boundary {worst}"
    );
}

#[test]
fn resonances_and_small_drives_have_no_periodic_solution() {
    for &w in &[1.0, 1.0 / 3.0, 0.2, 1.0 / 7.0] {
        let p = Params::new(0.0, w, 50.0).unwrap();
        assert!(matches!(
            PeriodicSolution::solve(&p).unwrap(),
            Err(Obstruction::Resonance { order }) if (f64::from(order) * w - 1.0).abs() < 1e-12
        ));
        assert!(matches!(
            stick_slip_boundary(0.0, w, 1.0),
            Err(Error::NoSolution { .. })
        ));
    }
    // Below the fold, and between it and β_c.
    let b = stick_slip_boundary(0.0468, 0.9, 1.0).unwrap();
    for beta in [0.1, b.beta_c * 0.999] {
        let p = Params::new(0.0468, 0.9, beta).unwrap();
        assert!(matches!(
            PeriodicSolution::new(&p),
            Err(Error::NoSolution { .. })
        ));
    }
}

// ---------------------------------------------------------------------------------------------
// Against simulation.

/// The exact solver, started 5% off the orbit, settles onto it: peak and A1 of the simulated
/// steady state agree with the closed form to 1e-8 (relative), for damped random cases and
/// Den Hartog's undamped solution.
#[test]
fn exact_solution_is_the_simulated_steady_state() {
    let mut rng = Rng(0x5eed_0003);
    let mut cases: Vec<(f64, f64, f64)> = Vec::new();
    while cases.len() < 40 {
        let zeta = rng.uniform(0.02, 0.3);
        let w = rng.log_uniform(0.3, 4.0);
        let b = stick_slip_boundary(zeta, w, 1.0).unwrap();
        cases.push((zeta, w, b.beta_c * rng.uniform(1.05, 3.0)));
    }
    // Den Hartog, ζ = 0.
    cases.extend([
        (0.0, 0.7, 2.0),
        (0.0, 1.3, 2.0),
        (0.0, 2.0, 3.0),
        (0.0, 0.4, 9.0),
    ]);
    let mut worst: f64 = 0.0;
    for (zeta, w, beta) in cases {
        let params = Params::new(zeta, w, beta).unwrap();
        let s = PeriodicSolution::new(&params).unwrap();
        assert!(
            s.spectral_radius() < 1.0,
            "ζ {zeta} w {w} β {beta}: unstable"
        );
        let on = s.state_at(0.0);
        let mut sim = Sim::new(
            params,
            State {
                y: on.y + 0.05 * s.peak,
                v: on.v,
            },
        );
        let periods = settle(&mut sim, &params, s.peak, 20_000);
        assert!(periods < 20_000, "ζ {zeta} w {w} β {beta}: did not settle");
        let tau0 = periods as f64 * params.drive_period();
        let (peak, a1, kinds) = simulated_period(&mut sim, &params, tau0);
        assert_eq!(
            kinds,
            [EventKind::Turn, EventKind::Turn],
            "ζ {zeta} w {w} β {beta}"
        );
        let (dp, da) = ((peak - s.peak).abs() / s.peak, (a1 - s.a1()).abs() / s.a1());
        assert!(
            dp < 1e-8 && da < 1e-8,
            "ζ {zeta} w {w} β {beta}: peak {dp:e}, A1 {da:e}"
        );
        worst = worst.max(dp).max(da);
    }
    eprintln!("largest relative deviation, exact vs simulated steady state: {worst:.2e}");
}

/// Just above β_c the simulated motion, started on the orbit, never stops; just below it the
/// steady state stops at its turning points. ζ = 0, 0.05, 0.1, 0.2 at 16 frequencies each.
#[test]
fn boundary_separates_sliding_from_sticking_in_simulation() {
    let ws = [
        0.3, 0.36, 0.42, 0.46, 0.55, 0.6, 0.7, 0.8, 0.9, 1.1, 1.25, 1.5, 2.0, 3.0, 5.0, 8.0,
    ];
    let margin = 1e-4;
    for &zeta in &[0.0, 0.05, 0.1, 0.2] {
        for &w in &ws {
            let b = stick_slip_boundary(zeta, w, 1.0).unwrap();
            assert_eq!(b.continuum, None);
            let period = TAU / w;

            let above = Params::new(zeta, w, b.beta_c * (1.0 + margin)).unwrap();
            let s = PeriodicSolution::new(&above).unwrap();
            let on = s.state_at(0.0);
            let mut sim = Sim::new(
                above,
                State {
                    y: on.y + 1e-6 * s.peak,
                    v: on.v,
                },
            );
            sim.run_to(300.0 * period, |_, _, _| {}).unwrap();
            assert_eq!(sim.sticks_after(0.0), 0, "ζ {zeta} w {w}: stops above β_c");

            // Below: start where the orbit at β_c is, and look at the last 100 periods.
            let at = PeriodicSolution::new(&Params::new(zeta, w, b.beta_c).unwrap()).unwrap();
            let below = Params::new(zeta, w, b.beta_c * (1.0 - margin)).unwrap();
            let mut sim = Sim::new(below, at.state_at(0.0));
            match sim.run_to(300.0 * period, |_, _, _| {}) {
                Ok(()) => assert!(
                    sim.sticks_after(200.0 * period) > 0,
                    "ζ {zeta} w {w}: no stop below β_c"
                ),
                // The solver can spin at one instant alternating stick and slip; that
                // happens only while the oscillator is held by static friction.
                Err(Stalled { tau }) => assert!(
                    sim.events.last().is_some_and(|e| e.kind != EventKind::Turn),
                    "ζ {zeta} w {w}: stalled at {tau} without stopping"
                ),
            }
        }
    }
}

/// β_c by definition: valid just above, invalid just below; the obstruction below is a stop
/// at the turning point or mid-swing, confirmed on a fine grid of the candidate's velocity.
#[test]
fn boundary_is_sharp() {
    let mut rng = Rng(0x5eed_0004);
    for _ in 0..60 {
        let zeta = rng.uniform(0.0, 0.6);
        let w = rng.log_uniform(0.05, 10.0);
        let mu_s = if rng.next() < 0.3 { 1.2 } else { 1.0 };
        let Ok(b) = stick_slip_boundary(zeta, w, mu_s) else {
            continue;
        };
        let p = |f: f64| {
            Params::new(zeta, w, b.beta_c * f)
                .unwrap()
                .with_mu_s(mu_s)
                .unwrap()
        };
        assert!(PeriodicSolution::new(&p(1.0)).is_ok());
        assert!(PeriodicSolution::new(&p(1.0 + 1e-9)).is_ok());
        match PeriodicSolution::solve(&p(1.0 - 1e-9)).unwrap() {
            Err(Obstruction::StopsAtTurn { force }) => assert!(force <= mu_s + 1e-6),
            Err(Obstruction::StopsMidSwing { fraction }) => {
                assert!(fraction > 0.0 && fraction <= 1.0 + 1e-9)
            }
            other => panic!("ζ {zeta} w {w}: unexpected {other:?}"),
        }
        assert!(matches!(
            b.below,
            Obstruction::StopsAtTurn { .. } | Obstruction::StopsMidSwing { .. }
        ));
    }
}

/// The search for β_c assumes nothing about monotonicity, but checks it here: on fine grids
/// nothing below β_c is a valid non-sticking motion and nothing up to 20·β_c is invalid.
#[test]
fn validity_changes_once_in_beta() {
    let mut frequencies = 0;
    for &zeta in &[0.0, 0.0468, 0.3] {
        for j in 0..24 {
            let w = 0.05 * (200.0f64).powf((j as f64 + 0.37) / 24.0);
            let Ok(b) = stick_slip_boundary(zeta, w, 1.0) else {
                continue;
            };
            let valid =
                |beta: f64| PeriodicSolution::new(&Params::new(zeta, w, beta).unwrap()).is_ok();
            for i in 1..400 {
                let beta = b.beta_c * i as f64 / 400.0;
                assert!(
                    !valid(beta),
                    "ζ {zeta} w {w}: valid at β = {beta} < β_c = {}",
                    b.beta_c
                );
            }
            for i in 0..=100 {
                let beta = b.beta_c * (1.0 + 19.0 * i as f64 / 100.0);
                assert!(
                    valid(beta),
                    "ζ {zeta} w {w}: invalid at β = {beta} > β_c = {}",
                    b.beta_c
                );
            }
            frequencies += 1;
        }
    }
    assert_eq!(frequencies, 72);
}

/// At the paper's circuit damping the boundary curve is finite and continuous from w = 0.05
/// to 10: neighbouring frequencies give neighbouring β_c.
#[test]
fn boundary_curve_is_continuous_across_the_range() {
    let zeta = 0.0468;
    let n = 400;
    let mut previous: Option<f64> = None;
    for j in 0..=n {
        let w = 0.05 * (200.0f64).powf(j as f64 / n as f64);
        let beta_c = stick_slip_boundary(zeta, w, 1.0).unwrap().beta_c;
        assert!(beta_c.is_finite() && beta_c > 1.0);
        if let Some(prev) = previous {
            // Log-spacing of 1.3%: β_c moves by well under a factor 1.5 per step.
            assert!(
                beta_c / prev < 1.5 && prev / beta_c < 1.5,
                "w {w}: {prev} → {beta_c}"
            );
        }
        previous = Some(beta_c);
    }
}

/// At ζ = 0, w = 1/(2n) the symmetric solution is one of a continuum: adding
/// A·cos(τ − τ_turn) gives another periodic sliding motion (flagged), which the simulation
/// keeps forever; with damping the offset dies out. Nearby, β_c is continuous.
#[test]
fn continuum_of_asymmetric_solutions_at_w_one_over_2n() {
    for &(n, beta) in &[(1u32, 4.5), (2, 24.0)] {
        let w = 1.0 / (2.0 * f64::from(n));
        let params = Params::new(0.0, w, beta).unwrap();
        let s = PeriodicSolution::new(&params).unwrap();
        assert_eq!(s.continuum, Some(n));
        assert!((s.spectral_radius() - 1.0).abs() < 1e-9);
        let t0 = s.first_lower_turn();
        let offset = 0.02 * s.peak;
        let on = s.state_at(0.0);
        let start = State {
            y: on.y + offset * (0.0 - t0).cos(),
            v: on.v - offset * (0.0 - t0).sin(),
        };
        let mut sim = Sim::new(params, start);
        sim.run_to(200.0 * params.drive_period(), |_, _, _| {})
            .unwrap();
        assert!(sim.events.len() >= 399);
        for e in &sim.events {
            assert_eq!(e.kind, EventKind::Turn);
            let want = if e.y > 0.0 { s.peak } else { -s.peak } + offset;
            assert!(
                (e.y - want).abs() < 1e-9 * s.peak,
                "n {n}: turn at {} vs {want}",
                e.y
            );
        }
        // Continuous boundary through the point, and flagged only nearby.
        let b = |dw: f64| stick_slip_boundary(0.0, w + dw, 1.0).unwrap();
        assert_eq!(b(0.0).continuum, Some(n));
        assert_eq!(b(1e-4 * w).continuum, Some(n));
        assert_eq!(b(0.05 * w).continuum, None);
        for dw in [1e-6, 1e-4, 1e-2] {
            let (lo, mid, hi) = (b(-dw * w).beta_c, b(0.0).beta_c, b(dw * w).beta_c);
            assert!(
                (hi - lo).abs() < 40.0 * dw * mid,
                "n {n} dw {dw}: {lo} {mid} {hi}"
            );
        }
    }
    // ζ = 0.05 at w = 1/2: the offset decays and the motion is symmetric again.
    let params = Params::new(0.05, 0.5, 4.5).unwrap();
    let s = PeriodicSolution::new(&params).unwrap();
    assert_eq!(s.continuum, None);
    let on = s.state_at(0.0);
    let mut sim = Sim::new(
        params,
        State {
            y: on.y + 0.02 * s.peak,
            v: on.v,
        },
    );
    sim.run_to(200.0 * params.drive_period(), |_, _, _| {})
        .unwrap();
    let last = sim.events.last().unwrap();
    assert!((last.y.abs() - s.peak).abs() < 1e-9 * s.peak);
}

/// The spectral radius ρ of the turning-point map predicts how fast a perturbed motion returns
/// to the orbit: the strobe deviation shrinks like ρ² per period.
#[test]
fn spectral_radius_predicts_the_approach_to_the_orbit() {
    for &(zeta, w, beta) in &[
        (0.05, 0.9, 1.6),
        (0.1, 1.3, 2.5),
        (0.02, 4.0, 3.0),
        (0.0, 1.1, 2.0),
    ] {
        let params = Params::new(zeta, w, beta).unwrap();
        let s = PeriodicSolution::new(&params).unwrap();
        let rho = s.spectral_radius();
        assert!(rho < 1.0 && rho > 0.3, "ζ {zeta} w {w}: ρ = {rho}");
        let on = s.state_at(0.0);
        let mut sim = Sim::new(
            params,
            State {
                y: on.y + 1e-3 * s.peak,
                v: on.v,
            },
        );
        let period = params.drive_period();
        let mut deviations = Vec::new();
        for k in 1..=2000 {
            sim.run_to(k as f64 * period, |_, _, _| {}).unwrap();
            let (a, b) = (sim.solver.state(), s.state_at(k as f64 * period));
            let d = (a.y - b.y).hypot(a.v - b.v) / s.peak;
            if d < 1e-10 {
                break;
            }
            deviations.push(d);
        }
        // Rate over the stretch from 1e-5 to 1e-10, averaged over many periods.
        let from = deviations.iter().position(|&d| d < 1e-5).unwrap();
        let to = deviations.len() - 1;
        assert!(to > from + 5, "ζ {zeta} w {w}: too short a stretch");
        let rate = (deviations[to] / deviations[from]).ln() / (to - from) as f64;
        let predicted = 2.0 * rho.ln();
        assert!(
            (rate - predicted).abs() < 0.1 * predicted.abs(),
            "ζ {zeta} w {w}: measured {rate}, predicted {predicted}"
        );
    }
}
