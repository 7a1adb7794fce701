//! The time-of-day sweep (docs/sun-position.md): a scene whose `[sun]` is placed by date, time
//! and place, moved through a list of local clock times on one date; at each time (a) the
//! contrast study's best view and the contrast at a fixed view, and (b) with a sensor, the
//! detection range of the best view and at the fixed view (`polbrdf_tasks::detect`).
//!
//! The sweep itself ([`sweep`]) is generic over what is evaluated at each time: a closure of
//! the scene at that time. A time with the sun at or below the horizon is evaluated without the
//! sun (night: emission and the sky only), except under the `cie-clear` sky, which the sun
//! sets: such a row is reported with its sun position and no evaluation (NaN).

use crate::contrast::{contrast, ContrastRequest, RankRequest, SourceRequest};
use crate::detect::out::max_range_value;
use crate::detect::{detect, DetectRequest, SceneSource, SensorSource, Views};
use crate::error::{TaskError, TaskResult};
use crate::scene::Warning;
use crate::sun::field_error;
use polbrdf::analysis::contrast::ContrastSample;
use polbrdf::analysis::detection::MaxRange;
use polbrdf::analysis::sun_position::{CivilTime, SunPosition, SunTime};
use polbrdf::analysis::SkyModel;
use polbrdf_io::date_time::{at_clock, parse_clock, parse_date};
use polbrdf_io::Scene;

/// The default grid of a sweep, `(Δθ, Δφ)` in degrees: coarser than a single study's 1°×2°,
/// since every time of the sweep is a full study (a clear sky costs about 1 ms per view and
/// material).
pub const DAYTIME_GRID_DEG: (f64, f64) = (5.0, 10.0);

/// The local times of a sweep given none, `(from, to, step in minutes)`: 06:00 to 18:00 every
/// 30 minutes ([`time_range`]).
pub const DEFAULT_TIMES: (&str, &str, f64) = ("06:00", "18:00", 30.0);

/// The fixed view of a sweep given none, `(θr, φr)` in degrees: nadir.
pub const DEFAULT_FIXED_VIEW_DEG: (f64, f64) = (0.0, 0.0);

/// The most times one sweep takes (one a minute over a day).
pub const MAX_TIMES: usize = 1441;

/// The scene at one time of the sweep.
#[derive(Debug, Clone)]
pub struct SceneAt {
    /// The instant (local clock, the scene's UTC offset).
    pub time: CivilTime,
    /// Where the sun is.
    pub position: SunPosition,
    /// The sun's azimuth in the surface frame, degrees.
    pub sun_phi_deg: f64,
    /// The scene with its sun at that time (no sun when it is down), or `None` when it cannot
    /// be evaluated (the sun down under a `cie-clear` sky).
    pub scene: Option<Scene>,
}

/// The scene's date, time, place and frame, or the error saying the sweep needs them.
fn sun_time_of(scene: &Scene) -> TaskResult<SunTime> {
    scene.sun_time.ok_or_else(|| {
        TaskError::usage(
            "scene",
            format!(
                "{}: a time-of-day sweep needs the sun placed by date and place: give [sun] \
                 date_time, latitude_deg and longitude_deg (and irradiance)",
                scene.path.display()
            ),
        )
    })
}

/// The scene with its sun placed at `time` (see [`SceneAt`]).
///
/// # Errors
/// [`TaskError::Invalid`] naming the sun's key when SPA refuses the time.
pub fn scene_at(scene: &Scene, time: CivilTime) -> TaskResult<SceneAt> {
    let sun_time = sun_time_of(scene)?.at(time);
    let (position, direction) = sun_time.surface_direction().map_err(field_error)?;
    let mut s = scene.clone();
    s.sun_time = Some(sun_time);
    let evaluable = match direction {
        Some((zenith, azimuth)) => {
            let sun = s
                .thermal
                .sun
                .as_mut()
                .expect("a scene with a sun time has a sun");
            sun.zenith = zenith;
            sun.azimuth = azimuth;
            true
        }
        None => {
            s.thermal.sun = None;
            !matches!(s.thermal.sky, SkyModel::ClearSky { .. })
        }
    };
    Ok(SceneAt {
        time,
        position,
        sun_phi_deg: position.phi_deg(sun_time.phi0_azimuth_deg),
        scene: evaluable.then_some(s),
    })
}

