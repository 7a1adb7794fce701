//! View-direction CSV (`polbrdf radiance --input`): any bytes parse into at least one view with
//! θ_r in [0°, 90°) and a finite φ_r, or give an error naming the file.
#![no_main]
use libfuzzer_sys::fuzz_target;
use std::path::Path;

fuzz_target!(|data: &[u8]| {
    match polbrdf_io::parse_views_csv(data, Path::new("fuzz.csv")) {
        Ok(views) => {
            assert!(!views.is_empty());
            for (t, p) in views {
                assert!((0.0..90.0).contains(&t), "{t}");
                assert!(p.is_finite(), "{p}");
            }
        }
        Err(e) => assert!(e.to_string().starts_with("fuzz.csv")),
    }
});
