//! `stickslip fit`: fit the circuit's (or the mechanical oscillator's) parameters to scope
//! records or a table of measured amplitudes.

use crate::model::ModelArgs;
use crate::output::{check_output_path, check_plot_path, outln, usage, AtomicFile};
use anyhow::{Context, Result};
use serde_json::Value;
use std::io::Write;
use std::path::{Path, PathBuf};
use stickslip::fit::{
    check_undriven, compare_models_monitored, fit_per_record_monitored, fit_records_monitored,
    fit_table_monitored, fit_undriven_monitored, FitError, FitMonitor, FitOptions, FitParameter,
    FitProgress, FitReport, Interval, RecordFit, UndrivenRecord,
};
use stickslip::measure::{
    read_amplitudes, read_scope, AmplitudeTable, MeasureError, Measurement, Record,
};
use stickslip::shockley::DiodePair;
use stickslip::{DiodeModel, SystemKind};

/// Fit the circuit's parameters to measurements: scope records of the drive and u_C, or a
/// table of measured amplitudes.
///
/// Records (--data, repeatable; a Tektronix export, one file per channel, is given as
/// FILE1+FILE2): Rigol, Tektronix, Keysight InfiniiVision and Siglent CSV exports are
/// detected from their header; a plain CSV needs a header row with a time column (t, time,
/// time_s, second). The first channel is the drive and the second u_C unless --drive and
/// --response name them (by name, CHn or position). Each record's drive (frequency,
/// amplitude, phase) is fitted as a sine over its whole periods; the model's steady u_C is
/// fitted to every record at once, with a DC offset of u_C and a time shift per record.
///
/// A table (--gain-table): columns freq_Hz, U_V, response_V (half the peak-to-peak of u_C),
/// optionally direction (up/down: the row settles from the row before on its sweep), A1_V,
/// A3_V. Unknown columns are refused.
///
/// The model flags give the starting values (and the diode law with --model). Free
/// parameters (--free): resistance, ut, rd (PWL), diode-is, diode-n, diode-rs (Shockley),
/// inductance, capacitance, mu-s.
///
/// --plot draws the records (measured u_C, the fitted model over two drive periods and the
/// residual below) or the table (measured amplitudes on the fitted resonance curves, with
/// the exact theory and the paper's).
///
/// A mechanical oscillator (--mass, --stiffness, --damping, --friction) is fitted to records
/// of the drive force and the displacement, whose header says their units in N and m (a
/// plain CSV: time_s,F (N),r (m)). Free parameters: damping, friction, mass, stiffness, mu-s
/// (default damping,friction), and with --friction-law stribeck its stribeck-speed and
/// viscous-friction (the belt speed, --belt-speed in m/s, is given; the law's values not
/// freed are held in their physical units). On a belt or with the Stribeck law the Jacobian
/// is by central differences of the solver. The keys and columns named in V then hold N (the
/// drive) and m (the displacement), and the JSON says so: units {drive: N, response: m}.
/// Tables and --compare are for circuits.
///
/// An undriven belt (no drive force: the block's self-excited stick-slip or pure-slip cycle
/// on a belt at --belt-speed) is fitted to records of its displacement alone (a plain CSV
/// time_s,r (m), or beside a constant force channel): the model is the settled self-excited
/// cycle, its period found at the parameters' values, aligned to each record by the time of
/// a section fitted with the rest (and an offset of r). Each record must hold at least one
/// whole cycle. With the offset free the kinetic level F0 only shifts r: give F0 and fit
/// mu-s, stribeck-speed, viscous-friction, damping. A record that starts as the belt starts
/// under the block at rest is fitted with --from-rest [M] (the block at rest on the ground, M
/// metres from the spring's rest length, 0 by default, at each record's first sample): the
/// model is the motion from there, and F0 is seen apart from mu-s. A record taken at a belt
/// speed of its own is given as FILE@SPEED (m/s; the others at --belt-speed): one fit over
/// several belt speeds.
///
/// What to trust. A fit is converged when the step and gradient criteria hold at its solution
/// and a restart from elsewhere finds no lower χ². The 95 % intervals are value ± t·stderr
/// (I_s in its logarithm) where the model is linear enough over them, else the profile
/// likelihood's ("profile" in the report). A Shockley fit starts in the valley of I_s and n
/// where the PWL law's equivalent says the diodes work. Parameters the records cannot
/// separate (R and R_s, R and R_D: only their sum; L, C and R with PWL diodes: only ω0 and ζ)
/// are named in a warning and the last named is held at its start; correlations beyond
/// ±0.99, values at the edge of their range (R_s = 0) and clipped samples are warned of.
/// Warnings go to standard error, one line each, and into the JSON report.
///
/// Exit status: 0 when every fit converged; 3 when one did not (the report and the files
/// are written, and a warning says why); 2 for bad input (a file, a flag, a record whose
/// channels are not what they should be); 1 when the model cannot be computed.
///
/// JSON keys: model, parameters {name: {value, stderr, ci95: [lo, hi], interval (linear,
/// profile, held or none)}}, correlation, records [{file, freq_Hz, amplitude_V, w, beta,
/// class, periods, clipped, rms_residual_V, offset_V, time_shift_s}], rows (a table) [{line,
/// freq_Hz, U_V, direction, measured_V, model_V, class}], rms_residual_V, chi2_dof,
/// converged, iterations, jacobian (exact, sensitivities, central-differences or
/// finite-differences: how the Jacobian at the solution was computed), aic, bic, warnings [{kind, parameters, message}]; with
/// --per-record a list of such objects; with --compare {pwl, shockley, preferred,
/// delta_aic}.
///
/// Example: stickslip fit --preset paper --data run1.csv --data run2.csv --free resistance,ut
/// --json --plot fit.png
#[derive(Debug, clap::Args)]
#[command(verbatim_doc_comment)]
pub struct Args {
    #[command(flatten)]
    model: ModelArgs,
    /// A scope record (CSV); repeat for several records; FILE1+FILE2 merges single-channel
    /// files on the same times.
    #[arg(long, value_name = "FILE", help_heading = "Measurements")]
    data: Vec<String>,
    /// A table of measured amplitudes (CSV).
    #[arg(
        long,
        value_name = "FILE",
        help_heading = "Measurements",
        conflicts_with = "data"
    )]
    gain_table: Option<PathBuf>,
    /// The drive channel of each record (name, CHn or position) [default: the first].
    #[arg(long, value_name = "COL", help_heading = "Measurements")]
    drive: Option<String>,
    /// The u_C channel of each record [default: the second].
    #[arg(long, value_name = "COL", help_heading = "Measurements")]
    response: Option<String>,
    #[arg(long, value_name = "KEYS", help_heading = "Fit", help = free_help())]
    free: Option<String>,
    /// Undriven records from rest: the block at rest on the ground, M (m) from the spring's
    /// rest length, when the belt starts at each record's first sample [default M: 0].
    #[arg(
        long,
        value_name = "M",
        help_heading = "Measurements",
        num_args = 0..=1,
        default_missing_value = "0",
        allow_negative_numbers = true
    )]
    from_rest: Option<f64>,
    /// Fit each record alone (how a parameter drifts with the drive).
    #[arg(long, help_heading = "Fit", conflicts_with = "compare")]
    per_record: bool,
    /// Fit PWL diodes (free --free) and 1N4148-like Shockley diodes (free --free-shockley)
    /// and compare them by AIC.
    #[arg(long, help_heading = "Fit")]
    compare: bool,
    #[arg(long, value_name = "KEYS", help_heading = "Fit", help = free_shockley_help())]
    free_shockley: Option<String>,
    /// Print JSON instead of text.
    #[arg(long)]
    json: bool,
    /// Residuals as CSV: model,file,t_s,measured_V,model_V,residual_V (records; a mechanical
    /// oscillator's in m: measured_m, model_m, residual_m) or
    /// line,freq_Hz,U_V,measured_V,model_V,residual_V (a table).
    #[arg(long, value_name = "FILE")]
    out: Option<PathBuf>,
    /// Plot (.png or .svg). Records: per record the measured u_C and the fitted model over
    /// its first two drive periods, the residual below. A table: per drive amplitude the
    /// measured amplitudes on the fitted model's resonance curves (along the table's legs),
    /// with the exact sliding orbit and the paper's eq. (11) at the fitted values.
    #[arg(long, value_name = "FILE")]
    plot: Option<PathBuf>,
}

