//! The types a table's readers and writers share, whatever the format (CSV, `.npy`, Arrow):
//! a column of an Arrow input ([`Column`], [`Kind`]) and what `eval` computes for a row
//! ([`RowResult`], [`result_values`]). They live here so that the format modules use them
//! without using each other: `stream` dispatches to `csv_io`, `npy` and `arrow`, and none of
//! those uses `stream` (issue 33's cycle `stream ↔ csv_io ↔ npy ↔ arrow`).

use polbrdf::Mueller;

/// One input column of a chunk, column-major (Arrow input).
#[derive(Debug, Clone, PartialEq)]
pub enum Column {
    /// Numbers (any numeric Arrow type, as f64).
    Numbers(Vec<f64>),
    /// Text, passed through as written.
    Text(Vec<String>),
}

impl Column {
    /// The kind of the column.
    pub fn kind(&self) -> Kind {
        match self {
            Column::Numbers(_) => Kind::Number,
            Column::Text(_) => Kind::Text,
        }
    }
}

/// The kind of a column: numbers or text.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Kind {
    /// Numbers (Float64 in an Arrow output).
    Number,
    /// Text (Utf8 in an Arrow output).
    Text,
}

/// What `eval` computes for one row: the pBRDF, and its BRDF, DoLP and AoLP (rad) as the core
/// defines them once, by `polbrdf::Engine::brdf_dolp_aolp_into` — the numbers of `lut` and of
/// the Python module, bit for bit (the DoLP of the matrix's first column through `Stokes::dolp`
/// differed from them in the last bit in about a third of the rows: issue 35).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RowResult {
    /// The pBRDF F (psps basis, sr⁻¹).
    pub pbrdf: Mueller,
    /// BRDF, DoLP and AoLP (rad) of F·(1, 0, 0, 0), from the engine.
    pub brdf_dolp_aolp: [f64; 3],
}

/// The 19 numbers `eval` appends for one row: brdf, dolp, aolp_deg, then F row-major.
pub fn result_values(r: &RowResult) -> [f64; 19] {
    let [brdf, dolp, aolp] = r.brdf_dolp_aolp;
    let mut v = [0.0; 19];
    v[0] = brdf;
    v[1] = dolp;
    v[2] = aolp.to_degrees();
    v[3..].copy_from_slice(&r.pbrdf.to_row_major());
    v
}
