//! `stickslip orbit`: a periodic orbit by Newton's method, with its Floquet multipliers.

use crate::flags::{count, help, int, num, number};
use crate::model::ModelArgs;
use crate::output::{check_interrupt, interrupted, progress};
use anyhow::Result;
use stickslip::options::OrbitOptions;
use stickslip::stability::{
    Dynamics, Multiplier, NewtonOptions, OrbitReport, PeriodicOrbit, Stability, StabilityError,
};
use stickslip::steady::{MotionClass, SelfExcitedOrbit};
use stickslip::{Error, EventKind, OptionKey};

/// Find a periodic orbit by Newton's method on the p-fold strobe map (the state once every p
/// drive periods), with its Jacobian, and report its Floquet multipliers: whether it is
/// stable, and how fast perturbations grow or decay. With the PWL law the Jacobian is exact
/// (closed-form segments and saltation matrices); with --model shockley it is the derivative
/// of the stiff solver's computed map (the variational equations on the solver's own steps).
///
/// Without --period the motion from the initial state is run to its steady state (as
/// `stickslip steady`), which gives the period p and the guess. With --period P, Newton's
/// method starts from the state --transient drive periods after the initial state (0: the
/// initial state --y0 --v0 itself), so it also finds unstable orbits, which no simulation
/// settles on.
///
/// JSON keys: period (drive periods), drive_period (T = 2π/w, dimensionless time),
/// y, v (the state at the orbit's strobe, τ = 0 mod pT), stuck_at_strobe, multipliers
/// [{"re", "im"}, ...] (larger modulus first), moduli, stable, stability (stable, unstable,
/// neutral), lambda1 and lambda1_per_period (λ1 = ln|μ1|/(pT) and ln|μ1|/p, or "-inf"),
/// monodromy [[a, b], [c, d]], iterations, residuals, stops_per_period, events
/// [{"tau", "y", "kind"}] and stops [{"start", "duration"}] over one orbit period (times
/// from the strobe), w, beta, zeta, mu_s, phi.
///
/// Without a drive on a belt (--beta 0, --vb ≠ 0) the motion is self-excited: the orbit is
/// the cycle `stickslip steady` finds, with its own period (cycle_period_tau, and
/// cycle_period_s for the mechanical oscillator), not a drive period; one multiplier is 1
/// (the motion is autonomous) and, for a stick-slip cycle, the other is exactly 0 (every stop
/// ends in the same state); steady sliding is reported with the eigenvalues of its
/// linearisation. JSON keys then: summary, class, cycle_period_tau, cycle_period_s, section,
/// release_y, multipliers, stability, y_max, y_min, stick_fraction, sliding,
/// sliding_eigenvalues, sliding_stability.
///
/// Examples: stickslip orbit --preset paper --w 0.7 --beta 1.2
///           stickslip orbit --zeta 0 --mu-s 3 --w 0.33 --beta 9 --period 1 --transient 2000 --json
///           stickslip orbit --preset paper --model shockley --freq 3k --amplitude 1.5
#[derive(Debug, clap::Args)]
#[command(verbatim_doc_comment)]
pub struct Args {
    #[command(flatten)]
    model: ModelArgs,
    #[arg(long, help = help(OptionKey::OrbitPeriod), allow_hyphen_values = true)]
    period: Option<i64>,
    #[arg(long, help = help(OptionKey::OrbitTransient), default_value_t = int(OptionKey::OrbitTransient) as _, allow_hyphen_values = true)]
    transient: i64,
    #[arg(long = OptionKey::OrbitMaxPeriods.flag(), help = help(OptionKey::OrbitMaxPeriods), default_value_t = int(OptionKey::OrbitMaxPeriods) as _, allow_hyphen_values = true)]
    max_periods: i64,
    #[arg(long = OptionKey::OrbitMaxPeriod.flag(), help = help(OptionKey::OrbitMaxPeriod), default_value_t = int(OptionKey::OrbitMaxPeriod) as _, allow_hyphen_values = true)]
    max_period: i64,
    #[arg(long = OptionKey::NewtonTolerance.flag(), help = help(OptionKey::NewtonTolerance), default_value_t = num(OptionKey::NewtonTolerance), value_parser = crate::model::finite, allow_hyphen_values = true)]
    newton_tolerance: f64,
    #[arg(long = OptionKey::MaxIterations.flag(), help = help(OptionKey::MaxIterations), default_value_t = int(OptionKey::MaxIterations) as _, allow_hyphen_values = true)]
    max_iterations: i64,
    /// Print JSON instead of text.
    #[arg(long)]
    json: bool,
}

