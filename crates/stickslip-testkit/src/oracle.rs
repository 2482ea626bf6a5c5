//! An independent integrator of the block on a moving belt, for the tests that check the
//! library's solvers of friction ([`stickslip::ExactSolver`] with Coulomb's law,
//! [`stickslip::friction_solver::FrictionSolver`] with the Stribeck and cubic laws) and that
//! make records the fit has to explain:
//!
//! ```text
//! slipping, s = y' − vb ≠ 0:   y'' + 2ζ y' + y + sgn(s) μ(|s|) = β cos(w τ + φ)
//! stuck,    y' = vb:           holds while |β cos(w τ + φ) − y − 2ζ vb| ≤ μs
//! ```
//!
//! Another method with another tolerance than the library's: the classical fourth-order
//! Runge–Kutta method at a fixed step h (1e-3 or 5e-4 in the tests: global error about
//! h⁴ per unit time) on the slips, with the laws written out here again ([`OracleLaw`]), the
//! stops as y = y_s + vb t checked on the same grid, and every event placed by bisection on
//! a partial Runge–Kutta step from the last grid point (a one-step method: a step of θh from
//! there is a solution of the same order).

use stickslip::friction::FrictionLaw;
use stickslip::{EventKind, Params};

/// The friction laws, written out independently of the library's.
#[derive(Debug, Clone, Copy)]
pub enum OracleLaw {
    /// μ(s) = 1.
    Coulomb,
    /// μ(s) = 1 + (μs − 1) exp(−(s/vs)^δ) + η s.
    Stribeck {
        /// Stribeck speed.
        vs: f64,
        /// Exponent.
        delta: f64,
        /// Viscous coefficient.
        eta: f64,
    },
    /// μ(s) = μs − k1 s + k3 s³.
    Cubic {
        /// Linear coefficient.
        k1: f64,
        /// Cubic coefficient.
        k3: f64,
    },
}

impl OracleLaw {
    /// μ at slip speed s ≥ 0 with the static level `mu_s`.
    pub fn mu(&self, mu_s: f64, s: f64) -> f64 {
        match *self {
            OracleLaw::Coulomb => 1.0,
            OracleLaw::Stribeck { vs, delta, eta } => {
                1.0 + (mu_s - 1.0) * (-(s / vs).powf(delta)).exp() + eta * s
            }
            OracleLaw::Cubic { k1, k3 } => mu_s - k1 * s + k3 * s * s * s,
        }
    }

    /// The same law as the library's type.
    pub fn library(&self) -> FrictionLaw {
        match *self {
            OracleLaw::Coulomb => FrictionLaw::Coulomb,
            OracleLaw::Stribeck { vs, delta, eta } => FrictionLaw::Stribeck { vs, delta, eta },
            OracleLaw::Cubic { k1, k3 } => FrictionLaw::Cubic { k1, k3 },
        }
    }
}

/// What the oracle is doing.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Mode {
    /// Slipping with slip sign ±1.
    Slip(f64),
    /// Stuck since τ_s at y_s.
    Stick {
        /// When the stop began.
        tau: f64,
        /// Where.
        y: f64,
    },
}

/// The independent integrator (see the module documentation). The law is `law`, whatever
/// `p.law` says (μs, vb, ζ and the drive are `p`'s).
pub struct Oracle {
    /// The parameters.
    pub p: Params,
    /// The law.
    pub law: OracleLaw,
    /// The fixed step.
    pub h: f64,
    /// The time reached.
    pub tau: f64,
    /// y there.
    pub y: f64,
    /// y' there.
    pub v: f64,
    /// What it is doing.
    pub mode: Mode,
    /// (τ, y, kind) of every event.
    pub events: Vec<(f64, f64, EventKind)>,
    /// (τ, y) of every zero of y' (an extreme of y) inside a slide.
    pub extremes: Vec<(f64, f64)>,
}

impl Oracle {
    /// The oracle of `p` with `law` and step `h` from (y, v) at τ = 0.
    pub fn new(p: Params, law: OracleLaw, h: f64, y: f64, v: f64) -> Self {
        let mut o = Self {
            p,
            law,
            h,
            tau: 0.0,
            y,
            v,
            mode: Mode::Slip(1.0),
            events: Vec::new(),
            extremes: Vec::new(),
        };
        o.mode = if v != p.vb {
            Mode::Slip((v - p.vb).signum())
        } else {
            let f = o.force(0.0, y);
            if f.abs() <= p.mu_s {
                Mode::Stick { tau: 0.0, y }
            } else {
                Mode::Slip(f.signum())
            }
        };
        o
    }

    fn drive(&self, tau: f64) -> f64 {
        self.p.beta * (self.p.w * tau + self.p.phi).cos()
    }

    /// The net force static friction must hold while stuck.
    fn force(&self, tau: f64, y: f64) -> f64 {
        self.drive(tau) - y - 2.0 * self.p.zeta * self.p.vb
    }

    fn accel(&self, tau: f64, y: f64, v: f64, sign: f64) -> f64 {
        // The law continued by its value at s = 0 where an RK4 stage overshoots.
        let s = (sign * (v - self.p.vb)).max(0.0);
        self.drive(tau) - y - 2.0 * self.p.zeta * v - sign * self.law.mu(self.p.mu_s, s)
    }

