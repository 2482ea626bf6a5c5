//! Tests of `stickslip reproduce`.

use crate::common::*;
use std::path::Path;
use stickslip::experiment::{Experiment, Key};
use stickslip::report::{
    BasinsTable, BifurcationRow, BranchTable, CurveTable, MapRow, OrbitTable, SweepRow,
    TrajectoryColumns,
};
use stickslip::Parameter;
use stickslip_cli::reproduce_columns as columns;

/// A CSV file of the report without quoted cells: its columns, and its rows, whose cells are
/// read by column name ([`Csv::at`]).
struct Csv {
    columns: Vec<String>,
    rows: Vec<Vec<String>>,
}

impl Csv {
    fn read(report: &Path, name: &str) -> Self {
        let text =
            std::fs::read_to_string(report.join(name)).unwrap_or_else(|e| panic!("{name}: {e}"));
        let mut lines = text
            .lines()
            .map(|l| l.split(',').map(String::from).collect());
        let columns: Vec<String> = lines.next().unwrap_or_else(|| panic!("{name} is empty"));
        let rows: Vec<Vec<String>> = lines.collect();
        assert!(
            rows.iter().all(|r| r.len() == columns.len()),
            "{name}: a row without a cell per column"
        );
        Self { columns, rows }
    }

    /// The index of the column `name`.
    fn at(&self, name: &str) -> usize {
        self.columns
            .iter()
            .position(|c| c == name)
            .unwrap_or_else(|| panic!("no column {name} in {:?}", self.columns))
    }
}

/// The columns of every CSV file of the report: a file that holds a library result has the
/// columns of the library's table (as `stickslip sweep`, `phase-diagram`, `simulate`,
/// `bifurcation`, `basins` and `continue` write them), after the columns the figure adds;
/// the report's own files the columns their figure writes once. Every CSV the page lists
/// is one of them.
fn every_csv_has_its_columns(report: &Path, html: &str) {
    let names = |c: &[&str]| c.iter().map(|s| s.to_string()).collect::<Vec<String>>();
    let then = |lead: &[&str], c: &[&str]| [names(lead), names(c)].concat();
    let map = MapRow::columns(false);
    let exponents = MapRow::columns(true);
    let trace = then(
        &[Key::W.name(), Key::Beta.name()],
        &TrajectoryColumns {
            units: Experiment::paper().units(),
        }
        .names(),
    );
    // The curves over the chaos map: the library's table of a curve in (β, w).
    let curve = then(
        &[Parameter::Beta.label(), Parameter::W.label()],
        &CurveTable::COLUMNS,
    );
    let expected: Vec<(&str, Vec<String>)> = vec![
        ("fig1a.csv", names(columns::FRICTION_COLUMNS)),
        ("fig1b.csv", names(&columns::DIODE_COLUMNS)),
        ("table1.csv", names(&columns::TABLE1_COLUMNS)),
        ("fig3_traces.csv", trace.clone()),
        ("fig3_spectra.csv", names(&columns::SPECTRA_COLUMNS)),
        ("fig3_xy.csv", names(&columns::XY_COLUMNS)),
        ("fig4.csv", names(&SweepRow::COLUMNS)),
        ("fig5.csv", then(&columns::FIG5_LEADING, &SweepRow::COLUMNS)),
        ("fig6.csv", trace),
        ("fig7a.csv", names(&map)),
        ("fig7b.csv", names(&map)),
        // Fig. 7's grazing curves: the same table in (β, w).
        ("fig7-grazing.csv", curve.clone()),
        ("accuracy.csv", names(&columns::ACCURACY_COLUMNS)),
        ("chaos-sweep.csv", names(&exponents)),
        ("chaos-map.csv", names(&exponents)),
        ("paper-exponents.csv", names(&exponents)),
        (
            "beyond-bifurcation.csv",
            then(&[Parameter::W.label()], &BifurcationRow::COLUMNS),
        ),
        (
            "beyond-bifurcation-special.csv",
            names(&columns::SPECIAL_COLUMNS),
        ),
        ("beyond-basins.csv", names(&BasinsTable::COLUMNS)),
        ("chaos-map-grazing.csv", curve.clone()),
        ("chaos-map-fold.csv", curve.clone()),
        ("chaos-map-period-doubling.csv", curve),
        (
            "beyond-branch.csv",
            then(&[Parameter::Beta.label()], &BranchTable::COLUMNS),
        ),
        (
            "floquet-laws.csv",
            then(&[Key::Diode.name()], &OrbitTable::COLUMNS),
        ),
        // The chapter "Friction-induced vibration".
        (
            "belt-sweep.csv",
            then(
                &[Key::FrictionLaw.name(), Parameter::Vb.label()],
                &columns::BELT_SWEEP_COLUMNS,
            ),
        ),
        (
            "belt-closed-form.csv",
            then(
                &[Key::MuS.name(), Parameter::Vb.label()],
                &columns::CLOSED_FORM_COLUMNS,
            ),
        ),
        (
            "belt-approximation.csv",
            then(
                &[
                    Key::Zeta.name(),
                    Key::K1.name(),
                    Key::K3.name(),
                    Parameter::Vb.label(),
                ],
                &columns::APPROXIMATION_COLUMNS,
            ),
        ),
        ("belt-forced-map.csv", names(&map)),
    ];
    for (csv, header) in &expected {
        let text = std::fs::read_to_string(report.join(csv)).unwrap();
        assert_eq!(
            text.lines().next(),
            Some(header.join(",").as_str()),
            "{csv}"
        );
    }
    for csv in html
        .split("href=\"")
        .skip(1)
        .filter_map(|s| s.split('"').next())
        .filter(|s| s.ends_with(".csv"))
    {
        assert!(
            expected.iter().any(|(name, _)| *name == csv),
            "{csv}: a CSV of the report whose columns this test does not know (write it \
             through a library table, Report::table, or with columns written once beside its \
             figure, and list it here)"
        );
    }
}