/// Run `stickslip orbit`.
pub fn run(args: Args) -> Result<()> {
    let period = args
        .period
        .map(|p| count(OptionKey::OrbitPeriod, p))
        .transpose()?;
    let transient = count(OptionKey::OrbitTransient, args.transient)?;
    let orbit = OrbitOptions {
        period,
        transient,
        max_periods: count(OptionKey::OrbitMaxPeriods, args.max_periods)?,
        max_period: count(OptionKey::OrbitMaxPeriod, args.max_period)?,
        newton: NewtonOptions {
            tolerance: number(OptionKey::NewtonTolerance, args.newton_tolerance)?,
            max_iterations: count(OptionKey::MaxIterations, args.max_iterations)?,
            ..NewtonOptions::default()
        },
    }
    .validate()?;
    let experiment = args.model.experiment()?;
    let params = experiment.params()?;
    let dynamics = experiment.dynamics()?;
    let steady = experiment
        .steady_options()
        .with_max_periods(orbit.max_periods)?
        .with_max_period(orbit.max_period)?;
    let newton = orbit.newton;
    eprintln!("orbit: {experiment}");
    // Without a drive the cycle's own period is found; a period asked for is the library's
    // to refuse (`periodic_orbit`).
    if experiment.is_self_excited() && orbit.period.is_none() {
        let cycle = experiment.self_excited_orbit(&steady)?;
        if args.json {
            println!("{}", serde_json::to_string_pretty(&cycle)?);
        } else {
            print_self_excited(&cycle);
        }
        return Ok(());
    }
    let transient = orbit.transient;
    let bar = progress(transient as u64, "transient");
    let result = experiment.periodic_orbit(
        orbit.period,
        transient,
        &steady,
        &newton,
        &|done: usize, _: usize| {
            bar.set_position(done as u64);
            !interrupted()
        },
    );
    bar.finish_and_clear();
    check_interrupt()?;
    let orbit = match result {
        Err(Error::Stability(e @ StabilityError::NoPeriod { .. })) => anyhow::bail!(
            "{e}. With no period up to {} there is no orbit to start from: give --period P \
             (and --transient N) to look for an orbit of period P, more --max-periods, or see \
             `stickslip lyapunov`",
            args.max_period
        ),
        other => other?,
    };
    let report = OrbitReport::of(&orbit, &params, dynamics.as_ref())?;
    if args.json {
        println!("{}", serde_json::to_string_pretty(&report)?);
    } else {
        print_text(&orbit, &report, dynamics.as_ref());
    }
    Ok(())
}

/// A multiplier as text: `+0.62645`, `+5.5e-18` or `+0.3 + 0.4i`.
fn multiplier(m: &Multiplier) -> String {
    let number = |x: f64| {
        if x != 0.0 && x.abs() < 1e-4 {
            format!("{x:+.3e}")
        } else {
            format!("{x:+.10}")
        }
    };
    if m.is_real() {
        number(m.re)
    } else {
        format!(
            "{} {} {}i",
            number(m.re),
            if m.im < 0.0 { "−" } else { "+" },
            number(m.im.abs()).trim_start_matches('+')
        )
    }
}

