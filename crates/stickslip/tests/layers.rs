//! The library's modules import one way (docs/library.md, "Layers"): every path into the
//! crate (`use crate::...` and `crate::...` in code) of a module names a module of a lower
//! layer. A few files are nodes of their own (the leaves the errors are built from, the
//! monitor and the ranges of a scan, the netlist above the physical description).
//!
//! Comments, `#[cfg(test)] mod tests` and files named `tests.rs` are not read; `pub use`
//! items are not dependencies (they keep old paths working, and point up by nature).

use std::collections::{BTreeMap, BTreeSet};
use std::path::{Path, PathBuf};

/// The documented order, lowest first. A node imports only nodes of lower layers.
const LAYERS: &[&[&str]] = &[
    &[
        "units",
        "trig",
        "certify",
        "checkpoint",
        "options::key",
        "experiment::keys",
        "experiment::errors",
        "stability::error",
        "stability::verdict",
        "theory::obstruction",
        "fit::linalg",
    ],
    &["error", "linear", "measure"],
    &["options", "scan::monitor", "scan::range", "friction"],
    &["limits"],
    &["params"],
    &["solver"],
    &["cancel"],
    &["stiff"],
    &["exact", "shockley"],
    &["friction_solver"],
    &["physical", "stability", "theory"],
    &["attractor", "shockley::netlist", "steady"],
    &["experiment"],
    &["continuation", "fit", "scan"],
    &["basins", "bifurcation"],
    &["names", "report"],
];

/// Files that are nodes of their own (`dir/file.rs` → `dir::file`).
const OWN_NODES: &[&str] = &[
    "options/key.rs",
    "experiment/keys.rs",
    "experiment/errors.rs",
    "stability/error.rs",
    "stability/verdict.rs",
    "theory/obstruction.rs",
    "scan/monitor.rs",
    "scan/range.rs",
    "fit/linalg.rs",
    "shockley/netlist.rs",
];

fn src() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("src")
}

fn files(dir: &Path, out: &mut Vec<PathBuf>) {
    for entry in std::fs::read_dir(dir).expect("the source directory is readable") {
        let path = entry.expect("a directory entry").path();
        if path.is_dir() {
            files(&path, out);
        } else if path.extension().is_some_and(|e| e == "rs") {
            out.push(path);
        }
    }
}

/// `a/b.rs` relative to `src`, with forward slashes.
fn relative(path: &Path) -> String {
    path.strip_prefix(src())
        .expect("under src")
        .components()
        .map(|c| c.as_os_str().to_string_lossy().into_owned())
        .collect::<Vec<_>>()
        .join("/")
}

fn node_of_file(rel: &str) -> String {
    if OWN_NODES.contains(&rel) {
        return rel.trim_end_matches(".rs").replace('/', "::");
    }
    let top = rel.split('/').next().expect("a path");
    top.trim_end_matches(".rs").to_string()
}

/// The code of a file: without comments (line comments, doc comments), without its test
/// module and without `pub use` items.
fn code(text: &str) -> String {
    let text = match text.find("#[cfg(test)]\nmod tests") {
        Some(i) => &text[..i],
        None => text,
    };
    let mut out = String::new();
    for line in text.lines() {
        let line = match line.find("//") {
            // `//` inside a string is rare in these files; a URL in a string would only
            // shorten the line, never add a path.
            Some(i) => &line[..i],
            None => line,
        };
        out.push_str(line);
        out.push('\n');
    }
    // Drop `pub use ...;` and `pub(crate) use ...;` items.
    let mut kept = String::new();
    let mut rest = out.as_str();
    while let Some(i) = find_pub_use(rest) {
        kept.push_str(&rest[..i]);
        let end = rest[i..].find(';').map_or(rest.len(), |j| i + j + 1);
        rest = &rest[end..];
    }
    kept.push_str(rest);
    kept
}

