//! Figures: panels of line, marker, bar and cell series, rendered to PNG or SVG (chosen by the
//! file's extension) with a bundled font, so rendering needs no system fonts.

use crate::output::AtomicFile;
use anyhow::{Context, Result};
use plotters::coord::types::RangedCoordf64;
use plotters::coord::Shift;
use plotters::prelude::*;
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
    /// values are left out. Always includes 0.
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

/// Corner of a panel that holds its legend.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Legend {
    /// Upper left.
    UpperLeft,
    /// Upper right.
    UpperRight,
    /// Lower right.
    LowerRight,
    /// The corner where the legend covers the fewest data points (upper right on a tie).
    Best,
}

/// Colour of each motion class in maps, the same in every figure.
pub fn class_color(class: stickslip::steady::MotionClass) -> RGBColor {
    use stickslip::steady::MotionClass;
    match class {
        MotionClass::Sliding => RGBColor(235, 235, 235),
        MotionClass::PeriodicStick => PALETTE[0],
        MotionClass::NonperiodicStick => PALETTE[1],
        MotionClass::Static => PALETTE[2],
        MotionClass::Chaotic => CHAOTIC,
    }
}

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
        if svg {
            let root = SVGBackend::new(&temp, size).into_drawing_area();
            self.draw(&root, rows)?;
            root.present().context("cannot write SVG")?;
        } else {
            let root = BitMapBackend::new(&temp, size).into_drawing_area();
            self.draw(&root, rows)?;
            root.present().context("cannot write PNG")?;
        }
        file.commit()
    }

    fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>, rows: u32) -> Result<()>
    where
        DB::ErrorType: 'static,
    {
        root.fill(&WHITE).map_err(|e| anyhow::anyhow!("{e:?}"))?;
        let areas = root.split_evenly((rows as usize, self.columns.max(1)));
        for (panel, area) in self.panels.iter().zip(areas.iter()) {
            draw_panel(panel, area)
                .map_err(|e| anyhow::anyhow!("cannot draw '{}': {e}", panel.title))?;
        }
        Ok(())
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
        if svg {
            let root = SVGBackend::new(&temp, size).into_drawing_area();
            self.draw(&root)?;
            root.present().context("cannot write SVG")?;
        } else {
            let root = BitMapBackend::new(&temp, size).into_drawing_area();
            self.draw(&root)?;
            root.present().context("cannot write PNG")?;
        }
        file.commit()
    }

    fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> Result<()>
    where
        DB::ErrorType: 'static,
    {
        root.fill(&WHITE).map_err(|e| anyhow::anyhow!("{e:?}"))?;
        let top = self.panels.first().map_or(0, |(_, h)| *h);
        let font = (self.width.min(top) / 22).clamp(11, 20);
        let mut rest = root.clone();
        for (i, (panel, h)) in self.panels.iter().enumerate() {
            let area = if i + 1 == self.panels.len() {
                rest.clone()
            } else {
                let (top, bottom) = rest.split_vertically(*h);
                rest = bottom;
                top
            };
            draw_panel_with_font(panel, &area, font)
                .map_err(|e| anyhow::anyhow!("cannot draw '{}': {e}", panel.title))?;
        }
        Ok(())
    }
}