fn print_text(orbit: &PeriodicOrbit, r: &OrbitReport, dynamics: &dyn Dynamics) {
    let p = orbit.period;
    let plural =
        |n: usize, one: &str, many: &str| format!("{n} {}", if n == 1 { one } else { many });
    println!(
        "periodic orbit of period {} (T = 2π/w = {:.6} in τ = ω0·t), found by Newton's method \
         in {}",
        plural(p, "drive period", "drive periods"),
        orbit.drive_period,
        plural(orbit.iterations, "step", "steps")
    );
    if r.least_period < p {
        println!(
            "                  (it repeats after {} already: the orbit of period {} taken {} \
             times; the multipliers below are those of {p} drive periods)",
            plural(r.least_period, "drive period", "drive periods"),
            r.least_period,
            p / r.least_period
        );
    }
    let residuals: Vec<String> = orbit.residuals.iter().map(|x| format!("{x:.1e}")).collect();
    println!("residuals         {}", residuals.join(" → "));
    println!(
        "strobe state      y = {:.12}, y' = {:.12}{}",
        orbit.state.y,
        orbit.state.v,
        if orbit.stuck_at_strobe {
            " (stuck there)"
        } else {
            ""
        }
    );
    let count = |kind| orbit.events.iter().filter(|e| e.kind == kind).count();
    println!(
        "events per orbit  {} turns, {} stops, {} releases",
        count(EventKind::Turn),
        count(EventKind::Stick),
        count(EventKind::Slip)
    );
    let stops: Vec<String> = orbit
        .stops
        .iter()
        .map(|s| format!("at τ = {:.6} for {:.6}", s.start, s.duration))
        .collect();
    if stops.is_empty() {
        println!("stops             none (the orbit slides throughout)");
    } else {
        println!(
            "stops             {} per drive period: {}",
            r.stops_per_period,
            stops.join("; ")
        );
    }
    let m = orbit.monodromy.0;
    println!(
        "monodromy M       [[{:+.6e}, {:+.6e}], [{:+.6e}, {:+.6e}]]",
        m[0][0], m[0][1], m[1][0], m[1][1]
    );
    let [mu1, mu2] = orbit.multipliers;
    println!(
        "multipliers       μ1 = {} (|μ1| = {:.10}), μ2 = {} (|μ2| = {:.3e})",
        multiplier(&mu1),
        mu1.modulus(),
        multiplier(&mu2),
        mu2.modulus()
    );
    let exponent = orbit.exponent();
    println!(
        "exponent          ln|μ1|/(pT) = {:+.6e} per unit τ ({:+.6e} per drive period)",
        exponent,
        exponent * orbit.drive_period
    );
    println!("stability         {}", stability_label(orbit.stability));
    println!();
    println!(
        "What the multipliers say: a small change δ of the state (y, y') at the strobe comes \
         back {} later as M·δ, and along an eigenvector of M it is multiplied by its \
         multiplier μ.",
        plural(p, "drive period", "drive periods")
    );
    let modulus = mu1.modulus();
    match orbit.stability {
        Stability::Stable => {
            println!(
            "Here |μ1| = {modulus:.6} < 1: every perturbation shrinks, by at least that factor \
             per orbit, so the orbit attracts the motions near it{}.",
            if modulus > 0.0 {
                format!(" (a perturbation halves every {:.3} orbits)", -(2f64.ln()) / modulus.ln())
            } else {
                String::new()
            }
        )
        }
        Stability::Unstable => println!(
            "Here |μ1| = {modulus:.6} > 1: a perturbation along the first eigenvector grows by \
             that factor per orbit, so a simulation never settles on this orbit; its stable \
             neighbours or chaos do."
        ),
        Stability::Neutral if (1.0 - modulus).abs() <= 1e-9 => println!(
            "Here |μ1| is 1 within 1e-9: neutral (a bifurcation, or a continuum of orbits, as \
             rest is: the oscillator stays wherever it stopped)."
        ),
        Stability::Neutral => println!(
            "Here |μ1| = {modulus:.10} goes to 1 as Newton's method goes on (one more step \
             takes it closer to 1 by more than a tenth of its distance): the orbit sits where \
             P(x) − x touches zero, at the edge of a continuum of orbits, and its multiplier is 1 \
             there: neutral."
        ),
    }
    if !mu1.is_real() {
        println!(
            "The multipliers are a complex pair: perturbations spiral around the orbit, turning \
             by {:.4} rad per orbit.",
            mu1.im.atan2(mu1.re).abs()
        );
    } else if mu1.re < 0.0 {
        println!("μ1 < 0: a perturbation changes sign from one orbit to the next.");
    }
    if mu2.modulus() < 1e-12 * modulus.max(1.0) && !orbit.stops.is_empty() {
        // Why μ2 vanishes is the model's: the exact Coulomb model's stops, a smooth friction
        // law's stops on a belt, or the Shockley diodes' steep slope near zero current.
        if dynamics.is_exact() {
            println!(
                "μ2 = 0 because the orbit stops: a stop erases the velocity perturbation, so \
                 the strobe map is one-dimensional there (M has rank one)."
            );
        } else if dynamics.sticks() {
            println!(
                "μ2 = 0 because the orbit stops: while it sticks the block moves with the belt \
                 (y' = vb) until the net force reaches ±μs, whatever its velocity was, so a \
                 stop of the friction law erases the velocity perturbation and the strobe map \
                 is one-dimensional there (M has rank one)."
            );
        } else {
            println!(
                "μ2 ≈ 0 because the orbit stops: while the current stays near zero the diodes' \
                 slope (about n V_T/(2 I_s), megohms) damps a current perturbation by \
                 e^(−∫D'dτ), so the strobe map is one-dimensional there; below 1e-12·|μ1| the \
                 value of μ2 is the solver's (it depends on its steps), not the circuit's."
            );
        }
    }
}

