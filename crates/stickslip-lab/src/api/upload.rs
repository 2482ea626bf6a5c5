//! What the endpoints that take a measurement share (`POST /api/record`, `POST /api/fit`):
//! the body (a scope record's CSV text, at most [`Caps::upload_bytes`](stickslip::limits::Caps)
//! bytes), its name and channels as query keys, and the library's readers
//! ([`stickslip::measure`]): the lab reads no file, only the text the page sends.

use super::caps::CAPS;
use crate::query::{ApiError, Query};
use axum::body::{Body, HttpBody};
use axum::http::{header, HeaderMap, StatusCode};
use std::pin::Pin;
use std::time::Duration;
use stickslip::measure::{read_scope, MeasureError, Measurement, Record};

/// Time allowed to send the body, from the end of the headers.
pub const UPLOAD_TIME: Duration = Duration::from_secs(10);

/// The field an error about the record's text names (the page shows it beside the record).
pub const RECORD_FIELD: &str = "record";

/// The upload cap in words: `2 MB (2097152 bytes)`.
pub fn cap_text() -> String {
    let bytes = CAPS.upload_bytes;
    format!("{} MB ({bytes} bytes)", bytes as f64 / (1024.0 * 1024.0))
}

fn too_large(size: Option<u64>) -> ApiError {
    let size = size.map_or(String::new(), |s| format!(" ({s} bytes)"));
    ApiError::status(
        StatusCode::PAYLOAD_TOO_LARGE,
        format!(
            "the record{size} is over the lab's cap of {}: send a shorter record (a few drive \
             periods of a few hundred samples each are enough to fit)",
            cap_text()
        ),
    )
}

/// The body as text: at most the cap (a 413 naming it, from the `Content-Length` header
/// before a byte is read, or as soon as more arrive), sent within [`UPLOAD_TIME`] (a 408),
/// UTF-8 (a 400).
///
/// # Errors
/// As above, and an empty body (a 400).
pub async fn read_body(headers: &HeaderMap, body: Body) -> Result<String, ApiError> {
    let cap = CAPS.upload_bytes;
    let declared = headers
        .get(header::CONTENT_LENGTH)
        .and_then(|v| v.to_str().ok())
        .and_then(|v| v.trim().parse::<u64>().ok());
    if declared.is_some_and(|n| n > cap as u64) {
        return Err(too_large(declared));
    }
    let read = async {
        let mut body = body;
        let mut bytes: Vec<u8> = Vec::new();
        while let Some(frame) = std::future::poll_fn(|cx| Pin::new(&mut body).poll_frame(cx)).await
        {
            let frame =
                frame.map_err(|e| ApiError::bad(format!("the record's upload broke off: {e}")))?;
            if let Ok(data) = frame.into_data() {
                if bytes.len() + data.len() > cap {
                    return Err(too_large(None));
                }
                bytes.extend_from_slice(&data);
            }
        }
        Ok(bytes)
    };
    let bytes = tokio::time::timeout(UPLOAD_TIME, read)
        .await
        .map_err(|_| {
            ApiError::status(
                StatusCode::REQUEST_TIMEOUT,
                format!(
                    "the record did not arrive within {} s: send it again",
                    UPLOAD_TIME.as_secs()
                ),
            )
        })??;
    if bytes.is_empty() {
        return Err(ApiError::field(
            RECORD_FIELD,
            "no record: the request's body must be the scope record's CSV text",
        ));
    }
    String::from_utf8(bytes).map_err(|e| {
        ApiError::field(
            RECORD_FIELD,
            format!(
                "the record is not text (UTF-8): byte {} is not; send the scope's CSV export",
                e.utf8_error().valid_up_to() + 1
            ),
        )
    })
}

/// The keys that name a record and its channels: `file` (its name, for messages; default
/// `record.csv`), `drive` and `response` (channel names, `CHn` or positions; default the
/// first and the second channel).
#[derive(Debug, Clone)]
pub struct RecordKeys {
    /// The record's name.
    pub file: String,
    /// The drive channel.
    pub drive: Option<String>,
    /// The u_C channel.
    pub response: Option<String>,
}

/// The keys of [`RecordKeys`].
pub const RECORD_KEYS: [&str; 3] = ["file", "drive", "response"];

impl RecordKeys {
    /// Take the keys from `q`.
    ///
    /// # Errors
    /// An empty or overlong name (a 400 naming the key).
    pub fn take(q: &mut Query) -> Result<Self, ApiError> {
        let mut name = |key: &str| -> Result<Option<String>, ApiError> {
            match q.take(key) {
                None => Ok(None),
                Some(text) => {
                    let text = text.trim().to_string();
                    if text.is_empty() || text.chars().count() > 120 {
                        return Err(ApiError::field(
                            key,
                            format!("invalid {key}: a name of 1 to 120 characters"),
                        ));
                    }
                    Ok(Some(
                        text.chars()
                            .map(|c| if c.is_control() { ' ' } else { c })
                            .collect(),
                    ))
                }
            }
        };
        Ok(Self {
            file: name("file")?.unwrap_or_else(|| "record.csv".to_string()),
            drive: name("drive")?,
            response: name("response")?,
        })
    }

    /// Read `text` as a scope export and prepare it for fitting, as `stickslip fit --data`
    /// does: a 400 with the reader's one line (file and line) naming the field at fault
    /// (`drive` or `response` for a channel that is not there, else `record`).
    ///
    /// # Errors
    /// As above.
    pub fn read(&self, text: &str) -> Result<(Record, Measurement), ApiError> {
        let record = read_scope(text, &self.file).map_err(|e| measure_error(&e))?;
        for (key, name) in [("drive", &self.drive), ("response", &self.response)] {
            if let Some(name) = name {
                record
                    .channel_index(name)
                    .map_err(|e| ApiError::field(key, e.to_string()))?;
            }
        }
        let m = Measurement::new(&record, self.drive.as_deref(), self.response.as_deref())
            .map_err(|e| measure_error(&e))?;
        Ok((record, m))
    }
}

/// A reader's refusal as a 400 about the record, in the reader's words.
pub fn measure_error(e: &MeasureError) -> ApiError {
    ApiError::field(RECORD_FIELD, e.to_string())
}
