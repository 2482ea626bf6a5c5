//! The paper's series solution and the exact periodic solution side by side at one point:
//! what `stickslip theory --json` prints, what the Python package's `theory()` returns and the
//! lab shows.

use super::boundary::stick_slip_boundary;
use super::paper::{paper_boundary, PaperHarmonic, PaperSeries};
use super::periodic::PeriodicSolution;
use crate::error::{Error, NoSolutionReason, Result};
use crate::params::Params;
use serde::{Serialize, Serializer};

/// Why a value of the report is missing, or a caveat about it.
#[derive(Debug, Clone, Copy, PartialEq)]
#[non_exhaustive]
pub enum TheoryNote {
    /// The quantity `label` does not exist.
    Missing {
        /// What is missing, e.g. `A1 (eq. 11)`.
        label: &'static str,
        /// Why.
        reason: NoSolutionReason,
    },
    /// The paper's eq. (13) takes static friction equal to kinetic friction.
    StaticFriction {
        /// The experiment's μs (≠ 1).
        mu_s: f64,
    },
    /// β lies below the paper's own boundary: by its criterion the motion sticks.
    BelowOwnBoundary,
    /// The exact non-sticking periodic solution does not exist.
    NoOrbit(NoSolutionReason),
    /// Near w = 1/(2n) with little damping the symmetric solution is one of a continuum.
    Continuum(u32),
}

impl std::fmt::Display for TheoryNote {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match *self {
            TheoryNote::Missing { label, reason } => write!(f, "{label}: {reason}"),
            TheoryNote::StaticFriction { mu_s } => write!(
                f,
                "eq. (13) takes static friction equal to kinetic (μs = 1), not μs = {mu_s}"
            ),
            TheoryNote::BelowOwnBoundary => f.write_str(
                "β is below the paper's own boundary (eq. 13): by its criterion the motion sticks",
            ),
            TheoryNote::NoOrbit(reason) => {
                write!(f, "no non-sticking periodic solution: {reason}")
            }
            TheoryNote::Continuum(n) => {
                let at = if n == 1 {
                    "1/2".to_string()
                } else {
                    format!("1/{}", 2 * n)
                };
                write!(
                    f,
                    "w is near {at} with little damping: there the symmetric solution is one of \
                     a continuum of periodic motions, most of them asymmetric (exactly so at \
                     ζ = 0, w = {at}), and attracts only weakly; a simulation may settle elsewhere"
                )
            }
        }
    }
}

fn join_notes<S: Serializer>(notes: &[TheoryNote], s: S) -> Result<S::Ok, S::Error> {
    let text: Vec<String> = notes.iter().map(|n| n.to_string()).collect();
    s.serialize_str(&text.join("; "))
}

/// The parameters of a report.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct ReportParams {
    /// Damping ratio ζ.
    pub zeta: f64,
    /// Drive frequency w.
    pub w: f64,
    /// Drive amplitude β.
    pub beta: f64,
    /// Static-to-kinetic friction ratio μs.
    pub mu_s: f64,
}

/// The paper's values (eqs. (11) and (13)); `None` where they do not exist.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct PaperValues {
    /// A1 of eq. (11).
    #[serde(rename = "A1")]
    pub a1: Option<f64>,
    /// A3 of eq. (11).
    #[serde(rename = "A3")]
    pub a3: Option<f64>,
    /// A5 of eq. (11).
    #[serde(rename = "A5")]
    pub a5: Option<f64>,
    /// Lag φ0 of the fundamental behind the drive (radians).
    pub phi0: Option<f64>,
    /// Gain of the fundamental G1 = A1/β.
    pub gain1: Option<f64>,
    /// β_c of eq. (13).
    pub beta_c: Option<f64>,
    /// Why values are missing, and caveats.
    #[serde(
        rename = "note",
        skip_serializing_if = "Vec::is_empty",
        serialize_with = "join_notes"
    )]
    pub notes: Vec<TheoryNote>,
}

/// The exact values; `None` where they do not exist.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct ExactValues {
    /// Whether the symmetric non-sticking periodic solution exists.
    pub exists: bool,
    /// Its peak max |y|.
    pub peak: Option<f64>,
    /// Its A1.
    #[serde(rename = "A1")]
    pub a1: Option<f64>,
    /// Its A3.
    #[serde(rename = "A3")]
    pub a3: Option<f64>,
    /// Its A5.
    #[serde(rename = "A5")]
    pub a5: Option<f64>,
    /// Lag of its fundamental behind the drive (radians).
    pub phase: Option<f64>,
    /// Its gain of the fundamental G1 = A1/β.
    pub gain1: Option<f64>,
    /// The exact stick-slip boundary β_c(w, ζ, μs).
    pub beta_c: Option<f64>,
    /// Spectral radius of its turning-point map (< 1: it attracts nearby motions).
    pub spectral_radius: Option<f64>,
    /// Why values are missing, and caveats.
    #[serde(
        rename = "note",
        skip_serializing_if = "Vec::is_empty",
        serialize_with = "join_notes"
    )]
    pub notes: Vec<TheoryNote>,
}

