//! Fig. 3: capacitor voltage and drive against time with their spectra, and X-Y loops.

use super::super::report::{Report, Samples, Section};
use super::super::Context;
use super::common::{beta_color, class_title, num, padded, steady_pwl};
use crate::plot::{Figure, Legend, Panel, Quantity, Series, Style};
use anyhow::Result;
use serde_json::json;
use stickslip::experiment::Key;

const FREQUENCIES: [f64; 3] = [0.29, 0.95, 1.43];
const TRACE_BETAS: [f64; 2] = [1.07, 2.14];
const XY_BETAS: [f64; 4] = [1.07, 1.43, 2.14, 3.61];
/// The spectra's lowest amplitude shown, relative to the fundamental (−80 dB).
const SPECTRUM_FLOOR: f64 = 1e-4;

/// The columns of fig3_spectra.csv, the report's own (no library table holds a spectrum).
pub const SPECTRA_COLUMNS: [&str; 6] = ["w", "beta", "k", "f_kHz", "amplitude_V", "phase_rad"];

/// The columns of fig3_xy.csv, the report's own (the X-Y loops of the oscilloscope).
pub const XY_COLUMNS: [&str; 4] = ["w", "beta", "u_V", "uc_V"];

/// The power of ten by which a response `uc` is drawn beside its drive `drive` so that its
/// peak reaches at least 30 % of the drive's (1 when it already does), and its legend label.
fn magnified(uc: &[(f64, f64)], drive: &[(f64, f64)]) -> (f64, String) {
    let peak = |v: &[(f64, f64)]| v.iter().fold(0.0f64, |m, p| m.max(p.1.abs()));
    let (u, d) = (peak(uc), peak(drive));
    if u <= 0.0 || u >= 0.3 * d {
        return (1.0, "u_C".into());
    }
    let gain = 10f64.powi((0.3 * d / u).log10().ceil() as i32);
    (gain, format!("u_C × {gain}"))
}

