//! The text of an export: its bytes decoded, its lines split into fields with the separator
//! and the decimal mark that the scope or a spreadsheet wrote.

use super::error::MeasureError;
use std::borrow::Cow;

/// The text of a file's bytes, as the readers take it: UTF-8 (with or without a byte-order
/// mark), UTF-16 with a byte-order mark (a spreadsheet's "Unicode text"), or else Windows-1252
/// (the code page a spreadsheet in Western Europe saves in: `µs` as the byte 0xB5). `file`
/// names the file in messages.
///
/// # Errors
/// An empty file; a binary file (a byte 0 without a UTF-16 byte-order mark: a scope's own
/// waveform format, a picture), naming the byte; UTF-16 that is cut or broken; a byte that
/// neither UTF-8 nor Windows-1252 gives a character (0x81, 0x8D, 0x8F, 0x90, 0x9D), naming
/// the byte and its line.
pub fn decode(bytes: &[u8], file: &str) -> Result<String, MeasureError> {
    if bytes.is_empty() {
        return Err(empty(file));
    }
    let utf16 = match bytes {
        [0xFF, 0xFE, rest @ ..] => Some((rest, u16::from_le_bytes as fn([u8; 2]) -> u16)),
        [0xFE, 0xFF, rest @ ..] => Some((rest, u16::from_be_bytes as fn([u8; 2]) -> u16)),
        _ => None,
    };
    if let Some((rest, unit)) = utf16 {
        let broken = || {
            MeasureError::file(
                file,
                "starts with UTF-16's byte-order mark but is not UTF-16 text (cut short or \
                 broken); save it again as CSV (UTF-8)",
            )
        };
        if rest.len() % 2 != 0 {
            return Err(broken());
        }
        let units = rest.chunks_exact(2).map(|c| unit([c[0], c[1]]));
        return char::decode_utf16(units)
            .collect::<Result<String, _>>()
            .map_err(|_| broken());
    }
    if let Some(i) = bytes.iter().position(|&b| b == 0) {
        return Err(MeasureError::file(
            file,
            format!(
                "not a text file: byte {} is 0, as in a binary file (a scope's own waveform \
                 format, a picture, UTF-16 without its byte-order mark); export the record \
                 as CSV",
                i + 1
            ),
        ));
    }
    match std::str::from_utf8(bytes) {
        Ok(text) => Ok(text.to_string()),
        Err(_) => bytes
            .iter()
            .enumerate()
            .map(|(i, &b)| {
                windows_1252(b).ok_or_else(|| {
                    let line = 1 + bytes[..i].iter().filter(|&&b| b == b'\n').count();
                    MeasureError::at(
                        file,
                        line,
                        format!(
                            "byte {} (0x{b:02X}) is neither UTF-8 text nor Windows-1252 text; \
                             save the file as CSV (UTF-8)",
                            i + 1
                        ),
                    )
                })
            })
            .collect(),
    }
}

/// The error of a file without bytes.
pub(crate) fn empty(file: &str) -> MeasureError {
    MeasureError::file(
        file,
        "the file is empty (0 bytes): was the export cut short, or the wrong file picked?",
    )
}

/// The character of a byte in Windows-1252; `None` for the five bytes it leaves undefined.
fn windows_1252(b: u8) -> Option<char> {
    const HIGH: [u16; 32] = [
        0x20AC, 0, 0x201A, 0x0192, 0x201E, 0x2026, 0x2020, 0x2021, 0x02C6, 0x2030, 0x0160, 0x2039,
        0x0152, 0, 0x017D, 0, 0, 0x2018, 0x2019, 0x201C, 0x201D, 0x2022, 0x2013, 0x2014, 0x02DC,
        0x2122, 0x0161, 0x203A, 0x0153, 0, 0x017E, 0x0178,
    ];
    match b {
        0x80..=0x9F => match HIGH[usize::from(b - 0x80)] {
            0 => None,
            c => char::from_u32(u32::from(c)),
        },
        _ => Some(char::from(b)),
    }
}

/// A line of the text, split into trimmed fields (quotes removed, trailing empty fields
/// dropped: scopes end rows with a separator).
pub(crate) struct Line<'a> {
    /// The 1-based line of the text.
    pub number: usize,
    pub fields: Vec<Cow<'a, str>>,
}

impl Line<'_> {
    /// Field `i`, when there is one.
    pub fn field(&self, i: usize) -> Option<&str> {
        self.fields.get(i).map(|f| f.as_ref())
    }
}

