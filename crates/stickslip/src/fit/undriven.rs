//! Fitting records of an undriven belt: a block on a belt moving at a given speed, with no
//! drive force (β = 0), whose self-excited motion was recorded as a displacement r(t) alone.
//!
//! **Which records.** A record of the settled self-excited cycle (a stick-slip cycle or a
//! pure-slip cycle), at least one whole cycle long at the starting values, with a displacement
//! channel in m and no drive: its only channel, or beside channels that are constant (a force
//! channel that reads no drive). A record with a varying force channel is a driven record
//! ([`super::fit_records`]); a record too short for one cycle, an oscillator without a belt,
//! starting values whose motion is steady sliding (nothing to align a record with) are refused
//! in one line naming what is missing. A record of the settled cycle whose belt started
//! during the record is not this model (its residuals then stay far above the noise): a
//! record that starts with the belt is a record from rest, below.
//!
//! **A record from rest** ([`UndrivenRecord::from_rest`], [`UndrivenStart::FromRest`]): the
//! block is at rest on the ground (r' = 0) at the record's first sample, a known distance
//! r_0 from the spring's rest length, and the belt runs from that sample on (it slips the
//! block up to the belt's speed, carries it to the release and the motion settles). The
//! model is that motion, y(ω0·t) from y = r_0·k/F0, y' = 0 at t = 0, times F0/k plus the
//! record's offset: aligned by the first sample, no section time fitted; the offset starts
//! at the first sample's reading less r_0. It need not hold a whole cycle, and the starting
//! values may slide steadily. Since r_0 is known in the spring's frame, the stick from r_0 to
//! the release fixes μs·F0 − γ·vb and the slips about the kinetic level fix F0: such a
//! record shows F0 apart from μs (no level is held).
//!
//! **Belt speeds** ([`UndrivenRecord::on_belt`]): a record may have a belt speed of its own
//! (m/s), the experiment's being that of the others. Each belt speed's cycle is computed
//! once per evaluation (the belt's speed in m/s held, as the law's values are, while the
//! scales move), and each record's model is its own belt's. The law's fall is seen from two
//! sides at two speeds: one oscillator's records at two belt speeds fix it far better than
//! one.
//!
//! **The model of a record.** The oscillator at the free parameters' values, β = 0, settles
//! on its self-excited cycle ([`Experiment::steady_with`]: its period T is found, not given).
//! The cycle's section (the onset of sticking, or the reversal or turning point of a pure-slip
//! cycle) is at τ = 0; a record's samples at its times t (s) are the cycle's
//! y((ω0·(t − t_s)) mod T), times the position scale F0/k, plus the record's offset of r.
//! The time t_s of a section (s since the record's first sample, kept near the record's
//! middle) and the offset are each record's nuisance values, fitted with the rest; without
//! a drive nothing else fixes the record's phase. The cycle is the same for every record of
//! one oscillator: it is computed once per evaluation and run over one period only (the
//! samples sorted by their phase), so that the model is periodic to the solver's accuracy.
//!
//! **The fit.** As for driven records: Levenberg–Marquardt over the free parameters (scaled
//! by their starting values) and the nuisance values, two passes (the second weighting each
//! record by its RMS residual of the first), a restart from elsewhere, error bars from
//! s²(JᵀJ)⁻¹ and 95 % intervals checked at both ends (the profile likelihood's where the
//! linear interval does not hold, or crosses a value's range: `profile`). The Jacobian: by central differences of the whole model for
//! the free parameters (each cycle settling from the last one's section, so that both sides
//! of a difference are the same attractor), exact for the offsets (1) and the section times
//! (−ω0·y'(ψ)·F0/k). The start of each section time comes from a scan of one period at the
//! starting values (the shift with the least sum of squares, the offset at its mean).
//!
//! **What a record shows.** Of a stick-slip cycle: μs (where the block leaves the belt),
//! the law's fall (vs) and its viscous slope (η), γ; with the offset of r free, the kinetic
//! level F0 only shifts r, so F0 and μs are seen only as (μs − 1)·F0 (the fit holds the last
//! named of the two and says so); with the cubic law the static level μs·F0 only shifts r
//! (both held). A parameter the records do not change with is named in an
//! `unseen` warning, without an error bar.

use super::*;
use crate::friction::FrictionLaw;
use crate::measure::{noise, MeasureError, Record, MIN_SAMPLES};
use crate::params::{Params, State};
use crate::solver::sample_at;
use crate::steady::{MotionClass, SolverFactory};
use options::Watch;
use rayon::prelude::*;

