//! Which free parameters the records can determine.
//!
//! **Structurally** ([`plan`]), before any fit: the model sees a circuit's parameters only
//! through a few combinations. With PWL diodes: ζ through (R + R_D)·√(C/L), the natural
//! frequency through LC (a record's time axis is in seconds, its drive frequency known), the
//! turn-on voltage U_t (the unit of y and β) and μs. With Shockley diodes the same circuit
//! is seen through (R + R_s)/√(L/C), LC, n and I_s·√(L/C) (the diode's current in units of
//! U_t/√(L/C)); U_t is then only the unit of y. A mechanical oscillator's ζ = γ/(2√(km)),
//! ω0 = √(k/m), F0 (which divides the drive) and F0/k (the unit of r) fix all four of its
//! parameters. When the free parameters are more than the combinations they enter (R and
//! R_s both free; L, C and R with PWL diodes), the records cannot separate them, however many
//! and however good: the fit holds one of them at its starting value (the one named last)
//! and says so ([`FitWarning::NotIdentified`]). The rank is that of the matrix of
//! ∂ ln(combination)/∂ ln(parameter) (for R_D and R_s, whose value may be 0, the derivative
//! by the parameter over the whole series resistance), its null vectors from its
//! eigen-decomposition.
//!
//! **At the solution** ([`correlations`]): two fitted parameters correlated beyond ±0.99 are
//! named ([`FitWarning::Correlated`]).

use super::linalg::symmetric_eigen;
use super::{FitParameter, FitWarning};
use crate::experiment::{DiodeModel, Experiment};
use crate::physical::System;

/// The free parameters split into those fitted and those held, with the warnings that say
/// why.
#[derive(Debug, Clone, PartialEq)]
pub(super) struct Plan {
    /// The parameters to fit, in the order named.
    pub fitted: Vec<FitParameter>,
    /// The parameters held at their starting values.
    pub held: Vec<FitParameter>,
    /// One [`FitWarning::NotIdentified`] per combination the records cannot see.
    pub warnings: Vec<FitWarning>,
}

/// ∂ ln(combination)/∂ ln(parameter) of `p` for the combinations the model of `experiment`
/// sees (see the module documentation), and their names.
fn combinations(experiment: &Experiment) -> (Vec<&'static str>, Vec<(FitParameter, Vec<f64>)>) {
    use FitParameter as P;
    let Some(system) = experiment.system() else {
        return (Vec::new(), Vec::new());
    };
    match system {
        System::Circuit(_) => {
            let shockley = experiment.diode_model() == DiodeModel::Shockley;
            // The share of each resistance in the series sum is 1 by the convention of the
            // module documentation (the derivative over the whole sum).
            let rows = if shockley {
                vec![
                    (P::Resistance, vec![1.0, 0.0, 0.0, 0.0]),
                    (P::DiodeRs, vec![1.0, 0.0, 0.0, 0.0]),
                    (P::Inductance, vec![-0.5, -0.5, 0.0, 0.5]),
                    (P::Capacitance, vec![0.5, -0.5, 0.0, -0.5]),
                    (P::DiodeN, vec![0.0, 0.0, 1.0, 0.0]),
                    (P::DiodeIs, vec![0.0, 0.0, 0.0, 1.0]),
                ]
            } else {
                vec![
                    (P::Resistance, vec![1.0, 0.0, 0.0, 0.0]),
                    (P::Rd, vec![1.0, 0.0, 0.0, 0.0]),
                    (P::Inductance, vec![-0.5, -0.5, 0.0, 0.0]),
                    (P::Capacitance, vec![0.5, -0.5, 0.0, 0.0]),
                    (P::Ut, vec![0.0, 0.0, 1.0, 0.0]),
                    (P::MuS, vec![0.0, 0.0, 0.0, 1.0]),
                ]
            };
            let names = if shockley {
                vec!["(R + R_s)/√(L/C)", "LC", "n", "I_s·√(L/C)"]
            } else {
                vec!["(R + R_D)·√(C/L)", "LC", "U_t", "μs"]
            };
            (names, rows)
        }
        System::Mechanics(_) => (
            vec!["γ/√(km)", "k/m", "F0", "F0/k", "μs"],
            vec![
                (P::Damping, vec![1.0, 0.0, 0.0, 0.0, 0.0]),
                (P::Mass, vec![-0.5, -1.0, 0.0, 0.0, 0.0]),
                (P::Stiffness, vec![-0.5, 1.0, 0.0, -1.0, 0.0]),
                (P::Friction, vec![0.0, 0.0, 1.0, 1.0, 0.0]),
                (P::MuS, vec![0.0, 0.0, 0.0, 0.0, 1.0]),
            ],
        ),
    }
}

