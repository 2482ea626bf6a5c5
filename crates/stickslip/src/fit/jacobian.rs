//! Where a fit of records takes its Jacobian: one function ([`Records::jacobian_source`])
//! chooses among the exact tangent dynamics of the PWL law, the forward sensitivities of a
//! smooth law's periodic orbit, and plain finite differences, and says which served.
//!
//! **A smooth law's periodic orbit** ([`Records::sensitivity_jacobian`]). The model of a
//! record is the steady periodic orbit through the strobe state x* (the fixed point of the
//! p-period strobe map), sampled over the record. Its derivatives by the dimensionless
//! parameters (ζ_R, β, w, φ) and by the law's own (a, ε, r) come from the stiff solver's
//! forward sensitivities on its own steps ([`crate::stiff::sensitivity`]), with the fixed
//! point moving by (I − M)⁻¹ ∂P/∂q ([`ShockleyDynamics::orbit_sensitivity`]): one run of the
//! record per record and Jacobian, the derivatives of the computed samples, not differences
//! of runs whose steps differ, at a tolerance of their own ([`SENSITIVITY_RTOL`]) from the
//! residuals' fixed point. The chain rule takes them to the circuit's values:
//! ζ_R = R/(2Z), ω0 = 1/√(LC), Z = √(L/C), a = n·V_T/U_t, ε = 2·I_s·Z/U_t, r = R_s/Z (with
//! τ = ω0·t and w = Ω/ω0 at a fixed time in seconds), and ln I_s's coordinate by
//! [`super::Setup::slope`]. The report then says `sensitivities`.

use super::{FitError, FitParameter, Jacobian, Orbit, Records};
use crate::experiment::{DiodeModel, Law};
use crate::physical::{Diode, System};
use crate::shockley::ShockleyOptions;
use crate::stability::{ShockleyDynamics, SmoothOrbitSample};
use rayon::prelude::*;

/// The relative and absolute tolerance of the stiff solver in a fit with a smooth law (its
/// own default is 10⁻⁶): the residuals' own noise, which the steps of the minimisation and
/// the intervals' profiles see, well below a record's quantisation.
pub(crate) const SMOOTH_RTOL: f64 = 1e-7;

/// The relative and absolute tolerance of the runs that carry the sensitivities. The
/// derivative of the computed solution converges more slowly with the tolerance than the
/// solution itself (through a diode's turn the law's slope peaks over a time that loose
/// steps do not resolve): against Richardson differences of a tight model the columns of I_s,
/// n and R_s are 1.4 % off at 10⁻⁷ and within 3·10⁻⁴ (the reference's own accuracy) at this
/// tolerance (test `the_sensitivity_jacobian_matches_central_differences`).
const SENSITIVITY_RTOL: f64 = 1e-9;

/// How a free value moves a smooth law's model: ∂/∂p of ζ_R, ω0, a, ε and r.
#[derive(Debug, Clone, Copy, Default)]
struct SmoothLink {
    zeta: f64,
    omega0: f64,
    scale: f64,
    knee: f64,
    resistance: f64,
}

impl SmoothLink {
    /// How `p` moves the Shockley circuit `system` with the law (a, ε, r), or `None` where
    /// it does not enter the smooth model.
    fn of(p: FitParameter, system: &System, law: [f64; 3]) -> Option<Self> {
        let System::Circuit(c) = system else {
            return None;
        };
        let Diode::Shockley(d) = c.diode else {
            return None;
        };
        let (l, cap) = (c.inductance, c.capacitance);
        let z = c.impedance();
        let zeta = c.resistance / (2.0 * z);
        let omega0 = 1.0 / (l * cap).sqrt();
        let [a, eps, r] = law;
        let link = SmoothLink::default();
        Some(match p {
            FitParameter::Resistance => SmoothLink {
                zeta: 1.0 / (2.0 * z),
                ..link
            },
            FitParameter::Inductance => SmoothLink {
                zeta: -zeta / (2.0 * l),
                omega0: -omega0 / (2.0 * l),
                knee: eps / (2.0 * l),
                resistance: -r / (2.0 * l),
                ..link
            },
            FitParameter::Capacitance => SmoothLink {
                zeta: zeta / (2.0 * cap),
                omega0: -omega0 / (2.0 * cap),
                knee: -eps / (2.0 * cap),
                resistance: r / (2.0 * cap),
                ..link
            },
            FitParameter::DiodeIs => SmoothLink {
                knee: eps / d.pair.saturation_current,
                ..link
            },
            FitParameter::DiodeN => SmoothLink {
                scale: a / d.pair.emission,
                ..link
            },
            FitParameter::DiodeRs => SmoothLink {
                resistance: 1.0 / z,
                ..link
            },
            _ => return None,
        })
    }
}

