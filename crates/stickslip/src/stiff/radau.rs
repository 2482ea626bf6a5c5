//! Radau IIA of order 5 (three stages) for y'' + 2ζ y' + y + D(y') = β cos(w τ + φ), after
//! Hairer and Wanner, *Solving Ordinary Differential Equations II*, §IV.8 (the code RADAU5),
//! for any smooth law D ([`SmoothLaw`]).
//!
//! **The stage equations.** With x = (y, v), v = y', the collocation conditions at the stage
//! times τ0 + c_i h, written with W = A⁻¹, are
//!
//! ```text
//! F(V) = L V + D(V) − b = 0,      L = W/h + h A + 2ζ I,      b_i = g_i − y0 + (W 1)_i v0/h,
//! ```
//!
//! for the three stage velocities V (the stage positions Y = y0 + h A V are eliminated
//! exactly; g_i is the drive at stage i). The only nonlinearity, D, acts stage by stage. Its
//! slope may be steep: a Shockley diode's runs from about 0.07 at working currents to
//! a/ε ≈ 7.5·10³ at zero current for a 1N4148 (and to 10²⁰ and beyond in the PWL limit).
//! Newton's method in V alone stalls there: where D is steep its linearisation moves V by
//! less than the tolerance while the law's value is still far from consistent. So:
//!
//! - **Two charts per stage.** Where the law offers a steep chart ([`SmoothLaw::steep_slope`])
//!   and it dominates the stage (du/dV > L_ii), the Newton unknown of that stage is u (for a
//!   diode its junction voltage u = a·asinh(V/ε), in which D is linear); elsewhere it is V.
//!   Each iteration is a Newton step in the current charts (same linear system, columns
//!   rescaled by dV/du), so convergence stays quadratic near the root.
//! - **Limiting**: a step in the steep chart is limited by the law
//!   ([`SmoothLaw::steep_step`]: a diode cuts a junction-voltage step that leaves the
//!   diode-dominated range back logarithmically beyond its edge, as SPICE limits junction
//!   voltages, so sinh cannot overshoot); a step in V across the law's knee
//!   ([`SmoothLaw::knee`], a diode's zero current) stops on it (the linearisation in V cannot
//!   see the jump of the law's slope there), where the steep chart takes over.
//! - **Convergence** is measured on the increments of V, of Y and of h·D(V), each scaled by
//!   the error weights, so a stage is converged only when its law's value is.
//! - **Full Newton**: the matrix L + diag(D'(V)) is re-evaluated at every iteration.
//! - **Reversals**: after a step is rejected across the knee, the retry ends at the crossing
//!   predicted by the rejected step's collocation polynomial (the error of a step across a
//!   diode's jump does not shrink like h⁴, so the controller alone rejects several times; this
//!   halves the rejections at loose tolerances).
//!
//! Kept from RADAU5: the embedded error estimate filtered by (I − h γ0 J)⁻¹, with the second
//! filtering after a rejection; the step-size controller with Gustafsson's predictive rule;
//! starting values extrapolated from the previous collocation polynomial; the dense output,
//! which is that polynomial (cubic in θ through the step start and the three stage values,
//! continuous across steps since c3 = 1). Tolerances are used as given (RADAU5 rescales them).

use super::cubic::crossings;
use super::law::SmoothLaw;
use crate::error::{Error, Result};
use crate::params::Params;

/// Dimension of the first-order system (y, y').
pub const N: usize = 2;
/// A state vector (y, y').
pub type Vector = [f64; N];

