//! The dimensionless model and its state.
//!
//! In dimensionless time τ = ω0·t the oscillator obeys
//!
//! ```text
//! y'' + 2ζ y' + y + sgn(y') = β cos(w τ + φ)          while sliding,
//! y' = 0  and  |β cos(w τ + φ) − y| ≤ μs              while stuck,
//! ```
//!
//! which is eq. (6) of the paper with α = 2ζω0 and y = ω0²x, time measured in units of 1/ω0.
//! The kinetic friction force has magnitude 1 (it sets the unit of y); μs ≥ 1 is the ratio of
//! static to kinetic friction (the paper takes μs = 1).

use crate::error::{check, Result};
use crate::friction::{check_vb, FrictionLaw};
use crate::limits;
use serde::{Deserialize, Serialize};
use std::f64::consts::TAU;

/// Parameters of the dimensionless model. Build with [`Params::new`] (validated) and the
/// `with_*` setters; fields are public for reading.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Params {
    /// Damping ratio ζ = α/(2ω0) ≥ 0 (viscous part only; the diodes' R_D included).
    pub zeta: f64,
    /// Drive frequency w = Ω/ω0 > 0.
    pub w: f64,
    /// Drive amplitude β = F/F0 = U/U_t ≥ 0, in units of the kinetic friction force.
    pub beta: f64,
    /// Drive phase φ (radians) at τ = 0.
    pub phi: f64,
    /// Static-to-kinetic friction ratio μs ≥ 1 (1 in the paper).
    pub mu_s: f64,
    /// Belt speed vb (dimensionless, in units of y'; 0 in the paper): friction acts on the
    /// slip y' − vb ([`crate::friction`]). Mechanical models only.
    #[serde(default, skip_serializing_if = "is_zero")]
    pub vb: f64,
    /// The friction law of the slip speed ([`FrictionLaw`]; Coulomb's in the paper).
    #[serde(default, skip_serializing_if = "FrictionLaw::is_coulomb")]
    pub law: FrictionLaw,
}

/// Whether a value is zero (serde skips a belt at rest).
fn is_zero(x: &f64) -> bool {
    *x == 0.0
}

impl Params {
    /// Validated parameters with φ = 0 and μs = 1.
    ///
    /// # Errors
    /// [`crate::Error::InvalidParameter`] when a value is not finite or outside the range the
    /// solvers support ([`crate::limits`]): 0 ≤ ζ ≤ 1e4, 1e-5 ≤ w ≤ 1e5, 0 ≤ β ≤ 1e9.
    pub fn new(zeta: f64, w: f64, beta: f64) -> Result<Self> {
        Ok(Self {
            zeta: check("zeta", zeta, limits::zeta_ok(zeta), limits::ZETA_ALLOWED)?,
            w: check("w", w, limits::w_ok(w), limits::W_ALLOWED)?,
            beta: check("beta", beta, limits::beta_ok(beta), limits::BETA_ALLOWED)?,
            phi: 0.0,
            mu_s: 1.0,
            vb: 0.0,
            law: FrictionLaw::Coulomb,
        })
    }

    /// Set the drive phase φ (radians).
    ///
    /// # Errors
    /// [`crate::Error::InvalidParameter`] when φ is not finite or |φ| > 1e6.
    pub fn with_phi(mut self, phi: f64) -> Result<Self> {
        self.phi = check("phi", phi, limits::phi_ok(phi), limits::PHI_ALLOWED)?;
        Ok(self)
    }

    /// Set the static-to-kinetic friction ratio μs.
    ///
    /// # Errors
    /// [`crate::Error::InvalidParameter`] when μs < 1, μs > 1e9 or not finite.
    pub fn with_mu_s(mut self, mu_s: f64) -> Result<Self> {
        self.mu_s = check("mu_s", mu_s, limits::mu_s_ok(mu_s), limits::MU_S_ALLOWED)?;
        Ok(self)
    }

    /// Set the belt speed vb (−0 is read as 0).
    ///
    /// # Errors
    /// [`crate::Error::InvalidParameter`] when vb is not finite or |vb| > 1e6.
    pub fn with_vb(mut self, vb: f64) -> Result<Self> {
        self.vb = check_vb(vb)?;
        Ok(self)
    }

    /// Set the friction law, checked with this μs ([`FrictionLaw::validate`]).
    ///
    /// # Errors
    /// [`crate::Error::InvalidParameter`] naming the law's parameter.
    pub fn with_law(mut self, law: FrictionLaw) -> Result<Self> {
        self.law = law.validate(self.mu_s)?;
        Ok(self)
    }

