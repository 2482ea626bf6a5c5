//! The page writes no model key by hand: the keys each system sends, the fields a preset
//! fills, what a fit may free and each key's symbol and unit come from `/api/keys`, so that a
//! new key is a row of the library's table. A scan of the page's scripts for every flag of
//! the table's system, diode and friction groups (the circuit's, the diodes' and the
//! mechanical oscillator's keys, the belt's and the friction laws') finds each occurrence
//! outside comments and regular expressions: an identifier (`{ inductance: … }`, `shockley.temperature`) or a word of a string (`'rd'`,
//! `[name="mu-s"]`; a string with a space in it is prose, and skipped). Only the occurrences
//! below, each with its reason, are allowed.

use crate::router::{LAB_JS, MODULES};
use stickslip::experiment::{Key, KeyGroup};
use stickslip_testkit::allowances::{Allowance, Scan};

/// The occurrences of a key's flag the page may write, each on a line holding its fragment.
const ALLOWED: [Allowance; 8] = [
    Allowance {
        file: "lab/state.js",
        word: "preset",
        fragment: "p.set('preset', 'paper')",
        reason: "behaviour of its own: while no part is edited, the paper's circuit is sent \
                 by the preset's name, as the page has always sent it",
    },
    Allowance {
        file: "lab/state.js",
        word: "model",
        fragment: "p.set('model', 'shockley')",
        reason: "behaviour of its own: the diode law is the system's selector, not a field",
    },
    Allowance {
        file: "lab.js",
        word: "model",
        fragment: "steady.model === 'shockley'",
        reason: "the steady state's answer field `model` (its diode law), not a query key",
    },
    Allowance {
        file: "lab/panels.js",
        word: "model",
        fragment: "state.stuckVelocity[s.model]",
        reason: "the steady state's answer field `model`, which picks the served stuck speed",
    },
    Allowance {
        file: "lab/sweepmap.js",
        word: "model",
        fragment: "answer.model",
        reason: "a sweep's or map's answer field `model`: what it was computed for",
    },
    Allowance {
        file: "lab/panels.js",
        word: "vb",
        fragment: "const speed = s.vb ?? 0;",
        reason: "the steady state's answer field `vb` (the belt's speed it was computed for), \
                 which the mechanical view moves the belt and the block by",
    },
    Allowance {
        file: "lab/orbit.js",
        word: "damping",
        fragment: "damping 2ζ + μ′ = ${num(c.sliding.damping, 6)}",
        reason: "the self-excited orbit's answer field `sliding.damping` (steady sliding's \
                 2ζ + μ'(|vb|)), not the oscillator's γ",
    },
    Allowance {
        file: "lab/panels.js",
        word: "zeta",
        fragment: "num(c.zeta, 5)",
        reason: "the answer's ζ of the circuit, shown derived (the form has no field for it)",
    },
];

/// Words (identifiers, numbers and the words of string literals) of a script, each with its
/// line, without its comments, regular-expression literals and prose (a string, or a
/// template literal's text between its `${…}`, with a space in it). A word of a string is a
/// run of letters, digits, `_` and `-` (a flag such as `mu-s` is one word); a template
/// literal's `${…}` is code.
fn words(source: &str) -> Vec<(usize, String)> {
    let s: Vec<char> = source.chars().collect();
    let mut out = Vec::new();
    let mut line = 1;
    let mut i = 0;
    // The last significant character of code (`a` after a word or a literal): a `/` after an
    // operand divides, elsewhere it opens a regular expression.
    let mut last = '(';
    // Brace depths at which an open template literal's `${` closes.
    let mut templates: Vec<usize> = Vec::new();
    let mut depth = 0usize;
    let is_word = |c: char| c.is_alphanumeric() || c == '_' || c == '-';
    let split = |text: &str, line: usize, out: &mut Vec<(usize, String)>| {
        if text.contains(char::is_whitespace) {
            return; // prose: "a mass on a spring", "the PWL model"
        }
        for w in text.split(|c: char| !is_word(c)).filter(|w| !w.is_empty()) {
            out.push((line, w.to_string()));
        }
    };
    // Reads a template literal's text from `i` to its end or to a `${`; true at a `${`.
    let template = |i: &mut usize, line: &mut usize, out: &mut Vec<(usize, String)>| {
        let (start, mut text) = (*line, String::new());
        while *i < s.len() {
            match s[*i] {
                '\\' => *i += 2,
                '`' => {
                    *i += 1;
                    split(&text, start, out);
                    return false;
                }
                '$' if s.get(*i + 1) == Some(&'{') => {
                    *i += 2;
                    split(&text, start, out);
                    return true;
                }
                c => {
                    if c == '\n' {
                        *line += 1;
                    }
                    text.push(c);
                    *i += 1;
                }
            }
        }
        split(&text, start, out);
        false
    };
    while i < s.len() {
        let c = s[i];
        let next = s.get(i + 1).copied();
        if c == '\n' {
            line += 1;
            i += 1;
        } else if c.is_whitespace() {
            i += 1;
        } else if c == '/' && next == Some('/') {
            while i < s.len() && s[i] != '\n' {
                i += 1;
            }
        } else if c == '/' && next == Some('*') {
            i += 2;
            while i < s.len() && !(s[i] == '*' && s.get(i + 1) == Some(&'/')) {
                line += usize::from(s[i] == '\n');
                i += 1;
            }
            i += 2;
        } else if c == '/' && last != 'a' && last != ')' && last != ']' {
            // A regular expression: to its closing `/` outside a class, then its flags.
            let mut class = false;
            i += 1;
            while i < s.len() && (s[i] != '/' || class) {
                match s[i] {
                    '\\' => i += 1,
                    '[' => class = true,
                    ']' => class = false,
                    _ => {}
                }
                i += 1;
            }
            i += 1;
            while i < s.len() && s[i].is_alphanumeric() {
                i += 1;
            }
            last = 'a';
        } else if c == '\'' || c == '"' {
            let mut text = String::new();
            i += 1;
            while i < s.len() && s[i] != c && s[i] != '\n' {
                if s[i] == '\\' {
                    i += 1;
                }
                text.extend(s.get(i));
                i += 1;
            }
            i += 1;
            split(&text, line, &mut out);
            last = 'a';
        } else if c == '`' || (c == '}' && templates.last() == Some(&depth)) {
            // A template literal's text: from its start, or from the end of one of its `${…}`.
            if c == '}' {
                templates.pop();
                depth -= 1;
            }
            i += 1;
            if template(&mut i, &mut line, &mut out) {
                depth += 1;
                templates.push(depth);
                last = '(';
            } else {
                last = 'a';
            }
        } else if c.is_alphanumeric() || c == '_' || c == '$' {
            let start = i;
            while i < s.len() && (s[i].is_alphanumeric() || s[i] == '_' || s[i] == '$') {
                i += 1;
            }
            let word: String = s[start..i].iter().collect();
            // After `return` or `typeof` an expression starts: a `/` there opens a regex.
            last = if ["return", "typeof", "case"].contains(&word.as_str()) {
                '('
            } else {
                'a'
            };
            out.push((line, word));
        } else {
            match c {
                '{' => depth += 1,
                '}' => depth = depth.saturating_sub(1),
                _ => {}
            }
            last = c;
            i += 1;
        }
    }
    out
}

