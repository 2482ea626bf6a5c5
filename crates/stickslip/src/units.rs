//! Numbers with SI prefixes and units, as people write component values: `20n`, `0.02uF`,
//! `11.5mH`, `9.97kHz`, `68ohm`, `1e-3`.
//!
//! The unit is optional; [`parse_si`] strips it without checking it against the quantity,
//! [`crate::experiment::Key::parse`] checks it against the key's. The prefix scales the
//! number. Prefixes: f p n u µ m k M G.
//!
//! **A decimal comma** is read where it cannot be anything else: one comma and no point
//! (`9,97k`, `0,02u`, `1,5e-3`), unless it could as well separate thousands, that is 1 to 3
//! digits (not starting with 0) before it and exactly 3 after it (`1,500`: 1.5 or 1500?),
//! which is refused naming both readings. A comma beside a point (`1,000.5`) or a second
//! comma is refused as before.

/// Why a text is not a number.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
pub enum NumberError {
    /// The text does not parse as a number, with or without a prefix.
    #[error("'{0}' is not a number (plain, or with an SI prefix such as 20n, 11.5m, 9.9k)")]
    NotANumber(String),
    /// The number is infinite or NaN.
    #[error("'{0}' is not a finite number")]
    NotFinite(String),
    /// A comma that may be a decimal comma or a thousands separator (`1,500`).
    #[error(
        "'{text}' is ambiguous: {decimal} with a decimal comma, {thousands} with a thousands \
         separator; write {decimal} or {thousands}"
    )]
    AmbiguousComma {
        /// The text given.
        text: String,
        /// Its value read with a decimal comma, as written back (`1.5`).
        decimal: String,
        /// Its value read with a thousands separator (`1500`).
        thousands: String,
    },
    /// The number ends with a unit that is not the quantity's (`9.97kV` for a frequency).
    #[error(
        "the unit {unit} does not fit: write {}the number alone",
        Alternatives(allowed)
    )]
    WrongUnit {
        /// The unit written.
        unit: &'static str,
        /// The units the quantity may be written with (none: dimensionless).
        allowed: &'static [&'static str],
    },
}

/// `H or ` for the units of a quantity, nothing for none.
struct Alternatives(&'static [&'static str]);

impl std::fmt::Display for Alternatives {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        if self.0.is_empty() {
            Ok(())
        } else {
            write!(f, "{} or ", self.0.join(" or "))
        }
    }
}

/// The text as a message shows it: control characters (a line break in a quoted value, say)
/// escaped, so that the message stays one line, and at most 40 characters of it (then `…`),
/// so that text from a network request cannot make a long message.
pub(crate) fn shown(text: &str) -> String {
    let escaped: String = text
        .chars()
        .flat_map(|c| {
            let escaped: Vec<char> = if c.is_control() {
                c.escape_default().collect()
            } else {
                vec![c]
            };
            escaped
        })
        .collect();
    let mut clipped: String = escaped.chars().take(40).collect();
    if escaped.chars().count() > 40 {
        clipped.push('…');
    }
    clipped
}

/// Units that may follow a number, longest first where one ends another.
pub const UNITS: [&str; 10] = ["Hz", "ohm", "Ohm", "Ω", "H", "F", "V", "A", "s", "N"];

/// SI prefixes and their factors.
const PREFIXES: [(char, f64); 9] = [
    ('f', 1e-15),
    ('p', 1e-12),
    ('n', 1e-9),
    ('u', 1e-6),
    ('µ', 1e-6),
    ('m', 1e-3),
    ('k', 1e3),
    ('M', 1e6),
    ('G', 1e9),
];

/// `body` (a number without prefix or unit) with its decimal comma made a point, where it
/// has one (see the module documentation); `text` is the whole text, for the message.
fn decimal_point<'a>(body: &'a str, text: &str) -> Result<std::borrow::Cow<'a, str>, NumberError> {
    let body = body.trim();
    if body.contains('.') || body.matches(',').count() != 1 {
        return Ok(body.into());
    }
    let (whole, fraction) = body.split_once(',').expect("one comma");
    let digits = whole.trim_start_matches(['+', '-']);
    let thousands = (1..=3).contains(&digits.len())
        && !digits.starts_with('0')
        && digits.bytes().all(|b| b.is_ascii_digit())
        && fraction.len() == 3
        && fraction.bytes().all(|b| b.is_ascii_digit());
    let point = format!("{whole}.{fraction}");
    if thousands {
        let shown_as = |t: &str| {
            t.parse::<f64>()
                .map_or_else(|_| t.to_string(), |x| x.to_string())
        };
        return Err(NumberError::AmbiguousComma {
            text: shown(text),
            decimal: shown_as(&point),
            thousands: shown_as(&format!("{whole}{fraction}")),
        });
    }
    Ok(point.into())
}