/// Data range of the panel's series and cells, padded.
fn ranges(panel: &Panel) -> ((f64, f64), (f64, f64)) {
    let mut xs = (f64::INFINITY, f64::NEG_INFINITY);
    let mut ys = (f64::INFINITY, f64::NEG_INFINITY);
    let mut take = |x: f64, y: f64| {
        if x.is_finite() && y.is_finite() {
            xs = (xs.0.min(x), xs.1.max(x));
            ys = (ys.0.min(y), ys.1.max(y));
        }
    };
    for s in &panel.series {
        for &(x, y) in &s.points {
            take(x, y);
            if let Style::Bars(_) = s.style {
                take(x, 0.0);
            }
        }
    }
    for c in &panel.cells {
        take(c.x.0, c.y.0);
        take(c.x.1, c.y.1);
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
    let x = panel.x_range.unwrap_or_else(|| pad(xs, 0.0));
    let y = panel.y_range.unwrap_or_else(|| pad(ys, 0.06));
    (x, y)
}

fn draw_panel<DB: DrawingBackend>(
    panel: &Panel,
    area: &DrawingArea<DB, Shift>,
) -> Result<(), String>
where
    DB::ErrorType: 'static,
{
    let (w, h) = area.dim_in_pixel();
    draw_panel_with_font(panel, area, (w.min(h) / 22).clamp(11, 20))
}

/// [`draw_panel`] with a given font size (panels of a [`Stack`] share one, so that their
/// plotting areas line up).
fn draw_panel_with_font<DB: DrawingBackend>(
    panel: &Panel,
    area: &DrawingArea<DB, Shift>,
    font: u32,
) -> Result<(), String>
where
    DB::ErrorType: 'static,
{
    let (xr, yr) = ranges(panel);
    let (w, _) = area.dim_in_pixel();
    let area = match &panel.color_bar {
        Some(bar) => {
            let (main, side) = area.split_horizontally(w.saturating_sub(font * 8));
            draw_color_bar(bar, &side, font)?;
            main
        }
        None => area.clone(),
    };
    let mut chart = ChartBuilder::on(&area)
        .caption(&panel.title, (FAMILY, font + 2))
        .margin(8)
        // Room for the last tick label, centred on the right edge.
        .margin_right(font * 2)
        .x_label_area_size(font * 3)
        .y_label_area_size(font * 4)
        .build_cartesian_2d(xr.0..xr.1, yr.0..yr.1)
        .map_err(|e| e.to_string())?;
    chart
        .configure_mesh()
        .x_desc(&panel.x_label)
        .y_desc(&panel.y_label)
        .x_label_formatter(&tick)
        .y_label_formatter(&tick)
        .label_style((FAMILY, font))
        .axis_desc_style((FAMILY, font))
        .light_line_style(RGBColor(235, 235, 235))
        .x_labels(6)
        .y_labels(6)
        .draw()
        .map_err(|e| e.to_string())?;

    for c in &panel.cells {
        chart
            .draw_series(std::iter::once(Rectangle::new(
                [(c.x.0, c.y.0), (c.x.1, c.y.1)],
                c.color.filled(),
            )))
            .map_err(|e| e.to_string())?;
    }
    for (label, color) in &panel.cell_legend {
        let color = *color;
        chart
            .draw_series(std::iter::empty::<Rectangle<(f64, f64)>>())
            .map_err(|e| e.to_string())?
            .label(label.clone())
            .legend(move |(x, y)| Rectangle::new([(x, y - 5), (x + 12, y + 5)], color.filled()));
    }

    for s in &panel.series {
        let color = s.color;
        let finite = || {
            s.points
                .iter()
                .copied()
                .filter(|p| p.0.is_finite() && p.1.is_finite())
        };
        match s.style {
            Style::Line(width) | Style::Dashed(width) => {
                let style = color.stroke_width(width);
                // Break the polyline at non-finite points.
                let mut pieces: Vec<Vec<(f64, f64)>> = vec![Vec::new()];
                for &(x, y) in &s.points {
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
                chart
                    .draw_series(finite().map(|(x, y)| {
                        Rectangle::new(
                            [(x - width / 2.0, 0.0), (x + width / 2.0, y)],
                            color.filled(),
                        )
                    }))
                    .map_err(|e| e.to_string())?;
            }
        }
        if !s.label.is_empty() {
            // The legend's sample is drawn as the series is: a dashed line for a dashed
            // series, a dot for markers. A series with no points is a legend entry only.
            let style = s.style;
            chart
                .draw_series(std::iter::empty::<Circle<(f64, f64), u32>>())
                .map_err(|e| e.to_string())?
                .label(s.label.clone())
                .legend(move |(x, y)| match style {
                    Style::Line(w) => {
                        PathElement::new(vec![(x, y), (x + 20, y)], color.stroke_width(w.max(2)))
                            .into_dyn()
                    }
                    Style::Dashed(w) => plotters::element::DashedPathElement::new(
                        vec![(x, y), (x + 20, y)],
                        5,
                        3,
                        color.stroke_width(w.max(2)),
                    )
                    .into_dyn(),
                    Style::Markers(r) => {
                        Circle::new((x + 10, y), r.clamp(3, 5), color.filled()).into_dyn()
                    }
                    Style::Squares(_) => {
                        Rectangle::new([(x + 6, y - 4), (x + 14, y + 4)], color.stroke_width(1))
                            .into_dyn()
                    }
                    Style::Bars(_) => {
                        Rectangle::new([(x + 4, y - 5), (x + 16, y + 5)], color.filled()).into_dyn()
                    }
                    Style::Dots(_) => {
                        Rectangle::new([(x + 7, y - 3), (x + 13, y + 3)], color.filled()).into_dyn()
                    }
                });
        }
    }
    if let Some(position) = panel.legend {
        let position = match position {
            Legend::UpperLeft => SeriesLabelPosition::UpperLeft,
            Legend::UpperRight => SeriesLabelPosition::UpperRight,
            Legend::LowerRight => SeriesLabelPosition::LowerRight,
            Legend::Best => best_corner(panel, &chart, font),
        };
        chart
            .configure_series_labels()
            .position(position)
            .background_style(WHITE.mix(0.85))
            .border_style(RGBColor(180, 180, 180))
            .label_font((FAMILY, font))
            .draw()
            .map_err(|e| e.to_string())?;
    }
    Ok(())
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
        .margin_top(8 + font + 2 + 5)
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

/// The corner where a legend box would cover the fewest data points (upper right, upper
/// left, lower right, lower left, in that order of preference on a tie). The box's size is
/// estimated from the number of entries and the longest label at the legend's font size.
fn best_corner<DB: DrawingBackend>(
    panel: &Panel,
    chart: &ChartContext<DB, Cartesian2d<RangedCoordf64, RangedCoordf64>>,
    font: u32,
) -> SeriesLabelPosition {
    let labels: Vec<&str> = panel
        .series
        .iter()
        .map(|s| s.label.as_str())
        .chain(panel.cell_legend.iter().map(|c| c.0.as_str()))
        .filter(|l| !l.is_empty())
        .collect();
    let chars = labels.iter().map(|l| l.chars().count()).max().unwrap_or(0) as f64;
    let font = f64::from(font);
    let (width, height) = (
        chars * 0.6 * font + 40.0,
        labels.len() as f64 * (font + 6.0) + 12.0,
    );
    let (xs, ys) = chart.plotting_area().get_pixel_range();
    let (left, right, top, bottom) = (
        f64::from(xs.start),
        f64::from(xs.end),
        f64::from(ys.start),
        f64::from(ys.end),
    );
    let margin = 10.0;
    let corners = [
        (
            SeriesLabelPosition::UpperRight,
            right - margin - width,
            top + margin,
        ),
        (SeriesLabelPosition::UpperLeft, left + margin, top + margin),
        (
            SeriesLabelPosition::LowerRight,
            right - margin - width,
            bottom - margin - height,
        ),
        (
            SeriesLabelPosition::LowerLeft,
            left + margin,
            bottom - margin - height,
        ),
    ];
    let points: Vec<(f64, f64)> = panel
        .series
        .iter()
        .flat_map(|s| s.points.iter().copied())
        .filter(|p| p.0.is_finite() && p.1.is_finite())
        .map(|p| {
            let (x, y) = chart.backend_coord(&p);
            (f64::from(x), f64::from(y))
        })
        .collect();
    let covered = |x0: f64, y0: f64| {
        points
            .iter()
            .filter(|&&(x, y)| x >= x0 && x <= x0 + width && y >= y0 && y <= y0 + height)
            .count()
    };
    let mut best = (usize::MAX, SeriesLabelPosition::UpperRight);
    for (position, x0, y0) in corners {
        let n = covered(x0, y0);
        if n < best.0 {
            best = (n, position);
        }
    }
    best.1
}
