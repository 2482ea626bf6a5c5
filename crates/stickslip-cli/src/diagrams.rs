//! Figures of bifurcation diagrams, basin maps and branches of periodic orbits, shared by the
//! `bifurcation`, `basins` and `continue` commands and the report.

use crate::plot::{Cell, Legend, Panel, Series, Stack, Style, PALETTE};
use plotters::style::RGBColor;
use stickslip::attractor::AttractorKind;
use stickslip::basins::BasinMap;
use stickslip::bifurcation::BifurcationStep;
use stickslip::continuation::{Branch, BranchPoint, SpecialKind, SpecialPoint};
use stickslip::scan::SweepLeg;
use stickslip::stability::Multiplier;
use stickslip::Parameter;

/// The axis label of a parameter, with what it is.
pub fn parameter_label(parameter: Parameter) -> &'static str {
    match parameter {
        Parameter::W => "w = Ω/ω0 (drive frequency)",
        Parameter::Beta => "β (drive amplitude)",
        Parameter::Zeta => "ζ (damping ratio)",
        Parameter::MuS => "μs (static/kinetic friction)",
        Parameter::Vb => "vb (belt speed)",
        Parameter::Vs => "vs (Stribeck speed)",
        Parameter::Delta => "δ (Stribeck exponent)",
        Parameter::Eta => "η (viscous friction)",
        Parameter::K1 => "k1 (cubic law)",
        Parameter::K3 => "k3 (cubic law)",
    }
}

/// The symbol of a parameter for labels: w, β, ζ, μs.
pub fn symbol(parameter: Parameter) -> &'static str {
    match parameter {
        Parameter::W => "w",
        Parameter::Beta => "β",
        Parameter::Zeta => "ζ",
        Parameter::MuS => "μs",
        Parameter::Vb => "vb",
        Parameter::Vs => "vs",
        Parameter::Delta => "δ",
        Parameter::Eta => "η",
        Parameter::K1 => "k1",
        Parameter::K3 => "k3",
    }
}

/// Whether an orbit with these multipliers is stable (largest modulus below 1).
pub fn stable(multipliers: &[Multiplier; 2]) -> bool {
    multipliers[0].modulus() < 1.0
}

/// Colour of the points of each leg of a diagram.
fn leg_color(leg: SweepLeg) -> RGBColor {
    match leg {
        SweepLeg::Up => crate::plot::Quantity::SweepUp.color(),
        SweepLeg::Down => crate::plot::Quantity::SweepDown.color(),
    }
}

/// Colour and label of each kind of special point.
fn special_style(kind: SpecialKind) -> (RGBColor, &'static str) {
    match kind {
        SpecialKind::Fold => (RGBColor(204, 0, 0), "fold"),
        SpecialKind::BranchPoint => (PALETTE[3], "branch point"),
        SpecialKind::PeriodDoubling => (PALETTE[2], "period doubling"),
        SpecialKind::NeimarkSacker => (PALETTE[4], "Neimark–Sacker"),
        SpecialKind::Grazing => (RGBColor(120, 60, 160), "grazing (stops change)"),
    }
}

/// The curves of `branches` as series: for every branch, `coordinate` of each of its p strobe
/// points (of the first only, without `per_strobe`) against the parameter, stable pieces
/// solid and unstable ones dashed; labelled once.
pub fn branch_series(
    branches: &[Branch],
    coordinate: &dyn Fn(&BranchPoint, usize) -> f64,
    per_strobe: bool,
) -> Vec<Series> {
    let stable_color = RGBColor(20, 20, 20);
    let unstable_color = RGBColor(204, 0, 0);
    let mut out = Vec::new();
    let (mut stable_named, mut unstable_named) = (false, false);
    for branch in branches {
        let curves = if per_strobe { branch.period } else { 1 };
        for k in 0..curves {
            let mut piece: Vec<(f64, f64)> = Vec::new();
            let mut piece_stable = None;
            for point in &branch.points {
                let s = stable(&point.orbit.multipliers);
                let xy = (point.value, coordinate(point, k));
                if piece_stable.is_some_and(|p| p != s) {
                    // Close the piece at this point, so that the curve stays connected.
                    piece.push(xy);
                    let was = piece_stable.expect("set");
                    out.push(curve(
                        std::mem::take(&mut piece),
                        was,
                        &mut stable_named,
                        &mut unstable_named,
                        stable_color,
                        unstable_color,
                    ));
                }
                piece_stable = Some(s);
                piece.push(xy);
            }
            if let Some(was) = piece_stable {
                if piece.len() > 1 {
                    out.push(curve(
                        piece,
                        was,
                        &mut stable_named,
                        &mut unstable_named,
                        stable_color,
                        unstable_color,
                    ));
                }
            }
        }
    }
    out
}

