//! Theory curves over one parameter: the paper's series solution and boundary (eqs. (11) and
//! (13)) and the exact symmetric sliding orbit and boundary, cut where they do not exist.
//!
//! These are the curves drawn over simulated sweeps and maps, and the rows of
//! `stickslip theory --curve`. A value that does not exist (no solution, or outside a window
//! the caller sets) is NaN, which breaks a drawn line.
//!
//! ```
//! use stickslip::theory::curves::{theory_curve, Theory, TheoryQuantity};
//! use stickslip::{Parameter, Params};
//! let base = Params::new(0.0468, 1.0, 1.6).unwrap();
//! let ws = [0.2, 0.9];
//! let exact = theory_curve(Theory::Exact, TheoryQuantity::Gain1, &base, Parameter::W, &ws);
//! // At β = 1.6 the orbit slides at w = 0.9 and sticks at w = 0.2 (no sliding orbit).
//! assert!(exact.y[0].is_nan() && exact.y[1] > 1.0);
//! ```

use super::boundary::stick_slip_boundary;
use super::paper::{paper_boundary, PaperHarmonic, PaperSeries};
use super::periodic::PeriodicSolution;
use crate::params::{Parameter, Params};
use serde::{Deserialize, Serialize};

/// Fewest points of a theory curve drawn over a range; more when the data has more.
pub const MIN_POINTS: usize = 200;

/// Which theory.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Theory {
    /// The paper's series solution (eq. (11)) and boundary (eq. (13), which takes μs = 1).
    Paper,
    /// The exact symmetric sliding orbit and the exact stick-slip boundary β_c(w, ζ, μs).
    Exact,
}

impl Theory {
    /// Both theories.
    pub const ALL: [Theory; 2] = [Theory::Paper, Theory::Exact];

    /// `paper` or `exact`.
    pub fn label(self) -> &'static str {
        match self {
            Theory::Paper => "paper",
            Theory::Exact => "exact",
        }
    }
}

/// A curve of both theories over w, as `stickslip theory --curve` writes it.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum CurveKind {
    /// The stick-slip boundary β_c over w: `w,beta_c_paper,beta_c_exact`.
    Boundary,
    /// The gain of the fundamental G1 = A1/β over w at a given β:
    /// `w,gain1_paper,gain1_exact` (label `gain1`; before: `gain`, which still reads).
    #[serde(alias = "gain")]
    Gain1,
}

impl CurveKind {
    /// Both.
    pub const ALL: [CurveKind; 2] = [CurveKind::Boundary, CurveKind::Gain1];

    /// Names retired, with the value each now reads as: `gain` (now `gain1`: G1 = A1/β, not
    /// the gain G = (y_max − y_min)/(2β) of a steady state).
    pub const RETIRED: [(&'static str, CurveKind); 1] = [("gain", CurveKind::Gain1)];

    /// `boundary` or `gain1`.
    pub fn label(self) -> &'static str {
        match self {
            CurveKind::Boundary => "boundary",
            CurveKind::Gain1 => "gain1",
        }
    }

    /// The quantity along the curve.
    pub fn quantity(self) -> TheoryQuantity {
        match self {
            CurveKind::Boundary => TheoryQuantity::Boundary,
            CurveKind::Gain1 => TheoryQuantity::Gain1,
        }
    }

    /// The quantity's name in the CSV columns: `beta_c` or `gain1`
    /// ([`crate::report::TheoryTable::quantity`]).
    pub fn quantity_name(self) -> &'static str {
        match self {
            CurveKind::Boundary => "beta_c",
            CurveKind::Gain1 => "gain1",
        }
    }

    /// The CSV columns of the paper's and the exact values.
    pub fn columns(self) -> [&'static str; 2] {
        match self {
            CurveKind::Boundary => ["beta_c_paper", "beta_c_exact"],
            CurveKind::Gain1 => ["gain1_paper", "gain1_exact"],
        }
    }

    /// What the curve is, in one line.
    pub fn description(self) -> &'static str {
        match self {
            CurveKind::Boundary => "β_c over w: `w,beta_c_paper,beta_c_exact`",
            CurveKind::Gain1 => {
                "Gain of the fundamental G1 = A1/β over w at the given β: `w,gain1_paper,gain1_exact`"
            }
        }
    }
}

