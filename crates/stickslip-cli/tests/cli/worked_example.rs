//! The worked example of docs/fit.md cannot go stale: every `stickslip fit` command the page
//! shows runs on the committed records (examples/fit/data) and must print the page's output
//! block (each number within one unit of its last printed digit, or 10⁻⁶ of it); every number
//! the page's conclusions quote is recomputed from the program's JSON at the page's rounding.

use super::common::{run_in, stderr, stdout};
use serde_json::Value;
use std::path::PathBuf;
use stickslip::shockley::DiodePair;

fn root() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../..")
}

fn page() -> String {
    std::fs::read_to_string(root().join("docs/fit.md")).expect("docs/fit.md")
}

fn data_dir() -> PathBuf {
    root().join("examples/fit/data")
}

/// Each (command, output) of the page: a fenced `sh` block that runs `stickslip fit`, and the
/// fenced `text` block right after it.
fn examples(page: &str) -> Vec<(Vec<String>, Vec<String>)> {
    let mut blocks: Vec<(String, Vec<String>)> = Vec::new();
    let mut current: Option<(String, Vec<String>)> = None;
    for line in page.lines() {
        let fence = line.trim_start();
        match current.take() {
            None => {
                if let Some(kind) = fence.strip_prefix("```") {
                    current = Some((kind.to_string(), Vec::new()));
                }
            }
            Some((kind, lines)) => {
                if fence == "```" {
                    blocks.push((kind, lines));
                } else {
                    let mut lines = lines;
                    lines.push(line.to_string());
                    current = Some((kind, lines));
                }
            }
        }
    }
    blocks
        .windows(2)
        .filter(|b| {
            b[0].0 == "sh"
                && b[1].0 == "text"
                && b[0]
                    .1
                    .first()
                    .is_some_and(|l| l.starts_with("stickslip fit"))
        })
        .map(|b| {
            let command = b[0].1.join(" ").replace('\\', " ");
            let args: Vec<String> = command
                .split_whitespace()
                .skip(1)
                .map(String::from)
                .collect();
            (args, b[1].1.clone())
        })
        .collect()
}

/// One unit in the last digit `token` shows ("8.281674e1" → 10⁻⁵, "-50257.592" → 10⁻³).
fn last_digit(token: &str) -> f64 {
    let (mantissa, exponent) = match token.split_once(['e', 'E']) {
        Some((m, e)) => (m, e.parse::<i32>().expect("an exponent")),
        None => (token, 0),
    };
    let decimals = mantissa.split_once('.').map_or(0, |(_, d)| d.len()) as i32;
    10f64.powi(exponent - decimals)
}

/// A token's number and the text before and after it ("(95" → ("(", "95", "")).
fn number_in(t: &str) -> Option<(&str, &str, &str)> {
    let start = t.find(|c: char| c.is_ascii_digit() || c == '-' || c == '.')?;
    let end = t.rfind(|c: char| c.is_ascii_digit() || c == '.')?;
    (start <= end).then(|| (&t[..start], &t[start..=end], &t[end + 1..]))
}

/// Whether the page's `want` token is the program's `got`: the same text, or the same
/// punctuation around numbers that agree to the page's last digit (or 10⁻⁶ of the value:
/// another platform's libm may move the last digit of a fitted value).
fn same_token(want: &str, got: &str) -> bool {
    if want == got {
        return true;
    }
    let (Some((wa, w, wb)), Some((ga, g, gb))) = (number_in(want), number_in(got)) else {
        return false;
    };
    let (Ok(x), Ok(y)) = (w.parse::<f64>(), g.parse::<f64>()) else {
        return false;
    };
    wa == ga && wb == gb && (x - y).abs() <= last_digit(w).max(1e-6 * y.abs())
}

/// Run `stickslip` in the records' directory; its standard output.
fn run(args: &[String]) -> String {
    let args: Vec<&str> = args.iter().map(String::as_str).collect();
    let out = run_in(&data_dir(), &args);
    assert!(
        out.status.success(),
        "stickslip {}: {}",
        args.join(" "),
        stderr(&out)
    );
    stdout(&out)
}

#[test]
fn the_page_shows_what_each_command_prints() {
    let page = page();
    let examples = examples(&page);
    assert_eq!(
        examples.len(),
        4,
        "docs/fit.md should show four `stickslip fit` commands with their output"
    );
    for (args, want) in &examples {
        let got = run(args);
        let got: Vec<&str> = got.lines().collect();
        // A block that starts with "..." shows the output's last lines.
        let (want, got) = match want.first().map(String::as_str) {
            Some("...") => (&want[1..], &got[got.len().saturating_sub(want.len() - 1)..]),
            _ => (&want[..], &got[..]),
        };
        assert_eq!(
            want.len(),
            got.len(),
            "stickslip {}: the page shows {} lines, the program prints {}:\n{}",
            args.join(" "),
            want.len(),
            got.len(),
            got.join("\n")
        );
        for (w, g) in want.iter().zip(got) {
            let (wt, gt): (Vec<&str>, Vec<&str>) = (
                w.split_whitespace().collect(),
                g.split_whitespace().collect(),
            );
            assert!(
                wt.len() == gt.len() && wt.iter().zip(&gt).all(|(a, b)| same_token(a, b)),
                "stickslip {}:\n  the page: {w}\n  printed:  {g}",
                args.join(" ")
            );
        }
    }
}

/// `x` to `decimals` places with a typographic minus, as the page writes numbers.
fn fixed(x: f64, decimals: usize) -> String {
    format!("{x:.decimals$}").replace('-', "−")
}

fn value(report: &Value, name: &str) -> f64 {
    report["parameters"][name]["value"].as_f64().unwrap()
}

