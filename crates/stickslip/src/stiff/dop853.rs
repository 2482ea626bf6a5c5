//! An explicit integrator of order 8 for smooth laws that are not stiff: the Runge–Kutta
//! pair of Dormand and Prince, DOP853 (Hairer, Nørsett and Wanner, *Solving Ordinary
//! Differential Equations I*, §II.10: twelve stages, an 8th-order solution, error
//! estimates of orders 5 and 3 combined as in their code, and a dense output of order 7
//! from three more stages), on y'' + 2ζ y' + y + D(y') = β cos(w τ + φ) for any smooth law D
//! ([`SmoothLaw`]; only its value is used).
//!
//! For the slips of a friction law on a moving belt ([`crate::friction_solver`]): |D'| is
//! moderate there, so the explicit method is stable at the steps its accuracy asks for, and at
//! a tolerance of 10⁻¹² its steps are several times longer than those of the stiff
//! integrator ([`super::Radau5`], order 5), without a Newton iteration. It has no tangent
//! dynamics: the stability tools differentiate the stiff integrator's steps.
//!
//! The step-size control is the elementary one (a factor 0.9·err^(−1/8), within [0.2, 10],
//! no growth right after a rejection); the error norm is DOP853's, the RMS over the two
//! components of the 5th-order estimate scaled by its ratio to the 3rd-order one.

use super::law::SmoothLaw;
use super::radau::{Counters, Settings, Vector, N};
use crate::error::{Error, Result};
use crate::params::Params;