    /// Re-check all fields (for values built by struct literal or deserialised).
    ///
    /// # Errors
    /// The first invalid field, as in [`Params::new`].
    pub fn validate(&self) -> Result<Self> {
        let p = Params::new(self.zeta, self.w, self.beta)?
            .with_phi(self.phi)?
            .with_mu_s(self.mu_s)?;
        if self.vb == 0.0 && self.law.is_coulomb() {
            // (The paper's model: nothing more to check.)
            return Ok(p);
        }
        p.with_vb(self.vb)?.with_law(self.law)
    }

    /// Whether the model is the paper's own: no belt and Coulomb's law.
    pub fn is_paper_friction(&self) -> bool {
        self.vb == 0.0 && self.law.is_coulomb()
    }

    /// The viscous force 2ζ·vb of a block stuck to the belt, which static friction must
    /// hold besides the drive and the spring: while stuck, |β cos(wτ + φ) − y − 2ζ vb| ≤ μs.
    /// Exactly 0 without a belt.
    pub fn belt_force(&self) -> f64 {
        if self.vb == 0.0 {
            0.0
        } else {
            2.0 * self.zeta * self.vb
        }
    }

    /// The net force β cos(wτ + φ) − y − 2ζ·vb that static friction holds at y while stuck
    /// to the belt (β cos(wτ + φ) − y without one, bit for bit).
    pub fn net_force(&self, tau: f64, y: f64) -> f64 {
        self.drive(tau) - y - self.belt_force()
    }

    /// The drive β cos(w τ + φ) at time τ.
    pub fn drive(&self, tau: f64) -> f64 {
        self.beta * (self.w * tau + self.phi).cos()
    }

    /// The drive period 2π/w in units of τ.
    pub fn drive_period(&self) -> f64 {
        std::f64::consts::TAU / self.w
    }

    /// Quality factor Q = 1/(2ζ) of the linear circuit (infinite for ζ = 0).
    pub fn quality_factor(&self) -> f64 {
        1.0 / (2.0 * self.zeta)
    }
}

/// One of the dimensionless parameters that sweeps and grids vary: the paper's four (ζ, w,
/// β, μs), the belt speed vb and the friction law's own parameters.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Parameter {
    /// Damping ratio ζ ≥ 0.
    Zeta,
    /// Drive frequency w = Ω/ω0 > 0.
    W,
    /// Drive amplitude β ≥ 0.
    Beta,
    /// Static-to-kinetic friction ratio μs ≥ 1.
    MuS,
    /// Belt speed vb ([`crate::friction`]).
    Vb,
    /// Stribeck speed vs > 0 (Stribeck law).
    Vs,
    /// Stribeck exponent δ > 0 (Stribeck law).
    Delta,
    /// Viscous coefficient η ≥ 0 (Stribeck law).
    Eta,
    /// Linear coefficient k1 (cubic law).
    K1,
    /// Cubic coefficient k3 ≥ 0 (cubic law).
    K3,
}

/// What a law's parameter asks when the law is another.
const STRIBECK_ONLY: &str = "is a parameter of the Stribeck law (friction_law = stribeck)";
const CUBIC_ONLY: &str = "is a parameter of the cubic law (friction_law = cubic)";

impl Parameter {
    /// All of them, in the order ζ, w, β, μs, vb, vs, δ, η, k1, k3 (the paper's four first,
    /// so that their codes stay what they were).
    pub const ALL: [Parameter; 10] = [
        Parameter::Zeta,
        Parameter::W,
        Parameter::Beta,
        Parameter::MuS,
        Parameter::Vb,
        Parameter::Vs,
        Parameter::Delta,
        Parameter::Eta,
        Parameter::K1,
        Parameter::K3,
    ];

