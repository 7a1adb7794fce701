//! `eval`'s streaming geometry reader: any bytes, as CSV, as `.npy` and as an Arrow IPC stream,
//! read in chunks of 7 rows, give validated rows (angles or direction vectors) whose pBRDF
//! through the engine is finite with F00 ≥ 0, or an error naming the file.
#![no_main]
use libfuzzer_sys::fuzz_target;
use polbrdf::{DirectionBatch, Engine};
use polbrdf_fuzz::{paint, EVAL_FORMATS};
use polbrdf_io::stream::{Format, Geometries, GeometryReader};
use std::path::Path;

fn read_all(data: &[u8], name: &str, format: Format) {
    let path = Path::new(name);
    let src = Box::new(std::io::Cursor::new(data.to_vec()));
    let engine = Engine::new(paint());
    let mut reader = match GeometryReader::from_reader(src, path, format) {
        Ok(r) => r,
        Err(e) => return assert!(e.to_string().starts_with(name), "{e}"),
    };
    loop {
        match reader.next_chunk(7) {
            Ok(None) => return,
            Ok(Some(chunk)) => {
                assert!(chunk.len() <= 7 && !chunk.is_empty());
                assert_eq!(chunk.lines.len(), chunk.len());
                let rows: Vec<[f64; 16]> = match &chunk.geometries {
                    Geometries::Angles(g) => engine
                        .pbrdf_of(g)
                        .unwrap()
                        .iter()
                        .map(|m| m.to_row_major())
                        .collect(),
                    Geometries::Directions { w_i, w_r } => {
                        let batch = DirectionBatch::new(w_i, w_r).expect("validated vectors");
                        let mut out = vec![[0.0; 16]; w_i.len()];
                        engine.mueller_into(&batch, &mut out).unwrap();
                        out
                    }
                };
                for f in &rows {
                    assert!(f.iter().all(|x| x.is_finite()) && f[0] >= 0.0, "{f:?}");
                }
            }
            Err(e) => return assert!(e.to_string().starts_with(name), "{e}"),
        }
    }
}

fuzz_target!(|data: &[u8]| {
    for (name, format) in EVAL_FORMATS {
        read_all(data, name, format);
    }
});
