//! The key table walked row by row: every key is read under each of its spellings (TOML name
//! and aliases, flag and aliases, text with its unit), and refused out of its range with the
//! message the table gives. The documentation's table of keys (`docs/limits.md`) is the one
//! the library renders (`STICKSLIP_BLESS=1` rewrites it).

use stickslip::experiment::{ExperimentSpec, Key, KeyForm, KeyRange};
use stickslip::{Error, Number};

/// A value well inside the range.
fn inside(range: &KeyRange) -> f64 {
    match (range.min.is_finite(), range.max.is_finite()) {
        (true, true) => 0.5 * (range.min + range.max),
        (true, false) => range.min + 1.0,
        (false, true) => range.max - 1.0,
        (false, false) => 0.25,
    }
}

/// Values just outside the range (none for a range without bounds).
fn outside(range: &KeyRange) -> Vec<f64> {
    let mut out = Vec::new();
    let step = |x: f64| x.abs().max(1.0) * 1e-9;
    if range.min.is_finite() {
        out.push(if range.min_inclusive {
            range.min - step(range.min)
        } else {
            range.min
        });
    }
    if range.max.is_finite() {
        out.push(if range.max_inclusive {
            range.max + step(range.max)
        } else {
            range.max
        });
    }
    out
}

/// Just inside each bound.
fn at_the_ends(range: &KeyRange) -> Vec<f64> {
    let step = |x: f64| x.abs().max(1.0) * 1e-9;
    let mut out = Vec::new();
    if range.min.is_finite() {
        out.push(if range.min_inclusive {
            range.min
        } else {
            range.min + step(range.min)
        });
    }
    if range.max.is_finite() {
        out.push(if range.max_inclusive {
            range.max
        } else {
            range.max - step(range.max)
        });
    }
    out
}

fn numbers() -> impl Iterator<Item = Key> {
    Key::ALL.into_iter().filter(|k| k.form() != KeyForm::Choice)
}

#[test]
fn every_number_is_read_and_refused_as_its_row_says() {
    for key in numbers() {
        let range = key.range();
        let v = inside(&range);
        assert!(range.contains(v), "{key} {v}");
        for text in [format!("{v}"), format!("{v:e}")] {
            assert_eq!(key.parse(&text).unwrap(), v, "{key} {text}");
        }
        for &unit in key.units() {
            assert_eq!(key.parse(&format!("{v}{unit}")).unwrap(), v, "{key} {unit}");
        }
        if key.form() == KeyForm::Si {
            assert_eq!(key.number("2k").unwrap(), 2e3, "{key}");
        } else {
            assert!(key.number("2k").is_err(), "{key}");
        }
        for x in at_the_ends(&range) {
            assert_eq!(key.check(x).unwrap(), x, "{key} {x}");
        }
        for x in outside(&range)
            .into_iter()
            .chain([f64::NAN, f64::INFINITY, f64::NEG_INFINITY])
        {
            let err = key.check(x).unwrap_err();
            match &err {
                Error::InvalidParameter {
                    name,
                    value,
                    allowed,
                } => {
                    assert_eq!((*name, *allowed), (key.name(), key.allowed()), "{key} {x}");
                    assert!(*value == x || (x.is_nan() && value.is_nan()), "{key} {x}");
                }
                other => panic!("{key} {x}: {other:?}"),
            }
            assert_eq!(err.key(), Some(key));
            if x.is_finite() {
                assert_eq!(
                    key.parse(&format!("{x:e}")).unwrap_err().to_string(),
                    format!("invalid {} = {}: {}", key.name(), Number(x), key.allowed())
                );
            }
        }
        assert!(matches!(
            key.parse("abc"),
            Err(Error::InvalidText { key: k, .. }) if k == key
        ));
    }
}

/// A unit that is not the key's is refused, naming the units the key takes.
#[test]
fn a_unit_that_is_not_the_keys_is_refused() {
    for key in numbers() {
        for unit in ["Hz", "H", "F", "V", "A", "ohm", "s", "N"] {
            let text = format!("1{unit}");
            let result = key.parse(&text);
            if key.units().contains(&unit) {
                assert!(result.is_ok(), "{key} {text}");
            } else {
                let err = result.unwrap_err();
                assert_eq!(err.key(), Some(key));
                assert!(err.to_string().contains("does not fit"), "{key}: {err}");
            }
        }
    }
}

