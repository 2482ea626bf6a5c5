//! What the endpoints that take a measurement share (`POST /api/record`, `POST /api/fit`):
//! the body (at most [`Caps::upload_bytes`](stickslip::limits::Caps) bytes: a scope record's
//! CSV text, or JSON `{"files": [{"name", "text"}, …]}` with the texts of several files on the
//! same times, such as a Tektronix export's file per channel), its name and channels as query
//! keys, and the library's readers ([`stickslip::measure`]): the lab reads no file, only the
//! text the page sends.

use super::caps::CAPS;
use crate::query::{ApiError, Query};
use axum::body::{Body, HttpBody};
use axum::http::{header, HeaderMap, StatusCode};
use serde::Deserialize;
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

/// Most files of one JSON body.
pub const MAX_FILES: usize = 4;

/// What the page sends: one CSV text, or the texts of several files to merge.
#[derive(Debug, Clone, Default)]
pub enum Upload {
    /// Nothing yet (the body is read after the keys were checked).
    #[default]
    None,
    /// One record's CSV text (named by the key `file`).
    Csv(String),
    /// Files on the same times, merged channel after channel
    /// (`stickslip::measure::Record::merge`): name, text.
    Files(Vec<(String, String)>),
}

/// A JSON body: `{"files": [{"name": "ch1.csv", "text": "…"}, …]}`.
#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct FilesBody {
    files: Vec<FileText>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct FileText {
    name: String,
    text: String,
}

/// A file's name as messages show it: at most 120 characters, no control characters.
fn clean_name(name: &str) -> String {
    let name: String = name
        .trim()
        .chars()
        .take(120)
        .map(|c| if c.is_control() { ' ' } else { c })
        .collect();
    if name.is_empty() {
        "record.csv".to_string()
    } else {
        name
    }
}

/// The body as an [`Upload`]: JSON files when its `Content-Type` is `application/json`, else
/// one CSV text ([`read_body`]).
///
/// # Errors
/// Those of [`read_body`]; JSON that is not `{"files": [{"name", "text"}, …]}` with 1 to
/// [`MAX_FILES`] files (a 400 about the record).
pub async fn read_upload(headers: &HeaderMap, body: Body) -> Result<Upload, ApiError> {
    let json = headers
        .get(header::CONTENT_TYPE)
        .and_then(|v| v.to_str().ok())
        .is_some_and(|v| {
            v.trim()
                .to_ascii_lowercase()
                .starts_with("application/json")
        });
    let text = read_body(headers, body).await?;
    if !json {
        return Ok(Upload::Csv(text));
    }
    let files: FilesBody = serde_json::from_str(&text).map_err(|e| {
        ApiError::field(
            RECORD_FIELD,
            format!("the JSON body must be {{\"files\": [{{\"name\": …, \"text\": …}}, …]}}: {e}"),
        )
    })?;
    if files.files.is_empty() || files.files.len() > MAX_FILES {
        return Err(ApiError::field(
            RECORD_FIELD,
            format!(
                "{} files: send 1 to {MAX_FILES} files of the same record",
                files.files.len()
            ),
        ));
    }
    Ok(Upload::Files(
        files
            .files
            .into_iter()
            .map(|f| (clean_name(&f.name), f.text))
            .collect(),
    ))
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
    // UTF-8, UTF-16 or Windows-1252 (a spreadsheet's µ), or the cause of what is not text.
    stickslip::measure::decode(&bytes, "the record")
        .map_err(|e| ApiError::field(RECORD_FIELD, e.message))
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

    /// Read the upload as a scope export (several files merged, as `stickslip fit --data
    /// a.csv+b.csv` merges them) and prepare it for fitting, as `stickslip fit --data` does: a 400 with the reader's one line (file and line) naming the field at fault
    /// (`drive` or `response` for a channel that is not there, else `record`).
    ///
    /// # Errors
    /// As above.
    pub fn read(&self, upload: &Upload) -> Result<(Record, Measurement), ApiError> {
        let record = match upload {
            Upload::None => {
                return Err(ApiError::field(
                    RECORD_FIELD,
                    "no record: the request's body must be the scope record's CSV text",
                ))
            }
            Upload::Csv(text) => read_scope(text, &self.file).map_err(|e| measure_error(&e))?,
            Upload::Files(files) => {
                let parts = files
                    .iter()
                    .map(|(name, text)| read_scope(text, name))
                    .collect::<Result<Vec<_>, _>>()
                    .map_err(|e| measure_error(&e))?;
                Record::merge(parts).map_err(|e| measure_error(&e))?
            }
        };
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
