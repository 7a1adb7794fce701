//! Detection studies: the example sensors on the example scenes, a scene path that only
//! attenuates, the CSV/JSON tables, the request's validation.

use crate::common::{example, write};
use polbrdf::analysis::detection::MaxRange;
use polbrdf_tasks::detect::{detect, DetectRequest, SceneSource, SensorSource, Views};
use polbrdf_tasks::TaskError;

fn request(scene: &str, sensor: &str, views: Views) -> DetectRequest {
    DetectRequest {
        scene: SceneSource::File(example(scene)),
        sensor: SensorSource::File(example(sensor)),
        views,
        ranges_m: vec![500.0, 2000.0],
        ..DetectRequest::default()
    }
}

const VISIBLE: &str = "sensors/sony-imx250mzr-dofp.toml";
const LWIR: &str = "sensors/lwir-microbolometer-dofp.toml";

#[test]
fn the_visible_camera_detects_the_paint_on_soil_and_pd_falls_with_range() {
    let views = Views::List(vec![(30.0, 180.0), (60.0, 90.0), (10.0, 0.0)]);
    let s = detect(&request("detect-daylight-scene.toml", VISIBLE, views)).unwrap();
    assert_eq!(s.views.len(), 3);
    for v in &s.views {
        let (near, far) = (&v.at_ranges[0], &v.at_ranges[1]);
        assert!(near.pd >= far.pd, "{} {}", near.pd, far.pd);
        // Pixels on target ∝ 1/R².
        assert!((near.pixels / far.pixels - 16.0).abs() < 1e-9);
        // The detection range is where P_d crosses 0.9: above it at shorter ranges.
        if let Some(MaxRange::At { range_m, .. }) = v.max_range {
            let at = s
                .detector
                .detect(&v.target, &v.background, v.theta_r, range_m)
                .unwrap();
            assert!((at.pd - 0.9).abs() < 1e-6, "{}", at.pd);
            for d in &v.at_ranges {
                assert_eq!(d.pd >= 0.9 - 1e-9, d.range_m <= range_m * (1.0 + 1e-9));
            }
        }
    }
    let csv = String::from_utf8(s.csv()).unwrap();
    assert_eq!(csv.lines().count(), 1 + 3 * 2);
    assert!(csv.starts_with("theta_r_deg,phi_r_deg,range_m,pixels_on_target,snr_s0,snr_dolp,"));
    let best = s.best_json();
    assert_eq!(best["views"].as_array().unwrap().len(), 3);
    assert_eq!(best["best"], best["views"][0]);
}

#[test]
fn a_hazier_path_never_detects_farther() {
    let dir = tempfile::tempdir().unwrap();
    let text = std::fs::read_to_string(example("detect-daylight-scene.toml")).unwrap();
    let mut ranges = Vec::new();
    for km in [50.0, 23.0, 5.0] {
        let hazy = text
            .replace("visibility_km = 23", &format!("visibility_km = {km}"))
            .replace("horizon_radiance = 60", "horizon_radiance = 0")
            .replace(
                "\"olive-paint.toml\"",
                &format!("{:?}", example("olive-paint.toml")),
            )
            .replace(
                "\"dry-soil.toml\"",
                &format!("{:?}", example("dry-soil.toml")),
            );
        let p = write(dir.path(), "hazy.toml", &hazy);
        let mut r = request(
            "detect-daylight-scene.toml",
            VISIBLE,
            Views::List(vec![(45.0, 120.0)]),
        );
        r.scene = SceneSource::File(p);
        let s = detect(&r).unwrap();
        ranges.push(polbrdf_tasks::detect::out::max_range_value(
            s.views[0].max_range,
        ));
    }
    assert!(
        ranges[0] >= ranges[1] && ranges[1] >= ranges[2],
        "{ranges:?}"
    );
}

