//! `POST /api/record`: a scope record read by the library's readers, so that the page draws
//! it as reference traces without a reader of its own.

use super::upload::{RecordKeys, Upload, RECORD_KEYS};
use crate::limit::Budget;
use crate::query::{ApiError, Query};
use serde::Serialize;
use std::sync::Arc;

/// `POST /api/record`.
#[derive(Debug)]
pub struct RecordRequest {
    keys: RecordKeys,
    upload: Upload,
}

/// A channel of a record.
#[derive(Debug, Serialize)]
pub struct ChannelAnswer {
    /// Its name in the file (`CH1`, `1`, `u_V`, …).
    pub name: String,
    /// Its unit as the file gives it (`V` where it says nothing).
    pub unit: String,
    /// The samples, at the times `t_s`.
    pub values: Vec<f64>,
    /// The vertical resolution: the smallest step between two distinct values (null for a
    /// constant channel).
    pub resolution: Option<f64>,
    /// Samples at a flat run at the channel's extreme (clipped), left out of fits.
    pub clipped: usize,
}

/// The drive's sine fitted over the record's whole periods:
/// `offset_V + amplitude_V·cos(2π·f_Hz·t_s + phase)`.
#[derive(Debug, Serialize)]
pub struct DriveAnswer {
    /// Frequency (Hz).
    #[serde(rename = "f_Hz")]
    pub f_hz: f64,
    /// Amplitude (V, peak).
    #[serde(rename = "amplitude_V")]
    pub amplitude_v: f64,
    /// Phase at the first sample (radians).
    pub phase: f64,
    /// DC offset (V).
    #[serde(rename = "offset_V")]
    pub offset_v: f64,
    /// Whole drive periods in the record.
    pub periods: usize,
    /// RMS residual of the sine (V).
    #[serde(rename = "rms_residual_V")]
    pub rms_residual_v: f64,
}

/// The answer of `/api/record`.
#[derive(Debug, Serialize)]
pub struct RecordAnswer {
    /// The record's name (the key `file`).
    pub file: String,
    /// The format detected from the header (`rigol`, `tektronix`, `keysight`, `siglent`,
    /// `plain`).
    pub format: &'static str,
    /// Samples.
    pub samples: usize,
    /// Mean sample interval (s).
    pub sample_interval_s: f64,
    /// The time of the first sample in the file (s); `t_s` counts from it.
    pub t0_s: f64,
    /// Times since the first sample (s).
    pub t_s: Vec<f64>,
    /// Every channel, in the file's order.
    pub channels: Vec<ChannelAnswer>,
    /// The drive channel's name.
    pub drive_channel: String,
    /// The u_C channel's name.
    pub response_channel: String,
    /// The drive's sine fit.
    pub drive: DriveAnswer,
    /// Samples left out of a fit as clipped (in either channel).
    pub clipped: usize,
    /// The noise of u_C estimated from the data (V).
    #[serde(rename = "noise_V")]
    pub noise_v: f64,
}

impl RecordRequest {
    /// Keys: `file`, `drive`, `response` (see [`RecordKeys`]); the body: the CSV text, given by
    /// [`Self::with_upload`].
    ///
    /// # Errors
    /// A 400 naming the key at fault.
    pub fn parse(raw: Option<&str>) -> Result<Self, ApiError> {
        let mut q = Query::parse(raw)?;
        let keys = RecordKeys::take(&mut q)?;
        q.finish(&RECORD_KEYS)?;
        Ok(Self {
            keys,
            upload: Upload::None,
        })
    }

    /// The request with the record (the body, read after the keys were checked).
    pub fn with_upload(mut self, upload: Upload) -> Self {
        self.upload = upload;
        self
    }

    /// Read the record and fit its drive.
    ///
    /// # Errors
    /// The reader's refusal, a 400 naming the file and the line.
    pub fn run(self, _budget: &Arc<Budget>) -> Result<RecordAnswer, ApiError> {
        let (record, m) = self.keys.read(&self.upload)?;
        let t0 = record.time[0];
        Ok(RecordAnswer {
            file: record.file.clone(),
            format: record.format.label(),
            samples: record.len(),
            sample_interval_s: record.sample_interval,
            t0_s: t0,
            t_s: m.time.clone(),
            channels: record
                .channels
                .iter()
                .map(|c| ChannelAnswer {
                    name: c.name.clone(),
                    unit: c.unit.clone(),
                    values: c.values.clone(),
                    resolution: c.resolution,
                    clipped: c.clipped_count(),
                })
                .collect(),
            drive_channel: m.drive_channel.clone(),
            response_channel: m.response_channel.clone(),
            drive: DriveAnswer {
                f_hz: m.drive.frequency,
                amplitude_v: m.drive.amplitude,
                phase: m.drive.phase,
                offset_v: m.drive.offset,
                periods: m.drive.periods,
                rms_residual_v: m.drive.rms_residual,
            },
            clipped: m.clipped,
            noise_v: m.noise,
        })
    }
}
