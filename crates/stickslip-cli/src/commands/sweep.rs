//! `stickslip sweep` (not yet available).

/// Flags of `stickslip sweep`.
#[derive(Debug, clap::Args)]
pub struct Args {}

/// Run `stickslip sweep`.
pub fn run(_args: Args) -> anyhow::Result<()> {
    anyhow::bail!("`stickslip sweep` is not available in this version")
}