/// Both theories at one point.
///
/// ```
/// use stickslip::theory::TheoryReport;
/// use stickslip::Params;
/// let r = TheoryReport::new(&Params::new(0.0468, 0.9, 2.0).unwrap()).unwrap();
/// assert!(r.exact.exists);
/// // The paper's A1 is off; its A3 is exact on a sliding orbit.
/// assert!((r.paper.a3.unwrap() - r.exact.a3.unwrap()).abs() < 1e-12);
/// ```
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct TheoryReport {
    /// ζ, w, β and μs.
    pub params: ReportParams,
    /// The paper's series solution and boundary.
    pub paper: PaperValues,
    /// The exact periodic solution and boundary.
    pub exact: ExactValues,
}

/// `Some(x)`, or `None` with a note when the quantity does not exist; other errors pass.
fn value(
    result: Result<f64>,
    label: &'static str,
    notes: &mut Vec<TheoryNote>,
) -> Result<Option<f64>> {
    match result {
        Ok(x) if x.is_finite() => Ok(Some(x)),
        Ok(_) => Ok(None),
        Err(Error::NoSolution { reason, .. }) => {
            notes.push(TheoryNote::Missing { label, reason });
            Ok(None)
        }
        Err(e) => Err(e),
    }
}

impl TheoryReport {
    /// Both theories at `params`.
    ///
    /// # Errors
    /// Invalid parameters; [`crate::Unsupported::TheoryNeedsCoulombAtRest`] for a belt or a
    /// Stribeck or cubic law; a numerical failure of the exact construction.
    pub fn new(params: &Params) -> Result<Self> {
        let params = params.validate()?;
        super::periodic::check_coulomb_at_rest(&params)?;
        let (zeta, w, beta) = (params.zeta, params.w, params.beta);
        let mut paper_notes = Vec::new();
        let series = PaperSeries::new(zeta, w, beta);
        let a1 = value(
            series.clone().map(|s| s.a1),
            "A1 (eq. 11)",
            &mut paper_notes,
        )?;
        let phi0 = series.as_ref().ok().map(|s| s.phi0);
        let a3 = value(
            PaperHarmonic::new(zeta, w, 3).map(|h| h.amplitude),
            "A3 (eq. 11)",
            &mut paper_notes,
        )?;
        let a5 = value(
            PaperHarmonic::new(zeta, w, 5).map(|h| h.amplitude),
            "A5 (eq. 11)",
            &mut paper_notes,
        )?;
        let paper_beta_c = value(paper_boundary(zeta, w), "beta_c (eq. 13)", &mut paper_notes)?;
        if params.mu_s != 1.0 {
            paper_notes.push(TheoryNote::StaticFriction { mu_s: params.mu_s });
        }
        if let (Ok(s), Some(_)) = (&series, paper_beta_c) {
            if !s.slides_by_eq13() {
                paper_notes.push(TheoryNote::BelowOwnBoundary);
            }
        }

        let mut exact_notes = Vec::new();
        let orbit = match PeriodicSolution::new(&params) {
            Ok(s) => Some(s),
            Err(Error::NoSolution { reason, .. }) => {
                exact_notes.push(TheoryNote::NoOrbit(reason));
                None
            }
            Err(e) => return Err(e),
        };
        let exact_beta_c = match stick_slip_boundary(zeta, w, params.mu_s) {
            Ok(b) => {
                if orbit.is_none() {
                    if let Some(n) = b.continuum {
                        exact_notes.push(TheoryNote::Continuum(n));
                    }
                }
                Some(b.beta_c)
            }
            Err(Error::NoSolution { reason, .. }) => {
                if !exact_notes.contains(&TheoryNote::NoOrbit(reason)) {
                    exact_notes.push(TheoryNote::Missing {
                        label: "beta_c",
                        reason,
                    });
                }
                None
            }
            Err(e) => return Err(e),
        };
        if let Some(n) = orbit.as_ref().and_then(|s| s.continuum) {
            exact_notes.push(TheoryNote::Continuum(n));
        }
        let harmonic = |k: u32| orbit.as_ref().map(|s| s.harmonic(k).amplitude);
        Ok(Self {
            params: ReportParams {
                zeta,
                w,
                beta,
                mu_s: params.mu_s,
            },
            paper: PaperValues {
                a1,
                a3,
                a5,
                phi0,
                gain1: a1.map(|a| a / beta),
                beta_c: paper_beta_c,
                notes: paper_notes,
            },
            exact: ExactValues {
                exists: orbit.is_some(),
                peak: orbit.as_ref().map(|s| s.peak),
                a1: orbit.as_ref().map(|s| s.a1()),
                a3: harmonic(3),
                a5: harmonic(5),
                phase: orbit.as_ref().map(|s| s.phase_lag()),
                gain1: orbit.as_ref().map(|s| s.gain1()),
                beta_c: exact_beta_c,
                spectral_radius: orbit.as_ref().map(|s| s.spectral_radius()),
                notes: exact_notes,
            },
        })
    }
}
