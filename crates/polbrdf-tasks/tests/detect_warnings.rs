//! The setup warnings of a detection study and of a day's sweep (values, shown by both
//! adapters): the scene's checks judged over the sensor's band, a scene written for another
//! part of the spectrum, the materials' unit checks, and saturation, flagged in best.json.

use crate::common::{band_scene, example, write};
use polbrdf_tasks::contrast::RankRequest;
use polbrdf_tasks::daytime::{daytime, DaytimeDetect, DaytimeRequest};
use polbrdf_tasks::detect::{detect, DetectRequest, SceneSource, SensorSource, Views};
use std::path::{Path, PathBuf};

const VISIBLE: &str = "sensors/sony-imx250mzr-dofp.toml";
const LWIR: &str = "sensors/lwir-microbolometer-dofp.toml";

fn request(scene: PathBuf, sensor: PathBuf) -> DetectRequest {
    DetectRequest {
        scene: SceneSource::File(scene),
        sensor: SensorSource::File(sensor),
        views: Views::List(vec![(30.0, 0.0), (25.0, 180.0)]),
        ranges_m: vec![500.0],
        ..DetectRequest::default()
    }
}

fn warnings(r: &DetectRequest) -> Vec<String> {
    detect(r)
        .unwrap()
        .warnings
        .iter()
        .map(ToString::to_string)
        .collect()
}

fn count(w: &[String], part: &str) -> usize {
    w.iter().filter(|m| m.contains(part)).count()
}

/// The example camera with a longer exposure (ms).
fn exposed(dir: &Path, ms: f64) -> PathBuf {
    let text = std::fs::read_to_string(example(VISIBLE)).unwrap();
    let line = text
        .lines()
        .find(|l| l.starts_with("integration_time_ms"))
        .unwrap();
    write(
        dir,
        "long.toml",
        &text.replace(line, &format!("integration_time_ms = {ms}")),
    )
}

#[test]
fn the_shipped_examples_warn_of_nothing() {
    for (scene, sensor) in [
        ("detect-daylight-scene.toml", VISIBLE),
        ("detect-lwir-scene.toml", LWIR),
    ] {
        let w = warnings(&request(example(scene), example(sensor)));
        assert!(w.is_empty(), "{scene}: {w:?}");
    }
}

/// The visible scene (0.55 µm, no temperatures) seen by the 8–12 µm polarimeter: the surfaces'
/// missing temperatures matter over the sensor's band (not over the scene's 0.55 µm, which
/// said nothing), and the scene is written for a wavelength outside it.
#[test]
fn a_visible_scene_seen_in_the_thermal_infrared_warns() {
    let w = warnings(&request(
        example("detect-daylight-scene.toml"),
        example(LWIR),
    ));
    assert_eq!(count(&w, "has no temperature_k"), 2, "{w:?}");
    assert!(w[0].contains("[target] has no temperature_k"), "{w:?}");
    let mismatch = "detect-daylight-scene.toml: the scene is written for wavelength_um = 0.55, \
                    outside the band of the sensor";
    assert_eq!(count(&w, mismatch), 1, "{w:?}");
    assert!(w.iter().any(|m| m.contains("(8–12 µm)")), "{w:?}");
}

/// An 8–12 µm scene without temperatures seen by the visible camera: emission does not matter
/// over 0.45–0.65 µm (the scene's band would have warned), but the scene is for another band.
#[test]
fn a_thermal_band_scene_seen_in_the_visible_warns_of_the_band_only() {
    let dir = tempfile::tempdir().unwrap();
    let scene = band_scene(
        dir.path(),
        "lwir.toml",
        &format!(
            "[sun]\nzenith_deg = 40\nirradiance = 10\n[target]\nmaterial = {:?}\n\
             [background]\nmaterial = {:?}\n",
            example("olive-paint.toml"),
            example("dry-soil.toml")
        ),
    );
    let w = warnings(&request(scene, example(VISIBLE)));
    assert_eq!(count(&w, "temperature_k"), 0, "{w:?}");
    assert_eq!(
        count(&w, "its [band] (7.8–12.2 µm), outside the band"),
        1,
        "{w:?}"
    );
}

