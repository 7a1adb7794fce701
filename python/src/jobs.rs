//! The task layer's remaining jobs for Python (`polbrdf-tasks`): the validity check, the band
//! emissivity, the rows of a lookup table, `.pbsdf` tables (export, read, band fit) and the
//! measurement CSV the CLI fits. Each function builds the task's request from what the Python
//! layer hands over, calls the task with the GIL released and returns plain values: the
//! numbers of `polbrdf check`, `polbrdf emission`, `polbrdf lut`, `polbrdf export` and
//! `polbrdf fit`, bit for bit. Nothing here computes.

use crate::buffers::can_allocate;
use crate::errors::io_err;
use crate::material::PyMaterial;
use crate::tasks::{spectral_request, task_err, Spectral};
use crate::thermal::emissivity_arrays;
use numpy::ndarray::{Array2, ArrayD, IxDyn};
use numpy::{IntoPyArray, PyArray1, PyArray2, PyArrayDyn};
use polbrdf::analysis::emission::Emissivity;
use polbrdf_fit::{FitOptions, Param};
use polbrdf_io::lut::Quantity;
use polbrdf_io::PbsdfTable;
use polbrdf_tasks::check::{check, check_of, CheckRequest};
use polbrdf_tasks::emission::{emission, emission_of, EmissionRequest};
use polbrdf_tasks::lut::{material_rows, Axes};
use polbrdf_tasks::pbsdf::{export, fit_table, plan, ExportRequest};
use polbrdf_tasks::spectrum::NamedMaterial;
use polbrdf_tasks::TaskError;
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use std::path::PathBuf;

/// A material as the Python layer hands it over: a file or preset name, or a `Material`.
#[derive(FromPyObject)]
pub(crate) enum MaterialArg<'py> {
    /// A `polbrdf.Material`.
    Object(PyRef<'py, PyMaterial>),
    /// A material file or a preset name.
    Name(String),
}

impl MaterialArg<'_> {
    /// The display source of the material (what messages name).
    fn source(&self) -> String {
        match self {
            MaterialArg::Object(_) => "<polbrdf.Material>".into(),
            MaterialArg::Name(n) => n.clone(),
        }
    }

    /// A `Material` as the task layer's named material (request field `material`); `None`
    /// for a name, which the task reads itself (after checking the request).
    fn named(&self) -> Option<NamedMaterial> {
        let MaterialArg::Object(m) = self else {
            return None;
        };
        let spec = m.inner.spec().clone();
        Some(NamedMaterial {
            name: spec.name.clone().unwrap_or_else(|| "material".into()),
            spec,
            source: self.source(),
            field: "material".into(),
        })
    }

    /// The material's specification (a name is read by `polbrdf-io`'s one reader).
    fn spec(&self) -> Result<polbrdf::MaterialSpec, TaskError> {
        match self {
            MaterialArg::Object(m) => Ok(m.inner.spec().clone()),
            MaterialArg::Name(n) => Ok(polbrdf_io::load_material(n)?),
        }
    }
}

/// A validity check (`polbrdf_tasks::check`), as `polbrdf check --output` runs it: the JSON
/// document of `check.json`. `grid_deg` `None` takes the task's default.
#[pyfunction]
#[pyo3(signature = (material, grid_deg, spectral))]
pub(crate) fn check_task(
    py: Python<'_>,
    material: MaterialArg<'_>,
    grid_deg: Option<f64>,
    spectral: Spectral,
) -> PyResult<String> {
    let request = CheckRequest {
        material: material.source(),
        grid_deg: grid_deg.unwrap_or(polbrdf_tasks::check::DEFAULT_GRID_DEG),
        spectral: spectral_request(spectral),
    };
    let named = material.named();
    let outcome = py
        .detach(|| match named {
            Some(m) => check_of(m, &request),
            None => check(&request),
        })
        .map_err(|e| task_err(py, &e))?;
    serde_json::to_string(&outcome.to_json()).map_err(|e| PyValueError::new_err(e.to_string()))
}

/// What [`emission_task`] returns: the view angles (degrees), `eps (n, 4)`, `eps_b (n, 4)`,
/// `eps_s`, `eps_p`, `dolp`, `reciprocity_residual`, `valid`.
type Emitted<'py> = (
    Bound<'py, PyArray1<f64>>,
    Bound<'py, PyArray2<f64>>,
    Bound<'py, PyArray2<f64>>,
    Bound<'py, PyArray1<f64>>,
    Bound<'py, PyArray1<f64>>,
    Bound<'py, PyArray1<f64>>,
    Bound<'py, PyArray1<f64>>,
    Bound<'py, PyArray1<bool>>,
);

