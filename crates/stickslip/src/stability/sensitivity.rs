//! Parameter sensitivities of the exact solution: the derivatives of a periodic orbit's
//! motion y(τ) by the model's parameters p = (ζ, β, w, φ, μs), from the closed-form segments,
//! for fitting the model to measurements ([`crate::fit`]).
//!
//! **Along a trajectory.** Beside the state Jacobian J = ∂x(τ)/∂x(0) of [`super::tangent`]
//! the propagation carries the parameter sensitivities S_p = ∂x(τ)/∂p at a fixed initial
//! state, as one 2×7 matrix [J | S_ζ S_β S_w S_φ S_μs] that starts as [I | 0].
//!
//! - *On a slide* in direction s the closed form is x(τ) = P(τ) + Φ(τ − τa)(xa − P(τa)), with
//!   Φ the state-transition matrix of [`super::segment`] and P = (y_p − s, y_p') the periodic
//!   particular solution, y_p = Re[β H e^{i(wτ+φ)}], H = 1/(1 − w² + 2iζw). Differentiating at
//!   a fixed start (τa, xa):
//!   ```text
//!   S_p(τ) = Φ (S_p(τa) − ∂P(τa)/∂p) + ∂P(τ)/∂p + [p = ζ] ∂Φ/∂ζ (xa − P(τa)),
//!   ```
//!   with ∂H/∂w = −H²(2iζ − 2w), ∂H/∂ζ = −2iwH², and the factor iτ of ∂e^{i(wτ+φ)}/∂w (the
//!   drive's phase at τ moves with w). ∂Φ/∂ζ comes from EC = e^{−ζt}C, ES = e^{−ζt}S as entire
//!   functions of q = ζ² − 1: ∂EC/∂ζ = −t EC + ζ t ES, ∂ES/∂ζ = −t ES + ζ(t EC − ES)/q (a
//!   power series in q where |q|t² ≤ 1, so that ζ near 1 loses nothing). μs does not enter a
//!   slide.
//! - *Stuck*, the block moves with the belt, y = y_s + vb (τ − τ_s), y' = vb: the position
//!   row is carried, the velocity row is zero (the stick's saltation); ∂y/∂vb grows by the
//!   time stuck and ∂y'/∂vb = 1.
//! - *At events* every column jumps by the saltation of [`super::saltation`]; the event
//!   surfaces of a turn and a stop (y' = 0) do not depend on p, so that is all. A release
//!   happens where h = s N − μs = 0, N = F(τ) − y − 2ζ vb the net force on the stuck block,
//!   which does: its time moves by δτ_r = (s δy − s ∂N/∂p δp + [p = μs] δp)/(s(F' − vb)), and
//!   with the acceleration a⁺ = s(μs − 1) after it the velocity row gains
//!   ```text
//!   δy'⁺ = −(μs − 1)/(s(F' − vb)) · (δy − ∂N/∂p + s [p = μs]),
//!   ```
//!   the state part of which is the release's saltation; ∂N/∂ζ = −2vb, ∂N/∂β = cos θ,
//!   ∂N/∂w = −βτ sin θ, ∂N/∂φ = −β sin θ, ∂N/∂vb = −2ζ at θ = wτ_r + φ.
//! - *On a belt* the velocity zeros are zeros of the slip, h = y' − vb, so that vb moves them:
//!   a stop sets ∂y'/∂vb = 1 (the block takes the belt's speed), a turn from a⁻ to a⁺ sets
//!   ∂y'/∂vb to (a⁺/a⁻) ∂y'/∂vb + 1 − a⁺/a⁻. vb enters no slide: its column is carried by Φ
//!   ([`strobe_map_parameter_derivative`] gives it).
//!
//! **The periodic orbit.** A fixed point x* of the p-fold strobe map, x* = x(kT; x*, p) with
//! kT = 2πk/w, moves with the parameters by
//!
//! ```text
//! dx*/dp = (I − M)⁻¹ (S_p(kT) + ẋ(kT) d(kT)/dp),     d(kT)/dw = −2πk/w²,
//! ```
//!
//! M = J(kT) the monodromy matrix, ẋ(kT) = (vb, 0) when stuck there, and a sample at τ by dy/dp = J_y(τ) dx*/dp + S_{p,y}(τ).
//! This needs I − M invertible (no multiplier 1: not a motion that stays stuck, whose stuck
//! position is neutral), a release that is not tangential, and a periodic particular solution
//! (not ζ = 0 at w = 1).

