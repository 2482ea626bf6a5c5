//! A resumable record of finished work: the units of a long computation that are done (the
//! rows of a map, the steps of a sweep), with everything that determines the result and a
//! checksum.
//!
//! A front end keeps a [`Checkpoint`] while it works, stores each finished unit with
//! [`Checkpoint::insert`], and saves [`Checkpoint::to_bytes`] from time to time (written to a
//! temporary file and renamed, so that a saved checkpoint is always whole). Run again with
//! the same checkpoint, it reads it back with [`Checkpoint::from_bytes`], which refuses a
//! checkpoint of other parameters or a damaged one, and computes only the units still
//! missing. What a unit holds is the front end's affair: bytes, written and read with
//! [`UnitWriter`] and [`UnitReader`], which keep numbers bit for bit, so that a resumed run
//! gives the same output as an uninterrupted one.
//!
//! ```
//! use stickslip::checkpoint::{Checkpoint, Identity, UnitReader, UnitWriter};
//! let identity = Identity::new("phase-diagram").with("grid", "w 0.1..2.5 x 10");
//! let mut checkpoint = Checkpoint::new(identity.clone(), 10);
//! let mut unit = UnitWriter::new();
//! unit.f64(0.25).u64(3);
//! checkpoint.insert(4, unit.finish()).unwrap();
//! let bytes = checkpoint.to_bytes();
//! let back = Checkpoint::from_bytes(&bytes, &identity).unwrap();
//! let mut reader = UnitReader::new(back.unit(4).unwrap());
//! assert_eq!((reader.f64().unwrap(), reader.u64().unwrap()), (0.25, 3));
//! assert_eq!(back.missing().count(), 9);
//! ```
//!
//! **Format** (version [`FORMAT_VERSION`]), all integers little-endian: the magic line
//! `stickslip checkpoint\n`; the format version (u32); the identity as text (u64 length, then
//! UTF-8 lines `name = value`, the first naming the computation); the number of units of the
//! whole computation (u64) and of those stored (u64); each stored unit as its index (u64),
//! length (u64) and bytes, in increasing index; and last the CRC-32 (IEEE) of everything
//! before it (u32).

use std::collections::BTreeMap;

/// The version of the format written; other versions are refused.
pub const FORMAT_VERSION: u32 = 1;

const MAGIC: &[u8] = b"stickslip checkpoint\n";

/// Everything that determines the result of a computation, as named text values: the
/// computation's name first, then (for example) the experiment, the axes and the options,
/// and the library's version. Two checkpoints belong to the same computation when their
/// identities are equal.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Identity {
    fields: Vec<(String, String)>,
}

impl Identity {
    /// The identity of the computation `name` (e.g. `phase-diagram`), with the library's
    /// version, so that a checkpoint is never resumed by another version of the solvers.
    pub fn new(name: &str) -> Self {
        Self {
            fields: vec![
                ("computation".into(), name.into()),
                ("stickslip".into(), env!("CARGO_PKG_VERSION").into()),
            ],
        }
    }

    /// Add a named value (line breaks are written as `\n`).
    pub fn with(mut self, name: &str, value: impl std::fmt::Display) -> Self {
        let value = value.to_string().replace('\\', "\\\\").replace('\n', "\\n");
        self.fields.push((name.replace(['=', '\n'], "_"), value));
        self
    }

    /// The named values, in order.
    pub fn fields(&self) -> &[(String, String)] {
        &self.fields
    }

    fn to_text(&self) -> String {
        self.fields
            .iter()
            .map(|(k, v)| format!("{k} = {v}\n"))
            .collect()
    }

    fn from_text(text: &str) -> Option<Self> {
        let fields = text
            .lines()
            .map(|line| {
                line.split_once(" = ")
                    .map(|(k, v)| (k.to_string(), v.to_string()))
            })
            .collect::<Option<Vec<_>>>()?;
        Some(Self { fields })
    }
}

/// Why a checkpoint cannot be resumed. `Display` is one line.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
#[non_exhaustive]
pub enum CheckpointError {
    /// The bytes are not a checkpoint (no magic line).
    #[error("not a stickslip checkpoint")]
    NotACheckpoint,
    /// A checkpoint of another format version.
    #[error("checkpoint format version {found}, this version reads {expected}")]
    Version {
        /// The version found.
        found: u32,
        /// The version this library reads.
        expected: u32,
    },
    /// The checksum does not match, or the content is cut short or malformed.
    #[error("damaged checkpoint ({0})")]
    Damaged(&'static str),
    /// The checkpoint belongs to another computation.
    #[error(
        "checkpoint of other parameters: its {field} {}",
        differs(found, expected)
    )]
    Mismatch {
        /// The first value that differs.
        field: String,
        /// Its value in the checkpoint (`(none)` when missing).
        found: String,
        /// Its value in this run (`(none)` when missing).
        expected: String,
    },
    /// A unit index beyond the computation, or a unit stored twice.
    #[error("unit {index} is not a unit of this computation of {total}")]
    BadUnit {
        /// The index.
        index: usize,
        /// Units of the computation.
        total: usize,
    },
}

