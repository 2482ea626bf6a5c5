//! What the cells of a map of steady states show.

use serde::{Deserialize, Serialize};

/// What the cells of a map ([`super::Grid`]) show: the motion class of each point, or its
/// largest Lyapunov exponent (which the map then measures at every point,
/// [`super::Grid::lyapunov`]).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default, Serialize, Deserialize)]
#[serde(rename_all = "lowercase")]
pub enum MapColor {
    /// The motion class.
    #[default]
    Class,
    /// The largest Lyapunov exponent λ1 per unit τ (label `lambda1`; before: `lyapunov`,
    /// which still reads).
    #[serde(alias = "lyapunov")]
    Lambda1,
}

impl MapColor {
    /// Both.
    pub const ALL: [MapColor; 2] = [MapColor::Class, MapColor::Lambda1];

    /// Names retired, with the value each now reads as: `lyapunov` (now `lambda1`, the
    /// exponent's name in every table).
    pub const RETIRED: [(&'static str, MapColor); 1] = [("lyapunov", MapColor::Lambda1)];

    /// `class` or `lambda1`.
    pub fn label(self) -> &'static str {
        match self {
            MapColor::Class => "class",
            MapColor::Lambda1 => "lambda1",
        }
    }

    /// What the cells show, in one line.
    pub fn description(self) -> &'static str {
        match self {
            MapColor::Class => "The motion class",
            MapColor::Lambda1 => "The largest Lyapunov exponent λ1 per unit τ",
        }
    }

    /// Whether the map measures the exponent at every point.
    pub fn needs_lyapunov(self) -> bool {
        self == MapColor::Lambda1
    }
}
