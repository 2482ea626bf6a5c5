//! Motion classes (the paper's Fig. 6), decided from the exact event log, and `chaotic`, decided
//! from the largest Lyapunov exponent of a motion that does not repeat.
//!
//! A *stop* is a Stick event followed by a Slip event (or the end of the record); it counts
//! only when it lasts longer than a tiny fraction of the drive period
//! ([`super::SteadyOptions::min_stop_fraction`], 10⁻⁸ by default). A stop of exactly zero
//! duration is a turning point at which the net force sits on the static-friction limit, and
//! rounding can turn such a point into a Stick followed by a Slip a few ulps later; no
//! genuine stop is that short, since a stop of duration Δτ needs the force to pass the limit
//! by about β(wΔτ)²/2, i.e. ~10⁻¹⁵β for Δτ = 10⁻⁸·T.

use crate::solver::{Event, EventKind};
use serde::{Deserialize, Serialize};

/// The largest gain of a [`MotionClass::Static`] motion: a motion is static when its amplitude
/// (max y − min y)/2 is at most this fraction of β, i.e. its gain G = amplitude/β is at most
/// 0.01 (1 %), whether or not it stops; [`classify`] applies it before anything else.
pub const STATIC_GAIN: f64 = 0.01;

/// The kinds of steady motion of the paper's Fig. 6, chaos, and the motions not decided
/// within the budget.
///
/// [`classify`] decides from the event log. A motion that does not repeat is then measured by
/// its largest Lyapunov exponent λ₁ (with the exact model or a smooth law's tangent, see
/// [`super::SteadyOptions::lyapunov`]): it is [`MotionClass::Chaotic`] when λ₁ is positive
/// beyond its error, and otherwise stays [`MotionClass::Undecided`] (with stops) or
/// [`MotionClass::Sliding`] (without), with λ₁ and its verdict reported beside it.
///
/// [`MotionClass::Undecided`] is no kind of motion: it says that the budget (no period up to
/// the maximum period within the cap on drive periods, and no significantly positive λ₁) did
/// not decide. The paper's fourth class, "non-periodic motion with sticking", is where such
/// motions land: its label was `nonperiodic-stick`, which [`MotionClass::from_label`] and
/// serde still read.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum MotionClass {
    /// No stop in the recorded cycle: the velocity only reverses.
    Sliding,
    /// Periodic (period p ≤ the maximum period) with at least one stop of non-zero duration.
    PeriodicStick,
    /// Not decided within the budget: no period found within the cap on drive periods, with
    /// stops, and λ₁ not positive beyond its error (or not measured). Label `undecided`
    /// (before: `nonperiodic-stick`, the paper's "non-periodic motion with sticking").
    #[serde(alias = "nonperiodic-stick")]
    Undecided,
    /// Amplitude of y at most β/100 (gain at most [`STATIC_GAIN`]; for example never leaves
    /// rest, or creeps with stops).
    Static,
    /// No period found, and the largest Lyapunov exponent is positive beyond its error
    /// (nearby motions separate exponentially): chaos.
    Chaotic,
    /// A self-excited cycle on a moving belt (no drive) with stops: the block sticks to the
    /// belt, is carried, slips and sticks again ([`super::self_excited`]).
    StickSlipCycle,
    /// A self-excited cycle on a moving belt that never sticks.
    PureSlipCycle,
    /// Steady sliding on a moving belt: the equilibrium y' = 0, y = sgn(vb)·μ(|vb|).
    SteadySliding,
}

impl MotionClass {
    /// All classes, in the order used for legends and colours. The index of a class here is
    /// its code in the Python package's `motion` arrays, so a new class is always added last.
    pub const ALL: [MotionClass; 8] = [
        MotionClass::Sliding,
        MotionClass::PeriodicStick,
        MotionClass::Undecided,
        MotionClass::Static,
        MotionClass::Chaotic,
        MotionClass::StickSlipCycle,
        MotionClass::PureSlipCycle,
        MotionClass::SteadySliding,
    ];

