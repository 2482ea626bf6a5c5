//! The circuit as a SPICE netlist, for cross-checks in ngspice or any SPICE.
//!
//! ```text
//! V1 drive 0 SIN(0 U f 0 0 φ+90°)      U cos(Ω t + φ) = U sin(Ω t + φ + 90°)
//! R1 drive n1 R
//! L1 n1 n2 L IC=i(0)
//! D1 n2 uc DPAIR                        the two diodes, anti-parallel, with the same .model
//! D2 uc n2 DPAIR
//! C1 uc 0 C IC=u_C(0)
//! .model DPAIR D(IS=I_s N=n RS=R_s)
//! .options temp=T tnom=T                I_s is taken as given at T: no temperature scaling
//! .tran Δt t_stop 0 Δt_max uic
//! ```
//!
//! The `.model` has no junction capacitance, transit time or breakdown (SPICE defaults:
//! CJO = 0, TT = 0, BV = ∞), so it is the Shockley law with series resistance and nothing else.
//! SPICE also adds its GMIN (10⁻¹² S by default) across each junction, about 10⁻⁵ of the
//! diodes' own conductance at zero current. The node `uc` is the capacitor voltage u_C and
//! i(L1) the loop current i, both with the sign conventions of the crate.
//!
//! The generator is a pure function returning the text; it does no I/O.

use crate::error::{Error, Result, Unsupported};
use crate::options::OptionKey;
use crate::params::{Params, State};
use crate::physical::{Circuit, Diode};
use serde::{Deserialize, Serialize};
use std::fmt::Write;

/// What the netlist asks SPICE to do. Tolerances left at `None` are not written (SPICE's
/// defaults apply: reltol = 1e-3, abstol = 1e-12 A, vntol = 1e-6 V).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct NetlistOptions {
    /// Simulated time in drive periods (> 0). Default 300.
    pub periods: f64,
    /// Output points per drive period: `.tran`'s print step is the period over this. Default
    /// 200.
    pub points_per_period: u32,
    /// The largest time step, as a fraction of the drive period (`.tran`'s Δt_max).
    /// Default 1/1000.
    pub max_step_fraction: f64,
    /// `.options reltol`. Default None.
    pub reltol: Option<f64>,
    /// `.options abstol` in amperes. Default None.
    pub abstol: Option<f64>,
    /// `.options vntol` in volts. Default None.
    pub vntol: Option<f64>,
    /// When set, an ngspice `.control` block runs the analysis and writes time, u_C and i
    /// with `wrdata` to this file (15 digits), then quits; when None, a portable
    /// `.print tran v(uc) i(L1)` line is written instead. Default None.
    pub wrdata: Option<String>,
}

impl Default for NetlistOptions {
    fn default() -> Self {
        Self {
            periods: 300.0,
            points_per_period: 200,
            max_step_fraction: 1e-3,
            reltol: None,
            abstol: None,
            vntol: None,
            wrdata: None,
        }
    }
}

/// Shortest text that reads back as the same number, in exponent form (no SPICE scale
/// suffixes, which would be ambiguous: `m` is milli, `M` too).
fn number(x: f64) -> String {
    format!("{x:e}")
}

impl NetlistOptions {
    /// Check every field against the option table ([`OptionKey::NetlistPeriods`] and the
    /// rows after it).
    ///
    /// # Errors
    /// [`Error::InvalidOption`] naming the first bad field: periods ≤ 0, no output points, a
    /// step fraction outside (0, 1], a tolerance ≤ 0, or a `wrdata` file name that is empty
    /// or contains white space or a quote.
    pub fn validate(&self) -> Result<()> {
        OptionKey::NetlistPeriods.check(self.periods)?;
        OptionKey::NetlistPoints.check(f64::from(self.points_per_period))?;
        OptionKey::NetlistMaxStep.check(self.max_step_fraction)?;
        for (key, value) in [
            (OptionKey::NetlistReltol, self.reltol),
            (OptionKey::NetlistAbstol, self.abstol),
            (OptionKey::NetlistVntol, self.vntol),
        ] {
            if let Some(x) = value {
                key.check(x)?;
            }
        }
        if let Some(file) = &self.wrdata {
            if file.is_empty() || file.contains(|c: char| c.is_whitespace() || c == '"') {
                return Err(OptionKey::NetlistWrdata.invalid(f64::NAN));
            }
        }
        Ok(())
    }
}

