//! Basins by recurrence against the exhaustive method on the same grid: the same attractors
//! (kind, period, and the same orbit or strobe set) with fractions within 0.01, on maps of
//! periodic orbits, rest, chaos and a mirror pair of chaotic attractors beside a period-3
//! orbit; the same map for any number of threads and when resumed from saved rows.

use stickslip::attractor::AttractorKind;
use stickslip::basins::{Attractor, BasinMap, BasinMethod, BasinOptions, Basins};
use stickslip::scan::ParameterRange;
use stickslip::solver::run_until;
use stickslip::{ExactSolver, Experiment, Params, Solver, State};

fn experiment(zeta: f64, mu_s: f64, w: f64, beta: f64) -> Experiment {
    Experiment::dimensionless(zeta, w, beta)
        .and_then(|e| e.with_mu_s(mu_s))
        .expect("valid experiment")
}

fn grid(e: &Experiment, lo: f64, hi: f64, steps: usize, options: BasinOptions) -> Basins {
    let r = ParameterRange::new("y0", lo, hi, steps).unwrap();
    Basins::new(e, &r, &r).unwrap().options(options).unwrap()
}

fn with(method: BasinMethod, options: BasinOptions) -> BasinOptions {
    BasinOptions { method, ..options }
}

fn distance(a: State, b: State) -> f64 {
    (a.y - b.y).abs().max((a.v - b.v).abs())
}

/// An attractor with the strobe points that stand for it: for an orbit or rest its own; for
/// chaos or a torus every 13th strobe of 26 000 periods run from its state (a stride prime to
/// the short periods a chaotic band can cycle through, so that every band is sampled). (An attractor's
/// own record, 1 024 strobes, can sample part of an intermittent chaotic attractor only: at
/// ζ = 0, μs = 3, w = 0.33, β = 9 one method's record stayed in the attractor's descending
/// phase, y from 6.7 to 9.0, while the other's spanned 6.6 to 11.0, the same exponent within
/// 0.5 %.)
struct Sampled<'a> {
    attractor: &'a Attractor,
    strobes: Vec<State>,
}

fn sampled<'a>(params: &Params, attractor: &'a Attractor) -> Sampled<'a> {
    let strobes = match attractor.kind {
        AttractorKind::Periodic | AttractorKind::Static => attractor.strobes.clone(),
        _ => {
            let period = params.drive_period();
            let mut solver = ExactSolver::new(*params, attractor.state);
            let mut strobes = Vec::new();
            for k in 1..=26_000u32 {
                run_until(&mut solver, f64::from(k) * period, |_| {}).expect("the motion runs");
                if k % 13 == 0 {
                    strobes.push(solver.state());
                }
            }
            strobes
        }
    };
    Sampled { attractor, strobes }
}

/// Whether two attractors are the same: kind and period, and for an orbit a fixed point of
/// one within 1e-6 (relative) of a strobe point of the other; for chaos or a torus, 90 % of
/// the sampled strobe points of each within 10 % of the other's extent of the other's points.
fn same(a: &Sampled, b: &Sampled) -> bool {
    let (a_strobes, b_strobes) = (&a.strobes, &b.strobes);
    let (a, b) = (a.attractor, b.attractor);
    if a.kind != b.kind || a.period != b.period {
        return false;
    }
    match a.kind {
        AttractorKind::Static => true,
        AttractorKind::Periodic => {
            let scale = 1f64.max(a.state.y.abs()).max(a.state.v.abs());
            b.strobes
                .iter()
                .any(|s| distance(*s, a.state) <= 1e-6 * scale)
        }
        _ => covers(a_strobes, b_strobes) && covers(b_strobes, a_strobes),
    }
}

fn covers(reference: &[State], sample: &[State]) -> bool {
    let extent = |f: fn(&State) -> f64| {
        let lo = reference.iter().map(f).fold(f64::INFINITY, f64::min);
        let hi = reference.iter().map(f).fold(f64::NEG_INFINITY, f64::max);
        hi - lo
    };
    let radius = 0.1 * extent(|s| s.y).max(extent(|s| s.v));
    let near = sample
        .iter()
        .filter(|x| reference.iter().any(|r| distance(*r, **x) <= radius))
        .count();
    near * 10 >= sample.len() * 9
}

fn summary(map: &BasinMap) -> String {
    map.attractors
        .iter()
        .map(|a| {
            format!(
                "#{} {} p{:?} {:.4} λ {:.3e} mirror {:?}",
                a.id, a.kind, a.period, a.fraction, a.exponent, a.mirror
            )
        })
        .collect::<Vec<_>>()
        .join("; ")
        + &format!("; undecided {}", map.undecided)
}

