//! Figures of measurements: the records of a fit (measured u_C, the fitted model and the
//! residual below it), a fitted table of amplitudes (the measured amplitudes on the fitted
//! resonance curves, with both theories), and a scope record drawn on a computed trace's time
//! axis (`simulate --data`, `steady --data`).
//!
//! Every model value drawn comes from the library: a record's model and residual are the
//! arrays of its [`RecordFit`]; a resonance curve is the fitted experiment's steady state,
//! stepped along the frequencies as [`stickslip::fit::fit_table`] steps a table's rows.

use crate::plot::{Figure, Legend, Panel, Quantity, Series, Stack, Style, PALETTE};
use plotters::style::RGBColor;
use rayon::prelude::*;
use std::f64::consts::TAU;
use stickslip::experiment::{DiodeModel, Experiment};
use stickslip::fit::{FitReport, FittedParameter, RecordFit};
use stickslip::measure::{AmplitudeTable, Direction, Measurement};
use stickslip::params::State;
use stickslip::scan::grid_value;
use stickslip::steady::SteadyOptions;
use stickslip::theory::curves::SweepTheory;
use stickslip::Parameter;

/// Width of the figures of records and tables (pixels).
const WIDTH: u32 = 1100;
/// Heights of a record's panel and of its residual's panel (pixels).
const RECORD_HEIGHT: u32 = 380;
const RESIDUAL_HEIGHT: u32 = 200;
/// Points of a fitted resonance curve (its frequencies are evenly spaced over the rows').
pub const CURVE_POINTS: usize = 150;

/// The colour of the `k`-th model of a figure: the response's blue for the first (the only
/// one of a plain fit, PWL of `--compare`), bluish green for the second (Shockley).
fn model_color(k: usize) -> RGBColor {
    if k == 0 {
        Quantity::Response.color()
    } else {
        PALETTE[2]
    }
}

/// `value ± error` with the error to two significant digits and the value to the same
/// decimal place; one power of ten for both outside 10⁻³ … 10⁵ ("(4.18 ± 0.80)e-9").
pub fn plus_minus(value: f64, error: f64) -> String {
    if !error.is_finite() || error <= 0.0 {
        return format!("{value:.4e} ± ?");
    }
    let big = value.abs().max(error);
    let exponent = if (1e-3..1e5).contains(&big) {
        0
    } else {
        big.log10().floor() as i32
    };
    let scale = 10f64.powi(exponent);
    let (v, e) = (value / scale, error / scale);
    let decimals = (1 - e.log10().floor() as i32).max(0) as usize;
    if exponent == 0 {
        format!("{v:.decimals$} ± {e:.decimals$}")
    } else {
        format!("({v:.decimals$} ± {e:.decimals$})e{exponent}")
    }
}

/// A fitted parameter as text, with its key's symbol and unit: `R = 80.1 ± 0.3 Ω`.
pub fn parameter_text(p: &FittedParameter) -> String {
    let key = p.parameter.key();
    let text = format!("{} = {}", key.symbol(), plus_minus(p.value, p.stderr));
    match key.shown_unit() {
        Some(unit) => format!("{text} {unit}"),
        None => text,
    }
}

/// A report's law and fitted values: `PWL: R = 80.1 ± 0.3 Ω, U_t = 0.600 ± 0.002 V`.
fn fitted_text(report: &FitReport) -> String {
    let values: Vec<String> = report.parameters.iter().map(parameter_text).collect();
    format!("{}: {}", law(report.model), values.join(", "))
}

fn law(model: DiodeModel) -> &'static str {
    match model {
        DiodeModel::Pwl => "PWL",
        DiodeModel::Shockley => "Shockley",
    }
}

/// The time unit of a window of `seconds`: (factor from seconds, axis label).
pub fn time_unit(seconds: f64) -> (f64, &'static str) {
    if seconds < 2e-3 {
        (1e6, "t (µs)")
    } else if seconds < 2.0 {
        (1e3, "t (ms)")
    } else {
        (1.0, "t (s)")
    }
}

