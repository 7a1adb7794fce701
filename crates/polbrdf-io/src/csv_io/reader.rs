//! The streaming CSV record reader of every numeric table: one record per physical line, memory
//! bounded by one line.

use super::fields::check_header;
use super::message::short_name;
use crate::error::{Error, Result};
use std::io::BufRead;
use std::path::{Path, PathBuf};

/// The longest line a CSV reader accepts (bytes, line end excluded): a header of 10⁵ columns
/// fits; a longer line is an error naming it, so that no single line can exhaust memory.
pub const MAX_LINE_BYTES: usize = 1 << 20;
/// A streaming CSV reader for the project's numeric tables: one record per physical line.
///
/// Lines end at `\n`, `\r\n` or a lone `\r` (old Mac files), a UTF-8 BOM is skipped, blank lines
/// are skipped (and counted), fields are separated by `,` and may be quoted (`"a,b"`, `""` for a
/// quote). A quoted field never spans lines: none of our files has a newline inside a field, so
/// a quote still open at the end of a line is an error naming that line (the `csv` crate would
/// read the rest of the file into that field and silently drop every later row). Memory is
/// bounded by one line ([`MAX_LINE_BYTES`]), whatever the file's length.
pub struct CsvReader<R> {
    src: R,
    path: PathBuf,
    headers: Vec<String>,
    /// Physical line number of the last line read.
    line: usize,
    /// The raw bytes of the current line.
    raw: Vec<u8>,
    /// The unquoted text of the current record's fields, and each field's range in it.
    text: String,
    fields: Vec<std::ops::Range<usize>>,
    /// A lone `\r` ended the last line: a `\n` right after it belongs to it.
    after_cr: bool,
}

impl<R> std::fmt::Debug for CsvReader<R> {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("CsvReader")
            .field("path", &self.path)
            .field("line", &self.line)
            .finish_non_exhaustive()
    }
}

/// One record of a [`CsvReader`].
#[derive(Debug, Clone, Copy)]
pub struct Record<'a> {
    /// 1-based physical line.
    pub line: usize,
    text: &'a str,
    fields: &'a [std::ops::Range<usize>],
}

impl<'a> Record<'a> {
    /// Field `k` (unquoted, untrimmed).
    pub fn get(&self, k: usize) -> &'a str {
        &self.text[self.fields[k].clone()]
    }

    /// Number of fields.
    pub fn len(&self) -> usize {
        self.fields.len()
    }

    /// True for a record without fields (never returned by the reader).
    pub fn is_empty(&self) -> bool {
        self.fields.is_empty()
    }

    /// Every field, in order.
    pub fn iter(&self) -> impl Iterator<Item = &'a str> + '_ {
        self.fields.iter().map(|r| &self.text[r.clone()])
    }
}

impl CsvReader<Box<dyn BufRead>> {
    /// Opens `path` (`-` = standard input, read as a stream) and reads its header.
    ///
    /// # Errors
    /// [`Error::Read`] when it cannot be opened; else as [`CsvReader::new`].
    pub fn open(path: &Path) -> Result<Self> {
        let src: Box<dyn BufRead> = if path.as_os_str() == "-" {
            Box::new(std::io::stdin().lock())
        } else {
            let file = std::fs::File::open(path).map_err(|source| Error::Read {
                path: path.to_path_buf(),
                source,
            })?;
            Box::new(std::io::BufReader::with_capacity(1 << 16, file))
        };
        Self::new(src, path)
    }
}

impl<R: BufRead> CsvReader<R> {
    /// Reads the header line from `src`; `path` is used in messages only.
    ///
    /// # Errors
    /// [`Error::File`] for an empty file; [`Error::Syntax`] for bad UTF-8, an unclosed quote,
    /// a line over [`MAX_LINE_BYTES`] or a column named twice.
    pub fn new(src: R, path: &Path) -> Result<Self> {
        let mut r = Self {
            src,
            path: path.to_path_buf(),
            headers: Vec::new(),
            line: 0,
            raw: Vec::new(),
            text: String::new(),
            fields: Vec::new(),
            after_cr: false,
        };
        // The header is the first line that is not blank.
        while r.next_line()? && r.fields.is_empty() {}
        if !r.fields.is_empty() {
            r.headers = r
                .fields
                .iter()
                .map(|f| r.text[f.clone()].trim().to_string())
                .collect();
        }
        if r.headers.is_empty() || r.headers.iter().all(String::is_empty) {
            return Err(r.file_error("empty file: expected a header line naming the columns"));
        }
        let mut seen = std::collections::HashSet::with_capacity(r.headers.len());
        for h in &r.headers {
            if !seen.insert(h.as_str()) {
                return Err(Error::Syntax {
                    path: r.path.clone(),
                    line: r.line,
                    message: format!("column `{}` appears twice in the header", short_name(h)),
                });
            }
        }
        Ok(r)
    }

