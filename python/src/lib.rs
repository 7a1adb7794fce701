//! `polbrdf._polbrdf`: the compiled half of the Python package `polbrdf`.
//!
//! The Python half (`python/polbrdf/__init__.py`) broadcasts the user's angles with NumPy and
//! hands this module four contiguous 1-D float64 arrays of equal length. Everything here works
//! on those flat arrays with the GIL released: in parallel chunks (rayon), each chunk converted
//! from degrees on the stack when needed, validated as a core [`GeometryBatch`] and evaluated by
//! the core's batch API ([`polbrdf::batch::mueller_into`], [`polbrdf::batch::brdf_dolp_into`]), writing straight
//! into the NumPy output arrays.
//!
//! Thermal emission takes the same road: Planck's law on flat wavelength/temperature arrays
//! (`planck_flat`, `brightness_temperature_flat`), the emissivity Stokes vector per view
//! zenith and wavelength, batched by distinct wavelength and zenith into the core's
//! `analysis::emission::emissivities` (`emissivity_flat`), and the observed Stokes radiance of
//! a thermal scene through `analysis::scene::observed_radiance` (`radiance_flat`).
//!
//! Errors are Python exceptions: the core's `InvalidAngle` / `InvalidParameter` /
//! `InconsistentParameters` / `UnknownPreset` become `ValueError` with the core's message, file
//! errors of `polbrdf-io` become `ValueError` (content) or an `OSError` subclass (reading).

use numpy::{
    PyArray1, PyArray2, PyArrayMethods, PyReadonlyArray1, PyReadonlyArray2, PyUntypedArrayMethods,
};
use polbrdf::analysis::emission::{emissivities, Emissivity};
use polbrdf::analysis::scene::{observed_radiance, Atmosphere, SkyModel, Sun, ThermalScene};
use polbrdf::analysis::sky::{TableSky, ZenithProfile};
use polbrdf::analysis::thermal;
use polbrdf::engine::batch::{try_for_chunks, Split};
use polbrdf::engine::Planes;
use polbrdf::engine::{Kernel, Precision};
use polbrdf::model::KeyValue;
use polbrdf::Engine;
use polbrdf::{AngleProblem, AzimuthTerm, Band, Form, Material, MaterialSpec, Spectrum};
use polbrdf::{Batch, DirectionBatch, GeometryBatch};
use pyo3::exceptions::{
    PyFileNotFoundError, PyIsADirectoryError, PyOSError, PyPermissionError, PyValueError,
};
use pyo3::prelude::*;
use pyo3::types::{PyDict, PyTuple};
use rayon::prelude::*;
use std::collections::HashMap;
use std::f64::consts::FRAC_PI_2;
use std::path::{Path, PathBuf};

/// Most elements per parallel task: the core's driver (`try_for_chunks`) hands out at most
/// this many.
const CHUNK: usize = polbrdf::engine::batch::CHUNK;

// ---------------------------------------------------------------------------------------------
// Errors

/// A core error as a `ValueError` carrying the core's message. For a bad angle of a batch (and a
/// wavelength of a batch outside a spectral index's data) the exception also gets the
/// attributes `index` (flat position) and `argument` (`theta_i`, …, `wavelength_um`), which the
/// Python layer turns into a position in the broadcast shape.
fn core_err(py: Python<'_>, e: &polbrdf::Error) -> PyErr {
    let err = PyValueError::new_err(e.to_string());
    let located = match e {
        polbrdf::Error::InvalidAngle { name, index, .. } => Some((python_name(name), *index)),
        polbrdf::Error::InvalidDirection { name, index, .. } => Some((*name, *index)),
        polbrdf::Error::WavelengthOutOfRange {
            position: Some(i), ..
        } => Some(("wavelength_um", Some(*i))),
        _ => None,
    };
    if let Some((argument, index)) = located {
        let value = err.value(py);
        // Setting attributes on a fresh ValueError cannot fail; ignore it if it ever does.
        let _ = value.setattr("argument", argument);
        if let Some(i) = index {
            let _ = value.setattr("index", i);
        }
    }
    err
}

/// As [`core_err`] for an error about one element of the flat arrays handed over by the Python
/// layer: a [`polbrdf::Error::InvalidParameterAt`] also gets `argument` and `index` (its
/// position in those arrays). Not for positions in other tables (a band, a sky profile).
fn element_err(py: Python<'_>, e: &polbrdf::Error) -> PyErr {
    let err = core_err(py, e);
    if let polbrdf::Error::InvalidParameterAt { name, index, .. } = e {
        let value = err.value(py);
        let _ = value.setattr("argument", *name);
        let _ = value.setattr("index", *index);
    }
    err
}

/// A `polbrdf-io` error: reading failures become the matching `OSError` subclass, everything
/// else (syntax, unknown key, bad value) a `ValueError`. The message names file and line.
fn io_err(e: &polbrdf_io::Error) -> PyErr {
    let msg = e.to_string();
    match e {
        polbrdf_io::Error::Read { source, .. } | polbrdf_io::Error::Write { source, .. } => {
            os_err(source.kind(), msg)
        }
        _ => PyValueError::new_err(msg),
    }
}

fn os_err(kind: std::io::ErrorKind, msg: String) -> PyErr {
    use std::io::ErrorKind;
    match kind {
        ErrorKind::NotFound => PyFileNotFoundError::new_err(msg),
        ErrorKind::PermissionDenied => PyPermissionError::new_err(msg),
        ErrorKind::IsADirectory => PyIsADirectoryError::new_err(msg),
        _ => PyOSError::new_err(msg),
    }
}

// ---------------------------------------------------------------------------------------------
// Material

/// The material-file keys (the core's list) in the order of the constructor's keyword
/// arguments: `name` last.
fn python_keys() -> impl Iterator<Item = &'static str> {
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
struct PyMaterial {
    inner: Material,
}

fn parse_form(s: &str) -> PyResult<Form> {
    s.parse::<Form>()
        .map_err(|m| PyValueError::new_err(format!("invalid `form`: {m}")))
}

fn parse_azimuth(s: &str) -> PyResult<AzimuthTerm> {
    s.parse::<AzimuthTerm>()
        .map_err(|m| PyValueError::new_err(format!("invalid `azimuth_term`: {m}")))
}

/// Validates a spec into a material; a spectral one is built at the first wavelength of its
/// data (every evaluation then takes its wavelengths from the call).
fn build(py: Python<'_>, spec: &MaterialSpec) -> PyResult<PyMaterial> {
    match spec.wavelength_range() {
        Some((lo, _)) => spec.build_at(lo),
        None => spec.build(),
    }
    .map(|inner| PyMaterial { inner })
    .map_err(|e| core_err(py, &e))
}

/// 1-based line of byte offset `pos` in `bytes`.
fn line_of(bytes: &[u8], pos: usize) -> usize {
    bytes[..pos.min(bytes.len())]
        .iter()
        .filter(|&&b| b == b'\n')
        .count()
        + 1
}

/// Python literal of a float (shortest round-trip form, as `repr(float)` gives).
fn py_float(x: f64) -> String {
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
        n = None, k = None, sigma_deg = None, b = None, a = None, form = "standard",
        shadowing = true, tau_deg = 15.0, omega_deg = 40.0, azimuth_term = "none", rho_d = 0.0,
        rho_v = 0.0, name = None, index = None
    ))]
    #[allow(clippy::too_many_arguments)]
    fn new(
        py: Python<'_>,
        n: Option<f64>,
        k: Option<f64>,
        sigma_deg: Option<f64>,
        b: Option<f64>,
        a: Option<f64>,
        form: &str,
        shadowing: bool,
        tau_deg: f64,
        omega_deg: f64,
        azimuth_term: &str,
        rho_d: f64,
        rho_v: f64,
        name: Option<String>,
        index: Option<String>,
    ) -> PyResult<Self> {
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
            form: parse_form(form)?,
            shadowing,
            tau_deg,
            omega_deg,
            azimuth_term: parse_azimuth(azimuth_term)?,
            rho_d,
            rho_v,
            spectral,
        };
        build(py, &spec)
    }

    /// Load a material file (flat TOML; the keys of the constructor).
    ///
    /// Raises ``ValueError`` whose message starts ``path:line:`` and names the key for malformed
    /// TOML, an unknown key, a wrong type or an invalid value; ``FileNotFoundError`` (or another
    /// ``OSError``) when the file cannot be read.
    #[staticmethod]
    fn from_toml(py: Python<'_>, path: PathBuf) -> PyResult<Self> {
        let bytes = std::fs::read(&path)
            .map_err(|e| os_err(e.kind(), format!("{}: cannot read: {e}", path.display())))?;
        let text = String::from_utf8(bytes).map_err(|e| {
            let line = line_of(e.as_bytes(), e.utf8_error().valid_up_to());
            PyValueError::new_err(format!(
                "{}:{line}: file is not valid UTF-8 text",
                path.display()
            ))
        })?;
        let spec = polbrdf_io::parse_material(&text, &path).map_err(|e| io_err(&e))?;
        build(py, &spec)
    }

    /// Parse the text of a material file (as :meth:`from_toml`, for a string). ``source`` is the
    /// name used in error messages.
    #[staticmethod]
    #[pyo3(signature = (text, source = "<string>"))]
    fn from_toml_str(py: Python<'_>, text: &str, source: &str) -> PyResult<Self> {
        let spec = polbrdf_io::parse_material(text, Path::new(source)).map_err(|e| io_err(&e))?;
        build(py, &spec)
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

    /// Pickle support: rebuilt through the constructor from :meth:`to_dict`.
    fn __getnewargs_ex__<'py>(
        &self,
        py: Python<'py>,
    ) -> PyResult<(Bound<'py, PyTuple>, Bound<'py, PyDict>)> {
        Ok((PyTuple::empty(py), self.to_dict(py)?))
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

// ---------------------------------------------------------------------------------------------
// Evaluation

/// The four angle arrays as slices (contiguous by construction in the Python layer).
fn slices<'a>(arrays: [&'a PyReadonlyArray1<'_, f64>; 4]) -> PyResult<[&'a [f64]; 4]> {
    let mut out: [&[f64]; 4] = [&[]; 4];
    for (o, (a, name)) in out.iter_mut().zip(
        arrays
            .into_iter()
            .zip(["theta_i", "phi_i", "theta_r", "phi_r"]),
    ) {
        *o = a.as_slice().map_err(|e| {
            PyValueError::new_err(format!("`{name}` must be a contiguous 1-D array: {e}"))
        })?;
    }
    Ok(out)
}