/// The measured u_C, the model and the residual of one record, over its first two drive
/// periods: (time in s, measured, model, residual), all from the fit's arrays.
pub fn record_window(record: &RecordFit) -> Vec<(f64, f64, f64, f64)> {
    let end = 2.0 / record.freq_hz;
    record
        .time
        .iter()
        .zip(record.model.iter().zip(&record.residuals))
        .filter(|(&t, _)| t <= end)
        .map(|(&t, (&m, &r))| (t, m - r, m, r))
        .collect()
}

/// The figure of the records of a fit: per record, a panel of the measured u_C and the
/// fitted model over two drive periods, and the residual below it on the same time axis.
/// `groups` holds, per record, its fit by each model drawn (one, or PWL and Shockley of
/// `--compare`), each with its report (for the fitted values in the title).
pub fn records_stack(groups: &[Vec<(&FitReport, &RecordFit)>]) -> Stack {
    let mut panels = Vec::new();
    for group in groups {
        let Some(&(_, first)) = group.first() else {
            continue;
        };
        let window = record_window(first);
        let end = window.last().map_or(2.0 / first.freq_hz, |w| w.0);
        let (factor, x_label) = time_unit(end);
        let x_range = Some((0.0, end * factor));
        let mut series = vec![Quantity::Measured.series(
            "measured u_C",
            window.iter().map(|w| (w.0 * factor, w.1)).collect(),
        )];
        let mut residuals = vec![Series::new(
            "",
            vec![(0.0, 0.0), (end * factor, 0.0)],
            RGBColor(150, 150, 150),
            Style::Line(1),
        )];
        let mut fits = Vec::new();
        let mut rms = Vec::new();
        for (k, &(report, record)) in group.iter().enumerate() {
            let window = record_window(record);
            let color = model_color(k);
            let label = if group.len() > 1 {
                format!("model, {}", law(report.model))
            } else {
                format!("fitted model ({})", law(report.model))
            };
            series.push(
                Quantity::Response
                    .series(label, window.iter().map(|w| (w.0 * factor, w.2)).collect())
                    .colored(color),
            );
            residuals.push(Series::new(
                "",
                window.iter().map(|w| (w.0 * factor, w.3)).collect(),
                color,
                Style::Markers(2),
            ));
            fits.push(format!(
                "{} ({})",
                fitted_text(report),
                record.class.label()
            ));
            rms.push(format!(
                "{} RMS {:.2e} V",
                law(report.model),
                record.rms_residual_v
            ));
        }
        panels.push((
            Panel {
                title: format!(
                    "{}: {:.2} Hz, {:.4} V · {}",
                    first.file,
                    first.freq_hz,
                    first.amplitude_v,
                    fits.join(" · ")
                ),
                x_label: x_label.into(),
                y_label: "u_C (V)".into(),
                series,
                x_range,
                legend: Some(Legend::UpperRight),
                ..Default::default()
            },
            RECORD_HEIGHT,
        ));
        panels.push((
            Panel {
                title: format!(
                    "residual, model − measured: {}; noise {:.2e} V",
                    rms.join(", "),
                    first.noise_v
                ),
                x_label: x_label.into(),
                y_label: "residual (V)".into(),
                series: residuals,
                x_range,
                ..Default::default()
            },
            RESIDUAL_HEIGHT,
        ));
    }
    Stack {
        panels,
        width: WIDTH,
    }
}

/// The steady-state options of a fit of `experiment` (as the library's fit uses them: the
/// PWL solver's steady state to 10⁻¹², no spectrum, no Lyapunov measurement).
fn fit_steady_options(experiment: &Experiment) -> SteadyOptions {
    SteadyOptions {
        tolerance: if experiment.diode_model() == DiodeModel::Pwl {
            1e-12
        } else {
            experiment.steady_options().tolerance
        },
        spectrum: false,
        lyapunov: None,
        ..experiment.steady_options()
    }
}

