//! What a motion settles on, read off its strobe points: a periodic orbit, rest, chaos or
//! quasi-periodic motion.
//!
//! The strobe points are the states at τ = kT (T = 2π/w, drive phase φ), the orbit of the
//! strobe map P. [`record_strobes`] runs the exact solver through a transient and then records
//! N strobe points, carrying the exact Jacobian J of the flow along
//! ([`crate::stability::TangentSolver`]), so that the largest Lyapunov exponent of the same
//! stretch of motion comes with the points at about 1.2 times the cost of the points alone:
//!
//! ```text
//! λ₁ = Σ_b ln‖J_b‖ / (N T)     per unit τ,
//! ```
//!
//! with J renormalised at the end of each of B blocks of N/B periods (B = 10, or N/4 when
//! N < 40), and the standard error of λ₁ from the B block means (as in
//! [`crate::stability::lyapunov`], which measures the exponent at length).
//!
//! **Verdict** ([`AttractorKind`]), from the points and the exponent:
//!
//! - *periodic* with period p: the smallest p ≤ [`RecordOptions::max_period`] (and ≤ N/2)
//!   with |x_{k+p} − x_k| ≤ tol·scale for every recorded k (max norm over y and y', scale the
//!   largest |y| or |y'| recorded, at least 1); a period-p orbit gives exactly p distinct
//!   strobe points;
//! - *static* (rest): periodic without a single event while recording: the oscillator stays
//!   stuck (a motion that slides has turning points or stops);
//! - otherwise, with σ the standard error and k = [`RecordOptions::significance`]: *chaotic*
//!   when λ₁ > kσ, *quasi-periodic* when |λ₁| ≤ kσ, and *undecided* (no verdict within the
//!   budget) when λ₁ < −kσ (the motion still contracts onto an attractor it has not reached,
//!   for example a periodic orbit whose multiplier is close to 1, or one of a longer period
//!   than was looked for), or when too few points were recorded (N < 8) to judge.
//!
//! The verdict rests on N periods only: a short record calls a weakly chaotic motion
//! quasi-periodic or undecided rather than chaotic.
//! [`crate::stability::classify_nonperiodic`] decides at length.

use crate::error::{invalid, Result};
use crate::options::OptionKey;
use crate::params::{Params, State};
use crate::solver::{EventKind, Phase};
use crate::stability::{Dynamics, ExactDynamics, NonperiodicVerdict, TangentRun};
use serde::{Deserialize, Serialize};

/// What a motion settles on (see the module documentation).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum AttractorKind {
    /// A periodic orbit: the strobe points repeat after p drive periods.
    Periodic,
    /// Rest: the oscillator stays stuck.
    Static,
    /// Chaos: a significantly positive largest Lyapunov exponent.
    Chaotic,
    /// Neither repeating nor separating nor contracting: a largest exponent within its error
    /// of zero (motion on a torus).
    #[serde(rename = "quasiperiodic")]
    QuasiPeriodic,
    /// Not decided within the budget (label `undecided`, as the steady states'
    /// [`crate::steady::MotionClass::Undecided`]; before: `unsettled`, which still reads): the
    /// motion still contracts onto something it has not reached, or the record is too short
    /// to judge. No kind of motion.
    #[serde(alias = "unsettled")]
    Undecided,
}

impl AttractorKind {
    /// Every kind, in the order of legends.
    pub const ALL: [AttractorKind; 5] = [
        AttractorKind::Periodic,
        AttractorKind::Static,
        AttractorKind::Chaotic,
        AttractorKind::QuasiPeriodic,
        AttractorKind::Undecided,
    ];