/// Runs `f` with the engine for elements `start .. start + len`: the material's own index, or
/// with `wavelengths` (µm, one per element) the material's index at each (a spectral index;
/// a constant one does not depend on it). A spectral material needs the wavelengths.
fn with_engine<T>(
    m: &Material,
    wavelengths: Option<&[f64]>,
    start: usize,
    len: usize,
    f: impl FnOnce(&Engine<'_>) -> Result<T, polbrdf::Error>,
) -> Result<T, polbrdf::Error> {
    let spec = m.spec();
    match wavelengths {
        None if spec.is_spectral() => Err(needs_wavelength(spec)),
        None => f(&Engine::new(m)),
        Some(wl) => {
            // A wavelength outside the data: its position in the whole array.
            let engine = Engine::new(m)
                .with_wavelengths(&wl[start..start + len])
                .map_err(|e| match e {
                    polbrdf::Error::WavelengthOutOfRange {
                        material,
                        wavelength_um,
                        range,
                        position,
                    } => polbrdf::Error::WavelengthOutOfRange {
                        material,
                        wavelength_um,
                        range,
                        position: position.map(|p| p + start),
                    },
                    other => other,
                })?;
            f(&engine)
        }
    }
}

/// The refusal to evaluate a material with a spectral index without wavelengths.
fn needs_wavelength(spec: &MaterialSpec) -> polbrdf::Error {
    let (lo, hi) = spec.wavelength_range().unwrap_or((f64::NAN, f64::NAN));
    polbrdf::Error::InconsistentParameters(format!(
        "the material has a spectral index ({lo}–{hi} µm): give wavelength_um="
    ))
}

/// The wavelength array as a slice of the angles' length.
fn wavelength_slice<'a>(
    wl: &'a Option<PyReadonlyArray1<'_, f64>>,
    n: usize,
) -> PyResult<Option<&'a [f64]>> {
    let Some(a) = wl else { return Ok(None) };
    let s = a.as_slice().map_err(|e| {
        PyValueError::new_err(format!(
            "`wavelength_um` must be a contiguous 1-D array: {e}"
        ))
    })?;
    if s.len() != n {
        return Err(PyValueError::new_err(format!(
            "`wavelength_um` has {} elements, the angles {n}",
            s.len()
        )));
    }
    Ok(Some(s))
}

/// Checks that the four angle arrays are equally long; returns the length.
fn common_len(input: [&[f64]; 4]) -> Result<usize, polbrdf::Error> {
    let n = input[0].len();
    for (s, name) in input[1..].iter().zip(["phi_i", "theta_r", "phi_r"]) {
        if s.len() != n {
            return Err(polbrdf::Error::LengthMismatch {
                name,
                got: s.len(),
                expected: n,
            });
        }
    }
    Ok(n)
}

/// The length of four angle arrays each of which is `n` long or a single value broadcast to
/// every element (the Python layer passes a scalar argument so, not materialized): the
/// wavelengths' length when given (always `n` long), else 0 when one is empty (as numpy
/// broadcasts), else the longest.
fn broadcast_len(input: [&[f64]; 4], wavelengths: Option<usize>) -> Result<usize, polbrdf::Error> {
    let n = match wavelengths {
        Some(n) => n,
        None if input.iter().any(|s| s.is_empty()) => 0,
        None => input.iter().map(|s| s.len()).max().unwrap_or(0),
    };
    for (s, name) in input.iter().zip(["theta_i", "phi_i", "theta_r", "phi_r"]) {
        if s.len() != n && s.len() != 1 {
            return Err(polbrdf::Error::LengthMismatch {
                name,
                got: s.len(),
                expected: n,
            });
        }
    }
    Ok(n)
}

/// Runs `f` on the geometries `start .. start + len` (`len ≤ CHUNK`) as a validated core batch
/// ([`GeometryBatch::new`]) in radians. With `degrees` the chunk is first converted into a
/// buffer on the stack (`f64::to_radians`, as `Geometry::from_degrees` does): the conversion
/// happens in the same pass as the evaluation, with no whole-array temporaries.
///
/// An invalid angle is reported with its index in the whole array and, in degrees mode, with
/// its value in degrees (as `Geometry::from_degrees` reports it); the name stays the Python
/// argument's (`theta_i`, …).
fn chunk_batch<T>(
    input: [&[f64]; 4],
    start: usize,
    len: usize,
    degrees: bool,
    f: impl FnOnce(&GeometryBatch<'_>) -> Result<T, polbrdf::Error>,
) -> Result<T, polbrdf::Error> {
    // A single value (broadcast) stands for every element.
    let part = input.map(|s| {
        if s.len() == 1 {
            s
        } else {
            &s[start..start + len]
        }
    });
    let mut buf = [[0.0f64; CHUNK]; 4];
    let mut rad: [&[f64]; 4] = part;
    for ((b, s), r) in buf.iter_mut().zip(part).zip(rad.iter_mut()) {
        if s.len() == 1 && len != 1 {
            b[..len].fill(if degrees { s[0].to_radians() } else { s[0] });
            *r = &b[..len];
        } else if degrees {
            for (r, d) in b.iter_mut().zip(s) {
                *r = d.to_radians();
            }
            *r = &b[..len];
        }
    }
    let batch = GeometryBatch::new(rad[0], rad[1], rad[2], rad[3]).map_err(|e| match e {
        polbrdf::Error::InvalidAngle { index: Some(i), .. } if degrees => {
            // The element as given, in degrees, as `Geometry::from_degrees` checks it; named
            // by the Python argument.
            let [a, b, c, d] = part.map(|s| s[if s.len() == 1 { 0 } else { i }]);
            match polbrdf::Geometry::from_degrees(a, b, c, d) {
                Err(polbrdf::Error::InvalidAngle {
                    name,
                    value,
                    problem,
                    ..
                }) => polbrdf::Error::InvalidAngle {
                    name: python_name(name),
                    value,
                    degrees: true,
                    index: Some(i + start),
                    problem,
                },
                _ => e,
            }
        }
        polbrdf::Error::InvalidAngle {
            name,
            value,
            degrees,
            index,
            problem,
        } => polbrdf::Error::InvalidAngle {
            name,
            value,
            degrees,
            index: index.map(|i| i + start),
            problem,
        },
        other => other,
    })?;
    f(&batch)
}

/// A new float64 array of `n` zeros, or `MemoryError` when it cannot be allocated (numpy's
/// `zeros`: `PyArray1::zeros` would panic on a null pointer instead, a `BaseException`).
fn zeros1(py: Python<'_>, n: usize) -> PyResult<Bound<'_, PyArray1<f64>>> {
    let a = py.import("numpy")?.call_method1("zeros", ((n,),))?;
    Ok(a.cast_into::<PyArray1<f64>>()?)
}

/// A new `(n, m)` array of zeros of `T`'s dtype, or `MemoryError` ([`zeros1`]).
fn zeros2<T: numpy::Element>(
    py: Python<'_>,
    n: usize,
    m: usize,
) -> PyResult<Bound<'_, PyArray2<T>>> {
    let kwargs = PyDict::new(py);
    kwargs.set_item("dtype", numpy::dtype::<T>(py))?;
    let a = py
        .import("numpy")?
        .call_method("zeros", ((n, m),), Some(&kwargs))?;
    Ok(a.cast_into::<PyArray2<T>>()?)
}

/// `MemoryError` unless `count` values of `T` can be allocated (tried, then freed): for results
/// the core returns as a `Vec`, whose failed allocation would abort the interpreter.
fn can_allocate<T>(count: usize) -> PyResult<()> {
    let fail = || {
        pyo3::exceptions::PyMemoryError::new_err(format!(
            "cannot allocate {count} results of {} bytes",
            size_of::<T>()
        ))
    };
    let bytes = count.checked_mul(size_of::<T>()).ok_or_else(fail)?;
    Vec::<u8>::new()
        .try_reserve_exact(bytes)
        .map_err(|_| fail())
}

/// The Python argument that a core angle name stands for (`theta_i_deg` → `theta_i`).
fn python_name(core: &'static str) -> &'static str {
    ["theta_i", "phi_i", "theta_r", "phi_r"]
        .into_iter()
        .find(|n| core.strip_suffix("_deg") == Some(n) || core == *n)
        .unwrap_or(core)
}

/// Elements `start .. start + len` of `w`, or its single vector `len` times (in `buf`).
fn spread<'a>(
    w: &'a [[f64; 3]],
    start: usize,
    len: usize,
    buf: &'a mut [[f64; 3]; CHUNK],
) -> &'a [[f64; 3]] {
    match w {
        [one] if len > 1 => {
            buf[..len].fill(*one);
            &buf[..len]
        }
        [_] => w,
        _ => &w[start..start + len],
    }
}

/// How a Mueller-matrix array is filled, chunk by chunk, whatever the kind of batch: the
/// serial kernel's `mueller_into` (f64) or `mueller_f32_into` (f32, which reports an entry
/// beyond f32's range).
trait Store<T>: Sync {
    /// Fills `rows` for `batch`; true when an entry overflowed f32.
    fn store(&self, k: &Kernel<'_>, batch: &impl Batch, rows: &mut [[T; 16]]) -> bool;
    /// Fills `planes` for `batch` (the planar layout); as [`Store::store`].
    fn store_planes(&self, k: &Kernel<'_>, batch: &impl Batch, planes: &mut Planes<'_, T>) -> bool;
}

/// Where a Python pBRDF call writes: one row-major 4×4 per geometry (an `(n, 16)` array), or
/// 16 planes (a `(16, n)` array, `layout="planar"`). (The planes' 16 slices make that variant
/// 256 bytes; a target is made once per chunk, so its size does not matter.)
#[allow(clippy::large_enum_variant)]
enum Target<'a, T> {
    Rows(&'a mut [[T; 16]]),
    Planes(Planes<'a, T>),
}

impl<T: Send> Split for Target<'_, T> {
    fn len(&self) -> usize {
        match self {
            Target::Rows(r) => r.len(),
            Target::Planes(p) => p.len(),
        }
    }
    fn split_at(self, mid: usize) -> (Self, Self) {
        match self {
            Target::Rows(r) => {
                let (a, b) = r.split_at_mut(mid);
                (Target::Rows(a), Target::Rows(b))
            }
            Target::Planes(p) => {
                let (a, b) = p.split_at(mid);
                (Target::Planes(a), Target::Planes(b))
            }
        }
    }
}

impl<T> Target<'_, T> {
    /// Fills the target through `store`; as [`Store::store`].
    fn store(self, store: &impl Store<T>, k: &Kernel<'_>, batch: &impl Batch) -> bool {
        match self {
            Target::Rows(r) => store.store(k, batch, r),
            Target::Planes(mut p) => store.store_planes(k, batch, &mut p),
        }
    }
}

