//! Fig. 7's boundaries between numbers of stops per period, traced as grazing curves with
//! `continuation::curve`, their starts found from the map's own changes of region, and the
//! check that they lie on the map's edges.

use anyhow::Result;
use rayon::prelude::*;
use std::collections::BTreeMap;
use stickslip::continuation::{
    curve_within, ContinuationOptions, Curve, CurveSpec, Follow, NoStart,
};
use stickslip::scan::{GridPoint, ParameterRange};
use stickslip::steady::MotionClass;
use stickslip::{Experiment, Parameter};

/// The most starts tried (pairs of neighbouring cells whose number of stops per period
/// differs and that no curve traced before crosses): a bound on the time, far above the
/// starts the paper's maps need (each curve crosses every edge of its region's side).
const MAX_STARTS: usize = 16;

/// Most points of each curve each way: a curve inside the map's range of β takes fewer.
const MAX_POINTS: usize = 400;

/// A cell's region: its class, its period and its stops per period.
fn region(p: &GridPoint) -> (MotionClass, Option<usize>, u64) {
    (p.class, p.period, p.stops_per_period.to_bits())
}

/// Two neighbouring cells on either side of a change in the number of stops per period (or
/// of the period) of a periodic stick-slip motion: what a grazing curve can explain.
fn stops_change(a: &GridPoint, b: &GridPoint) -> bool {
    a.class == MotionClass::PeriodicStick
        && b.class == MotionClass::PeriodicStick
        && region(a) != region(b)
}

/// One cell on each side of the exact sliding boundary's change: sliding against periodic
/// stick.
fn sliding_change(a: &GridPoint, b: &GridPoint) -> bool {
    let pair = [a.class, b.class];
    pair.contains(&MotionClass::Sliding) && pair.contains(&MotionClass::PeriodicStick)
}

/// The map's grid: its points (β fastest) and its axes.
pub struct MapGrid<'a> {
    /// The points, index `iw · nβ + iβ`.
    pub points: &'a [GridPoint],
    /// The axis of w.
    pub w: &'a ParameterRange,
    /// The axis of β.
    pub beta: &'a ParameterRange,
}

/// How many times a set of polylines in (w, β) crosses the segment between the centres of
/// two neighbouring cells: `right[k]` for the pair (k, k + nβ) (w's neighbour), `up[k]` for
/// (k, k + 1) (β's neighbour). An odd count puts the two cells on either side.
struct Crossed {
    right: Vec<u32>,
    up: Vec<u32>,
}

/// Whether the segments p1–p2 and q1–q2 cross (touching counts).
fn segments_cross(p1: (f64, f64), p2: (f64, f64), q1: (f64, f64), q2: (f64, f64)) -> bool {
    let orient = |a: (f64, f64), b: (f64, f64), c: (f64, f64)| {
        (b.0 - a.0) * (c.1 - a.1) - (b.1 - a.1) * (c.0 - a.0)
    };
    let (d1, d2) = (orient(q1, q2, p1), orient(q1, q2, p2));
    let (d3, d4) = (orient(p1, p2, q1), orient(p1, p2, q2));
    d1 * d2 <= 0.0 && d3 * d4 <= 0.0 && (d1 != 0.0 || d2 != 0.0)
}