/// "is A, this run's is B", or "differs from this run's" when either is long.
fn differs(found: &str, expected: &str) -> String {
    if found.chars().count() <= 60 && expected.chars().count() <= 60 {
        format!("is {found}, this run's is {expected}")
    } else {
        "differs from this run's".into()
    }
}

/// The finished units of one computation (see the module documentation).
#[derive(Debug, Clone, PartialEq)]
pub struct Checkpoint {
    identity: Identity,
    total: usize,
    units: BTreeMap<usize, Vec<u8>>,
}

impl Checkpoint {
    /// An empty checkpoint of a computation of `total` units.
    pub fn new(identity: Identity, total: usize) -> Self {
        Self {
            identity,
            total,
            units: BTreeMap::new(),
        }
    }

    /// The computation's identity.
    pub fn identity(&self) -> &Identity {
        &self.identity
    }

    /// Units of the whole computation.
    pub fn total(&self) -> usize {
        self.total
    }

    /// Units stored.
    pub fn done(&self) -> usize {
        self.units.len()
    }

    /// Whether every unit is stored.
    pub fn is_complete(&self) -> bool {
        self.units.len() == self.total
    }

    /// Store the finished unit `index`.
    ///
    /// # Errors
    /// [`CheckpointError::BadUnit`] for an index outside the computation or already stored.
    pub fn insert(&mut self, index: usize, unit: Vec<u8>) -> Result<(), CheckpointError> {
        if index >= self.total || self.units.contains_key(&index) {
            return Err(CheckpointError::BadUnit {
                index,
                total: self.total,
            });
        }
        self.units.insert(index, unit);
        Ok(())
    }

    /// The stored unit `index`, if any.
    pub fn unit(&self, index: usize) -> Option<&[u8]> {
        self.units.get(&index).map(Vec::as_slice)
    }

    /// The indices of the units not stored yet, in order.
    pub fn missing(&self) -> impl Iterator<Item = usize> + '_ {
        (0..self.total).filter(|i| !self.units.contains_key(i))
    }

    /// The checkpoint as bytes (see the module documentation for the format).
    pub fn to_bytes(&self) -> Vec<u8> {
        let mut out =
            Vec::with_capacity(64 + self.units.values().map(|u| u.len() + 16).sum::<usize>());
        out.extend_from_slice(MAGIC);
        out.extend_from_slice(&FORMAT_VERSION.to_le_bytes());
        let text = self.identity.to_text();
        out.extend_from_slice(&(text.len() as u64).to_le_bytes());
        out.extend_from_slice(text.as_bytes());
        out.extend_from_slice(&(self.total as u64).to_le_bytes());
        out.extend_from_slice(&(self.units.len() as u64).to_le_bytes());
        for (&index, unit) in &self.units {
            out.extend_from_slice(&(index as u64).to_le_bytes());
            out.extend_from_slice(&(unit.len() as u64).to_le_bytes());
            out.extend_from_slice(unit);
        }
        let crc = crc32(&out);
        out.extend_from_slice(&crc.to_le_bytes());
        out
    }

    /// Read a checkpoint and check that it belongs to the computation `expected`.
    ///
    /// # Errors
    /// [`CheckpointError::NotACheckpoint`], [`CheckpointError::Version`],
    /// [`CheckpointError::Damaged`] (checksum, truncation, malformed content),
    /// [`CheckpointError::Mismatch`] naming the first value that differs,
    /// [`CheckpointError::BadUnit`].
    pub fn from_bytes(bytes: &[u8], expected: &Identity) -> Result<Self, CheckpointError> {
        if !bytes.starts_with(MAGIC) {
            return Err(CheckpointError::NotACheckpoint);
        }
        let mut r = UnitReader::new(&bytes[MAGIC.len()..]);
        let version = r.u32().ok_or(CheckpointError::Damaged("cut short"))?;
        if version != FORMAT_VERSION {
            return Err(CheckpointError::Version {
                found: version,
                expected: FORMAT_VERSION,
            });
        }
        if bytes.len() < MAGIC.len() + 8 {
            return Err(CheckpointError::Damaged("cut short"));
        }
        let (body, tail) = bytes.split_at(bytes.len() - 4);
        let stored = u32::from_le_bytes(tail.try_into().expect("four bytes"));
        if crc32(body) != stored {
            return Err(CheckpointError::Damaged("checksum mismatch"));
        }
        let mut r = UnitReader::new(&body[MAGIC.len() + 4..]);
        let malformed = CheckpointError::Damaged("malformed content");
        let length = r.len().ok_or(malformed.clone())?;
        let text = r.bytes(length).ok_or(malformed.clone())?;
        let identity = std::str::from_utf8(text)
            .ok()
            .and_then(Identity::from_text)
            .ok_or(malformed.clone())?;
        if let Some(mismatch) = first_difference(&identity, expected) {
            return Err(mismatch);
        }
        let total = r.len().ok_or(malformed.clone())?;
        let count = r.len().ok_or(malformed.clone())?;
        let mut checkpoint = Checkpoint::new(identity, total);
        for _ in 0..count {
            let index = r.len().ok_or(malformed.clone())?;
            let length = r.len().ok_or(malformed.clone())?;
            let unit = r.bytes(length).ok_or(malformed.clone())?;
            checkpoint.insert(index, unit.to_vec())?;
        }
        if !r.is_empty() {
            return Err(malformed);
        }
        Ok(checkpoint)
    }
}

