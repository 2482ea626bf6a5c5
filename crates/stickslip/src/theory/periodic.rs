//! The exact symmetric non-sticking periodic solution, for every ζ ≥ 0.
//!
//! For ζ = 0 this is the solution of Den Hartog (*Forced vibrations with combined viscous and
//! Coulomb damping*, Phil. Mag. 9 (1930) 801–817); for ζ > 0 it follows from the same
//! matching, done here in closed form.
//!
//! **Matching.** A symmetric motion has y(τ + T/2) = −y(τ), y'(τ + T/2) = −y'(τ), T = 2π/w.
//! Take its lower turning point y = −Y as local time t = 0, at drive phase θ. On the half
//! period t ∈ (0, L), L = T/2 = π/w, it slides up (y' > 0, friction −1), so it is the linear
//! segment y'' + 2ζy' + y = β cos(wt + θ) − 1 and must end at y(L) = +Y, y'(L) = 0. With
//! the particular solution −1 + P·(a cos wt − b sin wt) + Q·(a sin wt + b cos wt),
//! a = β cos θ, b = β sin θ, P = (1 − w²)/D, Q = 2ζw/D, D = (1 − w²)² + 4ζ²w², and Φ the
//! transition matrix of y'' + 2ζy' + y = 0 over L, the end conditions become
//!
//! ```text
//! (I + Φ)·(m, r) = (Φ − I)·(1, 0),   m = Y + s,   s = Pa + Qb,   r = w(Qa − Pb),
//! ```
//!
//! so m and r depend on (ζ, w) only. With E = e^{−ζL} and Φ = E·[[C + ζS, S], [−S, C − ζS]]
//! (C = cos ω_d L, S = sin(ω_d L)/ω_d, continued to cosh/sinh above critical damping):
//!
//! ```text
//! m = (2ζES − (1 − E²)) / (1 + 2EC + E²),     r = −2ES / (1 + 2EC + E²).
//! ```
//!
//! Since (a, b) ↦ (s, r/w) is √D times a reflection, β² = D·(s² + r²/w²), hence
//!
//! ```text
//! Y = m ± √(β²/D − r²/w²).
//! ```
//!
//! m ≤ 0 (because ζ|S| ≤ sinh(ζL)/E), so only the + root can be a motion. For ζ = 0, m = 0 and
//! r = −tan(π/(2w)): Y = √(β²/(1 − w²)² − tan²(π/(2w))/w²), Den Hartog's amplitude.
//!
//! **Validity.** The root is the motion only if it never stops: the net force β cos θ + Y at
//! the turning point must exceed μs (else static friction holds it there), and y' must stay
//! positive on (0, L). The second condition is checked rigorously by running
//! [`crate::ExactSolver`], whose velocity-zero search cannot step over a zero, from the turning
//! point over the half period.
//!
//! **Harmonics.** Friction is then exactly a square wave, so y has odd harmonics only; their
//! amplitudes are integrated exactly from the closed form ([`super::fourier`]):
//!
//! ```text
//! c_1 = (β e^{iθ} + 4i/π) / (2H_1),   c_k = (2i/(kπ)) / H_k (k ≥ 3 odd),   H_k = 1 − k²w² + 2iζkw,
//! ```
//!
//! in local time (y = Σ 2 Re(c_k e^{ikwt})). So A_k = 4/(kπ|H_k|) for k ≥ 3, exactly the
//! paper's eq. (11), while A1 = |β e^{iθ} + 4i/π|/|H_1| differs from it through θ.
//!
//! **Stability.** The map from one turning point (y, θ) to the next, reflected, is smooth
//! near the orbit; [`PeriodicSolution::spectral_radius`] is the spectral radius of its
//! Jacobian, in closed form. The orbit attracts nearby motions when it is below 1.

pub use super::obstruction::Obstruction;

use super::fourier::{segment_integral, wrap_phase, Harmonic};
use crate::error::{Error, NoSolutionReason, Quantity, Result};
use crate::exact::ExactSolver;
use crate::linear::{Damping, LinearSegment};
use crate::params::{Params, State};
use crate::solver::{EventKind, Phase, Solver};
use rustfft::num_complex::Complex64;
use std::f64::consts::{PI, TAU};