/// The default free set of a system and law, as `--free` takes it: the library's
/// ([`FitParameter::defaults`]).
fn default_free(system: SystemKind, law: DiodeModel) -> String {
    FitParameter::list(&FitParameter::defaults(system, law))
}

/// The help of `--free`, its defaults the library's.
fn free_help() -> String {
    format!(
        "Free parameters, comma-separated [default: {} with PWL diodes, {} with Shockley \
         diodes; a mechanical oscillator: {}]",
        default_free(SystemKind::Circuit, DiodeModel::Pwl),
        default_free(SystemKind::Circuit, DiodeModel::Shockley),
        default_free(SystemKind::Mechanics, DiodeModel::Pwl)
    )
}

/// The help of `--free-shockley`, its default the library's.
fn free_shockley_help() -> String {
    format!(
        "Free parameters of the Shockley fit of --compare [default: {}]",
        default_free(SystemKind::Circuit, DiodeModel::Shockley)
    )
}

fn parse_free(text: &str, flag: &str) -> Result<Vec<FitParameter>> {
    let mut free = Vec::new();
    for name in text.split(',').map(str::trim).filter(|s| !s.is_empty()) {
        match name.parse::<FitParameter>() {
            Ok(p) => free.push(p),
            Err(e) => usage!("invalid {flag} {name}: {e}"),
        }
    }
    if free.is_empty() {
        usage!("{flag} names no parameter");
    }
    Ok(free)
}