/// The steady amplitude (V, half the peak-to-peak of u_C) of `experiment` driven at
/// `drive_v` (V) and each of `frequencies` (Hz) in turn: each from the motion of the one
/// before (`continued`, a leg of a sweep) or each from rest; NaN where there is none. This is
/// how the library's table fit computes its rows.
pub fn model_amplitudes(
    experiment: &Experiment,
    drive_v: f64,
    frequencies: &[f64],
    continued: bool,
) -> Vec<f64> {
    let options = fit_steady_options(experiment);
    let mut state = State::default();
    frequencies
        .iter()
        .map(|&f| {
            // Ctrl-C: the rest is left out (the caller stops before drawing).
            if crate::output::interrupted() {
                return f64::NAN;
            }
            let start = if continued { state } else { State::default() };
            let steady = experiment
                .clone()
                .with_frequency(f)
                .and_then(|e| e.with_amplitude(drive_v))
                .and_then(|e| e.with_initial(start))
                .and_then(|e| {
                    let steady = e.steady_with(&options)?;
                    Ok((steady, e.scales()))
                });
            match steady {
                Ok((steady, Some(scales))) => {
                    state = steady.final_state();
                    steady.amplitude() * scales.position
                }
                _ => {
                    state = State::default();
                    f64::NAN
                }
            }
        })
        .collect()
}

/// The rows of a table grouped by drive amplitude: rows whose U lies within 2 % of the
/// smallest U of their group (a generator's output drifts a little as the load changes).
pub fn drive_levels(table: &AmplitudeTable) -> Vec<Vec<usize>> {
    let mut order: Vec<usize> = (0..table.rows.len()).collect();
    order.sort_by(|&a, &b| table.rows[a].drive.total_cmp(&table.rows[b].drive));
    let mut levels: Vec<Vec<usize>> = Vec::new();
    for i in order {
        let u = table.rows[i].drive;
        match levels.last_mut() {
            Some(level) if u <= 1.02 * table.rows[level[0]].drive => level.push(i),
            _ => levels.push(vec![i]),
        }
    }
    levels
}

/// One curve of a table's figure: the leg (None: each point from rest), the level's drive
/// (V), frequencies (Hz, in the order computed) and amplitudes (V).
struct Curve {
    leg: Option<Direction>,
    frequencies: Vec<f64>,
    amplitudes: Vec<f64>,
}

