//! The stability tools on a Coulomb belt (vb ≠ 0): the strobe map's Jacobian from the exact
//! segments and saltation matrices against Richardson-extrapolated central differences of the
//! map itself, at a sliding orbit and at stick-slip orbits; and the Stribeck and cubic laws
//! refused by every entry point, never a panic.

use stickslip::friction::FrictionLaw;
use stickslip::stability::{
    find_periodic_orbit, lyapunov_exponents, strobe_map, LyapunovOptions, NewtonOptions,
};
use stickslip::{Error, Params, Solver, State, Unsupported};
use stickslip_testkit::differences::state_jacobian;

fn belt(zeta: f64, w: f64, beta: f64, mu_s: f64, vb: f64) -> Params {
    let mut p = Params::new(zeta, w, beta).unwrap().with_mu_s(mu_s).unwrap();
    p.vb = vb;
    p.validate().unwrap()
}

/// The image of the 1-fold strobe map.
fn image(params: &Params, x: State) -> [f64; 2] {
    let s = strobe_map(params, x, 1).unwrap().state;
    [s.y, s.v]
}

/// The settled state 400 drive periods after rest.
fn settled(params: &Params) -> State {
    let mut solver = stickslip::ExactSolver::new(*params, State::default());
    stickslip::solver::run_until(&mut solver, 400.0 * params.drive_period(), |_| {}).unwrap();
    solver.state()
}

#[test]
fn the_coulomb_belts_monodromy_matches_differences_of_the_strobe_map() {
    // (ζ, w, β, μs, vb): forced belts that settle on period-1 orbits; the test asserts that
    // they include a sliding orbit with turns and stick-slip orbits (stops and releases).
    let cases = [
        (0.05, 1.0, 2.0, 1.5, 0.5),
        (0.05, 0.5, 1.0, 1.5, 0.3),
        (0.1, 0.7, 1.5, 1.3, 0.2),
        (0.05, 0.4, 2.0, 1.5, 0.2),
        (0.02, 1.2, 3.0, 1.2, 0.4),
    ];
    let (mut sliding, mut sticking) = (0, 0);
    for (zeta, w, beta, mu_s, vb) in cases {
        let params = belt(zeta, w, beta, mu_s, vb);
        let guess = settled(&params);
        let orbit = match find_periodic_orbit(&params, guess, 1, &NewtonOptions::default()) {
            Ok(o) => o,
            Err(e) => panic!("{params:?}: {e}"),
        };
        if orbit.stuck_at_strobe {
            continue;
        }
        let fd = state_jacobian(|x| image(&params, x), orbit.state, 1e-5);
        let m = orbit.monodromy.0;
        let scale = m.iter().flatten().fold(1.0f64, |a, b| a.max(b.abs()));
        for i in 0..2 {
            for j in 0..2 {
                assert!(
                    (m[i][j] - fd[i][j]).abs() <= 1e-6 * scale,
                    "{params:?}: M = {m:?}, differences {fd:?}"
                );
            }
        }
        if orbit.stops.is_empty() {
            sliding += usize::from(!orbit.events.is_empty());
        } else {
            sticking += 1;
        }
    }
    assert!(
        sliding >= 1 && sticking >= 1,
        "sliding {sliding}, sticking {sticking}"
    );
}

#[test]
fn the_stribeck_and_cubic_laws_are_refused_by_the_exact_tools() {
    let laws = [
        FrictionLaw::Stribeck {
            vs: 0.3,
            delta: 2.0,
            eta: 0.0,
        },
        FrictionLaw::Cubic { k1: 0.5, k3: 0.5 },
    ];
    for law in laws {
        let mut params = belt(0.05, 1.0, 2.0, 1.5, 0.5);
        params.law = law;
        let refused = |r: Result<(), Error>| {
            assert!(
                matches!(r, Err(Error::Unsupported(Unsupported::SmoothFrictionLaw))),
                "{r:?}"
            )
        };
        refused(strobe_map(&params, State::default(), 1).map(|_| ()));
        refused(
            find_periodic_orbit(&params, State::default(), 1, &NewtonOptions::default())
                .map(|_| ()),
        );
        let options = LyapunovOptions {
            transient_periods: 10,
            periods: 40,
            ..Default::default()
        };
        refused(lyapunov_exponents(&params, State::default(), &options).map(|_| ()));
    }
}
