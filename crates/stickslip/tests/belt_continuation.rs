//! Continuation in the belt speed vb of a forced Coulomb belt: the branch passes through the
//! steady states that a sweep over vb settles on, and a special point it locates (a grazing:
//! the stops per period change; a fold) lies where the sweep's stops or class change, and
//! only there. At two drive phases: one puts the strobe in a slide, the other in a stop (y' = vb
//! there, moving with the continued vb, the corrector solving for (y, vb) alone).

use stickslip::continuation::{
    continue_orbit, settled_orbit, Branch, BranchEnd, ContinuationOptions, Obstacle, SpecialKind,
};
use stickslip::scan::{Axis, ParameterRange, Sweep, SweepDirection, SweepPoint};
use stickslip::stability::{find_periodic_orbit, NewtonOptions};
use stickslip::steady::SteadyState;
use stickslip::{Experiment, Parameter, State};

/// A forced belt that sticks and slips at slow belt speeds and slides through at fast ones.
fn forced_belt(vb: f64, phi: f64) -> Experiment {
    Experiment::dimensionless(0.05, 0.5, 1.0)
        .and_then(|e| e.with_phi(phi))
        .and_then(|e| e.with_mu_s(1.5))
        .and_then(|e| e.with_vb(vb))
        .unwrap()
}

/// The branch's strobe state (y, y') and amplitude at `vb` by linear interpolation between the
/// two points that bracket it (the first such pair along the branch), with their stops.
fn on_branch(branch: &Branch, vb: f64) -> Option<([f64; 3], usize)> {
    branch.points.windows(2).find_map(|pair| {
        let (a, b) = (&pair[0], &pair[1]);
        let (lo, hi) = (a.value.min(b.value), a.value.max(b.value));
        if !(lo <= vb && vb <= hi) || a.stops != b.stops {
            return None;
        }
        let f = if hi > lo {
            (vb - a.value) / (b.value - a.value)
        } else {
            0.0
        };
        let (sa, sb) = (a.orbit.state, b.orbit.state);
        Some((
            [
                sa.y + f * (sb.y - sa.y),
                sa.v + f * (sb.v - sa.v),
                a.amplitude() + f * (b.amplitude() - a.amplitude()),
            ],
            a.stops,
        ))
    })
}

fn sweep(from: f64, to: f64, steps: usize, phi: f64) -> Vec<SweepPoint> {
    let range = ParameterRange::new("vb", from, to, steps).unwrap();
    Sweep::new(
        &forced_belt(from, phi),
        Axis::range(Parameter::Vb, &range).unwrap(),
    )
    .unwrap()
    .direction(SweepDirection::Up)
    .run(&())
    .unwrap()
}

#[test]
fn continuation_in_vb_passes_through_the_sweeps_steady_states() {
    let stuck = [0.0, 3.0].map(check_branch_against_sweep);
    assert_eq!(
        stuck,
        [true, false],
        "strobes stuck at φ = 0, sliding at φ = 3"
    );
}