/// The local times of a sweep: `date` (`YYYY-MM-DD`; `None`: the scene's) at each clock time
/// (`HH:MM[:SS]`), on the scene's UTC offset.
///
/// # Errors
/// [`TaskError::Invalid`] naming `date` or `times`; [`TaskError::Usage`] naming `scene` when
/// its sun is not placed by date and place.
pub fn times_of(scene: &Scene, date: Option<&str>, times: &[String]) -> TaskResult<Vec<CivilTime>> {
    let base = sun_time_of(scene)?.time;
    let day = match date {
        Some(d) => parse_date(d).map_err(|m| TaskError::invalid("date", m))?,
        None => (base.year, base.month, base.day),
    };
    if times.is_empty() {
        return Err(TaskError::usage("times", "give at least one time of day"));
    }
    if times.len() > MAX_TIMES {
        return Err(TaskError::invalid(
            "times",
            format!("{} times: at most {MAX_TIMES} (one a minute)", times.len()),
        ));
    }
    times
        .iter()
        .map(|t| {
            let s = parse_clock(t).map_err(|m| TaskError::invalid("times", m))?;
            Ok(at_clock(&base, day, s))
        })
        .collect()
}

/// Clock times from `from` to `to` (inclusive, `HH:MM`) every `step_min` minutes, as
/// `HH:MM:SS` text for [`times_of`].
///
/// # Errors
/// [`TaskError::Invalid`] naming `from`, `to` or `step_min`.
pub fn time_range(from: &str, to: &str, step_min: f64) -> TaskResult<Vec<String>> {
    let a = parse_clock(from).map_err(|m| TaskError::invalid("from", m))?;
    let b = parse_clock(to).map_err(|m| TaskError::invalid("to", m))?;
    if b < a {
        return Err(TaskError::invalid(
            "to",
            format!("{to} is before `from` ({from}): a sweep stays within one date"),
        ));
    }
    if !(step_min.is_finite() && step_min >= 1.0 / 60.0) {
        return Err(TaskError::invalid(
            "step_min",
            format!("{step_min}: must be finite and at least 1 s (1/60 min)"),
        ));
    }
    let n = ((b - a) / (step_min * 60.0) + 1e-9).floor() as usize + 1;
    if n > MAX_TIMES {
        return Err(TaskError::invalid(
            "step_min",
            format!("{step_min} min from {from} to {to} is {n} times: at most {MAX_TIMES}"),
        ));
    }
    Ok((0..n)
        .map(|k| {
            let s = a + k as f64 * step_min * 60.0;
            let whole = s.floor() as u32;
            format!(
                "{:02}:{:02}:{:02}",
                whole / 3600,
                whole / 60 % 60,
                whole % 60
            )
        })
        .collect())
}

/// One time of a sweep: the scene there and what was evaluated (`None`: not evaluable).
#[derive(Debug, Clone)]
pub struct SweepRow<T> {
    /// The scene at that time.
    pub at: SceneAt,
    /// The evaluation.
    pub value: Option<T>,
}

/// Moves the scene's sun through `times` and evaluates `eval` on each evaluable scene.
///
/// # Errors
/// As [`scene_at`], and the first error of `eval`.
pub fn sweep<T>(
    scene: &Scene,
    times: &[CivilTime],
    mut eval: impl FnMut(&Scene) -> TaskResult<T>,
) -> TaskResult<Vec<SweepRow<T>>> {
    times
        .iter()
        .map(|t| {
            let at = scene_at(scene, *t)?;
            let value = at.scene.as_ref().map(&mut eval).transpose()?;
            Ok(SweepRow { at, value })
        })
        .collect()
}

/// The detection side of a sweep: a sensor and the detection criteria (as `polbrdf detect`'s
/// request; its scene, views and sun are the sweep's).
#[derive(Debug, Clone, PartialEq)]
pub struct DaytimeDetect {
    /// The request's sensor, target area, criteria, features and range limit.
    pub template: DetectRequest,
}