/// The forward voltage of one diode at `current` (A): n V_T ln(1 + I/I_s) + I R_s.
fn forward_voltage(pair: &DiodePair, current: f64) -> f64 {
    pair.slope_voltage() * (current / pair.saturation_current).ln_1p()
        + current * pair.series_resistance
}

fn json(args: &str) -> Value {
    let mut args: Vec<String> = args.split_whitespace().map(String::from).collect();
    args.push("--json".into());
    serde_json::from_str(&run(&args)).expect("JSON")
}

#[test]
fn the_conclusions_quote_what_the_program_finds() {
    let page = page();
    let records = "--preset paper --data rigol-3kHz.csv --data keysight-10kHz.csv \
                   --data rigol-15kHz.csv";
    let both = json(&format!(
        "fit {records} --compare --free resistance,ut --free-shockley diode-is,diode-n,diode-rs"
    ));
    let per = json(&format!("fit {records} --per-record --free ut"));
    let (pwl, shockley) = (&both["pwl"], &both["shockley"]);
    let chi2 = |r: &Value| r["chi2_dof"].as_f64().unwrap();
    let mut quoted = vec![
        format!("(χ²/dof = {})", fixed(chi2(shockley), 2)),
        format!("ΔAIC = {}", fixed(both["delta_aic"].as_f64().unwrap(), 0)),
        format!("fit has χ²/dof = {}:", fixed(chi2(pwl), 2)),
        format!("R = {} Ω", fixed(value(pwl, "resistance"), 1)),
        format!("U_t = {} V", fixed(value(pwl, "ut"), 3)),
        format!(
            "(r = {})",
            fixed(pwl["correlation"][0][1].as_f64().unwrap(), 2)
        ),
        format!(
            "(r = {})",
            fixed(shockley["correlation"][0][1].as_f64().unwrap(), 3)
        ),
        format!("(χ²/dof = {})", fixed(chi2(&per[0]), 1)),
    ];
    for (i, freq) in ["at 3 kHz", "at 10 kHz", "at 15 kHz"].iter().enumerate() {
        quoted.push(format!("{} V {freq}", fixed(value(&per[i], "ut"), 3)));
        let stderr = per[i]["parameters"]["ut"]["stderr"].as_f64().unwrap();
        assert!(stderr < 0.005, "U_t {freq}: standard error {stderr} V");
    }
    let rs = &shockley["parameters"]["diode-rs"];
    let ci = rs["ci95"].as_array().unwrap();
    quoted.push(format!(
        "(R_s = {} Ω, 95 %: {} … {} Ω;",
        fixed(rs["value"].as_f64().unwrap(), 2),
        fixed(ci[0].as_f64().unwrap(), 2),
        fixed(ci[1].as_f64().unwrap(), 2)
    ));
    // The forward voltages of the table: fitted, the card ngspice simulated, the start.
    let fitted = DiodePair::new(
        value(shockley, "diode-is"),
        value(shockley, "diode-n"),
        value(shockley, "diode-rs"),
        27.0,
    )
    .unwrap();
    let card = DiodePair::new(2.682e-9, 1.836, 0.5664, 27.0).unwrap();
    let start = DiodePair::one_n4148();
    for (current, label, within) in [(1e-3, "1 mA", 0.1), (1e-2, "10 mA", 0.5)] {
        let (f, c, s) = (
            forward_voltage(&fitted, current),
            forward_voltage(&card, current),
            forward_voltage(&start, current),
        );
        let deviation = 100.0 * (f / c - 1.0);
        quoted.push(format!(
            "| {label} | {:.4} V | {:.4} V | {}{} % | {:.4} V |",
            f,
            c,
            if deviation >= 0.0 { "+" } else { "" },
            fixed(deviation, 2),
            s
        ));
        // "within 0.1 % of the card at 1 mA, within 0.5 % at 10 mA; the cards agree to 0.6 %".
        assert!(deviation.abs() < within, "{label}: {deviation} %");
        assert!(
            (s / c - 1.0).abs() < 0.006,
            "{label}: start {s} V, card {c} V"
        );
    }
    for q in &quoted {
        assert!(
            page.contains(q.as_str()),
            "docs/fit.md does not quote {q:?} (what the program finds now)"
        );
    }
    // "error bars well under 1 %" of the PWL values; "twice the noise" on the 3 kHz record.
    for name in ["resistance", "ut"] {
        let p = &pwl["parameters"][name];
        let relative = p["stderr"].as_f64().unwrap() / p["value"].as_f64().unwrap();
        assert!(relative < 0.005, "{name}: relative error {relative}");
    }
    assert!(page.contains("its residual is twice the noise"));
    let text = run(&format!("fit {records} --model pwl")
        .split_whitespace()
        .map(String::from)
        .collect::<Vec<_>>());
    let line = text
        .lines()
        .find(|l| l.starts_with("record rigol-3kHz.csv:"))
        .expect("the 3 kHz record's line");
    let volts = |after: &str| -> f64 {
        let rest = &line[line.find(after).expect(after) + after.len()..];
        rest.split_whitespace().next().unwrap().parse().unwrap()
    };
    let ratio = volts("RMS residual ") / volts("(noise ");
    assert!(
        (1.75..2.25).contains(&ratio),
        "PWL residual/noise at 3 kHz: {ratio}"
    );
}

#[test]
fn the_page_reads_its_records() {
    // The records the page names are the committed ones.
    for file in ["rigol-3kHz.csv", "keysight-10kHz.csv", "rigol-15kHz.csv"] {
        assert!(data_dir().join(file).is_file(), "{file}");
        assert!(page().contains(file), "{file}");
    }
}
