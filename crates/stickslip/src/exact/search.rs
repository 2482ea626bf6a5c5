//! The search for the first velocity zero of a sliding segment: a predicted search that
//! usually needs one evaluation of the closed form, and the careful search it falls back on.
//!
//! **Careful search.** On a sliding segment with direction s, let g(t) = s·y'(t) ≥ 0. From a
//! point a with known g, g', g'' and bounds M₂ ≥ |g''|, M₃ ≥ |g'''| on [a, a + H] (from the
//! closed form: every term's amplitude times its frequency to the power of the derivative, or
//! the modulus of the two rotating phasors), Taylor's theorem gives
//!
//! ```text
//! g(a + h) ≥ g + g'h − M₂h²/2      and      g(a + h) ≥ g + g'h + g''h²/2 − M₃h³/6,
//! ```
//!
//! so g has no zero before the first positive root of either right-hand side. Second, while
//! |g''(a)| > M₃·h the curvature keeps its sign on [a, a + h]: where g is convex it lies above
//! its tangent (no zero before the Newton point), and where it is concave it is at least
//! min(g(a), g(a + h)), so a positive value at a + h proves the stretch free of zeros and a
//! sign change brackets exactly one zero, which a safeguarded Newton iteration then locates to
//! rounding. Every step is thus derived from the segment's own frequencies, amplitudes and
//! curvature (not from a fixed dt) and can never pass a zero, however tangential.
//!
//! **A moving belt.** With a belt at speed vb the slide ends where the slip y' − vb
//! vanishes: g(t) = s·(y'(t) − vb), whose derivatives are those of s·y' (vb is constant), so
//! every bound and step below holds unchanged.
//!
//! **Predicted search.** A slide usually lasts as long as the last slide that started the same
//! way (same direction, from a stop or not): in a steady state exactly so. The search
//! evaluates the closed form once, a hair before that predicted end b, and then proves, from
//! Taylor data at 0 and at b alone, that (0, b] has no zero (lower bounds reaching from both
//! ends, [`certify::reach`]) and that the zero lies in a bracket of rounding size just past b
//! where g is strictly decreasing ([`certify::locate`]). Where b is already past the zero it
//! steps back to just short of the root of the cubic model at b (by twice the model's error);
//! where a proof fails it evaluates once more (a split point, a Newton point); where it still
//! fails, the careful search continues from the last point up to which no zero is proved.
//!
//! **First guesses.** Before any slide of a kind has ended, the prediction is a guess from the
//! drive frequency alone: half a drive period π/w for a slide that starts at a turn (each
//! slide of a symmetric sliding cycle lasts exactly that), and 0.6·min(π, π/w) for one that
//! starts from a stop (it ends within about half a natural period, or when the drive turns;
//! aimed short, because a guess short of the zero costs less than one past it: the stretch
//! it proves free of zeros is kept). Like every prediction, a guess changes where the search
//! looks, never what it proves.

use crate::certify::{self, cubic_safe_step, quadratic_safe_step, Jet, Location};
use crate::error::{Error, Result};
use crate::linear::{Derivatives, LinearSegment};
use crate::solver::Stats;

/// Largest number of search steps on one segment before the search reports failure.
const MAX_SEARCH_STEPS: u64 = 1_000_000;

/// Shortest length over which the careful search takes its derivative bounds.
const MIN_SPAN: f64 = 2.0;

/// Kinds of slide told apart for prediction (see [`slide_kind`]).
const KINDS: usize = 4;

/// Slides are told apart by direction and by how they start (from a stop, or otherwise), so
/// that the duration of the last slide of the same kind predicts the next one's.
pub(super) fn slide_kind(sign: f64, from_stop: bool) -> usize {
    usize::from(sign > 0.0) + 2 * usize::from(from_stop)
}

/// The first velocity zero of a sliding segment.
#[derive(Debug, Clone, Copy)]
pub(super) struct Zero {
    /// Local time.
    pub t: f64,
    /// Position there.
    pub y: f64,
    /// (sin, cos) of the drive phase there, when the search has them at hand.
    pub drive: Option<(f64, f64)>,
}