/// What a theory curve shows.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize, Deserialize)]
pub enum TheoryQuantity {
    /// The gain of the fundamental G1 = A1/β (what the paper's formula, its eq. 11, gives for
    /// its G).
    Gain1,
    /// The gain G = (y_max − y_min)/(2β) of the exact orbit (its max|y|/β: the orbit is
    /// symmetric), what a steady state's `gain` measures on a sliding orbit. The paper has
    /// none (NaN).
    PeakGain,
    /// The amplitude A_k of the odd harmonic k of y (units of y). The paper's A_k for k ≥ 3
    /// does not depend on β and exists even where its A1 does not.
    Harmonic(u32),
    /// The stick-slip boundary β_c, over w (the base β is not used).
    Boundary,
}

/// The value of `quantity` of `theory` at `params`, `None` where it does not exist.
pub fn theory_value(theory: Theory, quantity: TheoryQuantity, params: &Params) -> Option<f64> {
    let (zeta, w, beta) = (params.zeta, params.w, params.beta);
    let exact = || PeriodicSolution::new(params).ok();
    let value = match (theory, quantity) {
        (Theory::Paper, TheoryQuantity::Gain1) => {
            PaperSeries::new(zeta, w, beta).ok().map(|s| s.gain1())
        }
        (Theory::Exact, TheoryQuantity::Gain1) => exact().map(|s| s.gain1()),
        (Theory::Paper, TheoryQuantity::PeakGain) => None,
        (Theory::Exact, TheoryQuantity::PeakGain) => {
            (beta > 0.0).then(exact).flatten().map(|s| s.peak / beta)
        }
        (Theory::Paper, TheoryQuantity::Harmonic(1)) => {
            PaperSeries::new(zeta, w, beta).ok().map(|s| s.a1)
        }
        (Theory::Paper, TheoryQuantity::Harmonic(k)) => (k >= 3 && k % 2 == 1)
            .then(|| PaperHarmonic::new(zeta, w, k).ok())
            .flatten()
            .map(|h| h.amplitude.abs()),
        (Theory::Exact, TheoryQuantity::Harmonic(1)) => exact().map(|s| s.a1()),
        (Theory::Exact, TheoryQuantity::Harmonic(k)) => (k % 2 == 1)
            .then(exact)
            .flatten()
            .map(|s| s.harmonic(k).amplitude),
        (Theory::Paper, TheoryQuantity::Boundary) => paper_boundary(zeta, w).ok(),
        (Theory::Exact, TheoryQuantity::Boundary) => stick_slip_boundary(zeta, w, params.mu_s)
            .ok()
            .map(|b| b.beta_c),
    };
    value.filter(|v| v.is_finite())
}

/// A theory curve: `y[i]` at `x[i]`, NaN where it does not exist.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct TheoryCurve {
    /// The theory.
    pub theory: Theory,
    /// The quantity.
    pub quantity: TheoryQuantity,
    /// The parameter along the curve.
    pub over: Parameter,
    /// Abscissae.
    pub x: Vec<f64>,
    /// Values, NaN where the quantity does not exist.
    pub y: Vec<f64>,
}

impl TheoryCurve {
    /// The points (x, y), NaN where the curve does not exist.
    pub fn points(&self) -> Vec<(f64, f64)> {
        self.x.iter().copied().zip(self.y.iter().copied()).collect()
    }

    /// Number of points where the curve exists.
    pub fn present(&self) -> usize {
        self.y.iter().filter(|y| y.is_finite()).count()
    }

    /// The curve with every value outside [lo, hi] made NaN (kept only inside a plot's range).
    pub fn within(mut self, lo: f64, hi: f64) -> Self {
        for y in &mut self.y {
            if !(lo..=hi).contains(y) {
                *y = f64::NAN;
            }
        }
        self
    }

    /// The curve with every value multiplied by `factor` (to volts, say).
    pub fn scaled(mut self, factor: f64) -> Self {
        for y in &mut self.y {
            *y *= factor;
        }
        self
    }
}

/// The curve of `quantity` of `theory` with `over` taking the values `xs` and the other
/// parameters from `base`.
pub fn theory_curve(
    theory: Theory,
    quantity: TheoryQuantity,
    base: &Params,
    over: Parameter,
    xs: &[f64],
) -> TheoryCurve {
    let y = xs
        .iter()
        .map(|&x| {
            over.set(*base, x)
                .ok()
                .and_then(|p| theory_value(theory, quantity, &p))
                .unwrap_or(f64::NAN)
        })
        .collect();
    TheoryCurve {
        theory,
        quantity,
        over,
        x: xs.to_vec(),
        y,
    }
}