const SQ6: f64 = 2.449_489_742_783_178;
const C1: f64 = (4.0 - SQ6) / 10.0;
const C2: f64 = (4.0 + SQ6) / 10.0;
pub(super) const C: [f64; 3] = [C1, C2, 1.0];
pub(super) const A: [[f64; 3]; 3] = [
    [
        (88.0 - 7.0 * SQ6) / 360.0,
        (296.0 - 169.0 * SQ6) / 1800.0,
        (-2.0 + 3.0 * SQ6) / 225.0,
    ],
    [
        (296.0 + 169.0 * SQ6) / 1800.0,
        (88.0 + 7.0 * SQ6) / 360.0,
        (-2.0 - 3.0 * SQ6) / 225.0,
    ],
    [(16.0 - SQ6) / 36.0, (16.0 + SQ6) / 36.0, 1.0 / 9.0],
];
/// Error-estimate weights e_i/γ0 of RADAU5.
const DD: [f64; 3] = [
    -(13.0 + 7.0 * SQ6) / 3.0,
    (-13.0 + 7.0 * SQ6) / 3.0,
    -1.0 / 3.0,
];
/// 1/γ0 = 30/(6 + 81^(1/3) − 9^(1/3)): the real eigenvalue of A⁻¹.
const U1: f64 = 3.637_834_252_744_496;

/// Most Newton iterations per step attempt.
const MAX_NEWTON: usize = 10;
/// The iteration count RADAU5's step-size factor is tuned for.
const NIT: f64 = 7.0;
/// Safety factor of the step-size controller.
const SAFE: f64 = 0.9;
/// Bounds on h_old/h_new: at most 8-fold growth, at most 5-fold shrinkage per step.
const FAC_GROW: f64 = 1.0 / 8.0;
const FAC_SHRINK: f64 = 5.0;

/// Accuracy settings of [`Radau5`].
#[derive(Debug, Clone, Copy)]
pub struct Settings {
    /// Relative tolerance.
    pub rtol: f64,
    /// Absolute tolerance.
    pub atol: f64,
    /// Largest step.
    pub max_step: f64,
    /// First trial step.
    pub initial_step: f64,
}

/// One accepted step with its dense output.
#[derive(Debug, Clone, Copy)]
pub struct Step {
    /// Start time.
    pub t0: f64,
    /// Step size.
    pub h: f64,
    /// State at the start.
    pub x0: Vector,
    /// State at the end (exactly the value the integrator continues from).
    pub x1: Vector,
    /// Per component, the monomial coefficients of x(t0 + θh) − x0 in θ (degree 1 to 3).
    coef: [[f64; 3]; N],
    /// The converged stage velocities V_i at τ0 + c_i h (V_3 is the end's).
    pub stages: [f64; 3],
    /// The law's slope D'(V_i) there: with them the Newton matrix of the converged stages,
    /// which the forward sensitivities solve with ([`super::sensitivity`]).
    pub slopes: [f64; 3],
}

impl Step {
    fn new(t0: f64, h: f64, x0: Vector, z: &[Vector; 3]) -> Self {
        // Newton divided differences through (0, 0), (c1, z1), (c2, z2), (1, z3).
        let mut coef = [[0.0; 3]; N];
        for k in 0..N {
            let d1 = z[0][k] / C1;
            let d12 = (z[1][k] - z[0][k]) / (C2 - C1);
            let d2 = (d12 - d1) / C2;
            let d23 = (z[2][k] - z[1][k]) / (1.0 - C2);
            let d123 = (d23 - d12) / (1.0 - C1);
            let d3 = d123 - d2;
            // d1 θ + d2 θ(θ − c1) + d3 θ(θ − c1)(θ − c2)
            coef[k] = [d1 - C1 * d2 + C1 * C2 * d3, d2 - (C1 + C2) * d3, d3];
        }
        let x1 = [x0[0] + z[2][0], x0[1] + z[2][1]];
        Self {
            t0,
            h,
            x0,
            x1,
            coef,
            stages: [x0[1] + z[0][1], x0[1] + z[1][1], x1[1]],
            slopes: [f64::NAN; 3],
        }
    }

    /// The step with its converged stage velocities and the law's slopes there.
    fn with_stages(mut self, stages: [f64; 3], slopes: [f64; 3]) -> Self {
        self.stages = stages;
        self.slopes = slopes;
        self
    }

    /// The abscissae c_i of the three stages in the step (θ = c_i).
    pub const NODES: [f64; 3] = C;

    /// End time.
    pub fn t1(&self) -> f64 {
        self.t0 + self.h
    }