/// A record of an undriven belt prepared for fitting: the displacement alone.
#[derive(Debug, Clone, PartialEq)]
pub struct UndrivenRecord {
    /// The record's file name.
    pub file: String,
    /// The displacement channel's name.
    pub channel: String,
    /// Times since the record's first sample (s).
    pub time: Vec<f64>,
    /// The displacement r (m).
    pub response: Vec<f64>,
    /// Which samples are used (not clipped).
    pub used: Vec<bool>,
    /// Samples left out as clipped.
    pub clipped: usize,
    /// The displacement's vertical resolution (m).
    pub resolution: Option<f64>,
    /// The displacement's noise (m, standard deviation), from its second differences (as
    /// [`Measurement::noise`]).
    pub noise: f64,
    /// Where the record's motion starts: the settled cycle (the default of
    /// [`UndrivenRecord::new`]) or rest ([`UndrivenRecord::from_rest`]).
    pub start: UndrivenStart,
    /// The belt's speed under this record (m/s), when it is not the experiment's
    /// ([`UndrivenRecord::on_belt`]).
    pub belt_speed: Option<f64>,
}

/// Where the motion of an undriven record starts (the model of the record).
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum UndrivenStart {
    /// The record holds the settled self-excited cycle: the model is that cycle, aligned by
    /// a section time fitted with the rest.
    Settled,
    /// The block is at rest on the ground (r' = 0) at the record's first sample, `position`
    /// (m) from the spring's rest length, and the belt runs from then on: the model is the
    /// motion from that state, aligned by the record's first sample (no time fitted).
    FromRest {
        /// The block's displacement from the spring's rest length at the start (m).
        position: f64,
    },
}

impl UndrivenRecord {
    /// The displacement of `record`: the channel named `response`, else its only channel in
    /// m. Every other channel must be constant (no drive).
    ///
    /// # Errors
    /// No channel in m (or more than one, none named), a channel that varies beside it (a
    /// driven record), a displacement clipped or constant.
    pub fn new(record: &Record, response: Option<&str>) -> Result<Self, MeasureError> {
        let file = &record.file;
        let index = match response {
            Some(name) => record.channel_index(name)?,
            None => {
                let metres: Vec<usize> = (0..record.channels.len())
                    .filter(|&i| record.channels[i].unit == "m")
                    .collect();
                match metres.as_slice() {
                    [one] => *one,
                    [] => {
                        return Err(MeasureError::file(
                            file,
                            "an undriven record needs a displacement channel in m (name its \
                             column with its unit, e.g. `r (m)`), and this record has none",
                        ))
                    }
                    _ => {
                        return Err(MeasureError::file(
                            file,
                            "the record has several channels in m: name the displacement \
                             with --response",
                        ))
                    }
                }
            }
        };
        let channel = &record.channels[index];
        if channel.unit != "m" {
            return Err(MeasureError::file(
                file,
                format!(
                    "an undriven record's displacement is in m, and channel {} is in {}",
                    channel.name, channel.unit
                ),
            ));
        }
        if let Some(other) = record
            .channels
            .iter()
            .enumerate()
            .find(|&(i, c)| i != index && c.resolution.is_some())
        {
            return Err(MeasureError::file(
                file,
                format!(
                    "channel {} varies: a record with a drive is fitted as a driven record \
                     (an undriven record has the displacement alone, or beside a constant \
                     channel)",
                    other.1.name
                ),
            ));
        }
        if channel.values.len() < MIN_SAMPLES {
            return Err(MeasureError::file(
                file,
                format!(
                    "channel {} has {} samples: too few to fit (at least {MIN_SAMPLES})",
                    channel.name,
                    channel.values.len()
                ),
            ));
        }
        if channel.resolution.is_none() || channel.clipped_count() * 10 > channel.values.len() {
            return Err(MeasureError::file(
                file,
                format!(
                    "channel {} is clipped or constant in more than a tenth of its {} \
                     samples: nothing left to fit",
                    channel.name,
                    channel.values.len()
                ),
            ));
        }
        let t0 = record.time[0];
        let used: Vec<bool> = channel.clipped.iter().map(|c| !c).collect();
        Ok(Self {
            file: file.clone(),
            channel: channel.name.clone(),
            time: record.time.iter().map(|&t| t - t0).collect(),
            response: channel.values.clone(),
            clipped: channel.clipped_count(),
            resolution: channel.resolution,
            noise: noise(&channel.values, &used),
            used,
            start: UndrivenStart::Settled,
            belt_speed: None,
        })
    }

    /// The record of a motion from rest: the block at rest on the ground at the record's
    /// first sample, `position` (m) from the spring's rest length, the belt started then
    /// ([`UndrivenStart::FromRest`]).
    ///
    /// # Errors
    /// A position that is not finite.
    pub fn from_rest(mut self, position: f64) -> Result<Self, MeasureError> {
        if !position.is_finite() {
            return Err(MeasureError::file(
                &self.file,
                format!("the start position of a record from rest is {position}: a finite displacement in m"),
            ));
        }
        self.start = UndrivenStart::FromRest { position };
        Ok(self)
    }

