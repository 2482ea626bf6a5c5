//! Figures: panels of line, marker, bar and cell series, rendered to PNG or SVG (chosen by the
//! file's extension) with a bundled font, so rendering needs no system fonts.

use crate::output::AtomicFile;
use anyhow::{Context, Result};
use plotters::coord::types::RangedCoordf64;
use plotters::coord::Shift;
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};
use std::path::Path;
use std::sync::Once;

/// The bundled font (DejaVu Sans; licence in `assets/DejaVuSans-LICENSE.txt`).
static FONT: &[u8] = include_bytes!("../assets/DejaVuSans.ttf");
const FAMILY: &str = "sans-serif";

fn register_font() {
    static ONCE: Once = Once::new();
    ONCE.call_once(|| {
        for style in [
            FontStyle::Normal,
            FontStyle::Bold,
            FontStyle::Italic,
            FontStyle::Oblique,
        ] {
            if plotters::style::register_font(FAMILY, style, FONT).is_err() {
                panic!("the bundled font is not a valid TrueType font");
            }
        }
    });
}

/// A colour-blind-friendly palette (Okabe–Ito), one colour per series or per β.
pub const PALETTE: [RGBColor; 8] = [
    RGBColor(0, 114, 178),
    RGBColor(213, 94, 0),
    RGBColor(0, 158, 115),
    RGBColor(204, 121, 167),
    RGBColor(230, 159, 0),
    RGBColor(86, 180, 233),
    RGBColor(0, 0, 0),
    RGBColor(240, 228, 66),
];

/// What a series shows: each quantity has one colour and one way of being drawn in every
/// figure of the report, every `--plot` of the CLI, the lab and the notebook (the table is
/// `docs/plot-style.md`). Where one figure shows a quantity at several drive amplitudes,
/// the colour is the amplitude's (see `reproduce`'s `beta_color`) and the style stays.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Quantity {
    /// The drive U (or βcos(wτ+φ)): a thin grey line, under the response.
    Drive,
    /// The response u_C (or y): a 2-px blue line.
    Response,
    /// Where the motion stops: vermilion dots.
    Stops,
    /// A sweep's upward leg: filled blue dots.
    SweepUp,
    /// A sweep's downward leg: open vermilion squares.
    SweepDown,
    /// The paper's approximate formulas (its eqs. 11 and 13): dashed reddish purple.
    PaperTheory,
    /// The exact sliding orbit and the exact boundary β_c: solid black.
    ExactTheory,
    /// The fundamental A1: blue.
    Harmonic1,
    /// The third harmonic A3: vermilion.
    Harmonic3,
    /// A measured u_C (a scope record, a measured amplitude): black dots.
    Measured,
    /// A measured drive U (a scope record's drive channel): small grey dots.
    MeasuredDrive,
}

impl Quantity {
    /// The quantity's colour.
    pub fn color(self) -> RGBColor {
        match self {
            Quantity::Drive => DRIVE,
            Quantity::Response | Quantity::SweepUp | Quantity::Harmonic1 => PALETTE[0],
            Quantity::Stops | Quantity::SweepDown | Quantity::Harmonic3 => PALETTE[1],
            Quantity::PaperTheory => PALETTE[3],
            Quantity::ExactTheory | Quantity::Measured => INK,
            Quantity::MeasuredDrive => DRIVE,
        }
    }

    /// How the quantity is drawn.
    pub fn style(self) -> Style {
        match self {
            Quantity::Drive => Style::Line(1),
            Quantity::Response => Style::Line(2),
            Quantity::Stops => Style::Markers(3),
            Quantity::SweepUp | Quantity::Harmonic1 | Quantity::Harmonic3 => Style::Markers(3),
            Quantity::SweepDown => Style::Squares(5),
            Quantity::PaperTheory => Style::Dashed(2),
            Quantity::ExactTheory => Style::Line(2),
            Quantity::Measured => Style::Markers(2),
            Quantity::MeasuredDrive => Style::Markers(1),
        }
    }

    /// A series of this quantity.
    pub fn series(self, label: impl Into<String>, points: Vec<(f64, f64)>) -> Series {
        Series::new(label, points, self.color(), self.style())
    }
}

/// The drive's grey.
pub const DRIVE: RGBColor = RGBColor(120, 120, 120);
/// Black, for the exact theory and for legend entries that stand for a style, not for data.
pub const INK: RGBColor = RGBColor(0, 0, 0);

/// How a series is drawn.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Style {
    /// A polyline of this stroke width.
    Line(u32),
    /// A dashed polyline of this stroke width.
    Dashed(u32),
    /// Filled circles of this radius.
    Markers(u32),
    /// Hollow squares of this half-size.
    Squares(u32),
    /// Vertical bars from y = 0, of this width in data units.
    Bars(f64),
    /// Filled squares of this side in pixels, for clouds of many points (bifurcation
    /// diagrams).
    Dots(u32),
}

/// One data series.
#[derive(Debug, Clone)]
pub struct Series {
    /// Legend entry (empty: not in the legend).
    pub label: String,
    /// The points (x, y); non-finite points break a line.
    pub points: Vec<(f64, f64)>,
    /// Colour.
    pub color: RGBColor,
    /// Drawing style.
    pub style: Style,
}

impl Series {
    /// The same series in another colour (a quantity drawn once per drive amplitude).
    pub fn colored(mut self, color: RGBColor) -> Self {
        self.color = color;
        self
    }

    /// A series with a label, points, colour and style.
    pub fn new(
        label: impl Into<String>,
        points: Vec<(f64, f64)>,
        color: RGBColor,
        style: Style,
    ) -> Self {
        Self {
            label: label.into(),
            points,
            color,
            style,
        }
    }
}