impl Records<'_> {
    /// The Jacobian of the residuals `r` at `x`, column by column, and how it was computed:
    /// the exact tangent dynamics where they serve (PWL diodes, periodic models), the
    /// forward sensitivities of a smooth law's periodic orbits (Shockley diodes, periodic
    /// models), else finite differences of the whole model (a model that does not repeat, a
    /// table, [`super::FitOptions::exact_jacobian`] off).
    pub(super) fn jacobian_source(
        &self,
        x: &[f64],
        r: &[f64],
    ) -> Result<(Vec<Vec<f64>>, Jacobian), FitError> {
        if self.exact && self.central() {
            let columns = self.central_difference_jacobian(x)?;
            return Ok((columns, Jacobian::CentralDifferences));
        }
        if let Some(columns) = self.exact_jacobian(x) {
            return Ok((columns, Jacobian::Exact));
        }
        if let Some(columns) = self.sensitivity_jacobian(x) {
            return Ok((columns, Jacobian::Sensitivities));
        }
        Ok((
            self.finite_difference_jacobian(x, r)?,
            Jacobian::FiniteDifferences,
        ))
    }

    /// The Jacobian of a smooth law's periodic orbits from the stiff solver's forward
    /// sensitivities (see the module documentation), or `None` where it does not serve: PWL
    /// diodes, a record whose model has no period, a multiplier 1, a run that fails.
    pub(super) fn sensitivity_jacobian(&self, x: &[f64]) -> Option<Vec<Vec<f64>>> {
        if !self.exact || self.setup.experiment.diode_model() != DiodeModel::Shockley {
            return None;
        }
        let free = self.setup.free.len();
        let orbits: Vec<Orbit> = match &self.orbits {
            Some((at, orbits)) if at.as_slice() == x => orbits.clone(),
            _ => self.evaluate_all(x)?.into_iter().map(|(_, o)| o).collect(),
        };
        let experiment = self.setup.at(&x[..free])?;
        let Law::Shockley(law) = experiment.law().ok()? else {
            return None;
        };
        let options = *experiment.shockley_options();
        let options = ShockleyOptions {
            rtol: options.rtol.min(SENSITIVITY_RTOL),
            atol: options.atol.min(SENSITIVITY_RTOL),
            ..options
        };
        let dynamics = ShockleyDynamics::new(law, options)
            .ok()?
            .with_cancel(experiment.cancel().clone());
        let system = *experiment.system()?;
        let scales = system.scales();
        let (omega0, position, force) = (scales.omega0, scales.position, scales.force);
        let links: Vec<SmoothLink> = self
            .setup
            .free
            .iter()
            .map(|&p| SmoothLink::of(p, &system, [law.scale, law.knee, law.resistance]))
            .collect::<Option<_>>()?;
        let sensitivities: Vec<Vec<SmoothOrbitSample>> = (0..self.data.len())
            .into_par_iter()
            .map(|j| {
                let orbit = orbits[j];
                let taus: Vec<f64> = self.time[j].iter().map(|&s| s * omega0).collect();
                dynamics
                    .orbit_sensitivity(&orbit.params, orbit.strobe, orbit.period?, &taus)
                    .ok()
            })
            .collect::<Option<_>>()?;
        let n_res = 2 * self.time.iter().map(Vec::len).sum::<usize>();
        let mut columns = vec![vec![0.0; n_res]; x.len()];
        self.fill_drive_columns(x, &mut columns);
        for (j, &(start, len)) in self.spans().iter().enumerate() {
            let half = len / 2;
            let wr = self.weights[j].1;
            let slots = self.slots[j];
            let w = orbits[j].params.w;
            let sine = &self.data[j].drive;
            for (i, (sample, &seconds)) in sensitivities[j].iter().zip(&self.time[j]).enumerate() {
                let [dz, db, dw, dphi, _] = sample.dy;
                let [da, de, dr] = sample.dlaw;
                let row = start + half + i;
                for (k, link) in links.iter().enumerate() {
                    // u = U_t·y(τ = ω0·s; ζ_R, w = Ω/ω0, a, ε, r).
                    let dy = dz * link.zeta
                        + (sample.v * seconds - dw * w / omega0) * link.omega0
                        + da * link.scale
                        + de * link.knee
                        + dr * link.resistance;
                    columns[k][row] = wr * position * dy * self.setup.slope(k, x[k]);
                }
                slots.fill_drive(
                    &mut columns,
                    row,
                    wr * position,
                    [db, dw, dphi],
                    sine,
                    force,
                    omega0,
                );
            }
        }
        Some(columns)
    }
}

