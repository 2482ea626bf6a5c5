//! The property of the solvers that the fuzz target `solvers` and the property test
//! `crates/stickslip/tests/fuzz_props.rs` both check (this file is included by both).
//!
//! A case is a set of parameters and an initial state anywhere in the documented ranges
//! (`stickslip::limits`), decoded from numbers in [0, 1), and a bounded horizon. The exact
//! solver must run it without an error or a panic, every value it reports must be finite and
//! in time order, and every event must obey the switching rules. The stiff Shockley solver
//! must not panic (it may report a typed error).

#![allow(dead_code)]

use stickslip::limits;
use stickslip::solver::{run_until, stream, Record};
use stickslip::steady::{steady_state, SteadyOptions};
use stickslip::{
    Circuit, DiodePair, Error, Event, EventKind, ExactSolver, Params, ShockleyOptions,
    ShockleySolver, Solver, State,
};

/// One case.
#[derive(Debug, Clone, Copy)]
pub struct Case {
    /// The parameters.
    pub params: Params,
    /// The initial state.
    pub initial: State,
    /// What to run: 0 and 1 the exact solver to the horizon, 2 a stream of samples, 3 a
    /// steady state of at most 20 periods, 4 the Shockley solver.
    pub mode: u8,
    /// The horizon's class, 0 to 9 ([`Case::horizon`]).
    pub length: u8,
}

/// Log-uniform in [lo, hi].
fn log_uniform(u: f64, lo: f64, hi: f64) -> f64 {
    (lo.ln() + u * (hi.ln() - lo.ln())).exp().clamp(lo, hi)
}

/// A number in [0, 1) from 8 bytes (missing bytes are zeros).
fn unit(bytes: &[u8]) -> f64 {
    let mut b = [0u8; 8];
    b[..bytes.len().min(8)].copy_from_slice(&bytes[..bytes.len().min(8)]);
    (u64::from_le_bytes(b) >> 11) as f64 / (1u64 << 53) as f64
}

impl Case {
    /// The case of nine numbers in [0, 1): the edges of every range come up often.
    pub fn from_units(u: [f64; 9]) -> Self {
        // Each number picks a branch with its first digit and a value with the rest.
        let split = |x: f64| ((x * 10.0).floor() as u32, (x * 10.0).fract());
        let (b, r) = split(u[0]);
        let zeta = match b {
            0 => 0.0,
            1 => 1.0,
            2 => limits::ZETA_MAX,
            _ => log_uniform(r, 1e-4, limits::ZETA_MAX),
        };
        let (b, r) = split(u[1]);
        let w = match b {
            0 => 1.0,
            1 => limits::W_MIN,
            2 => limits::W_MAX,
            3..=6 => log_uniform(r, 0.05, 20.0),
            _ => log_uniform(r, limits::W_MIN, limits::W_MAX),
        };
        let (b, r) = split(u[2]);
        let beta = match b {
            0 => 0.0,
            1 => limits::BETA_MAX,
            2..=6 => log_uniform(r, 0.1, 10.0),
            _ => log_uniform(r, 1e-6, limits::BETA_MAX),
        };
        let (b, r) = split(u[3]);
        let mu_s = match b {
            0..=4 => 1.0,
            5 => limits::MU_S_MAX,
            6..=8 => 1.0 + r,
            _ => log_uniform(r, 1.0, limits::MU_S_MAX),
        };
        let (b, r) = split(u[4]);
        let phi = match b {
            0 => 0.0,
            1 => limits::PHI_MAX * (2.0 * r - 1.0),
            _ => std::f64::consts::TAU * r,
        };
        let state = |x: f64| {
            let (b, r) = split(x);
            match b {
                0..=3 => 0.0,
                4 => limits::STATE_MAX,
                5 => -limits::STATE_MAX,
                6..=7 => 10.0 * (2.0 * r - 1.0),
                _ => {
                    (if r < 0.5 { -1.0 } else { 1.0 })
                        * log_uniform((2.0 * r).fract(), 1e-6, limits::STATE_MAX)
                }
            }
        };
        let params = Params::new(zeta, w, beta)
            .and_then(|p| p.with_mu_s(mu_s))
            .and_then(|p| p.with_phi(phi))
            .expect("parameters inside the ranges");
        let initial = limits::check_state(state(u[5]), state(u[6])).expect("inside");
        let mode = (u[7] * 5.0) as u8;
        Self {
            params,
            initial,
            mode: mode.min(4),
            length: ((u[8] * 10.0) as u8).min(9),
        }
    }

    /// The case of raw bytes (the fuzzer's input): nine numbers of 8 bytes each.
    pub fn from_bytes(data: &[u8]) -> Self {
        let mut u = [0.0; 9];
        for (i, x) in u.iter_mut().enumerate() {
            *x = unit(data.get(8 * i..).unwrap_or(&[]));
        }
        Self::from_units(u)
    }

    /// The horizon: mostly short (5 drive periods, at most 100 time units), sometimes 20
    /// periods up to 2000 time units, and sometimes one long stretch of up to 2·10⁴ time
    /// units (slow drives), so that a case takes at most tens of milliseconds.
    pub fn horizon(&self) -> f64 {
        let period = self.params.drive_period();
        match self.length {
            0..=7 => (5.0 * period).min(100.0),
            8 => (20.0 * period).min(2000.0),
            _ => (20.0 * period).min(2e4),
        }
    }
}