fn curve(
    points: Vec<(f64, f64)>,
    stable: bool,
    stable_named: &mut bool,
    unstable_named: &mut bool,
    stable_color: RGBColor,
    unstable_color: RGBColor,
) -> Series {
    let (named, label, color, style) = if stable {
        (
            stable_named,
            "stable orbit (continuation)",
            stable_color,
            Style::Line(2),
        )
    } else {
        (
            unstable_named,
            "unstable orbit (continuation)",
            unstable_color,
            Style::Dashed(2),
        )
    };
    let label = if *named { "" } else { label };
    *named = true;
    Series::new(label, points, color, style)
}

/// Markers at the special points of `branches`, one series per kind present, at
/// `coordinate` of the orbit there (for a grazing or fold: the strobe y).
fn special_series(
    branches: &[Branch],
    coordinate: &dyn Fn(&SpecialPoint) -> f64,
    with_values: bool,
    parameter: Parameter,
) -> Vec<Series> {
    let kinds = [
        SpecialKind::Fold,
        SpecialKind::PeriodDoubling,
        SpecialKind::BranchPoint,
        SpecialKind::NeimarkSacker,
        SpecialKind::Grazing,
    ];
    let mut out = Vec::new();
    for kind in kinds {
        let found: Vec<&SpecialPoint> = branches
            .iter()
            .flat_map(|b| b.special.iter())
            .filter(|s| s.kind == kind)
            .collect();
        if found.is_empty() {
            continue;
        }
        let (color, name) = special_style(kind);
        let label = if with_values {
            let values: Vec<String> = found
                .iter()
                .take(3)
                .map(|s| format!("{:.5}", s.value))
                .collect();
            let more = if found.len() > 3 { ", …" } else { "" };
            format!(
                "{name} at {} = {}{more}",
                symbol(parameter),
                values.join(", ")
            )
        } else {
            name.to_string()
        };
        let points = found.iter().map(|s| (s.value, coordinate(s))).collect();
        out.push(Series::new(label, points, color, Style::Squares(5)));
    }
    out
}

/// A bifurcation diagram: the strobe points of every step as dots (the up and the down leg
/// in two colours), the continued branches on top (stable solid, unstable dashed) with their
/// special points, and the largest Lyapunov exponent in a panel below.
pub fn diagram_figure(
    steps: &[BifurcationStep],
    branches: &[Branch],
    parameter: Parameter,
    title: &str,
) -> Stack {
    let total: usize = steps.iter().map(|s| s.record.strobes.len()).sum();
    let side = if total > 60_000 { 1 } else { 2 };
    let mut series = Vec::new();
    let both = steps.iter().any(|s| s.leg == SweepLeg::Down)
        && steps.iter().any(|s| s.leg == SweepLeg::Up);
    for leg in [SweepLeg::Up, SweepLeg::Down] {
        let points: Vec<(f64, f64)> = steps
            .iter()
            .filter(|s| s.leg == leg)
            .flat_map(|s| s.record.strobes.iter().map(move |x| (s.value, x.y)))
            .collect();
        if points.is_empty() {
            continue;
        }
        let label = if both {
            format!(
                "strobe points, {} {}",
                symbol(parameter),
                if leg == SweepLeg::Up {
                    "increasing"
                } else {
                    "decreasing"
                }
            )
        } else {
            "strobe points".to_string()
        };
        series.push(Series::new(
            label,
            points,
            leg_color(leg),
            Style::Dots(side),
        ));
    }
    series.extend(branch_series(branches, &|p, k| p.strobes[k].y, true));
    series.extend(special_series(branches, &|s| s.state.y, false, parameter));
    let (lo, hi) = steps
        .iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), s| {
            (a.min(s.value), b.max(s.value))
        });
    let x_range = (lo < hi).then_some((lo, hi));
    let top = Panel {
        title: title.to_string(),
        x_label: String::new(),
        y_label: "y at the strobe (drive phase φ)".into(),
        y_range: headroom(&series, x_range),
        series,
        x_range,
        legend: Some(Legend::UpperLeft),
        ..Default::default()
    };
    let mut lambda = Vec::new();
    for leg in [SweepLeg::Up, SweepLeg::Down] {
        let points: Vec<(f64, f64)> = steps
            .iter()
            .filter(|s| s.leg == leg)
            .map(|s| (s.value, s.record.exponent))
            .collect();
        if !points.is_empty() {
            lambda.push(Series::new("", points, leg_color(leg), Style::Line(1)));
        }
    }
    if let Some((a, b)) = x_range {
        lambda.push(Series::new(
            "",
            vec![(a, 0.0), (b, 0.0)],
            RGBColor(150, 150, 150),
            Style::Dashed(1),
        ));
    }
    let bottom = Panel {
        title: "largest Lyapunov exponent over the recorded periods".into(),
        x_label: parameter_label(parameter).into(),
        y_label: "λ₁ per unit τ".into(),
        series: lambda,
        x_range,
        ..Default::default()
    };
    Stack {
        panels: vec![(top, 620), (bottom, 300)],
        width: 1000,
    }
}

