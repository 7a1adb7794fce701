//! `polbrdf eval`: the pBRDF at every geometry of a CSV file.

use crate::error::CliError;
use crate::output::write_output;
use polbrdf::{batch, Engine};
use polbrdf_io::csv_io::WAVELENGTH_COLUMN;
use std::path::Path;

/// Runs `polbrdf eval`. A material with a spectral index needs the input's `wavelength_um`
/// column: every row is evaluated with the index at its wavelength, in one engine call.
pub fn run(material: &str, input: &Path, output: Option<&Path>) -> Result<(), CliError> {
    let spec = polbrdf_io::load_material(material)?;
    let table = polbrdf_io::read_geometry_csv(input)?;
    let pbrdf = if spec.is_spectral() {
        let Some(wl) = &table.wavelengths else {
            return Err(CliError::Io(polbrdf_io::Error::File {
                path: input.to_path_buf(),
                message: format!(
                    "the material `{material}` has a spectral index: the input needs a \
                     `{WAVELENGTH_COLUMN}` column (µm)"
                ),
            }));
        };
        let m = match wl.first() {
            Some(l) => spec
                .build_at(*l)
                .map_err(|e| wavelength_err(input, &table, e))?,
            None => return write_output(output, &polbrdf_io::csv_io::results_csv(&table, &[])?),
        };
        Engine::new(&m)
            .with_wavelengths(wl)
            .map_err(|e| wavelength_err(input, &table, e))?
            .pbrdf_of(&table.geometries)?
    } else {
        batch::pbrdf_of(&spec.build()?, &table.geometries)
    };
    let bytes = polbrdf_io::csv_io::results_csv(&table, &pbrdf)?;
    write_output(output, &bytes)
}

/// A wavelength error of the engine, at the row it came from.
fn wavelength_err(input: &Path, table: &polbrdf_io::GeometryTable, e: polbrdf::Error) -> CliError {
    let line = match &e {
        polbrdf::Error::WavelengthOutOfRange {
            position: Some(i), ..
        } => Some(table.lines[*i]),
        polbrdf::Error::WavelengthOutOfRange { .. } => table.lines.first().copied(),
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
