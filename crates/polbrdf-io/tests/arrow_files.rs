//! Arrow IPC tables (feature `arrow`): the fuzz target's seeds and every prefix and single-byte
//! corruption of them read as file (footer; front to back) and as stream give rows or an error
//! naming the file — never a panic.

use polbrdf_io::arrow::{ArrowReader, Column};
use std::io::Cursor;
use std::path::{Path, PathBuf};

/// Reads every row of `r` in chunks of 7 rows; the rows read, or the error's text.
fn drain(r: polbrdf_io::Result<ArrowReader>) -> Result<usize, String> {
    let mut r = r.map_err(|e| e.to_string())?;
    let width = r.columns().len();
    let mut rows = 0;
    while let Some(cols) = r.next_rows(7).map_err(|e| e.to_string())? {
        assert_eq!(cols.len(), width);
        let len = |c: &Column| match c {
            Column::Numbers(v) => v.len(),
            Column::Text(v) => v.len(),
        };
        let n = cols.first().map_or(0, len);
        assert!(cols.iter().all(|c| len(c) == n));
        for (c, k) in cols.iter().zip(r.kinds()) {
            assert_eq!(c.kind(), *k);
        }
        rows += n;
    }
    Ok(rows)
}

/// The three ways to read `bytes`; each gives rows or an error starting with the file's name.
fn read_all_ways(bytes: &[u8]) -> [Result<usize, String>; 3] {
    let file = Path::new("t.arrow");
    let stream = Path::new("t.arrows");
    let r = [
        drain(ArrowReader::file(Cursor::new(bytes.to_vec()), file)),
        drain(ArrowReader::file_sequential(
            Cursor::new(bytes.to_vec()),
            file,
        )),
        drain(ArrowReader::stream(Cursor::new(bytes.to_vec()), stream)),
    ];
    for (res, name) in r.iter().zip(["t.arrow:", "t.arrow:", "t.arrows:"]) {
        if let Err(e) = res {
            assert!(e.starts_with(name), "{e}");
        }
    }
    r
}

fn seeds() -> Vec<(PathBuf, Vec<u8>)> {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../fuzz/corpus/arrow");
    let mut v: Vec<(PathBuf, Vec<u8>)> = std::fs::read_dir(&dir)
        .unwrap()
        .map(|e| {
            let p = e.unwrap().path();
            let b = std::fs::read(&p).unwrap();
            (p, b)
        })
        .collect();
    v.sort();
    assert!(v.len() >= 3, "seeds in {}", dir.display());
    v
}

#[test]
fn seeds_read_as_their_format_says() {
    for (p, b) in seeds() {
        let name = p.file_name().unwrap().to_str().unwrap().to_string();
        let [file, sequential, stream] = read_all_ways(&b);
        match name.as_str() {
            "geometry.arrow" => {
                assert_eq!(file, Ok(2));
                assert_eq!(sequential, Ok(2));
                assert!(stream.is_err());
            }
            "geometry.arrows" => {
                assert_eq!(stream, Ok(2));
                assert!(file.is_err() && sequential.is_err());
            }
            "null.arrow" => {
                let e = file.unwrap_err();
                assert!(e.starts_with("t.arrow:2: field `theta_i_deg`: null"), "{e}");
            }
            _ => {}
        }
    }
}

#[test]
fn every_prefix_and_flipped_byte_is_rows_or_an_error() {
    for (_, b) in seeds() {
        for n in 0..b.len() {
            let _ = read_all_ways(&b[..n]);
        }
        for i in 0..b.len() {
            let mut c = b.clone();
            c[i] ^= 0xff;
            let _ = read_all_ways(&c);
        }
    }
}

#[test]
fn a_table_without_columns_is_refused_however_many_rows_it_claims() {
    // Found by the fuzz target: a batch without columns costs no bytes for any row count, and
    // reading 2⁴⁰ rows of nothing 7 at a time did not end.
    use arrow_array::{RecordBatch, RecordBatchOptions};
    use arrow_schema::Schema;
    use std::sync::Arc;
    let schema = Arc::new(Schema::empty());
    let opts = RecordBatchOptions::new().with_row_count(Some(1 << 40));
    let batch = RecordBatch::try_new_with_options(schema.clone(), vec![], &opts).unwrap();
    let mut stream = Vec::new();
    {
        let mut w = arrow_ipc::writer::StreamWriter::try_new(&mut stream, &schema).unwrap();
        w.write(&batch).unwrap();
        w.finish().unwrap();
    }
    let mut file = Vec::new();
    {
        let mut w = arrow_ipc::writer::FileWriter::try_new(&mut file, &schema).unwrap();
        w.write(&batch).unwrap();
        w.finish().unwrap();
    }
    for bytes in [&stream, &file] {
        for r in read_all_ways(bytes) {
            if let Err(e) = &r {
                if e.contains("without columns") {
                    continue;
                }
            }
            // The stream read as a file (and the file as a stream) fail earlier, on the format.
            assert!(r.is_err(), "{r:?}");
        }
    }
    let r = drain(ArrowReader::stream(
        Cursor::new(stream),
        Path::new("t.arrows"),
    ));
    assert!(
        r.as_ref().is_err_and(|e| e.contains("without columns")),
        "{r:?}"
    );
    let r = drain(ArrowReader::file(Cursor::new(file), Path::new("t.arrow")));
    assert!(
        r.as_ref().is_err_and(|e| e.contains("without columns")),
        "{r:?}"
    );
}