#[allow(clippy::excessive_precision)]
mod coefficients {
    /// Nodes c_i (stages 1–12, the end, and the three stages of the dense output).
    pub(super) const C: [f64; 16] = [
        0.0,
        0.05260015195876773,
        0.0789002279381516,
        0.1183503419072274,
        0.2816496580927726,
        0.3333333333333333,
        0.25,
        0.3076923076923077,
        0.6512820512820513,
        0.6,
        0.8571428571428571,
        1.0,
        1.0,
        0.1,
        0.2,
        0.7777777777777778,
    ];
    /// Runge–Kutta matrix a_ij (row 12: the weights b_j of the 8th-order solution).
#[rustfmt::skip]
pub(super) const A: [[f64; 16]; 16] = [
    [0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0],
    [5.26001519587677318785587544488e-2, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0],
    [1.97250569845378994544595329183e-2, 5.91751709536136983633785987549e-2, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0],
    [2.95875854768068491816892993775e-2, 0.0, 8.87627564304205475450678981324e-2, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0],
    [2.41365134159266685502369798665e-1, 0.0, -8.84549479328286085344864962717e-1, 9.24834003261792003115737966543e-1, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0],
    [3.7037037037037037037037037037e-2, 0.0, 0.0, 1.70828608729473871279604482173e-1, 1.25467687566822425016691814123e-1, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0],
    [3.7109375e-2, 0.0, 0.0, 1.70252211019544039314978060272e-1, 6.02165389804559606850219397283e-2, -1.7578125e-2, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0],
    [3.70920001185047927108779319836e-2, 0.0, 0.0, 1.70383925712239993810214054705e-1, 1.07262030446373284651809199168e-1, -1.53194377486244017527936158236e-2, 8.27378916381402288758473766002e-3, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0],
    [6.24110958716075717114429577812e-1, 0.0, 0.0, -3.36089262944694129406857109825, -8.68219346841726006818189891453e-1, 2.75920996994467083049415600797e1, 2.01540675504778934086186788979e1, -4.34898841810699588477366255144e1, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0],
    [4.77662536438264365890433908527e-1, 0.0, 0.0, -2.48811461997166764192642586468, -5.90290826836842996371446475743e-1, 2.12300514481811942347288949897e1, 1.52792336328824235832596922938e1, -3.32882109689848629194453265587e1, -2.03312017085086261358222928593e-2, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0],
    [-9.3714243008598732571704021658e-1, 0.0, 0.0, 5.18637242884406370830023853209, 1.09143734899672957818500254654, -8.14978701074692612513997267357, -1.85200656599969598641566180701e1, 2.27394870993505042818970056734e1, 2.49360555267965238987089396762, -3.0467644718982195003823669022, 0.0, 0.0, 0.0, 0.0, 0.0, 0.0],
    [2.27331014751653820792359768449, 0.0, 0.0, -1.05344954667372501984066689879e1, -2.00087205822486249909675718444, -1.79589318631187989172765950534e1, 2.79488845294199600508499808837e1, -2.85899827713502369474065508674, -8.87285693353062954433549289258, 1.23605671757943030647266201528e1, 6.43392746015763530355970484046e-1, 0.0, 0.0, 0.0, 0.0, 0.0],
    [5.42937341165687622380535766363e-2, 0.0, 0.0, 0.0, 0.0, 4.45031289275240888144113950566, 1.89151789931450038304281599044, -5.8012039600105847814672114227, 3.1116436695781989440891606237e-1, -1.52160949662516078556178806805e-1, 2.01365400804030348374776537501e-1, 4.47106157277725905176885569043e-2, 0.0, 0.0, 0.0, 0.0],
    [5.61675022830479523392909219681e-2, 0.0, 0.0, 0.0, 0.0, 0.0, 2.53500210216624811088794765333e-1, -2.46239037470802489917441475441e-1, -1.24191423263816360469010140626e-1, 1.5329179827876569731206322685e-1, 8.20105229563468988491666602057e-3, 7.56789766054569976138603589584e-3, -8.298e-3, 0.0, 0.0, 0.0],
    [3.18346481635021405060768473261e-2, 0.0, 0.0, 0.0, 0.0, 2.83009096723667755288322961402e-2, 5.35419883074385676223797384372e-2, -5.49237485713909884646569340306e-2, 0.0, 0.0, -1.08347328697249322858509316994e-4, 3.82571090835658412954920192323e-4, -3.40465008687404560802977114492e-4, 1.41312443674632500278074618366e-1, 0.0, 0.0],
    [-4.28896301583791923408573538692e-1, 0.0, 0.0, 0.0, 0.0, -4.69762141536116384314449447206, 7.68342119606259904184240953878, 4.06898981839711007970213554331, 3.56727187455281109270669543021e-1, 0.0, 0.0, 0.0, -1.39902416515901462129418009734e-3, 2.9475147891527723389556272149, -9.15095847217987001081870187138, 0.0],
];
    /// Weights of the 5th-order error estimate.
    pub(super) const E5: [f64; 12] = [
        0.1312004499419488073250102996e-1,
        0.0,
        0.0,
        0.0,
        0.0,
        -0.1225156446376204440720569753e1,
        -0.4957589496572501915214079952,
        0.1664377182454986536961530415e1,
        -0.3503288487499736816886487290,
        0.3341791187130174790297318841,
        0.8192320648511571246570742613e-1,
        -0.2235530786388629525884427845e-1,
    ];
    /// The 3rd-order weights b̂ (E3 = b − b̂): nonzero at stages 1, 9 and 12.
    pub(super) const BHAT3: [(usize, f64); 3] = [
        (0, 0.244094488188976377952755905512),
        (8, 0.733846688281611857341361741547),
        (11, 0.220588235294117647058823529412e-1),
    ];
    /// Coefficients of the dense output's terms of degree 4 to 7.
#[rustfmt::skip]
pub(super) const D: [[f64; 16]; 4] = [
    [-0.84289382761090128651353491142e1, 0.0, 0.0, 0.0, 0.0, 0.56671495351937776962531783590, -0.30689499459498916912797304727e1, 0.23846676565120698287728149680e1, 0.21170345824450282767155149946e1, -0.87139158377797299206789907490, 0.22404374302607882758541771650e1, 0.63157877876946881815570249290, -0.88990336451333310820698117400e-1, 0.18148505520854727256656404962e2, -0.91946323924783554000451984436e1, -0.44360363875948939664310572000e1],
    [0.10427508642579134603413151009e2, 0.0, 0.0, 0.0, 0.0, 0.24228349177525818288430175319e3, 0.16520045171727028198505394887e3, -0.37454675472269020279518312152e3, -0.22113666853125306036270938578e2, 0.77334326684722638389603898808e1, -0.30674084731089398182061213626e2, -0.93321305264302278729567221706e1, 0.15697238121770843886131091075e2, -0.31139403219565177677282850411e2, -0.93529243588444783865713862664e1, 0.35816841486394083752465898540e2],
    [0.19985053242002433820987653617e2, 0.0, 0.0, 0.0, 0.0, -0.38703730874935176555105901742e3, -0.18917813819516756882830838328e3, 0.52780815920542364900561016686e3, -0.11573902539959630126141871134e2, 0.68812326946963000169666922661e1, -0.10006050966910838403183860980e1, 0.77771377980534432092869265740, -0.27782057523535084065932004339e1, -0.60196695231264120758267380846e2, 0.84320405506677161018159903784e2, 0.11992291136182789328035130030e2],
    [-0.25693933462703749003312586129e2, 0.0, 0.0, 0.0, 0.0, -0.15418974869023643374053993627e3, -0.23152937917604549567536039109e3, 0.35763911791061412378285349910e3, 0.93405324183624310003907691704e2, -0.37458323136451633156875139351e2, 0.10409964950896230045147246184e3, 0.29840293426660503123344363579e2, -0.43533456590011143754432175058e2, 0.96324553959188282948394950600e2, -0.39177261675615439165231486172e2, -0.14972683625798562581422125276e3],
];
}
use coefficients::{A, BHAT3, C, D, E5};