/// Check the branch against the sweep at drive phase `phi`; whether its strobes are stuck.
fn check_branch_against_sweep(phi: f64) -> bool {
    let (from, to) = (0.2, 0.42);
    let (params, orbit) = settled_orbit(&forced_belt(from, phi)).unwrap();
    assert!(!orbit.stops.is_empty(), "a stick-slip start: {orbit:?}");
    let options = ContinuationOptions::default().with_max_step(0.02);
    let branch = continue_orbit(&params, Parameter::Vb, &orbit, to, &options, &()).unwrap();
    let last = branch.points.last().unwrap().value;
    assert!(
        (last - to).abs() < 1e-12,
        "the branch reaches vb = {to}: {last}, {} points, ends {:?}; start {:?}",
        branch.points.len(),
        branch.end,
        orbit
    );

    let steps = sweep(from, to, 12, phi);
    assert!(
        matches!(branch.end, BranchEnd::Boundary { .. }),
        "{:?}",
        branch.end
    );
    let mut matched = 0;
    for step in &steps {
        if step.steady.period != Some(1) {
            continue;
        }
        let Some((x, stops)) = on_branch(&branch, step.value) else {
            panic!("vb = {}: not on the branch", step.value);
        };
        let s = step.steady.strobes[0];
        assert!(
            (x[0] - s.y).abs() < 2e-3 && (x[1] - s.v).abs() < 2e-3,
            "vb = {}: branch {x:?}, sweep {s:?}",
            step.value
        );
        // The extremes inside the slides count (y' = 0 is no event on a belt).
        assert!(
            (x[2] - step.steady.amplitude()).abs() < 2e-3,
            "vb = {}: amplitude {} on the branch, {} swept",
            step.value,
            x[2],
            step.steady.amplitude()
        );
        assert_eq!(
            stops as f64, step.steady.stops_per_period,
            "vb = {}",
            step.value
        );
        matched += 1;
    }
    assert!(
        matched >= 5,
        "{matched} of the sweep's steady states on the branch"
    );

    // Every grazing or fold lies between two sweep steps whose stops or class differ, and
    // every change of the sweep's stops is a grazing or fold of the branch.
    let specials: Vec<_> = branch
        .special
        .iter()
        .filter(|s| matches!(s.kind, SpecialKind::Grazing | SpecialKind::Fold))
        .collect();
    for pair in steps.windows(2) {
        let (a, b) = (&pair[0].steady, &pair[1].steady);
        let changed = a.stops_per_period != b.stops_per_period || a.class != b.class;
        let located = specials
            .iter()
            .any(|s| pair[0].value < s.value && s.value < pair[1].value);
        assert_eq!(
            changed,
            located,
            "between vb = {} ({:?}, {} stops) and {} ({:?}, {} stops): specials {:?}",
            pair[0].value,
            a.class,
            a.stops_per_period,
            pair[1].value,
            b.class,
            b.stops_per_period,
            branch.special
        );
    }
    let stuck = branch
        .points
        .iter()
        .filter(|p| p.orbit.stuck_at_strobe)
        .count();
    assert!(
        stuck == 0 || stuck == branch.points.len(),
        "φ = {phi}: {stuck} of {} strobes stuck",
        branch.points.len()
    );
    stuck > 0
}

/// The forced belt of the second case: ζ = 0.1, w = 0.7, β = 1.5, μs = 1.3 at drive phase φ.
fn second_belt(vb: f64, phi: f64) -> Experiment {
    Experiment::dimensionless(0.1, 0.7, 1.5)
        .and_then(|e| e.with_phi(phi))
        .and_then(|e| e.with_mu_s(1.3))
        .and_then(|e| e.with_vb(vb))
        .unwrap()
}

/// The steady states `steady` settles on from rest at `values` of vb for the belt `model`.
fn steady_at(
    model: fn(f64, f64) -> Experiment,
    phi: f64,
    values: &[f64],
) -> Vec<(f64, SteadyState)> {
    values
        .iter()
        .map(|&vb| (vb, model(vb, phi).steady().unwrap()))
        .collect()
}

