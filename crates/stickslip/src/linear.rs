//! Closed-form solution of one linear segment,
//!
//! ```text
//! y'' + 2ζ y' + y = β cos(w t + θ) − c,      y(0) = y0, y'(0) = v0,
//! ```
//!
//! in local time t. A sliding segment has c = sgn(y') (the kinetic friction force); the
//! solution is exact in every damping regime (under-, critically and overdamped, and ζ = 0
//! including the secular case w = 1).
//!
//! The homogeneous part is written in one basis for all regimes,
//! `EC(t) = e^{−ζt} C(t)`, `ES(t) = e^{−ζt} S(t)` with C = cos(ω_d t), S = sin(ω_d t)/ω_d
//! (ζ < 1), C = 1, S = t (ζ = 1) and C = cosh(κt), S = sinh(κt)/κ (ζ > 1); differentiation
//! maps the coefficients (p, q) of `p·EC + q·ES` to `(q − ζp, −(1−ζ²)p − ζq)`.

use crate::trig::sin_cos;

/// Damping regime of y'' + 2ζy' + y = 0, with what the basis needs.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Damping {
    zeta: f64,
    /// ω_d for ζ < 1, κ for ζ > 1, 0 at ζ = 1.
    omega: f64,
    /// Decay rate ρ of the slowest mode: ζ (ζ ≤ 1) or 1/(ζ + κ) (ζ > 1).
    decay: f64,
    /// Bound on |S(t)| independent of t: 1/ω_d, 1/(2κ) or infinity.
    s_cap: f64,
    /// 1/ω_d (underdamped only).
    inv_omega: f64,
    /// (1 − ζ)(1 + ζ).
    one_minus_zeta2: f64,
    /// Decay rate ζ + κ of the fast mode (overdamped only, else 0).
    fast: f64,
}

impl Damping {
    pub(crate) fn new(zeta: f64) -> Self {
        if zeta < 1.0 {
            let omega = ((1.0 - zeta) * (1.0 + zeta)).sqrt();
            Self {
                zeta,
                omega,
                decay: zeta,
                s_cap: 1.0 / omega,
                inv_omega: 1.0 / omega,
                one_minus_zeta2: (1.0 - zeta) * (1.0 + zeta),
                fast: 0.0,
            }
        } else if zeta == 1.0 {
            Self {
                zeta,
                omega: 0.0,
                decay: 1.0,
                s_cap: f64::INFINITY,
                inv_omega: f64::NAN,
                one_minus_zeta2: (1.0 - zeta) * (1.0 + zeta),
                fast: 0.0,
            }
        } else {
            let kappa = ((zeta - 1.0) * (zeta + 1.0)).sqrt();
            Self {
                zeta,
                omega: kappa,
                decay: 1.0 / (zeta + kappa),
                s_cap: 0.5 / kappa,
                inv_omega: f64::NAN,
                one_minus_zeta2: (1.0 - zeta) * (1.0 + zeta),
                fast: zeta + kappa,
            }
        }
    }

    /// `(EC(t), ES(t), e^{−ρt}, e^{−ζt} sin ω_d t)` (the last is 0 unless underdamped).
    #[inline(always)]
    fn basis(&self, t: f64) -> (f64, f64, f64, f64) {
        let z = self.zeta;
        if z < 1.0 {
            // Undamped, e^{−0·t} is 1 exactly for every finite t: no call to `exp`.
            let e = if z == 0.0 && t.is_finite() {
                1.0
            } else {
                (-z * t).exp()
            };
            let (s, c) = sin_cos(self.omega * t);
            (e * c, e * s / self.omega, e, e * s)
        } else {
            self.basis_damped(t)
        }
    }

    /// [`Damping::basis`] for ζ ≥ 1.
    #[inline(never)]
    fn basis_damped(&self, t: f64) -> (f64, f64, f64, f64) {
        let z = self.zeta;
        if z == 1.0 {
            let e = (-t).exp();
            (e, e * t, e, 0.0)
        } else {
            let k = self.omega;
            let slow = (-self.decay * t).exp();
            if k * t <= 1.0 {
                let e = (-z * t).exp();
                (e * (k * t).cosh(), e * (k * t).sinh() / k, slow, 0.0)
            } else {
                let fast = ((-z - k) * t).exp();
                (0.5 * (slow + fast), 0.5 * (slow - fast) / k, slow, 0.0)
            }
        }
    }