/// [`Store`] in float64; `stream`: with non-temporal stores, as the engine writes an output of
/// the whole array's length (`Engine::streams`).
struct StoreF64 {
    stream: bool,
}

impl StoreF64 {
    fn new(m: &Material, n: usize) -> Self {
        Self {
            stream: Engine::new(m).streams(n),
        }
    }
}

impl Store<f64> for StoreF64 {
    fn store(&self, k: &Kernel<'_>, batch: &impl Batch, rows: &mut [[f64; 16]]) -> bool {
        if self.stream {
            k.clone().streaming(true).mueller_into(batch, 0, rows);
        } else {
            k.mueller_into(batch, 0, rows);
        }
        false
    }
    fn store_planes(&self, k: &Kernel<'_>, b: &impl Batch, planes: &mut Planes<'_, f64>) -> bool {
        k.mueller_planes_into(b, 0, planes);
        false
    }
}

/// [`Store`] in float32; `stream` as [`StoreF64`] (non-temporal stores only where they pay on
/// this CPU: `Kernel::streaming`).
struct StoreF32 {
    stream: bool,
}

impl StoreF32 {
    fn new(m: &Material, n: usize) -> Self {
        Self {
            stream: Engine::new(m).streams(n),
        }
    }
}

impl Store<f32> for StoreF32 {
    fn store(&self, k: &Kernel<'_>, batch: &impl Batch, rows: &mut [[f32; 16]]) -> bool {
        if self.stream {
            k.clone().streaming(true).mueller_f32_into(batch, 0, rows)
        } else {
            k.mueller_f32_into(batch, 0, rows)
        }
    }
    fn store_planes(&self, k: &Kernel<'_>, b: &impl Batch, planes: &mut Planes<'_, f32>) -> bool {
        k.mueller_planes_f32_into(b, 0, planes)
    }
}

/// Fills `rows` (one row-major 4×4 per geometry) through the core's parallel driver
/// (`try_for_chunks`: parts of at most [`CHUNK`], a small batch on the calling thread):
/// `chunk(start, rows)` evaluates the part at `start` through the serial kernel (true when an
/// entry overflowed f32), with the stores the batch API would use (`StoreF64`).
fn mueller_chunks<T: Send>(
    rows: Target<'_, T>,
    chunk: impl Fn(usize, Target<'_, T>) -> Result<bool, polbrdf::Error> + Sync,
) -> Result<(), polbrdf::Error> {
    let overflow = try_for_chunks(rows, chunk)?;
    if overflow {
        return Err(polbrdf::engine::batch::f32_overflow());
    }
    Ok(())
}

/// The pBRDF of the geometries `input` (angles) into `rows` ([`mueller_chunks`]).
fn mueller_rows<T: Send>(
    m: &Material,
    input: [&[f64]; 4],
    wl: Option<&[f64]>,
    degrees: bool,
    rows: Target<'_, T>,
    store: &impl Store<T>,
) -> Result<(), polbrdf::Error> {
    mueller_chunks(rows, |start, rows| {
        let len = rows.len();
        chunk_batch(input, start, len, degrees, |b| {
            with_engine(m, wl, start, len, |e| Ok(rows.store(store, e.kernel(), b)))
        })
    })
}

/// The pBRDF of the direction vectors `w_i`, `w_r` (equally long, or one of them a single
/// vector standing for all) into `rows` ([`mueller_chunks`]); a bad vector is named by its
/// index in the whole array.
fn direction_rows<T: Send>(
    m: &Material,
    [w_i, w_r]: [&[[f64; 3]]; 2],
    wl: Option<&[f64]>,
    rows: Target<'_, T>,
    store: &impl Store<T>,
) -> Result<(), polbrdf::Error> {
    mueller_chunks(rows, |start, rows| {
        let len = rows.len();
        let (mut bi, mut br) = ([[0.0f64; 3]; CHUNK], [[0.0f64; 3]; CHUNK]);
        let (si, sr) = (
            spread(w_i, start, len, &mut bi),
            spread(w_r, start, len, &mut br),
        );
        let batch = DirectionBatch::new(si, sr).map_err(|e| match e {
            polbrdf::Error::InvalidDirection { name, value, index } => {
                polbrdf::Error::InvalidDirection {
                    name,
                    value,
                    index: index.map(|i| i + start),
                }
            }
            other => other,
        })?;
        with_engine(m, wl, start, len, |e| {
            Ok(rows.store(store, e.kernel(), &batch))
        })
    })
}

/// A caller's output array for `n` pBRDFs: an `(n, 16)` (or, planar, `(16, n)`) C-contiguous,
/// writeable array of the precision's dtype (the Python layer checks the user's array and
/// passes this view of it).
fn out_rows<'py, T: numpy::Element>(
    out: &Bound<'py, PyAny>,
    shape: [usize; 2],
    dtype: &str,
) -> PyResult<Bound<'py, PyArray2<T>>> {
    let [a0, a1] = shape;
    let a = out.cast::<PyArray2<T>>().map_err(|_| {
        PyValueError::new_err(format!(
            "`out` must be a 2-D {dtype} array of shape ({a0}, {a1})"
        ))
    })?;
    if a.shape() != shape || !a.is_c_contiguous() {
        return Err(PyValueError::new_err(format!(
            "`out` must be a C-contiguous {dtype} array of shape ({a0}, {a1}), got shape {:?}",
            a.shape()
        )));
    }
    Ok(a.clone())
}

/// The pBRDF `F` (sr⁻¹, psps basis) at `n` geometries as an `(n, 16)` array, row-major 4×4 per
/// geometry, in `precision` (`"float64"`, or `"float32"`: computed in single precision within
/// the float32 contract, `1e-5·F00 + 1e-6·P + 2⁻¹⁵⁰` of float64, docs/model.md §12), written
/// into `out` when given (an `(n, 16)` C-contiguous array of that dtype, which is returned).
/// The Python layer reshapes it to `shape + (4, 4)`. With `planar`, a `(16, n)` array of 16 planes instead
/// (`Planes`), which the Python layer reshapes to `(4, 4) + shape`.
#[pyfunction]
#[pyo3(signature = (material, theta_i, phi_i, theta_r, phi_r, degrees, wavelength_um=None, out=None, precision="float64", planar=false))]
#[allow(clippy::too_many_arguments)]
fn mueller_flat<'py>(
    py: Python<'py>,
    material: &PyMaterial,
    theta_i: PyReadonlyArray1<'py, f64>,
    phi_i: PyReadonlyArray1<'py, f64>,
    theta_r: PyReadonlyArray1<'py, f64>,
    phi_r: PyReadonlyArray1<'py, f64>,
    degrees: bool,
    wavelength_um: Option<PyReadonlyArray1<'py, f64>>,
    out: Option<Bound<'py, PyAny>>,
    precision: &str,
    planar: bool,
) -> PyResult<Bound<'py, PyAny>> {
    let precision: Precision = precision.parse().map_err(|e| core_err(py, &e))?;
    let input = slices([&theta_i, &phi_i, &theta_r, &phi_r])?;
    let n = broadcast_len(input, wavelength_um.as_ref().map(|w| w.len()))
        .map_err(|e| core_err(py, &e))?;
    let wl = wavelength_slice(&wavelength_um, n)?;
    let m = &material.inner;
    match precision {
        Precision::F64 => mueller_array::<f64>(py, out, n, "float64", planar, |rows| {
            mueller_rows(m, input, wl, degrees, rows, &StoreF64::new(m, n))
        }),
        Precision::F32 => mueller_array::<f32>(py, out, n, "float32", planar, |rows| {
            mueller_rows(m, input, wl, degrees, rows, &StoreF32::new(m, n))
        }),
    }
}

/// The vectors of an `(n, 3)` C-contiguous float64 array.
fn vectors<'a>(a: &'a PyReadonlyArray2<'_, f64>, name: &str) -> PyResult<&'a [[f64; 3]]> {
    let flat = a
        .as_slice()
        .ok()
        .filter(|_| a.shape()[1] == 3)
        .ok_or_else(|| {
            PyValueError::new_err(format!(
                "`{name}` must be a C-contiguous (n, 3) array of vectors, got shape {:?}",
                a.shape()
            ))
        })?;
    Ok(flat.as_chunks::<3>().0)
}

/// The pBRDF at direction vectors (the direction entry point, docs/model.md §9.11): `w_i`,
/// `w_r` as `(n, 3)` C-contiguous float64 arrays (or `(1, 3)`, standing for every element),
/// each vector in the surface frame, of any length within 1e-15..1e15; otherwise as
/// [`mueller_flat`].
#[pyfunction]
#[pyo3(signature = (material, w_i, w_r, wavelength_um=None, out=None, precision="float64", planar=false))]
#[allow(clippy::too_many_arguments)]
fn mueller_directions_flat<'py>(
    py: Python<'py>,
    material: &PyMaterial,
    w_i: PyReadonlyArray2<'py, f64>,
    w_r: PyReadonlyArray2<'py, f64>,
    wavelength_um: Option<PyReadonlyArray1<'py, f64>>,
    out: Option<Bound<'py, PyAny>>,
    precision: &str,
    planar: bool,
) -> PyResult<Bound<'py, PyAny>> {
    let precision: Precision = precision.parse().map_err(|e| core_err(py, &e))?;
    let (wi, wr) = (vectors(&w_i, "w_i")?, vectors(&w_r, "w_r")?);
    let lens = [wi.len(), wr.len()];
    let n = match wavelength_um.as_ref() {
        Some(w) => w.len(),
        None if lens.contains(&0) => 0,
        None => lens[0].max(lens[1]),
    };
    for (len, name) in lens.into_iter().zip(["w_i", "w_r"]) {
        if len != n && len != 1 {
            let e = polbrdf::Error::LengthMismatch {
                name,
                got: len,
                expected: n,
            };
            return Err(core_err(py, &e));
        }
    }
    let wl = wavelength_slice(&wavelength_um, n)?;
    let m = &material.inner;
    match precision {
        Precision::F64 => mueller_array::<f64>(py, out, n, "float64", planar, |rows| {
            direction_rows(m, [wi, wr], wl, rows, &StoreF64::new(m, n))
        }),
        Precision::F32 => mueller_array::<f32>(py, out, n, "float32", planar, |rows| {
            direction_rows(m, [wi, wr], wl, rows, &StoreF32::new(m, n))
        }),
    }
}

