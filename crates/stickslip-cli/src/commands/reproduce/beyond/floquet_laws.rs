//! The Floquet multipliers of the orbits along Fig. 4's resonance curves, PWL diodes beside
//! Shockley diodes: where the smooth law's stability agrees with the paper's model and where
//! it does not.

use super::super::figures::{beta_color, FIG4_BETAS};
use super::super::report::{sig, Report, Section};
use super::super::Context;
use super::frequency;
use crate::plot::{Figure, Legend, Panel, Series, Style, INK};
use anyhow::Result;
use rayon::prelude::*;
use serde_json::json;
use stickslip::experiment::{DiodeModel, Key};
use stickslip::report::{OrbitReport, OrbitTable};
use stickslip::scan::ParameterRange;
use stickslip::stability::NewtonOptions;
use stickslip::{DiodePair, Error, Experiment};

/// The range of w, as in Fig. 4.
const W: (f64, f64) = (0.2, 2.0);

/// Below this times max(|μ₁|, 1), μ₂ of an orbit that stops is not resolved: zero exactly
/// for the PWL law, and for the Shockley law a number that depends on the solver's steps
/// (as `stickslip orbit` says).
const RESOLVED: f64 = 1e-12;

/// One orbit of the figure: its law and its report, or why there is none.
struct Point {
    law: DiodeModel,
    beta: f64,
    w: f64,
    orbit: std::result::Result<OrbitReport, String>,
}

impl Point {
    /// Whether the orbit stops for a positive time (a PWL orbit that does has μ₂ = 0
    /// exactly: a stop forgets the velocity).
    fn sticks(&self) -> bool {
        self.orbit
            .as_ref()
            .is_ok_and(|o| o.stops.iter().any(|s| s.duration > 0.0))
    }

    fn modulus(&self, k: usize) -> f64 {
        self.orbit.as_ref().map_or(f64::NAN, |o| o.moduli[k])
    }

    /// Whether |μ₂| is resolved (see [`RESOLVED`]).
    fn resolved(&self) -> bool {
        self.modulus(1) >= RESOLVED * self.modulus(0).max(1.0)
    }
}

/// The orbit from rest of `experiment`, with its report.
fn orbit_from_rest(experiment: &Experiment) -> std::result::Result<OrbitReport, Error> {
    let orbit = experiment.periodic_orbit(
        None,
        0,
        &experiment.steady_options(),
        &NewtonOptions::default(),
        &|_: usize, _: usize| !crate::output::interrupted(),
    )?;
    OrbitReport::of(
        &orbit,
        &experiment.params()?,
        experiment.dynamics()?.as_ref(),
    )
}

