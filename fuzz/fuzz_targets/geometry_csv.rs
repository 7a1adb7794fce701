//! Geometry CSV: any bytes parse into valid geometries or give an error naming the file.
#![no_main]
use libfuzzer_sys::fuzz_target;
use std::path::Path;

fuzz_target!(|data: &[u8]| {
    match polbrdf_io::parse_geometry_csv(data, Path::new("fuzz.csv")) {
        Ok(t) => {
            assert_eq!(t.rows.len(), t.geometries.len());
            assert_eq!(t.rows.len(), t.lines.len());
            let paint = polbrdf_fuzz::paint();
            let f = polbrdf::batch::pbrdf_of(paint, &t.geometries);
            // The scalars as eval computes them (the engine's one definition).
            let g = &t.geometries;
            let ti: Vec<f64> = g.iter().map(polbrdf::Geometry::theta_i).collect();
            let pi: Vec<f64> = g.iter().map(polbrdf::Geometry::phi_i).collect();
            let tr: Vec<f64> = g.iter().map(polbrdf::Geometry::theta_r).collect();
            let pr: Vec<f64> = g.iter().map(polbrdf::Geometry::phi_r).collect();
            let batch = polbrdf::GeometryBatch::new(&ti, &pi, &tr, &pr).unwrap();
            let n = g.len();
            let (mut b, mut d, mut a) = (vec![0.0; n], vec![0.0; n], vec![0.0; n]);
            polbrdf::Engine::new(paint)
                .brdf_dolp_aolp_into(&batch, &mut b, &mut d, &mut a)
                .unwrap();
            let rows: Vec<polbrdf_io::stream::RowResult> = (0..n)
                .map(|k| polbrdf_io::stream::RowResult {
                    pbrdf: f[k],
                    brdf_dolp_aolp: [b[k], d[k], a[k]],
                })
                .collect();
            let bytes = polbrdf_io::csv_io::results_csv(&t, &rows);
            if let Ok(bytes) = bytes {
                assert!(std::str::from_utf8(&bytes).is_ok());
            }
        }
        Err(e) => assert!(e.to_string().starts_with("fuzz.csv")),
    }
});
