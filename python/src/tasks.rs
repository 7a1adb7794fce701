//! The jobs of the task layer (`polbrdf-tasks`) for Python: a contrast study, a hemisphere
//! map and the albedo. Each function builds the task's request from the arguments the Python
//! layer hands over, calls the task with the GIL released and returns its table as NumPy arrays
//! (plus, for a contrast, the `best.json` document as JSON text): the numbers of `polbrdf
//! contrast`, `polbrdf map` and `polbrdf albedo`, bit for bit. Nothing here computes.

use crate::errors::{core_err, io_err};
use numpy::ndarray::Array2;
use numpy::{IntoPyArray, PyArray1, PyArray2};
use polbrdf::analysis::contrast::Ranking;
use polbrdf::analysis::scene::Sun;
use polbrdf::Albedo;
use polbrdf_tasks::albedo::{albedo, AlbedoRequest};
use polbrdf_tasks::contrast::{contrast, ContrastRequest, RankRequest, SourceRequest};
use polbrdf_tasks::hemisphere::{
    deg, hemisphere, Hemisphere, HemisphereRequest, LightRequest, DEFAULT_GRID_DEG,
};
use polbrdf_tasks::spectrum::SpectralRequest;
use polbrdf_tasks::TaskError;
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use std::path::{Path, PathBuf};

/// A task error as a Python exception: a request field's error is a `ValueError` naming the
/// keyword (and carrying it as `argument`), file errors as [`io_err`], model errors as
/// [`core_err`].
pub(crate) fn task_err(py: Python<'_>, e: &TaskError) -> PyErr {
    match e {
        TaskError::Invalid { field, message } | TaskError::Usage { field, message } => {
            let err = PyValueError::new_err(format!("invalid `{field}`: {message}"));
            let _ = err.value(py).setattr("argument", field.as_str());
            err
        }
        TaskError::Limit { field, what, max } => {
            let err = PyValueError::new_err(format!(
                "invalid `{field}`{what}: at most {max} (the limit of this argument; see \
                 docs/reliability.md)"
            ));
            let _ = err.value(py).setattr("argument", field.as_str());
            err
        }
        TaskError::Io(e) => io_err(e),
        TaskError::Model(e) => core_err(py, e),
        other => PyValueError::new_err(other.to_string()),
    }
}

/// A table of rows as a 2-D array (one row per direction).
fn table<'py>(py: Python<'py>, rows: Vec<Vec<f64>>, width: usize) -> Bound<'py, PyArray2<f64>> {
    let n = rows.len();
    let flat: Vec<f64> = rows.into_iter().flatten().collect();
    Array2::from_shape_vec((n, width), flat)
        .expect("every row has one value per column")
        .into_pyarray(py)
}

/// A collimated source and its spectrum, as the Python layer hands them over:
/// `(sun_zenith_deg, sun_azimuth_deg, stokes)` and `(wavelength_um, band file, band_step_um)`.
/// An azimuth of `None` takes the sun's default ([`Sun::DEFAULT_AZIMUTH`], as the CLI's).
type Light = (f64, Option<f64>, Option<[f64; 4]>);
pub(crate) type Spectral = (Option<f64>, Option<PathBuf>, Option<f64>);

fn light_request((zenith, azimuth, stokes): Light) -> LightRequest {
    LightRequest {
        sun_zenith_deg: Some(zenith),
        sun_azimuth_deg: azimuth.unwrap_or(Sun::DEFAULT_AZIMUTH.to_degrees()),
        stokes,
    }
}

pub(crate) fn spectral_request((wavelength_um, band, band_step_um): Spectral) -> SpectralRequest {
    SpectralRequest {
        wavelength_um,
        band,
        band_step_um,
    }
}

/// The ranking of a contrast: each argument left at `None` takes the task's default.
fn rank_request(
    py: Python<'_>,
    rank_by: Option<&str>,
    top: Option<usize>,
    min_separation_deg: Option<f64>,
    max_zenith_deg: Option<f64>,
    refine: Option<bool>,
) -> PyResult<RankRequest> {
    let d = RankRequest::default();
    let by = match rank_by {
        None => d.by,
        Some(s) => s.parse::<Ranking>().map_err(|m| {
            let err = PyValueError::new_err(format!("invalid `rank_by`: {m}"));
            let _ = err.value(py).setattr("argument", "rank_by");
            err
        })?,
    };
    Ok(RankRequest {
        by,
        top: top.unwrap_or(d.top),
        min_separation_deg: min_separation_deg.unwrap_or(d.min_separation_deg),
        max_zenith_deg: max_zenith_deg.unwrap_or(d.max_zenith_deg),
        refine: refine.unwrap_or(d.refine),
    })
}

