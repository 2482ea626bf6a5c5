//! `GET /api/orbit`: the periodic orbit at one point by Newton's method on the strobe map,
//! with its Floquet multipliers (`stickslip orbit --json`), for either diode law and the
//! mechanical oscillator; without a drive on a belt (β = 0) the self-excited cycle or steady
//! sliding (`stickslip orbit --json` prints the same), with the cycle run again for the
//! phase plane.

use super::answer::*;
use super::caps::CAPS;
use super::request::*;
use crate::limit::Budget;
use crate::query::{option_key, ApiError, Query};
use serde::Serialize;
use std::sync::Arc;
use stickslip::experiment::Experiment;
use stickslip::options::{OptionKey, OrbitOptions};
use stickslip::report::{Columns, OrbitTable};
use stickslip::stability::{NewtonOptions, OrbitReport};
use stickslip::steady::{self_excited_trace, SelfExcitedOrbit};
use stickslip::Error;

/// The options `/api/orbit` takes, rows of the option table's `orbit` group (the flags of
/// `stickslip orbit`).
const ORBIT_OPTIONS: [OptionKey; 6] = [
    OptionKey::OrbitPeriod,
    OptionKey::OrbitTransient,
    OptionKey::OrbitMaxPeriods,
    OptionKey::OrbitMaxPeriod,
    OptionKey::NewtonTolerance,
    OptionKey::MaxIterations,
];

/// `GET /api/orbit`.
#[derive(Debug)]
pub struct OrbitRequest {
    experiment: Experiment,
    options: OrbitOptions,
}

/// The answer of `/api/orbit`: the description, and the orbit as `stickslip orbit --json`
/// prints it with its row of the orbits' table, or, where Newton's method (or the steady
/// state that starts it) finds no orbit, `converged: false` and the library's line saying why.
#[derive(Debug, Serialize)]
pub struct OrbitAnswer {
    /// The experiment.
    #[serde(flatten)]
    pub about: About,
    /// Whether Newton's method converged on a periodic orbit (its residual within the
    /// tolerance); `false` with `orbit` null and the `reason`.
    pub converged: bool,
    /// What `stickslip orbit --json` prints ([`OrbitReport`]).
    pub orbit: Option<OrbitReport>,
    /// The orbit's row of the orbits' table ([`OrbitTable`], the columns of `w,beta,period,...`
    /// by name, one value each).
    pub table: Option<Columns>,
    /// The arguments arg μ of the two multipliers in radians (−π to π), in the order of
    /// `orbit.multipliers`; their moduli are `orbit.moduli`.
    pub arguments: Option<[f64; 2]>,
    /// Why there is no orbit (the library's one line), when `converged` is false.
    pub reason: Option<String>,
    /// Without a drive on a belt (β = 0): the self-excited cycle or steady sliding, as
    /// `stickslip orbit --json` prints it ([`SelfExcitedOrbit`]); `orbit`, `table` and
    /// `arguments` are then null. Left out for a driven motion.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub self_excited: Option<SelfExcitedOrbit>,
    /// The self-excited cycle run again from its section, [`CYCLE_SAMPLES`] samples over one
    /// period (the library's `self_excited_trace`), for the phase plane; left out for a
    /// driven motion and for steady sliding.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub cycle: Option<CycleSamples>,
}

impl OrbitAnswer {
    /// The answer where no orbit (or self-excited cycle) was found: `converged: false` and
    /// the library's line `err` saying why.
    fn not_found(about: About, err: &Error) -> Self {
        Self {
            about,
            converged: false,
            orbit: None,
            table: None,
            arguments: None,
            reason: Some(err.to_string()),
            self_excited: None,
            cycle: None,
        }
    }
}

/// Samples of a self-excited cycle over one period.
pub const CYCLE_SAMPLES: usize = 256;

/// One period of a self-excited cycle: τ from the start of the steady state's record, y and
/// y' (dimensionless).
#[derive(Debug, Serialize)]
pub struct CycleSamples {
    /// Dimensionless time τ.
    pub tau: Vec<f64>,
    /// Position y.
    pub y: Vec<f64>,
    /// Velocity y'.
    pub v: Vec<f64>,
}

/// A whole number of `option` from the query, if given.
fn optional_whole(q: &mut Query, option: OptionKey) -> Result<Option<usize>, ApiError> {
    let key = option_key(option);
    if !q.has(key) {
        return Ok(None);
    }
    q.whole(key, 0).map(Some)
}

