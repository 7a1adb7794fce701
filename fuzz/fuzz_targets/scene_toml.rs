//! Scene files: any bytes either parse into a scene that validates, at a finite wavelength
//! above 0 (or over a valid band), or give an error naming the scene file and saying what is
//! wrong; never a panic.
#![no_main]
use libfuzzer_sys::fuzz_target;
use polbrdf::Spectrum;
use std::path::Path;

fuzz_target!(|data: &[u8]| {
    let Ok(text) = std::str::from_utf8(data) else {
        return;
    };
    // A scene names files to read; keep the fuzzer away from devices and pseudo-files that
    // never end (/dev/zero) or block (a FIFO), also when spelled with TOML escapes.
    if ["/dev", "/proc", "/sys", "\\u", "\\U"]
        .iter()
        .any(|s| text.contains(s))
    {
        return;
    }
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
