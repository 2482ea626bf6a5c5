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
    /// The largest Lyapunov exponent per unit τ.
    Lyapunov,
}

impl MapColor {
    /// Both.
    pub const ALL: [MapColor; 2] = [MapColor::Class, MapColor::Lyapunov];

    /// `class` or `lyapunov`.
    pub fn label(self) -> &'static str {
        match self {
            MapColor::Class => "class",
            MapColor::Lyapunov => "lyapunov",
        }
    }

    /// What the cells show, in one line.
    pub fn description(self) -> &'static str {
        match self {
            MapColor::Class => "The motion class",
            MapColor::Lyapunov => "The largest Lyapunov exponent per unit τ",
        }
    }

    /// Whether the map measures the exponent at every point.
    pub fn needs_lyapunov(self) -> bool {
        self == MapColor::Lyapunov
    }
}