/// A library refusal of the user's input (a file, a flag) as a usage error (exit 2).
fn refused(err: FitError) -> anyhow::Error {
    match err {
        FitError::Model { .. } => anyhow::Error::new(err),
        FitError::Stopped(e) => anyhow::Error::new(e),
        _ => anyhow::Error::new(crate::output::UsageError(err.to_string())),
    }
}

fn measure(err: MeasureError) -> anyhow::Error {
    let message = match &err.swap {
        Some((drive, response)) => format!("{err}: give --drive {drive} --response {response}"),
        None => err.to_string(),
    };
    anyhow::Error::new(crate::output::UsageError(message))
}

fn read_text(path: &Path) -> Result<String> {
    match std::fs::read(path) {
        Ok(bytes) => {
            stickslip::measure::decode(&bytes, &path.display().to_string()).map_err(measure)
        }
        Err(e) => usage!("{}: {e}", path.display()),
    }
}

/// Read the record of `spec`: one file, or single-channel files joined by `+` (merged on
/// their common times).
/// A `--data` spec and its belt speed: `FILE@SPEED` (m/s) where what follows the last `@`
/// is a number, else the spec as it is.
fn belt_of(spec: &str) -> (&str, Option<f64>) {
    match spec.rsplit_once('@') {
        Some((file, speed)) => match speed.parse::<f64>() {
            Ok(v) => (file, Some(v)),
            Err(_) => (spec, None),
        },
        None => (spec, None),
    }
}

pub(crate) fn read_record(spec: &str) -> Result<Record> {
    let parts = spec
        .split('+')
        .map(|file| {
            let text = read_text(Path::new(file))?;
            read_scope(&text, file).map_err(measure)
        })
        .collect::<Result<Vec<_>>>()?;
    Record::merge(parts).map_err(measure)
}

/// The channels of the record that `simulate --data` and `steady --data` draw (the
/// command's own `--data` flag names the record).
#[derive(Debug, clap::Args)]
pub(crate) struct RecordChannels {
    /// The record's drive channel (name, CHn or position) [default: the first].
    #[arg(long, value_name = "COL", help_heading = "Measurements")]
    drive: Option<String>,
    /// The record's u_C channel [default: the second].
    #[arg(long, value_name = "COL", help_heading = "Measurements")]
    response: Option<String>,
}

