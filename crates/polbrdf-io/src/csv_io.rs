//! Geometry CSV in, result CSV out (the `polbrdf eval` contract in the README).

use crate::error::{Error, Result};
use polbrdf::{Geometry, Mueller, Stokes};
use std::io::Read;
use std::path::{Path, PathBuf};

/// The four angle columns every geometry file must have (degrees, any order).
pub const ANGLE_COLUMNS: [&str; 4] = ["theta_i_deg", "phi_i_deg", "theta_r_deg", "phi_r_deg"];

/// The columns `polbrdf eval` appends: `brdf, dolp, aolp_deg, m00 … m33`.
pub fn result_columns() -> Vec<String> {
    let mut cols = vec!["brdf".to_string(), "dolp".into(), "aolp_deg".into()];
    cols.extend((0..16).map(|k| format!("m{}{}", k / 4, k % 4)));
    cols
}

/// A parsed geometry file: the raw rows (copied through unchanged) and the validated
/// geometries.
#[derive(Debug, Clone)]
pub struct GeometryTable {
    /// Where it came from (`-` for standard input).
    pub path: PathBuf,
    /// Header names as written (surrounding whitespace trimmed).
    pub headers: Vec<String>,
    /// Every data row's fields, unchanged.
    pub rows: Vec<Vec<String>>,
    /// 1-based line number of each row.
    pub lines: Vec<usize>,
    /// One validated geometry per row.
    pub geometries: Vec<Geometry>,
    /// The `wavelength_um` column (µm, finite and > 0), when the file has one: the wavelength
    /// of each row for a spectral material (the column is also copied through).
    pub wavelengths: Option<Vec<f64>>,
}

/// The optional wavelength column of geometry and measurement files (µm).
pub const WAVELENGTH_COLUMN: &str = "wavelength_um";

/// The bytes of `path`, or of standard input for `-`.
pub(crate) fn read_all(path: &Path) -> Result<Vec<u8>> {
    let read_err = |source| Error::Read {
        path: path.to_path_buf(),
        source,
    };
    if path.as_os_str() == "-" {
        let mut buf = Vec::new();
        std::io::stdin().read_to_end(&mut buf).map_err(read_err)?;
        Ok(buf)
    } else {
        std::fs::read(path).map_err(read_err)
    }
}

/// A CSV file as text fields.
struct RawTable {
    headers: Vec<String>,
    rows: Vec<Vec<String>>,
    /// 1-based line of each row.
    lines: Vec<usize>,
    /// Column index of each required column.
    index: Vec<usize>,
}

/// Parses CSV text whose header names columns, with `required` columns among them; `path` is
/// used in messages only.
fn parse_table(bytes: &[u8], path: &Path, required: &[&str]) -> Result<RawTable> {
    let bytes = bytes.strip_prefix(b"\xef\xbb\xbf").unwrap_or(bytes);
    if let Err(e) = std::str::from_utf8(bytes) {
        let line = bytes[..e.valid_up_to()]
            .iter()
            .filter(|&&b| b == b'\n')
            .count()
            + 1;
        return Err(Error::Syntax {
            path: path.to_path_buf(),
            line,
            message: "not valid UTF-8 text (is this a CSV file?)".into(),
        });
    }
    let mut reader = csv::ReaderBuilder::new()
        .trim(csv::Trim::Headers)
        .flexible(false)
        .from_reader(bytes);
    // Physical line of a byte offset (the csv crate's own line count skips blank lines).
    let line_at = |byte: u64| {
        bytes[..(byte as usize).min(bytes.len())]
            .iter()
            .filter(|&&b| b == b'\n')
            .count()
            + 1
    };
    let syntax = |e: csv::Error| {
        let line = e.position().map_or(1, |p| line_at(p.byte()));
        let message = match e.kind() {
            csv::ErrorKind::UnequalLengths {
                expected_len, len, ..
            } => format!("row has {len} fields, the header has {expected_len}"),
            _ => e.to_string(),
        };
        Error::Syntax {
            path: path.to_path_buf(),
            line,
            message,
        }
    };
    let headers: Vec<String> = reader
        .headers()
        .map_err(syntax)?
        .iter()
        .map(str::to_string)
        .collect();
    let index = check_header(&headers, path, required)?;
    let mut rows = Vec::new();
    let mut lines = Vec::new();
    // Count newlines incrementally: rows come in file order.
    let (mut seen_byte, mut seen_line) = (0usize, 1usize);
    for record in reader.records() {
        let record = record.map_err(syntax)?;
        let mut byte = record
            .position()
            .map_or(0, |p| p.byte() as usize)
            .min(bytes.len());
        // The recorded position can sit before skipped blank lines.
        while byte < bytes.len() && matches!(bytes[byte], b'\n' | b'\r') {
            byte += 1;
        }
        seen_line += bytes[seen_byte..byte]
            .iter()
            .filter(|&&b| b == b'\n')
            .count();
        seen_byte = byte;
        lines.push(seen_line);
        rows.push(record.iter().map(str::to_string).collect());
    }
    Ok(RawTable {
        headers,
        rows,
        lines,
        index,
    })
}

