//! `stickslip netlist`: the circuit as a SPICE netlist with Shockley diodes.

use crate::model::ModelArgs;
use crate::output::{usage, Sink};
use anyhow::Result;
use std::io::Write;
use std::path::PathBuf;
use stickslip::experiment::DiodeModel;
use stickslip::shockley::{netlist, NetlistOptions};
use stickslip::{Error, Unsupported};

/// Write the circuit as a SPICE netlist, to cross-check a simulation in ngspice or any SPICE:
/// source U cos(Ω t + φ) (as SIN with phase φ + 90°), R, L, two anti-parallel diodes sharing
/// one .model (IS, N, RS from --diode-is/--diode-n/--diode-rs), and C, with the initial
/// u_C and i as IC= values and `.tran ... uic`. The diodes always follow the Shockley law
/// (SPICE has no PWL diode); the PWL R_D is not used.
///
/// Example: stickslip netlist --preset paper --w 0.95 --beta 2.14 --periods 300 -o paper.cir
///          ngspice -b paper.cir
#[derive(Debug, clap::Args)]
#[command(verbatim_doc_comment)]
pub struct Args {
    #[command(flatten)]
    model: ModelArgs,
    /// Simulated time in drive periods (> 0).
    #[arg(long, default_value_t = 300.0, value_parser = crate::model::finite, allow_hyphen_values = true)]
    periods: f64,
    /// Output points per drive period (the .tran print step), ≥ 1.
    #[arg(long = "points-per-period", default_value_t = 200)]
    points_per_period: u32,
    /// Largest SPICE time step as a fraction of the drive period, in (0, 1].
    #[arg(long = "max-step", default_value_t = 1e-3, value_parser = crate::model::finite, allow_hyphen_values = true)]
    max_step: f64,
    /// SPICE relative tolerance (.options reltol) [default: SPICE's, 1e-3].
    #[arg(long, value_parser = crate::model::finite, allow_hyphen_values = true)]
    reltol: Option<f64>,
    /// SPICE absolute current tolerance in A (.options abstol) [default: SPICE's, 1e-12].
    #[arg(long, value_parser = crate::model::finite, allow_hyphen_values = true)]
    abstol: Option<f64>,
    /// SPICE absolute voltage tolerance in V (.options vntol) [default: SPICE's, 1e-6].
    #[arg(long, value_parser = crate::model::finite, allow_hyphen_values = true)]
    vntol: Option<f64>,
    /// Add an ngspice .control block that runs the analysis and writes time, u_C and i to
    /// this file with wrdata (a name without spaces; relative to where ngspice runs).
    #[arg(long, value_name = "FILE")]
    wrdata: Option<String>,
    /// Netlist file [default: standard output].
    #[arg(long, short)]
    out: Option<PathBuf>,
}

/// Run `stickslip netlist`.
pub fn run(args: Args) -> Result<()> {
    Sink::check(args.out.as_deref())?;
    // SPICE has no PWL diode: the netlist's diodes follow the Shockley law.
    let mut spec = args.model.spec()?;
    spec.set_diode(DiodeModel::Shockley);
    let experiment = spec.build()?;
    let Some(circuit) = experiment.circuit_ref() else {
        return Err(Error::Unsupported(Unsupported::ShockleyNeedsCircuit).into());
    };
    let params = experiment.params()?;
    let options = NetlistOptions {
        periods: args.periods,
        points_per_period: args.points_per_period,
        max_step_fraction: args.max_step,
        reltol: args.reltol,
        abstol: args.abstol,
        vntol: args.vntol,
        wrdata: args.wrdata.clone(),
    };
    let text = match netlist(circuit, &params, experiment.initial(), &options) {
        Ok(text) => text,
        Err(Error::InvalidParameter {
            name,
            value,
            allowed,
        }) => {
            let flag = match name {
                "periods" => "--periods".to_string(),
                "points_per_period" => "--points-per-period".to_string(),
                "max_step_fraction" => "--max-step".to_string(),
                "wrdata" => {
                    usage!("invalid --wrdata: {allowed}")
                }
                other => format!("--{other}"),
            };
            usage!("invalid {flag} {value}: {allowed}");
        }
        Err(e) => return Err(e.into()),
    };
    eprintln!("netlist: {experiment}");
    let mut sink = Sink::open(args.out.as_deref())?;
    sink.write_all(text.as_bytes())?;
    sink.finish()?;
    Ok(())
}
