//! `stickslip lab`: the flags of the lab's server; the server is the `stickslip-lab` crate.

use crate::output::UsageError;
use anyhow::Result;
use stickslip::OptionKey;

/// Serve the lab: an oscilloscope and a function generator in the browser, on the exact solver.
///
/// A two-channel scope and a function generator on the RLC-diode circuit (or its mechanical
/// twin), computed by the library on request. The page opens on the paper's circuit at its Fig. 3 point Ω/ω0 = 0.95, β = 2.14:
/// generator (frequency, amplitude, phase), circuit (L, C, R, PWL or Shockley diodes,
/// presets) or mass-spring-friction view, scope (Y-T, X-Y, FFT; steady cycle or transient
/// from rest; cursors), measurements beside the paper's series values and the exact orbit's,
/// the gain swept up and down, the (w, β) map, CSV and PNG export.
///
/// The server listens on 127.0.0.1 (this computer only) unless --host says otherwise, and
/// prints the address to open (with --host 0.0.0.0, also the addresses students type). It
/// reads no files; each request is capped in size and time, computations take fair turns
/// between clients, and requests must name the lab by one of its addresses (the Host
/// header), so that other web pages cannot read its answers.
/// The JSON API under /api/ takes the model flags without dashes as query keys
/// (e.g. /api/steady?preset=paper&freq=9.97k&amplitude=1.498): see docs/lab.md.
///
/// Examples:
///   stickslip lab --open
///   stickslip lab --port 0            # any free port
///   stickslip lab --host 0.0.0.0      # the whole classroom network (a warning says so)
///   stickslip lab --host 0.0.0.0 --allow-host lab.school.example
#[derive(Debug, clap::Args)]
#[command(verbatim_doc_comment)]
pub struct Args {
    /// TCP port to listen on (0: any free port; the address printed says which).
    #[arg(long, default_value_t = 8080)]
    port: u16,
    /// Address to listen on: 127.0.0.1 serves this computer only; 0.0.0.0 every network
    /// the computer is on.
    #[arg(long, default_value = "127.0.0.1")]
    host: String,
    /// Open the page in the default browser.
    #[arg(long)]
    open: bool,
    #[arg(long = OptionKey::LabTimeLimit.flag(), help = crate::flags::help(OptionKey::LabTimeLimit), default_value_t = crate::flags::num(OptionKey::LabTimeLimit), value_parser = crate::model::finite, allow_hyphen_values = true)]
    time_limit: f64,
    #[arg(long, help = crate::flags::help(OptionKey::LabJobs), allow_hyphen_values = true)]
    jobs: Option<i64>,
    /// Print one line per request on standard error (method, path, status, milliseconds),
    /// and one per request or connection that ended early.
    #[arg(long)]
    verbose: bool,
    /// Also answer requests that name the lab by this host name (e.g. a name the school's
    /// DNS gives this computer); the addresses it listens on and localhost are always
    /// answered. Repeat for more names.
    #[arg(long, value_name = "NAME")]
    allow_host: Vec<String>,
}

/// Run `stickslip lab` until Ctrl-C.
pub fn run(args: Args) -> Result<()> {
    let config = stickslip_lab::Config {
        port: args.port,
        host: args.host,
        open: args.open,
        time_limit: args.time_limit,
        jobs: args.jobs,
        verbose: args.verbose,
        allow_host: args.allow_host,
    };
    stickslip_lab::run(config, crate::output::interrupted).map_err(|err| {
        match err.downcast::<stickslip_lab::InvalidSetting>() {
            Ok(invalid) => anyhow::Error::new(UsageError(invalid.0)),
            Err(other) => other,
        }
    })
}