/// What the predicted search concludes.
enum Predicted {
    /// The first zero.
    Zero(Zero),
    /// No zero in (0, t]: the careful search continues from t (with the closed form there
    /// in `ZeroSearch::resume` when the predicted search has it).
    Clear(f64),
}

/// The state of the search on the current sliding segment, and what it learns from one
/// segment for the next.
#[derive(Debug, Clone)]
pub(super) struct ZeroSearch {
    /// Local time up to which the current sliding segment is known to have no velocity zero.
    searched: f64,
    /// The closed form at `searched` when the predicted search left it there (the careful
    /// search takes it instead of evaluating the same point again).
    resume: Option<Derivatives>,
    /// The first velocity zero of the current sliding segment, once found.
    zero: Option<Zero>,
    /// Whether the predicted search has run on the current sliding segment.
    predicted_tried: bool,
    /// The kind of the current slide.
    kind: usize,
    /// Per kind of slide: the duration of the last one (at first a guess, see the module
    /// documentation).
    pub(super) durations: [f64; KINDS],
    /// Whether to try the predicted search first (off only in tests that compare the two).
    pub(super) predict: bool,
    /// Work counters.
    pub(super) stats: Stats,
    /// The belt speed vb: the search looks for the zeros of the slip y' − vb (an exact 0
    /// without a belt, so that every number is what it was).
    vb: f64,
}

impl ZeroSearch {
    /// The search of a solver at drive frequency `w`, its predictions the first guesses (see
    /// the module documentation).
    pub(super) fn new(w: f64, vb: f64) -> Self {
        let half_period = std::f64::consts::PI / w;
        let from_stop = 0.6 * half_period.min(std::f64::consts::PI);
        let mut durations = [f64::NAN; KINDS];
        for sign in [-1.0, 1.0] {
            durations[slide_kind(sign, false)] = half_period;
            durations[slide_kind(sign, true)] = from_stop;
        }
        Self {
            searched: 0.0,
            resume: None,
            zero: None,
            predicted_tried: false,
            kind: 0,
            durations,
            predict: true,
            stats: Stats::default(),
            vb,
        }
    }

    /// Start on a new sliding segment of the given kind.
    pub(super) fn begin(&mut self, kind: usize) {
        self.searched = 0.0;
        self.resume = None;
        self.zero = None;
        self.predicted_tried = false;
        self.kind = kind;
    }

    /// The first velocity zero of the current sliding segment in local times (0, limit], or
    /// None when there is none up to `limit`. `tau0` (the segment's start)
    /// only labels errors.
    ///
    /// # Errors
    /// [`Error::SlideSearch`] when the careful search does not converge.
    pub(super) fn first_zero(
        &mut self,
        sign: f64,
        linear: &LinearSegment,
        limit: f64,
        tau0: f64,
    ) -> Result<Option<Zero>> {
        if !self.predicted_tried && self.predict {
            self.predicted_tried = true;
            match self.predicted(sign, linear) {
                Predicted::Zero(zero) => self.zero = Some(zero),
                Predicted::Clear(t) => {
                    self.searched = t;
                    self.stats.rejected += 1;
                }
            }
        }
        let found = match self.zero {
            Some(zero) if zero.t > limit => return Ok(None),
            Some(zero) => zero,
            // (The predicted search may have cleared the segment past the limit.)
            None if self.searched >= limit => return Ok(None),
            None => match self.careful(sign, linear, limit, tau0)? {
                Some((t, y)) => Zero { t, y, drive: None },
                None => return Ok(None),
            },
        };
        self.durations[self.kind] = found.t;
        Ok(Some(found))
    }

    /// The closed form at local time t, counted.
    fn evaluate(&mut self, linear: &LinearSegment, t: f64) -> Derivatives {
        self.stats.evaluations += 1;
        linear.eval(t)
    }

