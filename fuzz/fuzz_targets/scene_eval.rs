//! A scene evaluated, not only parsed (issue 35): any text that parses as a scene file gives,
//! for the paint preset at a few views (one at the azimuth bound, 1e8°), an observed Stokes
//! radiance that is finite with S0 ≥ 0 and a degree of polarization ≤ 1 (up to rounding) — no
//! panic (a sun at the azimuth bound panicked), no ∞ or NaN (a sky profile of 1e308 gave them).
#![no_main]
use libfuzzer_sys::fuzz_target;
use polbrdf::analysis::scene::observed_radiance;
use std::path::Path;

fuzz_target!(|data: &[u8]| {
    // The file names files to read: no devices or pseudo-files.
    let Some(text) = polbrdf_fuzz::file_text(data) else {
        return;
    };
    let Ok(scene) = polbrdf_io::parse_scene(text, Path::new("fuzz.toml")) else {
        return;
    };
    let paint = polbrdf::preset("paint").unwrap();
    let views = [
        (0.0, 0.0),
        (0.7, 1.0),
        (1.2, 4.0),
        (1.5, -2.0),
        (0.5, polbrdf::MAX_AZIMUTH_DEG.to_radians()),
    ];
    let out = observed_radiance(&paint, &scene.thermal, &scene.spectrum, &views)
        .unwrap_or_else(|e| panic!("a parsed scene evaluates: {e}"));
    for r in &out {
        let [s0, s1, s2, s3] = r.stokes.0;
        assert!(r.stokes.0.iter().all(|v| v.is_finite()), "{r:?}");
        assert!(s0 >= 0.0, "{r:?}");
        assert!(
            s1.hypot(s2).hypot(s3) <= s0 * (1.0 + 1e-9) + 1e-300,
            "{r:?}"
        );
    }
});
