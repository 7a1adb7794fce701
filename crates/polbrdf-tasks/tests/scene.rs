//! Scene setup: the defaults defined once in the core, the setup's warnings as values.

use crate::common::{band_scene, write};
use polbrdf_tasks::scene::{
    contrast_warnings, defaults, read_scene, SceneRequest, SkyRequest, SunRequest,
};

#[test]
fn scene_defaults_are_the_cores_and_round_trip() {
    let dir = tempfile::tempdir().unwrap();
    let implicit = write(
        dir.path(),
        "implicit.toml",
        "wavelength_um = 0.55\n[sun]\nzenith_deg = 40\nirradiance = 1000\n\
         [sky]\nmodel = \"cie-clear\"\nirradiance = 100\n",
    );
    let explicit = write(
        dir.path(),
        "explicit.toml",
        &format!(
            "wavelength_um = 0.55\n[sun]\nzenith_deg = 40\nirradiance = 1000\nazimuth_deg = {}\n\
             stokes = [1, 0, 0, 0]\n[sky]\nmodel = \"cie-clear\"\nirradiance = 100\n\
             dop_max = {}\n[atmosphere]\ntransmittance = {}\npath_radiance = {}\n",
            defaults::Sun::DEFAULT_AZIMUTH.to_degrees(),
            defaults::DOP_MAX,
            defaults::Atmosphere::default().transmittance,
            defaults::Atmosphere::default().path_radiance,
        ),
    );
    let a = read_scene(&implicit).unwrap();
    let b = read_scene(&explicit).unwrap();
    assert_eq!(a.thermal, b.thermal, "absent keys take the core's defaults");
    match &a.thermal.sky {
        defaults::SkyModel::ClearSky { dop_max, .. } => {
            assert_eq!(*dop_max, defaults::ClearSky::DEFAULT_DOP_MAX);
        }
        other => panic!("{other:?}"),
    }
    let json = polbrdf_tasks::sky_json(&a.thermal.sky);
    assert_eq!(json["dop_max"], serde_json::json!(defaults::DOP_MAX));
    assert!(
        contrast_warnings(&a).is_empty(),
        "visible, no [surface]: no warning"
    );
}

#[test]
fn contrast_warnings_name_the_file_and_table() {
    let dir = tempfile::tempdir().unwrap();
    let path = band_scene(
        dir.path(),
        "w.toml",
        "[surface]\ntemperature_k = 300\n[target]\nmaterial = \"paint\"\n\
         [background]\nmaterial = \"paint\"\ntemperature_k = 290\n",
    );
    let scene = read_scene(&path).unwrap();
    let w: Vec<String> = contrast_warnings(&scene)
        .iter()
        .map(ToString::to_string)
        .collect();
    assert_eq!(w.len(), 2, "{w:?}");
    assert!(w[0].contains("w.toml") && w[0].contains("[target] has no temperature_k"));
    assert!(w[1].contains("[surface] is for `polbrdf radiance`"));
}

#[test]
fn a_scene_from_options_equals_the_same_scene_from_a_file() {
    let dir = tempfile::tempdir().unwrap();
    let file = write(
        dir.path(),
        "day.toml",
        "wavelength_um = 0.55\n[surface]\ntemperature_k = 300\n[sun]\nzenith_deg = 35\n\
         irradiance = 1400\nstokes = [2, 0.5, 0, 0]\n[sky]\nmodel = \"cie-clear\"\nirradiance = 200\n\
         [atmosphere]\ntransmittance = 0.8\n",
    );
    let request = SceneRequest {
        surface_temperature_k: Some(300.0),
        sky: SkyRequest::ClearSky {
            irradiance: 200.0,
            dop_max: None,
        },
        sun: Some(SunRequest {
            zenith_deg: 35.0,
            azimuth_deg: None,
            irradiance: 1400.0,
            stokes: Some([2.0, 0.5, 0.0, 0.0]),
        }),
        transmittance: Some(0.8),
        path_radiance: None,
    };
    assert_eq!(
        request.thermal().unwrap(),
        read_scene(&file).unwrap().thermal
    );
    // The file's checks, with the file's key names.
    let bad = SceneRequest {
        sky: SkyRequest::ClearSky {
            irradiance: 200.0,
            dop_max: Some(1.5),
        },
        ..request.clone()
    };
    let e = bad.thermal().unwrap_err().to_string();
    assert!(e.contains("dop_max"), "{e}");
    let sunless = SceneRequest {
        sun: None,
        ..request
    };
    let e = sunless.thermal().unwrap_err().to_string();
    assert!(e.contains("needs a sun"), "{e}");
}
