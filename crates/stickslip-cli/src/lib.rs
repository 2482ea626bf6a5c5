//! The `stickslip` command-line tool as a library: the binary (`src/main.rs`) calls [`main`].
//! Its flag types are public for the fuzz targets (`fuzz/` of the repository), which parse
//! command lines the way the tool does ([`Cli`]) without running them.
//!
//! Every subcommand is glue over the `stickslip` library.

use clap::Parser;
use std::process::ExitCode;

mod checkpoint;
mod choice;
mod commands;
mod diagrams;
mod flags;
#[cfg(test)]
mod legend_check;
mod measured;
pub mod model;
pub mod output;

/// The columns of the CSV files of `stickslip reproduce` that no library table holds, for
/// the tests that read the report.
pub use commands::reproduce::columns as reproduce_columns;
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
pub struct Cli {
    #[command(subcommand)]
    command: commands::Command,
}

/// The model flags alone (`--zeta --w --beta ...`, `--preset`, `--config`, the physical
/// flags), as every command that solves takes them: for parsing tests and fuzz targets.
#[derive(Debug, Parser)]
#[command(name = "stickslip")]
pub struct ModelFlags {
    /// The flags.
    #[command(flatten)]
    pub model: model::ModelArgs,
}

/// Run the tool on the process's arguments: parse, run the command, report errors in one
/// line, and return the exit status (0; 1 for a failure of the computation; 2 for bad
/// input; 3 for a fit that did not converge, [`output::NOT_CONVERGED`]).
pub fn main() -> ExitCode {
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
        // The reader of standard output has gone (`stickslip simulate | head`): stop without
        // a word, as a writer killed by SIGPIPE does. (Unfinished output files were removed
        // on the way here.)
        Err(err) if output::is_broken_pipe(&err) => broken_pipe(),
        // The command said why on standard error and wrote its output.
        Err(err) if err.downcast_ref::<output::ExitStatus>().is_some() => {
            ExitCode::from(err.downcast_ref::<output::ExitStatus>().map_or(1, |s| s.0))
        }
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

/// End as command-line tools end when their reader goes away: killed by SIGPIPE (status
/// 141 in a shell), which Rust programs ignore by default; 141 as an exit code where the
/// signal cannot be raised.
fn broken_pipe() -> ExitCode {
    #[cfg(unix)]
    {
        let _ = signal_hook::low_level::emulate_default_handler(signal_hook::consts::SIGPIPE);
    }
    ExitCode::from(141)
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
                    | Error::InvalidOption { .. }
                    | Error::OptionProduct { .. }
                    | Error::InvalidText { .. }
                    | Error::ImageOutOfRange { .. }
                    | Error::HorizonTooLong { .. }
                    | Error::Spec(_)
                    | Error::Config(_)
                    | Error::Unsupported(_)
            )
        });
    // An option or a key names its flag (`invalid --max-period 65: must be from 1 to 64`,
    // `invalid --freq 1e9: it gives w = …`), in the library's words.
    if let Some(
        e @ (Error::InvalidOption { .. }
        | Error::OptionProduct { .. }
        | Error::Spec(_)
        | Error::ImageOutOfRange { .. }),
    ) = library
    {
        return (e.render(stickslip::Spelling::Flag), true);
    }
    // The chain of causes joined.
    let message = err
        .chain()
        .map(|c| c.to_string())
        .collect::<Vec<_>>()
        .join(": ");
    (message, usage)
}
