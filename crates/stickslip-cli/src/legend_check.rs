//! No legend hides data: every figure of `stickslip reproduce` and every `--plot` is drawn,
//! and for each legend the plot module reports how many pixels of data (series and cells,
//! drawn alone with the final layout) lie under its box.

use crate::plot::LEGEND_LOG;
use clap::Parser;
use std::path::Path;

/// Pixels of data a legend box may cover: antialiasing of a line that grazes its edge.
const TOLERANCE: usize = 4;

/// Run the tool in this process with `args` (paths relative to `dir`).
fn run(dir: &Path, args: &[&str]) {
    let args: Vec<String> = std::iter::once("stickslip".to_string())
        .chain(args.iter().map(|a| {
            if a.ends_with(".png") || a.ends_with(".svg") || a.ends_with(".csv") || *a == "report" {
                dir.join(a).display().to_string()
            } else {
                a.to_string()
            }
        }))
        .collect();
    let cli = crate::Cli::try_parse_from(&args).unwrap_or_else(|e| panic!("{args:?}: {e}"));
    crate::commands::run(cli.command).unwrap_or_else(|e| panic!("{args:?}: {e:#}"));
}

/// The legends drawn into files under `dir`: (file name, placement).
fn placements(dir: &Path) -> Vec<(String, crate::plot::LegendPlacement)> {
    LEGEND_LOG
        .lock()
        .unwrap_or_else(|e| e.into_inner())
        .iter()
        .filter(|(path, _)| path.starts_with(dir))
        .map(|(path, p)| {
            let name = path.file_name().unwrap_or_default().to_string_lossy();
            (name.to_string(), p.clone())
        })
        .collect()
}

/// Every legend of `dir` covers at most [`TOLERANCE`] pixels of data; every name of
/// `expected` has at least one legend (so that the test sees what it claims to check).
fn check(dir: &Path, expected: &[&str]) {
    let seen = placements(dir);
    let bad: Vec<String> = seen
        .iter()
        .filter(|(_, p)| p.overlap > TOLERANCE)
        .map(|(file, p)| format!("{file} '{}': {} px at {:?}", p.panel, p.overlap, p.rect))
        .collect();
    assert!(bad.is_empty(), "legends on data:\n{}", bad.join("\n"));
    for name in expected {
        assert!(
            seen.iter().any(|(file, _)| file.starts_with(name)),
            "no legend recorded for {name}: {:?}",
            seen.iter().map(|s| &s.0).collect::<Vec<_>>()
        );
    }
    // A box outside the plotting area lies right of it; one inside, within it.
    for (file, p) in &seen {
        let inside = p.rect.0 >= p.plot.0
            && p.rect.1 >= p.plot.1
            && p.rect.2 <= p.plot.2
            && p.rect.3 <= p.plot.3;
        assert!(
            inside != p.outside && (!p.outside || p.rect.0 >= p.plot.2),
            "{file} '{}': {p:?}",
            p.panel
        );
    }
}

#[test]
fn no_legend_of_the_report_hides_data() {
    let dir = tempfile::tempdir().expect("a temporary directory");
    run(dir.path(), &["reproduce", "--quick", "--out", "report"]);
    // The report renders into a staging directory inside its target's parent.
    check(
        dir.path(),
        &[
            "fig3.png",
            "fig3.svg",
            "fig4.png",
            "fig5.png",
            "fig6.png",
            "fig7.png",
            "chaos-sweep.png",
            "chaos-map.png",
            "paper-exponents.png",
            "beyond-bifurcation.png",
            "beyond-basins.png",
            "beyond-branch.png",
            "floquet-laws.png",
        ],
    );
    // The basin map is a phase plane, y0 and y0' over the same range: a square plotting area.
    let basins: Vec<_> = placements(dir.path())
        .into_iter()
        .filter(|(file, _)| file.starts_with("beyond-basins"))
        .collect();
    assert!(!basins.is_empty());
    for (file, p) in basins {
        let (w, h) = (p.plot.2 - p.plot.0, p.plot.3 - p.plot.1);
        assert!(
            (w - h).abs() <= 2,
            "{file}: a plotting area of {w} × {h} px"
        );
    }
}