/// At φ = 0 the stop that ends each period of the second belt begins after the strobe below
/// vb ≈ 0.88100 and before it above: the strobe leaves a slide for the stop. The map is
/// continuous there (a state a little off the belt's speed sticks at once) but its derivative
/// in λ jumps (stuck, P's y' is vb itself), so the corrector takes ∂P/∂λ afresh and the
/// branch goes on through the kink, over the steady states on both sides. It ends at
/// vb ≈ 1.00853, named: a stop that begins at the static limit.
#[test]
fn a_stop_edge_crossing_the_strobe_is_passed() {
    let (params, orbit) = settled_orbit(&second_belt(0.5, 0.0)).unwrap();
    let options = ContinuationOptions::default().with_max_step(0.02);
    let branch = continue_orbit(&params, Parameter::Vb, &orbit, 1.2, &options, &()).unwrap();
    // It ends at vb ≈ 1.00853, where the stop that follows the drive's trough begins at the
    // static limit: past it the motion reverses there instead of sticking (the map jumps).
    let BranchEnd::Failed { value, obstacle } = branch.end else {
        panic!("{:?}", branch.end)
    };
    assert!((1.0084..1.0087).contains(&value), "ends at {value}");
    assert!(
        matches!(obstacle, Obstacle::TurnAtStaticLimit { margin, .. } if (-1e-2..0.0).contains(&margin)),
        "{obstacle:?}"
    );
    let stuck_from = branch
        .points
        .iter()
        .position(|p| p.orbit.stuck_at_strobe)
        .expect("stuck strobes past vb = 0.881");
    // Started from the branch's last state, `steady` stays on a period-1 orbit with two stops
    // just before the end and leaves for period-2 stick-slip just past it (from rest it
    // settles on period 2 on both sides: the branch's orbit coexists with it).
    let last = branch.points.last().unwrap().orbit.state;
    let from_last = |vb: f64| {
        second_belt(vb, 0.0)
            .with_initial(State { y: last.y, v: vb })
            .unwrap()
            .steady()
            .unwrap()
    };
    let (before, after) = (from_last(1.008), from_last(1.009));
    assert_eq!((before.period, before.stops_per_period), (Some(1), 2.0));
    assert_eq!(after.period, Some(2));
    let (slid, stuck) = (
        branch.points[stuck_from - 1].value,
        branch.points[stuck_from].value,
    );
    assert!(
        slid < 0.88100 && 0.88099 < stuck,
        "the last sliding strobe at vb = {slid}, the first stuck one at {stuck}"
    );
    assert!(branch.points[stuck_from..]
        .iter()
        .all(|p| p.orbit.stuck_at_strobe));
    // No special point at the edge: the stops and the class stay.
    assert!(
        branch
            .special
            .iter()
            .all(|s| !(slid - 1e-3..stuck + 1e-3).contains(&s.value)),
        "{:?}",
        branch.special
    );
    // The steady states on both sides lie on the branch: Newton's method from the branch's
    // state (interpolated between its points, across the kink too) lands on them.
    let values = [0.86, 0.87, 0.8805, 0.8815, 0.89, 0.9];
    for (vb, steady) in steady_at(second_belt, 0.0, &values) {
        assert_eq!(steady.period, Some(1), "vb = {vb}");
        let (x, stops) =
            on_branch(&branch, vb).unwrap_or_else(|| panic!("vb = {vb}: not on the branch"));
        assert_eq!(stops as f64, steady.stops_per_period, "vb = {vb}");
        let params = second_belt(vb, 0.0).params().unwrap();
        let guess = State { y: x[0], v: x[1] };
        let orbit = find_periodic_orbit(&params, guess, 1, &NewtonOptions::default()).unwrap();
        let s = steady.strobes[0];
        assert!(
            (orbit.state.y - s.y).abs() < 1e-8 && (orbit.state.v - s.v).abs() < 1e-8,
            "vb = {vb}: from the branch's {x:?} to {:?}, steady {s:?}",
            orbit.state
        );
        assert_eq!(orbit.stuck_at_strobe, vb > 0.881, "vb = {vb}");
    }
}

/// On the first belt the stop that follows the long slide is reached ever more tangentially
/// as vb rises (y'' → 0 on arrival at the belt's speed): at vb ≈ 0.43188 the slide only
/// touches the belt's speed, and past it it misses: the stop vanishes at once, the map jumps
/// and the period-1 orbit ends (the sweep goes to orbits of periods 7, 5, 3, 2). The branch
/// ends there, at either drive phase, naming the stop reached tangentially; the steady state
/// just before is on the branch, the one just past is of another period.
#[test]
fn a_stop_reached_tangentially_ends_the_branch_by_name() {
    for phi in [0.0, 3.0] {
        let (params, orbit) = settled_orbit(&forced_belt(0.3, phi)).unwrap();
        let options = ContinuationOptions::default().with_max_step(0.02);
        let branch = continue_orbit(&params, Parameter::Vb, &orbit, 0.6, &options, &()).unwrap();
        let (value, obstacle) = match &branch.end {
            BranchEnd::Failed { value, obstacle }
            | BranchEnd::Stalled {
                value, obstacle, ..
            } => (*value, *obstacle),
            end => panic!("φ = {phi}: {end:?}"),
        };
        assert!(
            matches!(obstacle, Obstacle::TangentialStick { acceleration, .. } if acceleration < 1e-2),
            "φ = {phi}: {obstacle:?}"
        );
        assert!(
            (0.4318..0.4320).contains(&value),
            "φ = {phi}: ends at {value}"
        );
        assert!(
            branch.end.to_string().contains("tangentially"),
            "{}",
            branch.end
        );
        let steps = steady_at(forced_belt, phi, &[0.431, 0.433]);
        let before = &steps[0].1;
        assert_eq!(before.period, Some(1));
        let (x, _) = on_branch(&branch, 0.431).unwrap();
        let s = before.strobes[0];
        assert!(
            (x[0] - s.y).abs() < 2e-3 && (x[1] - s.v).abs() < 2e-3,
            "φ = {phi}: branch {x:?}, steady {s:?}"
        );
        assert_ne!(steps[1].1.period, Some(1), "φ = {phi}: past the end");
    }
}