/// [`mueller_flat`] in the element type `T` (numpy's `dtype`): `out` (checked by [`out_rows`])
/// or a new `(n, 16)` array — `(16, n)` when `planar` — filled by `fill` ([`mueller_rows`],
/// [`direction_rows`]) with the GIL released.
#[allow(clippy::too_many_arguments)]
fn mueller_array<'py, T: numpy::Element + Send>(
    py: Python<'py>,
    out: Option<Bound<'py, PyAny>>,
    n: usize,
    dtype: &str,
    planar: bool,
    fill: impl FnOnce(Target<'_, T>) -> Result<(), polbrdf::Error> + Send,
) -> PyResult<Bound<'py, PyAny>> {
    let shape = if planar { [16, n] } else { [n, 16] };
    let arr = match &out {
        Some(o) => out_rows::<T>(o, shape, dtype)?,
        None => zeros2::<T>(py, shape[0], shape[1])?,
    };
    let mut rw = arr.try_readwrite().map_err(|e| {
        PyValueError::new_err(format!("`out` must be writeable and not in use: {e}"))
    })?;
    let flat = rw.as_slice_mut().expect("checked C-contiguous");
    let target = if planar {
        Target::Planes(Planes::new(flat, n).map_err(|e| core_err(py, &e))?)
    } else {
        Target::Rows(flat.as_chunks_mut::<16>().0)
    };
    py.detach(|| fill(target)).map_err(|e| core_err(py, &e))?;
    drop(rw);
    Ok(arr.into_any())
}

/// The scalar BRDF `f` (sr⁻¹) and the DoLP for unpolarized input at `n` geometries, as two
/// float64 arrays of length `n`.
#[pyfunction]
#[pyo3(signature = (material, theta_i, phi_i, theta_r, phi_r, degrees, wavelength_um=None))]
#[allow(clippy::type_complexity, clippy::too_many_arguments)]
fn brdf_dolp_flat<'py>(
    py: Python<'py>,
    material: &PyMaterial,
    theta_i: PyReadonlyArray1<'py, f64>,
    phi_i: PyReadonlyArray1<'py, f64>,
    theta_r: PyReadonlyArray1<'py, f64>,
    phi_r: PyReadonlyArray1<'py, f64>,
    degrees: bool,
    wavelength_um: Option<PyReadonlyArray1<'py, f64>>,
) -> PyResult<ArrayPair<'py>> {
    let input = slices([&theta_i, &phi_i, &theta_r, &phi_r])?;
    let n = broadcast_len(input, wavelength_um.as_ref().map(|w| w.len()))
        .map_err(|e| core_err(py, &e))?;
    let wl = wavelength_slice(&wavelength_um, n)?;
    let brdf = zeros1(py, n)?;
    let dolp = zeros1(py, n)?;
    {
        let (mut bw, mut dw) = (brdf.readwrite(), dolp.readwrite());
        let b = bw.as_slice_mut().expect("a new array is contiguous");
        let d = dw.as_slice_mut().expect("a new array is contiguous");
        let m = &material.inner;
        py.detach(|| {
            try_for_chunks((b, d), |start, (b, d)| {
                chunk_batch(input, start, b.len(), degrees, |g| {
                    with_engine(m, wl, start, b.len(), |e| e.brdf_dolp_into(g, b, d))
                })
                .map(|()| false)
            })
        })
        .map_err(|e| core_err(py, &e))?;
    }
    Ok((brdf, dolp))
}

type Evaluated<'py> = (
    Bound<'py, PyArray1<f64>>,
    Bound<'py, PyArray1<f64>>,
    Bound<'py, PyArray1<f64>>,
    Option<Bound<'py, PyArray2<f64>>>,
);

/// BRDF (sr⁻¹), DoLP and AoLP (of `F·(1,0,0,0)`; degrees when `degrees`, else radians) at `n`
/// geometries, plus the `(n, 16)` pBRDF when `with_mueller`; one pass over the geometries.
#[pyfunction]
#[pyo3(signature = (material, theta_i, phi_i, theta_r, phi_r, degrees, with_mueller, wavelength_um=None))]
#[allow(clippy::too_many_arguments)]
fn evaluate_flat<'py>(
    py: Python<'py>,
    material: &PyMaterial,
    theta_i: PyReadonlyArray1<'py, f64>,
    phi_i: PyReadonlyArray1<'py, f64>,
    theta_r: PyReadonlyArray1<'py, f64>,
    phi_r: PyReadonlyArray1<'py, f64>,
    degrees: bool,
    with_mueller: bool,
    wavelength_um: Option<PyReadonlyArray1<'py, f64>>,
) -> PyResult<Evaluated<'py>> {
    let input = slices([&theta_i, &phi_i, &theta_r, &phi_r])?;
    let n = broadcast_len(input, wavelength_um.as_ref().map(|w| w.len()))
        .map_err(|e| core_err(py, &e))?;
    let wl = wavelength_slice(&wavelength_um, n)?;
    let brdf = zeros1(py, n)?;
    let dolp = zeros1(py, n)?;
    let aolp = zeros1(py, n)?;
    let mueller = with_mueller.then(|| zeros2(py, n, 16)).transpose()?;
    {
        let (mut bw, mut dw, mut aw) = (brdf.readwrite(), dolp.readwrite(), aolp.readwrite());
        let mut mw = mueller.as_ref().map(|m| m.readwrite());
        let b = bw.as_slice_mut().expect("a new array is contiguous");
        let d = dw.as_slice_mut().expect("a new array is contiguous");
        let a = aw.as_slice_mut().expect("a new array is contiguous");
        let f = mw
            .as_mut()
            .map(|m| m.as_slice_mut().expect("a new array is contiguous"));
        let m = &material.inner;
        // BRDF, DoLP and AoLP (the core's `Stokes::dolp`/`Stokes::aolp` of F·(1, 0, 0, 0)) from
        // the kernel's BRDF+DoLP+AoLP path, so that they are bitwise those of `brdf`/`dolp`.
        let scalars =
            |start: usize, g: &GeometryBatch<'_>, b: &mut [f64], d: &mut [f64], a: &mut [f64]| {
                with_engine(m, wl, start, b.len(), |e| e.brdf_dolp_aolp_into(g, b, d, a))?;
                if degrees {
                    a.iter_mut().for_each(|x| *x = x.to_degrees());
                }
                Ok(())
            };
        py.detach(|| match f {
            Some(f) => {
                let (rows, _) = f.as_chunks_mut::<16>();
                try_for_chunks((((b, d), a), rows), |start, (((b, d), a), rows)| {
                    chunk_batch(input, start, b.len(), degrees, |g| {
                        with_engine(m, wl, start, b.len(), |e| e.mueller_into(g, rows))?;
                        scalars(start, g, b, d, a)
                    })
                    .map(|()| false)
                })
            }
            None => try_for_chunks(((b, d), a), |start, ((b, d), a)| {
                chunk_batch(input, start, b.len(), degrees, |g| {
                    scalars(start, g, b, d, a)
                })
                .map(|()| false)
            }),
        })
        .map_err(|e| core_err(py, &e))?;
    }
    Ok((brdf, dolp, aolp, mueller))
}

/// Two float64 arrays.
type ArrayPair<'py> = (Bound<'py, PyArray1<f64>>, Bound<'py, PyArray1<f64>>);

/// The complex index `n + ik` of a material at each wavelength (µm), as two float64 arrays:
/// the spectral index there, or the constant one.
#[pyfunction]
#[pyo3(signature = (material, wavelength_um))]
fn index_flat<'py>(
    py: Python<'py>,
    material: &PyMaterial,
    wavelength_um: PyReadonlyArray1<'py, f64>,
) -> PyResult<ArrayPair<'py>> {
    let wl = wavelength_um.as_slice().map_err(|e| {
        PyValueError::new_err(format!(
            "`wavelength_um` must be a contiguous 1-D array: {e}"
        ))
    })?;
    let spec = material.inner.spec();
    let (n, k) = py.detach(|| spec.index_columns(wl)).map_err(|(i, e)| {
        PyValueError::new_err(format!("wavelength_um = {} (at index {i}): {e}", wl[i]))
    })?;
    Ok((PyArray1::from_vec(py, n), PyArray1::from_vec(py, k)))
}

/// The central-difference step of the fit's Jacobian for parameter `name` at value `value`
/// (`polbrdf_fit::Param::derivative_step`): the uncertainty propagation of `polbrdf.xarray`
/// differentiates with the same steps as the fit that produced the covariance.
#[pyfunction]
fn derivative_step(name: &str, value: f64) -> PyResult<f64> {
    let p = polbrdf_fit::Param::parse(name).map_err(|e| PyValueError::new_err(e.to_string()))?;
    Ok(p.derivative_step(value))
}

// ---------------------------------------------------------------------------------------------
// Thermal emission and the observed radiance

/// A flat argument as a slice (contiguous by construction in the Python layer).
fn flat<'a>(a: &'a PyReadonlyArray1<'_, f64>, name: &str) -> PyResult<&'a [f64]> {
    a.as_slice()
        .map_err(|e| PyValueError::new_err(format!("`{name}` must be a contiguous 1-D array: {e}")))
}

/// Two flat arguments of equal length.
fn flat_pair<'a>(
    a: &'a PyReadonlyArray1<'_, f64>,
    b: &'a PyReadonlyArray1<'_, f64>,
    names: [&'static str; 2],
) -> PyResult<(&'a [f64], &'a [f64])> {
    let (x, y) = (flat(a, names[0])?, flat(b, names[1])?);
    if x.len() != y.len() {
        return Err(PyValueError::new_err(format!(
            "`{}` has {} elements, `{}` {}",
            names[1],
            y.len(),
            names[0],
            x.len()
        )));
    }
    Ok((x, y))
}

/// Checks that `value` (element `index` of the argument `name`) is finite and > 0, with the
/// core's wording.
fn positive_at(name: &'static str, value: f64, index: usize) -> Result<f64, polbrdf::Error> {
    if value.is_finite() && value > 0.0 {
        Ok(value)
    } else {
        Err(polbrdf::Error::InvalidParameterAt {
            name,
            value,
            index,
            reason: "must be finite and > 0",
        })
    }
}

/// A core [`polbrdf::Error::InvalidParameter`] about element `index` of a flat argument.
fn at_index(e: polbrdf::Error, index: usize) -> polbrdf::Error {
    e.at_position(Some(index))
}