    /// The record taken on a belt at `belt_speed` (m/s), whatever the experiment's.
    ///
    /// # Errors
    /// A belt speed that is not finite or is 0.
    pub fn on_belt(mut self, belt_speed: f64) -> Result<Self, MeasureError> {
        if !belt_speed.is_finite() || belt_speed == 0.0 {
            return Err(MeasureError::file(
                &self.file,
                format!("the belt speed of an undriven record is {belt_speed}: a finite speed in m/s other than 0"),
            ));
        }
        self.belt_speed = Some(belt_speed);
        Ok(self)
    }

    /// Whether `record` has no drive: one channel in m, every other channel constant (see
    /// [`UndrivenRecord::new`]).
    pub fn is_undriven(record: &Record) -> bool {
        let metres = record.channels.iter().filter(|c| c.unit == "m").count();
        metres == 1
            && record
                .channels
                .iter()
                .all(|c| c.unit == "m" || c.resolution.is_none())
    }
}

/// The self-excited cycle of one oscillator: the parameters (β = 0), the section's state at
/// τ = 0, the period in τ (`None` for steady sliding, at y_e) and the class.
#[derive(Debug, Clone, Copy)]
struct Cycle {
    experiment_params: Params,
    section: State,
    period: Option<f64>,
    class: MotionClass,
    equilibrium: f64,
}

/// The cycle of `experiment` without a drive, settling from `start` (a section of a cycle
/// nearby) or from rest.
fn cycle_of(
    experiment: &Experiment,
    steady: &crate::steady::SteadyOptions,
    start: Option<State>,
) -> Result<Cycle, crate::Error> {
    let mut e = experiment.clone().with_beta(0.0)?;
    if let Some(s) = start {
        e = e.with_initial(s)?;
    }
    let state = e.steady_with(steady)?;
    let Some(cycle) = state.self_excited else {
        return Err(crate::Error::InvalidParameter {
            name: "vb",
            value: e.vb(),
            allowed: "a moving belt (vb ≠ 0): an undriven block's motion is self-excited",
        });
    };
    let period = match (state.class, cycle.period) {
        (MotionClass::SteadySliding, _) => None,
        (_, Some(t)) => Some(t),
        (_, None) => {
            return Err(crate::Error::InvalidParameter {
                name: "self-excited cycle",
                value: f64::NAN,
                allowed: "a motion that settles on a cycle or on steady sliding",
            })
        }
    };
    Ok(Cycle {
        experiment_params: state.params,
        section: state.final_state(),
        period,
        class: state.class,
        equilibrium: cycle.equilibrium,
    })
}

/// y and y' of `cycle` at the times `time` (s) with its section at `t_s` (s), ω0 in rad/s.
fn sample_cycle(
    experiment: &Experiment,
    cycle: &Cycle,
    omega0: f64,
    t_s: f64,
    time: &[f64],
) -> Result<Vec<(f64, f64)>, crate::Error> {
    let Some(period) = cycle.period else {
        return Ok(vec![(cycle.equilibrium, 0.0); time.len()]);
    };
    let phases: Vec<f64> = time
        .iter()
        .map(|&t| (omega0 * (t - t_s)).rem_euclid(period).min(period))
        .collect();
    let mut order: Vec<usize> = (0..time.len()).collect();
    order.sort_by(|&a, &b| phases[a].total_cmp(&phases[b]));
    let sorted: Vec<f64> = order.iter().map(|&i| phases[i]).collect();
    let e = experiment.clone().with_beta(0.0)?;
    let mut solver = e.factory().make(cycle.experiment_params, cycle.section)?;
    let samples = sample_at(solver.as_mut(), &sorted, |_| {})?;
    let mut out = vec![(0.0, 0.0); time.len()];
    for (&i, s) in order.iter().zip(&samples) {
        out[i] = (s.y, s.v);
    }
    Ok(out)
}

/// y and y' of the motion of `experiment` without a drive from rest on the ground (y = y0,
/// y' = 0) at τ = 0, at the times `time` (s, increasing), ω0 in rad/s.
fn sample_from_rest(
    experiment: &Experiment,
    y0: f64,
    omega0: f64,
    time: &[f64],
) -> Result<Vec<(f64, f64)>, crate::Error> {
    let e = experiment.clone().with_beta(0.0)?;
    let taus: Vec<f64> = time.iter().map(|&t| omega0 * t).collect();
    let mut solver = e.factory().make(e.params()?, State::new(y0, 0.0)?)?;
    let samples = sample_at(solver.as_mut(), &taus, |_| {})?;
    Ok(samples.iter().map(|s| (s.y, s.v)).collect())
}

/// Where a record's values are among the fit's: its offset's slot (with the offset free), its
/// section time's (a record of the settled cycle), and which of the fit's belts it was taken
/// on.
#[derive(Debug, Clone, Copy)]
struct Slot {
    offset: Option<usize>,
    section: Option<usize>,
    belt: usize,
}

