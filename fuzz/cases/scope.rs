//! The property of the measurement readers that the fuzz target `scope_csv` and the property
//! test in `crates/stickslip/tests/fit.rs` both check (included by both): any bytes are
//! decoded (UTF-8, UTF-16, Windows-1252) or refused, and any text is read as a scope export
//! and as an amplitude table (fields separated by commas, semicolons or tabs, decimal
//! points or commas) without a panic; a refusal is one line naming the
//! file; a record that is read has strictly increasing finite times, channels as long as the
//! times, a positive resolution and a clipping mask of every sample; a record prepared for
//! fitting has a positive finite drive frequency and at least one whole period.

#![allow(dead_code)]

use stickslip::measure::{decode, read_amplitudes, read_scope, Measurement, Record};

fn refusal(message: String) {
    assert!(!message.contains('\n'), "two lines: {message:?}");
    assert!(
        message.starts_with("fuzz.csv"),
        "the file is not named: {message}"
    );
}

/// Check the bytes of one file: decoded, then read; or refused in one line naming the file.
pub fn check_bytes(bytes: &[u8]) {
    match decode(bytes, "fuzz.csv") {
        Ok(text) => check(&text),
        Err(e) => refusal(e.to_string()),
    }
}

/// Check one text.
pub fn check(text: &str) {
    match read_amplitudes(text, "fuzz.csv") {
        Ok(table) => {
            assert!(!table.rows.is_empty());
            for row in &table.rows {
                assert!(row.frequency > 0.0 && row.frequency.is_finite());
                assert!(row.drive > 0.0 && row.drive.is_finite());
                assert!(row.response >= 0.0 && row.response.is_finite());
            }
        }
        Err(e) => refusal(e.to_string()),
    }
    let record = match read_scope(text, "fuzz.csv") {
        Ok(record) => record,
        Err(e) => return refusal(e.to_string()),
    };
    assert!(record.len() >= stickslip::measure::MIN_SAMPLES);
    assert!(record.time.iter().all(|t| t.is_finite()));
    assert!(record.time.windows(2).all(|w| w[1] > w[0]));
    assert!(record.sample_interval > 0.0);
    for c in &record.channels {
        assert_eq!(c.values.len(), record.len());
        assert_eq!(c.clipped.len(), record.len());
        assert!(c.values.iter().all(|v| v.is_finite()));
        if let Some(q) = c.resolution {
            assert!(q > 0.0 && q.is_finite(), "resolution {q}");
        }
        assert!(!c.name.contains('\n'));
    }
    let merged = Record::merge(vec![record.clone(), record.clone()]).expect("same times merge");
    assert_eq!(merged.channels.len(), 2 * record.channels.len());
    match Measurement::new(&record, None, None) {
        Ok(m) => {
            assert!(
                m.drive.frequency > 0.0 && m.drive.frequency.is_finite(),
                "{m:?}"
            );
            assert!(m.drive.amplitude.is_finite() && m.drive.phase.is_finite());
            assert!(m.drive.periods >= 1);
            assert!(m.noise.is_finite() && m.noise >= 0.0);
            assert_eq!(m.used.len(), record.len());
        }
        Err(e) => refusal(e.to_string()),
    }
}