    /// Labels retired, with the kind each now reads as: `unsettled` (now `undecided`).
    pub const RETIRED: [(&'static str, AttractorKind); 1] =
        [("unsettled", AttractorKind::Undecided)];

    /// The former name of [`AttractorKind::Undecided`].
    #[deprecated(note = "the kind is `AttractorKind::Undecided` (label `undecided`)")]
    #[allow(non_upper_case_globals)]
    pub const Unsettled: AttractorKind = AttractorKind::Undecided;

    /// The label used in CSV and JSON: `periodic`, `static`, `chaotic`, `quasiperiodic`,
    /// `undecided`.
    pub fn label(self) -> &'static str {
        match self {
            AttractorKind::Periodic => "periodic",
            AttractorKind::Static => "static",
            AttractorKind::Chaotic => "chaotic",
            AttractorKind::QuasiPeriodic => "quasiperiodic",
            AttractorKind::Undecided => "undecided",
        }
    }

    /// The kind with this label.
    pub fn from_label(label: &str) -> Option<Self> {
        label.parse().ok()
    }
}

/// Options of [`record_strobes`].
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct RecordOptions {
    /// Drive periods run before recording. Default 200.
    pub transient_periods: usize,
    /// Strobe points recorded (N ≥ 1; the exponent is measured over these N periods).
    /// Default 100.
    pub points: usize,
    /// Longest period looked for, in drive periods (at most N/2 is used). Default 32.
    pub max_period: usize,
    /// Relative tolerance of the repetition of the strobe points. Default 1e-8.
    pub tolerance: f64,
    /// Standard errors that make the exponent significantly positive or negative. Default 4.
    pub significance: f64,
}

impl Default for RecordOptions {
    fn default() -> Self {
        Self {
            transient_periods: 200,
            points: 100,
            max_period: 32,
            tolerance: 1e-8,
            significance: 4.0,
        }
    }
}

impl RecordOptions {
    /// Check every field.
    ///
    /// # Errors
    /// [`Error::InvalidOption`](crate::Error::InvalidOption) naming the points, the transient or the longest period
    /// ([`crate::options`]); [`Error::InvalidParameter`](crate::Error::InvalidParameter) naming the tolerance or the
    /// significance.
    pub fn validate(self) -> Result<Self> {
        OptionKey::Points.check_count(self.points)?;
        OptionKey::BifurcationTransient.check_count(self.transient_periods)?;
        OptionKey::BifurcationMaxPeriod.check_count(self.max_period)?;
        if !(self.tolerance > 0.0 && self.tolerance < 1.0) {
            return invalid("tolerance", self.tolerance, "must be > 0 and < 1");
        }
        if !(self.significance > 0.0 && self.significance.is_finite()) {
            return invalid("significance", self.significance, "must be finite and > 0");
        }
        Ok(self)
    }
}

/// The strobe points of a motion after a transient, the largest Lyapunov exponent measured
/// along them, and the verdict (see the module documentation).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct StrobeRecord {
    /// The recorded strobe points x_1 … x_N, at τ = (transient + k)T from the start.
    pub strobes: Vec<State>,
    /// The largest Lyapunov exponent over the N recorded periods, per unit τ (in a
    /// [`crate::bifurcation`] diagram, for a motion that does not repeat, the sequential
    /// measurement from the last point instead).
    pub exponent: f64,
    /// Its standard error from the block means, per unit τ (NaN when N < 8).
    pub exponent_error: f64,
    /// The period p in drive periods, when the points repeat.
    pub period: Option<usize>,
    /// The verdict.
    pub kind: AttractorKind,
    /// Events while recording.
    pub events: usize,
    /// Stops (stick events) while recording.
    pub stops: usize,
    /// The drive period T = 2π/w (dimensionless time).
    pub drive_period: f64,
}

impl StrobeRecord {
    /// The state at the end of the record (the last strobe point).
    pub fn final_state(&self) -> State {
        *self
            .strobes
            .last()
            .expect("a record has at least one point")
    }

    /// The largest exponent per drive period, λ₁·T.
    pub fn exponent_per_period(&self) -> f64 {
        self.exponent * self.drive_period
    }
}

/// Whether the strobe points `sample` lie on the strobe set `reference`: at least 90 % of
/// them within 10 % of the set's extent of one of its points (how a basin map tells the cells
/// of one chaotic or quasi-periodic attractor from another's).
pub fn strobe_sets_overlap(reference: &[State], sample: &[State]) -> bool {
    if reference.is_empty() || sample.is_empty() {
        return false;
    }
    let (mut ylo, mut yhi, mut vlo, mut vhi) = (
        f64::INFINITY,
        f64::NEG_INFINITY,
        f64::INFINITY,
        f64::NEG_INFINITY,
    );
    for s in reference {
        (ylo, yhi, vlo, vhi) = (ylo.min(s.y), yhi.max(s.y), vlo.min(s.v), vhi.max(s.v));
    }
    let radius = 0.1 * (yhi - ylo).max(vhi - vlo).max(1e-9 * scale_of(reference));
    let near = sample
        .iter()
        .filter(|x| reference.iter().any(|r| distance(*r, **x) <= radius))
        .count();
    near * 10 >= sample.len() * 9
}