/// The scope record that `simulate --data` and `steady --data` draw beside the computed
/// trace (`spec` as `fit --data`, channels picked as `fit --drive/--response`), or none
/// without `--data`. The record is in volts and seconds: the experiment must be a circuit,
/// and the record is drawn in the plot, which must be asked for. A channel picked without
/// a record is refused, naming `--data`.
pub(crate) fn record_to_draw(
    spec: Option<&str>,
    channels: &RecordChannels,
    experiment: &stickslip::Experiment,
    plot: Option<&Path>,
) -> Result<Option<Measurement>> {
    let Some(spec) = spec else {
        for (flag, picked) in [("drive", &channels.drive), ("response", &channels.response)] {
            if let Some(column) = picked {
                usage!(
                    "--{flag} {column} picks a channel of a scope record: give the record \
                     with --data FILE (CSV, as `fit --data`)"
                );
            }
        }
        return Ok(None);
    };
    if plot.is_none() {
        usage!("--data {spec} is drawn in the plot: add --plot FILE (.png or .svg)");
    }
    match experiment.units() {
        Some(u) if u.circuit => {}
        Some(_) => usage!(
            "--data {spec}: a scope record is in volts and seconds, and this model is a \
             mechanical oscillator: describe a circuit (--preset paper or its parts)"
        ),
        None => usage!(
            "--data {spec}: a scope record is in volts and seconds, and this model is \
             dimensionless: describe a circuit (--preset paper or its parts)"
        ),
    }
    let record = read_record(spec)?;
    Measurement::new(
        &record,
        channels.drive.as_deref(),
        channels.response.as_deref(),
    )
    .map(Some)
    .map_err(measure)
}

/// The progress line on a terminal: iterations done of the most allowed, and the sum of
/// squares reached.
struct Line(indicatif::ProgressBar);

impl FitMonitor for Line {
    fn iteration(&self, p: &FitProgress) -> std::ops::ControlFlow<()> {
        self.0.set_length(p.total as u64);
        self.0.set_position(p.iteration as u64);
        self.0.set_message(format!("fit {:.3e}", p.sum_squares));
        if crate::output::interrupted() {
            std::ops::ControlFlow::Break(())
        } else {
            std::ops::ControlFlow::Continue(())
        }
    }
}

/// Run `stickslip fit`.
pub fn run(args: Args) -> Result<()> {
    let line = Line(crate::output::progress(0, "fit"));
    let result = run_with(args, &line);
    line.0.finish_and_clear();
    result
}