/// Decode a PNG fully and return its size.
fn decode_png(path: &Path) -> (u32, u32) {
    let file = std::fs::File::open(path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    let mut reader = png::Decoder::new(file).read_info().expect("a PNG header");
    let mut buf = vec![0; reader.output_buffer_size()];
    let info = reader.next_frame(&mut buf).expect("PNG data decodes");
    // Not blank: more than one colour in the image.
    let first = &buf[..3];
    assert!(
        buf.chunks(info.line_size / info.width as usize)
            .any(|px| &px[..3] != first),
        "{} is blank",
        path.display()
    );
    (info.width, info.height)
}

#[test]
fn writes_every_figure_table_and_the_report() {
    let (dir, out) = run(&["reproduce", "--quick", "--out", "report"]);
    assert!(out.status.success(), "{}", stderr(&out));
    let report = dir.path().join("report");
    let figures = [
        "fig1",
        "fig3",
        "fig4",
        "fig5",
        "fig6",
        "fig7",
        "chaos-sweep",
        "chaos-map",
        "paper-exponents",
        "beyond-bifurcation",
        "beyond-basins",
        "beyond-branch",
        "belt-sweep",
        "belt-approximation",
        "belt-forced-map",
    ];
    let html = std::fs::read_to_string(report.join("index.html")).expect("index.html");
    for f in figures {
        for ext in ["png", "svg"] {
            let name = format!("{f}.{ext}");
            let path = report.join(&name);
            assert!(path.is_file(), "{name} missing");
            assert!(html.contains(&name), "index.html does not reference {name}");
        }
        let (w, h) = decode_png(&report.join(format!("{f}.png")));
        assert!(
            (400..=4000).contains(&w) && (300..=4000).contains(&h),
            "{f}: {w}×{h}"
        );
        let svg = std::fs::read_to_string(report.join(format!("{f}.svg"))).unwrap();
        assert!(
            svg.starts_with("<svg") && svg.trim_end().ends_with("</svg>"),
            "{f}.svg"
        );
    }
    // The page's table of contents gives each section's title, not its file id, and a flag
    // in a caption cannot break at its hyphens.
    assert!(
        html.contains("<li><a href=\"#fig3\">Fig. 3 — "),
        "table of contents"
    );
    assert!(
        !html.contains(">beyond-basins</a>"),
        "raw ids in the table of contents"
    );
    assert!(
        html.contains("<span class=\"nw\">--v0-min</span>"),
        "flags in captions"
    );
    // Every "<" of the page opens a tag (a comparison in a caption is "&lt;").
    for (k, _) in html.match_indices('<') {
        let next = html[k + 1..].chars().next().unwrap_or(' ');
        assert!(
            next.is_ascii_alphabetic() || next == '/' || next == '!',
            "an unescaped '<' in index.html: {}",
            &html[k..(k + 40).min(html.len())]
        );
    }
    // Every figure is shown at its full size: the page gives each image its PNG's size and
    // lets it be wider than the text.
    for f in figures {
        let (w, h) = decode_png(&report.join(format!("{f}.png")));
        let img = format!("<img src=\"{f}.png\" width=\"{w}\" height=\"{h}\"");
        assert!(
            html.contains(&img),
            "index.html does not show {f} at {w} × {h}"
        );
    }
    assert!(
        html.contains(".fig img{max-width:none"),
        "figures scaled to the text"
    );
    // The paper's Fig. 2, a drawing, is said to be skipped; its LSODA is our reading.
    assert!(html.contains("The paper's Fig. 2 is not reproduced"));
    assert!(html.contains("The paper says only that it integrated with LSODA; our reading"));
    assert!(!html.contains("The paper integrated"));
    // One symbol per gain: G1 = A1/β in Fig. 4 (its axis and its CSV's gain1), G the peak gain
    // of Table 1 and of the CSV's gain; no CSV of the report uses a retired name.
    let fig4 = std::fs::read_to_string(report.join("fig4.svg")).unwrap();
    assert!(
        fig4.contains("G1 = A1/β") && !fig4.contains("gain G "),
        "fig4's axis"
    );
    assert!(html.contains("(y_max − y_min)/(2β)"), "Table 1's G");
    every_csv_has_its_columns(&report, &html);
    // Fig. 5's legend lists only the theories drawn, and its caption counts the values of β
    // of (b) that stick, recounted here from fig5.csv (the up sweep against β).
    let fig5 = std::fs::read_to_string(report.join("fig5.svg")).unwrap();
    // (The SVG writes a legend's text on a line of its own.)
    let exact_entries = fig5.lines().filter(|l| l.trim() == "exact").count();
    if html.contains("(in (b) nowhere") {
        assert_eq!(
            exact_entries, 1,
            "fig5: an 'exact' entry in (b), which draws none"
        );
    } else {
        assert_eq!(exact_entries, 2, "fig5");
    }
    let fig5 = Csv::read(&report, "fig5.csv");
    let (swept, direction, class) = (
        fig5.at(columns::FIG5_LEADING[0]),
        fig5.at("direction"),
        fig5.at("class"),
    );
    let rows: Vec<&Vec<String>> = fig5
        .rows
        .iter()
        .filter(|f| f[swept] == "beta" && f[direction] == "up")
        .collect();
    let sticking = rows.iter().filter(|f| f[class] != "sliding").count();
    let said = if sticking == rows.len() {
        format!(
            "sticks at every one of the {} values of β shown",
            rows.len()
        )
    } else {
        format!(
            "sticks at {sticking} of the {} values of β shown",
            rows.len()
        )
    };
    assert!(
        sticking > 0 && html.contains(&said),
        "fig5 does not say: {said}"
    );
    assert!(!html.contains("sticks for most β"));
    // Fig. 7 (b): its curves are named the PWL model's, and its sliding share is said to
    // depend on the stop threshold.
    let fig7 = std::fs::read_to_string(report.join("fig7.svg")).unwrap();
    let legend: Vec<&str> = fig7.lines().map(str::trim).collect();
    assert!(legend.contains(&"PWL exact β_c") && legend.contains(&"PWL paper, eq. 13"));
    assert!(html.contains("the sliding share of (b) depends on that threshold"));
    fig3_shows_what_is_small(&report, &html);
    // A full report's caption does not speak of --quick's sizes.
    assert!(!html.contains("--quick uses"));
    // "static" is the paper's rule, said where the word appears.
    assert!(html.contains("\"static\" is the paper's rule, an amplitude below β/100"));
    // Every data file the page lists exists and has a header and rows.
    for csv in html
        .split("href=\"")
        .skip(1)
        .filter_map(|s| s.split('"').next())
        .filter(|s| s.ends_with(".csv"))
    {
        let text =
            std::fs::read_to_string(report.join(csv)).unwrap_or_else(|_| panic!("{csv} missing"));
        assert!(text.lines().count() >= 2, "{csv} is empty");
    }
    // summary.json: Table 1 and the four Fig. 6 classes.
    let summary: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(report.join("summary.json")).unwrap())
            .unwrap();
    let t1 = &summary["table1"];
    assert_eq!(format!("{:.1}", t1["alpha"].as_f64().unwrap()), "6173.9");
    assert_eq!(format!("{:.1}", t1["omega0"].as_f64().unwrap()), "65938.0");
    for key in ["zeta", "Q", "f0"] {
        assert!(t1[key].as_f64().is_some(), "table1.{key}");
    }
    let fig6 = summary["fig6"].as_array().expect("fig6 classes");
    assert_eq!(fig6.len(), 4);
    let classes: Vec<&str> = fig6.iter().map(|p| p["class"].as_str().unwrap()).collect();
    let allowed = [
        "sliding",
        "periodic-stick",
        "undecided",
        "static",
        "chaotic",
    ];
    assert!(classes.iter().all(|c| allowed.contains(c)), "{classes:?}");
    // The first and last of the paper's points are unambiguous.
    assert_eq!(classes[0], "sliding");
    assert_eq!(classes[3], "static");
    // The chapter "Beyond the paper": chaos at μs = 3, none on the paper's map (μs = 1).
    assert!(html.contains("Beyond the paper"));
    let sweep = &summary["beyond_chaos_sweep"];
    assert!(sweep["chaotic"].as_u64().unwrap() > 0, "{sweep}");
    assert!(
        sweep["lambda_chaotic"][0].as_f64().unwrap() > 0.0,
        "{sweep}"
    );
    let map = &summary["beyond_chaos_map"];
    assert!(map["chaotic"].as_u64().unwrap() > 0, "{map}");
    above_the_boundary_the_sliding_orbit_exists(&report, map, &html);
    curves_over_the_chaos_map(&report);
    fig7s_grazing_curves(&report, &summary["fig7a_curves"], &html);
    assert_eq!(map["periodic_with_positive_exponent"], 0, "{map}");
    let paper = &summary["beyond_paper_exponents"];
    assert_eq!(paper["positive"], 0, "{paper}");
    // Its colour bar still has a red half, and the caption says that no point takes it.
    assert!(html.contains("in reds that no point takes: no exponent is positive"));
    assert_eq!(paper["nonperiodic"], 0, "{paper}");
    assert!(paper["largest_moving"]["lambda1"].as_f64().unwrap() < 0.0);
    // The diagram in w at μs = 3 has periodic and chaotic values and branches found by
    // continuation; the basin map two coexisting orbits that are mirror images; the branch
    // a grazing above its fold.
    let bif = &summary["beyond_bifurcation_w"];
    assert!(bif["up_chaotic"].as_u64().unwrap() > 0, "{bif}");
    assert!(bif["up_periodic"].as_u64().unwrap() > 0, "{bif}");
    assert!(bif["branches"].as_u64().unwrap() > 0, "{bif}");
    legs_compared_as_attractors(&report, bif, &html);
    let basins = &summary["beyond_basins"];
    let attractors = basins["attractors"].as_array().unwrap();
    assert_eq!(attractors.len(), 2, "{basins}");
    assert!(attractors.iter().all(|a| a["period"] == 1), "{basins}");
    assert!(basins["mirror_gap"].as_f64().unwrap() < 1e-9, "{basins}");
    let branch = &summary["beyond_branch"];
    let (graze, fold) = (
        branch["grazing_beta"].as_f64().unwrap(),
        branch["fold_beta"].as_f64().unwrap(),
    );
    assert!(1.25 < fold && fold < graze && graze < 1.6, "{branch}");
    for id in ["beyond-bifurcation", "beyond-basins", "beyond-branch"] {
        assert!(html.contains(&format!("id=\"{id}\"")), "no section {id}");
    }
    belt_chapter(&report, &summary, &html);
    // The report is the same on every run: no timings in it.
    assert!(!html.contains(" s on "), "a timing in index.html");
    assert!(
        !std::fs::read_to_string(report.join("summary.json"))
            .unwrap()
            .contains("\"seconds\""),
        "a timing in summary.json"
    );
    // No staging directory is left behind.
    let left: Vec<_> = std::fs::read_dir(dir.path())
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    assert_eq!(left, vec!["report".to_string()]);
}