#[test]
fn no_legend_of_a_plot_hides_data() {
    let dir = tempfile::tempdir().expect("a temporary directory");
    let d = dir.path();
    let chaos = ["--zeta", "0", "--mu-s", "3", "--beta", "9"];
    let with = |first: &[&'static str], rest: &[&'static str]| -> Vec<&'static str> {
        first.iter().chain(rest).copied().collect()
    };
    let cases: Vec<Vec<&str>> = vec![
        vec![
            "simulate",
            "--w",
            "0.6",
            "--beta",
            "1.2",
            "--periods",
            "6",
            "--out",
            "sim.csv",
            "--plot",
            "simulate.png",
        ],
        vec![
            "simulate",
            "--preset",
            "paper",
            "--freq",
            "6k",
            "--amplitude",
            "1.0",
            "--periods",
            "6",
            "--out",
            "simc.csv",
            "--plot",
            "simulate-circuit.svg",
        ],
        vec![
            "steady",
            "--w",
            "0.6",
            "--beta",
            "1.2",
            "--plot",
            "steady.png",
        ],
        vec![
            "steady",
            "--w",
            "0.7",
            "--beta",
            "1.0",
            "--plot",
            "steady-static.png",
        ],
        vec![
            "sweep",
            "--preset",
            "paper",
            "--over",
            "w",
            "--beta",
            "2.14",
            "--from",
            "0.2",
            "--to",
            "2",
            "--steps",
            "31",
            "--out",
            "sweep.csv",
            "--plot",
            "sweep.png",
        ],
        vec![
            "sweep",
            "--zeta",
            "0.047",
            "--over",
            "beta",
            "--w",
            "0.5",
            "--from",
            "1",
            "--to",
            "6",
            "--steps",
            "21",
            "--out",
            "sweepb.csv",
            "--plot",
            "sweep-beta.png",
        ],
        vec![
            "phase-diagram",
            "--preset",
            "paper",
            "--w-min",
            "0.2",
            "--w-max",
            "2",
            "--w-steps",
            "12",
            "--beta-min",
            "0.5",
            "--beta-max",
            "4",
            "--beta-steps",
            "12",
            "--out",
            "map.csv",
            "--plot",
            "map.png",
        ],
        vec![
            "phase-diagram",
            "--zeta",
            "0",
            "--mu-s",
            "3",
            "--w-min",
            "0.25",
            "--w-max",
            "0.40",
            "--w-steps",
            "4",
            "--beta-min",
            "2",
            "--beta-max",
            "9",
            "--beta-steps",
            "3",
            "--color",
            "lyapunov",
            "--out",
            "lmap.csv",
            "--plot",
            "map-lyapunov.png",
        ],
        vec![
            "theory",
            "--zeta",
            "0.0468",
            "--curve",
            "boundary",
            "--out",
            "b.csv",
            "--plot",
            "theory-boundary.png",
        ],
        vec![
            "theory",
            "--zeta",
            "0.0468",
            "--curve",
            "boundary",
            "--w-min",
            "0.05",
            "--w-max",
            "10",
            "--log",
            "--out",
            "bl.csv",
            "--plot",
            "theory-boundary-log.png",
        ],
        vec![
            "theory",
            "--zeta",
            "0.0468",
            "--curve",
            "gain",
            "--beta",
            "1.5",
            "--out",
            "g.csv",
            "--plot",
            "theory-gain.png",
        ],
        with(&["bifurcation"], &chaos)
            .into_iter()
            .chain([
                "--over",
                "w",
                "--from",
                "0.33",
                "--to",
                "0.42",
                "--steps",
                "4",
                "--points",
                "30",
                "--transient",
                "100",
                "--out",
                "bif.csv",
                "--plot",
                "bifurcation.png",
            ])
            .collect(),
        vec![
            "basins",
            "--zeta",
            "0",
            "--mu-s",
            "3",
            "--w",
            "0.6",
            "--beta",
            "3.269",
            "--y0-min",
            "-8",
            "--y0-max",
            "8",
            "--v0-min",
            "-8",
            "--v0-max",
            "8",
            "--steps",
            "12",
            "--out",
            "basins.csv",
            "--plot",
            "basins.png",
        ],
        vec![
            "continue",
            "--zeta",
            "0.046816",
            "--mu-s",
            "1.5",
            "--w",
            "0.9",
            "--y0",
            "0.25",
            "--v0",
            "2.1",
            "--over",
            "beta",
            "--from",
            "1.45",
            "--to",
            "1.2",
            "--out",
            "branch.csv",
            "--plot",
            "continue.png",
        ],
    ];
    for args in &cases {
        run(d, args);
    }
    check(
        d,
        &[
            "simulate.png",
            "simulate-circuit.svg",
            "steady.png",
            "steady-static.png",
            "sweep.png",
            "sweep-beta.png",
            "map.png",
            "map-lyapunov.png",
            "theory-boundary.png",
            "theory-boundary-log.png",
            "theory-gain.png",
            "bifurcation.png",
            "basins.png",
            "continue.png",
        ],
    );
}

#[test]
fn no_legend_of_a_measurement_plot_hides_data() {
    use crate::measured::synthetic;
    let dir = tempfile::tempdir().expect("a temporary directory");
    let d = dir.path();
    let write = |name: &str, text: String| std::fs::write(d.join(name), text).expect("written");
    write("rec-a.csv", synthetic::record(0.5, 2.5, false));
    write("rec-b.csv", synthetic::record(1.2, 2.0, true));
    write("legs.csv", synthetic::table(&[0.9, 1.5], true));
    write("rest.csv", synthetic::table(&[1.2], false));
    let circuit = ["--preset", "paper", "--resistance", "80", "--ut", "0.6"];
    let cases: Vec<Vec<&str>> = vec![
        vec![
            "fit",
            "--preset",
            "paper",
            "--data",
            "rec-a.csv",
            "--data",
            "rec-b.csv",
            "--plot",
            "fit-records.png",
        ],
        vec![
            "fit",
            "--preset",
            "paper",
            "--gain-table",
            "legs.csv",
            "--plot",
            "fit-legs.png",
        ],
        vec![
            "fit",
            "--preset",
            "paper",
            "--gain-table",
            "rest.csv",
            "--plot",
            "fit-rest.png",
        ],
        [
            &["steady"][..],
            &circuit,
            &[
                "--w",
                "0.5",
                "--beta",
                "2.5",
                "--data",
                "rec-a.csv",
                "--plot",
                "steady-data.png",
            ],
        ]
        .concat(),
        [
            &["simulate"][..],
            &circuit,
            &[
                "--w",
                "1.2",
                "--beta",
                "2",
                "--periods",
                "12",
                "--out",
                "sim-data.csv",
                "--data",
                "rec-b.csv",
                "--plot",
                "simulate-data.png",
            ],
        ]
        .concat(),
    ];
    for args in &cases {
        run(d, args);
    }
    check(
        d,
        &[
            "fit-records.png",
            "fit-legs.png",
            "fit-rest.png",
            "steady-data.png",
            "simulate-data.png",
        ],
    );
}