/// Checks a table's header: not empty, no column twice, every `required` column present;
/// returns the index of each required column.
pub(crate) fn check_header(
    headers: &[String],
    path: &Path,
    required: &[&str],
) -> Result<Vec<usize>> {
    if headers.is_empty() || headers.iter().all(String::is_empty) {
        return Err(Error::File {
            path: path.to_path_buf(),
            message: format!(
                "empty file: expected a header line naming the columns {}",
                required.join(", ")
            ),
        });
    }
    for (i, h) in headers.iter().enumerate() {
        if headers[..i].contains(h) {
            return Err(Error::Syntax {
                path: path.to_path_buf(),
                line: 1,
                message: format!("column `{h}` appears twice in the header"),
            });
        }
    }
    let missing: Vec<&str> = required
        .iter()
        .copied()
        .filter(|r| !headers.iter().any(|h| h == r))
        .collect();
    if !missing.is_empty() {
        return Err(Error::File {
            path: path.to_path_buf(),
            message: format!(
                "missing column(s) {} (the header has: {})",
                missing.join(", "),
                headers.join(", ")
            ),
        });
    }
    Ok(required
        .iter()
        .map(|r| headers.iter().position(|h| h == r).expect("checked above"))
        .collect())
}

/// Parses a number in a CSV field (surrounding whitespace allowed).
pub(crate) fn parse_number(path: &Path, line: usize, column: &str, field: &str) -> Result<f64> {
    field.trim().parse::<f64>().map_err(|_| Error::Field {
        path: path.to_path_buf(),
        line,
        field: column.to_string(),
        message: format!("expected a number, got {:?}", truncate(field)),
    })
}

/// A number in a message: as it would be written, in exponent form when very large or small
/// (as the core's messages show values).
pub(crate) fn show(v: f64) -> String {
    if v == 0.0 || !v.is_finite() || (1e-5..1e16).contains(&v.abs()) {
        format!("{v}")
    } else {
        format!("{v:e}")
    }
}

fn truncate(s: &str) -> String {
    if s.chars().count() > 40 {
        s.chars().take(40).collect::<String>() + "…"
    } else {
        s.to_string()
    }
}

/// Reads a geometry CSV (`-` = standard input): a header holding `theta_i_deg, phi_i_deg,
/// theta_r_deg, phi_r_deg` in any order, other columns kept as they are.
///
/// # Errors
/// [`Error::Read`], [`Error::Syntax`] (bad CSV or UTF-8, with the line), [`Error::File`] (empty
/// file, missing columns), [`Error::Field`] (a non-number or an invalid angle, with line and
/// column).
pub fn read_geometry_csv(path: &Path) -> Result<GeometryTable> {
    parse_geometry_csv(&read_all(path)?, path)
}

/// Parses the bytes of a geometry CSV; `path` is used in messages only.
///
/// # Errors
/// As [`read_geometry_csv`], except [`Error::Read`].
pub fn parse_geometry_csv(bytes: &[u8], path: &Path) -> Result<GeometryTable> {
    let RawTable {
        headers,
        rows,
        lines,
        index: idx,
    } = parse_table(bytes, path, &ANGLE_COLUMNS)?;
    let mut geometries = Vec::with_capacity(rows.len());
    for (row, &line) in rows.iter().zip(&lines) {
        let fields = [0, 1, 2, 3].map(|k| row[idx[k]].as_str());
        geometries.push(row_geometry(path, line, fields)?);
    }
    let wavelengths = match headers.iter().position(|h| h == WAVELENGTH_COLUMN) {
        None => None,
        Some(c) => Some(
            rows.iter()
                .zip(&lines)
                .map(|(row, &line)| row_wavelength(path, line, &row[c]))
                .collect::<Result<Vec<f64>>>()?,
        ),
    };
    Ok(GeometryTable {
        path: path.to_path_buf(),
        headers,
        rows,
        lines,
        geometries,
        wavelengths,
    })
}

