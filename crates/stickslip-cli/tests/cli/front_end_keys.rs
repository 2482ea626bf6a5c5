//! The front ends write no key of the system by hand: a fit parameter's name, a key's symbol
//! or unit, a default free set are the library's (`Key`, `FitParameter`), so that a new key
//! or fit parameter is one row of the key table. A scan of the Rust sources of the command
//! line, the lab and the Python package, and of the package's Python modules (their test code
//! left out), finds every string literal that is, or whose words are, a flag, a name or a
//! symbol of a key of the table's system and diode groups (the circuit's and the mechanical
//! oscillator's parts, the diodes' parameters; not the keys whose values are names, nor those
//! a sweep varies, which have names of their own, `Parameter`), or such a key's unit: a
//! literal with a space in it is prose and skipped, as are one-letter ASCII names (`R`, `m`,
//! `n` name too many other things). Only the occurrences below, each with its reason, are
//! allowed. The lab's scripts have their own scan (`crates/stickslip-lab/src/tests/page_keys.rs`).

use std::collections::BTreeSet;
use std::path::{Path, PathBuf};
use stickslip::experiment::{Key, KeyForm, KeyGroup};
use stickslip::fit::FitParameter;
use stickslip::Parameter;
use stickslip_testkit::allowances::{Allowance, Scan};

/// Python's static signatures: pyo3 needs each keyword of a constructor written out (so that
/// `help()` shows it); `tests/test_keys.py` checks every one against the key table.
const SIGNATURE: &str = "a keyword of a Python constructor's static signature (pyo3), which \
                         tests/test_keys.py checks against the table";

/// The occurrences a front end may write, each on a line holding its fragment.
const ALLOWED: &[Allowance] = &[
    Allowance {
        file: "stickslip-py/python/stickslip/_stability.py",
        word: "damping",
        fragment: "self.sliding_damping: float = sliding[\"damping\"]",
        reason: "the self-excited orbit's answer field `sliding.damping` (steady sliding's \
                 2ζ + μ'(|vb|)), not the oscillator's γ",
    },
    Allowance {
        file: "stickslip-cli/src/commands/reproduce/figures/fig1.rs",
        word: "friction",
        fragment: "&[\"velocity\", \"friction\"]",
        reason: "the columns of fig1a.csv: the friction force against the velocity (the \
                 paper's Fig. 1), not the key F0",
    },
    Allowance {
        file: "stickslip-py/src/experiment.rs",
        word: "U_t",
        fragment: "(\"U_t\", U_t)",
        reason: SIGNATURE,
    },
    Allowance {
        file: "stickslip-py/src/experiment.rs",
        word: "R_D",
        fragment: "(\"R_D\", R_D)",
        reason: SIGNATURE,
    },
    Allowance {
        file: "stickslip-py/src/experiment.rs",
        word: "Is",
        fragment: "(\"Is\", Is)",
        reason: SIGNATURE,
    },
    Allowance {
        file: "stickslip-py/src/experiment.rs",
        word: "Rs",
        fragment: "(\"Rs\", Rs)",
        reason: SIGNATURE,
    },
    Allowance {
        file: "stickslip-py/src/experiment.rs",
        word: "temperature",
        fragment: "(\"temperature\", temperature)",
        reason: SIGNATURE,
    },
    Allowance {
        file: "stickslip-py/src/experiment.rs",
        word: "gamma",
        fragment: "(\"gamma\", gamma)",
        reason: SIGNATURE,
    },
    Allowance {
        file: "stickslip-py/src/experiment.rs",
        word: "F0",
        fragment: "(\"F0\", F0)",
        reason: SIGNATURE,
    },
];

/// The keys whose spellings no front end writes: numbers of the system and diode groups that
/// no sweep varies.
fn keys() -> Vec<Key> {
    Key::ALL
        .into_iter()
        .filter(|k| matches!(k.group(), KeyGroup::System | KeyGroup::Diode))
        .filter(|k| k.form() != KeyForm::Choice)
        .filter(|k| !Parameter::ALL.iter().any(|p| p.keys().contains(k)))
        .collect()
}

