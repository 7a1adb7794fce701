//! Arrow IPC tables: any bytes, read as an IPC file (through its footer, and front to back)
//! and as an IPC stream, give rows or an error naming the file; never a panic or an abort.
//! Every chunk has one column per schema column, all of one length.
#![no_main]
use libfuzzer_sys::fuzz_target;
use polbrdf_io::arrow::{ArrowReader, Column};
use std::io::Cursor;
use std::path::Path;

/// Reads every row of `r` in chunks of 7 rows; an error must name `name`.
fn drain(r: polbrdf_io::Result<ArrowReader>, name: &str) {
    let mut r = match r {
        Ok(r) => r,
        Err(e) => return assert!(e.to_string().starts_with(name), "{e}"),
    };
    let width = r.columns().len();
    loop {
        match r.next_rows(7) {
            Ok(Some(cols)) => {
                assert_eq!(cols.len(), width);
                let len = |c: &Column| match c {
                    Column::Numbers(v) => v.len(),
                    Column::Text(v) => v.len(),
                };
                let n = cols.first().map_or(0, len);
                assert!((1..=7).contains(&n) || width == 0);
                assert!(cols.iter().all(|c| len(c) == n));
                for (c, k) in cols.iter().zip(r.kinds()) {
                    assert_eq!(c.kind(), *k);
                }
            }
            Ok(None) => break,
            Err(e) => return assert!(e.to_string().starts_with(name), "{e}"),
        }
    }
}

fuzz_target!(|data: &[u8]| {
    let file = Path::new("fuzz.arrow");
    drain(
        ArrowReader::file(Cursor::new(data.to_vec()), file),
        "fuzz.arrow:",
    );
    drain(
        ArrowReader::file_sequential(Cursor::new(data.to_vec()), file),
        "fuzz.arrow:",
    );
    let stream = Path::new("fuzz.arrows");
    drain(
        ArrowReader::stream(Cursor::new(data.to_vec()), stream),
        "fuzz.arrows:",
    );
});
