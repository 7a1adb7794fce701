//! Scene files: any bytes either parse into a scene that validates, at a finite wavelength
//! above 0 (or over a valid band), with its sun above the horizon (angles in radians, a Stokes
//! vector of s0 = 1; one placed by date, time and place where SPA puts it) and a clear sky
//! only with a sun, or give an error naming the scene file
//! and saying what is wrong; never a panic.
#![no_main]
use libfuzzer_sys::fuzz_target;
use polbrdf::analysis::SkyModel;
use polbrdf::Spectrum;
use std::path::Path;

fuzz_target!(|data: &[u8]| {
    // The file names files to read: no devices or pseudo-files.
    let Some(text) = polbrdf_fuzz::file_text(data) else {
        return;
    };
    match polbrdf_io::parse_scene(text, Path::new("fuzz.toml")) {
        Ok(scene) => {
            scene.thermal.validate().expect("a parsed scene validates");
            match &scene.spectrum {
                Spectrum::Wavelength(l) => assert!(l.is_finite() && *l > 0.0, "{l}"),
                Spectrum::Band(band, step) => {
                    let (lo, hi) = band.range();
                    assert!(lo.is_finite() && lo > 0.0 && hi.is_finite() && lo < hi);
                    assert!(step.is_none_or(|s| s.is_finite() && s > 0.0));
                }
            }
            if let Some(sun) = &scene.thermal.sun {
                assert!(
                    (0.0..std::f64::consts::FRAC_PI_2).contains(&sun.zenith),
                    "{sun:?}"
                );
                assert!(sun.azimuth.is_finite(), "{sun:?}");
                assert!(
                    sun.irradiance.is_finite() && sun.irradiance >= 0.0,
                    "{sun:?}"
                );
                let [s0, s1, s2, s3] = sun.stokes.0;
                assert!(
                    s0 == 1.0 && s1.hypot(s2).hypot(s3) <= 1.0 + 1e-12,
                    "{sun:?}"
                );
            }
            // A sun placed by date, time and place is where SPA puts it, above the horizon.
            if let Some(t) = &scene.sun_time {
                let sun = scene.thermal.sun.as_ref().expect("date_time places a sun");
                let (_, dir) = t.surface_direction().expect("a parsed sun time is valid");
                assert_eq!(dir, Some((sun.zenith, sun.azimuth)), "{t:?}");
            }
            match &scene.thermal.sky {
                SkyModel::ClearSky {
                    irradiance,
                    dop_max,
                } => {
                    assert!(scene.thermal.sun.is_some(), "a clear sky without a sun");
                    assert!(irradiance.is_finite() && *irradiance >= 0.0, "{irradiance}");
                    assert!((0.0..=1.0).contains(dop_max), "{dop_max}");
                }
                SkyModel::Table(t) => {
                    let (theta, phi) = t.grid();
                    assert!(theta.first() == Some(&0.0) && theta.last() == Some(&90.0));
                    assert!(phi.iter().all(|p| (0.0..360.0).contains(p)), "{phi:?}");
                }
                _ => {}
            }
            for t in [scene.target.temperature_k, scene.background.temperature_k]
                .into_iter()
                .flatten()
            {
                assert!(t.is_finite() && t > 0.0, "{t}");
            }
        }
        Err(e) => {
            // It names the file, and says what is wrong.
            let m = e.to_string();
            assert!(m.starts_with("fuzz.toml"), "{m}");
            assert!(!m.trim_end().ends_with(':'), "an empty message: {m:?}");
        }
    }
});
