//! `stickslip theory` (not yet available).

/// Flags of `stickslip theory`.
#[derive(Debug, clap::Args)]
pub struct Args {}

/// Run `stickslip theory`.
pub fn run(_args: Args) -> anyhow::Result<()> {
    anyhow::bail!("`stickslip theory` is not available in this version")
}