    /// Component `k` as a cubic in θ ∈ [0, 1]: coefficients of 1, θ, θ², θ³.
    pub fn cubic(&self, k: usize) -> [f64; 4] {
        let c = self.coef[k];
        [self.x0[k], c[0], c[1], c[2]]
    }

    /// The state at θ ∈ [0, 1] (θ = 1 gives the end state exactly).
    pub fn eval_theta(&self, theta: f64) -> Vector {
        if theta == 1.0 {
            return self.x1;
        }
        let mut x = [0.0; N];
        for k in 0..N {
            let c = self.coef[k];
            x[k] = self.x0[k] + theta * (c[0] + theta * (c[1] + theta * c[2]));
        }
        x
    }

    /// The state at time `t` (extrapolates outside the step).
    pub fn eval(&self, t: f64) -> Vector {
        let theta = if t == self.t1() {
            1.0
        } else {
            (t - self.t0) / self.h
        };
        self.eval_theta(theta)
    }
}

/// Work counters of [`Radau5`].
#[derive(Debug, Clone, Copy, Default)]
pub struct Counters {
    /// Accepted steps.
    pub accepted: u64,
    /// Rejected step attempts (error too large or Newton failure).
    pub rejected: u64,
    /// Evaluations of the right-hand side (each stage of each Newton iteration counts one).
    pub rhs: u64,
    /// Newton iterations.
    pub newton: u64,
}

/// W = A⁻¹ by Gauss–Jordan elimination (A is well conditioned).
pub(super) fn inverse_of_a() -> [[f64; 3]; 3] {
    let mut m = A;
    let mut w = [[1.0, 0.0, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]];
    for col in 0..3 {
        let pivot = (col..3)
            .max_by(|&i, &j| m[i][col].abs().total_cmp(&m[j][col].abs()))
            .expect("non-empty range");
        m.swap(col, pivot);
        w.swap(col, pivot);
        let inv = 1.0 / m[col][col];
        for k in 0..3 {
            m[col][k] *= inv;
            w[col][k] *= inv;
        }
        for row in 0..3 {
            if row != col {
                let f = m[row][col];
                for k in 0..3 {
                    m[row][k] -= f * m[col][k];
                    w[row][k] -= f * w[col][k];
                }
            }
        }
    }
    w
}

/// The integrator's state between steps, for the law `L`.
#[derive(Debug, Clone)]
pub struct Radau5<L: SmoothLaw> {
    /// ζ, w, β and φ.
    params: Params,
    law: L,
    settings: Settings,
    /// A⁻¹.
    w: [[f64; 3]; 3],
    t: f64,
    x: Vector,
    /// Step size for the next attempt.
    h: f64,
    first: bool,
    reject: bool,
    h_acc: f64,
    err_acc: f64,
    /// Newton's contraction memory η from the last step.
    eta: f64,
    last: Option<Step>,
    /// The drive and (D, D') at the current state, when the last Newton solve left them.
    start: Option<(f64, (f64, f64))>,
    /// Work done so far.
    pub counters: Counters,
}

/// A converged Newton solve.
struct Converged {
    /// Stage increments Z_i = (Y_i − y0, V_i − v0).
    z: [Vector; 3],
    /// The stage velocities V_i and the law's slopes D'(V_i) there.
    stages: [f64; 3],
    slopes: [f64; 3],
    /// Newton iterations used.
    iterations: usize,
    /// The drive and (D, D') at the last stage, which is the step's end.
    end: (f64, (f64, f64)),
}

impl<L: SmoothLaw> Radau5<L> {
    /// Start at (t, x) on y'' + 2ζ y' + y + D(y') = β cos(w τ + φ) with ζ, w, β, φ from
    /// `params` and D the law `law` (taken as valid).
    pub fn new(params: Params, law: L, t: f64, x: Vector, settings: Settings) -> Self {
        Self {
            params,
            law,
            settings,
            w: inverse_of_a(),
            t,
            x,
            h: settings.initial_step.min(settings.max_step),
            first: true,
            reject: false,
            h_acc: 0.0,
            err_acc: 1e-2,
            eta: 1.0,
            last: None,
            start: None,
            counters: Counters::default(),
        }
    }

