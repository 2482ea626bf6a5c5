//! Turns, stops and slips of a smooth diode, read off the dense output step by step.
//!
//! A smooth diode never holds the current at exactly zero, so the PWL notion of sticking is
//! replaced by a threshold rule:
//!
//! - a **dip** is an interval where |y'| < threshold (default 1e-3);
//! - a dip that lasts longer than a fraction of the drive period (default 1 %) is a **stop**:
//!   a `Stick` event at the time the dip began, and a `Slip` event when |y'| reaches the
//!   threshold again; the phase is `Stick` throughout, whatever the sign of the small current;
//! - a shorter dip is a **turn** when the current leaves it with the opposite sign to the one
//!   it entered with: one `Turn` event at the first zero of y' inside the dip (the phase
//!   changes there); a dip left with the entry sign is no event.
//!
//! Whether a dip is a stop is known only once it has lasted the minimum duration, so the
//! classification runs ahead of what the solver reports: events are always reported in time
//! order at their own times, and the integrator runs at most one minimum stop plus one step
//! ahead.

use crate::solver::{EventKind, Phase};
use crate::stiff::cubic::{crossings, horner, range};
use crate::stiff::Step;
use std::collections::VecDeque;

/// An event decided by the classifier, not yet reported.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Mark {
    /// Time of the event.
    pub tau: f64,
    /// What happened.
    pub kind: EventKind,
    /// The phase from the event on.
    pub phase_after: Phase,
}

#[derive(Debug, Clone, Copy, PartialEq)]
enum Mode {
    /// |y'| ≥ threshold, with the sign of y'.
    Moving { sign: f64 },
    /// |y'| < threshold since `start`, not yet long enough to be a stop.
    Dip {
        start: f64,
        entry_sign: f64,
        first_zero: Option<f64>,
        sign_now: f64,
    },
    /// A confirmed stop.
    Stopped,
}

/// The classifier's state.
#[derive(Debug, Clone)]
pub(crate) struct Classifier {
    mode: Mode,
    threshold: f64,
    min_stop: f64,
    /// The phase at τ = 0, once known.
    initial_phase: Option<Phase>,
    /// Events decided and not yet taken by the solver, in time order.
    pub marks: VecDeque<Mark>,
}

fn slip(sign: f64) -> Phase {
    if sign > 0.0 {
        Phase::SlipPositive
    } else {
        Phase::SlipNegative
    }
}

fn sign_of(v: f64) -> f64 {
    if v > 0.0 {
        1.0
    } else if v < 0.0 {
        -1.0
    } else {
        0.0
    }
}

impl Classifier {
    /// Start at τ = 0 with current `v0`.
    pub fn new(v0: f64, threshold: f64, min_stop: f64) -> Self {
        let (mode, initial_phase) = if v0.abs() >= threshold {
            (Mode::Moving { sign: sign_of(v0) }, Some(slip(v0)))
        } else {
            (
                Mode::Dip {
                    start: 0.0,
                    entry_sign: sign_of(v0),
                    first_zero: None,
                    sign_now: sign_of(v0),
                },
                None,
            )
        };
        Self {
            mode,
            threshold,
            min_stop,
            initial_phase,
            marks: VecDeque::new(),
        }
    }

    /// The phase at τ = 0, known once the initial dip (if any) is resolved.
    pub fn initial_phase(&self) -> Option<Phase> {
        self.initial_phase
    }

    /// Everything before this time is classified, given that the integration reached
    /// `integrated`.
    pub fn frontier(&self, integrated: f64) -> f64 {
        match self.mode {
            Mode::Dip { start, .. } => start,
            _ => integrated,
        }
    }