/// What the scan looks for: `words`, each key's flag (`resistance`, `diode-is`: found in a
/// literal or among its words, as in `"resistance,ut"`), and `literals`, each key's name,
/// symbol and unit as the table and the pages write them (`U_t`, `γ`, `N/m`: found as a whole
/// literal, not inside a formula such as `"U/U_t"`), one-letter ASCII ones and one-letter
/// units left out.
fn spellings() -> (BTreeSet<String>, BTreeSet<String>) {
    let (mut words, mut literals) = (BTreeSet::new(), BTreeSet::new());
    let long = |w: &str| w.chars().count() > 1;
    for key in keys() {
        for flag in std::iter::once(key.flag()).chain(key.aliases().iter().copied()) {
            if long(flag) {
                words.insert(flag.to_string());
            }
        }
        let names = [key.name(), key.symbol()]
            .into_iter()
            .chain(key.name_aliases().iter().copied());
        for w in names {
            if long(w) || !w.is_ascii() {
                literals.insert(w.to_string());
            }
        }
        for unit in key.unit().into_iter().chain(key.shown_unit()) {
            if long(unit) {
                literals.insert(unit.to_string());
            }
        }
    }
    assert!(words.contains("diode-is") && literals.contains("U_t") && literals.contains("N/m"));
    (words, literals)
}

/// The string literals of `source` (Rust `"…"`, Python `'…'` and `"…"`; Python's triple-quoted
/// docstrings are prose), each with its line, comments left out.
fn literals(source: &str, python: bool) -> Vec<(usize, String)> {
    let s: Vec<char> = source.chars().collect();
    let mut out = Vec::new();
    let (mut i, mut line) = (0, 1);
    while i < s.len() {
        let c = s[i];
        let next = s.get(i + 1).copied();
        if c == '\n' {
            line += 1;
            i += 1;
        } else if (!python && c == '/' && next == Some('/')) || (python && c == '#') {
            while i < s.len() && s[i] != '\n' {
                i += 1;
            }
        } else if !python && c == '/' && next == Some('*') {
            while i + 1 < s.len() && !(s[i] == '*' && s[i + 1] == '/') {
                line += usize::from(s[i] == '\n');
                i += 1;
            }
            i += 2;
        } else if python && (c == '"' || c == '\'') && next == Some(c) && s.get(i + 2) == Some(&c) {
            // A docstring: prose to its closing quotes.
            i += 3;
            while i + 2 < s.len() && !(s[i] == c && s[i + 1] == c && s[i + 2] == c) {
                line += usize::from(s[i] == '\n');
                i += 1;
            }
            i += 3;
        } else if c == '"' || (python && c == '\'') {
            let (start, mut text) = (line, String::new());
            i += 1;
            while i < s.len() && s[i] != c {
                if s[i] == '\\' {
                    // An escape, or a line continuation (`\` at the end of a line).
                    i += 1;
                    if s.get(i) == Some(&'\n') {
                        line += 1;
                        text.push(' ');
                        i += 1;
                        continue;
                    }
                }
                if s[i] == '\n' {
                    line += 1;
                }
                text.extend(s.get(i));
                i += 1;
            }
            i += 1;
            out.push((start, text));
        } else if !python && c == '\'' {
            // A char literal or a lifetime: skip the quote and the char.
            i += if s.get(i + 2) == Some(&'\'') { 3 } else { 1 };
        } else {
            i += 1;
        }
    }
    out
}

/// The source without its test code: a Rust file from its `#[cfg(test)]` on.
fn without_tests(source: &str) -> &str {
    match source.find("#[cfg(test)]") {
        Some(at) => &source[..at],
        None => source,
    }
}

fn files(dir: &Path, out: &mut Vec<PathBuf>) {
    for entry in std::fs::read_dir(dir).expect("a readable source directory") {
        let path = entry.expect("a directory entry").path();
        let name = path.file_name().unwrap().to_string_lossy().into_owned();
        if path.is_dir() {
            if name != "tests" && name != "__pycache__" {
                files(&path, out);
            }
        } else if (name.ends_with(".rs") && name != "tests.rs")
            || (name.ends_with(".py") && !name.starts_with("test_"))
        {
            out.push(path);
        }
    }
}

