//! Fitting: `fit_flat`, its `FitResult` and that class's pickled state.

use crate::buffers::slices;
use crate::errors::core_err;
use crate::errors::python_name;
use crate::evaluation::common_len;
use crate::evaluation::wavelength_slice;
use crate::material::py_float;
use crate::material::PyMaterial;
use numpy::{PyArray1, PyArray2, PyReadonlyArray1};
use polbrdf::Material;
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use pyo3::types::PyDict;

/// The central-difference step of the fit's Jacobian for parameter `name` at value `value`
/// (`polbrdf_fit::Param::derivative_step`): the uncertainty propagation of `polbrdf.xarray`
/// differentiates with the same steps as the fit that produced the covariance.
#[pyfunction]
pub(crate) fn derivative_step(name: &str, value: f64) -> PyResult<f64> {
    let p = polbrdf_fit::Param::parse(name).map_err(|e| PyValueError::new_err(e.to_string()))?;
    Ok(p.derivative_step(value))
}

/// The outcome of [`fit_flat`]: the fitted parameters with their uncertainties.
#[pyclass(name = "FitResult", module = "polbrdf", frozen)]
pub(crate) struct PyFitResult {
    result: polbrdf_fit::FitResult,
    material: Material,
}

impl PyFitResult {
    /// The fit's result (for the tasks that take a fit, e.g. a detection range's uncertainty).
    pub(crate) fn result(&self) -> &polbrdf_fit::FitResult {
        &self.result
    }
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

/// The first `n` geometries of the four angle arrays (degrees when `degrees`), a bad angle
/// named by its Python argument and index.
fn geometries(
    py: Python<'_>,
    input: [&[f64]; 4],
    n: usize,
    degrees: bool,
) -> PyResult<Vec<polbrdf::Geometry>> {
    (0..n)
        .map(|i| {
            let [a, b, c, d] = input.map(|s| s[i]);
            let g = if degrees {
                polbrdf::Geometry::from_degrees(a, b, c, d)
            } else {
                polbrdf::Geometry::new(a, b, c, d)
            };
            g.map_err(|e| match e {
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
            })
            .map_err(|e| core_err(py, &e))
        })
        .collect()
}

/// Fits the `free` parameters of `material` to measured quantities at `n` geometries.
/// `names[k]` is `brdf`, `dolp` or `m00` … `m33`; `values[k]` has length `n` with NaN where not
/// measured; `sigmas[k]` (1-σ, > 0 where measured) or `None` for equal weights; `wavelength_um`
/// (µm, length `n`) places each geometry at a wavelength (a spectral index is fixed there).
#[pyfunction]
#[pyo3(signature = (material, theta_i, phi_i, theta_r, phi_r, names, values, sigmas, free, degrees, starts, seed, wavelength_um=None))]
#[allow(clippy::too_many_arguments)]
// long function: the flat NumPy signature (13 arguments, one per line) takes 17 of its lines.
pub(crate) fn fit_flat<'py>(
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
    let geometries = geometries(py, input, n, degrees)?;
    if degrees {
        let mut scan = polbrdf_io::AngleScan::default();
        geometries.iter().for_each(|g| scan.add(g));
        crate::errors::warn_units(py, scan.warning("polbrdf.fit (degrees=True)").as_slice())?;
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
pub(crate) type BoundState = Option<(Option<f64>, Option<Vec<f64>>)>;
/// A zero-bistatic start as plain values.
pub(crate) type ZbsState = (
    (f64, f64, f64, f64, f64),
    (Vec<(f64, f64)>, Vec<usize>, bool),
);
/// A [`PyFitResult`] as plain values (its pickled state).
pub(crate) type FitState = (
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
pub(crate) fn _fit_result_from_state(
    state: FitState,
    m: PyRef<'_, PyMaterial>,
) -> PyResult<PyFitResult> {
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

/// Fits the measurement CSV `path` as `polbrdf fit --data path` does: the file read by
/// `polbrdf-io`'s reader, the measurements assembled by the task layer
/// (`polbrdf_tasks::fit::measurements`, in file order) and fitted by `polbrdf_fit::fit` with the
/// same options, so that the result is the CLI's `fit.json`, bit for bit.
#[pyfunction]
#[pyo3(signature = (material, path, free, starts, seed))]
pub(crate) fn fit_measurements_task(
    py: Python<'_>,
    material: &PyMaterial,
    path: std::path::PathBuf,
    free: Vec<String>,
    starts: usize,
    seed: u64,
) -> PyResult<PyFitResult> {
    use polbrdf_fit::Param;
    let fit_err = |e: polbrdf_fit::FitError| PyValueError::new_err(e.to_string());
    // Options before data (as the CLI: the free parameters, the starts, then the file).
    let free: Vec<Param> = Param::parse_list(&free.join(",")).map_err(fit_err)?;
    if starts > polbrdf_tasks::limits::STARTS {
        let e = polbrdf_tasks::TaskError::Limit {
            field: "starts".into(),
            what: format!(" = {starts}"),
            max: polbrdf_tasks::limits::STARTS,
        };
        return Err(crate::tasks::task_err(py, &e));
    }
    let spec = material.inner.spec().clone();
    let opts = polbrdf_fit::FitOptions {
        extra_starts: starts,
        seed,
        ..polbrdf_fit::FitOptions::default()
    };
    let (result, first_wavelength) = py
        .detach(|| {
            let table = polbrdf_io::read_measurements_csv(&path)?;
            let data = polbrdf_tasks::fit::measurements(&table)?;
            let wl = data.first().and_then(|m| m.wavelength_um);
            let result = polbrdf_fit::fit(&spec, &free, &data, &opts)?;
            Ok::<_, polbrdf_tasks::TaskError>((result, wl))
        })
        .map_err(|e| crate::tasks::task_err(py, &e))?;
    let material = match (result.spec.is_spectral(), first_wavelength) {
        (true, Some(w)) => result.spec.build_at(w),
        _ => result.spec.build(),
    }
    .map_err(|e| core_err(py, &e))?;
    Ok(PyFitResult { result, material })
}