    /// Labels retired, with the class each now reads as: `nonperiodic-stick` (now
    /// `undecided`).
    pub const RETIRED: [(&'static str, MotionClass); 1] =
        [("nonperiodic-stick", MotionClass::Undecided)];

    /// The former name of [`MotionClass::Undecided`].
    #[deprecated(note = "the class is `MotionClass::Undecided` (label `undecided`)")]
    #[allow(non_upper_case_globals)]
    pub const NonperiodicStick: MotionClass = MotionClass::Undecided;

    /// The label used in CSV and JSON: `sliding`, `periodic-stick`, `undecided`, `static`,
    /// `chaotic`, `stick-slip-cycle`, `pure-slip-cycle`, `steady-sliding`.
    pub fn label(self) -> &'static str {
        match self {
            MotionClass::Sliding => "sliding",
            MotionClass::PeriodicStick => "periodic-stick",
            MotionClass::Undecided => "undecided",
            MotionClass::Static => "static",
            MotionClass::Chaotic => "chaotic",
            MotionClass::StickSlipCycle => "stick-slip-cycle",
            MotionClass::PureSlipCycle => "pure-slip-cycle",
            MotionClass::SteadySliding => "steady-sliding",
        }
    }

    /// The classes of the paper's driven oscillator (and chaos): those a map of a driven
    /// motion can show, in [`MotionClass::ALL`]'s order.
    pub const DRIVEN: [MotionClass; 5] = [
        MotionClass::Sliding,
        MotionClass::PeriodicStick,
        MotionClass::Undecided,
        MotionClass::Static,
        MotionClass::Chaotic,
    ];

    /// The class with this label (or a retired label, [`MotionClass::RETIRED`]).
    pub fn from_label(label: &str) -> Option<Self> {
        MotionClass::ALL
            .into_iter()
            .find(|c| c.label() == label)
            .or_else(|| {
                MotionClass::RETIRED
                    .iter()
                    .find(|(old, _)| *old == label)
                    .map(|&(_, c)| c)
            })
    }
}

/// The class of a recorded stretch of motion and its stops.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Classification {
    /// The motion class.
    pub class: MotionClass,
    /// Stops longer than the threshold in the record (a stop straddling the ends of a
    /// periodic record counts once; being stuck for the whole record is not a stop).
    pub stops: usize,
    /// Stops per drive period.
    pub stops_per_period: f64,
    /// Longest stop in the record, dimensionless time (0 without stops; infinite when the
    /// oscillator is stuck for the whole record).
    pub longest_stop: f64,
}