/// Down in vb the first belt's period-1 orbit loses its stability through a multiplier −1 at
/// vb ≈ 0.09801 (a period doubling: the orbit's other multiplier is 0, it stops), and `steady`
/// changes there from period 1 to period 2: at 0.099 it settles on the branch, at 0.097 on
/// an orbit of period 2.
#[test]
fn a_period_doubling_in_vb_lies_where_steady_doubles_its_period() {
    let (params, orbit) = settled_orbit(&forced_belt(0.2, 0.0)).unwrap();
    let options = ContinuationOptions::default().with_max_step(0.02);
    let branch = continue_orbit(&params, Parameter::Vb, &orbit, 0.06, &options, &()).unwrap();
    let doublings: Vec<_> = branch
        .special
        .iter()
        .filter(|s| s.kind == SpecialKind::PeriodDoubling)
        .collect();
    assert_eq!(doublings.len(), 1, "{:?}", branch.special);
    let pd = doublings[0];
    assert!(pd.located && (0.097..0.099).contains(&pd.value), "{pd:?}");
    assert!(pd.before.multipliers[0].re > -1.0 && pd.after.multipliers[0].re < -1.0);
    let steps = steady_at(forced_belt, 0.0, &[0.097, 0.099]);
    assert_eq!(steps[0].1.period, Some(2), "vb = 0.097");
    assert_eq!(steps[1].1.period, Some(1), "vb = 0.099");
    let (x, _) = on_branch(&branch, 0.099).unwrap();
    let s = steps[1].1.strobes[0];
    assert!(
        (x[0] - s.y).abs() < 2e-3 && (x[1] - s.v).abs() < 2e-3,
        "branch {x:?}, steady {s:?}"
    );
}

/// The undamped belt ζ = 0, w = 0.5, β = 1, μs = 1.5 at φ = 3: its period-1 orbit with a stop
/// folds back at vb ≈ 0.44739 and again at 0.42441 (three orbits coexist between). A sweep up
/// in vb follows the branch up to the first fold and jumps there; the branch reports the fold
/// where the sweep leaves it, and no Neimark–Sacker point (its orbits stop: det M = 0). Past
/// the second fold it ends at vb ≈ 0.4251, named: a stop reached tangentially.
#[test]
fn a_fold_in_vb_lies_where_the_sweep_jumps() {
    let belt = |vb: f64| {
        Experiment::dimensionless(0.0, 0.5, 1.0)
            .and_then(|e| e.with_phi(3.0))
            .and_then(|e| e.with_mu_s(1.5))
            .and_then(|e| e.with_vb(vb))
            .unwrap()
    };
    let (params, orbit) = settled_orbit(&belt(0.3)).unwrap();
    let options = ContinuationOptions::default().with_max_step(0.02);
    let branch = continue_orbit(&params, Parameter::Vb, &orbit, 1.5, &options, &()).unwrap();
    let folds: Vec<f64> = branch
        .special
        .iter()
        .filter(|s| s.kind == SpecialKind::Fold)
        .map(|s| s.value)
        .collect();
    assert_eq!(folds.len(), 2, "{:?}", branch.special);
    assert!(
        (0.447..0.448).contains(&folds[0]) && (0.424..0.425).contains(&folds[1]),
        "{folds:?}"
    );
    assert!(branch
        .special
        .iter()
        .all(|s| s.kind != SpecialKind::NeimarkSacker));
    assert!(
        matches!(
            branch.end,
            BranchEnd::Failed {
                value,
                obstacle: Obstacle::TangentialStick { .. }
            } if (0.4245..0.4255).contains(&value)
        ),
        "{:?}",
        branch.end
    );

    let range = ParameterRange::new("vb", 0.40, 0.47, 15).unwrap();
    let steps = Sweep::new(&belt(0.40), Axis::range(Parameter::Vb, &range).unwrap())
        .unwrap()
        .direction(SweepDirection::Up)
        .run(&())
        .unwrap();
    for step in &steps {
        // The branch's lower piece, up to the first fold, comes first along it.
        let on = step.steady.period == Some(1)
            && on_branch(&branch, step.value).is_some_and(|(x, _)| {
                let s = step.steady.strobes[0];
                (x[0] - s.y).abs() < 2e-3 && (x[1] - s.v).abs() < 2e-3
            });
        assert_eq!(
            on,
            step.value < folds[0],
            "vb = {}: steady {:?} (fold at {})",
            step.value,
            step.steady.strobes.first(),
            folds[0]
        );
    }
}
