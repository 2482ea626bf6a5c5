//! `stickslip netlist`: the circuit as a SPICE netlist with Shockley diodes.

use crate::flags::{help, int, num};
use crate::model::ModelArgs;
use crate::output::Sink;
use anyhow::Result;
use std::io::Write;
use std::path::PathBuf;
use stickslip::experiment::DiodeModel;
use stickslip::shockley::{netlist, NetlistOptions};
use stickslip::OptionKey;
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
    #[arg(long, help = help(OptionKey::NetlistPeriods), default_value_t = num(OptionKey::NetlistPeriods), value_parser = crate::model::finite, allow_hyphen_values = true)]
    periods: f64,
    #[arg(long = OptionKey::NetlistPoints.flag(), help = help(OptionKey::NetlistPoints), default_value_t = int(OptionKey::NetlistPoints) as _)]
    points_per_period: u32,
    #[arg(long = OptionKey::NetlistMaxStep.flag(), help = help(OptionKey::NetlistMaxStep), default_value_t = num(OptionKey::NetlistMaxStep), value_parser = crate::model::finite, allow_hyphen_values = true)]
    max_step: f64,
    #[arg(long, help = help(OptionKey::NetlistReltol), value_parser = crate::model::finite, allow_hyphen_values = true)]
    reltol: Option<f64>,
    #[arg(long, help = help(OptionKey::NetlistAbstol), value_parser = crate::model::finite, allow_hyphen_values = true)]
    abstol: Option<f64>,
    #[arg(long, help = help(OptionKey::NetlistVntol), value_parser = crate::model::finite, allow_hyphen_values = true)]
    vntol: Option<f64>,
    #[arg(long, help = help(OptionKey::NetlistWrdata), value_name = "FILE")]
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
    let text = netlist(circuit, &params, experiment.initial(), &options)?;
    eprintln!("netlist: {experiment}");
    let mut sink = Sink::open(args.out.as_deref())?;
    sink.write_all(text.as_bytes())?;
    sink.finish()?;
    Ok(())
}
