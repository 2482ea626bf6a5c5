//! Special points between two neighbouring points of a branch, located by bisection along
//! the arclength: changes of the event counts (grazing), and real multipliers through +1
//! (folds, branch points), through −1 (period doublings) and complex pairs through the unit
//! circle (Neimark–Sacker).

use super::corrector::{counts, Problem, Solution};
use super::{Side, SpecialKind, SpecialPoint};
use crate::error::Result;
use crate::params::State;
use crate::stability::Stability;

/// A solution at the fraction `t` of an interval of the branch.
#[derive(Clone)]
struct Sample {
    t: f64,
    solution: Solution,
}

/// The solutions inside an interval of the branch, by the fraction t ∈ [0, 1] of the way.
pub(crate) type Sampler<'a> = dyn Fn(f64) -> Result<Option<Solution>> + 'a;

impl Sample {
    fn side(&self) -> Side {
        side(&self.solution)
    }
}

/// The orbit of a solution as one side of a special point.
pub(crate) fn side(solution: &Solution) -> Side {
    {
        let o = &solution.orbit;
        let (turns, stops) = counts(o);
        Side {
            value: solution.u[2],
            state: o.state,
            multipliers: o.multipliers,
            // Strictly: the bracket's ends lie within its width of the special point.
            stability: match o.multipliers[0].modulus() {
                m if m < 1.0 => Stability::Stable,
                m if m > 1.0 => Stability::Unstable,
                _ => Stability::Neutral,
            },
            turns,
            stops,
        }
    }
}

/// det(M − I) = (μ₁ − 1)(μ₂ − 1): changes sign where a real multiplier passes +1.
fn plus_one(s: &Solution) -> f64 {
    s.orbit.monodromy.minus_identity().det()
}

/// det(M + I) = (μ₁ + 1)(μ₂ + 1): changes sign where a real multiplier passes −1.
fn minus_one(s: &Solution) -> f64 {
    let m = s.orbit.monodromy.0;
    (m[0][0] + 1.0) * (m[1][1] + 1.0) - m[0][1] * m[1][0]
}

/// |μ|² − 1 = det M − 1 for a complex pair (NaN for real multipliers).
fn unit_circle(s: &Solution) -> f64 {
    if s.orbit.multipliers[0].im != 0.0 {
        s.orbit.monodromy.det() - 1.0
    } else {
        f64::NAN
    }
}

/// The special points between `from` (t = 0) and `to` (t = 1), with the solutions in
/// between given by `sample`, in order along the branch; `index` is the position of `from` in
/// the branch.
pub(crate) fn between(
    problem: &Problem,
    sample: &Sampler,
    from: &Solution,
    to: &Solution,
    index: usize,
) -> Result<Vec<SpecialPoint>> {
    let mut out = Vec::new();
    let lo = Sample {
        t: 0.0,
        solution: from.clone(),
    };
    let hi = Sample {
        t: 1.0,
        solution: to.clone(),
    };
    scan(problem, sample, lo, hi, index, &mut out, 0)?;
    Ok(out)
}

/// Grazing points first (they split the interval into smooth pieces), then the smooth tests
/// on each piece.
fn scan(
    problem: &Problem,
    sample: &Sampler,
    lo: Sample,
    hi: Sample,
    index: usize,
    out: &mut Vec<SpecialPoint>,
    depth: usize,
) -> Result<()> {
    let start = problem.pieces(&lo.solution.orbit);
    if depth < 8 && start != problem.pieces(&hi.solution.orbit) {
        let (l, r, located) = bisect(problem, sample, lo.clone(), hi.clone(), &|s| {
            problem.pieces(&s.orbit) == start
        })?;
        smooth(problem, sample, &lo, &l, index, out)?;
        out.push(special(SpecialKind::Grazing, &l, &r, located, index));
        if r.t < hi.t {
            scan(problem, sample, r, hi, index, out, depth + 1)?;
        }
        Ok(())
    } else {
        smooth(problem, sample, &lo, &hi, index, out)
    }
}

/// Sign changes of the test functions on a piece with constant event counts.
fn smooth(
    problem: &Problem,
    sample: &Sampler,
    lo: &Sample,
    hi: &Sample,
    index: usize,
    out: &mut Vec<SpecialPoint>,
) -> Result<()> {
    if hi.t <= lo.t {
        return Ok(());
    }
    let mut found = Vec::new();
    type Test = fn(&Solution) -> f64;
    let tests: [Test; 3] = [plus_one, minus_one, unit_circle];
    for (k, test) in tests.into_iter().enumerate() {
        let (a, b) = (test(&lo.solution), test(&hi.solution));
        if !(a.is_finite() && b.is_finite()) || (a > 0.0) == (b > 0.0) {
            continue;
        }
        let sign = a > 0.0;
        let (l, r, located) = bisect(problem, sample, lo.clone(), hi.clone(), &|s| {
            (test(s) > 0.0) == sign
        })?;
        let kind = match k {
            // A fold turns the branch back in the parameter; a branch point does not.
            0 if l.solution.tangent[2] * r.solution.tangent[2] < 0.0 => SpecialKind::Fold,
            0 => SpecialKind::BranchPoint,
            1 => SpecialKind::PeriodDoubling,
            _ => SpecialKind::NeimarkSacker,
        };
        found.push((l.t, special(kind, &l, &r, located, index)));
    }
    found.sort_by(|a, b| a.0.total_cmp(&b.0));
    out.extend(found.into_iter().map(|(_, s)| s));
    Ok(())
}

/// Bisection until the bracket is at most the locating tolerance wide (in (y, y', λ)): `lo`
/// satisfies `same`, `hi` does not. Returns the final bracket and whether it reached the
/// tolerance (false when no solution was found inside it).
fn bisect(
    problem: &Problem,
    sample: &Sampler,
    mut lo: Sample,
    mut hi: Sample,
    same: &dyn Fn(&Solution) -> bool,
) -> Result<(Sample, Sample, bool)> {
    let tolerance = problem.options.locate_tolerance;
    for _ in 0..200 {
        if width(&lo, &hi) <= tolerance {
            return Ok((lo, hi, true));
        }
        let mid = 0.5 * (lo.t + hi.t);
        if mid <= lo.t || mid >= hi.t {
            return Ok((lo, hi, true));
        }
        let Some(solution) = sample(mid)? else {
            return Ok((lo, hi, false));
        };
        let sample = Sample { t: mid, solution };
        if same(&sample.solution) {
            lo = sample;
        } else {
            hi = sample;
        }
    }
    Ok((lo, hi, false))
}

/// The distance of two samples in (y, y', λ).
fn width(a: &Sample, b: &Sample) -> f64 {
    let (a, b) = (&a.solution.u, &b.solution.u);
    ((a[0] - b[0]).powi(2) + (a[1] - b[1]).powi(2) + (a[2] - b[2]).powi(2)).sqrt()
}

fn special(kind: SpecialKind, l: &Sample, r: &Sample, located: bool, index: usize) -> SpecialPoint {
    let (a, b) = (&l.solution.u, &r.solution.u);
    SpecialPoint {
        kind,
        value: 0.5 * (a[2] + b[2]),
        state: State {
            y: 0.5 * (a[0] + b[0]),
            v: 0.5 * (a[1] + b[1]),
        },
        width: width(l, r),
        located,
        after_point: index,
        before: l.side(),
        after: r.side(),
    }
}