/// The first value in which two identities differ.
fn first_difference(found: &Identity, expected: &Identity) -> Option<CheckpointError> {
    let get = |id: &Identity, name: &str| {
        id.fields
            .iter()
            .find(|(k, _)| k == name)
            .map_or_else(|| "(none)".to_string(), |(_, v)| v.clone())
    };
    let names = expected
        .fields
        .iter()
        .chain(found.fields.iter())
        .map(|(k, _)| k.as_str());
    for name in names {
        let (f, e) = (get(found, name), get(expected, name));
        if f != e {
            return Some(CheckpointError::Mismatch {
                field: name.to_string(),
                found: f,
                expected: e,
            });
        }
    }
    None
}

/// Builds the bytes of a unit: numbers in little-endian order, f64 bit for bit.
#[derive(Debug, Clone, Default)]
pub struct UnitWriter {
    bytes: Vec<u8>,
}

impl UnitWriter {
    /// An empty unit.
    pub fn new() -> Self {
        Self::default()
    }

    /// Append an f64 (its bits: NaN and infinities come back as they were).
    pub fn f64(&mut self, x: f64) -> &mut Self {
        self.bytes.extend_from_slice(&x.to_bits().to_le_bytes());
        self
    }

    /// Append a u64.
    pub fn u64(&mut self, x: u64) -> &mut Self {
        self.bytes.extend_from_slice(&x.to_le_bytes());
        self
    }

    /// Append a byte.
    pub fn u8(&mut self, x: u8) -> &mut Self {
        self.bytes.push(x);
        self
    }

    /// The bytes.
    pub fn finish(&mut self) -> Vec<u8> {
        std::mem::take(&mut self.bytes)
    }
}

/// Reads the numbers of a unit back in the order [`UnitWriter`] wrote them; every read
/// returns `None` past the end.
#[derive(Debug, Clone)]
pub struct UnitReader<'a> {
    bytes: &'a [u8],
}

impl<'a> UnitReader<'a> {
    /// Read `bytes`.
    pub fn new(bytes: &'a [u8]) -> Self {
        Self { bytes }
    }

    fn bytes(&mut self, n: usize) -> Option<&'a [u8]> {
        if n > self.bytes.len() {
            return None;
        }
        let (head, rest) = self.bytes.split_at(n);
        self.bytes = rest;
        Some(head)
    }

    fn u32(&mut self) -> Option<u32> {
        Some(u32::from_le_bytes(self.bytes(4)?.try_into().ok()?))
    }

    fn len(&mut self) -> Option<usize> {
        usize::try_from(self.u64()?).ok()
    }

    /// The next f64.
    pub fn f64(&mut self) -> Option<f64> {
        Some(f64::from_bits(self.u64()?))
    }

    /// The next u64.
    pub fn u64(&mut self) -> Option<u64> {
        Some(u64::from_le_bytes(self.bytes(8)?.try_into().ok()?))
    }

    /// The next byte.
    pub fn u8(&mut self) -> Option<u8> {
        Some(self.bytes(1)?[0])
    }

    /// Whether everything was read.
    pub fn is_empty(&self) -> bool {
        self.bytes.is_empty()
    }
}