/// The lines of a text, with its separator.
pub(crate) struct Table<'a> {
    /// The lines that hold a field.
    pub lines: Vec<Line<'a>>,
    /// The separator between fields: `,`, `;` or a tab.
    pub separator: char,
}

/// The separator of a text: given by a spreadsheet's `sep=;` first line, else the first of
/// `;`, tab and `,` found outside quotes on the first line that holds any (a `;` or a tab
/// between fields leaves the comma to the numbers, as a European spreadsheet writes them).
fn separator(lines: &[(usize, &str)]) -> (char, bool) {
    if let Some((_, first)) = lines.first() {
        let first = first.trim();
        if let Some(sep) = first
            .strip_prefix("sep=")
            .or_else(|| first.strip_prefix("SEP="))
        {
            let mut chars = sep.chars();
            if let (Some(c), None) = (chars.next(), chars.next()) {
                return (c, true);
            }
        }
    }
    for (_, line) in lines {
        let mut quoted = false;
        let (mut semicolons, mut tabs, mut commas) = (0, 0, 0);
        for c in line.chars() {
            match c {
                '"' => quoted = !quoted,
                ';' if !quoted => semicolons += 1,
                '\t' if !quoted => tabs += 1,
                ',' if !quoted => commas += 1,
                _ => {}
            }
        }
        if semicolons > 0 {
            return (';', false);
        }
        if tabs > 0 {
            return ('\t', false);
        }
        if commas > 0 {
            return (',', false);
        }
    }
    (',', false)
}

/// The fields of one line: split at `separator` outside double quotes (`""` in a quoted
/// field is a quote), each trimmed and stripped of its quotes.
fn fields(line: &str, separator: char) -> Vec<Cow<'_, str>> {
    let mut out = Vec::new();
    let mut rest = line;
    loop {
        let trimmed = rest.trim_start_matches([' ', '\r']);
        let (field, next) = if let Some(body) = trimmed.strip_prefix('"') {
            // A quoted field: up to the closing quote (the rest of the line without one).
            let mut end = None;
            let mut escaped = false;
            let mut chars = body.char_indices().peekable();
            while let Some((i, c)) = chars.next() {
                if c == '"' {
                    if chars.peek().is_some_and(|&(_, c)| c == '"') {
                        chars.next();
                        escaped = true;
                    } else {
                        end = Some(i);
                        break;
                    }
                }
            }
            let (inner, after) = match end {
                Some(i) => (&body[..i], &body[i + 1..]),
                None => (body, ""),
            };
            let field: Cow<'_, str> = if escaped {
                Cow::Owned(inner.replace("\"\"", "\""))
            } else {
                Cow::Borrowed(inner)
            };
            // Text after the closing quote up to the separator is dropped.
            let next = after
                .find(separator)
                .map(|i| &after[i + separator.len_utf8()..]);
            (field, next)
        } else {
            match trimmed.find(separator) {
                Some(i) => (
                    Cow::Borrowed(&trimmed[..i]),
                    Some(&trimmed[i + separator.len_utf8()..]),
                ),
                None => (Cow::Borrowed(trimmed), None),
            }
        };
        out.push(match field {
            Cow::Borrowed(f) => Cow::Borrowed(f.trim().trim_matches('"').trim()),
            Cow::Owned(f) => Cow::Owned(f.trim().to_string()),
        });
        match next {
            Some(next) => rest = next,
            None => break,
        }
    }
    while out.last().is_some_and(|f| f.is_empty()) {
        out.pop();
    }
    out
}

/// A number written with a decimal comma (`-3,5e-03`: one comma, no point), as a number
/// with a decimal point.
fn comma_number(field: &str) -> Option<String> {
    if field.contains('.') || field.matches(',').count() != 1 {
        return None;
    }
    let text = field.replace(',', ".");
    text.parse::<f64>().is_ok().then_some(text)
}

/// A number written with thousands separators (`1,500`, `-12,345.25`, `1,000,000e-3`: 1 to 3
/// digits, not starting with 0, then groups of a comma and 3 digits, then an optional
/// fraction and exponent), without them.
fn grouped_number(field: &str) -> Option<String> {
    let body = field.strip_prefix(['+', '-']).unwrap_or(field);
    let end = body.find(['.', 'e', 'E']).unwrap_or(body.len());
    let mut groups = body[..end].split(',');
    let first = groups.next()?;
    let mut count = 0;
    for g in groups {
        if g.len() != 3 || !g.bytes().all(|b| b.is_ascii_digit()) {
            return None;
        }
        count += 1;
    }
    if count == 0
        || !(1..=3).contains(&first.len())
        || first.starts_with('0')
        || !first.bytes().all(|b| b.is_ascii_digit())
    {
        return None;
    }
    let text = field.replace(',', "");
    text.parse::<f64>().is_ok().then_some(text)
}