/// The (ζ, w)-only part of the matching: m, r and the pieces of Φ(L).
#[derive(Debug, Clone, Copy)]
pub(crate) struct Matching {
    zeta: f64,
    w: f64,
    /// Half period L = π/w.
    length: f64,
    /// D = (1 − w²)² + 4ζ²w² = |H_1|².
    d: f64,
    m: f64,
    r: f64,
    /// E·C and E·S of Φ(L).
    ec: f64,
    es: f64,
}

impl Matching {
    /// The matching constants, or the resonance that forbids them.
    pub(crate) fn new(zeta: f64, w: f64) -> std::result::Result<Self, Obstruction> {
        if zeta == 0.0 {
            let k = (1.0 / w).round();
            if k >= 1.0 && k % 2.0 == 1.0 && (k * w - 1.0).abs() <= 8.0 * f64::EPSILON {
                return Err(Obstruction::Resonance { order: k as u32 });
            }
        }
        let length = PI / w;
        let (ec, es, det) = if zeta < 1.0 {
            let omega = ((1.0 - zeta) * (1.0 + zeta)).sqrt();
            let e = (-zeta * length).exp();
            let (sn, cs) = (omega * length).sin_cos();
            let half_cos = (0.5 * omega * length).cos();
            let one_minus_e = -(-zeta * length).exp_m1();
            (
                e * cs,
                e * sn / omega,
                one_minus_e * one_minus_e + 4.0 * e * half_cos * half_cos,
            )
        } else if zeta == 1.0 {
            let e = (-length).exp();
            (e, e * length, (1.0 + e) * (1.0 + e))
        } else {
            let kappa = ((zeta - 1.0) * (zeta + 1.0)).sqrt();
            let e = (-zeta * length).exp();
            let (ec, es) = if kappa * length <= 1.0 {
                (
                    e * (kappa * length).cosh(),
                    e * (kappa * length).sinh() / kappa,
                )
            } else {
                let slow = (-length / (zeta + kappa)).exp();
                let fast = (-(zeta + kappa) * length).exp();
                (0.5 * (slow + fast), 0.5 * (slow - fast) / kappa)
            };
            (ec, es, 1.0 + 2.0 * ec + e * e)
        };
        if !(det > 0.0) {
            // Only ζ = 0 with cos(π/w) = −1 exactly, caught above up to rounding.
            let k = (1.0 / w).round().max(1.0);
            return Err(Obstruction::Resonance { order: k as u32 });
        }
        let one_minus_e2 = -(-2.0 * zeta * length).exp_m1();
        let detune = (1.0 - w) * (1.0 + w);
        Ok(Self {
            zeta,
            w,
            length,
            d: detune * detune + 4.0 * zeta * zeta * w * w,
            m: (2.0 * zeta * es - one_minus_e2) / det,
            r: -2.0 * es / det,
            ec,
            es,
        })
    }

    /// β_min = √D·|r|/w: below it the matching equations have no real root.
    pub(crate) fn beta_min(&self) -> f64 {
        self.d.sqrt() * self.r.abs() / self.w
    }

    /// The + root at β: (Y, θ ∈ [0, 2π), net force at the turning point, s).
    fn root(&self, beta: f64) -> std::result::Result<(f64, f64, f64, f64), Obstruction> {
        let ratio = self.r.abs() / self.w;
        let root_d = self.d.sqrt();
        // β²/D − r²/w², factored to keep its zero accurate.
        let radicand = (beta / root_d - ratio) * (beta / root_d + ratio);
        if !(radicand >= 0.0) {
            return Err(Obstruction::BelowFold {
                beta_min: self.beta_min(),
            });
        }
        let sigma = radicand.sqrt();
        let peak = self.m + sigma;
        if !(peak > 0.0) {
            return Err(Obstruction::NoMotion { peak });
        }
        let s = -sigma;
        let detune = (1.0 - self.w) * (1.0 + self.w);
        let a = detune * s + 2.0 * self.zeta * self.r;
        let b = 2.0 * self.zeta * self.w * s - detune * self.r / self.w;
        let theta = b.atan2(a).rem_euclid(TAU);
        Ok((peak, theta, a + peak, s))
    }
}