/// The least-squares problem of undriven records.
struct Problem<'a> {
    setup: &'a Setup,
    data: &'a [UndrivenRecord],
    /// Used times and displacements of each record.
    time: Vec<Vec<f64>>,
    response: Vec<Vec<f64>>,
    /// 1/σ of each record.
    weights: Vec<f64>,
    /// Each record's values.
    slots: Vec<Slot>,
    /// The belts the records were taken on: each record's own belt speed (m/s), `None` for
    /// the experiment's; and whether a record of the settled cycle was taken on it.
    belts: Vec<(Option<f64>, bool)>,
    /// The last evaluation's cycle on each belt (the warm start of the next).
    last: Option<Vec<Option<Cycle>>>,
    watch: Watch<'a>,
    /// A coordinate held at a value (a profile likelihood's).
    pinned: Option<(usize, f64)>,
}

impl profile::Pin for Problem<'_> {
    fn pin(&mut self, pinned: Option<(usize, f64)>) {
        self.pinned = pinned;
    }
}

/// A record's model at one evaluation.
struct Model {
    /// r at the used times (m), offset included.
    r: Vec<f64>,
    /// dr/dt_s at those times (m/s); 0 for a record from rest.
    dr_dts: Vec<f64>,
}

/// The experiment of a belt at `speed` (m/s; `None`: `e`'s own).
fn on_belt(e: &Experiment, speed: Option<f64>) -> Option<Experiment> {
    match speed {
        None => Some(e.clone()),
        Some(v) => {
            let vb =
                super::parameter::dimensionless(crate::experiment::Key::BeltSpeed, v, &e.scales()?);
            e.clone().with_vb(vb).ok()
        }
    }
}

impl Problem<'_> {
    /// (offset, section time) of record j (0 for those not fitted).
    fn nuisance(&self, x: &[f64], j: usize) -> (f64, f64) {
        let slot = self.slots[j];
        (
            slot.offset.map_or(0.0, |k| x[k]),
            slot.section.map_or(0.0, |k| x[k]),
        )
    }

    /// The experiment on each belt at x, and its cycle where a record of the settled cycle
    /// needs it (settling from the last evaluation's section).
    fn cycles(&self, x: &[f64]) -> Option<Vec<(Experiment, Option<Cycle>)>> {
        let e = self.setup.at(&x[..self.setup.free.len()])?;
        (0..self.belts.len())
            .into_par_iter()
            .map(|b| {
                let (speed, settled) = self.belts[b];
                let e = on_belt(&e, speed)?;
                if !settled {
                    return Some((e, None));
                }
                let warm = self.last.as_ref().and_then(|l| l[b]).map(|c| c.section);
                let cycle = cycle_of(&e, &self.setup.steady, warm).ok()?;
                Some((e, Some(cycle)))
            })
            .collect()
    }

    fn model(&self, e: &Experiment, cycle: Option<&Cycle>, x: &[f64], j: usize) -> Option<Model> {
        let scales = e.scales()?;
        let (offset, t_s) = self.nuisance(x, j);
        let samples = match (self.data[j].start, cycle) {
            (UndrivenStart::FromRest { position }, _) => {
                sample_from_rest(e, position / scales.position, scales.omega0, &self.time[j])
            }
            (UndrivenStart::Settled, Some(cycle)) => {
                sample_cycle(e, cycle, scales.omega0, t_s, &self.time[j])
            }
            (UndrivenStart::Settled, None) => return None,
        }
        .ok()?;
        let settled = self.slots[j].section.is_some();
        Some(Model {
            r: samples
                .iter()
                .map(|(y, _)| scales.position * y + offset)
                .collect(),
            dr_dts: samples
                .iter()
                .map(|(_, v)| {
                    if settled {
                        -scales.position * scales.omega0 * v
                    } else {
                        0.0
                    }
                })
                .collect(),
        })
    }

    /// Every record's model at x, and the cycle on each belt.
    fn models(&self, x: &[f64]) -> Option<(Vec<Model>, Vec<Option<Cycle>>)> {
        let belts = self.cycles(x)?;
        let models = (0..self.data.len())
            .into_par_iter()
            .map(|j| {
                let (e, cycle) = &belts[self.slots[j].belt];
                self.model(e, cycle.as_ref(), x, j)
            })
            .collect::<Option<Vec<_>>>()?;
        Some((models, belts.into_iter().map(|(_, c)| c).collect()))
    }

    fn weighted(&self, models: &[Model]) -> Vec<f64> {
        let mut out = Vec::new();
        for (j, m) in models.iter().enumerate() {
            let w = self.weights[j];
            out.extend(m.r.iter().zip(&self.response[j]).map(|(a, b)| w * (a - b)));
        }
        out
    }

    fn all(&self, x: &[f64]) -> Option<Vec<f64>> {
        self.models(x).map(|(m, _)| self.weighted(&m))
    }
}

