//! `polbrdf materials`: the built-in materials.

use crate::error::CliError;
use crate::output::write_output;

/// Runs `polbrdf materials`.
pub fn run(show: Option<&str>) -> Result<(), CliError> {
    let text = match show {
        Some(name) => polbrdf_io::material_to_toml(&polbrdf::preset(name)?),
        None => {
            let mut text = String::from("Built-in materials (use the name with --material):\n\n");
            for p in polbrdf::presets::all() {
                text.push_str(&format!("  {:<13} {}\n", p.name, p.description));
            }
            text.push_str("\n`polbrdf materials --show NAME` prints one as a material file.\n");
            text.push_str(&library_listing()?);
            text
        }
    };
    write_output(None, text.as_bytes())
}

/// The refractive-index library: id, material, range and source of each entry.
fn library_listing() -> Result<String, CliError> {
    let mut text = String::from(
        "\nRefractive-index library (pages of the refractiveindex.info database, CC0): name one \
         in a\nmaterial file as `index = \"library:<id>\"` (or give the path of such a YAML \
         file).\n\n",
    );
    let entries = polbrdf_io::library::entries();
    let id_width = entries.iter().map(|e| e.id.len()).max().unwrap_or(0);
    let material_width = entries
        .iter()
        .map(|e| e.material.chars().count())
        .max()
        .unwrap_or(0);
    text.push_str(&format!(
        "  {:<id_width$}  {:<material_width$}  {:<15}  source\n",
        "id", "material", "range (µm)"
    ));
    for e in entries {
        let (lo, hi) = polbrdf_io::library::load(e.id)?.range();
        let range = format!("{}–{}", four_figures(lo), four_figures(hi));
        text.push_str(&format!(
            "  {:<id_width$}  {:<material_width$}  {range:<15}  {}\n",
            e.id, e.material, e.description
        ));
    }
    Ok(text)
}

/// `x` (> 0) to four significant figures, in the shortest form.
fn four_figures(x: f64) -> String {
    let scale = 10f64.powf(3.0 - x.log10().floor());
    format!("{}", (x * scale).round() / scale)
}
