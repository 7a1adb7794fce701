//! `polbrdf eval`: the pBRDF at every geometry of a table (CSV, `.npy` or Arrow IPC), streamed
//! in chunks so memory stays bounded for any number of rows.

use crate::error::CliError;
use polbrdf::{DirectionBatch, Engine, Geometry, GeometryBatch, Mueller};
use polbrdf_io::csv_io::WAVELENGTH_COLUMN;
use polbrdf_io::stream::{
    Geometries, GeometryChunk, GeometryReader, ResultWriter, RowResult, CHUNK_ROWS,
};
use polbrdf_io::Output;
use std::path::Path;

/// Runs `polbrdf eval`. Each row's geometry is its angles or, in a table with the direction
/// columns instead (`w_i_x … w_r_z`), its two direction vectors. A material with a spectral
/// index needs the input's `wavelength_um` column: every row is evaluated with the index at
/// its wavelength. The formats follow the
/// extensions (`.npy`; `.arrow`/`.feather`: Arrow IPC file; `.arrows`: Arrow IPC stream; else
/// CSV); the output is `-` (standard output) when absent. An error
/// mid-stream leaves a regular output file as it was.
pub fn run(material: &str, input: &Path, output: Option<&Path>) -> Result<(), CliError> {
    let spec = crate::output::load_material(material)?;
    let out_path = output.unwrap_or(Path::new("-"));
    polbrdf_io::check_distinct(&[input, Path::new(material)], &[out_path])?;
    let mut reader = GeometryReader::open(input)?;
    if spec.is_spectral() && !reader.has_wavelengths() {
        return Err(CliError::Io(polbrdf_io::Error::File {
            path: input.to_path_buf(),
            message: format!(
                "the material `{material}` has a spectral index: the input needs a \
                 `{WAVELENGTH_COLUMN}` column (µm)"
            ),
        }));
    }
    let fixed = if spec.is_spectral() {
        None
    } else {
        Some(spec.build()?)
    };
    let headers = reader.headers().to_vec();
    let out = Output::create(out_path)?;
    let mut writer = ResultWriter::new(out, input, &headers, reader.rows_hint())?;
    if let Some(kinds) = reader.column_kinds() {
        writer.column_kinds(kinds);
    }
    let mut scan = polbrdf_io::AngleScan::default();
    let bar = progress_bar(input, reader.rows_hint());
    let total = reader.rows_hint().unwrap_or(0);
    let mut done = 0u64;
    let mut progress = |rows: usize| {
        done += rows as u64;
        if let Some(bar) = &bar {
            bar.set(done, total, None);
        }
    };
    while let Some(chunk) = reader.next_chunk(CHUNK_ROWS)? {
        if let Geometries::Angles(g) = &chunk.geometries {
            g.iter().for_each(|g| scan.add(g));
        }
        let pbrdf = match &fixed {
            Some(m) => pbrdf_of(&Engine::new(m), &chunk.geometries)?,
            None => {
                let wl = chunk.wavelengths.as_deref().expect("checked above");
                let m = spec
                    .build_at(wl[0])
                    .map_err(|e| wavelength_err(input, &chunk, e, true))?;
                let engine = Engine::new(&m)
                    .with_wavelengths(wl)
                    .map_err(|e| wavelength_err(input, &chunk, e, false))?;
                pbrdf_of(&engine, &chunk.geometries)?
            }
        };
        writer.write_chunk(&chunk, &pbrdf)?;
        progress(chunk.geometries.len());
    }
    drop(bar);
    writer.finish()?;
    crate::output::unit_warnings(scan.warning(&input.display().to_string()).as_slice());
    Ok(())
}

/// Rows from which an `eval` is large enough for a progress bar: about 2 s of work at the
/// ~4 µs per row of a CSV table read, evaluated and written (full Mueller matrix, 25 columns
/// of shortest round-trip text; docs/cli-conventions.md).
pub const LARGE_EVAL_ROWS: u64 = 500_000;

