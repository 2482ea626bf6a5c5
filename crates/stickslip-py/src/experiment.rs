//! `stickslip.Experiment`: the library's [`ExperimentSpec`] (what the user gave, key by key)
//! and the [`Experiment`] it builds.

use crate::{either, error, json_value};
use pyo3::exceptions::{
    PyFileNotFoundError, PyIsADirectoryError, PyOSError, PyPermissionError, PyTypeError,
    PyValueError,
};
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyString, PyTuple};
use std::path::PathBuf;
use stickslip::experiment::{
    DiodeModel, Experiment, ExperimentSpec, Key, KeyForm, Preset, SpecError,
};

/// One experiment: a dimensionless model, a circuit with PWL or Shockley diodes, or a
/// mechanical oscillator (on a belt moving at vb, or at rest); a drive; the friction ratio μs;
/// an initial state.
///
/// Everything is dimensionless inside (τ = ω0·t):
///     y'' + 2ζ y' + y + sgn(y' − vb) = β cos(w τ + φ)   while slipping,
///     y' = vb and |β cos(w τ + φ) − y − 2ζ vb| ≤ μs       while stuck
/// (vb = 0, the paper's model, unless a belt is given; a belt without a drive is
/// self-excited).
///
/// Build one with ``Experiment(zeta=, w=, beta=)`` (dimensionless),
/// ``Experiment.paper(w=, beta=)`` (the paper's circuit), ``Experiment.circuit(...)``,
/// ``Experiment.shockley(...)``, ``Experiment.mechanics(...)`` or
/// ``Experiment.from_toml(path)``; change values with ``.replace(**changes)``, which returns a
/// new experiment. The drive (w and β) may be left out when a sweep or a phase diagram sets
/// it. Keyword names are those of the TOML experiment file: zeta w beta phi mu_s y0 v0, L C R
/// U_t R_D, m k gamma F0, U (or F) f omega, uc0 i0, Is n Rs temperature, diode, preset, vb
/// (the belt speed, dimensionless) or belt_speed (m/s; mechanical only: a circuit has no
/// belt), friction_law (coulomb, stribeck or cubic) with vs delta eta (Stribeck) or k1 k3
/// (cubic), dimensionless, or stribeck_speed viscous_friction cubic_k1 cubic_k3 (mechanical,
/// SI units).
/// Physical values may be numbers in SI units or strings with an SI prefix ("11.5m").
///
/// Experiments are immutable, comparable and picklable (through their JSON, ``to_json``).
///
/// ``Experiment(zeta=None, w=None, beta=None, phi=0, mu_s=1, y0=0, v0=0, vb=0)`` is the
/// dimensionless model:
///
/// Args:
///     zeta: damping ratio ζ ≥ 0 (default: the paper's circuit, 0.046816).
///     w: drive frequency w = Ω/ω0 > 0 (None: set later by a sweep or a map).
///     beta: drive amplitude β ≥ 0 in units of the kinetic friction force (None: set
///         later).
///     phi: drive phase φ at τ = 0, radians (default 0).
///     mu_s: static-to-kinetic friction ratio μs ≥ 1 (default 1, as in the paper).
///     y0: initial position (default 0).
///     v0: initial velocity (default 0).
///     vb: belt speed vb in units of y' (default 0: no belt; with vb ≠ 0 and no drive the
///         motion is self-excited, and ``steady`` finds its own period).
///
/// Raises:
///     ValueError: a value out of range, or a description that is incomplete or contradicts
///         itself, with the library's one-line message.
///     TypeError: an unknown keyword.
///
/// Example:
///     >>> import stickslip
///     >>> Experiment(zeta=0.05, w=0.7, beta=1.2).mu_s
///     1.0
///     >>> exp = stickslip.Experiment.paper(w=0.95, beta=2.14)
///     >>> round(exp.zeta, 6)
///     0.046816
///     >>> exp.replace(beta=1.2).beta
///     1.2
#[pyclass(module = "stickslip", name = "Experiment", frozen)]
pub struct PyExperiment {
    spec: ExperimentSpec,
    experiment: Experiment,
}

