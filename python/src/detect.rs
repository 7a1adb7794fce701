//! Detection (`polbrdf_tasks::detect`, docs/detection.md) for Python: builds the task's request
//! from what `polbrdf.detect` hands over, runs it with the GIL released and returns the rows of
//! `detect.csv` as NumPy arrays, `best.json` as JSON text and, when asked, the simulated frame
//! of `polbrdf detect --frame` (`polbrdf_tasks::frame::of_study`): the numbers of the CLI, bit
//! for bit. Nothing here computes.

use crate::errors::io_err;
use crate::tasks::task_err;
use numpy::ndarray::Array2;
use numpy::{IntoPyArray, PyArray1};
use polbrdf::analysis::detection::frame::Frame;
use polbrdf::analysis::detection::Feature;
use polbrdf_tasks::detect::{detect, DetectRequest, SceneSource, SensorSource, Views};
use polbrdf_tasks::detect_out::{max_range_text, COLUMNS};
use pyo3::exceptions::PyValueError;
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

/// A detection study (`polbrdf_tasks::detect`), as `polbrdf detect` runs it; with
/// `frame_seed`, also its simulated frame (`polbrdf detect --frame --seed`). Returns a dict:
/// `columns`, `values` (rows × the numeric columns up to `pd`), `feature`, `saturated`,
/// `max_range_text`, `max_range_feature` (per row), `max_range_m` (per view), `grid`
/// (`(zeniths, azimuths)` or `None`), `best` (JSON text), `warnings` and `frame`.
#[pyfunction]
#[pyo3(signature = (scene_file, scene_text, sensor, target, background, grid_deg, views,
    ranges_m, search, range_limit_m, area_m2, pfa, pd, features, sun_deg, frame_seed))]
#[allow(clippy::too_many_arguments)] // One per keyword of `polbrdf.detect`, all plain values.
pub(crate) fn detect_task<'py>(
    py: Python<'py>,
    scene_file: Option<PathBuf>,
    scene_text: Option<(String, String)>,
    sensor: PathBuf,
    target: Option<String>,
    background: Option<String>,
    grid_deg: Option<(f64, f64)>,
    views: Option<Vec<(f64, f64)>>,
    ranges_m: Vec<f64>,
    search: bool,
    range_limit_m: f64,
    area_m2: f64,
    pfa: f64,
    pd: f64,
    features: Vec<String>,
    sun_deg: Option<(f64, f64)>,
    frame_seed: Option<u64>,
) -> PyResult<Bound<'py, PyDict>> {
    let request = DetectRequest {
        scene: scene_source(scene_file, scene_text)?,
        sensor: SensorSource::File(sensor),
        target,
        background,
        views: match views {
            Some(list) => Views::List(list),
            None => Views::Grid(grid_deg.unwrap_or(polbrdf_tasks::hemisphere::DEFAULT_GRID_DEG)),
        },
        ranges_m,
        search,
        range_limit_m,
        area_m2,
        pfa,
        pd,
        features: features_of(py, &features)?,
        sun_deg,
    };
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
    d.set_item(
        "values",
        Array2::from_shape_vec((rows.len(), 11), values)
            .expect("every row has 11 values")
            .into_pyarray(py),
    )?;
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