/// The exact symmetric periodic motion that never stops, with one lower and one upper turning
/// point per drive period T = 2π/w. Build with [`PeriodicSolution::new`].
///
/// All quantities are dimensionless (y in units of the friction force over the stiffness,
/// time τ = ω0·t). Phases refer to the drive phase ψ = wτ + φ (drive = β cos ψ).
#[derive(Debug, Clone, Copy)]
pub struct PeriodicSolution {
    /// The parameters it solves.
    pub params: Params,
    /// Peak amplitude Y = max |y| (the turning points are y = ±Y).
    pub peak: f64,
    /// Drive phase ψ = wτ + φ at the lower turning point y = −Y, radians in [0, 2π).
    pub turn_phase: f64,
    /// Net force β cos θ + Y at the lower turning point, pushing up (> μs).
    pub turn_force: f64,
    /// `Some(n)` in the neighbourhood of w = 1/(2n) with little damping, where the free
    /// oscillation over a half period is within [`CONTINUUM_DEFECT`] of the identity. At
    /// ζ = 0, w = 1/(2n) exactly, this solution is one of a continuum of periodic motions,
    /// most of them asymmetric (adding A·cos(τ − τ_turn) to y keeps every turning point at
    /// rest), so Den Hartog's solution is not unique there and a simulation keeps whatever
    /// offset it starts with. Nearby, the symmetric solution attracts only weakly
    /// ([`PeriodicSolution::spectral_radius`] close to 1) and asymmetric motions persist
    /// for many periods.
    pub continuum: Option<u32>,
    matching: Matching,
    segment: LinearSegment,
    /// Fundamental coefficient c_1 in local time.
    c1: Complex64,
}

/// `Ok` for Coulomb's law with the base at rest, the model of the theories.
///
/// # Errors
/// [`crate::Unsupported::TheoryNeedsCoulombAtRest`] for a belt speed or another law.
pub(crate) fn check_coulomb_at_rest(params: &Params) -> Result<()> {
    if params.is_paper_friction() {
        Ok(())
    } else {
        Err(crate::Error::Unsupported(
            crate::Unsupported::TheoryNeedsCoulombAtRest,
        ))
    }
}

impl PeriodicSolution {
    /// The symmetric non-sticking periodic solution at `params` (φ sets where it sits in
    /// time; μs enters the stop condition at the turning points).
    ///
    /// # Errors
    /// [`Error::NoSolution`] when it does not exist, the reason naming the [`Obstruction`];
    /// a numerical failure of the velocity check ([`Error::EventSearch`]).
    pub fn new(params: &Params) -> Result<Self> {
        Self::solve(params)?.map_err(|why| Error::NoSolution {
            what: Quantity::ExactOrbit,
            reason: NoSolutionReason::Obstruction(why),
        })
    }

    /// As [`PeriodicSolution::new`], with the obstruction as a value.
    ///
    /// # Errors
    /// Invalid parameters; a numerical failure of the velocity check.
    pub fn solve(params: &Params) -> Result<std::result::Result<Self, Obstruction>> {
        let params = params.validate()?;
        let matching = match Matching::new(params.zeta, params.w) {
            Ok(m) => m,
            Err(why) => return Ok(Err(why)),
        };
        Self::from_matching(&params, &matching)
    }