/// A filled rectangle in data coordinates (for maps).
#[derive(Debug, Clone, Copy)]
pub struct Cell {
    /// Lower-left and upper-right corners.
    pub x: (f64, f64),
    /// Lower and upper y.
    pub y: (f64, f64),
    /// Fill colour.
    pub color: RGBColor,
}

/// One chart.
#[derive(Debug, Clone, Default)]
pub struct Panel {
    /// Title over the chart.
    pub title: String,
    /// x-axis label, with units.
    pub x_label: String,
    /// y-axis label, with units.
    pub y_label: String,
    /// Series, drawn in order.
    pub series: Vec<Series>,
    /// Filled cells, drawn under the series.
    pub cells: Vec<Cell>,
    /// Legend entries for cells: (label, colour).
    pub cell_legend: Vec<(String, RGBColor)>,
    /// x range; from the data when None.
    pub x_range: Option<(f64, f64)>,
    /// y range; from the data when None.
    pub y_range: Option<(f64, f64)>,
    /// Where the legend goes (None: no legend).
    pub legend: Option<Legend>,
    /// A colour bar at the right of the chart, for cells coloured by a value (None: none).
    pub color_bar: Option<ColorBar>,
    /// A logarithmic x axis (points with x ≤ 0 are left out).
    pub x_log: bool,
    /// A logarithmic y axis (points with y ≤ 0 are left out).
    pub y_log: bool,
    /// One unit of x as long as one unit of y (a phase plane): the plotting area shrinks
    /// along its longer side. Linear axes only.
    pub equal_aspect: bool,
}

/// The scale of cells coloured by a signed value, drawn as a bar beside the chart: white at
/// 0, blue below down to the bottom of the range, red above up to its top, each side on its
/// own linear scale (so that small positive values stay visible beside large negative ones).
#[derive(Debug, Clone)]
pub struct ColorBar {
    /// What the colour means, with units.
    pub label: String,
    /// The values at the bottom (≤ 0) and the top (≥ 0) of the bar; values beyond take the
    /// end colours.
    pub range: (f64, f64),
}

impl ColorBar {
    /// A bar for `values`: from the 2nd percentile of the negative ones (a long tail of
    /// strongly negative values is clipped to the end colour) to the largest; non-finite
    /// values are left out. Always includes 0, and always has both halves: without a
    /// positive value its top is as far above 0 as its bottom is below, so that the bar shows
    /// the colours a positive value would take (a map without red then says "none positive").
    pub fn for_values(label: &str, values: &[f64]) -> Self {
        let mut negative: Vec<f64> = values
            .iter()
            .copied()
            .filter(|v| v.is_finite() && *v < 0.0)
            .collect();
        negative.sort_by(f64::total_cmp);
        let lo = negative.get(negative.len() / 50).copied().unwrap_or(0.0);
        let hi = values
            .iter()
            .copied()
            .filter(|v| v.is_finite())
            .fold(0.0f64, f64::max);
        let range = if lo == 0.0 && hi == 0.0 {
            (-1.0, 1.0)
        } else if hi == 0.0 {
            (lo, -lo)
        } else {
            (lo, hi)
        };
        Self {
            label: label.to_string(),
            range,
        }
    }

    /// The colour of `value` on this bar's [`diverging`] scale (grey for NaN).
    pub fn color(&self, value: f64) -> RGBColor {
        let (lo, hi) = self.range;
        if value.is_nan() {
            RGBColor(160, 160, 160)
        } else if value < 0.0 {
            diverging(if lo < 0.0 { value / -lo } else { -1.0 })
        } else if value > 0.0 {
            diverging(if hi > 0.0 { value / hi } else { 1.0 })
        } else {
            diverging(0.0)
        }
    }
}

/// A diverging colour scale for signed values: t = −1 deep blue, 0 white, +1 deep red (the
/// ends of ColorBrewer's RdBu), clamped outside [−1, 1]; readable by colour-blind viewers.
pub fn diverging(t: f64) -> RGBColor {
    const STOPS: [(f64, (f64, f64, f64)); 5] = [
        (-1.0, (5.0, 48.0, 97.0)),
        (-0.5, (67.0, 147.0, 195.0)),
        (0.0, (247.0, 247.0, 247.0)),
        (0.5, (214.0, 96.0, 77.0)),
        (1.0, (103.0, 0.0, 31.0)),
    ];
    let t = t.clamp(-1.0, 1.0);
    let k = STOPS
        .windows(2)
        .position(|w| t <= w[1].0)
        .unwrap_or(STOPS.len() - 2);
    let ((t0, a), (t1, b)) = (STOPS[k], STOPS[k + 1]);
    let f = (t - t0) / (t1 - t0);
    let mix = |x: f64, y: f64| (x + (y - x) * f).round() as u8;
    RGBColor(mix(a.0, b.0), mix(a.1, b.1), mix(a.2, b.2))
}

/// The corner of a panel's plotting area tried first for its legend. The legend goes to the
/// first corner (this one, then upper right, upper left, lower right, lower left) where it
/// covers no pixel of data, and outside the plotting area, on its right, when every corner
/// covers some.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Legend {
    /// Upper left.
    UpperLeft,
    /// Upper right.
    UpperRight,
    /// Lower right.
    LowerRight,
    /// Lower left.
    LowerLeft,
    /// No preference: upper right first.
    Best,
}

/// Colour of each motion class in maps, the same in every figure.
pub fn class_color(class: stickslip::steady::MotionClass) -> RGBColor {
    use stickslip::steady::MotionClass;
    match class {
        MotionClass::Sliding => SLIDING,
        MotionClass::PeriodicStick => PALETTE[0],
        MotionClass::Undecided => PALETTE[1],
        MotionClass::Static => PALETTE[2],
        MotionClass::Chaotic => CHAOTIC,
        MotionClass::StickSlipCycle => PALETTE[0],
        MotionClass::PureSlipCycle => PALETTE[4],
        MotionClass::SteadySliding => SLIDING,
    }
}

