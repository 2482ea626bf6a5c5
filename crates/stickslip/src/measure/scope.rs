//! The readers of scope exports: the format detected from the header, then parsed.

use super::error::{quote, MeasureError};
use super::record::{Record, ScopeFormat};
use super::text::{extra_fields, number_hint, split, Line, Table};

/// A finite number in field `column` (0-based) of `line`.
fn number(file: &str, line: &Line<'_>, column: usize) -> Result<f64, MeasureError> {
    let Some(text) = line.fields.get(column) else {
        return Err(MeasureError::at(
            file,
            line.number,
            format!(
                "{} fields, but column {} is needed",
                line.fields.len(),
                column + 1
            ),
        ));
    };
    match text.parse::<f64>() {
        Ok(v) if v.is_finite() => Ok(v),
        _ => Err(MeasureError::at(
            file,
            line.number,
            format!(
                "{} in column {} is not a finite number{}",
                quote(text),
                column + 1,
                number_hint(text)
            ),
        )),
    }
}

/// The scale to seconds of a time column's name: `t`, `time`, `second`, `seconds`, with or
/// without a unit `s`, `ms`, `µs` (`us`) or `ns` after `_` or in brackets (`time (µs)`,
/// `t[ms]`, `time_s`); `None` for another name.
fn time_scale(name: &str) -> Option<f64> {
    let n: String = name
        .chars()
        .filter(|c| !c.is_whitespace())
        .collect::<String>()
        .to_lowercase();
    if matches!(n.as_str(), "second" | "seconds") {
        return Some(1.0);
    }
    let (base, unit) = match n.find(['(', '[', '_']) {
        Some(i) => {
            let unit = n[i + 1..].trim_end_matches([')', ']']);
            let closed = match &n[i..i + 1] {
                "(" => n.ends_with(')'),
                "[" => n.ends_with(']'),
                _ => !n.ends_with([')', ']']),
            };
            if !closed {
                return None;
            }
            (&n[..i], unit)
        }
        None => (n.as_str(), "s"),
    };
    if !matches!(base, "t" | "time") {
        return None;
    }
    match unit {
        "s" => Some(1.0),
        "ms" => Some(1e-3),
        "µs" | "μs" | "us" => Some(1e-6),
        "ns" => Some(1e-9),
        _ => None,
    }
}

fn is_time_name(name: &str) -> bool {
    time_scale(name).is_some()
}

/// Detect the format of a scope export from its first lines.
pub fn detect(text: &str) -> Option<ScopeFormat> {
    detect_lines(&split(text, false).lines)
}

