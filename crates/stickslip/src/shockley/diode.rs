//! Two identical anti-parallel diodes obeying the Shockley law with a series resistance, and
//! the dimensionless form of that law used by the solver.
//!
//! One diode conducts I = I_s (e^{V_j/(n V_T)} − 1) at junction voltage V_j. Two of them in
//! anti-parallel carry i = 2 I_s sinh(V_j/(n V_T)), so with the series resistance R_s the pair
//! drops
//!
//! ```text
//! U_D(i) = n V_T asinh(i / (2 I_s)) + R_s i,        V_T = k T / q.
//! ```
//!
//! SPICE gives each diode its own R_s; the two descriptions differ only through R_s times the
//! reverse current of the blocking diode (at most R_s·I_s ≈ 3 nV for the 1N4148), far below
//! anything measurable here.
//!
//! **Difference from the paper.** The paper's eq. (14) (`eq:Shockley model`) writes
//! U = V_th asinh(I/(2 I_0)) and replaces sgn(ẋ) in its eq. (6) by asinh(ẋ U_t/(2 I_0 L)),
//! which drops the factor V_th/U_t (about 0.07 for a 1N4148 against U_t = 0.7 V): taken
//! literally that friction term grows to about 14 instead of about 1 at the working currents.
//! We implement the physical law above; its dimensionless form is [`DiodeLaw`].

use crate::error::{check, Result};
use crate::stiff::SmoothLaw;
use serde::{Deserialize, Serialize};

/// Boltzmann constant k in J/K (exact in the 2019 SI).
pub const BOLTZMANN: f64 = 1.380_649e-23;
/// Elementary charge q in C (exact in the 2019 SI).
pub const ELEMENTARY_CHARGE: f64 = 1.602_176_634e-19;
/// 0 °C in kelvin.
pub const ZERO_CELSIUS: f64 = 273.15;

/// Two identical anti-parallel diodes: U_D(i) = n V_T asinh(i/(2 I_s)) + R_s i.
///
/// Build with [`DiodePair::new`] (validated) or take the default, the 1N4148 at 27 °C
/// ([`DiodePair::one_n4148`]).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct DiodePair {
    /// Saturation current I_s of one diode, in amperes (> 0).
    pub saturation_current: f64,
    /// Emission coefficient n (> 0, typically 1 to 2).
    pub emission: f64,
    /// Series resistance R_s of one diode, in ohms (≥ 0).
    pub series_resistance: f64,
    /// Junction temperature in °C (above absolute zero); sets V_T = k T/q. I_s is taken as
    /// given at this temperature (no temperature scaling of I_s).
    pub temperature: f64,
}

impl DiodePair {
    /// Validated diode pair.
    ///
    /// # Errors
    /// [`crate::Error::InvalidParameter`] when I_s ≤ 0, n ≤ 0, R_s < 0, the temperature is at
    /// or below absolute zero, or any value is not finite.
    pub fn new(
        saturation_current: f64,
        emission: f64,
        series_resistance: f64,
        temperature: f64,
    ) -> Result<Self> {
        Ok(Self {
            saturation_current: check(
                "Is",
                saturation_current,
                saturation_current > 0.0,
                "must be finite and > 0 (amperes)",
            )?,
            emission: check("n", emission, emission > 0.0, "must be finite and > 0")?,
            series_resistance: check(
                "Rs",
                series_resistance,
                series_resistance >= 0.0,
                "must be finite and >= 0 (ohms)",
            )?,
            temperature: check(
                "temperature",
                temperature,
                temperature > -ZERO_CELSIUS,
                "must be finite and above -273.15 (degrees Celsius)",
            )?,
        })
    }

    /// The 1N4148 small-signal diode at 27 °C (the SPICE default temperature):
    /// I_s = 4.352 nA, n = 1.906, R_s = 0.6458 Ω.
    pub fn one_n4148() -> Self {
        Self {
            saturation_current: 4.352e-9,
            emission: 1.906,
            series_resistance: 0.6458,
            temperature: 27.0,
        }
    }

    /// Re-check all fields (for values built by struct literal or deserialised).
    ///
    /// # Errors
    /// The first invalid field, as in [`DiodePair::new`].
    pub fn validate(&self) -> Result<Self> {
        Self::new(
            self.saturation_current,
            self.emission,
            self.series_resistance,
            self.temperature,
        )
    }