/// The flags of the keys the page's form and query are about: the table's system, diode and
/// friction groups (the circuit's parts, R_D, the Shockley diodes' parameters, the
/// mechanical parts, μs, ζ, the diode law, the preset, the belt, the friction law and its
/// parameters).
fn model_flags() -> Vec<&'static str> {
    Key::ALL
        .into_iter()
        .filter(|k| {
            matches!(
                k.group(),
                KeyGroup::System | KeyGroup::Diode | KeyGroup::Friction
            )
        })
        .map(Key::flag)
        .collect()
}

/// Every occurrence of a model flag in `scripts` not in [`ALLOWED`], as `file:line: flag:
/// the line`, and the allowances that matched nothing (with their reasons).
fn hand_written(scripts: &[(String, &str)]) -> (Vec<String>, Vec<String>) {
    let flags = model_flags();
    let mut scan = Scan::new(&ALLOWED);
    for (file, text) in scripts {
        let lines: Vec<&str> = text.lines().collect();
        for (line, word) in words(text) {
            if !flags.contains(&word.as_str()) {
                continue;
            }
            let source = lines.get(line - 1).copied().unwrap_or_default();
            scan.occurrence(file, line, &word, source);
        }
    }
    scan.finish()
}

/// The scripts the page runs, as the server serves them.
fn scripts() -> Vec<(String, &'static str)> {
    std::iter::once(("lab.js".to_string(), LAB_JS))
        .chain(
            MODULES
                .iter()
                .map(|&(name, text)| (format!("lab/{name}"), text)),
        )
        .collect()
}

#[test]
fn the_page_writes_no_model_key_by_hand() {
    assert!(model_flags().len() >= 29, "{:?}", model_flags());
    assert!(
        model_flags().contains(&"friction-law"),
        "{:?}",
        model_flags()
    );
    let (found, stale) = hand_written(&scripts());
    assert!(
        found.is_empty(),
        "model keys written by hand in the lab's scripts (take them from /api/keys' form, \
         fit and keys, or allow the occurrence in ALLOWED with its reason):\n{}",
        found.join("\n")
    );
    assert!(
        stale.is_empty(),
        "allowances that match nothing any more: {stale:?}"
    );
}

/// The scan finds the lists the page had before its keys were served, and what comments,
/// regular expressions and prose hide.
#[test]
fn the_scan_finds_hand_lists_and_skips_comments_and_regexes() {
    let before = "// state.js: 'inductance' in a comment is fine\n\
                  export const PART_KEYS = ['inductance', 'capacitance', 'resistance', 'ut'];\n\
                  const LABELS = { rd: ['R_D', 'Ω'], 'diode-is': ['I_s', 'A'] };\n\
                  /* 'mass' in a block\n comment */ x = a / 2; y = /'stiffness'[/]/g.test(b);\n\
                  field('temperature').value = num(state.shockley.temperature, 6);\n\
                  t = `free-${k} ${'mu-s'}` + `[name=\"damping\"]`; u = `${`${ `friction` }`}`;\n\
                  v = 'a mass on a spring' + `the ${k} model`;\n";
    let (found, stale) = hand_written(&[("lab/state.js".to_string(), before)]);
    let flags: Vec<&str> = found
        .iter()
        .map(|f| f.split(": ").nth(1).unwrap())
        .collect();
    assert_eq!(
        flags,
        [
            "inductance",
            "capacitance",
            "resistance",
            "ut",
            "rd",
            "diode-is",
            "temperature",
            "temperature",
            "mu-s",
            "damping",
            "friction"
        ],
        "{found:#?}"
    );
    assert!(
        found[4].starts_with("lab/state.js:3: rd: const LABELS"),
        "{found:?}"
    );
    assert!(
        found[10].starts_with("lab/state.js:7: friction:"),
        "{found:?}"
    );
    assert_eq!(stale.len(), ALLOWED.len());
}