/// A field that a decimal comma and a thousands separator would read alike (`1,500`).
fn ambiguous(field: &str) -> bool {
    comma_number(field).is_some() && grouped_number(field).is_some()
}

/// Split a text into lines of fields: a byte-order mark dropped; the separator as
/// [`separator`] finds it; empty lines (and, with `comments`, lines starting with `#`) left
/// out. A number with a decimal comma (`1,5`, from a `;`- or tab-separated export, or quoted
/// in a comma-separated one) is read as a number when the file writes no number with a
/// decimal point, and one with thousands separators (`"1,500.25"`) when it writes no decimal
/// comma; otherwise the comma stays and the number is refused, the message saying why
/// ([`number_hint`]).
pub(crate) fn split(text: &str, comments: bool) -> Table<'_> {
    let text = text.strip_prefix('\u{feff}').unwrap_or(text);
    let raw: Vec<(usize, &str)> = text
        .lines()
        .enumerate()
        .map(|(i, l)| (i + 1, l))
        .filter(|(_, l)| !(l.trim().is_empty() || comments && l.trim_start().starts_with('#')))
        .collect();
    let (separator, declared) = separator(&raw);
    let raw = if declared { &raw[1..] } else { &raw[..] };
    let mut lines: Vec<Line<'_>> = raw
        .iter()
        .map(|&(number, line)| Line {
            number,
            fields: fields(line, separator),
        })
        .filter(|l| !l.fields.is_empty())
        .collect();
    // The file's decimal mark, from the numbers that only one mark reads: a comma (`0,5`,
    // `1234,5`, `-3,0e-3`) or a point (`0.5`, `1,500.25`). Commas are then decimal commas,
    // or thousands separators; with both marks, or with only numbers that read either way
    // (`1,500`), they are left and the number refused ([`number_hint`]).
    let fields = || lines.iter().flat_map(|l| &l.fields);
    if fields().any(|f| f.contains(',')) {
        let decimal_comma = fields().any(|f| comma_number(f).is_some() && !ambiguous(f));
        let decimal_point = fields()
            .any(|f| f.contains('.') && (f.parse::<f64>().is_ok() || grouped_number(f).is_some()));
        let read: Option<fn(&str) -> Option<String>> = match (decimal_comma, decimal_point) {
            (true, false) => Some(comma_number),
            (false, true) => Some(grouped_number),
            _ => None,
        };
        if let Some(read) = read {
            for field in lines.iter_mut().flat_map(|l| &mut l.fields) {
                if let Some(number) = read(field) {
                    *field = Cow::Owned(number);
                }
            }
        }
    }
    Table { lines, separator }
}

/// Why a field that holds a comma is not a number, as its file was read ([`split`]).
pub(crate) fn number_hint(text: &str) -> String {
    if !text.contains(',') {
        return String::new();
    }
    let shown = |t: Option<String>| {
        t.and_then(|t| t.parse::<f64>().ok())
            .map_or_else(String::new, |x| x.to_string())
    };
    if ambiguous(text) {
        format!(
            ": {} with a decimal comma, {} with a thousands separator, and no other number of \
             the file tells which; write it with a decimal point",
            shown(comma_number(text)),
            shown(grouped_number(text))
        )
    } else if comma_number(text).is_some() || grouped_number(text).is_some() {
        ": the file writes numbers with a decimal point and others with a decimal comma, so \
         which a comma is (decimal or thousands) is not clear"
            .to_string()
    } else {
        ": a comma is read as a decimal comma or as thousands separators, and this is neither"
            .to_string()
    }
}

/// The name of a separator for messages.
pub(crate) fn separator_name(separator: char) -> &'static str {
    match separator {
        ',' => "commas",
        ';' => "semicolons",
        '\t' => "tabs",
        _ => "its separator",
    }
}