impl MapGrid<'_> {
    fn nw(&self) -> usize {
        self.w.steps()
    }

    fn nb(&self) -> usize {
        self.beta.steps()
    }

    fn at(&self, iw: usize, ib: usize) -> &GridPoint {
        &self.points[iw * self.nb() + ib]
    }

    fn center(&self, iw: usize, ib: usize) -> (f64, f64) {
        let p = self.at(iw, ib);
        (p.params.w, p.params.beta)
    }

    /// The pairs of neighbouring cells whose centres' segment one of `lines` crosses (a
    /// non-finite point breaks a line).
    fn crossed(&self, lines: &[Vec<(f64, f64)>]) -> Crossed {
        let (nw, nb) = (self.nw(), self.nb());
        let mut out = Crossed {
            right: vec![0; nw * nb],
            up: vec![0; nw * nb],
        };
        for line in lines {
            self.mark(&mut out, line);
        }
        out
    }

    /// Mark in `out` the pairs of neighbouring cells that `line` crosses.
    fn mark(&self, out: &mut Crossed, line: &[(f64, f64)]) {
        let (nw, nb) = (self.nw(), self.nb());
        let index = |x: f64, range: &ParameterRange, n: usize| -> usize {
            (((x - range.from()) / range.spacing()).floor().max(0.0) as usize).min(n - 1)
        };
        {
            for s in line.windows(2) {
                let (a, b) = (s[0], s[1]);
                if !(a.0.is_finite() && a.1.is_finite() && b.0.is_finite() && b.1.is_finite()) {
                    continue;
                }
                let (w0, w1) = (
                    index(a.0.min(b.0), self.w, nw),
                    index(a.0.max(b.0), self.w, nw),
                );
                let (b0, b1) = (
                    index(a.1.min(b.1), self.beta, nb),
                    index(a.1.max(b.1), self.beta, nb),
                );
                for iw in w0.saturating_sub(1)..=w1.min(nw - 1) {
                    for ib in b0.saturating_sub(1)..=b1.min(nb - 1) {
                        let k = iw * nb + ib;
                        let c = self.center(iw, ib);
                        if iw + 1 < nw && segments_cross(a, b, c, self.center(iw + 1, ib)) {
                            out.right[k] += 1;
                        }
                        if ib + 1 < nb && segments_cross(a, b, c, self.center(iw, ib + 1)) {
                            out.up[k] += 1;
                        }
                    }
                }
            }
        }
    }

    /// Every pair of neighbouring cells, (first, second, crossings counted in `crossed`).
    fn pairs<'b>(
        &'b self,
        crossed: &'b Crossed,
    ) -> impl Iterator<Item = (&'b GridPoint, &'b GridPoint, u32)> + 'b {
        let (nw, nb) = (self.nw(), self.nb());
        (0..nw * nb).flat_map(move |k| {
            let (iw, ib) = (k / nb, k % nb);
            let right =
                (iw + 1 < nw).then(|| (self.at(iw, ib), self.at(iw + 1, ib), crossed.right[k]));
            let up = (ib + 1 < nb).then(|| (self.at(iw, ib), self.at(iw, ib + 1), crossed.up[k]));
            right.into_iter().chain(up)
        })
    }
}

/// The grazing curves that bound the regions of different numbers of stops per period on a
/// map, and how they were found.
pub struct StopCurves {
    /// The curves, in the order traced.
    pub curves: Vec<Curve>,
    /// Starts tried (pairs of neighbouring cells along w that no curve crossed yet).
    pub tried: usize,
    /// Starts whose orbit, continued in w from one cell to the other, met no grazing (the
    /// cells' motions are different attractors reached from rest, not one orbit's change).
    pub no_start: usize,
}

