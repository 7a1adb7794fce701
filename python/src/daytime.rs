//! The time-of-day sweep (`polbrdf_tasks::daytime`, docs/sun-position.md) for Python: builds
//! the task's request from what `polbrdf.daytime` hands over (the task's defaults where it
//! gives none, as the CLI's), runs it with the GIL released and returns `daytime.csv`'s
//! columns as NumPy arrays: the numbers of `polbrdf daytime`, bit for bit. Nothing here
//! computes.

use crate::detect::scene_source;
use crate::tasks::task_err;
use numpy::ndarray::Array2;
use numpy::{IntoPyArray, PyArray2};
use polbrdf_tasks::daytime::{daytime, time_range, DaytimeDetect, DaytimeRequest, DEFAULT_TIMES};
use polbrdf_tasks::detect::SensorSource;
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

/// The range of local times `(from, to, step_min)`, each `None` taking the task's default.
type TimeRange = (Option<String>, Option<String>, Option<f64>);

/// A time-of-day sweep (`polbrdf_tasks::daytime`), as `polbrdf daytime` runs it: `times`, or
/// the range of local times; with `sensor`, the detection ranges too. Every `None` takes the
/// task's default ([`DaytimeRequest::new`], [`DaytimeDetect::new`], [`DEFAULT_TIMES`]).
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
    range: TimeRange,
    grid_deg: Option<(f64, f64)>,
    fixed_view_deg: Option<(f64, f64)>,
    criteria: Criteria,
) -> PyResult<DaytimeOut<'py>> {
    let times = match times {
        Some(t) => t,
        None => time_range(
            range.0.as_deref().unwrap_or(DEFAULT_TIMES.0),
            range.1.as_deref().unwrap_or(DEFAULT_TIMES.1),
            range.2.unwrap_or(DEFAULT_TIMES.2),
        )
        .map_err(|e| task_err(py, &e))?,
    };
    let (area_m2, pfa, pd, range_limit_m) = criteria;
    let mut request = DaytimeRequest::new(scene_source(scene_file, scene_text)?, times);
    request.detect = sensor.map(|s| {
        let mut d = DaytimeDetect::new(SensorSource::File(s));
        let t = &mut d.template;
        t.area_m2 = area_m2.unwrap_or(t.area_m2);
        t.pfa = pfa.unwrap_or(t.pfa);
        t.pd = pd.unwrap_or(t.pd);
        t.range_limit_m = range_limit_m.unwrap_or(t.range_limit_m);
        d
    });
    request.target = target;
    request.background = background;
    request.date = date;
    request.grid_deg = grid_deg.unwrap_or(request.grid_deg);
    request.fixed_view_deg = fixed_view_deg.unwrap_or(request.fixed_view_deg);
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