/// A view zenith angle (element `index` of the argument `name`, in degrees when `degrees`) in
/// radians, checked to lie in `[0, π/2)` as the emissivity needs (`-0` becomes `+0`).
fn view_zenith(
    name: &'static str,
    value: f64,
    degrees: bool,
    index: usize,
) -> Result<f64, polbrdf::Error> {
    let rad = if degrees { value.to_radians() } else { value };
    if rad.is_finite() && (0.0..FRAC_PI_2).contains(&rad) {
        Ok(rad + 0.0)
    } else {
        Err(polbrdf::Error::InvalidAngle {
            name,
            value,
            degrees,
            index: Some(index),
            problem: if value.is_finite() {
                AngleProblem::ViewBelowHorizon
            } else {
                AngleProblem::NotFinite
            },
        })
    }
}

/// A view azimuth angle in radians, checked to be finite.
fn view_azimuth(value: f64, degrees: bool, index: usize) -> Result<f64, polbrdf::Error> {
    let rad = if degrees { value.to_radians() } else { value };
    if rad.is_finite() {
        Ok(rad)
    } else {
        Err(polbrdf::Error::InvalidAngle {
            name: "phi_r",
            value,
            degrees,
            index: Some(index),
            problem: AngleProblem::NotFinite,
        })
    }
}

/// Planck's law `B_λ(λ, T)` (W·m⁻²·sr⁻¹·µm⁻¹) at `n` pairs of a wavelength (µm) and a
/// temperature (K), through the core's `planck_checked`.
#[pyfunction]
fn planck_flat<'py>(
    py: Python<'py>,
    wavelength_um: PyReadonlyArray1<'py, f64>,
    temperature_k: PyReadonlyArray1<'py, f64>,
) -> PyResult<Bound<'py, PyArray1<f64>>> {
    let (l, t) = flat_pair(
        &wavelength_um,
        &temperature_k,
        ["wavelength_um", "temperature_k"],
    )?;
    let out = zeros1(py, l.len())?;
    {
        let mut w = out.readwrite();
        let o = w.as_slice_mut().expect("a new array is contiguous");
        let valid = py.detach(|| {
            o.par_chunks_mut(CHUNK).enumerate().all(|(c, o)| {
                let start = c * CHUNK;
                o.iter_mut().enumerate().all(|(j, o)| {
                    match thermal::planck_checked(l[start + j], t[start + j]) {
                        Ok(b) => {
                            *o = b;
                            true
                        }
                        Err(_) => false,
                    }
                })
            })
        });
        if !valid {
            // The first bad element, found again in order (the parallel pass may stop at any).
            for (i, (&l, &t)) in l.iter().zip(t).enumerate() {
                if let Err(e) = thermal::planck_checked(l, t) {
                    return Err(element_err(py, &at_index(e, i)));
                }
            }
        }
    }
    Ok(out)
}

/// The brightness temperature (K) of `n` spectral radiances (W·m⁻²·sr⁻¹·µm⁻¹) at wavelengths
/// (µm), through the core's `brightness_temperature`.
#[pyfunction]
fn brightness_temperature_flat<'py>(
    py: Python<'py>,
    wavelength_um: PyReadonlyArray1<'py, f64>,
    radiance: PyReadonlyArray1<'py, f64>,
) -> PyResult<Bound<'py, PyArray1<f64>>> {
    let (l, r) = flat_pair(&wavelength_um, &radiance, ["wavelength_um", "radiance"])?;
    for (i, (&l, &r)) in l.iter().zip(r).enumerate() {
        positive_at("wavelength_um", l, i)
            .and_then(|_| positive_at("radiance", r, i))
            .map_err(|e| element_err(py, &e))?;
    }
    let out = zeros1(py, l.len())?;
    {
        let mut w = out.readwrite();
        let o = w.as_slice_mut().expect("a new array is contiguous");
        py.detach(|| {
            o.par_chunks_mut(CHUNK).enumerate().for_each(|(c, o)| {
                let start = c * CHUNK;
                for (j, o) in o.iter_mut().enumerate() {
                    *o = thermal::brightness_temperature(l[start + j], r[start + j]);
                }
            })
        });
    }
    Ok(out)
}

/// The emissivity of `m` toward every view zenith of `theta_r`, each at its wavelength:
/// validated in order, then one core `emissivities` call per distinct wavelength (one in all
/// for a constant index) with the distinct zenith angles of that wavelength.
fn emissivity_batch(
    m: &Material,
    theta_r: &[f64],
    degrees: bool,
    wavelengths: Option<&[f64]>,
) -> Result<Vec<Emissivity>, polbrdf::Error> {
    let n = theta_r.len();
    let rad = theta_r
        .iter()
        .enumerate()
        .map(|(i, &t)| view_zenith("theta_r", t, degrees, i))
        .collect::<Result<Vec<f64>, _>>()?;
    let spec = m.spec();
    // The material of each element: one per distinct wavelength of a spectral index.
    let mut materials: Vec<Material> = Vec::new();
    let mut group = vec![0usize; n];
    match wavelengths {
        None if spec.is_spectral() => return Err(needs_wavelength(spec)),
        Some(wl) if spec.is_spectral() => {
            let mut seen: HashMap<u64, usize> = HashMap::new();
            for (i, &l) in wl.iter().enumerate() {
                positive_at("wavelength_um", l, i)?;
                group[i] = match seen.get(&l.to_bits()) {
                    Some(&g) => g,
                    None => {
                        materials.push(m.at_wavelength(l).map_err(|e| at_index(e, i))?);
                        seen.insert(l.to_bits(), materials.len() - 1);
                        materials.len() - 1
                    }
                };
            }
        }
        Some(wl) => {
            // A constant index does not depend on λ: one evaluation for every wavelength.
            for (i, &l) in wl.iter().enumerate() {
                positive_at("wavelength_um", l, i)?;
            }
            materials.push(m.clone());
        }
        None => materials.push(m.clone()),
    }
    // The distinct zenith angles of each material, in first-seen order.
    let mut seen: Vec<HashMap<u64, usize>> = vec![HashMap::new(); materials.len()];
    let mut zeniths: Vec<Vec<f64>> = vec![Vec::new(); materials.len()];
    let slot: Vec<usize> = rad
        .iter()
        .zip(&group)
        .map(|(&t, &g)| {
            *seen[g].entry(t.to_bits()).or_insert_with(|| {
                zeniths[g].push(t);
                zeniths[g].len() - 1
            })
        })
        .collect();
    let results: Vec<Vec<Emissivity>> = materials
        .par_iter()
        .zip(zeniths.par_iter())
        .map(|(m, z)| emissivities(m, z))
        .collect::<Result<_, _>>()?;
    Ok(group
        .iter()
        .zip(&slot)
        .map(|(&g, &j)| results[g][j])
        .collect())
}

/// The arrays of [`emissivity_flat`].
type Emitted<'py> = (
    Bound<'py, PyArray2<f64>>,
    Bound<'py, PyArray2<f64>>,
    Bound<'py, PyArray1<f64>>,
    Bound<'py, PyArray1<f64>>,
    Bound<'py, PyArray1<f64>>,
    Bound<'py, PyArray1<f64>>,
    Bound<'py, PyArray1<bool>>,
);

/// `n` Stokes vectors as an `(n, 4)` float64 array.
fn stokes_array<'py>(
    py: Python<'py>,
    s: impl Iterator<Item = polbrdf::Stokes>,
    n: usize,
) -> PyResult<Bound<'py, PyArray2<f64>>> {
    let v: Vec<f64> = s.flat_map(|s| s.0).collect();
    PyArray1::from_vec(py, v).reshape([n, 4])
}

/// The emissivity (Kirchhoff's law, the core's `analysis::emission::emissivities`) toward `n`
/// view zenith angles `theta_r` (degrees when `degrees`, else radians; in `[0°, 90°)`), each at
/// its wavelength (µm; required for a spectral index): `(eps (n, 4), eps_b (n, 4), eps_s,
/// eps_p, dolp, reciprocity_residual, valid)`.
#[pyfunction]
#[pyo3(signature = (material, theta_r, degrees, wavelength_um=None))]
fn emissivity_flat<'py>(
    py: Python<'py>,
    material: &PyMaterial,
    theta_r: PyReadonlyArray1<'py, f64>,
    degrees: bool,
    wavelength_um: Option<PyReadonlyArray1<'py, f64>>,
) -> PyResult<Emitted<'py>> {
    let t = flat(&theta_r, "theta_r")?;
    let n = t.len();
    let wl = wavelength_slice(&wavelength_um, n)?;
    // The results and their 14 output columns: MemoryError now rather than an abort later.
    can_allocate::<Emissivity>(n)?;
    can_allocate::<f64>(n.saturating_mul(14))?;
    let m = &material.inner;
    let e = py
        .detach(|| emissivity_batch(m, t, degrees, wl))
        .map_err(|e| element_err(py, &e))?;
    let column = |f: fn(&Emissivity) -> f64| PyArray1::from_vec(py, e.iter().map(f).collect());
    Ok((
        stokes_array(py, e.iter().map(|e| e.eps), n)?,
        stokes_array(py, e.iter().map(|e| e.eps_b), n)?,
        column(Emissivity::eps_s),
        column(Emissivity::eps_p),
        column(Emissivity::dolp),
        column(Emissivity::reciprocity_residual),
        PyArray1::from_vec(py, e.iter().map(Emissivity::is_valid).collect()),
    ))
}

/// Most quadrature pieces a band may be split into (`band_step_um` against the band's width):
/// every spectral node costs an emissivity quadrature, and a vanishing step would not end.
const MAX_BAND_PIECES: f64 = 1e5;

