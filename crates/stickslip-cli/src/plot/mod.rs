//! Figures: panels of line, marker, bar and cell series, rendered to PNG or SVG (chosen by the
//! file's extension) with a bundled font, so rendering needs no system fonts.
//!
//! This file holds the figure model (panels, series, colours, colour bars); `render` draws a
//! [`Figure`] or a [`Stack`] on a backend, and `legend` sizes the legends and places each
//! where it hides the least data.

use plotters::prelude::*;
use std::sync::Once;

/// The bundled font (DejaVu Sans; licence in `assets/DejaVuSans-LICENSE.txt`).
static FONT: &[u8] = include_bytes!("../../assets/DejaVuSans.ttf");
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

mod legend;
mod render;

#[cfg(test)]
pub(crate) use legend::{LegendPlacement, LEGEND_LOG};
pub use render::{Figure, Stack};

#[cfg(test)]
mod tests {
    use super::render::*;
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