/// The figure of a fitted table: per drive amplitude, the measured amplitudes (filled dots
/// up, open squares down, black dots without a direction), the fitted model's resonance
/// curves along the same legs, and the exact sliding orbit and the paper's eq. (11) at the
/// fitted values, in volts over kilohertz; one panel per drive amplitude, one above the
/// other.
pub fn table_figure(report: &FitReport, table: &AmplitudeTable) -> Figure {
    let experiment = &report.experiment;
    let levels = drive_levels(table);
    // Every (level, leg) curve at once: each a sequence of steady states.
    let jobs: Vec<(usize, Option<Direction>, f64, Vec<f64>)> = levels
        .iter()
        .enumerate()
        .flat_map(|(k, level)| {
            let u = level.iter().map(|&i| table.rows[i].drive).sum::<f64>() / level.len() as f64;
            let grid = frequency_grid(level.iter().map(|&i| table.rows[i].frequency));
            let mut legs: Vec<Option<Direction>> = Vec::new();
            for &i in level {
                let d = table.rows[i].direction;
                if !legs.contains(&d) {
                    legs.push(d);
                }
            }
            legs.into_iter().map(move |leg| {
                let mut f = grid.clone();
                if leg == Some(Direction::Down) {
                    f.reverse();
                }
                (k, leg, u, f)
            })
        })
        .collect();
    let curves: Vec<(usize, Curve)> = jobs
        .into_par_iter()
        .map(|(k, leg, u, frequencies)| {
            let amplitudes = model_amplitudes(experiment, u, &frequencies, leg.is_some());
            (
                k,
                Curve {
                    leg,
                    frequencies,
                    amplitudes,
                },
            )
        })
        .collect();
    let shockley = experiment.diode_model() == DiodeModel::Shockley;
    let fitted = fitted_text(report);
    let panels = levels
        .iter()
        .enumerate()
        .map(|(k, level)| {
            let u = level.iter().map(|&i| table.rows[i].drive).sum::<f64>() / level.len() as f64;
            let mut series = Vec::new();
            let grid = frequency_grid(level.iter().map(|&i| table.rows[i].frequency));
            let (lo, hi) = (grid[0], grid[grid.len() - 1]);
            let base = experiment
                .clone()
                .with_frequency(0.5 * (lo + hi))
                .and_then(|e| e.with_amplitude(u))
                .ok();
            let mut beta = f64::NAN;
            if let Some((params, scales)) = base
                .as_ref()
                .and_then(|e| Some((e.params().ok()?, e.scales()?)))
            {
                beta = params.beta;
                let w = |f: f64| TAU * f / scales.omega0;
                let theory = SweepTheory::new(
                    &params,
                    Parameter::W,
                    (w(lo), w(hi), CURVE_POINTS),
                    shockley,
                );
                let volts = params.beta * scales.position;
                let points = |c: &stickslip::theory::curves::TheoryCurve| {
                    c.x.iter()
                        .zip(&c.y)
                        .map(|(&w, &g)| (w * scales.omega0 / TAU / 1e3, g * volts))
                        .collect::<Vec<_>>()
                };
                series.push(Quantity::ExactTheory.series(
                    format!("{}exact sliding orbit (peak)", theory.prefix),
                    points(&theory.exact),
                ));
                series.push(Quantity::PaperTheory.series(
                    format!("{}paper, eq. (11) (A1)", theory.prefix),
                    points(&theory.paper),
                ));
            }
            for (_, curve) in curves.iter().filter(|(j, _)| *j == k) {
                let points = curve
                    .frequencies
                    .iter()
                    .map(|f| f / 1e3)
                    .zip(curve.amplitudes.iter().copied())
                    .collect();
                series.push(match curve.leg {
                    Some(Direction::Up) => Series::new(
                        "fitted model, up",
                        points,
                        Quantity::SweepUp.color(),
                        Style::Line(2),
                    ),
                    Some(Direction::Down) => Series::new(
                        "fitted model, down",
                        points,
                        Quantity::SweepDown.color(),
                        Style::Dashed(2),
                    ),
                    None => Quantity::Response.series("fitted model (from rest)", points),
                });
            }
            for (leg, quantity, label) in [
                (Some(Direction::Down), Quantity::SweepDown, "measured, down"),
                (Some(Direction::Up), Quantity::SweepUp, "measured, up"),
                (None, Quantity::Measured, "measured"),
            ] {
                let points: Vec<(f64, f64)> = level
                    .iter()
                    .map(|&i| &table.rows[i])
                    .filter(|r| r.direction == leg)
                    .map(|r| (r.frequency / 1e3, r.response))
                    .collect();
                if !points.is_empty() {
                    let mut s = quantity.series(label, points);
                    if leg.is_none() {
                        s.style = Style::Markers(4);
                    }
                    series.push(s);
                }
            }
            Panel {
                title: format!("{}: U = {u:.4} V (β = {beta:.3}) · {fitted}", table.file),
                x_label: "drive frequency (kHz)".into(),
                y_label: "amplitude of u_C (V, half peak-to-peak)".into(),
                series,
                legend: Some(Legend::UpperRight),
                ..Default::default()
            }
        })
        .collect::<Vec<_>>();
    Figure {
        panels,
        columns: 1,
        panel_size: (WIDTH, 540),
    }
}

