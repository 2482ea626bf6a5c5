//! The parameter sensitivities of the exact solution on a Coulomb belt (vb ≠ 0): the
//! derivatives of the strobe map and of the periodic orbit by (ζ, β, w, φ, μs), and of the
//! strobe map by vb, against Richardson-extrapolated central differences of the map and of
//! the orbits themselves, on forced belts that stick and slip (stops moving with the belt,
//! releases where β cos − y − 2ζ vb reaches ±μs), at strobes that fall in a slide and in a
//! stop.

use stickslip::solver::run_until;
use stickslip::stability::{
    find_periodic_orbit, periodic_orbit_sensitivity, strobe_map, strobe_map_parameter_derivative,
    strobe_map_parameter_derivatives, NewtonOptions, PeriodicOrbit,
};
use stickslip::{ExactSolver, Parameter, Params, Solver, State};
use stickslip_testkit::differences::richardson;

fn belt(zeta: f64, w: f64, beta: f64, mu_s: f64, vb: f64, phi: f64) -> Params {
    let mut p = Params::new(zeta, w, beta)
        .unwrap()
        .with_mu_s(mu_s)
        .unwrap()
        .with_phi(phi)
        .unwrap();
    p.vb = vb;
    p.validate().unwrap()
}

/// The parameters (ζ, β, w, φ, μs, vb) by index, in the sensitivities' order (vb last).
fn shifted(params: &Params, index: usize, d: f64) -> Params {
    let mut p = *params;
    match index {
        0 => p.zeta += d,
        1 => p.beta += d,
        2 => p.w += d,
        3 => p.phi += d,
        4 => p.mu_s += d,
        _ => p.vb += d,
    }
    p
}

const NAMES: [&str; 6] = ["zeta", "beta", "w", "phi", "mu_s", "vb"];

/// d f(p)/dp_index by [`richardson`] differences in the parameter.
fn differences<const N: usize>(
    params: &Params,
    index: usize,
    h: f64,
    f: impl Fn(&Params) -> [f64; N],
) -> [f64; N] {
    richardson(|d| f(&shifted(params, index, d)), 0.0, h)
}

/// The settled state 400 drive periods after rest.
fn settled(params: &Params) -> State {
    let mut solver = ExactSolver::new(*params, State::default());
    run_until(&mut solver, 400.0 * params.drive_period(), |_| {}).unwrap();
    solver.state()
}

/// Forced belts that settle on period-1 stick-slip orbits, each at drive phases that put the
/// strobe in a slide and in a stop; one of them reverses its slip without a stop (a turn).
fn stick_slip_orbits() -> Vec<(Params, PeriodicOrbit)> {
    let cases = [
        (0.05, 0.5, 1.0, 1.5, 0.3),
        (0.1, 0.7, 1.5, 1.3, 0.2),
        (0.05, 0.4, 2.0, 1.5, 0.2),
        (0.08, 0.3, 1.2, 1.4, -0.25),
        (0.1, 0.6, 3.0, 1.3, 0.5),
    ];
    let mut out = Vec::new();
    for (zeta, w, beta, mu_s, vb) in cases {
        for phi in [0.0, 1.3, 2.6, 3.9, 5.2] {
            let params = belt(zeta, w, beta, mu_s, vb, phi);
            let orbit =
                find_periodic_orbit(&params, settled(&params), 1, &NewtonOptions::default())
                    .unwrap_or_else(|e| panic!("{params:?}: {e}"));
            if !orbit.stops.is_empty() {
                out.push((params, orbit));
            }
        }
    }
    let stuck = out.iter().filter(|(_, o)| o.stuck_at_strobe).count();
    let turning = out.iter().any(|(_, o)| {
        o.events
            .iter()
            .any(|e| e.kind == stickslip::EventKind::Turn)
    });
    assert!(turning, "a stick-slip orbit with a reversal of the slip");
    assert!(
        stuck >= 2 && out.len() - stuck >= 2,
        "{} stick-slip orbits, {stuck} stuck at the strobe",
        out.len()
    );
    out
}

fn image(params: &Params, x: State) -> [f64; 2] {
    let s = strobe_map(params, x, 1).unwrap().state;
    [s.y, s.v]
}

#[test]
fn the_strobe_maps_parameter_derivatives_on_a_belt_match_differences() {
    for (params, orbit) in stick_slip_orbits() {
        let x = orbit.state;
        let exact = strobe_map_parameter_derivatives(&params, x, 1).unwrap();
        let scale = 1.0 + exact.iter().flatten().fold(0.0f64, |a, b| a.max(b.abs()));
        for index in 0..6 {
            // From a state stuck to the belt, vb moves the state too (y' = vb): the derivative
            // along the stuck states, as the continuation in vb follows a stuck strobe.
            let along = orbit.stuck_at_strobe && index == 5;
            let fd = differences(&params, index, 1e-5, |p| {
                image(p, if along { State { y: x.y, v: p.vb } } else { x })
            });
            let d = if index < 5 {
                [exact[0][index], exact[1][index]]
            } else {
                strobe_map_parameter_derivative(&params, x, 1, Parameter::Vb).unwrap()
            };
            for r in 0..2 {
                assert!(
                    (d[r] - fd[r]).abs() <= 1e-6 * scale,
                    "{params:?} at {x:?} (stuck {}): d/d{} = {d:?}, differences {fd:?}",
                    orbit.stuck_at_strobe,
                    NAMES[index]
                );
            }
        }
        // The single-parameter form agrees with the matrix for the paper's parameters.
        for (parameter, index) in [
            (Parameter::Zeta, 0),
            (Parameter::Beta, 1),
            (Parameter::W, 2),
            (Parameter::MuS, 4),
        ] {
            let d = strobe_map_parameter_derivative(&params, x, 1, parameter).unwrap();
            assert_eq!(d, [exact[0][index], exact[1][index]], "{parameter:?}");
        }
    }
}

/// y at `taus` along the period-1 orbit of `params` near `guess`.
fn orbit_samples<const N: usize>(params: &Params, guess: State, taus: &[f64; N]) -> [f64; N] {
    let options = NewtonOptions {
        tolerance: 1e-14,
        ..NewtonOptions::default()
    };
    let orbit = find_periodic_orbit(params, guess, 1, &options).unwrap();
    let mut solver = ExactSolver::new(*params, orbit.state);
    let mut out = [0.0; N];
    for (o, &tau) in out.iter_mut().zip(taus) {
        run_until(&mut solver, tau, |_| {}).unwrap();
        *o = solver.state().y;
    }
    out
}

#[test]
fn the_periodic_orbits_sensitivities_on_a_belt_match_differences() {
    for (params, orbit) in stick_slip_orbits() {
        let t = params.drive_period();
        let taus = [0.0, 0.17 * t, 0.41 * t, 0.66 * t, 0.93 * t];
        let samples = periodic_orbit_sensitivity(&params, orbit.state, 1, &taus).unwrap();
        let scale = 1.0
            + samples
                .iter()
                .flat_map(|s| s.dy)
                .fold(0.0f64, |a, b| a.max(b.abs()));
        for index in 0..5 {
            let fd = differences(&params, index, 1e-5, |p| {
                orbit_samples(p, orbit.state, &taus)
            });
            for (s, fd) in samples.iter().zip(fd) {
                assert!(
                    (s.dy[index] - fd).abs() <= 1e-6 * scale,
                    "{params:?} (stuck at the strobe {}): dy({})/d{} = {}, differences {fd}",
                    orbit.stuck_at_strobe,
                    s.tau,
                    NAMES[index],
                    s.dy[index]
                );
            }
        }
    }
}