/// Every occurrence of a word of [`words`] in the front ends' sources not in [`ALLOWED`], as
/// `file:line: word: the line`, and the allowances that matched nothing.
fn hand_written(sources: &[(String, String)]) -> (Vec<String>, Vec<String>) {
    let (words, whole) = spellings();
    let mut scan = Scan::new(ALLOWED);
    for (file, text) in sources {
        let python = file.ends_with(".py");
        let code = if python {
            text.as_str()
        } else {
            without_tests(text)
        };
        let lines: Vec<&str> = code.lines().collect();
        for (line, literal) in literals(code, python) {
            let hits: Vec<&str> = if words.contains(&literal) || whole.contains(&literal) {
                vec![literal.as_str()]
            } else if literal.contains(char::is_whitespace) {
                continue; // prose: "the paper's circuit (L = 11.5 mH, …)"
            } else {
                literal
                    .split(|c: char| !(c.is_alphanumeric() || c == '_' || c == '-'))
                    .filter(|w| words.contains(*w))
                    .collect()
            };
            let source = lines.get(line - 1).copied().unwrap_or_default();
            for word in hits {
                scan.occurrence(file, line, word, source);
            }
        }
    }
    scan.finish()
}

/// The front ends' sources: the command line's, the lab's and the Python package's.
fn sources() -> Vec<(String, String)> {
    let crates = Path::new(env!("CARGO_MANIFEST_DIR"))
        .parent()
        .expect("the crates folder")
        .to_path_buf();
    let mut paths = Vec::new();
    for dir in [
        "stickslip-cli/src",
        "stickslip-lab/src",
        "stickslip-py/src",
        "stickslip-py/python",
    ] {
        files(&crates.join(dir), &mut paths);
    }
    paths.sort();
    assert!(paths.len() >= 40, "{} files", paths.len());
    paths
        .into_iter()
        .map(|p| {
            let text = std::fs::read_to_string(&p).expect("a readable source file");
            let name = p
                .strip_prefix(&crates)
                .unwrap()
                .to_string_lossy()
                .into_owned();
            (name, text)
        })
        .collect()
}

#[test]
fn the_front_ends_write_no_key_or_fit_parameter_by_hand() {
    let (found, stale) = hand_written(&sources());
    assert!(
        found.is_empty(),
        "keys written by hand in the front ends (take them from the library's Key or \
         FitParameter, or allow the occurrence in ALLOWED with its reason):\n{}",
        found.join("\n")
    );
    assert!(
        stale.is_empty(),
        "allowances that match nothing any more: {stale:?}"
    );
}

/// The scan finds what the front ends wrote before the fit parameters were keys: the command
/// line's symbol and unit table, the default free sets, the lab's list of parameters; and
/// skips comments, prose and test code.
#[test]
fn the_scan_finds_the_tables_and_lists_that_were_written_by_hand() {
    let before = "// 'resistance' in a comment is fine\n\
                  fn symbol(p: FitParameter) -> (&'static str, &'static str) {\n\
                  \x20   match p { Ut => (\"U_t\", \"V\"), Rd => (\"R_D\", \"Ω\"), \
                  Damping => (\"γ\", \"kg/s\"), MuS => (\"μs\", \"\") }\n}\n\
                  let default_free = if mechanics { \"damping,friction\" } else { \"resistance,ut\" };\n\
                  let prose = \"a circuit (preset=paper, or inductance, capacitance)\";\n\
                  #[cfg(test)]\nmod tests { const X: &str = \"diode-is\"; }\n";
    let (found, stale) = hand_written(&[("stickslip-cli/src/measured.rs".into(), before.into())]);
    let hits: Vec<&str> = found
        .iter()
        .map(|f| f.split(": ").nth(1).unwrap())
        .collect();
    assert_eq!(
        hits,
        ["U_t", "R_D", "γ", "damping", "friction", "resistance", "ut"],
        "{found:#?}"
    );
    assert!(found[3].starts_with("stickslip-cli/src/measured.rs:5: damping"));
    assert_eq!(stale.len(), ALLOWED.len());
    let python = "def f(free=('resistance', 'ut')):\n    \"\"\"Free 'diode-is' in prose.\"\"\"\n";
    let (found, _) = hand_written(&[(
        "stickslip-py/python/stickslip/_fit.py".into(),
        python.into(),
    )]);
    assert_eq!(found.len(), 2, "{found:#?}");
    // Every fit parameter but those of swept parameters (μs, the Stribeck law's: named by
    // `Parameter`) is scanned for.
    let (words, whole) = spellings();
    let swept = |p: FitParameter| Parameter::ALL.iter().any(|q| q.keys().contains(&p.key()));
    assert!(swept(FitParameter::MuS) && swept(FitParameter::StribeckSpeed));
    for p in FitParameter::ALL {
        assert_eq!(words.contains(p.label()), !swept(p), "{p} is not scanned");
        if !swept(p) && p.symbol().chars().count() > 1 {
            assert!(whole.contains(p.symbol()), "{p}'s symbol is not scanned");
        }
    }
}