/// CRC-32 (IEEE 802.3, reflected, polynomial 0xEDB88320), as zlib and PNG compute it.
pub fn crc32(bytes: &[u8]) -> u32 {
    const TABLE: [u32; 256] = {
        let mut table = [0u32; 256];
        let mut i = 0;
        while i < 256 {
            let mut c = i as u32;
            let mut k = 0;
            while k < 8 {
                c = if c & 1 != 0 {
                    0xEDB8_8320 ^ (c >> 1)
                } else {
                    c >> 1
                };
                k += 1;
            }
            table[i] = c;
            i += 1;
        }
        table
    };
    let mut crc = !0u32;
    for &b in bytes {
        crc = TABLE[((crc ^ u32::from(b)) & 0xFF) as usize] ^ (crc >> 8);
    }
    !crc
}

#[cfg(test)]
mod tests {
    use super::*;

    fn identity() -> Identity {
        Identity::new("phase-diagram")
            .with("experiment", "{\"zeta\":0.0468}")
            .with("axes", "w 0.1 2.5 100; beta 0.5 4 100")
    }

    fn sample() -> Checkpoint {
        let mut c = Checkpoint::new(identity(), 5);
        for (i, x) in [(0usize, 1.5f64), (3, f64::NAN), (4, f64::NEG_INFINITY)] {
            let mut u = UnitWriter::new();
            u.f64(x).u64(i as u64).u8(7);
            c.insert(i, u.finish()).unwrap();
        }
        c
    }

    #[test]
    fn crc32_of_the_standard_check_string() {
        assert_eq!(crc32(b"123456789"), 0xCBF4_3926);
        assert_eq!(crc32(b""), 0);
    }

    #[test]
    fn round_trips_bit_for_bit() {
        let c = sample();
        let back = Checkpoint::from_bytes(&c.to_bytes(), &identity()).unwrap();
        assert_eq!(back.done(), 3);
        assert_eq!(back.missing().collect::<Vec<_>>(), vec![1, 2]);
        let mut r = UnitReader::new(back.unit(3).unwrap());
        assert!(r.f64().unwrap().is_nan());
        assert_eq!((r.u64(), r.u8(), r.u8()), (Some(3), Some(7), None));
        let mut r = UnitReader::new(back.unit(4).unwrap());
        assert_eq!(r.f64(), Some(f64::NEG_INFINITY));
        assert_eq!(back.to_bytes(), c.to_bytes());
    }

    #[test]
    fn other_parameters_are_refused_naming_the_value() {
        let bytes = sample().to_bytes();
        let other = Identity::new("phase-diagram")
            .with("experiment", "{\"zeta\":0.05}")
            .with("axes", "w 0.1 2.5 100; beta 0.5 4 100");
        match Checkpoint::from_bytes(&bytes, &other) {
            Err(CheckpointError::Mismatch { field, .. }) => assert_eq!(field, "experiment"),
            other => panic!("{other:?}"),
        }
        let sweep = Identity::new("sweep");
        let err = Checkpoint::from_bytes(&bytes, &sweep).unwrap_err();
        assert_eq!(
            err.to_string(),
            "checkpoint of other parameters: its computation is phase-diagram, this run's is sweep"
        );
        let more = identity().with("options", "x");
        assert!(matches!(
            Checkpoint::from_bytes(&bytes, &more),
            Err(CheckpointError::Mismatch { .. })
        ));
    }

    #[test]
    fn damage_anywhere_is_found() {
        let bytes = sample().to_bytes();
        for i in 0..bytes.len() {
            for bit in [0x01u8, 0x80] {
                let mut bad = bytes.clone();
                bad[i] ^= bit;
                assert!(
                    Checkpoint::from_bytes(&bad, &identity()).is_err(),
                    "flip at byte {i} went unnoticed"
                );
            }
        }
        for n in 0..bytes.len() {
            assert!(
                Checkpoint::from_bytes(&bytes[..n], &identity()).is_err(),
                "cut at {n}"
            );
        }
        let mut version = bytes.clone();
        version[MAGIC.len()] = 9;
        assert_eq!(
            Checkpoint::from_bytes(&version, &identity()),
            Err(CheckpointError::Version {
                found: 9,
                expected: FORMAT_VERSION
            })
        );
        assert_eq!(
            Checkpoint::from_bytes(b"w,beta,class\n", &identity()),
            Err(CheckpointError::NotACheckpoint)
        );
    }

    #[test]
    fn units_are_checked() {
        let mut c = Checkpoint::new(identity(), 2);
        assert!(c.insert(0, vec![]).is_ok());
        assert!(c.insert(0, vec![]).is_err());
        assert!(c.insert(2, vec![]).is_err());
        assert!(!c.is_complete());
        c.insert(1, vec![1]).unwrap();
        assert!(c.is_complete());
    }
}
