//! The experiment's choices that are not numbers: the diode law, the built-in presets, and
//! where a description came from.

use crate::physical::Circuit;
use serde::{Deserialize, Serialize};

/// Which law the diode pair follows, and so which solver runs.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum DiodeModel {
    /// Piecewise linear U_t sgn(i) + R_D i, or Coulomb friction: the exact solver.
    #[default]
    Pwl,
    /// The Shockley law of two anti-parallel diodes: the stiff solver.
    Shockley,
}

impl DiodeModel {
    /// Both laws.
    pub const ALL: [DiodeModel; 2] = [DiodeModel::Pwl, DiodeModel::Shockley];

    /// What the law is and which solver runs it, in one line.
    pub fn description(self) -> &'static str {
        match self {
            DiodeModel::Pwl => {
                "Piecewise linear: U_t sgn(i) + R_D i (the paper's model; solved exactly)"
            }
            DiodeModel::Shockley => {
                "Shockley law of two anti-parallel diodes: n V_T asinh(i/2I_s) + R_s i (stiff \
                 solver)"
            }
        }
    }

    /// `pwl` or `shockley`.
    pub fn label(self) -> &'static str {
        match self {
            DiodeModel::Pwl => "pwl",
            DiodeModel::Shockley => "shockley",
        }
    }
}

/// Built-in physical descriptions.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum Preset {
    /// The paper's experiment ([`Circuit::paper`]).
    Paper,
}

impl Preset {
    /// Every preset.
    pub const ALL: [Preset; 1] = [Preset::Paper];

    /// What the preset describes, in one line.
    pub fn description(self) -> &'static str {
        match self {
            Preset::Paper => "The paper's experiment",
        }
    }

    /// The preset's name: `paper`.
    pub fn label(self) -> &'static str {
        match self {
            Preset::Paper => "paper",
        }
    }

    /// The circuit it describes (with PWL diodes).
    pub fn circuit(self) -> Circuit {
        match self {
            Preset::Paper => Circuit::paper(),
        }
    }
}

/// Where a physical description came from, for descriptions of the experiment.
#[derive(Debug, Clone, PartialEq, Eq, Serialize, Deserialize)]
pub enum Origin {
    /// Dimensionless parameters only.
    Parameters,
    /// A built-in description.
    Preset(Preset),
    /// A file, by name.
    File(String),
    /// Parts given one by one.
    Parts,
}
