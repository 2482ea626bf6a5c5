//! The keys of an experiment description, as a plain enum ([`Key`]). A leaf: it imports
//! nothing of the crate, so [`crate::error`] can carry a key. Everything about a key (its
//! names, unit, range, help; `Display`) is in its table, `experiment/key.rs`.

use serde::{Deserialize, Serialize};

/// One value of an experiment description. Its [`Key::name`] is the key of the TOML file and
/// the keyword of the Python package; [`Key::flag`] is its command-line flag (without the
/// dashes) and the lab's query key. Everything about a key comes from one table
/// ([`Key::table`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord, Serialize, Deserialize)]
#[non_exhaustive]
pub enum Key {
    /// Damping ratio ζ (dimensionless description only).
    Zeta,
    /// Drive frequency w = Ω/ω0.
    W,
    /// Drive amplitude β.
    Beta,
    /// Drive phase φ in radians.
    Phi,
    /// Static-to-kinetic friction ratio μs.
    MuS,
    /// Initial position y0.
    Y0,
    /// Initial velocity v0.
    V0,
    /// Inductance L (H).
    Inductance,
    /// Capacitance C (F).
    Capacitance,
    /// Series resistance R without the diodes (Ω).
    Resistance,
    /// Diode turn-on voltage U_t (V), also the reference voltage of y and β.
    TurnOn,
    /// PWL diode resistance R_D (Ω).
    DiodeResistance,
    /// Mass m (kg).
    Mass,
    /// Spring constant k (N/m).
    Stiffness,
    /// Viscous damping γ (N·s/m).
    Damping,
    /// Kinetic friction force F0 (N).
    Friction,
    /// Drive amplitude U (V) or F (N).
    Amplitude,
    /// Drive frequency f (Hz).
    Frequency,
    /// Drive angular frequency Ω (rad/s).
    Omega,
    /// Initial capacitor voltage u_C(0) (V), or initial position r(0) (m).
    Uc0,
    /// Initial current i(0) (A), or initial velocity ṙ(0) (m/s).
    I0,
    /// Shockley saturation current I_s (A).
    SaturationCurrent,
    /// Shockley emission coefficient n.
    Emission,
    /// Shockley series resistance R_s (Ω).
    SeriesResistance,
    /// Diode temperature (°C).
    Temperature,
    /// The diode law, `pwl` or `shockley`.
    Diode,
    /// A built-in physical description (`paper`).
    Preset,
    /// Belt speed vb (dimensionless).
    Vb,
    /// The friction law, `coulomb`, `stribeck` or `cubic`.
    FrictionLaw,
    /// Stribeck speed vs (dimensionless).
    Vs,
    /// Stribeck exponent δ.
    Delta,
    /// Viscous friction coefficient η of the Stribeck law (dimensionless).
    Eta,
    /// Coefficient k1 of the cubic law (dimensionless).
    K1,
    /// Coefficient k3 of the cubic law (dimensionless).
    K3,
    /// Belt speed (m/s).
    BeltSpeed,
    /// Stribeck speed (m/s).
    StribeckSpeed,
    /// Viscous friction coefficient (N·s/m).
    ViscousFriction,
    /// Coefficient of the cubic law's linear term (N·s/m).
    CubicK1,
    /// Coefficient of the cubic law's cubic term (N·s³/m³).
    CubicK3,
}