/// The chaos map's exact boundary: its legend says that the sliding orbit exists above it
/// (not that the motion slides there), and the caption counts the points above it that do
/// not slide from rest, recounted here from chaos-map.csv and the exact boundary.
/// The chaos map's curves: a legend entry per kind, and each kind's CSV holding curves of
/// that kind (their followed multiplier at +1 or −1) inside the map's range of β, one start
/// marked per curve.
/// Fig. 7's grazing curves: in both panels' legends, one start per curve in
/// fig7-grazing.csv, inside the map's range of β, and on the map's edges: nearly every
/// change of the number of stops per period between neighbouring cells has a curve between
/// them, and nearly every pair with a curve between them changes region (the counts the
/// caption gives).
fn fig7s_grazing_curves(report: &Path, counts: &serde_json::Value, html: &str) {
    let svg = std::fs::read_to_string(report.join("fig7.svg")).unwrap();
    let legend: Vec<&str> = svg.lines().map(str::trim).collect();
    assert!(legend.contains(&"grazing curves") && legend.contains(&"PWL grazing curves"));
    let csv = Csv::read(report, "fig7-grazing.csv");
    let (beta, special) = (csv.at("beta"), csv.at("special"));
    let starts = csv
        .rows
        .iter()
        .filter(|r| r[special].split(';').any(|s| s == "start"))
        .count();
    let curves = counts["curves"].as_u64().unwrap() as usize;
    assert!(curves >= 1, "{counts}");
    assert_eq!(starts, curves, "fig7-grazing.csv: the curves' starts");
    for r in &csv.rows {
        let b: f64 = r[beta].parse().unwrap();
        assert!((0.5..=4.0).contains(&b), "fig7-grazing.csv: β = {b}");
    }
    let n = |key: &str| counts[key].as_u64().unwrap() as usize;
    let (edges, crossed) = (n("stop_edges"), n("stop_edges_crossed"));
    assert!(edges > 0 && crossed * 10 >= edges * 9, "{counts}");
    let (odd, changing) = (n("pairs_crossed_odd"), n("pairs_crossed_odd_changing"));
    assert!(odd > 0 && changing * 10 >= odd * 9, "{counts}");
    let (sliding, under) = (n("sliding_edges"), n("sliding_edges_crossed_by_beta_c"));
    assert!(sliding > 0 && under * 10 >= sliding * 9, "{counts}");
    let said = format!(
        "of the {edges} pairs of neighbouring cells of (a) whose numbers of stops per period \
         differ, {crossed} ("
    );
    assert!(html.contains(&said), "fig7 does not say: {said}");
}