/// The spectrum of [`radiance_flat`]: one wavelength or a band, exactly one.
fn radiance_spectrum(
    wavelength_um: Option<f64>,
    band: Option<(Vec<f64>, Vec<f64>)>,
    band_step_um: Option<f64>,
) -> PyResult<Spectrum> {
    match (wavelength_um, band) {
        (Some(_), Some(_)) => Err(PyValueError::new_err(
            "give either `wavelength_um` (one wavelength, µm) or `band` = (wavelengths_um, \
             response), not both",
        )),
        (None, None) => Err(PyValueError::new_err(
            "give `wavelength_um` (one wavelength, µm) or `band` = (wavelengths_um, response): \
             the radiance is spectral",
        )),
        (Some(_), None) if band_step_um.is_some() => Err(PyValueError::new_err(
            "`band_step_um` is the quadrature step of a band: give `band`, not `wavelength_um`",
        )),
        (Some(l), None) => Ok(Spectrum::Wavelength(l)),
        (None, Some((w, r))) => {
            let band = Band::new("band", w, r).map_err(|e| {
                let msg = e.to_string();
                PyValueError::new_err(if msg.starts_with("band `band`") {
                    msg
                } else {
                    format!("`band`: {msg}")
                })
            })?;
            if let Some(s) = band_step_um {
                let (lo, hi) = band.range();
                if !(s.is_finite() && s > 0.0) {
                    return Err(PyValueError::new_err(
                        polbrdf::Error::InvalidParameter {
                            name: "band_step_um",
                            value: s,
                            reason: "must be finite and > 0 (µm)",
                        }
                        .to_string(),
                    ));
                }
                if (hi - lo) / s > MAX_BAND_PIECES {
                    return Err(PyValueError::new_err(format!(
                        "invalid parameter `band_step_um` = {s:e}: it would split the band \
                         ({lo}–{hi} µm) into more than {MAX_BAND_PIECES} pieces"
                    )));
                }
            }
            Ok(Spectrum::Band(band, band_step_um))
        }
    }
}

/// The default δ_max of the `cie-clear` sky (the Python signature's `dop_max=0.75`).
const DEFAULT_DOP_MAX: f64 = 0.75;

/// The sky arguments of [`radiance_flat`], as handed over by the Python layer.
struct SkyArgs<'py> {
    radiance: Option<f64>,
    temperature_k: Option<f64>,
    profile: Table<'py>,
    irradiance: Option<f64>,
    dop_max: f64,
    table: SkyTable<'py>,
}

/// A sky table as handed over by the Python layer: zenith angles and azimuths (degrees, 1-D)
/// and the Stokes radiances of the nodes, θ-major, shape `(len(theta_deg)·len(phi_deg), 4)`.
type SkyTable<'py> = Option<(
    PyReadonlyArray1<'py, f64>,
    PyReadonlyArray1<'py, f64>,
    PyReadonlyArray2<'py, f64>,
)>;

/// The sky of [`radiance_flat`] from its model name and the arguments that model takes
/// (`has_sun`: whether a sun was given, which the `cie-clear` sky needs).
fn radiance_sky(sky: &str, args: SkyArgs<'_>, has_sun: bool) -> PyResult<SkyModel> {
    let given = [
        ("sky_radiance", args.radiance.is_some()),
        ("sky_temperature_k", args.temperature_k.is_some()),
        ("sky_profile", args.profile.is_some()),
        ("sky_irradiance", args.irradiance.is_some()),
        // A default value cannot be told from no value: only another one "is given".
        (
            "dop_max",
            args.dop_max.to_bits() != DEFAULT_DOP_MAX.to_bits(),
        ),
        ("sky_table", args.table.is_some()),
    ];
    // The arguments the model needs, those it may take, and how to say so.
    let (needs, optional, what): (&[&str], &[&str], &str) = match sky {
        "none" => (&[], &[], "no sky argument"),
        "uniform" => (&["sky_radiance"], &[], "`sky_radiance` (W·m⁻²·sr⁻¹·µm⁻¹)"),
        "thermal" => (&["sky_temperature_k"], &[], "`sky_temperature_k` (K)"),
        "profile" => (
            &["sky_profile"],
            &[],
            "`sky_profile` = (zenith_deg, radiance)",
        ),
        "cie-clear" => (
            &["sky_irradiance"],
            &["dop_max"],
            "`sky_irradiance` (W·m⁻²·µm⁻¹), optionally `dop_max`, and a `sun`",
        ),
        "table" => (
            &["sky_table"],
            &[],
            "`sky_table` = (theta_deg, phi_deg, stokes)",
        ),
        other => {
            return Err(PyValueError::new_err(format!(
                "invalid `sky`: unknown sky model `{other}` (expected \"none\", \"uniform\", \
                 \"thermal\", \"profile\", \"cie-clear\" or \"table\")"
            )))
        }
    };
    for (name, is_given) in given {
        if is_given && !needs.contains(&name) && !optional.contains(&name) {
            return Err(PyValueError::new_err(format!(
                "`{name}` does not apply to sky = \"{sky}\", which takes {what}"
            )));
        }
        if !is_given && needs.contains(&name) {
            return Err(PyValueError::new_err(format!(
                "sky = \"{sky}\" needs {what}"
            )));
        }
    }
    if sky == "cie-clear" && !has_sun {
        return Err(PyValueError::new_err(
            "sky = \"cie-clear\" needs a `sun` = (zenith, azimuth, irradiance): the clear \
             sky's radiance and polarization are set by the sun's position",
        ));
    }
    Ok(match sky {
        "none" => SkyModel::None,
        "uniform" => SkyModel::Uniform {
            radiance: args.radiance.expect("checked above"),
        },
        "thermal" => SkyModel::Thermal {
            temperature_k: args.temperature_k.expect("checked above"),
        },
        "profile" => {
            let (zenith_deg, radiance) = table(args.profile).expect("checked above");
            SkyModel::Profile(
                ZenithProfile::new(zenith_deg, radiance)
                    .map_err(|e| PyValueError::new_err(format!("`sky_profile`: {e}")))?,
            )
        }
        "cie-clear" => SkyModel::ClearSky {
            irradiance: args.irradiance.expect("checked above"),
            dop_max: args.dop_max,
        },
        _ => SkyModel::Table(sky_table(args.table.expect("checked above"))?),
    })
}

/// The [`TableSky`] of the `sky_table` argument; its errors prefixed with `sky_table`, the
/// flat node of a bad Stokes parameter also given as its `(theta, phi)` position.
fn sky_table(
    (theta, phi, stokes): (
        PyReadonlyArray1<'_, f64>,
        PyReadonlyArray1<'_, f64>,
        PyReadonlyArray2<'_, f64>,
    ),
) -> PyResult<TableSky> {
    let theta = theta.as_array().to_vec();
    let phi = phi.as_array().to_vec();
    let stokes = stokes.as_array();
    if stokes.ncols() != 4 {
        return Err(PyValueError::new_err(format!(
            "`sky_table`: the Stokes radiances must have 4 columns (s0, s1, s2, s3), got {}",
            stokes.ncols()
        )));
    }
    let nodes: Vec<polbrdf::Stokes> = stokes
        .rows()
        .into_iter()
        .map(|r| polbrdf::Stokes([r[0], r[1], r[2], r[3]]))
        .collect();
    let n_phi = phi.len();
    TableSky::new(theta, phi, nodes).map_err(|e| {
        let node = match &e {
            polbrdf::Error::InvalidParameterAt { name, index, .. }
                if name.starts_with('s') && n_phi > 0 =>
            {
                format!(
                    " (node {index} is stokes[{}, {}])",
                    index / n_phi,
                    index % n_phi
                )
            }
            _ => String::new(),
        };
        PyValueError::new_err(format!("`sky_table`: {e}{node}"))
    })
}

/// The sun of [`radiance_flat`]: `(zenith, azimuth, irradiance, stokes)` with the angles in
/// degrees when `degrees` (else radians) and the Stokes vector normalized to `s0 = 1` here
/// (a degree of polarization up to 1e-9 above 1 scaled to 1, as in a scene file); the rest is
/// checked by the core ([`ThermalScene::validate`]).
fn radiance_sun(sun: Option<(f64, f64, f64, [f64; 4])>, degrees: bool) -> PyResult<Option<Sun>> {
    let Some((zenith, azimuth, irradiance, s)) = sun else {
        return Ok(None);
    };
    let show = |s: &[f64; 4]| format!("({}, {}, {}, {})", s[0], s[1], s[2], s[3]);
    if !(s.iter().all(|v| v.is_finite()) && s[0] > 0.0) {
        return Err(PyValueError::new_err(format!(
            "invalid parameter `sun[3] (stokes)` = {}: must be finite with s0 > 0 (it is \
             normalized to s0 = 1)",
            show(&s)
        )));
    }
    let mut n = s.map(|v| v / s[0]);
    let dop = (n[1] * n[1] + n[2] * n[2] + n[3] * n[3]).sqrt();
    // As a scene file's `[sun] stokes`: up to 1e-9 above 1 is rounding, scaled back to 1.
    if dop.is_nan() || dop > 1.0 + 1e-9 {
        return Err(PyValueError::new_err(format!(
            "invalid parameter `sun[3] (stokes)` = {}: its degree of polarization \
             sqrt(s1² + s2² + s3²)/s0 = {dop} exceeds 1",
            show(&s)
        )));
    }
    if dop > 1.0 {
        for v in &mut n[1..] {
            *v /= dop;
        }
    }
    let rad = |a: f64| if degrees { a.to_radians() } else { a };
    Ok(Some(Sun {
        zenith: rad(zenith) + 0.0,
        azimuth: rad(azimuth),
        irradiance,
        stokes: polbrdf::Stokes(n),
    }))
}

/// The Python argument of a key of the core's [`ThermalScene::validate`].
fn scene_argument(core: &'static str) -> &'static str {
    match core {
        "surface.temperature_k" => "temperature_k",
        "sky.radiance" => "sky_radiance",
        "sky.temperature_k" => "sky_temperature_k",
        "sky.irradiance" => "sky_irradiance",
        "sky.dop_max" => "dop_max",
        "sun.zenith_deg" => "sun[0] (zenith)",
        "sun.azimuth_deg" => "sun[1] (azimuth)",
        "sun.irradiance" => "sun[2] (irradiance)",
        "sun.stokes" => "sun[3] (stokes)",
        "atmosphere.transmittance" => "transmittance",
        "atmosphere.path_radiance" => "path_radiance",
        other => other,
    }
}

/// The arrays of [`radiance_flat`].
type Observed<'py> = (
    Bound<'py, PyArray2<f64>>,
    Bound<'py, PyArray2<f64>>,
    Bound<'py, PyArray2<f64>>,
    Bound<'py, PyArray1<f64>>,
    Bound<'py, PyArray1<f64>>,
);

/// An optional pair of 1-D arrays (a band, a sky profile) as two vectors.
type Table<'py> = Option<(PyReadonlyArray1<'py, f64>, PyReadonlyArray1<'py, f64>)>;

fn table(t: Table<'_>) -> Option<(Vec<f64>, Vec<f64>)> {
    t.map(|(a, b)| (a.as_array().to_vec(), b.as_array().to_vec()))
}

