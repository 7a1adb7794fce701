//! The sky files of a scene: an unpolarized sky's radiance by zenith angle (sky profile) and a
//! polarized sky's Stokes radiance on a grid of directions (sky table).

use super::fields::{parse_number, row_error};
use super::message::show;
use super::reader::{for_each_record, CsvReader, Record};
use crate::error::{Error, Result};
use polbrdf::analysis::sky::TableSky;
use polbrdf::Stokes;
use std::collections::hash_map::{Entry, HashMap};
use std::io::BufRead;
use std::path::Path;

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
    sky_profile_from(CsvReader::open(path)?)
}

/// Parses sky profile CSV bytes ([`read_sky_profile_csv`]); `path` is used in messages only.
///
/// # Errors
/// As [`read_sky_profile_csv`].
pub fn parse_sky_profile_csv(
    bytes: &[u8],
    path: &Path,
) -> Result<polbrdf::analysis::sky::ZenithProfile> {
    sky_profile_from(CsvReader::new(bytes, path)?)
}

fn sky_profile_from<R: BufRead>(
    mut reader: CsvReader<R>,
) -> Result<polbrdf::analysis::sky::ZenithProfile> {
    let index = reader.require(&SKY_PROFILE_COLUMNS)?;
    let path = reader.path().to_path_buf();
    let path = path.as_path();
    let (mut zenith, mut radiance, mut lines) = (Vec::new(), Vec::new(), Vec::new());
    for_each_record(&mut reader, |r| {
        zenith.push(parse_number(
            path,
            r.line,
            SKY_PROFILE_COLUMNS[0],
            r.get(index[0]),
        )?);
        radiance.push(parse_number(
            path,
            r.line,
            SKY_PROFILE_COLUMNS[1],
            r.get(index[1]),
        )?);
        lines.push(r.line);
        Ok(())
    })?;
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
pub fn read_sky_table_csv(path: &Path) -> Result<TableSky> {
    sky_table_from(CsvReader::open(path)?)
}

/// Parses sky table CSV bytes ([`read_sky_table_csv`]); `path` is used in messages only.
///
/// # Errors
/// As [`read_sky_table_csv`].
pub fn parse_sky_table_csv(bytes: &[u8], path: &Path) -> Result<TableSky> {
    sky_table_from(CsvReader::new(bytes, path)?)
}

/// The sky table of a reader: the rows read and checked, the grid their angles span, each
/// node's row found, then the core's table built (a short driver over the steps below).
fn sky_table_from<R: BufRead>(mut reader: CsvReader<R>) -> Result<TableSky> {
    let index = reader.require(&SKY_TABLE_COLUMNS)?;
    let path = reader.path().to_path_buf();
    let (values, lines) = sky_table_rows(&mut reader, &index)?;
    let grid = SkyGrid::of(&values);
    let order = sky_table_order(&path, &grid, &values, &lines)?;
    sky_table_of(&path, grid, &values, &lines, &order)
}

/// The values of one sky table row, in [`SKY_TABLE_COLUMNS`] order.
type SkyRow = [f64; 6];

/// An error about the field `column` of the row at `line` of the sky table `path`.
fn sky_field(path: &Path, line: usize, column: &str, message: String) -> Error {
    Error::Field {
        path: path.to_path_buf(),
        line,
        field: column.to_string(),
        message,
    }
}

/// Every row's values (columns at `index`) and line, each row's angles checked; an error for a
/// file without rows.
fn sky_table_rows<R: BufRead>(
    reader: &mut CsvReader<R>,
    index: &[usize],
) -> Result<(Vec<SkyRow>, Vec<usize>)> {
    let path = reader.path().to_path_buf();
    let path = path.as_path();
    let (mut values, mut lines) = (Vec::new(), Vec::new());
    for_each_record(reader, |r| {
        values.push(sky_table_row(path, r, index)?);
        lines.push(r.line);
        Ok(())
    })?;
    if values.is_empty() {
        return Err(Error::File {
            path: path.to_path_buf(),
            message: "no rows (the file has a header but no sky nodes)".into(),
        });
    }
    Ok((values, lines))
}

/// One record's values (−0 read as 0): numbers, the zenith angle in [0°, 90°] and the azimuth
/// in [0°, 360°) (the Stokes parameters are the core's to check).
fn sky_table_row(path: &Path, r: &Record<'_>, index: &[usize]) -> Result<SkyRow> {
    let line = r.line;
    let mut v = [0.0; 6];
    for (k, x) in v.iter_mut().enumerate() {
        *x = parse_number(path, line, SKY_TABLE_COLUMNS[k], r.get(index[k]))? + 0.0;
    }
    if !(v[0].is_finite() && (0.0..=90.0).contains(&v[0])) {
        return Err(sky_field(
            path,
            line,
            SKY_TABLE_COLUMNS[0],
            format!("{}: a zenith angle must lie in [0°, 90°]", show(v[0])),
        ));
    }
    if !(v[1].is_finite() && (0.0..360.0).contains(&v[1])) {
        return Err(sky_field(
            path,
            line,
            SKY_TABLE_COLUMNS[1],
            format!(
                "{}: an azimuth must lie in [0°, 360°) (the table is periodic in azimuth: \
                 give 360° as 0°, once)",
                show(v[1])
            ),
        ));
    }
    Ok(v)
}

/// The grid a sky table's rows span: their distinct zenith angles × distinct azimuths, each
/// increasing.
struct SkyGrid {
    theta: Vec<f64>,
    phi: Vec<f64>,
}

impl SkyGrid {
    /// The grid of the rows' angles.
    fn of(values: &[SkyRow]) -> Self {
        let distinct = |k: usize| {
            let mut a: Vec<f64> = values.iter().map(|v| v[k]).collect();
            a.sort_by(f64::total_cmp);
            a.dedup();
            a
        };
        Self {
            theta: distinct(0),
            phi: distinct(1),
        }
    }

    /// The (zenith index, azimuth index) of a row's node (its angles are in the grid).
    fn node(&self, v: &SkyRow) -> (usize, usize) {
        let position = |a: &[f64], x: f64| a.binary_search_by(|v| v.total_cmp(&x)).expect("in it");
        (position(&self.theta, v[0]), position(&self.phi, v[1]))
    }
}

/// The row of each node of `grid`, θ-major: an error naming both lines for a node given twice,
/// and one naming the first missing node for a grid with a hole. Memory by the rows, not by
/// the grid they span (10⁵ rows of distinct angles span 10¹⁰ nodes: issue 35).
fn sky_table_order(
    path: &Path,
    grid: &SkyGrid,
    values: &[SkyRow],
    lines: &[usize],
) -> Result<Vec<usize>> {
    let mut node_row: HashMap<(usize, usize), usize> = HashMap::with_capacity(values.len());
    for (r, v) in values.iter().enumerate() {
        match node_row.entry(grid.node(v)) {
            Entry::Occupied(first) => {
                return Err(sky_field(
                    path,
                    lines[r],
                    "theta_deg,phi_deg",
                    format!(
                        "the node (theta_deg = {}, phi_deg = {}) is given twice: at lines {} \
                         and {}",
                        show(v[0]),
                        show(v[1]),
                        lines[*first.get()],
                        lines[r]
                    ),
                ))
            }
            Entry::Vacant(e) => {
                e.insert(r);
            }
        }
    }
    // Every node given once: there are as many nodes as rows.
    let (nt, np) = (grid.theta.len(), grid.phi.len());
    if (node_row.len() as u128) < nt as u128 * np as u128 {
        return Err(sky_table_hole(
            path,
            &grid.theta,
            &grid.phi,
            &node_row,
            values.len(),
        ));
    }
    let mut order = vec![0; nt * np];
    for ((t, p), r) in node_row {
        order[t * np + p] = r;
    }
    Ok(order)
}

/// The core's sky table of the rows in node `order` on `grid`; an invalid Stokes parameter is
/// an error at its row's line naming its node.
fn sky_table_of(
    path: &Path,
    grid: SkyGrid,
    values: &[SkyRow],
    lines: &[usize],
    order: &[usize],
) -> Result<TableSky> {
    let stokes = order
        .iter()
        .map(|&r| {
            let v = values[r];
            Stokes([v[2], v[3], v[4], v[5]])
        })
        .collect();
    let np = grid.phi.len();
    let nodes = (grid.theta.clone(), grid.phi.clone());
    TableSky::new(grid.theta, grid.phi, stokes).map_err(|e| match e {
        // The Stokes parameters are indexed by node (the angles cannot be wrong here): the
        // message names the node instead of its index.
        polbrdf::Error::InvalidParameterAt {
            name,
            value,
            index,
            reason,
        } if name.starts_with('s') && index < order.len() => sky_field(
            path,
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

/// The error of a sky table whose rows leave a node of their grid (zenith angles `theta` ×
/// azimuths `phi`) without a row: it names the first missing node (θ-major), the grid and how
/// many nodes are missing. Time and memory by the rows given (`node_row`), never by the grid.
fn sky_table_hole(
    path: &Path,
    theta: &[f64],
    phi: &[f64],
    node_row: &HashMap<(usize, usize), usize>,
    rows: usize,
) -> Error {
    let np = phi.len() as u128;
    let mut given: Vec<u128> = node_row
        .keys()
        .map(|&(t, p)| t as u128 * np + p as u128)
        .collect();
    given.sort_unstable();
    // The first index not given: the first k with given[k] ≠ k (the indices are distinct).
    let hole = given
        .iter()
        .enumerate()
        .find(|&(k, &g)| g != k as u128)
        .map_or(given.len() as u128, |(k, _)| k as u128);
    let nodes = theta.len() as u128 * np;
    let missing = nodes - given.len() as u128;
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
    Error::File {
        path: path.to_path_buf(),
        message: format!(
            "the sky table has a hole: no row for the node (theta_deg = {}, phi_deg = {}); the \
             grid of its zenith angles [{}] × azimuths [{}] has {} nodes, each needed once, and \
             {} of them {} missing ({} rows given)",
            show(theta[(hole / np) as usize]),
            show(phi[(hole % np) as usize]),
            list(theta),
            list(phi),
            nodes,
            missing,
            if missing == 1 { "is" } else { "are" },
            rows
        ),
    }
}
