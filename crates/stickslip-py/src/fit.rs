//! Measurements and fits: `read_scope`, `read_amplitudes` and `fit`. The files are read here
//! (the library takes text); the library's readers and fits do the rest, and the fit's JSON
//! is the library's [`FitReportJson`](stickslip::fit::FitReportJson), the same as
//! `stickslip fit --json` prints.

use crate::experiment::PyExperiment;
use crate::json_value;
use crate::runner::run_with;
use numpy::PyArray1;
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyList};
use std::path::Path;
use stickslip::fit::{
    fit_per_record_monitored, fit_records_monitored, fit_table_monitored, fit_undriven_monitored,
    FitMonitor, FitOptions, FitParameter, FitProgress, FitReport, UndrivenRecord,
};
use stickslip::measure::{self, AmplitudeTable, MeasureError, Measurement, Record};
use stickslip::scan::Monitor;

fn measure_error(e: MeasureError) -> PyErr {
    match &e.swap {
        Some((drive, response)) => PyValueError::new_err(format!(
            "{e}: give drive=\"{drive}\", response=\"{response}\""
        )),
        None => PyValueError::new_err(e.to_string()),
    }
}

/// The text of the file `path` (UTF-8, UTF-16 or Windows-1252, see
/// [`measure::decode`]); a missing, empty or binary file is a `ValueError` naming it.
fn read_text(path: &str) -> PyResult<String> {
    match std::fs::read(Path::new(path)) {
        Ok(bytes) => measure::decode(&bytes, path).map_err(measure_error),
        Err(e) => Err(PyValueError::new_err(format!("{path}: {e}"))),
    }
}

/// The record of `paths` (several single-channel files merged on their common times).
fn record_of(paths: &[String]) -> PyResult<Record> {
    let parts = paths
        .iter()
        .map(|p| measure::read_scope(&read_text(p)?, p).map_err(measure_error))
        .collect::<PyResult<Vec<_>>>()?;
    Record::merge(parts).map_err(measure_error)
}

/// The record and its measurement (drive and response picked, the drive's sine fitted).
fn measurement_of(
    paths: &[String],
    drive: Option<&str>,
    response: Option<&str>,
) -> PyResult<(Record, Measurement)> {
    let record = record_of(paths)?;
    let m = Measurement::new(&record, drive, response).map_err(measure_error)?;
    Ok((record, m))
}

fn array<'py>(py: Python<'py>, data: Vec<f64>) -> Bound<'py, PyArray1<f64>> {
    PyArray1::from_vec(py, data)
}

/// A scope record as a dict of numpy arrays and metadata; see `stickslip.read_scope`.
#[pyfunction]
#[pyo3(signature = (paths, drive=None, response=None))]
pub fn read_scope<'py>(
    py: Python<'py>,
    paths: Vec<String>,
    drive: Option<String>,
    response: Option<String>,
) -> PyResult<Bound<'py, PyDict>> {
    let (record, m) = measurement_of(&paths, drive.as_deref(), response.as_deref())?;
    let out = PyDict::new(py);
    out.set_item("file", &record.file)?;
    out.set_item("format", record.format.label())?;
    out.set_item("sample_interval_s", record.sample_interval)?;
    out.set_item("t_s", array(py, record.time.clone()))?;
    let channels = PyDict::new(py);
    let units = PyDict::new(py);
    let resolution = PyDict::new(py);
    let clipped = PyDict::new(py);
    for c in &record.channels {
        channels.set_item(&c.name, array(py, c.values.clone()))?;
        units.set_item(&c.name, &c.unit)?;
        resolution.set_item(&c.name, c.resolution)?;
        clipped.set_item(&c.name, c.clipped_count())?;
    }
    out.set_item("channels", channels)?;
    out.set_item("units", units)?;
    out.set_item("resolution_V", resolution)?;
    out.set_item("clipped", clipped)?;
    let metadata = PyDict::new(py);
    for (k, v) in &record.metadata {
        metadata.set_item(k, v)?;
    }
    out.set_item("metadata", metadata)?;
    out.set_item("drive_channel", &m.drive_channel)?;
    out.set_item("response_channel", &m.response_channel)?;
    out.set_item("freq_Hz", m.drive.frequency)?;
    out.set_item("amplitude_V", m.drive.amplitude)?;
    out.set_item("phase", m.drive.phase)?;
    out.set_item("drive_offset_V", m.drive.offset)?;
    out.set_item("periods", m.drive.periods)?;
    out.set_item("noise_V", m.noise)?;
    Ok(out)
}

