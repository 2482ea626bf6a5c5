//! One function per figure or table of the paper.

mod fig1;
mod table1;

pub use fig1::fig1;
pub use table1::table1;