/// Check the switching rules at an event (with the rounding of forces of this size).
fn check_event(case: &Case, event: &Event, previous: f64) {
    let p = &case.params;
    assert!(
        event.tau.is_finite() && event.y.is_finite(),
        "{case:?}: {event:?}"
    );
    assert!(
        event.tau >= previous,
        "{case:?}: events out of order at {event:?}"
    );
    let force = p.drive(event.tau) - event.y;
    // The drive's phase at τ is rounded to ε·(wτ + |φ|); forces of size X to ε·X.
    let slack = 1e-9 * (p.mu_s + p.beta + event.y.abs())
        + p.beta * p.w * 1e-12 * (event.tau.abs() + 1.0)
        + p.beta * 1e-12 * p.phi.abs();
    match event.kind {
        EventKind::Stick => assert!(
            force.abs() <= p.mu_s + slack,
            "{case:?}: stop with |force| = {} > μs at {event:?}",
            force.abs()
        ),
        EventKind::Slip | EventKind::Turn => assert!(
            force.abs() >= p.mu_s - slack || event.kind == EventKind::Turn,
            "{case:?}: slip with |force| = {} < μs at {event:?}",
            force.abs()
        ),
    }
}

/// Run the case (see the module documentation). Panics on a violation.
pub fn check(case: &Case) {
    let p = case.params;
    let end = case.horizon();
    match case.mode {
        0 | 1 => {
            let mut solver = ExactSolver::new(p, case.initial);
            let mut previous = 0.0;
            run_until(&mut solver, end, |e| {
                check_event(case, e, previous);
                previous = e.tau;
            })
            .unwrap_or_else(|e| panic!("{case:?}: {e}"));
            let s = solver.state();
            assert!(s.y.is_finite() && s.v.is_finite(), "{case:?}: {s:?}");
            assert_eq!(solver.time(), end);
        }
        2 => {
            let mut solver = ExactSolver::new(p, case.initial);
            let mut previous = 0.0;
            let mut samples = 0;
            for record in stream(&mut solver, 0.0, end, 500).expect("a horizon in range") {
                match record.unwrap_or_else(|e| panic!("{case:?}: {e}")) {
                    Record::Sample(s) => {
                        assert!(s.y.is_finite() && s.v.is_finite(), "{case:?}: {s:?}");
                        assert!(s.tau >= previous, "{case:?}: {s:?} before {previous}");
                        // The velocity has the sign of the phase (to rounding).
                        let noise = 1e-9 * (1.0 + p.beta + p.mu_s + s.y.abs());
                        assert!(
                            s.v * s.phase.sign() >= -noise,
                            "{case:?}: velocity against the phase at {s:?}"
                        );
                        previous = s.tau;
                        samples += 1;
                    }
                    Record::Event(e) => {
                        check_event(case, &e, previous);
                        previous = e.tau;
                    }
                }
            }
            assert_eq!(samples, 501);
        }
        3 => {
            let mut solver = ExactSolver::new(p, case.initial);
            let options = SteadyOptions::default()
                .with_max_periods(20)
                .and_then(|o| o.with_max_period(4))
                .expect("valid options")
                .with_spectrum(false);
            if 30.0 * p.drive_period() <= 4000.0 {
                let steady =
                    steady_state(&mut solver, &options).unwrap_or_else(|e| panic!("{case:?}: {e}"));
                assert!(
                    steady.y_min.is_finite() && steady.y_max.is_finite(),
                    "{case:?}"
                );
                // The gain is amplitude/β: infinite for a motion without a drive.
                let gain_ok = if p.beta > 0.0 {
                    steady.gain.is_finite() && steady.gain >= 0.0
                } else {
                    steady.gain == 0.0 || steady.gain == f64::INFINITY
                };
                assert!(gain_ok, "{case:?}: gain {}", steady.gain);
            }
        }
        _ => {
            // The paper's circuit with Shockley diodes at this drive (its ζ is the circuit's).
            let circuit = Circuit::paper().with_shockley(DiodePair::one_n4148());
            let Ok(Some(model)) = circuit.shockley_model(&p) else {
                return;
            };
            let Ok(mut solver) =
                ShockleySolver::new(model, case.initial, ShockleyOptions::default())
            else {
                return;
            };
            // The stiff solver is far slower: a short horizon.
            let end = p.drive_period().min(20.0);
            let mut previous = 0.0;
            let result = run_until(&mut solver, end, |e| {
                assert!(e.tau.is_finite() && e.y.is_finite(), "{case:?}: {e:?}");
                assert!(e.tau >= previous, "{case:?}: events out of order");
                previous = e.tau;
            });
            match result {
                Ok(()) => {
                    let s = solver.state();
                    assert!(s.y.is_finite() && s.v.is_finite(), "{case:?}: {s:?}");
                }
                Err(Error::StepSizeTooSmall { .. }) => {}
                Err(e) => panic!("{case:?}: {e}"),
            }
        }
    }
}
