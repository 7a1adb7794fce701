//! Measurement CSV: any bytes parse into finite measurements or give an error naming the file.
#![no_main]
use libfuzzer_sys::fuzz_target;
use std::path::Path;

fuzz_target!(|data: &[u8]| {
    match polbrdf_io::parse_measurements_csv(data, Path::new("fuzz.csv")) {
        Ok(t) => {
            for c in &t.columns {
                assert_eq!(c.values.len(), t.geometries.len());
                assert!(c.values.iter().flatten().all(|v| v.is_finite()));
                if let Some(s) = &c.sigmas {
                    assert!(s.iter().flatten().all(|v| v.is_finite() && *v > 0.0));
                }
            }
        }
        Err(e) => assert!(e.to_string().starts_with("fuzz.csv")),
    }
});