/// The geometry of a row from its four angle fields (in [`ANGLE_COLUMNS`] order, degrees).
pub(crate) fn row_geometry(path: &Path, line: usize, fields: [&str; 4]) -> Result<Geometry> {
    let mut deg = [0.0; 4];
    for (k, d) in deg.iter_mut().enumerate() {
        *d = parse_number(path, line, ANGLE_COLUMNS[k], fields[k])?;
    }
    geometry_of_degrees(path, line, deg)
}

/// The geometry of four angles in degrees ([`ANGLE_COLUMNS`] order) at a row's line; an
/// invalid angle is an error naming its column.
pub(crate) fn geometry_of_degrees(path: &Path, line: usize, deg: [f64; 4]) -> Result<Geometry> {
    Geometry::from_degrees(deg[0], deg[1], deg[2], deg[3]).map_err(|e| {
        let field = match &e {
            polbrdf::Error::InvalidAngle { name, .. } => name.to_string(),
            _ => "angles".to_string(),
        };
        Error::Field {
            path: path.to_path_buf(),
            line,
            field,
            message: e.to_string(),
        }
    })
}

/// A row's `wavelength_um` field: a number, finite and > 0 (µm).
pub(crate) fn row_wavelength(path: &Path, line: usize, field: &str) -> Result<f64> {
    check_wavelength(
        path,
        line,
        parse_number(path, line, WAVELENGTH_COLUMN, field)?,
    )
}

/// A wavelength (µm) at a row's line: finite and > 0.
pub(crate) fn check_wavelength(path: &Path, line: usize, v: f64) -> Result<f64> {
    if v.is_finite() && v > 0.0 {
        Ok(v)
    } else {
        Err(Error::Field {
            path: path.to_path_buf(),
            line,
            field: WAVELENGTH_COLUMN.into(),
            message: format!("{v}: a wavelength must be finite and > 0 (µm)"),
        })
    }
}

/// The columns of a band file: the wavelength (µm) and the relative spectral response.
pub const BAND_COLUMNS: [&str; 2] = ["wavelength_um", "response"];

/// Reads a band file (CSV with columns `wavelength_um, response`: a relative spectral response,
/// linear between the rows and zero outside, wavelengths strictly increasing).
///
/// # Errors
/// [`Error::Field`] naming the file, the line and the column for a malformed or invalid value;
/// [`Error::File`] for a missing column, fewer than two rows, or a response zero everywhere.
pub fn read_band_csv(path: &Path) -> Result<polbrdf::Band> {
    parse_band_csv(&read_all(path)?, path)
}

/// Parses band CSV bytes ([`read_band_csv`]); `path` is used in messages only.
///
/// # Errors
/// As [`read_band_csv`].
pub fn parse_band_csv(bytes: &[u8], path: &Path) -> Result<polbrdf::Band> {
    let RawTable {
        rows, lines, index, ..
    } = parse_table(bytes, path, &BAND_COLUMNS)?;
    let mut wl = Vec::with_capacity(rows.len());
    let mut response = Vec::with_capacity(rows.len());
    for (row, &line) in rows.iter().zip(&lines) {
        wl.push(parse_number(path, line, BAND_COLUMNS[0], &row[index[0]])?);
        response.push(parse_number(path, line, BAND_COLUMNS[1], &row[index[1]])?);
    }
    let name = path.file_name().map_or_else(
        || path.display().to_string(),
        |n| n.to_string_lossy().into_owned(),
    );
    polbrdf::Band::new(&name, wl, response).map_err(|e| row_error(path, &lines, e))
}

