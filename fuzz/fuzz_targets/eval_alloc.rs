//! Allocation proportional to the input (issue 35): any bytes as `eval`'s input — CSV, `.npy`,
//! an Arrow IPC stream — read in chunks of the CLI's size (`CHUNK_ROWS`), as `eval` reads them.
//! The bytes allocated at once never exceed a fixed chunk budget plus a multiple of the input's
//! length: a sparse or lying header (a huge row count, a wide header over one row) must not
//! make the reader reserve what the header claims (65 536 × columns cells were reserved before
//! the first row). A counting allocator measures the peak.
#![no_main]
use libfuzzer_sys::fuzz_target;
use polbrdf_fuzz::{measure_peak, Counting, EVAL_FORMATS};
use polbrdf_io::stream::{Format, GeometryReader, CHUNK_ROWS};
use std::path::Path;

#[global_allocator]
static ALLOC: Counting = Counting;

/// A chunk's fixed budget: 2²¹ cells of f64 or of field ends, its CSV text, the readers'
/// buffers and Arrow's decoder state.
const CHUNK_BUDGET: usize = 96 << 20;

fn read_all(data: &[u8], name: &str, format: Format) {
    let ((), peak) = measure_peak(|| {
        let src = Box::new(std::io::Cursor::new(data.to_vec()));
        if let Ok(mut reader) = GeometryReader::from_reader(src, Path::new(name), format) {
            while let Ok(Some(chunk)) = reader.next_chunk(CHUNK_ROWS) {
                assert!(!chunk.is_empty() && chunk.len() <= CHUNK_ROWS);
            }
        }
    });
    assert!(
        peak <= CHUNK_BUDGET + 64 * data.len(),
        "{name}: {peak} bytes held at once for {} bytes of input",
        data.len()
    );
}

fuzz_target!(|data: &[u8]| {
    for (name, format) in EVAL_FORMATS {
        read_all(data, name, format);
    }
});
