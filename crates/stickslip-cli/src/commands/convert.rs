//! `stickslip convert`: a physical description's dimensionless parameters.

use crate::model::ModelArgs;
use crate::output::{outln, usage};
use anyhow::Result;
use stickslip::experiment::{Key, SpecError};

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
    let experiment = args.model.experiment()?;
    if experiment.w().is_some() != experiment.beta().is_some() {
        let key = if experiment.w().is_none() {
            Key::W
        } else {
            Key::Beta
        };
        return Err(stickslip::Error::Spec(SpecError::MissingDrive { key }).into());
    }
    let Some(c) = experiment.conversion() else {
        usage!("convert needs a physical description: --preset paper, --config FILE, or --inductance --capacitance --resistance --ut --rd (or --mass --stiffness --damping --friction)");
    };
    // What was converted goes to standard error, as every command's description does:
    // standard output holds the numbers alone (text or JSON).
    let description = experiment.to_string();
    eprintln!(
        "convert: {}",
        description.split("; dimensionless").next().unwrap_or("")
    );
    let mut text = String::new();
    if args.json {
        outln!(text, "{}", serde_json::to_string_pretty(&c)?);
    } else {
        outln!(
            text,
            "omega0 = {:.1} rad/s   (1/sqrt(LC) or sqrt(k/m))",
            c.omega0
        );
        outln!(text, "f0     = {:.3} Hz", c.f0);
        outln!(
            text,
            "alpha  = {:.1} 1/s     (the paper's alpha = 2 zeta omega0)",
            c.alpha
        );
        outln!(text, "zeta   = {:.6}", c.zeta);
        outln!(text, "Q      = {:.4}", c.q);
        if let (Some(w), Some(beta)) = (c.w, c.beta) {
            outln!(text, "w      = {w:.6}  (Omega/omega0)");
            outln!(text, "beta   = {beta:.6}  (drive amplitude / friction)");
        }
    }
    crate::output::print(&text)
}