#[test]
fn every_spelling_names_its_key() {
    for key in Key::ALL {
        assert_eq!(Key::from_name(key.name()), Some(key));
        for &alias in key.name_aliases() {
            assert_eq!(Key::from_name(alias), Some(key));
        }
        assert_eq!(Key::from_flag(key.flag()), Some(key));
        for &alias in key.aliases() {
            assert_eq!(Key::from_flag(alias), Some(key));
        }
        assert!(
            !key.help().is_empty() && !key.help().ends_with('.'),
            "{key}"
        );
        assert!(!key.help().contains('\n'), "{key}");
    }
    let mut flags: Vec<&str> = Key::ALL
        .iter()
        .flat_map(|k| std::iter::once(k.flag()).chain(k.aliases().iter().copied()))
        .collect();
    let n = flags.len();
    flags.sort_unstable();
    flags.dedup();
    assert_eq!(flags.len(), n, "a flag names two keys");
}

/// Every key of a section is read from a TOML file under each of its names, and refused
/// there out of range with the table's message.
#[test]
fn every_key_is_read_from_its_toml_section() {
    for key in Key::ALL {
        let Some(section) = key.section() else {
            assert_eq!(key, Key::Preset);
            continue;
        };
        let section = section.name();
        for name in std::iter::once(key.name()).chain(key.name_aliases().iter().copied()) {
            if key.form() == KeyForm::Choice {
                for choice in key.choices() {
                    let text = format!("[{section}]\n{name} = \"{choice}\"\n");
                    let spec = ExperimentSpec::from_toml(&text, "k.toml").unwrap();
                    match key {
                        Key::Diode => assert_eq!(spec.diode(), Some(choice.parse().unwrap())),
                        Key::FrictionLaw => assert_eq!(spec.law(), Some(choice.parse().unwrap())),
                        other => panic!("{other} takes names: read it here"),
                    }
                }
                continue;
            }
            let v = inside(&key.range());
            let text = format!("[{section}]\n{name} = {v:e}\n");
            let spec = ExperimentSpec::from_toml(&text, "k.toml").unwrap();
            assert_eq!(spec.get(key), Some(v), "{text}");
            for x in outside(&key.range()) {
                let text = format!("[{section}]\n{name} = {x:e}\n");
                let err = ExperimentSpec::from_toml(&text, "k.toml")
                    .unwrap_err()
                    .to_string();
                assert_eq!(
                    err,
                    format!(
                        "k.toml, line 2, [{section}] {name}: invalid {} = {}: {}",
                        key.name(),
                        Number(x),
                        key.allowed()
                    )
                );
            }
        }
    }
}

#[test]
fn the_table_serialises_every_row() {
    let table = Key::table();
    assert_eq!(table.len(), Key::ALL.len());
    let json = serde_json::to_value(&table).unwrap();
    let w = &json[1];
    assert_eq!(w["name"], "w");
    assert_eq!(w["flag"], "w");
    assert_eq!(w["group"], "drive");
    assert_eq!(w["min"], 1e-5);
    assert_eq!(w["max"], 1e5);
    let l = &json[7];
    assert_eq!(l["name"], "L");
    assert_eq!(l["aliases"][0], "L");
    assert_eq!(l["unit"], "H");
    assert_eq!(l["min"], 0.0);
    assert_eq!(l["min_inclusive"], false);
    assert!(l["max"].is_null());
    let diode = &json[Key::Diode as usize];
    assert_eq!(diode["choices"], serde_json::json!(["pwl", "shockley"]));
    assert_eq!(diode["default"], "pwl");
}

/// `docs/limits.md` holds the table of keys that [`Key::markdown_table`] renders, between
/// its markers.
#[test]
fn docs_limits_holds_the_rendered_table_of_keys() {
    const BEGIN: &str = "<!-- keys: begin (generated by Key::markdown_table; STICKSLIP_BLESS=1 cargo test -p stickslip --test keys rewrites it) -->\n";
    const END: &str = "<!-- keys: end -->\n";
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../../docs/limits.md");
    let text = std::fs::read_to_string(&path).expect("docs/limits.md");
    let start = text
        .find(BEGIN)
        .expect("the begin marker in docs/limits.md")
        + BEGIN.len();
    let end = start
        + text[start..]
            .find(END)
            .expect("the end marker in docs/limits.md");
    let table = Key::markdown_table();
    if std::env::var_os("STICKSLIP_BLESS").is_some_and(|v| v == "1") {
        let updated = format!("{}{table}{}", &text[..start], &text[end..]);
        std::fs::write(&path, updated).expect("write docs/limits.md");
        return;
    }
    assert_eq!(
        &text[start..end],
        table,
        "docs/limits.md: the table of keys differs from Key::markdown_table() \
         (STICKSLIP_BLESS=1 cargo test -p stickslip --test keys rewrites it)"
    );
}