    /// Thermal voltage V_T = k T/q in volts (25.865 mV at 27 °C).
    pub fn thermal_voltage(&self) -> f64 {
        BOLTZMANN * (self.temperature + ZERO_CELSIUS) / ELEMENTARY_CHARGE
    }

    /// n·V_T in volts.
    pub fn slope_voltage(&self) -> f64 {
        self.emission * self.thermal_voltage()
    }

    /// Voltage U_D(i) across the pair at current `i` (A), in volts; odd in i.
    pub fn voltage(&self, i: f64) -> f64 {
        self.slope_voltage() * (i / (2.0 * self.saturation_current)).asinh()
            + self.series_resistance * i
    }

    /// Differential resistance dU_D/di at current `i`, in ohms
    /// (n V_T/(2 I_s) ≈ 5.7 MΩ at i = 0 for the 1N4148).
    pub fn differential_resistance(&self, i: f64) -> f64 {
        self.slope_voltage() / (2.0 * self.saturation_current).hypot(i) + self.series_resistance
    }

    /// Current through the pair at voltage `u` (V), in amperes: the inverse of
    /// [`DiodePair::voltage`], found by a safeguarded Newton iteration on the junction voltage.
    pub fn current(&self, u: f64) -> f64 {
        let nvt = self.slope_voltage();
        let two_is = 2.0 * self.saturation_current;
        let rs = self.series_resistance;
        if u == 0.0 || !u.is_finite() {
            // 0 → 0, ±∞ → ±∞, NaN → NaN.
            return u;
        }
        // Unknown: the junction voltage x ∈ (0, |u|]. g(x) = x + R_s·2I_s·sinh(x/nV_T) − |u|
        // is increasing and convex, so Newton's method from any point right of the root
        // decreases monotonically onto it. Both |u| and nV_T·asinh(|u|/(2 I_s R_s)) lie right
        // of the root, and the second keeps sinh from overflowing.
        let target = u.abs();
        let mut x = target;
        if rs > 0.0 {
            x = x.min(nvt * (target / (rs * two_is)).asinh());
            for _ in 0..200 {
                let g = x + rs * two_is * (x / nvt).sinh() - target;
                let slope = 1.0 + rs * two_is / nvt * (x / nvt).cosh();
                let next = x - g / slope;
                if !(next < x) {
                    break;
                }
                let done = x - next <= 1e-16 * x;
                x = next;
                if done {
                    break;
                }
            }
        }
        u.signum() * two_is * (x / nvt).sinh()
    }

    /// The dimensionless law D(v) = U_D(i)/U_ref with i = v·U_ref/Z, for a reference voltage
    /// `reference_voltage` (the U_t that makes y = u_C/U_t) and a characteristic impedance
    /// Z = √(L/C) in ohms.
    ///
    /// # Errors
    /// [`crate::Error::InvalidParameter`] when either argument is not finite and > 0.
    pub fn law(&self, reference_voltage: f64, impedance: f64) -> Result<DiodeLaw> {
        check(
            "U_t",
            reference_voltage,
            reference_voltage > 0.0,
            "must be finite and > 0 (volts)",
        )?;
        check(
            "sqrt(L/C)",
            impedance,
            impedance > 0.0,
            "must be finite and > 0 (ohms)",
        )?;
        DiodeLaw::new(
            self.slope_voltage() / reference_voltage,
            2.0 * self.saturation_current * impedance / reference_voltage,
            self.series_resistance / impedance,
        )
    }
}

impl Default for DiodePair {
    /// [`DiodePair::one_n4148`].
    fn default() -> Self {
        Self::one_n4148()
    }
}

/// The diode law in dimensionless form, D(v) = a·asinh(v/ε) + r·v, with v = y' the
/// dimensionless current:
///
/// - a = n V_T/U_t, the diode's voltage scale over the reference voltage (≈ 0.0704 for the
///   1N4148 against U_t = 0.7 V);
/// - ε = 2 I_s √(L/C)/U_t, the current scale where the law turns from linear to logarithmic
///   (≈ 9.4·10⁻⁶ in the paper's circuit);
/// - r = R_s/√(L/C), the series resistance (≈ 8.5·10⁻⁴).
///
/// Its slope at v = 0 is a/ε + r (≈ 7.5·10³ in the paper's circuit): the stiffness.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct DiodeLaw {
    /// Voltage scale a = n V_T/U_t (> 0).
    pub scale: f64,
    /// Current scale ε = 2 I_s √(L/C)/U_t (> 0).
    pub knee: f64,
    /// Series resistance r = R_s/√(L/C) (≥ 0).
    pub resistance: f64,
}