    /// The name used in files, flags and column headers: `zeta`, `w`, `beta`, `mu_s`, `vb`,
    /// `vs`, `delta`, `eta`, `k1`, `k3`.
    pub fn label(self) -> &'static str {
        match self {
            Parameter::Zeta => "zeta",
            Parameter::W => "w",
            Parameter::Beta => "beta",
            Parameter::MuS => "mu_s",
            Parameter::Vb => "vb",
            Parameter::Vs => "vs",
            Parameter::Delta => "delta",
            Parameter::Eta => "eta",
            Parameter::K1 => "k1",
            Parameter::K3 => "k3",
        }
    }

    /// The parameter named `label` ([`Parameter::label`]).
    pub fn from_label(label: &str) -> Option<Self> {
        Self::ALL.into_iter().find(|p| p.label() == label)
    }

    /// A description with its symbol, for axis labels and metadata (e.g. "drive frequency
    /// w = Ω/ω0").
    pub fn long_name(self) -> &'static str {
        match self {
            Parameter::Zeta => "damping ratio ζ",
            Parameter::W => "drive frequency w = Ω/ω0",
            Parameter::Beta => "drive amplitude β (in units of the kinetic friction force)",
            Parameter::MuS => "static-to-kinetic friction ratio μs",
            Parameter::Vb => "belt speed vb (in units of F/(k)·ω0)",
            Parameter::Vs => "Stribeck speed vs",
            Parameter::Delta => "Stribeck exponent δ",
            Parameter::Eta => "viscous friction coefficient η",
            Parameter::K1 => "linear coefficient k1 of the cubic law",
            Parameter::K3 => "cubic coefficient k3 of the cubic law",
        }
    }

    /// Whether the parameter belongs to the friction law or the belt (not to the paper's
    /// model).
    pub fn is_friction(self) -> bool {
        !matches!(
            self,
            Parameter::Zeta | Parameter::W | Parameter::Beta | Parameter::MuS
        )
    }

    /// Whether `params` has something to say about the parameter: the paper's four always, the
    /// belt speed when the belt moves, a law's parameters when `params` follows that law
    /// (what a title of fixed values lists).
    pub fn is_set_in(self, params: &Params) -> bool {
        match self {
            Parameter::Vb => params.vb != 0.0,
            _ => !self.get(params).is_nan(),
        }
    }

    /// Its value in `params` (NaN for a parameter of a law that `params` does not follow).
    pub fn get(self, params: &Params) -> f64 {
        match (self, params.law) {
            (Parameter::Zeta, _) => params.zeta,
            (Parameter::W, _) => params.w,
            (Parameter::Beta, _) => params.beta,
            (Parameter::MuS, _) => params.mu_s,
            (Parameter::Vb, _) => params.vb,
            (Parameter::Vs, FrictionLaw::Stribeck { vs, .. }) => vs,
            (Parameter::Delta, FrictionLaw::Stribeck { delta, .. }) => delta,
            (Parameter::Eta, FrictionLaw::Stribeck { eta, .. }) => eta,
            (Parameter::K1, FrictionLaw::Cubic { k1, .. }) => k1,
            (Parameter::K3, FrictionLaw::Cubic { k3, .. }) => k3,
            _ => f64::NAN,
        }
    }

    /// `params` with this parameter set to `value`, validated.
    ///
    /// # Errors
    /// [`crate::Error::InvalidParameter`] when the value is out of range
    /// ([`crate::limits`]), or for a parameter of a law that `params` does not follow.
    pub fn set(self, params: Params, value: f64) -> Result<Params> {
        let mut p = params;
        let law_only = |allowed| crate::error::invalid(self.label(), value, allowed);
        match (self, &mut p.law) {
            (Parameter::Zeta, _) => p.zeta = value,
            (Parameter::W, _) => p.w = value,
            (Parameter::Beta, _) => p.beta = value,
            (Parameter::MuS, _) => p.mu_s = value,
            (Parameter::Vb, _) => p.vb = value,
            (Parameter::Vs, FrictionLaw::Stribeck { vs, .. }) => *vs = value,
            (Parameter::Delta, FrictionLaw::Stribeck { delta, .. }) => *delta = value,
            (Parameter::Eta, FrictionLaw::Stribeck { eta, .. }) => *eta = value,
            (Parameter::K1, FrictionLaw::Cubic { k1, .. }) => *k1 = value,
            (Parameter::K3, FrictionLaw::Cubic { k3, .. }) => *k3 = value,
            (Parameter::Vs | Parameter::Delta | Parameter::Eta, _) => {
                return law_only(STRIBECK_ONLY)
            }
            (_, _) => return law_only(CUBIC_ONLY),
        }
        p.validate()
    }
}

impl std::fmt::Display for Parameter {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.label())
    }
}

/// Position and velocity (y, y') at one instant, dimensionless.
#[derive(Debug, Clone, Copy, PartialEq, Default, Serialize, Deserialize)]
pub struct State {
    /// Position y (capacitor voltage over U_t, or k·r/F0).
    pub y: f64,
    /// Velocity y' = dy/dτ (current over U_t/√(L/C)).
    pub v: f64,
}

impl State {
    /// A state from position and velocity (any finite values: an initial state given by a
    /// user is checked against the supported range by [`crate::limits::check_state`]).
    ///
    /// # Errors
    /// [`crate::Error::InvalidParameter`] when either value is not finite.
    pub fn new(y: f64, v: f64) -> Result<Self> {
        Ok(Self {
            y: check("y0", y, true, "must be finite")?,
            v: check("v0", v, true, "must be finite")?,
        })
    }

