//! The stability tools of the smooth friction laws (Stribeck, cubic) on a forced belt
//! ([`FrictionDynamics`]): the monodromy matrix of Newton's periodic orbits, from the stiff
//! integrator's own sensitivities, stick phases and saltation matrices, against
//! Richardson-extrapolated central differences of the strobe map itself (the friction solver
//! at its 10⁻¹² tolerance), at sliding orbits with reversals and at stick-slip orbits; and
//! the largest Lyapunov exponent measured on the tangent dynamics against ln|μ1|/T.

use stickslip::friction::FrictionLaw;
use stickslip::stability::{
    FrictionDynamics, LyapunovOptions, Matrix2, NewtonOptions, PeriodicOrbit,
};
use stickslip::{EventKind, Parameter, Params, State};
use stickslip_testkit::differences::{richardson, state_jacobian};

const STRIBECK: FrictionLaw = FrictionLaw::Stribeck {
    vs: 0.3,
    delta: 2.0,
    eta: 0.05,
};
const CUBIC: FrictionLaw = FrictionLaw::Cubic { k1: 0.5, k3: 0.5 };

/// (ζ, w, β, μs, vb).
type Case = (f64, f64, f64, f64, f64);

fn belt(law: FrictionLaw, (zeta, w, beta, mu_s, vb): Case) -> Params {
    let mut p = Params::new(zeta, w, beta).unwrap().with_mu_s(mu_s).unwrap();
    p.vb = vb;
    p.law = law;
    p.validate().unwrap()
}

/// The image of the 1-fold strobe map.
fn image(params: &Params, x: State) -> [f64; 2] {
    let s = FrictionDynamics::new()
        .strobe_map(params, x, 1)
        .unwrap()
        .state;
    [s.y, s.v]
}

/// The period-1 orbit the motion from rest settles on.
fn settled_orbit(params: &Params) -> PeriodicOrbit {
    let dynamics = FrictionDynamics::new();
    let mut solver = dynamics.plain_solver(params, State::default()).unwrap();
    stickslip::solver::run_until(&mut solver, 200.0 * params.drive_period(), |_| {}).unwrap();
    use stickslip::Solver;
    dynamics
        .find_periodic_orbit(params, solver.state(), 1, &NewtonOptions::default())
        .unwrap()
}

/// The cases: (law, (ζ, w, β, μs, vb), sticks). Period-1 orbits whose strobe falls in a slip
/// phase; the sliding ones reverse twice a period, the stick-slip ones stop twice.
fn cases() -> Vec<(FrictionLaw, Case, bool)> {
    vec![
        (STRIBECK, (0.05, 1.0, 2.0, 1.5, 0.5), false),
        // (A complex pair of multipliers.)
        (STRIBECK, (0.05, 1.2, 2.5, 1.5, 0.2), false),
        (STRIBECK, (0.1, 0.7, 1.5, 1.5, 0.3), true),
        (CUBIC, (0.05, 1.0, 6.0, 1.5, 0.3), false),
        (CUBIC, (0.05, 1.0, 2.0, 1.5, 0.5), true),
    ]
}

/// The multipliers sorted by modulus, then by their real part.
fn sorted(m: &Matrix2) -> Vec<(f64, f64)> {
    let mut v: Vec<(f64, f64)> = m.eigenvalues().iter().map(|u| (u.re, u.im.abs())).collect();
    v.sort_by(|a, b| {
        (b.0.hypot(b.1), b.0)
            .partial_cmp(&(a.0.hypot(a.1), a.0))
            .unwrap()
    });
    v
}

