//! `stickslip netlist` (not yet available).

/// Flags of `stickslip netlist`.
#[derive(Debug, clap::Args)]
pub struct Args {}

/// Run `stickslip netlist`.
pub fn run(_args: Args) -> anyhow::Result<()> {
    anyhow::bail!("`stickslip netlist` is not available in this version")
}