fn curves_over_the_chaos_map(report: &Path) {
    let svg = std::fs::read_to_string(report.join("chaos-map.svg")).unwrap();
    for (label, file, starts, multiplier) in [
        ("grazing curve", "chaos-map-grazing.csv", 1, None),
        ("fold curve", "chaos-map-fold.csv", 1, Some(1.0)),
        (
            "period-doubling curve",
            "chaos-map-period-doubling.csv",
            1,
            Some(-1.0),
        ),
    ] {
        assert!(svg.contains(label), "the chaos map's legend has no {label}");
        let csv = Csv::read(report, file);
        let (beta, special) = (csv.at("beta"), csv.at("special"));
        let (mu1, mu2) = (csv.at("mu1_re"), csv.at("mu2_re"));
        assert!(!csv.rows.is_empty(), "{file} is empty");
        let count = csv
            .rows
            .iter()
            .filter(|r| r[special].split(';').any(|s| s == "start"))
            .count();
        assert_eq!(count, starts, "{file}: the curves' starts");
        for r in &csv.rows {
            let b: f64 = r[beta].parse().unwrap();
            assert!((3.0..=14.0).contains(&b), "{file}: β = {b}");
            if let Some(m) = multiplier {
                let near = [mu1, mu2]
                    .iter()
                    .map(|&i| (r[i].parse::<f64>().unwrap() - m).abs())
                    .fold(f64::INFINITY, f64::min);
                assert!(near < 1e-6, "{file}: β = {b}, no multiplier at {m}");
            }
        }
    }
}

