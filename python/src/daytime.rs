//! The time-of-day sweep (`polbrdf_tasks::daytime`, docs/sun-position.md) for Python: builds
//! the task's request from what `polbrdf.daytime` hands over (with the CLI's defaults), runs it
//! with the GIL released and returns `daytime.csv`'s columns as NumPy arrays: the numbers of
//! `polbrdf daytime`, bit for bit. Nothing here computes.

use crate::detect::scene_source;
use crate::tasks::task_err;
use numpy::ndarray::Array2;
use numpy::{IntoPyArray, PyArray2};
use polbrdf_tasks::contrast::RankRequest;
use polbrdf_tasks::daytime::{
    daytime, time_range, DaytimeDetect, DaytimeRequest, DAYTIME_GRID_DEG,
};
use polbrdf_tasks::detect::{DetectRequest, SensorSource};
use pyo3::prelude::*;
use std::path::PathBuf;

/// The detection criteria of a sweep with a sensor: `(area_m2, pfa, pd, range_limit_m)`, each
/// `None` taking the task's default.
type Criteria = (Option<f64>, Option<f64>, Option<f64>, Option<f64>);

/// What [`daytime_task`] returns: the columns after `date_time`, the `date_time` of each row
/// (RFC 3339 with the offset), the table (one row per time) and the setup's warnings.
type DaytimeOut<'py> = (
    Vec<&'static str>,
    Vec<String>,
    Bound<'py, PyArray2<f64>>,
    Vec<String>,
);

/// A time-of-day sweep (`polbrdf_tasks::daytime`), as `polbrdf daytime` runs it: `times`, or
/// the range `(from, to, step_min)` of local times; with `sensor`, the detection ranges too.
#[pyfunction]
#[pyo3(signature = (scene_file, scene_text, sensor, target, background, date, times, range,
    grid_deg, fixed_view_deg, criteria))]
#[allow(clippy::too_many_arguments)] // One per keyword of `polbrdf.daytime`, all plain values.
pub(crate) fn daytime_task<'py>(
    py: Python<'py>,
    scene_file: Option<PathBuf>,
    scene_text: Option<(String, String)>,
    sensor: Option<PathBuf>,
    target: Option<String>,
    background: Option<String>,
    date: Option<String>,
    times: Option<Vec<String>>,
    range: (String, String, f64),
    grid_deg: Option<(f64, f64)>,
    fixed_view_deg: (f64, f64),
    criteria: Criteria,
) -> PyResult<DaytimeOut<'py>> {
    let times = match times {
        Some(t) => t,
        None => time_range(&range.0, &range.1, range.2).map_err(|e| task_err(py, &e))?,
    };
    let (area_m2, pfa, pd, range_limit_m) = criteria;
    let detect = sensor.map(|s| {
        let d = DetectRequest::default();
        DaytimeDetect {
            template: DetectRequest {
                sensor: SensorSource::File(s),
                area_m2: area_m2.unwrap_or(d.area_m2),
                pfa: pfa.unwrap_or(d.pfa),
                pd: pd.unwrap_or(d.pd),
                range_limit_m: range_limit_m.unwrap_or(d.range_limit_m),
                ..d
            },
        }
    });
    let request = DaytimeRequest {
        scene: scene_source(scene_file, scene_text)?,
        target,
        background,
        date,
        times,
        grid_deg: grid_deg.unwrap_or(DAYTIME_GRID_DEG),
        // As the CLI's: the best view is the best grid node (refining it costs a sky integral
        // per trial view under a clear sky, at every time).
        rank: RankRequest {
            refine: false,
            ..RankRequest::default()
        },
        fixed_view_deg,
        detect,
    };
    let study = py
        .detach(|| daytime(&request))
        .map_err(|e| task_err(py, &e))?;
    let columns = study.columns();
    let width = columns.len();
    let rows: Vec<f64> = study.rows().flatten().collect();
    let table = Array2::from_shape_vec((rows.len() / width.max(1), width), rows)
        .expect("every row has one value per column")
        .into_pyarray(py);
    let warnings = study.warnings.iter().map(ToString::to_string).collect();
    Ok((columns, study.date_times(), table, warnings))
}
