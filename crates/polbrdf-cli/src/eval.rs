//! `polbrdf eval`: the pBRDF at every geometry of a CSV file.

use crate::error::CliError;
use crate::output::write_output;
use polbrdf::batch;
use std::path::Path;

/// Runs `polbrdf eval`.
pub fn run(material: &str, input: &Path, output: Option<&Path>) -> Result<(), CliError> {
    let material = polbrdf_io::load_material(material)?.build()?;
    let table = polbrdf_io::read_geometry_csv(input)?;
    let pbrdf = batch::pbrdf_of(&material, &table.geometries);
    let bytes = polbrdf_io::csv_io::results_csv(&table, &pbrdf)?;
    write_output(output, &bytes)
}