fn above_the_boundary_the_sliding_orbit_exists(report: &Path, map: &serde_json::Value, html: &str) {
    use stickslip::theory::curves::{theory_value, Theory, TheoryQuantity};
    for ext in ["svg", "png"] {
        assert!(report.join(format!("chaos-map.{ext}")).is_file());
    }
    let svg = std::fs::read_to_string(report.join("chaos-map.svg")).unwrap();
    assert!(
        svg.contains("exact β_c: the sliding orbit exists above") && !svg.contains("sliding above"),
        "the chaos map's legend"
    );
    let csv = Csv::read(report, "chaos-map.csv");
    let (w, beta, class) = (csv.at("w"), csv.at("beta"), csv.at("class"));
    let (mut above, mut not_sliding) = (0, 0);
    for f in &csv.rows {
        let mut params =
            stickslip::Params::new(0.0, f[w].parse().unwrap(), f[beta].parse().unwrap()).unwrap();
        params.mu_s = 3.0;
        let beta_c = theory_value(Theory::Exact, TheoryQuantity::Boundary, &params);
        if beta_c.is_some_and(|b| params.beta >= b) {
            above += 1;
            not_sliding += usize::from(f[class] != "sliding");
        }
    }
    assert_eq!(map["above_exact_boundary"], above, "{map}");
    assert_eq!(
        map["above_exact_boundary_not_sliding"], not_sliding,
        "{map}"
    );
    // Rest does not always lead to the sliding orbit where it exists.
    assert!(not_sliding > 0 && not_sliding < above, "{map}");
    let said = format!("{not_sliding} of the {above} points above it do not slide from rest");
    assert!(html.contains(&said), "the caption does not say: {said}");
}