fn read_table(path: &str) -> PyResult<AmplitudeTable> {
    measure::read_amplitudes(&read_text(path)?, path).map_err(measure_error)
}

/// A table of measured amplitudes as a dict of numpy arrays; see `stickslip.read_amplitudes`.
#[pyfunction]
pub fn read_amplitudes<'py>(py: Python<'py>, path: String) -> PyResult<Bound<'py, PyDict>> {
    let table = read_table(&path)?;
    let out = PyDict::new(py);
    out.set_item("file", &table.file)?;
    let rows = &table.rows;
    let col = |f: fn(&measure::AmplitudeRow) -> f64| array(py, rows.iter().map(f).collect());
    out.set_item(
        "line",
        PyArray1::from_vec(py, rows.iter().map(|r| r.line as i64).collect()),
    )?;
    out.set_item("freq_Hz", col(|r| r.frequency))?;
    out.set_item("U_V", col(|r| r.drive))?;
    out.set_item("response_V", col(|r| r.response))?;
    out.set_item("A1_V", col(|r| r.a1.unwrap_or(f64::NAN)))?;
    out.set_item("A3_V", col(|r| r.a3.unwrap_or(f64::NAN)))?;
    let direction = PyList::empty(py);
    for r in rows {
        direction.append(r.direction.map(|d| match d {
            measure::Direction::Up => "up",
            _ => "down",
        }))?;
    }
    out.set_item("direction", direction)?;
    Ok(out)
}

/// A fit's report as a dict: `report` (the JSON shape as Python objects), `records` (per
/// record: t_s, measured_V, model_V, residual_V arrays) and `values` (name → fitted value).
fn report_dict<'py>(py: Python<'py>, report: &FitReport) -> PyResult<Bound<'py, PyDict>> {
    let out = PyDict::new(py);
    out.set_item("report", json_value(py, &report.to_json())?)?;
    let records = PyList::empty(py);
    for rec in &report.records {
        let r = PyDict::new(py);
        r.set_item("file", &rec.file)?;
        r.set_item("t_s", array(py, rec.time.clone()))?;
        r.set_item(
            "measured_V",
            array(
                py,
                rec.model
                    .iter()
                    .zip(&rec.residuals)
                    .map(|(m, e)| m - e)
                    .collect(),
            ),
        )?;
        r.set_item("model_V", array(py, rec.model.clone()))?;
        r.set_item("residual_V", array(py, rec.residuals.clone()))?;
        records.append(r)?;
    }
    out.set_item("records", records)?;
    let n = report.parameters.len();
    let covariance: Vec<Vec<f64>> = (0..n)
        .map(|i| {
            (0..n)
                .map(|j| {
                    report.correlation[i][j]
                        * report.parameters[i].stderr
                        * report.parameters[j].stderr
                })
                .collect()
        })
        .collect();
    out.set_item("covariance", covariance)?;
    // The fitted values by the experiment's key names (`R`, `U_t`, ...), for `replace`.
    let keys = PyDict::new(py);
    for p in &report.parameters {
        keys.set_item(p.parameter.key().name(), p.value)?;
    }
    out.set_item("keys", keys)?;
    let names: Vec<&str> = report
        .parameters
        .iter()
        .map(|p| p.parameter.label())
        .collect();
    out.set_item("names", names)?;
    Ok(out)
}

/// The runner's monitor told of a fit's iterations (done, most allowed).
struct Iterations<'a>(&'a dyn Monitor);

impl FitMonitor for Iterations<'_> {
    fn iteration(&self, p: &FitProgress) -> std::ops::ControlFlow<()> {
        self.0.step(p.iteration, p.total)
    }
}

