//! Every tool with every friction law and a belt: it works, or it refuses in one line naming
//! what it does not take (exit status 2); it never panics.

use crate::common::*;

/// The laws: Stribeck's and the cubic on a belt, and Coulomb's on a belt.
const STRIBECK: &[&str] = &[
    "--friction-law",
    "stribeck",
    "--mu-s",
    "1.5",
    "--vs",
    "0.3",
    "--vb",
    "0.5",
];
pub(crate) const CUBIC: &[&str] = &[
    "--friction-law",
    "cubic",
    "--mu-s",
    "1.5",
    "--k1",
    "0.5",
    "--k3",
    "0.5",
    "--vb",
    "0.3",
];
const COULOMB_BELT: &[&str] = &["--vb", "0.5", "--mu-s", "1.5"];

/// What a tool does with a law: works (exit 0), fits (exit 0, or 3 when the fit did not
/// converge), or refuses with a line containing the text.
#[derive(Debug, Clone, Copy)]
enum Outcome {
    Works,
    Fits,
    Refuses(&'static str),
}

/// The cubic belt's branch from w = 0.9, β = 1.45 has no fold down to β = 1.2: `curve` runs
/// and says so.
const NO_FOLD: Outcome = Outcome::Refuses("no fold on the branch");
const THEORY: Outcome = Outcome::Refuses("the theory (the paper's series, the exact periodic");

fn tools() -> Vec<(Vec<&'static str>, [Outcome; 3])> {
    use Outcome::Works;
    vec![
        (
            vec!["orbit", "--w", "1", "--beta", "2"],
            [Works, Works, Works],
        ),
        (
            vec![
                "lyapunov",
                "--w",
                "1",
                "--beta",
                "2",
                "--transient",
                "50",
                "--periods",
                "100",
            ],
            [Works, Works, Works],
        ),
        (
            vec![
                "continue", "--beta", "2", "--over", "w", "--from", "1", "--to", "1.1",
            ],
            [Works, Works, Works],
        ),
        (
            vec![
                "bifurcation",
                "--beta",
                "2",
                "--over",
                "w",
                "--from",
                "1",
                "--to",
                "1.1",
                "--steps",
                "3",
                "--points",
                "10",
                "--transient",
                "20",
                "--first-transient",
                "50",
            ],
            [Works, Works, Works],
        ),
        (
            vec![
                "basins", "--w", "1", "--beta", "2", "--steps", "3", "--y0-min", "-1", "--y0-max",
                "1", "--v0-min", "-1", "--v0-max", "1",
            ],
            [Works, Works, Works],
        ),
        (
            [&["curve"][..], &FOLD_CURVE].concat(),
            [Works, NO_FOLD, Works],
        ),
        (
            vec![
                "phase-diagram",
                "--zeta",
                "0.1",
                "--w-min",
                "0.9",
                "--w-max",
                "1.1",
                "--w-steps",
                "2",
                "--beta-min",
                "1.5",
                "--beta-max",
                "2.5",
                "--beta-steps",
                "2",
                "--color",
                "lambda1",
            ],
            [Works, Works, Works],
        ),
        (
            vec!["theory", "--w", "1", "--beta", "2"],
            [THEORY, THEORY, THEORY],
        ),
        (
            vec!["steady", "--w", "1", "--beta", "2"],
            [Works, Works, Works],
        ),
        (
            vec![
                "sweep", "--beta", "2", "--over", "w", "--from", "0.5", "--to", "1", "--steps", "3",
            ],
            [Works, Works, Works],
        ),
    ]
}

fn check(dir: &std::path::Path, args: &[&str], outcome: Outcome) {
    let out = run_in(dir, args);
    let err = stderr(&out);
    assert!(!err.contains("panicked"), "{args:?} panicked: {err}");
    match outcome {
        Outcome::Works => assert!(out.status.success(), "{args:?}: {err}"),
        Outcome::Fits => assert!(matches!(out.status.code(), Some(0 | 3)), "{args:?}: {err}"),
        Outcome::Refuses(text) => {
            assert_eq!(out.status.code(), Some(2), "{args:?}: {err}");
            let errors: Vec<&str> = err.lines().filter(|l| l.starts_with("error:")).collect();
            assert_eq!(errors.len(), 1, "{args:?}: {err}");
            assert!(errors[0].contains(text), "{args:?}: {err}");
            assert_eq!(
                err.lines().last(),
                Some(errors[0]),
                "{args:?}: one line at the end"
            );
        }
    }
}

#[test]
fn every_tool_with_every_law_works_or_refuses_in_one_line() {
    let dir = tempfile::tempdir().unwrap();
    for (tool, outcomes) in tools() {
        for (law, outcome) in [STRIBECK, CUBIC, COULOMB_BELT].into_iter().zip(outcomes) {
            let mut args = tool.clone();
            args.extend_from_slice(law);
            check(dir.path(), &args, outcome);
        }
    }
}

/// A grazing curve with a smooth law is refused in one line naming the law (its fold, period
/// doubling and Neimark–Sacker curves are followed).
#[test]
fn a_grazing_curve_with_a_smooth_law_is_refused_naming_the_law() {
    let dir = tempfile::tempdir().unwrap();
    for (law, name) in [(STRIBECK, "stribeck"), (CUBIC, "cubic")] {
        let mut args = vec!["curve"];
        args.extend_from_slice(&FOLD_CURVE);
        let follow = args.iter().position(|a| *a == "fold").unwrap();
        args[follow] = "grazing";
        args.extend_from_slice(law);
        let out = run_in(dir.path(), &args);
        check(
            dir.path(),
            &args,
            Outcome::Refuses("grazing curves follow the exact solver's events"),
        );
        assert!(
            stderr(&out).contains(&format!("with the {name} law a curve follows a fold")),
            "{}",
            stderr(&out)
        );
    }
}

/// A mechanical record fitted with a belt or another law: the fit runs with the law (it
/// converges or says it did not), it never panics.
#[test]
fn fit_takes_a_belt_and_the_smooth_laws() {
    let dir = tempfile::tempdir().unwrap();
    let mechanics = [
        "--mass",
        "0.5",
        "--stiffness",
        "200",
        "--damping",
        "1.5",
        "--friction",
        "0.4",
    ];
    let mut simulate = vec!["simulate"];
    simulate.extend(mechanics);
    simulate.extend(["--freq", "2", "--amplitude", "1", "--periods", "5"]);
    let out = run_in(dir.path(), &simulate);
    assert!(out.status.success(), "{}", stderr(&out));
    let mut record = String::from("time_s,F (N),r (m)\n");
    let text = stdout(&out);
    let mut lines = text.lines();
    let header: Vec<&str> = lines.next().unwrap().split(',').collect();
    let at = |name: &str| header.iter().position(|h| *h == name).unwrap();
    let (t, f, r) = (at("t_s"), at("F_N"), at("r_m"));
    for line in lines {
        let cells: Vec<&str> = line.split(',').collect();
        record.push_str(&format!("{},{},{}\n", cells[t], cells[f], cells[r]));
    }
    std::fs::write(dir.path().join("record.csv"), record).unwrap();
    for law in [
        &[
            "--friction-law",
            "stribeck",
            "--mu-s",
            "1.5",
            "--stribeck-speed",
            "0.01",
        ][..],
        &[
            "--friction-law",
            "cubic",
            "--mu-s",
            "1.5",
            "--cubic-k1",
            "0.5",
            "--cubic-k3",
            "0.5",
        ],
        &["--belt-speed", "0.01", "--mu-s", "1.5"],
    ] {
        let mut args = vec!["fit"];
        args.extend(mechanics);
        args.extend_from_slice(law);
        args.extend(["--data", "record.csv"]);
        check(dir.path(), &args, Outcome::Fits);
    }
}
