//! Lyapunov exponents from the exact tangent dynamics, with a statistical error.
//!
//! **Largest exponent.** The Jacobian J of the flow ([`TangentSolver`]) is carried along the
//! trajectory and renormalised at the end of every block of L drive periods: J ← J/‖J‖,
//! recording g_b = ln‖J‖ (the Frobenius norm; within a block the solver keeps the entries of J
//! within 10^±100 itself, [`TangentSolver::log_scale`]). After a transient (during which J is
//! carried too, so that its columns have turned into the most unstable direction) the exponent
//! is
//!
//! ```text
//! λ₁ = Σ_b g_b / (N T)      per unit τ,       λ₁ T per drive period,
//! ```
//!
//! over N = blocks × L periods. Every drive period (of the transient and of the measurement)
//! runs on a solver restarted at τ = 0 from the strobe state, J kept and renormalised at its
//! end, its growth recorded: the rounding of absolute times grows with τ (ulp(τ) doubles at
//! every power of two) and would change the segment durations the Jacobian sees by about
//! 10⁻¹⁰ relative at τ ~ 10⁵, from one period to the next; and so a measurement that stops
//! early is, number for number, the fixed measurement of that length.
//! **Error**: the N periods are cut into blocks of L periods; the
//! block means are nearly independent when L is long against the correlation time, and the
//! error is their standard error, sd/√blocks. **Convergence check**: the means of the first
//! and the second half of the blocks must agree within [`LyapunovOptions::significance`]
//! times 2σ_r, the standard deviation of their difference for a stationary motion, with
//! σ_r = 1.4826·MAD/√blocks the standard error from the median absolute deviation of the block
//! means (plus 10⁻¹²·(1 + |λ₁|), the rounding of a periodic motion, whose blocks agree to the
//! last bits). The robust spread is not widened by a transient confined to a few blocks, so
//! such a transient cannot excuse itself; the slow, bounded beat of ln‖J‖ along an orbit with
//! complex multipliers (a focus) spreads over all blocks and passes. A drift between the
//! halves makes the estimate not converged.
//!
//! **Stopping when the verdict is known** ([`LyapunovOptions::sequential`], the default).
//! The growth is recorded drive period by drive period (the clock restarted and J renormalised
//! at every strobe), so the measurement can be cut into `blocks` equal blocks at any length
//! that is a multiple of `blocks`. It is looked at after n_j = blocks·⌊L/2^j⌋ periods,
//! j = J, J − 1, …, 0, where L = ⌊periods/blocks⌋ is the block length at the cap and J ≤ 5 the
//! largest with ⌊L/2^J⌋ ≥ 10 (at most six looks, lengths nearly doubling, the last the cap).
//! At every look the estimate λ₁ ± σ and the convergence check are those of a fixed
//! measurement of that length, and the run stops at the first look where the verdict is
//! decided: the halves agree and λ₁ > kσ (chaotic) or λ₁ < −kσ (contracting), k =
//! [`LyapunovOptions::significance`]; or λ₁ is zero to rounding, |λ₁| + kσ ≤ 10⁻¹²·(1 + |λ₁|)
//! (an exactly neutral motion: rest, a neutral family). Otherwise (|λ₁| ≤ kσ, or halves that
//! disagree) it goes on, and the cap gives the fixed measurement's answer. **Significance**:
//! with σ the standard error of `blocks` = 20 nearly independent, nearly normal block means, a
//! motion whose true exponent has the other sign (or is 0) passes one look with probability
//! P(|t₁₉| > 4)/2 ≈ 3.9·10⁻⁴ at k = 4 (Student's t with 19 degrees of freedom), so at most
//! 6 × 3.9·10⁻⁴ ≈ 2.3·10⁻³ over all looks (Bonferroni; about 1.9·10⁻⁴ should the means be
//! normal with a known spread). `sequential: false` always runs to the cap (the measurement as
//! it was before the early stop).
//!
//! **Second exponent.** λ₁ + λ₂ = lim (1/τ) ln|det J|, and ln|det J| is known exactly as a sum
//! ([`TangentSolver::log_det`]): −2ζ per unit of sliding time (Liouville, between events) plus
//! ln(a⁺/a⁻) < 0 per turn (the turn saltation, [`super::saltation`]): the turns contract phase
//! area as well, so λ₁ + λ₂ = −2ζ only for the sliding segments themselves. A stop makes J
//! singular (det J = 0): λ₂ = −∞, reported as [`SecondExponent::MinusInfinity`], never as the
//! logarithm of a rounded zero.