use super::error::StabilityError;
use crate::error::{Error, Result};
use crate::exact::ExactSolver;
use crate::params::{Parameter, Params, State};
use crate::solver::{EventKind, Phase, Solver};
use crate::trig::sin_cos;
use std::f64::consts::TAU;

/// The parameters of [`OrbitSample::dy`], in its order.
pub const SENSITIVITY_PARAMETERS: [&str; 5] = ["zeta", "beta", "w", "phi", "mu_s"];

/// One sample of a periodic orbit with its sensitivities.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct OrbitSample {
    /// Time τ since the strobe of the fixed point.
    pub tau: f64,
    /// Position y(τ).
    pub y: f64,
    /// Velocity y'(τ).
    pub v: f64,
    /// ∂y(τ)/∂(ζ, β, w, φ, μs) along the periodic orbit (the fixed point moving with the
    /// parameters), at fixed τ.
    pub dy: [f64; 5],
}

/// Columns of the propagated matrix: δy0, δv0, then the five parameters and vb.
const COLUMNS: usize = 8;

/// The column of vb in the propagated matrix.
const VB: usize = 7;

/// EC, ES and their derivatives by ζ at local time `t` ≥ 0 (see the module documentation).
fn basis(zeta: f64, t: f64) -> (f64, f64, f64, f64) {
    let q = (zeta - 1.0) * (zeta + 1.0);
    let x = q * t * t;
    let decay = (-zeta * t).exp();
    let (ec, es, g2) = if x.abs() <= 1.0 {
        // C = Σ xⁿ/(2n)!, S = t Σ xⁿ/(2n+1)!, (tC − S)/q = t³ Σ_{n≥1} 2n x^{n−1}/(2n+1)!.
        let (mut c, mut s, mut g) = (1.0, 1.0, 0.0);
        let mut term = 1.0; // xⁿ/(2n)!
        for n in 1..40 {
            let m = 2.0 * n as f64;
            let previous = term / (m - 1.0); // x^{n−1}/(2n−1)!
            g += previous / (m + 1.0);
            term *= x / ((m - 1.0) * m);
            c += term;
            s += term / (m + 1.0);
            if term.abs() < 1e-18 && previous.abs() < 1e-18 {
                break;
            }
        }
        (decay * c, decay * s * t, decay * g * t * t * t)
    } else if zeta < 1.0 {
        let omega = (-q).sqrt();
        let (sn, cs) = sin_cos(omega * t);
        let (ec, es) = (decay * cs, decay * sn / omega);
        (ec, es, (t * ec - es) / q)
    } else {
        let kappa = q.sqrt();
        let slow = (-t / (zeta + kappa)).exp();
        let fast = (-(zeta + kappa) * t).exp();
        let (ec, es) = (0.5 * (slow + fast), 0.5 * (slow - fast) / kappa);
        (ec, es, (t * ec - es) / q)
    };
    (ec, es, -t * ec + zeta * t * es, -t * es + zeta * g2)
}

/// Φ(t) and ∂Φ/∂ζ.
fn transition(zeta: f64, t: f64) -> ([[f64; 2]; 2], [[f64; 2]; 2]) {
    let (ec, es, dec, des) = basis(zeta, t);
    (
        [[ec + zeta * es, es], [-es, ec - zeta * es]],
        [[dec + es + zeta * des, des], [-des, dec - es - zeta * des]],
    )
}

/// The particular solution of a slide in direction `sign` at τ, P = (y_p − s, y_p'), and its
/// derivatives by (ζ, β, w, φ) (μs: zero).
struct Particular {
    w: f64,
    beta: f64,
    phi: f64,
    /// H = 1/(1 − w² + 2iζw).
    h: (f64, f64),
    /// ∂H/∂ζ, ∂H/∂w.
    dh_zeta: (f64, f64),
    dh_w: (f64, f64),
}

fn mul(a: (f64, f64), b: (f64, f64)) -> (f64, f64) {
    (a.0 * b.0 - a.1 * b.1, a.0 * b.1 + a.1 * b.0)
}

