//! The Jacobian of a law without sensitivities: central differences of the whole model.
//!
//! A mechanical oscillator on a moving belt, or with the Stribeck or cubic friction law, is
//! solved by the exact solver with a belt or by the friction solver
//! ([`crate::friction_solver::FrictionSolver`]: slips on the stiff integrator at a relative
//! and absolute tolerance of 10⁻¹², stops exact, every event located to 10⁻¹²), for which
//! neither the closed-form tangent dynamics of the beltless PWL law nor a smooth law's
//! forward sensitivities exist. Its Jacobian is then by central differences,
//! (r(x + h) − r(x − h))/2h: an error of order h² instead of forward differences' h, with
//! h = [`CENTRAL_STEP`] of each value's coordinate (scaled to 1 at the start): the
//! truncation is of order h² ≈ 10⁻⁸ of a column, and the model's own error over the step of
//! order 10⁻¹²/h ≈ 10⁻⁸ (the solver's tolerance and the steady state's, both 10⁻¹²), far
//! below what the fit's steps and error bars need. Each record's steady state settles from
//! the last model's strobe state (`Records::warm_start`), so that both sides of a
//! difference are the same attractor. Each record's own drive columns (amplitude, frequency,
//! phase; the time shift's is the phase's) come from that record alone. The report then
//! says `central-differences` ([`super::Jacobian::CentralDifferences`]).

use super::records::no_value;
use super::{FitError, Records};
use rayon::prelude::*;

/// The step of the central differences, relative to each coordinate (at least 1).
pub(super) const CENTRAL_STEP: f64 = 1e-4;

impl Records<'_> {
    /// Whether the records' model is a law without sensitivities (a belt, a friction law
    /// other than Coulomb's): its Jacobian is by central differences.
    pub(super) fn central(&self) -> bool {
        self.setup.friction.is_some()
    }

    /// The Jacobian by central differences (see the module documentation).
    pub(super) fn central_difference_jacobian(&self, x: &[f64]) -> Result<Vec<Vec<f64>>, FitError> {
        let n_free = self.setup.free.len();
        let spans = self.spans();
        let n_res = spans.last().map_or(0, |&(start, len)| start + len);
        let mut columns = vec![vec![0.0; n_res]; x.len()];
        let file = &self.data[0].file;
        for (k, column) in columns.iter_mut().enumerate().take(n_free) {
            let dx = CENTRAL_STEP * x[k].abs().max(1.0);
            let (lo, hi) = self.setup.bounds(k);
            let mut up = x.to_vec();
            let mut down = x.to_vec();
            up[k] = (x[k] + dx).min(hi);
            down[k] = (x[k] - dx).max(lo);
            let rp = self.all(&up);
            let rm = self.all(&down);
            let (rp, rm, width) = match (rp, rm) {
                (Some(rp), Some(rm)) => (rp, rm, up[k] - down[k]),
                _ => return Err(no_value(file, x[k] * self.setup.scale[k])),
            };
            for (i, (a, b)) in rp.concat().iter().zip(rm.concat()).enumerate() {
                column[i] = (a - b) / width;
            }
        }
        let experiment = self
            .setup
            .at(&x[..n_free])
            .ok_or_else(|| no_value(file, f64::NAN))?;
        // Per record, the response's derivatives by the drive amplitude, frequency and phase.
        let derivatives: Vec<Option<[Vec<f64>; 3]>> = (0..self.data.len())
            .into_par_iter()
            .map(|j| {
                let k = self.slots[j].drive;
                let (_, len) = spans[j];
                let half = len / 2;
                let mut out: [Vec<f64>; 3] = Default::default();
                for (q, column) in out.iter_mut().enumerate() {
                    let h = CENTRAL_STEP * x[k + q].abs().max(1.0);
                    let mut up = x.to_vec();
                    let mut down = x.to_vec();
                    up[k + q] += h;
                    down[k + q] -= h;
                    let (rp, _) = self.record_residuals(&experiment, &up, j)?;
                    let (rm, _) = self.record_residuals(&experiment, &down, j)?;
                    *column = rp[half..]
                        .iter()
                        .zip(&rm[half..])
                        .map(|(a, b)| (a - b) / (2.0 * h))
                        .collect();
                }
                Some(out)
            })
            .collect();
        self.place_drive_derivatives(x, &derivatives, &mut columns)?;
        Ok(columns)
    }
}