/// Parse a finite number with an optional SI prefix and unit (a decimal comma where it is
/// unambiguous, see the module documentation).
///
/// ```
/// use stickslip::units::parse_si;
/// assert_eq!(parse_si("11.5m").unwrap(), 11.5e-3);
/// assert_eq!(parse_si("9.9kHz").unwrap(), 9900.0);
/// assert_eq!(parse_si("9,97k").unwrap(), 9970.0);
/// assert!(parse_si("1,500").is_err());
/// assert!(parse_si("nan").is_err());
/// ```
///
/// # Errors
/// [`NumberError`] when the text is not a number or not finite.
pub fn parse_si(text: &str) -> Result<f64, NumberError> {
    let t = text.trim();
    let mut body = t;
    for unit in UNITS {
        if let Some(rest) = body.strip_suffix(unit) {
            body = rest;
            break;
        }
    }
    let mut scale = 1.0;
    if let Some(last) = body.chars().last() {
        if let Some(&(_, s)) = PREFIXES.iter().find(|(c, _)| *c == last) {
            scale = s;
            body = &body[..body.len() - last.len_utf8()];
        }
    }
    match decimal_point(body, text)?.parse::<f64>() {
        Ok(x) if x.is_finite() => Ok(x * scale),
        Ok(_) => Err(NumberError::NotFinite(shown(text))),
        Err(_) => Err(NumberError::NotANumber(shown(text))),
    }
}

/// Parse a finite plain number (no prefix, no unit), as dimensionless values are written (a
/// decimal comma where it is unambiguous, see the module documentation).
///
/// # Errors
/// [`NumberError`] when the text is not a finite number.
pub fn parse_plain(text: &str) -> Result<f64, NumberError> {
    match decimal_point(text, text)?.parse::<f64>() {
        Ok(x) if x.is_finite() => Ok(x),
        Ok(_) => Err(NumberError::NotFinite(shown(text))),
        Err(_) => Err(NumberError::NotFinite(shown(text))),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn si_values() {
        assert_eq!(parse_si("11.5m").unwrap(), 11.5e-3);
        assert!((parse_si("0.02uF").unwrap() - 0.02e-6).abs() < 1e-22);
        assert_eq!(parse_si("68ohm").unwrap(), 68.0);
        assert_eq!(parse_si("9.9kHz").unwrap(), 9900.0);
        assert_eq!(parse_si("-1e-3").unwrap(), -1e-3);
        assert_eq!(parse_si("2µ").unwrap(), 2e-6);
        assert!(matches!(parse_si("abc"), Err(NumberError::NotANumber(_))));
        assert!(parse_si("nan").is_err());
        assert!(matches!(parse_si("1e400"), Err(NumberError::NotFinite(_))));
    }

    /// The fuzz target `toml_experiment` found it: a value with a line break made a
    /// two-line message.
    #[test]
    fn regression_messages_stay_one_line() {
        let e = parse_si("\n!1.5m").unwrap_err().to_string();
        assert!(e.starts_with("'\\n!1.5m' is not a number"), "{e}");
        assert!(!parse_plain("1\r\n2")
            .unwrap_err()
            .to_string()
            .contains('\n'));
    }

    /// One comma and no point is a decimal comma, unless it could separate thousands.
    #[test]
    fn decimal_commas_where_unambiguous() {
        for (text, value) in [
            ("9,97k", 9970.0),
            ("0,02u", 0.02e-6),
            ("1,5e-3", 1.5e-3),
            ("-0,5", -0.5),
            ("68,0ohm", 68.0),
            ("0,001", 0.001),
            ("12,5", 12.5),
            ("1,2345", 1.2345),
            ("1234,567", 1234.567),
            (" 2,25 ", 2.25),
        ] {
            assert_eq!(parse_si(text).unwrap(), value, "{text}");
        }
        assert_eq!(parse_plain("0,95").unwrap(), 0.95);
        assert_eq!(parse_plain("-1,5").unwrap(), -1.5);
        let err = parse_si("1,500").unwrap_err();
        assert_eq!(
            err.to_string(),
            "'1,500' is ambiguous: 1.5 with a decimal comma, 1500 with a thousands separator; \
             write 1.5 or 1500"
        );
        assert!(matches!(
            parse_plain("-250,000"),
            Err(NumberError::AmbiguousComma { .. })
        ));
        assert!(matches!(
            parse_si("2,500k"),
            Err(NumberError::AmbiguousComma { .. })
        ));
        for text in ["1,000.5", "1,2,3", ",", ",5e", "1.5,3"] {
            assert!(parse_si(text).is_err(), "{text}");
        }
        // As a point would be read: ".5" and "1." are numbers.
        assert_eq!(parse_plain(",5").unwrap(), 0.5);
        assert_eq!(parse_plain("1,").unwrap(), 1.0);
    }

    #[test]
    fn plain_values() {
        assert_eq!(parse_plain(" 0.25 ").unwrap(), 0.25);
        assert!(parse_plain("1k").is_err());
        assert!(parse_plain("inf").is_err());
    }
}