/// The colour of the sliding class: a light grey that reads as "nothing happens here" under
/// the other classes, with a dark border in legends so that its swatch shows on white.
pub const SLIDING: RGBColor = RGBColor(218, 218, 218);

/// The colour of the chaotic class: a purple apart from the Okabe–Ito colours of the other
/// classes and of the boundary curves.
const CHAOTIC: RGBColor = RGBColor(117, 112, 179);

/// Panels on a grid.
#[derive(Debug, Clone)]
pub struct Figure {
    /// Panels, filled row by row.
    pub panels: Vec<Panel>,
    /// Panels per row.
    pub columns: usize,
    /// Size of one panel in pixels.
    pub panel_size: (u32, u32),
}

impl Figure {
    /// A figure of one panel of the given size.
    pub fn single(panel: Panel, size: (u32, u32)) -> Self {
        Self {
            panels: vec![panel],
            columns: 1,
            panel_size: size,
        }
    }

    /// Render to `path` (`.png` or `.svg`), atomically.
    pub fn render(&self, path: &Path) -> Result<()> {
        register_font();
        let rows = self.panels.len().div_ceil(self.columns.max(1)) as u32;
        let size = (
            self.panel_size.0 * self.columns as u32,
            self.panel_size.1 * rows.max(1),
        );
        let file = AtomicFile::create(path)?;
        let temp = file.temp_path().to_path_buf();
        let svg = path
            .extension()
            .and_then(|e| e.to_str())
            .is_some_and(|e| e.eq_ignore_ascii_case("svg"));
        let placements = if svg {
            let root = SVGBackend::new(&temp, size).into_drawing_area();
            let placements = self.draw(&root, rows)?;
            root.present().context("cannot write SVG")?;
            placements
        } else {
            let root = BitMapBackend::new(&temp, size).into_drawing_area();
            let placements = self.draw(&root, rows)?;
            root.present().context("cannot write PNG")?;
            placements
        };
        log_placements(path, placements);
        file.commit()
    }

    fn draw<DB: DrawingBackend>(
        &self,
        root: &DrawingArea<DB, Shift>,
        rows: u32,
    ) -> Result<Vec<LegendPlacement>>
    where
        DB::ErrorType: 'static,
    {
        root.fill(&WHITE).map_err(|e| anyhow::anyhow!("{e:?}"))?;
        let areas = root.split_evenly((rows as usize, self.columns.max(1)));
        let font = font_size(
            self.panel_size.0 * self.columns.max(1) as u32,
            self.panel_size,
        );
        let mut placements = Vec::new();
        for (panel, area) in self.panels.iter().zip(areas.iter()) {
            placements.extend(
                draw_panel(panel, area, font)
                    .map_err(|e| anyhow::anyhow!("cannot draw '{}': {e}", panel.title))?,
            );
        }
        Ok(placements)
    }
}

/// Panels stacked in one column, each with its own height (a main chart over a narrow one
/// sharing its x axis, say).
#[derive(Debug, Clone)]
pub struct Stack {
    /// Panels from top to bottom, with their heights in pixels.
    pub panels: Vec<(Panel, u32)>,
    /// Width in pixels.
    pub width: u32,
}

impl Stack {
    /// Render to `path` (`.png` or `.svg`), atomically.
    pub fn render(&self, path: &Path) -> Result<()> {
        register_font();
        let height: u32 = self.panels.iter().map(|(_, h)| h).sum();
        let size = (self.width, height.max(1));
        let file = AtomicFile::create(path)?;
        let temp = file.temp_path().to_path_buf();
        let svg = path
            .extension()
            .and_then(|e| e.to_str())
            .is_some_and(|e| e.eq_ignore_ascii_case("svg"));
        let placements = if svg {
            let root = SVGBackend::new(&temp, size).into_drawing_area();
            let placements = self.draw(&root)?;
            root.present().context("cannot write SVG")?;
            placements
        } else {
            let root = BitMapBackend::new(&temp, size).into_drawing_area();
            let placements = self.draw(&root)?;
            root.present().context("cannot write PNG")?;
            placements
        };
        log_placements(path, placements);
        file.commit()
    }

    fn draw<DB: DrawingBackend>(
        &self,
        root: &DrawingArea<DB, Shift>,
    ) -> Result<Vec<LegendPlacement>>
    where
        DB::ErrorType: 'static,
    {
        root.fill(&WHITE).map_err(|e| anyhow::anyhow!("{e:?}"))?;
        let top = self.panels.first().map_or(0, |(_, h)| *h);
        let font = font_size(self.width, (self.width, top));
        let mut placements = Vec::new();
        let mut rest = root.clone();
        let mut areas = Vec::new();
        for (i, (_, h)) in self.panels.iter().enumerate() {
            areas.push(if i + 1 == self.panels.len() {
                rest.clone()
            } else {
                let (top, bottom) = rest.split_vertically(*h);
                rest = bottom;
                top
            });
        }
        // One room for legends right of every plotting area, so that the x axes line up.
        let mut floor = 0;
        for ((panel, _), area) in self.panels.iter().zip(&areas) {
            let (_, reserve) = plan_legend(panel, area, font, 0)
                .map_err(|e| anyhow::anyhow!("cannot draw '{}': {e}", panel.title))?;
            floor = floor.max(reserve);
        }
        for ((panel, _), area) in self.panels.iter().zip(&areas) {
            placements.extend(
                draw_panel_with_font(panel, area, font, floor)
                    .map_err(|e| anyhow::anyhow!("cannot draw '{}': {e}", panel.title))?,
            );
        }
        Ok(placements)
    }
}