impl Particular {
    fn new(params: &Params) -> Result<Self> {
        let (zeta, w) = (params.zeta, params.w);
        let (re, im) = ((1.0 - w) * (1.0 + w), 2.0 * zeta * w);
        let norm = re * re + im * im;
        if !(norm > 1e-24) {
            return Err(Error::InvalidParameter {
                name: "w",
                value: w,
                allowed: "not 1 at zeta = 0 for sensitivities (the secular case has no \
                          periodic particular solution)",
            });
        }
        let h = (re / norm, -im / norm);
        let h2 = mul(h, h);
        Ok(Self {
            w,
            beta: params.beta,
            phi: params.phi,
            h,
            // ∂H/∂ζ = −H²·2iw; ∂H/∂w = −H²(−2w + 2iζ).
            dh_zeta: mul(h2, (0.0, -2.0 * w)),
            dh_w: mul(h2, (2.0 * w, -2.0 * zeta)),
        })
    }

    /// (P, ∂P/∂(ζ, β, w, φ)) at τ.
    fn at(&self, tau: f64, sign: f64) -> ([f64; 2], [[f64; 2]; 4]) {
        let (sn, cs) = sin_cos(self.w * tau + self.phi);
        let e = (cs, sn);
        let he = mul(self.h, e);
        let z = (self.beta * he.0, self.beta * he.1);
        // v = Re(iwz) = −w Im z.
        let value = [z.0 - sign, -self.w * z.1];
        let dz_zeta = mul(self.dh_zeta, e);
        let dz_zeta = (self.beta * dz_zeta.0, self.beta * dz_zeta.1);
        let dz_beta = he;
        let dz_w = {
            let a = mul(self.dh_w, e);
            // βE(∂H/∂w + iτH).
            (self.beta * a.0 - tau * z.1, self.beta * a.1 + tau * z.0)
        };
        let dz_phi = (-z.1, z.0);
        let row = |dz: (f64, f64)| [dz.0, -self.w * dz.1];
        let mut d_w = row(dz_w);
        d_w[1] -= z.1; // ∂(−w Im z)/∂w includes −Im z.
        (value, [row(dz_zeta), row(dz_beta), d_w, row(dz_phi)])
    }
}

/// The solver with the 2×7 matrix [J | S_p] at its current time.
struct Propagation {
    solver: ExactSolver,
    particular: Particular,
    params: Params,
    s: [[f64; COLUMNS]; 2],
}

impl Propagation {
    fn new(params: Params, initial: State) -> Result<Self> {
        let mut s = [[0.0; COLUMNS]; 2];
        s[0][0] = 1.0;
        s[1][1] = 1.0;
        Ok(Self {
            solver: ExactSolver::new(params, initial),
            particular: Particular::new(&params)?,
            params,
            s,
        })
    }

    /// Advance to the next event or `t_end`, carrying [J | S_p] along.
    fn advance(&mut self, t_end: f64) -> Result<()> {
        let sign = self.solver.phase().sign();
        let from = self.solver.time();
        let start = self.solver.state();
        let event = self.solver.advance(t_end)?;
        let to = self.solver.time();
        if sign == 0.0 {
            // Stuck: y = y_s + vb (τ − τ_s), y' = vb.
            self.s[1] = [0.0; COLUMNS];
            self.s[1][VB] = 1.0;
            self.s[0][VB] += to - from;
        } else if to > from {
            let (pa, dpa) = self.particular.at(from, sign);
            let (_, dpb) = self.particular.at(to, sign);
            let (phi, dphi) = transition(self.params.zeta, to - from);
            let mut q = self.s;
            for (p, dp) in dpa.iter().enumerate() {
                q[0][2 + p] -= dp[0];
                q[1][2 + p] -= dp[1];
            }
            let rest = [start.y - pa[0], start.v - pa[1]];
            let mut next = [[0.0; COLUMNS]; 2];
            for r in 0..2 {
                for c in 0..COLUMNS {
                    next[r][c] = phi[r][0] * q[0][c] + phi[r][1] * q[1][c];
                }
                for (p, dp) in dpb.iter().enumerate() {
                    next[r][2 + p] += dp[r];
                }
                next[r][2] += dphi[r][0] * rest[0] + dphi[r][1] * rest[1];
            }
            self.s = next;
        }
        if let Some(event) = event {
            self.jump(event.kind, event.tau)?;
        }
        Ok(())
    }

