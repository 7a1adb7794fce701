//! The time-of-day sweep (docs/sun-position.md): the sun moved by SPA through the day, a row
//! equal to the study of the scene file written for that time, the best view never worse
//! than a fixed one, the night without the sun (or not evaluated under a clear sky), and the
//! request's validation.

use crate::common::{example, write};
use polbrdf_tasks::contrast::{contrast, ContrastRequest, RankRequest, SourceRequest};
use polbrdf_tasks::daytime::{daytime, time_range, DaytimeDetect, DaytimeRequest};
use polbrdf_tasks::detect::{DetectRequest, SceneSource, SensorSource};
use polbrdf_tasks::TaskError;

/// A fast ranking: no refinement (a clear sky costs a sky integral per refined view).
fn rank() -> RankRequest {
    RankRequest {
        refine: false,
        ..RankRequest::default()
    }
}

fn request(scene: SceneSource, times: &[&str]) -> DaytimeRequest {
    DaytimeRequest {
        scene,
        target: None,
        background: None,
        date: None,
        times: times.iter().map(|t| t.to_string()).collect(),
        grid_deg: (15.0, 30.0),
        rank: rank(),
        fixed_view_deg: (45.0, 180.0),
        detect: None,
    }
}

#[test]
fn clock_ranges() {
    let t = time_range("06:00", "18:00", 30.0).unwrap();
    assert_eq!(t.len(), 25);
    assert_eq!((t[0].as_str(), t[24].as_str()), ("06:00:00", "18:00:00"));
    assert_eq!(time_range("06:00", "06:59", 20.0).unwrap().len(), 3);
    assert_eq!(time_range("12:00", "12:00", 5.0).unwrap(), ["12:00:00"]);
    let field = |e: TaskError| match e {
        TaskError::Invalid { field, .. } => field,
        other => panic!("{other}"),
    };
    assert_eq!(field(time_range("18:00", "06:00", 30.0).unwrap_err()), "to");
    assert_eq!(field(time_range("6am", "18:00", 30.0).unwrap_err()), "from");
    assert_eq!(
        field(time_range("00:00", "23:59", 0.0).unwrap_err()),
        "step_min"
    );
    assert_eq!(
        field(time_range("00:00", "23:59:59", 1.0 / 120.0).unwrap_err()),
        "step_min"
    );
}

/// The row at 15:30 is the contrast study of the scene file written for 15:30, bit for bit;
/// the best view is never worse than the fixed one (a node of the same grid); the sun
/// follows SPA across the sky (east in the morning, west in the evening, highest at noon).
#[test]
fn a_row_is_the_study_of_its_time_and_the_sun_crosses_the_sky() {
    let dir = tempfile::tempdir().unwrap();
    let text = std::fs::read_to_string(example("daytime-scene.toml")).unwrap();
    for m in ["olive-paint.toml", "dry-soil.toml"] {
        std::fs::copy(example(m), dir.path().join(m)).unwrap();
    }
    let scene = write(dir.path(), "s.toml", &text);
    let study = daytime(&request(
        SceneSource::File(scene),
        &["07:00", "13:00", "15:30", "19:30"],
    ))
    .unwrap();
    let rows: Vec<Vec<f64>> = study.rows().collect();
    let col = |name: &str| study.columns().iter().position(|c| *c == name).unwrap();
    let (zen, az, phi) = (
        col("sun_zenith_deg"),
        col("sun_azimuth_deg"),
        col("sun_phi_deg"),
    );
    assert!(rows[0][az] < 120.0 && rows[3][az] > 240.0, "{rows:?}");
    assert!(rows[1][zen] < rows[0][zen] && rows[1][zen] < rows[2][zen]);
    // φ = 180° − azimuth (φ = 0 to the south).
    for r in &rows {
        assert!(((180.0 - r[az]).rem_euclid(360.0) - r[phi]).abs() < 1e-9);
        let (best, fixed) = (r[col("best_delta_dolp")], r[col("fixed_delta_dolp")]);
        assert!(best >= fixed, "{best} < {fixed}");
    }
    // The study of the scene file for 15:30.
    let at = write(
        dir.path(),
        "t.toml",
        &text.replace("2026-06-21T13:00:00+02:00", "2026-06-21T15:30:00+02:00"),
    );
    let one = contrast(&ContrastRequest {
        target: None,
        background: None,
        source: SourceRequest::Scene(at),
        grid_deg: (15.0, 30.0),
        rank: rank(),
    })
    .unwrap();
    let best = one.top[0];
    assert_eq!(rows[2][col("best_delta_dolp")], best.delta_dolp());
    assert_eq!(rows[2][col("best_theta_r_deg")], best.theta_r.to_degrees());
    let fixed = one.problem.at(45f64.to_radians(), 180f64.to_radians());
    assert_eq!(
        rows[2][col("fixed_polarization_contrast")],
        fixed.polarization_contrast()
    );
    assert_eq!(study.date_times()[2], "2026-06-21T15:30:00+02:00");
    // The CSV holds the same numbers.
    let csv = String::from_utf8(study.csv()).unwrap();
    assert!(
        csv.starts_with("date_time,local_time_h,sun_zenith_deg,"),
        "{csv}"
    );
    assert_eq!(csv.lines().count(), 5);
}