/// The start of the next `pub use` or `pub(...) use` item.
fn find_pub_use(text: &str) -> Option<usize> {
    let mut from = 0;
    while let Some(i) = text[from..].find("pub") {
        let at = from + i;
        let before_ok = at == 0 || !is_ident(text.as_bytes()[at - 1] as char);
        let mut j = at + 3;
        let bytes = text.as_bytes();
        if bytes.get(j) == Some(&b'(') {
            match text[j..].find(')') {
                Some(k) => j += k + 1,
                None => return None,
            }
        }
        let after = text[j..].trim_start();
        if before_ok && after.starts_with("use ") {
            return Some(at);
        }
        from = at + 3;
    }
    None
}

fn is_ident(c: char) -> bool {
    c.is_ascii_alphanumeric() || c == '_'
}

/// The paths (as segments) that start at `text`, just after `crate::`: `a::b::C`, or a
/// group `a::{b::C, d}` expanded.
fn paths(text: &str) -> Vec<Vec<String>> {
    let mut out = Vec::new();
    expand(Vec::new(), text, &mut out);
    out
}

fn expand(prefix: Vec<String>, text: &str, out: &mut Vec<Vec<String>>) {
    let text = text.trim_start();
    if let Some(group) = text.strip_prefix('{') {
        let mut depth = 0;
        let mut item = String::new();
        for c in group.chars() {
            match c {
                '{' => {
                    depth += 1;
                    item.push(c);
                }
                '}' if depth == 0 => break,
                '}' => {
                    depth -= 1;
                    item.push(c);
                }
                ',' if depth == 0 => {
                    expand(prefix.clone(), &item, out);
                    item.clear();
                }
                _ => item.push(c),
            }
        }
        if !item.trim().is_empty() {
            expand(prefix, &item, out);
        }
        return;
    }
    let name: String = text.chars().take_while(|&c| is_ident(c)).collect();
    if name.is_empty() {
        return;
    }
    let mut path = prefix;
    path.push(name.clone());
    let rest = &text[name.len()..];
    match rest.strip_prefix("::") {
        Some(more) => expand(path, more, out),
        None => out.push(path),
    }
}

/// What the crate's paths resolve to: modules, the root's re-exports, and the names a
/// module's `mod.rs` re-exports from a file that is a node of its own.
struct Resolver {
    modules: BTreeSet<String>,
    root: BTreeMap<String, String>,
    own: BTreeMap<(String, String), String>,
}

/// The names of `pub use <from>::{...};` items of `text`, with `<from>`'s first segment.
fn reexports(text: &str) -> Vec<(String, String)> {
    let mut out = Vec::new();
    for item in text.split(';') {
        let item = item.trim();
        let Some(body) = item.strip_prefix("pub use ") else {
            continue;
        };
        if body.starts_with("crate::") {
            continue;
        }
        let from: String = body.chars().take_while(|&c| is_ident(c)).collect();
        for path in paths(body) {
            if let Some(name) = path.last() {
                out.push((from.clone(), name.clone()));
            }
        }
    }
    out
}

impl Resolver {
    fn new() -> Self {
        let lib = std::fs::read_to_string(src().join("lib.rs")).expect("lib.rs");
        let lib_code = code_keeping_reexports(&lib);
        let mut modules = BTreeSet::new();
        for line in lib_code.lines() {
            let line = line.trim();
            let line = line.strip_prefix("pub ").unwrap_or(line);
            if let Some(name) = line.strip_prefix("mod ").and_then(|l| l.strip_suffix(';')) {
                modules.insert(name.trim().to_string());
            }
        }
        let root = reexports(&lib_code)
            .into_iter()
            .map(|(from, name)| (name, from))
            .collect();
        let mut own = BTreeMap::new();
        for file in OWN_NODES {
            let (dir, name) = file.split_once('/').expect("dir/file.rs");
            let sub = name.trim_end_matches(".rs");
            let Ok(text) = std::fs::read_to_string(src().join(dir).join("mod.rs")) else {
                continue;
            };
            for (from, item) in reexports(&code_keeping_reexports(&text)) {
                if from == sub {
                    own.insert((dir.to_string(), item), format!("{dir}::{sub}"));
                }
            }
        }
        Self { modules, root, own }
    }