/// [`CURVE_POINTS`] frequencies evenly spaced over the range of `frequencies` (±10 % around a
/// single one).
fn frequency_grid(frequencies: impl Iterator<Item = f64>) -> Vec<f64> {
    let (mut lo, mut hi) = frequencies.fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), f| {
        (a.min(f), b.max(f))
    });
    if hi <= lo {
        (lo, hi) = (0.9 * lo, 1.1 * hi);
    }
    (0..CURVE_POINTS)
        .map(|i| grid_value(lo, hi, i, CURVE_POINTS - 1))
        .collect()
}

/// A scope record placed on a computed trace's time axis: the drive and u_C as (t, V).
#[derive(Debug, Clone, Default)]
pub struct AlignedRecord {
    /// The record's drive channel.
    pub drive: Vec<(f64, f64)>,
    /// The record's u_C channel.
    pub response: Vec<(f64, f64)>,
}

/// Place `record` on the time axis of a computed trace whose drive is cos(ω·t + φ) in the
/// axis's unit t (`omega` radians per unit, `phase` at t = 0), the record's time converted by
/// `per_second` units per second: the record's first sample goes where the computed drive has
/// the phase of the record's drive there (from the record's sine fit), shifted by whole drive
/// periods: a record shorter than the axis ends as late as it can end at or before `end`, a
/// longer one starts at most a period before 0; samples outside [0, `end`] are left out.
pub fn align(
    record: &Measurement,
    omega: f64,
    phase: f64,
    per_second: f64,
    end: f64,
) -> AlignedRecord {
    let period = TAU / omega;
    let start = (record.drive.phase - phase).rem_euclid(TAU) / omega;
    let duration = record.time.last().copied().unwrap_or(0.0) * per_second;
    let whole = if duration < end {
        ((end - start - duration) / period).floor()
    } else {
        (-start / period).floor()
    };
    let t0 = start + whole * period;
    let at = |values: &[f64]| {
        record
            .time
            .iter()
            .zip(values)
            .map(|(&s, &v)| (t0 + s * per_second, v))
            .filter(|&(t, _)| (0.0..=end).contains(&t))
            .collect()
    };
    AlignedRecord {
        drive: at(&record.drive_values),
        response: at(&record.response),
    }
}

/// The series of an aligned record: its drive (grey dots) and u_C (black dots), named by
/// `file`.
pub fn record_series(record: &AlignedRecord, file: &str) -> Vec<Series> {
    vec![
        Quantity::MeasuredDrive.series(format!("{file}: drive"), record.drive.clone()),
        Quantity::Measured.series(format!("{file}: u_C"), record.response.clone()),
    ]
}

/// Records and tables for tests, made by the library's exact solver at R = 80 Ω,
/// U_t = 0.6 V.
#[cfg(test)]
pub(crate) mod synthetic {
    pub use stickslip_testkit::{circuit, truth};
    use stickslip_testkit::{stepped_record, Format};

    /// A Rigol export (Keysight with `keysight`) of 800 samples over 2.6 drive periods of the
    /// steady state of [`truth`] at (w, β), 8-bit quantised with a step of uniform noise.
    pub fn record(w: f64, beta: f64, keysight: bool) -> String {
        let e = truth().with_w(w).unwrap().with_beta(beta).unwrap();
        let format = if keysight {
            Format::Keysight
        } else {
            Format::Rigol
        };
        stepped_record(&e, 800, 2.6, 0x2545_f491_4f6c_dd1d, format)
    }