/// Keep where the legends of the figure written to `path` went, for the test that no legend
/// hides data (a no-op outside tests).
fn log_placements(path: &Path, placements: Vec<LegendPlacement>) {
    #[cfg(test)]
    {
        let mut log = LEGEND_LOG.lock().unwrap_or_else(|e| e.into_inner());
        log.extend(placements.into_iter().map(|p| (path.to_path_buf(), p)));
    }
    #[cfg(not(test))]
    let _ = (path, placements);
}

/// A point in the panel's plotting coordinates: log10 of the value on a logarithmic axis.
fn to_plot(panel: &Panel, (x, y): (f64, f64)) -> (f64, f64) {
    let axis = |v: f64, log: bool| {
        if !log {
            v
        } else if v > 0.0 {
            v.log10()
        } else {
            f64::NAN
        }
    };
    (axis(x, panel.x_log), axis(y, panel.y_log))
}

/// Data range of the panel's series and cells, padded, in plotting coordinates.
fn ranges(panel: &Panel) -> ((f64, f64), (f64, f64)) {
    let mut xs = (f64::INFINITY, f64::NEG_INFINITY);
    let mut ys = (f64::INFINITY, f64::NEG_INFINITY);
    let mut take = |p: (f64, f64)| {
        let (x, y) = to_plot(panel, p);
        if x.is_finite() && y.is_finite() {
            xs = (xs.0.min(x), xs.1.max(x));
            ys = (ys.0.min(y), ys.1.max(y));
        }
    };
    for s in &panel.series {
        for &(x, y) in &s.points {
            take((x, y));
            if let Style::Bars(_) = s.style {
                take((x, 0.0));
            }
        }
    }
    for c in &panel.cells {
        take((c.x.0, c.y.0));
        take((c.x.1, c.y.1));
    }
    let pad = |(lo, hi): (f64, f64), frac: f64| {
        if !lo.is_finite() {
            (0.0, 1.0)
        } else if hi - lo <= f64::EPSILON * (lo.abs() + hi.abs()).max(1e-300) {
            let d = if lo == 0.0 { 1.0 } else { 0.1 * lo.abs() };
            (lo - d, hi + d)
        } else {
            let d = (hi - lo) * frac;
            (lo - d, hi + d)
        }
    };
    let given = |range: Option<(f64, f64)>, log: bool| {
        range.map(|(lo, hi)| {
            if log {
                (lo.max(f64::MIN_POSITIVE).log10(), hi.log10())
            } else {
                (lo, hi)
            }
        })
    };
    let x = given(panel.x_range, panel.x_log).unwrap_or_else(|| pad(xs, 0.0));
    let y = given(panel.y_range, panel.y_log).unwrap_or_else(|| pad(ys, 0.06));
    (x, y)
}

/// The font size of the panels of a figure `width` pixels wide whose panels measure
/// `panel`: about 1/80 of the figure's width (so that the text keeps its size when the figure
/// is shown at page width, whatever its number of columns), and no less than 1/22 of the
/// panel's smaller side; from 13 to 22 px.
pub fn font_size(width: u32, panel: (u32, u32)) -> u32 {
    (width / 80).max(panel.0.min(panel.1) / 22).clamp(13, 22)
}

/// The space between a panel's title and its plotting area: half a tick label and more (the
/// top tick label is centred on the top edge and must not touch the title).
fn top_margin(font: u32) -> u32 {
    8 + font / 2
}

/// The entries of a panel's legend: text and how its sample is drawn.
fn legend_entries(panel: &Panel) -> Vec<(String, Sample)> {
    panel
        .cell_legend
        .iter()
        .map(|(label, color)| (label.clone(), Sample::Swatch(*color)))
        .chain(
            panel
                .series
                .iter()
                .filter(|s| !s.label.is_empty())
                .map(|s| (s.label.clone(), Sample::Series(s.style, s.color))),
        )
        .collect()
}

/// How a legend entry's sample is drawn.
#[derive(Debug, Clone, Copy)]
enum Sample {
    /// As the series is drawn: a short line, a dashed line, a marker, a bar.
    Series(Style, RGBColor),
    /// A filled square with a dark border (a class of a map; the border keeps a pale colour
    /// visible on white).
    Swatch(RGBColor),
}

/// Sizes of a legend box, in pixels.
const LEGEND_PAD: i32 = 6;
const SAMPLE_WIDTH: i32 = 26;

/// A rectangle in pixels: left, top, right, bottom (right and bottom excluded).
pub type PixelRect = (i32, i32, i32, i32);

/// Where a panel's legend went, and how many pixels of data it covers there (measured on the
/// data drawn alone, with the final layout).
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct LegendPlacement {
    /// The panel's title.
    pub panel: String,
    /// The legend box, in the panel's pixels.
    pub rect: PixelRect,
    /// The plotting area, in the panel's pixels.
    pub plot: PixelRect,
    /// Whether the box is outside the plotting area (no corner was free).
    pub outside: bool,
    /// Pixels of data (series and cells) under the box.
    pub overlap: usize,
}

/// What the rendering of every legend reported, for the test that no legend hides data:
/// (file, placement).
#[cfg(test)]
pub(crate) static LEGEND_LOG: std::sync::Mutex<Vec<(std::path::PathBuf, LegendPlacement)>> =
    std::sync::Mutex::new(Vec::new());

/// The legend box's size for `entries` at `font`, measured with the backend's text metrics.
fn legend_size<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    entries: &[(String, Sample)],
    font: u32,
) -> (i32, i32) {
    let style = TextStyle::from((FAMILY, font).into_font());
    let text_width = entries
        .iter()
        .map(|(label, _)| {
            area.estimate_text_size(label, &style)
                .map_or(label.chars().count() as u32 * font * 6 / 10, |s| s.0)
        })
        .max()
        .unwrap_or(0) as i32;
    let row = font as i32 + 6;
    (
        2 * LEGEND_PAD + SAMPLE_WIDTH + 6 + text_width,
        2 * LEGEND_PAD + row * entries.len() as i32 - 4,
    )
}