    fn node(&self, path: &[String]) -> Option<String> {
        let first = path.first()?;
        if self.modules.contains(first) {
            if let Some(second) = path.get(1) {
                let file = format!("{first}/{second}.rs");
                if OWN_NODES.contains(&file.as_str()) {
                    return Some(format!("{first}::{second}"));
                }
                if let Some(node) = self.own.get(&(first.clone(), second.clone())) {
                    return Some(node.clone());
                }
            }
            return Some(first.clone());
        }
        self.root.get(first).cloned()
    }
}

/// Comments stripped, `pub use` kept (to read the re-exports themselves).
fn code_keeping_reexports(text: &str) -> String {
    text.lines()
        .map(|l| l.find("//").map_or(l, |i| &l[..i]))
        .collect::<Vec<_>>()
        .join("\n")
}

/// Every edge `from → to` with the files that make it.
fn edges() -> BTreeMap<(String, String), BTreeSet<String>> {
    let resolver = Resolver::new();
    let mut all = Vec::new();
    files(&src(), &mut all);
    let mut edges: BTreeMap<(String, String), BTreeSet<String>> = BTreeMap::new();
    for path in all {
        let rel = relative(&path);
        if rel == "lib.rs" || rel == "test_rng.rs" || rel.ends_with("tests.rs") {
            continue;
        }
        let from = node_of_file(&rel);
        let text = std::fs::read_to_string(&path).expect("a source file");
        let code = code(&text);
        let mut rest = code.as_str();
        while let Some(i) = rest.find("crate::") {
            let start = i + "crate::".len();
            let before = if i == 0 {
                ' '
            } else {
                rest.as_bytes()[i - 1] as char
            };
            if !is_ident(before) {
                for p in paths(&rest[start..]) {
                    if let Some(to) = resolver.node(&p) {
                        if to != from {
                            edges
                                .entry((from.clone(), to))
                                .or_default()
                                .insert(rel.clone());
                        }
                    }
                }
            }
            rest = &rest[start..];
        }
    }
    edges
}

fn layer_of(node: &str) -> Option<usize> {
    LAYERS.iter().position(|layer| layer.contains(&node))
}

#[test]
fn modules_import_only_lower_layers() {
    let edges = edges();
    assert!(
        edges.len() > 50,
        "the parser found only {} edges: it reads nothing",
        edges.len()
    );
    let mut wrong = Vec::new();
    for ((from, to), files) in &edges {
        match (layer_of(from), layer_of(to)) {
            (Some(a), Some(b)) if a > b => {}
            (Some(a), Some(b)) => wrong.push(format!(
                "{from} (layer {a}) imports {to} (layer {b}) in {files:?}"
            )),
            _ => wrong.push(format!(
                "{from} → {to} ({files:?}): a module missing from LAYERS (place it in the \
                 documented order, docs/library.md)"
            )),
        }
    }
    assert!(
        wrong.is_empty(),
        "imports against the layers:\n{}",
        wrong.join("\n")
    );
}

#[test]
fn every_module_has_a_layer() {
    let resolver = Resolver::new();
    let missing: Vec<_> = resolver
        .modules
        .iter()
        .filter(|m| layer_of(m).is_none() && m.as_str() != "test_rng")
        .collect();
    assert!(missing.is_empty(), "modules without a layer: {missing:?}");
}

#[test]
fn the_parser_sees_groups_and_reexports() {
    assert_eq!(
        paths("{a::B, c::{d::E, F}, g};"),
        vec![
            vec!["a".to_string(), "B".into()],
            vec!["c".into(), "d".into(), "E".into()],
            vec!["c".into(), "F".into()],
            vec!["g".into()],
        ]
    );
    let code = code("use crate::a::B;\npub use crate::c::D;\n// crate::e::F\nfn f() {}\n");
    assert!(
        code.contains("crate::a::B") && !code.contains("crate::c") && !code.contains("crate::e")
    );
    // The edges this file's order rests on are found.
    let edges = edges();
    for (from, to) in [
        ("steady", "stability"),
        ("scan", "steady"),
        ("params", "limits"),
    ] {
        assert!(
            edges.contains_key(&(from.to_string(), to.to_string())),
            "{from} → {to} not found"
        );
    }
}