/// The SPICE netlist of `circuit` driven by U cos(Ω t + φ) with U = β U_t, Ω = w ω0 and φ
/// from `params` (its ζ and μs are not used: the circuit's parts decide the damping), started
/// from `initial` (dimensionless: u_C(0) = y0·U_t, i(0) = v0·U_t/√(L/C)).
///
/// # Errors
/// [`Error::Unsupported`] for a circuit with PWL diodes;
/// [`crate::Error::InvalidParameter`] when the circuit, the parameters or the initial state
/// is invalid; [`crate::Error::InvalidOption`] for an option
/// ([`NetlistOptions::validate`]).
pub fn netlist(
    circuit: &Circuit,
    params: &Params,
    initial: State,
    options: &NetlistOptions,
) -> Result<String> {
    let c = circuit.validate()?;
    let Diode::Shockley(shockley) = c.diode else {
        return Err(Error::Unsupported(Unsupported::NetlistNeedsShockley));
    };
    let p = params.validate()?;
    let initial = State::new(initial.y, initial.v)?;
    options.validate()?;

    let s = c.scales();
    let amplitude = s.drive_amplitude(p.beta);
    let omega = s.drive_omega(p.w);
    let freq = omega / std::f64::consts::TAU;
    let period = 1.0 / freq;
    let phase_deg = (p.phi.to_degrees() + 90.0).rem_euclid(360.0);
    let uc0 = initial.y * s.position;
    let i0 = initial.v * s.velocity;
    let d = &shockley.pair;

    let mut n = String::new();
    // `write!` into a String cannot fail.
    let mut line = |text: String| {
        n.push_str(&text);
        n.push('\n');
    };
    line("* stickslip: series RLC circuit damped by two anti-parallel Shockley diodes".into());
    line(format!(
        "* L q'' + R q' + q/C + U_D(q') = U cos(Omega t + phi), U_D(i) = n V_T asinh(i/(2 I_s)) \
         + R_s i, V_T = {} V",
        number(d.thermal_voltage())
    ));
    line(format!(
        "* dimensionless: zeta_R = {}, w = {}, beta = {} (U_t = {} V), phi = {} rad, \
         f0 = {} Hz",
        number(s.zeta()),
        number(p.w),
        number(p.beta),
        number(shockley.reference_voltage),
        number(p.phi),
        number(s.f0())
    ));
    line(format!(
        "V1 drive 0 SIN(0 {} {} 0 0 {})",
        number(amplitude),
        number(freq),
        number(phase_deg)
    ));
    let l_node = if c.resistance > 0.0 {
        line(format!("R1 drive n1 {}", number(c.resistance)));
        "n1"
    } else {
        "drive"
    };
    line(format!(
        "L1 {l_node} n2 {} IC={}",
        number(c.inductance),
        number(i0)
    ));
    line("D1 n2 uc DPAIR".into());
    line("D2 uc n2 DPAIR".into());
    line(format!(
        "C1 uc 0 {} IC={}",
        number(c.capacitance),
        number(uc0)
    ));
    line(format!(
        ".model DPAIR D(IS={} N={} RS={})",
        number(d.saturation_current),
        number(d.emission),
        number(d.series_resistance)
    ));
    let mut opts = format!(
        ".options temp={} tnom={}",
        number(d.temperature),
        number(d.temperature)
    );
    for (name, value) in [
        ("reltol", options.reltol),
        ("abstol", options.abstol),
        ("vntol", options.vntol),
    ] {
        if let Some(x) = value {
            let _ = write!(opts, " {name}={}", number(x));
        }
    }
    line(opts);
    line(format!(
        ".tran {} {} 0 {} uic",
        number(period / options.points_per_period as f64),
        number(options.periods * period),
        number(period * options.max_step_fraction)
    ));
    match &options.wrdata {
        Some(file) => {
            line(".control".into());
            line("set wr_singlescale".into());
            line("set numdgt=15".into());
            line("run".into());
            line(format!("wrdata {file} v(uc) i(L1)"));
            line("quit".into());
            line(".endc".into());
        }
        None => line(".print tran v(uc) i(L1)".into()),
    }
    line(".end".into());
    Ok(n)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn paper_netlist_has_the_parts_and_the_drive() {
        let c = Circuit::paper_shockley();
        let p = Params::new(0.0, 0.95, 2.14).unwrap();
        let text = netlist(&c, &p, State::default(), &NetlistOptions::default()).unwrap();
        let f = 0.95 * c.scales().f0();
        assert!(text.contains(&format!(
            "V1 drive 0 SIN(0 {} {} 0 0 9e1)",
            number(1.498),
            number(f)
        )));
        assert!(text.contains("R1 drive n1 6.8e1\n"));
        assert!(text.contains("L1 n1 n2 1.15e-2 IC=0e0\n"));
        assert!(text.contains("D1 n2 uc DPAIR\nD2 uc n2 DPAIR\n"));
        assert!(text.contains("C1 uc 0 2e-8 IC=0e0\n"));
        assert!(text.contains(".model DPAIR D(IS=4.352e-9 N=1.906e0 RS=6.458e-1)\n"));
        assert!(text.contains(".options temp=2.7e1 tnom=2.7e1\n"));
        assert!(text.contains(".print tran v(uc) i(L1)\n"));
        assert!(text.ends_with(".end\n"));
    }

    #[test]
    fn initial_state_phase_and_options() {
        let c = Circuit::paper_shockley();
        let p = Params::new(0.0, 0.5, 1.0)
            .unwrap()
            .with_phi(std::f64::consts::FRAC_PI_2)
            .unwrap();
        let o = NetlistOptions {
            reltol: Some(1e-6),
            vntol: Some(1e-9),
            wrdata: Some("out.txt".into()),
            ..Default::default()
        };
        let text = netlist(&c, &p, State { y: 1.0, v: -0.5 }, &o).unwrap();
        assert!(text.contains(" 0 0 1.8e2)\n"), "{text}");
        assert!(text.contains("C1 uc 0 2e-8 IC=7e-1\n"));
        let i0 = -0.5 * 0.7 / c.impedance();
        assert!(text.contains(&format!("IC={}\n", number(i0))));
        assert!(text.contains("reltol=1e-6 vntol=1e-9\n"));
        assert!(text.contains("wrdata out.txt v(uc) i(L1)\n"));
        assert!(!text.contains(".print"));
    }

    #[test]
    fn zero_resistance_connects_the_source_to_the_inductor() {
        let c = Circuit {
            resistance: 0.0,
            ..Circuit::paper_shockley()
        };
        let p = Params::new(0.0, 1.0, 1.0).unwrap();
        let text = netlist(&c, &p, State::default(), &NetlistOptions::default()).unwrap();
        assert!(!text.contains("R1"));
        assert!(text.contains("L1 drive n2 "));
    }

    #[test]
    fn a_pwl_circuit_has_no_netlist() {
        let p = Params::new(0.0, 1.0, 1.0).unwrap();
        let r = netlist(
            &Circuit::paper(),
            &p,
            State::default(),
            &NetlistOptions::default(),
        );
        assert_eq!(
            r,
            Err(Error::Unsupported(Unsupported::NetlistNeedsShockley))
        );
    }

    #[test]
    fn rejects_bad_options() {
        let c = Circuit::paper_shockley();
        let p = Params::new(0.0, 1.0, 1.0).unwrap();
        let bad = [
            NetlistOptions {
                periods: 0.0,
                ..Default::default()
            },
            NetlistOptions {
                points_per_period: 0,
                ..Default::default()
            },
            NetlistOptions {
                max_step_fraction: 2.0,
                ..Default::default()
            },
            NetlistOptions {
                reltol: Some(-1.0),
                ..Default::default()
            },
            NetlistOptions {
                wrdata: Some("a\"b".into()),
                ..Default::default()
            },
        ];
        for o in bad {
            let e = netlist(&c, &p, State::default(), &o).unwrap_err();
            assert!(e.option().is_some(), "{o:?}: {e}");
        }
        let e = NetlistOptions {
            wrdata: Some("a b".into()),
            ..Default::default()
        }
        .validate()
        .unwrap_err();
        assert_eq!(
            e.render(crate::Spelling::Flag),
            "invalid --wrdata: must be a file name without spaces, quotes or line breaks"
        );
    }
}