/// Classify a record of `periods` drive periods from τ = `start` to τ = `end` from its events
/// (never [`MotionClass::Chaotic`], which takes the Lyapunov exponent).
///
/// - `events`: the events inside the record, in order;
/// - `stuck_at_start`: whether the oscillator was stuck at `start`;
/// - `periodic`: whether the record is one period of a converged cycle (then a stop running
///   over the end continues at the start, and the two parts are one stop);
/// - `amplitude`: (max y − min y)/2 over the record; `beta`: the drive amplitude;
/// - `min_stop`: shortest duration that counts as a stop (dimensionless time).
pub fn classify(
    events: &[Event],
    start: f64,
    end: f64,
    periods: usize,
    stuck_at_start: bool,
    periodic: bool,
    amplitude: f64,
    beta: f64,
    min_stop: f64,
) -> Classification {
    let mut durations = Vec::new();
    let mut stuck_since = stuck_at_start.then_some(start);
    // Duration of a stop that began before the record, up to its first Slip.
    let mut head: Option<f64> = None;
    for e in events {
        match e.kind {
            EventKind::Stick => stuck_since = Some(e.tau),
            EventKind::Slip => {
                if let Some(s) = stuck_since.take() {
                    if stuck_at_start && s == start && head.is_none() && durations.is_empty() {
                        head = Some(e.tau - start);
                    } else {
                        durations.push(e.tau - s);
                    }
                }
            }
            EventKind::Turn => {}
        }
    }
    let tail = stuck_since.map(|s| end - s);
    match (head, tail) {
        (Some(h), Some(t)) if periodic => durations.push(h + t),
        (None, Some(_)) if stuck_at_start && events.is_empty() => durations.push(f64::INFINITY),
        (h, t) => durations.extend(h.into_iter().chain(t)),
    }
    // A stop lasting the whole record is rest, not a stop of the motion.
    let stops = durations
        .iter()
        .filter(|&&d| d > min_stop && d.is_finite())
        .count();
    let longest_stop = durations.iter().copied().fold(0.0, f64::max);
    let class = if amplitude <= beta * STATIC_GAIN {
        MotionClass::Static
    } else if stops > 0 && periodic {
        MotionClass::PeriodicStick
    } else if stops > 0 {
        MotionClass::Undecided
    } else {
        MotionClass::Sliding
    };
    Classification {
        class,
        stops,
        stops_per_period: stops as f64 / periods.max(1) as f64,
        longest_stop,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn ev(tau: f64, kind: EventKind) -> Event {
        Event { tau, y: 0.0, kind }
    }

    #[test]
    fn labels_round_trip() {
        for c in MotionClass::ALL {
            assert_eq!(MotionClass::from_label(c.label()), Some(c));
        }
        assert_eq!(MotionClass::from_label("none"), None);
        // The label retired keeps reading, in text and in JSON (checkpoints, old files).
        assert_eq!(
            MotionClass::from_label("nonperiodic-stick"),
            Some(MotionClass::Undecided)
        );
        let old: MotionClass = serde_json::from_str("\"nonperiodic-stick\"").unwrap();
        assert_eq!(old, MotionClass::Undecided);
        assert_eq!(
            serde_json::to_string(&MotionClass::Undecided).unwrap(),
            "\"undecided\""
        );
    }

    #[test]
    fn codes_of_the_paper_classes_stay_put() {
        // The Python package's int8 `motion` codes are indices into ALL: chaos came last.
        let labels: Vec<&str> = MotionClass::ALL.iter().map(|c| c.label()).collect();
        assert_eq!(
            labels,
            [
                "sliding",
                "periodic-stick",
                "undecided",
                "static",
                "chaotic",
                "stick-slip-cycle",
                "pure-slip-cycle",
                "steady-sliding"
            ]
        );
    }

    #[test]
    fn zero_duration_stops_are_turns() {
        let events = [
            ev(1.0, EventKind::Stick),
            ev(1.0, EventKind::Slip),
            ev(3.0, EventKind::Turn),
        ];
        let c = classify(&events, 0.0, 4.0, 1, false, true, 2.0, 1.5, 1e-8);
        assert_eq!(c.class, MotionClass::Sliding);
        assert_eq!(c.stops, 0);
    }

    #[test]
    fn a_stop_over_the_end_of_a_cycle_counts_once() {
        // Stuck at the start until 0.5, slides, sticks again at 3.5 until the end (4.0).
        let events = [ev(0.5, EventKind::Slip), ev(3.5, EventKind::Stick)];
        let c = classify(&events, 0.0, 4.0, 1, true, true, 1.0, 1.2, 1e-8);
        assert_eq!(c.class, MotionClass::PeriodicStick);
        assert_eq!(c.stops, 1);
        assert!((c.longest_stop - 1.0).abs() < 1e-15);
        // Two stops per period over two periods.
        let events = [
            ev(1.0, EventKind::Stick),
            ev(1.5, EventKind::Slip),
            ev(3.0, EventKind::Stick),
            ev(3.5, EventKind::Slip),
        ];
        let c = classify(&events, 0.0, 4.0, 2, false, false, 1.0, 1.2, 1e-8);
        assert_eq!(c.class, MotionClass::Undecided);
        assert_eq!(c.stops_per_period, 1.0);
    }

    #[test]
    fn small_amplitude_is_static() {
        let c = classify(&[], 0.0, 4.0, 1, true, true, 0.0, 0.9, 1e-8);
        assert_eq!(c.class, MotionClass::Static);
        assert_eq!(c.longest_stop, f64::INFINITY);
        assert_eq!(c.stops, 0);
    }
}