impl lm::Problem for Problem<'_> {
    type Error = FitError;

    fn residuals(&mut self, x: &[f64]) -> Result<Option<Vec<f64>>, FitError> {
        self.setup.check_stop()?;
        let Some((models, cycles)) = self.models(x) else {
            return Ok(None);
        };
        self.last = Some(cycles);
        Ok(Some(self.weighted(&models)))
    }

    fn jacobian(&mut self, x: &[f64], r: &[f64]) -> Result<Vec<Vec<f64>>, FitError> {
        self.setup.check_stop()?;
        let file = &self.data[0].file;
        let n_free = self.setup.free.len();
        let mut columns = vec![vec![0.0; r.len()]; x.len()];
        for (k, column) in columns.iter_mut().enumerate().take(n_free) {
            let dx = central::CENTRAL_STEP * x[k].abs().max(1.0);
            let (lo, hi) = self.setup.bounds(k);
            let mut up = x.to_vec();
            let mut down = x.to_vec();
            up[k] = (x[k] + dx).min(hi);
            down[k] = (x[k] - dx).max(lo);
            let (Some(rp), Some(rm)) = (self.all(&up), self.all(&down)) else {
                return Err(no_value(file, x[k] * self.setup.scale[k]));
            };
            let width = up[k] - down[k];
            for (i, (a, b)) in rp.iter().zip(&rm).enumerate() {
                column[i] = (a - b) / width;
            }
        }
        let (models, _) = self.models(x).ok_or_else(|| no_value(file, f64::NAN))?;
        let mut start = 0;
        for (j, m) in models.iter().enumerate() {
            let w = self.weights[j];
            let len = m.r.len();
            if let Some(k) = self.slots[j].offset {
                columns[k][start..start + len].fill(w);
            }
            if let Some(k) = self.slots[j].section {
                for (i, d) in m.dr_dts.iter().enumerate() {
                    columns[k][start + i] = w * d;
                }
            }
            start += len;
        }
        Ok(columns)
    }

    fn iteration(&mut self, iteration: usize, sum_squares: f64) -> Result<(), FitError> {
        self.watch.tell(iteration, sum_squares)
    }

    fn floor(&self) -> f64 {
        let mut sum = 0.0;
        let mut count = 0;
        for (j, m) in self.data.iter().enumerate() {
            let f = self.weights[j] * noise_floor(0.0, &self.response[j], m.resolution);
            sum += self.time[j].len() as f64 * f * f;
            count += self.time[j].len();
        }
        sum / count.max(1) as f64
    }

    fn bounds(&self, n: usize) -> Vec<(f64, f64)> {
        self.setup.all_bounds(n, self.pinned)
    }
}

impl passes::Passes for Problem<'_> {
    /// Each record by its RMS residual.
    fn reweight(&mut self, first: &lm::Solution) {
        let mut start_row = 0;
        let weights: Vec<f64> = (0..self.data.len())
            .map(|j| {
                let len = self.time[j].len();
                let w = self.weights[j];
                let s = rms(&first.residuals[start_row..start_row + len]) / w;
                start_row += len;
                1.0 / noise_floor(s, &self.response[j], self.data[j].resolution)
            })
            .collect();
        self.weights = weights;
    }

    fn advance(&mut self, iterations: usize) {
        self.watch.before += iterations;
    }
}

/// Points of one period in the scan of a record's section time.
const SCAN: usize = 400;

/// The section time t_s (s) and offset (m) of record `j` that fit it best with the
/// cycle at the starting values: the least sum of squares over [`SCAN`] shifts of one
/// period (the offset at the mean difference at each), t_s then moved by whole periods to
/// the record's middle.
fn start_nuisance(
    e: &Experiment,
    cycle: &Cycle,
    time: &[f64],
    response: &[f64],
) -> Result<(f64, f64), crate::Error> {
    let scales = e.scales().expect("a mechanical oscillator has scales");
    let period = cycle.period.expect("a cycle");
    let seconds = period / scales.omega0;
    // One period sampled densely, for interpolation.
    let fine = 8 * SCAN;
    let grid: Vec<f64> = (0..=fine)
        .map(|k| seconds * k as f64 / fine as f64)
        .collect();
    let table: Vec<f64> = sample_cycle(e, cycle, scales.omega0, 0.0, &grid)?
        .iter()
        .map(|(y, _)| scales.position * y)
        .collect();
    let at = |t: f64| {
        let u = (t / seconds).rem_euclid(1.0) * fine as f64;
        let i = (u.floor() as usize).min(fine - 1);
        let f = u - i as f64;
        table[i] * (1.0 - f) + table[i + 1] * f
    };
    let mut best = (f64::INFINITY, 0.0, 0.0);
    for k in 0..SCAN {
        let t_s = seconds * k as f64 / SCAN as f64;
        let model: Vec<f64> = time.iter().map(|&t| at(t - t_s)).collect();
        let offset =
            response.iter().zip(&model).map(|(r, m)| r - m).sum::<f64>() / time.len() as f64;
        let ssr: f64 = response
            .iter()
            .zip(&model)
            .map(|(r, m)| (m + offset - r).powi(2))
            .sum();
        if ssr < best.0 {
            best = (ssr, t_s, offset);
        }
    }
    let middle = 0.5 * (time[0] + time[time.len() - 1]);
    let t_s = best.1 + ((middle - best.1) / seconds).round() * seconds;
    Ok((t_s, best.2))
}