#[test]
fn the_thermal_polarimeter_sees_the_warm_panel() {
    let views = Views::List(vec![(70.0, 0.0), (20.0, 0.0)]);
    let s = detect(&request("detect-lwir-scene.toml", LWIR, views)).unwrap();
    for v in &s.views {
        assert!(v.target.0[0] > v.background.0[0]);
        assert!(!matches!(v.max_range, Some(MaxRange::NotDetectable)));
    }
}

#[test]
fn the_request_is_checked_before_anything_is_computed() {
    let mut r = request(
        "detect-daylight-scene.toml",
        VISIBLE,
        Views::Grid((5.0, 10.0)),
    );
    r.ranges_m = vec![100.0, -1.0];
    assert!(matches!(detect(&r), Err(TaskError::Invalid { field, .. }) if field == "ranges_m"));
    r.ranges_m.clear();
    r.search = false;
    assert!(matches!(detect(&r), Err(TaskError::Usage { field, .. }) if field == "ranges_m"));
    r.search = true;
    r.pfa = 1.5;
    assert!(matches!(detect(&r), Err(TaskError::Invalid { field, .. }) if field == "pfa"));
    r.pfa = 1e-6;
    r.area_m2 = 0.0;
    assert!(matches!(detect(&r), Err(TaskError::Invalid { field, .. }) if field == "area_m2"));
    r.area_m2 = 1.0;
    r.sun_deg = Some((95.0, 0.0));
    assert!(detect(&r).is_err());
    // The LWIR scene's [atmosphere] is the identity: allowed. A real one is refused.
    let mut r = request("lwir-scene.toml", LWIR, Views::List(vec![(10.0, 0.0)]));
    assert!(detect(&r).is_ok());
    let dir = tempfile::tempdir().unwrap();
    let text = std::fs::read_to_string(example("lwir-scene.toml"))
        .unwrap()
        .replace("transmittance = 1.0", "transmittance = 0.5")
        .replace(
            "\"lwir-8-12um.csv\"",
            &format!("{:?}", example("lwir-8-12um.csv")),
        )
        .replace(
            "\"painted-aluminium-lwir.toml\"",
            &format!("{:?}", example("painted-aluminium-lwir.toml")),
        )
        .replace(
            "\"soil-lwir.toml\"",
            &format!("{:?}", example("soil-lwir.toml")),
        );
    r.scene = SceneSource::File(write(dir.path(), "atm.toml", &text));
    let e = detect(&r).unwrap_err().to_string();
    assert!(e.contains("[atmosphere]") && e.contains("atm.toml"), "{e}");
}

#[test]
fn a_wavelength_independent_scene_observed_at_the_band_centre_is_the_band_integral() {
    // The shortcut of the task (docs/detection.md): constant indices, no emission, flat sun
    // and sky — the band integral equals the centre's radiance times ∫ weight dλ.
    use polbrdf::analysis::scene::Observer;
    let scene = polbrdf_io::read_scene(&example("detect-daylight-scene.toml")).unwrap();
    let sensor = polbrdf_io::read_sensor(&example(VISIBLE)).unwrap();
    let polbrdf::Spectrum::Band(band, _) = &sensor.spectrum else {
        panic!("a photon band")
    };
    let (lo, hi) = band.range();
    let total: f64 = sensor
        .spectrum
        .integral_nodes(&[])
        .iter()
        .map(|n| n.1)
        .sum();
    let spec = scene.target.material.clone().unwrap().0;
    let views = [(0.6, 2.0), (1.2, 0.3)];
    let full = Observer::new(&spec, &scene.thermal, &sensor.spectrum)
        .unwrap()
        .observe(&views);
    let centre = Observer::new(
        &spec,
        &scene.thermal,
        &polbrdf::Spectrum::Wavelength(0.5 * (lo + hi)),
    )
    .unwrap()
    .observe(&views);
    for (f, c) in full.iter().zip(&centre) {
        for k in 0..3 {
            let (a, b) = (f.stokes.0[k], c.stokes.0[k] * total);
            assert!((a - b).abs() <= 1e-12 * f.stokes.0[0], "{k}: {a} {b}");
        }
    }
}