    /// Coefficients of the derivative of `p·EC + q·ES`.
    #[inline]
    fn derive(&self, (p, q): (f64, f64)) -> (f64, f64) {
        let z = self.zeta;
        (q - z * p, -self.one_minus_zeta2 * p - z * q)
    }
}

/// From this ζ on, overdamped segments are evaluated mode by mode (see
/// `LinearSegment::modes`); below it the basis EC, ES, whose coefficients then grow at most
/// 16-fold, is accurate, and also near ζ = 1, where the two modes merge.
const MODE_FORM_ZETA: f64 = 2.0;

/// Number of derivatives of y kept per segment: y, y', y'', y''', y''''.
const ORDERS: usize = 5;

/// Position, velocity and the next three derivatives at one instant, with the size of the
/// rounding noise in the velocity.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Derivatives {
    /// y, y', y'', y''', y''''.
    pub d: [f64; ORDERS],
    /// e^{−ρt}, for the derivative bounds.
    pub envelope: f64,
    /// Estimate of the absolute rounding error of y'.
    pub velocity_noise: f64,
    /// e^{−ζt} cos ω_d t, e^{−ζt} sin ω_d t, cos(wt + θ), sin(wt + θ), for the phasor bounds.
    trig: [f64; 4],
}

/// The drive's share of every segment of a run: its particular solution and the bounds
/// that follow from it, computed once.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Forcing {
    damping: Damping,
    w: f64,
    beta: f64,
    /// Particular solution of the drive, P cos(wt+θ) + Q sin(wt+θ).
    drive_p: f64,
    drive_q: f64,
    /// β/2 in the secular case (ζ = 0, w = 1), where the particular solution is
    /// (β/2)·t·sin(t + θ); zero otherwise.
    secular: f64,
    /// √(P² + Q²), amplitude of the drive's particular solution.
    drive_amplitude: f64,
    /// Coefficients (P_k, Q_k) of the k-th derivative of the particular solution,
    /// P_k cos(wt+θ) + Q_k sin(wt+θ): (P, Q) rotated k times by (P, Q) → (wQ, −wP).
    drive_orders: [(f64, f64); ORDERS],
    /// Drive amplitude times w³ and w⁴.
    drive_bound: [f64; 2],
    /// Complex amplitudes P_k − i Q_k of the drive in orders 3 and 4.
    drive_phasors: [(f64, f64); 2],
}

impl Forcing {
    /// The drive β cos(wt + θ) of y'' + 2ζy' + y = β cos(wt + θ) − c.
    pub(crate) fn new(damping: Damping, w: f64, beta: f64) -> Self {
        let zeta = damping.zeta;
        let detune = (1.0 - w) * (1.0 + w);
        let (drive_p, drive_q, secular) = if zeta == 0.0 && detune == 0.0 {
            (0.0, 0.0, 0.5 * beta)
        } else {
            let two_zw = 2.0 * zeta * w;
            let den = detune * detune + two_zw * two_zw;
            (beta * detune / den, beta * two_zw / den, 0.0)
        };
        let drive_amplitude = drive_p.hypot(drive_q);
        let mut forcing = Self {
            damping,
            w,
            beta,
            drive_p,
            drive_q,
            secular,
            drive_amplitude,
            drive_orders: [(0.0, 0.0); ORDERS],
            drive_bound: [0.0; 2],
            drive_phasors: [(0.0, 0.0); 2],
        };
        // Drive coefficients of order k: (P, Q) rotated k times by (P, Q) → (wQ, −wP).
        let (mut dp, mut dq) = (drive_p, drive_q);
        for k in 0..ORDERS {
            forcing.drive_orders[k] = (dp, dq);
            if k >= 3 {
                forcing.drive_bound[k - 3] = drive_amplitude * w.powi(k as i32);
                forcing.drive_phasors[k - 3] = (dp, -dq);
            }
            (dp, dq) = (w * dq, -w * dp);
        }
        forcing
    }
}

