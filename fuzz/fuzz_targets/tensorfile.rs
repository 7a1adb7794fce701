//! Mitsuba TensorFile (`.pbsdf`) headers: any bytes give an error naming the file, or fields
//! whose data lie inside the file, after the header, without overlapping; a file that passes
//! the header check is opened as a `.pbsdf` table, which either fails with an error naming the
//! file or has axes that increase and slabs that read back in full.
#![no_main]
use libfuzzer_sys::fuzz_target;
use std::io::Write;
use std::path::Path;

fuzz_target!(|data: &[u8]| {
    let path = Path::new("fuzz.pbsdf");
    match polbrdf_io::tensorfile::parse_header(data, data.len() as u64, path) {
        Ok((fields, header_end)) => {
            assert!(header_end as usize <= data.len());
            let mut spans: Vec<(u64, u64)> = fields
                .iter()
                .map(|f| (f.offset, f.offset + f.len() * f.dtype.size()))
                .filter(|s| s.1 > s.0)
                .collect();
            spans.sort();
            for s in &spans {
                assert!(s.0 >= header_end && s.1 <= data.len() as u64);
            }
            assert!(spans.windows(2).all(|w| w[0].1 <= w[1].0));
            if fields.iter().any(|f| f.name == "M") {
                let mut tmp = tempfile::NamedTempFile::new().unwrap();
                tmp.write_all(data).unwrap();
                match polbrdf_io::PbsdfTable::open(tmp.path()) {
                    Ok(mut t) => {
                        for ax in [&t.phi_d, &t.theta_d, &t.theta_h] {
                            assert!(ax.windows(2).all(|w| w[0] < w[1]));
                        }
                        let mut slab = Vec::new();
                        for p in 0..t.phi_d.len() {
                            t.read_slab(p, &mut slab).unwrap();
                            assert_eq!(slab.len(), t.slab_len());
                        }
                    }
                    Err(e) => assert!(e.to_string().starts_with(&tmp.path().display().to_string())),
                }
            }
        }
        Err(e) => assert!(e.to_string().starts_with("fuzz.pbsdf")),
    }
});