    fn jump(&mut self, kind: EventKind, tau: f64) -> Result<()> {
        match kind {
            EventKind::Stick => {
                self.s[1] = [0.0; COLUMNS];
                self.s[1][VB] = 1.0;
            }
            EventKind::Turn => {
                let (sign, d) = self.solver.slide_start().expect("a turn starts a slide");
                let ratio = d[2] / (d[2] + 2.0 * sign);
                for v in &mut self.s[1] {
                    *v *= ratio;
                }
                self.s[1][VB] += 1.0 - ratio;
            }
            EventKind::Slip => {
                let mu_s = self.params.mu_s;
                if mu_s == 1.0 {
                    return Ok(());
                }
                let (sign, d) = self.solver.slide_start().expect("a release starts a slide");
                // s(F' − vb), from y''' = F' − y' − 2ζy'' at the start, where y' = vb.
                let rate = sign * (d[3] + 2.0 * self.params.zeta * d[2]);
                if !(rate > 0.0) {
                    return Err(StabilityError::NonFiniteJacobian { tau }.into());
                }
                let shear = -(mu_s - 1.0) / rate;
                let (sn, cs) = sin_cos(self.params.w * tau + self.params.phi);
                let (beta, vb) = (self.params.beta, self.params.vb);
                // ∂N/∂(ζ, β, w, φ, μs, vb) of the net force N = F − y − 2ζ vb at the release,
                // and the μs term of the event surface.
                let df = [
                    -2.0 * vb,
                    cs,
                    -beta * tau * sn,
                    -beta * sn,
                    -sign,
                    -2.0 * self.params.zeta,
                ];
                for c in 0..COLUMNS {
                    let mut change = self.s[0][c];
                    if c >= 2 {
                        change -= df[c - 2];
                    }
                    self.s[1][c] += shear * change;
                }
            }
        }
        Ok(())
    }

    /// ẋ at the current time ((vb, 0) while stuck).
    fn velocity_field(&self) -> [f64; 2] {
        let x = self.solver.state();
        match self.solver.phase() {
            Phase::Stick => [self.params.vb, 0.0],
            phase => [
                x.v,
                self.params.drive(self.solver.time())
                    - x.y
                    - 2.0 * self.params.zeta * x.v
                    - phase.sign(),
            ],
        }
    }
}

/// Check a request for samples of a periodic orbit (either law's): `period` at least 1, the
/// times `taus` sorted and ≥ 0.
///
/// # Errors
/// [`Error::InvalidParameter`] for p = 0; [`Error::TimeBeforeCurrent`] for the first time
/// before the one before it (or before 0).
pub(crate) fn check_orbit_samples(period: usize, taus: &[f64]) -> Result<()> {
    if period == 0 {
        return Err(Error::InvalidParameter {
            name: "periods",
            value: 0.0,
            allowed: "must be at least 1",
        });
    }
    let mut previous = 0.0;
    for &tau in taus {
        if !(tau >= previous) {
            return Err(Error::TimeBeforeCurrent {
                requested: tau,
                current: previous,
            });
        }
        previous = tau;
    }
    Ok(())
}