/// One linear segment in closed form.
#[derive(Debug, Clone, Copy)]
pub(crate) struct LinearSegment {
    forcing: Forcing,
    /// Drive phase at local time 0.
    theta: f64,
    /// The constant particular solution −c.
    offset: f64,
    /// Homogeneous coefficients (p, q) of y and its derivatives.
    hom: [(f64, f64); ORDERS],
    /// Amplitude √(p² + (q/ω_d)²) of the underdamped homogeneous mode (the same for every
    /// derivative), infinite when not underdamped.
    mode_amplitude: f64,
    /// Complex amplitudes of the homogeneous mode (p_k − i q_k/ω_d) in orders 3 and 4
    /// (underdamped segments only).
    hom_phasors: [(f64, f64); 2],
    /// Segments with ζ ≥ [`MODE_FORM_ZETA`] only: the homogeneous part as its two decaying modes,
    /// A e^{−ρ_s t} + B e^{−ρ_f t} (ρ_s = 1/(ζ + κ), ρ_f = ζ + κ), and of each derivative:
    /// (A(−ρ_s)ᵏ, B(−ρ_f)ᵏ). In the basis EC, ES the coefficients of order k grow like ζᵏ
    /// while the slow mode's derivatives shrink like ζ⁻ᵏ, so there the rounding would swamp
    /// them; mode by mode every term is exact to rounding.
    modes: [(f64, f64); ORDERS],
    /// y, y', …, y'''' at local time 0, from the initial state and the equation itself.
    start: Derivatives,
}

impl LinearSegment {
    /// Segment of y'' + 2ζy' + y = β cos(wt + θ) − c from (y0, v0).
    pub(crate) fn new(
        damping: Damping,
        w: f64,
        beta: f64,
        theta: f64,
        c: f64,
        y0: f64,
        v0: f64,
    ) -> Self {
        let forcing = Forcing::new(damping, w, beta);
        Self::with_forcing(&forcing, theta, sin_cos(theta), c, y0, v0)
    }

    /// Segment of y'' + 2ζy' + y = β cos(wt + θ) − c from (y0, v0), for a drive computed
    /// once, with `(sin θ, cos θ)` given.
    #[inline]
    pub(crate) fn with_forcing(
        forcing: &Forcing,
        theta: f64,
        trig: (f64, f64),
        c: f64,
        y0: f64,
        v0: f64,
    ) -> Self {
        let mut segment = Self {
            forcing: *forcing,
            theta,
            offset: 0.0,
            hom: [(0.0, 0.0); ORDERS],
            mode_amplitude: f64::INFINITY,
            hom_phasors: [(0.0, 0.0); 2],
            modes: [(0.0, 0.0); ORDERS],
            start: Derivatives {
                d: [0.0; ORDERS],
                envelope: 1.0,
                velocity_noise: 0.0,
                trig: [1.0, 0.0, 1.0, 0.0],
            },
        };
        segment.restart(theta, trig, c, y0, v0);
        segment
    }