fn json(args: &[&str]) -> serde_json::Value {
    let (_dir, out) = crate::common::run(args);
    assert!(out.status.success(), "{}", crate::common::stderr(&out));
    serde_json::from_str(&crate::common::stdout(&out)).expect("valid JSON")
}

/// Without `--free`, `fit` frees the library's default set of the experiment's system and
/// diode law: with Shockley diodes R, I_s and n (it freed R and U_t, which refused: U_t is
/// no parameter of that law); the help names the library's sets.
#[test]
fn fit_frees_the_librarys_default_set_of_the_diode_law() {
    use stickslip::{DiodeModel, SystemKind};
    let record =
        Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples/fit/data/rigol-3kHz.csv");
    let record = record.to_str().unwrap();
    for law in DiodeModel::ALL {
        let report = json(&[
            "fit",
            "--preset",
            "paper",
            "--model",
            law.label(),
            "--data",
            record,
            "--json",
        ]);
        let freed: BTreeSet<&str> = report["parameters"]
            .as_object()
            .unwrap()
            .keys()
            .map(String::as_str)
            .collect();
        let defaults = FitParameter::defaults(SystemKind::Circuit, law);
        assert_eq!(freed, defaults.iter().map(|p| p.label()).collect(), "{law}");
    }
    let (_dir, out) = crate::common::run(&["fit", "--help"]);
    let help = crate::common::stdout(&out);
    for (system, law) in [
        (SystemKind::Circuit, DiodeModel::Pwl),
        (SystemKind::Circuit, DiodeModel::Shockley),
        (SystemKind::Mechanics, DiodeModel::Pwl),
    ] {
        let list = FitParameter::list(&FitParameter::defaults(system, law));
        assert!(
            help.contains(&list),
            "fit --help does not say {list}:\n{help}"
        );
    }
}

/// "9,97k": a decimal comma is read by every number flag, as the library reads it; a comma
/// that may separate thousands is refused naming both readings.
#[test]
fn a_decimal_comma_is_read_where_it_is_unambiguous() {
    let point = json(&[
        "convert",
        "--preset",
        "paper",
        "--freq",
        "9.97k",
        "--amplitude",
        "1.498",
        "--json",
    ]);
    let comma = json(&[
        "convert",
        "--preset",
        "paper",
        "--freq",
        "9,97k",
        "--amplitude",
        "1,4980",
        "--json",
    ]);
    assert_eq!(comma, point);
    let dimensionless =
        |zeta, w, beta| json(&["steady", "--zeta", zeta, "--w", w, "--beta", beta, "--json"]);
    assert_eq!(
        dimensionless("0,05", "0,95", "2,14"),
        dimensionless("0.05", "0.95", "2.14")
    );
    let (dir, out) = crate::common::run(&["convert", "--preset", "paper", "--freq", "1,500"]);
    crate::common::assert_usage_error(dir.path(), &out, "--freq");
    assert!(
        crate::common::stderr(&out).contains("write 1.5 or 1500"),
        "{}",
        crate::common::stderr(&out)
    );
}