#[test]
fn the_monodromy_matches_richardson_differences_of_the_strobe_map() {
    for (law, case, sticks) in cases() {
        let params = belt(law, case);
        let orbit = settled_orbit(&params);
        let kinds: Vec<EventKind> = orbit.events.iter().map(|e| e.kind).collect();
        assert!(!orbit.stuck_at_strobe, "{law:?} {case:?}");
        if sticks {
            assert!(
                kinds.contains(&EventKind::Stick) && kinds.contains(&EventKind::Slip),
                "{law:?} {case:?}: {kinds:?}"
            );
        } else {
            assert!(
                kinds.len() == 2 && kinds.iter().all(|k| *k == EventKind::Turn),
                "{law:?} {case:?}: {kinds:?}"
            );
        }
        let fd = Matrix2(state_jacobian(|x| image(&params, x), orbit.state, 1e-5));
        let m = orbit.monodromy;
        let mut worst = 0.0f64;
        for i in 0..2 {
            for j in 0..2 {
                worst = worst.max((m.0[i][j] - fd.0[i][j]).abs());
            }
        }
        let (a, b) = (sorted(&m), sorted(&fd));
        let mut worst_multiplier = 0.0f64;
        for k in 0..2 {
            worst_multiplier = worst_multiplier.max((a[k].0 - b[k].0).hypot(a[k].1 - b[k].1));
        }
        println!(
            "{law:?} {case:?}: multipliers {a:?}, |M - differences| {worst:.1e}, \
             multipliers {worst_multiplier:.1e}"
        );
        assert!(
            worst <= 1e-6,
            "{law:?} {case:?}: M = {m:?}, differences {fd:?}"
        );
        assert!(
            worst_multiplier <= 1e-6,
            "{law:?} {case:?}: multipliers {a:?}, of the differences {b:?}"
        );
        // The orbit's own multipliers are those of its monodromy matrix.
        let mu = orbit.multipliers[0];
        assert!((mu.re.hypot(mu.im) - a[0].0.hypot(a[0].1)).abs() <= 1e-12);
        if sticks {
            assert_eq!(orbit.multipliers[1].modulus(), 0.0, "a stop erases δy'");
        }
    }
}

#[test]
fn the_measured_exponent_at_a_periodic_point_is_ln_mu1_over_t() {
    let options = LyapunovOptions {
        transient_periods: 20,
        periods: 100,
        ..Default::default()
    };
    for (law, case, _) in cases() {
        let params = belt(law, case);
        let orbit = settled_orbit(&params);
        if orbit.multipliers[0].im != 0.0 {
            // (A complex pair rotates the tangent: its growth per period oscillates.)
            continue;
        }
        let measured = FrictionDynamics::new()
            .lyapunov_exponents(&params, orbit.state, &options, &())
            .unwrap();
        let expected = orbit.exponent();
        let error = (measured.largest.per_tau - expected).abs();
        println!("{law:?} {case:?}: λ1 {expected:.12}, measured off by {error:.1e}");
        assert!(
            error <= 1e-6,
            "{law:?} {case:?}: measured {}, ln|μ1|/T = {expected}",
            measured.largest.per_tau
        );
    }
}

/// ∂P/∂λ by central differences of the strobe map with steps h and h/2, extrapolated.
fn richardson_parameter(params: &Params, x: State, parameter: Parameter, h: f64) -> [f64; 2] {
    let at = |value: f64| image(&parameter.set(*params, value).unwrap(), x);
    richardson(at, parameter.get(params), h)
}

#[test]
fn the_parameter_derivatives_match_richardson_differences_of_the_strobe_map() {
    let dynamics = FrictionDynamics::new();
    for (law, case, _) in cases() {
        let params = belt(law, case);
        let orbit = settled_orbit(&params);
        let own: &[Parameter] = match law {
            FrictionLaw::Stribeck { .. } => &[Parameter::Vs, Parameter::Delta, Parameter::Eta],
            _ => &[Parameter::K1, Parameter::K3],
        };
        let common = [
            Parameter::Zeta,
            Parameter::W,
            Parameter::Beta,
            Parameter::MuS,
            Parameter::Vb,
        ];
        for &parameter in common.iter().chain(own) {
            let d = dynamics
                .strobe_parameter_derivative(&params, orbit.state, 1, parameter)
                .unwrap();
            let fd = richardson_parameter(&params, orbit.state, parameter, 1e-5);
            let error = (d[0] - fd[0]).abs().max((d[1] - fd[1]).abs());
            let scale = 1f64.max(fd[0].abs()).max(fd[1].abs());
            println!(
                "{law:?} {case:?} {}: {d:?}, differences {fd:?}, off by {error:.1e}",
                parameter.label()
            );
            assert!(
                error <= 1e-6 * scale,
                "{law:?} {case:?} {}: {d:?}, differences {fd:?}",
                parameter.label()
            );
        }
        // The state columns are the monodromy matrix.
        let (_, s) = dynamics
            .strobe_sensitivity(&params, orbit.state, 1)
            .unwrap();
        let m = orbit.monodromy.0;
        for (i, row) in s.state().iter().enumerate() {
            for (j, x) in row.iter().enumerate() {
                assert!((x - m[i][j]).abs() <= 1e-12 * 1f64.max(m[i][j].abs()));
            }
        }
    }
}