/// The main area of a panel (left of its colour bar, if any) and the colour bar's strip.
fn split_for_bar<DB: DrawingBackend>(
    panel: &Panel,
    area: &DrawingArea<DB, Shift>,
    font: u32,
) -> (DrawingArea<DB, Shift>, Option<DrawingArea<DB, Shift>>) {
    let (w, _) = area.dim_in_pixel();
    match &panel.color_bar {
        Some(_) => {
            let (main, side) = area.split_horizontally(w.saturating_sub(font * 8));
            (main, Some(side))
        }
        None => (area.clone(), None),
    }
}

type Chart<'a, DB> = ChartContext<'a, DB, Cartesian2d<RangedCoordf64, RangedCoordf64>>;

/// Draw the title of `panel` across the top of its whole `area` (colour bar and legend room
/// included) and return the area below it. A title wider than the panel is set smaller,
/// down to the size of the axes' text, and then wrapped onto more lines rather than cut or
/// set in tiny type ([`title_lines`]).
fn titled<DB: DrawingBackend>(
    panel: &Panel,
    area: &DrawingArea<DB, Shift>,
    font: u32,
) -> Result<DrawingArea<DB, Shift>, String> {
    if panel.title.is_empty() {
        return Ok(area.clone());
    }
    let width = area.dim_in_pixel().0.saturating_sub(16);
    let measure = |text: &str, size: u32| {
        area.estimate_text_size(text, &TextStyle::from((FAMILY, size).into_font()))
            .map_or(u32::MAX, |s| s.0)
    };
    let (title_font, lines) = title_lines(&panel.title, width, font, measure);
    if let [line] = lines.as_slice() {
        return area
            .titled(line, (FAMILY, title_font))
            .map_err(|e| e.to_string());
    }
    let style =
        TextStyle::from((FAMILY, title_font).into_font()).pos(Pos::new(HPos::Center, VPos::Top));
    let line_height = title_font * 5 / 4;
    let center = (area.dim_in_pixel().0 / 2) as i32;
    for (k, line) in lines.iter().enumerate() {
        area.draw_text(line, &style, (center, 4 + (k as u32 * line_height) as i32))
            .map_err(|e| e.to_string())?;
    }
    let used = 4 + lines.len() as u32 * line_height + 4;
    Ok(area.split_vertically(used).1)
}

/// The size and lines of a title `width` pixels wide at most, with `measure(text, size)` its
/// width in pixels: one line at `font` + 2 down to `font` when it fits, else the words
/// wrapped onto lines at `font` (a word wider than the panel alone on its line).
fn title_lines(
    title: &str,
    width: u32,
    font: u32,
    measure: impl Fn(&str, u32) -> u32,
) -> (u32, Vec<String>) {
    for size in (font..=font + 2).rev() {
        if measure(title, size) <= width {
            return (size, vec![title.to_string()]);
        }
    }
    let mut lines: Vec<String> = Vec::new();
    let mut line = String::new();
    for word in title.split(' ') {
        let candidate = if line.is_empty() {
            word.to_string()
        } else {
            format!("{line} {word}")
        };
        if measure(&candidate, font) <= width || line.is_empty() {
            line = candidate;
        } else {
            lines.push(std::mem::replace(&mut line, word.to_string()));
        }
    }
    lines.push(line);
    (font, lines)
}

/// The chart of `panel` on `area` (below its title), with `reserve` pixels kept free on the
/// right of the plotting area for a legend.
fn build_chart<'a, DB: DrawingBackend>(
    panel: &Panel,
    area: &'a DrawingArea<DB, Shift>,
    font: u32,
    reserve: u32,
) -> Result<Chart<'a, DB>, String> {
    let (xr, yr) = ranges(panel);
    let build = |right: u32, bottom: u32| {
        ChartBuilder::on(area)
            .margin(8)
            .margin_top(top_margin(font))
            // Room for the last tick label, centred on the right edge (and for a legend).
            .margin_right(font * 2 + reserve + right)
            .margin_bottom(8 + bottom)
            .x_label_area_size(font * 3)
            .y_label_area_size(font * 4)
            .build_cartesian_2d(xr.0..xr.1, yr.0..yr.1)
            .map_err(|e| e.to_string())
    };
    let chart = build(0, 0)?;
    if !panel.equal_aspect || panel.x_log || panel.y_log {
        return Ok(chart);
    }
    // As many pixels per unit on both axes: the longer side gives up its excess.
    let (xs, ys) = chart.plotting_area().get_pixel_range();
    let (w, h) = (f64::from(xs.end - xs.start), f64::from(ys.end - ys.start));
    let (dx, dy) = ((xr.1 - xr.0).abs(), (yr.1 - yr.0).abs());
    if !(w > 0.0 && h > 0.0 && dx > 0.0 && dy > 0.0) {
        return Ok(chart);
    }
    let scale = (w / dx).min(h / dy);
    build(
        (w - scale * dx).round() as u32,
        (h - scale * dy).round() as u32,
    )
}

/// The plotting area of `chart`, in pixels of `area`.
fn plot_rect<DB: DrawingBackend>(
    chart: &Chart<'_, DB>,
    area: &DrawingArea<DB, Shift>,
) -> PixelRect {
    let (xs, ys) = chart.plotting_area().get_pixel_range();
    let (bx, by) = area.get_base_pixel();
    (xs.start - bx, ys.start - by, xs.end - bx, ys.end - by)
}