impl DiodeLaw {
    /// Validated law.
    ///
    /// # Errors
    /// [`crate::Error::InvalidParameter`] when a ≤ 0, ε ≤ 0, r < 0 or any value is not finite.
    pub fn new(scale: f64, knee: f64, resistance: f64) -> Result<Self> {
        Ok(Self {
            scale: check("a", scale, scale > 0.0, "must be finite and > 0")?,
            knee: check("epsilon", knee, knee > 0.0, "must be finite and > 0")?,
            resistance: check(
                "r",
                resistance,
                resistance >= 0.0,
                "must be finite and >= 0",
            )?,
        })
    }

    /// A law that tends to the PWL law sgn(v) + r·v as `scale` → 0: the knee is chosen so
    /// that the junction part a·asinh(v/ε) equals 1 at the current `turn_on_current`
    /// (dimensionless, > 0), i.e. ε = v₀/sinh(1/a). For |v| ≫ ε the junction part is
    /// 1 + a·ln(|v|/v₀) + O(ε²/v²), so it converges to sgn(v) at the rate a.
    ///
    /// # Errors
    /// [`crate::Error::InvalidParameter`] when a value is out of range, or when a is so small
    /// that ε underflows (a below about 1/700).
    pub fn pwl_limit(scale: f64, turn_on_current: f64, resistance: f64) -> Result<Self> {
        check("a", scale, scale > 0.0, "must be finite and > 0")?;
        check(
            "v0",
            turn_on_current,
            turn_on_current > 0.0,
            "must be finite and > 0",
        )?;
        let knee = turn_on_current / (1.0 / scale).sinh();
        Self::new(scale, knee, resistance).map_err(|_| crate::Error::InvalidParameter {
            name: "a",
            value: scale,
            allowed: "must be large enough that v0/sinh(1/a) is a positive normal number",
        })
    }

    /// D(v).
    #[inline]
    pub fn value(&self, v: f64) -> f64 {
        self.scale * (v / self.knee).asinh() + self.resistance * v
    }

    /// D'(v) = a/√(ε² + v²) + r.
    #[inline]
    pub fn slope(&self, v: f64) -> f64 {
        self.scale / self.knee.hypot(v) + self.resistance
    }

    /// D(v) and D'(v) together, sharing one square root and one logarithm (the solver's inner
    /// loop). Accurate to a few units in the last place for |v|/ε up to 10¹⁵⁰, beyond which
    /// it falls back to [`DiodeLaw::value`] and [`DiodeLaw::slope`].
    #[inline]
    pub fn value_and_slope(&self, v: f64) -> (f64, f64) {
        let x = (v / self.knee).abs();
        if !(x < 1e150) {
            return (self.value(v), self.slope(v));
        }
        // asinh x = ln(x + √(1 + x²)); below x = 1/2 written as ln(1 + x + x²/(1 + √(1 + x²)))
        // to avoid cancellation (ln is cheaper than ln_1p, and most currents are far beyond
        // the knee).
        let root = (1.0 + x * x).sqrt();
        let asinh = if x > 0.5 {
            (x + root).ln()
        } else {
            (x + x * x / (1.0 + root)).ln_1p()
        };
        (
            (self.scale * asinh).copysign(v) + self.resistance * v,
            self.scale / (self.knee * root) + self.resistance,
        )
    }

    /// The current |v| at which the junction part a·asinh(|v|/ε) reaches `level`
    /// (dimensionless voltage): ε·sinh(level/a).
    pub fn current_at(&self, level: f64) -> f64 {
        self.knee * (level / self.scale).sinh()
    }
}