/// Split `free` into the parameters the records can determine and those held at their
/// starting values (see the module documentation).
pub(super) fn plan(experiment: &Experiment, free: &[FitParameter]) -> Plan {
    let (names, rows) = combinations(experiment);
    let column = |p: FitParameter| rows.iter().find(|(q, _)| *q == p).map(|(_, c)| c);
    let mut fitted = free.to_vec();
    let mut held = Vec::new();
    let mut warnings = Vec::new();
    loop {
        let known: Vec<FitParameter> = fitted
            .iter()
            .copied()
            .filter(|&p| column(p).is_some())
            .collect();
        let n = known.len();
        if n < 2 {
            break;
        }
        // DᵀD over the known parameters, and its smallest eigenpair.
        let mut a = vec![0.0; n * n];
        for (i, &p) in known.iter().enumerate() {
            for (k, &q) in known.iter().enumerate() {
                let (cp, cq) = (column(p).unwrap(), column(q).unwrap());
                a[i * n + k] = cp.iter().zip(cq).map(|(x, y)| x * y).sum();
            }
        }
        let (values, vectors) = symmetric_eigen(&a, n);
        let largest = values.last().copied().unwrap_or(0.0).max(f64::MIN_POSITIVE);
        if values[0] > 1e-10 * largest {
            break;
        }
        let null = &vectors[0];
        let group: Vec<FitParameter> = known
            .iter()
            .zip(null)
            .filter(|(_, v)| v.abs() > 1e-6)
            .map(|(&p, _)| p)
            .collect();
        let Some(&last) = group.last() else {
            break;
        };
        // The combinations the group enters, in words; two resistances in series: their sum.
        let combination = match group.as_slice() {
            [a, b] if is_resistance(*a) && is_resistance(*b) => {
                format!("{} + {}", symbol(*a), symbol(*b))
            }
            _ => {
                let used: Vec<&str> = names
                    .iter()
                    .enumerate()
                    .filter(|(c, _)| group.iter().any(|&p| column(p).unwrap()[*c] != 0.0))
                    .map(|(_, n)| *n)
                    .collect();
                match used.as_slice() {
                    [one] => one.to_string(),
                    [init @ .., last] => format!("{} and {last}", init.join(", ")),
                    [] => "fewer combinations".to_string(),
                }
            }
        };
        warnings.push(FitWarning::NotIdentified {
            parameters: group.clone(),
            combination,
            held: last,
        });
        fitted.retain(|&p| p != last);
        held.push(last);
    }
    Plan {
        fitted,
        held,
        warnings,
    }
}

fn is_resistance(p: FitParameter) -> bool {
    matches!(
        p,
        FitParameter::Resistance | FitParameter::Rd | FitParameter::DiodeRs
    )
}

fn symbol(p: FitParameter) -> &'static str {
    match p {
        FitParameter::Resistance => "R",
        FitParameter::Rd => "R_D",
        FitParameter::DiodeRs => "R_s",
        _ => p.label(),
    }
}

/// [`FitWarning::Correlated`] for every pair of `parameters` whose correlation (row-major
/// `correlation`) is beyond ±0.99.
pub(super) fn correlations(
    parameters: &[FitParameter],
    correlation: &[Vec<f64>],
) -> Vec<FitWarning> {
    let mut out = Vec::new();
    for i in 0..parameters.len() {
        for k in i + 1..parameters.len() {
            let r = correlation[i][k];
            if r.abs() > 0.99 {
                out.push(FitWarning::Correlated {
                    first: parameters[i],
                    second: parameters[k],
                    correlation: r,
                });
            }
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::shockley::DiodePair;
    use FitParameter as P;

    #[test]
    fn resistances_in_series_are_one_combination() {
        let e = Experiment::paper()
            .with_shockley(DiodePair::one_n4148())
            .unwrap();
        let plan = plan(&e, &[P::Resistance, P::DiodeIs, P::DiodeN, P::DiodeRs]);
        assert_eq!(plan.fitted, vec![P::Resistance, P::DiodeIs, P::DiodeN]);
        assert_eq!(plan.held, vec![P::DiodeRs]);
        let text = plan.warnings[0].to_string();
        assert!(
            text.contains("resistance and diode-rs enter the model only as R + R_s"),
            "{text}"
        );
        let plan = super::plan(&Experiment::paper(), &[P::Resistance, P::Rd, P::Ut]);
        assert_eq!(plan.held, vec![P::Rd]);
    }

    #[test]
    fn l_c_and_r_are_two_combinations_with_pwl_diodes_and_three_with_shockley() {
        let plan = plan(
            &Experiment::paper(),
            &[P::Inductance, P::Capacitance, P::Resistance, P::Ut],
        );
        assert_eq!(plan.fitted, vec![P::Inductance, P::Capacitance, P::Ut]);
        assert_eq!(plan.held, vec![P::Resistance]);
        let text = plan.warnings[0].to_string();
        assert!(
            text.contains("inductance, capacitance and resistance enter the model only as (R + R_D)·√(C/L) and LC"),
            "{text}"
        );
        // Shockley diodes also see √(L/C) through I_s·√(L/C).
        let shockley = Experiment::paper()
            .with_shockley(DiodePair::one_n4148())
            .unwrap();
        let all = [P::Inductance, P::Capacitance, P::Resistance];
        assert!(super::plan(&shockley, &all).held.is_empty());
        let with_is = [P::Inductance, P::Capacitance, P::Resistance, P::DiodeIs];
        assert_eq!(super::plan(&shockley, &with_is).held, vec![P::DiodeIs]);
        // A mechanical oscillator's four are four combinations.
        let m =
            Experiment::mechanics(crate::physical::Mechanics::new(0.5, 200.0, 2.0, 0.3).unwrap())
                .unwrap();
        assert!(super::plan(&m, &FitParameter::MECHANICS).held.is_empty());
    }
}