    /// The predicted search (see the module documentation).
    fn predicted(&mut self, sign: f64, linear: &LinearSegment) -> Predicted {
        // At most this many split points to cover (0, b], and Newton points to bracket.
        const SPLITS: usize = 3;
        const NEWTON: usize = 4;
        let predicted = self.durations[self.kind];
        if !(predicted > 0.0) || !linear.is_two_phasor() {
            return Predicted::Clear(0.0);
        }
        let vb = self.vb;
        let jet = |e: &Derivatives| Jet {
            g: [
                sign * (e.d[1] - vb),
                sign * e.d[2],
                sign * e.d[3],
                sign * e.d[4],
            ],
            noise: e.velocity_noise,
        };
        let mut start = jet(linear.start());
        if start.g[0] == 0.0 {
            // From rest the acceleration along the slide is ≥ 0 (the force has crossed ±μs
            // outward, or exceeds it after a turn); a negative value is rounding.
            start.g[1] = start.g[1].max(0.0);
        }
        if start.g[0] < 0.0 {
            return Predicted::Clear(0.0);
        }
        // Aim a hair short of the prediction: in a steady state the zero is then just beyond
        // b. (Aiming short by the last miss as well costs more than it saves: the paper's map
        // took 3 % more instructions.)
        let margin = 1e-7 * predicted;
        let mut b = predicted - margin;
        if !(b > 0.0) {
            return Predicted::Clear(0.0);
        }
        let mut eb = self.evaluate(linear, b);
        let mut jb = jet(&eb);
        if jb.g[0] <= jb.noise {
            // Past the zero (or on it): step back to just short of the root of the cubic
            // model at b, by twice the model's error there over the slope, so that the zero is
            // within reach of `certify::locate` from the next point (twice the Newton distance
            // where the model has no root behind b).
            if !(jb.g[1] < 0.0) {
                return Predicted::Clear(0.0);
            }
            let root = certify::model_root(jb.g);
            b += if root < 0.0 {
                // (The model's error: the Taylor remainder m4·x⁴/24 and the noise of g.)
                let (_, m4) = linear.global_bounds();
                let error = m4 * root.powi(4) / 24.0 + jb.noise;
                root - 2.0 * error / -jb.g[1] - margin
            } else {
                -2.0 * (jb.g[0] - jb.noise) / jb.g[1] - margin
            };
            if !(b > 0.0) {
                return Predicted::Clear(0.0);
            }
            eb = self.evaluate(linear, b);
            jb = jet(&eb);
            if jb.g[0] <= jb.noise {
                return Predicted::Clear(0.0);
            }
        }
        // (0, b] has no zero: cover it from both ends.
        let (m2, m3) = linear.derivative_bounds(0.0, b, linear.start());
        let (mut left, mut jl, mut el) = (0.0, start, None);
        let mut splits = 0;
        loop {
            if certify::covers(jl, jb, b - left, m2, m3) {
                break;
            }
            let ahead = certify::reach(jl, m2, m3, b - left);
            splits += 1;
            if splits > SPLITS || !(ahead > 0.0) || left + ahead >= b {
                self.resume = el;
                return Predicted::Clear(left);
            }
            left += ahead;
            let e = self.evaluate(linear, left);
            jl = jet(&e);
            el = Some(e);
        }
        // The zero beyond b.
        let (m3_all, m4_all) = linear.global_bounds();
        let (mut from, mut p, mut e) = (b, b, eb);
        for _ in 0..NEWTON {
            match certify::locate(jet(&e), p, from, m3_all, m4_all) {
                Location::Found(located) => {
                    let x = located.offset;
                    let d = e.d;
                    let y =
                        d[0] + x * (d[1] + x * (0.5 * d[2] + x * (d[3] / 6.0 + x * d[4] / 24.0)));
                    self.stats.steps += 1;
                    return Predicted::Zero(Zero {
                        t: p + x,
                        y,
                        drive: Some(linear.drive_trig_after(&e, p, x)),
                    });
                }
                Location::Closer(offset) => {
                    let q = p + offset;
                    let eq = self.evaluate(linear, q);
                    if sign * (eq.d[1] - vb) > eq.velocity_noise && q > from {
                        // g decreases from `from` to q and is still positive at q.
                        from = q;
                    }
                    (p, e) = (q, eq);
                }
                Location::Unknown => break,
            }
        }
        // The closed form at `from`, when it is one of the points evaluated last.
        self.resume = if from == p {
            Some(e)
        } else if from == b {
            Some(eb)
        } else {
            None
        };
        Predicted::Clear(from)
    }