    /// Make this the segment of the same drive with phase θ at its start, from (y0, v0), with
    /// friction force c and `(sin θ, cos θ)` given: in place, so that the drive's share is not
    /// copied again.
    #[inline]
    pub(crate) fn restart(
        &mut self,
        theta: f64,
        (sin0, cos0): (f64, f64),
        c: f64,
        y0: f64,
        v0: f64,
    ) {
        let f = &self.forcing;
        let (zeta, w, beta) = (f.damping.zeta, f.w, f.beta);
        // Derivatives at 0 straight from the equation y'' = β cos(wt + θ) − c − y − 2ζy' and
        // its derivatives: exact to rounding, with no cancellation between the homogeneous
        // and particular parts.
        let mut d = [y0, v0, 0.0, 0.0, 0.0];
        d[2] = beta * cos0 - c - d[0] - 2.0 * zeta * d[1];
        d[3] = -beta * w * sin0 - d[1] - 2.0 * zeta * d[2];
        d[4] = -beta * w * w * cos0 - d[2] - 2.0 * zeta * d[3];
        let yp0 = -c + f.drive_p * cos0 + f.drive_q * sin0;
        let vp0 = w * (f.drive_q * cos0 - f.drive_p * sin0) + f.secular * sin0;
        let u0 = y0 - yp0;
        let u1 = v0 - vp0;
        self.hom[0] = (u0, u1 + zeta * u0);
        // The velocity's coefficients straight from (u0, u1): through `derive`, the first
        // would be (u1 + ζu0) − ζu0, rounded to ε·ζ·|u0|, an error of the velocity that the
        // noise estimate of `eval` does not see (at ζ = 1, u0 = 1e9 it put a velocity zero
        // 2.5e-10 after a start with acceleration 124).
        self.hom[1] = (u1, -u0 - zeta * u1);
        for k in 2..ORDERS {
            self.hom[k] = f.damping.derive(self.hom[k - 1]);
        }
        if zeta < 1.0 {
            let (p, q) = self.hom[0];
            let inv = f.damping.inv_omega;
            self.mode_amplitude = (p * p + q * q * inv * inv).sqrt();
            self.hom_phasors = [
                (self.hom[3].0, -self.hom[3].1 * inv),
                (self.hom[4].0, -self.hom[4].1 * inv),
            ];
        } else if zeta >= MODE_FORM_ZETA {
            // u = A e^{−ρ_s t} + B e^{−ρ_f t} with u(0) = u0, u'(0) = u1.
            let (slow, fast) = (f.damping.decay, f.damping.fast);
            let gap = fast - slow;
            let (mut a, mut b) = ((fast * u0 + u1) / gap, -(slow * u0 + u1) / gap);
            for k in 0..ORDERS {
                self.modes[k] = (a, b);
                (a, b) = (-slow * a, -fast * b);
            }
        }
        self.theta = theta;
        self.offset = -c;
        self.start = Derivatives {
            d,
            envelope: 1.0,
            velocity_noise: 0.0,
            trig: [1.0, 0.0, cos0, sin0],
        };
    }

    /// y, y', …, y'''' at local time t.
    #[inline]
    pub(crate) fn eval(&self, t: f64) -> Derivatives {
        if self.forcing.damping.zeta >= MODE_FORM_ZETA {
            return self.eval_overdamped(t);
        }
        let (ec, es, envelope, e_sin) = self.forcing.damping.basis(t);
        let (s, c) = sin_cos(self.forcing.w * t + self.theta);
        // Drive: P_k c + Q_k s.
        let mut d = [0.0; ORDERS];
        let mut hom_v = 0.0;
        let mut drive_v = 0.0;
        for (k, dk) in d.iter_mut().enumerate() {
            let (hp, hq) = self.hom[k];
            let (p, q) = self.forcing.drive_orders[k];
            let h = hp * ec + hq * es;
            let f = p * c + q * s;
            if k == 1 {
                hom_v = (hp * ec).abs() + (hq * es).abs();
                drive_v = f.abs() + (p * c).abs() + (q * s).abs();
            }
            *dk = h + f;
        }
        d[0] += self.offset;
        if self.forcing.secular != 0.0 {
            // d^k/dt^k [t sin x] = t sin(x + kπ/2) + k sin(x + (k−1)π/2), x = t + θ.
            let h = self.forcing.secular;
            let rot = [s, c, -s, -c];
            for (k, dk) in d.iter_mut().enumerate() {
                *dk += h * (t * rot[k % 4] + k as f64 * rot[(k + 3) % 4]);
            }
            drive_v += h * (t.abs() + 1.0);
        }
        Derivatives {
            d,
            envelope,
            velocity_noise: 8.0 * f64::EPSILON * (hom_v + drive_v + d[1].abs()),
            trig: [ec, e_sin, c, s],
        }
    }

