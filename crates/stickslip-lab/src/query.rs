//! Query strings → library types. The keys of the model are the library's key table
//! ([`Key::flag`], the command-line flags without their dashes: `w`, `beta`, `preset=paper`,
//! `freq`, `amplitude`, `inductance`, `model=shockley`, `diode-is`, `mu-s`, ...), and they
//! take what the flags take ([`Key::parse`]: SI prefixes for physical values, `freq=9.97k`,
//! with the key's unit). Every failure is an [`ApiError`]: one line, naming the key, never a
//! panic.

use axum::http::StatusCode;
use std::collections::BTreeMap;
use std::str::FromStr;
use stickslip::experiment::{Experiment, ExperimentSpec, Key};
use stickslip::names::NameError;
use stickslip::options::{OptionKey, Spelling};
use stickslip::Error;

/// Longest query string accepted, in bytes.
pub const MAX_QUERY_BYTES: usize = 4096;

/// An answer other than 200: its status, its one-line message and, where one key is to blame,
/// that key (so that the page can show the message beside its field).
#[derive(Debug, Clone, PartialEq)]
pub struct ApiError {
    /// HTTP status.
    pub status: StatusCode,
    /// One line.
    pub message: String,
    /// The query key at fault, if one is.
    pub field: Option<String>,
}

impl ApiError {
    /// A 400 about the query as a whole.
    pub fn bad(message: impl Into<String>) -> Self {
        Self {
            status: StatusCode::BAD_REQUEST,
            message: one_line(message.into()),
            field: None,
        }
    }

    /// A 400 about one key.
    pub fn field(field: &str, message: impl Into<String>) -> Self {
        Self {
            field: Some(field.to_string()),
            ..Self::bad(message)
        }
    }

    /// An answer with another status.
    pub fn status(status: StatusCode, message: impl Into<String>) -> Self {
        Self {
            status,
            ..Self::bad(message)
        }
    }

    /// A library error about the request (400, naming keys as the API does), a computation
    /// stopped by its caller (503, as the lab's own time limit), or a failed computation (500).
    pub fn library(err: &Error) -> Self {
        match err {
            Error::InvalidOption {
                option,
                value,
                allowed,
            } => {
                let key = option_key(*option);
                Self::field(
                    key,
                    format!(
                        "invalid {key} {}: {}",
                        short(*value),
                        allowed.render(*option, Spelling::Query)
                    ),
                )
            }
            Error::OptionProduct {
                what,
                first,
                second,
                product,
                max,
            } => Self::field(
                option_key(*second),
                format!(
                    "{} × {} = {} {what}: at most {max} allowed",
                    option_key(*first),
                    option_key(*second),
                    short(*product)
                ),
            ),
            Error::Cancelled { .. } | Error::DeadlineExceeded | Error::BudgetExceeded { .. } => {
                Self::status(
                    StatusCode::SERVICE_UNAVAILABLE,
                    format!("the computation was stopped ({err}): ask for less (fewer points, steps or periods)"),
                )
            }
            // A key's value or the description as a whole: in the library's words, the
            // key spelled as the query spells it, its field marked.
            Error::Spec(_)
            | Error::ImageOutOfRange { .. }
            | Error::InvalidText { .. }
            | Error::InvalidName { .. }
            | Error::InvalidParameter { .. }
                if err.key().is_some() =>
            {
                Self {
                    field: err.key().map(api_name),
                    ..Self::bad(err.render(Spelling::Query))
                }
            }
            Error::Spec(_)
            | Error::InvalidParameter { .. }
            | Error::HorizonTooLong { .. }
            | Error::Config(_)
            | Error::Unsupported(_) => Self::bad(err.render(Spelling::Query)),
            _ => Self::status(StatusCode::INTERNAL_SERVER_ERROR, err.to_string()),
        }
    }
}

/// The lab's names of the options whose query key is not the option's flag.
const RENAMED: [(OptionKey, &str); 2] = [
    (OptionKey::SimulateSamples, "samples"),
    (OptionKey::SimulatePeriods, "periods"),
];

/// The query key of an option: its flag ([`OptionKey::flag`]) but for the keys the lab renames (`RENAMED`).
pub fn option_key(option: OptionKey) -> &'static str {
    RENAMED
        .iter()
        .find(|r| r.0 == option)
        .map_or(option.flag(), |r| r.1)
}

/// A number as a message shows it: huge and tiny ones in exponent form.
pub fn short(x: f64) -> String {
    if x != 0.0 && !(1e-4..1e6).contains(&x.abs()) {
        format!("{x:e}")
    } else {
        x.to_string()
    }
}