/// Trace the grazing curves of the map `grid` of `experiment` (over β within the map's range,
/// w following within its range): from the first pair of neighbouring cells along w (in the map's order)
/// whose numbers of stops per period differ, the orbit the motion settles on in the first
/// cell is continued in w towards the second's w up to its first grazing, which is followed
/// over β; then from the next such pair that no curve crosses, up to [`MAX_STARTS`] starts.
///
/// The curves are traced several at once (as many as there are threads): the next pairs that
/// no curve crosses yet are started together, and their curves taken in the map's order, a
/// pair that an earlier curve of the batch crosses dropped as if never started. The result is
/// that of tracing them one after the other, for any number of threads.
pub fn stop_curves(experiment: &Experiment, grid: &MapGrid) -> Result<StopCurves> {
    let (nw, nb) = (grid.nw(), grid.nb());
    let options = ContinuationOptions {
        max_points: MAX_POINTS,
        ..ContinuationOptions::default()
    };
    let mut out = StopCurves {
        curves: Vec::new(),
        tried: 0,
        no_start: 0,
    };
    let mut crossed = grid.crossed(&[]);
    // The pairs along w whose numbers of stops differ, in the map's order.
    let pairs: Vec<usize> = (0..nw.saturating_sub(1) * nb)
        .filter(|&k| stops_change(grid.at(k / nb, k % nb), grid.at(k / nb + 1, k % nb)))
        .collect();
    let trace = |k: usize| -> Result<std::result::Result<Curve, NoStart>> {
        let (a, b) = (grid.at(k / nb, k % nb), grid.at(k / nb + 1, k % nb));
        let spec = CurveSpec {
            follow: Follow::Grazing,
            vary: Parameter::W,
            vary_to: b.params.w,
            over: Parameter::Beta,
            from: grid.beta.from(),
            to: grid.beta.to(),
        };
        let start = experiment
            .clone()
            .with_w(a.params.w)?
            .with_beta(a.params.beta)?;
        let monitor = |_: usize, _: usize| !crate::output::interrupted();
        // Within the map's range of w: the curve ends where it leaves the map.
        let within = Some((grid.w.from(), grid.w.to()));
        Ok(curve_within(&start, &spec, within, &options, &monitor)?)
    };
    let batch = rayon::current_num_threads().max(1);
    let mut traced: BTreeMap<usize, Result<std::result::Result<Curve, NoStart>>> = BTreeMap::new();
    for (i, &k) in pairs.iter().enumerate() {
        if crossed.right[k] > 0 {
            continue;
        }
        if out.tried == MAX_STARTS {
            return Ok(out);
        }
        out.tried += 1;
        if !traced.contains_key(&k) {
            let next: Vec<usize> = pairs[i..]
                .iter()
                .copied()
                .filter(|q| crossed.right[*q] == 0 && !traced.contains_key(q))
                .take(batch.min(MAX_STARTS + 1 - out.tried))
                .collect();
            let done: Vec<_> = next.par_iter().map(|&q| (q, trace(q))).collect();
            traced.extend(done);
        }
        match traced.remove(&k).expect("traced above")? {
            Ok(c) => {
                let line: Vec<(f64, f64)> = c.points.iter().map(|p| (p.vary, p.over)).collect();
                grid.mark(&mut crossed, &line);
                out.curves.push(c);
            }
            Err(_) => out.no_start += 1,
        }
    }
    Ok(out)
}

/// How well curves lie on a map's edges: counts of pairs of neighbouring cells.
pub struct EdgeCheck {
    /// Pairs whose numbers of stops per period (or periods) of periodic stick differ.
    pub stop_edges: usize,
    /// Of those, the pairs the grazing curves cross an odd number of times (the two cells on
    /// either side).
    pub stop_edges_crossed: usize,
    /// Pairs the grazing curves cross an odd number of times.
    pub crossed: usize,
    /// Of those, the pairs whose regions differ (class, period or stops).
    pub crossed_changing: usize,
    /// Pairs the grazing curves cross an even number of times (a region thinner than a cell
    /// between them).
    pub crossed_even: usize,
    /// Of those, the pairs whose regions are the same.
    pub crossed_even_same: usize,
    /// Pairs of a sliding and a periodic stick-slip cell.
    pub sliding_edges: usize,
    /// Of those, the pairs the exact boundary β_c crosses.
    pub sliding_edges_crossed: usize,
}

/// Count, on `grid`, the changes of region that `curves` and the exact sliding boundary
/// (`boundary`, points (w, β)) cross.
pub fn check_edges(grid: &MapGrid, curves: &[Curve], boundary: &[(f64, f64)]) -> EdgeCheck {
    let lines: Vec<Vec<(f64, f64)>> = curves
        .iter()
        .map(|c| c.points.iter().map(|p| (p.vary, p.over)).collect())
        .collect();
    let by_curves = grid.crossed(&lines);
    let by_boundary = grid.crossed(&[boundary.to_vec()]);
    let mut check = EdgeCheck {
        stop_edges: 0,
        stop_edges_crossed: 0,
        crossed: 0,
        crossed_changing: 0,
        crossed_even: 0,
        crossed_even_same: 0,
        sliding_edges: 0,
        sliding_edges_crossed: 0,
    };
    for ((a, b, curve), (_, _, beta_c)) in grid.pairs(&by_curves).zip(grid.pairs(&by_boundary)) {
        let odd = curve % 2 == 1;
        if stops_change(a, b) {
            check.stop_edges += 1;
            check.stop_edges_crossed += usize::from(odd);
        }
        if odd {
            check.crossed += 1;
            check.crossed_changing += usize::from(region(a) != region(b));
        } else if curve > 0 {
            check.crossed_even += 1;
            check.crossed_even_same += usize::from(region(a) == region(b));
        }
        if sliding_change(a, b) {
            check.sliding_edges += 1;
            check.sliding_edges_crossed += usize::from(beta_c % 2 == 1);
        }
    }
    check
}
