//! Forward sensitivities on the integrator's own steps: the derivatives of the computed
//! solution by its initial state (the tangent dynamics, the monodromy matrix) and by the
//! parameters (ζ, β, w, φ and the law's own θ).
//!
//! **The method.** As CVODES and IDAS do for implicit methods (their *staggered direct*
//! corrector: the state's corrector first, then the sensitivity systems, which are linear,
//! solved with the Newton matrix of the converged step), each accepted step is
//! differentiated at its converged stages. The stage equations of [`super::radau`],
//!
//! ```text
//! F(V; y0, v0, p) = L V + D(V) − b = 0,      L = W/h + h A + 2ζ I,
//! b_i = β cos(w τ_i + φ) − y0 + (W 1)_i v0/h,   τ_i = τ0 + c_i h,
//! ```
//!
//! give, for any column c (y0, v0 or a parameter), the linear system
//!
//! ```text
//! J ∂V/∂c = ∂b/∂c − ∂(L V + D(V))/∂c,       J = L + diag(D'(V_i)),
//! ```
//!
//! with right-hand sides −1 (y0), (W 1)_i/h (v0), −2V_i (ζ), cos θ_i (β), −β τ_i sin θ_i (w),
//! −β sin θ_i (φ) and −∂D/∂θ_k(V_i) (the law's parameters, [`SmoothLaw::parameter_derivatives`]),
//! θ_i = w τ_i + φ. The stage increments Z_i = (h Σ_j A_ij V_j, V_i − v0) follow, and so the
//! step's end (x1 = x0 + Z_3) and its dense output (the collocation polynomial, linear in the
//! Z_i). Over a run the sensitivity S = ∂x/∂(x_init, p) is carried from step to step by the
//! chain rule ([`StepDerivative::apply`]).
//!
//! There is no iteration and no error control of its own: the step sizes are the state's
//! (CVODES's `errconS = false`), so S is the exact derivative of the solution the integrator
//! computes (of the converged stage equations: the Newton iteration's last correction, below
//! its tolerance, is the only difference), not a noisy difference of two runs whose steps
//! differ. It converges to the derivative of the flow at the method's order as the tolerance
//! tightens; the tests compare it with Richardson-extrapolated central differences.
//!
//! The determinant of the state block is carried as a logarithm ([`Track`]): where a steep
//! law damps the velocity (a diode's stop) it falls far below anything the entries of the
//! product could show.

use super::law::{SmoothLaw, MAX_LAW_PARAMETERS};
use super::radau::{inverse_of_a, solve3, Step, A, C};
use crate::params::Params;
use std::sync::OnceLock;

/// The parameters of the equation a sensitivity is taken by, before the law's own: ζ, β, w,
/// φ (the columns after y0 and v0).
pub const EQUATION_PARAMETERS: [&str; 4] = ["zeta", "beta", "w", "phi"];

/// Most columns of a [`Sensitivity`]: y0, v0, ζ, β, w, φ and the law's parameters.
pub const MAX_COLUMNS: usize = 2 + EQUATION_PARAMETERS.len() + MAX_LAW_PARAMETERS;

/// What a sensitivity is taken by.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Columns {
    /// The initial state (y0, v0) only: the tangent dynamics.
    State,
    /// The initial state, then ζ, β, w, φ ([`EQUATION_PARAMETERS`]), then the law's own
    /// parameters ([`SmoothLaw::PARAMETERS`]).
    Parameters,
}

impl Columns {
    /// How many columns this is for the law `L`.
    pub fn count<L: SmoothLaw>(self) -> usize {
        match self {
            Columns::State => 2,
            Columns::Parameters => 2 + EQUATION_PARAMETERS.len() + L::PARAMETERS.len(),
        }
    }
}

/// ∂x(τ)/∂(y0, v0, p) at one time: two rows (y, y'), the columns of [`Columns`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Sensitivity {
    columns: usize,
    rows: [[f64; MAX_COLUMNS]; 2],
}

