//! The project's one CSV writer: numbers in shortest round-trip text, tables of a header and
//! rows, and the result table of `polbrdf eval`.

use super::geometry::GeometryTable;
use crate::error::{Error, Result};

/// The columns `polbrdf eval` appends: `brdf, dolp, aolp_deg, m00 … m33`.
pub fn result_columns() -> Vec<String> {
    let mut cols = vec!["brdf".to_string(), "dolp".into(), "aolp_deg".into()];
    cols.extend(polbrdf::Mueller::COLUMNS.map(String::from));
    cols
}

/// Shortest round-trip text of a finite `f64` (`-0.0` printed as `0.0`).
pub fn fmt_f64(v: f64) -> String {
    let mut b = Vec::with_capacity(24);
    fmt_f64_into(v, &mut b);
    String::from_utf8(b).expect("ASCII")
}

/// Appends [`fmt_f64`]'s text of `v` to `out`, without allocating: shortest round-trip digits
/// by `zmij` (Schubfach), in the notation of Rust's `{:?}` — zmij writes `[1e-5, 1e-4)` in
/// positional notation and exponents from 1e16 on with a `+`, which are rewritten here (tested
/// against `{:?}`). Where two last digits are equally short and both round-trip, zmij's choice
/// may differ from Rust's: the value read back is the same.
pub fn fmt_f64_into(v: f64, out: &mut Vec<u8>) {
    let v = v + 0.0;
    let mut b = zmij::Buffer::new();
    let text = b.format(v).as_bytes();
    let a = v.abs();
    if (1e-5..1e-4).contains(&a) {
        // "0.0000d…" (or "-0.0000d…") → "d.…e-5".
        let (sign, digits) = match text.split_first() {
            Some((b'-', rest)) => (&text[..1], rest),
            _ => (&text[..0], text),
        };
        match digits.strip_prefix(b"0.0000") {
            Some(d) if !d.is_empty() => {
                out.extend_from_slice(sign);
                out.push(d[0]);
                if d.len() > 1 {
                    out.push(b'.');
                    out.extend_from_slice(&d[1..]);
                }
                out.extend_from_slice(b"e-5");
            }
            _ => out.extend_from_slice(text),
        }
    } else if a >= 1e16 {
        out.extend(text.iter().filter(|c| **c != b'+'));
    } else {
        out.extend_from_slice(text);
    }
}

/// The project's one CSV writer: a header, then rows of fields — numbers in shortest
/// round-trip form ([`fmt_f64`]), text quoted where CSV needs it.
#[derive(Debug)]
pub struct CsvTable {
    w: csv::Writer<Vec<u8>>,
}

impl CsvTable {
    /// A table with these column names.
    pub fn new<S: AsRef<str>>(header: impl IntoIterator<Item = S>) -> Self {
        let mut t = Self {
            w: csv::Writer::from_writer(Vec::new()),
        };
        t.fields(header);
        t
    }

    /// The document of a header and rows of numbers.
    pub fn document<S: AsRef<str>, R: AsRef<[f64]>>(
        header: impl IntoIterator<Item = S>,
        rows: impl IntoIterator<Item = R>,
    ) -> Vec<u8> {
        let mut t = Self::new(header);
        for row in rows {
            t.row(row.as_ref());
        }
        t.into_bytes()
    }

    /// Appends a row of numbers.
    pub fn row(&mut self, values: &[f64]) {
        self.fields(values.iter().map(|v| fmt_f64(*v)));
    }

    /// Appends a row of text fields.
    pub fn fields<S: AsRef<str>>(&mut self, fields: impl IntoIterator<Item = S>) {
        self.w
            .write_record(fields.into_iter().map(|f| f.as_ref().to_string()))
            .expect("writing to memory cannot fail");
    }

    /// The document.
    pub fn into_bytes(self) -> Vec<u8> {
        self.w.into_inner().expect("writing to memory cannot fail")
    }
}

/// The result CSV of `polbrdf eval`: the input columns unchanged, then `brdf, dolp, aolp_deg,
/// m00 … m33` (F row-major, psps basis, sr⁻¹) for each row's result in `pbrdf`.
///
/// # Errors
/// [`Error::File`] when an input column has the name of an output column.
pub fn results_csv(table: &GeometryTable, pbrdf: &[crate::table::RowResult]) -> Result<Vec<u8>> {
    let extra = result_columns();
    if let Some(clash) = table.headers.iter().find(|h| extra.contains(h)) {
        return Err(Error::File {
            path: table.path.clone(),
            message: format!("input column `{clash}` has the name of an output column; rename it"),
        });
    }
    let mut t = CsvTable::new(table.headers.iter().chain(extra.iter()));
    for (row, f) in table.rows.iter().zip(pbrdf) {
        let mut fields: Vec<String> = row.clone();
        fields.extend(crate::table::result_values(f).iter().map(|v| fmt_f64(*v)));
        t.fields(fields);
    }
    Ok(t.into_bytes())
}

#[cfg(test)]
mod tests {
    #[test]
    fn fast_float_text_round_trips_in_rusts_notation() {
        // Every magnitude from subnormals to 1e300, with awkward mantissas.
        let mut x: u64 = 0x9E37_79B9_7F4A_7C15;
        for e in -320..300 {
            for _ in 0..40 {
                x ^= x << 13;
                x ^= x >> 7;
                x ^= x << 17;
                let m = 1.0 + (x >> 11) as f64 / (1u64 << 53) as f64;
                for v in [
                    m * 10f64.powi(e),
                    -m * 10f64.powi(e),
                    10f64.powi(e),
                    5.0 * 10f64.powi(e),
                ] {
                    same_value_and_notation(v);
                }
            }
        }
        for v in [
            0.0,
            -0.0,
            1.0,
            0.1,
            1e-4,
            1e-5,
            9.99e-5,
            1e16,
            9.999e15,
            f64::MAX,
            f64::MIN_POSITIVE,
        ] {
            same_value_and_notation(v);
        }
    }

    fn same_value_and_notation(v: f64) {
        let mut b = Vec::new();
        super::fmt_f64_into(v, &mut b);
        let ours = String::from_utf8(b).unwrap();
        let rust = format!("{:?}", v + 0.0);
        assert_eq!(
            ours.parse::<f64>().unwrap().to_bits(),
            (v + 0.0).to_bits(),
            "{ours}"
        );
        assert_eq!(ours.len(), rust.len(), "{ours} vs {rust}");
        assert_eq!(ours.contains('e'), rust.contains('e'), "{ours} vs {rust}");
    }
}