    integrator_accessors!(Radau5);

    /// Weights atol + rtol·max(|a|, |b|).
    fn scale(&self, a: &Vector, b: &Vector) -> Vector {
        let s = &self.settings;
        let mut w = [0.0; N];
        for k in 0..N {
            w[k] = s.atol + s.rtol * a[k].abs().max(b[k].abs());
        }
        w
    }

    /// f(t, x) = (v, a(t, y, v)) and the Jacobian entries a_y = −1, a_v = −2ζ − D'(v).
    fn rhs(&self, t: f64, x: &Vector) -> (Vector, f64) {
        let p = &self.params;
        let (d, slope) = self.law.value_and_slope(x[1]);
        let c = 2.0 * p.zeta;
        ([x[1], p.drive(t) - x[0] - c * x[1] - d], -c - slope)
    }

    /// Solve F(V) = L V + D(V) − b = 0 for step size h by Newton's method in per-stage
    /// charts (see the module documentation), or None when Newton does not converge.
    fn newton(&mut self, h: f64, start: [f64; 3]) -> Option<Converged> {
        let scale = self.scale(&self.x, &self.x);
        let kappa = self.settings.rtol.sqrt().min(0.03);
        let law = self.law;
        let knee = law.knee();
        let p = self.params;
        let [y0, v0] = self.x;
        let damping = 2.0 * p.zeta;
        let w = &self.w;
        // (No cosines without a drive: a self-excited belt's slips, β = 0.)
        let drive = if p.beta == 0.0 {
            [0.0; 3]
        } else {
            [
                p.drive(self.t + C[0] * h),
                p.drive(self.t + C[1] * h),
                p.drive(self.t + h),
            ]
        };
        let mut l = [[0.0; 3]; 3];
        let mut b = [0.0; 3];
        for i in 0..3 {
            for j in 0..3 {
                l[i][j] = w[i][j] / h + h * A[i][j];
            }
            l[i][i] += damping;
            b[i] = drive[i] - y0 + (w[i][0] + w[i][1] + w[i][2]) * v0 / h;
        }
        let mut v = [v0 + start[0], v0 + start[1], v0 + start[2]];
        // D and D' at the current iterate, evaluated once per iterate.
        let mut d = [(0.0, 0.0); 3];
        for i in 0..3 {
            d[i] = law.value_and_slope(v[i]);
        }
        let mut eta = self.eta.max(f64::EPSILON).powf(0.8);
        let mut previous = 0.0;
        for iteration in 0..MAX_NEWTON {
            self.counters.newton += 1;
            self.counters.rhs += 3;
            let mut jac = l;
            let mut residual = [0.0; 3];
            // dV/du of each stage's chart: 1 (current) or √(ε² + V²)/a (junction voltage).
            let mut dv_du = [1.0; 3];
            for i in 0..3 {
                let (value, slope) = d[i];
                jac[i][i] += slope;
                residual[i] = l[i][0] * v[0] + l[i][1] * v[1] + l[i][2] * v[2] + value - b[i];
                if let Some(steep) = law.steep_slope(v[i], slope) {
                    if steep > l[i][i] {
                        dv_du[i] = 1.0 / steep;
                    }
                }
            }
            for row in &mut jac {
                for k in 0..3 {
                    row[k] *= dv_du[k];
                }
            }
            let [[d0], [d1], [d2]] =
                solve3(jac, [[-residual[0]], [-residual[1]], [-residual[2]]], 1)?;
            let delta = [d0, d1, d2];
            let mut norm = 0.0;
            let mut moved = [0.0; 3];
            for i in 0..3 {
                let old = v[i];
                v[i] = if dv_du[i] == 1.0 {
                    let next = old + delta[i];
                    // A linearisation in V cannot see the jump of the law's slope at its
                    // knee (a diode's zero current): a step across the knee stops on it,
                    // where the steep chart takes over.
                    match knee {
                        Some(k) if (next - k) * (old - k) < 0.0 => k,
                        _ => next,
                    }
                } else {
                    law.steep_step(old, d[i].0, delta[i], l[i][i])
                };
                moved[i] = v[i] - old;
                let next = law.value_and_slope(v[i]);
                let dd = next.0 - d[i].0;
                d[i] = next;
                norm += (moved[i] / scale[1]).powi(2) + (h * dd / scale[1]).powi(2);
            }
            for i in 0..3 {
                let dy = h * (A[i][0] * moved[0] + A[i][1] * moved[1] + A[i][2] * moved[2]);
                norm += (dy / scale[0]).powi(2);
            }
            let norm = (norm / 9.0).sqrt();
            if !norm.is_finite() || !v.iter().all(|x| x.is_finite()) {
                return None;
            }
            if iteration > 0 {
                let theta = norm / previous;
                // The first iterations may move between charts; after that, insist on
                // contraction.
                if iteration >= 3 && theta >= 0.9 {
                    return None;
                }
                eta = if theta < 1.0 {
                    theta / (1.0 - theta)
                } else {
                    f64::INFINITY
                };
            }
            previous = norm.max(f64::MIN_POSITIVE);
            if eta * norm <= kappa || norm == 0.0 {
                self.eta = eta;
                let mut z = [[0.0; N]; 3];
                for i in 0..3 {
                    z[i] = [
                        h * (A[i][0] * v[0] + A[i][1] * v[1] + A[i][2] * v[2]),
                        v[i] - v0,
                    ];
                }
                return Some(Converged {
                    z,
                    stages: v,
                    slopes: [d[0].1, d[1].1, d[2].1],
                    iterations: iteration + 1,
                    end: (drive[2], d[2]),
                });
            }
        }
        None
    }

