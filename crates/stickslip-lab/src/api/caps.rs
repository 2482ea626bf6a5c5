//! What one request may ask for at most.

/// Most display samples per drive period of the steady cycle's trace.
pub const STEADY_SAMPLES: usize = 4096;
/// Longest period looked for by a steady state (drive periods).
pub const MAX_PERIOD: usize = 16;
/// Most drive periods run to reach a steady state.
pub const MAX_PERIODS: usize = 5000;
/// Most drive periods of a simulation from the initial state.
pub const SIMULATE_PERIODS: f64 = 2000.0;
/// Most samples per drive period of a simulation.
pub const SIMULATE_SAMPLES: usize = 10_000;
/// Most samples of a simulation in all.
pub const SIMULATE_TOTAL: usize = 200_000;
/// Most values of a sweep (each leg).
pub const SWEEP_STEPS: usize = 400;
/// Most values on one side of a map.
pub const MAP_SIDE: usize = 1000;
/// Most points of a map.
pub const MAP_POINTS: usize = 40_000;