/// The periodic orbit through `fixed_point` (the state at a strobe, drive phase φ, that the
/// `period`-fold strobe map keeps), sampled at the sorted times `taus` ≥ 0 with the
/// derivatives of y by (ζ, β, w, φ, μs) (see the module documentation).
///
/// The fixed point is taken as given: a state that repeats to a tolerance ε gives the
/// derivatives of the orbit it approximates to about ε relative.
///
/// ```
/// use stickslip::stability::periodic_orbit_sensitivity;
/// use stickslip::{Params, State};
/// // Linear limit (β large, no stops): y ≈ β·Re[H e^{iwτ}], ∂y/∂β ≈ y/β up to the friction.
/// let params = Params::new(0.1, 0.5, 1.0e6).unwrap();
/// let orbit = stickslip::stability::find_periodic_orbit(
///     &params, State { y: 1.0e6, v: 0.0 }, 1, &Default::default()).unwrap();
/// let samples = periodic_orbit_sensitivity(&params, orbit.state, 1, &[0.0, 1.0]).unwrap();
/// for s in &samples {
///     assert!((s.dy[1] - s.y / 1.0e6).abs() < 1e-5 * s.y.abs().max(1.0));
/// }
/// ```
///
/// # Errors
/// [`Error::InvalidParameter`] for invalid parameters, unsorted or negative times, p = 0, or
/// ζ = 0 at w = 1; [`StabilityError::NonFiniteJacobian`] at a tangential release;
/// [`StabilityError::SingularJacobian`] when I − M is singular (a multiplier 1); whatever
/// the solver reports.
pub fn periodic_orbit_sensitivity(
    params: &Params,
    fixed_point: State,
    period: usize,
    taus: &[f64],
) -> Result<Vec<OrbitSample>> {
    let params = params.validate()?;
    crate::exact::check_coulomb(&params)?;
    let fixed_point = State::new(fixed_point.y, fixed_point.v)?;
    check_orbit_samples(period, taus)?;
    let strobe = period as f64 * params.drive_period();
    let mut run = Propagation::new(params, fixed_point)?;
    // Per sample: y, v and the y row of [J | S_p]; then M, S_p(kT) and ẋ(kT).
    let mut rows = Vec::with_capacity(taus.len());
    let mut at_strobe = None;
    let mut next = 0;
    while next < taus.len() || at_strobe.is_none() {
        let target = match (taus.get(next), at_strobe.is_none()) {
            (Some(&tau), true) => tau.min(strobe),
            (Some(&tau), false) => tau,
            (None, _) => strobe,
        };
        while run.solver.time() < target {
            run.advance(target)?;
        }
        if at_strobe.is_none() && target == strobe {
            at_strobe = Some((run.s, run.velocity_field()));
        }
        while next < taus.len() && taus[next] == target {
            let x = run.solver.state();
            rows.push((target, x.y, x.v, run.s[0]));
            next += 1;
        }
    }
    let (s_strobe, field) = at_strobe.expect("the strobe was reached");
    let m = [
        [s_strobe[0][0], s_strobe[0][1]],
        [s_strobe[1][0], s_strobe[1][1]],
    ];
    let a = [[1.0 - m[0][0], -m[0][1]], [-m[1][0], 1.0 - m[1][1]]];
    let det = a[0][0] * a[1][1] - a[0][1] * a[1][0];
    let scale = 1.0 + m.iter().flatten().fold(0.0f64, |s, v| s.max(v.abs()));
    if !(det.abs() > 1e-12 * scale * scale) {
        return Err(StabilityError::SingularJacobian {
            y: fixed_point.y,
            v: fixed_point.v,
            determinant: det,
        }
        .into());
    }
    let period_by_w = -TAU * period as f64 / (params.w * params.w);
    let mut moved = [[0.0; 5]; 2];
    for p in 0..5 {
        let mut b = [s_strobe[0][2 + p], s_strobe[1][2 + p]];
        if p == 2 {
            b[0] += field[0] * period_by_w;
            b[1] += field[1] * period_by_w;
        }
        moved[0][p] = (a[1][1] * b[0] - a[0][1] * b[1]) / det;
        moved[1][p] = (a[0][0] * b[1] - a[1][0] * b[0]) / det;
    }
    Ok(rows
        .into_iter()
        .map(|(tau, y, v, row)| {
            let mut dy = [0.0; 5];
            for (p, d) in dy.iter_mut().enumerate() {
                *d = row[0] * moved[0][p] + row[1] * moved[1][p] + row[2 + p];
            }
            OrbitSample { tau, y, v, dy }
        })
        .collect())
}

/// The derivatives of the p-fold strobe map P^p by the parameters at `state` (the state at a
/// strobe, not necessarily a fixed point): ∂P^p/∂(ζ, β, w, φ, μs) as columns of
/// [`SENSITIVITY_PARAMETERS`]' order, rows (y, y'). The propagation of
/// [`periodic_orbit_sensitivity`] up to the strobe p drive periods on, with the strobe's time
/// moving with w (the column of w gains ẋ(pT)·d(pT)/dw, d(pT)/dw = −2πp/w²): what the
/// continuation of special points in two parameters ([`crate::continuation`]) needs exactly.
///
/// # Errors
/// As [`periodic_orbit_sensitivity`] (no singular I − M: nothing is inverted here).
pub fn strobe_map_parameter_derivatives(
    params: &Params,
    state: State,
    period: usize,
) -> Result<[[f64; 5]; 2]> {
    let all = strobe_columns(params, state, period)?;
    Ok(all.map(|row| std::array::from_fn(|p| row[p])))
}

