//! Physical units at the edges: the conversion of a run's samples and of a description to the
//! dimensionless model.

use crate::physical::Scales;
use serde::{Deserialize, Serialize};

/// Conversion between the dimensionless samples of a run and physical units.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PhysicalUnits {
    /// Whether the system is a circuit (volts, amperes) or a mechanical oscillator (metres,
    /// newtons).
    pub circuit: bool,
    /// The scales.
    pub scales: Scales,
}

impl PhysicalUnits {
    /// Column names of [`PhysicalUnits::convert`]: `t_s, uc_V, i_A, u_V` for a circuit,
    /// `t_s, r_m, rdot_m_s, F_N` for a mechanical oscillator.
    pub fn columns(&self) -> [&'static str; 4] {
        if self.circuit {
            ["t_s", "uc_V", "i_A", "u_V"]
        } else {
            ["t_s", "r_m", "rdot_m_s", "F_N"]
        }
    }

    /// Time (s), position (V or m), velocity (A or m/s) and drive (V or N) of a sample at τ
    /// with position y, velocity y' and drive β cos(wτ + φ).
    pub fn convert(&self, tau: f64, y: f64, v: f64, drive: f64) -> [f64; 4] {
        let s = &self.scales;
        [s.time(tau), y * s.position, v * s.velocity, drive * s.force]
    }
}

/// What a physical description means in the dimensionless model.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Conversion {
    /// Natural angular frequency ω0 (rad/s).
    pub omega0: f64,
    /// Natural frequency f0 = ω0/2π (Hz).
    pub f0: f64,
    /// The paper's α = 2ζω0 (1/s).
    pub alpha: f64,
    /// Damping ratio ζ.
    pub zeta: f64,
    /// Quality factor Q = 1/(2ζ).
    #[serde(rename = "Q")]
    pub q: f64,
    /// Drive frequency w = Ω/ω0, when a drive was given.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub w: Option<f64>,
    /// Drive amplitude β, when a drive was given.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub beta: Option<f64>,
}