/// A roughness that looks like radians, given as the request's target.
#[test]
fn a_material_in_radians_warns_as_the_cli_does_for_other_jobs() {
    let dir = tempfile::tempdir().unwrap();
    let m = write(
        dir.path(),
        "rad.toml",
        "n = 1.65\nsigma_deg = 0.26\nrho_d = 0.03\n",
    );
    let mut r = request(example("detect-daylight-scene.toml"), example(VISIBLE));
    r.target = Some(m.display().to_string());
    let w = warnings(&r);
    let expected = polbrdf_io::material_warnings(
        &polbrdf_io::load_material(&m.display().to_string()).unwrap(),
        &m.display().to_string(),
    );
    assert_eq!(expected.len(), 1);
    assert_eq!(w, [expected[0].to_string()]);
}

/// A 20 ms exposure in daylight fills the wells: the warning counts the views, best.json
/// flags each one, and detect.csv's `saturated` column agrees at the listed range.
#[test]
fn saturation_is_warned_and_flagged_in_best_json() {
    let dir = tempfile::tempdir().unwrap();
    let r = request(
        example("detect-daylight-scene.toml"),
        exposed(dir.path(), 20.0),
    );
    let s = detect(&r).unwrap();
    assert!(s.views.iter().all(|v| v.at_ranges[0].saturated));
    let w: Vec<String> = s.warnings.iter().map(ToString::to_string).collect();
    assert_eq!(
        count(
            &w,
            "a channel saturates (beyond full_well_e) at 2 of 2 views"
        ),
        1,
        "{w:?}"
    );
    let best = s.best_json();
    assert_eq!(best["saturated_views"], 2);
    for v in best["views"].as_array().unwrap() {
        assert_eq!(v["saturated"], true);
    }
    assert_eq!(best["warnings"].as_array().unwrap().len(), w.len());
    // The shipped exposure does not saturate there.
    let s = detect(&request(
        example("detect-daylight-scene.toml"),
        example(VISIBLE),
    ))
    .unwrap();
    assert_eq!(s.best_json()["saturated_views"], 0);
    assert!(s.views.iter().all(|v| !s.view_saturated(v)));
}

/// A day's sweep shows its studies' warnings once each, and saturation as one line.
#[test]
fn a_sweep_warns_once_per_warning() {
    let dir = tempfile::tempdir().unwrap();
    let mut template = DetectRequest {
        sensor: SensorSource::File(exposed(dir.path(), 20.0)),
        ..DetectRequest::default()
    };
    template.range_limit_m = 20_000.0;
    let study = daytime(&DaytimeRequest {
        scene: SceneSource::File(example("daytime-scene.toml")),
        target: Some(
            write(
                dir.path(),
                "rad.toml",
                "n = 1.65\nsigma_deg = 0.26\nrho_d = 0.03\n",
            )
            .display()
            .to_string(),
        ),
        background: None,
        date: None,
        times: vec!["10:00".into(), "13:00".into(), "23:00".into()],
        grid_deg: (30.0, 90.0),
        rank: RankRequest {
            refine: false,
            ..RankRequest::default()
        },
        fixed_view_deg: (30.0, 0.0),
        detect: Some(DaytimeDetect { template }),
    })
    .unwrap();
    let w: Vec<String> = study.warnings.iter().map(ToString::to_string).collect();
    assert_eq!(count(&w, "sigma_deg = 0.26"), 1, "{w:?}");
    assert_eq!(
        count(
            &w,
            "at some views at 2 of 3 times (the first at 2026-06-21T10:00:00+02:00"
        ),
        1,
        "{w:?}"
    );
    assert_eq!(w.len(), 2, "{w:?}");
}
