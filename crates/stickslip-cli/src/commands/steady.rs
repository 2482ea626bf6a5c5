//! `stickslip steady` (not yet available).

/// Flags of `stickslip steady`.
#[derive(Debug, clap::Args)]
pub struct Args {}

/// Run `stickslip steady`.
pub fn run(_args: Args) -> anyhow::Result<()> {
    anyhow::bail!("`stickslip steady` is not available in this version")
}
