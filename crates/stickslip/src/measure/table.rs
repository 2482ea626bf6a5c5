//! The table of measured amplitudes (the paper's Fig. 4, taken point by point).

use super::error::{quote, MeasureError};
use super::text::{extra_fields, number_hint, split};
use serde::{Deserialize, Serialize};

/// Which leg of a frequency sweep a row was measured on.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Direction {
    /// Frequency rising: each point settles from the motion of the point below.
    Up,
    /// Frequency falling: each point settles from the motion of the point above.
    Down,
}

/// One row of an amplitude table.
#[derive(Debug, Clone, Copy, PartialEq, Serialize, Deserialize)]
pub struct AmplitudeRow {
    /// The row's line in the file (1-based).
    pub line: usize,
    /// Drive frequency (Hz).
    pub frequency: f64,
    /// Drive amplitude U (V, peak).
    pub drive: f64,
    /// Response amplitude: half the peak-to-peak of u_C (V).
    pub response: f64,
    /// The leg of the sweep, when the table says.
    pub direction: Option<Direction>,
    /// The fundamental's amplitude A1 of u_C from the scope's FFT (V), when given.
    pub a1: Option<f64>,
    /// The third harmonic's amplitude A3 of u_C (V), when given.
    pub a3: Option<f64>,
}

/// A table of measured amplitudes.
#[derive(Debug, Clone, PartialEq, Serialize, Deserialize)]
pub struct AmplitudeTable {
    /// The file's name, as the caller gave it.
    pub file: String,
    /// The rows, in the file's order.
    pub rows: Vec<AmplitudeRow>,
}

/// The column names of an amplitude table (any case), each with the names it also answers
/// to. The first three are required.
pub const AMPLITUDE_COLUMNS: [(&str, &[&str], &str); 6] = [
    ("freq_Hz", &["frequency_Hz", "f_Hz"], "drive frequency (Hz)"),
    (
        "U_V",
        &["drive_V", "amplitude_V"],
        "drive amplitude U (V, peak)",
    ),
    (
        "response_V",
        &["uc_V", "A_V"],
        "response amplitude, half the peak-to-peak of u_C (V)",
    ),
    (
        "direction",
        &[],
        "up or down: the leg of the sweep (optional)",
    ),
    (
        "A1_V",
        &[],
        "the fundamental of u_C from the scope's FFT (V, optional)",
    ),
    ("A3_V", &[], "the third harmonic of u_C (V, optional)"),
];

fn column_of(name: &str) -> Option<usize> {
    AMPLITUDE_COLUMNS.iter().position(|(n, aliases, _)| {
        n.eq_ignore_ascii_case(name) || aliases.iter().any(|a| a.eq_ignore_ascii_case(name))
    })
}

/// Read a table of measured amplitudes: a header row of the names of
/// [`AMPLITUDE_COLUMNS`], then one row per measurement; lines starting with `#` and empty
/// lines are skipped.
///
/// # Errors
/// An unknown or repeated column, a missing required column, a field that is not a finite
/// number > 0 (or ≥ 0 for the response and harmonics), a direction other than `up` or
/// `down`; each naming the line. An empty table.
pub fn read_amplitudes(text: &str, file: &str) -> Result<AmplitudeTable, MeasureError> {
    let body = text.strip_prefix('\u{feff}').unwrap_or(text);
    if body.is_empty() {
        return Err(super::text::empty(file));
    }
    let table = split(text, true);
    let mut lines = table.lines.iter();
    let Some(header) = lines.next() else {
        return Err(MeasureError::file(file, "the table is empty"));
    };
    let header_line = header.number;
    let mut columns: Vec<usize> = Vec::new();
    for name in header.fields.iter() {
        let Some(c) = column_of(name) else {
            let known: Vec<&str> = AMPLITUDE_COLUMNS.iter().map(|c| c.0).collect();
            return Err(MeasureError::at(
                file,
                header_line,
                format!(
                    "unknown column {} (the columns are {})",
                    quote(name),
                    known.join(", ")
                ),
            ));
        };
        if columns.contains(&c) {
            return Err(MeasureError::at(
                file,
                header_line,
                format!("column {} is given twice", quote(name)),
            ));
        }
        columns.push(c);
    }
    for required in 0..3 {
        if !columns.contains(&required) {
            return Err(MeasureError::at(
                file,
                header_line,
                format!("no column {}", AMPLITUDE_COLUMNS[required].0),
            ));
        }
    }
    let mut rows = Vec::new();
    for line in lines {
        let (number, values) = (line.number, &line.fields);
        if values.len() > columns.len() {
            extra_fields(file, line, columns.len(), table.separator)?;
        }
        if values.len() != columns.len() {
            return Err(MeasureError::at(
                file,
                number,
                format!(
                    "{} fields, but the header names {}",
                    values.len(),
                    columns.len()
                ),
            ));
        }
        let mut row = AmplitudeRow {
            line: number,
            frequency: 0.0,
            drive: 0.0,
            response: 0.0,
            direction: None,
            a1: None,
            a3: None,
        };
        for (&c, text) in columns.iter().zip(values) {
            let name = AMPLITUDE_COLUMNS[c].0;
            if c == 3 {
                row.direction = match text.to_ascii_lowercase().as_str() {
                    "up" => Some(Direction::Up),
                    "down" => Some(Direction::Down),
                    _ => {
                        return Err(MeasureError::at(
                            file,
                            number,
                            format!("direction {} must be up or down", quote(text)),
                        ))
                    }
                };
                continue;
            }
            let value = text.parse::<f64>().ok().filter(|v| v.is_finite());
            let hint = number_hint(text);
            let positive = c < 2;
            let ok = value.filter(|&v| if positive { v > 0.0 } else { v >= 0.0 });
            let Some(v) = ok else {
                return Err(MeasureError::at(
                    file,
                    number,
                    format!(
                        "{name} = {} must be a finite number {}{hint}",
                        quote(text),
                        if positive { "> 0" } else { ">= 0" }
                    ),
                ));
            };
            match c {
                0 => row.frequency = v,
                1 => row.drive = v,
                2 => row.response = v,
                4 => row.a1 = Some(v),
                _ => row.a3 = Some(v),
            }
        }
        rows.push(row);
    }
    if rows.is_empty() {
        return Err(MeasureError::file(file, "the table has no rows"));
    }
    Ok(AmplitudeTable {
        file: file.to_string(),
        rows,
    })
}