    pub(crate) fn from_matching(
        params: &Params,
        matching: &Matching,
    ) -> Result<std::result::Result<Self, Obstruction>> {
        check_coulomb_at_rest(params)?;
        let (peak, theta, force, _) = match matching.root(params.beta) {
            Ok(root) => root,
            Err(why) => return Ok(Err(why)),
        };
        if !(force > params.mu_s) {
            return Ok(Err(Obstruction::StopsAtTurn { force }));
        }
        let length = matching.length;
        // Slide up from the turning point with the exact solver: its search cannot step over a
        // velocity zero, so the first event is the first zero of y'.
        let start = Params {
            phi: theta,
            ..*params
        };
        let mut solver = ExactSolver::new(start, State { y: -peak, v: 0.0 });
        if solver.phase() != Phase::SlipPositive {
            return Ok(Err(Obstruction::StopsAtTurn { force }));
        }
        match solver.advance(2.0 * length)? {
            Some(e) if (e.tau - length).abs() <= 1e-7 * length => {
                if e.kind != EventKind::Turn {
                    // At the boundary itself the turn's net force, recomputed from the end
                    // state, can land on μs through rounding.
                    return Ok(Err(Obstruction::StopsAtTurn {
                        force: (start.drive(e.tau) - e.y).abs(),
                    }));
                }
            }
            Some(e) => {
                return Ok(Err(Obstruction::StopsMidSwing {
                    fraction: e.tau / length,
                }))
            }
            None => {
                return Err(Error::EventSearch {
                    tau: 2.0 * length,
                    reason: "periodic solution check: no turning point at the half period",
                })
            }
        }
        let damping = Damping::new(params.zeta);
        let segment = LinearSegment::new(damping, params.w, params.beta, theta, 1.0, -peak, 0.0);
        let mut solution = Self {
            params: *params,
            peak,
            turn_phase: theta,
            turn_force: force,
            continuum: matching.continuum(),
            matching: *matching,
            segment,
            c1: Complex64::new(0.0, 0.0),
        };
        solution.c1 = solution.local_coefficient(1);
        Ok(Ok(solution))
    }

    /// Drive period T = 2π/w.
    pub fn period(&self) -> f64 {
        TAU / self.params.w
    }

    /// The first time τ ∈ [0, T) of a lower turning point y = −Y.
    pub fn first_lower_turn(&self) -> f64 {
        (self.turn_phase - self.params.phi).rem_euclid(TAU) / self.params.w
    }

    /// Position and velocity on the orbit at time τ (any τ, the orbit is periodic).
    pub fn state_at(&self, tau: f64) -> State {
        let length = self.matching.length;
        let t = (tau - self.first_lower_turn()).rem_euclid(self.period());
        let (y, v) = if t <= length {
            self.segment.state(t)
        } else {
            let (y, v) = self.segment.state(t - length);
            (-y, -v)
        };
        State { y, v }
    }

    /// Complex Fourier coefficient c_k of y in local time (origin at the lower turning point),
    /// y = Σ_k 2 Re(c_k e^{ikwt}); zero for even k.
    fn local_coefficient(&self, order: u32) -> Complex64 {
        if order.is_multiple_of(2) {
            return Complex64::new(0.0, 0.0);
        }
        let p = &self.params;
        let k = f64::from(order);
        let length = self.matching.length;
        // ∫₀ᴸ (β cos(wt + θ) − 1) e^{−ikwt} dt for odd k: the drive contributes to k = 1 only.
        let mut forcing = Complex64::new(0.0, 2.0 / (k * p.w));
        if order == 1 {
            forcing += Complex64::from_polar(p.beta * length / 2.0, self.turn_phase);
        }
        let integral = segment_integral(
            p.zeta,
            k * p.w,
            length,
            (-self.peak, 0.0),
            (self.peak, 0.0),
            forcing,
        );
        // Full period: (1/T)(1 − e^{−ikπ}) ∫₀ᴸ = (2/T) ∫₀ᴸ for odd k.
        integral * (2.0 / self.period())
    }

    /// The harmonic of order k ≥ 1 of y, exact: y = Σ_k A_k cos(kψ + φ_k) with ψ = wτ + φ the
    /// drive phase. Even orders vanish by symmetry.
    ///
    /// # Panics
    /// When `order` is 0.
    pub fn harmonic(&self, order: u32) -> Harmonic {
        assert!(order >= 1, "harmonic orders start at 1");
        let c = if order == 1 {
            self.c1
        } else {
            self.local_coefficient(order)
        };
        Harmonic {
            order,
            amplitude: 2.0 * c.norm(),
            phase: if c.norm() == 0.0 {
                0.0
            } else {
                wrap_phase(c.arg() - f64::from(order) * self.turn_phase)
            },
        }
    }