/// |μ₁| and |μ₂| of the orbits from rest against w at Fig. 4's drive amplitudes, PWL and
/// Shockley (1N4148) diodes.
pub fn floquet_laws(report: &mut Report, ctx: &Context) -> Result<()> {
    let steps = if ctx.quick { 19 } else { 91 };
    let ws = ParameterRange::new("w", W.0, W.1, steps)?.values();
    let pair = DiodePair::one_n4148();
    let shockley = ctx.paper.clone().with_shockley(pair)?;
    let mut jobs = Vec::new();
    for law in DiodeModel::ALL {
        for &beta in &FIG4_BETAS {
            for &w in &ws {
                jobs.push((law, beta, w));
            }
        }
    }
    let started = std::time::Instant::now();
    // Every orbit on its own: the same points for any number of threads.
    let points: Vec<Point> = jobs
        .into_par_iter()
        .map(|(law, beta, w)| -> Result<Point> {
            let base = match law {
                DiodeModel::Pwl => &ctx.paper,
                DiodeModel::Shockley => &shockley,
            };
            let experiment = base.clone().with_w(w)?.with_beta(beta)?;
            let orbit = match orbit_from_rest(&experiment) {
                Err(Error::Cancelled { .. }) => anyhow::bail!("interrupted"),
                other => other.map_err(|e| e.to_string()),
            };
            Ok(Point {
                law,
                beta,
                w,
                orbit,
            })
        })
        .collect::<Result<_>>()?;
    crate::output::check_interrupt()?;
    // The time goes to standard error: the report itself is the same on every run.
    eprintln!(
        "reproduce: {} orbits of the PWL and Shockley laws in {:.1} s",
        points.len(),
        started.elapsed().as_secs_f64()
    );

    let of = |law: DiodeModel, beta: f64| {
        points
            .iter()
            .filter(move |p| p.law == law && p.beta == beta)
    };
    let style = |law: DiodeModel| match law {
        DiodeModel::Pwl => Style::Line(2),
        DiodeModel::Shockley => Style::Dashed(2),
    };
    // |μ₁| of every orbit; |μ₂| where it is resolved.
    let curve = |law: DiodeModel, beta: f64, k: usize| -> Vec<(f64, f64)> {
        of(law, beta)
            .map(|p| {
                let shown = p.modulus(k) > 0.0 && (k == 0 || p.resolved());
                (p.w, if shown { p.modulus(k) } else { f64::NAN })
            })
            .collect()
    };
    let mut legend: Vec<Series> = FIG4_BETAS
        .iter()
        .map(|&beta| {
            Series::new(
                format!("β = {beta}"),
                vec![],
                beta_color(beta),
                Style::Bars(1.0),
            )
        })
        .collect();
    legend.push(Series::new(
        "PWL diodes (exact)",
        vec![],
        INK,
        style(DiodeModel::Pwl),
    ));
    legend.push(Series::new(
        "Shockley, 1N4148 (stiff solver)",
        vec![],
        INK,
        style(DiodeModel::Shockley),
    ));
    let panel = |k: usize, title: &str, y_label: &str| {
        let mut series = Vec::new();
        for law in DiodeModel::ALL {
            for &beta in &FIG4_BETAS {
                series.push(Series::new(
                    "",
                    curve(law, beta, k),
                    beta_color(beta),
                    style(law),
                ));
            }
        }
        series.extend(legend.clone());
        Panel {
            title: title.into(),
            x_label: "w = Ω/ω0".into(),
            y_label: y_label.into(),
            series,
            legend: Some(Legend::Best),
            x_range: Some(W),
            y_log: true,
            ..Default::default()
        }
    };
    report.figure(
        "floquet-laws",
        &Figure {
            panels: vec![
                panel(
                    0,
                    "(a) the larger Floquet multiplier of the orbit from rest",
                    "|μ1|",
                ),
                panel(
                    1,
                    "(b) the smaller, where resolved (an orbit that stops: not drawn)",
                    "|μ2|",
                ),
            ],
            columns: 1,
            panel_size: (1000, 480),
        },
    )?;
    let parts: Vec<(DiodeModel, Vec<OrbitReport>)> = DiodeModel::ALL
        .iter()
        .map(|&law| {
            let orbits = points
                .iter()
                .filter(|p| p.law == law)
                .filter_map(|p| p.orbit.as_ref().ok().cloned())
                .collect();
            (law, orbits)
        })
        .collect();
    let tables: Vec<(DiodeModel, OrbitTable)> = parts
        .iter()
        .map(|(law, orbits)| (*law, OrbitTable { orbits }))
        .collect();
    report.tables(
        "floquet-laws.csv",
        // The orbit's diode law (`pwl` or `shockley`), named as its key.
        &[Key::Diode.name()],
        tables
            .iter()
            .map(|(law, table)| (vec![law.label().to_string()], table)),
    )?;

    // The numbers of the caption: the two laws at the same (β, w).
    let pairs: Vec<(&Point, &Point)> = points
        .iter()
        .filter(|p| p.law == DiodeModel::Pwl && p.orbit.is_ok())
        .filter_map(|p| {
            points
                .iter()
                .find(|q| q.law == DiodeModel::Shockley && q.beta == p.beta && q.w == p.w)
                .filter(|q| q.orbit.is_ok())
                .map(|q| (p, q))
        })
        .collect();
    let failed: Vec<&Point> = points.iter().filter(|p| p.orbit.is_err()).collect();
    let ratio = |(p, q): &(&Point, &Point)| q.modulus(0) / p.modulus(0);
    let spread = |set: &[&(&Point, &Point)]| {
        set.iter().fold((f64::INFINITY, 0.0f64), |(lo, hi), pair| {
            let r = ratio(pair);
            (lo.min(r), hi.max(r))
        })
    };
    let kind = |slide_pwl: bool, slide_shockley: bool| -> Vec<&(&Point, &Point)> {
        pairs
            .iter()
            .filter(|(p, q)| p.sticks() != slide_pwl && q.sticks() != slide_shockley)
            .collect()
    };
    let (both_slide, both_stick) = (kind(true, true), kind(false, false));
    let (only_shockley_slides, only_pwl_slides) = (kind(false, true), kind(true, false));
    // Sliding orbits of both laws, β by β: the ratio of |μ1|.
    let sliding: Vec<(f64, usize, (f64, f64))> = FIG4_BETAS
        .iter()
        .map(|&beta| {
            let set: Vec<&(&Point, &Point)> = both_slide
                .iter()
                .copied()
                .filter(|(p, _)| p.beta == beta)
                .collect();
            (beta, set.len(), spread(&set))
        })
        .collect();
    let (stick_lo, stick_hi) = spread(&both_stick);
    // Orbits that stop, and of those, the ones whose μ2 is not resolved.
    let stopping = |law: DiodeModel| points.iter().filter(move |p| p.law == law && p.sticks());
    let unresolved = |law: DiodeModel| stopping(law).filter(|p| !p.resolved()).count();
    let (pwl_stops, shockley_stops) = (
        stopping(DiodeModel::Pwl).count(),
        stopping(DiodeModel::Shockley).count(),
    );
    let unstable = |law: DiodeModel| {
        points
            .iter()
            .filter(|p| p.law == law && p.modulus(0) > 1.0)
            .count()
    };
    // A PWL orbit that stops has μ2 = 0: the computed one is rounding.
    anyhow::ensure!(
        unresolved(DiodeModel::Pwl) == pwl_stops,
        "a PWL orbit that stops with |μ2| above {RESOLVED}·max(|μ1|, 1)"
    );
    report.summary.insert(
        "beyond_floquet_laws".into(),
        json!({
            "betas": FIG4_BETAS, "w": [W.0, W.1], "steps": steps,
            "orbits": points.len(), "failed": failed.len(),
            "both_slide": both_slide.len(), "both_stick": both_stick.len(),
            "only_shockley_slides": only_shockley_slides.len(),
            "only_pwl_slides": only_pwl_slides.len(),
            "ratio_mu1_sliding": sliding
                .iter()
                .map(|(beta, n, (lo, hi))| json!({"beta": beta, "pairs": n, "ratio": [lo, hi]}))
                .collect::<Vec<_>>(),
            "ratio_mu1_both_stick": [stick_lo, stick_hi],
            "stopping": {"pwl": pwl_stops, "shockley": shockley_stops},
            "mu2_unresolved_stopping": {
                "pwl": unresolved(DiodeModel::Pwl),
                "shockley": unresolved(DiodeModel::Shockley),
            },
            "unstable": {"pwl": unstable(DiodeModel::Pwl), "shockley": unstable(DiodeModel::Shockley)},
        }),
    );
    let sliding = sliding
        .iter()
        .filter(|(_, n, _)| *n > 0)
        .map(|(beta, n, (lo, hi))| {
            format!("{}–{} at β = {beta} ({n} pairs)", sig(*lo, 3), sig(*hi, 3))
        })
        .collect::<Vec<_>>()
        .join(", ");
    let where_only = |set: &[&(&Point, &Point)]| {
        let mut by_beta: Vec<String> = Vec::new();
        for &beta in &FIG4_BETAS {
            let ws: Vec<f64> = set
                .iter()
                .filter(|(p, _)| p.beta == beta)
                .map(|(p, _)| p.w)
                .collect();
            if let (Some(lo), Some(hi)) = (ws.first(), ws.last()) {
                by_beta.push(if lo == hi {
                    format!("at β = {beta}, w = {}", frequency(*lo))
                } else {
                    format!(
                        "{} frequencies at β = {beta} (w from {} to {})",
                        ws.len(),
                        frequency(*lo),
                        frequency(*hi)
                    )
                });
            }
        }
        if by_beta.is_empty() {
            "none".to_string()
        } else {
            by_beta.join(", ")
        }
    };
    let failed = match failed.as_slice() {
        [] => String::new(),
        list => format!(
            " {} of the {} orbits were not found and are left out: {}.",
            list.len(),
            points.len(),
            list.iter()
                .map(|p| format!(
                    "{} at β = {}, w = {} ({})",
                    p.law.label(),
                    p.beta,
                    sig(p.w, 3),
                    p.orbit.as_ref().err().map_or("", String::as_str)
                ))
                .collect::<Vec<_>>()
                .join("; ")
        ),
    };
    report.sections.push(Section {
        id: "floquet-laws".into(),
        title: "Stability of the orbits along Fig. 4: PWL and Shockley diodes".into(),
        caption: format!(
            "The Floquet multipliers of the periodic orbit reached from rest at each of {steps} \
             frequencies from w = {} to {} at Fig. 4's drive amplitudes β = {}, in the \
             paper's circuit with its PWL diodes (solid; the exact monodromy from the \
             closed-form segments and saltation matrices) and with two 1N4148 Shockley diodes \
             (dashed; the monodromy from the variational equations on the stiff solver's own \
             steps), as <code>stickslip orbit [--model shockley]</code> finds them; (b) shows \
             |μ2| where it is above 10<sup>−12</sup>·max(|μ1|, 1). Where both orbits slide throughout, both multipliers are set by the \
             damping over one period (a complex pair has |μ1|² = det M), and the Shockley \
             |μ1| is {sliding} times the PWL one: close to 1 at large β, where the diodes' \
             voltage is small beside the drive, further from it at small β, where the diodes' \
             slope adds to the damping while they conduct. Where the PWL orbit \
             stops ({pwl_stops} orbits), a stop forgets the velocity: its μ2 is zero exactly \
             (below 10<sup>−12</sup> in every computed matrix: rounding). The \
             Shockley pair never holds the current at zero: its differential resistance \
             rises to {} MΩ at i = 0, so near i = 0 it damps a current perturbation \
             enormously instead of erasing it; μ2 = det M/μ1 is positive but below what the \
             solver resolves at {} of the {shockley_stops} Shockley orbits that stop \
             (|μ2| &lt; 10<sup>−12</sup>·max(|μ1|, 1): its value depends on the solver's steps, \
             so (b) leaves it out). Where both stick, the Shockley |μ1| is from {} to \
             {} times the PWL one: the stops differ, the soft knee changing when and for how \
             long the current stays near zero, and |μ1| of a sticking orbit, what of a \
             perturbation survives its stops, has deep minima (the dips of (a)) at a \
             different w for each law. The largest differences are not of the law's \
             smoothness but of its voltage: the 1N4148 pair has {} V at 1 mA, below \
             U_t = 0.7 V (Fig. 1 (b)), so at the same β its drive is relatively stronger and \
             its orbit slides where the PWL orbit sticks: {}.{} Orbits with |μ1| > 1: {} \
             PWL, {} Shockley.{failed}",
            W.0,
            W.1,
            FIG4_BETAS
                .iter()
                .map(|b| b.to_string())
                .collect::<Vec<_>>()
                .join(", "),
            sig(pair.differential_resistance(0.0) / 1e6, 3),
            unresolved(DiodeModel::Shockley),
            sci(stick_lo),
            sci(stick_hi),
            sig(pair.voltage(1e-3), 3),
            where_only(&only_shockley_slides),
            match only_pwl_slides.as_slice() {
                [] => String::new(),
                set => format!(" Only the PWL orbit slides at {}.", where_only(set)),
            },
            unstable(DiodeModel::Pwl),
            unstable(DiodeModel::Shockley),
        ),
        figures: vec!["floquet-laws".into()],
        data: vec!["floquet-laws.csv".into()],
        tables: vec![],
    });
    Ok(())
}

/// A positive number for a caption: 3 significant digits, or a power of ten below 10⁻³.
fn sci(x: f64) -> String {
    if x.is_finite() && x != 0.0 && x.abs() < 1e-3 {
        let text = format!("{x:.1e}");
        let (mantissa, exponent) = text.split_once('e').expect("an exponent");
        format!("{mantissa}·10<sup>{}</sup>", exponent.replace('-', "−"))
    } else {
        sig(x, 3)
    }
}
