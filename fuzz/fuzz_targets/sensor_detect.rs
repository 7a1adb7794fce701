//! A sensor file parsed and used (issue 37): any text that parses as a sensor file makes a
//! sensor whose detection of a bright target on a dim one, through a hazy path, at a few
//! ranges and by the range search, gives finite or well-defined numbers: P_d in [0, 1], per-pixel
//! d′ ≥ 0, pixels on target ≥ 0 — no panic.
#![no_main]
use libfuzzer_sys::fuzz_target;
use polbrdf::analysis::detection::{Criteria, Detector, MaxRange, Path as AirPath};
use polbrdf::Stokes;
use std::path::Path;

fuzz_target!(|data: &[u8]| {
    // The file names files to read: no devices or pseudo-files.
    let Some(text) = polbrdf_fuzz::file_text(data) else {
        return;
    };
    let Ok(file) = polbrdf_io::parse_sensor(text, Path::new("fuzz.toml")) else {
        return;
    };
    let path = AirPath::from_visibility(5_000.0, 1.0).unwrap();
    let criteria = Criteria {
        range_limit_m: 1e4,
        ..Criteria::default()
    };
    let det = Detector::new(file.sensor, path, 1.0, criteria)
        .unwrap_or_else(|e| panic!("a parsed sensor makes a detector: {e}"));
    let (t, b) = (
        Stokes::new(3.0, 0.5, 0.2, 0.0),
        Stokes::new(1.0, 0.0, 0.05, 0.0),
    );
    for r in [1.0, 100.0, 1e4] {
        let d = det.detect(&t, &b, 0.4, r).unwrap();
        assert!((0.0..=1.0).contains(&d.pd), "{d:?}");
        assert!(d.pixels >= 0.0, "{d:?}");
        for f in polbrdf::analysis::detection::Feature::ALL {
            assert!(d.scores.get(f) >= 0.0, "{d:?}");
        }
    }
    match det.max_range(&t, &b, 0.4).unwrap() {
        MaxRange::At { range_m, .. } => assert!(range_m > 0.0 && range_m <= 1e4),
        MaxRange::Beyond | MaxRange::NotDetectable => {}
    }
});