fn run_with(args: Args, line: &Line) -> Result<()> {
    if args.data.is_empty() && args.gain_table.is_none() {
        usage!("give the measurements: --data FILE (repeatable) or --gain-table FILE");
    }
    if let Some(p) = &args.out {
        check_output_path(p)?;
    }
    if let Some(p) = &args.plot {
        check_plot_path(p)?;
    }
    let experiment = args.model.experiment()?;
    let mechanics = matches!(
        experiment.system(),
        Some(stickslip::physical::System::Mechanics(_))
    );
    // The library's default free set of the system and diode law.
    let free = match &args.free {
        Some(text) => parse_free(text, "--free")?,
        None => FitParameter::defaults_of(&experiment).map_err(refused)?,
    };
    // A parameter of the other twin or diode law is refused before any file is read.
    for p in &free {
        p.get(&experiment).map_err(refused)?;
    }
    if mechanics && args.compare {
        usage!("--compare compares diode laws: it takes a circuit, not a mechanical oscillator");
    }
    if mechanics && args.plot.is_some() {
        usage!("--plot draws a circuit's records in volts: it takes a circuit, not a mechanical oscillator (use --out for the residuals)");
    }
    let options = FitOptions::default();
    let mut report_json: Value;
    let mut residual_reports: Vec<FitReport> = Vec::new();
    let mut fitted_table = None;
    if let Some(path) = &args.gain_table {
        if args.per_record || args.compare {
            usage!("--per-record and --compare take records (--data), not a table");
        }
        let name = path.display().to_string();
        let table = read_amplitudes(&read_text(path)?, &name).map_err(measure)?;
        eprintln!("fit: {} rows of {name}; {experiment}", table.rows.len());
        let report =
            fit_table_monitored(&experiment, &table, &free, &options, line).map_err(refused)?;
        report_json = to_json(&report)?;
        residual_reports.push(report);
        fitted_table = Some(table);
    } else {
        let mut data = Vec::new();
        let mut undriven = Vec::new();
        for spec in &args.data {
            let (spec, belt_speed) = belt_of(spec);
            let record = read_record(spec)?;
            // A mechanical record without a drive: the displacement of an undriven belt.
            if mechanics && args.drive.is_none() && UndrivenRecord::is_undriven(&record) {
                let mut u =
                    UndrivenRecord::new(&record, args.response.as_deref()).map_err(measure)?;
                if let Some(position) = args.from_rest {
                    u = u.from_rest(position).map_err(measure)?;
                }
                if let Some(v) = belt_speed {
                    u = u.on_belt(v).map_err(measure)?;
                }
                undriven.push(u);
                continue;
            }
            if belt_speed.is_some() {
                usage!(
                    "{spec}: a belt speed of its own (FILE@SPEED) is for a record of an \
                     undriven belt (a displacement without a drive)"
                );
            }
            data.push(
                Measurement::new(&record, args.drive.as_deref(), args.response.as_deref())
                    .map_err(measure)?,
            );
        }
        if let (Some(u), Some(d)) = (undriven.first(), data.first()) {
            usage!(
                "{} has no drive and {} has one: undriven and driven records are fitted apart",
                u.file,
                d.file
            );
        }
        if args.from_rest.is_some() && undriven.is_empty() {
            usage!(
                "--from-rest is for records of an undriven belt (a displacement without a drive)"
            );
        }
        if !undriven.is_empty() {
            if args.compare {
                usage!("--compare compares diode laws: it takes a circuit's records");
            }
            // Refused in one line, before the fit is announced.
            for u in if args.per_record {
                undriven.chunks(1).collect::<Vec<_>>()
            } else {
                vec![&undriven[..]]
            } {
                check_undriven(&experiment, u, &free, &options).map_err(refused)?;
            }
            eprintln!("fit: {} undriven records; {experiment}", undriven.len());
            let reports = if args.per_record {
                undriven
                    .iter()
                    .map(|u| {
                        fit_undriven_monitored(
                            &experiment,
                            std::slice::from_ref(u),
                            &free,
                            &options,
                            line,
                        )
                    })
                    .collect::<Result<Vec<_>, _>>()
            } else {
                fit_undriven_monitored(&experiment, &undriven, &free, &options, line)
                    .map(|r| vec![r])
            }
            .map_err(refused)?;
            report_json = if args.per_record {
                Value::Array(reports.iter().map(to_json).collect::<Result<_>>()?)
            } else {
                to_json(&reports[0])?
            };
            residual_reports = reports;
        } else {
            eprintln!("fit: {} records; {experiment}", data.len());
            if args.compare {
                let shockley_free = match &args.free_shockley {
                    Some(text) => parse_free(text, "--free-shockley")?,
                    None => FitParameter::defaults(SystemKind::Circuit, DiodeModel::Shockley),
                };
                let c = compare_models_monitored(
                    &experiment,
                    DiodePair::one_n4148(),
                    &data,
                    &free,
                    &shockley_free,
                    &options,
                    line,
                )
                .map_err(refused)?;
                report_json = serde_json::to_value(c.to_json())?;
                residual_reports.push(c.pwl);
                residual_reports.push(c.shockley);
            } else if args.per_record {
                let reports = fit_per_record_monitored(&experiment, &data, &free, &options, line)
                    .map_err(refused)?;
                report_json = Value::Array(reports.iter().map(to_json).collect::<Result<_>>()?);
                residual_reports = reports;
            } else {
                let report = fit_records_monitored(&experiment, &data, &free, &options, line)
                    .map_err(refused)?;
                report_json = to_json(&report)?;
                residual_reports.push(report);
            }
        }
    }
    crate::output::check_interrupt()?;
    if args.json {
        crate::output::print(&format!(
            "{}\n",
            serde_json::to_string_pretty(&report_json)?
        ))?;
    } else {
        let mut text = String::new();
        for r in &residual_reports {
            describe(&mut text, r, args.from_rest);
        }
        if let Some(obj) = report_json.as_object_mut() {
            if let (Some(p), Some(d)) = (obj.get("preferred"), obj.get("delta_aic")) {
                // AIC differences below a few tenths mean nothing: one decimal (the JSON
                // keeps every digit).
                let d = d
                    .as_f64()
                    .map_or_else(|| d.to_string(), |d| format!("{d:+.1}"));
                outln!(
                    text,
                    "preferred         {} (AIC Shockley − PWL = {d})",
                    p.as_str().unwrap_or("")
                );
            }
        }
        crate::output::print(&text)?;
    }
    if let Some(path) = &args.out {
        let mut file = AtomicFile::create(path)?;
        write_residuals(&mut file, &residual_reports)
            .with_context(|| format!("writing {}", path.display()))?;
        file.commit()?;
    }
    if let Some(path) = &args.plot {
        plot(
            path,
            &residual_reports,
            fitted_table.as_ref(),
            args.per_record,
        )?;
    }
    // Each report's warnings, one line each; a fit that did not converge ends the run with
    // its own exit status (the report and the files are written).
    for r in &residual_reports {
        let whose = if args.compare {
            format!("{} fit: ", r.model.label())
        } else if args.per_record {
            r.records
                .first()
                .map_or(String::new(), |rec| format!("{}: ", rec.file))
        } else {
            String::new()
        };
        for w in &r.warnings {
            line.0.suspend(|| eprintln!("warning: {whose}{w}"));
        }
    }
    if residual_reports.iter().any(|r| !r.converged) {
        return Err(anyhow::Error::new(crate::output::ExitStatus(
            crate::output::NOT_CONVERGED,
        )));
    }
    Ok(())
}