/// The theory's gain curves over a sweep's range, at the sweep's other parameters: what is
/// drawn over a simulated sweep (the command line's plot, the lab's sweep view).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct SweepTheory {
    /// The paper's gain A1/β, eq. (11).
    pub paper: TheoryCurve,
    /// The exact sliding orbit's peak/β: what the simulated gain (y_max − y_min)/(2β)
    /// measures on a sliding orbit.
    pub exact: TheoryCurve,
    /// Legend prefix: `PWL theory: ` when the experiment's diodes are Shockley diodes (the
    /// theory is that of the piecewise-linear model), else empty.
    pub prefix: &'static str,
}

impl SweepTheory {
    /// The curves over [`abscissae`]`(from, to, steps)` of `over`, the other parameters from
    /// `base`; `shockley` says that the swept experiment has Shockley diodes ([`Self::prefix`]).
    pub fn new(
        base: &Params,
        over: Parameter,
        (from, to, steps): (f64, f64, usize),
        shockley: bool,
    ) -> Self {
        let xs = abscissae(from, to, steps);
        let curve = |theory, quantity| theory_curve(theory, quantity, base, over, &xs);
        Self {
            paper: curve(Theory::Paper, TheoryQuantity::Gain1),
            exact: curve(Theory::Exact, TheoryQuantity::PeakGain),
            prefix: if shockley { "PWL theory: " } else { "" },
        }
    }

    /// The exact sliding orbit's A1/β over the same abscissae: the gain of the paper's
    /// definition, to compare with the paper's eq. (11) and with the simulated A1/β.
    pub fn exact_a1(
        base: &Params,
        over: Parameter,
        (from, to, steps): (f64, f64, usize),
    ) -> TheoryCurve {
        let xs = abscissae(from, to, steps);
        theory_curve(Theory::Exact, TheoryQuantity::Gain1, base, over, &xs)
    }
}

/// Abscissae of a theory curve over [from, to]: evenly spaced, both ends included, at least
/// [`MIN_POINTS`] (or `steps` if more); a single point when the range is one value.
pub fn abscissae(from: f64, to: f64, steps: usize) -> Vec<f64> {
    if to <= from {
        return vec![from];
    }
    let n = steps.max(MIN_POINTS);
    (0..n)
        .map(|i| crate::scan::grid_value(from, to, i, n - 1))
        .collect()
}

/// The frequencies of a curve over w (`stickslip theory --curve`): from `w_min` to `w_max`,
/// both included, `steps` points, evenly or logarithmically spaced.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct CurveRange {
    /// Smallest w (within the range of w). Default 0.2.
    pub w_min: f64,
    /// Largest w (> `w_min`, within the range of w). Default 3.
    pub w_max: f64,
    /// Points, both ends included (2 to 100000). Default 200.
    pub steps: usize,
    /// Logarithmic spacing. Default false.
    pub log: bool,
}

impl Default for CurveRange {
    fn default() -> Self {
        Self {
            w_min: 0.2,
            w_max: 3.0,
            steps: 200,
            log: false,
        }
    }
}

impl CurveRange {
    /// Check every field against the option table, and that `w_max` > `w_min`.
    ///
    /// # Errors
    /// [`crate::Error::InvalidOption`] naming the first bad field.
    pub fn validate(self) -> crate::Result<Self> {
        use crate::options::{Allowed, OptionKey};
        OptionKey::CurveWMin.check(self.w_min)?;
        OptionKey::CurveWMax.check(self.w_max)?;
        if !(self.w_max > self.w_min) {
            return Err(crate::Error::InvalidOption {
                option: OptionKey::CurveWMax,
                value: self.w_max,
                allowed: Allowed::Above {
                    other: OptionKey::CurveWMin,
                    value: self.w_min,
                },
            });
        }
        OptionKey::CurveSteps.check_count(self.steps)?;
        Ok(self)
    }

