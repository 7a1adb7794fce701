//! Geometry CSV: any bytes parse into valid geometries or give an error naming the file.
#![no_main]
use libfuzzer_sys::fuzz_target;
use std::path::Path;

fuzz_target!(|data: &[u8]| {
    match polbrdf_io::parse_geometry_csv(data, Path::new("fuzz.csv")) {
        Ok(t) => {
            assert_eq!(t.rows.len(), t.geometries.len());
            assert_eq!(t.rows.len(), t.lines.len());
            let paint = polbrdf::preset("paint").unwrap().build().unwrap();
            let f = polbrdf::batch::pbrdf_of(&paint, &t.geometries);
            let bytes = polbrdf_io::csv_io::results_csv(&t, &f);
            if let Ok(bytes) = bytes {
                assert!(std::str::from_utf8(&bytes).is_ok());
            }
        }
        Err(e) => assert!(e.to_string().starts_with("fuzz.csv")),
    }
});
