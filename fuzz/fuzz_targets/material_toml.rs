//! Material files: any bytes either parse into a material that evaluates to finite numbers, or
//! give an error naming the file; never a panic.
#![no_main]
use libfuzzer_sys::fuzz_target;
use std::path::Path;

fuzz_target!(|data: &[u8]| {
    let Ok(text) = std::str::from_utf8(data) else {
        return;
    };
    match polbrdf_io::parse_material(text, Path::new("fuzz.toml")) {
        Ok(spec) => {
            let m = spec.build().expect("a parsed material builds");
            let g = polbrdf::Geometry::from_degrees(30.0, 0.0, 40.0, 170.0).unwrap();
            let f = m.pbrdf(&g);
            assert!(f.0.iter().flatten().all(|v| v.is_finite()), "{spec:?}");
            // What we write back reads back to the same material.
            let again =
                polbrdf_io::parse_material(&polbrdf_io::material_to_toml(&spec), Path::new("x"))
                    .expect("round trip");
            assert_eq!(again, spec);
        }
        Err(e) => assert!(e.to_string().starts_with("fuzz.toml")),
    }
});