/// The emissivity at view angles over a wavelength or band (`polbrdf_tasks::emission`), as
/// `polbrdf emission` runs it.
#[pyfunction]
#[pyo3(signature = (material, theta_deg, temperature_k, spectral))]
pub(crate) fn emission_task<'py>(
    py: Python<'py>,
    material: MaterialArg<'_>,
    theta_deg: Vec<f64>,
    temperature_k: Option<f64>,
    spectral: Spectral,
) -> PyResult<Emitted<'py>> {
    let request = EmissionRequest {
        material: material.source(),
        theta_deg,
        temperature_k,
        spectral: spectral_request(spectral),
    };
    let named = material.named();
    let t = py
        .detach(|| match named {
            Some(m) => emission_of(m, &request),
            None => emission(&request),
        })
        .map_err(|e| task_err(py, &e))?;
    let e: Vec<Emissivity> = t.rows.iter().map(|r| r.emissivity).collect();
    let valid = t.rows.iter().map(|r| r.valid).collect();
    let (eps, eps_b, eps_s, eps_p, dolp, residual, valid) = emissivity_arrays(py, &e, valid)?;
    Ok((
        PyArray1::from_vec(py, t.rows.iter().map(|r| r.theta_deg).collect()),
        eps,
        eps_b,
        eps_s,
        eps_p,
        dolp,
        residual,
        valid,
    ))
}

/// The rows of one material of a lookup table (`polbrdf_tasks::lut::material_rows`): one row
/// per (wavelength, θi, θr, Δφ) in C order, the columns of the quantities in the order given.
#[pyfunction]
#[pyo3(signature = (material, wavelength_um, theta_i_deg, theta_r_deg, dphi_deg, quantities))]
pub(crate) fn lut_rows<'py>(
    py: Python<'py>,
    material: &PyMaterial,
    wavelength_um: Vec<f64>,
    theta_i_deg: Vec<f64>,
    theta_r_deg: Vec<f64>,
    dphi_deg: Vec<f64>,
    quantities: Vec<String>,
) -> PyResult<Bound<'py, PyArray2<f64>>> {
    let qs = quantities
        .iter()
        .map(|q| {
            Quantity::ALL
                .iter()
                .find(|(name, _)| name == q)
                .map(|(_, q)| *q)
                .ok_or_else(|| PyValueError::new_err(format!("invalid `quantities`: {q:?}")))
        })
        .collect::<PyResult<Vec<_>>>()?;
    let width = polbrdf_tasks::lut::columns(&qs).len();
    let axes = Axes {
        theta_i_deg: &theta_i_deg,
        theta_r_deg: &theta_r_deg,
        dphi_deg: &dphi_deg,
    };
    let n = axes.len().saturating_mul(wavelength_um.len());
    can_allocate::<f64>(n.saturating_mul(width))?;
    let m = &material.inner;
    let rows = py
        .detach(|| {
            let mut rows = Vec::with_capacity(n * width);
            material_rows(m, &wavelength_um, axes, &qs, |block| {
                rows.extend_from_slice(block);
                Ok(())
            })
            .map(|()| rows)
        })
        .map_err(|e| task_err(py, &e))?;
    Ok(Array2::from_shape_vec((n, width), rows)
        .expect("one row per geometry and wavelength")
        .into_pyarray(py))
}

/// Writes a material as a `.pbsdf` table (`polbrdf_tasks::pbsdf::export`), as `polbrdf
/// export` writes it (`None`: the task's default bands and grid); returns the bytes of its
/// matrices.
#[pyfunction]
#[pyo3(signature = (material, path, bands_nm, grid))]
pub(crate) fn export_pbsdf_task(
    py: Python<'_>,
    material: MaterialArg<'_>,
    path: PathBuf,
    bands_nm: Option<Vec<u16>>,
    grid: Option<[usize; 3]>,
) -> PyResult<u64> {
    let request = ExportRequest {
        bands_nm: bands_nm.unwrap_or_else(|| polbrdf_tasks::pbsdf::DEFAULT_BANDS_NM.to_vec()),
        grid: grid.unwrap_or(polbrdf_tasks::pbsdf::DEFAULT_GRID),
    };
    // The request before the material (options before data).
    request.validate().map_err(|e| task_err(py, &e))?;
    let spec = material.spec().map_err(|e| task_err(py, &e))?;
    py.detach(|| export(&spec, &request, &path))
        .map_err(|e| task_err(py, &e))
}

/// What [`read_pbsdf_task`] returns: `phi_d`, `theta_d`, `theta_h` (radians), the band
/// wavelengths (nm) and the matrices `(P, D, H, bands, 4, 4)` (float32, plane-of-reflection
/// frame, as stored).
type PbsdfOut<'py> = (
    Bound<'py, PyArray1<f64>>,
    Bound<'py, PyArray1<f64>>,
    Bound<'py, PyArray1<f64>>,
    Vec<u16>,
    Bound<'py, PyArrayDyn<f32>>,
);

