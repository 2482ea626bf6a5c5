//! `stickslip`: the forced oscillator with dry friction and its diode-RLC twin, from the
//! command line. Every subcommand is glue over the `stickslip` library; the tool itself is
//! the library `stickslip_cli` (`src/lib.rs`).

fn main() -> std::process::ExitCode {
    stickslip_cli::main()
}