impl DaytimeDetect {
    /// Detection with `sensor` and `polbrdf detect`'s defaults ([`DetectRequest::new`]).
    pub fn new(sensor: SensorSource) -> Self {
        Self {
            template: DetectRequest::new(SceneSource::File(std::path::PathBuf::new()), sensor),
        }
    }
}

/// A time-of-day sweep ([`DaytimeRequest::new`] has the adapters' defaults).
#[derive(Debug, Clone, PartialEq)]
pub struct DaytimeRequest {
    /// The scene (its `[sun]` placed by `date_time`).
    pub scene: SceneSource,
    /// The target material, replacing the scene's.
    pub target: Option<String>,
    /// The background material, replacing the scene's.
    pub background: Option<String>,
    /// The date `YYYY-MM-DD` (`None`: the scene's `date_time`'s).
    pub date: Option<String>,
    /// Local clock times `HH:MM[:SS]` on the scene's UTC offset ([`time_range`] makes a range).
    pub times: Vec<String>,
    /// The grid `(Δθ, Δφ)`, degrees, of both the contrast study and the detection views.
    pub grid_deg: (f64, f64),
    /// The contrast's ranking (the best view is its first).
    pub rank: RankRequest,
    /// The fixed view `(θr, φr)`, degrees.
    pub fixed_view_deg: (f64, f64),
    /// Detection with a sensor; `None`: contrast only.
    pub detect: Option<DaytimeDetect>,
}

impl DaytimeRequest {
    /// The sweep of `scene` at `times` that `polbrdf daytime` and `polbrdf.daytime` make
    /// without further options: the scene's materials and date, the [`DAYTIME_GRID_DEG`] grid,
    /// the best view the best grid node (not refined: refining costs a sky integral per trial
    /// view under a clear sky, at every time), the fixed view [`DEFAULT_FIXED_VIEW_DEG`], no
    /// sensor.
    pub fn new(scene: SceneSource, times: Vec<String>) -> Self {
        Self {
            scene,
            target: None,
            background: None,
            date: None,
            times,
            grid_deg: DAYTIME_GRID_DEG,
            rank: RankRequest {
                refine: false,
                ..RankRequest::default()
            },
            fixed_view_deg: DEFAULT_FIXED_VIEW_DEG,
            detect: None,
        }
    }
}

/// With a sensor: the view of the longest detection range, `(θr, φr)` in radians, its range,
/// and the range at the fixed view.
pub type DaytimeDetection = ((f64, f64), Option<MaxRange>, Option<MaxRange>);

/// What one time of a sweep gives.
#[derive(Debug, Clone, PartialEq)]
pub struct DaytimeValue {
    /// The contrast study's best view.
    pub best: ContrastSample,
    /// The contrast at the fixed view.
    pub fixed: ContrastSample,
    /// With a sensor: see [`DaytimeDetection`].
    pub detection: Option<DaytimeDetection>,
    /// With a sensor: the views of the grid where the camera saturates
    /// ([`crate::detect::DetectStudy::view_saturated`]).
    pub saturated_views: usize,
    /// The setup warnings of the contrast and detection studies at this time, without
    /// saturation.
    pub warnings: Vec<Warning>,
}

/// The result of [`daytime`].
#[derive(Debug, Clone)]
pub struct DaytimeStudy {
    /// The scene as read.
    pub scene: Box<Scene>,
    /// The request (for the fixed view and whether a sensor was given).
    pub request: DaytimeRequest,
    /// One row per time.
    pub rows: Vec<SweepRow<DaytimeValue>>,
    /// The setup warnings ([`DaytimeValue::warnings`] of every time, once each, and the times
    /// at which the camera saturates).
    pub warnings: Vec<Warning>,
}