/// A core error about the row `index` of a table (`InvalidParameterAt`) at that row's line;
/// any other as an error of the whole file.
fn row_error(path: &Path, lines: &[usize], e: polbrdf::Error) -> Error {
    match e {
        polbrdf::Error::InvalidParameterAt { name, index, .. } => Error::Field {
            path: path.to_path_buf(),
            line: lines[index],
            field: name.to_string(),
            message: e.to_string(),
        },
        other => Error::File {
            path: path.to_path_buf(),
            message: other.to_string(),
        },
    }
}

/// The columns of a sky profile file: the zenith angle of a sky point (degrees) and the sky's
/// spectral radiance there (W·m⁻²·sr⁻¹·µm⁻¹).
pub const SKY_PROFILE_COLUMNS: [&str; 2] = ["zenith_deg", "radiance"];

/// Reads a sky profile file (CSV with columns `zenith_deg, radiance` in any order: an
/// unpolarized sky's radiance by zenith angle, linear between the rows, zenith angles strictly
/// increasing from 0° to 90°; [`polbrdf::analysis::sky::ZenithProfile`]).
///
/// # Errors
/// [`Error::Field`] naming the file, the line and the column for a malformed or invalid value
/// (a zenith angle outside [0°, 90°] or not above the previous one, a radiance that is not
/// finite and ≥ 0); [`Error::File`] for a missing column, fewer than two rows, or a table that
/// does not start at 0° and end at 90°.
pub fn read_sky_profile_csv(path: &Path) -> Result<polbrdf::analysis::sky::ZenithProfile> {
    parse_sky_profile_csv(&read_all(path)?, path)
}

/// Parses sky profile CSV bytes ([`read_sky_profile_csv`]); `path` is used in messages only.
///
/// # Errors
/// As [`read_sky_profile_csv`].
pub fn parse_sky_profile_csv(
    bytes: &[u8],
    path: &Path,
) -> Result<polbrdf::analysis::sky::ZenithProfile> {
    let RawTable {
        rows, lines, index, ..
    } = parse_table(bytes, path, &SKY_PROFILE_COLUMNS)?;
    let mut zenith = Vec::with_capacity(rows.len());
    let mut radiance = Vec::with_capacity(rows.len());
    for (row, &line) in rows.iter().zip(&lines) {
        zenith.push(parse_number(
            path,
            line,
            SKY_PROFILE_COLUMNS[0],
            &row[index[0]],
        )?);
        radiance.push(parse_number(
            path,
            line,
            SKY_PROFILE_COLUMNS[1],
            &row[index[1]],
        )?);
    }
    polbrdf::analysis::sky::ZenithProfile::new(zenith, radiance)
        .map_err(|e| row_error(path, &lines, e))
}

/// The columns of a sky table file: the direction of a sky point (zenith angle and azimuth,
/// degrees) and the Stokes radiance arriving from it, in the arriving beam's psps basis.
pub const SKY_TABLE_COLUMNS: [&str; 6] = ["theta_deg", "phi_deg", "s0", "s1", "s2", "s3"];

/// Reads a sky table file (CSV with columns `theta_deg, phi_deg, s0, s1, s2, s3` in any order,
/// other columns ignored; [`polbrdf::analysis::sky::TableSky`]): the Stokes radiance of a sky
/// on a full grid of zenith angles × azimuths. The rows may come in any order; the grid is
/// made of the distinct zenith angles (which must include 0° and 90°) and the distinct
/// azimuths (in `[0°, 360°)`: the table is periodic, 360° is 0°), and every node of it must be
/// given exactly once.
///
/// # Errors
/// [`Error::Field`] naming the file, the line and the column for a malformed value, an angle
/// out of range, a non-finite Stokes parameter, `s0 < 0` or a degree of polarization above 1,
/// and for a node given twice (naming both lines); [`Error::File`] for a missing column, a
/// file without rows, a grid with a hole (naming the missing node and the grid) or zenith
/// angles that do not span 0° to 90°.
pub fn read_sky_table_csv(path: &Path) -> Result<polbrdf::analysis::sky::TableSky> {
    parse_sky_table_csv(&read_all(path)?, path)
}