    /// Mechanical energy v²/2 + y²/2 (spring plus kinetic, in units of F0²/k).
    pub fn energy(&self) -> f64 {
        0.5 * (self.y * self.y + self.v * self.v)
    }
}

// The ranges a run from the parameters must stay within (`crate::limits` re-exports these
// under their old paths).

/// Check an initial state (y0, v0) given by a user: finite and within ±[`limits::STATE_MAX`].
///
/// States the solvers reach themselves (the end of a sweep step, say) may grow beyond it and
/// are only required to be finite ([`State::new`]).
///
/// # Errors
/// [`crate::Error::InvalidParameter`] naming `y0` or `v0`.
pub fn check_state(y0: f64, v0: f64) -> Result<State> {
    check("y0", y0, limits::state_ok(y0), limits::STATE_ALLOWED)?;
    check("v0", v0, limits::state_ok(v0), limits::STATE_ALLOWED)?;
    Ok(State { y: y0, v: v0 })
}

/// The most drive periods a run from τ = 0 may last at these parameters: the end time τ and
/// the drive phase w·τ both within [`limits::TAU_MAX`], i.e. 2³²/(2π)·min(1, w) periods.
pub fn max_periods(params: &Params) -> f64 {
    limits::TAU_MAX / TAU * params.w.min(1.0)
}

/// Check that a run of `periods` drive periods from τ = 0 stays within the time range the
/// solvers resolve ([`max_periods`]).
///
/// # Errors
/// [`crate::Error::HorizonTooLong`] with the largest number of periods allowed.
pub fn check_horizon(params: &Params, periods: f64) -> Result<()> {
    let max = max_periods(params);
    if periods <= max {
        Ok(())
    } else {
        Err(crate::Error::HorizonTooLong {
            periods,
            w: params.w,
            max_periods: max,
        })
    }
}

/// Check that the time τ (from τ = 0) lies within the time range the solvers resolve: τ and
/// w·τ at most [`limits::TAU_MAX`].
///
/// # Errors
/// [`crate::Error::HorizonTooLong`] as [`check_horizon`] for τ/T periods.
pub fn check_time(params: &Params, tau: f64) -> Result<()> {
    if tau <= limits::TAU_MAX && params.w * tau <= limits::TAU_MAX {
        Ok(())
    } else {
        Err(crate::Error::HorizonTooLong {
            periods: tau / params.drive_period(),
            w: params.w,
            max_periods: max_periods(params),
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::Error;

    #[test]
    fn rejects_bad_values_naming_the_field() {
        let cases = [
            (Params::new(-0.1, 1.0, 1.0), "zeta"),
            (Params::new(f64::NAN, 1.0, 1.0), "zeta"),
            (Params::new(0.1, 0.0, 1.0), "w"),
            (Params::new(0.1, f64::INFINITY, 1.0), "w"),
            (Params::new(0.1, 1.0, -1.0), "beta"),
            (
                Params::new(0.1, 1.0, 1.0).and_then(|p| p.with_mu_s(0.5)),
                "mu_s",
            ),
            (
                Params::new(0.1, 1.0, 1.0).and_then(|p| p.with_phi(f64::NAN)),
                "phi",
            ),
        ];
        for (result, field) in cases {
            match result {
                Err(Error::InvalidParameter { name, .. }) => assert_eq!(name, field),
                other => panic!("expected an error for {field}, got {other:?}"),
            }
        }
    }

    #[test]
    fn parameters_set_and_get_by_name() {
        let p = Params::new(0.1, 1.0, 2.0).unwrap();
        for (param, value) in Parameter::ALL.into_iter().zip([0.2, 0.5, 3.0, 1.5]) {
            let q = param.set(p, value).unwrap();
            assert_eq!(param.get(&q), value);
            assert_eq!(Parameter::from_label(param.label()), Some(param));
        }
        assert!(Parameter::MuS.set(p, 0.9).is_err());
        assert!(Parameter::W.set(p, 0.0).is_err());
        assert_eq!(Parameter::from_label("gamma"), None);
    }

    #[test]
    fn accepts_edge_values() {
        let p = Params::new(0.0, 1e-5, 0.0).unwrap().with_mu_s(1.0).unwrap();
        assert_eq!(p.mu_s, 1.0);
        let p = Params::new(1e4, 1e5, 1e9)
            .unwrap()
            .with_mu_s(1e9)
            .unwrap()
            .with_phi(-1e6)
            .unwrap();
        assert!(p.validate().is_ok());
        assert!(p.validate().is_ok());
    }
}
