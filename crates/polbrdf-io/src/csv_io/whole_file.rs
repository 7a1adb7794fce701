//! Small files read whole (material, scene, `lut` configuration, refractive-index and whole
//! `.npy` files): their size bounded, their text checked as UTF-8 with the line named, and line
//! ends counted as the CSV reader counts them.

use crate::error::{Error, Result};
use std::io::Read;
use std::path::Path;

/// The most bytes of a file read whole (`read_all`: material, scene, `lut` configuration,
/// refractive-index and whole `.npy` files): 16 MiB, far above any such file (the library's
/// largest index file is under 100 kB), so that a device or a huge file named by mistake
/// (`--material /dev/zero`) is an error naming it instead of a read until memory runs out.
pub const MAX_WHOLE_FILE_BYTES: u64 = 16 << 20;

/// The bytes of `path`, or of standard input for `-`, read whole (for the small files only:
/// material, scene and refractive-index files; every CSV reader streams,
/// [`CsvReader`](crate::csv_io::CsvReader)), at most [`MAX_WHOLE_FILE_BYTES`].
///
/// # Errors
/// [`Error::Read`]; [`Error::File`] for a file longer than the bound.
pub(crate) fn read_all(path: &Path) -> Result<Vec<u8>> {
    let read_err = |source| Error::Read {
        path: path.to_path_buf(),
        source,
    };
    let src: Box<dyn Read> = if path.as_os_str() == "-" {
        Box::new(std::io::stdin())
    } else {
        Box::new(std::fs::File::open(path).map_err(read_err)?)
    };
    let mut buf = Vec::new();
    // One byte past the bound tells a file at the bound from a longer one.
    src.take(MAX_WHOLE_FILE_BYTES + 1)
        .read_to_end(&mut buf)
        .map_err(read_err)?;
    if buf.len() as u64 > MAX_WHOLE_FILE_BYTES {
        return Err(Error::File {
            path: path.to_path_buf(),
            message: format!(
                "longer than {} MiB: this file is read whole, and no file of its kind is that \
                 long (is it the file meant?)",
                MAX_WHOLE_FILE_BYTES >> 20
            ),
        });
    }
    Ok(buf)
}

/// The 1-based line of byte `pos` of `text` (for TOML spans).
pub(crate) fn line_of(text: &str, pos: usize) -> usize {
    text.as_bytes()[..pos.min(text.len())]
        .iter()
        .filter(|&&b| b == b'\n')
        .count()
        + 1
}

/// The text of `path` ([`read_all`]); bytes that are not UTF-8 are an error naming the line.
pub(crate) fn read_text(path: &Path) -> Result<String> {
    String::from_utf8(read_all(path)?).map_err(|e| {
        let pos = e.utf8_error().valid_up_to();
        Error::Syntax {
            path: path.to_path_buf(),
            line: line_of(&String::from_utf8_lossy(&e.as_bytes()[..pos]), pos),
            message: "file is not valid UTF-8 text".into(),
        }
    })
}
/// `text` with every lone `\r` (an old Mac line end) made a `\n`, so that the TOML readers
/// count lines as the CSV readers do (`\n`, `\r\n` or `\r`); `\r\n` is kept.
pub(crate) fn lone_cr_to_lf(text: &str) -> std::borrow::Cow<'_, str> {
    let b = text.as_bytes();
    let lone = |i: usize| b[i] == b'\r' && b.get(i + 1) != Some(&b'\n');
    if !(0..b.len()).any(lone) {
        return std::borrow::Cow::Borrowed(text);
    }
    let out: Vec<u8> = (0..b.len())
        .map(|i| if lone(i) { b'\n' } else { b[i] })
        .collect();
    // Only ASCII bytes were replaced by ASCII bytes.
    std::borrow::Cow::Owned(String::from_utf8(out).expect("still UTF-8"))
}
