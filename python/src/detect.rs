//! Detection (`polbrdf_tasks::detect`, docs/detection.md) for Python: builds the task's request
//! from what `polbrdf.detect` hands over, runs it with the GIL released and returns the rows of
//! `detect.csv` as NumPy arrays, `best.json` as JSON text and, when asked, the simulated frame
//! of `polbrdf detect --frame` (`polbrdf_tasks::frame::of_study`): the numbers of the CLI, bit
//! for bit. Nothing here computes.

use crate::errors::io_err;
use crate::fit::PyFitResult;
use crate::tasks::task_err;
use numpy::ndarray::Array2;
use numpy::{IntoPyArray, PyArray1};
use polbrdf::analysis::detection::frame::Frame;
use polbrdf::analysis::detection::Feature;
use polbrdf_tasks::detect::out::{max_range_text, COLUMNS, NUMERIC, UNCERTAINTY_COLUMNS};
use polbrdf_tasks::detect::{detect, DetectRequest, FitSource, SceneSource, SensorSource, Views};
use polbrdf_tasks::fit_covariance::FitCovariance;
use pyo3::exceptions::{PyTypeError, PyValueError};
use pyo3::prelude::*;
use pyo3::types::PyDict;
use std::path::{Path, PathBuf};

/// A `ValueError` naming the keyword `field` (also as the exception's `argument`).
fn invalid(py: Python<'_>, field: &str, message: String) -> PyErr {
    let err = PyValueError::new_err(format!("invalid `{field}`: {message}"));
    let _ = err.value(py).setattr("argument", field);
    err
}

/// The scene: a file, or a scene's text read as from a file named by its second element.
pub(crate) fn scene_source(
    file: Option<PathBuf>,
    text: Option<(String, String)>,
) -> PyResult<SceneSource> {
    match (file, text) {
        (Some(path), None) => Ok(SceneSource::File(path)),
        (None, Some((text, source))) => Ok(SceneSource::Loaded(Box::new(
            polbrdf_io::parse_scene(&text, Path::new(&source)).map_err(|e| io_err(&e))?,
        ))),
        _ => Err(PyValueError::new_err(
            "give exactly one of a scene file or a scene",
        )),
    }
}

/// The features by name (`s0`, `dolp`, `s0+dolp`).
fn features_of(py: Python<'_>, names: &[String]) -> PyResult<Vec<Feature>> {
    names
        .iter()
        .map(|f| {
            Feature::parse(f).ok_or_else(|| {
                invalid(
                    py,
                    "features",
                    format!(
                        "unknown feature {f:?} (known: {})",
                        polbrdf::names::quoted(&Feature::ALL, Feature::as_str)
                    ),
                )
            })
        })
        .collect()
}

/// The frame's arrays by name, shaped (`raw_counts` and `raw_saturated` `2·side × 2·side`,
/// the images `side × side`), with its sizes.
fn frame_dict<'py>(py: Python<'py>, f: Frame, pixels: f64) -> PyResult<Bound<'py, PyDict>> {
    let d = PyDict::new(py);
    let shaped = |n: usize, v: Vec<f64>| {
        Array2::from_shape_vec((n, n), v)
            .expect("a frame's arrays are square")
            .into_pyarray(py)
    };
    let (raw, n) = (2 * f.side, f.side);
    d.set_item(
        "raw_saturated",
        Array2::from_shape_vec((raw, raw), f.raw_saturated)
            .expect("a frame's arrays are square")
            .into_pyarray(py),
    )?;
    d.set_item("raw_counts", shaped(raw, f.raw_counts))?;
    d.set_item("s0", shaped(n, f.s0))?;
    d.set_item("s1", shaped(n, f.s1))?;
    d.set_item("s2", shaped(n, f.s2))?;
    d.set_item("dolp", shaped(n, f.dolp))?;
    d.set_item("aolp_deg", shaped(n, f.aolp_deg))?;
    d.set_item("side", f.side)?;
    d.set_item("target_side", f.target_side)?;
    d.set_item("pixels_on_target", pixels)?;
    Ok(d)
}