/// Safety factor, and the bounds of the step-size factor per step.
const SAFE: f64 = 0.9;
const MIN_FACTOR: f64 = 0.2;
const MAX_FACTOR: f64 = 10.0;

/// err^(−1/8) by three square roots (cheaper than `powf`).
fn inverse_eighth_root(err: f64) -> f64 {
    (1.0 / err).sqrt().sqrt().sqrt()
}

/// One accepted step with its dense output (a polynomial of degree 7 in θ).
#[derive(Debug, Clone, Copy)]
pub struct DopStep {
    /// Start time.
    pub t0: f64,
    /// Step size.
    pub h: f64,
    /// State at the start.
    pub x0: Vector,
    /// State at the end (exactly the value the integrator continues from).
    pub x1: Vector,
    /// Per component, the seven terms of the dense output in Hairer's nested form.
    terms: [[f64; 7]; N],
}

impl DopStep {
    /// End time.
    pub fn t1(&self) -> f64 {
        self.t0 + self.h
    }

    /// Component `k` at θ ∈ [0, 1] (θ = 1 gives the end state exactly).
    pub fn component(&self, k: usize, theta: f64) -> f64 {
        if theta == 1.0 {
            return self.x1[k];
        }
        let f = &self.terms[k];
        let u = 1.0 - theta;
        // x0 + θ(F0 + (1−θ)(F1 + θ(F2 + (1−θ)(F3 + θ(F4 + (1−θ)(F5 + θ F6)))))).
        let mut y = f[6] * theta;
        y = (y + f[5]) * u;
        y = (y + f[4]) * theta;
        y = (y + f[3]) * u;
        y = (y + f[2]) * theta;
        y = (y + f[1]) * u;
        y = (y + f[0]) * theta;
        self.x0[k] + y
    }

    /// A bound on |x_k(θ) − x_k(t0)| over θ ∈ [0, 1] for the dense output of component `k`
    /// as [`DopStep::component`] evaluates it: the sum of the magnitudes of its seven terms
    /// (each nested factor θ or 1 − θ lies in [0, 1]), raised by 10⁻¹² against the rounding
    /// of the fourteen operations (and of x1 − x0 at θ = 1). Costs seven additions, where a
    /// search of the step samples the polynomial many times.
    pub fn reach(&self, k: usize) -> f64 {
        let sum = self.terms[k].iter().fold(0.0, |s, t| s + t.abs());
        sum * (1.0 + 1e-12)
    }