    /// y, y', y'' at local time t: the first three of [`LinearSegment::eval`], the same bits,
    /// for Newton's method on y', which needs no more.
    #[inline]
    pub(crate) fn eval_newton(&self, t: f64) -> [f64; 3] {
        if self.forcing.damping.zeta >= MODE_FORM_ZETA {
            let d = self.eval_overdamped(t).d;
            return [d[0], d[1], d[2]];
        }
        let (ec, es, _, _) = self.forcing.damping.basis(t);
        let (s, c) = sin_cos(self.forcing.w * t + self.theta);
        let mut d = [0.0; 3];
        for (k, dk) in d.iter_mut().enumerate() {
            let (hp, hq) = self.hom[k];
            let (p, q) = self.forcing.drive_orders[k];
            let h = hp * ec + hq * es;
            let f = p * c + q * s;
            *dk = h + f;
        }
        d[0] += self.offset;
        if self.forcing.secular != 0.0 {
            let h = self.forcing.secular;
            let rot = [s, c, -s, -c];
            for (k, dk) in d.iter_mut().enumerate() {
                *dk += h * (t * rot[k % 4] + k as f64 * rot[(k + 3) % 4]);
            }
        }
        d
    }

    /// [`LinearSegment::eval`] of a segment with ζ ≥ [`MODE_FORM_ZETA`], mode by mode.
    fn eval_overdamped(&self, t: f64) -> Derivatives {
        let damping = &self.forcing.damping;
        let slow = (-damping.decay * t).exp();
        let fast = (-damping.fast * t).exp();
        let (s, c) = sin_cos(self.forcing.w * t + self.theta);
        let mut d = [0.0; ORDERS];
        let (mut hom_v, mut drive_v) = (0.0, 0.0);
        for (k, dk) in d.iter_mut().enumerate() {
            let (a, b) = self.modes[k];
            let (p, q) = self.forcing.drive_orders[k];
            let f = p * c + q * s;
            if k == 1 {
                hom_v = (a * slow).abs() + (b * fast).abs();
                drive_v = f.abs() + (p * c).abs() + (q * s).abs();
            }
            *dk = a * slow + b * fast + f;
        }
        d[0] += self.offset;
        Derivatives {
            d,
            envelope: slow,
            velocity_noise: 8.0 * f64::EPSILON * (hom_v + drive_v + d[1].abs()),
            trig: [0.0, 0.0, c, s],
        }
    }

    /// y, y', …, y'''' at local time 0 (the segment's initial state, exact).
    #[inline]
    pub(crate) fn start(&self) -> &Derivatives {
        &self.start
    }

    /// Whether the segment is an underdamped, non-secular one: a decaying mode at ω_d and
    /// the drive at w, each a rotating phasor, whose bounds [`LinearSegment::global_bounds`]
    /// gives.
    #[inline]
    pub(crate) fn is_two_phasor(&self) -> bool {
        self.forcing.damping.zeta < 1.0 && self.forcing.secular == 0.0
    }

    /// Bounds of |y''''| and |y⁽⁵⁾| over the whole segment (t ≥ 0) of a two-phasor segment:
    /// the mode's amplitude (|ω_d − iζ| = 1, so differentiation keeps it) plus the drive's
    /// times w⁴ and w⁵. Cheap, and loose where the two nearly cancel (near resonance), where
    /// [`LinearSegment::derivative_bounds`] is tighter.
    #[inline]
    pub(crate) fn global_bounds(&self) -> (f64, f64) {
        let w = self.forcing.w;
        let w4 = self.forcing.drive_amplitude * w * w * w * w;
        (self.mode_amplitude + w4, self.mode_amplitude + w4 * w)
    }

    /// Bound of |y'''| over the whole segment of a two-phasor segment (as
    /// [`LinearSegment::global_bounds`]): the scale of the rounding of its terms in tests.
    #[cfg(test)]
    pub(crate) fn third_derivative_bound(&self) -> f64 {
        let w = self.forcing.w;
        self.mode_amplitude + self.forcing.drive_amplitude * w * w * w
    }