/// Bytes of a CSV input from which an `eval` is large (its row count is not known before it
/// is read): [`LARGE_EVAL_ROWS`] rows of the four angle columns, ~20 bytes each.
pub const LARGE_EVAL_CSV_BYTES: u64 = 20 * LARGE_EVAL_ROWS;

/// The progress bar of a large `eval` (drawn on a terminal only): by rows of a table whose
/// count is known (`.npy`, Arrow), or a row counter for a large CSV file; none for a small
/// table or standard input.
fn progress_bar(input: &Path, rows: Option<u64>) -> Option<crate::progress::Progress> {
    match rows {
        Some(n) if n >= LARGE_EVAL_ROWS => Some(crate::progress::Progress::new(n, "eval: rows")),
        Some(_) => None,
        None => std::fs::metadata(input)
            .ok()
            .filter(|m| m.is_file() && m.len() >= LARGE_EVAL_CSV_BYTES)
            .map(|_| crate::progress::Progress::counter("eval: rows")),
    }
}

/// The results of a chunk's rows through the engine: from the angles, or from the direction
/// vectors by the direction entry point (`DirectionBatch`: no angle on the way, a vector at or
/// below the horizon gives a zero pBRDF). The BRDF, DoLP and AoLP come from the core's one
/// definition of them, `Engine::brdf_dolp_aolp_into` (as in `lut` and Python), not from the
/// matrix.
fn pbrdf_of(engine: &Engine<'_>, geometries: &Geometries) -> Result<Vec<RowResult>, CliError> {
    let n = geometries.len();
    let (mut b, mut d, mut a) = (vec![0.0; n], vec![0.0; n], vec![0.0; n]);
    let pbrdf = match geometries {
        Geometries::Angles(g) => {
            let angles: [Vec<f64>; 4] = [
                g.iter().map(Geometry::theta_i).collect(),
                g.iter().map(Geometry::phi_i).collect(),
                g.iter().map(Geometry::theta_r).collect(),
                g.iter().map(Geometry::phi_r).collect(),
            ];
            let [ti, pi, tr, pr] = &angles;
            let batch = GeometryBatch::new(ti, pi, tr, pr)?;
            engine.brdf_dolp_aolp_into(&batch, &mut b, &mut d, &mut a)?;
            engine.pbrdf_of(g)?
        }
        Geometries::Directions { w_i, w_r } => {
            let batch = DirectionBatch::new(w_i, w_r)?;
            let mut rows = vec![[0.0; 16]; n];
            engine.mueller_into(&batch, &mut rows)?;
            engine.brdf_dolp_aolp_into(&batch, &mut b, &mut d, &mut a)?;
            rows.iter().map(Mueller::from_row_major).collect()
        }
    };
    Ok(pbrdf
        .into_iter()
        .enumerate()
        .map(|(k, pbrdf)| RowResult {
            pbrdf,
            brdf_dolp_aolp: [b[k], d[k], a[k]],
        })
        .collect())
}

/// A wavelength error of the engine, at the row it came from (`first`: of the chunk's first
/// row).
fn wavelength_err(input: &Path, chunk: &GeometryChunk, e: polbrdf::Error, first: bool) -> CliError {
    let line = match &e {
        polbrdf::Error::WavelengthOutOfRange {
            position: Some(i), ..
        } if !first => chunk.lines.get(*i).copied(),
        polbrdf::Error::WavelengthOutOfRange { .. } => chunk.lines.first().copied(),
        _ => None,
    };
    match line {
        Some(line) => CliError::Io(polbrdf_io::Error::Field {
            path: input.to_path_buf(),
            line,
            field: WAVELENGTH_COLUMN.into(),
            // The line names the element: the message need not.
            message: match e {
                e @ polbrdf::Error::WavelengthOutOfRange { .. } => e.at_position(None).to_string(),
                other => other.to_string(),
            },
        }),
        None => CliError::Model(e),
    }
}