    /// Newton starting values for V − v0: the last collocation polynomial extrapolated, or
    /// zero.
    fn start_values(&self, h: f64) -> [f64; 3] {
        let mut z = [0.0; 3];
        if let (Some(last), false) = (&self.last, self.first) {
            for i in 0..3 {
                z[i] = last.eval(self.t + C[i] * h)[1] - self.x[1];
            }
        }
        z
    }

    /// Take one accepted step (retrying with smaller steps as needed).
    ///
    /// # Errors
    /// [`Error::StepSizeTooSmall`] when the step size underflows.
    pub fn step(&mut self) -> Result<Step> {
        let (f0, av0) = match self.start.take() {
            // The last Newton iterate of the previous step ends exactly here.
            Some((drive, (d, slope))) => {
                let c = 2.0 * self.params.zeta;
                (
                    [self.x[1], drive - self.x[0] - c * self.x[1] - d],
                    -c - slope,
                )
            }
            None => {
                self.counters.rhs += 1;
                self.rhs(self.t, &self.x)
            }
        };
        loop {
            let h = self.h.min(self.settings.max_step);
            if !(h > 16.0 * f64::EPSILON * self.t.abs().max(1.0)) {
                return Err(Error::StepSizeTooSmall {
                    tau: self.t,
                    step: h,
                });
            }
            let Some(Converged {
                z,
                stages,
                slopes,
                iterations,
                end,
            }) = self.newton(h, self.start_values(h))
            else {
                self.counters.rejected += 1;
                self.h = h * 0.5;
                self.reject = true;
                continue;
            };
            let x1 = [self.x[0] + z[2][0], self.x[1] + z[2][1]];
            let scale = self.scale(&self.x, &x1);
            // Embedded estimate, filtered: (u1/h − J0)⁻¹ (f0 + Σ dd_i z_i / h).
            let mut f2 = [0.0; N];
            for k in 0..N {
                f2[k] = (DD[0] * z[0][k] + DD[1] * z[1][k] + DD[2] * z[2][k]) / h;
            }
            let fac = U1 / h;
            let mut e = solve2(fac, av0, [f0[0] + f2[0], f0[1] + f2[1]]);
            let mut err = rms(&e, &scale);
            if err >= 1.0 && (self.first || self.reject) {
                if let Some(e1) = e {
                    let (f1, _) = self.rhs(self.t, &[self.x[0] + e1[0], self.x[1] + e1[1]]);
                    self.counters.rhs += 1;
                    e = solve2(fac, av0, [f1[0] + f2[0], f1[1] + f2[1]]);
                    err = rms(&e, &scale);
                }
            }
            let err = err.max(1e-10);
            // Fewer step-size gains when Newton needed many iterations.
            let fac = SAFE.min(SAFE * (1.0 + 2.0 * NIT) / (iterations as f64 + 2.0 * NIT));
            let mut quot = FAC_GROW.max(FAC_SHRINK.min(err.sqrt().sqrt() / fac));
            let mut h_new = h / quot;
            if err < 1.0 {
                if !self.first {
                    let gus = (self.h_acc / h) * (err / self.err_acc.sqrt()).sqrt() / SAFE;
                    quot = quot.max(FAC_GROW.max(FAC_SHRINK.min(gus)));
                    h_new = h / quot;
                }
                self.h_acc = h;
                self.err_acc = err.max(1e-2);
                if self.reject {
                    h_new = h_new.min(h);
                }
                let step = Step::new(self.t, h, self.x, &z).with_stages(stages, slopes);
                self.t += h;
                self.x = x1;
                self.h = h_new.min(self.settings.max_step);
                self.first = false;
                self.reject = false;
                self.last = Some(step);
                self.start = Some(end);
                self.counters.accepted += 1;
                return Ok(step);
            }
            self.counters.rejected += 1;
            if let Some(k) = self
                .law
                .knee()
                .filter(|k| (self.x[1] - k) * (x1[1] - k) < 0.0)
            {
                // The velocity crossed the knee inside the rejected step (a diode's current
                // reversed): its error is the jump of the law's slope, which the h^4 law of
                // the controller underestimates. Retry up to the crossing predicted by the
                // rejected step's own polynomial.
                let cubic = Step::new(self.t, h, self.x, &z).cubic(1);
                let mut first_zero = f64::NAN;
                crossings(&cubic, k, |theta| {
                    if first_zero.is_nan() {
                        first_zero = theta;
                    }
                });
                if first_zero > 0.0 {
                    h_new = h_new.min(first_zero * h);
                }
            }
            self.h = if self.first { h * 0.1 } else { h_new };
            self.reject = true;
        }
    }