/// Both methods on the same grid: every attractor of one is an attractor of the other, with
/// fractions within 0.01 (undecided cells too). Returns the recurrence map.
fn agree(basins: &Basins) -> BasinMap {
    let options = *basins.basin_options();
    let t = std::time::Instant::now();
    let exhaustive = basins
        .clone()
        .options(with(BasinMethod::Exhaustive, options))
        .unwrap()
        .run(&())
        .unwrap();
    let te = t.elapsed();
    let t = std::time::Instant::now();
    let recurrence = basins
        .clone()
        .options(with(BasinMethod::Recurrence, options))
        .unwrap()
        .run(&())
        .unwrap();
    let tr = t.elapsed();
    let cells = exhaustive.cells.len() as f64;
    let params = basins.params();
    let exhaustive_sampled: Vec<Sampled> = exhaustive
        .attractors
        .iter()
        .map(|a| sampled(params, a))
        .collect();
    let recurrence_sampled: Vec<Sampled> = recurrence
        .attractors
        .iter()
        .map(|a| sampled(params, a))
        .collect();
    let differ = exhaustive
        .cells
        .iter()
        .zip(&recurrence.cells)
        .filter(|(a, b)| match (a, b) {
            (Some(a), Some(b)) => !same(&exhaustive_sampled[*a], &recurrence_sampled[*b]),
            (None, None) => false,
            _ => true,
        })
        .count();
    eprintln!(
        "exhaustive {te:.2?}: {}\nrecurrence {tr:.2?}: {}\ncells on another attractor: {differ}",
        summary(&exhaustive),
        summary(&recurrence)
    );
    for (one, other, name) in [
        (&exhaustive_sampled, &recurrence_sampled, "recurrence"),
        (&recurrence_sampled, &exhaustive_sampled, "exhaustive"),
    ] {
        for sampled in one {
            let a = sampled.attractor;
            // The fraction of all attractors of the other map that are this one.
            let matched: Vec<&Sampled> = other.iter().filter(|b| same(sampled, b)).collect();
            assert!(
                !matched.is_empty(),
                "{name} misses {a:?}\n{}\n{}",
                summary(&exhaustive),
                summary(&recurrence)
            );
            let theirs: f64 = matched.iter().map(|b| b.attractor.fraction).sum();
            let ours: f64 = one
                .iter()
                .filter(|b| matched.iter().any(|m| same(b, m)))
                .map(|b| b.attractor.fraction)
                .sum();
            assert!(
                (ours - theirs).abs() <= 0.01,
                "attractor #{} ({}): fraction {ours} against {theirs} by {name}",
                a.id,
                a.kind
            );
        }
    }
    assert!(((exhaustive.undecided as f64 - recurrence.undecided as f64) / cells).abs() <= 0.01);
    recurrence
}

const PAPER_ZETA: f64 = 0.046816;

#[test]
fn a_mirror_pair_of_chaotic_attractors_beside_a_period_3_orbit() {
    // The workload, ζ = 0, μs = 3, w = 0.65, β = 3.3 on [−3, 3]², on a coarser grid.
    let basins = grid(
        &experiment(0.0, 3.0, 0.65, 3.3),
        -3.0,
        3.0,
        20,
        BasinOptions::default(),
    );
    let map = agree(&basins);
    let chaotic: Vec<&Attractor> = map
        .attractors
        .iter()
        .filter(|a| a.kind == AttractorKind::Chaotic)
        .collect();
    assert_eq!(chaotic.len(), 2, "{}", summary(&map));
    assert_eq!(chaotic[0].mirror, Some(chaotic[1].id));
    assert_eq!(chaotic[1].mirror, Some(chaotic[0].id));
    let orbit = map
        .attractors
        .iter()
        .find(|a| a.period == Some(3))
        .expect("the period-3 orbit");
    assert_eq!(orbit.kind, AttractorKind::Periodic);
    assert_eq!(orbit.mirror, Some(orbit.id), "symmetric by itself");
    assert_eq!(map.attractors.len(), 3);
}

#[test]
fn a_mirror_pair_of_orbits() {
    let basins = grid(
        &experiment(0.0, 3.0, 0.6, 3.269),
        -8.0,
        8.0,
        24,
        BasinOptions::default(),
    );
    let map = agree(&basins);
    assert_eq!(map.attractors.len(), 2, "{}", summary(&map));
    assert_eq!(
        (map.attractors[0].mirror, map.attractors[1].mirror),
        (Some(1), Some(0))
    );
}