impl OrbitRequest {
    /// Keys: the model keys, and the options of `stickslip orbit` (`period`, `transient`,
    /// `max-periods`, `max-period`, `newton-tolerance`, `max-iterations`, from the option
    /// table, within the lab's caps).
    ///
    /// # Errors
    /// A 400 naming the key at fault.
    pub fn parse(raw: Option<&str>) -> Result<Self, ApiError> {
        let mut q = Query::parse(raw)?;
        let experiment = q.experiment()?;
        let period = optional_whole(&mut q, OptionKey::OrbitPeriod)?;
        let default = |o: OptionKey| table_default(o) as usize;
        let transient = whole(
            &mut q,
            OptionKey::OrbitTransient,
            default(OptionKey::OrbitTransient),
        )?;
        let max_periods = whole(&mut q, OptionKey::OrbitMaxPeriods, CAPS.max_periods)?;
        let max_period = whole(
            &mut q,
            OptionKey::OrbitMaxPeriod,
            default(OptionKey::OrbitMaxPeriod),
        )?;
        let tolerance = q
            .number(option_key(OptionKey::NewtonTolerance), None)?
            .unwrap_or_else(|| table_default(OptionKey::NewtonTolerance));
        let max_iterations = whole(
            &mut q,
            OptionKey::MaxIterations,
            default(OptionKey::MaxIterations),
        )?;
        let options = OrbitOptions {
            period,
            transient,
            max_periods,
            max_period,
            newton: NewtonOptions {
                tolerance,
                max_iterations,
                ..NewtonOptions::default()
            },
        };
        CAPS.check_orbit(&options)
            .and_then(|_| options.validate())
            .map_err(|e| option_error(&e))?;
        q.finish(&known(&ORBIT_OPTIONS, &[]))?;
        needs_drive(&experiment)?;
        // The law's stability tools (a stiff solver's options checked) before any work.
        experiment.dynamics().map_err(|e| ApiError::library(&e))?;
        Ok(Self {
            experiment,
            options,
        })
    }

    /// The orbit, as `stickslip orbit` finds it.
    ///
    /// # Errors
    /// The time limit; the library's errors other than finding no orbit.
    pub fn run(self, budget: &Arc<Budget>) -> Result<OrbitAnswer, ApiError> {
        let e = &budget.limit_experiment(&self.experiment);
        let params = e.params().map_err(|err| ApiError::library(&err))?;
        let dynamics = e.dynamics().map_err(|err| ApiError::library(&err))?;
        let o = self.options;
        let steady = e
            .steady_options()
            .with_max_periods(o.max_periods)
            .and_then(|s| s.with_max_period(o.max_period))
            .map_err(|err| option_error(&err))?;
        let about = About::new(e);
        // Without a drive the cycle's own period is found; a period asked for is the
        // library's to refuse (`periodic_orbit`: a 400 naming it, before any work).
        if e.is_self_excited() && o.period.is_none() {
            return self_excited(e, &steady, about, budget);
        }
        let found = e.periodic_orbit(o.period, o.transient, &steady, &o.newton, &());
        let orbit = match found {
            Ok(orbit) => orbit,
            // No orbit to report: Newton's method did not converge, or the steady state
            // that starts it found no period (the library's line says which).
            Err(err @ Error::Stability(_)) => return Ok(OrbitAnswer::not_found(about, &err)),
            Err(err) => return Err(failed(err, budget, "periodic orbit")),
        };
        let report = OrbitReport::of(&orbit, &params, dynamics.as_ref())
            .map_err(|err| failed(err, budget, "periodic orbit"))?;
        let table = Columns::of(&OrbitTable {
            orbits: std::slice::from_ref(&report),
        });
        Ok(OrbitAnswer {
            about,
            converged: true,
            arguments: Some(report.multipliers.map(|m| m.argument())),
            table: Some(table),
            orbit: Some(report),
            reason: None,
            self_excited: None,
            cycle: None,
        })
    }
}

/// The answer for a belt without a drive: the self-excited cycle `stickslip orbit` finds
/// (or steady sliding), its one period run again for the phase plane; `converged: false`
/// with the library's line where no cycle was found.
fn self_excited(
    e: &Experiment,
    steady: &stickslip::SteadyOptions,
    about: About,
    budget: &Arc<Budget>,
) -> Result<OrbitAnswer, ApiError> {
    let found = e
        .steady_with(&steady.with_spectrum(false))
        .and_then(|settled| Ok((e.self_excited_orbit_of(&settled)?, settled)));
    let (orbit, settled) = match found {
        Ok(found) => found,
        Err(err @ Error::Stability(_)) => return Ok(OrbitAnswer::not_found(about, &err)),
        Err(err) => return Err(failed(err, budget, "self-excited cycle")),
    };
    let cycle = match orbit.cycle_period_tau {
        Some(_) => self_excited_trace(&e.factory(), &settled, CYCLE_SAMPLES)
            .map_err(|err| failed(err, budget, "self-excited cycle"))?
            .map(|samples| CycleSamples {
                tau: samples.iter().map(|s| s.tau).collect(),
                y: samples.iter().map(|s| s.y).collect(),
                v: samples.iter().map(|s| s.v).collect(),
            }),
        None => None,
    };
    Ok(OrbitAnswer {
        about,
        converged: true,
        orbit: None,
        table: None,
        arguments: None,
        reason: None,
        self_excited: Some(orbit),
        cycle,
    })
}