/// The bifurcation caption's comparison of the two directions, recomputed from
/// beyond-bifurcation.csv: the records rebuilt from their strobe points, compared as
/// attractors by the library's `same_attractor` at the basin map's tolerance.
fn legs_compared_as_attractors(report: &Path, bif: &serde_json::Value, html: &str) {
    use stickslip::attractor::{same_attractor, AttractorKind, StrobeRecord};
    use stickslip::State;
    let csv = Csv::read(report, "beyond-bifurcation.csv");
    let at = |name: &str| csv.at(name);
    let (w, y, v, direction) = (at("w"), at("y"), at("v"), at("direction"));
    let (lambda1, class, period) = (at("lambda1"), at("class"), at("period"));
    let mut records: std::collections::BTreeMap<(String, String), StrobeRecord> =
        Default::default();
    for f in &csv.rows {
        let r = records
            .entry((f[direction].clone(), f[w].clone()))
            .or_insert_with(|| StrobeRecord {
                strobes: vec![],
                exponent: f[lambda1].parse().unwrap(),
                exponent_error: 0.0,
                period: (!f[period].is_empty()).then(|| f[period].parse().unwrap()),
                kind: AttractorKind::from_label(&f[class]).unwrap_or_else(|| panic!("{f:?}")),
                events: 0,
                stops: 0,
                drive_period: 1.0,
            });
        r.strobes.push(State {
            y: f[y].parse().unwrap(),
            v: f[v].parse().unwrap(),
        });
    }
    let tolerance = stickslip::basins::BasinOptions::default().match_tolerance;
    let (mut differ, mut different, mut decided) = (0, 0, 0);
    for ((leg, w), up) in &records {
        if leg != "up" {
            continue;
        }
        let down = &records[&("down".to_string(), w.clone())];
        let (x, y) = (up.strobes[0].y, down.strobes[0].y);
        if up.kind == down.kind
            && up.period == down.period
            && (x - y).abs() <= 1e-6 * (1.0 + x.abs())
        {
            continue;
        }
        differ += 1;
        if !same_attractor(up, down, tolerance) {
            different += 1;
            decided += usize::from(
                up.kind != AttractorKind::Undecided && down.kind != AttractorKind::Undecided,
            );
        }
    }
    assert_eq!(bif["values_where_up_and_down_differ"], differ, "{bif}");
    assert_eq!(
        bif["values_with_different_attractors_up_and_down"], different,
        "{bif}"
    );
    assert_eq!(
        bif["values_with_different_decided_attractors_up_and_down"], decided,
        "{bif}"
    );
    // Sampled attractors: some records differ that are one attractor both ways.
    assert!(different < differ, "{bif}");
    let steps = bif["steps"].as_u64().unwrap();
    for said in [
        format!("records differ at {differ} of the {steps} values"),
        format!(
            "{} of those are the same attractor both ways and {different} values hold different \
             attractors up and down",
            differ - different
        ),
    ] {
        assert!(html.contains(&said), "the caption does not say: {said}");
    }
}