/// Draw the fit into `path`: the records of `reports` (one report, the two of `--compare`,
/// or one per record with `per_record`), or the fitted `table`.
fn plot(
    path: &Path,
    reports: &[FitReport],
    table: Option<&AmplitudeTable>,
    per_record: bool,
) -> Result<()> {
    if let (Some(table), Some(report)) = (table, reports.first()) {
        eprintln!(
            "fit: drawing the fitted resonance curves ({} points each)",
            crate::measured::CURVE_POINTS
        );
        let figure = crate::measured::table_figure(report, table);
        crate::output::check_interrupt()?;
        return figure.render(path);
    }
    let groups: Vec<Vec<(&FitReport, &RecordFit)>> = if per_record {
        reports
            .iter()
            .flat_map(|r| r.records.iter().map(move |rec| vec![(r, rec)]))
            .collect()
    } else {
        let n = reports.first().map_or(0, |r| r.records.len());
        (0..n)
            .map(|k| reports.iter().map(|r| (r, &r.records[k])).collect())
            .collect()
    };
    crate::measured::records_stack(&groups).render(path)
}

fn write_residuals(file: &mut impl Write, reports: &[FitReport]) -> Result<()> {
    let table = reports.iter().all(|r| r.records.is_empty());
    if table {
        writeln!(file, "line,freq_Hz,U_V,measured_V,model_V,residual_V")?;
    } else {
        let u = reports.first().map_or("V", |r| r.units().1);
        writeln!(file, "model,file,t_s,measured_{u},model_{u},residual_{u}")?;
    }
    for r in reports {
        for row in &r.rows {
            writeln!(
                file,
                "{},{},{},{},{},{}",
                row.line,
                row.freq_hz,
                row.drive_v,
                row.measured_v,
                row.model_v,
                row.model_v - row.measured_v
            )?;
        }
        for rec in &r.records {
            for k in 0..rec.time.len() {
                writeln!(
                    file,
                    "{},{},{},{},{},{}",
                    r.model.label(),
                    rec.file,
                    rec.time[k],
                    rec.model[k] - rec.residuals[k],
                    rec.model[k],
                    rec.residuals[k]
                )?;
            }
        }
    }
    Ok(())
}