impl SmoothLaw for DiodeLaw {
    /// a = n V_T/U_t, ε = 2 I_s √(L/C)/U_t, r = R_s/√(L/C).
    const PARAMETERS: &'static [&'static str] = &["a", "epsilon", "r"];

    fn validate(&self) -> Result<Self> {
        DiodeLaw::new(self.scale, self.knee, self.resistance)
    }

    #[inline]
    fn value_and_slope(&self, v: f64) -> (f64, f64) {
        DiodeLaw::value_and_slope(self, v)
    }

    /// ∂D/∂a = asinh(v/ε), ∂D/∂ε = −a v/(ε √(ε² + v²)), ∂D/∂r = v.
    fn parameter_derivatives(&self, v: f64, out: &mut [f64]) {
        out[0] = (v / self.knee).asinh();
        out[1] = -self.scale * v / (self.knee * self.knee.hypot(v));
        out[2] = v;
    }

    /// Zero current, where the junction's slope a/ε is largest.
    #[inline]
    fn knee(&self) -> Option<f64> {
        Some(0.0)
    }

    /// The junction chart u = a·asinh(v/ε) (the diode voltage less its series part), in
    /// which the law is linear: du/dv = D'(v) − r.
    #[inline]
    fn steep_slope(&self, _v: f64, slope: f64) -> Option<f64> {
        Some(slope - self.resistance)
    }

    /// A Newton step `delta` in the junction voltage, returned as the new current. Beyond the
    /// edge of the range where the diode dominates the stage (junction slope a/√(ε² + V²)
    /// above `diagonal`), an outward step is cut back to the edge plus a·ln(1 + excess/a), so
    /// that ε·sinh(u/a) grows at most linearly in the excess instead of exponentially (as
    /// SPICE limits junction voltages).
    #[inline]
    fn steep_step(&self, v: f64, value: f64, delta: f64, diagonal: f64) -> f64 {
        junction_step(self, v, value, delta, diagonal)
    }
}

