//! `stickslip phase-diagram` (not yet available).

/// Flags of `stickslip phase-diagram`.
#[derive(Debug, clap::Args)]
pub struct Args {}

/// Run `stickslip phase-diagram`.
pub fn run(_args: Args) -> anyhow::Result<()> {
    anyhow::bail!("`stickslip phase-diagram` is not available in this version")
}