    /// The header's names (surrounding whitespace trimmed).
    pub fn headers(&self) -> &[String] {
        &self.headers
    }

    /// The file name used in messages.
    pub fn path(&self) -> &Path {
        &self.path
    }

    fn file_error(&self, message: &str) -> Error {
        Error::File {
            path: self.path.clone(),
            message: message.to_string(),
        }
    }

    /// The column index of each of `required`.
    ///
    /// # Errors
    /// [`Error::File`] naming the missing columns (and the header, shortened).
    pub fn require(&self, required: &[&str]) -> Result<Vec<usize>> {
        check_header(&self.headers, &self.path, required)
    }

    /// The next record, or `None` at the end of the file.
    ///
    /// # Errors
    /// [`Error::Read`]; [`Error::Syntax`] naming the line for bad UTF-8, an unclosed quote, a
    /// line over [`MAX_LINE_BYTES`] or a field count different from the header's.
    pub fn next_record(&mut self) -> Result<Option<Record<'_>>> {
        loop {
            if !self.next_line()? {
                return Ok(None);
            }
            if self.fields.is_empty() {
                continue; // a blank line
            }
            if self.fields.len() != self.headers.len() {
                return Err(Error::Syntax {
                    path: self.path.clone(),
                    line: self.line,
                    message: format!(
                        "row has {} fields, the header has {}",
                        self.fields.len(),
                        self.headers.len()
                    ),
                });
            }
            return Ok(Some(Record {
                line: self.line,
                text: &self.text,
                fields: &self.fields,
            }));
        }
    }

    fn syntax(&self, message: String) -> Error {
        Error::Syntax {
            path: self.path.clone(),
            line: self.line,
            message,
        }
    }

    /// Reads one physical line into `raw` and splits it into `fields` (none for a blank line);
    /// false at the end of the file.
    fn next_line(&mut self) -> Result<bool> {
        self.raw.clear();
        let mut ended = false;
        let mut any = false;
        while !ended {
            let buf = self.src.fill_buf().map_err(|source| Error::Read {
                path: self.path.clone(),
                source,
            })?;
            if buf.is_empty() {
                break;
            }
            let mut start = 0;
            if self.after_cr {
                self.after_cr = false;
                if buf[0] == b'\n' {
                    start = 1;
                }
            }
            let (take, used) = match buf[start..].iter().position(|&b| b == b'\n' || b == b'\r') {
                Some(i) => {
                    ended = true;
                    if buf[start + i] == b'\r' {
                        self.after_cr = true;
                    }
                    (start + i, start + i + 1)
                }
                None => (buf.len(), buf.len()),
            };
            any |= take > start || ended;
            if self.raw.len() + (take - start) > MAX_LINE_BYTES {
                self.line += 1;
                return Err(self.syntax(format!(
                    "line longer than {MAX_LINE_BYTES} bytes (is this a CSV file?)"
                )));
            }
            self.raw.extend_from_slice(&buf[start..take]);
            self.src.consume(used);
        }
        if !any {
            return Ok(false);
        }
        self.line += 1;
        let mut bytes = &self.raw[..];
        if self.line == 1 {
            bytes = bytes.strip_prefix(b"\xef\xbb\xbf").unwrap_or(bytes);
        }
        let line = std::str::from_utf8(bytes)
            .map_err(|_| self.syntax("not valid UTF-8 text (is this a CSV file?)".into()))?;
        self.text.clear();
        self.fields.clear();
        if line.is_empty() {
            return Ok(true);
        }
        // Fields as the csv crate reads them: a field that starts with `"` is quoted up to the
        // next lone `"` (`""` is a quote), anything after that up to the comma is kept as is.
        let mut chars = line.chars().peekable();
        loop {
            let begin = self.text.len();
            if chars.peek() == Some(&'"') {
                chars.next();
                let mut closed = false;
                while let Some(c) = chars.next() {
                    if c == '"' {
                        if chars.peek() == Some(&'"') {
                            chars.next();
                            self.text.push('"');
                        } else {
                            closed = true;
                            break;
                        }
                    } else {
                        self.text.push(c);
                    }
                }
                if !closed {
                    return Err(self.syntax(
                        "a quote opened on this line is not closed on it (a field cannot span \
                         lines)"
                            .into(),
                    ));
                }
            }
            let mut more = false;
            for c in chars.by_ref() {
                if c == ',' {
                    more = true;
                    break;
                }
                self.text.push(c);
            }
            self.fields.push(begin..self.text.len());
            if !more {
                break;
            }
        }
        Ok(true)
    }
}

/// Reads every record of `reader`, calling `row` on each: the streaming loop of the numeric
/// readers.
pub(super) fn for_each_record<R: BufRead>(
    reader: &mut CsvReader<R>,
    mut row: impl FnMut(&Record<'_>) -> Result<()>,
) -> Result<()> {
    while let Some(r) = reader.next_record()? {
        row(&r)?;
    }
    Ok(())
}
