//! Continuation in the belt speed vb of a forced Coulomb belt: the branch passes through the
//! steady states that a sweep over vb settles on, and a special point it locates (a grazing:
//! the stops per period change; a fold) lies where the sweep's stops or class change, and
//! only there. At two drive phases: one puts the strobe in a slide, the other in a stop (y' = vb
//! there, moving with the continued vb, the corrector solving for (y, vb) alone).

use stickslip::continuation::{
    continue_orbit, settled_orbit, Branch, BranchEnd, ContinuationOptions, SpecialKind,
};
use stickslip::scan::{Axis, ParameterRange, Sweep, SweepDirection, SweepPoint};
use stickslip::{Experiment, Parameter};

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