    /// One step of exactly size `h`, without error control (convergence-order tests, and
    /// the step that ends on an event of a friction law's slip, [`crate::friction_solver`]).
    pub(crate) fn fixed_step(&mut self, h: f64) -> Option<Step> {
        let c = self.newton(h, [0.0; 3])?;
        let step = Step::new(self.t, h, self.x, &c.z).with_stages(c.stages, c.slopes);
        self.t += h;
        self.x = step.x1;
        self.last = Some(step);
        Some(step)
    }
}

/// Root-mean-square of e/scale; infinite when the estimate failed.
fn rms(e: &Option<Vector>, scale: &Vector) -> f64 {
    match e {
        Some(e) => {
            let mut s = 0.0;
            for k in 0..N {
                s += (e[k] / scale[k]).powi(2);
            }
            let r = (s / N as f64).sqrt();
            if r.is_finite() {
                r
            } else {
                f64::INFINITY
            }
        }
        None => f64::INFINITY,
    }
}

/// Solve (fac·I − J) x = b for J = [[0, 1], [−1, a_v]].
fn solve2(fac: f64, av: f64, b: Vector) -> Option<Vector> {
    let (a11, a12, a21, a22) = (fac, -1.0, 1.0, fac - av);
    let det = a11 * a22 - a12 * a21;
    if det == 0.0 || !det.is_finite() {
        return None;
    }
    Some([
        (b[0] * a22 - a12 * b[1]) / det,
        (a11 * b[1] - a21 * b[0]) / det,
    ])
}

