//! `stickslip curve --vb` on a forced Coulomb belt: the curve's start point is the special
//! point that `stickslip continue` locates on its own at the model's value of `--over` (both
//! commands run, their `--json` parsed), and the curve goes on from there to both ends of
//! its range.

use crate::common::*;

/// A case: the model's flags, what is followed, `[vary, from, to]` of the search (and of
/// `continue --over`), `[over, from, to]` of the curve.
type Case<'a> = (&'a [&'a str], &'a str, [&'a str; 3], [&'a str; 3]);

/// Run `args` with `--json`; the parsed standard output.
fn json(args: &[&str]) -> serde_json::Value {
    let (_dir, out) = run(&[args, &["--json"]].concat());
    assert!(out.status.success(), "{args:?}: {}", stderr(&out));
    serde_json::from_str(&stdout(&out)).unwrap()
}

#[test]
fn a_belts_curve_starts_at_continues_special_point() {
    // (model, follow, vary from → to, over from → to): a period doubling in vb over β on the
    // damped belt, a fold in vb over w on the undamped one.
    let cases: [Case; 2] = [
        (
            &[
                "--zeta", "0.05", "--w", "0.5", "--beta", "1", "--mu-s", "1.5",
            ],
            "period-doubling",
            ["vb", "0.2", "0.06"],
            ["beta", "0.9", "1.1"],
        ),
        (
            &[
                "--zeta", "0", "--w", "0.5", "--beta", "1", "--mu-s", "1.5", "--phi", "3",
            ],
            "fold",
            ["vb", "0.3", "1.5"],
            ["w", "0.47", "0.53"],
        ),
    ];
    for (model, follow, [vary, start, vary_to], [over, from, to]) in cases {
        let branch = json(
            &[
                &["continue"][..],
                model,
                &["--over", vary, "--from", start, "--to", vary_to],
            ]
            .concat(),
        );
        let special = branch["special"]
            .as_array()
            .unwrap()
            .iter()
            .find(|s| s["kind"] == follow)
            .unwrap_or_else(|| panic!("{follow}: {}", branch["special"]));
        let curve = json(
            &[
                &["curve"][..],
                model,
                &[
                    "--vb",
                    start,
                    "--follow",
                    follow,
                    "--vary",
                    vary,
                    "--vary-to",
                    vary_to,
                    "--over",
                    over,
                    "--from",
                    from,
                    "--to",
                    to,
                ],
            ]
            .concat(),
        );
        assert_eq!(curve["follow"], follow);
        assert_eq!(
            (curve["over"].as_str(), curve["vary"].as_str()),
            (Some(over), Some(vary))
        );
        let s = &curve["start"];
        let f = |v: &serde_json::Value| v.as_f64().unwrap();
        // The start at the model's value of --over, where the branch was continued.
        let model_over: f64 = model[model
            .iter()
            .position(|&m| m == format!("--{over}"))
            .unwrap()
            + 1]
        .parse()
        .unwrap();
        assert_eq!(f(&s["over"]), model_over, "{follow}");
        let (value, width) = (f(&special["value"]), f(&special["width"]));
        assert!(
            (f(&s["vary"]) - value).abs() < 1e-7,
            "{follow}: the curve starts at {vary} = {}, continue locates it at {value} \
             (width {width:e})",
            s["vary"]
        );
        for key in ["y", "v"] {
            assert!(
                (f(&s[key]) - f(&special[key])).abs() < 1e-6,
                "{follow}: start {key} = {}, continue's {}",
                s[key],
                special[key]
            );
        }
        // From there to both ends of --over's range.
        assert!(
            curve["points"].as_u64().unwrap() >= 20,
            "{}",
            curve["points"]
        );
        assert!(s["index"].as_u64().unwrap() > 0);
        for end in ["begin", "end"] {
            assert_eq!(curve[end]["reason"], "boundary", "{follow}: {}", curve[end]);
        }
    }
}