/// What the records cannot see of the friction levels with the offset of r free, without a
/// drive: with Coulomb's or the Stribeck law F0 and μs only as (μs − 1)·F0 (the last named of
/// the two held); with the cubic law (whose K1 and K3 are held in N·s/m and N·s³/m³) the
/// static level μs·F0 only shifts r, so neither F0 nor μs (each held).
fn friction_levels(experiment: &Experiment, free: &[FitParameter]) -> Vec<FitWarning> {
    let levels: Vec<FitParameter> = free
        .iter()
        .copied()
        .filter(|p| matches!(*p, FitParameter::Friction | FitParameter::MuS))
        .collect();
    if matches!(experiment.friction_law(), FrictionLaw::Cubic { .. }) {
        return levels
            .into_iter()
            .map(|p| FitWarning::NotIdentified {
                parameters: vec![p],
                combination: "the offset of r (the cubic law's static level μs·F0 only shifts \
                              r without a drive)"
                    .into(),
                held: p,
            })
            .collect();
    }
    if levels.len() < 2 {
        return Vec::new();
    }
    vec![FitWarning::NotIdentified {
        parameters: levels.clone(),
        combination: "(μs − 1)·F0 (without a drive, with the offset of r free, the kinetic \
                      level F0 only shifts r)"
            .into(),
        held: levels[1],
    }]
}

/// What a fit of undriven records starts from: the free parameters the records can show
/// (and the warnings of those held), the setup, the starting values (free, then each
/// record's offset and section time), and each record's used times, displacements and
/// weights.
struct Start {
    plan: identify::Plan,
    setup: Setup,
    x: Vec<f64>,
    slots: Vec<Slot>,
    belts: Vec<(Option<f64>, bool)>,
    time: Vec<Vec<f64>>,
    response: Vec<Vec<f64>>,
    weights: Vec<f64>,
}