/// Draw the cells and series of `panel` (no axes, no legend).
fn draw_data<DB: DrawingBackend>(panel: &Panel, chart: &mut Chart<'_, DB>) -> Result<(), String>
where
    DB::ErrorType: 'static,
{
    let map = |p: (f64, f64)| to_plot(panel, p);
    for c in &panel.cells {
        let (a, b) = (map((c.x.0, c.y.0)), map((c.x.1, c.y.1)));
        if a.0.is_finite() && a.1.is_finite() && b.0.is_finite() && b.1.is_finite() {
            chart
                .draw_series(std::iter::once(Rectangle::new([a, b], c.color.filled())))
                .map_err(|e| e.to_string())?;
        }
    }
    for s in &panel.series {
        let color = s.color;
        let finite = || {
            s.points
                .iter()
                .map(|&p| map(p))
                .filter(|p| p.0.is_finite() && p.1.is_finite())
        };
        match s.style {
            Style::Line(width) | Style::Dashed(width) => {
                let style = color.stroke_width(width);
                // Break the polyline at non-finite points.
                let mut pieces: Vec<Vec<(f64, f64)>> = vec![Vec::new()];
                for &p in &s.points {
                    let (x, y) = map(p);
                    if x.is_finite() && y.is_finite() {
                        pieces.last_mut().expect("non-empty").push((x, y));
                    } else if !pieces.last().expect("non-empty").is_empty() {
                        pieces.push(Vec::new());
                    }
                }
                for piece in pieces.into_iter().filter(|p| !p.is_empty()) {
                    if matches!(s.style, Style::Dashed(_)) {
                        chart.draw_series(DashedLineSeries::new(piece, 6, 4, style))
                    } else {
                        chart.draw_series(LineSeries::new(piece, style))
                    }
                    .map_err(|e| e.to_string())?;
                }
            }
            Style::Markers(r) => {
                chart
                    .draw_series(finite().map(|p| Circle::new(p, r, color.filled())))
                    .map_err(|e| e.to_string())?;
            }
            Style::Squares(r) => {
                let r = r as i32;
                chart
                    .draw_series(finite().map(|p| {
                        EmptyElement::at(p)
                            + Rectangle::new([(-r, -r), (r, r)], color.stroke_width(1))
                    }))
                    .map_err(|e| e.to_string())?;
            }
            Style::Dots(side) => {
                let side = side.max(1) as i32;
                chart
                    .draw_series(finite().map(|p| {
                        EmptyElement::at(p) + Rectangle::new([(0, 0), (side, side)], color.filled())
                    }))
                    .map_err(|e| e.to_string())?;
            }
            Style::Bars(width) => {
                let base = if panel.y_log {
                    chart.y_range().start
                } else {
                    0.0
                };
                chart
                    .draw_series(finite().map(|(x, y)| {
                        Rectangle::new(
                            [(x - width / 2.0, base), (x + width / 2.0, y)],
                            color.filled(),
                        )
                    }))
                    .map_err(|e| e.to_string())?;
            }
        }
    }
    Ok(())
}

/// Which pixels of a panel of `size` hold data (series or cells), drawn alone with the layout
/// of [`build_chart`] with `reserve`: the mask (row by row) and the plotting area.
fn data_mask(
    panel: &Panel,
    size: (u32, u32),
    font: u32,
    reserve: u32,
) -> Result<(Vec<bool>, PixelRect), String> {
    let (w, h) = size;
    let mut buffer = vec![255u8; w as usize * h as usize * 3];
    let rect = {
        let root = BitMapBackend::with_buffer(&mut buffer, size).into_drawing_area();
        let body = titled(panel, &root, font)?;
        let (main, _) = split_for_bar(panel, &body, font);
        let mut chart = build_chart(panel, &main, font, reserve)?;
        let rect = plot_rect(&chart, &root);
        draw_data(panel, &mut chart)?;
        root.present().map_err(|e| e.to_string())?;
        rect
    };
    // The caption is drawn too, outside the plotting area: keep what is inside.
    let mut mask = vec![false; w as usize * h as usize];
    for y in rect.1.max(0)..rect.3.min(h as i32) {
        for x in rect.0.max(0)..rect.2.min(w as i32) {
            let i = y as usize * w as usize + x as usize;
            mask[i] = buffer[3 * i..3 * i + 3] != [255, 255, 255];
        }
    }
    Ok((mask, rect))
}

/// Pixels of `mask` (a panel `width` wide) inside `rect`.
fn covered(mask: &[bool], width: u32, rect: PixelRect) -> usize {
    let height = (mask.len() / width.max(1) as usize) as i32;
    let mut n = 0;
    for y in rect.1.max(0)..rect.3.min(height) {
        for x in rect.0.max(0)..rect.2.min(width as i32) {
            n += usize::from(mask[y as usize * width as usize + x as usize]);
        }
    }
    n
}

/// The corners of `plot` where a legend of `size` may go, `preferred` first, then upper
/// right, upper left, lower right, lower left.
fn corners(plot: PixelRect, size: (i32, i32), preferred: Legend) -> Vec<PixelRect> {
    let gap = 6;
    let (w, h) = size;
    let at = |corner: Legend| {
        let (left, top) = match corner {
            Legend::UpperLeft => (plot.0 + gap, plot.1 + gap),
            Legend::LowerRight => (plot.2 - gap - w, plot.3 - gap - h),
            Legend::LowerLeft => (plot.0 + gap, plot.3 - gap - h),
            Legend::UpperRight | Legend::Best => (plot.2 - gap - w, plot.1 + gap),
        };
        (left, top, left + w, top + h)
    };
    let mut order = vec![preferred];
    for c in [
        Legend::UpperRight,
        Legend::UpperLeft,
        Legend::LowerRight,
        Legend::LowerLeft,
    ] {
        if !order.contains(&c) {
            order.push(c);
        }
    }
    order
        .into_iter()
        .map(at)
        // A box larger than the plotting area does not fit in any corner.
        .filter(|r| r.0 >= plot.0 && r.1 >= plot.1 && r.2 <= plot.2 && r.3 <= plot.3)
        .collect()
}

/// Draw the legend box `rect` with `entries` on `area`.
fn draw_legend<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    entries: &[(String, Sample)],
    rect: PixelRect,
    font: u32,
) -> Result<(), String>
where
    DB::ErrorType: 'static,
{
    let err = |e: DrawingAreaErrorKind<DB::ErrorType>| e.to_string();
    area.draw(&Rectangle::new(
        [(rect.0, rect.1), (rect.2, rect.3)],
        WHITE.filled(),
    ))
    .map_err(err)?;
    area.draw(&Rectangle::new(
        [(rect.0, rect.1), (rect.2, rect.3)],
        RGBColor(170, 170, 170).stroke_width(1),
    ))
    .map_err(err)?;
    let row = font as i32 + 6;
    let style =
        TextStyle::from((FAMILY, font).into_font()).pos(plotters::style::text_anchor::Pos::new(
            plotters::style::text_anchor::HPos::Left,
            plotters::style::text_anchor::VPos::Center,
        ));
    for (k, (label, sample)) in entries.iter().enumerate() {
        let y = rect.1 + LEGEND_PAD + row * k as i32 + (row - 4) / 2;
        let x = rect.0 + LEGEND_PAD;
        let mid = x + SAMPLE_WIDTH / 2;
        match *sample {
            Sample::Swatch(color) => {
                let r = (font as i32 / 2).clamp(5, 9);
                area.draw(&Rectangle::new(
                    [(mid - r, y - r), (mid + r, y + r)],
                    color.filled(),
                ))
                .map_err(err)?;
                area.draw(&Rectangle::new(
                    [(mid - r, y - r), (mid + r, y + r)],
                    RGBColor(90, 90, 90).stroke_width(1),
                ))
                .map_err(err)?;
            }
            Sample::Series(Style::Line(w), color) => {
                area.draw(&PathElement::new(
                    vec![(x, y), (x + SAMPLE_WIDTH, y)],
                    color.stroke_width(w.max(2)),
                ))
                .map_err(err)?;
            }
            Sample::Series(Style::Dashed(w), color) => {
                for a in (0..SAMPLE_WIDTH).step_by(9) {
                    area.draw(&PathElement::new(
                        vec![(x + a, y), (x + (a + 5).min(SAMPLE_WIDTH), y)],
                        color.stroke_width(w.max(2)),
                    ))
                    .map_err(err)?;
                }
            }
            Sample::Series(Style::Markers(r), color) => {
                area.draw(&Circle::new((mid, y), r.clamp(3, 5), color.filled()))
                    .map_err(err)?;
            }
            Sample::Series(Style::Squares(r), color) => {
                let r = (r as i32).clamp(3, 6);
                area.draw(&Rectangle::new(
                    [(mid - r, y - r), (mid + r, y + r)],
                    color.stroke_width(1),
                ))
                .map_err(err)?;
            }
            Sample::Series(Style::Bars(_), color) => {
                area.draw(&Rectangle::new(
                    [(mid - 7, y - 5), (mid + 7, y + 5)],
                    color.filled(),
                ))
                .map_err(err)?;
            }
            Sample::Series(Style::Dots(_), color) => {
                area.draw(&Rectangle::new(
                    [(mid - 3, y - 3), (mid + 3, y + 3)],
                    color.filled(),
                ))
                .map_err(err)?;
            }
        }
        area.draw(&Text::new(
            label.clone(),
            (x + SAMPLE_WIDTH + 6, y),
            style.clone(),
        ))
        .map_err(err)?;
    }
    Ok(())
}