    /// One RK4 step of size `h` from (τ, y, v) sliding with `sign`.
    fn rk4(&self, tau: f64, y: f64, v: f64, sign: f64, h: f64) -> (f64, f64) {
        let f = |t: f64, y: f64, v: f64| (v, self.accel(t, y, v, sign));
        let k1 = f(tau, y, v);
        let k2 = f(tau + 0.5 * h, y + 0.5 * h * k1.0, v + 0.5 * h * k1.1);
        let k3 = f(tau + 0.5 * h, y + 0.5 * h * k2.0, v + 0.5 * h * k2.1);
        let k4 = f(tau + h, y + h * k3.0, v + h * k3.1);
        (
            y + h / 6.0 * (k1.0 + 2.0 * k2.0 + 2.0 * k3.0 + k4.0),
            v + h / 6.0 * (k1.1 + 2.0 * k2.1 + 2.0 * k3.1 + k4.1),
        )
    }

    /// Bisection for the first θ in (0, 1] where `past` holds along a partial step.
    fn bisect(&self, past: impl Fn(f64) -> bool) -> f64 {
        let (mut lo, mut hi) = (0.0, 1.0);
        for _ in 0..60 {
            let mid = 0.5 * (lo + hi);
            if past(mid) {
                hi = mid;
            } else {
                lo = mid;
            }
        }
        hi
    }

    /// Advance one grid step (or to the event inside it).
    pub fn step(&mut self) {
        let h = self.h;
        let vb = self.p.vb;
        match self.mode {
            Mode::Slip(sign) => {
                let (y1, v1) = self.rk4(self.tau, self.y, self.v, sign, h);
                if self.v * v1 < 0.0 || (v1 == 0.0 && self.v != 0.0) {
                    let (t0, y0, v0) = (self.tau, self.y, self.v);
                    let theta = self.bisect(|th| {
                        let v = self.rk4(t0, y0, v0, sign, th * h).1;
                        v * v0 <= 0.0
                    });
                    let (y, _) = self.rk4(t0, y0, v0, sign, theta * h);
                    self.extremes.push((t0 + theta * h, y));
                }
                if sign * (v1 - vb) <= 0.0 {
                    let (t0, y0, v0) = (self.tau, self.y, self.v);
                    let theta = self.bisect(|th| {
                        let v = self.rk4(t0, y0, v0, sign, th * h).1;
                        sign * (v - vb) <= 0.0
                    });
                    let (y, _) = self.rk4(t0, y0, v0, sign, theta * h);
                    self.tau = t0 + theta * h;
                    self.y = y;
                    self.v = vb;
                    let f = self.force(self.tau, y);
                    if f.abs() <= self.p.mu_s {
                        self.mode = Mode::Stick { tau: self.tau, y };
                        self.events.push((self.tau, y, EventKind::Stick));
                    } else if f.signum() != sign {
                        self.mode = Mode::Slip(f.signum());
                        self.events.push((self.tau, y, EventKind::Turn));
                    }
                    return;
                }
                self.tau += h;
                self.y = y1;
                self.v = v1;
            }
            Mode::Stick { tau: ts, y: ys } => {
                let at = |t: f64| ys + vb * (t - ts);
                let t1 = self.tau + h;
                let f1 = self.force(t1, at(t1));
                if f1.abs() > self.p.mu_s {
                    let t0 = self.tau;
                    let theta = self
                        .bisect(|th| self.force(t0 + th * h, at(t0 + th * h)).abs() > self.p.mu_s);
                    self.tau = t0 + theta * h;
                    self.y = at(self.tau);
                    self.v = vb;
                    self.mode = Mode::Slip(f1.signum());
                    self.events.push((self.tau, self.y, EventKind::Slip));
                    return;
                }
                self.tau = t1;
                self.y = at(t1);
                self.v = vb;
            }
        }
    }

    /// Run to τ = `end` (the last step shortened to land on it).
    pub fn run_to(&mut self, end: f64) {
        while self.tau < end - 1e-12 {
            let full = self.h;
            if self.tau + full > end {
                self.h = end - self.tau;
                self.step();
                self.h = full;
            } else {
                self.step();
            }
        }
    }

    /// A self-excited cycle's period and extremes (period, y_max, y_min): the interval
    /// between the last two of the first `sticks` stops, and the extremes between them.
    pub fn cycle(&mut self, sticks: usize) -> (f64, f64, f64) {
        while self
            .events
            .iter()
            .filter(|e| e.2 == EventKind::Stick)
            .count()
            < sticks
        {
            self.step();
        }
        let onsets: Vec<f64> = self
            .events
            .iter()
            .filter(|e| e.2 == EventKind::Stick)
            .map(|e| e.0)
            .collect();
        let (a, b) = (onsets[sticks - 2], onsets[sticks - 1]);
        let ys = self
            .events
            .iter()
            .filter(|e| e.0 >= a && e.0 <= b)
            .map(|e| e.1)
            .chain(
                self.extremes
                    .iter()
                    .filter(|e| e.0 > a && e.0 < b)
                    .map(|e| e.1),
            );
        let (lo, hi) = ys.fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), y| {
            (lo.min(y), hi.max(y))
        });
        (b - a, hi, lo)
    }

    /// y at each of `taus` (increasing, none before the time reached), running on to each.
    pub fn sample(&mut self, taus: &[f64]) -> Vec<f64> {
        taus.iter()
            .map(|&tau| {
                self.run_to(tau);
                self.y
            })
            .collect()
    }
}