/// The start of a fit of `data` (see [`fit_undriven`]), or the fault that refuses it.
fn start(
    experiment: &Experiment,
    data: &[UndrivenRecord],
    free: &[FitParameter],
    options: &FitOptions,
) -> Result<Start, FitError> {
    if data.is_empty() {
        return Err(FitError::NoData);
    }
    match experiment.system() {
        Some(System::Mechanics(_)) => {}
        Some(System::Circuit(_)) => {
            return Err(FitError::Undriven(
                "an undriven record is a block's displacement on a moving belt: give the \
                 mechanical oscillator's parts and --belt-speed, not a circuit"
                    .into(),
            ))
        }
        None => return Err(FitError::NeedsCircuit),
    }
    if experiment.vb() == 0.0 && data.iter().any(|m| m.belt_speed.is_none()) {
        return Err(FitError::Undriven(
            "an undriven record needs a moving belt (--belt-speed): without a drive or a \
             belt the block comes to rest"
                .into(),
        ));
    }
    Setup::new(experiment, free)?;
    let mut plan = identify::plan(experiment, free);
    // A record from rest at a known position shows the levels apart.
    let from_rest = data.iter().any(|m| m.start != UndrivenStart::Settled);
    if options.offset && !from_rest {
        for w in friction_levels(experiment, &plan.fitted) {
            if let FitWarning::NotIdentified { held, .. } = &w {
                plan.fitted.retain(|p| p != held);
            }
            plan.warnings.push(w);
        }
        if plan.fitted.is_empty() {
            return Err(FitError::FreeParameters(
                "no free parameter the undriven records can show: without a drive, with the \
                 offset of r free, the friction's static level only shifts r",
            ));
        }
    }
    let setup = Setup::new(experiment, &plan.fitted)?;
    let pick = |values: &[f64], used: &[bool]| -> Vec<f64> {
        values
            .iter()
            .zip(used)
            .filter(|(_, &u)| u)
            .map(|(&v, _)| v)
            .collect()
    };
    let time: Vec<Vec<f64>> = data.iter().map(|m| pick(&m.time, &m.used)).collect();
    let response: Vec<Vec<f64>> = data.iter().map(|m| pick(&m.response, &m.used)).collect();
    let weights: Vec<f64> = data
        .iter()
        .zip(&response)
        .map(|(m, r)| 1.0 / noise_floor(m.noise, r, m.resolution))
        .collect();
    let model_error = |file: &str, error| FitError::Model {
        file: file.to_string(),
        error,
    };
    // The belts, the cycle at the starting values on each belt a record of the settled
    // cycle was taken on, and each record's offset and section time.
    let start = setup
        .at(&vec![1.0; setup.free.len()])
        .ok_or(FitError::FreeParameters(
            "the starting values are outside the parameters' ranges",
        ))?;
    let scales = start.scales().expect("a mechanical oscillator has scales");
    let mut belts: Vec<(Option<f64>, bool)> = Vec::new();
    let mut slots = Vec::with_capacity(data.len());
    let mut x: Vec<f64> = vec![1.0; setup.free.len()];
    for m in data {
        let settled = m.start == UndrivenStart::Settled;
        let belt = match belts.iter().position(|b| b.0 == m.belt_speed) {
            Some(b) => b,
            None => {
                belts.push((m.belt_speed, false));
                belts.len() - 1
            }
        };
        belts[belt].1 |= settled;
        let offset = options.offset.then(|| {
            x.push(0.0);
            x.len() - 1
        });
        let section = settled.then(|| {
            x.push(0.0);
            x.len() - 1
        });
        slots.push(Slot {
            offset,
            section,
            belt,
        });
    }
    let mut cycles = Vec::with_capacity(belts.len());
    for &(speed, settled) in &belts {
        let e = on_belt(&start, speed).ok_or(FitError::FreeParameters(
            "a record's belt speed is outside the belt speeds allowed",
        ))?;
        if !settled {
            cycles.push(None);
            continue;
        }
        let cycle = cycle_of(&e, &setup.steady, None).map_err(|e| model_error(&data[0].file, e))?;
        let Some(period) = cycle.period else {
            return Err(FitError::Undriven(format!(
                "at the starting values the block slides steadily on the belt (no cycle: \
                 2ζ + μ'(vb) = {:.4}{}): a record of the settled motion is fitted from values \
                 whose motion is a self-excited cycle (a record from rest: --from-rest)",
                e.friction_law().sliding_damping(
                    e.params().map_or(0.0, |p| p.zeta),
                    e.mu_s(),
                    e.vb()
                ),
                speed.map_or(String::new(), |v| format!(" at a belt speed of {v} m/s"))
            )));
        };
        cycles.push(Some((e, cycle, period / scales.omega0)));
    }
    for (j, (m, (t, r))) in data.iter().zip(time.iter().zip(&response)).enumerate() {
        let slot = slots[j];
        match (m.start, &cycles[slot.belt]) {
            (UndrivenStart::Settled, Some((e, cycle, seconds))) => {
                let seconds = *seconds;
                let span = t.last().copied().unwrap_or(0.0) - t.first().copied().unwrap_or(0.0);
                if span < seconds {
                    return Err(FitError::Undriven(format!(
                        "{}: the record spans {span:.4e} s, less than one self-excited cycle at \
                         the starting values ({seconds:.4e} s): an undriven record must hold a \
                         whole cycle of the settled motion (a record from rest: --from-rest)",
                        m.file
                    )));
                }
                let (t_s, offset) =
                    start_nuisance(e, cycle, t, r).map_err(|e| model_error(&m.file, e))?;
                if let Some(k) = slot.offset {
                    x[k] = offset;
                }
                if let Some(k) = slot.section {
                    x[k] = t_s;
                }
            }
            // From rest at a known position: the offset is the first sample's reading there.
            (UndrivenStart::FromRest { position }, _) => {
                if let Some(k) = slot.offset {
                    x[k] = r[0] - position;
                }
            }
            // (None: a settled record's belt has its cycle.)
            (UndrivenStart::Settled, None) => {}
        }
    }
    let n_res: usize = time.iter().map(Vec::len).sum();
    if n_res <= x.len() {
        return Err(FitError::TooFewSamples {
            residuals: n_res,
            values: x.len(),
        });
    }
    Ok(Start {
        plan,
        setup,
        x,
        slots,
        belts,
        time,
        response,
        weights,
    })
}

/// Whether [`fit_undriven`] takes `experiment`, `data` and `free`: every fault it refuses
/// before it fits (no belt, starting values that slide steadily, a record shorter than one
/// cycle, …), at the cost of one cycle at the starting values; a front end says so before it
/// announces a long fit.
///
/// # Errors
/// As [`fit_undriven`], but for the fit's own failures.
pub fn check_undriven(
    experiment: &Experiment,
    data: &[UndrivenRecord],
    free: &[FitParameter],
    options: &FitOptions,
) -> Result<(), FitError> {
    start(experiment, data, free, options).map(|_| ())
}

/// Fit the free parameters of `experiment` (a mechanical oscillator on a moving belt) to
/// records of its undriven, self-excited motion (see the module documentation). The
/// experiment's values are the starting point; its drive is not used (β = 0).
///
/// # Errors
/// No record; not a mechanical oscillator, or one without a belt; a free parameter named
/// twice, of another system or law, or none; starting values whose motion is steady sliding
/// (no cycle to align a record with); a record shorter than one cycle at the starting
/// values; fewer samples than values.
pub fn fit_undriven(
    experiment: &Experiment,
    data: &[UndrivenRecord],
    free: &[FitParameter],
    options: &FitOptions,
) -> Result<FitReport, FitError> {
    fit_undriven_monitored(experiment, data, free, options, &())
}