/// Ctrl-C stops the report at once, says so (not the progress of a grid computed alongside)
/// and leaves nothing behind: no report, no staging directory.
#[test]
fn ctrl_c_leaves_no_report() {
    let (out, stopping) = assert_ctrl_c_leaves_nothing(&["reproduce", "--out", "report"]);
    let err = stderr(&out);
    assert!(
        err.contains("interrupted during ") && err.contains("the report was not written"),
        "{err}"
    );
    assert!(!err.contains("cancelled after"), "{err}");
    // Counted in CPU time after the signal (`interrupt_in`), which load does not stretch.
    assert!(
        stopping < std::time::Duration::from_secs(20),
        "{stopping:?} of CPU after the signal"
    );
}

#[test]
fn bad_output_directory_is_a_usage_error() {
    let dir = tempfile::tempdir().unwrap();
    let out = run_in(dir.path(), &["reproduce", "--out", "missing/deeper/report"]);
    assert_usage_error(dir.path(), &out, "missing/deeper");
    std::fs::write(dir.path().join("file"), "x").unwrap();
    let out = run_in(dir.path(), &["reproduce", "--out", "file"]);
    assert_eq!(out.status.code(), Some(2));
    assert!(stderr(&out).contains("not a directory"));
}

/// Fig. 3: a trace whose u_C is too small to see beside U (its peak under 30 % of the drive's,
/// recounted here from fig3_traces.csv) is drawn magnified by a power of ten that the legend
/// and the caption name; the spectra are on a logarithmic axis (the caption says how far
/// down); the loops of β = 1.07 have a row of their own.
fn fig3_shows_what_is_small(report: &Path, html: &str) {
    let csv = Csv::read(report, "fig3_traces.csv");
    let (w, beta) = (csv.at(Key::W.name()), csv.at(Key::Beta.name()));
    let (uc_v, u_v) = (csv.at("uc_V"), csv.at("u_V"));
    let mut peaks: Vec<((String, String), (f64, f64))> = Vec::new();
    for f in &csv.rows {
        let key = (f[w].clone(), f[beta].clone());
        let (uc, u): (f64, f64) = (f[uc_v].parse().unwrap(), f[u_v].parse().unwrap());
        match peaks.iter_mut().find(|(k, _)| *k == key) {
            Some((_, p)) => *p = (p.0.max(uc.abs()), p.1.max(u.abs())),
            None => peaks.push((key, (uc.abs(), u.abs()))),
        }
    }
    assert_eq!(peaks.len(), 6, "{peaks:?}");
    let svg = std::fs::read_to_string(report.join("fig3.svg")).unwrap();
    let labels = ["(1a)", "(1b)", "(1c)", "(2a)", "(2b)", "(2c)"];
    let mut small = 0;
    for (label, (_, (uc, u))) in labels.iter().zip(&peaks) {
        if *uc < 0.3 * u {
            small += 1;
            let gain = 10f64.powi((0.3 * u / uc).log10().ceil() as i32);
            assert!(
                html.contains(&format!("{label} ×{gain}")),
                "{label}: u_C {uc} V beside U {u} V, not said to be magnified ×{gain}"
            );
            assert!(
                svg.contains(&format!("u_C × {gain}")),
                "{label}: no legend ×{gain}"
            );
        } else {
            assert!(!html.contains(&format!("{label} ×")), "{label} magnified");
        }
    }
    assert!(small > 0, "no trace of Fig. 3 is small: {peaks:?}");
    assert!(html.contains("on a logarithmic axis down to 80 dB below the fundamental"));
    assert!(svg.contains("amplitude (V, log)"));
    for col in ["a", "b", "c"] {
        assert!(
            svg.contains(&format!("(3{col}′)")),
            "no loop (3{col}′) of its own"
        );
    }
}