/// Whether two records settled on the same attractor, compared as sets of strobe points the
/// way a basin map identifies its attractors ([`crate::basins`]): rest is one attractor;
/// periodic orbits are the same when their periods agree and a strobe point of one lies within
/// `tolerance`·scale of one of the other's (the same orbit recorded at another phase);
/// chaotic and quasi-periodic motions of one kind are the same when each strobe set lies on
/// the other ([`strobe_sets_overlap`]: the same attractor sampled at other times). A record
/// not decided ([`AttractorKind::Undecided`]) matches nothing.
pub fn same_attractor(a: &StrobeRecord, b: &StrobeRecord, tolerance: f64) -> bool {
    if a.kind != b.kind {
        return false;
    }
    match a.kind {
        AttractorKind::Undecided => false,
        AttractorKind::Static => true,
        AttractorKind::Periodic => {
            let Some(&x) = a.strobes.first() else {
                return false;
            };
            let limit = tolerance * scale_of(&[x]);
            a.period == b.period && b.strobes.iter().any(|s| distance(*s, x) <= limit)
        }
        AttractorKind::Chaotic | AttractorKind::QuasiPeriodic => {
            strobe_sets_overlap(&a.strobes, &b.strobes)
                && strobe_sets_overlap(&b.strobes, &a.strobes)
        }
    }
}

/// Largest |component| difference of two states.
pub(crate) fn distance(a: State, b: State) -> f64 {
    (a.y - b.y).abs().max((a.v - b.v).abs())
}

/// The largest |y| or |y'| of `states`, at least 1.
pub(crate) fn scale_of(states: &[State]) -> f64 {
    states
        .iter()
        .fold(1.0f64, |s, x| s.max(x.y.abs()).max(x.v.abs()))
}

/// The smallest p ≤ `max_period` (and ≤ N/2) after which every recorded point repeats within
/// `tolerance`·scale (see the module documentation).
pub fn detect_period(strobes: &[State], max_period: usize, tolerance: f64) -> Option<usize> {
    let limit = tolerance * scale_of(strobes);
    let longest = max_period.min(strobes.len() / 2);
    (1..=longest)
        .find(|&p| (p..strobes.len()).all(|k| distance(strobes[k], strobes[k - p]) <= limit))
}

/// Run the exact solver from `initial` at τ = 0 (a strobe) through
/// [`RecordOptions::transient_periods`], then record [`RecordOptions::points`] strobe points
/// with the largest Lyapunov exponent along them, and judge what the motion settled on (see
/// the module documentation).
///
/// ```
/// use stickslip::attractor::{record_strobes, AttractorKind, RecordOptions};
/// use stickslip::{Params, State};
/// // The paper's circuit at (w, β) = (0.9, 1.6): a sliding orbit of period 1.
/// let params = Params::new(0.0468, 0.9, 1.6).unwrap();
/// let record = record_strobes(&params, State::default(), &RecordOptions::default()).unwrap();
/// assert_eq!((record.kind, record.period), (AttractorKind::Periodic, Some(1)));
/// assert!(record.exponent < 0.0);
/// ```
///
/// # Errors
/// [`Error::InvalidParameter`](crate::Error::InvalidParameter) for invalid parameters, state or options; whatever the solver
/// reports.
pub fn record_strobes(
    params: &Params,
    initial: State,
    options: &RecordOptions,
) -> Result<StrobeRecord> {
    record_strobes_of(&ExactDynamics, params, initial, options)
}