/// The fit of `experiment` to records (each `(paths, drive, response)`) or to the table
/// `table`; see `stickslip.fit`.
#[pyfunction]
#[pyo3(signature = (experiment, records, table, free, per_record, progress=None, from_rest=None, belt_speeds=None))]
#[allow(clippy::too_many_arguments)]
pub fn fit<'py>(
    py: Python<'py>,
    experiment: PyRef<'py, PyExperiment>,
    records: Vec<(Vec<String>, Option<String>, Option<String>)>,
    table: Option<String>,
    free: Option<Vec<String>>,
    per_record: bool,
    progress: Option<Bound<'py, PyAny>>,
    from_rest: Option<f64>,
    belt_speeds: Option<Vec<Option<f64>>>,
) -> PyResult<Bound<'py, PyList>> {
    let fit_error = |e: stickslip::fit::FitError| PyValueError::new_err(e.to_string());
    // The default: the library's free set of the system and diode law.
    let parameters = match free {
        Some(names) => names
            .iter()
            .map(|name| name.parse::<FitParameter>().map_err(fit_error))
            .collect::<PyResult<Vec<_>>>()?,
        None => FitParameter::defaults_of(experiment.experiment()).map_err(fit_error)?,
    };
    let table = table.as_deref().map(read_table).transpose()?;
    // A mechanical record without a drive (the displacement alone, or beside a constant
    // channel) is the record of an undriven belt.
    let mechanics = matches!(
        experiment.experiment().system(),
        Some(stickslip::physical::System::Mechanics(_))
    );
    let mut data = Vec::new();
    let mut undriven = Vec::new();
    if let Some(b) = &belt_speeds {
        if b.len() != records.len() {
            return Err(PyValueError::new_err(format!(
                "belt_speeds has {} values for {} records: give one per record (None for the \
                 experiment's belt speed)",
                b.len(),
                records.len()
            )));
        }
    }
    for (j, (paths, d, r)) in records.iter().enumerate() {
        let record = record_of(paths)?;
        let belt_speed = belt_speeds.as_ref().and_then(|b| b[j]);
        if mechanics && d.is_none() && UndrivenRecord::is_undriven(&record) {
            let mut u = UndrivenRecord::new(&record, r.as_deref()).map_err(measure_error)?;
            if let Some(position) = from_rest {
                u = u.from_rest(position).map_err(measure_error)?;
            }
            if let Some(v) = belt_speed {
                u = u.on_belt(v).map_err(measure_error)?;
            }
            undriven.push(u);
        } else if belt_speed.is_some() {
            return Err(PyValueError::new_err(format!(
                "{}: a belt speed of its own is for a record of an undriven belt (a \
                 displacement without a drive)",
                paths.join("+")
            )));
        } else {
            data.push(
                Measurement::new(&record, d.as_deref(), r.as_deref()).map_err(measure_error)?,
            );
        }
    }
    if let (Some(u), Some(d)) = (undriven.first(), data.first()) {
        return Err(PyValueError::new_err(format!(
            "{} has no drive and {} has one: undriven and driven records are fitted apart",
            u.file, d.file
        )));
    }
    if from_rest.is_some() && undriven.is_empty() {
        return Err(PyValueError::new_err(
            "from_rest is for records of an undriven belt (a displacement without a drive)",
        ));
    }
    let e = experiment.experiment().clone();
    let options = FitOptions::default();
    // `progress(done, total)`: Levenberg–Marquardt iterations done, of the most allowed.
    let result = run_with(py, progress.as_ref(), |monitor, cancel| {
        let e = e.with_cancel(cancel.clone());
        let monitor = &Iterations(monitor);
        Ok(match &table {
            Some(t) => fit_table_monitored(&e, t, &parameters, &options, monitor).map(|r| vec![r]),
            None if !undriven.is_empty() && per_record => undriven
                .iter()
                .map(|u| {
                    fit_undriven_monitored(
                        &e,
                        std::slice::from_ref(u),
                        &parameters,
                        &options,
                        monitor,
                    )
                })
                .collect(),
            None if !undriven.is_empty() => {
                fit_undriven_monitored(&e, &undriven, &parameters, &options, monitor)
                    .map(|r| vec![r])
            }
            None if per_record => {
                fit_per_record_monitored(&e, &data, &parameters, &options, monitor)
            }
            None => {
                fit_records_monitored(&e, &data, &parameters, &options, monitor).map(|r| vec![r])
            }
        })
    })?;
    let reports = result.map_err(|e| PyValueError::new_err(e.to_string()))?;
    let out = PyList::empty(py);
    for r in &reports {
        out.append(report_dict(py, r)?)?;
    }
    Ok(out)
}