impl PyExperiment {
    /// Build the experiment of `spec`.
    fn build(spec: ExperimentSpec) -> PyResult<Self> {
        let experiment = spec.build().map_err(error)?;
        Ok(Self { spec, experiment })
    }

    /// The built experiment as JSON: what equality and hashing compare.
    fn identity(&self) -> String {
        serde_json::to_string(&self.experiment).unwrap_or_default()
    }

    /// The library's experiment.
    pub(crate) fn experiment(&self) -> &Experiment {
        &self.experiment
    }
}

/// The library's key table, one dict per key (`_core.KEYS`): the stubs' keywords and the
/// tests are made from it.
pub(crate) fn key_table(py: Python<'_>) -> PyResult<Bound<'_, PyAny>> {
    json_value(py, &Key::table())
}

/// The library's error as a `ValueError`; a name a key does not take (the diode law, the
/// preset) named as the argument `name` that took it, in the words of the key's help:
/// `invalid diode 'spice': must be 'pwl' (exact solver) or 'shockley' (stiff solver)`.
fn text_error(e: stickslip::Error, name: &str) -> PyErr {
    match e.render_name_for_python(name) {
        Some(message) => PyValueError::new_err(message),
        None => error(e),
    }
}

/// Every keyword of a key (its name and the other names it takes), for messages.
fn key_names() -> String {
    let names: Vec<&str> = Key::ALL
        .iter()
        .flat_map(|k| std::iter::once(k.name()).chain(k.name_aliases().iter().copied()))
        .collect();
    names.join(", ")
}

/// Add `name = value` to `spec`; `None` removes the quantity (for `replace`).
fn put(
    spec: &mut ExperimentSpec,
    unset: &mut Vec<Key>,
    name: &str,
    value: &Bound<'_, PyAny>,
) -> PyResult<()> {
    let key = Key::from_name(name).ok_or_else(|| {
        PyTypeError::new_err(format!(
            "unknown experiment keyword '{name}': the keywords are {}",
            key_names()
        ))
    })?;
    if value.is_none() {
        unset.push(key);
        return Ok(());
    }
    if key.form() == KeyForm::Choice {
        let text: String = value.extract().map_err(|_| {
            PyTypeError::new_err(format!(
                "{name} must be a string: {}",
                either(key.choices())
            ))
        })?;
        spec.set_text(key, &text).map_err(|e| text_error(e, name))?;
        return Ok(());
    }
    let number =
        if let Ok(text) = value.cast::<PyString>() {
            spec.set_text(key, &text.to_cow()?)
                .map_err(|e| text_error(e, name))?;
            return Ok(());
        } else if value.is_instance_of::<pyo3::types::PyBool>() {
            return Err(PyTypeError::new_err(format!(
                "{name} must be a number, not a bool"
            )));
        } else {
            value.extract::<f64>().map_err(|_| {
                PyTypeError::new_err(format!(
                "{name} must be a number (or a string with an SI prefix such as \"20n\"), not {}",
                value.get_type().name().map(|n| n.to_string()).unwrap_or_default()
            ))
            })?
        };
    spec.set(key, number).map_err(error)?;
    Ok(())
}

/// A layer of keys from keyword arguments given one by one and as `**keys`.
fn layer(
    named: &[(&str, Option<&Bound<'_, PyAny>>)],
    keys: Option<&Bound<'_, PyDict>>,
) -> PyResult<(ExperimentSpec, Vec<Key>)> {
    let mut spec = ExperimentSpec::new();
    let mut unset = Vec::new();
    for (name, value) in named {
        if let Some(v) = value {
            put(&mut spec, &mut unset, name, v)?;
        }
    }
    if let Some(keys) = keys {
        for (k, v) in keys.iter() {
            let name: String = k.extract()?;
            put(&mut spec, &mut unset, &name, &v)?;
        }
    }
    Ok((spec, unset))
}

/// A new experiment from keyword arguments over `base`, keys given as `None` removed.
fn from_layer(
    base: ExperimentSpec,
    named: &[(&str, Option<&Bound<'_, PyAny>>)],
    keys: Option<&Bound<'_, PyDict>>,
) -> PyResult<PyExperiment> {
    let (top, unset) = layer(named, keys)?;
    let mut spec = base;
    for key in unset {
        spec.unset_quantity(key);
    }
    PyExperiment::build(spec.overlay(&top))
}

/// The experiment with the diode law `model` ('pwl' or 'shockley'): the `model=` argument of
/// the computations.
#[pyfunction]
pub fn with_diode(experiment: PyRef<'_, PyExperiment>, model: &str) -> PyResult<PyExperiment> {
    let mut top = ExperimentSpec::new();
    top.set_text(Key::Diode, model)
        .map_err(|e| text_error(e, "model"))?;
    PyExperiment::build(experiment.spec.overlay(&top))
}

fn preset_paper() -> ExperimentSpec {
    let mut spec = ExperimentSpec::new();
    spec.set_preset(Preset::Paper);
    spec
}

#[pymethods]
impl PyExperiment {
    /// A dimensionless experiment (documented on the class: Python shows the class's docstring).
    /// Any other keyword is refused with the keywords this constructor takes and where a
    /// physical one (`omega`, `L`, ...) goes.
    #[new]
    #[pyo3(
        signature = (zeta=None, w=None, beta=None, phi=None, mu_s=None, y0=None, v0=None, vb=None, **others),
        text_signature = "(zeta=None, w=None, beta=None, phi=0, mu_s=1, y0=0, v0=0, vb=0)"
    )]
    #[allow(clippy::too_many_arguments)]
    fn new(
        zeta: Option<&Bound<'_, PyAny>>,
        w: Option<&Bound<'_, PyAny>>,
        beta: Option<&Bound<'_, PyAny>>,
        phi: Option<&Bound<'_, PyAny>>,
        mu_s: Option<&Bound<'_, PyAny>>,
        y0: Option<&Bound<'_, PyAny>>,
        v0: Option<&Bound<'_, PyAny>>,
        vb: Option<&Bound<'_, PyAny>>,
        others: Option<&Bound<'_, PyDict>>,
    ) -> PyResult<Self> {
        if let Some((name, _)) = others.and_then(|o| o.iter().next()) {
            let name: String = name.extract()?;
            let known = "Experiment() takes the dimensionless model's keywords zeta, w, beta, \
                         phi, mu_s, y0, v0, vb";
            let elsewhere = "Experiment.paper(...), Experiment.circuit(...), \
                             Experiment.shockley(...), Experiment.mechanics(...) or \
                             Experiment.from_dict(...)";
            return Err(PyTypeError::new_err(match Key::from_name(&name) {
                Some(key) => {
                    let what = key.help().split(':').next().unwrap_or_default();
                    let mut letters = what.chars();
                    let what: String = letters
                        .next()
                        .map(|c| c.to_lowercase().chain(letters).collect())
                        .unwrap_or_default();
                    format!(
                        "{known}; {name} ({what}) belongs to a physical description: give it \
                         to {elsewhere}"
                    )
                }
                None => format!(
                    "unknown experiment keyword '{name}': {known}; a physical description \
                     takes {} (through {elsewhere})",
                    key_names()
                ),
            }));
        }
        let named = [
            ("zeta", zeta),
            ("w", w),
            ("beta", beta),
            ("phi", phi),
            ("mu_s", mu_s),
            ("y0", y0),
            ("v0", v0),
            ("vb", vb),
        ];
        from_layer(ExperimentSpec::new(), &named, None)
    }

    /// The paper's circuit: L = 11.5 mH, C = 0.02 µF, R = 68 Ω, PWL diodes U_t = 0.7 V,
    /// R_D = 3 Ω (ζ = 0.046816, f0 = 10494.37 Hz).
    ///
    /// Args:
    ///     w: drive frequency w = Ω/ω0 (or give f in Hz, or omega in rad/s).
    ///     beta: drive amplitude β = U/U_t (or give U in volts).
    ///     **keys: any other experiment key, e.g. U=1.498, f=9.97e3, diode="shockley",
    ///         R=100 (to change a part), mu_s, phi, y0, v0, uc0 (V), i0 (A).
    ///
    /// Example:
    ///     >>> exp = Experiment.paper(f=9.97e3, U=1.498)
    ///     >>> round(exp.w, 4), round(exp.beta, 4)
    ///     (0.95, 2.14)
    #[classmethod]
    #[pyo3(signature = (w=None, beta=None, **keys))]
    fn paper(
        _cls: &Bound<'_, pyo3::types::PyType>,
        w: Option<&Bound<'_, PyAny>>,
        beta: Option<&Bound<'_, PyAny>>,
        keys: Option<&Bound<'_, PyDict>>,
    ) -> PyResult<Self> {
        from_layer(preset_paper(), &[("w", w), ("beta", beta)], keys)
    }

    /// A series RLC circuit damped by two anti-parallel PWL diodes (U_t sgn(i) + R_D i).
    ///
    /// Args:
    ///     L: inductance in henry (> 0).
    ///     C: capacitance in farad (> 0).
    ///     R: series resistance in ohms without the diodes (≥ 0).
    ///     U_t: diode turn-on voltage in volts (> 0); the unit of y and β.
    ///     R_D: diode resistance in ohms (≥ 0).
    ///     U: drive amplitude in volts (or beta=).
    ///     f: drive frequency in hertz (or w=, or omega= in rad/s).
    ///     **keys: any other experiment key (phi, mu_s, uc0, i0, ...).
    ///
    /// Example:
    ///     >>> exp = Experiment.circuit(L="11.5m", C="20n", R=68, U_t=0.7, R_D=3, U=1.498, f=9.97e3)
    ///     >>> round(exp.beta, 2)
    ///     2.14
    #[classmethod]
    #[pyo3(signature = (L=None, C=None, R=None, U_t=None, R_D=None, U=None, f=None, **keys))]
    #[allow(non_snake_case)]
    fn circuit(
        _cls: &Bound<'_, pyo3::types::PyType>,
        L: Option<&Bound<'_, PyAny>>,
        C: Option<&Bound<'_, PyAny>>,
        R: Option<&Bound<'_, PyAny>>,
        U_t: Option<&Bound<'_, PyAny>>,
        R_D: Option<&Bound<'_, PyAny>>,
        U: Option<&Bound<'_, PyAny>>,
        f: Option<&Bound<'_, PyAny>>,
        keys: Option<&Bound<'_, PyDict>>,
    ) -> PyResult<Self> {
        let named = [
            ("L", L),
            ("C", C),
            ("R", R),
            ("U_t", U_t),
            ("R_D", R_D),
            ("U", U),
            ("f", f),
        ];
        from_layer(ExperimentSpec::new(), &named, keys)
    }

    /// A series RLC circuit damped by two anti-parallel Shockley diodes,
    /// U_D(i) = n·V_T·asinh(i/2I_s) + R_s·i, solved by the stiff (Radau IIA) solver.
    ///
    /// Args:
    ///     L, C, R: as for ``circuit`` (henry, farad, ohms).
    ///     U_t: reference voltage in volts (> 0): the unit of y and β (0.7 V in the paper).
    ///     U: drive amplitude in volts (or beta=).
    ///     f: drive frequency in hertz (or w=, or omega=).
    ///     Is: saturation current in amperes (default 4.352 nA, 1N4148).
    ///     n: emission coefficient (default 1.906).
    ///     Rs: series resistance in ohms (default 0.6458).
    ///     temperature: diode temperature in °C (default 27).
    ///     **keys: any other experiment key.
    ///
    /// The paper's circuit with Shockley diodes is ``Experiment.paper(diode="shockley")``.
    ///
    /// Example:
    ///     >>> Experiment.shockley(L=11.5e-3, C=20e-9, R=68, U_t=0.7, w=0.95, beta=2.14).model
    ///     'shockley'
    #[classmethod]
    #[pyo3(signature = (L=None, C=None, R=None, U_t=None, U=None, f=None, Is=None, n=None, Rs=None, temperature=None, **keys))]
    #[allow(non_snake_case)]
    fn shockley(
        _cls: &Bound<'_, pyo3::types::PyType>,
        L: Option<&Bound<'_, PyAny>>,
        C: Option<&Bound<'_, PyAny>>,
        R: Option<&Bound<'_, PyAny>>,
        U_t: Option<&Bound<'_, PyAny>>,
        U: Option<&Bound<'_, PyAny>>,
        f: Option<&Bound<'_, PyAny>>,
        Is: Option<&Bound<'_, PyAny>>,
        n: Option<&Bound<'_, PyAny>>,
        Rs: Option<&Bound<'_, PyAny>>,
        temperature: Option<&Bound<'_, PyAny>>,
        keys: Option<&Bound<'_, PyDict>>,
    ) -> PyResult<Self> {
        let mut base = ExperimentSpec::new();
        base.set_diode(DiodeModel::Shockley);
        let named = [
            ("L", L),
            ("C", C),
            ("R", R),
            ("U_t", U_t),
            ("U", U),
            ("f", f),
            ("Is", Is),
            ("n", n),
            ("Rs", Rs),
            ("temperature", temperature),
        ];
        from_layer(base, &named, keys)
    }

    /// A mass on a spring with viscous damping and dry (Coulomb) friction, driven by a
    /// harmonic force.
    ///
    /// Args:
    ///     m: mass in kg (> 0).
    ///     k: spring constant in N/m (> 0).
    ///     gamma: viscous damping in N·s/m (≥ 0).
    ///     F0: kinetic friction force in N (> 0): the unit of β.
    ///     F: drive amplitude in newtons (or beta=).
    ///     omega: drive angular frequency in rad/s (or w=, or f= in Hz).
    ///     **keys: any other experiment key (mu_s, phi, uc0 = r(0) in m, i0 = ṙ(0) in m/s,
    ///         belt_speed in m/s: the block on a moving belt).
    ///
    /// Example:
    ///     >>> exp = Experiment.mechanics(m=2, k=8, gamma=0.4, F0=0.5, F=1, omega=1.8)
    ///     >>> exp.w, exp.beta
    ///     (0.9, 2.0)
    #[classmethod]
    #[pyo3(signature = (m=None, k=None, gamma=None, F0=None, F=None, omega=None, **keys))]
    #[allow(non_snake_case)]
    fn mechanics(
        _cls: &Bound<'_, pyo3::types::PyType>,
        m: Option<&Bound<'_, PyAny>>,
        k: Option<&Bound<'_, PyAny>>,
        gamma: Option<&Bound<'_, PyAny>>,
        F0: Option<&Bound<'_, PyAny>>,
        F: Option<&Bound<'_, PyAny>>,
        omega: Option<&Bound<'_, PyAny>>,
        keys: Option<&Bound<'_, PyDict>>,
    ) -> PyResult<Self> {
        let named = [
            ("m", m),
            ("k", k),
            ("gamma", gamma),
            ("F0", F0),
            ("F", F),
            ("omega", omega),
        ];
        from_layer(ExperimentSpec::new(), &named, keys)
    }

    /// The experiment described by a TOML file (sections `[circuit]` or `[mechanics]`, `[drive]`,
    /// `[model]`, `[shockley]`; see the README), the same file ``stickslip --config`` reads.
    ///
    /// Raises:
    ///     FileNotFoundError: no such file; PermissionError, IsADirectoryError or another
    ///         OSError: the file cannot be read (as Python's ``open`` raises them).
    ///     ValueError: the file is not a valid description; the message names the file, the
    ///         line and the key.
    ///
    /// Example:
    ///     >>> exp = Experiment.from_toml("exp.toml")  # doctest: +SKIP
    #[classmethod]
    fn from_toml(_cls: &Bound<'_, pyo3::types::PyType>, path: PathBuf) -> PyResult<Self> {
        let name = path.display().to_string();
        let text = std::fs::read_to_string(&path).map_err(|e| {
            let message = format!("cannot read experiment file {name}: {e}");
            // The OSError subclass that Python's own open() raises for the same failure.
            match e.kind() {
                std::io::ErrorKind::NotFound => PyFileNotFoundError::new_err(message),
                std::io::ErrorKind::PermissionDenied => PyPermissionError::new_err(message),
                std::io::ErrorKind::IsADirectory => PyIsADirectoryError::new_err(message),
                _ => PyOSError::new_err(message),
            }
        })?;
        Self::build(ExperimentSpec::from_toml(&text, &name).map_err(error)?)
    }

    /// The experiment of a dict of keys, as ``to_dict`` returns it.
    ///
    /// Example:
    ///     >>> Experiment.from_dict({"preset": "paper", "w": 0.7}).w
    ///     0.7
    #[classmethod]
    fn from_dict(
        _cls: &Bound<'_, pyo3::types::PyType>,
        keys: &Bound<'_, PyDict>,
    ) -> PyResult<Self> {
        from_layer(ExperimentSpec::new(), &[], Some(keys))
    }

    /// The experiment of its JSON text (``to_json``).
    #[classmethod]
    fn from_json(_cls: &Bound<'_, pyo3::types::PyType>, text: &str) -> PyResult<Self> {
        let spec: ExperimentSpec = serde_json::from_str(text)
            .map_err(|e| PyValueError::new_err(format!("not an experiment's JSON: {e}")))?;
        Self::build(spec)
    }

    /// A new experiment with some keys changed (any experiment keyword; ``None`` removes a
    /// value). A value given in another form replaces the old one: ``replace(f=1e4)`` replaces
    /// w.
    ///
    /// Example:
    ///     >>> Experiment.paper(w=0.7, beta=1.2).replace(w=0.9).w
    ///     0.9
    #[pyo3(signature = (**changes))]
    fn replace(&self, changes: Option<&Bound<'_, PyDict>>) -> PyResult<Self> {
        from_layer(self.spec.clone(), &[], changes)
    }

    /// The keys as given, as a dict (``from_dict`` takes it back).
    fn to_dict<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        let out = PyDict::new(py);
        if let Some(p) = self.spec.preset() {
            out.set_item("preset", p.label())?;
        }
        if let Some(d) = self.spec.diode() {
            out.set_item("diode", d.label())?;
        }
        for key in Key::ALL {
            if let Some(v) = self.spec.get(key) {
                out.set_item(key.name(), v)?;
            }
        }
        Ok(out)
    }

    /// The description as JSON text, for storage (``from_json`` reads it back).
    fn to_json(&self) -> PyResult<String> {
        serde_json::to_string(&self.spec)
            .map_err(|e| PyValueError::new_err(format!("cannot serialise the experiment: {e}")))
    }

    /// What a physical description means in the dimensionless model: the dict that
    /// ``stickslip convert --json`` prints, with omega0 (rad/s), f0 (Hz), alpha (1/s),
    /// zeta, Q, and w and beta when the drive is given.
    ///
    /// Raises:
    ///     ValueError: for a dimensionless experiment, or a drive with only one of w, β.
    ///
    /// Example:
    ///     >>> round(Experiment.paper().convert()["f0"], 2)
    ///     10494.37
    fn convert<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyAny>> {
        let e = &self.experiment;
        if e.w().is_some() != e.beta().is_some() {
            let key = if e.w().is_none() { Key::W } else { Key::Beta };
            return Err(error(SpecError::MissingDrive { key }.into()));
        }
        let Some(conversion) = e.conversion() else {
            return Err(PyValueError::new_err(
                "convert needs a physical description: Experiment.paper(), .circuit(), \
                 .shockley(), .mechanics() or .from_toml()",
            ));
        };
        json_value(py, &conversion)
    }

    /// The scales from the dimensionless model to physical units, or None for a
    /// dimensionless experiment: a dict with ``omega0`` (rad/s), ``f0`` = ω0/2π (Hz: a drive
    /// frequency f = w·f0), ``position`` (V of u_C, or m, per unit of y), ``velocity`` (A,
    /// or m/s, per unit of y'), ``force`` (V of the drive U, or N of F, per unit of β), and
    /// the units of the last three: ``position_unit``, ``velocity_unit``, ``force_unit``.
    ///
    /// Example:
    ///     >>> s = Experiment.paper().scales()
    ///     >>> round(s["f0"], 2), s["force_unit"]
    ///     (10494.37, 'V')
    ///     >>> Experiment(w=1, beta=2).scales() is None
    ///     True
    fn scales<'py>(&self, py: Python<'py>) -> PyResult<Option<Bound<'py, PyDict>>> {
        let Some(units) = self.experiment.units() else {
            return Ok(None);
        };
        let s = units.scales;
        let (position, velocity, force) = if units.circuit {
            ("V", "A", "V")
        } else {
            ("m", "m/s", "N")
        };
        let out = PyDict::new(py);
        out.set_item("omega0", s.omega0)?;
        out.set_item("f0", s.f0())?;
        out.set_item("position", s.position)?;
        out.set_item("velocity", s.velocity)?;
        out.set_item("force", s.force)?;
        out.set_item("position_unit", position)?;
        out.set_item("velocity_unit", velocity)?;
        out.set_item("force_unit", force)?;
        Ok(Some(out))
    }

    /// Damping ratio ζ (ζ_R, of the resistance only, with Shockley diodes).
    #[getter]
    fn zeta(&self) -> f64 {
        self.experiment.zeta()
    }

    /// Drive frequency w = Ω/ω0, or None when not given.
    #[getter]
    fn w(&self) -> Option<f64> {
        self.experiment.w()
    }

    /// Drive amplitude β (U/U_t or F/F0), or None when not given.
    #[getter]
    fn beta(&self) -> Option<f64> {
        self.experiment.beta()
    }

    /// Drive phase φ at τ = 0 (radians).
    #[getter]
    fn phi(&self) -> f64 {
        self.experiment.phi()
    }

    /// Static-to-kinetic friction ratio μs.
    #[getter]
    fn mu_s(&self) -> f64 {
        self.experiment.mu_s()
    }

    /// Initial position y0 (dimensionless).
    #[getter]
    fn y0(&self) -> f64 {
        self.experiment.initial().y
    }

    /// Initial velocity v0 (dimensionless).
    #[getter]
    fn v0(&self) -> f64 {
        self.experiment.initial().v
    }

    /// The diode law and so the solver: 'pwl' (exact) or 'shockley' (stiff).
    #[getter]
    fn model(&self) -> &'static str {
        self.experiment.diode_model().label()
    }

    /// 'dimensionless', 'circuit' or 'mechanics'.
    #[getter]
    fn system(&self) -> &'static str {
        self.experiment.system_kind().label()
    }

    /// One line: the description, its natural frequency and drive in physical units, and the
    /// dimensionless numbers (what the command-line tool prints on standard error).
    fn __str__(&self) -> String {
        self.experiment.to_string()
    }

    fn __repr__(&self, py: Python<'_>) -> PyResult<String> {
        Ok(format!(
            "stickslip.Experiment.from_dict({})",
            self.to_dict(py)?.repr()?
        ))
    }

    /// Experiments are equal when they build the same experiment (the same system, values and
    /// origin), compared through their JSON so that equality and hashing agree.
    fn __eq__(&self, other: &Bound<'_, PyAny>) -> bool {
        other
            .cast::<PyExperiment>()
            .is_ok_and(|o| o.get().identity() == self.identity())
    }

    fn __hash__(&self) -> u64 {
        use std::hash::{Hash, Hasher};
        let mut h = std::collections::hash_map::DefaultHasher::new();
        self.identity().hash(&mut h);
        h.finish()
    }

    fn __reduce__<'py>(
        slf: &Bound<'py, Self>,
    ) -> PyResult<(Bound<'py, PyAny>, Bound<'py, PyTuple>)> {
        let from_json = slf.get_type().getattr("from_json")?;
        let json = slf.get().to_json()?;
        Ok((from_json, PyTuple::new(slf.py(), [json])?))
    }
}