/// The contrast and detection of one scene.
fn evaluate(request: &DaytimeRequest, scene: &Scene) -> TaskResult<DaytimeValue> {
    let study = contrast(&ContrastRequest {
        target: request.target.clone(),
        background: request.background.clone(),
        source: SourceRequest::Loaded(Box::new(scene.clone())),
        grid_deg: request.grid_deg,
        rank: request.rank,
    })?;
    let (ft, fp) = request.fixed_view_deg;
    let fixed = study.problem.at(ft.to_radians(), fp.to_radians());
    let best = *study
        .top
        .first()
        .expect("a ranking lists at least one view");
    let mut warnings = study.warnings;
    let mut saturated_views = 0;
    let detection = match &request.detect {
        None => None,
        Some(d) => {
            let run = |views: Views| {
                detect(&DetectRequest {
                    scene: SceneSource::Loaded(Box::new(scene.clone())),
                    target: request.target.clone(),
                    background: request.background.clone(),
                    views,
                    sun_deg: None,
                    search: true,
                    ..d.template.clone()
                })
            };
            let grid = run(Views::Grid(request.grid_deg))?;
            warnings.extend(crate::detect::warnings::setup_warnings(&grid));
            saturated_views = grid.saturated_views().len();
            let top = grid.ranked()[0];
            let at_fixed = run(Views::List(vec![request.fixed_view_deg]))?;
            Some((
                (top.theta_r, top.phi_r),
                top.max_range,
                at_fixed.views[0].max_range,
            ))
        }
    };
    Ok(DaytimeValue {
        best,
        fixed,
        detection,
        saturated_views,
        warnings,
    })
}

/// The warnings of a sweep: each setup warning of its times once, in order, and one line for
/// the times at which the camera saturates.
fn sweep_warnings(request: &DaytimeRequest, rows: &[SweepRow<DaytimeValue>]) -> Vec<Warning> {
    let mut out: Vec<Warning> = Vec::new();
    for w in rows
        .iter()
        .filter_map(|r| r.value.as_ref())
        .flat_map(|v| &v.warnings)
    {
        if !out.contains(w) {
            out.push(w.clone());
        }
    }
    let saturated: Vec<&SweepRow<DaytimeValue>> = rows
        .iter()
        .filter(|r| r.value.as_ref().is_some_and(|v| v.saturated_views > 0))
        .collect();
    if let (Some(first), Some(d)) = (saturated.first(), &request.detect) {
        let sensor = match &d.template.sensor {
            SensorSource::File(p) => p.display().to_string(),
            SensorSource::Loaded(s) => s.path.display().to_string(),
        };
        out.push(Warning {
            message: format!(
                "{sensor}: a channel saturates (beyond full_well_e) at some views at {} of {} \
                 times (the first at {}, {} views): the detection ranges there assume a linear \
                 response the camera does not have; a shorter integration_time_ms or a larger \
                 f_number avoids it",
                saturated.len(),
                rows.len(),
                polbrdf_io::date_time::format_date_time(&first.at.time),
                first.value.as_ref().map_or(0, |v| v.saturated_views),
            ),
        });
    }
    out
}

/// Runs a time-of-day sweep. The request is checked (scene, date, times, fixed view, and the
/// first time's studies) before the rest is computed.
///
/// # Errors
/// [`TaskError::Usage`] naming `scene` when its sun is not placed by date and place;
/// [`TaskError::Invalid`] naming `date`, `times` or `fixed_view_deg`; as
/// [`crate::contrast::contrast`] and [`crate::detect::detect`].
pub fn daytime(request: &DaytimeRequest) -> TaskResult<DaytimeStudy> {
    let scene = match &request.scene {
        SceneSource::File(p) => crate::scene::read_scene(p)?,
        SceneSource::Loaded(s) => (**s).clone(),
    };
    let times = times_of(&scene, request.date.as_deref(), &request.times)?;
    let (ft, fp) = request.fixed_view_deg;
    if !(ft.is_finite() && (0.0..90.0).contains(&ft) && fp.is_finite()) {
        return Err(TaskError::invalid(
            "fixed_view_deg",
            format!("({ft}, {fp}): the view zenith must lie in [0, 90) and the azimuth be finite"),
        ));
    }
    // The sensor file read once, not once per time.
    let detect = match request.detect.clone() {
        Some(mut d) => {
            if let SensorSource::File(p) = &d.template.sensor {
                d.template.sensor = SensorSource::Loaded(Box::new(polbrdf_io::read_sensor(p)?));
            }
            Some(d)
        }
        None => None,
    };
    let request = DaytimeRequest {
        detect,
        ..request.clone()
    };
    let rows = sweep(&scene, &times, |s| evaluate(&request, s))?;
    let warnings = sweep_warnings(&request, &rows);
    Ok(DaytimeStudy {
        scene: Box::new(scene),
        request,
        rows,
        warnings,
    })
}