/// Messages are one line: line breaks become spaces.
fn one_line(text: String) -> String {
    if text.contains(['\n', '\r']) {
        text.split(['\n', '\r'])
            .filter(|l| !l.trim().is_empty())
            .collect::<Vec<_>>()
            .join(" ")
    } else {
        text
    }
}

/// The query key of a model value: its flag in the library's key table ([`Key::flag`]).
pub fn api_name(key: Key) -> String {
    key.flag().to_string()
}

/// The query keys of a circuit's parts, from the key table (`inductance, capacitance,
/// resistance, ut, rd`).
pub fn circuit_keys() -> String {
    Key::ALL
        .into_iter()
        .filter(|k| k.is_circuit_part())
        .map(api_name)
        .collect::<Vec<_>>()
        .join(", ")
}

/// A parsed query string: each key once.
#[derive(Debug, Clone, Default)]
pub struct Query {
    values: BTreeMap<String, String>,
}

impl Query {
    /// Parse `raw` (the part after `?`, percent-encoded as in a form). Refuses a query longer
    /// than [`MAX_QUERY_BYTES`], a key given twice and an empty key.
    ///
    /// # Errors
    /// A 400 naming the problem.
    pub fn parse(raw: Option<&str>) -> Result<Self, ApiError> {
        let raw = raw.unwrap_or("");
        if raw.len() > MAX_QUERY_BYTES {
            return Err(ApiError::bad(format!(
                "the query is {} bytes long: at most {MAX_QUERY_BYTES} allowed",
                raw.len()
            )));
        }
        let mut values = BTreeMap::new();
        for (key, value) in form_urlencoded::parse(raw.as_bytes()) {
            let key = key.trim().to_string();
            if key.is_empty() {
                if value.is_empty() {
                    continue;
                }
                return Err(ApiError::bad(format!(
                    "a value without a key: '{}'",
                    clip(&value)
                )));
            }
            if values.contains_key(&key) {
                return Err(ApiError::field(
                    &key,
                    format!("{} is given twice: give each key once", clip(&key)),
                ));
            }
            values.insert(key, value.into_owned());
        }
        Ok(Self { values })
    }

    /// Remove and return the text of `key`.
    pub fn take(&mut self, key: &str) -> Option<String> {
        self.values.remove(key)
    }

    /// Remove `key` and read it as a plain finite number, or `default` when absent.
    ///
    /// # Errors
    /// A 400 naming the key and the text.
    pub fn number(&mut self, key: &str, default: Option<f64>) -> Result<Option<f64>, ApiError> {
        match self.take(key) {
            None => Ok(default),
            Some(text) => stickslip::units::parse_plain(&text)
                .map(Some)
                .map_err(|e| ApiError::field(key, format!("invalid {key}: {e}"))),
        }
    }

    /// Remove `key` and read it as a whole number (its range is the library's, checked
    /// where the number is used), or `default`.
    ///
    /// # Errors
    /// A 400 naming the key and the text.
    pub fn whole(&mut self, key: &str, default: usize) -> Result<usize, ApiError> {
        let Some(text) = self.take(key) else {
            return Ok(default);
        };
        text.trim()
            .parse::<u64>()
            .ok()
            .and_then(|n| usize::try_from(n).ok())
            .ok_or_else(|| {
                ApiError::field(
                    key,
                    format!("invalid {key} {}: must be a whole number", clip(&text)),
                )
            })
    }

    /// Remove `key` and read it as a whole number from `min` to `max`, or `default`.
    ///
    /// # Errors
    /// A 400 naming the key, the value and the allowed range.
    pub fn count(
        &mut self,
        key: &str,
        default: usize,
        min: usize,
        max: usize,
    ) -> Result<usize, ApiError> {
        let Some(text) = self.take(key) else {
            return Ok(default);
        };
        let bad = || {
            ApiError::field(
                key,
                format!(
                    "invalid {key} {}: must be a whole number from {min} to {max}",
                    clip(&text)
                ),
            )
        };
        let n: u64 = text.trim().parse().map_err(|_| bad())?;
        if n < min as u64 || n > max as u64 {
            return Err(bad());
        }
        Ok(n as usize)
    }

    /// Remove `key` and read it as one of the names of a library enum (its `FromStr`), or
    /// `default`.
    ///
    /// # Errors
    /// A 400 listing the names allowed.
    pub fn name<T: FromStr<Err = NameError>>(
        &mut self,
        key: &str,
        default: T,
    ) -> Result<T, ApiError> {
        let Some(text) = self.take(key) else {
            return Ok(default);
        };
        text.trim().parse().map_err(|e: NameError| {
            ApiError::field(
                key,
                format!(
                    "invalid {key} '{}': one of {}",
                    clip(&text),
                    e.allowed.join(", ")
                ),
            )
        })
    }

