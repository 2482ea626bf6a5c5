//! Rendering: a figure's panels drawn on a PNG or SVG backend, with titles, axes, data and
//! colour bars.

use super::legend::*;
use super::*;
use crate::output::AtomicFile;
use anyhow::{Context, Result};
use plotters::coord::types::RangedCoordf64;
use plotters::coord::Shift;
use plotters::style::text_anchor::{HPos, Pos, VPos};
use std::path::Path;

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
        let rows = self.rows();
        let size = (
            self.panel_size.0 * self.columns as u32,
            self.panel_size.1 * rows.max(1),
        );
        render_file(self, path, size)
    }

    /// Rows of panels.
    fn rows(&self) -> u32 {
        self.panels.len().div_ceil(self.columns.max(1)) as u32
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
        let height: u32 = self.panels.iter().map(|(_, h)| h).sum();
        render_file(self, path, (self.width, height.max(1)))
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

/// A figure that draws itself on any backend: [`Figure`] and [`Stack`].
trait Drawing {
    fn draw_on<DB: DrawingBackend>(
        &self,
        root: &DrawingArea<DB, Shift>,
    ) -> Result<Vec<LegendPlacement>>
    where
        DB::ErrorType: 'static;
}

impl Drawing for Figure {
    fn draw_on<DB: DrawingBackend>(
        &self,
        root: &DrawingArea<DB, Shift>,
    ) -> Result<Vec<LegendPlacement>>
    where
        DB::ErrorType: 'static,
    {
        self.draw(root, self.rows())
    }
}

impl Drawing for Stack {
    fn draw_on<DB: DrawingBackend>(
        &self,
        root: &DrawingArea<DB, Shift>,
    ) -> Result<Vec<LegendPlacement>>
    where
        DB::ErrorType: 'static,
    {
        self.draw(root)
    }
}

/// Render `drawing` to `path` at `size` pixels, as SVG when the file's extension says so and
/// as PNG otherwise, atomically (nothing is left at `path` if drawing fails).
fn render_file(drawing: &impl Drawing, path: &Path, size: (u32, u32)) -> Result<()> {
    register_font();
    let file = AtomicFile::create(path)?;
    let temp = file.temp_path().to_path_buf();
    let svg = path
        .extension()
        .and_then(|e| e.to_str())
        .is_some_and(|e| e.eq_ignore_ascii_case("svg"));
    let placements = if svg {
        let root = SVGBackend::new(&temp, size).into_drawing_area();
        let placements = drawing.draw_on(&root)?;
        root.present().context("cannot write SVG")?;
        placements
    } else {
        let root = BitMapBackend::new(&temp, size).into_drawing_area();
        let placements = drawing.draw_on(&root)?;
        root.present().context("cannot write PNG")?;
        placements
    };
    log_placements(path, placements);
    file.commit()
}

/// Keep where the legends of the figure written to `path` went, for the test that no legend
/// hides data (a no-op outside tests).
pub(super) fn log_placements(path: &Path, placements: Vec<LegendPlacement>) {
    #[cfg(test)]
    {
        let mut log = LEGEND_LOG.lock().unwrap_or_else(|e| e.into_inner());
        log.extend(placements.into_iter().map(|p| (path.to_path_buf(), p)));
    }
    #[cfg(not(test))]
    let _ = (path, placements);
}

/// A point in the panel's plotting coordinates: log10 of the value on a logarithmic axis.
pub(super) fn to_plot(panel: &Panel, (x, y): (f64, f64)) -> (f64, f64) {
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
pub(super) fn ranges(panel: &Panel) -> ((f64, f64), (f64, f64)) {
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
pub(super) fn top_margin(font: u32) -> u32 {
    8 + font / 2
}

/// The main area of a panel (left of its colour bar, if any) and the colour bar's strip.
pub(super) fn split_for_bar<DB: DrawingBackend>(
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

pub(super) type Chart<'a, DB> = ChartContext<'a, DB, Cartesian2d<RangedCoordf64, RangedCoordf64>>;

/// Draw the title of `panel` across the top of its whole `area` (colour bar and legend room
/// included) and return the area below it. A title wider than the panel is set smaller,
/// down to the size of the axes' text, and then wrapped onto more lines rather than cut or
/// set in tiny type ([`title_lines`]).
pub(super) fn titled<DB: DrawingBackend>(
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
pub(super) fn title_lines(
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
pub(super) fn build_chart<'a, DB: DrawingBackend>(
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
pub(super) fn plot_rect<DB: DrawingBackend>(
    chart: &Chart<'_, DB>,
    area: &DrawingArea<DB, Shift>,
) -> PixelRect {
    let (xs, ys) = chart.plotting_area().get_pixel_range();
    let (bx, by) = area.get_base_pixel();
    (xs.start - bx, ys.start - by, xs.end - bx, ys.end - by)
}

/// Draw the cells and series of `panel` (no axes, no legend).
pub(super) fn draw_data<DB: DrawingBackend>(
    panel: &Panel,
    chart: &mut Chart<'_, DB>,
) -> Result<(), String>
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

pub(super) fn draw_panel<DB: DrawingBackend>(
    panel: &Panel,
    area: &DrawingArea<DB, Shift>,
    font: u32,
) -> Result<Option<LegendPlacement>, String>
where
    DB::ErrorType: 'static,
{
    draw_panel_with_font(panel, area, font, 0)
}

/// Draw `panel` on `area` with text of `font` pixels; its legend goes in the first corner of
/// the plotting area where it covers no data (the panel's [`Legend`] is the corner tried
/// first), or, when every corner covers data, outside the plotting area on its right.
/// At least `floor` pixels are kept free right of the plotting area (panels of a [`Stack`]
/// share their width so that their x axes line up). Returns where the legend went and how
/// much data it covers there.
pub(super) fn draw_panel_with_font<DB: DrawingBackend>(
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
pub(super) fn log_tick(value: &f64) -> String {
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
pub(super) fn tick(value: &f64) -> String {
    use plotters::coord::ranged1d::ValueFormatter;
    let text = RangedCoordf64::format(value);
    match text.strip_prefix('-') {
        Some(rest) if rest.chars().all(|c| c == '0' || c == '.') => rest.to_string(),
        _ => text,
    }
}

/// The colour bar of `bar` in `area` (a narrow strip), labelled on its right.
pub(super) fn draw_color_bar<DB: DrawingBackend>(
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