#[cfg(test)]
mod tests {
    use super::super::tests::record;
    use super::super::{lm, FitOptions, FitParameter, Records, Setup, Watch};
    use crate::experiment::Experiment;
    use crate::measure::Measurement;
    use crate::shockley::{DiodePair, ShockleyOptions};

    /// The Jacobian from the forward sensitivities of Shockley records against
    /// Richardson-extrapolated central differences of the residuals, each model from a steady
    /// state sought to 10⁻⁹ with the stiff solver at 10⁻¹¹: every column within 10⁻³ of its
    /// largest entry, for the diode's three values, C and every nuisance value, on a
    /// stick-slip and a sliding record.
    #[test]
    fn the_sensitivity_jacobian_matches_central_differences() {
        let truth = Experiment::paper()
            .with_shockley(DiodePair::new(2.5e-9, 1.8, 0.8, 27.0).unwrap())
            .unwrap();
        let data: Vec<Measurement> = [(0.29, 2.6, 0.4), (0.95, 2.14, -1.1)]
            .iter()
            .map(|&(w, beta, phi)| record(&truth, w, beta, phi))
            .collect();
        let start = Experiment::paper()
            .with_shockley(DiodePair::new(3e-9, 1.85, 0.6, 27.0).unwrap())
            .unwrap();
        let free = [
            FitParameter::DiodeIs,
            FitParameter::DiodeN,
            FitParameter::DiodeRs,
            FitParameter::Capacitance,
        ];
        let watch = Watch {
            monitor: &(),
            before: 0,
            total: 1,
        };
        let setup = Setup::new(&start, &free).unwrap();
        let (mut problem, x) = Records::new(&setup, &data, &FitOptions::default(), watch).unwrap();
        let r = lm::Problem::residuals(&mut problem, &x).unwrap().unwrap();
        let sensitivities = problem.sensitivity_jacobian(&x).expect("periodic models");
        // The reference: the same problem with a tight solver and steady state.
        let tight = start
            .clone()
            .with_shockley_options(
                ShockleyOptions::default()
                    .with_rtol(1e-11)
                    .unwrap()
                    .with_atol(1e-11)
                    .unwrap(),
            )
            .unwrap();
        let mut reference = Setup::new(&tight, &free).unwrap();
        reference.steady.tolerance = 1e-9;
        let (mut fine, _) = Records::new(&reference, &data, &FitOptions::default(), watch).unwrap();
        lm::Problem::residuals(&mut fine, &x).unwrap().unwrap();
        let central = |fine: &mut Records, k: usize, h: f64| -> Vec<f64> {
            let mut up = x.clone();
            let mut down = x.clone();
            up[k] += h;
            down[k] -= h;
            let a = fine.all(&up).unwrap().concat();
            let b = fine.all(&down).unwrap().concat();
            a.iter().zip(&b).map(|(a, b)| (a - b) / (2.0 * h)).collect()
        };
        let mut bad = Vec::new();
        for k in 0..x.len() {
            let h = 1e-4 * x[k].abs().max(1.0);
            let (coarse, finer) = (central(&mut fine, k, h), central(&mut fine, k, h / 2.0));
            let size = finer.iter().fold(0.0f64, |a, v| a.max(v.abs()));
            let worst = (0..r.len()).fold(0.0f64, |m, i| {
                let richardson = (4.0 * finer[i] - coarse[i]) / 3.0;
                m.max((sensitivities[k][i] - richardson).abs())
            });
            let rms = ((0..r.len())
                .map(|i| (sensitivities[k][i] - (4.0 * finer[i] - coarse[i]) / 3.0).powi(2))
                .sum::<f64>()
                / r.len() as f64)
                .sqrt();
            let fd = (0..r.len()).fold(0.0f64, |m, i| m.max((coarse[i] - finer[i]).abs()));
            eprintln!(
                "column {k}: deviation {:.2e} (rms {:.2e}, h against h/2 {:.2e}) of its largest \
                 entry {size:.3e}",
                worst / size,
                rms / size,
                fd / size
            );
            bad.push((k, worst / size));
        }
        assert!(bad.iter().all(|&(_, d)| d <= 1e-3), "{bad:?}");
    }
}