/// The observed Stokes radiance (the core's `analysis::scene::observed_radiance`) at `n` views
/// `(theta_r, phi_r)` (degrees when `degrees`, else radians; `theta_r` in `[0°, 90°)`):
/// `(stokes (n, 4), emitted (n, 4), reflected (n, 4), dolp, aolp)`, AoLP in the unit of the
/// angles. W·m⁻²·sr⁻¹·µm⁻¹ at one wavelength, W·m⁻²·sr⁻¹ over a band. `sun` is
/// `(zenith, azimuth, irradiance, stokes)` (angles in the unit of the views, the Stokes vector
/// normalized here); `sky_table` the zenith angles and azimuths (degrees) and the
/// `(n_theta·n_phi, 4)` Stokes radiances, θ-major.
#[pyfunction]
#[pyo3(signature = (
    material, theta_r, phi_r, degrees, wavelength_um=None, band=None, band_step_um=None,
    temperature_k=None, sky="none", sky_radiance=None, sky_temperature_k=None, sky_profile=None,
    transmittance=1.0, path_radiance=0.0, sun=None, sky_irradiance=None,
    dop_max=DEFAULT_DOP_MAX, sky_table=None
))]
#[allow(clippy::too_many_arguments)]
fn radiance_flat<'py>(
    py: Python<'py>,
    material: &PyMaterial,
    theta_r: PyReadonlyArray1<'py, f64>,
    phi_r: PyReadonlyArray1<'py, f64>,
    degrees: bool,
    wavelength_um: Option<f64>,
    band: Table<'py>,
    band_step_um: Option<f64>,
    temperature_k: Option<f64>,
    sky: &str,
    sky_radiance: Option<f64>,
    sky_temperature_k: Option<f64>,
    sky_profile: Table<'py>,
    transmittance: f64,
    path_radiance: f64,
    sun: Option<(f64, f64, f64, [f64; 4])>,
    sky_irradiance: Option<f64>,
    dop_max: f64,
    sky_table: SkyTable<'py>,
) -> PyResult<Observed<'py>> {
    let (t, p) = flat_pair(&theta_r, &phi_r, ["theta_r", "phi_r"])?;
    let n = t.len();
    let spectrum = radiance_spectrum(wavelength_um, table(band), band_step_um)?;
    let sun = radiance_sun(sun, degrees)?;
    let sky_args = SkyArgs {
        radiance: sky_radiance,
        temperature_k: sky_temperature_k,
        profile: sky_profile,
        irradiance: sky_irradiance,
        dop_max,
        table: sky_table,
    };
    let scene = ThermalScene {
        surface_temperature_k: temperature_k,
        sky: radiance_sky(sky, sky_args, sun.is_some())?,
        atmosphere: Atmosphere {
            transmittance,
            path_radiance,
        },
        sun,
    };
    scene.validate().map_err(|e| match e {
        polbrdf::Error::InvalidParameter {
            name,
            value,
            reason,
        } => {
            let err = core_err(
                py,
                &polbrdf::Error::InvalidParameter {
                    name: scene_argument(name),
                    value,
                    reason,
                },
            );
            // The core reports the sun's zenith angle in degrees: say what was given.
            match (&scene.sun, name) {
                (Some(s), "sun.zenith_deg") if !degrees => PyValueError::new_err(format!(
                    "{} (given in radians: {})",
                    err.value(py),
                    s.zenith
                )),
                _ => err,
            }
        }
        other => core_err(py, &other),
    })?;
    // The views in radians, checked in order; each distinct one evaluated once.
    let mut seen: HashMap<(u64, u64), usize> = HashMap::new();
    let mut views: Vec<(f64, f64)> = Vec::new();
    let mut slot = Vec::with_capacity(n);
    for (i, (&t, &p)) in t.iter().zip(p).enumerate() {
        let v = view_zenith("theta_r", t, degrees, i)
            .and_then(|t| Ok((t, view_azimuth(p, degrees, i)?)))
            .map_err(|e| core_err(py, &e))?;
        slot.push(
            *seen
                .entry((v.0.to_bits(), v.1.to_bits()))
                .or_insert_with(|| {
                    views.push(v);
                    views.len() - 1
                }),
        );
    }
    let spec = material.inner.spec();
    let r = py
        .detach(|| observed_radiance(spec, &scene, &spectrum, &views))
        .map_err(|e| core_err(py, &e))?;
    let at = |k: &usize| &r[*k];
    let to_unit = |a: f64| if degrees { a.to_degrees() } else { a };
    Ok((
        stokes_array(py, slot.iter().map(|k| at(k).stokes), n)?,
        stokes_array(py, slot.iter().map(|k| at(k).emitted), n)?,
        stokes_array(py, slot.iter().map(|k| at(k).reflected), n)?,
        PyArray1::from_vec(py, slot.iter().map(|k| at(k).stokes.dolp()).collect()),
        PyArray1::from_vec(
            py,
            slot.iter().map(|k| to_unit(at(k).stokes.aolp())).collect(),
        ),
    ))
}

// ---------------------------------------------------------------------------------------------
// Fitting

/// The outcome of [`fit_flat`]: the fitted parameters with their uncertainties.
#[pyclass(name = "FitResult", module = "polbrdf", frozen)]
struct PyFitResult {
    result: polbrdf_fit::FitResult,
    material: Material,
}

#[pymethods]
impl PyFitResult {
    /// Names of the free parameters, in the order of every array below.
    #[getter]
    fn names(&self) -> Vec<&'static str> {
        self.result.params.iter().map(|p| p.name()).collect()
    }
    /// Fitted values (units of the material keys: degrees for `sigma_deg`, sr⁻¹ for ρ, …).
    #[getter]
    fn values<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        PyArray1::from_slice(py, &self.result.values)
    }
    /// Standard errors, `sqrt(diag(covariance))`; NaN for a parameter at its bound (see
    /// :attr:`bounds`).
    #[getter]
    fn stderr<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        PyArray1::from_slice(py, &self.result.stderr)
    }
    /// Per parameter: ``None`` when it ended inside its domain, else a dict
    /// ``{"bound": "lower", "upper_limit_95": float | None, "correlation_at_limit": array | None}``
    /// — the one-sided 95 % upper limit from the profile of χ² and the parameter's correlations
    /// at that limit.
    #[getter]
    fn bounds<'py>(&self, py: Python<'py>) -> PyResult<Vec<Option<Bound<'py, PyDict>>>> {
        self.result
            .bounds
            .iter()
            .map(|b| match b {
                polbrdf_fit::Bound::Interior => Ok(None),
                polbrdf_fit::Bound::AtLowerBound {
                    upper_limit_95,
                    correlation_at_limit,
                } => {
                    let d = PyDict::new(py);
                    d.set_item("bound", "lower")?;
                    d.set_item("upper_limit_95", *upper_limit_95)?;
                    d.set_item(
                        "correlation_at_limit",
                        correlation_at_limit
                            .as_ref()
                            .map(|c| PyArray1::from_slice(py, c)),
                    )?;
                    Ok(Some(d))
                }
            })
            .collect()
    }
    /// Covariance matrix, shape `(p, p)`.
    #[getter]
    fn covariance<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArray2<f64>>> {
        Ok(PyArray2::from_vec2(py, &self.result.covariance)?)
    }
    /// Correlation matrix, shape `(p, p)`.
    #[getter]
    fn correlation<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyArray2<f64>>> {
        Ok(PyArray2::from_vec2(py, &self.result.correlation)?)
    }
    /// `{name: (value, stderr)}`.
    #[getter]
    fn parameters<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        let d = PyDict::new(py);
        for (k, p) in self.result.params.iter().enumerate() {
            d.set_item(p.name(), (self.result.values[k], self.result.stderr[k]))?;
        }
        Ok(d)
    }
    /// χ² = Σ ((model − data)/σ)², σ = 1 where none was given.
    #[getter]
    fn chi2(&self) -> f64 {
        self.result.chi2
    }
    /// χ²/dof.
    #[getter]
    fn reduced_chi2(&self) -> f64 {
        self.result.reduced_chi2
    }
    /// Degrees of freedom: measured values − free parameters.
    #[getter]
    fn dof(&self) -> usize {
        self.result.dof
    }
    /// True when some value had no σ: the covariance is scaled by χ²/dof.
    #[getter]
    fn uncertainty_from_residuals(&self) -> bool {
        self.result.scaled_by_residuals
    }
    /// Whether the minimizer met a convergence test.
    #[getter]
    fn converged(&self) -> bool {
        self.result.converged
    }
    /// Minimizer steps of the best start.
    #[getter]
    fn iterations(&self) -> usize {
        self.result.iterations
    }
    /// How the minimizer stopped.
    #[getter]
    fn message(&self) -> &str {
        &self.result.message
    }
    /// `(starts tried, starts that reached the best χ²)`.
    #[getter]
    fn starts(&self) -> (usize, usize) {
        self.result.starts
    }
    /// Warnings about the data (e.g. repeated rows: the uncertainties are not meaningful);
    /// empty for a well-posed fit.
    #[getter]
    fn warnings(&self) -> Vec<String> {
        self.result.warnings.clone()
    }
    /// Pickle support: every field as plain values (the fitted material pickles itself),
    /// rebuilt by `_fit_result_from_state`.
    fn __reduce__<'py>(
        &self,
        py: Python<'py>,
    ) -> PyResult<(Bound<'py, PyAny>, (FitState, PyMaterial))> {
        let r = &self.result;
        let bounds = r
            .bounds
            .iter()
            .map(|b| match b {
                polbrdf_fit::Bound::Interior => None,
                polbrdf_fit::Bound::AtLowerBound {
                    upper_limit_95,
                    correlation_at_limit,
                } => Some((*upper_limit_95, correlation_at_limit.clone())),
            })
            .collect();
        let zbs = r.zero_bistatic.as_ref().map(|z| {
            (
                (z.a, z.b, z.stderr_a, z.stderr_b, z.correlation_ab),
                (z.samples.clone(), z.excluded.clone(), z.weighted),
            )
        });
        let state = (
            (
                r.warnings.clone(),
                r.params.iter().map(|p| p.name().to_string()).collect(),
                r.values.clone(),
                r.stderr.clone(),
                bounds,
                r.covariance.clone(),
                r.correlation.clone(),
            ),
            (
                r.chi2,
                r.dof,
                r.reduced_chi2,
                r.scaled_by_residuals,
                r.converged,
                r.iterations,
                r.message.clone(),
                r.starts,
            ),
            zbs,
            r.residuals
                .iter()
                .map(|x| (x.index, x.model, x.data, x.sigma))
                .collect(),
        );
        let material = PyMaterial {
            inner: self.material.clone(),
        };
        let f = py
            .import("polbrdf._polbrdf")?
            .getattr("_fit_result_from_state")?;
        Ok((f, (state, material)))
    }

    /// The fitted material.
    #[getter]
    fn material(&self) -> PyMaterial {
        PyMaterial {
            inner: self.material.clone(),
        }
    }
    /// Normalized residuals `(model − data)/σ`, one per measured value (in the order of the
    /// flattened data, quantity by quantity).
    #[getter]
    fn residuals<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        let r: Vec<f64> = self
            .result
            .residuals
            .iter()
            .map(|r| (r.model - r.data) / r.sigma)
            .collect();
        PyArray1::from_vec(py, r)
    }
    fn __repr__(&self) -> String {
        let params: Vec<String> = self
            .result
            .params
            .iter()
            .enumerate()
            .map(|(k, p)| {
                format!(
                    "{}={} ± {:.3e}",
                    p.name(),
                    py_float(self.result.values[k]),
                    self.result.stderr[k]
                )
            })
            .collect();
        format!(
            "FitResult({}; chi2/dof={:.4}, dof={}, converged={})",
            params.join(", "),
            self.result.reduced_chi2,
            self.result.dof,
            if self.result.converged {
                "True"
            } else {
                "False"
            }
        )
    }
}

