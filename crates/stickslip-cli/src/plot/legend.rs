//! Legends: their entries, their size, and where they go in a panel so that they hide the
//! least data.

use super::render::*;
use super::*;
use anyhow::Result;
use plotters::coord::Shift;

/// The entries of a panel's legend: text and how its sample is drawn.
pub(super) fn legend_entries(panel: &Panel) -> Vec<(String, Sample)> {
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
pub(super) enum Sample {
    /// As the series is drawn: a short line, a dashed line, a marker, a bar.
    Series(Style, RGBColor),
    /// A filled square with a dark border (a class of a map; the border keeps a pale colour
    /// visible on white).
    Swatch(RGBColor),
}

/// Sizes of a legend box, in pixels.
pub(super) const LEGEND_PAD: i32 = 6;
pub(super) const SAMPLE_WIDTH: i32 = 26;

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
pub(super) fn legend_size<DB: DrawingBackend>(
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

/// Which pixels of a panel of `size` hold data (series or cells), drawn alone with the layout
/// of [`build_chart`] with `reserve`: the mask (row by row) and the plotting area.
pub(super) fn data_mask(
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
pub(super) fn covered(mask: &[bool], width: u32, rect: PixelRect) -> usize {
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
pub(super) fn corners(plot: PixelRect, size: (i32, i32), preferred: Legend) -> Vec<PixelRect> {
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
pub(super) fn draw_legend<DB: DrawingBackend>(
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

/// Where the legend of `panel` goes: (box, plotting area, outside, data pixels covered), and
/// the room kept free right of the plotting area (at least `floor`).
#[allow(clippy::type_complexity)]
pub(super) fn plan_legend<DB: DrawingBackend>(
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
