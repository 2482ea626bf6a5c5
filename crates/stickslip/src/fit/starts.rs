//! Where a Shockley fit starts: in the valley of I_s and n.
//!
//! Over the currents a circuit reaches, many pairs (I_s, n) draw nearly the same diode: the
//! sum of squares has a long, narrow valley along which n·V_T·ln(i/I_s) stays the same at the
//! working current. A fit started off the valley (the 1N4148's values for a red LED) first
//! falls into it and then crawls along it. So the fit is started in the valley, at the
//! current the records work at: the PWL law's equivalent of the records (a PWL fit of U_t and
//! R_D, or the PWL fit `--compare` made) says what voltage the diodes drop there (the
//! **knee**, U_t + R_D·i plus whatever series resistance the PWL fit gave R beyond the
//! Shockley circuit's), and every (I_s, n) whose diode drops that voltage at that current is
//! a start ([`valley`]). The starts along n = 1 … 5 and the caller's own are screened by their
//! sum of squares, and the fit runs from the best.

use super::{FitParameter, Setup};
use crate::measure::Measurement;
use crate::physical::{Diode, System};
use crate::shockley::DiodePair;

/// A diode voltage at a current: what the PWL equivalent says the pair drops (V) at the
/// records' working current (A).
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) struct Knee {
    pub voltage: f64,
    pub current: f64,
}

/// The emission coefficients of the valley's starts (geometric, 1 to 5).
pub(super) const EMISSIONS: [f64; 7] = [1.0, 1.3, 1.7, 2.2, 2.9, 3.8, 5.0];

/// The records' working current (A): half the median over the records of the current
/// amplitude C·Ω·A that u_C's half peak-to-peak A at the drive's frequency Ω implies.
pub(super) fn working_current(capacitance: f64, data: &[Measurement]) -> Option<f64> {
    let mut currents: Vec<f64> = data
        .iter()
        .filter_map(|m| {
            let (lo, hi) = m
                .response
                .iter()
                .zip(&m.used)
                .filter(|(_, &u)| u)
                .fold((f64::INFINITY, f64::NEG_INFINITY), |(lo, hi), (&v, _)| {
                    (lo.min(v), hi.max(v))
                });
            let i = capacitance * std::f64::consts::TAU * m.drive.frequency * 0.5 * (hi - lo);
            (i.is_finite() && i > 0.0).then_some(i)
        })
        .collect();
    if currents.is_empty() {
        return None;
    }
    currents.sort_by(f64::total_cmp);
    Some(0.5 * currents[currents.len() / 2])
}

/// The PWL law's equivalent of a Shockley pair at the working current `i`: its junction
/// voltage there as U_t and its R_s as R_D (what a PWL fit of U_t and R_D starts from).
pub(super) fn pwl_equivalent(pair: &DiodePair, i: f64) -> (f64, f64) {
    (
        pair.voltage(i) - pair.series_resistance * i,
        pair.series_resistance,
    )
}

/// The knee a PWL fit gives: U_t + R_D·i, plus the series resistance its circuit has beyond
/// `resistance` (the Shockley circuit's R) times i.
pub(super) fn knee_of_pwl(system: &System, resistance: f64, i: f64) -> Option<Knee> {
    let System::Circuit(c) = system else {
        return None;
    };
    let Diode::Pwl(d) = c.diode else {
        return None;
    };
    let voltage = d.turn_on + (d.resistance + c.resistance - resistance) * i;
    (voltage.is_finite() && voltage > 0.0).then_some(Knee {
        voltage,
        current: i,
    })
}

/// Starts in the valley through `knee` for the free I_s and n of `setup` (coordinates of its
/// free values, the others as in `x`): for each of [`EMISSIONS`] the I_s whose pair drops the
/// knee's voltage at its current, with the pair's R_s; with only one of I_s and n free, the
/// one start that does. Empty when neither is free or the knee lies below R_s·i.
pub(super) fn valley(setup: &Setup, x: &[f64], knee: Knee) -> Vec<Vec<f64>> {
    let System::Circuit(c) = setup.system else {
        return Vec::new();
    };
    let Diode::Shockley(d) = c.diode else {
        return Vec::new();
    };
    let at = setup.values(&x[..setup.free.len()]);
    let value = |p: FitParameter, default: f64| {
        setup
            .free
            .iter()
            .position(|&q| q == p)
            .map_or(default, |k| at[k])
    };
    let pair = d.pair;
    let is = value(FitParameter::DiodeIs, pair.saturation_current);
    let n = value(FitParameter::DiodeN, pair.emission);
    let rs = value(FitParameter::DiodeRs, pair.series_resistance);
    let junction = knee.voltage - rs * knee.current;
    let vt = pair.thermal_voltage();
    if !(junction > 0.0) {
        return Vec::new();
    }
    let is_at = |n: f64| knee.current / (2.0 * (junction / (n * vt)).sinh());
    let k_is = setup.free.iter().position(|&q| q == FitParameter::DiodeIs);
    let k_n = setup.free.iter().position(|&q| q == FitParameter::DiodeN);
    let pairs: Vec<(f64, f64)> = match (k_is, k_n) {
        (Some(_), Some(_)) => EMISSIONS.iter().map(|&n| (is_at(n), n)).collect(),
        (Some(_), None) => vec![(is_at(n), n)],
        (None, Some(_)) => {
            vec![(is, junction / (vt * (knee.current / (2.0 * is)).asinh()))]
        }
        (None, None) => Vec::new(),
    };
    pairs
        .into_iter()
        .filter(|&(is, n)| is.is_finite() && is > 0.0 && n.is_finite() && n > 0.0)
        .map(|(is, n)| {
            let mut start = x.to_vec();
            if let Some(k) = k_is {
                start[k] = setup.coordinate(k, is);
            }
            if let Some(k) = k_n {
                start[k] = setup.coordinate(k, n);
            }
            start
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::experiment::Experiment;

    #[test]
    fn every_start_of_the_valley_drops_the_knee() {
        let e = Experiment::paper()
            .with_shockley(DiodePair::one_n4148())
            .unwrap();
        let free = [
            FitParameter::DiodeIs,
            FitParameter::DiodeN,
            FitParameter::DiodeRs,
        ];
        let setup = Setup::new(&e, &free).unwrap();
        let knee = Knee {
            voltage: 1.7,
            current: 2e-3,
        };
        let starts = valley(&setup, &[1.0, 1.0, 1.0], knee);
        assert_eq!(starts.len(), EMISSIONS.len());
        for (x, n) in starts.iter().zip(EMISSIONS) {
            let v = setup.values(x);
            assert!((v[1] - n).abs() < 1e-12);
            let pair = DiodePair::new(v[0], v[1], v[2], 27.0).unwrap();
            assert!((pair.voltage(2e-3) - 1.7).abs() < 1e-9, "{v:?}");
        }
    }
}
