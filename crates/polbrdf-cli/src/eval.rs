//! `polbrdf eval`: the pBRDF at every geometry of a table (CSV, `.npy` or Arrow IPC), streamed
//! in chunks so memory stays bounded for any number of rows.

use crate::error::CliError;
use polbrdf::Engine;
use polbrdf_io::csv_io::WAVELENGTH_COLUMN;
use polbrdf_io::stream::{GeometryChunk, GeometryReader, ResultWriter, CHUNK_ROWS};
use polbrdf_io::Output;
use std::path::Path;

/// Runs `polbrdf eval`. A material with a spectral index needs the input's `wavelength_um`
/// column: every row is evaluated with the index at its wavelength. The formats follow the
/// extensions (`.npy`; `.arrow`/`.feather`: Arrow IPC file; `.arrows`: Arrow IPC stream; else
/// CSV); the output is `-` (standard output) when absent. An error
/// mid-stream leaves a regular output file as it was.
pub fn run(material: &str, input: &Path, output: Option<&Path>) -> Result<(), CliError> {
    let spec = polbrdf_io::load_material(material)?;
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
    while let Some(chunk) = reader.next_chunk(CHUNK_ROWS)? {
        let pbrdf = match &fixed {
            Some(m) => Engine::new(m).pbrdf_of(&chunk.geometries)?,
            None => {
                let wl = chunk.wavelengths.as_deref().expect("checked above");
                let m = spec
                    .build_at(wl[0])
                    .map_err(|e| wavelength_err(input, &chunk, e, true))?;
                Engine::new(&m)
                    .with_wavelengths(wl)
                    .map_err(|e| wavelength_err(input, &chunk, e, false))?
                    .pbrdf_of(&chunk.geometries)?
            }
        };
        writer.write_chunk(&chunk, &pbrdf)?;
    }
    Ok(writer.finish()?)
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