    /// The frequencies, the ends exactly as given (a validated range).
    pub fn values(&self) -> Vec<f64> {
        let (lo, hi, n) = (self.w_min, self.w_max, self.steps.max(2) - 1);
        if self.log {
            let mut ws: Vec<f64> = crate::solver::grid(lo.ln(), hi.ln(), n)
                .into_iter()
                .map(f64::exp)
                .collect();
            // The ends exactly as given, not through ln and exp.
            ws[0] = lo;
            ws[n] = hi;
            ws
        } else {
            (0..=n)
                .map(|i| crate::scan::grid_value(lo, hi, i, n))
                .collect()
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_curve_range_is_checked_and_keeps_its_ends() {
        let e = CurveRange {
            w_min: 2.0,
            w_max: 1.0,
            ..Default::default()
        }
        .validate()
        .unwrap_err();
        assert_eq!(
            e.render(crate::Spelling::Flag),
            "invalid --w-max 1: must be greater than --w-min 2"
        );
        let e = CurveRange {
            w_min: 0.0,
            ..Default::default()
        }
        .validate()
        .unwrap_err();
        assert_eq!(e.option(), Some(crate::OptionKey::CurveWMin));
        for log in [false, true] {
            let r = CurveRange {
                w_min: 0.05,
                w_max: 10.0,
                steps: 7,
                log,
            }
            .validate()
            .unwrap();
            let ws = r.values();
            assert_eq!((ws.len(), ws[0], ws[6]), (7, 0.05, 10.0));
            assert!(ws.windows(2).all(|p| p[1] > p[0]));
        }
    }

    #[test]
    fn abscissae_cover_the_range_ends_included() {
        let xs = abscissae(0.5, 2.0, 3);
        assert_eq!(xs.len(), MIN_POINTS);
        assert_eq!((xs[0], xs[MIN_POINTS - 1]), (0.5, 2.0));
        assert!(xs.windows(2).all(|p| p[1] > p[0]));
        assert_eq!(abscissae(0.5, 2.0, 500).len(), 500);
        assert_eq!(abscissae(1.0, 1.0, 1), vec![1.0]);
    }

    #[test]
    fn gain_curves_exist_above_the_boundary_only() {
        let params = Params::new(0.0468, 0.9, 1.6).unwrap();
        let xs = [0.9, 0.2];
        let exact = theory_curve(
            Theory::Exact,
            TheoryQuantity::PeakGain,
            &params,
            Parameter::W,
            &xs,
        );
        let orbit = PeriodicSolution::new(&params).unwrap();
        assert_eq!(exact.y[0], orbit.peak / 1.6);
        // The peak is not the fundamental: the two gains differ.
        assert!((exact.y[0] - orbit.gain1()).abs() > 1e-3 * orbit.gain1());
        assert!(exact.y[1].is_nan());
        assert_eq!(exact.present(), 1);
        let paper = theory_curve(
            Theory::Paper,
            TheoryQuantity::Gain1,
            &params,
            Parameter::W,
            &xs,
        );
        assert!(paper.y[0] > 0.0);
        let none = theory_curve(
            Theory::Paper,
            TheoryQuantity::PeakGain,
            &params,
            Parameter::W,
            &xs,
        );
        assert_eq!(none.present(), 0);
    }

    #[test]
    fn boundary_curves_are_cut_to_a_window() {
        let base = Params::new(0.0468, 1.0, 0.0).unwrap();
        let ws = [0.3, 0.9, 1.5];
        for theory in [Theory::Paper, Theory::Exact] {
            let full = theory_curve(theory, TheoryQuantity::Boundary, &base, Parameter::W, &ws);
            assert_eq!(full.present(), 3);
            let cut = full.clone().within(0.5, 4.0);
            for (c, f) in cut.y.iter().zip(&full.y) {
                if (0.5..=4.0).contains(f) {
                    assert_eq!(c, f);
                } else {
                    assert!(c.is_nan());
                }
            }
        }
        // At w = 0.3 the exact β_c lies above 4 (many stops per period below it).
        let exact = theory_curve(
            Theory::Exact,
            TheoryQuantity::Boundary,
            &base,
            Parameter::W,
            &ws,
        );
        assert!(exact.y[0] > 4.0);
        assert!(exact.within(0.5, 4.0).y[0].is_nan());
    }

    #[test]
    fn harmonics_of_both_theories() {
        let p = Params::new(0.0468, 0.9, 2.0).unwrap();
        let a3p = theory_value(Theory::Paper, TheoryQuantity::Harmonic(3), &p).unwrap();
        let a3e = theory_value(Theory::Exact, TheoryQuantity::Harmonic(3), &p).unwrap();
        // The paper's superharmonics are exact for a sliding motion.
        assert!((a3p - a3e).abs() < 1e-12 * a3e);
        assert!(theory_value(Theory::Paper, TheoryQuantity::Harmonic(2), &p).is_none());
    }
}
