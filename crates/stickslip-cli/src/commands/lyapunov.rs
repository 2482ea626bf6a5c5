//! `stickslip lyapunov`: the Lyapunov exponents of a motion, from the exact tangent dynamics.

use crate::flags::{count, help, int, num};
use crate::model::ModelArgs;
use crate::output::{check_interrupt, interrupted, progress};
use anyhow::Result;
use stickslip::stability::{
    LyapunovOptions, LyapunovReport, NonperiodicClassification, NonperiodicVerdict, SecondExponent,
};
use stickslip::OptionKey;

/// The largest Lyapunov exponent λ1 of the motion from the initial state, with a standard
/// error, and the second exponent λ2, by the tangent dynamics: with the PWL law the 2×2
/// Jacobian of the exact flow (segment matrices and the saltation matrices of turns, stops
/// and releases), with --model shockley the derivative of the stiff solver's computed
/// solution (the variational equations on its own steps), carried along the trajectory and
/// renormalised every drive period.
///
/// λ1 is the mean rate at which two nearby motions separate: their distance grows like
/// e^(λ1 τ), τ = ω0·t. After --transient drive periods (the tangent is carried and aligned,
/// not recorded) it is averaged over at most --periods more, cut into --blocks blocks whose
/// spread gives the error σ. The measurement stops as soon as its verdict is decided: it is
/// looked at after about --periods/32, /16, /8, /4, /2 and all of them (blocks of at least
/// 10 periods), and stops at the first look where the halves agree and |λ1| > kσ; at k = 4
/// and 20 blocks a wrong sign passes a look with probability 3.9e-4, all looks together at
/// most 2.3e-3. --fixed always measures all --periods.
///
/// The class: periodic with its period when the motion is not chaotic and has reached a
/// periodic orbit or rest (its strobe at the end comes back within 1e-9 after at most 16
/// drive periods); else chaotic (λ1 > kσ, k = --significance), contracting (λ1 < −kσ:
/// settling onto a periodic attractor not reached yet), quasi-periodic (|λ1| ≤ kσ), or
/// undecided (the two halves of the measurement disagree: a transient). Without a drive
/// on a belt (β = 0, --vb ≠ 0) the motion is self-excited: limit-cycle (|λ1| ≤ kσ, λ2 < −kσ
/// or −∞) or equilibrium (λ1 < −kσ: steady sliding). λ2 is −∞ once the
/// motion stops: a stop erases the velocity perturbation (PWL law; with Shockley diodes λ2
/// stays finite, and very negative where the current stops).
///
/// JSON keys: lambda1, lambda1_error (λ1 and σ per unit τ = ω0·t), lambda1_per_period,
/// lambda1_error_per_period, class, verdict (what λ1 alone says), period (null unless
/// periodic), converged, lambda2 (a number, or null when λ2 = −∞), lambda2_error,
/// lambda2_per_period,
/// lambda2_reason (why λ2 = −∞, or null), stops_per_period, transient_periods, periods
/// (measured), cap_periods, sequential, blocks, significance, block_means, drive_period,
/// final_y, final_v, w, beta, zeta, mu_s, phi.
///
/// Examples: stickslip lyapunov --zeta 0 --mu-s 3 --w 0.33 --beta 9 --json
///           stickslip lyapunov --preset paper --model shockley --freq 3k --amplitude 1.5
#[derive(Debug, clap::Args)]
#[command(verbatim_doc_comment)]
pub struct Args {
    #[command(flatten)]
    model: ModelArgs,
    #[arg(long, help = help(OptionKey::LyapunovTransient), default_value_t = int(OptionKey::LyapunovTransient) as _, allow_hyphen_values = true)]
    transient: i64,
    #[arg(long, help = help(OptionKey::LyapunovMeasured), default_value_t = int(OptionKey::LyapunovMeasured) as _, allow_hyphen_values = true)]
    periods: i64,
    #[arg(long, help = help(OptionKey::Blocks), default_value_t = int(OptionKey::Blocks) as _, allow_hyphen_values = true)]
    blocks: i64,
    #[arg(long, help = help(OptionKey::Significance), default_value_t = num(OptionKey::Significance), value_parser = crate::model::finite, allow_hyphen_values = true)]
    significance: f64,
    #[arg(long, help = help(OptionKey::Fixed))]
    fixed: bool,
    /// Print JSON instead of text.
    #[arg(long)]
    json: bool,
}