/// Fig. 3 (1a)–(2c) traces with spectra, (3a)–(3c) X-Y loops.
pub fn fig3(report: &mut Report, ctx: &Context) -> Result<()> {
    let ut = ctx.diode.turn_on;
    let ms = 1e3 / ctx.scales.omega0;
    let mut trace_panels = Vec::new();
    let mut spectrum_panels = Vec::new();
    let mut traces = Vec::new();
    let mut spectrum_rows = Vec::new();
    let mut classes = Vec::new();
    let mut small = Vec::new();
    let mut magnified_panels = Vec::new();
    for (row, &beta) in TRACE_BETAS.iter().enumerate() {
        for (col, &w) in FREQUENCIES.iter().enumerate() {
            let (params, s) = steady_pwl(ctx, w, beta)?;
            let period = params.drive_period();
            // Two drive periods of the recorded cycle (repeated if it is one period long).
            let mut uc = Vec::new();
            let mut drive = Vec::new();
            let cycle = s.recorded_periods.max(1) as f64 * period;
            let mut trace = Samples::new(ctx.paper.units());
            let mut k = 0.0;
            while k * cycle < 2.0 * period - 1e-12 {
                for p in &s.trace {
                    let t = p.tau - s.start + k * cycle;
                    if t <= 2.0 * period {
                        uc.push((t * ms, p.y * ut));
                        drive.push((t * ms, params.drive(p.tau) * ut));
                        trace.push(t, p, params.drive(p.tau));
                    }
                }
                k += 1.0;
            }
            traces.push((vec![num(w), num(beta)], trace));
            let label = format!("({}{})", row + 1, ["a", "b", "c"][col]);
            if s.class == stickslip::steady::MotionClass::Static {
                let peak = uc.iter().fold(0.0f64, |m, p| m.max(p.1.abs()));
                small.push(format!("{label} at ±{:.1} mV", peak * 1e3));
            }
            // Where u_C is too small to see beside U, it is drawn magnified by a power of ten,
            // as a scope shows a channel at its own volts per division.
            let (gain, uc_label) = magnified(&uc, &drive);
            if gain > 1.0 {
                magnified_panels.push(format!("{label} ×{gain}"));
            }
            let uc_shown = uc.iter().map(|&(t, v)| (t, v * gain)).collect();
            trace_panels.push(Panel {
                title: format!("{label} β = {beta}, Ω/ω0 = {w}: {}", class_title(s.class)),
                x_label: "t (ms)".into(),
                y_label: "voltage (V)".into(),
                series: vec![
                    Quantity::Drive.series("U", drive),
                    Quantity::Response
                        .series(uc_label, uc_shown)
                        .colored(beta_color(beta)),
                ],
                legend: Some(Legend::UpperRight),
                ..Default::default()
            });
            let f_khz = ctx.scales.f0() * w / 1e3;
            let mut bars = Vec::new();
            let floor = s.harmonic(1).map_or(0.0, |a| a * ut) * SPECTRUM_FLOOR;
            if let Some(spec) = &s.spectrum {
                for h in spec.harmonics.iter().take(9) {
                    if h.amplitude * ut > floor {
                        bars.push((h.order as f64 * f_khz, h.amplitude * ut));
                    }
                    spectrum_rows.push(vec![
                        num(w),
                        num(beta),
                        h.order.to_string(),
                        num(h.order as f64 * f_khz),
                        num(h.amplitude * ut),
                        num(h.phase),
                    ]);
                }
            }
            spectrum_panels.push(Panel {
                title: format!("{label} spectrum of u_C"),
                x_label: "f (kHz)".into(),
                y_label: "amplitude (V, log)".into(),
                y_log: floor > 0.0,
                y_range: (floor > 0.0).then(|| (floor, floor / SPECTRUM_FLOOR * 2.0)),
                series: vec![Series::new(
                    "",
                    bars,
                    beta_color(beta),
                    Style::Bars(0.35 * f_khz),
                )],
                x_range: Some((0.0, 9.6 * f_khz)),
                ..Default::default()
            });
            classes.push(json!({"w": w, "beta": beta, "class": s.class.label(), "A1_V": s.harmonic(1).map(|a| a * ut), "A3_V": s.harmonic(3).map(|a| a * ut)}));
        }
    }
    let mut xy_panels = Vec::new();
    let mut alone_panels = Vec::new();
    let mut xy_rows = Vec::new();
    for (col, &w) in FREQUENCIES.iter().enumerate() {
        let mut series: Vec<Series> = Vec::new();
        for &beta in &XY_BETAS {
            let (_, s) = steady_pwl(ctx, w, beta)?;
            let mut pts: Vec<(f64, f64)> =
                s.xy().into_iter().map(|(u, y)| (u * ut, y * ut)).collect();
            if let Some(&first) = pts.first() {
                pts.push(first);
            }
            for (u, y) in &pts {
                xy_rows.push(vec![num(w), num(beta), num(*u), num(*y)]);
            }
            series.push(
                Quantity::Response
                    .series(format!("β = {beta}"), pts)
                    .colored(beta_color(beta)),
            );
        }
        // The loops reach the drive's extremes: a margin keeps them off the frame.
        let x_range = padded(
            series.iter().flat_map(|s| s.points.iter().map(|p| p.0)),
            0.04,
        );
        // The smallest drive's loop on a scale of its own (beside the others it is a line).
        let smallest = series[0].clone();
        alone_panels.push(Panel {
            title: format!(
                "(3{}′) Ω/ω0 = {w}, β = {} on its own scale",
                ["a", "b", "c"][col],
                XY_BETAS[0]
            ),
            x_label: "drive U (V)".into(),
            y_label: "u_C (V)".into(),
            x_range: padded(smallest.points.iter().map(|p| p.0), 0.04),
            series: vec![smallest],
            ..Default::default()
        });
        xy_panels.push(Panel {
            title: format!("(3{}) Ω/ω0 = {w}, X-Y mode", ["a", "b", "c"][col]),
            x_label: "drive U (V)".into(),
            y_label: "u_C (V)".into(),
            series,
            legend: Some(Legend::UpperLeft),
            x_range,
            ..Default::default()
        });
    }
    // Rows: traces β = 1.07, spectra β = 1.07, traces β = 2.14, spectra β = 2.14, X-Y, and
    // the X-Y loops of β = 1.07 alone.
    let mut panels = Vec::new();
    panels.extend(trace_panels[0..3].iter().cloned());
    panels.extend(spectrum_panels[0..3].iter().cloned());
    panels.extend(trace_panels[3..6].iter().cloned());
    panels.extend(spectrum_panels[3..6].iter().cloned());
    panels.extend(xy_panels);
    panels.extend(alone_panels);
    report.figure(
        "fig3",
        &Figure {
            panels,
            columns: 3,
            panel_size: (440, 290),
        },
    )?;
    // Two drive periods of each steady state in the shape of `stickslip simulate --out`
    // (τ from the start of the two periods), after its w and β.
    report.tables(
        "fig3_traces.csv",
        &[Key::W.name(), Key::Beta.name()],
        traces.iter().map(|(point, t)| (point.clone(), t)),
    )?;
    report.csv("fig3_spectra.csv", &SPECTRA_COLUMNS, &spectrum_rows)?;
    report.csv("fig3_xy.csv", &XY_COLUMNS, &xy_rows)?;
    report.summary.insert("fig3".into(), json!(classes));
    let magnified_note = if magnified_panels.is_empty() {
        String::new()
    } else {
        format!(
            " Where u_C is too small to see beside U it is drawn magnified, as a scope shows \
             a channel at its own volts per division: {} (the legend says so; the CSV holds \
             the volts).",
            magnified_panels.join(", ")
        )
    };
    let floor_db = (-20.0 * SPECTRUM_FLOOR.log10()).round();
    let static_note = if small.is_empty() {
        String::new()
    } else {
        format!(
            " \"static\" is the paper's rule, an amplitude below β/100, not rest: u_C still \
             moves, {}, a small square-like wave whose odd harmonics the spectra show.",
            small.join(", ")
        )
    };
    report.sections.push(Section {
        id: "fig3".into(),
        title: "Fig. 3 — capacitor voltage, spectra and X-Y loops".into(),
        caption: format!(
            "Steady state of the paper's circuit (PWL diodes, exact solver) at Ω/ω0 = \
                  0.29, 0.95 and 1.43. Rows 1–2: β = 1.07, capacitor voltage u_C (coloured) and \
                  drive U (grey) over two drive periods, and the amplitude spectrum of u_C \
                  (harmonics 1–9 of the drive, by FFT over whole periods: no leakage; on a \
                  logarithmic axis down to {floor_db} dB below the fundamental, so that the \
                  weak harmonics show). Rows 3–4: the same at β = 2.14.{magnified_note} Row \
                  5: u_C against U (the oscilloscope's X-Y mode) for β = 1.07, 1.43, 2.14 and \
                  3.61, one colour per β as in every figure; row 6: the loops of β = 1.07 \
                  alone, on their own scale (beside the others they are flat lines). Only \
                  odd harmonics appear (the motion is symmetric: the even ones lie below \
                  the axis); they are \
                  strongest at low frequency and small β, and at 0.29 the loop is the \
                  hysteresis loop of the paper's Fig. 3(3a). At β = 1.07 near and above \
                  resonance the PWL model, started from rest, barely moves (the drive exceeds \
                  the diodes' 0.7 V only briefly): the paper's oscilloscope traces there show \
                  more motion because real diodes conduct below 0.7 V, which the Shockley model \
                  of Fig. 7(b) describes.{static_note}"
        ),
        figures: vec!["fig3".into()],
        data: vec![
            "fig3_traces.csv".into(),
            "fig3_spectra.csv".into(),
            "fig3_xy.csv".into(),
        ],
        tables: vec![],
    });
    Ok(())
}