/// ∂P^p/∂λ of the p-fold strobe map at `state` by one parameter λ: ζ, β, w, μs (the columns
/// of [`strobe_map_parameter_derivatives`]) or the belt speed vb, rows (y, y').
///
/// vb enters no slide; it moves the stops (y = y_s + vb (τ − τ_s)), the slip zeros that end
/// the slides (y' = vb) and the releases (through the viscous force 2ζ vb): see the module
/// documentation. From a state stuck to the belt (y' = vb, the net force within μs) the
/// derivative is that of the map along the stuck states, y' = vb moving with vb: a strobe
/// inside a stop of a periodic orbit, as the continuation in vb follows it.
///
/// # Errors
/// [`Error::InvalidParameter`] for a parameter other than those five (a smooth law's);
/// otherwise as [`strobe_map_parameter_derivatives`].
pub fn strobe_map_parameter_derivative(
    params: &Params,
    state: State,
    period: usize,
    parameter: Parameter,
) -> Result<[f64; 2]> {
    let column = match parameter {
        Parameter::Zeta => 0,
        Parameter::Beta => 1,
        Parameter::W => 2,
        Parameter::MuS => 4,
        Parameter::Vb => 5,
        _ => {
            return Err(Error::InvalidParameter {
                name: parameter.label(),
                value: parameter.get(params),
                allowed: "not a parameter of the exact model's sensitivities (zeta, beta, w, \
                          mu_s and vb are)",
            })
        }
    };
    let all = strobe_columns(params, state, period)?;
    Ok([all[0][column], all[1][column]])
}

/// ∂P^p/∂(ζ, β, w, φ, μs, vb) at `state` (see [`strobe_map_parameter_derivatives`]).
fn strobe_columns(params: &Params, state: State, period: usize) -> Result<[[f64; 6]; 2]> {
    let params = params.validate()?;
    crate::exact::check_coulomb(&params)?;
    let state = State::new(state.y, state.v)?;
    if period == 0 {
        return Err(Error::InvalidParameter {
            name: "periods",
            value: 0.0,
            allowed: "must be at least 1",
        });
    }
    let strobe = period as f64 * params.drive_period();
    let mut run = Propagation::new(params, state)?;
    while run.solver.time() < strobe {
        run.advance(strobe)?;
    }
    let field = run.velocity_field();
    let period_by_w = -TAU * period as f64 / (params.w * params.w);
    let mut out = [[0.0; 6]; 2];
    for (r, row) in out.iter_mut().enumerate() {
        for (p, d) in row.iter_mut().enumerate() {
            *d = run.s[r][2 + p] + if p == 2 { field[r] * period_by_w } else { 0.0 };
        }
    }
    Ok(out)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::stability::segment::sliding_transition;

    #[test]
    fn the_basis_gives_the_transition_and_its_zeta_derivative() {
        for &zeta in &[0.0, 0.05, 0.7, 0.999, 1.0, 1.001, 1.5, 6.0] {
            for &t in &[0.0, 0.01, 0.4, 1.0, 1.7, 3.0, 9.0] {
                let (phi, dphi) = transition(zeta, t);
                let exact = sliding_transition(zeta, t).0;
                for r in 0..2 {
                    for c in 0..2 {
                        assert!(
                            (phi[r][c] - exact[r][c]).abs() < 1e-14 * (1.0 + exact[r][c].abs()),
                            "zeta {zeta} t {t}: {phi:?} vs {exact:?}"
                        );
                    }
                }
                let h = 1e-5 * zeta.max(1e-3);
                let up = sliding_transition(zeta + h, t).0;
                let down = sliding_transition((zeta - h).max(0.0), t).0;
                let width = zeta + h - (zeta - h).max(0.0);
                for r in 0..2 {
                    for c in 0..2 {
                        let fd = (up[r][c] - down[r][c]) / width;
                        assert!(
                            (dphi[r][c] - fd).abs() < 1e-7 * (1.0 + fd.abs()),
                            "zeta {zeta} t {t} [{r}][{c}]: {} vs {fd}",
                            dphi[r][c]
                        );
                    }
                }
            }
        }
    }
}
