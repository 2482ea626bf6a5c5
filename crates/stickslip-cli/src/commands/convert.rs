//! `stickslip convert`: a physical description's dimensionless parameters.

use crate::model::ModelArgs;
use crate::output::usage;
use anyhow::Result;
use serde_json::json;

/// Print ω0, f0, α, ζ, Q of a physical description, and w and β when a drive is given.
///
/// Example: stickslip convert --preset paper --freq 9.97k --amplitude 1.498 --json
#[derive(Debug, clap::Args)]
#[command(verbatim_doc_comment)]
pub struct Args {
    #[command(flatten)]
    model: ModelArgs,
    /// Print JSON: omega0 (rad/s), f0 (Hz), alpha (1/s), zeta, Q, and w, beta with a drive.
    #[arg(long)]
    json: bool,
}

/// Run `stickslip convert`.
pub fn run(args: Args) -> Result<()> {
    let mut m = args.model.clone();
    let has_drive = m.w.is_some()
        || m.freq.is_some()
        || m.omega.is_some()
        || m.beta.is_some()
        || m.amplitude.is_some();
    let partial_drive = has_drive
        && !((m.w.is_some() || m.freq.is_some() || m.omega.is_some())
            && (m.beta.is_some() || m.amplitude.is_some()));
    if partial_drive {
        usage!("a drive needs both a frequency (--freq, --omega or --w) and an amplitude (--amplitude or --beta)");
    }
    if !has_drive {
        // Only the circuit: fill a placeholder drive, reported as absent.
        m.w = Some(1.0);
        m.beta = Some(0.0);
    }
    let model = m.build()?;
    let Some(system) = model.system else {
        usage!("convert needs a physical description: --preset paper, --config FILE, or --inductance --capacitance --resistance --ut --rd (or --mass --stiffness --damping --friction)");
    };
    let s = system.scales();
    if args.json {
        let mut v = json!({
            "omega0": s.omega0,
            "f0": s.f0(),
            "alpha": s.alpha,
            "zeta": s.zeta(),
            "Q": s.quality_factor(),
        });
        if has_drive {
            v["w"] = json!(model.params.w);
            v["beta"] = json!(model.params.beta);
        }
        println!("{}", serde_json::to_string_pretty(&v)?);
    } else {
        println!(
            "{}",
            model.summary.split("; dimensionless").next().unwrap_or("")
        );
        println!("omega0 = {:.1} rad/s   (1/sqrt(LC) or sqrt(k/m))", s.omega0);
        println!("f0     = {:.3} Hz", s.f0());
        println!(
            "alpha  = {:.1} 1/s     (the paper's alpha = 2 zeta omega0)",
            s.alpha
        );
        println!("zeta   = {:.6}", s.zeta());
        println!("Q      = {:.4}", s.quality_factor());
        if has_drive {
            println!("w      = {:.6}  (Omega/omega0)", model.params.w);
            println!(
                "beta   = {:.6}  (drive amplitude / friction)",
                model.params.beta
            );
        }
    }
    Ok(())
}