/// The y range of `series` within `x_range`, with a margin of 4 % of its span (the legend
/// finds its own place: a free corner, or outside the plotting area).
fn headroom(series: &[Series], x_range: Option<(f64, f64)>) -> Option<(f64, f64)> {
    let (x0, x1) = x_range.unwrap_or((f64::NEG_INFINITY, f64::INFINITY));
    let (lo, hi) = series
        .iter()
        .flat_map(|s| s.points.iter())
        .filter(|(x, y)| x.is_finite() && y.is_finite() && *x >= x0 && *x <= x1)
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), (_, y)| {
            (a.min(*y), b.max(*y))
        });
    if !(lo <= hi) {
        return None;
    }
    let span = (hi - lo).max(1e-9 * hi.abs().max(1.0));
    Some((lo - 0.04 * span, hi + 0.04 * span))
}

/// Light colours of the basins, by attractor number; the marker colours are the palette's.
const BASIN_COLORS: [RGBColor; 8] = [
    RGBColor(166, 206, 227),
    RGBColor(251, 180, 160),
    RGBColor(178, 223, 138),
    RGBColor(253, 210, 140),
    RGBColor(210, 190, 225),
    RGBColor(255, 245, 160),
    RGBColor(200, 170, 140),
    RGBColor(250, 200, 230),
];
const MARKER_COLORS: [RGBColor; 8] = [
    RGBColor(31, 90, 160),
    RGBColor(200, 50, 30),
    RGBColor(40, 130, 40),
    RGBColor(200, 110, 0),
    RGBColor(110, 60, 160),
    RGBColor(150, 130, 0),
    RGBColor(110, 70, 30),
    RGBColor(200, 60, 140),
];
const UNDECIDED: RGBColor = RGBColor(190, 190, 190);

/// A one-line description of an attractor for legends: number, kind, period, share.
pub fn attractor_label(a: &stickslip::basins::Attractor) -> String {
    let what = match (a.kind, a.period) {
        (AttractorKind::Periodic, Some(p)) => format!("period {p}"),
        (AttractorKind::Static, _) => "rest".to_string(),
        (kind, _) => kind.label().to_string(),
    };
    format!("#{} {what}, {:.1} %", a.id, 100.0 * a.fraction)
}