/// The source of a contrast: a scene file, a scene's text (read by polbrdf-io's reader as from
/// a file named `source`), or a collimated source with its spectrum.
fn source_request(
    scene_file: Option<PathBuf>,
    scene_text: Option<(String, String)>,
    light: Option<Light>,
    spectral: Spectral,
) -> PyResult<SourceRequest> {
    Ok(match (scene_file, scene_text, light) {
        (Some(path), None, None) => SourceRequest::Scene(path),
        (None, Some((text, source)), None) => SourceRequest::Loaded(Box::new(
            polbrdf_io::parse_scene(&text, Path::new(&source)).map_err(|e| io_err(&e))?,
        )),
        (None, None, Some(light)) => SourceRequest::Collimated {
            light: light_request(light),
            spectral: spectral_request(spectral),
        },
        _ => {
            return Err(PyValueError::new_err(
                "give exactly one of a scene file, a scene or a collimated source",
            ))
        }
    })
}

/// What [`contrast_task`] returns: the table's columns, the table (one row per grid direction,
/// zenith-major), the number of zeniths and azimuths of the grid, `best.json` as JSON text,
/// the setup's warnings, and the grid zeniths (degrees) where either model, the target's and
/// the background's is flagged invalid.
type ContrastOut<'py> = (
    Vec<&'static str>,
    Bound<'py, PyArray2<f64>>,
    (usize, usize),
    String,
    Vec<String>,
    [Bound<'py, PyArray1<f64>>; 3],
);

/// Grid zeniths (rad) in degrees, as the tables and the figures show them.
fn zeniths_deg<'py>(py: Python<'py>, zeniths: &[f64]) -> Bound<'py, PyArray1<f64>> {
    PyArray1::from_vec(py, zeniths.iter().map(|&t| deg(t)).collect())
}

/// A contrast study (`polbrdf_tasks::contrast`), as `polbrdf contrast` runs it.
#[pyfunction]
#[pyo3(signature = (target, background, scene_file, scene_text, light, spectral, grid_deg,
    rank_by, top, min_separation_deg, max_zenith_deg, refine))]
#[allow(clippy::too_many_arguments)] // One per keyword of `polbrdf.contrast`, all plain values.
pub(crate) fn contrast_task<'py>(
    py: Python<'py>,
    target: Option<String>,
    background: Option<String>,
    scene_file: Option<PathBuf>,
    scene_text: Option<(String, String)>,
    light: Option<Light>,
    spectral: Spectral,
    grid_deg: Option<(f64, f64)>,
    rank_by: Option<&str>,
    top: Option<usize>,
    min_separation_deg: Option<f64>,
    max_zenith_deg: Option<f64>,
    refine: Option<bool>,
) -> PyResult<ContrastOut<'py>> {
    let request = ContrastRequest {
        target,
        background,
        source: source_request(scene_file, scene_text, light, spectral)?,
        grid_deg: grid_deg.unwrap_or(DEFAULT_GRID_DEG),
        rank: rank_request(py, rank_by, top, min_separation_deg, max_zenith_deg, refine)?,
    };
    let study = py
        .detach(|| contrast(&request))
        .map_err(|e| task_err(py, &e))?;
    let columns = study.columns();
    let width = columns.len();
    let rows: Vec<Vec<f64>> = study.rows().collect();
    let shape = grid_shape(rows.len(), &rows);
    let best = serde_json::to_string(&study.best_json())
        .map_err(|e| PyValueError::new_err(e.to_string()))?;
    let warnings = study.warnings.iter().map(ToString::to_string).collect();
    let invalid = &study.invalid_zeniths;
    let invalid = [
        zeniths_deg(py, &invalid.either()),
        zeniths_deg(py, &invalid.target),
        zeniths_deg(py, &invalid.background),
    ];
    Ok((
        columns,
        table(py, rows, width),
        shape,
        best,
        warnings,
        invalid,
    ))
}

/// The `(zeniths, azimuths)` of a zenith-major grid of `n` rows: the azimuths are the rows at
/// the first row's zenith.
fn grid_shape(n: usize, rows: &[Vec<f64>]) -> (usize, usize) {
    let first = rows.first().map_or(f64::NAN, |r| r[0]);
    let n_phi = rows.iter().take_while(|r| r[0] == first).count().max(1);
    (n / n_phi, n_phi)
}