/// A material's fit as `polbrdf.detect` takes it: a `FitResult`, or the path of a `fit.json`.
fn fit_source(
    py: Python<'_>,
    field: &str,
    fit: Option<&Bound<'_, PyAny>>,
) -> PyResult<Option<FitSource>> {
    let Some(fit) = fit else {
        return Ok(None);
    };
    if let Ok(r) = fit.cast::<PyFitResult>() {
        let f = FitCovariance::from_fit(r.get().result()).map_err(|e| task_err(py, &e))?;
        return Ok(Some(FitSource::Loaded(Box::new(f))));
    }
    match fit.extract::<PathBuf>() {
        Ok(path) => Ok(Some(FitSource::File(path))),
        Err(_) => Err(PyTypeError::new_err(format!(
            "`{field}` must be a polbrdf.FitResult or the path of a fit.json, not {}",
            fit.get_type().name()?
        ))),
    }
}

/// `uncertainty_views`: a number of views, or `"all"`.
fn uncertainty_views(py: Python<'_>, v: &Bound<'_, PyAny>) -> PyResult<Option<usize>> {
    if let Ok(text) = v.extract::<String>() {
        if text == "all" {
            return Ok(None);
        }
    } else if let Ok(n) = v.extract::<usize>() {
        if n > 0 && !v.is_instance_of::<pyo3::types::PyBool>() {
            return Ok(Some(n));
        }
    }
    Err(invalid(
        py,
        "uncertainty_views",
        format!("{}: expected a number of views ≥ 1 or \"all\"", v.repr()?),
    ))
}

/// What `polbrdf.detect` hands over besides the scene, the sensor and the frame's seed, each
/// `None` (or empty) taking the task's default ([`DetectRequest::new`]).
#[derive(FromPyObject)]
#[pyo3(from_item_all)]
pub(crate) struct DetectOptions<'py> {
    target: Option<String>,
    background: Option<String>,
    grid_deg: Option<(f64, f64)>,
    theta_deg: Option<Vec<f64>>,
    phi_deg: Option<Vec<f64>>,
    ranges_m: Option<Vec<f64>>,
    no_search: bool,
    range_limit_m: Option<f64>,
    area_m2: Option<f64>,
    pfa: Option<f64>,
    pd: Option<f64>,
    features: Option<Vec<String>>,
    sun_deg: Option<(f64, f64)>,
    target_fit: Option<Bound<'py, PyAny>>,
    background_fit: Option<Bound<'py, PyAny>>,
    uncertainty_views: Option<Bound<'py, PyAny>>,
}

/// The task's request: [`DetectRequest::new`] with what was given.
fn request_of(
    py: Python<'_>,
    scene: SceneSource,
    sensor: PathBuf,
    o: &DetectOptions<'_>,
) -> PyResult<DetectRequest> {
    let mut r = DetectRequest::new(scene, SensorSource::File(sensor));
    match (&o.theta_deg, o.grid_deg) {
        (Some(theta), _) => r.views = Views::listed(theta, o.phi_deg.as_deref().unwrap_or(&[])),
        (None, Some(g)) => r.views = Views::Grid(g),
        (None, None) => {}
    }
    if let Some(ranges) = &o.ranges_m {
        r.ranges_m.clone_from(ranges);
    }
    if let Some(f) = &o.features {
        r.features = features_of(py, f)?;
    }
    r.target.clone_from(&o.target);
    r.background.clone_from(&o.background);
    r.search = !o.no_search;
    r.range_limit_m = o.range_limit_m.unwrap_or(r.range_limit_m);
    r.area_m2 = o.area_m2.unwrap_or(r.area_m2);
    r.pfa = o.pfa.unwrap_or(r.pfa);
    r.pd = o.pd.unwrap_or(r.pd);
    r.sun_deg = o.sun_deg;
    r.target_fit = fit_source(py, "target_fit", o.target_fit.as_ref())?;
    r.background_fit = fit_source(py, "background_fit", o.background_fit.as_ref())?;
    if let Some(v) = &o.uncertainty_views {
        r.uncertainty_views = uncertainty_views(py, v)?;
    }
    Ok(r)
}

