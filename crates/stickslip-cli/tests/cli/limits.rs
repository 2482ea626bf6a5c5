//! The documented ranges (docs/limits.md) at the command line: a value outside gives one
//! line naming the flag, the value and the range, exit code 2, before any work.

use crate::common::*;

#[test]
fn values_outside_the_supported_ranges_are_refused_before_any_work() {
    let cases: &[(&[&str], &str)] = &[
        (
            &["steady", "--w", "1", "--beta", "1e300"],
            "invalid --beta 1e300: must be finite and from 0 to 1e9 (docs/limits.md)",
        ),
        (
            &["steady", "--w", "1", "--beta", "1", "--y0", "1e300"],
            "invalid --y0 1e300: must be finite and from -1e9 to 1e9",
        ),
        (
            &["steady", "--w", "1e-300", "--beta", "1"],
            "invalid --w 1e-300: must be finite and from 1e-5 to 1e5",
        ),
        (
            &["steady", "--w", "2e5", "--beta", "1"],
            "invalid --w 200000",
        ),
        (
            &["steady", "--w", "1", "--beta", "1", "--v0", "-2e9"],
            "invalid --v0 -2000000000",
        ),
        (
            &["steady", "--w", "1", "--beta", "1", "--zeta", "1e5"],
            "invalid --zeta 100000",
        ),
        (
            &["steady", "--w", "1", "--beta", "1", "--mu-s", "1e10"],
            "invalid --mu-s 10000000000",
        ),
        (
            &["steady", "--w", "1", "--beta", "1", "--phi", "1e7"],
            "invalid --phi 10000000",
        ),
        (
            &[
                "steady", "--preset", "paper", "--freq", "1.1G", "--beta", "1",
            ],
            "invalid --freq 1100000000: it gives w = 104818.1",
        ),
        (
            &[
                "steady",
                "--preset",
                "paper",
                "--w",
                "1",
                "--amplitude",
                "1e10",
            ],
            "invalid --amplitude 10000000000: it gives beta = 14285714285.7",
        ),
        (
            &[
                "steady",
                "--preset",
                "paper",
                "--w",
                "1",
                "--beta",
                "1",
                "--resistance",
                "2e7",
            ],
            "invalid --resistance 20000000: it gives zeta = 1318",
        ),
        (
            &[
                "simulate",
                "--w",
                "1e-5",
                "--beta",
                "1",
                "--periods",
                "7000",
            ],
            "a run of 7000 drive periods at w = 1e-5 is too long",
        ),
        (
            &[
                "steady",
                "--w",
                "0.1",
                "--beta",
                "1",
                "--max-periods",
                "100000000",
            ],
            "is too long",
        ),
        (
            &[
                "phase-diagram",
                "--w-min",
                "1e-5",
                "--w-max",
                "1",
                "--w-steps",
                "2",
                "--max-periods",
                "100000",
            ],
            "is too long",
        ),
    ];
    for (args, needle) in cases {
        let (dir, out) = run(args);
        assert_usage_error(dir.path(), &out, needle);
        assert!(
            !stderr(&out).contains(": dimensionless:"),
            "{args:?}: refused only after describing the run: {}",
            stderr(&out)
        );
    }
}

#[test]
fn values_just_inside_the_ranges_run() {
    let cases: &[&[&str]] = &[
        &[
            "steady",
            "--w",
            "1",
            "--beta",
            "1e9",
            "--max-periods",
            "200",
        ],
        &["simulate", "--w", "1e5", "--beta", "1e9", "--periods", "3"],
        &[
            "simulate",
            "--w",
            "1e-5",
            "--beta",
            "3",
            "--periods",
            "2",
            "--samples-per-period",
            "10",
        ],
        &[
            "simulate", "--w", "0.9", "--beta", "2", "--y0", "-1e9", "--v0", "1e9", "--zeta", "1e4",
        ],
        &[
            "simulate", "--w", "0.7", "--beta", "1e9", "--mu-s", "1e9", "--phi", "-1e6",
        ],
    ];
    for args in cases {
        let (_dir, out) = run(args);
        assert!(out.status.success(), "{args:?}: {}", stderr(&out));
    }
}