/// Fits the `free` parameters of `material` to measured quantities at `n` geometries.
/// `names[k]` is `brdf`, `dolp` or `m00` … `m33`; `values[k]` has length `n` with NaN where not
/// measured; `sigmas[k]` (1-σ, > 0 where measured) or `None` for equal weights; `wavelength_um`
/// (µm, length `n`) places each geometry at a wavelength (a spectral index is fixed there).
#[pyfunction]
#[pyo3(signature = (material, theta_i, phi_i, theta_r, phi_r, names, values, sigmas, free, degrees, starts, seed, wavelength_um=None))]
#[allow(clippy::too_many_arguments)]
fn fit_flat<'py>(
    py: Python<'py>,
    material: &PyMaterial,
    theta_i: PyReadonlyArray1<'py, f64>,
    phi_i: PyReadonlyArray1<'py, f64>,
    theta_r: PyReadonlyArray1<'py, f64>,
    phi_r: PyReadonlyArray1<'py, f64>,
    names: Vec<String>,
    values: Vec<PyReadonlyArray1<'py, f64>>,
    sigmas: Vec<Option<PyReadonlyArray1<'py, f64>>>,
    free: Vec<String>,
    degrees: bool,
    starts: usize,
    seed: u64,
    wavelength_um: Option<PyReadonlyArray1<'py, f64>>,
) -> PyResult<PyFitResult> {
    use polbrdf_fit::{Measurement, Observable, Param};
    let input = slices([&theta_i, &phi_i, &theta_r, &phi_r])?;
    let n = common_len(input).map_err(|e| core_err(py, &e))?;
    let wl = wavelength_slice(&wavelength_um, n)?;
    if let Some(wl) = wl {
        if let Some((i, l)) = wl
            .iter()
            .enumerate()
            .find(|(_, l)| !(l.is_finite() && **l > 0.0))
        {
            return Err(PyValueError::new_err(format!(
                "wavelength_um = {l} at index {i}: a wavelength must be finite and > 0 µm"
            )));
        }
    }
    let fit_err = |e: polbrdf_fit::FitError| PyValueError::new_err(e.to_string());
    let free: Vec<Param> = Param::parse_list(&free.join(",")).map_err(fit_err)?;
    let mut geometries = Vec::with_capacity(n);
    for i in 0..n {
        let [a, b, c, d] = input.map(|s| s[i]);
        let g = if degrees {
            polbrdf::Geometry::from_degrees(a, b, c, d)
        } else {
            polbrdf::Geometry::new(a, b, c, d)
        };
        let g = g.map_err(|e| match e {
            polbrdf::Error::InvalidAngle {
                name,
                value,
                degrees,
                problem,
                ..
            } => polbrdf::Error::InvalidAngle {
                name: python_name(name),
                value,
                degrees,
                index: Some(i),
                problem,
            },
            other => other,
        });
        geometries.push(g.map_err(|e| core_err(py, &e))?);
    }
    let mut data = Vec::new();
    for ((name, v), s) in names.iter().zip(&values).zip(&sigmas) {
        let observable = Observable::parse(name).ok_or_else(|| {
            PyValueError::new_err(format!(
                "unknown measured quantity `{name}` (expected brdf, dolp, brdf_s, brdf_p or m00 … m33)"
            ))
        })?;
        let v = v
            .as_slice()
            .map_err(|e| PyValueError::new_err(e.to_string()))?;
        let s = match s {
            Some(s) => Some(
                s.as_slice()
                    .map_err(|e| PyValueError::new_err(e.to_string()))?,
            ),
            None => None,
        };
        if v.len() != n || s.is_some_and(|s| s.len() != n) {
            return Err(PyValueError::new_err(format!(
                "`{name}` does not have one value per geometry"
            )));
        }
        for i in 0..n {
            if v[i].is_nan() {
                continue; // not measured
            }
            if !v[i].is_finite() {
                return Err(PyValueError::new_err(format!(
                    "`{name}` = {} at index {i}: a measured value must be finite (NaN = not measured)",
                    v[i]
                )));
            }
            let sigma = match s.map(|s| s[i]) {
                Some(x) if x.is_finite() && x > 0.0 => Some(x),
                Some(x) => {
                    return Err(PyValueError::new_err(format!(
                    "sigma of `{name}` = {x} at index {i}: an uncertainty must be finite and > 0"
                )))
                }
                None => None,
            };
            data.push(Measurement {
                geometry: geometries[i],
                observable,
                value: v[i],
                sigma,
                wavelength_um: wl.map(|w| w[i]),
            });
        }
    }
    let opts = polbrdf_fit::FitOptions {
        extra_starts: starts,
        seed,
        ..polbrdf_fit::FitOptions::default()
    };
    let spec = material.inner.spec().clone();
    let result = py
        .detach(|| polbrdf_fit::fit(&spec, &free, &data, &opts))
        .map_err(fit_err)?;
    let material = match (result.spec.is_spectral(), wl) {
        (true, Some(w)) => result.spec.build_at(w[0]),
        _ => result.spec.build(),
    }
    .map_err(|e| core_err(py, &e))?;
    Ok(PyFitResult { result, material })
}

/// A bound of a [`polbrdf_fit::Bound`] as plain values: `None` inside the domain.
type BoundState = Option<(Option<f64>, Option<Vec<f64>>)>;
/// A zero-bistatic start as plain values.
type ZbsState = (
    (f64, f64, f64, f64, f64),
    (Vec<(f64, f64)>, Vec<usize>, bool),
);
/// A [`PyFitResult`] as plain values (its pickled state).
type FitState = (
    (
        Vec<String>,
        Vec<String>,
        Vec<f64>,
        Vec<f64>,
        Vec<BoundState>,
        Vec<Vec<f64>>,
        Vec<Vec<f64>>,
    ),
    (f64, usize, f64, bool, bool, usize, String, (usize, usize)),
    Option<ZbsState>,
    Vec<(usize, f64, f64, f64)>,
);

/// The inverse of `FitResult.__reduce__`. The fit's material specification is the fitted
/// material's (for a spectral fit the constant index at the fitted wavelength; no attribute of
/// `FitResult` shows the difference).
#[pyfunction]
fn _fit_result_from_state(state: FitState, m: PyRef<'_, PyMaterial>) -> PyResult<PyFitResult> {
    let ((warnings, names, values, stderr, bounds, covariance, correlation), tail, zbs, res) =
        state;
    let (chi2, dof, reduced_chi2, scaled_by_residuals, converged, iterations, message, starts) =
        tail;
    let params = names
        .iter()
        .map(|n| polbrdf_fit::Param::parse(n))
        .collect::<Result<Vec<_>, _>>()
        .map_err(|e| PyValueError::new_err(e.to_string()))?;
    let bounds = bounds
        .into_iter()
        .map(|b| match b {
            None => polbrdf_fit::Bound::Interior,
            Some((upper_limit_95, correlation_at_limit)) => polbrdf_fit::Bound::AtLowerBound {
                upper_limit_95,
                correlation_at_limit,
            },
        })
        .collect();
    let zero_bistatic = zbs.map(
        |((a, b, stderr_a, stderr_b, correlation_ab), (samples, excluded, weighted))| {
            polbrdf_fit::zbs::ZbsFit {
                a,
                b,
                stderr_a,
                stderr_b,
                correlation_ab,
                samples,
                excluded,
                weighted,
            }
        },
    );
    let residuals = res
        .into_iter()
        .map(|(index, model, data, sigma)| polbrdf_fit::Residual {
            index,
            model,
            data,
            sigma,
        })
        .collect();
    let result = polbrdf_fit::FitResult {
        warnings,
        params,
        values,
        stderr,
        bounds,
        covariance,
        correlation,
        chi2,
        dof,
        reduced_chi2,
        scaled_by_residuals,
        converged,
        iterations,
        message,
        starts,
        zero_bistatic,
        spec: m.inner.spec().clone(),
        residuals,
    };
    Ok(PyFitResult {
        result,
        material: m.inner.clone(),
    })
}

/// The compiled part of the `polbrdf` package (import `polbrdf`, not this module).
#[pymodule]
fn _polbrdf(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_class::<PyMaterial>()?;
    m.add_function(wrap_pyfunction!(_fit_result_from_state, m)?)?;
    m.add_function(wrap_pyfunction!(mueller_flat, m)?)?;
    m.add_function(wrap_pyfunction!(mueller_directions_flat, m)?)?;
    m.add_function(wrap_pyfunction!(brdf_dolp_flat, m)?)?;
    m.add_function(wrap_pyfunction!(evaluate_flat, m)?)?;
    m.add_function(wrap_pyfunction!(index_flat, m)?)?;
    m.add_function(wrap_pyfunction!(derivative_step, m)?)?;
    m.add_function(wrap_pyfunction!(planck_flat, m)?)?;
    m.add_function(wrap_pyfunction!(brightness_temperature_flat, m)?)?;
    m.add_function(wrap_pyfunction!(emissivity_flat, m)?)?;
    m.add_function(wrap_pyfunction!(radiance_flat, m)?)?;
    m.add_class::<PyFitResult>()?;
    m.add_function(wrap_pyfunction!(fit_flat, m)?)?;
    Ok(())
}