impl Sensitivity {
    /// [I | 0] with `columns` columns (at least 2, at most [`MAX_COLUMNS`]): the sensitivity
    /// at the start of a run.
    ///
    /// # Panics
    /// When `columns` is out of that range (a broken contract).
    pub fn identity(columns: usize) -> Self {
        assert!((2..=MAX_COLUMNS).contains(&columns), "{columns} columns");
        let mut rows = [[0.0; MAX_COLUMNS]; 2];
        rows[0][0] = 1.0;
        rows[1][1] = 1.0;
        Self { columns, rows }
    }

    /// The number of columns.
    pub fn columns(&self) -> usize {
        self.columns
    }

    /// Row `k` (0: y, 1: y'), its `columns` entries.
    pub fn row(&self, k: usize) -> &[f64] {
        &self.rows[k][..self.columns]
    }

    /// Column `c`: ∂(y, y')/∂(column c).
    pub fn column(&self, c: usize) -> [f64; 2] {
        [self.rows[0][c], self.rows[1][c]]
    }

    /// Set column `c` to `value` (a jump of the perturbations at an event).
    pub fn set_column(&mut self, c: usize, value: [f64; 2]) {
        self.rows[0][c] = value[0];
        self.rows[1][c] = value[1];
    }

    /// The state block ∂(y, y')/∂(y0, v0).
    pub fn state(&self) -> [[f64; 2]; 2] {
        [
            [self.rows[0][0], self.rows[0][1]],
            [self.rows[1][0], self.rows[1][1]],
        ]
    }

    /// Every entry times `factor` (a renormalisation of the tangent).
    pub fn scale(&mut self, factor: f64) {
        for row in &mut self.rows {
            for x in &mut row[..self.columns] {
                *x *= factor;
            }
        }
    }
}

/// W = A⁻¹ and its row sums W·1, computed once.
fn w_and_sums() -> &'static ([[f64; 3]; 3], [f64; 3]) {
    static W: OnceLock<([[f64; 3]; 3], [f64; 3])> = OnceLock::new();
    W.get_or_init(|| {
        let w = inverse_of_a();
        let sums = [
            w[0][0] + w[0][1] + w[0][2],
            w[1][0] + w[1][1] + w[1][2],
            w[2][0] + w[2][1] + w[2][2],
        ];
        (w, sums)
    })
}

/// The weights ℓ_i(θ) of the stage increments in the dense output, x(τ0 + θh) − x0 =
/// Σ ℓ_i(θ) Z_i: the Lagrange basis of the nodes 0, c1, c2, 1 at c1, c2, 1 (exactly (0, 0, 1)
/// at θ = 1).
pub fn dense_weights(theta: f64) -> [f64; 3] {
    if theta == 1.0 {
        return [0.0, 0.0, 1.0];
    }
    let nodes = [0.0, C[0], C[1], C[2]];
    let mut out = [0.0; 3];
    for (i, weight) in out.iter_mut().enumerate() {
        let j = i + 1;
        let mut l = 1.0;
        for (m, &node) in nodes.iter().enumerate() {
            if m != j {
                l *= (theta - node) / (nodes[j] - node);
            }
        }
        *weight = l;
    }
    out
}

/// The local derivatives of one accepted step: how its stage increments Z_i move with the
/// step's start (y0, v0) and the parameters (see the module documentation).
#[derive(Debug, Clone, Copy)]
pub struct StepDerivative {
    columns: usize,
    /// ∂Z_i/∂c: stage i, component (y, y'), column c.
    dz: [[[f64; MAX_COLUMNS]; 2]; 3],
}