/// Run `stickslip lyapunov`.
pub fn run(args: Args) -> Result<()> {
    // Counts are typed signed, so that `-4` is refused by the table's range; the rule
    // between --periods and --blocks is the options' own (`validate`).
    let options = LyapunovOptions {
        transient_periods: count(OptionKey::LyapunovTransient, args.transient)?,
        blocks: count(OptionKey::Blocks, args.blocks)?,
        periods: OptionKey::LyapunovMeasured.whole(args.periods)?,
        significance: args.significance,
        sequential: !args.fixed,
    }
    .validate()?;
    let experiment = args.model.experiment()?;
    let params = experiment.params()?;
    let dynamics = experiment.dynamics()?;
    options.check_horizon(&params)?;
    eprintln!(
        "lyapunov: {experiment}; {} periods of transient, {}{} measured in {} blocks",
        options.transient_periods,
        if options.sequential { "at most " } else { "" },
        options.periods / options.blocks * options.blocks,
        options.blocks
    );
    let total = options.transient_periods + options.periods / options.blocks * options.blocks;
    let bar = progress(total as u64, "lyapunov");
    let result = experiment.lyapunov(&options, &|done: usize, _: usize| {
        bar.set_position(done as u64);
        !interrupted()
    });
    bar.finish_and_clear();
    check_interrupt()?;
    let c = result?;
    let report = LyapunovReport::of(&c, &options, &params, dynamics.as_ref())?;
    if args.json {
        println!("{}", serde_json::to_string_pretty(&report)?);
    } else {
        let per_second = experiment.scales().map(|s| s.omega0);
        print_text(&c, &options, report.period, per_second, dynamics.is_exact());
    }
    Ok(())
}

fn print_text(
    c: &NonperiodicClassification,
    options: &LyapunovOptions,
    period: Option<usize>,
    omega0: Option<f64>,
    exact: bool,
) {
    let e = &c.exponents;
    let l = e.largest;
    let k = options.significance;
    println!(
        "largest exponent  λ1 = {:+.6e} ± {:.1e} per unit τ ({:+.6e} ± {:.1e} per drive period)",
        l.per_tau, l.error_per_tau, l.per_period, l.error_per_period
    );
    if let Some(omega0) = omega0 {
        println!(
            "                  {:+.6e} ± {:.1e} per second (λ1·ω0)",
            l.per_tau * omega0,
            l.error_per_tau * omega0
        );
    }
    let class = match (c.verdict, period) {
        (NonperiodicVerdict::Chaotic, _) => format!(
            "chaotic: λ1 > {k}σ, two motions that start δ apart are e^(λ1 τ)·δ apart later \
             (a factor e every {:.4} drive periods)",
            1.0 / l.per_period
        ),
        (NonperiodicVerdict::LimitCycle, _) => format!(
            "limit cycle: |λ1| ≤ {k}σ along it and λ2 < 0 across it; β = 0, the motion is \
             self-excited (autonomous), so λ1 = 0 is the shift along the cycle, not a torus \
             (`stickslip orbit` gives its period)"
        ),
        (NonperiodicVerdict::Equilibrium, _) => format!(
            "equilibrium: λ1 < −{k}σ, both exponents negative; β = 0, the motion settles on \
             steady sliding"
        ),
        (NonperiodicVerdict::Contracting, Some(p)) => format!(
            "periodic with period {p} drive period{}: the motion has reached a periodic orbit \
             (its strobe repeats), and λ1 < −{k}σ: nearby motions converge to it \
             (`stickslip orbit --period {p}` gives its multipliers)",
            if p == 1 { "" } else { "s" }
        ),
        (_, Some(p)) => format!(
            "periodic with period {p} drive period{}: the motion has reached a periodic motion \
             (its strobe repeats), and |λ1| ≤ {k}σ or the halves disagree: perturbations \
             neither grow nor decay measurably (a neutral family of orbits, or rest)",
            if p == 1 { "" } else { "s" }
        ),
        (NonperiodicVerdict::Contracting, None) => format!(
            "contracting: λ1 < −{k}σ, nearby motions converge; the motion settles onto a \
             periodic motion not reached by the end of the measurement (or of a period above \
             16): more --transient, or see `stickslip orbit`"
        ),
        (NonperiodicVerdict::QuasiPeriodic, None) => {
            format!("quasi-periodic: |λ1| ≤ {k}σ, perturbations neither grow nor decay (a torus)")
        }
        (NonperiodicVerdict::Undecided, None) => "undecided: the first and the second half of the \
             measurement disagree (a transient, or chaos that ends): more --transient or \
             --periods"
            .to_string(),
    };
    println!("class             {class}");
    match e.second {
        SecondExponent::Finite(s) if exact => println!(
            "second exponent   λ2 = {:+.6e} ± {:.1e} per unit τ (λ1 + λ2 is the rate of \
             phase-area change: −2ζ while sliding, and each turn contracts)",
            s.per_tau, s.error_per_tau
        ),
        SecondExponent::Finite(s) => println!(
            "second exponent   λ2 = {:+.6e} ± {:.1e} per unit τ (λ1 + λ2 is the rate of \
             phase-area change, the mean of −2ζ − D'(y'): the diodes' slope D' is largest \
             where the current is near zero)",
            s.per_tau, s.error_per_tau
        ),
        SecondExponent::MinusInfinity { stops } => println!(
            "second exponent   λ2 = −∞: the motion stopped {stops} times while measured, and \
             a stop erases the velocity perturbation (det J = 0)"
        ),
    }
    println!("stops per period  {}", e.stops_per_period());
    let stopped = if e.periods < e.cap {
        format!(" (verdict decided: stopped early, the cap is {})", e.cap)
    } else {
        String::new()
    };
    println!(
        "measured over     {} drive periods{stopped} in {} blocks after {} of transient; \
         halves agree: {}",
        e.periods,
        options.blocks,
        options.transient_periods,
        if e.converged { "yes" } else { "no" }
    );
}