/// The orbit of a self-excited motion (β = 0 on a belt) in words.
fn print_self_excited(c: &SelfExcitedOrbit) {
    println!("{}", c.summary);
    if let Some(s) = c.cycle_period_s {
        println!("period            {s:.12e} s");
    }
    println!("y range           {:.12} … {:.12}", c.y_min, c.y_max);
    println!("stick fraction    {:.12}", c.stick_fraction);
    if let Some(y) = c.release_y {
        println!("every stop ends   at y = {y:.12}, y' = vb (the static limit)");
    }
    if let Some([trivial, other]) = c.multipliers {
        println!(
            "multipliers       μ1 = {} (trivial: the motion is autonomous), μ2 = {}",
            multiplier(&trivial),
            multiplier(&other)
        );
    }
    if c.class == MotionClass::PureSlipCycle && c.multipliers.is_some() {
        println!(
            "                  μ2 is the derivative of the return map on the turning point \
             y' = 0 at y_max, from the solver's tangent dynamics over one period"
        );
    }
    if c.release_y.is_some() {
        println!(
            "                  μ2 = 0 exactly: every stop ends in the same state, so sticking \
             collapses every perturbation; the cycle attracts all motions that stick"
        );
    }
    let [a, b] = c.sliding_eigenvalues;
    println!(
        "steady sliding    y = {:.12}, y' = 0: damping 2ζ + μ'(|vb|) = {:+.6}, eigenvalues \
         {} and {} ({})",
        c.sliding.equilibrium,
        c.sliding.damping,
        multiplier(&a),
        multiplier(&b),
        c.sliding_stability.label()
    );
    if let Some(stability) = c.stability {
        println!("stability         {}", stability_label(stability));
    }
}

/// A stability verdict in words.
fn stability_label(stability: Stability) -> &'static str {
    match stability {
        Stability::Stable => "stable",
        Stability::Unstable => "unstable",
        Stability::Neutral => "neutral",
    }
}