/// [`record_strobes`] on the model `dynamics` (its tangent dynamics, and the points taken to
/// repeat within its [`Dynamics::repeat_tolerance`] of [`RecordOptions::tolerance`]).
///
/// # Errors
/// As [`record_strobes`].
pub fn record_strobes_of(
    dynamics: &dyn Dynamics,
    params: &Params,
    initial: State,
    options: &RecordOptions,
) -> Result<StrobeRecord> {
    let options = options.validate()?;
    let params = params.validate()?;
    let initial = State::new(initial.y, initial.v)?;
    let period = params.drive_period();
    let mut tangent = dynamics.tangent(&params, initial)?;
    let tangent: &mut dyn TangentRun = tangent.as_mut();
    tangent.run_until(options.transient_periods as f64 * period, &mut |_| {})?;
    // The transient has turned J into the most unstable direction; measure from here, on a
    // solver whose clock starts afresh (small absolute times; see `TangentSolver`).
    tangent.renormalize();
    tangent.restart_clock();
    let n = options.points;
    let blocks = if n >= 40 { 10 } else { (n / 4).max(1) };
    let mut strobes = Vec::with_capacity(n);
    let mut block_growth = Vec::with_capacity(blocks);
    let mut block_periods = Vec::with_capacity(blocks);
    let (mut events, mut stops) = (0usize, 0usize);
    let mut in_block = 0usize;
    for k in 1..=n {
        tangent.run_until(k as f64 * period, &mut |e| {
            events += 1;
            stops += usize::from(e.kind == EventKind::Stick);
        })?;
        strobes.push(tangent.state());
        in_block += 1;
        // Blocks of n/blocks periods, the last one taking the remainder.
        let end_of_block = block_growth.len() + 1 < blocks && in_block == n / blocks || k == n;
        if end_of_block {
            if tangent.grazing().is_some() {
                // A tangential release: J is not finite from there on; start it afresh.
                tangent.reset();
                block_growth.push(f64::NAN);
            } else {
                block_growth.push(tangent.renormalize());
            }
            block_periods.push(in_block);
            in_block = 0;
        }
    }
    let means: Vec<f64> = block_growth
        .iter()
        .zip(&block_periods)
        .filter(|(g, _)| g.is_finite() || **g == f64::NEG_INFINITY)
        .map(|(g, &m)| g / (m as f64 * period))
        .collect();
    let total_periods: usize = block_growth
        .iter()
        .zip(&block_periods)
        .filter(|(g, _)| g.is_finite() || **g == f64::NEG_INFINITY)
        .map(|(_, &m)| m)
        .sum();
    let exponent = if total_periods > 0 {
        block_growth
            .iter()
            .filter(|g| g.is_finite() || **g == f64::NEG_INFINITY)
            .sum::<f64>()
            / (total_periods as f64 * period)
    } else {
        f64::NAN
    };
    let exponent_error = if n >= 8 && means.len() >= 2 && means.iter().all(|m| m.is_finite()) {
        let count = means.len() as f64;
        let mean = means.iter().sum::<f64>() / count;
        let var = means.iter().map(|m| (m - mean) * (m - mean)).sum::<f64>() / (count - 1.0);
        (var / count).sqrt()
    } else {
        f64::NAN
    };
    let found = detect_period(
        &strobes,
        options.max_period,
        dynamics.repeat_tolerance(options.tolerance),
    );
    let stuck = tangent.phase() == Phase::Stick;
    // (The verdict of every tool on a motion that does not repeat; a contracting one has
    // not reached its attractor, which is then not known.)
    let verdict = NonperiodicVerdict::of(
        exponent,
        exponent_error,
        exponent_error.is_finite(),
        options.significance,
    );
    let kind = match (found, verdict) {
        (Some(_), _) if events == 0 && stuck => AttractorKind::Static,
        (Some(_), _) => AttractorKind::Periodic,
        (None, NonperiodicVerdict::Chaotic) => AttractorKind::Chaotic,
        (None, NonperiodicVerdict::QuasiPeriodic) => AttractorKind::QuasiPeriodic,
        (None, _) => AttractorKind::Undecided,
    };
    Ok(StrobeRecord {
        strobes,
        exponent,
        exponent_error,
        period: found,
        kind,
        events,
        stops,
        drive_period: period,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::error::Error;

    fn s(y: f64, v: f64) -> State {
        State { y, v }
    }

    #[test]
    fn periods_are_the_smallest_repetition() {
        let two: Vec<State> = (0..10).map(|k| s((k % 2) as f64, 0.5)).collect();
        assert_eq!(detect_period(&two, 8, 1e-12), Some(2));
        let one = vec![s(1.0, 2.0); 6];
        assert_eq!(detect_period(&one, 8, 1e-12), Some(1));
        let drifting: Vec<State> = (0..10).map(|k| s(k as f64 * 1e-3, 0.0)).collect();
        assert_eq!(detect_period(&drifting, 8, 1e-6), None);
        // A period needs two repetitions in the record.
        let three: Vec<State> = (0..5).map(|k| s((k % 3) as f64, 0.0)).collect();
        assert_eq!(detect_period(&three, 8, 1e-12), None);
    }

    fn record(kind: AttractorKind, period: Option<usize>, strobes: Vec<State>) -> StrobeRecord {
        StrobeRecord {
            strobes,
            exponent: 0.0,
            exponent_error: 0.0,
            period,
            kind,
            events: 0,
            stops: 0,
            drive_period: 1.0,
        }
    }

    #[test]
    fn attractors_are_compared_as_sets_of_strobe_points() {
        let orbit: Vec<State> = (0..12).map(|k| s([1.0, 2.0, 3.0][k % 3], 0.0)).collect();
        // The same period-3 orbit recorded at another phase: the same attractor, though its
        // first strobe points differ.
        let shifted: Vec<State> = orbit.iter().skip(1).copied().collect();
        let a = record(AttractorKind::Periodic, Some(3), orbit.clone());
        let b = record(AttractorKind::Periodic, Some(3), shifted);
        assert!(a.strobes[0] != b.strobes[0] && same_attractor(&a, &b, 1e-6));
        let other = record(AttractorKind::Periodic, Some(3), vec![s(1.5, 0.0); 12]);
        assert!(!same_attractor(&a, &other, 1e-6));
        let once = record(AttractorKind::Periodic, Some(1), vec![s(1.0, 0.0); 12]);
        assert!(!same_attractor(&a, &once, 1e-6));
        // A chaotic set sampled at other times: the same attractor; a set elsewhere is not.
        let cloud = |phase: f64, shift: f64| -> Vec<State> {
            (0..200)
                .map(|k| {
                    let t = phase + 2.399 * k as f64;
                    s(t.cos() + shift, (1.3 * t).sin())
                })
                .collect()
        };
        let c1 = record(AttractorKind::Chaotic, None, cloud(0.0, 0.0));
        let c2 = record(AttractorKind::Chaotic, None, cloud(0.7, 0.0));
        let c3 = record(AttractorKind::Chaotic, None, cloud(0.0, 5.0));
        assert!(same_attractor(&c1, &c2, 1e-6) && !same_attractor(&c1, &c3, 1e-6));
        // Kinds differ: different attractors; undecided matches nothing, not even itself.
        let q = record(AttractorKind::QuasiPeriodic, None, cloud(0.0, 0.0));
        assert!(!same_attractor(&c1, &q, 1e-6));
        let u = record(AttractorKind::Undecided, None, cloud(0.0, 0.0));
        assert!(!same_attractor(&u, &u, 1e-6));
        let rest = record(AttractorKind::Static, Some(1), vec![s(0.3, 0.0); 4]);
        let rest2 = record(AttractorKind::Static, Some(1), vec![s(-0.2, 0.0); 4]);
        assert!(same_attractor(&rest, &rest2, 1e-6));
    }

    #[test]
    fn labels_round_trip() {
        for k in AttractorKind::ALL {
            assert_eq!(AttractorKind::from_label(k.label()), Some(k));
            let json = serde_json::to_string(&k).unwrap();
            assert_eq!(json, format!("\"{}\"", k.label()));
        }
    }

    #[test]
    fn rest_is_static_and_options_are_checked() {
        // β < μs − |y|: never leaves rest.
        let params = Params::new(0.05, 0.7, 0.5).unwrap();
        let r =
            record_strobes(&params, State { y: 0.2, v: 0.0 }, &RecordOptions::default()).unwrap();
        assert_eq!(
            (r.kind, r.period, r.events),
            (AttractorKind::Static, Some(1), 0)
        );
        assert_eq!(r.exponent, 0.0);
        let bad = RecordOptions {
            points: 0,
            ..RecordOptions::default()
        };
        assert!(matches!(
            record_strobes(&params, State::default(), &bad),
            Err(Error::InvalidOption {
                option: crate::options::OptionKey::Points,
                ..
            })
        ));
    }
}
