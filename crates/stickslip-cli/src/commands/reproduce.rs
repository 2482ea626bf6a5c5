//! `stickslip reproduce` (not yet available).

/// Flags of `stickslip reproduce`.
#[derive(Debug, clap::Args)]
pub struct Args {}

/// Run `stickslip reproduce`.
pub fn run(_args: Args) -> anyhow::Result<()> {
    anyhow::bail!("`stickslip reproduce` is not available in this version")
}
