//! The `Material` class: a validated material of the simplified Maxwell–Beard model.

use crate::errors::core_err;
use crate::errors::io_err;
use crate::errors::warn_units;
use polbrdf::model::KeyValue;
use polbrdf::optics::dispersion::{Dispersion, SpectralIndex};
use polbrdf::{AzimuthTerm, Form, Material, MaterialSpec};
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use pyo3::types::PyDict;
use std::path::{Path, PathBuf};

/// The material-file keys (the core's list) in the order of the constructor's keyword
/// arguments: `name` last.
pub(crate) fn python_keys() -> impl Iterator<Item = &'static str> {
    polbrdf::model::KEYS
        .iter()
        .copied()
        .filter(|k| *k != "name" && *k != "index")
        .chain(["name", "index"])
}

/// A validated material of the simplified Maxwell–Beard model.
///
/// The keyword arguments are exactly the keys of a material file (see the README):
///
/// - ``n``: real part of the refractive index (> 0).
/// - ``k``: extinction coefficient (≥ 0), default 0.
/// - ``index``: instead of ``n``, ``k``, a spectral index: ``"library:<id>"`` (a library entry,
///   e.g. ``"library:Au/Johnson"``; ``polbrdf materials`` lists them) or the path of a
///   refractiveindex.info YAML file. Evaluations then need ``wavelength_um=``.
/// - ``sigma_deg``: roughness σ in degrees (``b = 1/σ²``, σ in rad); or
/// - ``b``: width of the facet distribution ``D = a·exp(−b·θN²)`` in rad⁻².
///   Give exactly one of ``sigma_deg`` and ``b``.
/// - ``a``: amplitude of D in sr⁻¹; ``None`` (default) = hemispherical normalization.
/// - ``form``: ``"standard"`` (eq. 1, default) or ``"paper"`` (eq. 6 as printed).
/// - ``shadowing``: apply the shadowing/obscuration function SO (eq. 3), default True.
/// - ``tau_deg``, ``omega_deg``: τ and Ω of eq. 3 in degrees, default 15 and 40.
/// - ``azimuth_term``: ``"none"`` (default) or ``"eq3"`` (the ΦN factor of eq. 3).
/// - ``rho_d``, ``rho_v``: volume-scattering constants ρ_D, ρ_V in sr⁻¹, default 0.
/// - ``name``: an optional label.
///
/// Raises ``ValueError`` with the core's message (naming the key and value) for an invalid
/// parameter. Instances are immutable, comparable with ``==`` and picklable.
#[pyclass(name = "Material", module = "polbrdf", frozen, eq)]
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct PyMaterial {
    pub(crate) inner: Material,
}

pub(crate) fn parse_form(s: &str) -> PyResult<Form> {
    s.parse::<Form>()
        .map_err(|m| PyValueError::new_err(format!("invalid `form`: {m}")))
}

pub(crate) fn parse_azimuth(s: &str) -> PyResult<AzimuthTerm> {
    s.parse::<AzimuthTerm>()
        .map_err(|m| PyValueError::new_err(format!("invalid `azimuth_term`: {m}")))
}

/// Validates a spec into a material; a spectral one is built at the first wavelength of its
/// data (every evaluation then takes its wavelengths from the call).
pub(crate) fn build(py: Python<'_>, spec: &MaterialSpec) -> PyResult<PyMaterial> {
    match spec.wavelength_range() {
        Some((lo, _)) => spec.build_at(lo),
        None => spec.build(),
    }
    .map(|inner| PyMaterial { inner })
    .map_err(|e| core_err(py, &e))
}

/// A material key's value in a pickled state (`bool` before `float`: Python's `True` is an
/// `int`).
#[derive(FromPyObject, IntoPyObject)]
pub(crate) enum StateValue {
    Bool(bool),
    Number(f64),
    Text(String),
}