    /// The careful search: first velocity zero of the current sliding segment in local times
    /// (searched, limit], `Some((t, y(t)))`, or None. Advances `self.searched`.
    fn careful(
        &mut self,
        sign: f64,
        linear: &LinearSegment,
        limit: f64,
        tau0: f64,
    ) -> Result<Option<(f64, f64)>> {
        let mut a = self.searched;
        let resume = self.resume.take();
        let mut e = if a == 0.0 {
            *linear.start()
        } else if let Some(at) = resume {
            at
        } else {
            self.stats.evaluations += 1;
            linear.eval(a)
        };
        let mut steps = 0u64;
        // Length over which the derivative bounds are taken: 2, doubled after every step
        // that the span alone limited (a slide creeping on for a long time, or a velocity
        // decayed to nothing, crosses any length in logarithmically many steps), back to 2
        // after any other step.
        let mut span = MIN_SPAN;
        loop {
            if steps > MAX_SEARCH_STEPS {
                return Err(Error::SlideSearch {
                    start: tau0,
                    tau: tau0 + a,
                    direction: if sign > 0.0 { '+' } else { '-' },
                    steps,
                });
            }
            let g = sign * (e.d[1] - self.vb);
            let mut g1 = sign * e.d[2];
            let g2 = sign * e.d[3];
            if a == 0.0 && g == 0.0 {
                // A slide that starts from rest has an acceleration ≥ 0 along its direction
                // (the force has crossed ±μs outward, or exceeds it after a turn); a negative
                // value here is rounding.
                g1 = g1.max(0.0);
            }
            if a > 0.0 && ((g <= e.velocity_noise && g1 < 0.0) || g < -e.velocity_noise) {
                // Converged onto a zero from the left (or crossed it within rounding noise).
                self.searched = a;
                let newton = if g1 < 0.0 {
                    (g / -g1).clamp(0.0, 1e-6)
                } else {
                    0.0
                };
                // (y moves by y'·newton, nothing without a belt: y' is at rounding there.)
                let y = if self.vb == 0.0 {
                    e.d[0]
                } else {
                    e.d[0] + e.d[1] * newton
                };
                return Ok(Some((a + newton, y)));
            }
            let (m2, m3) = linear.derivative_bounds(a, span, &e);
            let g = g.max(0.0);
            // Taylor steps: rigorous lower bounds of the first zero.
            let mut h = quadratic_safe_step(g, g1, m2);
            if g1 >= 0.0 && g2 > 0.0 {
                // (Where g2 ≤ 0 the curvature step below does better.)
                h = h.max(cubic_safe_step(g, g1, g2, m3));
            }
            // Curvature-certified length: g'' keeps the sign of g2 on [a, a + hc].
            let hc = if m3 > 0.0 {
                (g2.abs() / m3).min(span)
            } else {
                span
            };
            if g2 > 0.0 {
                // Convex: g lies above its tangent, which stays positive up to the Newton
                // point (everywhere when g1 ≥ 0).
                let reach = if g1 < 0.0 { hc.min(g / -g1) } else { hc };
                h = h.max(reach);
            } else if g2 < 0.0 {
                // Concave: on [a, b] g is at least min(g(a), g(b)); aim just past the Newton
                // point, where the zero is expected.
                let target = if g1 < 0.0 {
                    // Root of the local quadratic model g + g1 h + g2 h²/2 (g2 < 0), a little
                    // beyond it so that the zero is bracketed.
                    let model = 2.0 * g / (-g1 + (g1 * g1 - 2.0 * g2 * g).sqrt());
                    hc.min(1.02 * model + 1e-9 * a.max(1.0))
                } else {
                    hc
                };
                // (Only when the target is past a in floating point: a step below one ulp
                // would evaluate the same point for ever.)
                if target > h && (a + target).min(limit) > a {
                    let b = (a + target).min(limit);
                    let eb = linear.eval(b);
                    self.stats.evaluations += 1;
                    steps += 1;
                    self.stats.steps += 1;
                    if sign * (eb.d[1] - self.vb) > 0.0 {
                        if b >= limit {
                            self.searched = limit;
                            return Ok(None);
                        }
                        a = b;
                        e = eb;
                        continue;
                    }
                    // Exactly one zero in (a, b]: g is concave there.
                    return Ok(Some(self.polish(sign, linear, a, b, eb)));
                }
            }
            let by_span = h >= span;
            h = h.min(span);
            span = if by_span { 2.0 * span } else { MIN_SPAN };
            if !(h > 0.0) || a + h == a {
                // Stalled on a double zero (g and g' both at rounding level): that is the event.
                if a > 0.0 {
                    self.searched = a;
                    return Ok(Some((a, e.d[0])));
                }
                h = 1e-12;
            }
            steps += 1;
            self.stats.steps += 1;
            if a + h >= limit {
                self.searched = limit;
                return Ok(None);
            }
            a += h;
            e = linear.eval(a);
            self.stats.evaluations += 1;
        }
    }

