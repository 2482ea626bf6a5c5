//! A small fixed-seed generator for the unit tests' random cases (xorshift64).

/// Uniform pseudo-random numbers from a fixed seed, the same on every run.
pub(crate) struct TestRng(u64);

impl TestRng {
    /// A generator from a nonzero seed.
    pub(crate) fn new(seed: u64) -> Self {
        assert!(seed != 0, "xorshift needs a nonzero seed");
        Self(seed)
    }

    /// Uniform in [0, 1).
    pub(crate) fn next(&mut self) -> f64 {
        self.0 ^= self.0 << 13;
        self.0 ^= self.0 >> 7;
        self.0 ^= self.0 << 17;
        (self.0 >> 11) as f64 / (1u64 << 53) as f64
    }

    /// Uniform in [lo, hi).
    pub(crate) fn range(&mut self, lo: f64, hi: f64) -> f64 {
        lo + (hi - lo) * self.next()
    }
}