/// The report `r` as text; `from_rest`: its undriven records are from rest at that position
/// (m).
fn describe(text: &mut String, r: &FitReport, from_rest: Option<f64>) {
    outln!(text, "model             {}", r.model.label());
    for p in &r.parameters {
        let name = p.parameter.label();
        let unit = p.parameter.unit();
        match p.interval {
            Interval::Held => outln!(
                text,
                "{name:<17} {:.6e} {unit} held at its start (not identified: see the warning)",
                p.value
            ),
            _ if !(p.stderr.is_finite() && p.ci95.iter().all(|v| v.is_finite())) => outln!(
                text,
                "{name:<17} {:.6e} {unit} (no error bar: see the warning; start {:.6e})",
                p.value,
                p.initial
            ),
            interval => outln!(
                text,
                "{name:<17} {:.6e} ± {:.2e} {unit} (95 %{}: {:.6e} … {:.6e}; start {:.6e})",
                p.value,
                p.stderr,
                if interval == Interval::Profile {
                    ", profile"
                } else {
                    ""
                },
                p.ci95[0],
                p.ci95[1],
                p.initial
            ),
        }
    }
    let (du, ru) = r.units();
    for rec in &r.records {
        // An undriven record from rest: its start, and the motion it settles on.
        if let (Some(position), 0.0, 0.0) = (from_rest, rec.beta, rec.amplitude_v) {
            outln!(
                text,
                "record {}: from rest at r = {position:.6e} m (the belt started at its first \
                 sample, offset {:.6e} m), settling on {} of {:.6} Hz (w = {:.5}), {} clipped, \
                 RMS residual {:.3e} {ru} (noise {:.3e} {ru})",
                rec.file,
                rec.offset_v,
                rec.class.label(),
                rec.freq_hz,
                rec.w,
                rec.clipped,
                rec.rms_residual_v,
                rec.noise_v
            );
            continue;
        }
        // An undriven record: its self-excited cycle's frequency and section time.
        if rec.beta == 0.0 && rec.amplitude_v == 0.0 {
            outln!(
                text,
                "record {}: self-excited cycle of {:.6} Hz (w = {:.5}), {}, section at \
                 t = {:.6e} s, {} cycles, {} clipped, RMS residual {:.3e} {ru} (noise {:.3e} {ru})",
                rec.file,
                rec.freq_hz,
                rec.w,
                rec.class.label(),
                rec.time_shift_s,
                rec.periods,
                rec.clipped,
                rec.rms_residual_v,
                rec.noise_v
            );
            continue;
        }
        outln!(
            text,
            "record {}: {:.6} Hz, {:.6} {du} (w = {:.5}, β = {:.5}), {}, {} periods, {} clipped, \
             RMS residual {:.3e} {ru} (noise {:.3e} {ru})",
            rec.file,
            rec.freq_hz,
            rec.amplitude_v,
            rec.w,
            rec.beta,
            rec.class.label(),
            rec.periods,
            rec.clipped,
            rec.rms_residual_v,
            rec.noise_v
        );
    }
    let unit = if r.records.is_empty() { "V" } else { ru };
    outln!(text, "RMS residual      {:.6e} {unit}", r.rms_residual_v);
    if let Some(c) = r.chi2_dof {
        outln!(text, "chi2/dof          {c:.4}");
    }
    outln!(text, "AIC, BIC          {:.3}, {:.3}", r.aic, r.bic);
    outln!(
        text,
        "iterations        {} ({})",
        r.iterations,
        if r.converged {
            "converged"
        } else {
            "not converged"
        }
    );
    outln!(text, "jacobian          {}", r.jacobian.label());
}

/// The report in the library's JSON shape.
fn to_json(r: &FitReport) -> Result<Value> {
    Ok(serde_json::to_value(r.to_json())?)
}