use super::error::StabilityError;
use super::tangent::{TangentRun, TangentSolver};
use crate::error::{Error, Result};
use crate::options::{Allowed, OptionKey};
use crate::params::{Params, State};
use crate::scan::Monitor;
use crate::solver::{Event, EventKind, Phase};
use serde::{Deserialize, Serialize};
use std::ops::ControlFlow;

/// Options of [`lyapunov_exponents`], [`super::two_trajectory_exponent`] and
/// [`super::classify_nonperiodic`].
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct LyapunovOptions {
    /// Drive periods run before measuring (the tangent is carried and renormalised, not
    /// recorded). Default 1000.
    pub transient_periods: usize,
    /// Drive periods measured; rounded down to a multiple of `blocks`. Default 20 000.
    pub periods: usize,
    /// Blocks the measured periods are cut into for the error, even and at least 4.
    /// Default 20.
    pub blocks: usize,
    /// Standard errors that make a difference significant (the convergence check and the
    /// verdicts of [`super::classify_nonperiodic`]). Default 4.
    pub significance: f64,
    /// Stop at the first look where the verdict is decided (see the module documentation);
    /// `false`: always measure `periods`. Default true.
    #[serde(default = "sequential_default")]
    pub sequential: bool,
}

fn sequential_default() -> bool {
    true
}

impl Default for LyapunovOptions {
    fn default() -> Self {
        Self {
            transient_periods: 1000,
            periods: 20_000,
            blocks: 20,
            significance: 4.0,
            sequential: true,
        }
    }
}

impl LyapunovOptions {
    /// Check every field.
    ///
    /// # Errors
    /// [`Error::InvalidOption`] naming the first bad field ([`crate::options`]).
    pub fn validate(self) -> Result<Self> {
        OptionKey::LyapunovTransient.check_count(self.transient_periods)?;
        OptionKey::Blocks.check_count(self.blocks)?;
        if self.periods < self.blocks || !OptionKey::LyapunovMeasured.allows(self.periods as f64) {
            return Err(Error::InvalidOption {
                option: OptionKey::LyapunovMeasured,
                value: self.periods as f64,
                allowed: Allowed::FromOption {
                    other: OptionKey::Blocks,
                    value: self.blocks as f64,
                    to: "1e9",
                },
            });
        }
        OptionKey::Significance.check(self.significance)?;
        Ok(self)
    }

    /// The measured lengths (drive periods) at which a sequential measurement looks at its
    /// verdict, in increasing order; the last is the cap, `periods` rounded down to a multiple
    /// of `blocks` (see the module documentation). Only the cap without
    /// [`LyapunovOptions::sequential`].
    ///
    /// ```
    /// use stickslip::stability::LyapunovOptions;
    /// let o = LyapunovOptions { periods: 5000, ..Default::default() };
    /// assert_eq!(o.looks(), vec![300, 620, 1240, 2500, 5000]);
    /// ```
    pub fn looks(&self) -> Vec<usize> {
        let blocks = self.blocks.max(1);
        let cap = (self.periods / blocks).max(1);
        if !self.sequential {
            return vec![cap * blocks];
        }
        let mut lengths: Vec<usize> = (0..=MAX_HALVINGS)
            .rev()
            .map(|j| cap >> j)
            .filter(|&m| m >= MIN_FIRST_BLOCK || m == cap)
            .map(|m| m * blocks)
            .collect();
        lengths.dedup();
        lengths
    }

    /// Check that the transient and the measurement, one run from τ = 0, stay within the time
    /// range the solvers resolve at these parameters ([`crate::limits::check_horizon`]).
    ///
    /// ```
    /// use stickslip::stability::LyapunovOptions;
    /// use stickslip::Params;
    /// let p = Params::new(0.0, 0.33, 9.0).unwrap();
    /// assert!(LyapunovOptions::default().check_horizon(&p).is_ok());
    /// let long = LyapunovOptions { periods: 1_000_000_000, ..Default::default() };
    /// assert!(long.check_horizon(&p).is_err());
    /// ```
    ///
    /// # Errors
    /// [`Error::HorizonTooLong`].
    pub fn check_horizon(&self, params: &Params) -> Result<()> {
        let measured = self.periods / self.blocks.max(1) * self.blocks;
        crate::limits::check_horizon(params, (self.transient_periods + measured) as f64)
    }
}

/// Most halvings of the block length below the cap: at most `MAX_HALVINGS + 1` looks.
const MAX_HALVINGS: u32 = 5;

