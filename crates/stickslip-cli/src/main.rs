//! `stickslip`: the forced oscillator with dry friction and its diode-RLC twin, from the
//! command line. Every subcommand is glue over the `stickslip` library.

use clap::Parser;
use std::process::ExitCode;

mod commands;
mod diagrams;
mod flags;
mod model;
mod output;
mod plot;

/// Forced oscillator with dry (Coulomb) friction, and its twin: a series RLC circuit damped by
/// two anti-parallel diodes. Exact stick-slip trajectories, spectra, resonance curves with
/// hysteresis, stick-slip maps, and every figure of the paper.
///
/// Inside, everything is dimensionless: τ = ω0·t and
///   y'' + 2ζ y' + y + sgn(y') = β cos(w τ + φ)   while sliding,
///   y' = 0 and |β cos(w τ + φ) − y| ≤ μs          while stuck.
/// For the circuit y = u_C/U_t, 2ζ = (R+R_D)√(C/L), β = U/U_t, w = Ω/ω0.
/// Give either dimensionless flags (--zeta --w --beta) or a physical description
/// (--preset paper, --config FILE.toml, or --L --C --R ...); every command says which it used.
#[derive(Debug, Parser)]
#[command(
    name = "stickslip",
    version,
    about,
    long_about,
    max_term_width = 100,
    verbatim_doc_comment
)]
struct Cli {
    #[command(subcommand)]
    command: commands::Command,
}

fn main() -> ExitCode {
    let cli = match Cli::try_parse() {
        Ok(cli) => cli,
        Err(err) => {
            use clap::error::ErrorKind;
            return match err.kind() {
                ErrorKind::DisplayHelp
                | ErrorKind::DisplayVersion
                | ErrorKind::DisplayHelpOnMissingArgumentOrSubcommand => {
                    let _ = err.print();
                    ExitCode::SUCCESS
                }
                _ => {
                    let text = err.render().to_string();
                    let first = text.lines().next().unwrap_or("error: invalid arguments");
                    eprintln!("{first} (see --help)");
                    ExitCode::from(2)
                }
            };
        }
    };
    output::install_interrupt_handler();
    match commands::run(cli.command) {
        Ok(()) => ExitCode::SUCCESS,
        Err(err) => {
            let (message, usage) = describe(&err);
            eprintln!("error: {message}");
            if usage {
                ExitCode::from(2)
            } else {
                ExitCode::FAILURE
            }
        }
    }
}

/// One line for the user, and whether the error is in what they typed (exit code 2): a
/// library error about the description names the flags, not the library's keys.
fn describe(err: &anyhow::Error) -> (String, bool) {
    use stickslip::Error;
    let library = err.downcast_ref::<Error>();
    let usage = err.downcast_ref::<output::UsageError>().is_some()
        || library.is_some_and(|e| {
            matches!(
                e,
                Error::InvalidParameter { .. }
                    | Error::Spec(_)
                    | Error::Config(_)
                    | Error::Unsupported(_)
            )
        });
    if let Some(Error::Spec(spec)) = library {
        return (spec.render(&model::flag_name), true);
    }
    // The chain of causes joined.
    let message = err
        .chain()
        .map(|c| c.to_string())
        .collect::<Vec<_>>()
        .join(": ");
    (message, usage)
}
