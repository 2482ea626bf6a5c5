//! The report directory: figures (PNG + SVG), data (CSV), `index.html` and `summary.json`.
//!
//! Everything is written first into a private staging directory next to the target and moved
//! into place file by file at the end, so an interrupted run leaves no half-written file and
//! files in the target that are not part of the report are left alone.

use crate::output::check_interrupt;
use crate::plot::Figure;
use anyhow::{Context, Result};
use serde_json::{Map, Value};
use std::fmt::Write as _;
use std::path::{Path, PathBuf};
use stickslip::experiment::PhysicalUnits;
use stickslip::report::{Table, TrajectoryColumns, TrajectorySample};
use stickslip::solver::Sample;

/// One section of the report: a figure or a table of the paper, with its caption.
#[derive(Debug, Default)]
pub struct Section {
    /// Anchor and file stem, e.g. `fig3`.
    pub id: String,
    /// Heading, e.g. "Fig. 3 — traces, spectra and X-Y loops".
    pub title: String,
    /// Caption (HTML allowed: it is our own text).
    pub caption: String,
    /// Figure files (stems; each written as `.png` and `.svg`).
    pub figures: Vec<String>,
    /// Data files (CSV) behind the section.
    pub data: Vec<String>,
    /// Tables shown in the page: (header, rows).
    pub tables: Vec<(Vec<String>, Vec<Vec<String>>)>,
}

/// A chapter heading of the report, shown before the section at index `before`.
#[derive(Debug, Default)]
pub struct Chapter {
    /// Index in [`Report::sections`] of the chapter's first section.
    pub before: usize,
    /// Anchor.
    pub id: String,
    /// Heading.
    pub title: String,
    /// Introduction (HTML allowed: it is our own text).
    pub intro: String,
}

/// A report being written.
pub struct Report {
    target: PathBuf,
    staging: PathBuf,
    files: Vec<String>,
    /// The sections, in order.
    pub sections: Vec<Section>,
    /// Chapter headings between the sections (the paper's figures come first, without one).
    pub chapters: Vec<Chapter>,
    /// Key numbers for `summary.json`.
    pub summary: Map<String, Value>,
}

impl Report {
    /// Start a report that will end up in `target` (created if missing).
    pub fn create(target: &Path) -> Result<Self> {
        let parent = target
            .parent()
            .filter(|p| !p.as_os_str().is_empty())
            .unwrap_or(Path::new("."));
        if !parent.is_dir() {
            crate::output::usage!(
                "cannot write the report to {}: directory {} does not exist",
                target.display(),
                parent.display()
            );
        }
        if target.exists() && !target.is_dir() {
            crate::output::usage!("--out {} exists and is not a directory", target.display());
        }
        let name = target
            .file_name()
            .map(|n| n.to_string_lossy().into_owned())
            .unwrap_or_else(|| "report".into());
        let staging = parent.join(format!(".partial-{}-{name}", std::process::id()));
        std::fs::create_dir_all(&staging)
            .with_context(|| format!("cannot create {}", staging.display()))?;
        Ok(Self {
            target: target.to_path_buf(),
            staging,
            files: Vec::new(),
            sections: Vec::new(),
            chapters: Vec::new(),
            summary: Map::new(),
        })
    }

    /// Start a chapter: the sections added from now on belong to it.
    pub fn chapter(&mut self, id: &str, title: &str, intro: &str) {
        self.chapters.push(Chapter {
            before: self.sections.len(),
            id: id.into(),
            title: title.into(),
            intro: intro.into(),
        });
    }

    /// Write a figure as `stem.png` and `stem.svg`.
    pub fn figure(&mut self, stem: &str, figure: &Figure) -> Result<()> {
        check_interrupt()?;
        for ext in ["png", "svg"] {
            let name = format!("{stem}.{ext}");
            figure.render(&self.staging.join(&name))?;
            self.files.push(name);
        }
        Ok(())
    }