fn draw_panel<DB: DrawingBackend>(
    panel: &Panel,
    area: &DrawingArea<DB, Shift>,
    font: u32,
) -> Result<Option<LegendPlacement>, String>
where
    DB::ErrorType: 'static,
{
    draw_panel_with_font(panel, area, font, 0)
}

/// Where the legend of `panel` goes: (box, plotting area, outside, data pixels covered), and
/// the room kept free right of the plotting area (at least `floor`).
#[allow(clippy::type_complexity)]
fn plan_legend<DB: DrawingBackend>(
    panel: &Panel,
    area: &DrawingArea<DB, Shift>,
    font: u32,
    floor: u32,
) -> Result<(Option<(PixelRect, PixelRect, bool, usize)>, u32), String> {
    let entries = legend_entries(panel);
    let size = area.dim_in_pixel();
    let Some(preferred) = panel.legend.filter(|_| !entries.is_empty()) else {
        return Ok((None, floor));
    };
    let (w, h) = legend_size(area, &entries, font);
    // The data drawn alone: the first corner where the box covers none.
    let (mask, plot) = data_mask(panel, size, font, floor)?;
    let free = corners(plot, (w, h), preferred)
        .into_iter()
        .map(|r| (r, covered(&mask, size.0, r)))
        .find(|&(_, n)| n == 0);
    if let Some((rect, overlap)) = free {
        return Ok((Some((rect, plot, false, overlap)), floor));
    }
    // Outside, right of the plotting area, top-aligned with it.
    let reserve = floor.max((w + 12) as u32);
    let (mask, plot) = data_mask(panel, size, font, reserve)?;
    let left = plot.2 + 10;
    let rect = (left, plot.1, left + w, plot.1 + h);
    let overlap = covered(&mask, size.0, rect);
    Ok((Some((rect, plot, true, overlap)), reserve))
}