    /// Fundamental amplitude A1.
    pub fn a1(&self) -> f64 {
        2.0 * self.c1.norm()
    }

    /// Phase lag of the fundamental behind the drive, radians in (−π, π] (in [0, π] in every
    /// case we have met): y's fundamental is A1 cos(ψ − lag) under the drive β cos ψ. The
    /// paper's φ0 (eq. (11)) approximates this lag.
    pub fn phase_lag(&self) -> f64 {
        -self.harmonic(1).phase
    }

    /// Gain of the fundamental G1 = A1/β, what the paper's eq. (11) gives. The orbit's gain
    /// G = (y_max − y_min)/(2β) is `peak / β` (the orbit is symmetric).
    pub fn gain1(&self) -> f64 {
        self.a1() / self.params.beta
    }

    /// The former name of [`PeriodicSolution::gain1`].
    #[deprecated(note = "A1/β is `gain1` (G1); the orbit's G is `peak / beta`")]
    pub fn gain(&self) -> f64 {
        self.gain1()
    }

    /// Spectral radius of the Jacobian of the turning-point map (y, θ) ↦ (−y, θ − π) at the
    /// next turning point, at the orbit. Below 1: the orbit attracts nearby motions, which
    /// approach it by this factor per half period (asymptotically).
    pub fn spectral_radius(&self) -> f64 {
        let mt = &self.matching;
        let (z, w) = (mt.zeta, mt.w);
        let (ec, es) = (mt.ec, mt.es);
        let sigma = self.peak - mt.m;
        // ∂y_p(0)/∂θ = r/w and ∂y_p'(0)/∂θ = −w·s = w·σ; then ∂(y, y')(L)/∂θ = −(I + Φ)(g0, g1).
        let g0 = mt.r / w;
        let g1 = w * sigma;
        let dy_dtheta = -((1.0 + ec + z * es) * g0 + es * g1);
        let dv_dtheta = -(-es * g0 + (1.0 + ec - z * es) * g1);
        // ∂(y, y')(L)/∂y0 = Φ(1, 0).
        let dy_dy0 = ec + z * es;
        let dv_dy0 = -es;
        let push = self.turn_force + 1.0; // −y''(L−)
        let j = [
            [-dy_dy0, -dy_dtheta],
            [w * dv_dy0 / push, 1.0 + w * dv_dtheta / push],
        ];
        let tr = j[0][0] + j[1][1];
        let det = j[0][0] * j[1][1] - j[0][1] * j[1][0];
        let disc = 0.25 * tr * tr - det;
        if disc >= 0.0 {
            let root = disc.sqrt();
            (0.5 * tr + root).abs().max((0.5 * tr - root).abs())
        } else {
            det.abs().sqrt()
        }
    }
}

/// How close the free oscillation over a half period may come to the identity,
/// max |Φ(T/2) − I|, for [`PeriodicSolution::continuum`] to flag the neighbourhood of
/// w = 1/(2n).
pub const CONTINUUM_DEFECT: f64 = 0.05;

impl Matching {
    /// `Some(n)` when Φ(L) is within [`CONTINUUM_DEFECT`] of the identity, which happens
    /// only near ζ = 0, w = 1/(2n).
    pub(crate) fn continuum(&self) -> Option<u32> {
        let z = self.zeta;
        let defect = (self.ec + z * self.es - 1.0)
            .abs()
            .max((self.ec - z * self.es - 1.0).abs())
            .max(self.es.abs());
        let two_n = (1.0 / self.w).round();
        (defect <= CONTINUUM_DEFECT && two_n >= 2.0 && two_n % 2.0 == 0.0)
            .then_some((two_n / 2.0) as u32)
    }
}