/// A Newton step `delta` in the junction voltage u = a·asinh(V/ε) of a stage currently at
/// current `v` with diode voltage `value` = D(v), returned as the new current. Beyond the edge
/// of the range where the diode dominates the stage (junction slope a/√(ε² + V²) above
/// `diagonal`), an outward step is cut back to the edge plus a·ln(1 + excess/a), so that
/// ε·sinh(u/a) grows at most linearly in the excess instead of exponentially.
fn junction_step(law: &DiodeLaw, v: f64, value: f64, delta: f64, diagonal: f64) -> f64 {
    let (a, knee) = (law.scale, law.knee);
    // The junction voltage is the diode voltage less its series part: no asinh needed.
    let u = value - law.resistance * v;
    let target = u + delta;
    let current = knee * (target / a).sinh();
    // Edge of the diode-dominated range: a/√(ε² + V²) = diagonal. A step inside it, or
    // inwards, stands as it is (|current| > edge_current is |target| > a·asinh(edge/ε)).
    let edge_current = ((a / diagonal).powi(2) - knee * knee).max(0.0).sqrt();
    if current.abs() <= edge_current || target.abs() <= u.abs() {
        return current;
    }
    // a·asinh(edge/ε) = a·ln((edge + √(ε² + edge²))/ε), and √(ε² + edge²) = a/diagonal there.
    let edge = if edge_current > 0.0 {
        a * ((edge_current + a / diagonal) / knee).ln()
    } else {
        0.0
    };
    let base = edge.max(u.abs());
    let excess = target.abs() - base;
    let limited = target.signum() * (base + a * (1.0 + excess / a).ln());
    knee * (limited / a).sinh()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn thermal_voltage_at_27_celsius() {
        let d = DiodePair::one_n4148();
        // k·300.15 K/q = 25.8649 mV.
        assert!((d.thermal_voltage() - 0.025_864_93).abs() < 1e-8);
    }

    #[test]
    fn voltage_is_odd_and_current_inverts_it() {
        let d = DiodePair::one_n4148();
        for i in [1e-12, 3e-9, 1e-6, 1e-3, 6.5e-3, 0.1, 2.0] {
            let u = d.voltage(i);
            assert_eq!(d.voltage(-i), -u);
            let back = d.current(u);
            assert!(((back - i) / i).abs() < 1e-12, "i = {i}: {back}");
            assert_eq!(d.current(-u), -back);
        }
        // 1N4148: about 0.7 V near 5 mA (the paper's turn-on voltage).
        let u5 = d.voltage(5e-3);
        assert!(u5 > 0.6 && u5 < 0.75, "{u5}");
        assert_eq!(d.current(0.0), 0.0);
    }

    #[test]
    fn differential_resistance_matches_finite_difference() {
        let d = DiodePair::one_n4148();
        for i in [0.0f64, 1e-9, 1e-6, 1e-3, 0.05] {
            let h = 1e-6 * (i.abs() + 1e-9);
            let fd = (d.voltage(i + h) - d.voltage(i - h)) / (2.0 * h);
            let r = d.differential_resistance(i);
            assert!(((fd - r) / r).abs() < 1e-6, "i = {i}: {fd} vs {r}");
        }
    }

    #[test]
    fn dimensionless_law_is_the_physical_law_rescaled() {
        let d = DiodePair::one_n4148();
        let (ut, z) = (0.7, (11.5e-3f64 / 0.02e-6).sqrt());
        let law = d.law(ut, z).unwrap();
        for v in [-3.0, -1e-4, 0.0, 2e-6, 0.3, 7.0] {
            let physical = d.voltage(v * ut / z) / ut;
            assert!((law.value(v) - physical).abs() < 1e-14, "v = {v}");
        }
        assert!((law.scale - 0.070_43).abs() < 1e-4);
        assert!((law.knee - 9.43e-6).abs() < 1e-8);
        // The fused evaluation agrees with the separate ones.
        for v in [
            0.0, -0.0, 1e-300, -3e-7, 4.7e-6, 4.72e-6, 9e-6, 1e-3, -0.4, 12.0, 1e200,
        ] {
            let (value, slope) = law.value_and_slope(v);
            assert!(
                (value - law.value(v)).abs() <= 4e-16 * law.value(v).abs(),
                "v = {v}"
            );
            assert!(
                (slope - law.slope(v)).abs() <= 4e-16 * law.slope(v),
                "v = {v}"
            );
        }
        // The derivative against a finite difference, including the knee.
        for v in [0.0f64, 1e-6, -5e-5, 0.2] {
            let h = 1e-4 * (v.abs() + law.knee);
            let fd = (law.value(v + h) - law.value(v - h)) / (2.0 * h);
            assert!(((fd - law.slope(v)) / law.slope(v)).abs() < 1e-7);
        }
    }

    #[test]
    fn pwl_limit_has_unit_junction_voltage_at_the_turn_on_current() {
        for a in [0.07, 0.02, 0.005] {
            let law = DiodeLaw::pwl_limit(a, 0.5, 0.004).unwrap();
            assert!((law.value(0.5) - 1.0 - 0.004 * 0.5).abs() < 1e-12);
            assert!((law.current_at(1.0) - 0.5).abs() < 1e-12);
        }
        assert!(DiodeLaw::pwl_limit(1e-3, 0.5, 0.0).is_err());
    }

    #[test]
    fn rejects_bad_values_naming_the_field() {
        let cases = [
            (DiodePair::new(0.0, 1.9, 0.6, 27.0), "Is"),
            (DiodePair::new(1e-9, f64::NAN, 0.6, 27.0), "n"),
            (DiodePair::new(1e-9, 1.9, -1.0, 27.0), "Rs"),
            (DiodePair::new(1e-9, 1.9, 0.6, -300.0), "temperature"),
        ];
        for (result, field) in cases {
            match result {
                Err(crate::Error::InvalidParameter { name, .. }) => assert_eq!(name, field),
                other => panic!("expected an error for {field}, got {other:?}"),
            }
        }
    }

    /// The junction step in its plain form: u = a·asinh(V/ε), the edge a·asinh(edge/ε).
    fn junction_step_reference(law: &DiodeLaw, v: f64, delta: f64, diagonal: f64) -> f64 {
        let a = law.scale;
        let u = a * (v / law.knee).asinh();
        let mut target = u + delta;
        let edge_current = ((a / diagonal).powi(2) - law.knee * law.knee)
            .max(0.0)
            .sqrt();
        let edge = a * (edge_current / law.knee).asinh();
        if target.abs() > edge && target.abs() > u.abs() {
            let excess = target.abs() - edge.max(u.abs());
            target = target.signum() * (edge.max(u.abs()) + a * (1.0 + excess / a).ln());
        }
        law.knee * (target / a).sinh()
    }

    #[test]
    fn junction_step_matches_its_plain_form() {
        let law = DiodeLaw::new(0.0704, 9.4e-6, 8.5e-4).unwrap();
        for &v in &[0.0, 1e-9, -3e-7, 4e-6, -2e-5, 1e-4, -3e-3, 0.02, -0.4] {
            for &delta in &[-0.3, -0.05, -1e-3, -1e-6, 0.0, 2e-6, 4e-3, 0.07, 0.5] {
                for &diagonal in &[0.5, 30.0, 700.0, 5e3, 1e5] {
                    let (value, _) = law.value_and_slope(v);
                    let fast = junction_step(&law, v, value, delta, diagonal);
                    let plain = junction_step_reference(&law, v, delta, diagonal);
                    let scale = plain.abs().max(law.knee);
                    let err = (fast - plain).abs() / scale;
                    assert!(
                        err < 1e-9,
                        "v {v} delta {delta} diagonal {diagonal}: {fast} vs {plain}"
                    );
                }
            }
        }
    }
}
