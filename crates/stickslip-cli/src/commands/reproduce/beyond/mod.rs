//! The chapter "Beyond the paper": what the exact solver and its stability analysis find in
//! the same oscillator that the paper could not. One function per figure.

mod basins_mirror;
mod bifurcation_w;
mod branch_fold;

pub use basins_mirror::basins_mirror;
pub use bifurcation_w::bifurcation_w;
pub use branch_fold::branch_fold;