/// Draw `panel` on `area` with text of `font` pixels; its legend goes in the first corner of
/// the plotting area where it covers no data (the panel's [`Legend`] is the corner tried
/// first), or, when every corner covers data, outside the plotting area on its right.
/// At least `floor` pixels are kept free right of the plotting area (panels of a [`Stack`]
/// share their width so that their x axes line up). Returns where the legend went and how
/// much data it covers there.
fn draw_panel_with_font<DB: DrawingBackend>(
    panel: &Panel,
    area: &DrawingArea<DB, Shift>,
    font: u32,
    floor: u32,
) -> Result<Option<LegendPlacement>, String>
where
    DB::ErrorType: 'static,
{
    let entries = legend_entries(panel);
    let (legend, reserve) = plan_legend(panel, area, font, floor)?;

    let body = titled(panel, area, font)?;
    let (main, side) = split_for_bar(panel, &body, font);
    if let (Some(bar), Some(side)) = (&panel.color_bar, &side) {
        draw_color_bar(bar, side, font)?;
    }
    let mut chart = build_chart(panel, &main, font, reserve)?;
    let formatter = |log: bool| -> fn(&f64) -> String {
        if log {
            log_tick
        } else {
            tick
        }
    };
    let (x_tick, y_tick) = (formatter(panel.x_log), formatter(panel.y_log));
    chart
        .configure_mesh()
        .x_desc(&panel.x_label)
        .y_desc(&panel.y_label)
        .x_label_formatter(&x_tick)
        .y_label_formatter(&y_tick)
        .label_style((FAMILY, font))
        .axis_desc_style((FAMILY, font))
        .light_line_style(RGBColor(235, 235, 235))
        .bold_line_style(RGBColor(215, 215, 215))
        .x_labels(6)
        .y_labels(6)
        .draw()
        .map_err(|e| e.to_string())?;
    draw_data(panel, &mut chart)?;
    Ok(match legend {
        Some((rect, plot, outside, overlap)) => {
            draw_legend(area, &entries, rect, font)?;
            Some(LegendPlacement {
                panel: panel.title.clone(),
                rect,
                plot,
                outside,
                overlap,
            })
        }
        None => None,
    })
}

/// A tick label on a logarithmic axis: 10^v with three significant digits at most.
fn log_tick(value: &f64) -> String {
    let x = 10f64.powf(*value);
    if !x.is_finite() {
        return String::new();
    }
    let text = format!("{x:.2e}");
    let parsed: f64 = text.parse().unwrap_or(x);
    if (1e-4..1e5).contains(&parsed.abs()) {
        let digits = (2 - parsed.abs().log10().floor() as i32).max(0) as usize;
        let fixed = format!("{parsed:.digits$}");
        if fixed.contains('.') {
            fixed
                .trim_end_matches('0')
                .trim_end_matches('.')
                .to_string()
        } else {
            fixed
        }
    } else {
        text
    }
}

/// A tick label as plotters writes it, without the sign of a zero that rounding left
/// negative ("-0.0" for a tick at −3e-17).
fn tick(value: &f64) -> String {
    use plotters::coord::ranged1d::ValueFormatter;
    let text = RangedCoordf64::format(value);
    match text.strip_prefix('-') {
        Some(rest) if rest.chars().all(|c| c == '0' || c == '.') => rest.to_string(),
        _ => text,
    }
}

/// The colour bar of `bar` in `area` (a narrow strip), labelled on its right.
fn draw_color_bar<DB: DrawingBackend>(
    bar: &ColorBar,
    area: &DrawingArea<DB, Shift>,
    font: u32,
) -> Result<(), String>
where
    DB::ErrorType: 'static,
{
    let (lo, hi) = bar.range;
    let mut chart = ChartBuilder::on(area)
        // As the chart beside it: the caption's height on top, the x labels' at the bottom.
        .margin(8)
        .margin_top(top_margin(font))
        .margin_bottom(8 + font * 3)
        .set_label_area_size(LabelAreaPosition::Right, font * 5)
        .build_cartesian_2d(0.0..1.0, lo..hi)
        .map_err(|e| e.to_string())?;
    let steps = 120;
    let cells = (0..steps).map(|k| {
        let (a, b) = (
            lo + (hi - lo) * k as f64 / steps as f64,
            lo + (hi - lo) * (k + 1) as f64 / steps as f64,
        );
        Rectangle::new([(0.0, a), (1.0, b)], bar.color(0.5 * (a + b)).filled())
    });
    chart.draw_series(cells).map_err(|e| e.to_string())?;
    chart
        .configure_mesh()
        .disable_x_mesh()
        .disable_y_mesh()
        .disable_x_axis()
        .y_label_formatter(&tick)
        .y_desc(&bar.label)
        .label_style((FAMILY, font))
        .axis_desc_style((FAMILY, font))
        .y_labels(7)
        .draw()
        .map_err(|e| e.to_string())?;
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_bar_of_negative_values_still_shows_where_positive_ones_would_go() {
        let bar = ColorBar::for_values("λ1", &[-0.5, -0.1, 0.0, f64::NAN]);
        assert_eq!(bar.range, (-0.5, 0.5));
        // A positive value takes a red, distinct from white, on this bar.
        let RGBColor(r, g, b) = bar.color(0.25);
        assert!(r > g && r > b, "{:?}", (r, g, b));
        // With positive values, the top is the largest of them.
        assert_eq!(
            ColorBar::for_values("λ1", &[-0.5, 0.02]).range,
            (-0.5, 0.02)
        );
    }

    #[test]
    fn a_long_title_wraps_instead_of_shrinking_below_the_axes_text() {
        // Half the size per character, in pixels.
        let measure = |text: &str, size: u32| text.chars().count() as u32 * size / 2;
        let short = "fit: 9969.65 Hz";
        assert_eq!(
            title_lines(short, 400, 14, measure),
            (16, vec![short.into()])
        );
        let long = "record a.csv: 9969.65 Hz, 1.4980 V · PWL: U_t = 0.70 V, R = 71.0 Ω · \
                    Shockley: I_s = 2.5e-9 A, n = 1.75, R = 65.3 Ω";
        let (size, lines) = title_lines(long, 400, 14, measure);
        assert_eq!(size, 14, "never below the axes' text");
        assert!(lines.len() > 1);
        assert!(lines.iter().all(|l| measure(l, size) <= 400), "{lines:?}");
        assert_eq!(lines.join(" "), long, "every word kept, in order");
    }
}
