//! Scans of the front ends' sources for words they should take from the library (keys, fit
//! parameters, model flags): the occurrences a scan finds, sorted into those that a listed
//! allowance excuses (with its reason) and the rest, and the allowances that excuse nothing
//! any more.

/// An occurrence of a word that a scan allows: in `file` (the end of its path), on a line that
/// contains `fragment`, for `reason`.
#[derive(Debug, Clone, Copy)]
pub struct Allowance {
    /// The end of the file's path, such as `lab/state.js`.
    pub file: &'static str,
    /// The word allowed there.
    pub word: &'static str,
    /// Text of the line that holds it.
    pub fragment: &'static str,
    /// Why it is written there.
    pub reason: &'static str,
}

/// The occurrences of one scan, checked against a list of allowances.
#[derive(Debug)]
pub struct Scan<'a> {
    allowed: &'a [Allowance],
    used: Vec<bool>,
    found: Vec<String>,
}

impl<'a> Scan<'a> {
    /// A scan with nothing found yet.
    pub fn new(allowed: &'a [Allowance]) -> Self {
        Self {
            allowed,
            used: vec![false; allowed.len()],
            found: Vec::new(),
        }
    }

    /// `word` occurs on line `line` (1-based) of `file`, whose text is `source`: excused by
    /// the first allowance of its file, word and fragment, else found.
    pub fn occurrence(&mut self, file: &str, line: usize, word: &str, source: &str) {
        let allowed = self
            .allowed
            .iter()
            .position(|a| file.ends_with(a.file) && a.word == word && source.contains(a.fragment));
        match allowed {
            Some(a) => self.used[a] = true,
            None => self
                .found
                .push(format!("{file}:{line}: {word}: {}", source.trim())),
        }
    }

    /// The occurrences no allowance excuses, as `file:line: word: the line`, and the
    /// allowances that excused none, as `file: fragment (reason)`.
    pub fn finish(self) -> (Vec<String>, Vec<String>) {
        let stale = self
            .allowed
            .iter()
            .zip(self.used)
            .filter(|(_, used)| !used)
            .map(|(a, _)| format!("{}: {} ({})", a.file, a.fragment, a.reason))
            .collect();
        (self.found, stale)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn an_allowance_excuses_its_line_only_and_one_that_excuses_nothing_is_stale() {
        let allowed = [
            Allowance {
                file: "lab/state.js",
                word: "preset",
                fragment: "p.set('preset'",
                reason: "sent by name",
            },
            Allowance {
                file: "lab/form.js",
                word: "mass",
                fragment: "mass:",
                reason: "gone",
            },
        ];
        let mut scan = Scan::new(&allowed);
        scan.occurrence(
            "crates/lab/state.js",
            3,
            "preset",
            "  p.set('preset', 'paper')",
        );
        scan.occurrence("crates/lab/state.js", 9, "preset", "  q = 'preset'");
        let (found, stale) = scan.finish();
        assert_eq!(found, ["crates/lab/state.js:9: preset: q = 'preset'"]);
        assert_eq!(stale, ["lab/form.js: mass: (gone)"]);
    }
}