    /// The state at θ ∈ [0, 1].
    pub fn eval_theta(&self, theta: f64) -> Vector {
        if theta == 1.0 {
            return self.x1;
        }
        [self.component(0, theta), self.component(1, theta)]
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

/// What [`Dop853::step_until`] did.
#[derive(Debug, Clone, Copy)]
pub enum Attempt {
    /// An accepted step.
    Accepted(DopStep),
    /// A rejected attempt of size `h` whose end state `end` is past the caller's surface.
    Crossed {
        /// The attempt's size.
        h: f64,
        /// Its end state.
        end: Vector,
    },
}

/// The integrator's state between steps, for the law `L`.
#[derive(Debug, Clone)]
pub struct Dop853<L: SmoothLaw> {
    params: Params,
    law: L,
    settings: Settings,
    t: f64,
    x: Vector,
    /// The right-hand side at (t, x).
    f: Vector,
    /// Step size for the next attempt.
    h: f64,
    /// Work done so far (`newton` stays 0).
    pub counters: Counters,
}

/// The stages of one attempt: k_1 … k_12 and k_13 = f at the end (filled by `finish`), and
/// the three of the dense output.
type Stages = [Vector; 16];

impl<L: SmoothLaw> Dop853<L> {
    /// Start at (t, x) on y'' + 2ζ y' + y + D(y') = β cos(w τ + φ) with ζ, w, β, φ from
    /// `params` and D the law `law` (taken as valid).
    pub fn new(params: Params, law: L, t: f64, x: Vector, settings: Settings) -> Self {
        let mut me = Self {
            params,
            law,
            settings,
            t,
            x,
            f: [0.0; N],
            h: settings.initial_step.min(settings.max_step),
            counters: Counters::default(),
        };
        me.f = me.rhs(t, &x);
        me
    }

    integrator_accessors!(Dop853);

    /// f(t, x) = (v, β cos(w t + φ) − y − 2ζ v − D(v)) (no cosine without a drive).
    fn rhs(&self, t: f64, x: &Vector) -> Vector {
        let p = &self.params;
        let drive = if p.beta == 0.0 { 0.0 } else { p.drive(t) };
        let (d, _) = self.law.value_and_slope(x[1]);
        [x[1], drive - x[0] - 2.0 * p.zeta * x[1] - d]
    }

    /// The twelve stages of a step of size `h` and its 8th-order end state.
    fn attempt(&mut self, h: f64) -> (Stages, Vector) {
        let mut k: Stages = [[0.0; N]; 16];
        k[0] = self.f;
        for s in 1..12 {
            let x = combine(&self.x, &k, &A[s], s, h);
            k[s] = self.rhs(self.t + C[s] * h, &x);
        }
        self.counters.rhs += 11;
        let x1 = combine(&self.x, &k, &A[12], 12, h);
        (k, x1)
    }

    /// DOP853's error norm of an attempt (≤ 1: accepted).
    fn error(&self, k: &Stages, x1: &Vector, h: f64) -> f64 {
        let s = &self.settings;
        let (mut e5, mut e3) = (0.0, 0.0);
        for c in 0..N {
            let scale = s.atol + s.rtol * self.x[c].abs().max(x1[c].abs());
            let mut a5 = 0.0;
            let mut a3 = 0.0;
            // (E5 and b vanish at stages 2 to 5.)
            for j in std::iter::once(0).chain(5..12) {
                a5 += E5[j] * k[j][c];
                a3 += A[12][j] * k[j][c];
            }
            for (j, b) in BHAT3 {
                a3 -= b * k[j][c];
            }
            e5 += (a5 / scale).powi(2);
            e3 += (a3 / scale).powi(2);
        }
        if e5 == 0.0 && e3 == 0.0 {
            return 0.0;
        }
        h.abs() * e5 / ((e5 + 0.01 * e3) * N as f64).sqrt()
    }

    /// The accepted attempt's step: f at its end, the dense output's three stages, and the
    /// integrator moved on to its end.
    fn finish(&mut self, mut k: Stages, x1: Vector, h: f64) -> DopStep {
        let t0 = self.t;
        let x0 = self.x;
        k[12] = self.rhs(t0 + h, &x1);
        for s in 13..16 {
            let x = combine(&x0, &k, &A[s], s, h);
            k[s] = self.rhs(t0 + C[s] * h, &x);
        }
        self.counters.rhs += 4;
        let mut terms = [[0.0; 7]; N];
        for c in 0..N {
            let delta = x1[c] - x0[c];
            let t = &mut terms[c];
            t[0] = delta;
            t[1] = h * k[0][c] - delta;
            t[2] = 2.0 * delta - h * (k[12][c] + k[0][c]);
            for (i, row) in D.iter().enumerate() {
                let mut sum = 0.0;
                // (D vanishes at stages 2 to 5.)
                for j in std::iter::once(0).chain(5..16) {
                    sum += row[j] * k[j][c];
                }
                t[3 + i] = h * sum;
            }
        }
        self.t = t0 + h;
        self.x = x1;
        self.f = k[12];
        self.counters.accepted += 1;
        DopStep {
            t0,
            h,
            x0,
            x1,
            terms,
        }
    }

    /// One accepted step under the error control (rejected attempts retried smaller).
    ///
    /// # Errors
    /// [`Error::StepSizeTooSmall`] when the step size underflows.
    pub fn step(&mut self) -> Result<DopStep> {
        match self.step_until(|_| false)? {
            Attempt::Accepted(step) => Ok(step),
            Attempt::Crossed { .. } => unreachable!("nothing is crossed"),
        }
    }

    /// As [`Dop853::step`], but a rejected attempt whose end state is `crossed` (past a
    /// switching surface of the caller's, where the law it integrates ends: an attempt
    /// across it is rejected for the kink, not for its size) is handed back as it is: the
    /// caller locates the surface by steps that end on it. The integrator stays where it
    /// was, its next step size shrunk as after any rejection.
    ///
    /// # Errors
    /// As [`Dop853::step`].
    pub fn step_until(&mut self, crossed: impl Fn(&Vector) -> bool) -> Result<Attempt> {
        let mut rejected = false;
        loop {
            let h = self.h.min(self.settings.max_step);
            if !(h > 16.0 * f64::EPSILON * self.t.abs().max(1.0)) {
                return Err(Error::StepSizeTooSmall {
                    tau: self.t,
                    step: h,
                });
            }
            let (k, x1) = self.attempt(h);
            let err = self.error(&k, &x1, h);
            if err <= 1.0 {
                let mut factor = if err == 0.0 {
                    MAX_FACTOR
                } else {
                    (SAFE * inverse_eighth_root(err)).min(MAX_FACTOR)
                };
                if rejected {
                    factor = factor.min(1.0);
                }
                let step = self.finish(k, x1, h);
                self.h = h * factor;
                return Ok(Attempt::Accepted(step));
            }
            self.counters.rejected += 1;
            rejected = true;
            self.h = h * (SAFE * inverse_eighth_root(err)).max(MIN_FACTOR);
            if crossed(&x1) {
                return Ok(Attempt::Crossed { h, end: x1 });
            }
        }
    }

    /// A step of exactly `h` from the current state when its error estimate accepts it
    /// (the integrator then moves to its end); `None` otherwise.
    pub fn checked_step(&mut self, h: f64) -> Option<DopStep> {
        let (k, x1) = self.attempt(h);
        (self.error(&k, &x1, h) <= 1.0).then(|| self.finish(k, x1, h))
    }

    /// A step of exactly `h` from the current state, without error control (the event
    /// location's iterates).
    pub fn fixed_step(&mut self, h: f64) -> DopStep {
        let (k, x1) = self.attempt(h);
        self.finish(k, x1, h)
    }

    /// The end state of a step of exactly `h` from the current state, the integrator left
    /// where it is.
    pub fn end_of(&mut self, h: f64) -> Vector {
        self.attempt(h).1
    }
}

/// x + h Σ_{j<s} a_j k_j over the nonzero a_j (`FIRST_STAGE`).
fn combine(x: &Vector, k: &Stages, a: &[f64; 16], s: usize, h: f64) -> Vector {
    let mut out = *x;
    let (mut y, mut v) = (0.0, 0.0);
    for j in std::iter::once(0).chain(FIRST_STAGE[s]..s) {
        y += a[j] * k[j][0];
        v += a[j] * k[j][1];
    }
    out[0] += h * y;
    out[1] += h * v;
    out
}

/// Per row s of [`A`], the first stage j ≥ 1 from which a_sj may be nonzero (a_s0 is
/// nonzero in every row; between them all are zero): the rows' sparsity, to skip the zeros.
const FIRST_STAGE: [usize; 16] = [1, 1, 1, 2, 2, 3, 3, 3, 3, 3, 3, 3, 5, 6, 5, 5];

#[cfg(test)]
mod tests {
    use super::*;

    /// The linear law D(v) = c·v: y'' + (2ζ + c) y' + y = 0 in closed form.
    #[derive(Debug, Clone, Copy)]
    struct Linear(f64);

    impl SmoothLaw for Linear {
        const PARAMETERS: &'static [&'static str] = &[];
        fn validate(&self) -> Result<Self> {
            Ok(*self)
        }
        fn value_and_slope(&self, v: f64) -> (f64, f64) {
            (self.0 * v, self.0)
        }
        fn parameter_derivatives(&self, _v: f64, _out: &mut [f64]) {}
    }

    #[test]
    fn a_damped_oscillation_to_its_tolerance_with_a_dense_output_of_the_same_order() {
        let (zeta, c) = (0.05, 0.03);
        let params = Params::new(zeta, 1.0, 0.0).expect("valid");
        let settings = Settings {
            rtol: 1e-12,
            atol: 1e-12,
            max_step: 0.25,
            initial_step: 1e-3,
        };
        let mut dop = Dop853::new(params, Linear(c), 0.0, [1.0, 0.0], settings);
        // y = e^{−d t}(cos ω t + d/ω sin ω t), d = ζ + c/2, ω = √(1 − d²).
        let d = zeta + 0.5 * c;
        let om = (1.0 - d * d).sqrt();
        let exact = |t: f64| {
            let (s, co) = (om * t).sin_cos();
            let e = (-d * t).exp();
            [
                e * (co + d / om * s),
                e * (-d * co - d * d / om * s - om * s + d * co),
            ]
        };
        let (mut worst, mut worst_dense) = (0.0f64, 0.0f64);
        while dop.time() < 30.0 {
            let step = dop.step().expect("steps");
            let x = exact(step.t1());
            worst = worst
                .max((step.x1[0] - x[0]).abs())
                .max((step.x1[1] - x[1]).abs());
            for i in 1..8 {
                let t = step.t0 + step.h * i as f64 / 8.0;
                let (y, e) = (step.eval(t), exact(t));
                worst_dense = worst_dense
                    .max((y[0] - e[0]).abs())
                    .max((y[1] - e[1]).abs());
            }
        }
        assert!(worst < 2e-11, "steps off by {worst:e}");
        assert!(worst_dense < 5e-11, "dense output off by {worst_dense:e}");
        // Steps of order 8 at 1e-12: far fewer than the stiff integrator's ~100 per τ.
        assert!(dop.counters.accepted < 30 * 20, "{:?}", dop.counters);
    }
}