/// The chapter "Friction-induced vibration": the closed form agrees with the exact cycle far
/// below the test's 1e-12, the approximation names the exact motion at every speed, and the
/// numbers the captions give are those of the CSV files, recounted here.
fn belt_chapter(report: &Path, summary: &serde_json::Value, html: &str) {
    assert!(html.contains("id=\"belt\"") && html.contains("Friction-induced vibration"));
    for id in [
        "belt-sweep",
        "belt-closed-form",
        "belt-approximation",
        "belt-forced-map",
    ] {
        assert!(html.contains(&format!("id=\"{id}\"")), "no section {id}");
    }
    let closed = Csv::read(report, "belt-closed-form.csv");
    let difference = closed.at("difference");
    let worst = closed
        .rows
        .iter()
        .map(|r| r[difference].parse::<f64>().unwrap().abs())
        .fold(0.0, f64::max);
    assert!(worst < 1e-12, "{worst}");
    assert_eq!(
        summary["belt_closed_form"]["largest_difference"].as_f64(),
        Some(worst)
    );
    let approx = Csv::read(report, "belt-approximation.csv");
    let (motion, class) = (approx.at("approximation_motion"), approx.at("class"));
    let agree = approx.rows.iter().filter(|r| r[motion] == r[class]).count();
    assert_eq!(agree, approx.rows.len());
    assert!(html.contains(&format!("at {agree} of the {} speeds", approx.rows.len())));
    // Both legs of both laws; the Coulomb belt's legs differ (hysteresis).
    let sweep = Csv::read(report, "belt-sweep.csv");
    let (law, direction) = (sweep.at("friction_law"), sweep.at("direction"));
    for l in ["coulomb", "stribeck"] {
        for d in ["up", "down"] {
            assert!(sweep.rows.iter().any(|r| r[law] == l && r[direction] == d));
        }
    }
    assert!(
        summary["belt_sweep"]["coulomb_hysteresis_steps"]
            .as_u64()
            .unwrap()
            > 0
    );
    let map = Csv::read(report, "belt-forced-map.csv");
    assert!(map.rows.len() >= 100);
}