/// Solve M X = R (3×3) for the first `columns` of the N right-hand sides in the columns of
/// R, by Gaussian elimination with partial pivoting; `None` when M is singular (a pivot zero
/// or not finite). The Newton corrector solves for one column, the sensitivities
/// ([`super::sensitivity`]) for all of theirs with the same elimination. A row whose factor
/// is zero is left as it is.
pub(super) fn solve3<const N: usize>(
    mut m: [[f64; 3]; 3],
    mut r: [[f64; N]; 3],
    columns: usize,
) -> Option<[[f64; N]; 3]> {
    for col in 0..3 {
        let mut pivot = col;
        for row in col + 1..3 {
            if m[row][col].abs() > m[pivot][col].abs() {
                pivot = row;
            }
        }
        if m[pivot][col] == 0.0 || !m[pivot][col].is_finite() {
            return None;
        }
        m.swap(col, pivot);
        r.swap(col, pivot);
        let inv = 1.0 / m[col][col];
        for row in col + 1..3 {
            let factor = m[row][col] * inv;
            if factor == 0.0 {
                continue;
            }
            for k in col..3 {
                m[row][k] -= factor * m[col][k];
            }
            let pivot_row = r[col];
            for (x, p) in r[row][..columns].iter_mut().zip(&pivot_row[..columns]) {
                *x -= factor * p;
            }
        }
    }
    let mut x = [[0.0; N]; 3];
    for row in (0..3).rev() {
        for c in 0..columns {
            let mut s = r[row][c];
            for k in row + 1..3 {
                s -= m[row][k] * x[k][c];
            }
            x[row][c] = s / m[row][row];
        }
    }
    Some(x)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::shockley::{DiodeLaw, ShockleyModel};

    /// y'' + c y' + y = β cos(w t + φ): exact solution from (y0, v0) at t = 0 (c < 2).
    fn linear_exact(c: f64, p: &Params, y0: f64, v0: f64, t: f64) -> (f64, f64) {
        let (w, beta, phi) = (p.w, p.beta, p.phi);
        let delta = (1.0 - w * w).powi(2) + (c * w).powi(2);
        let (pa, pb) = (beta * (1.0 - w * w) / delta, beta * c * w / delta);
        // Particular solution pa cos(wt + φ) + pb sin(wt + φ).
        let part = |t: f64| {
            let (s, co) = (w * t + phi).sin_cos();
            (pa * co + pb * s, w * (pb * co - pa * s))
        };
        let zeta = c / 2.0;
        let wd = (1.0 - zeta * zeta).sqrt();
        let (yp0, vp0) = part(0.0);
        let ca = y0 - yp0;
        let cb = (v0 - vp0 + zeta * ca) / wd;
        let e = (-zeta * t).exp();
        let (s, co) = (wd * t).sin_cos();
        let (yp, vp) = part(t);
        (
            yp + e * (ca * co + cb * s),
            vp + e * ((cb * wd - zeta * ca) * co - (ca * wd + zeta * cb) * s),
        )
    }

    /// A model whose diode is linear to rounding: D(v) = a asinh(v/ε) with ε = 10³ is
    /// (a/ε) v up to a cubic term below 10⁻¹³ for |v| < 3.
    fn linear_model() -> (ShockleyModel, f64) {
        let params = Params::new(0.05, 0.8, 1.5).unwrap().with_phi(0.3).unwrap();
        let law = DiodeLaw::new(1e-3, 1e3, 0.0).unwrap();
        (ShockleyModel::new(params, law).unwrap(), 2.0 * 0.05 + 1e-6)
    }

    fn settings() -> Settings {
        Settings {
            rtol: 1e-13,
            atol: 1e-13,
            max_step: 10.0,
            initial_step: 1e-3,
        }
    }

    #[test]
    fn w_is_the_inverse_of_a() {
        let w = inverse_of_a();
        for i in 0..3 {
            for j in 0..3 {
                let x: f64 = (0..3).map(|k| A[i][k] * w[k][j]).sum();
                let expected = if i == j { 1.0 } else { 0.0 };
                assert!((x - expected).abs() < 1e-14, "({i}, {j}): {x}");
            }
        }
        // U1 is the real eigenvalue of A⁻¹: det(W − U1 I) = 0.
        let m = |i: usize, j: usize| w[i][j] - if i == j { U1 } else { 0.0 };
        let det = m(0, 0) * (m(1, 1) * m(2, 2) - m(1, 2) * m(2, 1))
            - m(0, 1) * (m(1, 0) * m(2, 2) - m(1, 2) * m(2, 0))
            + m(0, 2) * (m(1, 0) * m(2, 1) - m(1, 1) * m(2, 0));
        assert!(det.abs() < 1e-12, "{det}");
    }

    /// Global error at t = 10 with n fixed steps, and the largest error of the dense output
    /// at the midpoints of the steps.
    fn fixed_run(n: usize) -> (f64, f64) {
        let (model, c) = linear_model();
        let (y0, v0) = (0.4, -0.2);
        let mut r = Radau5::new(model.params, model.law, 0.0, [y0, v0], settings());
        let h = 10.0 / n as f64;
        let mut dense = 0.0f64;
        for _ in 0..n {
            let step = r
                .fixed_step(h)
                .expect("Newton converges on a linear problem");
            let mid = step.t0 + 0.5 * h;
            let x = step.eval(mid);
            let (y, _) = linear_exact(c, &model.params, y0, v0, mid);
            dense = dense.max((x[0] - y).abs());
        }
        let (y, v) = linear_exact(c, &model.params, y0, v0, 10.0);
        ((r.x[0] - y).abs().max((r.x[1] - v).abs()), dense)
    }

    #[test]
    fn fifth_order_at_the_step_ends_and_fourth_order_in_between() {
        let runs: Vec<(f64, f64)> = [20, 40, 80].iter().map(|&n| fixed_run(n)).collect();
        eprintln!("fixed steps 20, 40, 80 over [0, 10]: (end error, dense error) {runs:?}");
        for k in 0..2 {
            let order = (runs[k].0 / runs[k + 1].0).log2();
            assert!(
                (4.7..5.4).contains(&order),
                "end-point order {order}: {runs:?}"
            );
            let dense_order = (runs[k].1 / runs[k + 1].1).log2();
            assert!(
                (3.7..4.4).contains(&dense_order),
                "dense order {dense_order}: {runs:?}"
            );
        }
        assert!(runs[2].0 < 1e-7, "{runs:?}");
    }

    #[test]
    fn adaptive_error_follows_the_tolerance() {
        let (model, c) = linear_model();
        let mut errors = Vec::new();
        for tol in [1e-5, 1e-7, 1e-9] {
            let s = Settings {
                rtol: tol,
                atol: tol,
                max_step: 10.0,
                initial_step: 1e-3,
            };
            let mut r = Radau5::new(model.params, model.law, 0.0, [0.0, 0.0], s);
            while r.time() < 30.0 {
                r.step().unwrap();
            }
            let (y, v) = linear_exact(c, &model.params, 0.0, 0.0, r.time());
            errors.push(((r.x[0] - y).abs().max((r.x[1] - v).abs()), r.counters));
        }
        for (k, (e, _)) in errors.iter().enumerate() {
            let tol = [1e-5, 1e-7, 1e-9][k];
            assert!(*e < 30.0 * tol, "tol {tol}: error {e}");
        }
        assert!(errors[2].0 < errors[0].0 / 100.0, "{errors:?}");
    }

    #[test]
    fn newton_converges_across_the_knee_of_a_nearly_ideal_diode() {
        // a = 0.01 puts the knee at ε ≈ 7e-44 with slope 1e41 at zero current; long steps
        // from sliding into a stop, from rest, and from a tiny current of the wrong sign must
        // all converge onto the stuck state, where the current is ε·sinh(force/a) ≈ 1e-22.
        let law = DiodeLaw::pwl_limit(0.01, 1.0, 0.0).unwrap();
        let params = Params::new(0.05, 0.5, 0.5).unwrap();
        let model = ShockleyModel::new(params, law).unwrap();
        for x0 in [[0.2, 0.3], [0.0, 0.0], [0.1, -1e-30]] {
            let mut r = Radau5::new(model.params, model.law, 0.0, x0, settings());
            let step = r.fixed_step(0.5).expect("converges");
            assert!(step.x1[1].abs() < 1e-20, "{x0:?} -> {:?}", step.x1);
        }
    }
}