    /// Remove the model keys and build the experiment they describe, as the command-line
    /// tool does with the same flags. `config` is refused: the lab reads no files.
    ///
    /// # Errors
    /// A 400 naming the key at fault.
    pub fn experiment(&mut self) -> Result<Experiment, ApiError> {
        if self.values.contains_key("config") {
            return Err(ApiError::field(
                "config",
                format!(
                    "config: the lab reads no files; give the values as keys ({}, {}, {}, ...)",
                    circuit_keys(),
                    api_name(Key::Frequency),
                    api_name(Key::Amplitude)
                ),
            ));
        }
        // The library reads each key's text (a number with its unit, a decimal comma, or a
        // name); its error names the key, which marks the field.
        let mut spec = ExperimentSpec::new();
        for key in Key::ALL {
            if let Some(text) = self.take(&api_name(key)) {
                spec.set_text(key, &text)
                    .map_err(|e| ApiError::library(&e))?;
            }
        }
        spec.build().map_err(|e| ApiError::library(&e))
    }

    /// Refuse whatever keys are left: `known` lists the endpoint's own keys for the message.
    ///
    /// # Errors
    /// A 400 naming the first unknown key.
    pub fn finish(self, known: &[&str]) -> Result<(), ApiError> {
        match self.values.keys().next() {
            None => Ok(()),
            Some(key) => {
                let own = if known.is_empty() {
                    String::new()
                } else {
                    format!(" and {}", known.join(", "))
                };
                Err(ApiError::field(
                    key,
                    format!(
                        "unknown key '{}': this endpoint takes the model keys (the command-line \
                         flags without dashes: w, beta, freq, amplitude, preset, ...){own}",
                        clip(key)
                    ),
                ))
            }
        }
    }

    /// Whether the model key `key` was given (before [`Query::experiment`] takes it).
    pub fn has_model(&self, key: Key) -> bool {
        self.values.contains_key(&api_name(key))
    }

    /// Whether the query holds `key`.
    pub fn has(&self, key: &str) -> bool {
        self.values.contains_key(key)
    }
}