    /// (sin, cos) of the drive phase w(t + dt) + θ, from the derivatives `at` local time t:
    /// the phase there turned on by w·dt (a short series, exact to rounding, for |w·dt| ≤
    /// 1e-3; the full function beyond).
    #[inline]
    pub(crate) fn drive_trig_after(&self, at: &Derivatives, t: f64, dt: f64) -> (f64, f64) {
        let x = self.forcing.w * dt;
        if !(x.abs() <= 1e-3) {
            return sin_cos(self.forcing.w * (t + dt) + self.theta);
        }
        let [_, _, c, s] = at.trig;
        let x2 = x * x;
        let cos_x = 1.0 - 0.5 * x2 * (1.0 - x2 / 12.0);
        let sin_x = x * (1.0 - x2 / 6.0 * (1.0 - x2 / 20.0));
        (s * cos_x + c * sin_x, c * cos_x - s * sin_x)
    }

    /// (y, y') at local time t.
    #[inline]
    pub(crate) fn state(&self, t: f64) -> (f64, f64) {
        if self.forcing.damping.zeta >= MODE_FORM_ZETA {
            let d = self.eval_overdamped(t).d;
            return (d[0], d[1]);
        }
        let (ec, es, _, _) = self.forcing.damping.basis(t);
        let (s, c) = sin_cos(self.forcing.w * t + self.theta);
        let (p, q) = (self.forcing.drive_p, self.forcing.drive_q);
        let (h0, h1) = (self.hom[0], self.hom[1]);
        let mut y = self.offset + h0.0 * ec + h0.1 * es + p * c + q * s;
        let mut v = h1.0 * ec + h1.1 * es + self.forcing.w * (q * c - p * s);
        if self.forcing.secular != 0.0 {
            y += self.forcing.secular * t * s;
            v += self.forcing.secular * (s + t * c);
        }
        (y, v)
    }