/// The columns of `daytime.csv` after `date_time` (every one a number; NaN where a time was
/// not evaluated), without and with a sensor.
pub const COLUMNS: [&str; 11] = [
    "local_time_h",
    "sun_zenith_deg",
    "sun_azimuth_deg",
    "sun_phi_deg",
    "sun_up",
    "best_theta_r_deg",
    "best_phi_r_deg",
    "best_delta_dolp",
    "best_polarization_contrast",
    "fixed_delta_dolp",
    "fixed_polarization_contrast",
];

/// The detection columns of `daytime.csv` (with a sensor): the view of the longest detection
/// range, that range, and the range at the fixed view; a range is `inf` beyond the search's
/// limit and 0 when not detectable.
pub const DETECT_COLUMNS: [&str; 4] = [
    "range_theta_r_deg",
    "range_phi_r_deg",
    "best_max_range_m",
    "fixed_max_range_m",
];

/// A detection range as a number: `inf` beyond the limit, 0 when not detectable.
fn range_number(m: Option<MaxRange>) -> f64 {
    match m {
        Some(MaxRange::NotDetectable) => 0.0,
        other => max_range_value(other),
    }
}

impl DaytimeStudy {
    /// The column names after `date_time`.
    pub fn columns(&self) -> Vec<&'static str> {
        let mut c = COLUMNS.to_vec();
        if self.request.detect.is_some() {
            c.extend(DETECT_COLUMNS);
        }
        c
    }

    /// The numbers of each row, in the order of [`Self::columns`].
    pub fn rows(&self) -> impl Iterator<Item = Vec<f64>> + '_ {
        let deg = f64::to_degrees;
        let with_detect = self.request.detect.is_some();
        self.rows.iter().map(move |r| {
            let t = &r.at.time;
            let p = &r.at.position;
            let hours = f64::from(t.hour) + f64::from(t.minute) / 60.0 + t.second / 3600.0;
            let mut row = vec![
                hours,
                p.zenith_deg,
                p.azimuth_deg,
                r.at.sun_phi_deg,
                if p.is_up() { 1.0 } else { 0.0 },
            ];
            let nan = f64::NAN;
            match &r.value {
                Some(v) => row.extend([
                    deg(v.best.theta_r),
                    deg(v.best.phi_r),
                    v.best.delta_dolp(),
                    v.best.polarization_contrast(),
                    v.fixed.delta_dolp(),
                    v.fixed.polarization_contrast(),
                ]),
                None => row.extend([nan; 6]),
            }
            if with_detect {
                match r.value.as_ref().and_then(|v| v.detection) {
                    Some(((theta, phi), best, fixed)) => row.extend([
                        deg(theta),
                        deg(phi),
                        range_number(best),
                        range_number(fixed),
                    ]),
                    None => row.extend([nan; 4]),
                }
            }
            row
        })
    }

    /// The local date-times of the rows (RFC 3339 with the offset).
    pub fn date_times(&self) -> Vec<String> {
        self.rows
            .iter()
            .map(|r| polbrdf_io::date_time::format_date_time(&r.at.time))
            .collect()
    }

    /// `daytime.csv`: `date_time`, then [`Self::columns`] at full precision.
    pub fn csv(&self) -> Vec<u8> {
        let mut header = vec!["date_time"];
        header.extend(self.columns());
        let mut t = polbrdf_io::CsvTable::new(&header);
        for (dt, row) in self.date_times().into_iter().zip(self.rows()) {
            t.fields(std::iter::once(dt).chain(row.into_iter().map(polbrdf_io::csv_io::fmt_f64)));
        }
        t.into_bytes()
    }
}
