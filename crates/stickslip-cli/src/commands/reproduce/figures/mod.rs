//! One function per figure or table of the paper.

mod accuracy;
mod common;
mod fig1;
mod fig3;
mod fig4;
mod fig5;
mod fig6;
mod fig7;
mod fig7_curves;
mod table1;
mod theory_curves;

pub use accuracy::{accuracy, ACCURACY_COLUMNS};
pub use common::beta_color;
pub use fig1::{fig1, DIODE_COLUMNS, FRICTION_COLUMNS};
pub use fig3::{fig3, SPECTRA_COLUMNS, XY_COLUMNS};
pub use fig4::{fig4, BETAS as FIG4_BETAS};
pub use fig5::{fig5, FIG5_LEADING};
pub use fig6::fig6;
pub use fig7::{fig7, ShockleyMap};
pub use table1::{table1, TABLE1_COLUMNS};
pub use theory_curves::boundary_curves;