    /// Write a CSV file from a header and rows of already formatted cells.
    pub fn csv(&mut self, name: &str, header: &[&str], rows: &[Vec<String>]) -> Result<()> {
        check_interrupt()?;
        let mut w = csv::Writer::from_path(self.staging.join(name))
            .with_context(|| format!("cannot write {name}"))?;
        w.write_record(header)?;
        for r in rows {
            w.write_record(r)?;
        }
        w.flush()?;
        self.files.push(name.to_string());
        Ok(())
    }

    /// Write a library result's table as a CSV file, its columns and cells the library's
    /// (as `stickslip … --out` writes them).
    pub fn table<T: Table>(&mut self, name: &str, table: &T) -> Result<()> {
        self.tables(name, &[], [(Vec::new(), table)])
    }

    /// Write several tables of one shape (one per value of the figure) as one CSV file: the
    /// `leading` columns the figure adds (which β, which model), each part's cells for them,
    /// then the table's own columns and cells.
    ///
    /// # Errors
    /// A part whose columns differ from the first's, or whose leading cells are not one per
    /// leading column (a mistake in the figure, not in its input); a failed write.
    pub fn tables<'a, T: Table + 'a>(
        &mut self,
        name: &str,
        leading: &[&str],
        parts: impl IntoIterator<Item = (Vec<String>, &'a T)>,
    ) -> Result<()> {
        let mut header: Option<Vec<String>> = None;
        let mut rows = Vec::new();
        for (cells, table) in parts {
            let columns = table.columns();
            match &header {
                None => header = Some(columns),
                Some(h) => anyhow::ensure!(
                    *h == columns,
                    "{name}: the tables have different columns ({} and {})",
                    h.join(","),
                    columns.join(",")
                ),
            }
            anyhow::ensure!(
                cells.len() == leading.len(),
                "{name}: {} leading cells for the columns {}",
                cells.len(),
                leading.join(",")
            );
            for i in 0..table.len() {
                let mut row = cells.clone();
                row.extend(table.row(i));
                rows.push(row);
            }
        }
        let Some(columns) = header else {
            anyhow::bail!("{name}: no table to write");
        };
        let header: Vec<&str> = leading
            .iter()
            .copied()
            .chain(columns.iter().map(String::as_str))
            .collect();
        self.csv(name, &header, &rows)
    }

    /// Write a stacked figure as `stem.png` and `stem.svg`.
    pub fn stack(&mut self, stem: &str, stack: &crate::plot::Stack) -> Result<()> {
        check_interrupt()?;
        for ext in ["png", "svg"] {
            let name = format!("{stem}.{ext}");
            stack.render(&self.staging.join(&name))?;
            self.files.push(name);
        }
        Ok(())
    }

    /// Write `index.html` and `summary.json`, then move every file into the target directory.
    pub fn finish(mut self) -> Result<PathBuf> {
        check_interrupt()?;
        let html = self.html();
        std::fs::write(self.staging.join("index.html"), html)?;
        self.files.push("index.html".into());
        let summary = serde_json::to_string_pretty(&Value::Object(self.summary.clone()))?;
        std::fs::write(self.staging.join("summary.json"), summary + "\n")?;
        self.files.push("summary.json".into());
        check_interrupt()?;
        std::fs::create_dir_all(&self.target)
            .with_context(|| format!("cannot create {}", self.target.display()))?;
        for f in &self.files {
            std::fs::rename(self.staging.join(f), self.target.join(f))
                .with_context(|| format!("cannot move {f} into {}", self.target.display()))?;
        }
        let _ = std::fs::remove_dir_all(&self.staging);
        Ok(self.target.clone())
    }

    fn html(&self) -> String {
        let mut h = String::new();
        h.push_str(
            "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n\
             <title>stickslip: the paper's figures, reproduced</title>\n<style>\n\
             body{font-family:sans-serif;max-width:1100px;margin:2em auto;padding:0 1em;color:#222;line-height:1.45}\n\
             img{max-width:100%;border:1px solid #ddd;margin:0.5em 0}\n\
             .fig{width:calc(100vw - 2em);margin-left:calc(50% - 50vw + 1em);overflow-x:auto;text-align:center}\n\
             .fig img{max-width:none;height:auto}\n\
             table{border-collapse:collapse;margin:0.8em 0}td,th{border:1px solid #ccc;padding:0.25em 0.6em;text-align:right}\n\
             th{background:#f4f4f4}td:first-child,th:first-child{text-align:left}\n\
             .caption{color:#333}.files{font-size:0.85em;color:#666}\n\
             nav ul{margin:0.3em 0 1em;padding-left:1.2em}nav li{margin:0.1em 0}nav b{display:block;margin-top:0.6em}\n\
             .nw{white-space:nowrap}\n\
             </style>\n</head>\n<body>\n",
        );
        h.push_str("<h1>The paper's figures, reproduced by stickslip</h1>\n");
        h.push_str(
            "<p>Xu, Fan, Wang and Jiang, <i>Nonlinear effect of forced harmonic oscillator subject \
             to sliding friction and simulation by a simple nonlinear circuit</i>. Every figure \
             below was computed by <code>stickslip reproduce</code> from the paper's circuit \
             (L = 11.5 mH, C = 0.02 µF, R = 68 Ω, diodes U<sub>t</sub> = 0.7 V, R<sub>D</sub> = \
             3.0 Ω). Simulated values come from the exact event-driven solver (PWL diodes) or \
             the stiff solver (Shockley diodes); where they differ from the paper's series \
             formula, the caption says so. The paper's Fig. 2 is not reproduced: it draws the \
             circuit and the PWL model of a diode, and computes nothing (the PWL diode pair's \
             I-V curve is Fig. 1 (b) here).</p>\n<nav>",
        );
        // A table of contents: one line per section, with its title, under its chapter.
        h.push_str("\n<ul>\n");
        for (k, s) in self.sections.iter().enumerate() {
            for c in self.chapters.iter().filter(|c| c.before == k) {
                let _ = write!(
                    h,
                    "</ul>\n<b><a href=\"#{}\">{}</a></b>\n<ul>\n",
                    c.id,
                    escape(&c.title)
                );
            }
            let _ = writeln!(h, "<li><a href=\"#{}\">{}</a></li>", s.id, escape(&s.title));
        }
        h.push_str("</ul>\n</nav>\n");
        for (k, s) in self.sections.iter().enumerate() {
            for c in self.chapters.iter().filter(|c| c.before == k) {
                let _ = write!(
                    h,
                    "<h1 id=\"{}\">{}</h1>\n<p>{}</p>\n",
                    c.id,
                    escape(&c.title),
                    c.intro
                );
            }
            let _ = write!(
                h,
                "<section id=\"{}\">\n<h2>{}</h2>\n",
                s.id,
                escape(&s.title)
            );
            // Each figure at its full size, wider than the text when it is wide (centred on
            // the window, scrolling sideways only in a window narrower than the figure).
            for f in &s.figures {
                let size = png_size(&self.staging.join(format!("{f}.png")))
                    .map(|(w, h)| format!(" width=\"{w}\" height=\"{h}\""))
                    .unwrap_or_default();
                let _ = writeln!(
                    h,
                    "<div class=\"fig\"><a href=\"{f}.svg\"><img src=\"{f}.png\"{size} \
                     alt=\"{f}\"></a></div>"
                );
            }
            for (header, rows) in &s.tables {
                h.push_str("<table>\n<tr>");
                for c in header {
                    let _ = write!(h, "<th>{}</th>", escape(c));
                }
                h.push_str("</tr>\n");
                for r in rows {
                    h.push_str("<tr>");
                    for c in r {
                        let _ = write!(h, "<td>{}</td>", escape(c));
                    }
                    h.push_str("</tr>\n");
                }
                h.push_str("</table>\n");
            }
            let _ = writeln!(h, "<p class=\"caption\">{}</p>", unbroken_flags(&s.caption));
            if !s.data.is_empty() || !s.figures.is_empty() {
                h.push_str("<p class=\"files\">Files: ");
                let mut names: Vec<String> = Vec::new();
                for f in &s.figures {
                    names.push(format!("<a href=\"{f}.png\">{f}.png</a>"));
                    names.push(format!("<a href=\"{f}.svg\">{f}.svg</a>"));
                }
                for d in &s.data {
                    names.push(format!("<a href=\"{d}\">{d}</a>"));
                }
                h.push_str(&names.join(", "));
                h.push_str("</p>\n");
            }
            h.push_str("</section>\n");
        }
        h.push_str("<p class=\"files\"><a href=\"summary.json\">summary.json</a> holds the key numbers.</p>\n</body>\n</html>\n");
        h
    }
}

/// Samples of a motion in the shape of `stickslip simulate --out` (the library's
/// [`TrajectoryColumns`] and [`TrajectorySample`] cells): `tau,y,v,drive,phase`, and with
/// physical units `t_s,uc_V,i_A,u_V`.
pub struct Samples {
    units: Option<PhysicalUnits>,
    samples: Vec<TrajectorySample>,
}

impl Samples {
    /// No samples yet, in `units` when the experiment has them.
    pub fn new(units: Option<PhysicalUnits>) -> Self {
        Self {
            units,
            samples: Vec::new(),
        }
    }