/// A dispersion of a pickled spectral index: `("table", wavelengths, values, kind 0, no
/// range)` or `("formula", coefficients, [], kind, range)`.
type DispersionState = (String, Vec<f64>, Vec<f64>, u8, (f64, f64));

/// A spectral index in a pickled state: source, name, references, comments, n, k.
type SpectralState = (
    String,
    String,
    String,
    String,
    DispersionState,
    Option<DispersionState>,
);

/// A [`PyMaterial`] as plain values: its keys but `index` (the core's `entries`), and its
/// spectral index's data.
pub(crate) type MaterialState = (Vec<(String, StateValue)>, Option<SpectralState>);

fn dispersion_state(d: &Dispersion) -> DispersionState {
    match d {
        Dispersion::Table {
            wavelengths,
            values,
        } => (
            "table".into(),
            wavelengths.clone(),
            values.clone(),
            0,
            (0.0, 0.0),
        ),
        Dispersion::Formula {
            kind,
            coefficients,
            range,
        } => (
            "formula".into(),
            coefficients.clone(),
            Vec::new(),
            *kind,
            *range,
        ),
    }
}

fn dispersion(state: DispersionState) -> PyResult<Dispersion> {
    match state {
        (t, wavelengths, values, _, _) if t == "table" => Ok(Dispersion::Table {
            wavelengths,
            values,
        }),
        (t, coefficients, _, kind, range) if t == "formula" => Ok(Dispersion::Formula {
            kind,
            coefficients,
            range,
        }),
        (t, ..) => Err(PyValueError::new_err(format!(
            "a pickled Material's dispersion is \"table\" or \"formula\", not {t:?}"
        ))),
    }
}

/// The pickled state of `spec` ([`MaterialState`]).
pub(crate) fn material_state(spec: &MaterialSpec) -> MaterialState {
    let keys = spec
        .entries()
        .into_iter()
        .filter(|(k, _)| *k != "index")
        .map(|(k, v)| {
            let v = match v {
                KeyValue::Number(x) => StateValue::Number(x),
                KeyValue::Text(t) => StateValue::Text(t),
                KeyValue::Bool(b) => StateValue::Bool(b),
            };
            (k.to_string(), v)
        })
        .collect();
    let spectral = spec.spectral.as_ref().map(|s| {
        let i = &s.index;
        (
            s.source.clone(),
            i.name.clone(),
            i.references.clone(),
            i.comments.clone(),
            dispersion_state(&i.n),
            i.k.as_ref().map(dispersion_state),
        )
    });
    (keys, spectral)
}

/// The inverse of `Material.__reduce__`: the keys set as a material file's are
/// (`MaterialSpec::set`), the spectral index from its data.
#[pyfunction]
pub(crate) fn _material_from_state(py: Python<'_>, state: MaterialState) -> PyResult<PyMaterial> {
    let (keys, spectral) = state;
    let mut spec = MaterialSpec::new(f64::NAN, f64::NAN);
    spec.sigma_deg = None;
    for (key, value) in keys {
        let value = match value {
            StateValue::Bool(b) => KeyValue::Bool(b),
            StateValue::Number(x) => KeyValue::Number(x),
            StateValue::Text(t) => KeyValue::Text(t),
        };
        spec.set(&key, value)
            .map_err(|m| PyValueError::new_err(format!("a pickled Material's `{key}`: {m}")))?;
    }
    if let Some((source, name, references, comments, n, k)) = spectral {
        let index = SpectralIndex {
            name,
            n: dispersion(n)?,
            k: k.map(dispersion).transpose()?,
            references,
            comments,
        };
        spec.spectral = Some(polbrdf::model::SpectralSource {
            source,
            index: std::sync::Arc::new(index),
        });
    }
    build(py, &spec)
}