    /// Upper bounds of |y⁽³⁾(t)| and |y⁽⁴⁾(t)| over local times t in [a, a + span], from the
    /// derivatives `at` a.
    ///
    /// Generic bound: each term's amplitude times its frequency to the power of the order.
    /// Underdamped segments also have the phasor bound: y⁽ᵏ⁾ = Re(H e^{(−ζ+iω_d)τ} + D e^{iwτ})
    /// with τ = t − a, so |y⁽ᵏ⁾(t)| ≤ |H + D| + (ζ|H| + |w − ω_d| |D|)·τ, tight near resonance
    /// where the two terms nearly cancel.
    #[inline]
    pub(crate) fn derivative_bounds(&self, a: f64, span: f64, at: &Derivatives) -> (f64, f64) {
        let reach = (a + span).min(self.forcing.damping.s_cap);
        let [ec, e_sin, c, s] = at.trig;
        let underdamped = self.forcing.damping.zeta < 1.0 && self.forcing.secular == 0.0;
        let detune = (self.forcing.w - self.forcing.damping.omega).abs();
        let damping = &self.forcing.damping;
        // Overdamped: each mode decays from a on at its own rate (a relative slack covers
        // the rounding of A, B and the rates).
        let modes = if damping.zeta >= MODE_FORM_ZETA {
            let fast_envelope = (-damping.fast * a).exp();
            [3, 4].map(|k| {
                let (a_k, b_k) = self.modes[k];
                (a_k.abs() * at.envelope + b_k.abs() * fast_envelope) * (1.0 + 1e-12)
            })
        } else {
            [f64::INFINITY; 2]
        };
        let mut out = [0.0; 2];
        for (i, o) in out.iter_mut().enumerate() {
            let (p, q) = self.hom[i + 3];
            let hom =
                ((p.abs() + q.abs() * reach).min(self.mode_amplitude) * at.envelope).min(modes[i]);
            *o = hom + self.forcing.drive_bound[i];
            if self.forcing.secular != 0.0 {
                *o += self.forcing.secular * (a + span + (i + 3) as f64);
            }
            if underdamped {
                let (hr, hi) = self.hom_phasors[i];
                let (dr, di) = self.forcing.drive_phasors[i];
                let (h_re, h_im) = (hr * ec - hi * e_sin, hr * e_sin + hi * ec);
                let (d_re, d_im) = (dr * c - di * s, dr * s + di * c);
                // Plain square roots: these moduli are far from overflow, and hypot is slow.
                let (s_re, s_im) = (h_re + d_re, h_im + d_im);
                let sum = (s_re * s_re + s_im * s_im).sqrt();
                let drift = self.forcing.damping.zeta * (h_re * h_re + h_im * h_im).sqrt()
                    + detune * (d_re * d_re + d_im * d_im).sqrt();
                *o = o.min(sum + drift * span);
            }
        }
        (out[0], out[1])
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Residual of the ODE and the initial conditions, checked in every damping regime.
    #[test]
    fn closed_form_satisfies_the_equation() {
        for &zeta in &[
            0.0, 0.05, 0.7, 0.999_999, 1.0, 1.000_001, 1.5, 2.0, 12.0, 1e4,
        ] {
            for &w in &[0.3, 1.0, 2.7] {
                let (beta, theta, c, y0, v0) = (1.7, 0.4, -1.0, 0.3, -0.8);
                let seg = LinearSegment::new(Damping::new(zeta), w, beta, theta, c, y0, v0);
                let start = seg.eval(0.0);
                assert!((start.d[0] - y0).abs() < 1e-12, "zeta {zeta} w {w}");
                assert!((start.d[1] - v0).abs() < 1e-12, "zeta {zeta} w {w}");
                for &t in &[0.0, 0.1, 1.3, 7.0, 40.0] {
                    let e = seg.eval(t);
                    let d = e.d;
                    let residual =
                        d[2] + 2.0 * zeta * d[1] + d[0] - beta * (w * t + theta).cos() + c;
                    let scale = 1.0 + d.iter().map(|x| x.abs()).sum::<f64>();
                    assert!(
                        residual.abs() < 1e-12 * scale,
                        "zeta {zeta} w {w} t {t}: {residual}"
                    );
                    // Higher derivatives are consistent with differentiating the equation.
                    let r3 = d[3] + 2.0 * zeta * d[2] + d[1] + beta * w * (w * t + theta).sin();
                    assert!(r3.abs() < 1e-11 * scale, "zeta {zeta} w {w} t {t}: {r3}");
                    let (y, v) = seg.state(t);
                    assert!((y - d[0]).abs() < 1e-13 * scale && (v - d[1]).abs() < 1e-13 * scale);
                }
            }
        }
    }

    /// The shortened evaluation for Newton's method gives the bits of the full one, in every
    /// damping regime and in the secular case (ζ = 0, w = 1).
    #[test]
    fn newton_evaluation_is_the_full_evaluation_to_the_bit() {
        for &zeta in &[0.0, 0.0468, 0.7, 1.0, 1.5, 2.0, 12.0] {
            for &w in &[0.3, 1.0, 2.7] {
                let seg = LinearSegment::new(Damping::new(zeta), w, 1.7, 0.4, -1.0, 0.3, -0.8);
                for i in 0..400 {
                    let t = f64::from(i) * 0.0371;
                    let full = seg.eval(t).d;
                    let newton = seg.eval_newton(t);
                    for k in 0..3 {
                        assert_eq!(
                            full[k].to_bits(),
                            newton[k].to_bits(),
                            "zeta {zeta} w {w} t {t} order {k}"
                        );
                    }
                }
            }
        }
    }

    #[test]
    fn derivative_bounds_hold_on_a_fine_grid() {
        for &zeta in &[0.0, 0.2, 1.0, 3.0, 40.0, 1e3] {
            for &w in &[0.5, 1.0, 1.9] {
                let seg = LinearSegment::new(Damping::new(zeta), w, 2.0, 1.1, 1.0, -0.5, 0.2);
                for &a in &[0.0, 0.5, 3.0] {
                    let (b3, b4) = seg.derivative_bounds(a, 1.0, &seg.eval(a));
                    for i in 0..=200 {
                        let t = a + i as f64 / 200.0;
                        let d = seg.eval(t).d;
                        assert!(d[3].abs() <= b3 * (1.0 + 1e-12), "zeta {zeta} w {w} t {t}");
                        assert!(d[4].abs() <= b4 * (1.0 + 1e-12), "zeta {zeta} w {w} t {t}");
                    }
                }
            }
        }
    }
}