/// At most 40 characters of untrusted text in a message, without control characters.
fn clip(text: &str) -> String {
    let clean: String = text
        .chars()
        .map(|c| if c.is_control() { ' ' } else { c })
        .collect();
    let mut out: String = clean.chars().take(40).collect();
    if clean.chars().count() > 40 {
        out.push('…');
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;
    use stickslip::experiment::Preset;

    fn query(raw: &str) -> Query {
        Query::parse(Some(raw)).unwrap()
    }

    #[test]
    fn model_keys_are_the_flags_without_dashes() {
        assert_eq!(api_name(Key::MuS), "mu-s");
        assert_eq!(api_name(Key::Frequency), "freq");
        assert_eq!(api_name(Key::Diode), "model");
        assert_eq!(api_name(Key::SaturationCurrent), "diode-is");
    }

    #[test]
    fn physical_keys_take_si_prefixes_and_build_what_the_flags_build() {
        let e = query("preset=paper&freq=9.97k&amplitude=1.498")
            .experiment()
            .unwrap();
        let mut spec = ExperimentSpec::new();
        spec.set_preset(Preset::Paper);
        spec.set(Key::Frequency, 9970.0).unwrap();
        spec.set(Key::Amplitude, 1.498).unwrap();
        assert_eq!(e, spec.build().unwrap());
    }

    #[test]
    fn a_physical_value_outside_the_limits_is_a_bad_request() {
        // Found by the random-query test: an initial current whose image v0 lies outside the
        // documented range is the request's fault (400, naming the key), not the server's.
        let err = query("preset=paper&i0=8.e23p").experiment().unwrap_err();
        assert_eq!(err.status, StatusCode::BAD_REQUEST, "{}", err.message);
        assert_eq!(err.field.as_deref(), Some("i0"));
        assert!(err.message.contains("invalid i0"), "{}", err.message);
    }

    #[test]
    fn bad_values_name_their_key() {
        let err = query("preset=paper&w=-1&beta=2").experiment().unwrap_err();
        assert_eq!(err.status, StatusCode::BAD_REQUEST);
        assert_eq!(err.field.as_deref(), Some("w"));
        assert!(
            err.message
                .contains("invalid w -1: must be finite and from 1e-5 to 1e5"),
            "{}",
            err.message
        );

        let err = query("w=abc").experiment().unwrap_err();
        assert_eq!(err.field.as_deref(), Some("w"));
        assert!(err.message.contains("abc"), "{}", err.message);

        // A physical value without a physical description names the key as the API does.
        let err = query("w=1&beta=1&amplitude=2").experiment().unwrap_err();
        assert_eq!(err.field.as_deref(), Some("amplitude"));
        assert!(
            err.message.starts_with("amplitude is a physical value"),
            "{}",
            err.message
        );

        let err = query("preset=paper&freq=1k&w=1").experiment().unwrap_err();
        assert!(
            err.message.contains("give the drive frequency once"),
            "{}",
            err.message
        );

        for raw in ["preset=lab", "model=spice", "config=/etc/passwd"] {
            let err = query(raw).experiment().unwrap_err();
            assert_eq!(err.status, StatusCode::BAD_REQUEST, "{raw}");
            assert!(err.field.is_some(), "{raw}");
        }
    }

    #[test]
    fn queries_are_checked_whole() {
        let err = Query::parse(Some("w=1&w=2")).unwrap_err();
        assert!(err.message.contains("given twice"));
        let long = "w=1&".repeat(MAX_QUERY_BYTES);
        assert!(Query::parse(Some(&long)).is_err());
        let mut q = query("w=1&beta=2&colour=red");
        q.experiment().unwrap();
        let err = q.finish(&["samples"]).unwrap_err();
        assert_eq!(err.field.as_deref(), Some("colour"));
        assert!(err.message.contains("unknown key 'colour'"));
        let mut q = query("samples=12");
        assert!(q.count("samples", 1, 16, 4096).is_err());
        let mut q = query("samples=99999999999999999999999");
        assert!(q.count("samples", 1, 16, 4096).is_err());
    }

    /// Random text from the alphabet of queries.
    fn noise() -> impl Strategy<Value = String> {
        proptest::collection::vec(
            prop_oneof![
                Just("=".to_string()),
                Just("&".to_string()),
                Just("%".to_string()),
                Just("%ZZ".to_string()),
                Just("%00".to_string()),
                Just("%E2%82".to_string()),
                Just("+".to_string()),
                Just("\n".to_string()),
                Just("µ".to_string()),
                proptest::sample::select(Key::ALL.iter().map(|&k| api_name(k)).collect::<Vec<_>>()),
                "[-0-9.eEkmunpMG]{0,8}",
                "\\PC{0,6}",
            ],
            0..24,
        )
        .prop_map(|parts| parts.concat())
    }

    /// key=value pairs with model keys and values that are numbers, almost numbers or junk.
    fn pairs() -> impl Strategy<Value = String> {
        let key = proptest::sample::select(
            Key::ALL
                .iter()
                .map(|&k| api_name(k))
                .chain(["config", "samples", ""].map(String::from))
                .collect::<Vec<_>>(),
        );
        let value = prop_oneof![
            any::<f64>().prop_map(|x| x.to_string()),
            "-?[0-9]{1,4}(\\.[0-9]{0,3})?(e-?[0-9]{1,3})?[fpnumkMG]?(Hz|H|F|V|A|ohm)?",
            Just("paper".to_string()),
            Just("shockley".to_string()),
            Just("pwl".to_string()),
            "\\PC{0,10}",
        ];
        proptest::collection::vec((key, value), 0..12).prop_map(|kv| {
            kv.into_iter()
                .map(|(k, v)| {
                    let v: String = form_urlencoded::byte_serialize(v.as_bytes()).collect();
                    format!("{k}={v}")
                })
                .collect::<Vec<_>>()
                .join("&")
        })
    }

    fn check_no_panic(raw: &str) {
        match Query::parse(Some(raw)) {
            Ok(mut q) => {
                if let Err(e) = q.experiment() {
                    assert_eq!(e.status, StatusCode::BAD_REQUEST, "{raw}: {}", e.message);
                    assert!(!e.message.contains('\n'), "{raw}: {}", e.message);
                    assert!(!e.message.is_empty());
                }
                let _ = q.count("samples", 512, 16, 4096);
                let _ = q.number("from", None);
                let _ = q.finish(&[]);
            }
            Err(e) => assert!(!e.message.contains('\n'), "{raw}: {}", e.message),
        }
    }

    proptest! {
        #![proptest_config(ProptestConfig { cases: 3000, ..ProptestConfig::default() })]

        /// No query string makes the parser panic; every error is one line and a 400.
        #[test]
        fn no_query_string_panics(raw in noise()) {
            check_no_panic(&raw);
        }

        /// The same for well-formed pairs of model keys and odd values.
        #[test]
        fn no_pairs_panic(raw in pairs()) {
            check_no_panic(&raw);
        }
    }
}