/// At night the clear sky (which the sun sets) is not evaluated; a thermal scene is, without
/// the sun: the row equals the scene without its [sun].
#[test]
fn the_night_without_the_sun() {
    let dir = tempfile::tempdir().unwrap();
    let text = std::fs::read_to_string(example("daytime-scene.toml")).unwrap();
    for m in ["olive-paint.toml", "dry-soil.toml"] {
        std::fs::copy(example(m), dir.path().join(m)).unwrap();
    }
    let scene = write(dir.path(), "s.toml", &text);
    let study = daytime(&request(SceneSource::File(scene), &["02:00"])).unwrap();
    let row: Vec<f64> = study.rows().next().unwrap();
    assert_eq!(row[4], 0.0, "sun_up");
    assert!(row[1] > 90.0);
    assert!(row[5..].iter().all(|v| v.is_nan()), "{row:?}");

    for m in [
        "painted-aluminium-lwir.toml",
        "soil-lwir.toml",
        "lwir-8-12um.csv",
    ] {
        std::fs::copy(example(m), dir.path().join(m)).unwrap();
    }
    let lwir = std::fs::read_to_string(example("lwir-scene.toml")).unwrap();
    let sun = "[sun]\ndate_time = \"2026-06-21T02:00:00+02:00\"\nlatitude_deg = 48.21\n\
               longitude_deg = 16.37\nirradiance = 10\n";
    let with_sun = write(
        dir.path(),
        "lwir-sun.toml",
        &format!("{lwir}\n{sun}").replace(
            "date_time = \"2026-06-21T02:00:00+02:00\"",
            "date_time = \"2026-06-21T12:00:00+02:00\"",
        ),
    );
    let night = daytime(&request(SceneSource::File(with_sun), &["02:00"])).unwrap();
    let no_sun = write(dir.path(), "lwir-nosun.toml", &lwir);
    let plain = contrast(&ContrastRequest {
        target: None,
        background: None,
        source: SourceRequest::Scene(no_sun),
        grid_deg: (15.0, 30.0),
        rank: rank(),
    })
    .unwrap();
    let row: Vec<f64> = night.rows().next().unwrap();
    assert_eq!(row[4], 0.0);
    assert_eq!(row[7], plain.top[0].delta_dolp());
    assert_eq!(
        row[9],
        plain
            .problem
            .at(45f64.to_radians(), 180f64.to_radians())
            .delta_dolp()
    );
}

/// With a sensor: the longest detection range over the grid is at least the fixed view's
/// (a node of the grid).
#[test]
fn detection_range_of_the_best_view_and_a_fixed_view() {
    let dir = tempfile::tempdir().unwrap();
    let text = std::fs::read_to_string(example("daytime-scene.toml")).unwrap();
    for m in ["olive-paint.toml", "dry-soil.toml"] {
        std::fs::copy(example(m), dir.path().join(m)).unwrap();
    }
    let scene = write(dir.path(), "s.toml", &text);
    let mut r = request(SceneSource::File(scene), &["09:00", "13:00"]);
    r.detect = Some(DaytimeDetect {
        template: DetectRequest {
            sensor: SensorSource::File(example("sensors/sony-imx250mzr-dofp.toml")),
            ..DetectRequest::default()
        },
    });
    let study = daytime(&r).unwrap();
    let cols = study.columns();
    let best = cols.iter().position(|c| *c == "best_max_range_m").unwrap();
    let fixed = cols.iter().position(|c| *c == "fixed_max_range_m").unwrap();
    for row in study.rows() {
        assert!(row[best] > 0.0 && row[best] >= row[fixed], "{row:?}");
    }
}

#[test]
fn the_request_is_checked() {
    let scene = SceneSource::File(example("detect-daylight-scene.toml"));
    // A scene whose sun is given by its angles cannot be moved through the day.
    match daytime(&request(scene, &["12:00"])).unwrap_err() {
        TaskError::Usage { field, message } => {
            assert_eq!(field, "scene");
            assert!(message.contains("give [sun] date_time"), "{message}");
        }
        other => panic!("{other}"),
    }
    let scene = SceneSource::File(example("daytime-scene.toml"));
    let field = |r: DaytimeRequest| match daytime(&r).unwrap_err() {
        TaskError::Invalid { field, .. } | TaskError::Usage { field, .. } => field,
        other => panic!("{other}"),
    };
    assert_eq!(field(request(scene.clone(), &[])), "times");
    assert_eq!(field(request(scene.clone(), &["25:00"])), "times");
    let mut r = request(scene.clone(), &["12:00"]);
    r.date = Some("2026-02-30".into());
    assert_eq!(field(r), "date");
    let mut r = request(scene, &["12:00"]);
    r.fixed_view_deg = (95.0, 0.0);
    assert_eq!(field(r), "fixed_view_deg");
}