impl StepDerivative {
    /// The derivatives of `step` (taken by the integrator on the equation with `params` and
    /// `law`), for `columns` columns ([`Columns::count`]); `None` when the Newton matrix of
    /// its converged stages is singular or not finite.
    pub fn new<L: SmoothLaw>(
        step: &Step,
        params: &Params,
        law: &L,
        columns: usize,
    ) -> Option<Self> {
        debug_assert!((2..=MAX_COLUMNS).contains(&columns));
        let (w, sums) = w_and_sums();
        let h = step.h;
        let mut jac = [[0.0; 3]; 3];
        for i in 0..3 {
            for j in 0..3 {
                jac[i][j] = w[i][j] / h + h * A[i][j];
            }
            jac[i][i] += 2.0 * params.zeta + step.slopes[i];
        }
        let mut rhs = [[0.0; MAX_COLUMNS]; 3];
        let mut law_derivatives = [0.0; MAX_LAW_PARAMETERS];
        let n_law = columns.saturating_sub(2 + EQUATION_PARAMETERS.len());
        for i in 0..3 {
            let r = &mut rhs[i];
            r[0] = -1.0;
            r[1] = sums[i] / h;
            if columns > 2 {
                let v = step.stages[i];
                let tau = step.t0 + C[i] * h;
                let (sin, cos) = (params.w * tau + params.phi).sin_cos();
                r[2] = -2.0 * v;
                r[3] = cos;
                r[4] = -params.beta * tau * sin;
                r[5] = -params.beta * sin;
                if n_law > 0 {
                    law.parameter_derivatives(v, &mut law_derivatives[..n_law]);
                    for k in 0..n_law {
                        r[6 + k] = -law_derivatives[k];
                    }
                }
            }
        }
        let dv = solve3(jac, rhs, columns).filter(|x| {
            x.iter()
                .all(|row| row[..columns].iter().all(|v| v.is_finite()))
        })?;
        let mut dz = [[[0.0; MAX_COLUMNS]; 2]; 3];
        for i in 0..3 {
            for c in 0..columns {
                dz[i][0][c] = h * (A[i][0] * dv[0][c] + A[i][1] * dv[1][c] + A[i][2] * dv[2][c]);
                dz[i][1][c] = dv[i][c];
            }
            dz[i][1][1] -= 1.0;
        }
        Some(Self { columns, dz })
    }

    /// The number of columns.
    pub fn columns(&self) -> usize {
        self.columns
    }

    /// The sensitivity at θ ∈ [0, 1] of the step, given `start`, the sensitivity at its start
    /// (θ = 1: at its end).
    pub fn apply(&self, start: &Sensitivity, theta: f64) -> Sensitivity {
        let weights = dense_weights(theta);
        let mut out = *start;
        for c in 0..self.columns.min(start.columns) {
            let (s0, s1) = (start.rows[0][c], start.rows[1][c]);
            for k in 0..2 {
                let mut change = 0.0;
                for (i, weight) in weights.iter().enumerate() {
                    if *weight == 0.0 {
                        continue;
                    }
                    let z = &self.dz[i][k];
                    let mut dz = z[0] * s0 + z[1] * s1;
                    if c >= 2 {
                        dz += z[c];
                    }
                    change += weight * dz;
                }
                out.rows[k][c] += change;
            }
        }
        out
    }

    /// ∂x(τ0 + θh)/∂x0: the state block of the step's own derivative at θ.
    pub fn state_jacobian(&self, theta: f64) -> [[f64; 2]; 2] {
        let weights = dense_weights(theta);
        let mut g = [[1.0, 0.0], [0.0, 1.0]];
        for (i, weight) in weights.iter().enumerate() {
            for k in 0..2 {
                for c in 0..2 {
                    g[k][c] += weight * self.dz[i][k][c];
                }
            }
        }
        g
    }
}

/// ln|det| and the sign of the determinant of a 2×2 matrix.
fn log_det(m: [[f64; 2]; 2]) -> (f64, f64) {
    let det = m[0][0] * m[1][1] - m[0][1] * m[1][0];
    (det.abs().ln(), det.signum())
}