/// Parses sky table CSV bytes ([`read_sky_table_csv`]); `path` is used in messages only.
///
/// # Errors
/// As [`read_sky_table_csv`].
pub fn parse_sky_table_csv(bytes: &[u8], path: &Path) -> Result<polbrdf::analysis::sky::TableSky> {
    let RawTable {
        rows, lines, index, ..
    } = parse_table(bytes, path, &SKY_TABLE_COLUMNS)?;
    let field = |line: usize, column: &str, message: String| Error::Field {
        path: path.to_path_buf(),
        line,
        field: column.to_string(),
        message,
    };
    if rows.is_empty() {
        return Err(Error::File {
            path: path.to_path_buf(),
            message: "no rows (the file has a header but no sky nodes)".into(),
        });
    }
    // Every row's values, its angles checked (−0 read as 0).
    let mut values = Vec::with_capacity(rows.len());
    for (row, &line) in rows.iter().zip(&lines) {
        let mut v = [0.0; 6];
        for (k, x) in v.iter_mut().enumerate() {
            *x = parse_number(path, line, SKY_TABLE_COLUMNS[k], &row[index[k]])? + 0.0;
        }
        if !(v[0].is_finite() && (0.0..=90.0).contains(&v[0])) {
            return Err(field(
                line,
                SKY_TABLE_COLUMNS[0],
                format!("{}: a zenith angle must lie in [0°, 90°]", show(v[0])),
            ));
        }
        if !(v[1].is_finite() && (0.0..360.0).contains(&v[1])) {
            return Err(field(
                line,
                SKY_TABLE_COLUMNS[1],
                format!(
                    "{}: an azimuth must lie in [0°, 360°) (the table is periodic in azimuth: \
                     give 360° as 0°, once)",
                    show(v[1])
                ),
            ));
        }
        values.push(v);
    }
    let distinct = |k: usize| {
        let mut a: Vec<f64> = values.iter().map(|v| v[k]).collect();
        a.sort_by(f64::total_cmp);
        a.dedup();
        a
    };
    let (theta, phi) = (distinct(0), distinct(1));
    let (nt, np) = (theta.len(), phi.len());
    let position = |a: &[f64], x: f64| a.binary_search_by(|v| v.total_cmp(&x)).expect("in it");
    // The row of each node, θ-major.
    let mut node_row: Vec<Option<usize>> = vec![None; nt * np];
    for (r, v) in values.iter().enumerate() {
        let node = position(&theta, v[0]) * np + position(&phi, v[1]);
        if let Some(first) = node_row[node] {
            return Err(field(
                lines[r],
                "theta_deg,phi_deg",
                format!(
                    "the node (theta_deg = {}, phi_deg = {}) is given twice: at lines {} and {}",
                    show(v[0]),
                    show(v[1]),
                    lines[first],
                    lines[r]
                ),
            ));
        }
        node_row[node] = Some(r);
    }
    if let Some(hole) = node_row.iter().position(Option::is_none) {
        let missing = node_row.iter().filter(|r| r.is_none()).count();
        let list = |a: &[f64]| {
            let shown: Vec<String> = if a.len() <= 12 {
                a.iter().map(|x| show(*x)).collect()
            } else {
                a[..5]
                    .iter()
                    .map(|x| show(*x))
                    .chain(["…".to_string()])
                    .chain(a[a.len() - 5..].iter().map(|x| show(*x)))
                    .collect()
            };
            shown.join(", ")
        };
        return Err(Error::File {
            path: path.to_path_buf(),
            message: format!(
                "the sky table has a hole: no row for the node (theta_deg = {}, phi_deg = {}); \
                 the grid of its zenith angles [{}] × azimuths [{}] has {} nodes, each needed \
                 once, and {} of them {} missing ({} rows given)",
                show(theta[hole / np]),
                show(phi[hole % np]),
                list(&theta),
                list(&phi),
                nt * np,
                missing,
                if missing == 1 { "is" } else { "are" },
                rows.len()
            ),
        });
    }
    let order: Vec<usize> = node_row.into_iter().map(|r| r.expect("no hole")).collect();
    let stokes = order
        .iter()
        .map(|&r| {
            let v = values[r];
            Stokes([v[2], v[3], v[4], v[5]])
        })
        .collect();
    let nodes = (theta.clone(), phi.clone());
    polbrdf::analysis::sky::TableSky::new(theta, phi, stokes).map_err(|e| match e {
        // The Stokes parameters are indexed by node (the angles cannot be wrong here): the
        // message names the node instead of its index.
        polbrdf::Error::InvalidParameterAt {
            name,
            value,
            index,
            reason,
        } if name.starts_with('s') && index < order.len() => field(
            lines[order[index]],
            name,
            format!(
                "invalid parameter `{name}` = {} (at the node theta_deg = {}, phi_deg = {}): \
                 {reason}",
                show(value),
                show(nodes.0[index / np]),
                show(nodes.1[index % np])
            ),
        ),
        other => Error::File {
            path: path.to_path_buf(),
            message: other.to_string(),
        },
    })
}