/// Why a row has more fields than its header gives: in a file separated by commas, decimal
/// commas that are not quoted split numbers in two.
pub(crate) fn extra_fields(
    file: &str,
    line: &Line<'_>,
    expected: usize,
    separator: char,
) -> Result<(), MeasureError> {
    if line.fields.len() <= expected {
        return Ok(());
    }
    let cause = if separator == ',' {
        ": are these numbers written with decimal commas? In a file separated by commas they \
         cannot be told from the separators; save it with ';' between the fields (or with \
         decimal points)"
    } else {
        ""
    };
    Err(MeasureError::at(
        file,
        line.number,
        format!(
            "{} fields separated by {}, where the header gives {expected}{cause}",
            line.fields.len(),
            separator_name(separator)
        ),
    ))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn texts(table: &Table<'_>) -> Vec<Vec<String>> {
        table
            .lines
            .iter()
            .map(|l| l.fields.iter().map(|f| f.to_string()).collect())
            .collect()
    }

    #[test]
    fn separators_quotes_and_decimal_commas() {
        let t = split("t;u\n0,5;-1,25e-3;\n", false);
        assert_eq!(t.separator, ';');
        assert_eq!(texts(&t), [vec!["t", "u"], vec!["0.5", "-1.25e-3"]]);
        let t = split("t\tu\r\n0,5\t1\r\n", false);
        assert_eq!(t.separator, '\t');
        assert_eq!(texts(&t), [vec!["t", "u"], vec!["0.5", "1"]]);
        let t = split("\"t\",\"u\"\n\"-3,0E-03\",\"1,5\"\n", false);
        assert_eq!(texts(&t), [vec!["t", "u"], vec!["-3.0E-03", "1.5"]]);
        // A quote inside a quoted field; a declared separator.
        let t = split("sep=;\n\"a \"\"b\"\"\";c\n", false);
        assert_eq!(texts(&t), [vec!["a \"b\"", "c"]]);
        // Points and commas in one file: the commas stay.
        let t = split("t;u\n0.5;1,5\n", false);
        assert_eq!(texts(&t), [vec!["t", "u"], vec!["0.5", "1,5"]]);
        // 1,500 is a decimal comma beside 0,5, thousands beside 0.5, and either alone.
        let t = split("t;u\n1,500;0,5\n", false);
        assert_eq!(texts(&t)[1], ["1.500", "0.5"]);
        let t = split("t,u\n\"1,500\",0.5\n\"-12,345.5\",1\n", false);
        assert_eq!(texts(&t)[1..], [vec!["1500", "0.5"], vec!["-12345.5", "1"]]);
        let t = split("t;u\n1,500;2\n", false);
        assert_eq!(texts(&t)[1], ["1,500", "2"]);
        assert_eq!(
            number_hint("1,500"),
            ": 1.5 with a decimal comma, 1500 with a thousands separator, and no other number \
             of the file tells which; write it with a decimal point"
        );
        assert!(number_hint("1,5").contains("decimal point and others with a decimal comma"));
        assert!(number_hint("1.234,5").contains("neither"));
        assert_eq!(number_hint("abc"), "");
        // Comments of an amplitude table.
        let t = split("# R = 71,5; x\nf,U\n", true);
        assert_eq!(t.separator, ',');
        assert_eq!(texts(&t), [vec!["f", "U"]]);
    }

    #[test]
    fn bytes_are_decoded_or_refused_with_their_cause() {
        assert_eq!(decode(b"t,u\n", "a.csv").unwrap(), "t,u\n");
        assert_eq!(decode(b"t (\xB5s),u\n", "a.csv").unwrap(), "t (µs),u\n");
        assert_eq!(decode(b"\x80\x9F", "a.csv").unwrap(), "€Ÿ");
        let utf16: Vec<u8> = [0xFF, 0xFE]
            .into_iter()
            .chain("t\tµ\n".encode_utf16().flat_map(u16::to_le_bytes))
            .collect();
        assert_eq!(decode(&utf16, "a.csv").unwrap(), "t\tµ\n");
        let e = decode(b"", "a.csv").unwrap_err().to_string();
        assert!(e.starts_with("a.csv: the file is empty"), "{e}");
        let e = decode(b"\x89PNG\r\n\x1a\n\0\0", "a.csv")
            .unwrap_err()
            .to_string();
        assert!(e.contains("byte 9 is 0") && e.contains("binary"), "{e}");
        let e = decode(b"t\n\x81", "a.csv").unwrap_err().to_string();
        assert!(e.starts_with("a.csv: line 2: byte 3 (0x81)"), "{e}");
        let e = decode(&utf16[..5], "a.csv").unwrap_err().to_string();
        assert!(e.contains("UTF-16"), "{e}");
    }
}