/// Outside [SCALE_BELOW, SCALE_ABOVE] the entries of a tracked state block are rescaled
/// into [`Track`]'s logarithmic factor, so that long runs neither overflow nor underflow.
const SCALE_BELOW: f64 = 1e-100;
const SCALE_ABOVE: f64 = 1e100;

/// The sensitivity carried along a run, step by step: it stands at the start of the step the
/// run is in (where the last step passed ended). Its entries are kept within 10^±100 by a
/// factor e^s taken out into a logarithm (a tangent over thousands of drive periods of a
/// contracting orbit would underflow), and ln|det| of its state block is kept apart: the
/// determinant of the product of the steps' state blocks, which the entries of the product
/// lose where a steep law damps the velocity.
#[derive(Debug, Clone)]
pub struct Track {
    /// The sensitivity divided by e^`log_scale`.
    base: Sensitivity,
    log_scale: f64,
    /// ln|det| and sign of the state block of the sensitivity at `base` (with the factor).
    log_det: f64,
    sign: f64,
}

impl Track {
    /// S = [I | 0] with `columns` columns.
    pub fn new(columns: usize) -> Self {
        Self {
            base: Sensitivity::identity(columns),
            log_scale: 0.0,
            log_det: 0.0,
            sign: 1.0,
        }
    }

    /// The number of columns.
    pub fn columns(&self) -> usize {
        self.base.columns
    }

    /// ln of the factor e^s the entries are divided by (0 until they leave 10^±100).
    pub fn log_scale(&self) -> f64 {
        self.log_scale
    }

    /// The sensitivity where the track stands (the start of the current step), divided by
    /// e^[`Track::log_scale`], with ln|det| and the sign of its state block.
    pub fn base(&self) -> (Sensitivity, (f64, f64)) {
        (self.base, (self.log_det, self.sign))
    }

    /// The sensitivity at θ of `step`, the step the track stands at the start of (divided by
    /// e^[`Track::log_scale`]), with ln|det| and the sign of its state block; `None` when the
    /// step's Newton matrix is singular.
    pub fn at<L: SmoothLaw>(
        &self,
        step: &Step,
        params: &Params,
        law: &L,
        theta: f64,
    ) -> Option<(Sensitivity, (f64, f64))> {
        if theta == 0.0 {
            return Some(self.base());
        }
        let d = StepDerivative::new(step, params, law, self.base.columns)?;
        let (l, s) = log_det(d.state_jacobian(theta));
        Some((
            d.apply(&self.base, theta),
            (self.log_det + l, self.sign * s),
        ))
    }

    /// Move the track past `step` (to its end); `None` when the step's Newton matrix is
    /// singular.
    pub fn pass<L: SmoothLaw>(&mut self, step: &Step, params: &Params, law: &L) -> Option<()> {
        let (base, (log_det, sign)) = self.at(step, params, law, 1.0)?;
        self.base = base;
        self.log_det = log_det;
        self.sign = sign;
        let state = base.state();
        let size = state.iter().flatten().fold(0.0f64, |m, x| m.max(x.abs()));
        if !(SCALE_BELOW..=SCALE_ABOVE).contains(&size) && size > 0.0 && size.is_finite() {
            self.base.scale(1.0 / size);
            self.log_scale += size.ln();
        }
        Some(())
    }

    /// Divide the sensitivity by `factor` and fold the factor e^s out of its entries in with
    /// it: the sensitivity becomes S/(`factor`·e^s) relative to the true one, and
    /// ln(`factor`) + s is returned (a renormalisation of a tangent: the growth since the
    /// last). ln|det| is kept (it is the flow's).
    pub fn renormalize(&mut self, factor: f64) -> f64 {
        self.base.scale(1.0 / factor);
        let growth = factor.ln() + self.log_scale;
        self.log_scale = 0.0;
        growth
    }
}