/// Reads a `.pbsdf` table by `polbrdf-io`'s reader (the one the band fit uses), slab by slab:
/// the memory is that of the data the file holds, never a size its header claims.
#[pyfunction]
pub(crate) fn read_pbsdf_task(py: Python<'_>, path: PathBuf) -> PyResult<PbsdfOut<'_>> {
    let (table, values) = py
        .detach(|| {
            let mut table = PbsdfTable::open(&path)?;
            let mut values = Vec::new();
            let mut slab = Vec::new();
            for p in 0..table.phi_d.len() {
                table.read_slab(p, &mut slab)?;
                values.extend_from_slice(&slab);
            }
            Ok::<_, polbrdf_io::Error>((table, values))
        })
        .map_err(|e| io_err(&e))?;
    let shape = [
        table.phi_d.len(),
        table.theta_d.len(),
        table.theta_h.len(),
        table.wavelengths_nm.len(),
        4,
        4,
    ];
    let values = ArrayD::from_shape_vec(IxDyn(&shape), values)
        .expect("every slab has its cells")
        .into_pyarray(py);
    Ok((
        PyArray1::from_slice(py, &table.phi_d),
        PyArray1::from_slice(py, &table.theta_d),
        PyArray1::from_slice(py, &table.theta_h),
        table.wavelengths_nm.clone(),
        values,
    ))
}

/// Fits every band of a `.pbsdf` table (`polbrdf_tasks::pbsdf::fit_table`), as `polbrdf fit
/// --data table.pbsdf` runs it: the `fit.json` document as JSON text.
#[pyfunction]
#[pyo3(signature = (material, path, free, subsample, starts, seed, exclude_inadmissible))]
#[allow(clippy::too_many_arguments)] // One per keyword of `polbrdf.fit_pbsdf`, plain values.
pub(crate) fn fit_pbsdf_task(
    py: Python<'_>,
    material: MaterialArg<'_>,
    path: PathBuf,
    free: Vec<String>,
    subsample: Option<usize>,
    starts: usize,
    seed: u64,
    exclude_inadmissible: bool,
) -> PyResult<String> {
    let free = Param::parse_list(&free.join(","))
        .map_err(|e| task_err(py, &TaskError::invalid("free", e.to_string())))?;
    if starts > polbrdf_tasks::limits::STARTS {
        let e = TaskError::Limit {
            field: "starts".into(),
            what: format!(" = {starts}"),
            max: polbrdf_tasks::limits::STARTS,
        };
        return Err(task_err(py, &e));
    }
    let base = material.spec().map_err(|e| task_err(py, &e))?;
    let opts = FitOptions {
        extra_starts: starts,
        seed,
        ..FitOptions::default()
    };
    let doc = py
        .detach(|| {
            let mut table = PbsdfTable::open(&path)?;
            let stride = plan(&table, subsample, starts)?;
            fit_table(
                &mut table,
                &base,
                &free,
                stride,
                exclude_inadmissible,
                &opts,
                |_| Ok::<(), TaskError>(()),
            )
        })
        .map_err(|e| task_err(py, &e))?;
    serde_json::to_string(&doc).map_err(|e| PyValueError::new_err(e.to_string()))
}

/// What [`read_measurements_task`] returns: the file's line of each row, `θi, φi, θr, φr`
/// (radians, as the CLI fits them), the measured columns' names, their values (NaN where a
/// row leaves the cell empty), their uncertainties (`None` for a column without
/// `sigma_<column>`), and the wavelengths (µm) when the file has the column.
type MeasurementsOut<'py> = (
    Vec<usize>,
    [Bound<'py, PyArray1<f64>>; 4],
    Vec<String>,
    Vec<Bound<'py, PyArray1<f64>>>,
    Vec<Option<Bound<'py, PyArray1<f64>>>>,
    Option<Bound<'py, PyArray1<f64>>>,
);

/// Reads a measurement CSV by `polbrdf-io`'s reader and checks it as `polbrdf fit` does
/// (`polbrdf_tasks::fit::measurements`: a value too large for a least-squares fit is refused
/// with its file, line and column).
#[pyfunction]
pub(crate) fn read_measurements_task(
    py: Python<'_>,
    path: PathBuf,
) -> PyResult<MeasurementsOut<'_>> {
    let table = py
        .detach(|| {
            let table = polbrdf_io::read_measurements_csv(&path)?;
            polbrdf_tasks::fit::measurements(&table)?;
            Ok::<_, TaskError>(table)
        })
        .map_err(|e| task_err(py, &e))?;
    let g = &table.geometries;
    let angle =
        |f: fn(&polbrdf::Geometry) -> f64| PyArray1::from_vec(py, g.iter().map(f).collect());
    let nan = |v: &[Option<f64>]| {
        PyArray1::from_vec(py, v.iter().map(|x| x.unwrap_or(f64::NAN)).collect())
    };
    Ok((
        table.lines.clone(),
        [
            angle(polbrdf::Geometry::theta_i),
            angle(polbrdf::Geometry::phi_i),
            angle(polbrdf::Geometry::theta_r),
            angle(polbrdf::Geometry::phi_r),
        ],
        table.columns.iter().map(|c| c.name.clone()).collect(),
        table.columns.iter().map(|c| nan(&c.values)).collect(),
        table
            .columns
            .iter()
            .map(|c| c.sigmas.as_deref().map(nan))
            .collect(),
        table
            .wavelengths
            .as_ref()
            .map(|w| PyArray1::from_slice(py, w)),
    ))
}