    /// A table of amplitudes of the truth, 1 % above the model, over 0.5 … 1.5 f0 at each
    /// drive amplitude of `levels` (V): an up and a down leg with `legs`, else rows from rest
    /// (and no direction column).
    pub fn table(levels: &[f64], legs: bool) -> String {
        let f0 = truth().scales().unwrap().f0();
        let freqs: Vec<f64> = (0..7).map(|k| f0 * (0.5 + k as f64 / 6.0)).collect();
        let mut text = if legs {
            "freq_Hz,U_V,response_V,direction\n"
        } else {
            "freq_Hz,U_V,response_V\n"
        }
        .to_string();
        for &u in levels {
            let runs: &[&str] = if legs { &["up", "down"] } else { &[""] };
            for &leg in runs {
                let mut f = freqs.clone();
                if leg == "down" {
                    f.reverse();
                }
                let a = super::model_amplitudes(&truth(), u, &f, legs);
                for (f, a) in f.iter().zip(a) {
                    let direction = if legs {
                        format!(",{leg}")
                    } else {
                        String::new()
                    };
                    text += &format!("{f},{u},{}{direction}\n", 1.01 * a);
                }
            }
        }
        text
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use stickslip::fit::{fit_records, fit_table, FitOptions, FitParameter};
    use stickslip::measure::{read_amplitudes, read_scope};

    #[test]
    fn the_records_figure_draws_the_fits_arrays() {
        let data: Vec<Measurement> = [(0.5, 2.5, false), (1.2, 2.0, true)]
            .iter()
            .enumerate()
            .map(|(k, &(w, beta, keysight))| {
                let text = synthetic::record(w, beta, keysight);
                let record = read_scope(&text, &format!("r{k}.csv")).unwrap();
                Measurement::new(&record, None, None).unwrap()
            })
            .collect();
        let free = [FitParameter::Resistance, FitParameter::Ut];
        let options = FitOptions::default();
        let start = synthetic::circuit(68.0, 0.7);
        let report = fit_records(&start, &data, &free, &options).unwrap();
        let groups: Vec<Vec<(&FitReport, &RecordFit)>> =
            report.records.iter().map(|r| vec![(&report, r)]).collect();
        let stack = records_stack(&groups);
        assert_eq!(stack.panels.len(), 4);
        for (k, record) in report.records.iter().enumerate() {
            let (main, _) = &stack.panels[2 * k];
            let (residual, _) = &stack.panels[2 * k + 1];
            // Two drive periods: the samples up to 2/f, in µs.
            let n = record
                .time
                .iter()
                .filter(|&&t| t <= 2.0 / record.freq_hz)
                .count();
            assert!(n > 500 && n < record.time.len(), "{n}");
            let (measured, model) = (&main.series[0].points, &main.series[1].points);
            let residuals = &residual.series[1].points;
            assert_eq!((measured.len(), model.len(), residuals.len()), (n, n, n));
            for i in 0..n {
                let t = record.time[i] * 1e6;
                assert_eq!(model[i], (t, record.model[i]));
                assert_eq!(residuals[i], (t, record.residuals[i]));
                assert_eq!(measured[i], (t, record.model[i] - record.residuals[i]));
            }
            assert!(main.title.contains(&parameter_text(&report.parameters[0])));
        }
    }

    #[test]
    fn the_resonance_curves_are_the_table_fits_model() {
        let free = [FitParameter::Resistance, FitParameter::Ut];
        let start = synthetic::circuit(70.0, 0.6);
        for legs in [true, false] {
            let levels: &[f64] = if legs { &[0.9, 1.5] } else { &[1.2] };
            let table = read_amplitudes(&synthetic::table(levels, legs), "gain.csv").unwrap();
            let report = fit_table(&start, &table, &free, &FitOptions::default()).unwrap();
            // Each leg of the table, stepped as the curves are, gives the fit's model values.
            let directions = if legs {
                vec![Some(Direction::Up), Some(Direction::Down)]
            } else {
                vec![None]
            };
            for &u in levels {
                for &direction in &directions {
                    let rows: Vec<_> = report
                        .rows
                        .iter()
                        .filter(|r| r.direction == direction && r.drive_v == u)
                        .collect();
                    assert_eq!(rows.len(), 7);
                    let frequencies: Vec<f64> = rows.iter().map(|r| r.freq_hz).collect();
                    let amplitudes = model_amplitudes(&report.experiment, u, &frequencies, legs);
                    for (row, a) in rows.iter().zip(amplitudes) {
                        assert_eq!(a, row.model_v, "line {}", row.line);
                    }
                }
            }
            assert_eq!(drive_levels(&table).len(), levels.len());
            let figure = table_figure(&report, &table);
            assert_eq!(figure.panels.len(), levels.len());
            let labels: Vec<&str> = figure.panels[0]
                .series
                .iter()
                .map(|s| s.label.as_str())
                .collect();
            if legs {
                // Both theories, the two fitted legs and the two measured legs.
                assert_eq!(
                    labels,
                    [
                        "exact sliding orbit (peak)",
                        "paper, eq. (11) (A1)",
                        "fitted model, up",
                        "fitted model, down",
                        "measured, down",
                        "measured, up"
                    ]
                );
            } else {
                assert_eq!(
                    labels,
                    [
                        "exact sliding orbit (peak)",
                        "paper, eq. (11) (A1)",
                        "fitted model (from rest)",
                        "measured"
                    ]
                );
                // The curve from rest starts at the lowest row's frequency, where it is
                // the fit's model value.
                let first = report
                    .rows
                    .iter()
                    .min_by(|a, b| a.freq_hz.total_cmp(&b.freq_hz))
                    .unwrap();
                let curve = &figure.panels[0].series[2];
                assert_eq!(curve.points[0], (first.freq_hz / 1e3, first.model_v));
                assert_eq!(curve.points.len(), CURVE_POINTS);
            }
        }
    }

    #[test]
    fn plus_minus_rounds_to_the_error() {
        assert_eq!(plus_minus(142.2333, 1.22), "142.2 ± 1.2");
        assert_eq!(plus_minus(0.4337585, 3.61e-3), "0.4338 ± 0.0036");
        assert_eq!(plus_minus(4.179436e-9, 7.95e-10), "(4.18 ± 0.80)e-9");
        assert_eq!(plus_minus(80.0, 0.0), "8.0000e1 ± ?");
    }

    #[test]
    fn a_record_lands_where_the_drive_phases_agree() {
        // A record whose drive is cos(2π·1000·s + 1): on an axis in ms where the computed
        // drive is cos(2π·t + 0.3) (1 ms per period), its first sample goes where 2πt + 0.3 ≡ 1.
        let f = 1000.0;
        let time: Vec<f64> = (0..200).map(|k| k as f64 * 1e-5).collect();
        let drive: Vec<f64> = time.iter().map(|&s| (TAU * f * s + 1.0).cos()).collect();
        let record = Measurement {
            file: "r.csv".into(),
            drive_channel: "CH1".into(),
            response_channel: "CH2".into(),
            drive: stickslip::measure::SineFit {
                frequency: f,
                amplitude: 1.0,
                phase: 1.0,
                offset: 0.0,
                periods: 2,
                rms_residual: 0.0,
            },
            time: time.clone(),
            drive_values: drive.clone(),
            response: drive,
            used: vec![true; 200],
            clipped: 0,
            resolution: None,
            noise: 0.0,
            drive_noise: 0.0,
            drive_unit: "V".into(),
            response_unit: "V".into(),
        };
        let aligned = align(&record, TAU, 0.3, 1e3, 10.0);
        for &(t, v) in &aligned.drive {
            assert!(((TAU * t + 0.3).cos() - v).abs() < 1e-9, "{t}: {v}");
        }
        // The record (2 ms) ends within the last whole period before 10 ms.
        let last = aligned.drive.last().unwrap().0;
        assert!(last <= 10.0 && last > 8.0, "{last}");
        // A record longer than the window (2 ms on 1 ms) fills it, still in phase.
        let aligned = align(&record, TAU, 0.3, 1e3, 1.0);
        let (first, last) = (aligned.drive[0].0, aligned.drive.last().unwrap().0);
        assert!((0.0..=0.01).contains(&first) && (0.99..=1.0).contains(&last));
        for &(t, v) in &aligned.drive {
            assert!(((TAU * t + 0.3).cos() - v).abs() < 1e-9, "{t}: {v}");
        }
    }
}