    /// The single velocity zero in (a, b], where s·v(a) > 0 ≥ s·v(b): Newton's method kept
    /// inside the shrinking bracket (bisection when a step leaves it).
    fn polish(
        &mut self,
        sign: f64,
        linear: &LinearSegment,
        mut a: f64,
        mut b: f64,
        eb: Derivatives,
    ) -> (f64, f64) {
        let mut t = b;
        // y, y', y'' at t: all that Newton's method reads.
        let mut d = [eb.d[0], eb.d[1], eb.d[2]];
        for _ in 0..100 {
            let g = sign * (d[1] - self.vb);
            if g > 0.0 {
                a = t;
            } else {
                b = t;
            }
            let g1 = sign * d[2];
            let newton = if g1 != 0.0 { t - g / g1 } else { f64::NAN };
            // Newton converges quadratically: after a step below 1e-10 the next iterate is
            // exact to rounding, and y moves by v·Δt.
            if (newton - t).abs() <= 1e-10 * t.abs().max(1.0) || g == 0.0 {
                let next = if g == 0.0 { t } else { newton.clamp(a, b) };
                self.searched = a;
                return (next, d[0] + d[1] * (next - t));
            }
            let next = if newton > a && newton < b {
                newton
            } else {
                0.5 * (a + b)
            };
            t = next;
            d = linear.eval_newton(t);
            self.stats.evaluations += 1;
        }
        self.searched = a;
        (t, d[0])
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::linear::Damping;

    /// A slide of y'' + 0.1 y' + y = −1 from rest at y = −5 in the + direction: its velocity
    /// rises until about τ = π/2 and first vanishes near τ = π.
    fn rising_slide() -> LinearSegment {
        LinearSegment::new(Damping::new(0.05), 0.9, 0.0, 0.0, 1.0, -5.0, 0.0)
    }

    /// Regression: with a prediction far too short (τ = 1, where the velocity still rises)
    /// the predicted search proves (0, 1) free of zeros but cannot bracket the zero. Asked for
    /// the first zero up to τ = 0.5, the search then started the careful search at τ = 1,
    /// past the requested end, and reported the zero near π as if it lay before 0.5.
    #[test]
    fn regression_no_zero_reported_past_the_requested_end() {
        let linear = rising_slide();
        let mut search = ZeroSearch::new(0.9, 0.0);
        search.begin(slide_kind(1.0, false));
        search.durations[search.kind] = 1.0;
        let early = search.first_zero(1.0, &linear, 0.5, 0.0).unwrap();
        assert!(early.is_none(), "a zero reported before 0.5: {early:?}");
        assert!(
            search.searched > 0.5,
            "the prediction cleared past the limit"
        );
        let zero = search.first_zero(1.0, &linear, 10.0, 0.0).unwrap().unwrap();
        let mut careful = ZeroSearch::new(0.9, 0.0);
        careful.predict = false;
        careful.begin(slide_kind(1.0, false));
        let expected = careful
            .first_zero(1.0, &linear, 10.0, 0.0)
            .unwrap()
            .unwrap();
        assert!((zero.t - expected.t).abs() < 1e-12 && zero.t > 3.0 && zero.t < 3.3);
    }
}