/// Shortest block (drive periods) of the first look, unless the cap's blocks are shorter.
const MIN_FIRST_BLOCK: usize = 10;

/// An exponent with its statistical error, per unit τ and per drive period. Dimensionless
/// (rates in units of ω0 per unit τ; per drive period a plain number).
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct Estimate {
    /// The exponent per unit τ.
    pub per_tau: f64,
    /// Its standard error from the block means, per unit τ.
    pub error_per_tau: f64,
    /// The exponent per drive period, λ·T.
    pub per_period: f64,
    /// Its standard error per drive period.
    pub error_per_period: f64,
}

impl Estimate {
    fn new(per_tau: f64, error_per_tau: f64, drive_period: f64) -> Self {
        Self {
            per_tau,
            error_per_tau,
            per_period: per_tau * drive_period,
            error_per_period: error_per_tau * drive_period,
        }
    }
}

/// The second Lyapunov exponent.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum SecondExponent {
    /// The motion never stopped while measured: λ₂ = (1/τ) ln|det J| − λ₁.
    Finite(Estimate),
    /// The motion stopped (`stops` times while measured): every stop erases the velocity
    /// perturbation, det J = 0 and λ₂ = −∞.
    MinusInfinity {
        /// Stops while measured.
        stops: u64,
    },
}

impl SecondExponent {
    /// The exponent per unit τ, −∞ for [`SecondExponent::MinusInfinity`].
    pub fn per_tau(&self) -> f64 {
        match self {
            SecondExponent::Finite(e) => e.per_tau,
            SecondExponent::MinusInfinity { .. } => f64::NEG_INFINITY,
        }
    }
}

/// The Lyapunov exponents of a motion (see the module documentation).
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct LyapunovExponents {
    /// The largest exponent.
    pub largest: Estimate,
    /// The second exponent.
    pub second: SecondExponent,
    /// Whether the two halves of the measurement agree (see the module documentation), at the
    /// length measured.
    pub converged: bool,
    /// The block means of the largest exponent, per unit τ, in time order.
    pub block_means: Vec<f64>,
    /// Drive periods measured (a multiple of the blocks): the look at which the verdict was
    /// decided, or the cap ([`LyapunovOptions::looks`]).
    pub periods: usize,
    /// Drive periods the options allowed ([`LyapunovOptions::periods`] rounded down to a
    /// multiple of the blocks); `periods` < `cap` when the measurement stopped early.
    pub cap: usize,
    /// The drive period T = 2π/w (dimensionless time).
    pub drive_period: f64,
    /// The state at the end of the measurement (at a strobe).
    pub final_state: State,
    /// Stops longer than 10⁻⁸ drive periods while measured (a stop running over the end of
    /// the measurement is not counted; being stuck throughout is no stop).
    pub stops: usize,
}

impl LyapunovExponents {
    /// Stops of non-zero duration per drive period while measured.
    pub fn stops_per_period(&self) -> f64 {
        self.stops as f64 / self.periods.max(1) as f64
    }
}

/// Mean and standard error of the block means `means`.
pub(super) fn mean_and_error(means: &[f64]) -> (f64, f64) {
    let n = means.len() as f64;
    let mean = means.iter().sum::<f64>() / n;
    let var = means.iter().map(|m| (m - mean) * (m - mean)).sum::<f64>() / (n - 1.0);
    (mean, (var / n).sqrt())
}

/// Whether the first and second halves of `means` agree (see the module documentation).
pub(super) fn halves_agree(means: &[f64], significance: f64) -> bool {
    let n = means.len();
    let (first, second) = means.split_at(n / 2);
    let m1 = first.iter().sum::<f64>() / first.len() as f64;
    let m2 = second.iter().sum::<f64>() / second.len() as f64;
    let median = |values: &mut Vec<f64>| {
        values.sort_by(f64::total_cmp);
        let k = values.len();
        if k % 2 == 1 {
            values[k / 2]
        } else {
            0.5 * (values[k / 2 - 1] + values[k / 2])
        }
    };
    let center = median(&mut means.to_vec());
    let mad = median(&mut means.iter().map(|m| (m - center).abs()).collect());
    let robust_error = 1.4826 * mad / (n as f64).sqrt();
    let floor = 1e-12 * (1.0 + m1.abs().max(m2.abs()));
    (m1 - m2).abs() <= significance * 2.0 * robust_error + floor
}