    /// Classify one more step, appending the events it decides to `marks`.
    pub fn feed(&mut self, step: &Step) {
        let cubic = step.cubic(1);
        // Most steps stay clear of the threshold: nothing to decide. First a cheap bound:
        // p(θ) minus its chord is −θ(1−θ)(p2 + p3(1+θ)), at most (|p2| + 2|p3|)/4.
        let (start, end) = (cubic[0], step.x1[1]);
        let bow = 0.25 * (cubic[2].abs() + 2.0 * cubic[3].abs());
        match self.mode {
            Mode::Moving { sign } if sign > 0.0 && start.min(end) - bow >= self.threshold => return,
            Mode::Moving { sign } if sign < 0.0 && start.max(end) + bow <= -self.threshold => {
                return
            }
            _ => {}
        }
        let (low, high) = range(&cubic);
        match self.mode {
            Mode::Moving { sign } if sign > 0.0 && low >= self.threshold => return,
            Mode::Moving { sign } if sign < 0.0 && high <= -self.threshold => return,
            Mode::Stopped if low > -self.threshold && high < self.threshold => return,
            _ => {}
        }
        let mut knots = [0.0; 12];
        let mut count = 0;
        for level in [-self.threshold, 0.0, self.threshold] {
            crossings(&cubic, level, |theta| {
                knots[count] = theta;
                count += 1;
            });
        }
        knots[count] = 0.0;
        knots[count + 1] = 1.0;
        let knots = &mut knots[..count + 2];
        knots.sort_unstable_by(f64::total_cmp);
        let time = |theta: f64| {
            if theta == 1.0 {
                step.t1()
            } else {
                step.t0 + theta * step.h
            }
        };
        for pair in knots.windows(2) {
            if pair[1] > pair[0] {
                let v = horner(&cubic, 0.5 * (pair[0] + pair[1]));
                self.run(time(pair[0]), time(pair[1]), v);
            }
        }
    }

    /// One run [a, b] over which |y'| stays on one side of the threshold with one sign; `v` is
    /// y' inside it.
    fn run(&mut self, a: f64, b: f64, v: f64) {
        let inside = v.abs() < self.threshold;
        let sign = sign_of(v);
        self.mode = match self.mode {
            Mode::Moving { sign: moving } => {
                if inside {
                    Mode::Dip {
                        start: a,
                        entry_sign: moving,
                        first_zero: None,
                        sign_now: if sign == 0.0 { moving } else { sign },
                    }
                } else {
                    Mode::Moving { sign }
                }
            }
            Mode::Dip {
                start,
                entry_sign,
                first_zero,
                sign_now,
            } => {
                if inside {
                    let mut first_zero = first_zero;
                    let mut sign_now = sign_now;
                    if sign != 0.0 {
                        if sign_now != 0.0 && sign != sign_now && first_zero.is_none() {
                            first_zero = Some(a);
                        }
                        sign_now = sign;
                    }
                    Mode::Dip {
                        start,
                        entry_sign,
                        first_zero,
                        sign_now,
                    }
                } else {
                    self.leave_dip(start, entry_sign, first_zero, a, sign)
                }
            }
            Mode::Stopped => {
                if inside {
                    Mode::Stopped
                } else {
                    self.marks.push_back(Mark {
                        tau: a,
                        kind: EventKind::Slip,
                        phase_after: slip(sign),
                    });
                    Mode::Moving { sign }
                }
            }
        };
        if let Mode::Dip { start, .. } = self.mode {
            if inside && b - start >= self.min_stop {
                if start == 0.0 && self.initial_phase.is_none() {
                    // Stuck from the start: the initial phase, no event.
                    self.initial_phase = Some(Phase::Stick);
                } else {
                    self.marks.push_back(Mark {
                        tau: start,
                        kind: EventKind::Stick,
                        phase_after: Phase::Stick,
                    });
                }
                self.mode = Mode::Stopped;
            }
        }
    }

    /// A dip shorter than a stop ends at `exit` with y' of sign `exit_sign`.
    fn leave_dip(
        &mut self,
        start: f64,
        entry_sign: f64,
        first_zero: Option<f64>,
        exit: f64,
        exit_sign: f64,
    ) -> Mode {
        let initial = start == 0.0 && self.initial_phase.is_none();
        if entry_sign != 0.0 && exit_sign != entry_sign {
            if initial {
                self.initial_phase = Some(slip(entry_sign));
            }
            self.marks.push_back(Mark {
                tau: first_zero.unwrap_or(exit),
                kind: EventKind::Turn,
                phase_after: slip(exit_sign),
            });
        } else if initial {
            self.initial_phase = Some(slip(exit_sign));
        }
        Mode::Moving { sign: exit_sign }
    }
}