#[test]
fn rest_and_an_orbit_below_the_static_limit() {
    let basins = grid(
        &experiment(PAPER_ZETA, 1.5, 0.9, 1.4),
        -3.0,
        3.0,
        16,
        BasinOptions::default(),
    );
    let map = agree(&basins);
    let rest = map
        .attractors
        .iter()
        .find(|a| a.kind == AttractorKind::Static)
        .expect("rest is stable");
    let (lo, hi) = rest.rest_range.unwrap();
    assert!(
        lo >= -0.1 - 1e-12 && hi <= 0.1 + 1e-12,
        "rest from {lo} to {hi}"
    );
    assert_eq!(rest.mirror, Some(rest.id));
}

#[test]
fn every_cell_chaotic() {
    let basins = grid(
        &experiment(0.0, 3.0, 0.33, 9.0),
        -8.0,
        8.0,
        12,
        BasinOptions::default(),
    );
    let map = agree(&basins);
    assert_eq!(map.attractors.len(), 1, "{}", summary(&map));
    assert_eq!(map.attractors[0].kind, AttractorKind::Chaotic);
}

#[test]
fn two_mirror_pairs_of_orbits_one_with_a_multiplier_near_one() {
    // ζ = 0.02, μs = 3, w = 0.3534, β = 9.731: two period-2 orbits (multiplier about 0.94)
    // and two period-3 orbits, whose strobe points all lie near y = 11.5, y' = 0.
    let basins = grid(
        &experiment(0.02, 3.0, 0.3534, 9.731),
        -10.0,
        10.0,
        16,
        BasinOptions::default(),
    );
    let map = agree(&basins);
    let periods: Vec<Option<usize>> = map.attractors.iter().map(|a| a.period).collect();
    assert_eq!(
        periods.iter().filter(|p| **p == Some(2)).count(),
        2,
        "{}",
        summary(&map)
    );
    assert_eq!(
        periods.iter().filter(|p| **p == Some(3)).count(),
        2,
        "{}",
        summary(&map)
    );
    for a in &map.attractors {
        let m = a.mirror.expect("each has its mirror image");
        assert_ne!(m, a.id);
        assert_eq!(map.attractors[m].mirror, Some(a.id));
    }
}

#[test]
fn the_map_is_the_same_for_any_threads_and_when_resumed_from_saved_rows() {
    let basins = grid(
        &experiment(0.0, 3.0, 0.65, 3.3),
        -3.0,
        3.0,
        12,
        BasinOptions::default(),
    );
    let one = basins.clone().threads(1).unwrap().run(&()).unwrap();
    let two = basins.clone().threads(2).unwrap().run(&()).unwrap();
    assert_eq!(one, two);
    // Rows 0–4 computed, saved, and replayed by a fresh run that computes the rest.
    let mut first = basins.recurrence();
    let mut cells = Vec::new();
    let mut memories = Vec::new();
    for _ in 0..5 {
        let row = first.run_row(cells.len(), &()).unwrap();
        cells.extend(row.cells);
        memories.push(row.memory);
    }
    let mut resumed = basins.recurrence();
    for memory in &memories {
        resumed.replay(memory).unwrap();
    }
    assert_eq!(resumed.next_row(), 5);
    while resumed.next_row() < 12 {
        cells.extend(resumed.run_row(cells.len(), &()).unwrap().cells);
    }
    assert_eq!(basins.identify(&cells).unwrap(), one);
    // A damaged memory is refused, naming it.
    let mut other = basins.recurrence();
    let mut damaged = memories[0].clone();
    damaged.pop();
    assert!(matches!(
        other.replay(&damaged),
        Err(stickslip::Error::InvalidParameter { name: "memory", .. })
    ));
}

#[test]
fn options_are_checked() {
    let e = experiment(0.0, 3.0, 0.65, 3.3);
    let r = ParameterRange::new("y0", -3.0, 3.0, 4).unwrap();
    for (options, name) in [
        (
            BasinOptions {
                resolution: 8,
                ..BasinOptions::default()
            },
            "resolution",
        ),
        (
            BasinOptions {
                found_revisits: 0,
                ..BasinOptions::default()
            },
            "found_revisits",
        ),
        (
            BasinOptions {
                basin_hits: 0,
                ..BasinOptions::default()
            },
            "basin_hits",
        ),
        (
            BasinOptions {
                max_steps: 0,
                ..BasinOptions::default()
            },
            "max_steps",
        ),
    ] {
        let err = Basins::new(&e, &r, &r)
            .unwrap()
            .options(options)
            .unwrap_err();
        // Options of the table are named by their key (its Python spelling here), the
        // others by their field.
        let named = match &err {
            stickslip::Error::InvalidParameter { name, .. } => *name,
            stickslip::Error::InvalidOption { option, .. } => option.name(),
            _ => "",
        };
        assert_eq!(named, name, "{err}");
    }
    assert_eq!(BasinOptions::default().method, BasinMethod::Recurrence);
    for m in BasinMethod::ALL {
        assert_eq!(BasinMethod::from_label(m.label()), Some(m));
    }
}