/// The largest Lyapunov exponent (and the second) of the motion from `initial` at τ = 0 (a
/// strobe), by the exact tangent dynamics (see the module documentation).
///
/// ```
/// use stickslip::stability::{lyapunov_exponents, LyapunovOptions};
/// use stickslip::{Params, State};
/// // A sliding motion: both exponents finite and negative.
/// let params = Params::new(0.0468, 0.9, 1.6).unwrap();
/// let options = LyapunovOptions { transient_periods: 200, periods: 400, ..Default::default() };
/// let lyap = lyapunov_exponents(&params, State::default(), &options).unwrap();
/// assert!(lyap.converged && lyap.largest.per_tau < 0.0 && lyap.second.per_tau() < 0.0);
/// ```
///
/// # Errors
/// [`Error::InvalidParameter`] for invalid parameters, state or options;
/// [`Error::HorizonTooLong`] when the transient and the measurement reach beyond the time
/// range the solvers resolve ([`crate::limits::max_periods`]);
/// [`StabilityError::NonFiniteJacobian`] at a tangential release; whatever the solver
/// reports.
pub fn lyapunov_exponents(
    params: &Params,
    initial: State,
    options: &LyapunovOptions,
) -> Result<LyapunovExponents> {
    lyapunov_exponents_monitored(params, initial, options, &())
}

/// [`lyapunov_exponents`], watched by `monitor`: it is told the drive periods run (transient
/// and measurement) after every block of them (blocks of the cap's length, at most 1000
/// periods), and can stop the run; a measurement that stops early tells it the total at the
/// end.
///
/// # Errors
/// As [`lyapunov_exponents`]; [`Error::Cancelled`] (counting drive periods) when the monitor
/// stops the run.
pub fn lyapunov_exponents_monitored(
    params: &Params,
    initial: State,
    options: &LyapunovOptions,
    monitor: &dyn Monitor,
) -> Result<LyapunovExponents> {
    let options = options.validate()?;
    let params = params.validate()?;
    crate::exact::check_coulomb(&params)?;
    let initial = State::new(initial.y, initial.v)?;
    options.check_horizon(&params)?;
    let mut tangent = TangentSolver::new(params, initial);
    measure_exponents(&mut tangent, &params, &options, monitor)
}

/// The measurement of [`lyapunov_exponents_monitored`] on any tangent dynamics (the exact
/// model's [`TangentSolver`], or a smooth law's), from where `tangent` stands (a strobe),
/// with `options` validated and its horizon checked.
pub(crate) fn measure_exponents<T: TangentRun + ?Sized>(
    tangent: &mut T,
    params: &Params,
    options: &LyapunovOptions,
    monitor: &dyn Monitor,
) -> Result<LyapunovExponents> {
    let period = params.drive_period();
    let per_block = options.periods / options.blocks;
    // The monitor hears after every block of the cap's length, or every REPORT_EVERY periods.
    let every = per_block.clamp(1, REPORT_EVERY);
    // One solver runs the transient and the measurement.
    let mut progress = Progress {
        monitor,
        done: 0,
        total: options.transient_periods + per_block * options.blocks,
    };
    for k in 0..options.transient_periods {
        tangent.restart_clock();
        tangent.run_until(period, &mut |_| {})?;
        tangent.renormalize();
        if tangent.grazing().is_some() {
            // (Only the measurement needs a finite Jacobian: start it afresh.)
            tangent.reset();
        }
        if (k + 1).is_multiple_of(every) {
            progress.step(every)?;
        }
    }
    // Keep the aligned J; restart ln|det J| and the stop count for the measurement.
    tangent.reset_log_det();
    let mut stops = StopCount::new(tangent.phase() == Phase::Stick, MIN_STOP_FRACTION * period);
    let looks = options.looks();
    let cap = *looks.last().expect("at least one look");
    // Growth ln‖J‖ of every measured period, and ln|det J| at its end (None once singular).
    let mut growth = Vec::with_capacity(cap);
    let mut log_det = Vec::with_capacity(cap + 1);
    log_det.push(Some(0.0));
    let mut look = 0;
    let mut result = None;
    while result.is_none() {
        let k = growth.len();
        let offset = k as f64 * period;
        tangent.restart_clock();
        tangent.run_until(period, &mut |e| stops.event(offset, e))?;
        if let Some(tau) = tangent.grazing() {
            return Err(StabilityError::NonFiniteJacobian { tau: offset + tau }.into());
        }
        growth.push(tangent.renormalize());
        log_det.push(tangent.log_det());
        let done = options.transient_periods + k + 1;
        if done.is_multiple_of(every) {
            progress.step(done - progress.done)?;
        }
        if k + 1 == looks[look] {
            let mut measured = Measured::new(&growth, &log_det, options.blocks, period);
            if measured.decided(options.significance) || k + 1 == cap {
                result = Some(measured);
            }
            look += 1;
        }
    }
    let measured = result.expect("the loop ends with a result");
    // A verdict decided early completes the work.
    progress.finish()?;
    let second = if let Some(means) = measured.second_means {
        let (mean2, error2) = mean_and_error(&means);
        SecondExponent::Finite(Estimate::new(mean2, error2, period))
    } else {
        SecondExponent::MinusInfinity {
            stops: tangent.stops(),
        }
    };
    Ok(LyapunovExponents {
        largest: Estimate::new(measured.mean, measured.error, period),
        second,
        converged: measured.converged,
        block_means: measured.block_means,
        periods: growth.len(),
        cap,
        drive_period: period,
        final_state: tangent.state(),
        stops: stops.count,
    })
}