fn detect_lines(lines: &[Line<'_>]) -> Option<ScopeFormat> {
    let first = lines.first()?;
    let head = first.fields[0].to_ascii_lowercase();
    let has = |name: &str| first.fields.iter().any(|f| f.eq_ignore_ascii_case(name));
    if head == "x" && has("start") && has("increment") {
        return Some(ScopeFormat::Rigol);
    }
    if head == "x-axis" {
        return Some(ScopeFormat::Keysight);
    }
    if head == "record length" {
        let tek = first.fields.len() >= 5 && first.fields[3].parse::<f64>().is_ok();
        return Some(if tek {
            ScopeFormat::Tektronix
        } else {
            ScopeFormat::Siglent
        });
    }
    if first.fields.iter().any(|f| is_time_name(f)) {
        return Some(ScopeFormat::Plain);
    }
    None
}

/// Read a scope export: detect its format from the header ([`detect`]) and parse it.
/// `file` names the text in messages. Fields are separated by commas, semicolons or tabs
/// (the first of `;`, tab and `,` on the first line, or a spreadsheet's `sep=;` line),
/// quoted or not; a decimal comma is read in a file that writes no decimal point (and
/// thousands separators in one that writes no decimal comma).
///
/// # Errors
/// An empty file, an unknown header, a field that is not a number (naming the line), times
/// that do not increase (naming the line), fewer than [`super::MIN_SAMPLES`] samples, rows
/// with too few fields or more than the header gives (decimal commas between commas).
pub fn read_scope(text: &str, file: &str) -> Result<Record, MeasureError> {
    let body = text.strip_prefix('\u{feff}').unwrap_or(text);
    if body.is_empty() {
        return Err(super::text::empty(file));
    }
    if body.trim().is_empty() {
        return Err(MeasureError::file(
            file,
            format!(
                "the file holds no text, only {} blank line(s): was the export cut short?",
                body.lines().count().max(1)
            ),
        ));
    }
    let table = split(text, false);
    let format = detect_lines(&table.lines).ok_or_else(|| {
        MeasureError::file(
            file,
            "not a scope export this reader knows: the header must be Rigol's (X,CH1,…,Start,\
             Increment), Tektronix's or Siglent's (Record Length,…), Keysight's (x-axis,1,2) \
             or a row of column names with a time column (t, time, time_s, time (µs), second)",
        )
    })?;
    match format {
        ScopeFormat::Rigol => rigol(&table, file),
        ScopeFormat::Keysight => keysight(&table, file),
        ScopeFormat::Tektronix => tektronix(&table, file),
        ScopeFormat::Siglent => siglent(&table, file),
        _ => plain(&table, file),
    }
}

/// Rows of `time, v1, v2, …` after the header lines, the time in column `time_column` and
/// `count` channels after it.
struct Columns {
    time: Vec<f64>,
    lines: Vec<usize>,
    values: Vec<Vec<f64>>,
}

/// The rows' times and `count` channels from column `first_value` on; a row with more than
/// `width` fields is refused ([`extra_fields`]).
fn rows(
    file: &str,
    table: &Table<'_>,
    rows: &[Line<'_>],
    count: usize,
    width: usize,
    time: impl Fn(&Line<'_>) -> Result<f64, MeasureError>,
    first_value: usize,
) -> Result<Columns, MeasureError> {
    let mut out = Columns {
        time: Vec::with_capacity(rows.len()),
        lines: Vec::with_capacity(rows.len()),
        values: vec![Vec::with_capacity(rows.len()); count],
    };
    for line in rows {
        extra_fields(file, line, width, table.separator)?;
        out.time.push(time(line)?);
        out.lines.push(line.number);
        for (c, values) in out.values.iter_mut().enumerate() {
            values.push(number(file, line, first_value + c)?);
        }
    }
    Ok(out)
}

fn header_line<'a, 'b>(
    lines: &'b [Line<'a>],
    index: usize,
    file: &str,
    what: &str,
) -> Result<&'b Line<'a>, MeasureError> {
    lines
        .get(index)
        .ok_or_else(|| MeasureError::file(file, format!("the file ends before {what}")))
}

fn rigol(table: &Table<'_>, file: &str) -> Result<Record, MeasureError> {
    let lines = &table.lines;
    let head = &lines[0];
    let start_column = head
        .fields
        .iter()
        .position(|f| f.eq_ignore_ascii_case("start"))
        .expect("detected by its Start column");
    let names: Vec<String> = head.fields[1..start_column]
        .iter()
        .map(|s| s.to_string())
        .collect();
    if names.is_empty() {
        return Err(MeasureError::at(
            file,
            head.number,
            "no channel before Start",
        ));
    }
    let units_line = header_line(lines, 1, file, "the units row (Sequence,Volt,…)")?;
    extra_fields(file, units_line, head.fields.len(), table.separator)?;
    let units: Vec<String> = (0..names.len())
        .map(|c| unit(units_line.field(c + 1)))
        .collect();
    let start = number(file, units_line, start_column)?;
    let increment = number(file, units_line, start_column + 1)?;
    if !(increment > 0.0) {
        return Err(MeasureError::at(
            file,
            units_line.number,
            format!("the increment {increment} s must be > 0"),
        ));
    }
    let columns = rows(
        file,
        table,
        &lines[2..],
        names.len(),
        1 + names.len(),
        |line| {
            let index = number(file, line, 0)?;
            Ok(start + index * increment)
        },
        1,
    )?;
    let metadata = vec![
        ("Start".to_string(), start.to_string()),
        ("Increment".to_string(), increment.to_string()),
    ];
    finish(file, ScopeFormat::Rigol, columns, names, units, metadata)
}

fn unit(text: Option<&str>) -> String {
    match text.map(str::trim) {
        None | Some("") => "V".into(),
        Some(u) if u.eq_ignore_ascii_case("volt") || u.eq_ignore_ascii_case("value") => "V".into(),
        Some(u) => u.to_string(),
    }
}

fn finish(
    file: &str,
    format: ScopeFormat,
    columns: Columns,
    names: Vec<String>,
    units: Vec<String>,
    metadata: Vec<(String, String)>,
) -> Result<Record, MeasureError> {
    let channels = names
        .into_iter()
        .zip(units)
        .zip(columns.values)
        .map(|((n, u), v)| (n, u, v))
        .collect();
    Record::build(
        file,
        format,
        columns.time,
        &columns.lines,
        channels,
        metadata,
    )
}

fn keysight(table: &Table<'_>, file: &str) -> Result<Record, MeasureError> {
    let lines = &table.lines;
    let names: Vec<String> = lines[0].fields[1..].iter().map(|s| s.to_string()).collect();
    if names.is_empty() {
        return Err(MeasureError::at(
            file,
            lines[0].number,
            "no channel after x-axis",
        ));
    }
    let units_line = header_line(lines, 1, file, "the units row (second,Volt,…)")?;
    let units = (0..names.len())
        .map(|c| unit(units_line.field(c + 1)))
        .collect();
    let width = 1 + names.len();
    let columns = rows(
        file,
        table,
        &lines[2..],
        names.len(),
        width,
        |l| number(file, l, 0),
        1,
    )?;
    finish(file, ScopeFormat::Keysight, columns, names, units, vec![])
}

fn tektronix(table: &Table<'_>, file: &str) -> Result<Record, MeasureError> {
    let lines = &table.lines;
    let mut metadata = Vec::new();
    for line in lines {
        if let (Some(key), Some(value)) = (line.field(0), line.field(1)) {
            if !key.is_empty() && !value.is_empty() {
                metadata.push((key.to_string(), value.to_string()));
            }
        }
    }
    let find = |key: &str| {
        metadata
            .iter()
            .find(|(k, _)| k.eq_ignore_ascii_case(key))
            .map(|(_, v)| v.clone())
    };
    let name = find("Source").unwrap_or_else(|| "CH1".into());
    let unit = unit(find("Vertical Units").as_deref());
    let columns = rows(file, table, lines, 1, 5, |l| number(file, l, 3), 4)?;
    finish(
        file,
        ScopeFormat::Tektronix,
        columns,
        vec![name],
        vec![unit],
        metadata,
    )
}

fn siglent(table: &Table<'_>, file: &str) -> Result<Record, MeasureError> {
    let lines = &table.lines;
    let Some(header) = lines
        .iter()
        .position(|l| l.fields[0].eq_ignore_ascii_case("second"))
    else {
        return Err(MeasureError::file(
            file,
            "no row Second,Volt (or Second,Value) before the samples",
        ));
    };
    let metadata: Vec<(String, String)> = lines[..header]
        .iter()
        .map(|l| (l.fields[0].to_string(), l.fields[1..].join(",")))
        .collect();
    let count = lines[header].fields.len() - 1;
    if count == 0 {
        return Err(MeasureError::at(
            file,
            lines[header].number,
            "no channel after Second",
        ));
    }
    // Channel names from `Source,CH1,CH2` or `Vertical Scale,CH1: 0.05,CH2: 0.1` when given.
    let named: Vec<String> = lines[..header]
        .iter()
        .find(|l| l.fields[0].eq_ignore_ascii_case("source"))
        .or_else(|| {
            lines[..header]
                .iter()
                .find(|l| l.fields[0].eq_ignore_ascii_case("vertical scale"))
        })
        .map(|l| {
            l.fields[1..]
                .iter()
                .map(|f| f.split(':').next().unwrap_or("").trim().to_string())
                .filter(|f| !f.is_empty())
                .collect()
        })
        .unwrap_or_default();
    let names = if named.len() == count {
        named
    } else {
        (1..=count).map(|c| format!("CH{c}")).collect()
    };
    let units = (0..count)
        .map(|c| unit(lines[header].field(c + 1)))
        .collect();
    let columns = rows(
        file,
        table,
        &lines[header + 1..],
        count,
        count + 1,
        |l| number(file, l, 0),
        1,
    )?;
    finish(file, ScopeFormat::Siglent, columns, names, units, metadata)
}

fn plain(table: &Table<'_>, file: &str) -> Result<Record, MeasureError> {
    let lines = &table.lines;
    let head = &lines[0];
    let (time_column, scale) = head
        .fields
        .iter()
        .enumerate()
        .find_map(|(c, f)| time_scale(f).map(|s| (c, s)))
        .expect("detected by its time column");
    let mut names = Vec::new();
    let mut units = Vec::new();
    let mut columns_of = Vec::new();
    for (c, name) in head.fields.iter().enumerate() {
        if c == time_column {
            continue;
        }
        if name.is_empty() {
            return Err(MeasureError::at(
                file,
                head.number,
                format!("column {} has no name", c + 1),
            ));
        }
        // `u_V`, `CH1(V)`, `CH1 [V]` carry their unit.
        let (n, u) = if let Some(open) = name.find(['(', '[']) {
            (
                name[..open].trim().to_string(),
                name[open + 1..]
                    .trim_end_matches([')', ']'])
                    .trim()
                    .to_string(),
            )
        } else {
            (name.to_string(), "V".to_string())
        };
        names.push(n);
        units.push(if u.is_empty() { "V".into() } else { u });
        columns_of.push(c);
    }
    if names.is_empty() {
        return Err(MeasureError::at(
            file,
            head.number,
            "no channel beside the time column",
        ));
    }
    let mut out = Columns {
        time: Vec::new(),
        lines: Vec::new(),
        values: vec![Vec::new(); names.len()],
    };
    for line in &lines[1..] {
        extra_fields(file, line, head.fields.len(), table.separator)?;
        out.time.push(scale * number(file, line, time_column)?);
        out.lines.push(line.number);
        for (values, &c) in out.values.iter_mut().zip(&columns_of) {
            values.push(number(file, line, c)?);
        }
    }
    finish(file, ScopeFormat::Plain, out, names, units, vec![])
}
