//! What a curve follows, and what meets it: the names users type and read.

use crate::continuation::SpecialKind;
use serde::{Deserialize, Serialize};

/// The special point a curve follows in two parameters (`stickslip curve --follow`).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum Follow {
    /// An event appears or disappears: a turning point at the static friction limit, a slide
    /// whose lowest speed touches rest, or a stop whose force touches the static limit.
    Grazing,
    /// A real multiplier at +1 with the branch turning back (a saddle-node).
    Fold,
    /// A real multiplier at −1.
    PeriodDoubling,
    /// A complex pair of multipliers on the unit circle.
    NeimarkSacker,
}

impl Follow {
    /// All four, in the order of the command's help.
    pub const ALL: [Follow; 4] = [
        Follow::Grazing,
        Follow::Fold,
        Follow::PeriodDoubling,
        Follow::NeimarkSacker,
    ];

    /// The label users type and read: `grazing`, `fold`, `period-doubling`,
    /// `neimark-sacker`.
    pub fn label(self) -> &'static str {
        match self {
            Follow::Grazing => "grazing",
            Follow::Fold => "fold",
            Follow::PeriodDoubling => "period-doubling",
            Follow::NeimarkSacker => "neimark-sacker",
        }
    }

    /// The special point of a branch of one parameter that starts such a curve.
    pub fn special_kind(self) -> SpecialKind {
        match self {
            Follow::Grazing => SpecialKind::Grazing,
            Follow::Fold => SpecialKind::Fold,
            Follow::PeriodDoubling => SpecialKind::PeriodDoubling,
            Follow::NeimarkSacker => SpecialKind::NeimarkSacker,
        }
    }

    /// In words for messages: "fold", "period doubling", "Neimark–Sacker point", "grazing".
    pub fn words(self) -> &'static str {
        match self {
            Follow::Grazing => "grazing",
            Follow::Fold => "fold",
            Follow::PeriodDoubling => "period doubling",
            Follow::NeimarkSacker => "Neimark–Sacker point",
        }
    }
}

impl std::fmt::Display for Follow {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.label())
    }
}

/// The condition a grazing curve holds at zero, by the event that appears (see the module
/// documentation of [`crate::continuation`]'s curves).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum BorderKind {
    /// The net force |F − y| at a velocity zero (a turning point, or the start of a stop)
    /// equals μs: a turning point becomes a stop.
    TurnAtLimit,
    /// A slide's lowest speed (where y'' = 0 inside it) is zero: the slide touches rest
    /// mid-swing.
    SlideTouchesRest,
    /// At an extremum of the drive near a stop, the net force |F − y_stop| equals μs: a
    /// release becomes tangential (a stop splits in two, or a release no longer happens).
    ReleaseTangential,
}

impl BorderKind {
    /// The label in reports: `turn-at-limit`, `slide-touches-rest`, `release-tangential`.
    pub fn label(self) -> &'static str {
        match self {
            BorderKind::TurnAtLimit => "turn-at-limit",
            BorderKind::SlideTouchesRest => "slide-touches-rest",
            BorderKind::ReleaseTangential => "release-tangential",
        }
    }

    /// In words: "a turning point at the static friction limit", ...
    pub fn words(self) -> &'static str {
        match self {
            BorderKind::TurnAtLimit => "a turning point at the static friction limit",
            BorderKind::SlideTouchesRest => "a slide whose lowest speed touches rest",
            BorderKind::ReleaseTangential => "a release where the drive's force is extremal",
        }
    }
}

/// A point of codimension two on a curve: where two curves meet, or where the followed
/// special point degenerates.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Serialize, Deserialize)]
#[serde(rename_all = "kebab-case")]
pub enum Codim2Kind {
    /// A cusp of folds: the fold curve turns back in the parameter plane (three orbits meet).
    Cusp,
    /// A fold meets a grazing.
    FoldGrazing,
    /// A period doubling meets a grazing.
    PeriodDoublingGrazing,
    /// A Neimark–Sacker curve meets a grazing.
    NeimarkSackerGrazing,
    /// A 1:1 resonance: a double multiplier +1.
    Resonance11,
    /// A 1:2 resonance: a double multiplier −1.
    Resonance12,
    /// A fold meets a period doubling: multipliers +1 and −1.
    FoldFlip,
    /// Two grazings at once: another event of the grazing orbit appears or disappears.
    DoubleGrazing,
}

impl Codim2Kind {
    /// The label in reports: `cusp`, `fold-grazing`, `period-doubling-grazing`,
    /// `neimark-sacker-grazing`, `resonance-1:1`, `resonance-1:2`, `fold-flip`,
    /// `double-grazing`.
    pub fn label(self) -> &'static str {
        match self {
            Codim2Kind::Cusp => "cusp",
            Codim2Kind::FoldGrazing => "fold-grazing",
            Codim2Kind::PeriodDoublingGrazing => "period-doubling-grazing",
            Codim2Kind::NeimarkSackerGrazing => "neimark-sacker-grazing",
            Codim2Kind::Resonance11 => "resonance-1:1",
            Codim2Kind::Resonance12 => "resonance-1:2",
            Codim2Kind::FoldFlip => "fold-flip",
            Codim2Kind::DoubleGrazing => "double-grazing",
        }
    }

    /// The codimension-two point where a curve of `follow` meets a grazing.
    pub fn meets_grazing(follow: Follow) -> Self {
        match follow {
            Follow::Fold => Codim2Kind::FoldGrazing,
            Follow::PeriodDoubling => Codim2Kind::PeriodDoublingGrazing,
            Follow::NeimarkSacker => Codim2Kind::NeimarkSackerGrazing,
            Follow::Grazing => Codim2Kind::DoubleGrazing,
        }
    }
}

impl std::fmt::Display for Codim2Kind {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.label())
    }
}