/// A detection study (`polbrdf_tasks::detect`), as `polbrdf detect` runs it; with
/// `frame_seed`, also its simulated frame (`polbrdf detect --frame --seed`). `options` is the
/// dict of `polbrdf.detect`'s keywords ([`DetectOptions`]). Returns a dict: `columns`,
/// `numeric_columns` and `values` (rows × those columns), `uncertainty_columns` and
/// `uncertainty` (rows × those, NaN where none), `feature`, `saturated`, `max_range_text`,
/// `max_range_feature` (per row), `max_range_m` (per view), `grid` (`(zeniths, azimuths)` or
/// `None`), `ranges_m` (the request's), `best` (JSON text), `warnings` and `frame`.
#[pyfunction]
#[pyo3(signature = (scene_file, scene_text, sensor, options, frame_seed))]
pub(crate) fn detect_task<'py>(
    py: Python<'py>,
    scene_file: Option<PathBuf>,
    scene_text: Option<(String, String)>,
    sensor: PathBuf,
    options: DetectOptions<'py>,
    frame_seed: Option<u64>,
) -> PyResult<Bound<'py, PyDict>> {
    let request = request_of(py, scene_source(scene_file, scene_text)?, sensor, &options)?;
    let (study, frame) = py
        .detach(|| {
            let study = detect(&request)?;
            let frame = frame_seed
                .map(|seed| polbrdf_tasks::frame::of_study(&study, None, seed))
                .transpose()?;
            Ok::<_, polbrdf_tasks::TaskError>((study, frame))
        })
        .map_err(|e| task_err(py, &e))?;
    let rows: Vec<_> = study.table_rows().collect();
    let values: Vec<f64> = rows.iter().flat_map(|r| r.values).collect();
    let d = PyDict::new(py);
    d.set_item("columns", COLUMNS.to_vec())?;
    d.set_item("numeric_columns", COLUMNS[..NUMERIC].to_vec())?;
    d.set_item(
        "values",
        Array2::from_shape_vec((rows.len(), NUMERIC), values)
            .expect("every row has its numeric values")
            .into_pyarray(py),
    )?;
    d.set_item("uncertainty_columns", UNCERTAINTY_COLUMNS.to_vec())?;
    let unc: Vec<f64> = rows.iter().flat_map(|r| r.uncertainty).collect();
    d.set_item(
        "uncertainty",
        Array2::from_shape_vec((rows.len(), UNCERTAINTY_COLUMNS.len()), unc)
            .expect("every row has its uncertainty")
            .into_pyarray(py),
    )?;
    d.set_item("ranges_m", study.ranges_m.clone())?;
    d.set_item(
        "feature",
        rows.iter().map(|r| r.feature).collect::<Vec<_>>(),
    )?;
    d.set_item(
        "saturated",
        PyArray1::from_vec(py, rows.iter().map(|r| r.saturated).collect()),
    )?;
    d.set_item(
        "max_range_text",
        rows.iter()
            .map(|r| max_range_text(r.max_range))
            .collect::<Vec<_>>(),
    )?;
    d.set_item(
        "max_range_feature",
        rows.iter().map(|r| r.max_range_feature).collect::<Vec<_>>(),
    )?;
    d.set_item("max_range_m", PyArray1::from_vec(py, study.max_ranges()))?;
    d.set_item(
        "grid",
        study.grid.as_ref().map(|g| (g.n_theta(), g.n_phi())),
    )?;
    let best = serde_json::to_string(&study.best_json())
        .map_err(|e| PyValueError::new_err(e.to_string()))?;
    d.set_item("best", best)?;
    let warnings: Vec<String> = study.warnings.iter().map(ToString::to_string).collect();
    d.set_item("warnings", warnings)?;
    match frame {
        Some(out) => d.set_item("frame", frame_dict(py, out.frame, out.pixels_on_target)?)?,
        None => d.set_item("frame", py.None())?,
    }
    Ok(d)
}