/// The estimate at one look: `blocks` equal blocks of the periods measured so far.
struct Measured {
    block_means: Vec<f64>,
    /// Block means of λ₂, while J is regular.
    second_means: Option<Vec<f64>>,
    mean: f64,
    error: f64,
    converged: bool,
}

impl Measured {
    fn new(growth: &[f64], log_det: &[Option<f64>], blocks: usize, period: f64) -> Self {
        let per_block = growth.len() / blocks;
        let length = per_block as f64 * period;
        let block_means: Vec<f64> = growth
            .chunks_exact(per_block)
            .map(|c| c.iter().sum::<f64>() / length)
            .collect();
        let second_means = (0..blocks)
            .map(|b| {
                let (from, to) = (log_det[b * per_block]?, log_det[(b + 1) * per_block]?);
                Some((to - from) / length - block_means[b])
            })
            .collect::<Option<Vec<f64>>>();
        let (mean, error) = mean_and_error(&block_means);
        Self {
            converged: false,
            block_means,
            second_means,
            mean,
            error,
        }
    }

    /// Whether the verdict is decided at significance `k` (see the module documentation); sets
    /// `converged`.
    fn decided(&mut self, k: f64) -> bool {
        self.converged = halves_agree(&self.block_means, k);
        let floor = 1e-12 * (1.0 + self.mean.abs());
        self.converged
            && (self.mean.abs() > k * self.error || self.mean.abs() + k * self.error <= floor)
    }
}

/// Most drive periods run between two reports to the monitor.
const REPORT_EVERY: usize = 1000;

/// The monitor of a run and the drive periods done.
struct Progress<'a> {
    monitor: &'a dyn Monitor,
    done: usize,
    total: usize,
}

impl Progress<'_> {
    /// Everything is done (told once more unless it was told already).
    fn finish(&mut self) -> Result<()> {
        if self.done < self.total {
            self.step(self.total - self.done)?;
        }
        Ok(())
    }

    /// `periods` more are done.
    fn step(&mut self, periods: usize) -> Result<()> {
        self.done += periods;
        if self.monitor.step(self.done, self.total) == ControlFlow::Break(()) {
            return Err(Error::Cancelled {
                done: self.done,
                total: self.total,
            });
        }
        Ok(())
    }
}

/// Shortest stop counted in [`LyapunovExponents::stops`], as a fraction of the drive period
/// (as [`crate::steady::SteadyOptions::min_stop_fraction`] by default: a stop of zero duration
/// is a turn on the static limit).
const MIN_STOP_FRACTION: f64 = 1e-8;

/// Stops of non-zero duration along a measurement made of blocks whose clocks restart at 0.
struct StopCount {
    /// Measured time at which the current stop began.
    since: Option<f64>,
    /// Shortest stop that counts (dimensionless time).
    shortest: f64,
    count: usize,
}

impl StopCount {
    fn new(stuck: bool, shortest: f64) -> Self {
        Self {
            since: stuck.then_some(0.0),
            shortest,
            count: 0,
        }
    }

    /// An event at time `offset + e.tau` of the measurement. A stop counts when it ends, so
    /// that a stop running over the start and one running over the end of a periodic motion
    /// make one.
    fn event(&mut self, offset: f64, e: &Event) {
        let tau = offset + e.tau;
        match e.kind {
            EventKind::Stick => self.since = Some(tau),
            EventKind::Slip => {
                if let Some(since) = self.since.take() {
                    if tau - since > self.shortest {
                        self.count += 1;
                    }
                }
            }
            EventKind::Turn => {}
        }
    }
}