/// What [`hemisphere_task`] returns: the columns, the table (zenith-major), the grid's
/// `(zeniths, azimuths)` and the grid zeniths (degrees) where the model is flagged invalid.
type HemisphereOut<'py> = (
    Vec<&'static str>,
    Bound<'py, PyArray2<f64>>,
    (usize, usize),
    Bound<'py, PyArray1<f64>>,
);

/// The hemisphere map of a material (`polbrdf_tasks::hemisphere`), as `polbrdf map` runs it.
#[pyfunction]
#[pyo3(signature = (material, light, spectral, grid_deg))]
pub(crate) fn hemisphere_task<'py>(
    py: Python<'py>,
    material: String,
    light: Light,
    spectral: Spectral,
    grid_deg: Option<(f64, f64)>,
) -> PyResult<HemisphereOut<'py>> {
    let request = HemisphereRequest {
        material,
        light: light_request(light),
        grid_deg: grid_deg.unwrap_or(DEFAULT_GRID_DEG),
        spectral: spectral_request(spectral),
    };
    let map = py
        .detach(|| hemisphere(&request))
        .map_err(|e| task_err(py, &e))?;
    let columns = Hemisphere::COLUMNS.to_vec();
    let rows: Vec<Vec<f64>> = map.rows().collect();
    let shape = grid_shape(rows.len(), &rows);
    let invalid = zeniths_deg(py, &map.invalid_zeniths);
    Ok((
        columns,
        table(py, rows, Hemisphere::COLUMNS.len()),
        shape,
        invalid,
    ))
}

/// What [`albedo_task`] returns: the columns of `polbrdf albedo --output` but the last
/// (`theta_i_deg`, `albedo`, `surface`, `volume`), one entry per incidence angle.
type AlbedoOut<'py> = (
    Bound<'py, PyArray1<f64>>,
    Bound<'py, PyArray1<f64>>,
    Bound<'py, PyArray1<f64>>,
    Bound<'py, PyArray1<f64>>,
);

/// The directional–hemispherical reflectance of a material (`polbrdf_tasks::albedo`), as
/// `polbrdf albedo` runs it; an empty `theta_i_deg` takes the task's default angles.
#[pyfunction]
#[pyo3(signature = (material, theta_i_deg, spectral))]
pub(crate) fn albedo_task<'py>(
    py: Python<'py>,
    material: String,
    theta_i_deg: Vec<f64>,
    spectral: Spectral,
) -> PyResult<AlbedoOut<'py>> {
    let request = AlbedoRequest {
        material,
        theta_i_deg,
        spectral: spectral_request(spectral),
    };
    let t = py
        .detach(|| albedo(&request))
        .map_err(|e| task_err(py, &e))?;
    let column =
        |f: &dyn Fn(&(f64, Albedo)) -> f64| PyArray1::from_vec(py, t.rows.iter().map(f).collect());
    Ok((
        column(&|r| r.0),
        column(&|r| r.1.total()),
        column(&|r| r.1.surface),
        column(&|r| r.1.volume),
    ))
}

/// The sun's position (`polbrdf_tasks::sun`), as `polbrdf sun` prints it: the JSON document.
#[pyfunction]
#[pyo3(signature = (date_time, latitude_deg, longitude_deg, elevation_m, pressure_hpa,
    temperature_c, delta_t_s, phi0_azimuth_deg))]
#[allow(clippy::too_many_arguments)] // One per keyword of `polbrdf.sun_position`, all plain values.
pub(crate) fn sun_task(
    py: Python<'_>,
    date_time: String,
    latitude_deg: f64,
    longitude_deg: f64,
    elevation_m: Option<f64>,
    pressure_hpa: Option<f64>,
    temperature_c: Option<f64>,
    delta_t_s: Option<f64>,
    phi0_azimuth_deg: Option<f64>,
) -> PyResult<String> {
    let request = polbrdf_tasks::sun::SunRequest {
        date_time,
        latitude_deg,
        longitude_deg,
        elevation_m,
        pressure_hpa,
        temperature_c,
        delta_t_s,
        phi0_azimuth_deg,
    };
    let report = polbrdf_tasks::sun::sun(&request).map_err(|e| task_err(py, &e))?;
    serde_json::to_string(&report.to_json()).map_err(|e| PyValueError::new_err(e.to_string()))
}