/// Python literal of a float (shortest round-trip form, as `repr(float)` gives).
pub(crate) fn py_float(x: f64) -> String {
    let s = format!("{x:?}");
    // Rust writes 1e-5 / 1e20, Python 1e-05 / 1e+20: both are valid literals, but match Python.
    match s.split_once('e') {
        Some((m, e)) => {
            let (sign, digits) = match e.strip_prefix('-') {
                Some(d) => ('-', d),
                None => ('+', e),
            };
            format!("{m}e{sign}{digits:0>2}")
        }
        None => s,
    }
}

#[pymethods]
impl PyMaterial {
    #[new]
    #[pyo3(signature = (
        n = None, k = None, sigma_deg = None, b = None, a = None, form = None,
        shadowing = None, tau_deg = None, omega_deg = None, azimuth_term = None, rho_d = None,
        rho_v = None, name = None, index = None
    ))]
    #[allow(clippy::too_many_arguments)]
    fn new(
        py: Python<'_>,
        n: Option<f64>,
        k: Option<f64>,
        sigma_deg: Option<f64>,
        b: Option<f64>,
        a: Option<f64>,
        form: Option<&str>,
        shadowing: Option<bool>,
        tau_deg: Option<f64>,
        omega_deg: Option<f64>,
        azimuth_term: Option<&str>,
        rho_d: Option<f64>,
        rho_v: Option<f64>,
        name: Option<String>,
        index: Option<String>,
    ) -> PyResult<Self> {
        // `None`: the core's default (written once, in `MaterialSpec::new`).
        let d = MaterialSpec::new(f64::NAN, f64::NAN);
        let spectral = match (&index, n, k) {
            (Some(_), Some(_), _) | (Some(_), _, Some(_)) => {
                return Err(PyValueError::new_err(
                    "give either `index` (a spectral index) or the constant `n`, `k`, not both",
                ))
            }
            (None, None, _) => {
                return Err(PyValueError::new_err(
                    "give `n` (and `k`): a constant index, or `index` (\"library:<id>\" or the \
                     path of a refractiveindex.info YAML file): a spectral one",
                ))
            }
            (Some(source), None, None) => {
                let index = polbrdf_io::library::resolve(source, None).map_err(|e| io_err(&e))?;
                let source = if source.starts_with(polbrdf_io::library::PREFIX) {
                    source.clone()
                } else {
                    std::fs::canonicalize(source)
                        .map_or_else(|_| source.clone(), |p| p.to_string_lossy().into_owned())
                };
                Some(polbrdf::model::SpectralSource {
                    source,
                    index: std::sync::Arc::new(index),
                })
            }
            (None, Some(_), _) => None,
        };
        let spec = MaterialSpec {
            name,
            n: n.unwrap_or(f64::NAN),
            k: k.unwrap_or(0.0),
            sigma_deg,
            b,
            a,
            form: form.map_or(Ok(d.form), parse_form)?,
            shadowing: shadowing.unwrap_or(d.shadowing),
            tau_deg: tau_deg.unwrap_or(d.tau_deg),
            omega_deg: omega_deg.unwrap_or(d.omega_deg),
            azimuth_term: azimuth_term.map_or(Ok(d.azimuth_term), parse_azimuth)?,
            rho_d: rho_d.unwrap_or(d.rho_d),
            rho_v: rho_v.unwrap_or(d.rho_v),
            spectral,
        };
        let material = build(py, &spec)?;
        warn_units(py, &polbrdf_io::material_warnings(&spec, "Material"))?;
        Ok(material)
    }

    /// Load a material file (flat TOML; the keys of the constructor).
    ///
    /// Raises ``ValueError`` whose message starts ``path:line:`` and names the key for malformed
    /// TOML, an unknown key, a wrong type or an invalid value; ``FileNotFoundError`` (or another
    /// ``OSError``) when the file cannot be read.
    #[staticmethod]
    fn from_toml(py: Python<'_>, path: PathBuf) -> PyResult<Self> {
        // polbrdf-io's reader (the CLI's): the same checks and messages. A file named `-` is
        // a file here, not standard input.
        let path = if path.as_os_str() == "-" {
            Path::new(".").join("-")
        } else {
            path
        };
        let spec = polbrdf_io::read_material(&path).map_err(|e| io_err(&e))?;
        let material = build(py, &spec)?;
        warn_units(
            py,
            &polbrdf_io::material_warnings(&spec, &path.display().to_string()),
        )?;
        Ok(material)
    }

    /// Parse the text of a material file (as :meth:`from_toml`, for a string). ``source`` is the
    /// name used in error messages.
    #[staticmethod]
    #[pyo3(signature = (text, source = "<string>"))]
    fn from_toml_str(py: Python<'_>, text: &str, source: &str) -> PyResult<Self> {
        let spec = polbrdf_io::parse_material(text, Path::new(source)).map_err(|e| io_err(&e))?;
        let material = build(py, &spec)?;
        warn_units(py, &polbrdf_io::material_warnings(&spec, source))?;
        Ok(material)
    }

    /// A built-in material by name (``Material.presets()`` lists them). ``ValueError`` for an
    /// unknown name (the message lists the known ones).
    #[staticmethod]
    fn preset(py: Python<'_>, name: &str) -> PyResult<Self> {
        let spec = polbrdf::preset(name).map_err(|e| core_err(py, &e))?;
        build(py, &spec)
    }

    /// Names of the built-in materials, in listing order.
    #[staticmethod]
    fn presets() -> Vec<&'static str> {
        polbrdf::presets::names()
    }

    /// ``{name: description}`` of the built-in materials: what each models and its source.
    #[staticmethod]
    fn preset_descriptions(py: Python<'_>) -> PyResult<Bound<'_, PyDict>> {
        let d = PyDict::new(py);
        for p in polbrdf::presets::all() {
            d.set_item(p.name, p.description)?;
        }
        Ok(d)
    }

    /// The material as a material file (TOML text) that :meth:`from_toml_str` reads back to an
    /// equal material.
    fn to_toml(&self) -> String {
        polbrdf_io::material_to_toml(self.inner.spec())
    }

    /// The material's keys as a dict (``None`` for unset optional keys), suitable for
    /// ``Material(**d)``.
    fn to_dict<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        let s = self.inner.spec();
        let d = PyDict::new(py);
        for key in python_keys() {
            // Exactly the keys that describe the material: `index` or the constant `n`, `k`.
            let omitted = match key {
                "index" => !s.is_spectral(),
                "n" | "k" => s.is_spectral(),
                _ => false,
            };
            if omitted {
                continue;
            }
            match s.get(key) {
                Some(KeyValue::Number(x)) => d.set_item(key, x)?,
                Some(KeyValue::Text(t)) => d.set_item(key, t)?,
                Some(KeyValue::Bool(b)) => d.set_item(key, b)?,
                None => d.set_item(key, py.None())?,
            }
        }
        Ok(d)
    }

    /// Pickle support, every protocol (0 to 5): the material's keys and, for a spectral index,
    /// its data ([`MaterialState`]), rebuilt by `_material_from_state` without reading the file
    /// or library entry the index names.
    fn __reduce__<'py>(&self, py: Python<'py>) -> PyResult<(Bound<'py, PyAny>, (MaterialState,))> {
        let f = py
            .import("polbrdf._polbrdf")?
            .getattr("_material_from_state")?;
        Ok((f, (material_state(self.inner.spec()),)))
    }

    fn __repr__(&self, py: Python<'_>) -> PyResult<String> {
        let s = self.inner.spec();
        let mut parts = Vec::new();
        for key in python_keys() {
            match s.get(key) {
                Some(KeyValue::Number(x)) => parts.push(format!("{key}={}", py_float(x))),
                Some(KeyValue::Text(t)) if key == "name" || key == "index" => {
                    let r = pyo3::types::PyString::new(py, &t).repr()?;
                    parts.push(format!("{key}={r}"));
                }
                Some(KeyValue::Text(t)) => parts.push(format!("{key}='{t}'")),
                Some(KeyValue::Bool(b)) => {
                    parts.push(format!("{key}={}", if b { "True" } else { "False" }))
                }
                None => {}
            }
        }
        Ok(format!("Material({})", parts.join(", ")))
    }

    /// Real part of the refractive index; ``None`` for a spectral index (see
    /// :func:`polbrdf.index`).
    #[getter]
    fn n(&self) -> Option<f64> {
        let s = self.inner.spec();
        (!s.is_spectral()).then_some(s.n)
    }
    /// Extinction coefficient (imaginary part of the refractive index); ``None`` for a
    /// spectral index.
    #[getter]
    fn k(&self) -> Option<f64> {
        let s = self.inner.spec();
        (!s.is_spectral()).then_some(s.k)
    }
    /// Where a spectral index comes from (``"library:<id>"`` or the YAML file's absolute
    /// path), or ``None`` for a constant index.
    #[getter]
    fn index(&self) -> Option<String> {
        self.inner
            .spec()
            .spectral
            .as_ref()
            .map(|s| s.source.clone())
    }
    /// ``(λ_min, λ_max)`` in µm where a spectral index has data, or ``None``.
    #[getter]
    fn wavelength_range(&self) -> Option<(f64, f64)> {
        self.inner.spec().wavelength_range()
    }
    /// The references of a spectral index's source (as the file gives them), or ``None``.
    #[getter]
    fn index_references(&self) -> Option<String> {
        self.inner
            .spec()
            .spectral
            .as_ref()
            .map(|s| s.index.references.clone())
    }
    /// Roughness σ in degrees as given, or ``None`` when ``b`` was given.
    #[getter]
    fn sigma_deg(&self) -> Option<f64> {
        self.inner.spec().sigma_deg
    }
    /// Width ``b`` of D in rad⁻² as given, or ``None`` when ``sigma_deg`` was given (see
    /// ``b_effective``).
    #[getter]
    fn b(&self) -> Option<f64> {
        self.inner.spec().b
    }
    /// Amplitude ``a`` of D in sr⁻¹ as given, or ``None`` for the hemispherical normalization
    /// (see ``a_effective``).
    #[getter]
    fn a(&self) -> Option<f64> {
        self.inner.spec().a
    }
    /// ``"standard"`` or ``"paper"``.
    #[getter]
    fn form(&self) -> &'static str {
        self.inner.spec().form.as_str()
    }
    /// Whether the shadowing/obscuration function (eq. 3) is applied.
    #[getter]
    fn shadowing(&self) -> bool {
        self.inner.spec().shadowing
    }
    /// τ of eq. 3 in degrees.
    #[getter]
    fn tau_deg(&self) -> f64 {
        self.inner.spec().tau_deg
    }
    /// Ω of eq. 3 in degrees.
    #[getter]
    fn omega_deg(&self) -> f64 {
        self.inner.spec().omega_deg
    }
    /// ``"none"`` or ``"eq3"``.
    #[getter]
    fn azimuth_term(&self) -> &'static str {
        self.inner.spec().azimuth_term.as_str()
    }
    /// Lambertian volume constant ρ_D in sr⁻¹.
    #[getter]
    fn rho_d(&self) -> f64 {
        self.inner.spec().rho_d
    }
    /// Non-Lambertian volume constant ρ_V in sr⁻¹.
    #[getter]
    fn rho_v(&self) -> f64 {
        self.inner.spec().rho_v
    }
    /// The label, or ``None``.
    #[getter]
    fn name(&self) -> Option<&str> {
        self.inner.name()
    }
    /// The amplitude ``a`` of D actually used, in sr⁻¹ (the given one or the normalization's).
    #[getter]
    fn a_effective(&self) -> f64 {
        self.inner.distribution().a()
    }
    /// The width ``b`` of D actually used, in rad⁻² (the given one or ``1/σ²``).
    #[getter]
    fn b_effective(&self) -> f64 {
        self.inner.distribution().b()
    }
}
