//! The one error of the readers: what is wrong, in which file, on which line.

use thiserror::Error;

/// A measurement that cannot be read or used, with the file (as the caller named it) and the
/// line (1-based) where there is one. Its `Display` is one line:
/// `scope.csv: line 17: "abc" in column 2 is not a number`.
#[derive(Debug, Clone, PartialEq, Eq, Error)]
#[error("{file}: {}{message}", line.map(|l| format!("line {l}: ")).unwrap_or_default())]
pub struct MeasureError {
    /// The file's name, as the caller gave it.
    pub file: String,
    /// The 1-based line of the text, when the fault is on one line.
    pub line: Option<usize>,
    /// What is wrong and what is allowed.
    pub message: String,
    /// When the record's channels look swapped (its drive channel is not a sine and another
    /// is): (the channel that looks like the drive, the one that looks like u_C), for each
    /// front end to say how its user picks them (`--drive`, `drive=`).
    pub swap: Option<(String, String)>,
}

impl MeasureError {
    /// A fault on one line of `file`.
    pub(crate) fn at(file: &str, line: usize, message: impl Into<String>) -> Self {
        Self {
            file: file.to_string(),
            line: Some(line),
            message: one_line(message.into()),
            swap: None,
        }
    }

    /// A fault of the whole file.
    pub(crate) fn file(file: &str, message: impl Into<String>) -> Self {
        Self {
            file: file.to_string(),
            line: None,
            message: one_line(message.into()),
            swap: None,
        }
    }

    /// A record whose channels look swapped: `drive` looks like the drive, `response` like
    /// u_C ([`MeasureError::swap`]).
    pub(crate) fn swapped(
        file: &str,
        message: impl Into<String>,
        drive: &str,
        response: &str,
    ) -> Self {
        Self {
            swap: Some((drive.to_string(), response.to_string())),
            ..Self::file(file, message)
        }
    }
}

/// Text quoted from a file, cut to 40 characters and with control characters escaped, so that
/// a message stays one short line whatever the file holds.
pub(crate) fn quote(text: &str) -> String {
    let mut out = String::from("\"");
    for (i, c) in text.chars().enumerate() {
        if i == 40 {
            out.push('…');
            break;
        }
        if c.is_control() {
            out.extend(c.escape_default());
        } else {
            out.push(c);
        }
    }
    out.push('"');
    out
}

fn one_line(message: String) -> String {
    if message.chars().any(char::is_control) {
        message
            .chars()
            .map(|c| if c.is_control() { ' ' } else { c })
            .collect()
    } else {
        message
    }
}
