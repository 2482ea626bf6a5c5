//! One function per figure or table of the paper.

mod common;
mod fig1;
mod fig3;
mod fig6;
mod table1;

pub use fig1::fig1;
pub use fig3::fig3;
pub use fig6::fig6;
pub use table1::table1;