    /// Add the sample `s` of a solver, shown at time `tau` (its own, or shifted), under the
    /// drive `drive` (units of y).
    pub fn push(&mut self, tau: f64, s: &Sample, drive: f64) {
        self.samples.push(TrajectorySample {
            tau,
            y: s.y,
            v: s.v,
            drive,
            phase: s.phase,
            physical: self.units.map(|u| u.convert(tau, s.y, s.v, drive)),
        });
    }
}

impl Table for Samples {
    fn columns(&self) -> Vec<String> {
        TrajectoryColumns { units: self.units }
            .names()
            .into_iter()
            .map(String::from)
            .collect()
    }

    fn len(&self) -> usize {
        self.samples.len()
    }

    fn row(&self, i: usize) -> Vec<String> {
        self.samples[i].row()
    }
}

/// The width and height of a PNG file, from its header (IHDR).
fn png_size(path: &Path) -> Option<(u32, u32)> {
    use std::io::Read;
    let mut header = [0u8; 24];
    std::fs::File::open(path)
        .ok()?
        .read_exact(&mut header)
        .ok()?;
    if &header[..8] != b"\x89PNG\r\n\x1a\n" || &header[12..16] != b"IHDR" {
        return None;
    }
    let be =
        |i: usize| u32::from_be_bytes([header[i], header[i + 1], header[i + 2], header[i + 3]]);
    Some((be(16), be(20)))
}

impl Drop for Report {
    fn drop(&mut self) {
        let _ = std::fs::remove_dir_all(&self.staging);
    }
}

/// A caption whose command-line flags (`--v0-min`, `-8`) cannot break across lines: in
/// `<code>` the words that hold a hyphen go into a no-wrap span (the browser would break
/// after their hyphens).
fn unbroken_flags(caption: &str) -> String {
    let mut out = String::new();
    let mut rest = caption;
    while let Some(start) = rest.find("<code>") {
        let (before, after) = rest.split_at(start + "<code>".len());
        out.push_str(before);
        let end = after.find("</code>").unwrap_or(after.len());
        let words: Vec<String> = after[..end]
            .split(' ')
            .map(|w| {
                if w.contains('-') {
                    format!("<span class=\"nw\">{w}</span>")
                } else {
                    w.to_string()
                }
            })
            .collect();
        out.push_str(&words.join(" "));
        rest = &after[end..];
    }
    out.push_str(rest);
    out
}

/// Escape text for HTML.
pub fn escape(s: &str) -> String {
    s.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
}

/// A number with `digits` significant digits for tables.
pub fn sig(x: f64, digits: usize) -> String {
    if !x.is_finite() {
        return "—".into();
    }
    if x == 0.0 {
        return "0".into();
    }
    let mag = x.abs().log10().floor() as i32;
    let decimals = (digits as i32 - 1 - mag).max(0) as usize;
    format!("{x:.decimals$}")
}