/// A basin map: every cell in the colour of its attractor (grey: undecided), and the
/// attractors' strobe points on top (the p points of a periodic orbit as circles, the strobe
/// set of chaos as dots).
pub fn basin_panel(map: &BasinMap, title: &str) -> Panel {
    let half = |v: &[f64]| {
        if v.len() > 1 {
            0.5 * (v[1] - v[0])
        } else {
            0.5
        }
    };
    let (hy, hv) = (half(&map.y0), half(&map.v0));
    let n = map.v0.len();
    let cells = map
        .cells
        .iter()
        .enumerate()
        .map(|(k, a)| {
            let (y, v) = (map.y0[k / n], map.v0[k % n]);
            Cell {
                x: (y - hy, y + hy),
                y: (v - hv, v + hv),
                color: a.map_or(UNDECIDED, |i| BASIN_COLORS[i % BASIN_COLORS.len()]),
            }
        })
        .collect();
    let mut cell_legend: Vec<(String, RGBColor)> = map
        .attractors
        .iter()
        .map(|a| (attractor_label(a), BASIN_COLORS[a.id % BASIN_COLORS.len()]))
        .collect();
    if map.undecided > 0 {
        cell_legend.push((
            format!(
                "undecided, {:.1} %",
                100.0 * map.undecided as f64 / map.cells.len() as f64
            ),
            UNDECIDED,
        ));
    }
    let (y_range, v_range) = (
        (map.y0[0] - hy, map.y0[map.y0.len() - 1] + hy),
        (map.v0[0] - hv, map.v0[n - 1] + hv),
    );
    let inside = |s: &stickslip::State| {
        s.y >= y_range.0 && s.y <= y_range.1 && s.v >= v_range.0 && s.v <= v_range.1
    };
    let mut series = Vec::new();
    for a in &map.attractors {
        let color = MARKER_COLORS[a.id % MARKER_COLORS.len()];
        let points: Vec<(f64, f64)> = a
            .strobes
            .iter()
            .filter(|s| inside(s))
            .map(|s| (s.y, s.v))
            .collect();
        let style = match a.kind {
            AttractorKind::Periodic => Style::Markers(5),
            AttractorKind::Static => Style::Squares(4),
            _ => Style::Dots(2),
        };
        if !points.is_empty() {
            // One entry per attractor, in its marker's colour.
            let label = format!("#{} at the strobe", a.id);
            series.push(Series::new(label, points, color, style));
        }
    }
    Panel {
        title: title.to_string(),
        x_label: "y0 (initial position)".into(),
        y_label: "y0' (initial velocity)".into(),
        series,
        cells,
        cell_legend,
        x_range: Some(y_range),
        y_range: Some(v_range),
        legend: Some(Legend::UpperRight),
        // A phase plane: y and y' on one scale.
        equal_aspect: true,
        ..Default::default()
    }
}

/// The signed largest multiplier for plots: its real part when real, its modulus for a
/// complex pair; clipped to ±3.
fn plotted_multiplier(m: &[Multiplier; 2]) -> f64 {
    let x = if m[0].im == 0.0 {
        m[0].re
    } else {
        m[0].modulus()
    };
    x.clamp(-3.0, 3.0)
}

/// A branch: its amplitude against the parameter (stable solid, unstable dashed) with its
/// special points labelled, and the largest multiplier in a panel below.
pub fn branch_figure(branch: &Branch, title: &str) -> Stack {
    let parameter = branch.parameter;
    let branches = std::slice::from_ref(branch);
    let mut series = branch_series(branches, &|p, _| p.amplitude(), false);
    // A special point sits between two points of the branch: mark it at their mean amplitude.
    let amplitude = |s: &SpecialPoint| -> f64 {
        match (
            branch.points.get(s.after_point),
            branch.points.get(s.after_point + 1),
        ) {
            (Some(a), Some(b)) => 0.5 * (a.amplitude() + b.amplitude()),
            _ => f64::NAN,
        }
    };
    series.extend(special_series(branches, &amplitude, true, parameter));
    let (lo, hi) = branch
        .points
        .iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), p| {
            (a.min(p.value), b.max(p.value))
        });
    // A margin on both sides: a fold at an end of the branch keeps its whole marker.
    let x_range = (lo < hi).then_some((lo - 0.03 * (hi - lo), hi + 0.03 * (hi - lo)));
    let top = Panel {
        title: title.to_string(),
        x_label: String::new(),
        y_label: "amplitude (max y − min y)/2".into(),
        y_range: headroom(&series, x_range),
        series,
        x_range,
        legend: Some(Legend::UpperLeft),
        ..Default::default()
    };
    let mut lower = branch_series(
        branches,
        &|p, _| plotted_multiplier(&p.orbit.multipliers),
        false,
    );
    if let Some((a, b)) = x_range {
        for level in [1.0, -1.0] {
            lower.push(Series::new(
                "",
                vec![(a, level), (b, level)],
                RGBColor(150, 150, 150),
                Style::Dashed(1),
            ));
        }
    }
    let bottom = Panel {
        title: "largest Floquet multiplier (real part; modulus when complex; clipped to ±3)".into(),
        x_label: parameter_label(parameter).into(),
        y_label: "μ".into(),
        series: lower,
        x_range,
        y_range: Some((-3.2, 3.2)),
        ..Default::default()
    };
    Stack {
        panels: vec![(top, 560), (bottom, 300)],
        width: 1000,
    }
}
