//! Steady-state analysis: convergence to a cycle, spectra, motion classes, sweeps and maps.