/// The columns of a view-direction file: the view zenith and azimuth angles in degrees.
pub const VIEW_COLUMNS: [&str; 2] = ["theta_r_deg", "phi_r_deg"];

/// Reads a view-direction file (CSV with columns `theta_r_deg, phi_r_deg` in any order; other
/// columns are ignored, so a geometry or result table can be reused) and returns the
/// `(θ_r, φ_r)` pairs in degrees, in file order.
///
/// # Errors
/// [`Error::Field`] naming the file, the line and the column for a value that is not a number,
/// a view zenith angle outside [0°, 90°) or a non-finite azimuth; [`Error::File`] for a missing
/// column or a file without rows.
pub fn read_views_csv(path: &Path) -> Result<Vec<(f64, f64)>> {
    parse_views_csv(&read_all(path)?, path)
}

/// Parses view-direction CSV bytes ([`read_views_csv`]); `path` is used in messages only.
///
/// # Errors
/// As [`read_views_csv`].
pub fn parse_views_csv(bytes: &[u8], path: &Path) -> Result<Vec<(f64, f64)>> {
    let RawTable {
        rows, lines, index, ..
    } = parse_table(bytes, path, &VIEW_COLUMNS)?;
    if rows.is_empty() {
        return Err(Error::File {
            path: path.to_path_buf(),
            message: "no view directions (the file has a header but no rows)".into(),
        });
    }
    let field = |line: usize, column: &str, message: String| Error::Field {
        path: path.to_path_buf(),
        line,
        field: column.to_string(),
        message,
    };
    let mut views = Vec::with_capacity(rows.len());
    for (row, &line) in rows.iter().zip(&lines) {
        let theta = parse_number(path, line, VIEW_COLUMNS[0], &row[index[0]])?;
        let phi = parse_number(path, line, VIEW_COLUMNS[1], &row[index[1]])?;
        if !(0.0..90.0).contains(&theta) {
            return Err(field(
                line,
                VIEW_COLUMNS[0],
                format!("{theta}: the view zenith angle must lie in [0, 90) degrees"),
            ));
        }
        if !phi.is_finite() {
            return Err(field(
                line,
                VIEW_COLUMNS[1],
                format!("{phi}: must be finite"),
            ));
        }
        views.push((theta, phi));
    }
    Ok(views)
}

/// Shortest round-trip text of a finite `f64` (`-0.0` printed as `0.0`).
pub fn fmt_f64(v: f64) -> String {
    let mut b = Vec::with_capacity(24);
    fmt_f64_into(v, &mut b);
    String::from_utf8(b).expect("ASCII")
}

/// Appends [`fmt_f64`]'s text of `v` to `out`, without allocating: shortest round-trip digits
/// by `ryu` in the notation of Rust's `{:?}` (Rust's own formatting is used in `[1e-5, 1e-4)`
/// and from 1e16 on, where ryu's notation differs). Where two last digits are equally short and
/// both round-trip, ryu's choice may differ from Rust's: the value read back is the same.
pub fn fmt_f64_into(v: f64, out: &mut Vec<u8>) {
    let v = v + 0.0;
    let a = v.abs();
    if !(1e-5..1e-4).contains(&a) && a < 1e16 {
        let mut b = ryu::Buffer::new();
        out.extend_from_slice(b.format(v).as_bytes());
    } else {
        use std::io::Write;
        write!(out, "{v:?}").expect("writing to memory cannot fail");
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
/// m00 … m33` (F row-major, psps basis, sr⁻¹) for each row's pBRDF in `pbrdf`.
///
/// # Errors
/// [`Error::File`] when an input column has the name of an output column.
pub fn results_csv(table: &GeometryTable, pbrdf: &[Mueller]) -> Result<Vec<u8>> {
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
        fields.extend(crate::stream::result_values(f).iter().map(|v| fmt_f64(*v)));
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