/// [`fit_undriven`], telling `monitor` of every iteration (of both passes, a restart and the
/// intervals' profiles: at most [`RECORD_PASSES`]·[`FitOptions::max_iterations`]), which can
/// stop the fit.
///
/// # Errors
/// As [`fit_undriven`]; [`FitError::Stopped`] when the monitor stops the fit.
pub fn fit_undriven_monitored(
    experiment: &Experiment,
    data: &[UndrivenRecord],
    free: &[FitParameter],
    options: &FitOptions,
    monitor: &dyn FitMonitor,
) -> Result<FitReport, FitError> {
    let Start {
        plan,
        setup,
        x,
        slots,
        belts,
        time,
        response,
        weights,
    } = start(experiment, data, free, options)?;
    let watch = Watch {
        monitor,
        before: 0,
        total: RECORD_PASSES * options.max_iterations,
    };
    let mut problem = Problem {
        setup: &setup,
        data,
        time,
        response,
        weights,
        slots,
        belts,
        last: None,
        watch,
        pinned: None,
    };
    let settings = lm::Settings {
        max_iterations: options.max_iterations,
        tolerance: options.tolerance,
        gradient: lm::GRADIENT,
    };
    let failed = || FitError::Model {
        file: data[0].file.clone(),
        error: crate::Error::InvalidParameter {
            name: "fit",
            value: f64::NAN,
            allowed: "a model that can be computed at the starting values",
        },
    };
    let n_free = setup.free.len();
    let passed = passes::run(
        &mut problem,
        x,
        n_free,
        settings,
        passes::Reach::Full,
        failed,
    )?;
    let summary = passed.summarise(
        &problem,
        (experiment, &setup),
        (free, &plan.warnings),
        options,
        data.iter()
            .map(|m| (m.file.clone(), m.clipped, m.time.len())),
    );
    let (solution, iterations, dof) = (&passed.solution, passed.iterations, passed.dof);
    let n_values = solution.x.len();
    let (models, cycles) = problem.models(&solution.x).ok_or_else(failed)?;
    let fitted = setup.at(&solution.x[..n_free]).ok_or_else(failed)?;
    let scales = fitted.scales().expect("a mechanical oscillator has scales");
    // The cycle each record's motion settles on at the fitted values (that of a record from
    // rest computed here, for the report).
    let cycles: Vec<Option<Cycle>> = cycles
        .into_iter()
        .zip(&problem.belts)
        .map(|(cycle, &(speed, _))| {
            cycle.or_else(|| {
                let e = on_belt(&fitted, speed)?;
                cycle_of(&e, &setup.steady, None).ok()
            })
        })
        .collect();
    let mut records = Vec::with_capacity(data.len());
    let mut chi2 = 0.0;
    let mut groups = Vec::new();
    let mut all = Vec::new();
    for (j, (m, model)) in data.iter().zip(&models).enumerate() {
        let (offset, t_s) = problem.nuisance(&solution.x, j);
        let cycle = cycles[problem.slots[j].belt];
        let period = cycle.and_then(|c| c.period);
        let cycle_seconds = period.map(|p| p / scales.omega0);
        let residuals: Vec<f64> = model
            .r
            .iter()
            .zip(&problem.response[j])
            .map(|(a, b)| a - b)
            .collect();
        let ssr: f64 = residuals.iter().map(|r| r * r).sum();
        chi2 += ssr / noise_floor(m.noise, &problem.response[j], m.resolution).powi(2);
        groups.push((ssr, residuals.len()));
        all.extend_from_slice(&residuals);
        let span = problem.time[j].last().copied().unwrap_or(0.0);
        records.push(RecordFit {
            file: m.file.clone(),
            freq_hz: cycle_seconds.map_or(0.0, |s| 1.0 / s),
            amplitude_v: 0.0,
            w: period.map_or(0.0, |p| TAU / p),
            beta: 0.0,
            class: cycle.map_or(MotionClass::Undecided, |c| c.class),
            periods: cycle_seconds.map_or(0, |s| (span / s).floor() as usize),
            clipped: m.clipped,
            rms_residual_v: rms(&residuals),
            offset_v: offset,
            time_shift_s: t_s,
            noise_v: m.noise,
            time: problem.time[j].clone(),
            model: model.r.clone(),
            residuals,
        });
    }
    let noise = (data
        .iter()
        .zip(&problem.time)
        .map(|(m, t)| m.noise * m.noise * t.len() as f64)
        .sum::<f64>()
        / all.len() as f64)
        .sqrt();
    let (aic, bic) = criteria(&groups, n_values);
    Ok(FitReport {
        model: experiment.diode_model(),
        parameters: summary.parameters,
        correlation: summary.correlation,
        records,
        rows: vec![],
        rms_residual_v: rms(&all),
        noise_v: Some(noise),
        chi2_dof: Some(chi2 / dof as f64),
        dof,
        residuals: solution.residuals.len(),
        fitted_values: n_values,
        aic,
        bic,
        iterations,
        converged: summary.converged,
        jacobian: Jacobian::CentralDifferences,
        experiment: fitted,
        warnings: summary.warnings,
    })
}
