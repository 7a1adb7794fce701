//! `.npy` tables: any bytes parse into a table or give an error naming the file; a table
//! written back reads back the same (bit for bit), and the streaming reader agrees.
#![no_main]
use libfuzzer_sys::fuzz_target;
use std::path::Path;

fuzz_target!(|data: &[u8]| {
    let path = Path::new("fuzz.npy");
    match polbrdf_io::npy::parse_npy(data, path) {
        Ok(t) => {
            assert_eq!(t.data.len(), t.rows() * t.columns.len());
            let bytes = polbrdf_io::npy::npy_bytes(&t.columns, &t.data).unwrap();
            let back = polbrdf_io::npy::parse_npy(&bytes, path).unwrap();
            assert_eq!(back.columns, t.columns);
            let bits = |v: &[f64]| v.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
            assert_eq!(bits(&back.data), bits(&t.data));
            let mut r = polbrdf_io::npy::NpyReader::new(data, path).unwrap();
            let mut out = Vec::new();
            while r.read_rows(7, &mut out).unwrap() > 0 {}
            assert_eq!(bits(&out), bits(&t.data));
        }
        Err(e) => assert!(e.to_string().starts_with("fuzz.npy: ")),
    }
});
